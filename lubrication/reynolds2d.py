r"""The Reynolds equation on (theta, z): an annulus of finite length L.

Every other force model of the package is per unit length of an infinitely
long annulus. The apparatus' inner cylinder is L = 10.35 cm long (L/2a = 6.47)
and its gap opens at z = +-L/2 into the oil-filled ends of the tube, so the gap
pressure must fall to the end pressure p_end there. With x = a theta the
two-dimensional Reynolds equation, in the conventions of the one-dimensional
solver (:mod:`lubrication.reynolds`, Appendix B of the paper), is

    (1/a^2) d/dtheta (h^3 dp/dtheta) + d/dz (h^3 dp/dz) = (6 mu / a) (U_a + U_b) dh/dtheta + 12 mu dh/dt,

U_a = a W_a, U_b = a W_b (b W_b for the exact eccentric gap), W_a = Omega_a - chi',
W_b = Omega_b - chi'. It states conservation of the liquid per unit theta and z,
a dh/dt + d q_theta/dtheta + a d q_z/dz = 0, with the fluxes
q_theta = U h/2 - h^3 p_theta/(12 mu a) and q_z = -h^3 p_z/(12 mu); for the exact
gap the squeeze source is that of the one-dimensional kernel (the sector area
a h + h^2/2) and the conductance h^3 the same in both directions. Ends:

* ``"open"``: p = p_end at z = +-L/2 (the gap opens into the end regions);
* ``"sealed"``: dp/dz = 0 at z = +-L/2; a z-independent gap then has the
  one-dimensional solution for every L.

Forces over the length, by parts in theta on every z-line as in (B13)-(B15):
f_eps = 12 mu a^2 int dz oint phi' sin, f_chi = 12 mu a^2 int dz oint phi' omega,
T_a = mu a^2 int dz oint [(U_b - U_a)/h - 6 phi' h] (Couette and Poiseuille
parts), phi = (p - p_end)/(12 mu a).

Discretisation
--------------
Tensor grid (xi_j, z_k). In theta the cells of the one-dimensional solver,
with the exact cell conductances 1/int h^-3 and the exact squeeze and Couette
loads of that scheme, on cells uniform in a computational angle xi mapped by

    tan(theta/2) = beta^c(xi) tan(xi/2),   c(xi) = c_w + (c_n - c_w) cos^2(xi/2),

beta = sqrt((1 - kappa)/(1 + kappa)) ~ zeta/2, zeta = sqrt(1 - kappa^2). A
constant exponent c_n = c_w = c is the Sommerfeld map with beta_g = beta^c
(c = 1: the one-dimensional grid, the default for sealed ends, on which every
thin-gap integrand of the one-dimensional problem is a trigonometric polynomial;
0: uniform in theta). In two dimensions that is not so (the axial term carries
h^3 dtheta/dpsi ~ (1 + kappa cos psi)^-4, which peaks on the wide side), and the
grid has to resolve every angular scale of the pressure: the narrow gap
(theta ~ zeta), where the force is made, and, for the ends, every theta from
zeta to 1, since the rotation's pressure decays only algebraically away from
the narrow gap and each angular scale theta has an end layer a theta long (the
zeta log(1/zeta) deficit of :mod:`lubrication.finite_length`). A constant c
gives the narrow gap a share ~ beta^(1 - c) of the cells, the wide side ~ beta^c,
and the scales between few; ``clustering`` = (c_n, c_w) grades the grid from
the angular scale beta^c_n at the narrow gap to beta^c_w on the wide side with
about N/(pi (c_n - c_w) log(1/beta)) cells per e-fold of theta in between. The
default (:func:`default_clustering`) is c_n = c_w = 1/2 (halfway on a log
scale, as the Stokes meshes, :mod:`lubrication.stokes_mesh`) while
beta >= 1/25 (kappa <= 0.9968); closer to contact c_n = 1 - log 5/log(1/beta)
and c_w = 1 - c_n: the scale 5 beta at the narrow gap, 1/5 on the wide side.
In the kernels' terms psi = 2 arctan(tan(xi/2) exp(gamma sin^2(xi/2))),
gamma = (c_n - c_w) log(1/beta), is the Sommerfeld angle of beta_g = beta^c_n,
and the quadrature weights and cell masses carry dpsi/dxi. Measured at
L/a = 12.9, n_axial = 64, against grids of 8192 cells: with a single scale, the
rotation factor's error at N = 128 grew to 2e-3 at 1 - kappa = 1e-6 and
3e-4 at 1e-9 (where it still moved at N = 8192); the graded grid is second
order there and its error at N = 128 is 1.8e-5 at 1 - kappa = 1e-6,
2e-6 at 1e-9 (8e-5 or less for every 1 - kappa from 1e-2 to 1e-12).

In z (units of a) the nodes are graded toward the open end, where the
pressure boundary layer sits: its width is a times the angular scale of the
pressure, a zeta near contact (zeta = sqrt(1 - kappa^2)) and ~ a far from it,
and the layer is a sum of exponentials exp(-d/l) with l between the two
(d the distance from the end). A geometric grading resolves every such scale
with the same number of nodes: d(s) = l_end (exp(beta_z (1 - s)) - 1), s uniform
in [0, 1] from the mid-plane to the end, beta_z = log(1 + L/(2 l_end)), l_end =
``end_layer`` (default a zeta/2; measured: l_end between a zeta/4 and a zeta/2 gives
the smallest errors, and a uniform grid 4 to 500 times larger ones for kappa from
0.3 to 0.9999). Sealed ends have no layer: uniform nodes.

The scheme is the tensor-product linear-element (Q1) Galerkin method with the
theta stiffness replaced by the exact-conductance one:

    (M_z (x) L_theta + K_z (x) M_theta) phi = -(w_z (x) r),

L_theta and r the one-dimensional operator and load of each line, M_theta the
consistent linear-element mass of the weight h^3 in theta, K_z and M_z the
linear-element stiffness and mass in z, w_z the trapezoid weights. The
consistent masses were measured to give errors 1.5 to 4 times smaller than
lumped ones near contact.

Forces: on each line the one-dimensional by-parts rule, which within a cell
takes h^3 phi' = (U/2) h + Q - c_j (the theta-flux balances the squeeze alone;
exact for a long bearing), corrected by the flux that leaves the cell axially:
h^3 phi' = (U/2) h + Q + int h^3 d - c_j, with d = -(1/h^3) d/dz (h^3 dphi/dz)
from the discrete solution, linear in the cell
(:func:`lubrication.reynolds2d_kernels.flux_correction`); then the trapezoid rule over
the lines. Without the correction the cells would carry a spurious intra-cell
Couette flux whose force is O(dpsi^2) of the long-bearing one: harmless at the
apparatus' length, but it swamps a short bearing's force, which is
O((L/a)^2) of it (measured: a relative error of 3 at L/a = 0.05, N = 64; with
the correction 3e-2). On an open end line, where phi = 0, all of the load
leaves axially: M_theta d = -r.

Accuracy. The error is second order in both directions, O(dxi^2) + O(ds^2),
with smooth maps, and the Richardson combination of a grid and its half
(``extrapolate``) is fourth order in each direction (tests/test_reynolds2d.py
measures all four). At L/a = 12.9 and (N, n_axial) = (128, 64) the error
is 5e-5 to 1.2e-4 plain for kappa from 0 to 0.99 and 2.1e-5 or less nearer
contact, and 1.7e-7 to 1.6e-6 extrapolated for kappa from 0 to 1 - 1e-9
(benchmarks/results/reynolds2d.md, against (4096, 2048) extrapolated; 1 - kappa
= 1e-6 in the tests). Near contact the extrapolation needs N >= 64: its half
grid must itself resolve the graded scales, and from (32, 16) it is worse than
the plain solve (4e-3 at 1 - kappa = 1e-6). Closer to contact than 1 - kappa ~ 1e-10 the rotation's axial modes meet a
rounding floor: with n_axial = 512 its factor moved by 8e-7 (1 - F_chi = 5e-6)
at 1 - kappa = 1e-11 where it should have converged, and at 1e-12 the solver
is only finite and bounded (tested). The linear d leaves an
O(dxi^4 (a/L)^2) term, which matters only for bearings shorter than their
radius: of order 1e-3 at L/a = 0.2 with N = 256, 1e-2 at L/a = 0.1 with N = 128.

Solvers
-------
* z-independent gaps (thin, eccentric, a one-dimensional
  :class:`~lubrication.reynolds.GapProfile`): the operator separates. The
  generalised eigenvectors of K_z v = lam M_z v (M_z-orthonormal) turn the
  system into one periodic tridiagonal problem per z-mode,
  (L_theta + lam M_theta) psi = -c r with c = v^T w_z, whose force integrals
  need no reconstruction of the field (:func:`lubrication.reynolds2d_kernels.modal_film`).
  The mid-plane symmetry halves the z-grid. Cost O(N n_z) per solve after an
  O(n_z^3) eigen-decomposition that depends only on the z-grid and is cached.
* A gap h(theta, z) (:class:`GapProfile2D`, e.g. :func:`tilted_gap`): the
  sparse system assembled by a kernel and solved by a sparse LU (SuperLU); the
  half length when the profile is mirror-symmetric in z (checked), else the
  whole length.

Cavitation
----------
With open ends the absolute pressure is fixed (p_end), so the half-Sommerfeld
(Guembel) truncation p -> max(p, p_cav) carries over: nodal pressures are
truncated and each line's force integrals count a cell that straddles p_cav
with the fraction above it, as the one-dimensional rule. Swift-Stieber
(Reynolds) and the mass-conserving JFO model do not carry over here: in two
dimensions they are complementarity problems on the whole (theta, z) grid
with a free boundary that moves in z as well; with sealed ends the problem is
the one-dimensional one for a z-independent gap, whose cavitation models are
in :mod:`lubrication.cavitation`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from . import reynolds2d_kernels, reynolds_kernels
from .geometry import Annulus, Fluid, FluidForces, Motion, check_finite, check_range
from .reynolds import (
    PROFILES,
    GapProfile,
    _antiderivative,
    _check_positive,
    _gauss_points,
    _jacobian,
    _theta_of_psi,
    psi_rule,
)

__all__ = [
    "CAVITATION_2D",
    "ENDS",
    "MIN_AXIAL_CELLS",
    "GapProfile2D",
    "Reynolds2DPressure",
    "axial_grid",
    "grid_parameter",
    "reynolds2d_forces",
    "reynolds2d_pressure",
    "tilted_gap",
]

ENDS = ("open", "sealed")
CAVITATION_2D = ("none", "half-sommerfeld")
MIN_CELLS = 8
MAX_CELLS = 1 << 16
MIN_AXIAL_CELLS = 4
MAX_AXIAL_CELLS = 4096
#: Clustering exponent of the theta grid with open ends away from contact (module docstring).
DEFAULT_CLUSTERING = 0.5
#: Near contact the narrow gap's angular scale on the grid is at most this many times beta (module docstring).
NARROW_SCALE = 5.0
#: Relative asymmetry below which a gap h(theta, z) counts as mirror-symmetric in z.
SYMMETRY_TOLERANCE = 1e-13


@dataclass(frozen=True)
class GapProfile2D:
    """A gap that varies along the axis: ``h(theta, z)`` in m and, optionally, ``h_dot(theta, z)`` in m/s.

    Vectorised callables of theta (rad, from the line of centres in the positive
    sense) and z (m, from the mid-plane, |z| <= L/2), broadcasting their two
    arguments; 2 pi periodic and smooth in theta. ``h_dot`` is the rate of
    change at fixed (theta, z) in the frame of the line of centres and must
    conserve the gap area of every cross-section, oint h_dot dtheta = 0, as the
    rigid motions of circular cylinders do.
    """

    h: Callable[[np.ndarray, np.ndarray], np.ndarray]
    h_dot: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None


@dataclass(frozen=True)
class Reynolds2DPressure:
    """The film on the (theta, z) grid, and the forces it gives.

    Attributes
    ----------
    theta : ndarray, shape (N,)
        Node angles (rad) from the line of centres.
    z : ndarray, shape (n_z,)
        Node positions (m) from -L/2 to L/2.
    p : ndarray, shape (n_z, N)
        Pressure (Pa): absolute (p_end at open ends, truncated at p_cav under
        half-Sommerfeld); with sealed ends, defined up to a constant and given with
        zero mean over the nodes.
    f_eps_per_length, f_chi_per_length : ndarray, shape (n_z,)
        Force per unit length on each z-line (N/m).
    t_a_per_length : ndarray, shape (n_z,)
        Torque per unit length (N m/m).
    forces : FluidForces
        Over the whole length.
    """

    theta: np.ndarray
    z: np.ndarray
    p: np.ndarray
    f_eps_per_length: np.ndarray
    f_chi_per_length: np.ndarray
    t_a_per_length: np.ndarray
    forces: FluidForces


def tilted_gap(annulus: Annulus, tilt: float, *, azimuth: float = 0.0, tilt_rate: float = 0.0,
               eps_dot: float = 0.0) -> GapProfile2D:
    """Thin gap of an inner cylinder whose axis is tilted by ``tilt`` about its mid-point.

    At height z the inner axis is displaced by eps e_eps + z tilt e_t, with e_t at
    angle ``azimuth`` from e_eps (0: tilted in the plane of the line of
    centres), so the local thin gap and its rate are

        h = delta - eps cos(theta) - z tilt cos(theta - azimuth),
        dh/dt = -eps' cos(theta) - z tilt' cos(theta - azimuth),

    both conserving each cross-section's area. A misalignment of the two axes
    is the same gap.

    Parameters
    ----------
    annulus : Annulus
        Radii, eccentricity at the mid-plane and length L.
    tilt : float
        Angle between the axes (rad, small); the ends must not touch:
        kappa delta + tilt L/2 < delta.
    azimuth : float
        Direction of the tilt from e_eps (rad).
    tilt_rate, eps_dot : float
        tilt' (rad/s) and eps' (m/s) for the squeeze term.
    """
    tilt = check_finite("tilt", tilt)
    azimuth = check_finite("azimuth", azimuth)
    tilt_rate = check_finite("tilt_rate", tilt_rate)
    eps_dot = check_finite("eps_dot", eps_dot)
    delta, eps, half = annulus.delta, annulus.eps, 0.5 * annulus.length
    reach = math.hypot(eps + half * tilt * math.cos(azimuth), half * tilt * math.sin(azimuth))
    reach = max(reach, math.hypot(eps - half * tilt * math.cos(azimuth), half * tilt * math.sin(azimuth)))
    if not reach < delta:
        msg = (f"tilt must keep the ends apart: the largest eccentricity along the axis is {reach:g} m "
               f"against a mean gap of {delta:g} m (tilt {tilt!r} rad)")
        raise ValueError(msg)

    def h(theta, z):
        return delta - eps * np.cos(theta) - z * tilt * np.cos(theta - azimuth)

    def h_dot(theta, z):
        return -eps_dot * np.cos(theta) - z * tilt_rate * np.cos(theta - azimuth)

    return GapProfile2D(h=h, h_dot=h_dot)


def default_clustering(kappa: float, omk: float) -> tuple[float, float]:
    """The default (narrow, wide) exponents of the theta grid with open ends: (c, 1 - c).

    c = max(1/2, 1 - log(NARROW_SCALE)/log(1/beta)): the single-scale grid
    beta_g = beta^(1/2) down to beta = 1/NARROW_SCALE^2 (kappa = 0.9968); closer
    to contact the grid's scale at the narrow gap stays within NARROW_SCALE
    times beta ~ zeta/2 and the exponent falls to 1 - c toward the wide side,
    so that every angular scale between them gets cells (module docstring).
    """
    beta_sq = omk / (1.0 + kappa)
    if beta_sq * NARROW_SCALE**4 >= 1.0:
        return DEFAULT_CLUSTERING, DEFAULT_CLUSTERING
    c = 1.0 - 2.0 * math.log(NARROW_SCALE) / math.log(1.0 / beta_sq)
    return c, 1.0 - c


def grading(kappa: float, omk: float, narrow: float, wide: float) -> float:
    """gamma = (narrow - wide) log(1/beta) of the graded map (module docstring); 0 for a single-scale grid."""
    if narrow == wide:
        return 0.0
    return 0.5 * (narrow - wide) * math.log((1.0 + kappa) / omk)


def _check_clustering(clustering) -> tuple[float, float]:
    """A number c means (c, c); a pair is (narrow, wide) with 0 <= wide <= narrow <= 1."""
    pair = (clustering, clustering) if np.ndim(clustering) == 0 else tuple(clustering)
    ok = len(pair) == 2
    if ok:
        try:
            narrow, wide = (float(c) for c in pair)
        except (TypeError, ValueError):
            ok = False
    if not (ok and 0.0 <= wide <= narrow <= 1.0):
        msg = (f"clustering must be a number in [0, 1] or a pair (narrow, wide) with "
               f"0 <= wide <= narrow <= 1, got {clustering!r}")
        raise ValueError(msg)
    return narrow, wide


def _sommerfeld_angle(xi: np.ndarray, gamma: float) -> tuple[np.ndarray, np.ndarray]:
    """psi(xi) and dpsi/dxi of the graded map tan(psi/2) = tan(xi/2) exp(gamma sin^2(xi/2)).

    With c2 = cos^2(xi/2), s2 = sin^2(xi/2) and e = exp(gamma s2),
    dpsi/dxi = (1 + 2 gamma s2 c2)/(c2/e + s2 e): 1 at xi = 0, exp(-gamma) at xi = pi,
    positive for gamma >= 0; formed without tan(xi/2), which is infinite at xi = pi.
    """
    half = 0.5 * xi
    s2 = np.sin(half) ** 2
    c2 = np.cos(half) ** 2
    e = np.exp(gamma * s2)
    psi = 2.0 * np.arctan2(np.sin(half) * e, np.cos(half))
    return psi, (1.0 + 2.0 * gamma * s2 * c2) / (c2 / e + s2 * e)


def _half_angle(xi: np.ndarray, gamma: float) -> tuple[np.ndarray, np.ndarray]:
    """sin(psi/2) and cos(psi/2) of the graded map, formed without psi (which rounds near +-pi)."""
    half = 0.5 * xi
    y = np.sin(half) * np.exp(gamma * np.sin(half) ** 2)
    x = np.cos(half)
    r = np.hypot(x, y)
    return y / r, x / r


@lru_cache(maxsize=64)
def _theta_rule(n: int, m: int, gamma: float):
    """The cells' quadrature rule for the kernels and the nodes' psi (cached: a solve at one kappa
    is repeated for each motion and for the extrapolation's half grid).

    Returns cos, sin, 1 - cos, 1 + cos of psi at the N m Gauss points of N equal
    cells in xi, the weights (in psi: times dpsi/dxi) and dpsi/dxi itself; and psi
    at the cell edges. gamma = 0 is the one-dimensional solver's rule, psi = xi.
    """
    if gamma == 0.0:
        rule, nodes = psi_rule(n, m)
        stretch = np.ones(n * m)
        stretch.setflags(write=False)
        return (*rule, stretch), nodes
    _, g = np.polynomial.legendre.leggauss(m)
    xi = _gauss_points(n, m).ravel()
    _, stretch = _sommerfeld_angle(xi, gamma)
    sin_half, cos_half = _half_angle(xi, gamma)
    weights = np.tile(0.5 * (2.0 * np.pi / n) * g, n) * stretch
    rule = ((cos_half - sin_half) * (cos_half + sin_half), 2.0 * sin_half * cos_half, 2.0 * sin_half**2,
            2.0 * cos_half**2, weights, stretch)
    nodes, _ = _sommerfeld_angle(-np.pi + (2.0 * np.pi / n) * np.arange(n), gamma)
    for arr in (*rule, nodes):  # shared by every caller through the cache
        arr.setflags(write=False)
    return rule, nodes


def grid_parameter(kappa: float, omk: float, clustering: float) -> tuple[float, float]:
    """(kappa_g, 1 - kappa_g) of the theta grid: beta_g = beta^clustering (module docstring).

    beta^2 = (1 - kappa)/(1 + kappa) and 1 - kappa_g = 2 beta_g^2/(1 + beta_g^2),
    both formed from 1 - kappa without cancellation.
    """
    beta_sq = omk / (1.0 + kappa)
    beta_g_sq = beta_sq**clustering
    omk_g = 2.0 * beta_g_sq / (1.0 + beta_g_sq)
    return 1.0 - omk_g, omk_g


def axial_grid(half_length: float, n_half: int, end_layer: float | None) -> np.ndarray:
    """z nodes from the mid-plane to the end, shape (n_half + 1,), in the unit of the arguments.

    ``end_layer`` is l_end of the geometric grading (module docstring); None
    gives uniform nodes.
    """
    s = np.arange(n_half + 1) / n_half
    if end_layer is None:
        return half_length * s
    beta = math.log1p(half_length / end_layer)
    z = half_length - end_layer * np.expm1(beta * (1.0 - s))
    z[0], z[-1] = 0.0, half_length
    return z


def _axial_matrices(z: np.ndarray):
    """Linear-element stiffness and mass tridiagonals in z, and the trapezoid weights."""
    dz = np.diff(z)
    k_diag = np.zeros(z.size)
    k_diag[:-1] += 1.0 / dz
    k_diag[1:] += 1.0 / dz
    m_diag = np.zeros(z.size)
    m_diag[:-1] += dz / 3.0
    m_diag[1:] += dz / 3.0
    weights = np.zeros(z.size)
    weights[:-1] += 0.5 * dz
    weights[1:] += 0.5 * dz
    return k_diag, -1.0 / dz, m_diag, dz / 6.0, weights


@lru_cache(maxsize=64)
def _axial_modes(half_length: float, n_half: int, end_layer: float | None, sealed: bool):
    """z-grid (units of a), trapezoid weights, eigenvalues lam, load coefficients c and eigenvectors V.

    Open: the end node is Dirichlet (phi = 0) and drops out; the load of the
    others is still their trapezoid weight (the source does not vanish on the
    end line). Sealed: every node is unknown and the constant is the lam = 0
    mode, set exactly (its load coefficient is sqrt(sum w), the others' zero).
    """
    from scipy.linalg import eigh

    z = axial_grid(half_length, n_half, end_layer)
    k_diag, k_off, m_diag, m_off, weights = _axial_matrices(z)
    size = z.size if sealed else z.size - 1

    def tri(diag, off):
        return np.diag(diag[:size]) + np.diag(off[:size - 1], 1) + np.diag(off[:size - 1], -1)

    lam, vec = eigh(tri(k_diag, k_off), tri(m_diag, m_off))
    coef = vec.T @ weights[:size]
    if sealed:
        lam[0] = 0.0
        vec[:, 0] = 1.0 / math.sqrt(weights.sum())
        coef[:] = 0.0
        coef[0] = math.sqrt(weights.sum())
    lam = np.maximum(lam, 0.0)
    for arr in (z, weights, lam, coef, vec):
        arr.setflags(write=False)
    return z, weights, lam, coef, vec


def _check_int(name: str, value, low: int, high: int, even: bool = False) -> int:
    ok = not isinstance(value, bool) and isinstance(value, (int, np.integer)) and low <= value <= high
    if ok and even and value % 2:
        ok = False
    if not ok:
        kind = "an even integer" if even else "an integer"
        msg = f"{name} must be {kind} in [{low}, {high}], got {value!r}"
        raise ValueError(msg)
    return int(value)


@dataclass(frozen=True)
class SolverSetup:
    """Everything the kernels need besides the motion (built-in and user profiles alike)."""

    kind: int
    kappa: float
    omk: float
    kappa_g: float
    omk_g: float
    centre: float
    rule: tuple
    nodes: np.ndarray
    cell_rule: tuple  # (tpos, lower0, lower1) of reynolds2d_kernels.cell_masses
    m: int
    h_lines: np.ndarray  # (n_lines, N m), or (1, 0) for a built-in profile
    q_lines: np.ndarray
    z: np.ndarray  # node positions in units of a: [0, L/2a] (half) or [-L/2a, L/2a]
    weights: np.ndarray
    half: bool  # the mid-plane symmetry is used
    modes: tuple | None  # (lam, coef, vec) of the z-modes for a z-independent gap, else None


def _evaluate2d(name: str, fn: Callable, theta: np.ndarray, z: np.ndarray) -> np.ndarray:
    values = np.asarray(fn(theta, z), dtype=float)
    shape = np.broadcast_shapes(np.shape(theta), np.shape(z))
    if values.shape != shape:
        msg = f"gap profile {name} must return an array shaped like theta and z broadcast together {shape}, " \
              f"got {values.shape}"
        raise ValueError(msg)
    if not np.all(np.isfinite(values)):
        msg = f"gap profile {name} must be finite for every theta and z"
        raise ValueError(msg)
    return values


def _profile_scale(profile, annulus: Annulus, n_probe: int = 1024, n_z: int = 65):
    """kappa_p = (h_max - h_min)/(h_max + h_min), 1 - kappa_p, the angle of h_min, and h on a probe."""
    theta = np.linspace(-np.pi, np.pi, n_probe, endpoint=False)
    if isinstance(profile, GapProfile2D):
        z = np.linspace(-0.5 * annulus.length, 0.5 * annulus.length, n_z)
        h = _evaluate2d("h", profile.h, theta[None, :], z[:, None])
        _check_positive(h.ravel(), np.broadcast_to(theta, h.shape).ravel())
        i = np.unravel_index(np.argmin(h), h.shape)
        h_min, h_max, centre = h[i], h.max(), float(theta[i[1]])
    else:
        h = np.asarray(profile.h(theta), dtype=float)
        _check_positive(h, theta)
        i = int(np.argmin(h))
        h_min, h_max, centre = h[i], h.max(), float(theta[i])
    kappa = float((h_max - h_min) / (h_max + h_min))
    return kappa, float(2.0 * h_min / (h_max + h_min)), centre


def _is_symmetric(profile: GapProfile2D, theta: np.ndarray, z: np.ndarray) -> bool:
    """Whether h and h_dot are mirror-symmetric in z at the grid points."""
    for name, fn in (("h", profile.h), ("h_dot", profile.h_dot)):
        if fn is None:
            continue
        up = _evaluate2d(name, fn, theta[None, :], z[:, None])
        down = _evaluate2d(name, fn, theta[None, :], -z[:, None])
        scale = float(np.max(np.abs(up)))
        if scale > 0.0 and np.max(np.abs(up - down)) > SYMMETRY_TOLERANCE * scale:
            return False
    return True


def _tabulate_lines(profile, annulus: Annulus, n: int, m: int, kappa_g: float, gamma: float, centre: float,
                    z_m: np.ndarray | None):
    """h and the squeeze flux Q at the Gauss points of every line, shape (n_lines, N m).

    ``z_m`` holds the lines' positions (m); None for a one-dimensional profile
    (one line). Q is the antiderivative in psi of a h_dot dtheta/dpsi, taken in
    the cell coordinate xi to the rule's order 2m
    (:func:`lubrication.reynolds._antiderivative`); every line must conserve its area.
    """
    psi, _ = _sommerfeld_angle(_gauss_points(n, m), gamma)
    theta = centre + _theta_of_psi(psi, kappa_g).ravel()
    lines = [None] if z_m is None else list(z_m)
    probe = np.linspace(-np.pi, np.pi, 4096, endpoint=False)
    h_out = np.empty((len(lines), n * m))
    q_out = np.zeros((len(lines), n * m))
    for k, zk in enumerate(lines):
        if zk is None:
            h_out[k] = profile.h(theta)
            h_dot = None if profile.h_dot is None else (lambda th, fn=profile.h_dot: fn(th))
        else:
            h_out[k] = _evaluate2d("h", profile.h, theta, np.full(1, zk))
            h_dot = None if profile.h_dot is None else (lambda th, fn=profile.h_dot, zz=zk: fn(th, zz))
        _check_positive(h_out[k], theta)
        if h_dot is None:
            continue
        rates = np.asarray(h_dot(probe), dtype=float).reshape(probe.shape)
        net, size = abs(float(np.sum(rates))), float(np.sum(np.abs(rates)))
        if net > 1e-8 * size:
            where = "" if zk is None else f" at z = {zk:g} m"
            msg = (f"gap profile h_dot must conserve each cross-section's area (oint h_dot dtheta = 0){where}; "
                   f"its mean is {net / probe.size:g} m/s against a mean magnitude of {size / probe.size:g} m/s")
            raise ValueError(msg)

        def rate(xi, h_dot=h_dot):
            psi_, stretch = _sommerfeld_angle(xi, gamma)
            th = centre + _theta_of_psi(psi_, kappa_g)
            return annulus.a * np.asarray(h_dot(th.ravel()), dtype=float).reshape(xi.shape) * \
                _jacobian(psi_, kappa_g) * stretch

        q_out[k] = _antiderivative(rate, n, m).ravel()
    return h_out, q_out


_NO_LINES = np.empty((1, 0))


@lru_cache(maxsize=8)
def _cell_rule(m: int):
    """Gauss points t_p in [0, 1] and the integrals of the Lagrange basis l_i through them.

    lower0[p, i] = int_0^(t_p) l_i(t) (1 - t) dt and lower1[p, i] = int_0^(t_p) l_i(t) t dt
    (:func:`lubrication.reynolds2d_kernels.cell_masses`).
    """
    from numpy.polynomial import Polynomial

    x, _ = np.polynomial.legendre.leggauss(m)
    tpos = 0.5 * (x + 1.0)
    lower0 = np.empty((m, m))
    lower1 = np.empty((m, m))
    t = Polynomial([0.0, 1.0])
    for i in range(m):
        basis = Polynomial([1.0])
        for k in range(m):
            if k != i:
                basis = basis * (t - tpos[k]) / (tpos[i] - tpos[k])
        zero = (basis * (1.0 - t)).integ()
        one = (basis * t).integ()
        lower0[:, i] = zero(tpos) - zero(0.0)
        lower1[:, i] = one(tpos) - one(0.0)
    for arr in (tpos, lower0, lower1):
        arr.setflags(write=False)
    return tpos, lower0, lower1


def solver_setup(annulus: Annulus, profile, n: int, n_axial: int, ends: str, clustering: float | None,
                 points_per_cell: int, end_layer: float | None) -> SolverSetup:
    n = _check_int("n", n, MIN_CELLS, MAX_CELLS)
    n_axial = _check_int("n_axial", n_axial, MIN_AXIAL_CELLS, MAX_AXIAL_CELLS, even=True)
    m = _check_int("points_per_cell", points_per_cell, 1, 8)
    if ends not in ENDS:
        msg = f"ends must be one of {', '.join(ENDS)}, got {ends!r}"
        raise ValueError(msg)
    sealed = ends == "sealed"
    if clustering is not None:
        clustering = _check_clustering(clustering)
    a = annulus.a
    if isinstance(profile, (GapProfile, GapProfile2D)):
        kappa, omk, centre = _profile_scale(profile, annulus)
        kind = reynolds_kernels.TABULATED
    elif profile in PROFILES:
        kappa, omk, centre = annulus.kappa, annulus.one_minus_kappa, 0.0
        kind = reynolds_kernels.THIN if profile == "thin" else reynolds_kernels.ECCENTRIC
    else:
        msg = f"profile must be one of {', '.join(PROFILES)}, a GapProfile or a GapProfile2D, got {profile!r}"
        raise ValueError(msg)
    if clustering is None:
        clustering = (1.0, 1.0) if sealed else default_clustering(kappa, omk)
    narrow, wide = clustering
    kappa_g, omk_g = grid_parameter(kappa, omk, narrow)
    gamma = grading(kappa, omk, narrow, wide)
    rule, nodes = _theta_rule(n, m, gamma)
    cell_rule = _cell_rule(m)
    half_length = 0.5 * annulus.length / a
    if end_layer is None:
        layer = 0.5 * math.sqrt(omk * (1.0 + kappa))
    else:
        layer = check_range("end_layer", end_layer, 0.0, math.inf, low_open=True, unit="m") / a
    layer = None if sealed else layer
    n_half = n_axial // 2
    if not isinstance(profile, GapProfile2D):
        z, weights, *modes = _axial_modes(half_length, n_half, layer, sealed)
        h_lines, q_lines = (_NO_LINES, _NO_LINES)
        if kind == reynolds_kernels.TABULATED:
            h_lines, q_lines = _tabulate_lines(profile, annulus, n, m, kappa_g, gamma, centre, None)
        return SolverSetup(kind, kappa, omk, kappa_g, omk_g, centre, rule, nodes, cell_rule, m, h_lines, q_lines,
                      z, weights, True, tuple(modes))
    z_half = axial_grid(half_length, n_half, layer)
    theta_nodes = centre + _theta_of_psi(nodes, kappa_g)
    half = _is_symmetric(profile, theta_nodes, a * z_half)
    z = z_half if half else np.concatenate((-z_half[:0:-1], z_half))
    weights = _axial_matrices(z)[4]
    h_lines, q_lines = _tabulate_lines(profile, annulus, n, m, kappa_g, gamma, centre, a * z)
    return SolverSetup(kind, kappa, omk, kappa_g, omk_g, centre, rule, nodes, cell_rule, m, h_lines, q_lines,
                  z, weights, half, None)


def line_data(setup: SolverSetup, annulus: Annulus, eps_dot: float):
    n_lines = setup.h_lines.shape[0]
    n = setup.nodes.size
    integrals = np.zeros((n_lines, n, reynolds_kernels.N_INTEGRALS))
    masses = np.zeros((n_lines, n, reynolds2d_kernels.N_MASSES))
    reynolds2d_kernels.film_lines(setup.kind, annulus.a, annulus.b, setup.kappa, setup.omk, eps_dot, setup.kappa_g,
                          setup.omk_g, *setup.rule, *setup.cell_rule, setup.m, setup.h_lines, setup.q_lines,
                          integrals, masses)
    return integrals, masses


def general_system(setup: SolverSetup, integrals, masses, half_u: float, sealed: bool):
    """The (theta, z) system of a z-dependent gap: sparse matrix, load, the known (zero) nodes, its axial part."""
    import scipy.sparse as sp

    n_lines, n = integrals.shape[:2]
    g_lines = np.empty((n_lines, n))
    r_lines = np.empty((n_lines, n))
    for k in range(n_lines):
        g_lines[k], r_lines[k] = reynolds2d_kernels.line_load(integrals[k], half_u)

    def assemble(conductances):
        size = (n_lines - 1) * n * reynolds2d_kernels.ENTRIES_PER_CELL
        rows = np.empty(size, dtype=np.int64)
        cols = np.empty(size, dtype=np.int64)
        vals = np.empty(size)
        rhs = np.zeros(n_lines * n)
        reynolds2d_kernels.assemble_general(conductances, masses, r_lines, setup.z, rows, cols, vals, rhs)
        return sp.csr_matrix((vals, (rows, cols)), shape=(rhs.size, rhs.size)), rhs

    matrix, rhs = assemble(g_lines)
    axial, _ = assemble(np.zeros_like(g_lines))
    end_lines = [] if sealed else ([n_lines - 1] if setup.half else [0, n_lines - 1])
    if sealed:
        known = np.zeros(1, dtype=np.int64)  # the operator has the constant in its kernel: pin one node
    else:
        known = np.concatenate([np.arange(n) + k * n for k in end_lines])
    return matrix, rhs, known, axial, end_lines


def general_solve(matrix, rhs, known) -> np.ndarray:
    """Sparse LU of the system with the known nodes at zero."""
    from scipy.sparse.linalg import splu

    free = np.setdiff1d(np.arange(rhs.size), known)
    phi = np.zeros(rhs.size)
    phi[free] = splu(matrix[free][:, free].tocsc()).solve(rhs[free])
    return phi


def general_outflow(setup: SolverSetup, integrals, masses, half_u: float, phi, axial, end_lines) -> np.ndarray:
    """The axial outflow density d of every line (:func:`lubrication.reynolds2d_kernels.flux_correction`).

    d = (M_z^-1 (x) I) blockdiag(M_theta)^-1 Z phi over the unknown lines, Z the
    assembled axial part, which for a z-independent gap is exactly the modal
    sum_m v_m lam_m psi_m; on an open end line M_theta d = -r
    (:func:`lubrication.reynolds2d_kernels.end_outflow`).
    """
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    n_lines, n = integrals.shape[:2]
    lines = [k for k in range(n_lines) if k not in end_lines]
    j = np.arange(n)
    jp = (j + 1) % n
    blocks = []
    for k in lines:
        m00, m01, m11 = (masses[k, :, c] for c in (reynolds2d_kernels.M00, reynolds2d_kernels.M01, reynolds2d_kernels.M11))
        blocks.append(sp.csr_matrix((np.concatenate((m00, m11, m01, m01)),
                                     (np.concatenate((j, jp, j, jp)), np.concatenate((j, jp, jp, j)))),
                                    shape=(n, n)))
    index = np.concatenate([np.arange(n) + k * n for k in lines])
    u = splu(sp.block_diag(blocks, format="csc")).solve((axial @ phi)[index])
    _, _, m_diag, m_off, _ = _axial_matrices(setup.z)
    keep = np.array(lines)
    m_z = sp.diags([m_diag[keep], m_off[keep[:-1]], m_off[keep[:-1]]], [0, 1, -1], format="csc")
    outflow = np.zeros((n_lines, n))
    outflow[keep] = splu(sp.kron(m_z, sp.identity(n), format="csc")).solve(u).reshape(keep.size, n)
    for k in end_lines:
        reynolds2d_kernels.end_outflow(integrals[k], masses[k], half_u, outflow[k])
    return outflow


def _solve_general(setup: SolverSetup, integrals, masses, half_u: float, sealed: bool):
    """phi and the axial outflow density d on every line of a z-dependent gap (sparse LU)."""
    matrix, rhs, known, axial, end_lines = general_system(setup, integrals, masses, half_u, sealed)
    phi = general_solve(matrix, rhs, known)
    outflow = general_outflow(setup, integrals, masses, half_u, phi, axial, end_lines)
    return phi.reshape(integrals.shape[:2]), outflow


def _check_cavitation(cavitation: str, ends: str, p_cav: float, p_end: float) -> tuple[float, float]:
    if cavitation not in CAVITATION_2D:
        msg = f"cavitation must be one of {', '.join(CAVITATION_2D)} on (theta, z), got {cavitation!r}"
        raise ValueError(msg)
    p_end = check_finite("p_end", p_end)
    p_cav = check_finite("p_cav", p_cav)
    if cavitation != "none":
        if ends != "open":
            msg = ("cavitation needs open ends (the end pressure fixes the level); with sealed ends use "
                   "lubrication.cavitation, whose one-dimensional problem it is")
            raise ValueError(msg)
        if not p_cav <= p_end:
            msg = f"p_cav must not exceed p_end = {p_end:g} Pa, got {p_cav:g} Pa"
            raise ValueError(msg)
    return p_cav, p_end


def _solve(annulus: Annulus, motion: Motion, fluid: Fluid, *, n: int, n_axial: int, ends: str, profile,
           p_end: float, cavitation: str, p_cav: float, clustering: float, points_per_cell: int,
           end_layer: float | None, field: bool):
    """Solve once; return the three z-integrated line integrals and, if asked for, the field."""
    p_cav, p_end = _check_cavitation(cavitation, ends, p_cav, p_end)
    setup = solver_setup(annulus, profile, n, n_axial, ends, clustering, points_per_cell, end_layer)
    a, mu = annulus.a, fluid.mu
    u_a = a * motion.w_a
    u_b = (annulus.b if setup.kind == reynolds_kernels.ECCENTRIC else a) * motion.w_b
    half_u = 0.5 * (u_a + u_b)
    integrals, masses = line_data(setup, annulus, motion.eps_dot)
    sealed = ends == "sealed"
    truncate = cavitation == "half-sommerfeld"
    n_lines = setup.z.size
    end_weight = 0.0 if sealed else float(setup.weights[-1])
    if setup.modes is not None:
        lam, coef, vec = setup.modes
        if not (field or truncate):
            sums = reynolds2d_kernels.modal_film(integrals[0], masses[0], u_a, u_b, lam, coef, setup.weights.sum(),
                                         end_weight, np.empty((0, setup.nodes.size)))
            return setup, sums, None, None
        modes = np.empty((lam.size, setup.nodes.size))
        reynolds2d_kernels.modal_film(integrals[0], masses[0], u_a, u_b, lam, coef, setup.weights.sum(), end_weight,
                              modes)
        phi = np.zeros((n_lines, setup.nodes.size))
        outflow = np.zeros((n_lines, setup.nodes.size))
        phi[:vec.shape[0]] = vec @ modes
        outflow[:vec.shape[0]] = vec @ (lam[:, None] * modes)
        if not sealed:
            reynolds2d_kernels.end_outflow(integrals[0], masses[0], half_u, outflow[-1])
        integrals = np.repeat(integrals, n_lines, axis=0)
        masses = np.repeat(masses, n_lines, axis=0)
    else:
        phi, outflow = _solve_general(setup, integrals, masses, half_u, sealed)
    y_cav = (p_cav - p_end) / (12.0 * mu * a)
    lines = np.empty((n_lines, 3))
    sums = reynolds2d_kernels.lines_film(integrals, masses, u_a, u_b, phi, outflow, setup.weights, truncate, y_cav, lines)
    return setup, sums, phi, lines


def _to_forces(setup: SolverSetup, annulus: Annulus, fluid: Fluid, sums) -> tuple[float, float, float]:
    """Scale the z-integrated line integrals (z in units of a) to f_eps, f_chi, T_a over the length."""
    a, mu = annulus.a, fluid.mu
    factor = (2.0 if setup.half else 1.0) * a
    f_x = 12.0 * mu * a * a * factor * sums[0]
    f_y = 12.0 * mu * a * a * factor * sums[1]
    c, s = math.cos(setup.centre), math.sin(setup.centre)
    return c * f_x - s * f_y, s * f_x + c * f_y, mu * a * a * factor * sums[2]


def reynolds2d_forces(annulus: Annulus, motion: Motion, fluid: Fluid, *, n: int = 64, n_axial: int = 64,
                      ends: str = "open", profile: str | GapProfile | GapProfile2D = "thin",
                      p_end: float = 0.0, cavitation: str = "none", p_cav: float = 0.0,
                      clustering: float | None = None, points_per_cell: int = 2,
                      end_layer: float | None = None, extrapolate: bool = False) -> FluidForces:
    """Force and torque on the inner cylinder of length L from the Reynolds equation on (theta, z).

    Parameters
    ----------
    annulus, motion, fluid
        Geometry (its ``length`` is L), velocities and fluid.
    n : int
        Cells around the gap, in [8, 65536].
    n_axial : int
        Cells along the whole length, even, in [4, 4096] (half of them from the
        mid-plane to each end).
    ends : {"open", "sealed"}
        p = p_end at z = +-L/2, or dp/dz = 0 there.
    profile : {"thin", "eccentric"}, GapProfile or GapProfile2D
        The thin gap (B1), the exact eccentric gap, a user gap h(theta) or h(theta, z).
    p_end : float
        End-region pressure (Pa); matters only with cavitation.
    cavitation : {"none", "half-sommerfeld"}
        Full film, or the pressure truncated at ``p_cav`` (Pa), open ends only.
    clustering : float or (float, float), optional
        Exponents (c_n, c_w) of the theta grid's angular scale at the narrow gap
        and on the wide side, 0 <= c_w <= c_n <= 1 (module docstring); a number c
        is (c, c). By default :func:`default_clustering` with open ends ((1/2, 1/2)
        up to kappa = 0.9968, graded beyond) and (1, 1) with sealed ones, whose
        problem is the one-dimensional one for a z-independent gap.
    points_per_cell : int
        Gauss points per theta cell for the cell integrals.
    end_layer : float, optional
        Width l_end (m) of the axial grading toward the ends; default a zeta/2.
    extrapolate : bool
        Return the Richardson combination (4 F(n, n_axial) - F(n/2, n_axial/2))/3,
        fourth order, for 1.25 times the cost; ``n`` and ``n_axial/2`` must then be even.
        Near contact (kappa > 0.9968, the graded grid) it needs n >= 64 (module docstring).

    Returns
    -------
    FluidForces
        f_eps, f_chi (N) and T_a (N m) over the length L, ``model="reynolds2d"``.
    """
    options = {"ends": ends, "profile": profile, "p_end": p_end, "cavitation": cavitation, "p_cav": p_cav,
                   "clustering": clustering, "points_per_cell": points_per_cell, "end_layer": end_layer}
    fine = _forces_once(annulus, motion, fluid, n, n_axial, options)
    if not extrapolate:
        return FluidForces(*fine, model="reynolds2d")
    _check_int("n", n, 2 * MIN_CELLS, MAX_CELLS, even=True)
    _check_int("n_axial", n_axial, 2 * MIN_AXIAL_CELLS, MAX_AXIAL_CELLS)
    if n_axial % 4:
        msg = f"n_axial must be a multiple of 4 to extrapolate (both grids symmetric), got {n_axial!r}"
        raise ValueError(msg)
    coarse = _forces_once(annulus, motion, fluid, n // 2, n_axial // 2, options)
    return FluidForces(*((4.0 * f - c) / 3.0 for f, c in zip(fine, coarse)), model="reynolds2d")


def _forces_once(annulus, motion, fluid, n, n_axial, options):
    setup, sums, _, _ = _solve(annulus, motion, fluid, n=n, n_axial=n_axial, field=False, **options)
    return _to_forces(setup, annulus, fluid, sums)


def reynolds2d_pressure(annulus: Annulus, motion: Motion, fluid: Fluid, *, n: int = 64, n_axial: int = 64,
                        ends: str = "open", profile: str | GapProfile | GapProfile2D = "thin",
                        p_end: float = 0.0, cavitation: str = "none", p_cav: float = 0.0,
                        clustering: float | None = None, points_per_cell: int = 2,
                        end_layer: float | None = None) -> Reynolds2DPressure:
    """The pressure on the (theta, z) grid, the force per unit length of every line and the totals.

    Arguments as :func:`reynolds2d_forces` (no extrapolation). The nodal
    pressures carry the scheme's O(dpsi^2 + ds^2) error.
    """
    setup, sums, phi, lines = _solve(annulus, motion, fluid, n=n, n_axial=n_axial, ends=ends, profile=profile,
                                     p_end=p_end, cavitation=cavitation, p_cav=p_cav, clustering=clustering,
                                     points_per_cell=points_per_cell, end_layer=end_layer, field=True)
    a, mu = annulus.a, fluid.mu
    z = setup.z
    if setup.half:  # mirror the half length
        phi = np.concatenate((phi[:0:-1], phi))
        lines = np.concatenate((lines[:0:-1], lines))
        z = np.concatenate((-z[:0:-1], z))
    p = 12.0 * mu * a * phi
    p = p - p.mean() + p_end if ends == "sealed" else p + p_end
    c, s = math.cos(setup.centre), math.sin(setup.centre)
    f_x = 12.0 * mu * a * a * lines[:, 0]
    f_y = 12.0 * mu * a * a * lines[:, 1]
    theta = setup.centre + _theta_of_psi(setup.nodes, setup.kappa_g)
    forces = FluidForces(*_to_forces(setup, annulus, fluid, sums), model="reynolds2d")
    return Reynolds2DPressure(theta=theta, z=a * z, p=p, f_eps_per_length=c * f_x - s * f_y,
                              f_chi_per_length=s * f_x + c * f_y, t_a_per_length=mu * a * a * lines[:, 2],
                              forces=forces)
