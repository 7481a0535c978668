r"""numba kernels of the Reynolds solver on (theta, z); the formulation is in :mod:`lubrication.reynolds2d`.

Unknown: phi = (p - p_end)/(12 mu a) at the nodes (xi_j, z_k) of a tensor grid,
xi uniform and periodic and mapped to the Sommerfeld angle psi of the grid
parameter (:mod:`lubrication.reynolds2d`), z in units of a. The cells are those
of :mod:`lubrication.reynolds_kernels`, their quadrature weights in psi carrying dpsi/dxi
(``stretch``). The discrete equations are

    (M_z (x) L_theta + K_z (x) M_theta) phi = -(w_z (x) r)

with, along a z-line, the periodic "exact-conductance" Laplacian L_theta
(conductances g_j = 1/int_cell h^-3) and load r_j = k_j - k_{j-1} + <Q>_j - <Q>_{j-1}
of the one-dimensional scheme, the consistent (linear-element) mass
M_theta of the weight h^3 in theta, and in z the linear-element stiffness
K_z and mass M_z, w_z = M_z 1 the trapezoid weights. Where h depends on z the
line matrices are those of each line, averaged over the two lines of a z-element
in the couplings between them (:func:`assemble_general`).
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
from .reynolds_kernels import (
    ECCENTRIC,
    H2,
    H3,
    N_INTEGRALS,
    OH3,
    QH3,
    SH3,
    THIN,
    cell_integrals,
    eccentric_gap,
)

# Columns of the per-cell integrals of h^3 (t in [0, 1] the position in the cell, linear in psi):
# the consistent mass, int h^3 (1-t)^2, int h^3 t (1-t), int h^3 t^2 dtheta; and the flux
# correction's int P_0 w/h^3, int P_1 w/h^3 for w = 1, sin, omega, and int P_0/h^2, int P_1/h^2,
# with P_0(t) = int_0^t h^3 (1-t') dtheta', P_1(t) = int_0^t h^3 t' dtheta' (modal_film).
M00, M01, M11, X0, X1, X0S, X1S, X0O, X1O, X0H, X1H = range(11)
N_MASSES = 11
# COO triplets per (z-element, theta-cell) of assemble_general: 16 theta-stiffness, 16 z-stiffness.
ENTRIES_PER_CELL = 32


@jit
def cell_masses(kind, a, b, kappa, omk, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, stretch, tpos, lower0,
                lower1, m, h_tab, out):
    """Add to ``out[j]`` the integrals of h^3 over cell j listed by the column constants above.

    Arguments as :func:`lubrication.reynolds_kernels.cell_integrals`, whose weights
    ``wpsi`` are in psi; ``stretch`` (shape (N m,)) is dpsi/dxi at the points, the
    cells being uniform in xi. ``tpos`` (shape (m,)) holds the Gauss points'
    positions in [0, 1] within a cell, linear in xi, and ``lower0``, ``lower1``
    (shape (m, m)) integrate the Lagrange interpolant through them:
    P_0(t_p) = dxi sum_i lower0[p, i] f_i with f = h^3 dtheta/dxi at the points
    (lower1 likewise for P_1), exact for the interpolant, O(dxi^m) for h.
    """
    n_cells = spsi.size // m
    zeta_g = math.sqrt(omk_g * (1.0 + kappa_g))
    dxi = 2.0 * math.pi / n_cells
    delta = b - a
    eps = kappa * delta
    vers_weight = kappa >= 0.5  # the same omega as cell_integrals
    f = np.empty(m)
    h3 = np.empty(m)
    inv_h = np.empty(m)
    jac = np.empty(m)
    sin_t = np.empty(m)
    om_t = np.empty(m)
    k = 0
    for j in range(n_cells):
        for i in range(m):
            d = omk_g + kappa_g * ppsi[k + i]
            r = 1.0 / d
            s = zeta_g * spsi[k + i] * r
            v = omk_g * vpsi[k + i] * r
            if kind == THIN:
                h = delta * (omk * d + kappa * omk_g * vpsi[k + i]) * r
            elif kind == ECCENTRIC:
                h, _ = eccentric_gap(a, b, eps, omk, s, v, 0.0)
            else:
                h = h_tab[k + i]
            jac[i] = zeta_g * r
            inv_h[i] = 1.0 / h
            h3[i] = h * h * h * jac[i]  # h^3 dtheta/dpsi
            f[i] = h3[i] * stretch[k + i]  # h^3 dtheta/dxi
            sin_t[i] = s
            om_t[i] = v if vers_weight else -(kappa_g + cpsi[k + i]) * r
        row = out[j]
        for p in range(m):
            t = tpos[p]
            w = wpsi[k + p] * h3[p]
            row[M00] += w * (1.0 - t) * (1.0 - t)
            row[M01] += w * t * (1.0 - t)
            row[M11] += w * t * t
            p0 = p1 = 0.0
            for i in range(m):
                p0 += lower0[p, i] * f[i]
                p1 += lower1[p, i] * f[i]
            c3 = wpsi[k + p] * jac[p] * dxi * inv_h[p] ** 3
            row[X0] += c3 * p0
            row[X1] += c3 * p1
            row[X0S] += c3 * p0 * sin_t[p]
            row[X1S] += c3 * p1 * sin_t[p]
            row[X0O] += c3 * p0 * om_t[p]
            row[X1O] += c3 * p1 * om_t[p]
            row[X0H] += c3 * p0 / inv_h[p]
            row[X1H] += c3 * p1 / inv_h[p]
        k += m


@jit
def line_load(integrals, half_u):
    """Conductances g (N,) and load r (N,) of one z-line: the one-dimensional scheme's."""
    n = integrals.shape[0]
    g, k, qm = _cell_coefficients(integrals, half_u)
    r = np.empty(n)
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        r[j] = k[j] - k[jm] + qm[j] - qm[jm]
    return g, r


@jit
def _spd_tridiagonal_solve2(diag, off, b1, b2):
    """Solve T x = b1 and T x = b2 in place for a symmetric positive definite tridiagonal T.

    ``diag`` (n,) and ``off`` (n-1,) are T's diagonal and off-diagonal; they are
    overwritten, as are ``b1``, ``b2``, which return the solutions. An SPD
    matrix needs no pivoting: this is its LDL^T factorisation.
    """
    n = diag.size
    for i in range(1, n):
        f = off[i - 1] / diag[i - 1]
        diag[i] -= f * off[i - 1]
        b1[i] -= f * b1[i - 1]
        b2[i] -= f * b2[i - 1]
    b1[n - 1] /= diag[n - 1]
    b2[n - 1] /= diag[n - 1]
    for i in range(n - 2, -1, -1):
        b1[i] = (b1[i] - off[i] * b1[i + 1]) / diag[i]
        b2[i] = (b2[i] - off[i] * b2[i + 1]) / diag[i]


@jit
def mode_solve(g, masses, stiffness, lam, r, y_out):
    """Nodal solution of (stiffness L_theta + lam M_theta) psi = -r, periodic, for a load with sum(r) = 0.

    With stiffness = 1 this is one z-mode (lam > 0); with stiffness = 0 and
    lam = 1, the consistent-mass solve M_theta psi = -r. The matrix is SPD
    but, as lam -> 0 (a long bearing), tends to the singular periodic
    Laplacian. Summing every row gives lam m^T psi = -sum(r) = 0 (the load
    telescopes; m = M_theta 1), which holds for any lam: so psi = y + c with
    y_0 = 0 pinned and c = -m^T y / sum(m), and rows 1..N-1 become the
    non-cyclic SPD tridiagonal system T_r y - u m^T y = -r with the rank-one
    term u = lam m / sum(m), solved by Sherman-Morrison. Neither step divides
    by lam, so the conditioning stays that of the one-dimensional problem.

    Parameters
    ----------
    g : ndarray, shape (N,)
        Cell conductances.
    masses : ndarray, shape (N, N_MASSES)
        Cell integrals of h^3 (:func:`cell_masses`).
    stiffness, lam : float
        Weights of L_theta and M_theta; lam > 0.
    r : ndarray, shape (N,)
        Load summing to zero.
    y_out : ndarray, shape (N,)
        Receives psi at the nodes.
    """
    n = g.size
    msum = 0.0
    mrow = np.empty(n)
    for j in range(n):
        jm = j - 1 if j > 0 else n - 1
        mrow[j] = masses[j, M00] + masses[j, M01] + masses[jm, M11] + masses[jm, M01]
        msum += mrow[j]
    size = n - 1
    diag = np.empty(size)
    off = np.empty(max(size - 1, 0))
    b1 = np.empty(size)
    b2 = np.empty(size)
    for i in range(size):
        j = i + 1
        jm = j - 1
        diag[i] = stiffness * (g[j] + g[jm]) + lam * (masses[j, M00] + masses[jm, M11])
        if i < size - 1:
            off[i] = -stiffness * g[j] + lam * masses[j, M01]
        b1[i] = -r[j]
        b2[i] = lam * mrow[j] / msum
    _spd_tridiagonal_solve2(diag, off, b1, b2)
    dot1 = 0.0
    dot2 = 0.0
    for i in range(size):
        dot1 += mrow[i + 1] * b1[i]
        dot2 += mrow[i + 1] * b2[i]
    scale = dot1 / (1.0 - dot2)
    y_out[0] = 0.0
    my = 0.0
    for i in range(size):
        y_out[i + 1] = b1[i] + scale * b2[i]
        my += mrow[i + 1] * y_out[i + 1]
    c = -my / msum
    for j in range(n):
        y_out[j] += c


@jit
def _long_jumps(integrals, half_u, coef, out):
    """Jumps phi_{j+1} - phi_j of the one-dimensional (lam = 0) solution, times ``coef``."""
    n = integrals.shape[0]
    s2 = s3 = sq = 0.0
    for j in range(n):
        s2 += integrals[j, H2]
        s3 += integrals[j, H3]
        sq += integrals[j, QH3]
    qhat = (half_u * s2 + sq) / s3
    for j in range(n):
        out[j] = coef * (half_u * integrals[j, H2] + integrals[j, QH3] - qhat * integrals[j, H3])


@jit
def _jump_sums(integrals, jumps):
    """d(oint phi' sin, oint phi' omega, torque sum) per unit jumps, contracted with ``jumps``.

    In cell j the flux constant is c_j = ((U/2) A_j + B_j - jump_j)/G_j
    (:func:`lubrication.cavitation_kernels._film_integrals`), so every line
    integral is its value at zero jumps plus sum_j jump_j (SH3_j, OH3_j, -6 H2_j)/G_j.
    """
    s_sin = s_chi = s_torque = 0.0
    for j in range(integrals.shape[0]):
        inv = jumps[j] / integrals[j, H3]
        s_sin += inv * integrals[j, SH3]
        s_chi += inv * integrals[j, OH3]
        s_torque -= 6.0 * inv * integrals[j, H2]
    return s_sin, s_chi, s_torque


@jit
def flux_correction(integrals, masses, d, weight):
    """The axial outflow's share of the line integrals, for the nodal outflow density ``d``.

    Within a theta-cell the one-dimensional rule takes the theta-flux as
    c_j - Q (it balances only the squeeze), which is exact for a long
    bearing. On (theta, z) the flux also loses what flows out axially,
    h^3 d with d = -(1/h^3) d/dz (h^3 dphi/dz) (lam psi for a z-mode):
    h^3 phi' = (U/2) h + Q + Phi - c_j, Phi = int_(theta_j)^theta h^3 d,
    d linear in the cell. Without it the cells carry a spurious
    intra-cell Couette flux whose force, O(dpsi^2) relative to the
    long-bearing one, would swamp a short bearing's. The terms added to
    oint phi' sin, oint phi' omega and the torque sum are, per cell,
    d_j (X0w - X0 W/G) + d_{j+1} (X1w - X1 W/G) for W = SH3, OH3 and -6 H2,
    counted with ``weight[j]``.
    """
    n = integrals.shape[0]
    c_sin = c_chi = c_torque = 0.0
    for j in range(n):
        if weight[j] == 0.0:
            continue
        jp = j + 1 if j < n - 1 else 0
        row = masses[j]
        inv_g = 1.0 / integrals[j, H3]
        c_sin += weight[j] * (d[j] * (row[X0S] - row[X0] * integrals[j, SH3] * inv_g)
                              + d[jp] * (row[X1S] - row[X1] * integrals[j, SH3] * inv_g))
        c_chi += weight[j] * (d[j] * (row[X0O] - row[X0] * integrals[j, OH3] * inv_g)
                              + d[jp] * (row[X1O] - row[X1] * integrals[j, OH3] * inv_g))
        c_torque -= 6.0 * weight[j] * (d[j] * (row[X0H] - row[X0] * integrals[j, H2] * inv_g)
                                       + d[jp] * (row[X1H] - row[X1] * integrals[j, H2] * inv_g))
    return c_sin, c_chi, c_torque


@jit
def end_outflow(integrals, masses, half_u, out):
    """d on an open end line, where phi = 0: M_theta d = -r, all of the load leaves axially."""
    g, r = line_load(integrals, half_u)
    mode_solve(g, masses, 0.0, 1.0, r, out)


@jit
def modal_film(integrals, masses, u_a, u_b, lam, coef, half_length, end_weight, modes_out):
    """z-integrated line integrals of a z-independent film, mode by mode.

    With K_z V = M_z V diag(lam), V^T M_z V = I, phi = sum_m v_m psi_m and each
    psi_m solves (L_theta + lam_m M_theta) psi_m = -c_m r, c_m = v_m^T w_z. The
    line integrals are linear in the jumps of phi and in the outflow density
    d = sum_m v_m lam_m psi_m (:func:`flux_correction`), and sum_k w_z,k v_m,k = c_m,
    so the integral over the half length of any line integral is
    half_length * (its value at zero jumps and outflow) + sum_m c_m (its part for
    psi_m) + end_weight (the end line's outflow part).

    Parameters
    ----------
    integrals : ndarray, shape (N, N_INTEGRALS)
        Cell integrals of the line (:func:`lubrication.reynolds_kernels.cell_integrals`).
    masses : ndarray, shape (N, N_MASSES)
        Cell integrals of h^3 (:func:`cell_masses`).
    u_a, u_b : float
        Wall speeds in the frame of the line of centres (m/s).
    lam, coef : ndarray, shape (n_modes,)
        z-eigenvalues (1/a^2 units) and load coefficients c_m (a^(1/2) units). A
        mode with lam = 0 (sealed ends: the constant) takes the one-dimensional solution.
    half_length : float
        Sum of the trapezoid weights w_z (L/2 in units of a).
    end_weight : float
        Trapezoid weight of an open end line (0 for sealed ends).
    modes_out : ndarray, shape (n_modes, N) or (0, N)
        When not empty, receives psi_m at the nodes (c_m included).

    Returns
    -------
    i_sin, i_chi, i_torque : float
        int dz of oint phi' sin, oint phi' omega and oint [(u_b - u_a)/h - 6 phi' h]
        (z in units of a), as :func:`lubrication.reynolds_kernels.full_film` per line.
    """
    n = integrals.shape[0]
    half_u = 0.5 * (u_a + u_b)
    ones = np.ones(n)
    e_sin, e_chi, e_torque = _film_integrals(integrals, half_u, u_a, u_b, np.zeros(n), ones, ones)
    i_sin = half_length * e_sin
    i_chi = half_length * e_chi
    i_torque = half_length * e_torque
    g, r = line_load(integrals, half_u)
    keep = modes_out.shape[0] == lam.size
    psi = np.empty(n)
    load = np.empty(n)
    jumps = np.empty(n)
    for i in range(lam.size):
        if coef[i] == 0.0:
            if keep:
                modes_out[i, :] = 0.0
            continue
        if lam[i] == 0.0:
            _long_jumps(integrals, half_u, coef[i], jumps)
            if keep:
                acc = 0.0
                for j in range(n):
                    modes_out[i, j] = acc
                    acc += jumps[j]
            c_sin = c_chi = c_torque = 0.0
        else:
            for j in range(n):
                load[j] = coef[i] * r[j]
            mode_solve(g, masses, 1.0, lam[i], load, psi)
            for j in range(n):
                jp = j + 1 if j < n - 1 else 0
                jumps[j] = psi[jp] - psi[j]
            if keep:
                modes_out[i, :] = psi
            c_sin, c_chi, c_torque = flux_correction(integrals, masses, lam[i] * psi, ones)
        s_sin, s_chi, s_torque = _jump_sums(integrals, jumps)
        i_sin += coef[i] * (s_sin + c_sin)
        i_chi += coef[i] * (s_chi + c_chi)
        i_torque += coef[i] * (s_torque + c_torque)
    if end_weight > 0.0:
        end_outflow(integrals, masses, half_u, psi)
        c_sin, c_chi, c_torque = flux_correction(integrals, masses, psi, ones)
        i_sin += end_weight * c_sin
        i_chi += end_weight * c_chi
        i_torque += end_weight * c_torque
    return i_sin, i_chi, i_torque


@jit
def assemble_general(g_lines, mass_lines, r_lines, z, rows, cols, vals, rhs):
    """COO triplets and load of the (theta, z) system for line-dependent coefficients.

    Node (j, k) is unknown k N + j. Over the z-element e = (k, k+1) of length dz,
    with the line matrices of k and k+1 (conductances g, masses M, load r):

        theta stiffness: dz/3 L^k at (k, k), dz/3 L^(k+1) at (k+1, k+1),
                         dz/6 (L^k + L^(k+1))/2 at (k, k+1) and (k+1, k);
        z stiffness:     (1/dz) (M^k + M^(k+1))/2 with signs [[1, -1], [-1, 1]];
        load:            -(dz/6) (2 r^k + r^(k+1)) at k, -(dz/6) (r^k + 2 r^(k+1)) at k+1.

    For lines that are all alike this is M_z (x) L + K_z (x) M exactly.

    Parameters
    ----------
    g_lines, r_lines : ndarray, shape (n_lines, N)
    mass_lines : ndarray, shape (n_lines, N, N_MASSES)
    z : ndarray, shape (n_lines,)
        Node positions (units of a), increasing.
    rows, cols, vals : ndarray, shape ((n_lines - 1) N ENTRIES_PER_CELL,)
        Receive the triplets (duplicates are to be summed).
    rhs : ndarray, shape (n_lines N,)
        Zero on entry; receives the load.
    """
    n_lines, n = g_lines.shape
    p = 0
    for k in range(n_lines - 1):
        dz = z[k + 1] - z[k]
        for j in range(n):
            jp = j + 1 if j < n - 1 else 0
            nodes_k = (k * n + j, k * n + jp)
            nodes_k1 = ((k + 1) * n + j, (k + 1) * n + jp)
            # theta stiffness of cell j on the two lines and between them
            for blk in range(3):
                if blk == 0:
                    c = dz / 3.0 * g_lines[k, j]
                    left, right = nodes_k, nodes_k
                elif blk == 1:
                    c = dz / 3.0 * g_lines[k + 1, j]
                    left, right = nodes_k1, nodes_k1
                else:
                    c = dz / 12.0 * (g_lines[k, j] + g_lines[k + 1, j])
                    left, right = nodes_k, nodes_k1
                for x in range(2):
                    for y in range(2):
                        sign = 1.0 if x == y else -1.0
                        rows[p] = left[x]
                        cols[p] = right[y]
                        vals[p] = sign * c
                        p += 1
                        if blk == 2:
                            rows[p] = right[y]
                            cols[p] = left[x]
                            vals[p] = sign * c
                            p += 1
            # z stiffness with the theta mass of cell j, averaged over the two lines
            m00 = 0.5 * (mass_lines[k, j, M00] + mass_lines[k + 1, j, M00]) / dz
            m01 = 0.5 * (mass_lines[k, j, M01] + mass_lines[k + 1, j, M01]) / dz
            m11 = 0.5 * (mass_lines[k, j, M11] + mass_lines[k + 1, j, M11]) / dz
            for zx in range(2):
                for zy in range(2):
                    zs = 1.0 if zx == zy else -1.0
                    ax = nodes_k if zx == 0 else nodes_k1
                    ay = nodes_k if zy == 0 else nodes_k1
                    for x in range(2):
                        for y in range(2):
                            mv = m00 if (x == 0 and y == 0) else (m11 if (x == 1 and y == 1) else m01)
                            rows[p] = ax[x]
                            cols[p] = ay[y]
                            vals[p] = zs * mv
                            p += 1
            rhs[nodes_k[0]] -= dz / 6.0 * (2.0 * r_lines[k, j] + r_lines[k + 1, j])
            rhs[nodes_k1[0]] -= dz / 6.0 * (r_lines[k, j] + 2.0 * r_lines[k + 1, j])


@jit
def lines_film(integrals_lines, masses_lines, u_a, u_b, phi, outflow, wz, half_sommerfeld, y_cav, line_out):
    """z-integrated line integrals of a nodal film, each line by the by-parts rule with its axial outflow.

    With ``half_sommerfeld``, nodes below ``y_cav`` = (p_cav - p_end)/(12 mu a) are
    truncated to it and a cell that straddles it is counted with the fraction above
    (as the one-dimensional half-Sommerfeld rule); ``phi`` is then truncated in place.

    Parameters
    ----------
    integrals_lines : ndarray, shape (n_lines, N, N_INTEGRALS)
    masses_lines : ndarray, shape (n_lines, N, N_MASSES)
    phi, outflow : ndarray, shape (n_lines, N)
        Nodal phi of every line and its axial outflow density d (:func:`flux_correction`).
    wz : ndarray, shape (n_lines,)
        Trapezoid weights in z (units of a).
    line_out : ndarray, shape (n_lines, 3)
        Receives each line's (oint phi' sin, oint phi' omega, torque sum).

    Returns
    -------
    i_sin, i_chi, i_torque : float
        The weighted sums over the lines.
    """
    n_lines, n = phi.shape
    half_u = 0.5 * (u_a + u_b)
    ones = np.ones(n)
    weight = np.ones(n)
    i_sin = i_chi = i_torque = 0.0
    for k in range(n_lines):
        y = phi[k]
        if half_sommerfeld:
            half_sommerfeld_weights(y, y_cav, weight)
        s_sin, s_chi, s_torque = _film_integrals(integrals_lines[k], half_u, u_a, u_b, y, weight, ones)
        c_sin, c_chi, c_torque = flux_correction(integrals_lines[k], masses_lines[k], outflow[k], weight)
        if half_sommerfeld:
            for j in range(n):
                y[j] = max(y[j], y_cav)
        line_out[k, 0] = s_sin + c_sin
        line_out[k, 1] = s_chi + c_chi
        line_out[k, 2] = s_torque + c_torque
        i_sin += wz[k] * line_out[k, 0]
        i_chi += wz[k] * line_out[k, 1]
        i_torque += wz[k] * line_out[k, 2]
    return i_sin, i_chi, i_torque


@jit
def film_lines(kind, a, b, kappa, omk, eps_dot, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, stretch, tpos,
               lower0, lower1, m, h_lines, q_lines, integrals_out, masses_out):
    """Cell integrals and masses of every z-line; a single line for THIN and ECCENTRIC.

    ``h_lines``, ``q_lines`` (shape (n_lines, N m)) tabulate a user profile per
    line (TABULATED); for the built-in profiles they are empty with one row
    and ``integrals_out`` (n_lines, N, N_INTEGRALS), ``masses_out``
    (n_lines, N, N_MASSES) have one line. Both outputs are zero on entry.
    """
    for k in range(integrals_out.shape[0]):
        h_tab = h_lines[k]
        q_tab = q_lines[k]
        cell_integrals(kind, a, b, kappa, omk, eps_dot, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, m,
                       h_tab, q_tab, integrals_out[k])
        cell_masses(kind, a, b, kappa, omk, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, stretch, tpos, lower0,
                    lower1, m, h_tab, masses_out[k])


@jit
def modal_forces(kind, a, b, mu, kappa, omk, eps_dot, w_a, w_b, kappa_g, omk_g,
                 cpsi, spsi, vpsi, ppsi, wpsi, stretch, tpos, lower0, lower1, m, lam, coef, half_length,
                 end_weight):
    """f_eps, f_chi (N) and T_a (N m) over the whole length of a z-independent full film.

    For the thin and the eccentric gap; ``lam``, ``coef``, ``half_length`` and
    ``end_weight`` describe the z-modes of the half length 0 <= z <= L/2 in
    units of a (:func:`modal_film`), and the mid-plane symmetry doubles the
    result. Scaled as :func:`lubrication.reynolds_kernels.film_forces`, with dz = a dz_hat.
    """
    n = spsi.size // m
    empty = np.empty((1, 0))
    integrals = np.zeros((1, n, N_INTEGRALS))
    masses = np.zeros((1, n, N_MASSES))
    film_lines(kind, a, b, kappa, omk, eps_dot, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, stretch, tpos,
               lower0, lower1, m, empty, empty, integrals, masses)
    u_b = (b if kind == ECCENTRIC else a) * w_b
    i_sin, i_chi, i_torque = modal_film(integrals[0], masses[0], a * w_a, u_b, lam, coef, half_length,
                                        end_weight, np.empty((0, n)))
    length_factor = 2.0 * a  # both halves, dz = a dz_hat
    force = 12.0 * mu * a * a * length_factor
    return force * i_sin, force * i_chi, mu * a * a * length_factor * i_torque
