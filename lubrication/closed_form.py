"""Leading-order lubrication forces (2.5)-(2.7) in closed form.

With the thin gap h = delta (1 - kappa cos theta) the Reynolds equation
integrates exactly with the integrals (B8)-(B9); per unit length, with
m''_a nu = pi a^2 mu,

    f_eps = -12 pi mu a^3 eps' / (delta^3 zeta^3)                          (2.5)
    f_chi =  12 pi mu a^3 kappa (W_a + W_b) / (delta^2 (2 + kappa^2) zeta)  (2.6)
    T_a   =   4 pi mu a^3 [(1 - kappa^2) W_b - (1 + 2 kappa^2) W_a]
              / (delta (2 + kappa^2) zeta)                                  (2.7)

where zeta = sqrt(1 - kappa^2), W_a = Omega_a - chi', W_b = Omega_b - chi'.
(2.7) is written in the form that follows from (B15); the printed text is
ambiguous there.
"""

from __future__ import annotations

import math

from numerics.jit import jit

from .geometry import Annulus, Fluid, FluidForces, Motion
from .spec import ForceModelSpec

__all__ = ["closed_form_forces", "lubrication_forces", "closed_form_resistance"]


@jit
def closed_form_resistance(a, delta, mu, kappa, omk):
    """The five coefficients of (2.5)-(2.7) per unit length, in RESISTANCE_NAMES order.

    R_eps (N s/m^2), R_chi_a, R_t_a, R_chi_b, R_t_b (N s/m, N s, N s/m, N s): f_eps = R_eps eps',
    f_chi = R_chi_a W_a + R_chi_b W_b, T_a = R_t_a W_a + R_t_b W_b. ``omk`` is 1 - kappa, kept
    for precision near contact.
    """
    zeta = math.sqrt(omk * (1.0 + kappa))
    c = 4.0 * math.pi * mu * a**3
    k2 = kappa * kappa
    r_chi = 3.0 * c * kappa / (delta**2 * (2.0 + k2) * zeta)
    torque = c / (delta * (2.0 + k2) * zeta)
    return (-3.0 * c / (delta**3 * zeta**3), r_chi, -(1.0 + 2.0 * k2) * torque, r_chi,
            omk * (1.0 + kappa) * torque)


@jit
def lubrication_forces(a, delta, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """(2.5)-(2.7) for the whole length; ``omk`` is 1 - kappa, kept for precision near contact.

    Returns
    -------
    f_eps, f_chi, T_a : float
        N, N, N m.
    """
    r = closed_form_resistance(a, delta, mu, kappa, omk)
    return (length * r[0] * eps_dot, length * (r[1] * w_a + r[3] * w_b), length * (r[2] * w_a + r[4] * w_b))


def closed_form_forces(annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
    """Closed-form lubrication force and torque (2.5)-(2.7) on the inner cylinder."""
    f = lubrication_forces(annulus.a, annulus.delta, fluid.mu, annulus.length,
                           annulus.kappa, annulus.one_minus_kappa,
                           motion.eps_dot, motion.w_a, motion.w_b)
    return FluidForces(*f, model="closed-form")


#: The model as the registry knows it (:mod:`lubrication.registry`).
MODEL = ForceModelSpec(
    "closed-form", "the lubrication forms (2.5)-(2.7) of the paper: leading order in delta/a", closed_form_forces,
    resistance=closed_form_resistance)
