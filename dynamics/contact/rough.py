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
-----------------------------------------------------------------------------------
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

The phases as compiled functions
--------------------------------
Each phase is a smooth system run by :func:`numerics.hybrid.run_phases`,
one compiled call per phase, with ``f(t, y, args)`` functions and ``args``
from :func:`phase_args` (the groups, the contact, the runaway limit and the
tables of both surfaces' heights):

free
    y = (xi, eta, Omega_a, Omega_b, X_b, Theta_a, S): :func:`free_rhs`,
    :func:`free_jacobian`, :func:`free_events` (:data:`FREE_EVENTS`: the
    runaway, the line of centres crossing the vertical, xi = 0, which keeps
    phi continuous between rows, and the touch r = r*).
sliding
    y = (phi, Omega_a, Omega_b, X_b, Theta_a): :func:`sliding_rhs`,
    :func:`sliding_jacobian`, :func:`sliding_events` (:data:`SLIDING_EVENTS`:
    the runaway, lift-off as C_e falls through 0, stick as D reaches 0).
locked
    y = (phi, Omega, X_b, Theta_a): :func:`locked_rhs`, :func:`locked_jacobian`,
    :func:`locked_events` (:data:`LOCKED_EVENTS`: the runaway, lift-off, and
    |C_lock| reaching C_e tan(psi) on either side).

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
then that of :mod:`dynamics.contact.reduced` to the last bit, and so are the
guards (lift-off as -cos(phi) falling through 0 is cos(phi) rising through it)
and resets. The trajectories differ only by the integrator: its error control
sees the extra passive components (Theta_a, S), and its Jacobian differs
(below).

The free phase has the analytic Jacobian of :mod:`dynamics.equations.reduced`. S is
left out of it, because nothing depends on S. In contact the Jacobian is
formed by central differences in compiled code (:func:`sliding_jacobian`,
step eps^(1/3) in every component: the scaled state is O(1), and the surfaces
vary on the correlation length, not on the size of the angles). C_e depends on
D through theta_a' - theta_b', with dC_e/dD = (k_b - k_a)/(2 zeta^3 (1 + A
P^2/(kappa zeta^3))), and sliding friction multiplies it by tan(psi). For large
friction that term is stiff, so it must appear in the Jacobian, and the uniform
contact's analytic Jacobian does not contain it.

Two situations where a guard starts at zero are settled exactly:

* A free phase that starts on the constraint (after a lift-off, a graze, or a
  start at kappa0 = kappa*) has clearance exactly 0 at its start. Its
  clearance is r - r* minus its own value at the initial state, which the
  phase's ``args`` record: a shift at the rounding level (ulps of r*, and
  of the angles times dr*/dtheta) that removes the rounding of
  hypot(xi, eta) - r*(theta_a, theta_b) there, whose sign is arbitrary. The
  engine does not fire an event that is exactly 0 at the start of a step, so
  the phase cannot touch at once.
* A touch with C_e <= rtol is a graze. The free motion meets the constraint
  tangentially to within the tolerance, so the run flies on, without a
  recorded switch, instead of entering a contact that would end as it began.

Without them, a clearance that rounds to -1e-16 at the start of a graze
could be positive at the end of the first step and touch again at once, and a
touch with a vanishing reaction would start a contact that lifts off at once.

Known limit: as tan(psi) -> infinity (tested to tan(psi) = 5.8), sliding can
follow a slow manifold with C_e -> 0+. There the friction pins D at the value
where the reaction vanishes. The manifold is stiff at rate ~ tan(psi) dC_e/dD,
and at tan(psi) = 1e6 the steps crawl.
"""

from __future__ import annotations

import math

import numpy as np

from dynamics.contact.reduced import (
    FREE,
    LOCKED,
    SLIDING,
    on_circle,
    tangential_rate,
)
from dynamics.contact.roughness import RoughContact, _local_kernel
from dynamics.equations import reduced
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams, initial_state
from lubrication.geometry import check_finite, check_range
from numerics.hybrid import MAX_SWITCHES, Phase, run_phases
from numerics.jit import jit
from numerics.packed import pack, part

__all__ = [
    "FREE_EVENTS",
    "LOCKED_EVENTS",
    "SLIDING_EVENTS",
    "RoughContactRun",
    "contact_state",
    "free_events",
    "free_jacobian",
    "free_rhs",
    "locked_events",
    "locked_jacobian",
    "locked_rhs",
    "normal_reaction",
    "phase_args",
    "sliding_events",
    "sliding_jacobian",
    "sliding_rhs",
]

#: Event components of the phases, in order (:func:`free_events`, :func:`sliding_events`,
#: :func:`locked_events`).
FREE_EVENTS = ("runaway", "turn", "touch")
SLIDING_EVENTS = ("runaway", "lift", "stick")
LOCKED_EVENTS = ("runaway", "lift", "slip", "slip")

# The args of every phase (phase_args), packed (numerics.packed): the groups of (2.11) (s, Upsilon, mu_), then
_TAN_PSI, _SIGMA, _XB_LIMIT, _XB0, _CLEARANCE0, _AMPLITUDE, _KAPPA_MEAN, _GAP_MEAN = range(3, 11)
# and the surfaces' tables (SurfaceHeights.jets) as the parts after these numbers
_JETS_A, _JETS_B = range(1, 3)

# The components of contact_state
_PHI_DOT, _OMEGA_A_DOT, _OMEGA_B_DOT, _C_E, _C_X, _KAPPA, _ONE_MINUS_KAPPA = range(7)

_CBRT_EPS = 6.0554544523933395e-06  # eps^(1/3): the central-difference step, truncation ~ rounding
_LIMITS = Limits()


def phase_args(params: ReducedParams, rough: RoughContact, sigma: float = 0.0, *, x_b_limit: float = math.inf,
               x_b0: float = 0.0, clearance0: float = 0.0) -> np.ndarray:
    """The ``args`` of every phase's compiled functions.

    Packed (:mod:`numerics.packed`): the numbers (s, Upsilon, mu_, tan(psi), sigma,
    x_b_limit, x_b0, clearance0, amplitude, kappa*_mean, 1 - kappa*_mean), then the
    tables of the inner and outer surface's heights
    (:attr:`~dynamics.contact.roughness.SurfaceHeights.jets`) as parts. ``sigma`` is the sliding phase's sgn(D);
    the runaway fires when |X_b - x_b0| reaches ``x_b_limit`` (units of b);
    ``clearance0`` is subtracted from the free phase's clearance r - r*
    (module docstring: a free phase that starts on the constraint).
    """
    mean = rough.mean
    numbers = [*params.args, mean.tan_psi, sigma, x_b_limit, x_b0, clearance0, rough.amplitude, mean.kappa_star,
               mean.one_minus_kappa_star]
    return pack(numbers, rough.inner.jets, rough.outer.jets)


@jit(inline="always")
def _local(theta_a, theta_b, args):
    """(kappa*, 1 - kappa*, d kappa*/d theta_a, d kappa*/d theta_b) at the body angles (roughness field)."""
    return _local_kernel(theta_a, theta_b, part(args, _JETS_A), part(args, _JETS_B), args[_AMPLITUDE],
                         args[_KAPPA_MEAN], args[_GAP_MEAN])


@jit
def normal_reaction(kappa, one_minus_kappa, dkappa_a, dkappa_b, phi, phi_dot_0, omega_a, omega_b):
    """(C_e, phi' - phi'_0, tau): reaction, turn and torque of the tilted constraint (module docstring).

    ``kappa``, ``one_minus_kappa`` and the slopes are the local kappa* of the
    surfaces; ``phi_dot_0`` is the uniform contact's phi' = W + A sin(phi) at that kappa*.
    """
    zeta = math.sqrt(one_minus_kappa * (1.0 + kappa))
    zeta3 = zeta * zeta * zeta
    slope = dkappa_a + dkappa_b
    lever = (2.0 + kappa * kappa) * zeta / (2.0 * kappa)
    approach = -math.cos(phi) - (dkappa_a * (phi_dot_0 - omega_a) + dkappa_b * (phi_dot_0 - omega_b)) / zeta3
    c_e = approach / (1.0 + lever * slope * slope / (kappa * zeta3))
    return c_e, lever * slope * c_e / kappa, 0.5 * c_e * (dkappa_b - dkappa_a)


@jit
def contact_state(t, y, args):
    """Rates and forces of a contact phase at ``y``: sliding (5 components) or locked (4).

    ``y`` is (phi, Omega_a, Omega_b, X_b, Theta_a) when sliding, with the sign
    sigma = ``args[4]``, and (phi, Omega, X_b, Theta_a) when locked.

    Returns
    -------
    ndarray, shape (7,)
        phi', Omega_a', Omega_b' (1/tau^2), the reaction C_e and the friction
        C_x of (5.2) (Coulomb's when sliding, C_lock when locked), kappa* and
        1 - kappa* where the surfaces touch.
    """
    locked = y.size == 4
    phi, omega_a = y[0], y[1]
    omega_b = y[1] if locked else y[2]
    x_b, turned_a = y[y.size - 2], y[y.size - 1]
    kappa, omk, dkappa_a, dkappa_b = _local(phi - turned_a, phi - x_b, args)
    r_star = kappa / math.sqrt(omk * (1.0 + kappa))
    # the uniform contact at the local kappa*, without friction (dynamics.contact.reduced)
    z = on_circle(phi, omega_a, omega_b, x_b, r_star)
    f = reduced.rhs(t, z, args)
    phi_dot_0 = tangential_rate(z, f, r_star)
    c_e, turn, tilt = normal_reaction(kappa, omk, dkappa_a, dkappa_b, phi, phi_dot_0, omega_a, omega_b)
    s, ups, mu_ = args[0], args[1], args[2]
    out = np.empty(7)
    out[_PHI_DOT] = phi_dot_0 + turn
    if locked:
        out[_OMEGA_A_DOT] = (mu_ * f[3] + 0.5 * f[2]) / (mu_ + 0.5)
        out[_OMEGA_B_DOT] = out[_OMEGA_A_DOT]
        # (5.4) at the local kappa*, and the torque of the tilted reaction
        out[_C_X] = -(2.0 * s + (1.0 - 2.0 * mu_) * kappa * math.sin(phi)) / (2.0 * (1.0 + 2.0 * mu_)) + tilt
    else:
        c_x = -args[_SIGMA] * args[_TAN_PSI] * c_e
        torque = c_x - tilt
        out[_OMEGA_A_DOT] = f[2] - 2.0 * torque / ups
        out[_OMEGA_B_DOT] = f[3] + torque / (mu_ * ups)
        out[_C_X] = c_x
    out[_C_E] = c_e
    out[_KAPPA] = kappa
    out[_ONE_MINUS_KAPPA] = omk
    return out


@jit
def sliding_rhs(t, y, args):
    """Sliding on the moving constraint: d/dt (phi, Omega_a, Omega_b, X_b, Theta_a), sigma = ``args[4]``."""
    r = contact_state(t, y, args)
    out = np.empty(5)
    out[0] = r[_PHI_DOT]
    out[1] = r[_OMEGA_A_DOT]
    out[2] = r[_OMEGA_B_DOT]
    out[3] = y[2]
    out[4] = y[1]
    return out


@jit
def locked_rhs(t, y, args):
    """Locked on the moving constraint: d/dt (phi, Omega, X_b, Theta_a)."""
    r = contact_state(t, y, args)
    out = np.empty(4)
    out[0] = r[_PHI_DOT]
    out[1] = r[_OMEGA_A_DOT]
    out[2] = y[1]
    out[3] = y[1]
    return out


@jit
def _difference_jacobian(t, y, args):
    """d(rhs)/dy of the contact phase of ``y`` (locked if 4 components) by central differences."""
    n = y.size
    jac = np.empty((n, n))
    shifted = y.copy()
    for j in range(n):
        up, down = y[j] + _CBRT_EPS, y[j] - _CBRT_EPS
        shifted[j] = up
        f_up = locked_rhs(t, shifted, args) if n == 4 else sliding_rhs(t, shifted, args)
        shifted[j] = down
        f_down = locked_rhs(t, shifted, args) if n == 4 else sliding_rhs(t, shifted, args)
        shifted[j] = y[j]
        for i in range(n):
            jac[i, j] = (f_up[i] - f_down[i]) / (up - down)  # up - down is exact (Sterbenz)
    return jac


@jit
def sliding_jacobian(t, y, args):
    """Jacobian of :func:`sliding_rhs` by central differences (module docstring: the stiff dC_e/dD)."""
    return _difference_jacobian(t, y, args)


@jit
def locked_jacobian(t, y, args):
    """Jacobian of :func:`locked_rhs` by central differences."""
    return _difference_jacobian(t, y, args)


@jit
def sliding_events(t, y, args):
    """:data:`SLIDING_EVENTS`: the runaway, lift-off (C_e falling through 0), stick (D reaching 0)."""
    g = np.empty(3)
    g[0] = args[_XB_LIMIT] - abs(y[3] - args[_XB0])
    g[1] = contact_state(t, y, args)[_C_E]
    g[2] = args[_SIGMA] * (y[2] - y[1])
    return g


@jit
def locked_events(t, y, args):
    """:data:`LOCKED_EVENTS`: the runaway, lift-off, and the friction bound |C_lock| = C_e tan(psi) either side."""
    r = contact_state(t, y, args)
    bound = r[_C_E] * args[_TAN_PSI]
    g = np.empty(4)
    g[0] = args[_XB_LIMIT] - abs(y[2] - args[_XB0])
    g[1] = r[_C_E]
    g[2] = bound - r[_C_X]
    g[3] = bound + r[_C_X]
    return g


@jit(inline="always")
def _free_local(y, args):
    """kappa* and its slopes where the line of centres of a free state, phi = atan2(xi, eta), meets the surfaces."""
    phi = math.atan2(y[0], y[1])
    return _local(phi - y[5], phi - y[4], args)


@jit
def free_rhs(t, y, args):
    """Free flight (2.11) with Theta_a' = Omega_a and the roughness seen, S' = kappa^2 r*'.

    ``y`` = (xi, eta, Omega_a, Omega_b, X_b, Theta_a, S). kappa^2 phi' =
    (eta xi' - xi eta')/rho^2 is regular at kappa = 0 (:mod:`dynamics.equations.reduced`).
    """
    f = reduced.rhs(t, y, args)
    xi, eta = y[0], y[1]
    rho2 = 1.0 + xi * xi + eta * eta
    kappa2 = (xi * xi + eta * eta) / rho2
    turning = (eta * f[0] - xi * f[1]) / rho2
    kappa, omk, dkappa_a, dkappa_b = _free_local(y, args)
    zeta3 = (omk * (1.0 + kappa)) ** 1.5
    out = np.empty(7)
    out[:5] = f
    out[5] = y[2]
    out[6] = (dkappa_a * (turning - kappa2 * y[2]) + dkappa_b * (turning - kappa2 * y[3])) / zeta3
    return out


@jit
def free_jacobian(t, y, args):
    """Jacobian of :func:`free_rhs`: the reduced model's, Theta_a' = Omega_a, and no row for S.

    S feeds back into nothing, so its row cannot slow Newton's iteration.
    """
    jac = np.zeros((7, 7))
    jac[:5, :5] = reduced.jacobian(t, y, args)
    jac[5, 2] = 1.0
    return jac


@jit
def free_events(t, y, args):
    """:data:`FREE_EVENTS`: the runaway, xi eta = 0 (quarter turns), and the clearance r - r* less ``args[7]``."""
    kappa, omk, _, _ = _free_local(y, args)
    g = np.empty(3)
    g[0] = args[_XB_LIMIT] - abs(y[4] - args[_XB0])
    g[1] = y[0] * y[1]
    g[2] = (math.hypot(y[0], y[1]) - kappa / math.sqrt(omk * (1.0 + kappa))) - args[_CLEARANCE0]
    return g


@jit
def _contact_table(y, args):
    """kappa*, 1 - kappa*, C_e, C_x, phi' and kappa*' of contact states ``y`` (shape (n, k)), shape (6, k).

    kappa*' = k_a theta_a' + k_b theta_b' with theta' = phi' - Omega: the gap
    follows the surfaces as they turn past the line of centres.
    """
    n, k = y.shape
    out = np.empty((6, k))
    row = np.empty(n)
    for i in range(k):
        for j in range(n):
            row[j] = y[j, i]
        r = contact_state(0.0, row, args)
        out[0, i] = r[_KAPPA]
        out[1, i] = r[_ONE_MINUS_KAPPA]
        out[2, i] = r[_C_E]
        out[3, i] = r[_C_X]
        phi_dot = r[_PHI_DOT]
        out[4, i] = phi_dot
        omega_a, omega_b = row[1], (row[1] if n == 4 else row[2])
        _, _, dkappa_a, dkappa_b = _local(row[0] - row[n - 1], row[0] - row[n - 2], args)
        out[5, i] = dkappa_a * (phi_dot - omega_a) + dkappa_b * (phi_dot - omega_b)
    return out


# -- the phases as the hybrid driver runs them ------------------------------------------

class RoughContactRun:
    """What the phases of one rough contact run share: groups, surfaces, limits, tolerances."""

    def __init__(self, params: ReducedParams, rough: RoughContact, limits: Limits, rtol: float, x_b0: float):
        self.params, self.rough, self.rtol = params, rough, rtol
        self.atol = rtol  # every component is O(1) in these units
        self.tan_psi = rough.mean.tan_psi
        self.x_b_limit = 2.0 * math.pi * limits.max_turns
        self.x_b0 = x_b0

    def args(self, sigma: float = 0.0, clearance0: float = 0.0) -> np.ndarray:
        return phase_args(self.params, self.rough, sigma, x_b_limit=self.x_b_limit, x_b0=self.x_b0,
                          clearance0=clearance0)

    def state(self, y) -> np.ndarray:
        """:func:`contact_state` of a contact state, sliding or locked (sigma 0: C_x is C_lock or 0)."""
        return contact_state(0.0, np.asarray(y, dtype=float), self.args())

    def free(self, y, *, on_constraint: bool = False, record: bool = True) -> Phase:
        """The free phase from ``y``; ``on_constraint``: clearance exactly 0 at its start (module docstring)."""
        y = np.asarray(y, dtype=float)
        args = self.args()
        if on_constraint:
            args = self.args(clearance0=float(free_events(0.0, y, args)[2]))
        return Phase(FREE, free_rhs, free_jacobian, free_events, args, y, FREE_EVENTS, (1, 0, 1), (-1, 0, 1),
                     np.full(7, self.atol), record=record)

    def sliding(self, y, sigma: float) -> Phase:
        stick = int(self.tan_psi > 0.0)  # with psi = 0 there is no friction and D = 0 is no event
        return Phase(SLIDING, sliding_rhs, sliding_jacobian, sliding_events, self.args(sigma),
                     np.asarray(y, dtype=float), SLIDING_EVENTS, (1, 1, stick), (-1, -1, -1), np.full(5, self.atol),
                     sigma=sigma)

    def locked(self, y) -> Phase:
        return Phase(LOCKED, locked_rhs, locked_jacobian, locked_events, self.args(), np.asarray(y, dtype=float),
                     LOCKED_EVENTS, (1, 1, 1, 1), (-1, -1, -1, -1), np.full(4, self.atol))

    def enter_contact(self, phi, omega_a, omega_b, x_b, turned_a) -> Phase:
        """Phase and state on touching or at D = 0: locked if the friction can hold it, else sliding.

        Locked, Omega_a jumps to Omega_b, and C_e depends on Omega_a: the test
        uses the reaction of the state after the jump. Sliding has sigma =
        sgn(D), or -sgn(C_lock) at D = 0 (the Filippov choice).
        """
        locked = np.array([phi, omega_b, x_b, turned_a])
        hold = self.state(locked)
        if abs(hold[_C_X]) < hold[_C_E] * self.tan_psi:
            return self.locked(locked)
        if self.tan_psi == 0.0:
            sigma = 0.0
        elif omega_b != omega_a:
            sigma = math.copysign(1.0, omega_b - omega_a)
        else:
            sigma = -math.copysign(1.0, hold[_C_X])
        return self.sliding([phi, omega_a, omega_b, x_b, turned_a], sigma)

    def transition(self, phase: Phase, reason: str, end, phi: float) -> Phase:
        """The phase after the switch ``reason`` from ``phase`` at the final state ``end``, angle ``phi``."""
        if reason == "lift":  # onto the free motion at r = r*(theta_a, theta_b), leaving tangentially
            omega_a, omega_b = (end[1], end[1]) if phase.name == LOCKED else (end[1], end[2])
            here = self.state(end)
            r_star = here[_KAPPA] / math.sqrt(here[_ONE_MINUS_KAPPA] * (1.0 + here[_KAPPA]))
            return self.free([r_star * math.sin(end[0]), r_star * math.cos(end[0]), omega_a, omega_b, end[-2],
                              end[-1], 0.0], on_constraint=True)
        if phase.name == FREE:
            if self.state([phi, end[2], end[3], end[4], end[5]])[_C_E] <= self.rtol:
                # A graze: the free motion meets the constraint tangentially to within the
                # tolerance, and a contact would end as it began. Fly on from the touch.
                return self.free(np.concatenate((end[:6], (0.0,))), on_constraint=True, record=False)
            return self.enter_contact(phi, end[2], end[3], end[4], end[5])
        if phase.name == SLIDING:  # D = 0: lock if the friction holds, else slide the other way
            return self.enter_contact(end[0], end[2], end[2], end[3], end[4])
        # the friction bound is reached: slide, from D = 0, the way the friction no longer prevents
        return self.sliding([end[0], end[1], end[1], end[2], end[3]], -math.copysign(1.0, self.state(end)[_C_X]))

    def columns(self, phase: Phase, t, y, kind) -> dict:
        """Output columns of one phase's rows (state y, shape (n_state, k)), scaled units, and the body angles."""
        if phase.name == FREE:
            cols = reduced.columns(y[:5], phase.extra["phi0"], self.params.args)
            zeros = np.zeros(t.size)
            return {**cols, "c_eps": zeros, "c_chi": zeros, "theta_a": cols["phi"] - y[5],
                    "theta_b": cols["phi"] - y[4]}
        kappa, omk, c_e, c_x, phi_dot, kappa_dot = _contact_table(y, phase.args)
        phi = y[0]
        return {"kappa": kappa, "one_minus_kappa": omk, "phi": phi, "kappa_dot": kappa_dot, "phi_dot": phi_dot,
                "omega_a": y[1],
                "omega_b": y[1] if phase.name == LOCKED else y[2], "x_b": y[-2], "c_eps": c_e, "c_chi": c_x,
                "theta_a": phi - y[-1], "theta_b": phi - y[-2]}


def run_rough_contact(params: ReducedParams, rough: RoughContact, t_end: float, kappa0: float, phi0: float,
                      omega_a0: float = 0.0, omega_b0: float = 0.0, x_b0: float = 0.0, *,
                      limits: Limits = _LIMITS, method: str = "radau", rtol: float = 1e-8, t_eval=None,
                      steps=None, max_steps: int = 2_000_000, max_switches: int = MAX_SWITCHES,
                      progress=None) -> dict:
    """The reduced model with contact on rough surfaces from t = 0 to ``t_end`` (units of tau).

    Parameters
    ----------
    params : ReducedParams
    rough : RoughContact
        Mean contact, amplitude and the two surfaces (:mod:`dynamics.contact.roughness`).
    t_end : float
        Final time in units of tau.
    kappa0 : float
        Initial eccentricity, in [0, kappa*(phi0, phi0 - x_b0)]: Theta_a
        starts at 0, so the initial body angles are theta_a = phi0 and
        theta_b = phi0 - x_b0. At that kappa*, with the free motion pushing in
        (C_e > 0), the run starts in contact as on touching.
    phi0, omega_a0, omega_b0, x_b0 : float
        Initial angle from the upward vertical (rad), rates (1/tau), position (b).
    limits, method, rtol, t_eval, steps, max_steps, max_switches, progress
        As for :func:`dynamics.contact.reduced.run_contact` (only ``limits.max_turns``
        applies: the gap floor lies beyond the asperities, and without an
        apparatus there is no Reynolds number).

    Returns
    -------
    dict
        The fields of :func:`numerics.hybrid.run_phases` with columns kappa,
        one_minus_kappa, phi, omega_a, omega_b, x_b, c_eps, c_chi, theta_a and
        theta_b (the body angles phi - Theta_a and phi - X_b, rad), scaled units.
        Use :func:`dynamics.simulation.simulate` for a :class:`~dynamics.simulation.Trajectory`.

    Raises
    ------
    ValueError
        For out-of-range arguments.
    """
    phi0 = check_finite("phi0", phi0)
    omega_a0, omega_b0, x_b0 = (check_finite(k, v) for k, v in
                                (("omega_a0", omega_a0), ("omega_b0", omega_b0), ("x_b0", x_b0)))
    kappa_touch = rough.local_at(phi0, phi0 - x_b0).kappa
    kappa0 = check_range("kappa0", kappa0, 0.0, kappa_touch, high_open=False,
                         unit="(kappa* at the initial contact angles)")
    run = RoughContactRun(params, rough, limits, rtol, x_b0)
    on_constraint = kappa0 == kappa_touch
    if on_constraint and run.state([phi0, omega_a0, omega_b0, x_b0, 0.0])[_C_E] > 0.0:
        start = run.enter_contact(phi0, omega_a0, omega_b0, x_b0, 0.0)
    else:
        start = run.free(np.concatenate((initial_state(kappa0, phi0, omega_a0, omega_b0, x_b0), (0.0, 0.0))),
                         on_constraint=on_constraint)
    return run_phases(start, lambda phase, reason, t, end, phi: run.transition(phase, reason, end, phi),
                      run.columns, t_end, phi0=phi0, method=method, rtol=rtol, t_eval=t_eval, steps=steps,
                      max_steps=max_steps, max_switches=max_switches, progress=progress)
