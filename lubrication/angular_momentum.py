r"""The fluid's angular momentum in the gap, as the equations of motion need it (``fluid_spin = "eccentric"``).

The quasi-steady Stokes flow carries, about B and in the frame moving with B
without turning (:func:`lubrication.stokes.fluid_angular_momentum`),

    L = rho L I_B chi' + J_a (Omega_a - chi') + J_b (Omega_b - chi'),

I_B = pi (b^4 - a^4)/2 - pi a^2 eps^2 the polar moment of the annulus' area
about B, and J_w = lambda_w m_f r_w^2 / 2 (r_a = a, r_b = b) the angular
momentum of wall w's rotation relative to the line of centres, a share
lambda_w of the concentric Couette flow's. lambda_w = 1 - mu_w kappa^2: even in
kappa, 1 in the concentric annulus, and, as the gap closes, small or negative
(the pinch blocks the circulation the walls drive). The shares come from a
table of finite-element solves (:mod:`lubrication.spin_table`), interpolated by
cubic Hermite polynomials in kappa (the table's slopes; continuous with its
derivative, which the equations need) and linearly in delta/a; beyond the
nodes in delta/a they are held at the nearest edge, beyond kappa = 0.999
continued along the tangent.
"""

from __future__ import annotations

from numerics.jit import jit

from .spin_table import DELTA_NODES, KAPPA_NODES, MU, SLOPE
from .tables import cell

__all__ = ["spin_shares"]


@jit(inline="always")
def _hermite(kappa, i, j, column):
    """The cubic Hermite interpolant of MU[:, j, column] on [KAPPA_NODES[i], KAPPA_NODES[i + 1]], and its slope."""
    k0, k1 = KAPPA_NODES[i], KAPPA_NODES[i + 1]
    h = k1 - k0
    t = (kappa - k0) / h
    y0, y1 = MU[i, j, column], MU[i + 1, j, column]
    s0, s1 = SLOPE[i, j, column] * h, SLOPE[i + 1, j, column] * h
    t2, t3 = t * t, t * t * t
    value = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * s0 + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * s1
    slope = ((6 * t2 - 6 * t) * y0 + (3 * t2 - 4 * t + 1) * s0 + (-6 * t2 + 6 * t) * y1 + (3 * t2 - 2 * t) * s1) / h
    return value, slope


@jit
def spin_shares(kappa, delta_over_a):
    """(mu_a, mu_b, dmu_a/dkappa, dmu_b/dkappa) at (kappa, delta/a): lambda_w = 1 - mu_w kappa^2.

    Beyond the last node (kappa > 0.999) continued along its tangent, which keeps mu and its slope continuous.
    """
    nk, nd = KAPPA_NODES.size, DELTA_NODES.size
    edge = KAPPA_NODES[nk - 1]
    k = min(kappa, edge)
    d = min(max(delta_over_a, DELTA_NODES[0]), DELTA_NODES[nd - 1])
    i, j = cell(KAPPA_NODES, k), cell(DELTA_NODES, d)
    w = (d - DELTA_NODES[j]) / (DELTA_NODES[j + 1] - DELTA_NODES[j])
    out = [0.0, 0.0, 0.0, 0.0]
    for column in range(2):
        lo = _hermite(k, i, j, column)
        hi = _hermite(k, i, j + 1, column)
        slope = (1.0 - w) * lo[1] + w * hi[1]
        out[column] = (1.0 - w) * lo[0] + w * hi[0] + slope * (kappa - k)
        out[2 + column] = slope
    return out[0], out[1], out[2], out[3]
