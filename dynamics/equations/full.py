r"""The full sixth-order dimensional model (2.1)-(2.4), in variables regular at eps = 0 and near contact.

Equations. In the frame of the plane, with i down the slope and k along its
normal, let r = eps (sin chi, cos chi) be the displacement B -> A (so that
e_eps = r/eps and e_chi = (cos chi, -sin chi)), F = f_eps e_eps + f_chi e_chi
the fluid force and m_r = m'_a. (2.1)-(2.2) are the two components of

    m_eff r'' = F + m_r g (sin alpha, -cos alpha) - m_r b Omega_b' (1, 0),

with the corrected effective mass m_eff = m_a + m''_a^2 / m_f (erratum 1);
(2.3) is (1/2) m_a a^2 Omega_a' = T_a. In the same components
eps^2 chi' = z x' - x z', eps sin chi = x and eps sin phi = z sin alpha + x cos alpha,
so (2.4) reads

    T_a + (M + m_b) b^2 Omega_b' + m_eff (z x'' - x z'') + m_r b x'' + m_r b Omega_b' z
        = M g b sin alpha + m_r g (z sin alpha + x cos alpha).

Eliminating r'' with the first equation (z F_x - x F_z = eps f_chi) leaves one
explicit equation for Omega_b',

    [(M + m_b) b^2 - (m_r b)^2 / m_eff] Omega_b'
        = M g b sin alpha - T_a - eps f_chi - (m_r b / m_eff)(F_x + m_r g sin alpha),

whose coefficient is positive because m_r^2 < m_a m_eff <= (M + m_b) m_eff.
The system is therefore explicit: state (r, r', Omega_a, Omega_b) is sixth
order, X_b (dX_b/dt = b Omega_b) a seventh, passive, one.

Variables. Cartesian r and r' are regular at eps = 0, where chi is not. Near
contact kappa = |r|/delta loses the relative precision of 1 - kappa, so the
position is carried as the stretched vector u = r / (delta zeta) with
zeta = sqrt(1 - kappa^2): |u| = kappa/zeta runs over [0, inf), kappa =
|u|/sqrt(1 + |u|^2) and 1 - kappa = 1/((1 + |u|^2)(1 + kappa)) without
cancellation, and

    u' = [r' + |u|^2 (e_eps . r') e_eps] / (delta zeta).

At eps = 0 exactly the direction e_eps is taken along r', which makes the
motion purely radial there (the resistance is isotropic at kappa = 0).
"""

from __future__ import annotations

import math

import numpy as np

from dynamics.equations.forces import ForceModel, evaluate
from lubrication._jit import jit

__all__ = [
    "STATE_NAMES",
    "force_response",
    "gravity_response",
    "initial_state",
    "jacobian",
    "observables",
    "params_array",
    "rhs",
]

STATE_NAMES = ("u_x", "u_z", "v_x", "v_z", "omega_a", "omega_b", "x_b")

# indices into the parameter array built by params_array
_A, _B, _LEN, _MU, _MEFF, _MRED, _MTOT, _MB, _MA, _G, _SIN, _COS = range(12)


def params_array(apparatus) -> np.ndarray:
    """The numbers the jitted right-hand side needs, from an :class:`~dynamics.apparatus.Apparatus`."""
    ap = apparatus
    return np.array([ap.a, ap.b, ap.length, ap.mu, ap.m_eff, ap.m_a_reduced, ap.M, ap.m_b, ap.m_a,
                     ap.g, math.sin(ap.alpha), math.cos(ap.alpha)])


@jit(inline="always")
def _geometry(y, delta):
    """kappa, 1 - kappa, zeta, eps, |u| and the unit vector e_eps from the state."""
    ux, uz, vx, vz = y[0], y[1], y[2], y[3]
    big_u = math.hypot(ux, uz)
    one_plus = 1.0 + big_u * big_u
    zeta = 1.0 / math.sqrt(one_plus)
    kappa = big_u * zeta
    omk = 1.0 / (one_plus * (1.0 + kappa))
    if big_u > 0.0:
        ex, ez = ux / big_u, uz / big_u
    else:
        speed = math.hypot(vx, vz)
        ex, ez = (vx / speed, vz / speed) if speed > 0.0 else (0.0, 1.0)
    return kappa, omk, zeta, kappa * delta, big_u, ex, ez


@jit(inline="always")
def force_response(p, eps, ex, ez, f_eps, f_chi, t_a):
    """(x'', z'', Omega_a', Omega_b') due to a force (f_eps, f_chi) on A and a torque t_a about A.

    The part of (2.1)-(2.4) linear in the forces (module docstring), without
    gravity: the fluid's, or a contact force acting between the cylinders.
    """
    a, b = p[_A], p[_B]
    cx, cz = ez, -ex  # e_chi
    fx = f_eps * ex + f_chi * cx
    fz = f_eps * ez + f_chi * cz
    m_eff, m_r = p[_MEFF], p[_MRED]
    inertia_b = (p[_MTOT] + p[_MB]) * b * b - (m_r * b) ** 2 / m_eff
    omega_b_dot = (-t_a - eps * f_chi - (m_r * b / m_eff) * fx) / inertia_b
    return (fx - m_r * b * omega_b_dot) / m_eff, fz / m_eff, t_a / (0.5 * p[_MA] * a * a), omega_b_dot


@jit(inline="always")
def gravity_response(p):
    """(x'', z'', Omega_a', Omega_b') due to gravity alone, from the same equations."""
    b, m_eff, m_r = p[_B], p[_MEFF], p[_MRED]
    gs, gc = p[_G] * p[_SIN], p[_G] * p[_COS]
    inertia_b = (p[_MTOT] + p[_MB]) * b * b - (m_r * b) ** 2 / m_eff
    omega_b_dot = (p[_MTOT] * gs * b - (m_r * b / m_eff) * m_r * gs) / inertia_b
    return (m_r * gs - m_r * b * omega_b_dot) / m_eff, -m_r * gc / m_eff, 0.0, omega_b_dot


@jit
def rhs(t, y, p, profile, sommerfeld, rule, points_per_cell, exact, cavitation):
    """dy/dt of the full model; ``p`` from :func:`params_array`, the model from a ForceModel."""
    a, b = p[_A], p[_B]
    delta = b - a
    kappa, omk, zeta, eps, big_u, ex, ez = _geometry(y, delta)
    vx, vz, omega_a, omega_b = y[2], y[3], y[4], y[5]
    eps_dot = ex * vx + ez * vz
    chi_dot = (ez * vx - ex * vz) / eps if eps > 0.0 else 0.0
    f_eps, f_chi, t_a = evaluate(profile, sommerfeld, rule, points_per_cell, exact, cavitation, a, b, p[_MU],
                                 p[_LEN], kappa, omk, eps_dot, omega_a - chi_dot, omega_b - chi_dot)
    fluid = force_response(p, eps, ex, ez, f_eps, f_chi, t_a)
    gravity = gravity_response(p)
    dy = np.empty(7)
    scale = 1.0 / (delta * zeta)
    stretch = big_u * big_u * eps_dot
    dy[0] = (vx + stretch * ex) * scale
    dy[1] = (vz + stretch * ez) * scale
    for i in range(4):
        dy[2 + i] = fluid[i] + gravity[i]
    dy[6] = b * omega_b
    return dy


@jit
def jacobian(t, y, p, profile, sommerfeld, rule, points_per_cell, exact, cavitation, typical):
    """d(rhs)/dy by central differences, steps eps^(1/3) max(|y_j|, typical_j).

    Central differences carry an O(h^2) truncation and O(eps/h) rounding error,
    balanced at h ~ eps^(1/3) |y|: about 1e-11 relative, far below what the
    implicit integrator's Newton iteration needs.
    """
    n = y.size
    jac = np.empty((n, n))
    yp = y.copy()
    for j in range(n):
        h = 6.0554544523933395e-06 * max(abs(y[j]), typical[j])  # eps^(1/3)
        yp[j] = y[j] + h
        up = rhs(t, yp, p, profile, sommerfeld, rule, points_per_cell, exact, cavitation)
        yp[j] = y[j] - h
        down = rhs(t, yp, p, profile, sommerfeld, rule, points_per_cell, exact, cavitation)
        yp[j] = y[j]
        for i in range(n):
            jac[i, j] = (up[i] - down[i]) / (2.0 * h)
    return jac


def initial_state(apparatus, kappa, phi, kappa_dot, phi_dot, omega_a, omega_b) -> np.ndarray:
    """State vector from (kappa, phi, kappa', phi', Omega_a, Omega_b) in SI units.

    phi = alpha + chi is measured from the upward vertical; chi' = phi'.
    """
    delta = apparatus.delta
    chi = phi - apparatus.alpha
    e_eps = np.array([math.sin(chi), math.cos(chi)])
    e_chi = np.array([math.cos(chi), -math.sin(chi)])
    zeta = math.sqrt((1.0 - kappa) * (1.0 + kappa))
    u = (kappa / zeta) * e_eps
    v = delta * (kappa_dot * e_eps + kappa * phi_dot * e_chi)
    return np.array([u[0], u[1], v[0], v[1], omega_a, omega_b, 0.0])


def typical_scales(apparatus) -> np.ndarray:
    """A size for each state component: the floor of the integrator's atol and of FD steps."""
    tau = apparatus.tau
    return np.array([1.0, 1.0, apparatus.delta / tau, apparatus.delta / tau, 1.0 / tau, 1.0 / tau,
                     apparatus.b])


def observables(apparatus, y: np.ndarray) -> dict[str, np.ndarray]:
    """kappa, 1 - kappa, eps, chi, phi, Omega_a, Omega_b, X_b from states y (shape (7, n)).

    chi is unwrapped to be continuous from sample to sample.
    """
    big_u = np.hypot(y[0], y[1])
    one_plus = 1.0 + big_u**2
    kappa = big_u / np.sqrt(one_plus)
    chi = np.unwrap(np.arctan2(y[0], y[1]))
    return {
        "kappa": kappa,
        "one_minus_kappa": 1.0 / (one_plus * (1.0 + kappa)),
        "eps": kappa * apparatus.delta,
        "chi": chi,
        "phi": chi + apparatus.alpha,
        "omega_a": y[4],
        "omega_b": y[5],
        "x_b": y[6],
    }


def model_arguments(force_model: ForceModel) -> tuple:
    """The trailing arguments of :func:`rhs` and :func:`jacobian` that select the force model."""
    return (force_model.profile, force_model.sommerfeld, force_model.rule,
            force_model.points_per_cell, force_model.exact, force_model.cavitation)
