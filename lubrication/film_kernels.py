"""numba kernels of the transported film; the formulation is in :mod:`lubrication.film_transport`.

Thin gap h = delta (1 - kappa cos theta) only, on the Reynolds solver's cells with
the Sommerfeld grid following the gap (kappa_g = kappa). Pressures are carried as
x = (p - p_cav)/(12 mu a) >= 0, volumes and contents per unit length (m^2).
"""

from __future__ import annotations

import math

import numpy as np

from numerics.jit import jit

from .cavitation_kernels import (
    _cell_coefficients,
    _film_integrals,
    half_sommerfeld_weights,
)
from .reynolds_kernels import N_INTEGRALS, THIN, cell_integrals

# How the film meets its reservoir: a liquid feed at the node opposite the narrowest gap
# (the steady models' convention), or the end reservoirs and their trapped bubble.
FEED, BUBBLE = 0, 1
# What a node is in the complementarity problem: at p_cav with x = 0, pressed (x solved for),
# or held at a given pressure (the feed node).
FREE, PRESSED, FIXED = 0, 1, 2
# Violations below this fraction of their node's scale are rounding, not a reason to switch.
SWITCH_TOLERANCE = 1e-12


@jit(inline="always")
def theta_minus_sin(theta):
    """theta - sin(theta) without cancellation for small theta (series below 0.5, 24 eps above)."""
    if abs(theta) >= 0.5:
        return theta - math.sin(theta)
    t2 = theta * theta
    term = theta * t2 / 6.0
    total = term
    for k in range(2, 10):  # the next term is below 1e-17 of the first
        term *= -t2 / ((2 * k) * (2 * k + 1))
        total += term
    return total


@jit
def film_geometry(a, b, kappa, omk, eps_dot, faces, node_p, volume, vdot, qtilde, dtheta, h_node):
    """Dual cells of the moving grid: their gap area, its rate, the faces' squeeze flux and widths.

    Parameters
    ----------
    faces : tuple of 4 ndarray, shape (N,)
        sin psi, 1 + cos psi, sin(psi/2), cos(psi/2) at the faces psi_j + dpsi/2.
    node_p : ndarray, shape (N,)
        1 + cos psi at the nodes.
    volume, vdot : ndarray, shape (N,)
        Receive V_j, the gap area a int h dtheta of dual cell j (m^2), and dV_j/dt.
    qtilde : ndarray, shape (N,)
        Receives Q~ at face j: Q(theta_f) + a h theta_f', the gap area swept through the
        moving face per unit time, with Q = -a eps' sin(theta) the squeeze antiderivative.
    dtheta, h_node : ndarray, shape (N,)
        Receive the width in theta of dual cell j and the gap at node j.
    """
    n = volume.size
    delta = b - a
    sin_psi, one_plus, sin_half, cos_half = faces
    zeta = math.sqrt(omk * (1.0 + kappa))
    beta = math.sqrt(omk / (1.0 + kappa))
    area = a * delta
    cumulative = np.empty(n)
    theta_f = np.empty(n)
    for j in range(n):
        d = omk + kappa * one_plus[j]  # 1 + kappa cos psi
        sin_t = zeta * sin_psi[j] / d
        theta = 2.0 * math.atan2(beta * sin_half[j], cos_half[j])
        theta_f[j] = theta
        # a int_0^theta h = a delta (theta - kappa sin theta), split so that no term cancels near contact
        cumulative[j] = area * (omk * theta + kappa * theta_minus_sin(theta))
        # theta_f' = -kappa' sin(theta_f)/zeta^2 and h_f = delta zeta^2/d: a h_f theta_f' = -a eps' sin/d
        qtilde[j] = -a * eps_dot * sin_t * (1.0 + 1.0 / d)
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        if j > 0:
            volume[j] = cumulative[j] - cumulative[jm]
            dtheta[j] = theta_f[j] - theta_f[jm]
        else:  # the cell across theta = +-pi, the widest gap
            volume[j] = 2.0 * math.pi * area - (cumulative[jm] - cumulative[j])
            dtheta[j] = 2.0 * math.pi - (theta_f[jm] - theta_f[j])
        vdot[j] = qtilde[j] - qtilde[jm]
        h_node[j] = delta * zeta * zeta / (omk + kappa * node_p[j])


@jit
def thomas(sub, diag, sup, rhs):
    """Tridiagonal solve without pivoting (the matrices here are diagonally dominant); returns x.

    ``sub[i]`` = A[i, i-1] (``sub[0]`` unused), ``sup[i]`` = A[i, i+1] (``sup[n-1]`` unused).
    """
    n = diag.size
    c = np.empty(n)
    x = np.empty(n)
    c[0] = sup[0] / diag[0]
    x[0] = rhs[0] / diag[0]
    for i in range(1, n):
        pivot = diag[i] - sub[i] * c[i - 1]
        c[i] = sup[i] / pivot if i < n - 1 else 0.0
        x[i] = (rhs[i] - sub[i] * x[i - 1]) / pivot
    for i in range(n - 2, -1, -1):
        x[i] -= c[i] * x[i + 1]
    return x


@jit
def cyclic_solve(sub, diag, sup, rhs):
    """A x = rhs for a tridiagonal A with corners, by Sherman-Morrison on :func:`thomas`.

    ``sub[i]`` = A[i, i-1] and ``sup[i]`` = A[i, i+1], indices mod n: ``sub[0]`` =
    A[0, n-1] and ``sup[n-1]`` = A[n-1, 0] are the corners. A must be diagonally
    dominant (with its corners).
    """
    n = diag.size
    alpha, beta = sup[n - 1], sub[0]
    if alpha == 0.0 and beta == 0.0:
        return thomas(sub, diag, sup, rhs)
    # A = T + u v^T with u = (gamma, 0, .., 0, alpha), v = (1, 0, .., 0, beta/gamma)
    gamma = -diag[0]
    d = diag.copy()
    d[0] -= gamma
    d[n - 1] -= alpha * beta / gamma
    x = thomas(sub, d, sup, rhs)
    u = np.zeros(n)
    u[0] = gamma
    u[n - 1] = alpha
    z = thomas(sub, d, sup, u)
    fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma)
    for i in range(n):
        x[i] -= fact * z[i]
    return x


@jit
def complementarity(g, lam, b, state, y_fixed, y_low, y, complementary, max_passes):
    """y >= y_low, w = A y + b >= 0, (y - y_low) w = 0 (or A y + b = 0 with ``complementary`` False).

    A is the periodic conductance Laplacian plus the end conductances,
    (A y)_j = (g_j + g_{j-1} + lam_j) y_j - g_j y_{j+1} - g_{j-1} y_{j-1}: a symmetric
    M-matrix once a node is held (``state`` FIXED, at ``y_fixed``) or some lam_j > 0,
    so the problem has one solution, Lipschitz in b. It is found by the primal-dual
    active-set method, which for M-matrices ends in finitely many passes from any
    start (Hintermueller, Ito & Kunisch, SIAM J. Optim. 13, 2002); ``state`` holds the
    start (FREE, at y_low, or PRESSED per node) and leaves with the solution's.
    Pressures are measured from the reference (``y_fixed`` = 0 at a feed), so that a
    cavitation level far below them costs no precision. Returns the passes, or -1 if
    the set still changed after ``max_passes``.
    """
    n = b.size
    sub, diag, sup, rhs = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    for iteration in range(1, max_passes + 1):
        for j in range(n):
            jm = j - 1 if j > 0 else n - 1
            a_jj = g[j] + g[jm] + lam[j]
            diag[j] = a_jj
            if state[j] == PRESSED or not complementary:
                sub[j], sup[j], rhs[j] = -g[jm], -g[j], -b[j]
            else:  # a row scaled like its neighbours: y_j = y_low or y_fixed
                sub[j], sup[j] = 0.0, 0.0
                rhs[j] = a_jj * (y_fixed if state[j] == FIXED else y_low)
        solution = cyclic_solve(sub, diag, sup, rhs)
        y[:] = solution
        if not complementary:
            return iteration
        x_scale = abs(y_fixed - y_low)
        for j in range(n):
            x_scale = max(x_scale, abs(y[j] - y_low))
        changed = False
        for j in range(n):
            if state[j] == FIXED:
                continue
            jm = j - 1 if j > 0 else n - 1
            jp = j + 1 if j < n - 1 else 0
            a_jj = g[j] + g[jm] + lam[j]
            if state[j] == PRESSED:
                if y[j] - y_low < -SWITCH_TOLERANCE * x_scale:
                    state[j] = FREE
                    changed = True
            else:
                w = b[j] + a_jj * y[j] - g[j] * y[jp] - g[jm] * y[jm]
                if w < -SWITCH_TOLERANCE * (abs(b[j]) + a_jj * (abs(y_low) + x_scale)):
                    state[j] = PRESSED
                    changed = True
        if not changed:
            for j in range(n):
                if state[j] == FREE:
                    y[j] = y_low
                elif state[j] == PRESSED:
                    y[j] = max(y[j], y_low)
            return iteration
    return -1


@jit
def film_fluxes(a, b, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m, faces, node_p,
                void, integrals, volume, vdot, dtheta, h_node, film, conv):
    """Cell integrals, dual cells, film fractions and the convective content flux of every face.

    ``conv[j]`` receives the content carried across face j (from node j to j+1, relative to
    the moving face) by the walls and by the squeeze and grid motion, each part at the film
    fraction of its upwind node; ``film`` the film fraction F_j = 1 - void_j/V_j.
    Returns (g, half_u): the cells' conductances and (U_a + U_b)/2.
    """
    n = void.size
    integrals[:, :] = 0.0
    cell_integrals(THIN, a, b, kappa, omk, eps_dot, kappa, omk, cpsi, spsi, vpsi, ppsi, wpsi, m,
                   np.empty(0), np.empty(0), integrals)
    half_u = 0.5 * a * (w_a + w_b)
    g, k, q_mean = _cell_coefficients(integrals, half_u)
    qtilde = np.empty(n)
    film_geometry(a, b, kappa, omk, eps_dot, faces, node_p, volume, vdot, qtilde, dtheta, h_node)
    for j in range(n):
        film[j] = 1.0 - void[j] / volume[j]
    for j in range(n):
        jp = j + 1 if j < n - 1 else 0
        squeeze = q_mean[j] - qtilde[j]
        conv[j] = (film[j] if half_u >= 0.0 else film[jp]) * k[j] + (film[j] if squeeze >= 0.0 else film[jp]) * squeeze
    return g, half_u


@jit
def film_rates(a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m,
               faces, node_p, gauge, p_cav, p_ref, bubble_volume, end_conductance, relaxation,
               void, reservoir, d_void, y, film, flux):
    """Rates of the film's state, its pressure and the force and torque it exerts.

    Parameters
    ----------
    a, b, mu, length : float
        Radii, viscosity, length (SI).
    kappa, omk, eps_dot, w_a, w_b : float
        Eccentricity, 1 - kappa, eps' (m/s), and the spins relative to the line of centres (rad/s).
    cpsi, spsi, vpsi, ppsi, wpsi, m
        The Gauss rule of the cells (``lubrication.reynolds.psi_rule``).
    faces, node_p
        As :func:`film_geometry`.
    gauge : int
        FEED (node 0 at ``p_ref``) or BUBBLE (end reservoirs; ``p_ref`` is then the
        bubble's pressure when the reservoir holds no extra liquid).
    p_cav : float
        Cavitation pressure (Pa).
    bubble_volume, end_conductance : float
        BUBBLE: the bubble's volume at ``p_ref`` (m^3) and the dimensionless end conductance.
    relaxation : float
        Time (s) in which a pressed node's void closes.
    void : ndarray, shape (N,)
        The state: gas volume of each dual cell per unit length, V_j - M_j (m^2).
    reservoir : float
        The state: liquid the reservoir has taken from the film per unit length (m^2).
    d_void, y, film, flux : ndarray, shape (N,)
        Receive dvoid/dt, y = (p - p_res)/(12 mu a), the film fraction and the liquid
        carried across face j from node j to j+1, relative to the moving face (m^2/s).

    Returns
    -------
    f_eps, f_chi, t_a : float
        Force (N) and torque (N m) over the length.
    d_reservoir : float
        d(reservoir)/dt (m^2/s).
    p_res : float
        The pressure y is measured from (Pa): ``p_ref`` at a feed, the bubble's with the end reservoirs.
    passes : int
        Active-set passes; -1 (and NaN everywhere) if the problem could not be solved.
    """
    n = void.size
    integrals = np.empty((n, N_INTEGRALS))
    volume, vdot, dtheta, h_node, conv = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    g, half_u = film_fluxes(a, b, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m, faces,
                               node_p, void, integrals, volume, vdot, dtheta, h_node, film, conv)
    scale_p = 12.0 * mu * a
    lam = np.zeros(n)
    state = np.empty(n, dtype=np.int64)
    if gauge == FEED:
        y_cav = (p_cav - p_ref) / scale_p
        p_res = p_ref
    else:
        gas = bubble_volume - length * reservoir
        # the reservoir cannot hold tension: it cavitates rather than fall below p_cav
        p_res = max(p_ref * bubble_volume / gas, p_cav) if gas > 0.0 else np.nan
        y_cav = (p_cav - p_res) / scale_p
        for j in range(n):
            lam[j] = end_conductance * h_node[j] ** 3 * dtheta[j]
    b = np.empty(n)
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        b[j] = vdot[j] - (conv[jm] - conv[j]) + void[j] / relaxation
        state[j] = PRESSED if void[j] <= 0.0 else FREE
    if gauge == FEED:
        state[0] = FIXED
    passes = complementarity(g, lam, b, state, 0.0, y_cav, y, True, n + 16) if np.isfinite(y_cav) else -1
    if passes < 0:
        d_void[:] = np.nan
        flux[:] = np.nan
        return np.nan, np.nan, np.nan, np.nan, p_res, passes
    # content fluxes through the faces, and each dual cell's balance
    for j in range(n):
        jp = j + 1 if j < n - 1 else 0
        flux[j] = conv[j] - g[j] * (y[jp] - y[j])
    d_reservoir = 0.0
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        exchange = lam[j] * y[j]  # to the end reservoirs, at p_res
        d_void[j] = vdot[j] - (flux[jm] - flux[j] - exchange)
        d_reservoir += exchange
    if gauge == FEED:  # the feed keeps its node full, taking or giving whatever that needs
        d_void[0] = -void[0] / relaxation
        d_reservoir = -((vdot[0] - d_void[0]) - (flux[n - 1] - flux[0]))
    # forces: a cell at p_cav at both ends carries no pressure; the shear is the liquid's
    weight = np.ones(n)
    shear_film = np.empty(n)
    for j in range(n):
        jp = j + 1 if j < n - 1 else 0
        if y[j] == y_cav and y[jp] == y_cav:
            weight[j] = 0.0
        shear_film[j] = min(max(film[j], 0.0), 1.0)
    i_sin, i_chi, i_torque = _film_integrals(integrals, half_u, a * w_a, a * w_b, y, weight, shear_film)
    scale = scale_p * a * length
    return scale * i_sin, scale * i_chi, mu * a * a * length * i_torque, d_reservoir, p_res, passes


@jit
def leaky_truncated_forces(a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m,
                           faces, node_p, p_cav, p_res, end_conductance, y):
    """The half-Sommerfeld forces with the end-reservoir gauge: the full film, then p = max(p, p_cav).

    The full film is the one that exchanges liquid with reservoirs at ``p_res`` through
    the ends (module docstring of :mod:`lubrication.film_transport`); ``y`` receives its
    (p - p_res)/(12 mu a). Returns f_eps, f_chi, T_a.
    """
    n = y.size
    integrals = np.empty((n, N_INTEGRALS))
    volume, vdot, dtheta, h_node, conv, film = (np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n),
                                                np.empty(n))
    g, half_u = film_fluxes(a, b, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m, faces,
                               node_p, np.zeros(n), integrals, volume, vdot, dtheta, h_node, film, conv)
    lam = np.empty(n)
    b = np.empty(n)
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        lam[j] = end_conductance * h_node[j] ** 3 * dtheta[j]
        b[j] = vdot[j] - (conv[jm] - conv[j])
    state = np.full(n, PRESSED, dtype=np.int64)
    complementarity(g, lam, b, state, 0.0, 0.0, y, False, 1)
    weight = np.empty(n)
    half_sommerfeld_weights(y, (p_cav - p_res) / (12.0 * mu * a), weight)
    i_sin, i_chi, i_torque = _film_integrals(integrals, half_u, a * w_a, a * w_b, y, weight, np.ones(n))
    scale = 12.0 * mu * a * a * length
    return scale * i_sin, scale * i_chi, mu * a * a * length * i_torque
