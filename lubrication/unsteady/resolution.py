r"""How many Fourier and Chebyshev points a geometry needs, and where the method stops.

Fourier. The walls' data and every field are analytic in theta; in the map's
variables their coefficients decay like exp(-beta |k|) (the factor
1/(cosh(s + beta) - cos theta) of the bipolar solution, :mod:`lubrication.unsteady.mapping`),
beta = -ln|p|, about sqrt(2 a (1 - kappa)/b) near contact: the wide part of the gap
is squeezed into an angle ~ beta of the computational circle. The default number
of modes is therefore K = ceil(c / beta), bounded below; the constant c was
measured on the steady Stokes loads against the exact solution
(:mod:`lubrication.stokes_exact`) and is stated with :data:`FOURIER_DECAY_MODES`.

Chebyshev. Across the gap the fields are smooth in s on [-tau, 0] at every
eccentricity (the bipolar structure of the exact solution); 16 points gave the
Stokes loads to 1e-10 at kappa <= 0.99. Impulsive starts (boundary layers of
thickness sqrt(nu t)) need more at early times: see the Couette spin-up test.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .mapping import AnnulusMap

__all__ = ["FOURIER_DECAY_MODES", "MIN_N_THETA", "Resolution", "default_resolution"]

#: beta K at the default resolution, exp(-beta K) ~ 1e-6. Measured on the steady Stokes
#: loads (tests/test_unsteady_stokes.py): at kappa = 0.99 (beta = 0.12) K = 63 gave 1e-4
#: (T_b per W_a) and K = 127 1e-9; at 1 - kappa = 1e-4 (beta = 0.0119) K = 1023 gave
#: f_chi and T_a per W_a to 1e-10 while K = 1683 (beta K = 20) gave 6e-4: the solve's
#: rounding floor rises with the number of modes, so more is not better there.
FOURIER_DECAY_MODES = 14.0
#: Fewest theta points of the default resolution.
MIN_N_THETA = 32


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


def default_resolution(geometry: AnnulusMap, n_r: int = 16) -> Resolution:
    """The resolution for the most eccentric geometry a run will meet (module docstring)."""
    beta = geometry.beta
    k = FOURIER_DECAY_MODES / beta if math.isfinite(beta) else 0.0
    n_theta = max(MIN_N_THETA, 2 * math.ceil(k) + 2)
    n_theta = 8 * math.ceil(n_theta / 8)
    return Resolution(n_theta=n_theta, n_r=n_r)
