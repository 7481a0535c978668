"""The Reynolds equation in the gap angle theta, solved numerically.

    d/dtheta (h^3 dp/dtheta) = 6 mu a (U_a + U_b) dh/dtheta + 12 mu a^2 dh/dt

(Appendix B; U_a = a W_a and U_b the wall speeds relative to the line of
centres), periodic in theta, for the thin-gap profile (B1), the exact gap
between the eccentric circles, or any smooth periodic profile a user supplies.
The kernels and the discretisation are described in
:mod:`lubrication.reynolds_kernels`; this module checks inputs, builds the grids and
picks the kernel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import numpy as np

from numerics.jit import jit

from . import reynolds_kernels
from .geometry import Annulus, Fluid, FluidForces, Motion
from .kernels import model_block

__all__ = ["GRIDS", "MAX_CELLS", "MAX_POINTS_PER_CELL", "MIN_CELLS", "PROFILES", "TRAJECTORY_CELLS", "GapProfile",
           "ReynoldsPressure", "film_block", "film_rule", "psi_rule", "reynolds_forces", "reynolds_kernel",
           "reynolds_pressure", "uniform_grid_cells", "uniform_grid_error", "uniform_grid_reach"]

GRIDS = ("sommerfeld", "uniform")
PROFILES = ("thin", "eccentric")
MIN_CELLS = 8
MAX_CELLS = 1 << 20
MAX_POINTS_PER_CELL = 8


def uniform_grid_error(n: int, kappa: float) -> float:
    """Estimated relative error of the forces on the grid uniform in theta with ``n`` cells.

    The film's integrands are analytic in theta with poles at distance
    alpha = acosh(1/kappa) from the real axis, so the composite rule's error
    falls as exp(-n alpha); measured, the largest error of the five coefficients
    (T_a per W_b against its row) is 0.4-1.3 (n alpha)^2 exp(-n alpha) for
    kappa in [0.3, 0.9999] and n in [8, 1024] with n alpha > 2. The estimate
    takes the prefactor 1.5, an upper bound, and 1 (nothing resolved) for
    n alpha <= 2, fewer cells than the pressure peak is wide. On the Sommerfeld
    grid the thin-gap forces are exact to rounding from 8 cells.
    """
    if kappa <= 0.0:
        return 0.0
    x = n * math.acosh(1.0 / kappa)
    if x <= 2.0:  # fewer cells than the peak's width: unresolved
        return 1.0
    return min(1.0, 1.5 * x * x * math.exp(-x))


def uniform_grid_cells(kappa: float, tolerance: float) -> int:
    """The fewest cells of the uniform-theta grid whose :func:`uniform_grid_error` at ``kappa`` meets ``tolerance``
    (MAX_CELLS if none does). The estimate falls with n beyond its peak at n = 2/acosh(1/kappa): a bisection there."""
    if kappa <= 0.0:
        return MIN_CELLS
    low = max(MIN_CELLS, math.ceil(2.0 / math.acosh(1.0 / kappa)))
    if uniform_grid_error(low, kappa) <= tolerance:
        return low
    high = MAX_CELLS
    if uniform_grid_error(high, kappa) > tolerance:
        return MAX_CELLS
    while high - low > 1:  # error(low) > tolerance >= error(high)
        mid = (low + high) // 2
        low, high = (low, mid) if uniform_grid_error(mid, kappa) <= tolerance else (mid, high)
    return high


def uniform_grid_reach(n: int, tolerance: float) -> float:
    """The largest kappa at which ``n`` cells uniform in theta meet ``tolerance`` (:func:`uniform_grid_error`).

    The estimate is 1.5 x^2 exp(-x) in x = n acosh(1/kappa), falling for x > 2;
    the root x* >= 2 of 1.5 x^2 exp(-x) = tolerance gives kappa = 1/cosh(x*/n).
    """
    if not 0.0 < tolerance < 1.0:
        msg = f"tolerance must be in (0, 1), got {tolerance!r}"
        raise ValueError(msg)
    x = 2.0 + 2.0 * math.log(1.0 / tolerance)  # an upper bracket: there 1.5 x^2 e^-x < tolerance
    low = 2.0
    for _ in range(200):  # bisection to rounding
        mid = 0.5 * (low + x)
        if mid in (low, x):
            break
        low, x = (mid, x) if 1.5 * mid * mid * math.exp(-mid) > tolerance else (low, mid)
    return 1.0 / math.cosh(x / n)


@dataclass(frozen=True)
class GapProfile:
    """A user-supplied gap: ``h(theta)`` in m and, optionally, ``h_dot(theta)`` in m/s.

    Both are vectorised callables of theta (rad, measured from the line of
    centres in the positive sense), 2 pi periodic and smooth. ``h_dot`` is the
    rate of change at fixed theta in the frame of the line of centres; the gap
    area must be conserved, oint h_dot dtheta = 0, as for the thin gap.
    """

    h: Callable[[np.ndarray], np.ndarray]
    h_dot: Callable[[np.ndarray], np.ndarray] | None = None


@dataclass(frozen=True)
class ReynoldsPressure:
    """Nodal pressure (Pa, zero mean over theta) at angles ``theta`` (rad)."""

    theta: np.ndarray
    p: np.ndarray


@lru_cache(maxsize=64)
def psi_rule(n: int, m: int):
    """Composite m-point Gauss-Legendre rule on N equal cells of psi in (-pi, pi].

    Returns cos, sin, 1 - cos, 1 + cos of psi and the weights at the N*m
    points, and psi at the N cell edges (the pressure nodes). The versines are
    formed from half angles so that they keep full relative precision.
    """
    _, g = np.polynomial.legendre.leggauss(m)
    dpsi = 2.0 * np.pi / n
    nodes = -np.pi + dpsi * np.arange(n)
    psi = _gauss_points(n, m).ravel()
    w = np.tile(0.5 * dpsi * g, n)
    half = 0.5 * psi
    rule = (np.cos(psi), np.sin(psi), 2.0 * np.sin(half) ** 2, 2.0 * np.cos(half) ** 2, w)
    for arr in (*rule, nodes):  # shared by every caller through the cache
        arr.setflags(write=False)
    return rule, nodes


def _theta_of_psi(psi: np.ndarray, kappa_g: float) -> np.ndarray:
    """theta in (-pi, pi] from psi under the Sommerfeld map.

    tan^2(theta/2) = (1 - cos theta)/(1 + cos theta) = (1 - kappa_g)/(1 + kappa_g) tan^2(psi/2).
    """
    beta = math.sqrt((1.0 - kappa_g) / (1.0 + kappa_g))
    return 2.0 * np.arctan2(beta * np.sin(0.5 * psi), np.cos(0.5 * psi))


def _check_discretisation(n: int, grid: str, points_per_cell: int) -> None:
    if grid not in GRIDS:
        msg = f"grid must be one of {', '.join(GRIDS)}, got {grid!r}"
        raise ValueError(msg)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not MIN_CELLS <= n <= MAX_CELLS:
        msg = f"n (cells around the gap) must be an integer in [{MIN_CELLS}, {MAX_CELLS}], got {n!r}"
        raise ValueError(msg)
    m = points_per_cell
    if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or not 1 <= m <= MAX_POINTS_PER_CELL:
        msg = f"points_per_cell must be an integer in [1, {MAX_POINTS_PER_CELL}], got {m!r}"
        raise ValueError(msg)


def _tabulate(profile: GapProfile, annulus: Annulus, n: int, m: int, grid: str):
    """The profile's eccentricity, grid centre, kappa_g, and h and the squeeze flux Q at the points.

    The profile's eccentricity is (h_max - h_min)/(h_max + h_min); the Sommerfeld
    grid is centred on the narrowest gap and uses it as kappa_g.
    """
    probe = np.linspace(-np.pi, np.pi, 4096, endpoint=False)
    h_probe = _evaluate("h", profile.h, probe)
    i_min = int(np.argmin(h_probe))
    _check_positive(h_probe, probe)
    kappa_p = float((np.max(h_probe) - h_probe[i_min]) / (np.max(h_probe) + h_probe[i_min]))
    centre, kappa_g = (float(probe[i_min]), kappa_p) if grid == "sommerfeld" else (0.0, 0.0)
    psi = _gauss_points(n, m)
    theta = centre + _theta_of_psi(psi, kappa_g)
    h = _evaluate("h", profile.h, theta.ravel())
    _check_positive(h, theta.ravel())
    if profile.h_dot is None:
        return kappa_p, centre, kappa_g, h, np.zeros_like(h)
    # the trapezoid rule on the uniform probe is spectrally accurate for a periodic rate
    h_dot_probe = _evaluate("h_dot", profile.h_dot, probe)
    net, scale = abs(float(np.sum(h_dot_probe))), float(np.sum(np.abs(h_dot_probe)))
    if net > 1e-8 * scale:
        msg = ("gap profile h_dot must conserve the gap area (oint h_dot dtheta = 0); "
               f"its mean is {net / probe.size:g} m/s against a mean magnitude of {scale / probe.size:g} m/s")
        raise ValueError(msg)

    def rate(psi_):
        # a dh/dt dtheta/dpsi: the squeeze source per unit psi
        theta_ = centre + _theta_of_psi(psi_, kappa_g)
        return annulus.a * _evaluate("h_dot", profile.h_dot, theta_.ravel()).reshape(psi_.shape) * \
            _jacobian(psi_, kappa_g)

    return kappa_p, centre, kappa_g, h, _antiderivative(rate, n, m).ravel()


def _gauss_points(n: int, m: int) -> np.ndarray:
    """psi at the m Gauss points of each of the N cells, shape (N, m)."""
    x, _ = np.polynomial.legendre.leggauss(m)
    dpsi = 2.0 * np.pi / n
    return -np.pi + dpsi * (np.arange(n)[:, None] + 0.5 * (x[None, :] + 1.0))


def _antiderivative(rate: Callable, n: int, m: int) -> np.ndarray:
    """int_{-pi}^{psi} rate at the Gauss points, shape (N, m), to the rule's order 2m.

    Each point gets the whole cells before it plus its own cell's start, integrated
    with the m-point rule mapped onto that sub-interval.
    """
    x, g = np.polynomial.legendre.leggauss(m)
    dpsi = 2.0 * np.pi / n
    psi = _gauss_points(n, m)
    start = -np.pi + dpsi * np.arange(n)
    cells = np.sum(rate(psi) * (0.5 * dpsi * g), axis=1)
    span = psi - start[:, None]
    sub = start[:, None, None] + span[:, :, None] * 0.5 * (x + 1.0)
    partial = np.sum(rate(sub) * span[:, :, None] * 0.5 * g, axis=2)
    before = np.concatenate(([0.0], np.cumsum(cells)[:-1]))
    return before[:, None] + partial


def _jacobian(psi: np.ndarray, kappa_g: float) -> np.ndarray:
    """dtheta/dpsi of the Sommerfeld map."""
    return math.sqrt(1.0 - kappa_g**2) / (1.0 + kappa_g * np.cos(psi))


def _check_positive(h: np.ndarray, theta: np.ndarray) -> None:
    i = int(np.argmin(h))
    if not h[i] > 0.0:
        msg = f"gap profile h must stay positive; h = {h[i]:g} m at theta = {theta[i]:.4f} rad"
        raise ValueError(msg)


def _evaluate(name: str, fn: Callable, theta: np.ndarray) -> np.ndarray:
    values = np.asarray(fn(theta), dtype=float)
    if values.shape != theta.shape:
        msg = f"gap profile {name} must return an array shaped like theta {theta.shape}, got {values.shape}"
        raise ValueError(msg)
    if not np.all(np.isfinite(values)):
        msg = f"gap profile {name} must be finite for every theta"
        raise ValueError(msg)
    return values


_EMPTY = np.empty(0)


def film_setup(annulus: Annulus, profile, n: int, grid: str, points_per_cell: int):
    """Everything a film kernel needs besides the motion, for a built-in or user profile.

    Returns
    -------
    kind : int
        Kernel profile code.
    kappa, omk : float
        Eccentricity and 1 - kappa (for a user profile, its own; see :func:`_tabulate`).
    kappa_g, omk_g : float
        Grid parameter and 1 - kappa_g.
    centre : float
        Angle of the grid's centre line from the line of centres (rad).
    h_tab, q_tab : ndarray
        Gap and squeeze flux at the points of a user profile, else empty.
    rule : tuple of ndarray
        cos, sin, 1 - cos, 1 + cos of psi and the weights at the points.
    nodes : ndarray
        psi at the pressure nodes.
    """
    _check_discretisation(n, grid, points_per_cell)
    rule, nodes = psi_rule(n, points_per_cell)
    kappa, omk = annulus.kappa, annulus.one_minus_kappa
    if isinstance(profile, GapProfile):
        kappa, centre, kappa_g, h_tab, q_tab = _tabulate(profile, annulus, n, points_per_cell, grid)
        return reynolds_kernels.TABULATED, kappa, 1.0 - kappa, kappa_g, 1.0 - kappa_g, centre, h_tab, q_tab, rule, nodes
    if profile not in PROFILES:
        msg = f"profile must be one of {', '.join(PROFILES)} or a GapProfile, got {profile!r}"
        raise ValueError(msg)
    kind = reynolds_kernels.THIN if profile == "thin" else reynolds_kernels.ECCENTRIC
    kappa_g, omk_g = (kappa, omk) if grid == "sommerfeld" else (0.0, 1.0)
    return kind, kappa, omk, kappa_g, omk_g, 0.0, _EMPTY, _EMPTY, rule, nodes


def _solve(annulus: Annulus, motion: Motion, fluid: Fluid, profile, n: int, grid: str,
           points_per_cell: int, phi_out: np.ndarray):
    """Run the full-film kernel; return (f_eps, f_chi, T_a), the grid centre and kappa_g."""
    kind, kappa, omk, kappa_g, omk_g, centre, h_tab, q_tab, rule, _ = film_setup(
        annulus, profile, n, grid, points_per_cell)
    f = reynolds_kernels.film_forces(kind, annulus.a, annulus.b, fluid.mu, annulus.length, kappa, omk,
                             motion.eps_dot, motion.w_a, motion.w_b, kappa_g, omk_g, *rule,
                             points_per_cell, h_tab, q_tab, math.cos(centre), math.sin(centre), phi_out)
    return f, centre, kappa_g


def reynolds_forces(annulus: Annulus, motion: Motion, fluid: Fluid, *, n: int = 32,
                    grid: str = "sommerfeld", profile: str | GapProfile = "thin",
                    points_per_cell: int = 2) -> FluidForces:
    """Force and torque on the inner cylinder from the Reynolds equation, (B13)-(B15).

    Parameters
    ----------
    annulus, motion, fluid
        Geometry, velocities and fluid.
    n : int
        Cells around the gap (pressure nodes), at least 8.
    grid : {"sommerfeld", "uniform"}
        Cells uniform in the Sommerfeld angle psi (clustered at the narrowest
        gap; accuracy independent of kappa for the thin gap) or uniform in theta.
    profile : {"thin", "eccentric"} or GapProfile
        The thin-gap profile delta (1 - kappa cos theta) of (B1), the exact gap
        between the eccentric circles, or a user profile.
    points_per_cell : int
        Gauss points per cell. Nodal pressures converge as dpsi^(2 m); the force
        and torque of the built-in profiles spectrally in N m; for a user profile
        with h_dot, whose squeeze flux is integrated cell by cell, as dpsi^(2 m).

    Returns
    -------
    FluidForces
        f_eps, f_chi (N) and T_a (N m) over the length of the annulus.
    """
    f, _, _ = _solve(annulus, motion, fluid, profile, n, grid, points_per_cell, _EMPTY)
    return FluidForces(*f, model="reynolds")


def reynolds_pressure(annulus: Annulus, motion: Motion, fluid: Fluid, *, n: int = 64,
                      grid: str = "sommerfeld", profile: str | GapProfile = "thin",
                      points_per_cell: int = 2) -> ReynoldsPressure:
    """Full-film pressure at the N nodes of the grid, with zero mean over theta.

    The nodal values carry only the cell quadrature error, O(dpsi^(2 m)).
    """
    _check_discretisation(n, grid, points_per_cell)
    phi = np.empty(n)
    _, centre, kappa_g = _solve(annulus, motion, fluid, profile, n, grid, points_per_cell, phi)
    _, nodes = psi_rule(n, points_per_cell)
    theta = centre + _theta_of_psi(nodes, kappa_g)
    p = 12.0 * fluid.mu * annulus.a * phi
    # zero mean in theta: trapezoid rule in psi with the map's Jacobian
    weights = _jacobian(nodes, kappa_g)
    p -= np.sum(p * weights) / np.sum(weights)
    return ReynoldsPressure(theta=theta, p=p)


# -- the kernel of the model "reynolds" (lubrication.film) ------------------------------------------

#: The cells of a trajectory's film by default: on the Sommerfeld grid the thin-gap forces are exact to
#: rounding from 8 (one instant takes 32, and 256 with cavitation, whose boundary converges as 1/N^2).
TRAJECTORY_CELLS = 16
#: The block of a film model's kernel: the gap profile, the Sommerfeld grid (1) or not, Gauss points per
#: cell, the cavitation model (its index in lubrication.cavitation.CAVITATION_MODELS), p_cav and p_ref (Pa),
#: then the rule's five arrays (cos, sin, 1 - cos, 1 + cos of psi, weights).
_PROFILE, _SOMMERFELD, _POINTS, _CAVITATION, _P_CAV, _P_REF, _RULE = range(7)


def film_block(n: int = TRAJECTORY_CELLS, grid: str = "sommerfeld", profile: str = "thin", points_per_cell: int = 1,
               cavitation: int = 0, p_cav: float = 0.0, p_ref: float = 101325.0) -> np.ndarray:
    """The packed block of a Reynolds film's kernel (:func:`reynolds_kernel`, the cavitating one)."""
    _check_discretisation(n, grid, points_per_cell)
    if profile not in PROFILES:
        msg = f"profile must be one of {', '.join(PROFILES)}, got {profile!r}"
        raise ValueError(msg)
    gap = reynolds_kernels.THIN if profile == "thin" else reynolds_kernels.ECCENTRIC
    rule = psi_rule(n, points_per_cell)[0]
    head = [gap, float(grid == "sommerfeld"), points_per_cell, cavitation, p_cav, p_ref]
    return np.concatenate([np.asarray(head, dtype=float), *rule])


@jit(inline="always")
def film_rule(block):
    """The grid's kappa flag, points per cell and the rule's five arrays (views of ``block``)."""
    m = (block.size - _RULE) // 5
    r = _RULE
    return (block[_SOMMERFELD] != 0.0, int(block[_POINTS]), block[r:r + m], block[r + m:r + 2 * m],
            block[r + 2 * m:r + 3 * m], block[r + 3 * m:r + 4 * m], block[r + 4 * m:r + 5 * m])


@jit
def reynolds_kernel(data, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """The "reynolds" model's kernel (:mod:`lubrication.kernels`): the full film on the block's grid."""
    block = model_block(data)
    sommerfeld, m, cpsi, spsi, vpsi, ppsi, wpsi = film_rule(block)
    kappa_g, omk_g = (kappa, omk) if sommerfeld else (0.0, 1.0)
    none = np.empty(0)  # no tabulated profile, no pressure wanted (a global would be read-only)
    return reynolds_kernels.film_forces(int(block[_PROFILE]), a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, kappa_g,
                                omk_g, cpsi, spsi, vpsi, ppsi, wpsi, m, none, none, 1.0, 0.0, none)
