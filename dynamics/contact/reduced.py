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

import numpy as np

from dynamics.equations import reduced
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import (
    ReducedParams,
    initial_state,
)
from lubrication.geometry import check_finite, check_range
from numerics.hybrid import MAX_SWITCHES, Phase, run_phases
from numerics.jit import jit

__all__ = [
    "FREE",
    "LOCKED",
    "LOCKED_EVENTS",
    "SLIDING",
    "SLIDING_EVENTS",
    "ContactParams",
    "ReducedContactRun",
    "locked_events",
    "locked_friction",
    "locked_jacobian",
    "locked_rhs",
    "on_circle",
    "phase_args",
    "sliding_events",
    "sliding_jacobian",
    "sliding_rhs",
    "tangential_rate",
]

FREE, SLIDING, LOCKED = "free", "sliding", "locked"


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

    @classmethod
    def from_device(cls, apparatus, *, sigma: float, friction_angle: float) -> ContactParams:
        """The contact of ``apparatus`` from what one measures: the asperities' gap ``sigma`` (m, in (0, delta))
        and the physical friction angle psi_hat (rad, in [0, pi/2)), tan(psi) = (a/delta) tan(psi_hat) (C2)."""
        delta = apparatus.delta
        sigma = check_range("sigma", sigma, 0.0, delta, low_open=True, unit=f"m (the gap delta = {delta:g} m)")
        friction_angle = check_range("friction_angle", friction_angle, 0.0, 0.5 * math.pi, unit="rad")
        return cls(1.0 - sigma / delta, math.atan(math.tan(friction_angle) / apparatus.delta_over_a))

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


# -- the contact phases -------------------------------------------------------------

def locked_friction(params: ReducedParams, kappa_star: float, phi):
    """Friction C_x that keeps the cylinders locked (5.4), derived in the module docstring."""
    return -(2.0 * params.s + (1.0 - 2.0 * params.mu_ratio) * kappa_star * np.sin(phi)) / (
        2.0 * (1.0 + 2.0 * params.mu_ratio))


@jit(inline="always")
def on_circle(phi, omega_a, omega_b, x_b, r_star):
    """The state of :mod:`dynamics.equations.reduced` at kappa = kappa*, for its right-hand side."""
    z = np.empty(5)
    z[0] = r_star * math.sin(phi)
    z[1] = r_star * math.cos(phi)
    z[2] = omega_a
    z[3] = omega_b
    z[4] = x_b
    return z


@jit(inline="always")
def tangential_rate(z, f, r_star):
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
    z = on_circle(y[0], y[1], y[2], y[3], r_star)
    f = reduced.rhs(t, z, args)
    c_x = args[_SIGMA] * args[_TAN_PSI] * math.cos(y[0])
    ups, mu_ = args[1], args[2]
    out = np.empty(4)
    out[0] = tangential_rate(z, f, r_star)
    out[1] = f[2] - 2.0 * c_x / ups
    out[2] = f[3] + c_x / (mu_ * ups)
    out[3] = f[4]
    return out


@jit
def sliding_jacobian(t, y, args):
    """Analytic Jacobian of :func:`sliding_rhs` (chain rule through the reduced Jacobian)."""
    r_star = args[_R_STAR]
    z = on_circle(y[0], y[1], y[2], y[3], r_star)
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
    z = on_circle(y[0], y[1], y[1], y[2], r_star)
    f = reduced.rhs(t, z, args)
    mu_ = args[2]
    out = np.empty(3)
    out[0] = tangential_rate(z, f, r_star)
    out[1] = (mu_ * f[3] + 0.5 * f[2]) / (mu_ + 0.5)
    out[2] = f[4]
    return out


@jit
def locked_jacobian(t, y, args):
    """Analytic Jacobian of :func:`locked_rhs`."""
    r_star = args[_R_STAR]
    z = on_circle(y[0], y[1], y[1], y[2], r_star)
    f = reduced.rhs(t, z, args)
    jac5 = reduced.jacobian(t, z, args)
    dz = _circle_tangent(z, 3, np.array([1, 1, 2]))
    mu_ = args[2]
    jac = np.empty((3, 3))
    jac[0] = _tangential_row(z, f, jac5, dz, r_star)
    jac[1] = (mu_ * jac5[3] + 0.5 * jac5[2]) @ dz / (mu_ + 0.5)
    jac[2] = jac5[4] @ dz
    return jac


def phase_args(params: ReducedParams, contact: ContactParams, sigma: float = 0.0) -> np.ndarray:
    """The compiled phases' args: (s, Upsilon, mu_, r*, tan(psi), sigma, kappa*)."""
    return np.array([*params.args, contact.r_star, contact.tan_psi, sigma, contact.kappa_star], dtype=float)


# -- the phases as the hybrid driver runs them ------------------------------------------

#: Event components of the contact phases, in order (:func:`sliding_events`, :func:`locked_events`).
SLIDING_EVENTS = ("runaway", "lift", "stick")
LOCKED_EVENTS = ("runaway", "lift", "slip", "slip")
# args of the contact phases after phase_args: the runaway's limit and origin of X_b
_XB_LIMIT, _XB0 = 7, 8


@jit(inline="always")
def _locked_friction(args, phi):
    """(5.4) from the phase's args."""
    s, mu_ = args[0], args[2]
    return -(2.0 * s + (1.0 - 2.0 * mu_) * args[_KAPPA_STAR] * math.sin(phi)) / (2.0 * (1.0 + 2.0 * mu_))


@jit
def sliding_events(t, y, args):
    """:data:`SLIDING_EVENTS`: the runaway, lift-off (cos(phi) rising through 0), stick (D reaching 0)."""
    g = np.empty(3)
    g[0] = args[_XB_LIMIT] - abs(y[3] - args[_XB0])
    g[1] = math.cos(y[0])
    g[2] = args[_SIGMA] * (y[2] - y[1])
    return g


@jit
def locked_events(t, y, args):
    """:data:`LOCKED_EVENTS`: the runaway, lift-off, and the friction bound (5.5) on either side."""
    bound = -math.cos(y[0]) * args[_TAN_PSI]
    c_lock = _locked_friction(args, y[0])
    g = np.empty(4)
    g[0] = args[_XB_LIMIT] - abs(y[2] - args[_XB0])
    g[1] = math.cos(y[0])
    g[2] = bound - c_lock
    g[3] = bound + c_lock
    return g


class ReducedContactRun:
    """What the phases of one reduced contact run share: groups, contact, limits, tolerances."""

    def __init__(self, params: ReducedParams, contact: ContactParams, limits: Limits, rtol: float, x_b0: float):
        self.params, self.contact, self.limits = params, contact, limits
        self.atol = rtol  # every component is O(1) in these units
        self.x_b_limit = 2.0 * math.pi * limits.max_turns
        self.free_args = reduced.run_args(params, gap_floor=limits.gap_floor, x_b_limit=self.x_b_limit,
                                          x_b0=x_b0, r_star=contact.r_star)
        self.x_b0 = x_b0

    def args(self, sigma: float = 0.0) -> np.ndarray:
        return np.append(phase_args(self.params, self.contact, sigma), [self.x_b_limit, self.x_b0])

    def free(self, y) -> Phase:
        # the touch ends the phase; the gap floor cannot be reached below kappa*; turns are recorded
        terminal = (int(self.limits.stops), 0, 1, 0, 1)
        return Phase(FREE, reduced.rhs, reduced.jacobian, reduced.events, self.free_args, np.asarray(y, float),
                     reduced.EVENT_NAMES, terminal, (-1, -1, -1, 0, 1), np.full(5, self.atol))

    def sliding(self, y, sigma: float) -> Phase:
        stick = int(self.contact.tan_psi > 0.0)  # with psi = 0 there is no friction and D = 0 is no event
        return Phase(SLIDING, sliding_rhs, sliding_jacobian, sliding_events, self.args(sigma),
                     np.asarray(y, float), SLIDING_EVENTS, (1, 1, stick), (-1, 1, -1), np.full(4, self.atol),
                     sigma=sigma)

    def locked(self, y) -> Phase:
        return Phase(LOCKED, locked_rhs, locked_jacobian, locked_events, self.args(), np.asarray(y, float),
                     LOCKED_EVENTS, (1, 1, 1, 1), (-1, 1, -1, -1), np.full(3, self.atol))

    def enter_contact(self, phi, omega_a, omega_b, x_b) -> Phase:
        """Phase and state on touching, or on leaving a phase at D = 0 or at the friction bound.

        Locked if (5.5) holds (Omega_a jumps to Omega_b, the paper's rule); else
        sliding with sigma = sgn(D), or -sgn(C_lock) when D = 0 (module docstring).
        """
        contact = self.contact
        bound = -math.cos(phi) * contact.tan_psi
        c_lock = locked_friction(self.params, contact.kappa_star, phi)
        if abs(c_lock) < bound:
            return self.locked([phi, omega_b, x_b])
        if contact.tan_psi == 0.0:
            sigma = 0.0
        elif omega_b != omega_a:
            sigma = math.copysign(1.0, omega_b - omega_a)
        else:
            sigma = -math.copysign(1.0, c_lock)
        return self.sliding([phi, omega_a, omega_b, x_b], sigma)

    def transition(self, phase: Phase, reason: str, end, phi: float) -> Phase:
        """The phase after the switch ``reason`` from ``phase`` at the final state ``end``, angle ``phi``."""
        if reason == "lift":  # a locked state carries one rate, (phi, Omega, X_b)
            rates = (end[1], end[1], end[2]) if phase.name == LOCKED else (end[1], end[2], end[3])
            return self.free(on_circle(end[0], *rates, self.contact.r_star))
        if phase.name == FREE:
            return self.enter_contact(phi, end[2], end[3], end[4])
        if phase.name == SLIDING:  # D = 0: lock if (5.5) holds, else slide the other way
            return self.enter_contact(end[0], end[2], end[2], end[3])
        # the friction bound is reached: slide, from D = 0
        return self.sliding([end[0], end[1], end[1], end[2]],
                            -math.copysign(1.0, locked_friction(self.params, self.contact.kappa_star, end[0])))

    def columns(self, phase: Phase, t, y, kind) -> dict:
        """Output columns of one phase's rows (state y, shape (n_state, k)), scaled units."""
        n = t.size
        if phase.name == FREE:
            cols = reduced.columns(y, phase.extra["phi0"], phase.args)
            zeros = np.zeros(n)
            return {**cols, "c_eps": zeros, "c_chi": zeros}
        phi = y[0]
        cos = np.cos(phi)
        phi_dot = np.array([phase.fun(0.0, np.ascontiguousarray(y[:, i]), phase.args)[0] for i in range(n)])
        if phase.name == SLIDING:
            rates = {"omega_a": y[1], "omega_b": y[2], "x_b": y[3], "c_chi": phase.sigma * self.contact.tan_psi * cos}
        else:
            rates = {"omega_a": y[1], "omega_b": y[1], "x_b": y[2],
                     "c_chi": locked_friction(self.params, self.contact.kappa_star, phi)}
        return {"kappa": np.full(n, self.contact.kappa_star),
                "one_minus_kappa": np.full(n, self.contact.one_minus_kappa_star), "phi": phi,
                "kappa_dot": np.zeros(n), "phi_dot": phi_dot.reshape(n), "c_eps": -cos, **rates}


def run_contact(params: ReducedParams, contact: ContactParams, t_end: float, kappa0: float, phi0: float,
                omega_a0: float = 0.0, omega_b0: float = 0.0, x_b0: float = 0.0, *, limits: Limits = Limits(),
                method: str = "radau", rtol: float = 1e-8, t_eval=None, steps=None, max_steps: int = 2_000_000,
                max_switches: int = MAX_SWITCHES, progress=None) -> dict:
    """The reduced model with rough contact from t = 0 to ``t_end`` (units of tau); the fields of
    :func:`numerics.hybrid.run_phases` with columns kappa, 1 - kappa, phi, Omega_a,
    Omega_b, X_b, C_e, C_x (scaled units).

    At kappa0 = kappa* with cos(phi0) < 0 the run starts in contact (locked or
    sliding as on touching). Use :func:`dynamics.simulation.simulate` for a
    :class:`~dynamics.simulation.Trajectory`.
    """
    kappa0 = check_range("kappa0", kappa0, 0.0, contact.kappa_star, high_open=False)
    phi0 = check_finite("phi0", phi0)
    run = ReducedContactRun(params, contact, limits, rtol, x_b0)
    if kappa0 == contact.kappa_star and math.cos(phi0) < 0.0:
        start = run.enter_contact(phi0, omega_a0, omega_b0, x_b0)
    else:
        start = run.free(initial_state(kappa0, phi0, omega_a0, omega_b0, x_b0))
    return run_phases(start, lambda phase, reason, t, end, phi: run.transition(phase, reason, end, phi),
                      run.columns, t_end, phi0=phi0, method=method, rtol=rtol, t_eval=t_eval, steps=steps,
                      max_steps=max_steps, max_switches=max_switches, progress=progress)


