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
accelerations are those of :func:`dynamics.equations.full.rhs` with these forces added,
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

Units. Every phase is integrated in scaled variables, time in tau and the
state over its typical size (:func:`dynamics.equations.full.typical_scales`), so that one
scalar absolute tolerance serves all phases.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import fsolve

from dynamics.contact.reduced import (
    FREE,
    LOCKED,
    SLIDING,
    ContactParams,
    PhaseStart,
    run_phases,
)
from dynamics.equations import full
from dynamics.equations.forces import ForceModel, evaluate
from dynamics.integrate import Event
from lubrication._jit import jit

__all__ = [
    "contact_rates",
    "friction_coefficient",
    "impact",
    "simulate_full_contact",
    "slip",
    "steady_full_contact",
]


def friction_coefficient(apparatus, contact: ContactParams) -> float:
    """The physical friction coefficient tan(psi_hat) = (delta/a) tan(psi) of the paper's scaled psi (C2)."""
    return apparatus.delta_over_a * contact.tan_psi


# -- contact forces and accelerations (jitted) -------------------------------------

@jit
def contact_rates(y, p, kappa_star, omk_star, locked, sigma, tan_psi_hat,
                  profile, sommerfeld, rule, points_per_cell, exact, cavitation):
    """(chi'', Omega_a', Omega_b', N, F) in contact, SI; ``y`` = (chi, chi', Omega_a, Omega_b, ...).

    ``locked`` keeps the slip at zero; otherwise F = -sigma tan(psi_hat) N.
    """
    a, b = p[0], p[1]
    eps = kappa_star * (b - a)
    chi, chi_dot, omega_a, omega_b = y[0], y[1], y[2], y[3]
    ex, ez = math.sin(chi), math.cos(chi)
    cx, cz = ez, -ex
    f_eps, f_chi, t_a = evaluate(profile, sommerfeld, rule, points_per_cell, exact, cavitation, a, b, p[3],
                                 p[2], kappa_star, omk_star, 0.0, omega_a - chi_dot, omega_b - chi_dot)
    fluid = full.force_response(p, eps, ex, ez, f_eps, f_chi, t_a)
    gravity = full.gravity_response(p)
    base = np.empty(4)
    for i in range(4):
        base[i] = fluid[i] + gravity[i]
    normal = full.force_response(p, eps, ex, ez, -1.0, 0.0, 0.0)   # unit N: pushes A towards B
    friction = full.force_response(p, eps, ex, ez, 0.0, 1.0, a)    # unit F along e_chi, torque a F
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


def impact(apparatus, contact: ContactParams, chi: float, velocity, omega_a: float, omega_b: float):
    """Velocities just after a plastic impact at eps = eps* (module docstring).

    Parameters
    ----------
    chi : float
        Direction of the line of centres.
    velocity : array_like, shape (2,)
        r' = (x', z') before the impact (m/s).
    omega_a, omega_b : float
        Rates before (rad/s).

    Returns
    -------
    (velocity, omega_a, omega_b, p_n, p_f)
        After the impact, and the normal and tangential impulses (N s).
    """
    p = full.params_array(apparatus)
    eps = contact.kappa_star * apparatus.delta
    ex, ez = math.sin(chi), math.cos(chi)
    e_eps, e_chi = np.array([ex, ez]), np.array([ez, -ex])
    normal = np.array(full.force_response(p, eps, ex, ez, -1.0, 0.0, 0.0))
    friction = np.array(full.force_response(p, eps, ex, ez, 0.0, 1.0, apparatus.a))
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


# -- the hybrid run ----------------------------------------------------------------

class _Scaled:
    """The full model's phases in scaled variables: time in tau, states over their typical sizes."""

    def __init__(self, apparatus, force_model: ForceModel, contact: ContactParams):
        self.ap, self.contact = apparatus, contact
        self.p = full.params_array(apparatus)
        self.model = full.model_arguments(force_model)
        self.tau = apparatus.tau
        self.free_scale = full.typical_scales(apparatus)
        tau = self.tau
        self.contact_scale = np.array([1.0, 1.0 / tau, 1.0 / tau, 1.0 / tau, apparatus.b])
        self.contact_args = (contact.kappa_star, contact.one_minus_kappa_star)
        self.tan_psi_hat = friction_coefficient(apparatus, contact)
        self.u_star = contact.kappa_star / math.sqrt(contact.one_minus_kappa_star * (1.0 + contact.kappa_star))

    def rates(self, y_si, locked: bool, sigma: float) -> np.ndarray:
        return contact_rates(y_si, self.p, *self.contact_args, locked, sigma, self.tan_psi_hat,
                             *self.model)

    def free_fun(self, t, y):
        scale = self.free_scale
        return self.tau * full.rhs(t * self.tau, y * scale, self.p, *self.model) / scale

    def free_jac(self, t, y):
        scale = self.free_scale
        jac = full.jacobian(t * self.tau, y * scale, self.p, *self.model, scale)
        return self.tau * jac * scale[None, :] / scale[:, None]

    def contact_fun(self, locked: bool, sigma: float):
        scale, tau, b = self.contact_scale, self.tau, self.ap.b

        def fun(t, y):
            y_si = y * scale
            r = self.rates(y_si, locked, sigma)
            return tau * np.array([y_si[1], r[0], r[1], r[2], b * y_si[3]]) / scale

        return fun


def _central_jacobian(fun, t, y):
    """d(fun)/dy by central differences, steps eps^(1/3) max(|y_j|, 1) of an O(1) scaled state."""
    jac = np.empty((y.size, y.size))
    for j in range(y.size):
        h = 6.0554544523933395e-06 * max(abs(y[j]), 1.0)
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        jac[:, j] = (fun(t, yp) - fun(t, ym)) / (2.0 * h)
    return jac


def _enter_contact(sc: _Scaled, y_si, sigma_hint: float = 0.0) -> PhaseStart:
    """Phase on touching (after the impact) or at a switch, for a contact state ``y_si`` (SI).

    Locked when the locking reaction is inside the friction cone, free when N < 0,
    else sliding with sigma = sgn(slip), or -sgn(F_lock) at zero slip.
    """
    scaled = y_si / sc.contact_scale
    s = slip(sc.ap, sc.contact.kappa_star, y_si)
    lock = sc.rates(y_si, True, 0.0)
    n_lock, f_lock = lock[3], lock[4]
    stuck = abs(s) <= 1e-12 * sc.ap.b / sc.tau
    if stuck and n_lock > 0.0 and abs(f_lock) < sc.tan_psi_hat * n_lock:
        return PhaseStart(LOCKED, scaled)
    sigma = math.copysign(1.0, s) if not stuck else (sigma_hint or -math.copysign(1.0, f_lock))
    if sc.rates(y_si, False, sigma)[3] <= 0.0 and n_lock <= 0.0:
        return PhaseStart(FREE, _free_state(sc.ap, sc.contact, y_si) / sc.free_scale)
    return PhaseStart(SLIDING, scaled, sigma)


def _touch(sc: _Scaled, y_free_si, phi: float) -> PhaseStart:
    """The impact on touching, then :func:`_enter_contact`."""
    chi = phi - sc.ap.alpha
    velocity, omega_a, omega_b, _, _ = impact(sc.ap, sc.contact, chi, y_free_si[2:4], y_free_si[4], y_free_si[5])
    eps = sc.contact.kappa_star * sc.ap.delta
    chi_dot = (math.cos(chi) * velocity[0] - math.sin(chi) * velocity[1]) / eps
    return _enter_contact(sc, np.array([chi, chi_dot, omega_a, omega_b, y_free_si[6]]))


def _setup(sc: _Scaled, phase: str, sigma: float, extra_events) -> tuple:
    if phase == FREE:
        touch = Event("touch", lambda t, y: math.hypot(y[0], y[1]) - sc.u_star, 1.0,
                      lambda t: f"contact at t = {t * sc.tau:.6g} s")
        return sc.free_fun, sc.free_jac, (touch, *extra_events(FREE))
    locked = phase == LOCKED
    fun = sc.contact_fun(locked, sigma)
    mu_f = sc.tan_psi_hat

    def reaction(y):
        return sc.rates(y * sc.contact_scale, locked, sigma)

    lift = Event("lift", lambda t, y: reaction(y)[3], -1.0, lambda t: f"lift-off at t = {t * sc.tau:.6g} s")
    events = [lift, *extra_events(phase)]
    if locked:
        for side in (1.0, -1.0):
            events.append(Event("slip", lambda t, y, side=side: mu_f * reaction(y)[3] - side * reaction(y)[4],
                                -1.0, lambda t: f"friction bound reached at t = {t * sc.tau:.6g} s"))
    elif mu_f > 0.0:
        events.append(Event("stick", lambda t, y: sigma * slip(sc.ap, sc.contact.kappa_star, y * sc.contact_scale),
                            -1.0, lambda t: f"slip stops at t = {t * sc.tau:.6g} s"))
    return fun, (lambda t, y: _central_jacobian(fun, t, y)), tuple(events)


def _transition(sc: _Scaled, phase, sigma, reason, end, phi) -> PhaseStart:
    if phase == FREE:
        return _touch(sc, end * sc.free_scale, phi)
    y_si = end * sc.contact_scale
    if reason == "lift":
        return PhaseStart(FREE, _free_state(sc.ap, sc.contact, y_si) / sc.free_scale)
    if reason == "stick":
        eps = sc.contact.kappa_star * sc.ap.delta
        y_si[2] = ((sc.ap.a + eps) * y_si[3] - eps * y_si[1]) / sc.ap.a  # slip = 0 exactly
        return _enter_contact(sc, y_si, -sigma)
    # the friction bound is reached: slide from zero slip, the way the friction no longer prevents
    return PhaseStart(SLIDING, end.copy(), -math.copysign(1.0, sc.rates(y_si, True, 0.0)[4]))


def _columns(sc: _Scaled, phase, sigma, y, t, phi_start) -> dict:
    ap, n = sc.ap, t.size
    if phase == FREE:
        obs = full.observables(ap, y * sc.free_scale[:, None])
        if n:
            turns = 2.0 * math.pi * round((phi_start - obs["phi"][0]) / (2.0 * math.pi))
            obs["phi"], obs["chi"] = obs["phi"] + turns, obs["chi"] + turns
        zeros = np.zeros(n)
        return {**obs, "c_eps": zeros, "c_chi": zeros}
    y_si = y * sc.contact_scale[:, None]
    forces = np.array([sc.rates(y_si[:, i], phase == LOCKED, sigma)[3:] for i in range(n)]).reshape(n, 2)
    weight = ap.m_a_reduced * ap.g
    kappa = sc.contact.kappa_star
    return {"kappa": np.full(n, kappa), "one_minus_kappa": np.full(n, sc.contact.one_minus_kappa_star),
            "eps": np.full(n, kappa * ap.delta), "chi": y_si[0], "phi": y_si[0] + ap.alpha,
            "omega_a": y_si[2], "omega_b": y_si[3], "x_b": y_si[4],
            "c_eps": forces[:, 0] / weight, "c_chi": -forces[:, 1] / (ap.delta_over_a * weight)}


def simulate_full_contact(apparatus, force_model: ForceModel, contact: ContactParams, y0_free: np.ndarray,
                          t_end: float, *, rtol: float = 1e-8, method: str = "LSODA", extra_events=None,
                          max_steps: int = 2_000_000, max_switches: int = 10_000,
                          progress: str | None = None) -> dict:
    """Integrate the full model with rough contact from the free state ``y0_free`` over ``t_end`` seconds.

    ``y0_free`` is a state of :mod:`dynamics.equations.full` (SI) with kappa <= kappa*;
    at kappa* the run starts as on touching. ``extra_events(phase)`` returns
    further terminal events of a phase (scaled state, time in tau). Returns the
    fields of :class:`dynamics.contact.reduced.ContactTrajectory` as
    :func:`dynamics.contact.reduced.run_phases` does, times in seconds.
    """
    sc = _Scaled(apparatus, force_model, contact)
    extra_events = extra_events or (lambda phase: ())
    kappa0 = math.hypot(y0_free[0], y0_free[1]) / math.hypot(1.0, math.hypot(y0_free[0], y0_free[1]))
    phi0 = math.atan2(y0_free[0], y0_free[1]) + apparatus.alpha
    if kappa0 > contact.kappa_star:
        msg = f"the initial kappa = {kappa0:.12g} must be at most kappa_star = {contact.kappa_star:.12g}"
        raise ValueError(msg)
    if kappa0 >= contact.kappa_star * (1.0 - 1e-14):
        start = _touch(sc, y0_free, phi0)
    else:
        start = PhaseStart(FREE, y0_free / sc.free_scale)
    fields = run_phases(
        start, lambda phase, sigma, _: _setup(sc, phase, sigma, extra_events),
        lambda phase, sigma, y, t, phi: _columns(sc, phase, sigma, y, t, phi),
        lambda phase, sigma, reason, end, phi: _transition(sc, phase, sigma, reason, end, phi),
        t_end / sc.tau, phi0, rtol=rtol, atol=rtol, method=method, max_steps=max_steps,
        max_switches=max_switches, progress=progress)
    fields["t_tau"] = fields["t"]
    fields["t"] = fields["t"] * sc.tau
    fields["switches"] = tuple(sw._replace(t=sw.t * sc.tau) for sw in fields["switches"])
    return fields


def steady_full_contact(apparatus, force_model: ForceModel, contact: ContactParams, locked: bool,
                        guess) -> np.ndarray:
    """A steadily rolling contact state (chi, Omega_a, Omega_b) of the full model, chi' = 0.

    Solves chi'' = Omega_b' = 0 with, locked, a Omega_a = (a + eps*) Omega_b, or, sliding
    (sigma = sgn(slip)), Omega_a' = 0 too; ``guess`` = (chi, Omega_a, Omega_b) in SI,
    e.g. the reduced fixed point of :func:`dynamics.contact.steady.steady_state`.
    """
    p = full.params_array(apparatus)
    model = full.model_arguments(force_model)
    args = (contact.kappa_star, contact.one_minus_kappa_star)
    tan_psi_hat = friction_coefficient(apparatus, contact)
    tau, a = apparatus.tau, apparatus.a
    arm = a + contact.kappa_star * apparatus.delta  # distance from B to the contact point
    guess = np.asarray(guess, dtype=float)
    sigma = math.copysign(1.0, a * guess[1] - arm * guess[2])

    if locked:
        def residual(x):
            y = np.array([x[0], 0.0, arm * x[1] / (a * tau), x[1] / tau])
            r = contact_rates(y, p, *args, True, 0.0, tan_psi_hat, *model)
            return [r[0] * tau * tau, r[2] * tau * tau]

        chi, omega_b = fsolve(residual, [guess[0], guess[2] * tau], xtol=1e-12)
        return np.array([chi, arm * omega_b / (a * tau), omega_b / tau])

    def residual(x):
        y = np.array([x[0], 0.0, x[1] / tau, x[2] / tau])
        r = contact_rates(y, p, *args, False, sigma, tan_psi_hat, *model)
        return [r[0] * tau * tau, r[1] * tau * tau, r[2] * tau * tau]

    chi, omega_a, omega_b = fsolve(residual, guess * np.array([1.0, tau, tau]), xtol=1e-12)
    return np.array([chi, omega_a / tau, omega_b / tau])
