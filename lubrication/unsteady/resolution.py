r"""How many Fourier and Chebyshev points a geometry needs, and where the method stops.

Fourier, quasi-steady part. The unknowns are H psi and omega (:mod:`lubrication.unsteady.mapping`):
for the steady Stokes flows of rigid walls they are trigonometric polynomials of degree 1
and 2 at every eccentricity, so that 16 points around (the least default) hold them
from kappa = 0 to the reach (tests/test_unsteady_stokes.py: 1e-9 of the exact loads at
1 - kappa = 1e-4, 2e-8 at 1e-5, with 16 x 12 points).

Fourier, the rest. What is not Stokes flow (the unsteady and convective parts) lives
where the gap is wide, which the map squeezes into an angle ~ beta = -ln|p| of the
computational circle (beta ~ sqrt(2 a (1 - kappa)/b)): its coefficients fall like
exp(-c beta |k|) with c ~ 1.4 (measured from an oscillation of the inner cylinder along
e_chi at kappa = 0.99 and 0.999). The default therefore resolves that part with
K = FOURIER_DECAY_MODES / beta modes when that stays within MAX_DEFAULT_N_THETA points,
and otherwise leaves it out with the least grid. Leaving it out is the better of the two
there: modes too few to resolve the wide part (beta K ~ 0.1-1) still represent some of its
fields, on which the discrete viscous term (the metric times the computational
Laplacian) nearly vanishes, and they carry the solve's rounding undamped. Measured on
the oscillation along e_chi at delta^2 w/nu = 0.3, amplitude 1e-3 of the gap, the force's
amplitude against the quasi-steady exact one (the unsteady share there is ~1e-3 of it):

    1 - kappa = 1e-4:  n_theta = 16: 5e-8,  64: 8e-7,  256: 6e-5
    1 - kappa = 1e-5:  n_theta = 16: 5e-6,  64: 5e-5,  256: 9e-4
    1 - kappa = 1e-6:  n_theta = 16: 1e-4,  64: 5e-3

and at kappa = 0.99 (beta = 0.12), against 128 points: 32 points 2e-3, 64 points 8e-5.

Chebyshev. Across the gap the fields are smooth in s on [-tau, 0] at every
eccentricity (the bipolar structure of the exact solution); 8 points give the Stokes
loads to 1e-8. Impulsive starts (boundary layers of thickness sqrt(nu t)) need more at
early times: see the Couette spin-up test.

Reach. Below 1 - kappa = 1e-5 (:data:`lubrication.unsteady.mapping.MIN_ONE_MINUS_KAPPA_UNSTEADY`) the Stokes loads
still come out (1e-5 of T_b per W_a at 1e-7), but the unsteady runs above scatter by
0.5% at 1e-6 and by 20% at 1e-7.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .mapping import AnnulusMap

__all__ = ["FOURIER_DECAY_MODES", "MAX_DEFAULT_N_THETA", "MIN_N_THETA", "Resolution", "default_resolution"]

#: beta K of the default resolution when it resolves the wide part of the gap: its
#: unsteady and convective fields to exp(-1.4 beta K) ~ 4e-3 of themselves.
FOURIER_DECAY_MODES = 4.0
#: Fewest theta points of the default resolution (the quasi-steady part needs 8).
MIN_N_THETA = 16
#: Most theta points the default resolves the wide part of the gap with (1 - kappa >~ 2e-4
#: for the apparatus); beyond, it takes MIN_N_THETA (module docstring).
MAX_DEFAULT_N_THETA = 512


@dataclass(frozen=True)
class Resolution:
    """Points of the computational grid.

    Parameters
    ----------
    n_theta : int
        Points of the theta grid; Fourier modes |k| <= (n_theta - 1)//2 are kept.
    n_r : int
        Chebyshev-Lobatto points across the gap, walls included.
    dealias : bool
        Form the convective products on a grid padded by the 3/2 rule.
    """

    n_theta: int = 64
    n_r: int = 16
    dealias: bool = True

    def __post_init__(self):
        for name, low in (("n_theta", 8), ("n_r", 4)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < low:
                msg = f"{name} must be an integer >= {low}, got {value!r}"
                raise ValueError(msg)


def default_resolution(geometry: AnnulusMap, n_r: int = 16, *, quasi_steady: bool = False) -> Resolution:
    """The resolution for the most eccentric geometry a run will meet (module docstring).

    Parameters
    ----------
    geometry : AnnulusMap
    n_r : int
        Chebyshev points across.
    quasi_steady : bool
        Only the quasi-steady Stokes part matters (Reynolds and Stokes numbers -> 0):
        MIN_N_THETA points at every gap.
    """
    beta = geometry.beta
    if quasi_steady or not math.isfinite(beta):
        return Resolution(n_theta=MIN_N_THETA, n_r=n_r)
    n_theta = 8 * math.ceil((2 * math.ceil(FOURIER_DECAY_MODES / beta) + 2) / 8)
    if n_theta > MAX_DEFAULT_N_THETA:
        n_theta = MIN_N_THETA
    return Resolution(n_theta=max(MIN_N_THETA, n_theta), n_r=n_r)
