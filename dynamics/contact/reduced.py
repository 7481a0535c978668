r"""Rough contact in the reduced model (section 5, Appendix C), as a hybrid system.

Asperities stop the approach of the cylinders at kappa = kappa* < 1,
zeta* = sqrt(1 - kappa*^2). Time is in units of tau, rates in 1/tau, as in
:mod:`dynamics.equations.reduced`, whose right-hand side (2.11) every phase below reuses.

Contact forces and their signs
------------------------------
A contact force C = C_eps e_eps + C_chi e_chi acts on the inner cylinder at the
touching point a e_eps from its centre, e_eps pointing from B to A and e_chi
towards increasing chi (clockwise); -C acts on B (C1). Dropping what (2.11a)
drops (radial inertia, the O(delta/a) rolling term), the radial balance (2.2)
is 0 = f_eps - m'_a g cos(phi) + C_eps with f_eps = -m'_a g kappa'/zeta^3 ((2.5) in units of tau). Hence

    (5.1)  kappa'/zeta^3 = -cos(phi) + C_eps/(m'_a g),

and in contact (kappa' = 0) the scaled reaction, positive when it pushes A
back towards B, is C_e = -C_eps/(m'_a g) = -cos(phi): the wall can only push,
so contact needs C_e >= 0, cos(phi) <= 0 (the centre of A at or below that
of B). (C2) prints C_e = -C_eps/(a m'_a g); the
extra a is dimensionally wrong. The torque a C_chi on A enters (C1); in units
of m'_a g delta, the unit of the torque T of (2.11c) (T_a = m'_a g delta T),

    (1/2) Upsilon Omega_a' = T + a C_chi/(delta m'_a g) = T - C_x,
    C_x = -(a/delta) C_chi/(m'_a g),

which is (5.2) with the paper's C_x: minus the physical friction, O(1) when
tan(psi_hat) ~ delta/a. (C2) prints C_x = delta C_chi/(m'_a g); only the form
above is O(1) and gives the Coulomb bound |C_chi| <= |C_eps| tan(psi_hat)
as |C_x| <= C_e tan(psi), tan(psi) = (a/delta) tan(psi_hat) (5.3), (C2).
Friction is O(delta/a) against f_chi, so (2.11b) is unchanged; C and -C act
at one point, so the total angular momentum balance (2.11d) is unchanged.

Phases
------
With W = (Omega_a + Omega_b)/2, D = Omega_b - Omega_a and
A* = (2 + kappa*^2) zeta* / (2 kappa*):

free (kappa < kappa*)
    (2.11a-d) exactly as in :mod:`dynamics.equations.reduced`, integrated in the
    stretched variables (xi, eta, Omega_a, Omega_b, X_b).

contact (kappa = kappa*): state (phi, Omega_a, Omega_b, X_b), C_e = -cos(phi),

    (2.11b)  phi'                  = W + A* sin(phi)
    (5.2)    (1/2) Upsilon Omega_a' = T - C_x,   T = D/(6 zeta*) + (kappa*/2) sin(phi)
    (2.11d)  mu_ Upsilon Omega_b'  = s + kappa* sin(phi) - (1/2) Upsilon Omega_a'
             X_b'                  = Omega_b

    (T is (2.11c)'s torque with phi' from (2.11b), see :mod:`dynamics.equations.reduced`).
    The right-hand side is that of :func:`dynamics.equations.reduced.reduced_rhs` on the
    circle r = r* = kappa*/zeta*, its radial part discarded (the reaction
    holds r fixed) and the friction added.

sliding
    C_x = sigma tan(psi) cos(phi), sigma = sgn(D) (5.2): |C_x| = C_e tan(psi)
    and, with cos(phi) < 0, the friction drags Omega_a and Omega_b together.
    sigma is a constant of the phase, not re-evaluated from the state, so the
    right-hand side is smooth within the phase.

locked (Omega_a = Omega_b = Omega)
    (2.11d)  (mu_ + 1/2) Upsilon Omega' = s + kappa* sin(phi),
    (2.11b)  phi' = Omega + A* sin(phi),
    and (5.2) becomes the diagnostic for the friction that keeps D = 0: with
    D = 0, T = (kappa*/2) sin(phi), and

    (5.4)  C_lock = T - (1/2) Upsilon Omega'
                  = -(2 s + (1 - 2 mu_) kappa* sin(phi)) / (2 (1 + 2 mu_)).

    It holds while (5.5) |C_lock| < C_e tan(psi) = |cos(phi)| tan(psi).

Switching (guards and resets)
-----------------------------
* free -> contact when r = r* (kappa = kappa*, r increasing: cos(phi) < 0),
  an event located by ``brentq`` on the dense output. Then locked if (5.5)
  holds, Omega_a jumping to Omega_b (below); sliding otherwise, with
  sigma = sgn(D).
* sliding -> locked when D reaches 0 and (5.5) holds there (no jump: D = 0).
  If (5.5) fails, sliding goes on with the opposite sigma.
* locked -> sliding when |C_lock| reaches C_e tan(psi), with
  sigma = -sgn(C_lock).
* contact -> free when cos(phi) rises through 0: beyond, the reaction
  C_e = -cos(phi) would have to pull. At that instant the free (2.11a) gives
  kappa' = -zeta^3 cos(phi) = 0, then negative: the cylinders separate.

The jump on locking. With D != 0 at first contact and (5.5) satisfied, the
locked constraint D = 0 can only be met by a jump. The paper's model
(section 5) keeps Omega_b and lets Omega_a jump to it, "an instantaneous
impulse that affects the inner cylinder", the opposite impulse on the outer
cylinder being "taken up by the other contact" (the plane). That is what is
implemented. It does not conserve the angular momentum of (2.11d),
L = Upsilon (mu_ Omega_b + Omega_a/2), which jumps by (1/2) Upsilon D; an
impulsive friction between the cylinders alone (no torque from the plane
about its own contact point) would conserve L and give both cylinders
Omega = (mu_ Omega_b + Omega_a/2)/(mu_ + 1/2) instead. The steady states do
not depend on this choice.

Why sigma = -sgn(C_lock) when sliding starts from D = 0. In sliding, at D = 0,
(5.2) and (2.11d) give

    D' = (1 + 2 mu_)/(mu_ Upsilon) (C_x - C_lock),

so with C_x = -sigma C_e tan(psi) and |C_lock| > C_e tan(psi), D moves
away from 0 with the sign sigma only for sigma = -sgn(C_lock): the one
consistent (Filippov) choice.

No chattering. Each phase has a smooth right-hand side; its guards are
terminal events located on the dense output, never by stepping past them;
every reset is chosen so that the new phase moves off the switching surface
it starts on (the D' above; (5.5) is strict), and a directional event that
starts at zero cannot fire on the first step of its phase. Switches are exact
and without hysteresis or regularisation, so the step size never collapses on
a discontinuity. With psi = 0 the friction vanishes and D = 0 is no event at
all. A run that still switched more than ``max_switches`` times would stop
with that reason rather than hang.

The steady rolling states are in :mod:`dynamics.contact.steady`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from dynamics.equations import reduced
from dynamics.equations.limits import MAX_TURNS, runaway_event
from dynamics.equations.reduced import (
    ReducedParams,
    ReducedTrajectory,
    initial_state,
    reduced_jacobian,
    reduced_rhs,
    stretched_to_kappa,
)
from dynamics.integrate import Event, integrate
from lubrication._jit import jit
from lubrication.geometry import check_finite, check_range

__all__ = [
    "FREE",
    "LOCKED",
    "SLIDING",
    "ContactParams",
    "ContactTrajectory",
    "PhaseStart",
    "Switch",
    "free_columns",
    "locked_friction",
    "locked_jacobian",
    "locked_rhs",
    "run_phases",
    "simulate_contact",
    "sliding_jacobian",
    "sliding_rhs",
]

FREE, SLIDING, LOCKED = "free", "sliding", "locked"
_SWITCHES = ("touch", "lift", "stick", "slip")  # the events that end a phase, not the run

# A hybrid run that switched this often is caught in a pathological cycle; it
# stops with that reason. Figure 7's run switches once, runs near the onset of
# sliding (stick-slip while rocking) some 20 times.
MAX_SWITCHES = 10_000


@dataclass(frozen=True)
class ContactParams:
    """Rough contact of section 5.

    Parameters
    ----------
    kappa_star : float
        Eccentricity at which the asperities touch, 1 - sigma/delta, in (0, 1).
    psi : float
        Scaled friction angle (rad), tan(psi) = (a/delta) tan(psi_hat) (C2),
        in [0, pi/2).
    """

    kappa_star: float
    psi: float

    def __post_init__(self):
        object.__setattr__(self, "kappa_star", check_range("kappa_star", self.kappa_star, 0.0, 1.0,
                                                           low_open=True))
        object.__setattr__(self, "psi", check_range("psi", self.psi, 0.0, 0.5 * math.pi, unit="rad"))

    @property
    def one_minus_kappa_star(self) -> float:
        """1 - kappa* = sigma/delta, exact in floating point for kappa* >= 1/2."""
        return 1.0 - self.kappa_star

    @property
    def zeta_star(self) -> float:
        """zeta* = sqrt(1 - kappa*^2), without cancellation near 1."""
        return math.sqrt((1.0 - self.kappa_star) * (1.0 + self.kappa_star))

    @property
    def r_star(self) -> float:
        """Stretched radius r* = kappa*/zeta* of :mod:`dynamics.equations.reduced` at contact."""
        return self.kappa_star / self.zeta_star

    @property
    def tan_psi(self) -> float:
        """tan(psi), the bound on |C_x|/C_e (5.3)."""
        return math.tan(self.psi)


class Switch(NamedTuple):
    """A change of phase at time ``t`` (units of tau)."""

    t: float
    old: str
    new: str


@dataclass(frozen=True, kw_only=True)
class ContactTrajectory(ReducedTrajectory):
    """A hybrid solution: the columns of :class:`dynamics.equations.reduced.ReducedTrajectory` and more.

    Every switching time appears twice: the state just before the switch
    (labelled with the old phase) and just after (the new phase), so that the
    jump of Omega_a on locking is resolved; ``t`` is non-decreasing. In contact
    kappa = kappa* exactly; ``nfev``, ``njev``, ``steps`` are totals over all
    phases, and ``stop_reason`` may also be ``"max_switches"``.

    Attributes
    ----------
    phase : ndarray of str, shape (n,)
        "free", "sliding" or "locked".
    c_eps, c_chi : ndarray, shape (n,)
        Scaled reaction C_e = -cos(phi) (>= 0) and friction C_x of (5.2);
        zero when free.
    switches : tuple of Switch
    """

    phase: np.ndarray
    c_eps: np.ndarray
    c_chi: np.ndarray
    switches: tuple[Switch, ...]


# -- the contact phases -------------------------------------------------------------

def locked_friction(params: ReducedParams, kappa_star: float, phi):
    """Friction C_x that keeps the cylinders locked (5.4), derived in the module docstring."""
    return -(2.0 * params.s + (1.0 - 2.0 * params.mu_ratio) * kappa_star * np.sin(phi)) / (
        2.0 * (1.0 + 2.0 * params.mu_ratio))


@jit(inline="always")
def _on_circle(phi, omega_a, omega_b, x_b, r_star):
    """The state of :mod:`dynamics.equations.reduced` at kappa = kappa*, for its right-hand side."""
    z = np.empty(5)
    z[0] = r_star * math.sin(phi)
    z[1] = r_star * math.cos(phi)
    z[2] = omega_a
    z[3] = omega_b
    z[4] = x_b
    return z


@jit(inline="always")
def _tangential(z, f, r_star):
    """phi' from the stretched rates f = (xi', eta', ...) at z: the (2.11b) part, radial part dropped."""
    return (z[1] * f[0] - z[0] * f[1]) / (r_star * r_star)


@jit(inline="always")
def _tangential_row(z, f, jac5, dz, r_star):
    """d(phi')/d(state) for phi' = (eta xi' - xi eta')/r*^2, dz = dz/d(state) with phi first."""
    row = (z[1] * (jac5[0] @ dz) - z[0] * (jac5[1] @ dz)) / (r_star * r_star)
    row[0] -= (z[0] * f[0] + z[1] * f[1]) / (r_star * r_star)  # from d(eta, -xi)/d phi
    return row


@jit(inline="always")
def _circle_tangent(z, n, rate_columns):
    """dz/d(state) (5 x n): phi turns (xi, eta) along (eta, -xi); rate_columns[i] is the state column of z[2 + i]."""
    dz = np.zeros((5, n))
    dz[0, 0] = z[1]
    dz[1, 0] = -z[0]
    for i in range(3):
        dz[2 + i, rate_columns[i]] = 1.0
    return dz


# The args of the contact phases: the groups of (2.11), then the contact's numbers.
#   (s, Upsilon, mu_, r*, tan(psi), sigma, kappa*)
_R_STAR, _TAN_PSI, _SIGMA, _KAPPA_STAR = 3, 4, 5, 6


@jit
def sliding_rhs(t, y, args):
    """Sliding contact: (2.11b), (5.2) with C_x = sigma tan(psi) cos(phi), (2.11d).

    ``y`` = (phi, Omega_a, Omega_b, X_b); ``args[5]`` is sigma = sgn(Omega_b - Omega_a)
    of the phase (0 when psi = 0).
    """
    r_star = args[_R_STAR]
    z = _on_circle(y[0], y[1], y[2], y[3], r_star)
    f = reduced.rhs(t, z, args)
    c_x = args[_SIGMA] * args[_TAN_PSI] * math.cos(y[0])
    ups, mu_ = args[1], args[2]
    out = np.empty(4)
    out[0] = _tangential(z, f, r_star)
    out[1] = f[2] - 2.0 * c_x / ups
    out[2] = f[3] + c_x / (mu_ * ups)
    out[3] = f[4]
    return out


@jit
def sliding_jacobian(t, y, args):
    """Analytic Jacobian of :func:`sliding_rhs` (chain rule through the reduced Jacobian)."""
    r_star = args[_R_STAR]
    z = _on_circle(y[0], y[1], y[2], y[3], r_star)
    f = reduced.rhs(t, z, args)
    jac5 = reduced.jacobian(t, z, args)
    dz = _circle_tangent(z, 4, np.array([1, 2, 3]))
    jac = np.empty((4, 4))
    jac[0] = _tangential_row(z, f, jac5, dz, r_star)
    jac[1:] = jac5[2:] @ dz
    dc_x = -args[_SIGMA] * args[_TAN_PSI] * math.sin(y[0])
    jac[1, 0] -= 2.0 * dc_x / args[1]
    jac[2, 0] += dc_x / (args[2] * args[1])
    return jac


@jit
def locked_rhs(t, y, args):
    """Locked contact: (2.11b) and (2.11d) with Omega_a = Omega_b; ``y`` = (phi, Omega, X_b).

    (mu_ + 1/2) Upsilon Omega' = mu_ Upsilon Omega_b' + (1/2) Upsilon Omega_a'
    of the reduced right-hand side, which no contact force enters.
    """
    r_star = args[_R_STAR]
    z = _on_circle(y[0], y[1], y[1], y[2], r_star)
    f = reduced.rhs(t, z, args)
    mu_ = args[2]
    out = np.empty(3)
    out[0] = _tangential(z, f, r_star)
    out[1] = (mu_ * f[3] + 0.5 * f[2]) / (mu_ + 0.5)
    out[2] = f[4]
    return out


@jit
def locked_jacobian(t, y, args):
    """Analytic Jacobian of :func:`locked_rhs`."""
    r_star = args[_R_STAR]
    z = _on_circle(y[0], y[1], y[1], y[2], r_star)
    f = reduced.rhs(t, z, args)
    jac5 = reduced.jacobian(t, z, args)
    dz = _circle_tangent(z, 3, np.array([1, 1, 2]))
    mu_ = args[2]
    jac = np.empty((3, 3))
    jac[0] = _tangential_row(z, f, jac5, dz, r_star)
    jac[1] = (mu_ * jac5[3] + 0.5 * jac5[2]) @ dz / (mu_ + 0.5)
    jac[2] = jac5[4] @ dz
    return jac


def phase_args(params: ReducedParams, contact: ContactParams, sigma: float = 0.0) -> tuple:
    """The compiled phases' args: (s, Upsilon, mu_, r*, tan(psi), sigma, kappa*)."""
    return (*params.args, contact.r_star, contact.tan_psi, float(sigma), contact.kappa_star)


# -- the hybrid driver --------------------------------------------------------------

class PhaseStart(NamedTuple):
    """Where a phase of :func:`run_phases` starts.

    Attributes
    ----------
    phase : str
        "free", "sliding" or "locked".
    y : ndarray
        Initial state of the phase.
    sigma : float
        Sign of the sliding friction, 0 when not sliding.
    on_constraint : bool
        The phase starts where its guard is zero; handed to ``setup``.
    switch : bool
        Record the change as a :class:`Switch`; False restarts the same phase
        without one.
    """

    phase: str
    y: np.ndarray
    sigma: float = 0.0
    on_constraint: bool = False
    switch: bool = True


def run_phases(start: PhaseStart, setup, columns, transition, t_end: float, phi0: float, *,
               rtol: float, atol: float, method: str, max_steps: int, max_switches: int,
               progress: str | None) -> dict:
    """Integrate a hybrid free/sliding/locked system phase by phase, from t = 0 to ``t_end``.

    Each phase is integrated until ``t_end`` or a terminal event. An event
    named "touch", "lift", "stick" or "slip" ends the phase and ``transition``
    chooses the next one; any other stop ends the run.

    Parameters
    ----------
    start : PhaseStart
        The first phase.
    setup : callable
        ``setup(phase, sigma, on_constraint) -> (fun, jac, events)`` for
        :func:`dynamics.integrate.integrate`.
    columns : callable
        ``columns(phase, sigma, y, t, phi_start) -> dict`` of output columns of
        one phase's samples (state ``y``, shape (n_state, n)), with a "phi"
        column continuing from ``phi_start``.
    transition : callable
        ``transition(phase, sigma, reason, y_end, phi_end) -> PhaseStart``: the
        next phase after the event ``reason`` at the final state ``y_end``.
    t_end : float
        Final time in units of tau.
    phi0 : float
        Initial angle, the ``phi_start`` of the first phase.
    rtol, atol, method, max_steps, max_switches, progress
        As for :func:`simulate_contact`.

    Returns
    -------
    dict
        The fields of :class:`ContactTrajectory`: ``t``, ``phase``,
        ``switches``, the status, the totals and the concatenated columns.

    Raises
    ------
    ValueError
        For out-of-range tolerances or an unknown method.
    """
    check_range("rtol", rtol, 0.0, 1.0, low_open=True)
    check_range("atol", atol, 0.0, math.inf, low_open=True)
    if method not in ("Radau", "BDF", "LSODA"):
        msg = f"method must be one of 'Radau', 'BDF', 'LSODA', got {method!r}"
        raise ValueError(msg)
    phase, y, sigma, on_constraint, _ = start
    t0, phi_now = 0.0, phi0
    pieces, switches = [], []
    totals = {"nfev": 0, "njev": 0, "steps": 0, "wall": 0.0}
    while True:
        fun, jac, events = setup(phase, sigma, on_constraint)
        run = integrate(fun, y, t_end - t0, jac=jac, rtol=rtol, atol=atol, method=method, events=events,
                        max_steps=max(max_steps - totals["steps"], 1), progress=progress)
        for key, value in (("nfev", run.nfev), ("njev", run.njev), ("steps", run.steps),
                           ("wall", run.wall_time_s)):
            totals[key] += value
        cols = columns(phase, sigma, run.y, run.t, phi_now)
        pieces.append((t0 + run.t, np.full(run.t.size, phase), cols))
        status = {"completed": 0, "stopped": 1}.get(run.status, -1)
        stop_reason = {"completed": "t_end", "stopped": run.event}.get(run.status, run.status)
        message = run.reason if status else f"reached t_end = {t_end:.6g}"
        if stop_reason == "max_steps":
            message = f"more than max_steps = {max_steps} steps by t = {t0 + float(run.t[-1]):.6g}"
        if stop_reason not in _SWITCHES:
            break
        t_switch = t0 + float(run.t[-1])
        if t_switch >= t_end:  # a switch exactly at t_end ends the run
            status, stop_reason, message = 0, "t_end", f"reached t_end = {t_end:.6g}"
            break
        if len(switches) >= max_switches:
            stop_reason = "max_switches"
            message = f"more than max_switches = {max_switches} phase switches by t = {t_switch:.6g}"
            break
        phi_now, t0, old = float(cols["phi"][-1]), t_switch, phase
        phase, y, sigma, on_constraint, switch = transition(old, sigma, stop_reason, run.y[:, -1], phi_now)
        if switch:
            switches.append(Switch(t0, old, phase))

    merged = {name: np.concatenate([p[2][name] for p in pieces]) for name in pieces[0][2]}
    return dict(t=np.concatenate([p[0] for p in pieces]), phase=np.concatenate([p[1] for p in pieces]),
                switches=tuple(switches), status=status, stop_reason=stop_reason, message=message,
                nfev=totals["nfev"], njev=totals["njev"], steps=totals["steps"], wall_time_s=totals["wall"],
                **merged)


def _enter_contact(params, contact, phi, omega_a, omega_b, x_b) -> PhaseStart:
    """Phase and state on touching, or on leaving a phase at D = 0 or at the friction bound.

    Locked if (5.5) holds (Omega_a jumps to Omega_b, the paper's rule); else
    sliding with sigma = sgn(D), or -sgn(C_lock) when D = 0 (module docstring).
    """
    bound = -math.cos(phi) * contact.tan_psi
    c_lock = locked_friction(params, contact.kappa_star, phi)
    if abs(c_lock) < bound:
        return PhaseStart(LOCKED, np.array([phi, omega_b, x_b]))
    if contact.tan_psi == 0.0:
        sigma = 0.0
    elif omega_b != omega_a:
        sigma = math.copysign(1.0, omega_b - omega_a)
    else:
        sigma = -math.copysign(1.0, c_lock)
    return PhaseStart(SLIDING, np.array([phi, omega_a, omega_b, x_b]), sigma)


def _transition(phase, sigma, reason, end, phi, params, contact) -> PhaseStart:
    """The phase after the switch ``reason`` from ``phase`` at the final state ``end`` (module docstring)."""
    if reason == "lift":  # a locked state carries one rate, (phi, Omega, X_b)
        rates = (end[1], end[1], end[2]) if phase == LOCKED else (end[1], end[2], end[3])
        return PhaseStart(FREE, _on_circle(phi, *rates, contact.r_star))
    if phase == FREE:
        return _enter_contact(params, contact, phi, end[2], end[3], end[4])
    if phase == SLIDING:  # D = 0: lock if (5.5) holds, else slide the other way
        return _enter_contact(params, contact, end[0], end[2], end[2], end[3])
    # the friction bound is reached: slide, from D = 0
    return PhaseStart(SLIDING, np.array([end[0], end[1], end[1], end[2]]),
                      -math.copysign(1.0, locked_friction(params, contact.kappa_star, end[0])))


def _phase_setup(phase, sigma, params, contact, x_b0, max_turns):
    """Right-hand side, Jacobian and the terminal events of one phase."""
    r_star, tan_psi = contact.r_star, contact.tan_psi
    xb = {FREE: 4, SLIDING: 3, LOCKED: 2}[phase]
    runaway = runaway_event(lambda y: y[xb] - x_b0, max_turns)
    if phase == FREE:
        touch = Event("touch", lambda t, y: math.hypot(y[0], y[1]) - r_star, 1.0,
                      lambda t: f"contact at t = {t:.6g}")
        return (lambda t, y: reduced_rhs(t, y, params), lambda t, y: reduced_jacobian(t, y, params),
                (touch, runaway))
    # Beyond cos(phi) = 0 the reaction -cos(phi) would have to pull.
    lift = Event("lift", lambda t, y: math.cos(y[0]), 1.0, lambda t: f"lift-off at t = {t:.6g}")
    if phase == SLIDING:
        events = (lift, runaway)
        if tan_psi > 0.0:
            events += (Event("stick", lambda t, y: sigma * (y[2] - y[1]), -1.0,
                             lambda t: f"Omega_a = Omega_b at t = {t:.6g}"),)
        args = phase_args(params, contact, sigma)
        return (lambda t, y: sliding_rhs(t, y, args), lambda t, y: sliding_jacobian(t, y, args), events)

    def slip(side):
        return Event("slip", lambda t, y: -math.cos(y[0]) * tan_psi
                     - side * locked_friction(params, contact.kappa_star, y[0]), -1.0,
                     lambda t: f"friction bound (5.5) reached at t = {t:.6g}")

    args = phase_args(params, contact)
    return (lambda t, y: locked_rhs(t, y, args), lambda t, y: locked_jacobian(t, y, args),
            (lift, runaway, slip(1.0), slip(-1.0)))


def free_columns(y, t, phi_start: float) -> dict:
    """Output columns of free-flight samples, y = (xi, eta, Omega_a, Omega_b, X_b, ...) of shape (n_state, n).

    phi is unwrapped and continues from ``phi_start``; C_e = C_x = 0.
    """
    n = t.size
    r = np.hypot(y[0], y[1])
    kappa, omk = stretched_to_kappa(r)
    phi = np.unwrap(np.where(r > 0.0, np.arctan2(y[0], y[1]), phi_start))
    if n:
        phi += 2.0 * math.pi * round((phi_start - phi[0]) / (2.0 * math.pi))
    zeros = np.zeros(n)
    return dict(kappa=kappa, one_minus_kappa=omk, phi=phi, omega_a=y[2], omega_b=y[3],
                x_b=y[4], c_eps=zeros, c_chi=zeros)


def _columns(phase, sigma, y, t, phi_start, params, contact):
    """Output columns of one phase's samples (state y, shape (n_state, n))."""
    if phase == FREE:
        return free_columns(y, t, phi_start)
    n = t.size
    phi = y[0]
    cos = np.cos(phi)
    if phase == SLIDING:
        rates = dict(omega_a=y[1], omega_b=y[2], x_b=y[3], c_chi=sigma * contact.tan_psi * cos)
    else:
        rates = dict(omega_a=y[1], omega_b=y[1], x_b=y[2],
                     c_chi=locked_friction(params, contact.kappa_star, phi))
    return dict(kappa=np.full(n, contact.kappa_star), one_minus_kappa=np.full(n, contact.one_minus_kappa_star),
                phi=phi, c_eps=-cos, **rates)


def simulate_contact(params: ReducedParams, contact: ContactParams, t_end: float, kappa0: float,
                     phi0: float, omega_a0: float = 0.0, omega_b0: float = 0.0, x_b0: float = 0.0, *,
                     rtol: float = 1e-8, atol: float = 1e-10, method: str = "LSODA",
                     max_turns: float = MAX_TURNS, max_steps: int = 2_000_000,
                     max_switches: int = MAX_SWITCHES, progress: str | None = None) -> ContactTrajectory:
    """Integrate the reduced model with rough contact from t = 0 to ``t_end`` (units of tau).

    Parameters
    ----------
    params : ReducedParams
    contact : ContactParams
    t_end : float
        Final time in units of tau, positive.
    kappa0 : float
        Initial eccentricity in [0, kappa*]. At kappa* with cos(phi0) < 0 the
        run starts in contact (locked or sliding as on touching).
    phi0, omega_a0, omega_b0, x_b0 : float
        Initial angle from the upward vertical (rad), rates (1/tau), position (b).
    rtol, atol : float
        Tolerances of every phase's integration.
    method : {"Radau", "BDF", "LSODA"}
        Implicit scipy solver; analytic Jacobians are supplied.
    max_turns : float
        Stop, as a runaway, after this many turns of the outer cylinder.
    max_steps, max_switches : int
        Budgets of accepted steps (all phases) and of phase switches; a run
        that exceeds either stops and says so.
    progress : str, optional
        Label of a progress bar shown on a terminal, one bar per phase.

    Returns
    -------
    ContactTrajectory

    Raises
    ------
    ValueError
        For out-of-range arguments.
    """
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True)
    kappa0 = check_range("kappa0", kappa0, 0.0, contact.kappa_star, high_open=False)
    phi0 = check_finite("phi0", phi0)
    max_turns = check_range("max_turns", max_turns, 0.0, math.inf, low_open=True)
    omega_a0, omega_b0, x_b0 = (check_finite(k, v) for k, v in
                                (("omega_a0", omega_a0), ("omega_b0", omega_b0), ("x_b0", x_b0)))

    if kappa0 == contact.kappa_star and math.cos(phi0) < 0.0:
        start = _enter_contact(params, contact, phi0, omega_a0, omega_b0, x_b0)
    else:
        start = PhaseStart(FREE, initial_state(kappa0, phi0, omega_a0, omega_b0, x_b0))
    fields = run_phases(
        start, lambda phase, sigma, _: _phase_setup(phase, sigma, params, contact, x_b0, max_turns),
        lambda phase, sigma, y, t, phi: _columns(phase, sigma, y, t, phi, params, contact),
        lambda phase, sigma, reason, end, phi: _transition(phase, sigma, reason, end, phi, params, contact),
        t_end, phi0, rtol=rtol, atol=atol, method=method, max_steps=max_steps, max_switches=max_switches,
        progress=progress)
    return ContactTrajectory(**fields)
