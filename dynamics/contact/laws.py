r"""Contact laws beyond section 5: velocity-weakening friction and a compliant asperity contact.

Section 5 and Appendix C close the contact with a rigid wall of asperities
(the gap cannot fall below sigma) and Coulomb friction with equal static and
kinetic coefficients. This module states two alternatives. The full equations
(2.1)-(2.4) take them (:mod:`dynamics.contact.rough_full`); the reduced model
(2.11) keeps section 5's.

Friction: Coulomb and Stribeck
------------------------------
The friction between the cylinders acts along e_chi at the contact, against
the slip s = eps chi' + a Omega_a - (a + eps) Omega_b (m/s), the speed of A's
surface past B's at the contact point (:mod:`dynamics.contact.full`). Its
coefficient is the physical mu = tan(psi_hat) = (delta/a) tan(psi) (C2). A
velocity-weakening (Stribeck-type) law lets the coefficient fall from a static
value mu_s at s = 0 to the kinetic mu_k while sliding,

    mu(s) = mu_k + (mu_s - mu_k) exp(-(s/v_S)^2),        mu_s >= mu_k,

with v_S the Stribeck velocity (m/s). Coulomb is mu_s = mu_k. With a hard
contact the surfaces stick while the friction that holds them is inside
|F| <= mu_s N, and slide with F = -sgn(s) mu(|s|) N; mu(0) = mu_s, so the
kinetic friction meets the static bound at the switch.

Compliant asperity contact (Greenwood-Williamson type)
------------------------------------------------------
Instead of a wall, the asperities yield. Let

    d = eps*(theta_a, theta_b) - eps          (m)

be the separation of the surfaces above the mean plane of the asperity
summits, which sits where the hard contact puts its wall (the minimum gap
sigma of :mod:`dynamics.contact.roughness`): d > 0 apart, d < 0 pressed in.
Summit heights above that plane are distributed with a density phi(z/l)/l
of scale l; each summit pressed in by w carries a Hertzian load ~ w^(3/2).
Summed over the summits (Greenwood & Williamson 1966) the load over the
whole length is

    P(d) = W Pi(d/l),     Pi(x) = F(x)/F(0),     F(x) = int_0^inf u^(3/2) phi(x + u) du,

in units of the reduced weight W = m'_a g (N), the normal reaction of section
5's steady contact (5.1). Two height distributions:

* exponential, phi(z) = e^-z (the upper tail GW used): Pi(x) = e^-x exactly;
* Gaussian, phi the standard normal density: F is evaluated by the
  trapezoidal rule in u = t^2, spectrally accurate for this smooth, even
  integrand (:func:`gw_integral`).

The stiffness k = -dP/dd at d = 0 (N/m) sets the height scale:
l = c W/k with c = -Pi'(0) = (3/2) F_1/2(0)/F_3/2(0) (1 for the exponential,
1.4340 for the Gaussian). As k grows, l -> 0 and P(d) becomes the wall: the
compliant contact tends to the hard one (measured in tests/test_rough_full.py).
So that contacts dissipate, a damping force acts with the elastic one,

    N = P(d) - c_d(d) d',     c_d = 2 zeta_d sqrt(m_eff P(d)/l),

zeta_d the damping ratio of the contact's radial oscillation (1: critical) at
its local stiffness P/l (exact for the exponential law; the scale of it for the
Gaussian), m_eff = m_a + m''_a^2/m_f the inner cylinder's mass in (2.1)-(2.2).
The damping vanishes with the load, so the force is smooth through the start
and end of a contact: no event, no impact law, one smooth system that the
integrator can follow through brief contacts. Its power is -c_d d'^2 <= 0.
The elastic part derives from the potential

    U(d) = int_d^inf P = W l Psi(d/l),   Psi(x) = F_5/2(x) / (5/2 F_3/2(0))

(e^-x for the exponential law), so that the mechanical energy plus U falls at
the rate of the fluid's, the friction's and the damping's dissipation.

N acts along the gradient of the constraint G = eps* - eps of the hard
contact (its e_eps, e_chi components and its torque on the inner cylinder:
:mod:`dynamics.contact.rough_full`). The friction is regularised, because a
smooth system cannot stick:

    F = -mu(|s|) P(d) s / sqrt(s^2 + v_e^2),

v_e the slip velocity below which it fades (m/s); F s <= 0, and F tends to the
hard contact's sliding friction where |s| >> v_e. It is bounded by the elastic
load P, not by N, which the damping can make negative while the surfaces part.

Units: d, l in m; W, P, N, F in N; k in N/m; c_d in N s/m; v_S, v_e in m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubrication.geometry import check_range
from numerics.jit import jit

__all__ = [
    "COMPLIANT",
    "CONTACT_LAWS",
    "FRICTION_LAWS",
    "HEIGHTS",
    "Compliance",
    "Stribeck",
    "friction_coefficient",
    "gw_integral",
    "gw_load",
    "gw_potential",
    "height_scale",
]

#: The name of the compliant contact's phase in trajectories (one smooth phase).
COMPLIANT = "compliant"
CONTACT_LAWS = ("hard", "compliant")
FRICTION_LAWS = ("coulomb", "stribeck")
HEIGHTS = ("exponential", "gaussian")

_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)


@dataclass(frozen=True)
class Stribeck:
    """Velocity-weakening friction: mu(s) = mu_k + (mu_s - mu_k) exp(-(s/v_S)^2) (module docstring).

    Parameters
    ----------
    psi_static : float
        Scaled static friction angle (rad), tan(psi_s) = (a/delta) mu_s (C2), in
        [0, pi/2); at least the kinetic psi of the contact (checked where both meet).
    velocity : float
        Stribeck velocity v_S (m/s), in (0, inf).
    """

    psi_static: float
    velocity: float

    def __post_init__(self):
        object.__setattr__(self, "psi_static", check_range("psi_static", self.psi_static, 0.0, 0.5 * math.pi,
                                                           unit="rad"))
        object.__setattr__(self, "velocity", check_range("stribeck_velocity", self.velocity, 0.0, math.inf,
                                                         low_open=True, unit="m/s"))


@dataclass(frozen=True)
class Compliance:
    """A compliant asperity contact (module docstring), for the full equations.

    Parameters
    ----------
    heights : {"exponential", "gaussian"}
        Distribution of the summit heights.
    stiffness : float or None
        k = -dP/dd where the summits' mean plane touches (N/m), in (0, inf).
        None: 1000 m'_a g / sigma_mean, the summits yield by a thousandth of the
        mean minimum gap under the weight.
    damping_ratio : float
        zeta_d, in [0, 100]: 1 damps the contact's radial oscillation critically.
    slip_velocity : float
        v_e (m/s), in (0, inf): the slip below which the friction fades smoothly.
    """

    heights: str = "exponential"
    stiffness: float | None = None
    damping_ratio: float = 1.0
    slip_velocity: float = 1e-5

    def __post_init__(self):
        if self.heights not in HEIGHTS:
            msg = f"heights must be one of {', '.join(map(repr, HEIGHTS))}, got {self.heights!r}"
            raise ValueError(msg)
        if self.stiffness is not None:
            object.__setattr__(self, "stiffness", check_range("stiffness", self.stiffness, 0.0, math.inf,
                                                              low_open=True, unit="N/m"))
        object.__setattr__(self, "damping_ratio", check_range("damping_ratio", self.damping_ratio, 0.0, 100.0,
                                                                 high_open=False))
        object.__setattr__(self, "slip_velocity", check_range("slip_velocity", self.slip_velocity, 0.0, math.inf,
                                                              low_open=True, unit="m/s"))

    def resolved_stiffness(self, weight: float, sigma_mean: float) -> float:
        """k in N/m: the given stiffness, or 1000 ``weight``/``sigma_mean`` (N, m)."""
        return 1000.0 * weight / sigma_mean if self.stiffness is None else self.stiffness


# -- the GW integrals -------------------------------------------------------------------

@jit
def gw_integral(x, power, gaussian):
    """F(x) = int_0^inf u^power phi(x + u) du for power = 1/2, 3/2 or 5/2 (any power > -1).

    ``gaussian``: phi is the standard normal density, integrated by the
    trapezoidal rule in u = t^2 (F = int_0^inf 2 t^(2 power + 1) phi(x + t^2) dt,
    even in t, so the rule converges faster than any power of its step); the
    step is a sixth of the integrand's width, 1/sqrt(1 + 4 max(-x, 0) + 2 max(x, 0)),
    and the rule runs nine widths past x + t^2 = 9, where phi < 1e-17: 4e-14
    relative to a rule of 400,000 nodes over x in [-40, 40] (72 nodes at x = 0).
    Otherwise phi(z) = e^-z and F = Gamma(power + 1) e^-x.
    """
    if not gaussian:
        return math.gamma(power + 1.0) * math.exp(-x)
    width = 1.0 / math.sqrt(1.0 + 4.0 * max(-x, 0.0) + 2.0 * max(x, 0.0))
    step = width / 6.0
    end = math.sqrt(max(9.0 - x, 0.0)) + 9.0 * width
    n = int(math.ceil(end / step))
    total = 0.0
    exponent = 2.0 * power + 1.0
    for i in range(1, n + 1):
        t = i * step
        z = x + t * t
        total += 2.0 * t**exponent * math.exp(-0.5 * z * z)
    # the t = 0 node carries 2 t^(2 power + 1) = 0 for power > -1/2, and 2 phi(x) (half of it) at -1/2
    if exponent == 0.0:
        total += math.exp(-0.5 * x * x)
    return total * step * _INV_SQRT_2PI


@jit
def gw_load(x, gaussian, norm):
    """Pi(x) = F_3/2(x)/F_3/2(0), ``norm`` = F_3/2(0) (Gamma(5/2) = 1.3293 exponential, 0.4300 Gaussian)."""
    if not gaussian:
        return math.exp(-x)
    return gw_integral(x, 1.5, True) / norm


def gw_potential(x, heights: str) -> np.ndarray:
    """Psi(x) = int_x^inf Pi = F_5/2(x) / (5/2 F_3/2(0)), the elastic energy over W l."""
    gaussian = heights == "gaussian"
    x = np.asarray(x, dtype=float)
    norm = float(gw_integral(0.0, 1.5, gaussian))
    flat = np.array([gw_integral(float(v), 2.5, gaussian) for v in x.ravel()]) / (2.5 * norm)
    return flat.reshape(x.shape)


def height_scale(heights: str, weight: float, stiffness: float) -> tuple[float, float]:
    """(l, F_3/2(0)): the summit height scale l = c W/k (m) and the load's normaliser (module docstring).

    c = -Pi'(0) = (3/2) F_1/2(0)/F_3/2(0): 1 for the exponential law, 1.4340 for the Gaussian.
    """
    gaussian = heights == "gaussian"
    norm = float(gw_integral(0.0, 1.5, gaussian))
    c = 1.5 * float(gw_integral(0.0, 0.5, gaussian)) / norm
    return c * weight / stiffness, norm


# -- friction ---------------------------------------------------------------------------

@jit
def friction_coefficient(slip, mu_kinetic, mu_static, velocity):
    """mu(|slip|) = mu_k + (mu_s - mu_k) exp(-(slip/v_S)^2); mu_k exactly for Coulomb (mu_s = mu_k)."""
    ratio = slip / velocity
    return mu_kinetic + (mu_static - mu_kinetic) * math.exp(-ratio * ratio)
