r"""Finite-length factors: the resistance coefficients of an annulus of length L against L times the 2-D ones.

The factor of a coefficient is its value for an annulus of length L with open
ends (:mod:`lubrication.reynolds2d`) divided by L times its value per unit
length of an infinitely long one (the one-dimensional Reynolds solver).

The thin gap: two functions and an identity
-------------------------------------------
For h = delta (1 - kappa cos theta) the equation in units of delta and a has
only (kappa, L/a) as parameters, so the factors do not depend on delta/a.
The rotation enters only through W_a + W_b, so f_chi per W_a and per W_b share
one factor F_chi; the squeeze has its own, F_eps. The torque needs no third:
its Poiseuille part is -(a/2) int dz oint h p_theta dtheta = (a/2) int dz oint
h_theta p dtheta = -(eps/2) f_chi (thin gap, h_theta = eps sin theta), for any
length, while its Couette part, mu a^3 L (W_b - W_a) oint dtheta/h, does not feel the
ends. With (2.6)-(2.7) split this way the torque factors are

    T_a per W_a:  ((2 + kappa^2) + 3 kappa^2 F_chi) / (2 + 4 kappa^2),
    T_a per W_b:  1 + 3 kappa^2 (1 - F_chi) / (2 zeta^2),

zeta = sqrt(1 - kappa^2). The second grows without bound at contact: the
infinite-length W_b torque is an O(zeta) remainder of Couette and Poiseuille
parts of order 1/zeta, and the ends change the Poiseuille part by O(a/L).

Limits (checks of the solver, derived here)
-------------------------------------------
* kappa -> 0 (exact at kappa = 0 for the squeeze, the limit for the rotation):
  h = delta, the pressure is cos(theta) P(z) (squeeze) or sin(theta) P(z)
  (rotation) with P'' - P/a^2 = const and P(+-L/2) = 0, so
  P = P_inf (1 - cosh(z/a)/cosh(L/2a)) and

      F_eps = F_chi = 1 - tanh(l/2)/(l/2),   l = L/a.

* Short bearing (Ocvirk), L << a zeta: the theta-flux drops out,
  h^3 p_zz = R(theta) = 6 mu (W_a + W_b) h_theta + 12 mu h_t, so
  p = -R (L^2/4 - z^2)/(2 h^3) and int p dz = -R L^3/(12 h^3). With
  oint sin^2/(1 - kappa cos)^3 = pi/zeta^3 and oint cos^2/(1 - kappa cos)^3 =
  pi (1 + 2 kappa^2)/zeta^5 (full film, both ends open):

      f_eps = -pi mu a L^3 eps' (1 + 2 kappa^2) / (delta^3 zeta^5),
      f_chi =  pi mu a L^3 kappa (W_a + W_b) / (2 delta^2 zeta^3),
      T_a   =  2 pi mu a^3 L (W_b - W_a) / (delta zeta) - pi mu a L^3 kappa^2 (W_a + W_b) / (4 delta zeta^3),

  the torque's Poiseuille part again -(eps/2) f_chi. Against (2.5)-(2.7):
  F_eps -> l^2 (1 + 2 kappa^2)/(12 zeta^2), F_chi -> l^2 (2 + kappa^2)/(24 zeta^2).
  The expansion parameter is (L/(a zeta))^2, so the limit is not uniform in kappa.
* Long bearing, L >> a: each end removes a fixed amount, F = 1 - C(kappa) a/L
  up to terms exponentially small in L/a. Near contact the end layer is
  a zeta wide: C ~ zeta for the squeeze, and C ~ zeta (A + B log(1/zeta)) for
  the rotation, whose pressure dipole decays only algebraically away from the
  narrow gap (measured at L/a = 12.9: 1 - F_eps = 0.0996 zeta, and
  (1 - F_chi)/zeta growing by 0.058 per halving of zeta).

A cheap evaluation for the equations of motion
----------------------------------------------
:func:`finite_length_factor_kernel` evaluates F_eps and F_chi from a table and
the other three by the identities above, in about a microsecond. Near
contact the factors depend on L and zeta mostly through x = L/(a zeta) (the
end layer is a zeta wide), and 1 - F ~ C/x for long bearings, so the table
holds the deficit divided by s,

    H = (1 - F)/s,   s = X0/(X0 + x) in [0, 1],   zeta in [ZETA_MIN, 1],

as a tensor Chebyshev interpolant on Chebyshev-Lobatto nodes. H is smooth
and O(1) everywhere: at s = 0 (the long bearing) it is C/X0, found at
L/a = LONG where the two ends no longer see each other; at s = 1 (no length)
it is 1; at zeta = 1 the closed form above gives it (H = 2/X0 at s = 0). The
zeta-axis is log(zeta), in which the rotation's zeta log(1/zeta) deficit is
linear (on a zeta axis the last coefficients were 30 times larger). The
kernel forms 1 - F = s H, which keeps its relative precision however long the
bearing. Below ZETA_MIN the series is continued linearly in log(zeta);
measured against direct solves at zeta = 5e-3 .. 5e-4: within 2e-6 at
L/a = 12.9, within 1.4e-3 (a tenth of the deficit) at L/a = 1. Inside the
table the largest error over 150 random (zeta, L/a), L/a from 0.3 to 200,
was 2.9e-5, at zeta = 0.012 and L/a = 0.94; 1e-5 or less for zeta > 0.02.
The W_b torque factor multiplies a coefficient that vanishes like zeta^2 at
contact; its error, 3 kappa^2/(2 zeta^2) times that of F_chi, is the error of
F_chi against the larger entry of the torque's row.
"""

from __future__ import annotations

import io
import logging
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from numerics.files import cache_folder, write_bytes
from numerics.jit import jit

from . import kernels
from .closed_form import lubrication_forces
from .geometry import RESISTANCE_NAMES, Annulus, Fluid, Motion, check_range
from .reynolds import reynolds_forces
from .reynolds2d import reynolds2d_forces

__all__ = [
    "APPARATUS_DELTA_OVER_A",
    "APPARATUS_LENGTH_OVER_A",
    "FACTOR_NAMES",
    "TABLE_VERSION",
    "FactorTable",
    "factor_table",
    "finite_length_factor_kernel",
    "finite_length_factors",
    "short_bearing_factors",
    "short_bearing_forces",
    "small_eccentricity_factor",
    "table_factors",
    "thin_gap_factors",
]

logger = logging.getLogger(__name__)

#: The paper's apparatus (Table 2): a = 0.8 cm, b = 1.125 cm, L = 10.35 cm.
APPARATUS_LENGTH_OVER_A = 10.35 / 0.8
APPARATUS_DELTA_OVER_A = (1.125 - 0.8) / 0.8
FACTOR_NAMES = RESISTANCE_NAMES

# Table settings; a stored table made with other settings is rebuilt.
TABLE_VERSION = 2
ZETA_MIN = 0.01
X0 = 4.0
#: L/a of the solves that give H at s = 0: exp(-LONG/2) is negligible.
LONG = 40.0
N_ZETA = 33
N_S = 33
TABLE_CELLS = 128
TABLE_AXIAL_CELLS = 64


def small_eccentricity_factor(length_over_a: float) -> float:
    """F_eps = F_chi at kappa -> 0: 1 - tanh(l/2)/(l/2), l = L/a (module docstring)."""
    x = 0.5 * check_range("length_over_a", length_over_a, 0.0, math.inf, low_open=True)
    if x < 1e-2:  # x - tanh(x) cancels: its series, to rounding
        x2 = x * x
        return x2 * (1.0 / 3.0 - x2 * (2.0 / 15.0 - x2 * (17.0 / 315.0 - x2 * 62.0 / 2835.0)))
    return (x - math.tanh(x)) / x


def short_bearing_forces(annulus: Annulus, motion: Motion, fluid: Fluid):
    """Force and torque of the short (Ocvirk) bearing with open ends, full film, thin gap.

    Leading order in L/(a zeta); see the module docstring for the derivation.

    Returns
    -------
    FluidForces
        f_eps, f_chi (N) and T_a (N m) over the length, ``model="short-bearing"``.
    """
    from .geometry import FluidForces

    a, delta, length, mu = annulus.a, annulus.delta, annulus.length, fluid.mu
    kappa, omk = annulus.kappa, annulus.one_minus_kappa
    zeta = math.sqrt(omk * (1.0 + kappa))
    w = motion.w_a + motion.w_b
    cube = length**3
    f_eps = -math.pi * mu * a * cube * motion.eps_dot * (1.0 + 2.0 * kappa**2) / (delta**3 * zeta**5)
    f_chi = math.pi * mu * a * cube * kappa * w / (2.0 * delta**2 * zeta**3)
    t_a = (2.0 * math.pi * mu * a**3 * length * (motion.w_b - motion.w_a) / (delta * zeta)
           - math.pi * mu * a * cube * kappa**2 * w / (4.0 * delta * zeta**3))
    return FluidForces(f_eps, f_chi, t_a, model="short-bearing")


def thin_gap_factors(kappa: float, f_eps: float, f_chi: float) -> dict[str, float]:
    """The five factors of the thin gap from F_eps and F_chi (the torque identity of the module docstring)."""
    k2 = kappa * kappa
    zeta_sq = (1.0 - kappa) * (1.0 + kappa)
    t_a = ((2.0 + k2) + 3.0 * k2 * f_chi) / (2.0 + 4.0 * k2)
    t_b = 1.0 + 3.0 * k2 * (1.0 - f_chi) / (2.0 * zeta_sq)
    return dict(zip(FACTOR_NAMES, (f_eps, f_chi, t_a, f_chi, t_b)))


def short_bearing_factors(kappa: float, length_over_a: float) -> dict[str, float]:
    """Leading-order factors as L/(a zeta) -> 0 (module docstring)."""
    kappa = check_range("kappa", kappa, 0.0, 1.0)
    l = check_range("length_over_a", length_over_a, 0.0, math.inf, low_open=True)
    zeta_sq = (1.0 - kappa) * (1.0 + kappa)
    f_eps = l * l * (1.0 + 2.0 * kappa**2) / (12.0 * zeta_sq)
    f_chi = l * l * (2.0 + kappa**2) / (24.0 * zeta_sq)
    return thin_gap_factors(kappa, f_eps, f_chi)


def finite_length_factors(kappa: float, length_over_a: float, *, delta_over_a: float = APPARATUS_DELTA_OVER_A,
                          profile: str = "thin", n: int = 128, n_axial: int = 64,
                          clustering: float | tuple[float, float] | None = None,
                          extrapolate: bool = True) -> dict[str, float]:
    """The five finite/infinite ratios of the resistance coefficients, from the (theta, z) solver.

    Parameters
    ----------
    kappa : float
        Eccentricity ratio in [0, 1).
    length_over_a : float
        L/a > 0.
    delta_over_a : float
        (b - a)/a; the thin-gap factors do not depend on it (module docstring),
        the exact eccentric gap's do.
    profile : {"thin", "eccentric"}
        Gap profile.
    n, n_axial, clustering, extrapolate
        Resolution, as :func:`lubrication.reynolds2d.reynolds2d_forces`. The
        defaults give F_eps and F_chi to 2e-6 or better at the apparatus' length
        for every kappa from 0.3 to 1 - 1e-9 (measured against N = 1024,
        n_axial = 512, extrapolated, which moves by 1e-8 from half that); the W_b
        torque factor carries that error times 3 kappa^2/(2 zeta^2).

    Returns
    -------
    dict
        Keyed by :data:`FACTOR_NAMES`. The two f_chi entries are NaN at kappa = 0,
        where both coefficients vanish; their limit is :func:`small_eccentricity_factor`.
    """
    kappa = check_range("kappa", kappa, 0.0, 1.0)
    length_over_a = check_range("length_over_a", length_over_a, 0.0, math.inf, low_open=True)
    delta_over_a = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    a = 1.0
    annulus = Annulus.from_kappa(a, a * (1.0 + delta_over_a), kappa, length=a * length_over_a)
    fluid = Fluid(nu=1.0, rho=1.0)
    options = {"n": n, "n_axial": n_axial, "profile": profile, "clustering": clustering,
               "extrapolate": extrapolate}
    out = {}
    for motion, names in ((Motion(eps_dot=1.0), ("f_eps_per_eps_dot",)),
                          (Motion(omega_a=1.0), ("f_chi_per_w_a", "t_a_per_w_a")),
                          (Motion(omega_b=1.0), ("f_chi_per_w_b", "t_a_per_w_b"))):
        finite = reynolds2d_forces(annulus, motion, fluid, **options)
        infinite = reynolds_forces(annulus, motion, fluid, n=max(n, 64), profile=profile)
        pick = {"f_eps_per_eps_dot": 0, "f_chi_per_w_a": 1, "f_chi_per_w_b": 1, "t_a_per_w_a": 2,
                "t_a_per_w_b": 2}
        for name in names:
            i = pick[name]
            vanishes = kappa == 0.0 and name.startswith("f_chi")
            out[name] = math.nan if vanishes else finite.as_tuple()[i] / infinite.as_tuple()[i]
    return {name: out[name] for name in FACTOR_NAMES}


# ---------------------------------------------------------------- the table and its kernel

def _table_resolution(zeta: float) -> int:
    """Cells around the gap for a table node: more near contact, where the peak narrows.

    Measured with the default grid, the largest over L/a = 4 zeta, 12.94 and 40:
    at n = 128 the extrapolated factors move by 1.4e-5 (zeta = 0.05) and 5.7e-5
    (zeta = 0.01) when n doubles; at n = 512, by 7e-7 and 1.1e-6.
    """
    return TABLE_CELLS if zeta >= 0.2 else 4 * TABLE_CELLS if zeta < 0.04 else 2 * TABLE_CELLS


def _thin_factor_pair(zeta: float, length_over_a: float) -> tuple[float, float]:
    """(F_eps, F_chi) of the thin gap from the (theta, z) solver, extrapolated."""
    kappa = math.sqrt((1.0 - zeta) * (1.0 + zeta))
    annulus = Annulus(a=1.0, b=2.0, length=length_over_a, one_minus_kappa=zeta * zeta / (1.0 + kappa))
    fluid = Fluid(nu=1.0, rho=1.0)
    options = {"n": _table_resolution(zeta), "n_axial": TABLE_AXIAL_CELLS, "extrapolate": True}
    squeeze = reynolds2d_forces(annulus, Motion(eps_dot=1.0), fluid, **options).f_eps
    rotation = reynolds2d_forces(annulus, Motion(omega_a=1.0), fluid, **options).f_chi
    ref = lubrication_forces(1.0, 1.0, 1.0, length_over_a, annulus.kappa, annulus.one_minus_kappa, 1.0, 1.0, 0.0)
    return squeeze / ref[0], rotation / ref[1]


def _lobatto(count: int) -> np.ndarray:
    """Chebyshev-Lobatto points cos(pi j/(count - 1)) on [-1, 1], from +1 down to -1."""
    return np.cos(np.pi * np.arange(count) / (count - 1))


def _to_coefficients(values: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients of the tensor interpolant of ``values`` at Lobatto points (both axes)."""
    from scipy.fft import dct

    out = values
    for axis in (0, 1):
        count = out.shape[axis]
        out = dct(out, type=1, axis=axis) / (count - 1)
        edge = [slice(None)] * 2
        for index in (0, count - 1):
            edge[axis] = index
            out[tuple(edge)] *= 0.5
    return out


@dataclass(frozen=True)
class FactorTable:
    """Chebyshev coefficients of H = (1 - F)/s for F_eps and F_chi in (zeta, s) (module docstring).

    ``args`` are the trailing arguments of :func:`finite_length_factor_kernel`.
    """

    coef_eps: np.ndarray
    coef_chi: np.ndarray
    zeta_min: float
    x0: float

    @property
    def args(self) -> tuple:
        return (self.coef_eps, self.coef_chi, self.zeta_min, self.x0)


def _build_table(n_zeta: int, n_s: int, zeta_min: float, x0: float) -> FactorTable:
    zeta = np.exp(0.5 * math.log(zeta_min) * (1.0 - _lobatto(n_zeta)))  # log(zeta) on Lobatto points, zeta = 1 first
    s = 0.5 * (1.0 + _lobatto(n_s))  # from s = 1 (no length) down to s = 0 (infinite length)
    h_eps = np.empty((n_zeta, n_s))
    h_chi = np.empty((n_zeta, n_s))
    for i, z in enumerate(zeta):
        for j, sj in enumerate(s):
            if sj == 1.0:
                h_eps[i, j] = h_chi[i, j] = 1.0
            elif i == 0:  # zeta = 1, kappa = 0: 1 - F = tanh(x/2)/(x/2)
                h_eps[i, j] = h_chi[i, j] = 2.0 / x0 if sj == 0.0 else (
                    1.0 - small_eccentricity_factor(x0 * (1.0 - sj) / sj)) / sj
            elif sj == 0.0:  # the long bearing: 1 - F = C/x
                x = LONG / z
                f_eps, f_chi = _thin_factor_pair(z, LONG)
                h_eps[i, j], h_chi[i, j] = (1.0 - f_eps) * x / x0, (1.0 - f_chi) * x / x0
            else:
                f_eps, f_chi = _thin_factor_pair(z, x0 * (1.0 - sj) / sj * z)
                h_eps[i, j], h_chi[i, j] = (1.0 - f_eps) / sj, (1.0 - f_chi) / sj
    return FactorTable(_to_coefficients(h_eps), _to_coefficients(h_chi), zeta_min, x0)


def _table_path():
    return cache_folder() / f"finite_length_v{TABLE_VERSION}_{N_ZETA}x{N_S}.npz"


@lru_cache(maxsize=1)
def factor_table() -> FactorTable:
    """The thin-gap factor table: read from the cache folder, or built and stored.

    Building it solves the Reynolds equation on (theta, z) at every node (the
    performance page gives the time).

    The cache folder is :func:`numerics.files.cache_folder` (``$SNAIL_CACHE``, else
    ``~/.cache/snail-cylinder``); a file with other settings is rebuilt.
    """
    path = _table_path()
    settings = np.array([TABLE_VERSION, N_ZETA, N_S, ZETA_MIN, X0, TABLE_CELLS, TABLE_AXIAL_CELLS], dtype=float)
    try:
        with np.load(path, allow_pickle=False) as data:
            if np.array_equal(data["settings"], settings):
                return FactorTable(data["coef_eps"], data["coef_chi"], ZETA_MIN, X0)
    except (OSError, KeyError, ValueError):
        pass
    logger.info("building the finite-length factor table (%d x %d nodes; first use only, about a minute with its "
                "kernels' compiling) into %s", N_ZETA, N_S, path)
    table = _build_table(N_ZETA, N_S, ZETA_MIN, X0)
    buf = io.BytesIO()
    np.savez(buf, settings=settings, coef_eps=table.coef_eps, coef_chi=table.coef_chi)
    write_bytes(path, buf.getvalue())
    return table


@jit(inline="always")
def _chebyshev_row(coef, i, v):
    """sum_j coef[i, j] T_j(v) by Clenshaw's recurrence."""
    b1 = b2 = 0.0
    for j in range(coef.shape[1] - 1, 0, -1):
        b1, b2 = coef[i, j] + 2.0 * v * b1 - b2, b1
    return coef[i, 0] + v * b1 - b2


@jit(inline="always")
def _chebyshev2(coef, u, v):
    """sum_ij coef[i, j] T_i(u) T_j(v): Clenshaw in u over rows summed by Clenshaw in v.

    For u < -1 (zeta below the table) the series is continued linearly from
    u = -1, where T_i = (-1)^i and T_i' = (-1)^(i+1) i^2.
    """
    if u < -1.0:
        value = slope = 0.0
        sign = 1.0
        for i in range(coef.shape[0]):
            row = _chebyshev_row(coef, i, v)
            value += sign * row
            slope -= sign * i * i * row
            sign = -sign
        return value + (u + 1.0) * slope
    b1 = b2 = 0.0
    for i in range(coef.shape[0] - 1, 0, -1):
        b1, b2 = _chebyshev_row(coef, i, v) + 2.0 * u * b1 - b2, b1
    return _chebyshev_row(coef, 0, v) + u * b1 - b2


@jit
def finite_length_factor_kernel(kappa, omk, length_over_a, coef_eps, coef_chi, zeta_min, x0):
    """The five thin-gap finite-length factors from the table, in FACTOR_NAMES order.

    Parameters
    ----------
    kappa, omk : float
        Eccentricity ratio and 1 - kappa (kept for precision near contact).
    length_over_a : float
        L/a in [0, inf]; inf gives 1 for every factor.
    coef_eps, coef_chi, zeta_min, x0
        ``factor_table().args``.

    Returns
    -------
    tuple of float
        Factors of f_eps per eps', f_chi and T_a per W_a, f_chi and T_a per W_b:
        multiply L times any per-unit-length coefficients by them.
    """
    zeta = math.sqrt(omk * (1.0 + kappa))
    # s = X0/(X0 + x) with x = L/(a zeta), written to stay finite at zeta = 0 and L = inf
    if math.isinf(length_over_a):
        s = 0.0
    else:
        s = x0 * zeta / (x0 * zeta + length_over_a) if zeta > 0.0 else 0.0
    # u = 1 at zeta = 1, -1 at zeta_min; zeta = 0 only with s = 0, where H is not needed
    u = 1.0 - 2.0 * math.log(zeta) / math.log(zeta_min) if zeta > 0.0 else -1.0
    v = 2.0 * s - 1.0
    deficit_eps = s * _chebyshev2(coef_eps, u, v)
    deficit_chi = s * _chebyshev2(coef_chi, u, v)
    k2 = kappa * kappa
    t_a = ((2.0 + k2) + 3.0 * k2 * (1.0 - deficit_chi)) / (2.0 + 4.0 * k2)
    # 1 + 3 kappa^2 (1 - F_chi)/(2 zeta^2) with (1 - F_chi)/zeta^2 = s H / zeta^2, s/zeta = x0/(x0 zeta + l)
    if math.isinf(length_over_a):
        t_b = 1.0
    else:
        t_b = 1.0 + 1.5 * k2 * x0 * _chebyshev2(coef_chi, u, v) / (zeta * (x0 * zeta + length_over_a))
    return 1.0 - deficit_eps, 1.0 - deficit_chi, t_a, 1.0 - deficit_chi, t_b


def table_factors(kappa: float, length_over_a: float) -> dict[str, float]:
    """:func:`finite_length_factor_kernel` with the stored table, as a dict keyed by FACTOR_NAMES."""
    kappa = check_range("kappa", kappa, 0.0, 1.0)
    length_over_a = check_range("length_over_a", length_over_a, 0.0, math.inf, high_open=False)
    return dict(zip(FACTOR_NAMES, finite_length_factor_kernel(kappa, 1.0 - kappa, length_over_a,
                                                              *factor_table().args)))


@jit(inline="always")
def end_factors(data, kappa, omk):
    """The finite-length factors of the five coefficients of a kernel's packed ``data``
    (:mod:`lubrication.kernels`); ones for an infinitely long annulus."""
    start = int(data[kernels.ENDS])
    if start == 0:
        return (1.0, 1.0, 1.0, 1.0, 1.0)
    rows, cols = int(data[kernels.ROWS]), int(data[kernels.COLS])
    size = rows * cols
    coef_eps = data[start:start + size].reshape((rows, cols))
    coef_chi = data[start + size:start + 2 * size].reshape((rows, cols))
    return finite_length_factor_kernel(kappa, omk, data[kernels.LENGTH_OVER_A], coef_eps, coef_chi,
                                       data[kernels.ZETA_MIN], data[kernels.X0])
