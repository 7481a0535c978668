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

Near contact the Cartesian velocity is a poor variable for an implicit
integrator: the squeeze force -R e_eps . r' (R ~ zeta^-3) is then bilinear in
the direction of u and in r', whose tangential part eps chi' dwarfs the radial
one (~ zeta^3), so the simplified Newton iteration of Radau IIA converges only
for steps in which the line of centres hardly turns (measured: 10-30 times the
steps of BDF from 1 - kappa = 1e-4, no progress at 1e-7). A free run therefore
carries, once |u| exceeds :data:`POLAR_ABOVE`, the velocity in the frame of the
line of centres (``polar_rhs`` (:func:`model_functions`)): q_r = d|u|/dt = kappa'/zeta^3 and
q_t = |u| chi', in which the squeeze force is linear,

    eps' = delta q_r / s^3,   eps chi' = delta q_t / s,   s = sqrt(1 + |u|^2),
    q_r' = s^3 a_r + s^2 q_t^2 / |u| + 3 |u| q_r^2 / s^2,
    q_t' = s a_t + (q_r q_t / |u|)(1 - 2/s^2),

a_r, a_t the components of r''/delta along e_eps and e_chi (from differentiating
kappa = |u|/s twice in polar form). These are singular at |u| = 0, so the run
returns to the Cartesian velocity below :data:`CARTESIAN_BELOW`; both switches
are events located on the dense output (:mod:`numerics.hybrid`).
"""

from __future__ import annotations

import functools
import math
from collections import namedtuple

import numpy as np

from lubrication.angular_momentum import spin_shares
from lubrication.kernels import KernelModel
from numerics.hybrid import Phase
from numerics.jit import jit, specialise
from numerics.packed import pack, part, parts

__all__ = [
    "CARTESIAN_BELOW",
    "CARTESIAN_EVENT_NAMES",
    "DEFAULT_FLUID_SPIN",
    "DEFAULT_FRAME_TERMS",
    "EVENT_NAMES",
    "FLUID_SPIN",
    "FRAME_TERMS",
    "EVENTS",
    "FreeFull",
    "MODEL",
    "PARAMETERS",
    "POLAR_ABOVE",
    "POLAR_EVENT_NAMES",
    "POLAR_STATE_NAMES",
    "STATE_NAMES",
    "TYPICAL",
    "cartesian_events",
    "central_differences",
    "check_frame_terms",
    "events",
    "force_response",
    "frame_force",
    "gravity_response",
    "spin_state",
    "state_spin",
    "initial_state",
    "observables",
    "params_array",
    "polar_events",
    "polar_observables",
    "reduced_reynolds",
    "run_args",
    "to_cartesian",
    "to_polar",
]

#: The parts of a run's ``args`` (:func:`run_args`, :mod:`numerics.packed`): the parameters
#: (:func:`params_array`), the force model's data, the typical scales, the event parameters.
PARAMETERS, MODEL, TYPICAL, EVENTS = range(4)

STATE_NAMES = ("u_x", "u_z", "v_x", "v_z", "omega_a", "omega_b", "x_b")
#: The state near contact (``polar_rhs`` (:func:`model_functions`)): the velocity in the frame of the line of centres.
POLAR_STATE_NAMES = ("u_x", "u_z", "q_r", "q_t", "omega_a", "omega_b", "x_b")
#: |u| = kappa/zeta above which a free run carries the polar velocity (kappa = 0.894), and below which
#: it returns to the Cartesian one (kappa = 0.707): apart, so that a run near either does not chatter.
POLAR_ABOVE, CARTESIAN_BELOW = 2.0, 1.0

# indices into the parameter array built by params_array
_A, _B, _LEN, _MU, _MEFF, _MRED, _MTOT, _MB, _MA, _G, _SIN, _COS, _FRAME, _SPIN, _ECCENTRIC = range(15)

#: How the equations treat the fluid's inertia in the frame of the line of centres: "quasi-steady"
#: carries m'_a instead of m_eff on the centripetal and Coriolis terms while the fluid turns with the
#: line of centres (:func:`frame_force`); "paper" is (2.1)-(2.2) as printed, m_eff on every term of r''.
#: Against the coupled Navier-Stokes runs the quasi-steady terms are the closer on the whole, by far on
#: runaways (docs/navier_stokes.md, docs/stokes_limit.md): they are the default, :data:`DEFAULT_FRAME_TERMS`.
FRAME_TERMS = ("quasi-steady", "paper")
DEFAULT_FRAME_TERMS = "quasi-steady"
#: The fluid's own angular momentum in (2.4): "none" drops it, as the paper writes (2.4); "couette" adds that of
#: the concentric Couette flow between the walls, m_f (a^2 Omega_a + b^2 Omega_b)/2, which a fluid turning with
#: the cylinders carries (against the coupled Navier-Stokes runs: docs/stokes_limit.md); "eccentric" that of the
#: Stokes flow at the run's eccentricity (:func:`spin_state`), which tends to "couette" as kappa -> 0. Against
#: the Navier-Stokes runs "eccentric" is the closest on the whole and never the farthest
#: (docs/site/equations_of_motion.md): it is the default, :data:`DEFAULT_FLUID_SPIN`.
FLUID_SPIN = ("none", "couette", "eccentric")
DEFAULT_FLUID_SPIN = "eccentric"


def check_frame_terms(frame_terms: str) -> str:
    """``frame_terms`` if it is one of :data:`FRAME_TERMS`, else ValueError naming them."""
    if frame_terms not in FRAME_TERMS:
        msg = f"frame_terms must be one of {', '.join(FRAME_TERMS)}, got {frame_terms!r}"
        raise ValueError(msg)
    return frame_terms


def params_array(apparatus, frame_terms: str = DEFAULT_FRAME_TERMS,
                 fluid_spin: str = DEFAULT_FLUID_SPIN) -> np.ndarray:
    """The numbers the jitted right-hand side needs, from an :class:`~dynamics.apparatus.Apparatus`."""
    check_frame_terms(frame_terms)
    if fluid_spin not in FLUID_SPIN:
        msg = f"fluid_spin must be one of {', '.join(FLUID_SPIN)}, got {fluid_spin!r}"
        raise ValueError(msg)
    ap = apparatus
    return np.array([ap.a, ap.b, ap.length, ap.mu, ap.m_eff, ap.m_a_reduced, ap.M, ap.m_b, ap.m_a,
                     ap.g, math.sin(ap.alpha), math.cos(ap.alpha), float(frame_terms == "quasi-steady"),
                     0.0 if fluid_spin == "none" else ap.m_f, float(fluid_spin == "eccentric")])


@jit(inline="always")
def frame_force(p, eps, eps_dot, chi_dot, omega_a=math.nan, omega_b=math.nan):
    """(f_eps, f_chi) that (2.1)-(2.2) leave out when the fluid turns with the line of centres (N).

    Steady flow in a turning frame. In a frame turning at a steady rate Omega
    about B, the centrifugal and Coriolis forces of a plane flow are gradients
    (2 Omega e_z x u = 2 Omega grad psi), so they only shift the pressure, and
    the pressure shift pushes the displaced fluid's disc with
    m''_a (-Omega^2 r + 2 Omega J v), v = r' - Omega J r the velocity of A in
    that frame (J: a quarter turn in the positive sense, J e_eps = e_chi):
    in all m''_a (Omega^2 r + 2 Omega J r'), or along (e_eps, e_chi)

        m''_a (eps Omega (Omega - 2 chi'),  2 Omega eps').

    For Omega = chi' (the frame of the line of centres, where the walls are
    fixed in shape) this is -m''_a chi'^2 eps e_eps + 2 m''_a chi' eps' e_chi.
    A fluid in rigid rotation with the inner cylinder at rest in it makes the
    point: it needs the force m'_a eps chi'^2 towards B, which (2.2) as printed
    writes m_eff eps chi'^2. With the paper's fluid force taken in the frame of
    the fluid's centre of mass the missing force carries m''_a (1 + m''_a/m_f)
    = m_eff - m'_a, and adding it puts m'_a instead of m_eff on the
    centripetal and Coriolis terms (lubrication.navier_stokes).

    The frame rate. The argument needs a frame in which the flow is steady.
    The line of centres is that frame while its rate changes slowly: the
    walls are fixed in shape there and turn at steady relative rates
    Omega - chi'. What the flow's inertia adds beyond the frame force depends
    on those relative rates only, and is the relative flow's correction
    (:mod:`lubrication.inertia`, ``inertia = "first-order"``). The line of
    centres stops being a steady frame as A passes near B: chi' =
    (e_chi . r')/eps grows without bound while the walls, and the fluid
    between them, turn at finite rates, and the force above would grow like
    |r'|^2/eps. No part of the fluid turns faster than the faster wall
    (circular Couette flow), so the rate used is chi' capped in size at that
    wall's, [-M, M] with M = max(|Omega_a|, |Omega_b|). This has no free
    constant, and it

    * is chi' wherever |chi'| <= M: the runaway and the approach to contact,
      where Omega_a ~ Omega_b ~ chi', and steady rolling, where chi' = 0 while
      the walls turn. There the steady Navier-Stokes force is the Stokes force
      plus the relative flow's first-order correction, with no frame force
      (tests/test_frame_terms.py), and the rate is smooth in chi' about 0, where
      a steady state sits (a cap at 0 itself made the integrator crawl there);
    * at eps -> 0, with the fluid turning rigidly (Omega_a = Omega_b = Omega),
      tends to the Coriolis force 2 m''_a Omega J r' on a disc crossing the
      fluid in the sense of its rotation, finite where the chi' form diverges.
      A disc crossing against it is given rate -Omega, and the force
      -2 m''_a Omega J r': off by 4 m''_a |Omega r'|, Re*/3 of the thin-gap
      Stokes drag 12 pi mu L (a/delta)^3 |r'| of the disc, the order of the
      next item;
    * elsewhere (|chi'| > M) exceeds the chi' form by
      m''_a (1 + m''_a/m_f) (eps W^2, 2 W eps'), W = +-M - chi' the rate of the
      cap relative to the line of centres, no larger than either wall's
      relative rate. Along e_eps that is at most (1 + m''_a/m_f) (delta/a)
      Re*/6 of the thin-gap Stokes force (2.6) of a wall's rotation at W
      (0.14 Re* for the apparatus): the order of the inertial error G Re* of
      the relative flow (G up to 0.08 there, :mod:`lubrication.inertia`), which
      the quasi-steady forces carry anyway.

    ``omega_a``, ``omega_b`` omitted: the fluid is taken to turn with the line
    of centres (Omega = chi'), as in contact, where Omega_a ~ Omega_b ~ chi'.
    Zero unless the parameters ask for it (``frame_terms = "quasi-steady"``).
    """
    if p[_FRAME] == 0.0:
        return 0.0, 0.0
    rate = chi_dot
    if not math.isnan(omega_a):
        top = max(abs(omega_a), abs(omega_b))
        rate = min(max(chi_dot, -top), top)
    extra = p[_MEFF] - p[_MRED]
    return extra * eps * rate * (rate - 2.0 * chi_dot), 2.0 * extra * rate * eps_dot


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
def spin_state(p, kappa, eps, eps_dot, chi_dot, omega_a, omega_b):
    """(J_a, J_b, K, torque): the fluid's own angular momentum in (2.4), as :func:`force_response` and
    :func:`gravity_response` take it.

    The fluid's angular momentum about its centre of mass, in the frame moving with B
    without turning, is L = J_a Omega_a + J_b Omega_b + K eps^2 chi'. With "couette" J_w
    = m_f r_w^2 / 2 (r_a = a, r_b = b) and K = 0; with "eccentric" (:mod:`lubrication.angular_momentum`)
    J_w = lambda_w m_f r_w^2 / 2, lambda_w = 1 - mu_w kappa^2, and K eps^2 =
    (m_f/2)(a^2 mu_a + b^2 mu_b) kappa^2 - (m_eff - m'_a) eps^2: the Stokes flow's
    rho L I_B chi' + J_a W_a + J_b W_b about B (lubrication.stokes.fluid_angular_momentum), less the
    angular momentum of the fluid's centre of mass about B, (m''_a^2/m_f) eps^2 chi', which m_eff already
    carries in (2.4). dL/dt enters (2.4); with eps^2 chi'' = (z x'' - x z'') - 2 eps eps' chi' it is
    J_a Omega_a' + J_b Omega_b' + K (z x'' - x z'') less ``torque``,
    2 K eps eps' chi' - kappa' (dk/dkappa chi' + dJ_a/dkappa Omega_a + dJ_b/dkappa Omega_b), k = K eps^2.
    """
    a, b = p[_A], p[_B]
    half_a, half_b = 0.5 * p[_SPIN] * a * a, 0.5 * p[_SPIN] * b * b
    if p[_ECCENTRIC] == 0.0:
        return half_a, half_b, 0.0, 0.0
    delta = b - a
    mu_a, mu_b, slope_a, slope_b = spin_shares(kappa, delta / a)
    centre = p[_MEFF] - p[_MRED]  # m''_a (1 + m''_a/m_f)
    dj_a = -half_a * kappa * (2.0 * mu_a + kappa * slope_a)
    dj_b = -half_b * kappa * (2.0 * mu_b + kappa * slope_b)
    big_k = (half_a * mu_a + half_b * mu_b) / (delta * delta) - centre
    dk = -dj_a - dj_b - 2.0 * centre * delta * delta * kappa
    torque = 2.0 * big_k * eps * eps_dot * chi_dot - (eps_dot / delta) * (dk * chi_dot + dj_a * omega_a + dj_b * omega_b)
    return half_a * (1.0 - mu_a * kappa * kappa), half_b * (1.0 - mu_b * kappa * kappa), big_k, torque


@jit(inline="always")
def state_spin(p, y):
    """:func:`spin_state` at a state of ``rhs`` (:func:`model_functions`), whose velocity is Cartesian."""
    kappa, _, _, eps, _, ex, ez = _geometry(y, p[_B] - p[_A])
    chi_dot = (ez * y[2] - ex * y[3]) / eps if eps > 0.0 else 0.0
    return spin_state(p, kappa, eps, ex * y[2] + ez * y[3], chi_dot, y[4], y[5])


@jit(inline="always")
def _inertia_b(p, eps, ez, spin):
    """The coefficient of Omega_b' in (2.4) once r'' and Omega_a' are eliminated (module docstring)."""
    b, m_r, m_eff = p[_B], p[_MRED], p[_MEFF]
    return (p[_MTOT] + p[_MB]) * b * b + spin[1] - (m_r * b) ** 2 / m_eff - spin[2] * m_r * b * eps * ez / m_eff


@jit(inline="always")
def force_response(p, eps, ex, ez, f_eps, f_chi, t_a, spin):
    """(x'', z'', Omega_a', Omega_b') due to a force (f_eps, f_chi) on A and a torque t_a about A.

    The part of (2.1)-(2.4) linear in the forces (module docstring), without
    gravity: the fluid's, or a contact force acting between the cylinders.
    ``spin``: the fluid's own angular momentum in the state (:func:`spin_state`).
    """
    a, b = p[_A], p[_B]
    cx, cz = ez, -ex  # e_chi
    fx = f_eps * ex + f_chi * cx
    fz = f_eps * ez + f_chi * cz
    m_eff, m_r = p[_MEFF], p[_MRED]
    # with the fluid's spin, J_a Omega_a' + J_b Omega_b' + K (z x'' - x z'') on the left of (2.4), Omega_a'
    # from (2.3) and z x'' - x z'' from (2.1)-(2.2)
    omega_b_dot = (-t_a * (1.0 + spin[0] / (0.5 * p[_MA] * a * a)) - eps * f_chi * (1.0 + spin[2] / m_eff)
                   - (m_r * b / m_eff) * fx) / _inertia_b(p, eps, ez, spin)
    return (fx - m_r * b * omega_b_dot) / m_eff, fz / m_eff, t_a / (0.5 * p[_MA] * a * a), omega_b_dot


@jit(inline="always")
def gravity_response(p, eps, ex, ez, spin):
    """(x'', z'', Omega_a', Omega_b') due to gravity alone, and the state's ``spin`` torque, from the same
    equations."""
    b, m_eff, m_r = p[_B], p[_MEFF], p[_MRED]
    gs, gc = p[_G] * p[_SIN], p[_G] * p[_COS]
    # K (z x'' - x z'') takes m_r g (z sin alpha + x cos alpha) / m_eff of gravity through r''
    moment = m_r * eps * (ez * gs + ex * gc) * spin[2] / m_eff
    omega_b_dot = (p[_MTOT] * gs * b - (m_r * b / m_eff) * m_r * gs - moment + spin[3]) / _inertia_b(p, eps, ez, spin)
    return (m_r * gs - m_r * b * omega_b_dot) / m_eff, -m_r * gc / m_eff, 0.0, omega_b_dot


@jit(inline="always")
def _accelerations(forces, p, model, kappa, omk, eps, ex, ez, eps_dot, chi_dot, omega_a, omega_b):
    """(x'', z'', Omega_a', Omega_b') of (2.1)-(2.4) in a state given by its geometry and rates.

    ``forces`` is a model's compiled force kernel (:mod:`lubrication.kernels`).
    """
    f_eps, f_chi, t_a = forces(model, p[_A], p[_B], p[_MU], p[_LEN], kappa, omk, eps_dot, omega_a - chi_dot,
                               omega_b - chi_dot)
    frame_eps, frame_chi = frame_force(p, eps, eps_dot, chi_dot, omega_a, omega_b)
    spin = spin_state(p, kappa, eps, eps_dot, chi_dot, omega_a, omega_b)
    fluid = force_response(p, eps, ex, ez, f_eps + frame_eps, f_chi + frame_chi, t_a, spin)
    gravity = gravity_response(p, eps, ex, ez, spin)
    return (fluid[0] + gravity[0], fluid[1] + gravity[1], fluid[2] + gravity[2], fluid[3] + gravity[3])


# _rhs, _polar_rhs and their Jacobians are templates: FORCES (a force kernel) and RHS or POLAR_RHS
# are bound, and the copies compiled, by _compiled below (model_functions).
def _rhs(t, y, args):
    """dy/dt of the full model; ``args`` from :func:`run_args` (the parameters, then the force model's data)."""
    p, model = part(args, PARAMETERS), part(args, MODEL)
    delta = p[_B] - p[_A]
    kappa, omk, zeta, eps, big_u, ex, ez = _geometry(y, delta)
    vx, vz, omega_a, omega_b = y[2], y[3], y[4], y[5]
    eps_dot = ex * vx + ez * vz
    chi_dot = (ez * vx - ex * vz) / eps if eps > 0.0 else 0.0
    rates = _accelerations(FORCES, p, model, kappa, omk, eps, ex, ez, eps_dot, chi_dot, omega_a, omega_b)  # noqa: F821
    dy = np.empty(7)
    scale = 1.0 / (delta * zeta)
    stretch = big_u * big_u * eps_dot
    dy[0] = (vx + stretch * ex) * scale
    dy[1] = (vz + stretch * ez) * scale
    for i in range(4):
        dy[2 + i] = rates[i]
    dy[6] = p[_B] * omega_b
    return dy


@jit(inline="always")
def _polar_geometry(y):
    """|u|, s^2 = 1 + |u|^2, s, kappa, 1 - kappa and e_eps of a state with |u| > 0."""
    big_u = math.hypot(y[0], y[1])
    s2 = 1.0 + big_u * big_u
    s = math.sqrt(s2)
    kappa = big_u / s
    return big_u, s2, s, kappa, 1.0 / (s2 * (1.0 + kappa)), y[0] / big_u, y[1] / big_u


def _polar_rhs(t, y, args):
    """dy/dt of the full model near contact, state :data:`POLAR_STATE_NAMES` (module docstring)."""
    p, model = part(args, PARAMETERS), part(args, MODEL)
    delta = p[_B] - p[_A]
    big_u, s2, s, kappa, omk, ex, ez = _polar_geometry(y)
    cx, cz = ez, -ex  # e_chi
    q_r, q_t, omega_a, omega_b = y[2], y[3], y[4], y[5]
    rates = _accelerations(FORCES, p, model, kappa, omk, kappa * delta, ex, ez,  # noqa: F821
                           delta * q_r / (s2 * s), q_t / big_u, omega_a, omega_b)
    a_r = (ex * rates[0] + ez * rates[1]) / delta
    a_t = (cx * rates[0] + cz * rates[1]) / delta
    dy = np.empty(7)
    dy[0] = q_r * ex + q_t * cx
    dy[1] = q_r * ez + q_t * cz
    dy[2] = s2 * s * a_r + s2 * q_t * q_t / big_u + 3.0 * big_u * q_r * q_r / s2
    dy[3] = s * a_t + (q_r * q_t / big_u) * (1.0 - 2.0 / s2)
    dy[4] = rates[2]
    dy[5] = rates[3]
    dy[6] = p[_B] * omega_b
    return dy


def to_polar(apparatus, y: np.ndarray) -> np.ndarray:
    """A state of ``rhs`` (:func:`model_functions`) (Cartesian velocity) as one of ``polar_rhs`` (:func:`model_functions`); needs |u| > 0."""
    big_u = math.hypot(y[0], y[1])
    s = math.sqrt(1.0 + big_u * big_u)
    ex, ez = y[0] / big_u, y[1] / big_u
    out = np.array(y, dtype=float)
    out[2] = s**3 * (ex * y[2] + ez * y[3]) / apparatus.delta
    out[3] = s * (ez * y[2] - ex * y[3]) / apparatus.delta
    return out


def to_cartesian(apparatus, y: np.ndarray) -> np.ndarray:
    """A state of ``polar_rhs`` (:func:`model_functions`) as one of ``rhs`` (:func:`model_functions`)."""
    big_u = math.hypot(y[0], y[1])
    s = math.sqrt(1.0 + big_u * big_u)
    ex, ez = y[0] / big_u, y[1] / big_u
    radial, tangential = apparatus.delta * y[2] / s**3, apparatus.delta * y[3] / s
    out = np.array(y, dtype=float)
    out[2] = radial * ex + tangential * ez
    out[3] = radial * ez - tangential * ex
    return out


@jit(inline="always")
def central_differences(fun, t, y, args, typical, passive=0):
    """d(fun)/dy by central differences, steps eps^(1/3) max(|y_j|, typical_j).

    Central differences carry an O(h^2) truncation and O(eps/h) rounding error,
    balanced at h ~ eps^(1/3) |y|: about 1e-11 relative, far below what the
    implicit integrator's Newton iteration needs. The last ``passive`` variables
    enter no derivative (as X_b, which only records the distance rolled): their
    columns are zero and cost no evaluation.
    """
    n = y.size
    jac = np.zeros((n, n))
    yp = y.copy()
    for j in range(n - passive):
        h = 6.0554544523933395e-06 * max(abs(y[j]), typical[j])  # eps^(1/3)
        yp[j] = y[j] + h
        up = fun(t, yp, args)
        yp[j] = y[j] - h
        down = fun(t, yp, args)
        yp[j] = y[j]
        for i in range(n):
            jac[i, j] = (up[i] - down[i]) / (2.0 * h)
    return jac


def _jacobian(t, y, args):
    """d(rhs)/dy by central differences (``central_differences``); X_b is passive."""
    return central_differences(RHS, t, y, args, part(args, TYPICAL), 1)  # noqa: F821


def _polar_jacobian(t, y, args):
    """d(polar_rhs)/dy by central differences (``central_differences``); X_b is passive."""
    return central_differences(POLAR_RHS, t, y, args, part(args, TYPICAL), 1)  # noqa: F821


#: The full model's compiled right-hand sides and Jacobians, for one force kernel.
ModelFunctions = namedtuple("ModelFunctions", ["rhs", "jacobian", "polar_rhs", "polar_jacobian"])


def _compiled(forces, name: str) -> ModelFunctions:
    """The templates above compiled with the force kernel ``forces``, filed under ``name``."""
    rhs = specialise(_rhs, name, FORCES=forces)
    polar_rhs = specialise(_polar_rhs, name, FORCES=forces)
    return ModelFunctions(rhs, specialise(_jacobian, name, RHS=rhs), polar_rhs,
                          specialise(_polar_jacobian, name, POLAR_RHS=polar_rhs))


@functools.cache
def _compiled_for(kernel, name: str) -> ModelFunctions:
    return _compiled(kernel, name)


def model_functions(model: KernelModel) -> ModelFunctions:
    """The full model's functions compiled with the kernel of ``model`` (:mod:`lubrication.kernels`).

    Each kernel gets its own copies of the templates above, filed under its
    :attr:`~lubrication.kernels.KernelModel.kernel_name`: a run loads the code of
    its own force model only, and the force model is one argument of one numba
    type (its packed data), so a kernel's copies serve every set of its options.
    """
    return _compiled_for(model.kernel, model.kernel_name)


#: The components of :func:`events`, in order, as in :data:`dynamics.equations.reduced.EVENT_NAMES`:
#: the validity limits, the line of centres crossing an axis (u_x u_z = 0: every quarter turn, which
#: keeps chi continuous between output rows), and the touch of rough walls (kappa = kappa*).
EVENT_NAMES = ("gap_floor", "reynolds", "runaway", "turn", "touch")

# entries of the events' parameter array (part EVENTS of args)
_LOG_FLOOR, _MAX_RE, _RE_A, _RE_B, _XB_LIMIT, _XB0, _U_STAR = range(7)


@jit(inline="always")
def _reynolds(kappa, chi_dot, omega_a, omega_b, ev):
    """Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a), W = Omega - chi'.

    The Reynolds number of the flow relative to the line of centres, which
    measures the error of quasi-steady Stokes forces (:mod:`lubrication.inertia`:
    the frame's rotation only shifts the pressure of a plane flow). Where the line
    of centres is undefined (kappa -> 0) chi' is not, and Re* is faded out over
    kappa ~ 1e-3.
    """
    fade = kappa * kappa / (kappa * kappa + 1e-6)
    return fade * max(abs(omega_a - chi_dot) * ev[_RE_A], abs(omega_b - chi_dot) * ev[_RE_B])


@jit(inline="always")
def reduced_reynolds(y, p, ev):
    """Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a), W = Omega - chi', of a state ``y`` of ``rhs`` (:func:`model_functions`).

    The Reynolds number of the flow relative to the line of centres, which
    measures the error of quasi-steady Stokes forces (:mod:`lubrication.inertia`),
    faded out where the line of centres is undefined (kappa -> 0).
    """
    big_u = math.hypot(y[0], y[1])
    if big_u == 0.0:
        return 0.0
    kappa = big_u / math.sqrt(1.0 + big_u * big_u)
    ex, ez = y[0] / big_u, y[1] / big_u
    return _reynolds(kappa, (ez * y[2] - ex * y[3]) / (kappa * (p[_B] - p[_A])), y[4], y[5], ev)


@jit(inline="always")
def _event_values(y, ev, big_u, re_star, g):
    """The first five event values (:data:`EVENT_NAMES`) into ``g``; ``ev`` the part EVENTS of ``args``."""
    one_plus = 1.0 + big_u * big_u
    kappa = big_u / math.sqrt(one_plus)
    omk = 1.0 / (one_plus * (1.0 + kappa))
    g[0] = math.log(omk) - ev[_LOG_FLOOR]
    g[1] = ev[_MAX_RE] - re_star
    g[2] = ev[_XB_LIMIT] - abs(y[6] - ev[_XB0])
    g[3] = y[0] * y[1]
    g[4] = big_u - ev[_U_STAR]


@jit
def events(t, y, args):
    """The event values of :data:`EVENT_NAMES`; each fires as it falls through (or rises to) 0."""
    p, ev = part(args, PARAMETERS), part(args, EVENTS)
    g = np.empty(5)
    _event_values(y, ev, math.hypot(y[0], y[1]), reduced_reynolds(y, p, ev), g)
    return g


#: The events of a free run in each representation: :data:`EVENT_NAMES` and the change of representation.
CARTESIAN_EVENT_NAMES = (*EVENT_NAMES, "to_polar")
POLAR_EVENT_NAMES = (*EVENT_NAMES, "to_cartesian")


@jit
def cartesian_events(t, y, args):
    """:func:`events` and |u| - POLAR_ABOVE (rising through 0: the run goes on in ``polar_rhs`` (:func:`model_functions`))."""
    p, ev = part(args, PARAMETERS), part(args, EVENTS)
    g = np.empty(6)
    big_u = math.hypot(y[0], y[1])
    _event_values(y, ev, big_u, reduced_reynolds(y, p, ev), g)
    g[5] = big_u - POLAR_ABOVE
    return g


@jit
def polar_events(t, y, args):
    """:data:`POLAR_EVENT_NAMES` of a state of ``polar_rhs`` (:func:`model_functions`); |u| - CARTESIAN_BELOW falls through 0 to return."""
    g = np.empty(6)
    big_u = math.hypot(y[0], y[1])
    kappa = big_u / math.sqrt(1.0 + big_u * big_u)
    ev = part(args, EVENTS)
    _event_values(y, ev, big_u, _reynolds(kappa, y[3] / big_u, y[4], y[5], ev), g)
    g[5] = big_u - CARTESIAN_BELOW
    return g


def run_args(apparatus, force_model: KernelModel, *, gap_floor: float, max_reynolds: float = math.inf,
             max_turns: float = math.inf, x_b0: float = 0.0, kappa_star: float = 1.0,
             frame_terms: str = DEFAULT_FRAME_TERMS, fluid_spin: str = DEFAULT_FLUID_SPIN) -> np.ndarray:
    """The ``args`` of ``rhs`` (:func:`model_functions`), ``jacobian`` and :func:`events` for a run.

    Its parts (:func:`numerics.packed.part`) :data:`PARAMETERS`, :data:`MODEL` (the force model's data),
    :data:`TYPICAL` (typical scales) and :data:`EVENTS` (event parameters): the gap-floor
    event at 1 - kappa = ``gap_floor``, the Reynolds event at ``max_reynolds``, the
    runaway event after ``max_turns`` turns of the outer cylinder from ``x_b0`` (m),
    the touch event at ``kappa_star`` (1: none); ``frame_terms`` (:data:`FRAME_TERMS`) and ``fluid_spin``
    (:data:`FLUID_SPIN`).
    """
    ap = apparatus
    u_star = math.inf if kappa_star >= 1.0 else kappa_star / math.sqrt((1.0 - kappa_star) * (1.0 + kappa_star))
    per_rate = ap.delta**2 / (ap.nu * ap.a)  # Re* per unit wall speed: (dynamics.equations.full.reduced_reynolds)
    ev = np.array([math.log(gap_floor), max_reynolds, per_rate * ap.a, per_rate * ap.b,
                   2.0 * math.pi * ap.b * max_turns, x_b0, u_star])
    return pack(params_array(ap, frame_terms, fluid_spin), model_arguments(force_model), typical_scales(ap), ev)


def initial_state(apparatus, kappa, phi, kappa_dot, phi_dot, omega_a, omega_b, *,
                  one_minus_kappa: float | None = None) -> np.ndarray:
    """State vector from (kappa, phi, kappa', phi', Omega_a, Omega_b) in SI units.

    phi = alpha + chi is measured from the upward vertical; chi' = phi'.
    ``one_minus_kappa``, when given, carries the gap to full precision near contact.
    """
    delta = apparatus.delta
    omk = 1.0 - kappa if one_minus_kappa is None else one_minus_kappa
    chi = phi - apparatus.alpha
    e_eps = np.array([math.sin(chi), math.cos(chi)])
    e_chi = np.array([math.cos(chi), -math.sin(chi)])
    zeta = math.sqrt(omk * (1.0 + kappa))
    u = (kappa / zeta) * e_eps
    v = delta * (kappa_dot * e_eps + kappa * phi_dot * e_chi)
    return np.array([u[0], u[1], v[0], v[1], omega_a, omega_b, 0.0])


def typical_scales(apparatus) -> np.ndarray:
    """A size for each state component: the floor of the integrator's atol and of FD steps."""
    tau = apparatus.tau
    return np.array([1.0, 1.0, apparatus.delta / tau, apparatus.delta / tau, 1.0 / tau, 1.0 / tau,
                     apparatus.b])


def observables(apparatus, y: np.ndarray, phi0: float) -> dict[str, np.ndarray]:
    """kappa, 1 - kappa, eps, chi, phi, kappa', phi', Omega_a, Omega_b, X_b from states y (shape (7, n)).

    chi is unwrapped to be continuous between rows (the rows must include the
    quarter-turn "turn" events, for that to hold whatever the spacing) and phi starts at the turn of ``phi0``. kappa' = e_eps . r'/delta and
    phi' = chi' = (e_chi . r')/eps (0 at eps = 0, where the direction is undefined).
    """
    big_u = np.hypot(y[0], y[1])
    one_plus = 1.0 + big_u**2
    kappa = big_u / np.sqrt(one_plus)
    chi = np.unwrap(np.arctan2(y[0], y[1]))
    if chi.size:
        chi += 2.0 * math.pi * round((phi0 - apparatus.alpha - chi[0]) / (2.0 * math.pi))
    eps = kappa * apparatus.delta
    ex, ez = np.sin(chi), np.cos(chi)
    with np.errstate(divide="ignore", invalid="ignore"):
        chi_dot = np.where(eps > 0.0, (ez * y[2] - ex * y[3]) / eps, 0.0)
    return {
        "kappa": kappa,
        "one_minus_kappa": 1.0 / (one_plus * (1.0 + kappa)),
        "eps": eps,
        "chi": chi,
        "phi": chi + apparatus.alpha,
        "kappa_dot": (ex * y[2] + ez * y[3]) / apparatus.delta,
        "phi_dot": chi_dot,
        "omega_a": y[4],
        "omega_b": y[5],
        "x_b": y[6],
    }


def polar_observables(apparatus, y: np.ndarray, phi0: float) -> dict[str, np.ndarray]:
    """As :func:`observables`, from states of ``polar_rhs`` (:func:`model_functions`)."""
    big_u = np.hypot(y[0], y[1])
    s = np.sqrt(1.0 + big_u**2)
    return observables(apparatus, np.vstack([y[:2], np.zeros((2, y.shape[1])), y[4:]]), phi0) | {
        "kappa_dot": y[2] / s**3, "phi_dot": y[3] / big_u}


def model_arguments(force_model: KernelModel) -> np.ndarray:
    """The force model's data as ``rhs`` (:func:`model_functions`) takes them (part :data:`MODEL` of ``args``)."""
    return force_model.data


# -- a free run: the Cartesian velocity away from contact, the polar one near it --------------------------

class FreeFull:
    """The free full model as a hybrid run: Cartesian velocity away from contact, polar near it.

    the module docstring explains why (the Newton iteration near
    contact) and where (|u| above POLAR_ABOVE, back below CARTESIAN_BELOW); a
    change of variables is a phase that continues the motion
    (:class:`numerics.hybrid.Phase`). A cavitating film stays in the
    Cartesian velocity (``polar=False``): its forces are only piecewise smooth,
    and at a kink of the Swift-Stieber film (steel, 1 degree, 1 atm below the
    bubble, 1 - kappa = 1.2e-4) the Newton iterations of Radau IIA and of BDF
    both failed in the polar velocity, where the Cartesian one runs through.
    """

    def __init__(self, apparatus, args, functions: ModelFunctions, stops: int, rtol: float, polar: bool = True):
        self.ap, self.args, self.f, self.polar = apparatus, args, functions, polar
        typical = parts(args)[TYPICAL]
        self.atol = rtol * typical
        # q_r and q_t are rates of |u|: 1/tau for the size of their absolute tolerance
        self.polar_atol = rtol * np.array([*typical[:2], 1.0 / apparatus.tau, 1.0 / apparatus.tau, *typical[4:]])
        self.terminal = (stops, stops, 1, 0, 0, 1)

    def phase(self, y) -> Phase:
        """The first phase, from state ``y`` of the right-hand side, in the variables its |u| calls for."""
        if self.polar and math.hypot(y[0], y[1]) > POLAR_ABOVE:
            return self._polar(to_polar(self.ap, y))
        return self._cartesian(np.asarray(y, float))

    def _cartesian(self, y, continues: bool = False) -> Phase:
        if not self.polar:
            return Phase("free", self.f.rhs, self.f.jacobian, events, self.args, y, EVENT_NAMES,
                         self.terminal[:5], (-1, -1, -1, 0, 1), self.atol, extra={"polar": False})
        return Phase("free", self.f.rhs, self.f.jacobian, cartesian_events, self.args, y,
                     CARTESIAN_EVENT_NAMES, self.terminal, (-1, -1, -1, 0, 1, 1), self.atol, continues=continues,
                     extra={"polar": False})

    def _polar(self, y, continues: bool = False) -> Phase:
        return Phase("free", self.f.polar_rhs, self.f.polar_jacobian, polar_events, self.args, y,
                     POLAR_EVENT_NAMES, self.terminal, (-1, -1, -1, 0, 1, -1), self.polar_atol,
                     continues=continues, extra={"polar": True})

    def transition(self, phase: Phase, reason: str, t: float, end, phi: float) -> Phase:
        if reason == "to_polar":
            return self._polar(to_polar(self.ap, end), continues=True)
        return self._cartesian(to_cartesian(self.ap, end), continues=True)

    def columns(self, phase: Phase, t, y, kind) -> dict:
        """Scaled columns of one phase's rows (t in tau, rates in 1/tau, X_b in b)."""
        ap, tau = self.ap, self.ap.tau
        observe = polar_observables if phase.extra["polar"] else observables
        obs = observe(ap, y, phase.extra["phi0"])
        return {"kappa": obs["kappa"], "one_minus_kappa": obs["one_minus_kappa"], "phi": obs["phi"],
                "kappa_dot": obs["kappa_dot"] * tau, "phi_dot": obs["phi_dot"] * tau, "omega_a": obs["omega_a"] * tau,
                "omega_b": obs["omega_b"] * tau, "x_b": obs["x_b"] / ap.b}
