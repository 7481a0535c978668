r"""Rough contact on surfaces whose minimum gap varies: :mod:`dynamics.contact.reduced` on a moving constraint.

The asperities now touch at kappa = kappa*(theta_a, theta_b), the field of
:mod:`dynamics.contact.roughness`, where theta_a = phi - Theta_a and
theta_b = phi - X_b are the body angles of the surfaces at the line of
centres. Time is in units of tau and rates in 1/tau, as in
:mod:`dynamics.equations.reduced`. Every phase evaluates the right-hand side of
:mod:`dynamics.contact.reduced` at the local kappa* and adds what the varying gap
changes.

The constraint and its reaction
-------------------------------
In the configuration (eps, chi, Theta_a, Theta_b) the asperities impose

    G = eps*(theta_a, theta_b) - eps >= 0,    eps* = delta kappa*.

G depends only on the relative configuration: a rigid rotation of the whole
device leaves theta_a, theta_b and eps unchanged. Its reaction N grad G
(N >= 0) is therefore an internal force system with no net force or torque.
That is why the total angular momentum balance (2.11d) stays as it is, as for
the uniform contact. To leading order, grad G is also the reaction of the
true contact. The narrowest point of the rough gap lies off the line of
centres, at an angle u ~ (h_a' + h_b')/eps fixed by the height slopes. By
the envelope theorem, the derivatives of the true minimum gap equal those of
the gap on the line of centres. The reaction's components are:

* along e_eps, -N: the normal reaction of (5.1). In units of m'_a g,
  C_e = N/(m'_a g) as in :mod:`dynamics.contact.reduced`;
* along e_chi, the force Q_chi/eps = N (d kappa*/d theta_a + d kappa*/d theta_b)/kappa.
  This is the tilt of the contact normal by the angle u. It is O(1) against
  f_chi when (1 - kappa*) amplitude / lambda is O(1), so it enters (2.11b);
* the torque Q_{Theta_a} = -N delta d kappa*/d theta_a on the inner cylinder.
  In the torque unit m'_a g delta of (2.11c) it is -C_e d kappa*/d theta_a,
  O(1) in (5.2), like the friction.

With k_a = d kappa*/d theta_a, k_b = d kappa*/d theta_b, P = k_a + k_b,
A = (2 + kappa^2) zeta / (2 kappa) (kappa, zeta local), the contact equations are

    (5.1)   r' = r*' = -cos(phi) - C_e,     r* = kappa*/zeta*,
            r*' = (k_a theta_a' + k_b theta_b') / zeta^3,  theta' = phi' - Omega,
    (2.11b) phi' = W + A (sin(phi) + C_e P / kappa),
    (5.2)   (1/2) Upsilon Omega_a' = T - C_x - C_e k_a,
    (2.11d) unchanged, X_b' = Omega_b, Theta_a' = Omega_a.

Here T is the lubrication torque (2.11c) at the actual phi'. Let phi'_0 =
W + A sin(phi) and T_0 be the uniform contact's values at the local kappa*
(:func:`dynamics.contact.reduced.sliding_rhs`, without friction). T depends on phi'
only through 3 kappa^2 phi' / (3 (2 + kappa^2) zeta), so
T = T_0 + C_e P / 2, and (5.2) becomes

    (1/2) Upsilon Omega_a' = T_0 - C_x + tau,   tau = C_e (k_b - k_a) / 2,

where tau is the torque of the tilted reaction on the inner cylinder. (5.1) and
(2.11b) are linear in (phi', C_e). Solved together they give

    C_e = c_0 / (1 + A P^2 / (kappa zeta^3)),
    c_0 = -cos(phi) - (k_a (phi'_0 - Omega_a) + k_b (phi'_0 - Omega_b)) / zeta^3,
    phi' = phi'_0 + A P C_e / kappa.

c_0 is the rate d(r - r*)/dt at which the free motion (2.11a) would enter
the constraint. The reaction is that rate reduced by the extra squeeze flow
that following the tilted constraint costs, so C_e has the sign of c_0.

Friction and phases
-------------------
The Coulomb law (5.3) now bounds |C_x| by C_e tan(psi) with this C_e. It
reduces to the uniform contact's -cos(phi) tan(psi) only when the gap is uniform.

sliding
    C_x = -sigma tan(psi) C_e, with sigma = sgn(Omega_b - Omega_a) fixed
    for the phase.

locked (Omega_a = Omega_b)
    (2.11d) is unchanged; (5.2) gives the friction that keeps D = 0,
    C_lock = C_lock,0 + tau, where C_lock,0 is the uniform contact's (5.4)
    at the local kappa*. The phase holds while |C_lock| < C_e tan(psi).
    The Filippov argument of :mod:`dynamics.contact.reduced` carries over:
    D' = (1 + 2 mu_)/(mu_ Upsilon) (C_x - C_lock) at D = 0.

Switching: the events of :mod:`dynamics.contact.reduced`, on the moving constraint
-------------------------------------------------------------------------
* free -> contact when r reaches r*(theta_a, theta_b), r - r* rising. The
  constraint moves, so this can happen with cos(phi) > 0 when an asperity
  comes round and meets the inner cylinder. At the touch c_0 > 0, hence
  C_e > 0. The run then locks if the locked state, with Omega_a jumped to
  Omega_b (the paper's rule), satisfies |C_lock| < C_e tan(psi); otherwise
  it slides with sigma = sgn(D). C_e depends on Omega_a through theta_a',
  so the test uses the reaction of the state after the jump.
* contact -> free when C_e falls through 0. For the uniform gap this is
  cos(phi) = 0. At that instant c_0 = 0: the free motion leaves the
  constraint tangentially and then separates from it.
* stick (D = 0) and slip (|C_lock| = C_e tan(psi)) are as before.

Every guard is a terminal event located on the dense output. The free
motion itself does not see the roughness, so its steps alone could stride
over an asperity. The free phase therefore carries one more, passive
component, the roughness seen along the path, S' = kappa^2 r*'. Its error
control makes the steps resolve the asperities that the line of centres
sweeps past, so a touch is not stepped over. The weight kappa^2 keeps S'
finite at kappa = 0, where phi' is not. S is dropped on leaving the phase.

Limits and numerics
-------------------
With amplitude 0, k_a = k_b = 0 exactly. Every phase's right-hand side is
then that of :mod:`dynamics.contact.reduced` to the last bit, and so are the guards
and resets. The trajectories differ only by the integrator: its error
control sees the extra passive components (Theta_a, S), and its Jacobian
differs (below).

The free phase has the analytic Jacobian of :mod:`dynamics.equations.reduced`. S is
left out of it, because nothing depends on S. In contact, the solver forms
the Jacobian by finite differences. C_e depends on D through theta_a' -
theta_b', with dC_e/dD = (k_b - k_a)/(2 zeta^3 (1 + A P^2/(kappa zeta^3))),
and sliding friction multiplies it by tan(psi). For large friction that term
is stiff, so it must appear in the Jacobian, and the uniform contact's
Jacobian does not contain it.

Two situations where a guard starts at zero are settled exactly:

* A free phase that starts on the constraint has clearance 0 at its start.
* A touch with C_e <= rtol is a graze. The free motion meets the constraint
  tangentially to within the tolerance, so the run flies on instead of
  entering a contact that would end as it began.

The event locator compares the guard's sign at the step start with its sign
on the dense output, and near zero those signs can differ by rounding. These
two rules keep such starts away from the locator.

Known limit: as tan(psi) -> infinity (tested to tan(psi) = 5.8), sliding can
follow a slow manifold with C_e -> 0+. There the friction pins D at the value
where the reaction vanishes. The manifold is stiff at rate ~ tan(psi) dC_e/dD,
and at tan(psi) = 1e6 the steps crawl.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from dynamics.contact.reduced import (
    FREE,
    LOCKED,
    MAX_SWITCHES,
    SLIDING,
    ContactParams,
    ContactTrajectory,
    PhaseStart,
    free_columns,
    locked_friction,
    locked_rhs,
    phase_args,
    run_phases,
    sliding_rhs,
)
from dynamics.contact.roughness import LocalGap, RoughContact
from dynamics.contact.steady import steady_state
from dynamics.equations.limits import MAX_TURNS, runaway_event
from dynamics.equations.reduced import (
    ReducedParams,
    initial_state,
    reduced_jacobian,
    reduced_rhs,
)
from dynamics.integrate import Event
from lubrication.geometry import check_finite, check_range

__all__ = [
    "ContactState",
    "RoughTrajectory",
    "SpeedRow",
    "contact_state",
    "free_rhs",
    "normal_reaction",
    "rolling_statistics",
    "simulate_rough_contact",
    "speed_table",
    "speed_table_markdown",
]

# Where each phase keeps X_b and Theta_a (free: xi, eta, Omega_a, Omega_b, X_b, Theta_a, S;
# sliding: phi, Omega_a, Omega_b, X_b, Theta_a; locked: phi, Omega, X_b, Theta_a).
_X_B = {FREE: 4, SLIDING: 3, LOCKED: 2}


@dataclass(frozen=True, kw_only=True)
class RoughTrajectory(ContactTrajectory):
    """A :class:`dynamics.contact.reduced.ContactTrajectory` on rough surfaces, kappa = local kappa* in contact.

    Attributes
    ----------
    theta_a, theta_b : ndarray, shape (n,)
        Body angles (rad, unwrapped) of the inner and outer surface at the line
        of centres, phi - Theta_a and phi - X_b.
    """

    theta_a: np.ndarray
    theta_b: np.ndarray


class ContactState(NamedTuple):
    """A contact phase's rates and forces at one state."""

    rates: np.ndarray  # dy/dt of the phase's state
    c_eps: float  # normal reaction C_e (5.1)
    c_chi: float  # friction C_x of (5.2): Coulomb when sliding, C_lock when locked
    local: LocalGap  # kappa* and its slopes where the surfaces touch


def normal_reaction(local: LocalGap, phi: float, phi_dot_0: float, omega_a: float,
                    omega_b: float) -> tuple[float, float, float]:
    """(C_e, phi' - phi'_0, tau): reaction, turn and torque of the tilted constraint (module docstring).

    ``phi_dot_0`` is the uniform contact's phi' = W + A sin(phi) at the local kappa*.
    """
    kappa = local.kappa
    zeta = math.sqrt(local.one_minus_kappa * (1.0 + kappa))
    zeta3 = zeta * zeta * zeta
    slope = local.dkappa_a + local.dkappa_b
    lever = (2.0 + kappa * kappa) * zeta / (2.0 * kappa)
    approach = -math.cos(phi) - (local.dkappa_a * (phi_dot_0 - omega_a)
                                 + local.dkappa_b * (phi_dot_0 - omega_b)) / zeta3
    c_e = approach / (1.0 + lever * slope * slope / (kappa * zeta3))
    return c_e, lever * slope * c_e / kappa, 0.5 * c_e * (local.dkappa_b - local.dkappa_a)


def contact_state(phase: str, sigma: float, y, params: ReducedParams, rough: RoughContact) -> ContactState:
    """Rates and forces of a contact phase: sliding (sign ``sigma``) or locked.

    ``y`` is (phi, Omega_a, Omega_b, X_b, Theta_a) when sliding and
    (phi, Omega, X_b, Theta_a) when locked.
    """
    phi = y[0]
    local = rough.local_at(phi - y[-1], phi - y[_X_B[phase]])
    here = ContactParams(local.kappa, rough.mean.psi)
    ups, mu_ = params.upsilon, params.mu_ratio
    if phase == SLIDING:
        base = sliding_rhs(0.0, y[:4], phase_args(params, here, 0.0))  # the uniform phase without friction
        c_e, turn, tilt = normal_reaction(local, phi, base[0], y[1], y[2])
        c_x = -sigma * here.tan_psi * c_e
        torque = c_x - tilt
        rates = np.array([base[0] + turn, base[1] - 2.0 * torque / ups, base[2] + torque / (mu_ * ups),
                          base[3], y[1]])
        return ContactState(rates, c_e, c_x, local)
    base = locked_rhs(0.0, y[:3], phase_args(params, here))
    c_e, turn, tilt = normal_reaction(local, phi, base[0], y[1], y[1])
    rates = np.array([base[0] + turn, base[1], base[2], y[1]])
    return ContactState(rates, c_e, locked_friction(params, local.kappa, phi) + tilt, local)


def _free_local(y, rough: RoughContact) -> LocalGap:
    """kappa* where the line of centres of a free state, phi = atan2(xi, eta), meets the surfaces."""
    phi = math.atan2(y[0], y[1])
    return rough.local_at(phi - y[5], phi - y[4])


def free_rhs(t: float, y, params: ReducedParams, rough: RoughContact) -> np.ndarray:
    """Free flight (2.11) with Theta_a' = Omega_a and the roughness seen, S' = kappa^2 r*'.

    ``y`` = (xi, eta, Omega_a, Omega_b, X_b, Theta_a, S). kappa^2 phi' =
    (eta xi' - xi eta')/rho^2 is regular at kappa = 0 (:mod:`dynamics.equations.reduced`).
    """
    f = reduced_rhs(t, y[:5], params)
    xi, eta = y[0], y[1]
    rho2 = 1.0 + xi * xi + eta * eta
    kappa2 = (xi * xi + eta * eta) / rho2
    turning = (eta * f[0] - xi * f[1]) / rho2
    local = _free_local(y, rough)
    zeta3 = (local.one_minus_kappa * (1.0 + local.kappa)) ** 1.5
    seen = (local.dkappa_a * (turning - kappa2 * y[2]) + local.dkappa_b * (turning - kappa2 * y[3])) / zeta3
    return np.concatenate((f, (y[2], seen)))


def _free_jacobian(t: float, y, params: ReducedParams) -> np.ndarray:
    """Jacobian of :func:`free_rhs`: the reduced model's, Theta_a' = Omega_a, and no row for S.

    S feeds back into nothing, so its row cannot slow Newton's iteration.
    """
    jac = np.zeros((7, 7))
    jac[:5, :5] = reduced_jacobian(t, y[:5], params)
    jac[5, 2] = 1.0
    return jac


def _enter_contact(params, rough, phi, omega_a, omega_b, x_b, turned_a):
    """Phase and state on touching or at D = 0: locked if the friction can hold it, else sliding."""
    locked = np.array([phi, omega_b, x_b, turned_a])
    hold = contact_state(LOCKED, 0.0, locked, params, rough)
    tan_psi = rough.mean.tan_psi
    if abs(hold.c_chi) < hold.c_eps * tan_psi:
        return PhaseStart(LOCKED, locked)
    if tan_psi == 0.0:
        sigma = 0.0
    elif omega_b != omega_a:
        sigma = math.copysign(1.0, omega_b - omega_a)
    else:
        sigma = -math.copysign(1.0, hold.c_chi)
    return PhaseStart(SLIDING, np.array([phi, omega_a, omega_b, x_b, turned_a]), sigma)


def _transition(phase, sigma, reason, end, phi, params, rough, rtol) -> PhaseStart:
    """The phase after the switch ``reason`` from ``phase`` at the final state ``end`` (module docstring)."""
    if reason == "lift":
        omega_a, omega_b = (end[1], end[2]) if phase == SLIDING else (end[1], end[1])
        r_star = contact_state(phase, sigma, end, params, rough).local.r_star
        return PhaseStart(FREE, np.array([r_star * math.sin(phi), r_star * math.cos(phi), omega_a, omega_b,
                                          end[_X_B[phase]], end[-1], 0.0]), on_constraint=True)
    if phase == FREE:
        touching = np.array([phi, end[2], end[3], end[4], end[5]])
        if contact_state(SLIDING, 0.0, touching, params, rough).c_eps <= rtol:
            # A graze: the free motion meets the constraint tangentially to within the
            # tolerance, and a contact would end as it began. Fly on from the touch.
            return PhaseStart(FREE, np.concatenate((end[:6], (0.0,))), on_constraint=True, switch=False)
        return _enter_contact(params, rough, phi, end[2], end[3], end[4], end[5])
    if phase == SLIDING:  # D = 0: lock if the friction holds, else slide the other way
        return _enter_contact(params, rough, end[0], end[2], end[2], end[3], end[4])
    # the friction bound is reached: slide, from D = 0
    return PhaseStart(SLIDING, np.array([end[0], end[1], end[1], end[2], end[3]]),
                      -math.copysign(1.0, contact_state(LOCKED, 0.0, end, params, rough).c_chi))


def _phase_setup(phase, sigma, params, rough, x_b0, max_turns, on_constraint):
    """Right-hand side, Jacobian and terminal events of one phase.

    A free phase ``on_constraint`` starts where r = r* exactly (after a
    lift-off or a graze): its clearance is 0 there, not the rounding of
    hypot(xi, eta) - r*, whose sign the dense output need not reproduce.
    """
    runaway = runaway_event(lambda y: y[_X_B[phase]] - x_b0, max_turns)
    if phase == FREE:
        def clearance(t, y):
            if on_constraint and t == 0.0:
                return 0.0
            return math.hypot(y[0], y[1]) - float(_free_local(y, rough).r_star)

        touch = Event("touch", clearance, 1.0, lambda t: f"contact at t = {t:.6g}")
        return (lambda t, y: free_rhs(t, y, params, rough), lambda t, y: _free_jacobian(t, y, params),
                (touch, runaway))

    def state(y):
        return contact_state(phase, sigma, y, params, rough)

    lift = Event("lift", lambda t, y: state(y).c_eps, -1.0, lambda t: f"lift-off at t = {t:.6g}")
    tan_psi = rough.mean.tan_psi
    if phase == SLIDING:
        events = (lift, runaway)
        if tan_psi > 0.0:
            events += (Event("stick", lambda t, y: sigma * (y[2] - y[1]), -1.0,
                             lambda t: f"Omega_a = Omega_b at t = {t:.6g}"),)
        return lambda t, y: state(y).rates, None, events

    def slip(side):
        def margin(t, y):
            here = state(y)
            return here.c_eps * tan_psi - side * here.c_chi

        return Event("slip", margin, -1.0, lambda t: f"friction bound (5.5) reached at t = {t:.6g}")

    return lambda t, y: state(y).rates, None, (lift, runaway, slip(1.0), slip(-1.0))


def _rough_columns(phase, sigma, y, t, phi_start, params, rough):
    """Output columns of one phase's samples: those of a ContactTrajectory, and the body angles."""
    if phase == FREE:
        cols = free_columns(y, t, phi_start)
        return dict(cols, theta_a=cols["phi"] - y[5], theta_b=cols["phi"] - y[4])
    states = [contact_state(phase, sigma, y[:, i], params, rough) for i in range(t.size)]
    omega_b = y[2] if phase == SLIDING else y[1]
    return dict(kappa=np.array([s.local.kappa for s in states]),
                one_minus_kappa=np.array([s.local.one_minus_kappa for s in states]),
                phi=y[0], omega_a=y[1], omega_b=omega_b, x_b=y[_X_B[phase]],
                c_eps=np.array([s.c_eps for s in states]), c_chi=np.array([s.c_chi for s in states]),
                theta_a=y[0] - y[-1], theta_b=y[0] - y[_X_B[phase]])


def simulate_rough_contact(params: ReducedParams, rough: RoughContact, t_end: float, kappa0: float,
                           phi0: float, omega_a0: float = 0.0, omega_b0: float = 0.0, x_b0: float = 0.0, *,
                           rtol: float = 1e-8, atol: float = 1e-10, method: str = "LSODA",
                           max_turns: float = MAX_TURNS, max_steps: int = 2_000_000,
                           max_switches: int = MAX_SWITCHES,
                           progress: str | None = None) -> RoughTrajectory:
    """Integrate the reduced model with contact on rough surfaces from t = 0 to ``t_end`` (units of tau).

    Parameters
    ----------
    params : ReducedParams
    rough : RoughContact
        Mean contact, amplitude and the two surfaces (:mod:`dynamics.contact.roughness`).
    t_end : float
        Final time in units of tau, positive.
    kappa0 : float
        Initial eccentricity, in [0, kappa*(phi0, phi0 - x_b0)]: Theta_a
        starts at 0, so the initial body angles are theta_a = phi0 and
        theta_b = phi0 - x_b0. At that kappa*, with the free motion pushing in,
        the run starts in contact.
    phi0, omega_a0, omega_b0, x_b0 : float
        Initial angle from the upward vertical (rad), rates (1/tau), position (b).
    rtol, atol, method, max_turns, max_steps, max_switches, progress
        As for :func:`dynamics.contact.reduced.simulate_contact`.

    Returns
    -------
    RoughTrajectory

    Raises
    ------
    ValueError
        For out-of-range arguments.
    """
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True)
    phi0 = check_finite("phi0", phi0)
    omega_a0, omega_b0, x_b0 = (check_finite(k, v) for k, v in
                                (("omega_a0", omega_a0), ("omega_b0", omega_b0), ("x_b0", x_b0)))
    kappa_touch = rough.local_at(phi0, phi0 - x_b0).kappa
    kappa0 = check_range("kappa0", kappa0, 0.0, kappa_touch, high_open=False,
                         unit="(kappa* at the initial contact angles)")
    max_turns = check_range("max_turns", max_turns, 0.0, math.inf, low_open=True)

    on_constraint = np.array([phi0, omega_a0, omega_b0, x_b0, 0.0])
    if kappa0 == kappa_touch and contact_state(SLIDING, 0.0, on_constraint, params, rough).c_eps > 0.0:
        start = _enter_contact(params, rough, phi0, omega_a0, omega_b0, x_b0, 0.0)
    else:
        start = PhaseStart(FREE, np.concatenate((initial_state(kappa0, phi0, omega_a0, omega_b0, x_b0),
                                                 (0.0, 0.0))))
    fields = run_phases(
        start, lambda phase, sigma, on: _phase_setup(phase, sigma, params, rough, x_b0, max_turns, on),
        lambda phase, sigma, y, t, phi: _rough_columns(phase, sigma, y, t, phi, params, rough),
        lambda phase, sigma, reason, end, phi: _transition(phase, sigma, reason, end, phi, params, rough, rtol),
        t_end, phi0, rtol=rtol, atol=atol, method=method, max_steps=max_steps, max_switches=max_switches,
        progress=progress)
    return RoughTrajectory(**fields)


# -- mean rolling against the roughness amplitude, and the uniform speed (6.1) ----------

class SpeedRow(NamedTuple):
    """Rolling statistics at one amplitude, over seeds (rates in 1/tau: speeds in b/tau)."""

    amplitude: float
    mean: float  # mean over seeds of each run's mean rolling rate <Omega_b>
    spread: float  # standard deviation of <Omega_b> over seeds
    ratio: float  # mean / the uniform kappa* steady Omega_b, (6.1) with exact=True
    fluctuation: float  # mean over seeds of the time standard deviation of Omega_b
    switch_rate: float  # mean over seeds of phase switches per tau
    seeds: int


def rolling_statistics(trajectory: ContactTrajectory, t_settle: float) -> tuple[float, float, float]:
    """Mean rolling rate, time standard deviation of Omega_b and switches per tau after ``t_settle``.

    The mean is (X_b(t_end) - X_b(t_settle)) / (t_end - t_settle); the standard
    deviation is time-weighted (trapezoidal) over the samples.
    """
    t, omega_b = trajectory.t, trajectory.omega_b
    span = t[-1] - t_settle
    if not span > 0.0:
        msg = f"t_settle must be before the end of the run, t = {t[-1]:.6g}; got {t_settle!r}"
        raise ValueError(msg)
    mean = (trajectory.x_b[-1] - np.interp(t_settle, t, trajectory.x_b)) / span
    late = t >= t_settle
    variance = np.trapezoid((omega_b[late] - mean) ** 2, t[late]) / span
    switches = sum(sw.t >= t_settle for sw in trajectory.switches)
    return float(mean), math.sqrt(max(float(variance), 0.0)), switches / span


def speed_table(params: ReducedParams, mean: ContactParams, correlation: float, amplitudes, seeds, *,
                t_end: float, t_settle: float, kappa0: float = 0.5, phi0: float = 0.3,
                rtol: float = 1e-8) -> tuple[float, tuple[SpeedRow, ...]]:
    """Mean rolling rate and its spread over ``seeds`` against the roughness amplitude.

    Every run starts from figure 2's release (``kappa0``, ``phi0``) at rest
    and is averaged over [t_settle, t_end] (units of tau). The correlation
    length ``correlation`` is in rad on both surfaces (a = b in the reduced model).

    Returns
    -------
    uniform : float
        The steady Omega_b of the uniform kappa*_mean (5.10)-(5.11). (6.1) is
        V = V* sin(alpha) Omega_b / (3 s), so ratios of rates are ratios of speeds.
    rows : tuple of SpeedRow
    """
    uniform = steady_state(params.s, mean.kappa_star, mean.psi).omega_b
    rows = []
    for amplitude in amplitudes:
        stats = []
        for seed in seeds:
            rough = RoughContact.from_seed(mean, amplitude, correlation, correlation, seed)
            traj = simulate_rough_contact(params, rough, t_end, kappa0, phi0, rtol=rtol, atol=rtol * 1e-2,
                                          max_turns=1e6)
            if traj.status != 0:
                msg = f"amplitude {amplitude:g}, seed {seed}: the run stopped early: {traj.message}"
                raise RuntimeError(msg)
            stats.append(rolling_statistics(traj, t_settle))
        rates, fluctuations, switch_rates = np.array(stats).T
        rows.append(SpeedRow(float(amplitude), float(rates.mean()), float(rates.std(ddof=1)) if rates.size > 1
                             else 0.0, float(rates.mean()) / uniform, float(fluctuations.mean()),
                             float(switch_rates.mean()), len(stats)))
    return uniform, tuple(rows)


def speed_table_markdown(uniform: float, rows) -> str:
    """The table of :func:`speed_table` in markdown."""
    lines = [f"uniform kappa* steady Omega_b (6.1): {uniform:.5g} / tau", "",
             "| amplitude | <Omega_b> | spread (seeds) | / uniform | Omega_b fluctuation | switches/tau | seeds |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {r.amplitude:g} | {r.mean:.5g} | {r.spread:.2g} | {r.ratio:.4f} | {r.fluctuation:.3g} | "
              f"{r.switch_rate:.3g} | {r.seeds} |" for r in rows]
    return "\n".join(lines)
