"""numba kernels of the Reynolds solver.

Only float64 arrays, ints and floats cross this boundary; checking inputs and
choosing the kernel is the job of :mod:`lubrication.reynolds`.

The grid. The gap angle theta is parametrised by psi, uniform on (-pi, pi],
through the Sommerfeld substitution with a grid parameter kappa_g,

    1 - kappa_g cos(theta) = (1 - kappa_g^2) / (1 + kappa_g cos(psi)),

so that, with D = 1 + kappa_g cos(psi) and zeta_g = sqrt(1 - kappa_g^2),

    cos(theta) = (kappa_g + cos psi) / D,   sin(theta) = zeta_g sin(psi) / D,
    1 - cos(theta) = (1 - kappa_g)(1 - cos psi) / D,   dtheta/dpsi = zeta_g / D.

kappa_g = 0 is the uniform theta grid; kappa_g = kappa clusters the points at the
narrowest gap so that every thin-gap integrand becomes a trigonometric
polynomial in psi. Everything is algebraic in cos(psi), sin(psi), 1 - cos(psi)
and 1 + cos(psi), which are tabulated once per grid: no transcendental function
is evaluated per solve, and no difference of nearly equal numbers is formed as
kappa_g -> 1.

The discretisation. Each of the N cells [psi_j, psi_j+1] carries m Gauss-Legendre
points. In one dimension the flux q = h (U_a + U_b)/2 - h^3 p'/(12 mu a) obeys
dq/dtheta = -dQ/dtheta, where Q(theta) is the antiderivative of the squeeze
source (a dh/dt for the thin gap), so q = qhat - Q(theta) with one constant
qhat. Integrating p' = 12 mu a phi' over cell j gives the exact finite-volume
relation between nodal pressures,

    phi_{j+1} - phi_j = (U/2) A_j + B_j - qhat G_j,
    A_j = int h^-2,  G_j = int h^-3,  B_j = int Q h^-3   (over cell j),

U = U_a + U_b: a vertex-centred scheme whose face conductances 1/G_j are the
exact cell integrals rather than h^3 sampled at a point. Periodicity fixes qhat.
Nodal pressures then carry only the cell quadrature error, O(dpsi^(2m)); the
force and torque are integrals over the whole period, for which the composite
rule converges spectrally (exactly, for a trigonometric polynomial of low enough
degree). Cavitation keeps the same cells and conductances and changes only how
the nodal pressures are found.

Forces, per unit length, by parts (p is periodic), (B13)-(B15):

    f_eps = -a oint p cos = a oint p' sin = 12 mu a^2 oint phi' sin(theta)
    f_chi = -a oint p sin = -a oint p' cos = 12 mu a^2 oint phi' omega
    T_a   = a^2 mu oint [(U_b - U_a)/h - 6 phi' h]

where omega is -cos(theta) or 1 - cos(theta): they differ by a constant and
oint phi' = 0. For kappa >= 1/2 the weight 1 - cos(theta), which vanishes where
h is smallest, removes a cancellation of relative size 1 - kappa^2; for
kappa < 1/2, -cos(theta) removes one of relative size kappa (the rotation
pressure itself is O(kappa)).
"""

from __future__ import annotations

import math

import numpy as np

from numerics.jit import jit

# Gap profiles known to the kernel; TABULATED takes h and Q from arrays.
THIN, ECCENTRIC, TABULATED = 0, 1, 2


@jit(inline="always")
def eccentric_gap(a, b, eps, omk, s, v, eps_dot):
    """Exact gap between the circles along the ray from A, and its squeeze flux.

    h = sqrt(b^2 - eps^2 sin^2) - eps cos - a, written without cancellation as
    delta (1 - kappa) + eps (1 - cos) - eps^2 sin^2 / (sqrt(b^2 - eps^2 sin^2) + b).
    Mass in the sector is the area int (a h + h^2/2) dtheta, so the squeeze
    source is d/dt (r^2/2) with r = a + h; its antiderivative in theta is
    Q = eps' (eps sin cos - sin sqrt(b^2 - eps^2 sin^2)), periodic, which makes
    mass conservation exact.
    """
    root = math.sqrt(b * b - (eps * s) ** 2)
    h = (b - a) * omk + eps * v - (eps * s) ** 2 / (root + b)
    q = eps_dot * s * (eps * (1.0 - v) - root)
    return h, q


# Columns of the per-cell integrals (dtheta over one cell): h^-1, h^-2, h^-3, Q h^-3, Q h^-2,
# and the sin(theta)- and omega-weighted h^-2, h^-3, Q h^-3 that the forces need.
H1, H2, H3, QH3, QH2, SH2, SH3, SQH3, OH2, OH3, OQH3 = range(11)
N_INTEGRALS = 11


@jit
def cell_integrals(kind, a, b, kappa, omk, eps_dot, kappa_g, omk_g,
                   cpsi, spsi, vpsi, ppsi, wpsi, m, h_tab, q_tab, out):
    """Add to ``out[j]`` the integrals over cell j listed by the column constants above.

    With ``out`` of one row, every cell adds to that row: the whole-period
    integrals, which is all the full film needs, without storing the cells.

    Parameters
    ----------
    kind : int
        THIN (h = delta (1 - kappa cos)), ECCENTRIC or TABULATED.
    a, b : float
        Radii (m).
    kappa, omk : float
        Eccentricity ratio and 1 - kappa; for TABULATED, the profile's own
        (h_max - h_min)/(h_max + h_min), which only chooses the f_chi weight omega.
    eps_dot : float
        Rate of change of the centre distance (m/s).
    kappa_g, omk_g : float
        Grid parameter and 1 - kappa_g.
    cpsi, spsi, vpsi, ppsi, wpsi : ndarray, shape (N*m,)
        cos, sin, 1 - cos, 1 + cos of psi and the quadrature weights at the points.
    m : int
        Points per cell.
    h_tab, q_tab : ndarray, shape (N*m,) or (0,)
        Gap and squeeze flux at the points, for TABULATED.
    out : ndarray, shape (N, N_INTEGRALS) or (1, N_INTEGRALS)
        Zero on entry.
    """
    n_cells = spsi.size // m
    zeta_g = math.sqrt(omk_g * (1.0 + kappa_g))
    delta = b - a
    inv_delta = 1.0 / delta
    eps = kappa * delta
    vers_weight = kappa >= 0.5
    per_cell = out.shape[0] == n_cells
    k = 0
    for j in range(n_cells):
        s1 = s2 = s3 = sq3 = sq2 = 0.0
        sin2 = sin3 = sinq3 = 0.0
        om2 = om3 = omq3 = 0.0
        for _ in range(m):
            d = omk_g + kappa_g * ppsi[k]
            if kind == THIN:
                # h = delta x / d: one division gives both 1/d and 1/h
                x = omk * d + kappa * omk_g * vpsi[k]
                inv = 1.0 / (d * x)
                r = x * inv
                r1 = d * d * inv * inv_delta
                s = zeta_g * spsi[k] * r
                v = omk_g * vpsi[k] * r
                q = -a * eps_dot * s
            else:
                r = 1.0 / d
                s = zeta_g * spsi[k] * r
                v = omk_g * vpsi[k] * r
                if kind == ECCENTRIC:
                    h, q = eccentric_gap(a, b, eps, omk, s, v, eps_dot)
                else:
                    h = h_tab[k]
                    q = q_tab[k]
                r1 = 1.0 / h
            om = v if vers_weight else -(kappa_g + cpsi[k]) * r
            w1 = wpsi[k] * zeta_g * r * r1
            w2 = w1 * r1
            w3 = w2 * r1
            s1 += w1
            s2 += w2
            s3 += w3
            sq3 += q * w3
            sq2 += q * w2
            sin2 += s * w2
            sin3 += s * w3
            sinq3 += s * q * w3
            om2 += om * w2
            om3 += om * w3
            omq3 += om * q * w3
            k += 1
        row = out[j] if per_cell else out[0]
        row[H1] += s1
        row[H2] += s2
        row[H3] += s3
        row[QH3] += sq3
        row[QH2] += sq2
        row[SH2] += sin2
        row[SH3] += sin3
        row[SQH3] += sinq3
        row[OH2] += om2
        row[OH3] += om3
        row[OQH3] += omq3


@jit
def full_film(integrals, u_a, u_b, phi_out):
    """The full-film solution from the cell integrals; return oint phi' sin, oint phi' omega, torque sum.

    Parameters
    ----------
    integrals : ndarray, shape (N, N_INTEGRALS) or (1, N_INTEGRALS)
        From :func:`cell_integrals`; per cell when nodal pressures are wanted.
    u_a, u_b : float
        Surface speeds of the inner and outer wall in the frame of the line of centres (m/s).
    phi_out : ndarray, shape (N,) or (0,)
        When of length N, receives phi = p/(12 mu a) at the nodes psi_j, up to a constant.

    Returns
    -------
    i_sin, i_chi, i_torque : float
        oint phi' sin(theta), oint phi' omega, and
        oint [(u_b - u_a)/h - 6 phi' h], all dtheta.
    """
    total = np.zeros(N_INTEGRALS)
    for j in range(integrals.shape[0]):
        for c in range(N_INTEGRALS):
            total[c] += integrals[j, c]
    half_u = 0.5 * (u_a + u_b)
    # periodicity of phi: sum over cells of (U/2) A_j + B_j - qhat G_j = 0
    qhat = (half_u * total[H2] + total[QH3]) / total[H3]
    i_sin = half_u * total[SH2] + total[SQH3] - qhat * total[SH3]
    i_chi = half_u * total[OH2] + total[OQH3] - qhat * total[OH3]
    i_torque = (u_b - u_a) * total[H1] - 6.0 * (half_u * total[H1] + total[QH2] - qhat * total[H2])
    if phi_out.size == integrals.shape[0]:
        phi = 0.0
        for j in range(integrals.shape[0]):
            phi_out[j] = phi
            phi += half_u * integrals[j, H2] + integrals[j, QH3] - qhat * integrals[j, H3]
    return i_sin, i_chi, i_torque


@jit
def film_forces(kind, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, kappa_g, omk_g,
                cpsi, spsi, vpsi, ppsi, wpsi, m, h_tab, q_tab, cos_c, sin_c, phi_out):
    """f_eps, f_chi (N) and T_a (N m) of the full film over the length.

    ``w_a``, ``w_b`` are the rotation rates relative to the line of centres; the
    walls move at a w_a and a w_b for the thin (leading-order) and tabulated
    gaps, at a w_a and b w_b for the exact eccentric gap. ``cos_c``, ``sin_c``
    rotate the force from a grid centred at angle c back to the line of centres.
    """
    u_b = (b if kind == ECCENTRIC else a) * w_b
    integrals = np.zeros((phi_out.size if phi_out.size else 1, N_INTEGRALS))
    cell_integrals(kind, a, b, kappa, omk, eps_dot, kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, m,
                   h_tab, q_tab, integrals)
    i_sin, i_chi, i_torque = full_film(integrals, a * w_a, u_b, phi_out)
    scale = 12.0 * mu * a * a * length
    f_x = scale * i_sin
    f_y = scale * i_chi
    return cos_c * f_x - sin_c * f_y, sin_c * f_x + cos_c * f_y, mu * a * a * length * i_torque
