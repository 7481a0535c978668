r"""Fluid inertia in the eccentric annulus: the parts known in closed form, and the error estimate.

The force models solve quasi-steady Stokes flow. What steady plane
Navier-Stokes flow adds (:mod:`lubrication.navier_stokes` solves it) splits
into two parts.

1. The rotating frame. In the frame turning with the line of centres at
   chi' the centrifugal and Coriolis forces of a plane flow are gradients and
   change only the pressure; on the inner cylinder they give, per length L,

       f_eps = -m''_a chi'^2 eps,    f_chi = 2 m''_a chi' eps',    T_a = 0,

   with m''_a = rho pi a^2 L the displaced mass (:func:`frame_forces`): exact,
   for any Reynolds number, and the whole effect of chi'.

2. The relative flow. The rest depends only on the wall velocities in that
   frame, (eps', W_a, W_b), through the relative wall Reynolds numbers

       Re_a = W_a a delta / nu,   Re_b = W_b b delta / nu,   Re_sq = eps' delta / nu

   (:func:`relative_reynolds`), not through the absolute rates Omega_a,
   Omega_b nor the rotation number chi' delta^2 / nu. To first order it is a
   quadratic form in them; the reflection about the line of centres makes
   the rotations' first correction a pure f_eps (f_chi and T_a change at
   O(Re^2) only). In a thin gap the inertial term is smaller than the
   viscous one by delta/a: the relative force error is
   G(kappa, motion) Re* with the reduced Reynolds number

       Re* = max(|Re_a|, |Re_b|) delta / a.

   The error is measured against a scale of the Stokes force that cannot
   cancel, the sum |R_chi_a W_a| + |R_chi_b W_b| of the magnitudes of its two
   rotational terms (f_chi = R_chi_a W_a + R_chi_b W_b): for walls turning in
   the same sense it is |f_chi| itself; for counter-rotating walls f_chi can
   vanish (R_chi_a W_a = -R_chi_b W_b) while the inertial f_eps does not, and
   a ratio to |f_chi| would have no bound. Against this scale G <= 0.0995 for
   every direction of (W_a, W_b), every kappa and delta/a >= 0.01 (largest
   for W_a a = W_b b at kappa -> 0, delta/a = 0.01; every table node and
   direction checked), and G -> 1/10 in the thin-gap limit (closed form
   below): at first order the relative force error is below Re*/10 for every
   wall motion. :func:`inertial_error_estimate` evaluates it from a table of
   finite-element solves. The first-order error agrees with full Newton
   solutions to 1% for Re* <= 1 and to 15% up to Re* = 30
   (docs/inertia/inertia.md). The squeeze eps' is not covered: its
   quasi-steady convective inertia came out negligible, and what remains
   is unsteady (the Stokes number h^2 / (nu T)).

Two references independent of the finite elements:

* :func:`small_eccentricity_forces`: the exact force to first order in kappa
  at any Reynolds number and any delta/a. Circular Couette flow
  V0 = A r + B / r is an exact solution at kappa = 0, with uniform
  vorticity 2A; moving the inner circle by eps e_x perturbs it by a mode
  psi_1 = Re[phi(r) e^{i theta}] whose vorticity obeys
  i (V0 / r) Omega = nu (Omega'' + Omega'/r - Omega/r^2),
  Omega = -(phi'' + phi'/r - phi/r^2), with phi(a) = a W_a,
  phi'(a) = V0'(a) (the boundary condition moved from r = a + eps cos theta
  to r = a), phi(b) = phi'(b) = 0. The force is the momentum flux through any
  circle r = R between the walls, int (sigma . e_r - rho u u_r) R dtheta;
  the pressure of the mode follows from the azimuthal momentum equation.
  Chebyshev collocation, spectrally accurate.

* :func:`thin_gap_small_kappa`: the thin-gap (delta/a -> 0) limit of the
  same first-order-in-kappa force, expanded to first order in the reduced
  Reynolds number, in closed form (derivation in its docstring):

      f_eps^(1) = (pi/5) rho a kappa (U_a^2 + 4 U_a U_b + U_b^2),
      f_chi^(0) = 6 pi mu a^2 kappa (U_a + U_b) / delta^2,

  U_a = W_a a, U_b = W_b b: inertia adds a force along the line of centres
  (towards the narrow gap) of relative size
  Re* |U_a^2 + 4 U_a U_b + U_b^2| / (30 (|U_a| + |U_b|) V) against the
  non-cancelling scale above: 1/30 of Re* for the inner or the outer wall
  alone or for U_b = -U_a, 1/10 (the largest over all directions) for both
  at one speed. This is the regime of the classical small-eccentricity,
  small-clearance expansion of DiPrima & Stuart (J. Lubr. Technol. 94,
  266-274, 1972; J. Fluid Mech. 54, 393-415, 1972). Their coefficients were
  not available to this project, so the numbers here are the project's own
  derivation, checked against the exact small-eccentricity solution above
  (their difference is O(delta/a), tests/test_navier_stokes.py). What is
  quoted of that theory agrees in kind: the first inertial correction of a
  journal bearing changes the radial (direct) stiffness d f_eps / d eps
  linearly in the Reynolds number and leaves the cross-coupled stiffness and
  the load magnitude unchanged at that order ("Approximations in
  hydrodynamic lubrication", J. Tribol. 114, 14-25, 1992, comparing full
  Navier-Stokes solutions with it). Here, for the journal (U_b = 0), the
  load at small kappa is f_chi^(0), perpendicular to the correction, so its
  magnitude changes at O(Re*^2) while the attitude angle turns by
  Re*/30 rad, and d f_eps / d eps gains (pi/5) rho a U_a^2 / delta per
  unit length (an outward force growing with eps: a negative stiffness).
"""

from __future__ import annotations

import math

import numpy as np

from numerics.jit import jit

from . import kernels
from .geometry import Annulus, Fluid, FluidForces, Motion, check_finite, check_range
from .tables import cell

__all__ = ["CORRECTED_MEASURED_TO", "CORRECTED_SECOND_ORDER", "INTERPOLATION_ABSOLUTE", "INTERPOLATION_RELATIVE",
           "KAPPA_AXIS", "TABLE_COLUMNS", "corrected_error_estimate", "first_order_f_eps",
           "frame_forces", "inertial_error_estimate", "inertial_force_correction", "reduced_reynolds",
           "relative_reynolds", "small_eccentricity_forces", "thin_gap_small_kappa"]


def frame_forces(annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
    """Force of the frame's centripetal and Coriolis accelerations on the displaced fluid.

    In the frame turning with the line of centres the centrifugal and
    Coriolis forces of a plane flow are pressure gradients: rho chi'^2 |x|^2/2
    and -2 rho chi' psi with psi the stream function, constant on the outer
    wall and eps' y + const on the inner one. On the inner cylinder, whole
    length L, with m''_a = rho pi a^2 L,

        f_eps = -m''_a chi'^2 eps,   f_chi = 2 m''_a chi' eps',   T_a = 0,

    and nothing on the outer cylinder (its disc is centred on the axis).

    Returns
    -------
    FluidForces
        N, N, N m; ``model="frame"``.
    """
    displaced = fluid.rho * math.pi * annulus.a**2 * annulus.length  # m''_a, kg
    chi_dot = motion.chi_dot
    return FluidForces(-displaced * chi_dot**2 * annulus.eps, 2.0 * displaced * chi_dot * motion.eps_dot,
                       0.0, model="frame")


def relative_reynolds(annulus: Annulus, motion: Motion, fluid: Fluid) -> tuple[float, float, float]:
    """Signed (Re_a, Re_b, Re_sq) = (W_a a, W_b b, eps') delta / nu of one instant."""
    scale = annulus.delta / fluid.nu
    return (scale * motion.w_a * annulus.a, scale * motion.w_b * annulus.b, scale * motion.eps_dot)


def reduced_reynolds(annulus: Annulus, motion: Motion, fluid: Fluid) -> float:
    """Re* = max(|W_a| a, |W_b| b, |eps'|) delta^2 / (nu a): the predictor of the inertial error."""
    re_a, re_b, re_sq = relative_reynolds(annulus, motion, fluid)
    return max(abs(re_a), abs(re_b), abs(re_sq)) * annulus.delta_over_a


def _chebyshev(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev-Lobatto points cos(pi j / n), j = 0..n, and the differentiation matrix."""
    x = np.cos(np.pi * np.arange(n + 1) / n)
    c = np.ones(n + 1)
    c[0] = c[-1] = 2.0
    c *= (-1.0) ** np.arange(n + 1)
    dx = x[:, None] - x[None, :]
    d = np.outer(c, 1.0 / c) / (dx + np.eye(n + 1))
    d -= np.diag(d.sum(axis=1))
    return x, d


def small_eccentricity_forces(delta_over_a: float, reynolds: float, w_a: float, w_b: float, *,
                              n: int = 40, radius: float = 0.5) -> tuple[float, float]:
    """Exact steady Navier-Stokes force to first order in kappa, at any Reynolds number.

    Parameters
    ----------
    delta_over_a : float
        (b - a)/a > 0.
    reynolds : float
        Re = V delta / nu >= 0 with V = max(|W_a| a, |W_b| b).
    w_a, w_b : float
        Direction of the wall rotations relative to the line of centres
        (only their ratio matters; not both zero).
    n : int
        Chebyshev degree (40 gives about 1e-9 for delta/a <= 1).
    radius : float
        Where between the walls, as a fraction of the gap in (0, 1), the
        momentum flux is taken; the result does not depend on it.

    Returns
    -------
    f_eps, f_chi : float
        lim f / kappa per unit length in units of mu V (the normalisation of
        :class:`lubrication.navier_stokes.InertialSweep`).
    """
    d = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    re = check_range("reynolds", reynolds, 0.0, math.inf)
    radius = check_range("radius", radius, 0.0, 1.0, low_open=True)
    w_a, w_b = check_finite("w_a", w_a), check_finite("w_b", w_b)
    b = 1.0 + d
    speed = max(abs(w_a), abs(w_b) * b)
    if speed == 0.0:
        msg = "w_a and w_b must not both be zero"
        raise ValueError(msg)
    w_a, w_b = w_a / speed, w_b / speed
    rho = re / d  # a = 1, mu = 1, V = 1
    xi, dxi = _chebyshev(n)
    r = 1.0 + 0.5 * d * (1.0 - xi)  # r[0] = a = 1, r[n] = b
    d1 = dxi * (-2.0 / d)
    d2 = d1 @ d1
    d3 = d2 @ d1
    big_a = (w_b * b * b - w_a) / (b * b - 1.0)
    big_b = (w_a - w_b) * b * b / (b * b - 1.0)
    v0 = big_a * r + big_b / r
    dv0 = big_a - big_b / r**2
    lap = d2 + d1 / r[:, None] - np.diag(1.0 / r**2)
    m = np.zeros((2 * (n + 1), 2 * (n + 1)), dtype=complex)
    m[:n + 1, :n + 1] = lap
    m[:n + 1, n + 1:] = np.eye(n + 1)
    m[n + 1:, n + 1:] = lap - 1j * rho * np.diag(v0 / r)
    rhs = np.zeros(2 * (n + 1), dtype=complex)
    # boundary rows: phi on both walls replaces the phi equation there, phi' the vorticity equation
    for row, col, value in ((0, 0, w_a), (n, n, 0.0)):
        m[row] = 0.0
        m[row, col] = 1.0
        rhs[row] = value
    for row, wall, value in ((n + 1, 0, dv0[0]), (2 * n + 1, n, 0.0)):
        m[row] = 0.0
        m[row, :n + 1] = d1[wall]
        rhs[row] = value
    phi = np.linalg.solve(m, rhs)[:n + 1]
    dphi, ddphi, dddphi = d1 @ phi, d2 @ phi, d3 @ phi
    u, v = 1j * phi / r, -dphi
    du, dv, ddv = 1j * (dphi / r - phi / r**2), -ddphi, -dddphi
    pressure = -1j * r * ((ddv + dv / r - 2.0 * v / r**2 + 2j * u / r**2)
                          - rho * (u * (dv0 + v0 / r) + 1j * v0 * v / r))
    s_rr = -pressure + 2.0 * du
    s_rt = (dv - v / r + 1j * u / r) - rho * v0 * u
    f_x = math.pi * r * (s_rr.real + s_rt.imag)
    f_y = math.pi * r * (-s_rr.imag + s_rt.real)
    # the flux integrals are the same on every circle: evaluate at the requested one
    target = 1.0 + radius * d
    weights = _barycentric_weights(r, target)
    eps_per_kappa = d
    return float(weights @ f_x) * eps_per_kappa, float(weights @ f_y) * eps_per_kappa


def _barycentric_weights(nodes: np.ndarray, x: float) -> np.ndarray:
    """Weights w with w @ f = the polynomial interpolant of f(nodes) at x (Chebyshev-Lobatto nodes)."""
    n = nodes.size - 1
    lam = (-1.0) ** np.arange(n + 1)
    lam[0] *= 0.5
    lam[-1] *= 0.5
    diff = x - nodes
    exact = np.flatnonzero(diff == 0.0)
    if exact.size:
        out = np.zeros(n + 1)
        out[exact[0]] = 1.0
        return out
    w = lam / diff
    return w / w.sum()


def thin_gap_small_kappa(u_a: float, u_b: float, *, a: float = 1.0, delta: float = 1.0,
                         rho: float = 1.0, mu: float = 1.0) -> tuple[float, float]:
    r"""Thin-gap, first-order-in-kappa force: the O(rho) f_eps and the Stokes f_chi, per unit length.

    Thin film, z in [0, h], h = delta (1 - kappa cos theta), wall speeds
    U_a = W_a a at z = 0 and U_b = W_b b at z = h. With zeta = z/delta the
    Stokes profile to O(kappa) is u0 = U_a + D zeta + kappa cos(theta) g(zeta),
    D = U_b - U_a, S = U_a + U_b, g = D zeta + 3 S zeta (1 - zeta), the
    pressure p0 = -6 mu a S kappa sin(theta) / delta^2 (hence f_chi^(0)), and
    continuity gives w0 = (delta/a) kappa sin(theta) G, G = int_0^zeta g. The
    first-order inertial pressure obeys mu u1_zz = p1_theta / a +
    rho (u0 u0_theta / a + w0 u0_z) with u1 = 0 on both walls and a
    theta-periodic p1, which makes the flux correction vanish at O(kappa) and

        p1_theta = 12 rho kappa sin(theta) I,
        I = -(1/2) int_0^1 n(s) s (1 - s) ds = (U_a^2 + 4 U_a U_b + U_b^2) / 60,
        n = -(U_a + D zeta) g + D G,

    so p1 = -12 rho kappa I cos(theta) and f_eps^(1) = -a oint p1 cos(theta)
    = (pi/5) rho a kappa (U_a^2 + 4 U_a U_b + U_b^2).

    Returns
    -------
    f_eps1_per_kappa, f_chi0_per_kappa : float
        f_eps^(1)/kappa and f_chi^(0)/kappa, N/m, in the units of the arguments.
    """
    f_eps1 = (math.pi / 5.0) * rho * a * (u_a * u_a + 4.0 * u_a * u_b + u_b * u_b)
    f_chi0 = 6.0 * math.pi * mu * a * a * (u_a + u_b) / delta**2
    return f_eps1, f_chi0


#: Columns of the coefficient table of the rotations, each normalised to be smooth and O(1)
#: on [0, 1) x (0, 1] (zeta = sqrt(1 - kappa^2), d = delta/a, b in units of a; R: Stokes
#: resistance f_chi per W, C: the f_eps quadratic form of
#: :func:`lubrication.navier_stokes.first_inertial_correction`). The powers of b turn
#: rates W_b into wall speeds W_b b, so that the table is used with Re_a and Re_b as they are.
TABLE_COLUMNS = ("R_chi_a (2 + kappa^2) zeta d^2 / kappa", "R_chi_b (2 + kappa^2) zeta d^2 / (kappa b)",
                 "C_eps[a, a] / kappa", "C_eps[a, b] / (kappa b)", "C_eps[b, b] / (kappa b^2)")

#: kappa at which the kappa = 0 node is solved: the normalised columns are even
#: in kappa, so this gives their limit to O(1e-8).
KAPPA_AXIS = 1e-4


def inertial_error_estimate(kappa, delta_over_a: float, re_a, re_b):
    """Estimated relative error of the quasi-steady Stokes force of the wall rotations.

    Parameters
    ----------
    kappa : float or array_like
        Eccentricity ratio in [0, 1).
    delta_over_a : float
        (b - a)/a > 0.
    re_a, re_b : float or array_like
        Signed relative Reynolds numbers W_a a delta / nu and W_b b delta / nu,
        W = Omega - chi' (:func:`relative_reynolds`); arrays broadcast with ``kappa``.

    Returns
    -------
    float or ndarray
        |F^(1)| / (|R_chi_a W_a| + |R_chi_b W_b|): the first-order inertial
        correction F^(1) of the flow relative to the line of centres (a pure
        f_eps) against the sum of the magnitudes of the two rotational terms
        of the Stokes force f_chi = R_chi_a W_a + R_chi_b W_b, a scale that
        does not cancel when the walls counter-rotate (it is |f_chi| when
        they turn in the same sense). The rotating-frame force
        (:func:`frame_forces`) is exact and not part of it, and the squeeze
        eps' is not covered (no frame makes it steady). It equals
        (delta/a) (2 + kappa^2) zeta |Q(Re_a, Re_b)| / (|L_a Re_a| + |L_b Re_b|),
        a quadratic over a linear form with tabulated coefficients, so it
        grows like the reduced Reynolds number Re* = max(|Re_a|, |Re_b|)
        delta/a, and it is below Re*/10 for every motion (module docstring).
        Zero when nothing turns. The torque's error is of second order in Re
        and smaller. Accuracy and range: :mod:`lubrication.inertia_table`.
    """
    d = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    kappa_arr, re_a_arr, re_b_arr = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (kappa, re_a, re_b)))
    if kappa_arr.ndim == 0:
        kappa = check_range("kappa", float(kappa_arr), 0.0, 1.0)
        re_a, re_b = check_finite("re_a", float(re_a_arr)), check_finite("re_b", float(re_b_arr))
    else:
        if not np.all((kappa_arr >= 0.0) & (kappa_arr < 1.0)):
            msg = "kappa must be in [0, 1) everywhere"
            raise ValueError(msg)
        for name, values in (("re_a", re_a_arr), ("re_b", re_b_arr)):
            if not np.all(np.isfinite(values)):
                msg = f"{name} must be finite everywhere"
                raise ValueError(msg)
    from .inertia_table import DELTA_NODES, KAPPA_NODES, TABLE

    if kappa_arr.ndim == 0:
        return _error_estimate(kappa, d, re_a, re_b, KAPPA_NODES, DELTA_NODES, TABLE)
    flat = [np.ascontiguousarray(v).ravel() for v in (kappa_arr, re_a_arr, re_b_arr)]
    return _error_estimates(*flat, d, KAPPA_NODES, DELTA_NODES, TABLE).reshape(kappa_arr.shape)


#: What the inertia-corrected forces leave of the inertial force at the table's nodes, per Re*^2 of
#: the Stokes force scale: at most 9.16e-5 over the Newton solutions of docs/inertia/inertia.md
#: ('The inertia-corrected force model'), 8.7e-5 from Re* = 0.1 to 10, every sweep.
CORRECTED_SECOND_ORDER = 9.2e-5
#: The table's interpolation error in G between its nodes: at most 3% of G where G > 0.01, and 1e-3
#: in G anywhere (the study's bounds; measured 1.5% and 4.9e-4 against fresh off-node solves).
INTERPOLATION_RELATIVE, INTERPOLATION_ABSOLUTE = 0.03, 1e-3
#: The largest Re* of those Newton solutions: beyond it what the correction leaves is not measured.
CORRECTED_MEASURED_TO = 30.0


def corrected_error_estimate(first_order_error, re_star):
    """Estimated relative force error of the inertia-corrected forces (``stokes_exact(inertia=True)``, ...).

    What adding the tabulated first inertial correction leaves: the table's
    interpolation error in the correction, max(3% G, 1e-3) Re*, and the
    second-order remainder, 9.2e-5 Re*^2 (:data:`CORRECTED_SECOND_ORDER`), both
    against the scale of :func:`inertial_error_estimate`. A bound from the
    study's worst cases: against Navier-Stokes solves between the table's
    nodes the corrected forces left 3-10% of it (tests/test_inertia_force_model.py).
    Measured up to Re* = :data:`CORRECTED_MEASURED_TO`; the squeeze and the
    unsteady inertia are not in it.

    Parameters
    ----------
    first_order_error : float or array_like
        G Re*, the estimated error of the quasi-steady Stokes forces
        (:func:`inertial_error_estimate`).
    re_star : float or array_like
        Re* of the same state (:func:`reduced_reynolds`).
    """
    error = np.asarray(first_order_error, dtype=float)
    re_star = np.asarray(re_star, dtype=float)
    interpolation = np.maximum(INTERPOLATION_RELATIVE * error, INTERPOLATION_ABSOLUTE * re_star)
    return interpolation + CORRECTED_SECOND_ORDER * re_star**2


def inertial_force_correction(annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
    """First-order inertial force of the wall rotations, from the table: a force along e_eps.

    f_eps^(1) = rho a^3 L (C_aa W_a^2 + 2 C_ab W_a W_b + C_bb W_b^2), with
    W = Omega - chi' and the coefficients of
    :func:`lubrication.navier_stokes.first_inertial_correction` interpolated
    from :mod:`lubrication.inertia_table`; f_chi and T_a have no first-order
    term. With it the Stokes force is off by O(Re*^2): 9e-5 of it at Re* = 1,
    8e-4 at Re* = 3 (docs/inertia/inertia.md). The
    rotating-frame force (:func:`frame_forces`) is separate and exact; the
    squeeze eps' is not covered.

    Returns
    -------
    FluidForces
        (f_eps^(1), 0, 0) in N, N, N m; ``model="inertia-first-order"``.
    """
    f_eps = first_order_f_eps(annulus.kappa, annulus.delta_over_a, annulus.a, fluid.rho, annulus.length,
                              motion.w_a, motion.w_b)
    return FluidForces(float(f_eps), 0.0, 0.0, model="inertia-first-order")


def first_order_f_eps(kappa, delta_over_a: float, a: float, rho, length: float, w_a, w_b):
    """f_eps^(1) (N) of :func:`inertial_force_correction` for arrays of states (kappa, rho, W_a, W_b broadcast).

    ``a`` (m), ``rho`` (kg/m^3), ``length`` (m); W = Omega - chi' in rad/s.
    """
    from .inertia_table import DELTA_NODES, KAPPA_NODES, TABLE

    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (kappa, rho, w_a, w_b)))
    flat = [np.ascontiguousarray(v).ravel() for v in arrays]
    return _first_order_f_eps_along(*flat, float(delta_over_a), float(a), float(length), KAPPA_NODES, DELTA_NODES,
                                    TABLE).reshape(arrays[0].shape)


@jit(inline="always")
def _interpolate(kappa, d, kappa_nodes, delta_nodes, table):
    """Bilinear interpolation of the normalised table in (kappa, delta/a), held at the edges."""
    nk, nd = kappa_nodes.size, delta_nodes.size
    k = min(max(kappa, kappa_nodes[0]), kappa_nodes[nk - 1])
    x = min(max(d, delta_nodes[0]), delta_nodes[nd - 1])
    i, j = cell(kappa_nodes, k), cell(delta_nodes, x)
    tk = (k - kappa_nodes[i]) / (kappa_nodes[i + 1] - kappa_nodes[i])
    tx = (x - delta_nodes[j]) / (delta_nodes[j + 1] - delta_nodes[j])
    return ((1.0 - tk) * (1.0 - tx) * table[i, j] + tk * (1.0 - tx) * table[i + 1, j]
            + (1.0 - tk) * tx * table[i, j + 1] + tk * tx * table[i + 1, j + 1])


@jit
def _first_order_f_eps(kappa, d, a, rho, length, w_a, w_b, kappa_nodes, delta_nodes, table):
    """rho a^3 L (C_aa W_a^2 + 2 C_ab W_a W_b + C_bb W_b^2) with the table's C (TABLE_COLUMNS)."""
    c = _interpolate(kappa, d, kappa_nodes, delta_nodes, table)
    b = 1.0 + d
    quadratic = c[2] * w_a * w_a + 2.0 * c[3] * b * w_a * w_b + c[4] * b * b * w_b * w_b
    return rho * a**3 * length * kappa * quadratic


@jit
def _error_estimate(kappa, d, re_a, re_b, kappa_nodes, delta_nodes, table):
    """The interpolated first-order force over |R_a W_a| + |R_b W_b| (see inertial_error_estimate)."""
    c = _interpolate(kappa, d, kappa_nodes, delta_nodes, table)
    stokes_scale = abs(c[0] * re_a) + abs(c[1] * re_b)
    inertial = abs(c[2] * re_a * re_a + 2.0 * c[3] * re_a * re_b + c[4] * re_b * re_b)
    if inertial == 0.0:
        return 0.0
    # (a^2/nu) |m C m| / (|R_a m_a| + |R_b m_b|) with m = (W_a, W_b) = nu (Re_a, Re_b a/b) / (a delta);
    # the kappa of the normalisation cancels, leaving the factor below
    zeta = math.sqrt((1.0 - kappa) * (1.0 + kappa))
    return d * (2.0 + kappa * kappa) * zeta * inertial / stokes_scale


@jit
def _error_estimates(kappa, re_a, re_b, d, kappa_nodes, delta_nodes, table):
    """:func:`_error_estimate` along 1-D arrays of states."""
    out = np.empty(kappa.size)
    for i in range(kappa.size):
        out[i] = _error_estimate(kappa[i], d, re_a[i], re_b[i], kappa_nodes, delta_nodes, table)
    return out


@jit
def _first_order_f_eps_along(kappa, rho, w_a, w_b, d, a, length, kappa_nodes, delta_nodes, table):
    """:func:`_first_order_f_eps` along 1-D arrays of states."""
    out = np.empty(kappa.size)
    for i in range(kappa.size):
        out[i] = _first_order_f_eps(kappa[i], d, a, rho[i], length, w_a[i], w_b[i], kappa_nodes, delta_nodes, table)
    return out


@jit(inline="always")
def inertial_f_eps(data, a, b, length, kappa, w_a, w_b):
    """The first inertial correction to f_eps of a kernel's packed ``data`` (:mod:`lubrication.kernels`);
    zero for a model without it."""
    start = int(data[kernels.INERTIA])
    if start == 0:
        return 0.0
    nk, nd, nc = int(data[kernels.N_KAPPA]), int(data[kernels.N_DELTA]), int(data[kernels.N_COLUMNS])
    table = start + nk + nd
    return _first_order_f_eps(kappa, (b - a) / a, a, data[kernels.RHO], length, w_a, w_b, data[start:start + nk],
                              data[start + nk:table], data[table:table + nk * nd * nc].reshape((nk, nd, nc)))
