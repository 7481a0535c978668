r"""Rough contact in the full dimensional model (2.1)-(2.4): a unilateral constraint with Coulomb friction.

Formulation
-----------
Asperities of height sigma stop the centres at eps = eps* = delta - sigma
(kappa* = 1 - sigma/delta). While the cylinders touch, the wall acts on A at
the point a e_eps from its centre with a normal reaction N >= 0 (along -e_eps,
towards B) and a friction F (along e_chi); -N, -F act on B at b e_eps from its
centre. In (2.1)-(2.3) the contact force adds to the fluid force,
f_eps -> f_eps - N, f_chi -> f_chi + F, and its torque about A to the fluid's,
T_a -> T_a + a F. (2.4), the angular momentum of the whole device about its
contact with the plane, holds unchanged: the contact force is internal. So the
accelerations are those of the ``rhs`` of :func:`dynamics.equations.full.model_functions` with these forces added,
through the same linear map :func:`dynamics.equations.full.force_response`; nothing of
(2.1)-(2.4) is derived twice.

In contact the state is (chi, chi', Omega_a, Omega_b, X_b), eps = eps*, and
two conditions fix N and F:

* eps'' = e_eps . r'' + eps* chi'^2 = 0 (the centres stay eps* apart);
* locked: the slip s = eps* (chi' - Omega_b) + a (Omega_a - Omega_b), the
  speed of A's surface past the asperity of B that touches it, stays zero,
  s' = 0;
  sliding: F = -sigma tan(psi_hat) N with sigma = sgn(s), constant in the phase.

The contact is one point, on A's surface a e_eps from A and (a + eps*) e_eps
from B, where the asperity of B's wall touches it: the pair (C, -C) acts at
that point, so (2.4) holds without a couple, and the power of C is F s
(the normal reaction does no work at eps' = 0). Measuring the slip at B's
own radius b instead would leave an unbalanced couple sigma F, and the energy
balance would be off by sigma F Omega_b (tested).

Both conditions are linear in (N, F): a 2 x 2 solve at each evaluation. The slip is a
linear function of the state with constant coefficients in contact, so any
Runge-Kutta or multistep method keeps s = 0 of a locked phase to rounding.

Switching and the impact law
----------------------------
* free -> contact when kappa rises through kappa* (an event on the integrator's
  dense output). The impact is plastic: an impulse P_N along -e_eps removes the
  normal approach speed, eps' = 0 after it, and a tangential impulse P_F stops
  the slip if |P_F| <= tan(psi_hat) P_N, else P_F = -sgn(s) tan(psi_hat) P_N
  (Coulomb's law for impulses). The velocity jumps are the force response to
  the impulses, since (2.1)-(2.4) are linear in the accelerations with
  bounded velocity terms. The angular momentum of (2.4) is conserved and
  kinetic energy is lost. Then locked if the locking reaction satisfies
  |F| < tan(psi_hat) N, else sliding; free again if N < 0.
* contact -> free when N falls through 0 (the wall would have to pull).
* locked -> sliding when |F| reaches tan(psi_hat) N, with sigma = -sgn(F):
  slip starts in the direction the friction no longer prevents.
* sliding -> locked when s reaches 0 and the locking reaction is inside the
  friction cone; else sliding on with the opposite sigma.

Each phase has a smooth right-hand side and every guard is a terminal event
located on the dense output, so there is no chattering regularisation and no
step-size collapse, as in :mod:`dynamics.contact.reduced`.

The limit delta/a -> 0: section 5
---------------------------------
Scale forces by m'_a g, time by tau, and write tan(psi) = (a/delta) tan(psi_hat)
(C2). Then N/(m'_a g) -> -cos(phi) = C_e (5.1), because radial inertia and the
rolling term of (2.2) are O(delta/a) and f_eps vanishes with kappa' = 0;
the torque a F on A, in units of m'_a g delta, is -C_x of (5.2) with
C_x = -(a/delta) F/(m'_a g), O(1), while F itself is O(delta/a) in (2.1);
the friction bound |F| <= tan(psi_hat) N becomes |C_x| <= C_e tan(psi) (5.3);
the slip s = a(Omega_a - Omega_b) + O(delta) makes "locked" Omega_a = Omega_b;
and (2.4) is (2.11d). Two differences vanish only in the limit: in the full
model a locked pair turns with a Omega_a = (a + eps*) Omega_b - eps* chi' (exact
rolling at the contact point), and the impulse on touching conserves the angular
momentum of (2.4), whereas section 5 lets Omega_a jump to Omega_b
(see :mod:`dynamics.contact.reduced`). Steady states do not depend on the jump; they
approach (5.6)-(5.11) at O(delta/a) (checked in the tests).

Units. Every phase is integrated in SI, with the absolute tolerance of each
component rtol times its typical size (:func:`dynamics.equations.full.typical_scales`;
in contact 1, 1/tau, 1/tau, 1/tau and b for chi, chi', Omega_a, Omega_b, X_b).
"""

from __future__ import annotations

import functools
import math
from collections import namedtuple

import numpy as np
from scipy.optimize import fsolve

from dynamics.contact.reduced import FREE, LOCKED, SLIDING, ContactParams
from dynamics.equations import full
from dynamics.equations.limits import Limits
from lubrication.kernels import KernelModel
from numerics.hybrid import MAX_SWITCHES, Phase, run_phases
from numerics.jit import specialise
from numerics.packed import pack, part, parts

__all__ = [
    "LOCKED_EVENTS",
    "SLIDING_EVENTS",
    "ContactFunctions",
    "FullContactRun",
    "contact_functions",
    "phases_in_tau",
    "friction_coefficient",
    "impact",
    "slip",
    "steady_full_contact",
]


def friction_coefficient(apparatus, contact: ContactParams) -> float:
    """The physical friction coefficient tan(psi_hat) = (delta/a) tan(psi) of the paper's scaled psi (C2)."""
    return apparatus.delta_over_a * contact.tan_psi


# -- contact forces and accelerations (jitted) -------------------------------------
# Templates: FORCES (a force kernel), CONTACT_RATES and CONTACT_RHS are bound, and the copies
# compiled, by _compiled below (contact_functions).

def _contact_rates(y, p, kappa_star, omk_star, locked, sigma, tan_psi_hat, model):
    """(chi'', Omega_a', Omega_b', N, F) in contact, SI; ``y`` = (chi, chi', Omega_a, Omega_b, ...).

    ``locked`` keeps the slip at zero; otherwise F = -sigma tan(psi_hat) N. ``model`` is
    :attr:`lubrication.kernels.KernelModel.data`.
    """
    a, b = p[0], p[1]
    eps = kappa_star * (b - a)
    chi, chi_dot, omega_a, omega_b = y[0], y[1], y[2], y[3]
    ex, ez = math.sin(chi), math.cos(chi)
    cx, cz = ez, -ex
    f_eps, f_chi, t_a = FORCES(model, a, b, p[3], p[2], kappa_star, omk_star, 0.0,  # noqa: F821
                               omega_a - chi_dot, omega_b - chi_dot)
    frame_eps, frame_chi = full.frame_force(p, eps, 0.0, chi_dot, omega_a, omega_b)
    spin = full.spin_state(p, kappa_star, eps, 0.0, chi_dot, omega_a, omega_b)
    fluid = full.force_response(p, eps, ex, ez, f_eps + frame_eps, f_chi + frame_chi, t_a, spin)
    gravity = full.gravity_response(p, eps, ex, ez, spin)
    base = np.empty(4)
    for i in range(4):
        base[i] = fluid[i] + gravity[i]
    normal = full.force_response(p, eps, ex, ez, -1.0, 0.0, 0.0, spin)   # unit N: pushes A towards B
    friction = full.force_response(p, eps, ex, ez, 0.0, 1.0, a, spin)    # unit F along e_chi, torque a F
    # eps'' = e_eps . r'' + eps chi'^2 and s' = e_chi . r'' + a Omega_a' - (a + eps) Omega_b'
    arm = a + eps
    r0 = ex * base[0] + ez * base[1] + eps * chi_dot * chi_dot
    r_n = ex * normal[0] + ez * normal[1]
    r_f = ex * friction[0] + ez * friction[1]
    if locked:
        s0 = cx * base[0] + cz * base[1] + a * base[2] - arm * base[3]
        s_n = cx * normal[0] + cz * normal[1] + a * normal[2] - arm * normal[3]
        s_f = cx * friction[0] + cz * friction[1] + a * friction[2] - arm * friction[3]
        det = r_n * s_f - r_f * s_n
        n_force = (-r0 * s_f + r_f * s0) / det
        f_force = (-r_n * s0 + s_n * r0) / det
    else:
        n_force = -r0 / (r_n - sigma * tan_psi_hat * r_f)
        f_force = -sigma * tan_psi_hat * n_force
    out = np.empty(5)
    acc = np.empty(4)
    for i in range(4):
        acc[i] = base[i] + n_force * normal[i] + f_force * friction[i]
    out[0] = (cx * acc[0] + cz * acc[1]) / eps
    out[1], out[2] = acc[2], acc[3]
    out[3], out[4] = n_force, f_force
    return out


def slip(apparatus, kappa_star: float, y) -> float:
    """Slip speed eps* (chi' - Omega_b) + a (Omega_a - Omega_b) (m/s) at the contact point, SI state."""
    eps = kappa_star * apparatus.delta
    return eps * (y[1] - y[3]) + apparatus.a * (y[2] - y[3])


def _free_state(apparatus, contact: ContactParams, y) -> np.ndarray:
    """The free state (u, r', Omega_a, Omega_b, X_b) of a contact state (SI), eps' = 0."""
    chi = y[0]
    zeta = math.sqrt(contact.one_minus_kappa_star * (1.0 + contact.kappa_star))
    u = contact.kappa_star / zeta
    speed = contact.kappa_star * apparatus.delta * y[1]
    return np.array([u * math.sin(chi), u * math.cos(chi), speed * math.cos(chi), -speed * math.sin(chi),
                     y[2], y[3], y[4]])


def impact(apparatus, contact: ContactParams, chi: float, velocity, omega_a: float, omega_b: float,
           fluid_spin: str = full.DEFAULT_FLUID_SPIN):
    """Velocities just after a plastic impact at eps = eps* (module docstring).

    Parameters
    ----------
    chi : float
        Direction of the line of centres.
    velocity : array_like, shape (2,)
        r' = (x', z') before the impact (m/s).
    omega_a, omega_b : float
        Rates before (rad/s).
    fluid_spin : str
        The run's fluid spin in (2.4) (:data:`dynamics.equations.full.FLUID_SPIN`): the impulses act on the
        inertia it gives.

    Returns
    -------
    (velocity, omega_a, omega_b, p_n, p_f)
        After the impact, and the normal and tangential impulses (N s).
    """
    p = full.params_array(apparatus, fluid_spin=fluid_spin)
    eps = contact.kappa_star * apparatus.delta
    ex, ez = math.sin(chi), math.cos(chi)
    e_eps, e_chi = np.array([ex, ez]), np.array([ez, -ex])
    spin = full.spin_state(p, contact.kappa_star, eps, e_eps @ velocity, (e_chi @ velocity) / eps, omega_a, omega_b)
    normal = np.array(full.force_response(p, eps, ex, ez, -1.0, 0.0, 0.0, spin))
    friction = np.array(full.force_response(p, eps, ex, ez, 0.0, 1.0, apparatus.a, spin))
    v = np.array([*velocity, omega_a, omega_b], dtype=float)
    radial = np.array([ex, ez, 0.0, 0.0])
    sliding = np.array([*e_chi, apparatus.a, -(apparatus.a + eps)])
    approach, slip0 = radial @ v, sliding @ v
    mu_f = friction_coefficient(apparatus, contact)
    p_n, p_f = np.linalg.solve([[radial @ normal, radial @ friction], [sliding @ normal, sliding @ friction]],
                               [-approach, -slip0])
    if abs(p_f) > mu_f * p_n:  # the stick impulse lies outside the friction cone
        sigma = math.copysign(1.0, slip0)
        p_n = -approach / (radial @ normal - sigma * mu_f * (radial @ friction))
        p_f = -sigma * mu_f * p_n
    v = v + p_n * normal + p_f * friction
    v[:2] -= (e_eps @ v[:2]) * e_eps  # eps' = 0 exactly, not to rounding
    return v[:2], v[2], v[3], p_n, p_f


# -- the phases as the hybrid driver runs them ------------------------------------------

#: Event components of the contact phases, in order (:func:`contact_events`).
# A steady contact state is accepted when its accelerations, in units of
# 1/tau^2, vanish to this: far below any physical acceleration, above the
# rounding of the forces near contact.
STEADY_RESIDUAL = 1e-9

LOCKED_EVENTS = ("runaway", "lift", "slip", "slip")
SLIDING_EVENTS = ("runaway", "lift", "stick")

# args of the contact phases: the parts (p, model, typical scales, numbers), packed as the free phase's
# (dynamics.equations.full.run_args), so that one compiled integrator serves both; the numbers are
# the runaway's limit and origin of X_b, then kappa*, 1 - kappa*, locked, sigma and tan(psi_hat)
_XB_LIMIT, _XB0, _KSTAR, _OMK_STAR, _LOCKED, _SIGMA, _MU_F = range(7)


def _contact_rhs(t, y, args):
    """d/dt (chi, chi', Omega_a, Omega_b, X_b) in contact (SI); ``args`` from :meth:`FullContactRun.contact_args`."""
    p, model, c = part(args, full.PARAMETERS), part(args, full.MODEL), part(args, full.EVENTS)
    r = CONTACT_RATES(y, p, c[_KSTAR], c[_OMK_STAR], c[_LOCKED] > 0.0, c[_SIGMA], c[_MU_F], model)  # noqa: F821
    out = np.empty(5)
    out[0] = y[1]
    out[1] = r[0]
    out[2] = r[1]
    out[3] = r[2]
    out[4] = p[1] * y[3]
    return out


def _contact_jacobian(t, y, args):
    """d(contact_rhs)/dy by central differences (:func:`dynamics.equations.full.central_differences`)."""
    return full.central_differences(CONTACT_RHS, t, y, args, part(args, full.TYPICAL))  # noqa: F821


def _contact_events(t, y, args):
    """Locked: :data:`LOCKED_EVENTS`; sliding: :data:`SLIDING_EVENTS` (the fourth component is unused).

    The runaway; lift-off as N falls through 0; locked, the friction bound
    |F| = tan(psi_hat) N on either side; sliding, the slip reaching 0.
    """
    p, model, c = part(args, full.PARAMETERS), part(args, full.MODEL), part(args, full.EVENTS)
    r = CONTACT_RATES(y, p, c[_KSTAR], c[_OMK_STAR], c[_LOCKED] > 0.0, c[_SIGMA], c[_MU_F], model)  # noqa: F821
    n_force, f_force = r[3], r[4]
    g = np.empty(4)
    g[0] = c[_XB_LIMIT] - abs(y[4] - c[_XB0])
    g[1] = n_force
    if c[_LOCKED] > 0.0:
        g[2] = c[_MU_F] * n_force - f_force
        g[3] = c[_MU_F] * n_force + f_force
    else:
        eps = c[_KSTAR] * (p[1] - p[0])
        g[2] = c[_SIGMA] * (eps * (y[1] - y[3]) + p[0] * (y[2] - y[3]))
        g[3] = 1.0
    return g


#: The contact phases' compiled functions, for one force kernel.
ContactFunctions = namedtuple("ContactFunctions", ["rates", "rhs", "jacobian", "events"])


def _compiled(forces, name: str) -> ContactFunctions:
    """The templates above compiled with the force kernel ``forces``, filed under ``name``."""
    rates = specialise(_contact_rates, name, FORCES=forces)
    rhs = specialise(_contact_rhs, name, CONTACT_RATES=rates)
    return ContactFunctions(rates, rhs, specialise(_contact_jacobian, name, CONTACT_RHS=rhs),
                            specialise(_contact_events, name, CONTACT_RATES=rates))


@functools.cache
def _compiled_for(kernel, name: str) -> ContactFunctions:
    return _compiled(kernel, name)


def contact_functions(model: KernelModel) -> ContactFunctions:
    """The contact phases' functions compiled with the kernel of ``model``.

    As :func:`dynamics.equations.full.model_functions`: one set per kernel, what a run takes.
    """
    return _compiled_for(model.kernel, model.kernel_name)


class FullContactRun:
    """What the phases of one full-model contact run share."""

    def __init__(self, apparatus, force_model: KernelModel, contact: ContactParams, limits: Limits, rtol: float,
                 frame_terms: str = full.DEFAULT_FRAME_TERMS, fluid_spin: str = full.DEFAULT_FLUID_SPIN):
        self.ap, self.contact, self.limits, self.rtol = apparatus, contact, limits, rtol
        self.fluid_spin = fluid_spin
        self.p = full.params_array(apparatus, frame_terms, fluid_spin)
        self.model = full.model_arguments(force_model)
        self.functions = contact_functions(force_model)
        self.free_functions = full.model_functions(force_model)
        self.tan_psi_hat = friction_coefficient(apparatus, contact)
        self.free_args = full.run_args(apparatus, force_model, gap_floor=limits.gap_floor,
                                       max_reynolds=limits.reynolds, max_turns=limits.max_turns,
                                       kappa_star=contact.kappa_star, frame_terms=frame_terms,
                                       fluid_spin=fluid_spin)
        tau = apparatus.tau
        self.contact_typical = np.array([1.0, 1.0 / tau, 1.0 / tau, 1.0 / tau, apparatus.b])
        self.runaway = np.array([2.0 * math.pi * apparatus.b * limits.max_turns, 0.0])

    def rates(self, y, locked: bool, sigma: float) -> np.ndarray:
        return self.functions.rates(np.asarray(y, float), self.p, self.contact.kappa_star,
                                    self.contact.one_minus_kappa_star, locked, sigma, self.tan_psi_hat, self.model)

    def contact_args(self, locked: bool, sigma: float) -> np.ndarray:
        numbers = np.array([*self.runaway, self.contact.kappa_star, self.contact.one_minus_kappa_star,
                            float(locked), sigma, self.tan_psi_hat])
        return pack(self.p, self.model, self.contact_typical, numbers)

    def free(self, y) -> Phase:
        stops = int(self.limits.stops)
        f = self.free_functions
        return Phase(FREE, f.rhs, f.jacobian, full.events, self.free_args, np.asarray(y, float),
                     full.EVENT_NAMES, (stops, stops, 1, 0, 1), (-1, -1, -1, 0, 1), self.rtol * parts(self.free_args)[full.TYPICAL])

    def locked(self, y) -> Phase:
        f = self.functions
        return Phase(LOCKED, f.rhs, f.jacobian, f.events, self.contact_args(True, 0.0),
                     np.asarray(y, float), LOCKED_EVENTS, (1, 1, 1, 1), (-1, -1, -1, -1),
                     self.rtol * self.contact_typical)

    def sliding(self, y, sigma: float) -> Phase:
        stick = int(self.tan_psi_hat > 0.0)
        f = self.functions
        return Phase(SLIDING, f.rhs, f.jacobian, f.events, self.contact_args(False, sigma),
                     np.asarray(y, float), (*SLIDING_EVENTS, ""), (1, 1, stick, 0), (-1, -1, -1, 0),
                     self.rtol * self.contact_typical, sigma=sigma)

    def enter_contact(self, y, sigma_hint: float = 0.0) -> Phase:
        """Phase on touching (after the impact) or at a switch, for a contact state ``y`` (SI).

        Locked when the locking reaction is inside the friction cone, free when N < 0,
        else sliding with sigma = sgn(slip), or -sgn(F_lock) at zero slip.
        """
        s = slip(self.ap, self.contact.kappa_star, y)
        lock = self.rates(y, True, 0.0)
        n_lock, f_lock = lock[3], lock[4]
        stuck = abs(s) <= 1e-12 * self.ap.b / self.ap.tau
        if stuck and n_lock > 0.0 and abs(f_lock) < self.tan_psi_hat * n_lock:
            return self.locked(y)
        sigma = math.copysign(1.0, s) if not stuck else (sigma_hint or -math.copysign(1.0, f_lock))
        if self.rates(y, False, sigma)[3] <= 0.0 and n_lock <= 0.0:
            return self.free(_free_state(self.ap, self.contact, y))
        return self.sliding(y, sigma)

    def touch(self, y_free, phi: float) -> Phase:
        """The impact on touching, then :meth:`enter_contact`."""
        chi = phi - self.ap.alpha
        velocity, omega_a, omega_b, _, _ = impact(self.ap, self.contact, chi, y_free[2:4], y_free[4], y_free[5],
                                                  self.fluid_spin)
        eps = self.contact.kappa_star * self.ap.delta
        chi_dot = (math.cos(chi) * velocity[0] - math.sin(chi) * velocity[1]) / eps
        return self.enter_contact(np.array([chi, chi_dot, omega_a, omega_b, y_free[6]]))

    def transition(self, phase: Phase, reason: str, end, phi: float) -> Phase:
        if phase.name == FREE:
            return self.touch(end, phi)
        y = np.array(end, dtype=float)
        if reason == "lift":
            return self.free(_free_state(self.ap, self.contact, y))
        if reason == "stick":
            eps = self.contact.kappa_star * self.ap.delta
            y[2] = ((self.ap.a + eps) * y[3] - eps * y[1]) / self.ap.a  # slip = 0 exactly
            return self.enter_contact(y, -phase.sigma)
        # the friction bound is reached: slide from zero slip, the way the friction no longer prevents
        return self.sliding(y, -math.copysign(1.0, self.rates(y, True, 0.0)[4]))

    def columns(self, phase: Phase, t, y, kind) -> dict:
        """Scaled columns of one phase's rows (t in tau, rates in 1/tau, X_b in b)."""
        ap, n, tau = self.ap, t.size, self.ap.tau
        if phase.name == FREE:
            obs = full.observables(ap, y, phase.extra["phi0"])
            zeros = np.zeros(n)
            return {"kappa": obs["kappa"], "one_minus_kappa": obs["one_minus_kappa"], "phi": obs["phi"],
                    "kappa_dot": obs["kappa_dot"] * tau, "phi_dot": obs["phi_dot"] * tau,
                    "omega_a": obs["omega_a"] * tau, "omega_b": obs["omega_b"] * tau, "x_b": obs["x_b"] / ap.b,
                    "c_eps": zeros, "c_chi": zeros}
        # rows as contiguous arrays, the layout every other call of the rates has: one compiled version
        locked = phase.name == LOCKED
        forces = np.array([self.rates(row, locked, phase.sigma)[3:] for row in np.array(y.T)]).reshape(n, 2)
        weight = ap.m_a_reduced * ap.g
        return {"kappa": np.full(n, self.contact.kappa_star),
                "one_minus_kappa": np.full(n, self.contact.one_minus_kappa_star), "phi": y[0] + ap.alpha,
                "kappa_dot": np.zeros(n), "phi_dot": y[1] * tau,
                "omega_a": y[2] * tau, "omega_b": y[3] * tau, "x_b": y[4] / ap.b,
                "c_eps": forces[:, 0] / weight, "c_chi": -forces[:, 1] / (ap.delta_over_a * weight)}


def run_full_contact(apparatus, force_model: KernelModel, contact: ContactParams, initial, t_end: float, *,
                     limits: Limits = Limits(), method: str = "radau", rtol: float = 1e-8, t_eval=None, steps=None,
                     max_steps: int = 2_000_000, max_switches: int = MAX_SWITCHES, progress=None,
                     frame_terms: str = full.DEFAULT_FRAME_TERMS, fluid_spin: str = full.DEFAULT_FLUID_SPIN) -> dict:
    """The full model with rough contact from ``initial`` (SI) over ``t_end`` seconds.

    Returns the fields of :func:`numerics.hybrid.run_phases` with times in
    tau and the columns scaled (rates in 1/tau, X_b in b), as
    :mod:`dynamics.simulation` expects; use :func:`dynamics.simulation.simulate` for a
    :class:`~dynamics.simulation.Trajectory`. At kappa = kappa* the run starts as
    on touching.
    """
    run = FullContactRun(apparatus, force_model, contact, limits, rtol, frame_terms, fluid_spin)
    y0 = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                            initial.omega_a, initial.omega_b)
    if initial.kappa >= contact.kappa_star * (1.0 - 1e-14):
        start = run.touch(y0, initial.phi)
    else:
        start = run.free(y0)
    return phases_in_tau(run, start, apparatus.tau, t_end, initial.phi, method=method, rtol=rtol, t_eval=t_eval,
                         steps=steps, max_steps=max_steps, max_switches=max_switches, progress=progress)


def phases_in_tau(run, start, tau: float, t_end: float, phi0: float, **options) -> dict:
    """The phases of a full-model contact ``run`` from ``start`` (:func:`numerics.hybrid.run_phases`, in
    seconds), its times and switches returned in units of ``tau``; ``options`` go to ``run_phases``."""
    fields = run_phases(start, lambda phase, reason, t, end, phi: run.transition(phase, reason, end, phi),
                        run.columns, t_end, phi0=phi0, **options)
    fields["t"] = fields["t"] / tau
    fields["switches"] = tuple(sw._replace(t=sw.t / tau) for sw in fields["switches"])
    return fields


def steady_full_contact(apparatus, force_model: KernelModel, contact: ContactParams, locked: bool,
                        guess) -> np.ndarray:
    """A steadily rolling contact state (chi, Omega_a, Omega_b) of the full model, chi' = 0.

    Solves chi'' = Omega_b' = 0 with, locked, a Omega_a = (a + eps*) Omega_b, or, sliding
    (sigma = sgn(slip)), Omega_a' = 0 too; ``guess`` = (chi, Omega_a, Omega_b) in SI,
    e.g. the reduced fixed point of :func:`dynamics.contact.steady.steady_state`.
    """
    p = full.params_array(apparatus)
    model = full.model_arguments(force_model)
    rates = contact_functions(force_model).rates
    args = (contact.kappa_star, contact.one_minus_kappa_star)
    tan_psi_hat = friction_coefficient(apparatus, contact)
    tau, a = apparatus.tau, apparatus.a
    arm = a + contact.kappa_star * apparatus.delta  # distance from B to the contact point
    guess = np.asarray(guess, dtype=float)
    sigma = math.copysign(1.0, a * guess[1] - arm * guess[2])

    if locked:
        def residual(x):
            y = np.array([x[0], 0.0, arm * x[1] / (a * tau), x[1] / tau])
            r = rates(y, p, *args, True, 0.0, tan_psi_hat, model)
            return [r[0] * tau * tau, r[2] * tau * tau]

        chi, omega_b = _solve(residual, [guess[0], guess[2] * tau])
        return np.array([chi, arm * omega_b / (a * tau), omega_b / tau])

    def residual(x):
        y = np.array([x[0], 0.0, x[1] / tau, x[2] / tau])
        r = rates(y, p, *args, False, sigma, tan_psi_hat, model)
        return [r[0] * tau * tau, r[1] * tau * tau, r[2] * tau * tau]

    chi, omega_a, omega_b = _solve(residual, guess * np.array([1.0, tau, tau]))
    return np.array([chi, omega_a / tau, omega_b / tau])


def _solve(residual, guess) -> np.ndarray:
    """Newton (MINPACK's hybrid method) on the scaled residual, accepted only if it vanishes.

    fsolve's "not making progress" at xtol = 1e-12 means the step cannot shrink
    further in floating point, not that the root was missed: the residual,
    of order one in units of 1/tau^2, decides.
    """
    x, info, _, message = fsolve(residual, guess, xtol=1e-12, full_output=True)
    worst = float(np.max(np.abs(info["fvec"])))
    if not worst <= STEADY_RESIDUAL:
        raise ValueError(f"no steady contact state found near {np.asarray(guess).tolist()}: residual {worst:.1e} "
                         f"(Newton: {message.strip()})")
    return x
