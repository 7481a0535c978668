r"""Rough surfaces that turn with the cylinders, in the full equations (2.1)-(2.4).

:mod:`dynamics.contact.full` stops the centres at a uniform eps* = delta kappa*;
:mod:`dynamics.contact.rough` moves the reduced model's contact onto the minimum
gap kappa*(theta_a, theta_b) of :mod:`dynamics.contact.roughness`, which turns with
both cylinders. This module does the same in the full equations, with the hard
contact of section 5 (free, locked and sliding phases on the moving constraint)
or the compliant asperity contact of :mod:`dynamics.contact.laws`, and Coulomb or
Stribeck friction.

State
-----
The body angles where the line of centres meets the surfaces are
theta_a = phi - Theta_a and theta_b = phi - X_b/b, phi = chi + alpha
(:mod:`dynamics.contact.roughness`), so the state carries Theta_a, the angle
the inner cylinder has turned, Theta_a' = Omega_a (X_b is already in it):

free
    (Theta_a, S, u_x, u_z, v_x, v_z, Omega_a, Omega_b, X_b): Theta_a, the
    roughness seen S (below), then the free full model's Cartesian state
    (:mod:`dynamics.equations.full`), whose right-hand side it calls unchanged:
    the free motion does not see the asperities.
contact (locked or sliding)
    (Theta_a, chi, chi', Omega_a, Omega_b, X_b), eps = eps*(theta_a, theta_b).
compliant
    (Theta_a, S, u_x, u_z, v_x, v_z, Omega_a, Omega_b, X_b), one smooth phase.

With amplitude 0 the surfaces are uniform: nothing depends on Theta_a and S is
identically 0, so the run carries neither, and its states are those of
:mod:`dynamics.contact.full` (below: the uniform limit).

The constraint and its reaction
-------------------------------
In the configuration (r, Theta_a, Theta_b = X_b/b), r = eps e_eps the
displacement B -> A, the asperities impose

    G = eps*(theta_a, theta_b) - eps >= 0,      eps* = delta kappa*.

With k_a, k_b the slopes of kappa* and P = k_a + k_b (theta_a and theta_b
both turn with chi, d eps*/d chi = delta P, and d chi/dr = e_chi/eps),

    grad G = ( delta P/eps e_chi - e_eps,  -delta k_a,  -delta k_b ).

The reaction is N grad G, N >= 0 (as :mod:`dynamics.contact.rough` derives it):
on A the force N(-e_eps + (delta P/eps) e_chi), the torque -N delta k_a about
A, and on B the opposite force and the torque -N delta k_b about B. G is
unchanged by a rigid rotation of everything (chi, Theta_a, Theta_b all
advanced by one angle), so the system has no net torque about B:
N delta P - N delta k_a - N delta k_b = 0. The full equations take it, as every
force between the cylinders, through :func:`dynamics.equations.full.force_response`
with (f_eps, f_chi, T_a) = (-N, N delta P/eps, -N delta k_a): the torque on B
that this map implies, -(T_a + eps f_chi) = -N delta k_b, is the reaction's.
In units of m'_a g this is section 5's C_e, its e_chi component the tilt of
(2.11b), its torque the tau of (5.2) (:mod:`dynamics.contact.rough`).

Friction F acts along e_chi at the contact, a e_eps from A, with the torque a F
on A (as :mod:`dynamics.contact.full`), against the slip
s = eps chi' + a Omega_a - (a + eps) Omega_b.

Contact equations. G stays 0, so G'' = 0. With eps' = e_eps . r',
chi' = e_chi . r'/eps, theta' = chi' - Omega,

    eps*'  = delta (k_a theta_a' + k_b theta_b'),
    eps*'' = delta (k_a theta_a'' + k_b theta_b'' + Q),
             Q = k_aa theta_a'^2 + 2 k_ab theta_a' theta_b' + k_bb theta_b'^2,
    eps''  = e_eps . r'' + eps chi'^2,
    chi''  = (e_chi . r'' - 2 eps' chi')/eps,

so G'' = 0 is, in the accelerations (x'', z'', Omega_a', Omega_b'),

    e_eps . r'' + eps chi'^2 - delta [P (e_chi . r'' - 2 eps' chi')/eps - k_a Omega_a' - k_b Omega_b' + Q] = 0,

linear in them, and the accelerations are linear in (N, F) (the force response).
Locked adds s' = 0, s' = e_chi . r'' + a Omega_a' - (a + eps) Omega_b' - eps'(chi' + Omega_b)
(d e_chi/dt = -chi' e_eps); sliding has F = -sigma mu(|s|) N, sigma = sgn(s)
fixed in the phase, mu of :func:`dynamics.contact.laws.friction_coefficient`. Both
are a 2 x 2 (locked) or 1 x 1 (sliding) solve at each evaluation, as in
:mod:`dynamics.contact.full`. The slip is no longer linear in the state with
constant coefficients (eps varies), so a locked phase keeps s' = 0 and s at zero to
the integrator's tolerance, not to rounding.

Power. The reaction's power is N G' = 0 in contact; the friction's is F s.
(2.1)-(2.4) make the mechanical energy of
:func:`dynamics.analysis.mechanical_energy` change at the power of
the forces between the cylinders, so a hard rough run dissipates in the
film (:func:`fluid_dissipation`), by friction and at the impacts.

Switching
---------
* free -> contact when the clearance |u| - u*(theta_a, theta_b) rises through 0,
  u = r/(delta zeta) the stretched displacement and u* = kappa*/zeta* its value
  on the asperities, located on the dense output. The constraint moves, so a
  touch can come from an asperity turning into the inner cylinder. The impact
  is plastic, along grad G: the impulse P_N grad G stops the approach G' (not
  eps'), the tangential one P_F stops the slip if |P_F| <= mu_s P_N, else
  P_F = -sgn(s) mu(|s|) P_N, and (2.4)'s angular momentum is conserved
  (:mod:`dynamics.contact.full`). Then locked, sliding or free as there.
* contact -> free when N falls through 0; the free state leaves on the
  constraint with G' = 0 (eps' = eps*').
* locked <-> sliding when |F| reaches mu_s N, and when s reaches 0.

The free phase's touch sees the asperities only at the points it evaluates.
So that its steps cannot stride over an asperity that the line of centres
sweeps past, the free phase carries S' = kappa^2 u*', the roughness seen along
its path, under error control (as :mod:`dynamics.contact.rough`; kappa^2 keeps it
finite at the centre), and a free phase that starts on the constraint measures
its clearance from its own start (the shift of :mod:`dynamics.contact.rough`).
In the full model the radial inertia already keeps the free steps short near
the constraint: no run of the tests, spinning cylinders on asperities of
correlation 0.02 rad included, missed a touch without S. It is kept as the
reduced model's safeguard, at the cost of its error control.

The compliant contact
---------------------
One smooth phase: the free full model plus the force of
:mod:`dynamics.contact.laws`, N grad G with N = P(d) - c_d(d) d', d = G, and the
regularised friction F along e_chi, through the same force response. It has
no touch, no impact and no lift. As the stiffness grows it tends to the hard
contact (tests/test_rough_full.py measures the order).

The uniform limit
-----------------
At amplitude 0, k_a = k_b = 0 and all curvatures vanish exactly, kappa* is
kappa*_mean to the last bit, and every formula above is written as the uniform
contact's plus terms that are then exactly 0 (x - 0 = x in floating point).
The run carries no Theta_a and no S (nothing depends on them), so its states,
tolerances, Jacobians and events are those of :mod:`dynamics.contact.full`: a
hard run with Coulomb friction reproduces the uniform contact's run bit for bit
(tests/test_rough_full.py). Zeros may differ in sign (-0.0 for 0.0), which no
comparison sees.

Units. SI, times in s, as :mod:`dynamics.contact.full`; the run's fields come
back in tau, rates in 1/tau, X_b in b, c_eps = N/(m'_a g) and
c_chi = -F/((delta/a) m'_a g), the C_e and C_x of section 5.
"""

from __future__ import annotations

import functools
import math
from collections import namedtuple

import numpy as np

from dynamics.contact.full import LOCKED_EVENTS, SLIDING_EVENTS, friction_coefficient, phases_in_tau
from dynamics.contact.laws import COMPLIANT, gw_load, height_scale
from dynamics.contact.laws import friction_coefficient as stribeck_mu
from dynamics.contact.reduced import FREE, LOCKED, SLIDING
from dynamics.contact.roughness import RoughContact, _local2_kernel
from dynamics.equations import full
from dynamics.equations.limits import Limits
from lubrication.geometry import check_range
from lubrication.kernels import KernelModel
from numerics.hybrid import MAX_SWITCHES, Phase
from numerics.jit import jit, specialise
from numerics.packed import pack, part, parts

__all__ = [
    "COMPLIANT_EVENTS",
    "FREE_EVENTS",
    "RoughFullFunctions",
    "RoughFullRun",
    "fluid_dissipation",
    "rough_full_functions",
    "run_rough_full",
]

#: The events of the free phase (those of :data:`dynamics.equations.full.EVENT_NAMES`, the touch on the
#: moving constraint) and of the compliant phase (no touch).
FREE_EVENTS = full.EVENT_NAMES
COMPLIANT_EVENTS = full.EVENT_NAMES[:4]

# part EVENTS of every phase's args: the first 7 numbers as dynamics.equations.full.run_args (free and compliant
# phases) or dynamics.contact.full (contact phases), then this block, ending with the sizes of the surfaces'
# tables (SurfaceHeights.jets) and the tables
_XB_LIMIT, _XB0, _KSTAR, _OMK_STAR, _LOCKED, _SIGMA, _MU_F = range(7)  # the contact phases' first 7
(_PASSIVE, _CLEARANCE0, _ALPHA, _AMPLITUDE, _KAPPA_MEAN, _GAP_MEAN, _MU_KINETIC, _MU_STATIC, _V_STRIBECK,
 _WEIGHT, _ELL, _DAMPING, _GAUSSIAN, _V_SLIP, _NORM, _SIZE_A, _SIZE_B, _JETS) = range(7, 25)
_A, _B = 0, 1  # in the parameter array of dynamics.equations.full


@jit(inline="always")
def _field(theta_a, theta_b, c):
    """kappa*, 1 - kappa*, k_a, k_b, k_aa, k_ab, k_bb at the body angles (:mod:`dynamics.contact.roughness`)."""
    j = _JETS + int(c[_SIZE_A])
    return _local2_kernel(theta_a, theta_b, c[_JETS:j], c[j:j + int(c[_SIZE_B])], c[_AMPLITUDE], c[_KAPPA_MEAN],
                          c[_GAP_MEAN])


@jit(inline="always")
def _core(y, off):
    """The full model's state (last 7 components) of a rough state with ``off`` leading passive ones."""
    core = np.empty(7)
    for i in range(7):
        core[i] = y[off + i]
    return core


@jit(inline="always")
def _seen(core, turned_a, p, c):
    """S' = kappa^2 u*', the rate at which the line of centres sweeps the threshold u* (module docstring)."""
    ux, uz, vx, vz = core[0], core[1], core[2], core[3]
    big_u = math.hypot(ux, uz)
    if big_u == 0.0:
        return 0.0
    one_plus = 1.0 + big_u * big_u
    ex, ez = ux / big_u, uz / big_u
    kappa = big_u / math.sqrt(one_plus)
    kappa2_chi_dot = kappa * (ez * vx - ex * vz) / (p[_B] - p[_A])  # kappa^2 chi', finite at the centre
    kappa2 = big_u * big_u / one_plus
    phi = math.atan2(ux, uz) + c[_ALPHA]
    ks, oms, ka, kb, _, _, _ = _field(phi - turned_a, phi - core[6] / p[_B], c)
    zeta3 = (oms * (1.0 + ks)) ** 1.5
    return (ka * (kappa2_chi_dot - kappa2 * core[4]) + kb * (kappa2_chi_dot - kappa2 * core[5])) / zeta3


# -- free flight (templates: RHS and JAC are the free full model's, bound by _compiled) -----------------

def _free_rhs(t, y, args):
    """d/dt of a free state: the full model's rates, Theta_a' = Omega_a and S' (module docstring)."""
    c = part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    if off == 0:
        return RHS(t, y, args)  # noqa: F821
    core = _core(y, off)
    f = RHS(t, core, args)  # noqa: F821
    out = np.empty(y.size)
    for i in range(7):
        out[off + i] = f[i]
    out[0] = core[4]
    out[1] = _seen(core, y[0], part(args, full.PARAMETERS), c)
    return out


def _free_jacobian(t, y, args):
    """The full model's Jacobian, Theta_a' = Omega_a, and no row for S (nothing depends on S)."""
    c = part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    if off == 0:
        return JAC(t, y, args)  # noqa: F821
    inner = JAC(t, _core(y, off), args)  # noqa: F821
    jac = np.zeros((y.size, y.size))
    for i in range(7):
        for j in range(7):
            jac[off + i, off + j] = inner[i, j]
    jac[0, off + 4] = 1.0
    return jac


@jit
def free_events(t, y, args):
    """:data:`FREE_EVENTS`: the full model's validity limits, runaway and turn, and the touch
    |u| - u*(theta_a, theta_b) less the phase's starting clearance."""
    p, c = part(args, full.PARAMETERS), part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    core = _core(y, off)
    g = np.empty(5)
    big_u = math.hypot(core[0], core[1])
    full._event_values(core, c, big_u, full.reduced_reynolds(core, p, c), g)
    turned = y[0] if off > 0 else 0.0
    phi = math.atan2(core[0], core[1]) + c[_ALPHA]
    ks, oms, _, _, _, _, _ = _field(phi - turned, phi - core[6] / p[_B], c)
    g[4] = (big_u - ks / math.sqrt(oms * (1.0 + ks))) - c[_CLEARANCE0]
    return g


# -- contact on the moving constraint (templates: FORCES, RATES, CONTACT_RHS bound by _compiled) ----------

def _contact_rates(y, p, c, locked, sigma, model):
    """(chi'', Omega_a', Omega_b', N, F, eps*', kappa*, 1 - kappa*) in contact, SI (module docstring).

    ``y`` = ([Theta_a,] chi, chi', Omega_a, Omega_b, X_b). Written as
    :func:`dynamics.contact.full._contact_rates` plus the terms of the moving
    constraint, which are exactly 0 on uniform surfaces.
    """
    off = int(c[_PASSIVE])
    a, b = p[0], p[1]
    delta = b - a
    chi, chi_dot, omega_a, omega_b, x_b = y[off], y[off + 1], y[off + 2], y[off + 3], y[off + 4]
    turned = y[0] if off > 0 else 0.0
    phi = chi + c[_ALPHA]
    kappa, omk, ka, kb, kaa, kab, kbb = _field(phi - turned, phi - x_b / b, c)
    eps = kappa * (b - a)
    dot_a, dot_b = chi_dot - omega_a, chi_dot - omega_b
    eps_dot = delta * (ka * dot_a + kb * dot_b) + 0.0  # eps*', with +0.0 for -0.0
    ex, ez = math.sin(chi), math.cos(chi)
    cx, cz = ez, -ex
    f_eps, f_chi, t_a = FORCES(model, a, b, p[3], p[2], kappa, omk, eps_dot,  # noqa: F821
                               omega_a - chi_dot, omega_b - chi_dot)
    frame_eps, frame_chi = full.frame_force(p, eps, eps_dot, chi_dot, omega_a, omega_b)
    spin = full.spin_state(p, kappa, eps, eps_dot, chi_dot, omega_a, omega_b)
    fluid = full.force_response(p, eps, ex, ez, f_eps + frame_eps, f_chi + frame_chi, t_a, spin)
    gravity = full.gravity_response(p, eps, ex, ez, spin)
    base = np.empty(4)
    for i in range(4):
        base[i] = fluid[i] + gravity[i]
    tilt = delta * (ka + kb) / eps
    normal = full.force_response(p, eps, ex, ez, -1.0, tilt, 0.0 - delta * ka, spin)  # unit N along grad G
    friction = full.force_response(p, eps, ex, ez, 0.0, 1.0, a, spin)    # unit F along e_chi, torque a F
    curl = kaa * dot_a * dot_a + 2.0 * kab * dot_a * dot_b + kbb * dot_b * dot_b
    arm = a + eps
    # G'' = -(r0 + N r_n + F r_f): eps'' less eps*'' in the accelerations
    r0 = ex * base[0] + ez * base[1] + eps * chi_dot * chi_dot - (
        tilt * (cx * base[0] + cz * base[1] - 2.0 * eps_dot * chi_dot) - delta * (ka * base[2] + kb * base[3] - curl))
    r_n = ex * normal[0] + ez * normal[1] - (
        tilt * (cx * normal[0] + cz * normal[1]) - delta * (ka * normal[2] + kb * normal[3]))
    r_f = ex * friction[0] + ez * friction[1] - (
        tilt * (cx * friction[0] + cz * friction[1]) - delta * (ka * friction[2] + kb * friction[3]))
    if locked:
        s0 = cx * base[0] + cz * base[1] + a * base[2] - arm * base[3] - eps_dot * (chi_dot + omega_b)
        s_n = cx * normal[0] + cz * normal[1] + a * normal[2] - arm * normal[3]
        s_f = cx * friction[0] + cz * friction[1] + a * friction[2] - arm * friction[3]
        det = r_n * s_f - r_f * s_n
        n_force = (-r0 * s_f + r_f * s0) / det
        f_force = (-r_n * s0 + s_n * r0) / det
    else:
        slip = eps * (chi_dot - omega_b) + a * (omega_a - omega_b)
        mu = stribeck_mu(slip, c[_MU_KINETIC], c[_MU_STATIC], c[_V_STRIBECK])
        n_force = -r0 / (r_n - sigma * mu * r_f)
        f_force = -sigma * mu * n_force
    out = np.empty(8)
    acc = np.empty(4)
    for i in range(4):
        acc[i] = base[i] + n_force * normal[i] + f_force * friction[i]
    out[0] = (cx * acc[0] + cz * acc[1] - 2.0 * eps_dot * chi_dot) / eps
    out[1], out[2] = acc[2], acc[3]
    out[3], out[4] = n_force, f_force
    out[5], out[6], out[7] = eps_dot, kappa, omk
    return out


def _contact_rhs(t, y, args):
    """d/dt ([Theta_a,] chi, chi', Omega_a, Omega_b, X_b) in contact (SI)."""
    p, model, c = part(args, full.PARAMETERS), part(args, full.MODEL), part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    r = RATES(y, p, c, c[_LOCKED] > 0.0, c[_SIGMA], model)  # noqa: F821
    out = np.empty(y.size)
    if off > 0:
        out[0] = y[off + 2]
    out[off] = y[off + 1]
    out[off + 1] = r[0]
    out[off + 2] = r[1]
    out[off + 3] = r[2]
    out[off + 4] = p[1] * y[off + 3]
    return out


def _contact_jacobian(t, y, args):
    """d(contact rhs)/dy by central differences (:func:`dynamics.equations.full.central_differences`)."""
    return full.central_differences(CONTACT_RHS, t, y, args, part(args, full.TYPICAL))  # noqa: F821


def _contact_events(t, y, args):
    """Locked: :data:`dynamics.contact.full.LOCKED_EVENTS`; sliding: ``SLIDING_EVENTS`` (the fourth unused).

    The runaway; lift-off as N falls through 0; locked, the static bound
    |F| = mu_s N on either side; sliding, the slip reaching 0.
    """
    p, model, c = part(args, full.PARAMETERS), part(args, full.MODEL), part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    r = RATES(y, p, c, c[_LOCKED] > 0.0, c[_SIGMA], model)  # noqa: F821
    n_force, f_force = r[3], r[4]
    g = np.empty(4)
    g[0] = c[_XB_LIMIT] - abs(y[off + 4] - c[_XB0])
    g[1] = n_force
    if c[_LOCKED] > 0.0:
        g[2] = c[_MU_STATIC] * n_force - f_force
        g[3] = c[_MU_STATIC] * n_force + f_force
    else:
        eps = r[6] * (p[1] - p[0])
        g[2] = c[_SIGMA] * (eps * (y[off + 1] - y[off + 3]) + p[0] * (y[off + 2] - y[off + 3]))
        g[3] = 1.0
    return g


def _contact_table(rows, p, c, locked, sigma, model):
    """RATES at each row of ``rows`` (shape (k, n), C-contiguous): shape (k, 8), for a contact phase's output
    columns in one call rather than one call a row."""
    out = np.empty((rows.shape[0], 8))
    for i in range(rows.shape[0]):
        r = RATES(rows[i], p, c, locked, sigma, model)  # noqa: F821
        for m in range(8):
            out[i, m] = r[m]
    return out


# -- the compliant contact (templates: RHS and COMPLIANT_RHS bound by _compiled) ----------------------

@jit(inline="always")
def _compliant_force(core, turned_a, p, c):
    """The compliant contact on a free state (:mod:`dynamics.contact.laws`).

    Returns (eps, e_x, e_z, f_eps, f_chi, T_a, N, F, P, c_d, d', slip, d): the force on A along
    e_eps and e_chi and its torque about A (N, N m), the normal force, friction and elastic
    load (N), the damping coefficient (N s/m), the rate of the separation d (m/s), the slip (m/s)
    and d (m).
    """
    a, b = p[_A], p[_B]
    delta = b - a
    kappa, omk, zeta, eps, big_u, ex, ez = full._geometry(core, delta)
    vx, vz, omega_a, omega_b = core[2], core[3], core[4], core[5]
    phi = math.atan2(ex, ez) + c[_ALPHA]
    ks, oms, ka, kb, _, _, _ = _field(phi - turned_a, phi - core[6] / b, c)
    separation = delta * (omk - oms)
    eps_dot = ex * vx + ez * vz
    tangential = ez * vx - ex * vz  # eps chi'
    chi_dot = tangential / eps if eps > 0.0 else 0.0
    rate = delta * (ka * (chi_dot - omega_a) + kb * (chi_dot - omega_b)) - eps_dot
    load = c[_WEIGHT] * gw_load(separation / c[_ELL], c[_GAUSSIAN] > 0.0, c[_NORM])
    slip = tangential + a * omega_a - (a + eps) * omega_b
    if load == 0.0:
        return eps, ex, ez, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, rate, slip, separation
    damping = c[_DAMPING] * math.sqrt(load / c[_ELL])
    normal = load - damping * rate
    mu = stribeck_mu(slip, c[_MU_KINETIC], c[_MU_STATIC], c[_V_STRIBECK])
    v_slip = c[_V_SLIP]
    friction = -mu * load * slip / math.sqrt(slip * slip + v_slip * v_slip)
    return (eps, ex, ez, -normal, normal * delta * (ka + kb) / eps + friction, a * friction - normal * delta * ka,
            normal, friction, load, damping, rate, slip, separation)


def _compliant_rhs(t, y, args):
    """d/dt of a compliant state: the free full model plus the contact force, Theta_a' = Omega_a and S'."""
    p, c = part(args, full.PARAMETERS), part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    core = _core(y, off)
    turned = y[0] if off > 0 else 0.0
    f = RHS(t, core, args)  # noqa: F821
    r = _compliant_force(core, turned, p, c)
    out = np.empty(y.size)
    for i in range(7):
        out[off + i] = f[i]
    if r[6] != 0.0 or r[7] != 0.0:
        response = full.force_response(p, r[0], r[1], r[2], r[3], r[4], r[5], full.state_spin(p, core))
        for i in range(4):
            out[off + 2 + i] += response[i]
    if off > 0:
        out[0] = core[4]
        out[1] = _seen(core, turned, p, c)
    return out


def _compliant_jacobian(t, y, args):
    """d(compliant rhs)/dy by central differences; X_b is passive on uniform surfaces."""
    passive = 1 if int(part(args, full.EVENTS)[_PASSIVE]) == 0 else 0
    return full.central_differences(COMPLIANT_RHS, t, y, args, part(args, full.TYPICAL), passive)  # noqa: F821


@jit
def compliant_events(t, y, args):
    """:data:`COMPLIANT_EVENTS`: the full model's validity limits, runaway and turn."""
    p, c = part(args, full.PARAMETERS), part(args, full.EVENTS)
    core = _core(y, int(c[_PASSIVE]))
    g = np.empty(5)
    _ = t
    full._event_values(core, c, math.hypot(core[0], core[1]), full.reduced_reynolds(core, p, c), g)
    return g[:4].copy()


@jit
def compliant_table(y, args):
    """The compliant force along states ``y`` (shape (n, k)): rows N, F, P, c_d, d', slip, d, kappa*, 1 - kappa*."""
    p, c = part(args, full.PARAMETERS), part(args, full.EVENTS)
    off = int(c[_PASSIVE])
    n, k = y.shape
    out = np.empty((9, k))
    row = np.empty(n)
    for i in range(k):
        for j in range(n):
            row[j] = y[j, i]
        core = _core(row, off)
        turned = row[0] if off > 0 else 0.0
        r = _compliant_force(core, turned, p, c)
        for m in range(7):
            out[m, i] = r[6 + m]
        phi = math.atan2(r[1], r[2]) + c[_ALPHA]
        ks, oms, _, _, _, _, _ = _field(phi - turned, phi - core[6] / p[_B], c)
        out[7, i] = ks
        out[8, i] = oms
    return out


#: The compiled functions of the rough phases, for one force kernel.
RoughFullFunctions = namedtuple("RoughFullFunctions", ["free_rhs", "free_jacobian", "rates", "contact_table",
                                                       "contact_rhs", "contact_jacobian", "contact_events",
                                                       "compliant_rhs", "compliant_jacobian"])


def _compiled(forces, free: full.ModelFunctions, name: str) -> RoughFullFunctions:
    rates = specialise(_contact_rates, name, FORCES=forces)
    contact_rhs = specialise(_contact_rhs, name, RATES=rates)
    compliant_rhs = specialise(_compliant_rhs, name, RHS=free.rhs)
    return RoughFullFunctions(specialise(_free_rhs, name, RHS=free.rhs),
                              specialise(_free_jacobian, name, JAC=free.jacobian), rates,
                              specialise(_contact_table, name, RATES=rates), contact_rhs,
                              specialise(_contact_jacobian, name, CONTACT_RHS=contact_rhs),
                              specialise(_contact_events, name, RATES=rates), compliant_rhs,
                              specialise(_compliant_jacobian, name, COMPLIANT_RHS=compliant_rhs))


@functools.cache
def _compiled_for(kernel, name: str) -> RoughFullFunctions:
    return _compiled(kernel, full._compiled_for(kernel, name), name)


def rough_full_functions(model: KernelModel) -> RoughFullFunctions:
    """The rough phases' functions compiled with the force kernel of ``model`` (one set per kernel)."""
    return _compiled_for(model.kernel, model.kernel_name)


def fluid_dissipation(f_eps: float, f_chi: float, t_a: float, eps: float, eps_dot: float, chi_dot: float,
                      omega_a: float, omega_b: float) -> float:
    """The power the fluid dissipates, D = -(f_eps eps' + T_a W_a + T_b W_b) >= 0 (W).

    Derivation. In quasi-steady Stokes flow the walls' power into the fluid is
    its dissipation: D = -(F_a . V_a + T_a Omega_a + F_b . V_b + T_b Omega_b),
    the forces and torques of the fluid on the cylinders. The fluid carries no
    net force, F_b = -F_a = -f, so F_a . V_a + F_b . V_b = f . r'
    = f_eps eps' + f_chi eps chi'; and it carries no net torque about B,
    T_b = -(T_a + eps f_chi) (the identity of PHYSICS.md). Substituting,
    D = -(f_eps eps' + f_chi eps (chi' - Omega_b) + T_a (Omega_a - Omega_b)),
    which is -(f_eps eps' + T_a W_a + T_b W_b) with W = Omega - chi': the loads
    in the frame that turns with the line of centres, where A only moves
    radially and the walls turn at W_a, W_b. For a linear force model
    (f_eps, f_chi, T_a) = -R (eps', W_a, W_b) with R symmetric by reciprocity
    (written for the conjugate loads (f_eps, T_a, T_b)), D is a quadratic form
    of R, positive. (2.1)-(2.4) make the mechanical energy fall at exactly this
    rate when the fluid is the only force between the cylinders.
    """
    t_b = -(t_a + eps * f_chi)
    return -(f_eps * eps_dot + t_a * (omega_a - chi_dot) + t_b * (omega_b - chi_dot))


# -- the phases as the hybrid driver runs them -------------------------------------------------------

class RoughFullRun:
    """What the phases of one rough full-model run share: device, surfaces, laws, limits, tolerances."""

    def __init__(self, apparatus, force_model: KernelModel, rough: RoughContact, limits: Limits, rtol: float,
                 frame_terms: str = full.DEFAULT_FRAME_TERMS, fluid_spin: str = full.DEFAULT_FLUID_SPIN):
        ap = apparatus
        self.ap, self.rough, self.limits, self.rtol = ap, rough, limits, rtol
        self.mean = rough.mean
        self.varies = rough.amplitude > 0.0
        self.p = full.params_array(ap, frame_terms, fluid_spin)
        self.model = full.model_arguments(force_model)
        self.functions = rough_full_functions(force_model)
        self.free_functions = full.model_functions(force_model)
        self.mu_k = friction_coefficient(ap, rough.mean)
        friction = rough.friction
        self.mu_s = self.mu_k if friction is None else ap.delta_over_a * math.tan(friction.psi_static)
        self.v_stribeck = math.inf if friction is None else friction.velocity
        self.weight = ap.m_a_reduced * ap.g
        self.compliance = rough.compliance
        if self.compliance is not None:
            sigma_mean = ap.delta * rough.mean.one_minus_kappa_star
            stiffness = self.compliance.resolved_stiffness(self.weight, sigma_mean)
            self.ell, self.norm = height_scale(self.compliance.heights, self.weight, stiffness)
            self.stiffness = stiffness
        tau = ap.tau
        self.free_args = full.run_args(ap, force_model, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                                       max_turns=limits.max_turns, kappa_star=rough.mean.kappa_star,
                                       frame_terms=frame_terms, fluid_spin=fluid_spin)
        self.contact_typical = np.array([1.0, 1.0 / tau, 1.0 / tau, 1.0 / tau, ap.b])
        self.runaway = np.array([2.0 * math.pi * ap.b * limits.max_turns, 0.0])
        self.passive_free = 2 if self.varies else 0
        self.passive_contact = 1 if self.varies else 0
        self._blocks: dict = {}
        self._numbers: dict = {}  # the contact phases' numbers and args, by (locked, sigma)
        self._contact_args: dict = {}

    # the numbers of every phase ----------------------------------------------------------------
    def _block(self, passive: int, clearance0: float = 0.0) -> np.ndarray:
        key = (passive, clearance0)
        if key not in self._blocks:
            self._blocks = {k: v for k, v in self._blocks.items() if k[1] == 0.0}  # keep the shifts' few
            self._blocks[key] = self._new_block(passive, clearance0)
        return self._blocks[key]

    def _new_block(self, passive: int, clearance0: float) -> np.ndarray:
        ap, rough, law = self.ap, self.rough, self.compliance
        inner, outer = rough.inner, rough.outer
        compliant = ([self.weight, self.ell, 2.0 * law.damping_ratio * math.sqrt(ap.m_eff),
                      float(law.heights == "gaussian"), law.slip_velocity, self.norm] if law is not None
                     else [self.weight, 1.0, 0.0, 0.0, 1.0, 1.0])
        return np.concatenate(([float(passive), clearance0, ap.alpha, rough.amplitude, self.mean.kappa_star,
                                self.mean.one_minus_kappa_star, self.mu_k, self.mu_s, self.v_stribeck],
                               compliant, [float(inner.jets.size), float(outer.jets.size)], inner.jets, outer.jets))

    def free_args_for(self, clearance0: float = 0.0) -> np.ndarray:
        p, model, typical, ev = parts(self.free_args)
        return pack(p, model, typical, np.concatenate((ev, self._block(self.passive_free, clearance0))))

    def _contact_numbers(self, locked: bool, sigma: float) -> np.ndarray:
        """The part EVENTS of a contact phase's args (the rates of every output row read it too); kept, as it holds
        the surfaces' tables and a run asks for it at every switch."""
        key = (locked, sigma)
        if key not in self._numbers:
            numbers = np.array([*self.runaway, self.mean.kappa_star, self.mean.one_minus_kappa_star, float(locked),
                                sigma, self.mu_k])
            self._numbers[key] = np.concatenate((numbers, self._block(self.passive_contact)))
        return self._numbers[key]

    def contact_args(self, locked: bool, sigma: float) -> np.ndarray:
        key = (locked, sigma)
        if key not in self._contact_args:
            typical = (np.concatenate(([1.0], self.contact_typical)) if self.varies else self.contact_typical)
            self._contact_args[key] = pack(self.p, self.model, typical, self._contact_numbers(locked, sigma))
        return self._contact_args[key]

    def compliant_args(self) -> np.ndarray:
        typical = parts(self.free_args)[full.TYPICAL]
        if self.varies:
            typical = np.concatenate(([1.0, 1.0], typical))
        ev = parts(self.free_args)[full.EVENTS].copy()
        ev[6] = math.inf  # no touch
        return pack(self.p, self.model, typical, np.concatenate((ev, self._block(self.passive_free))))

    # rates and states in Python --------------------------------------------------------------------
    def rates(self, y, locked: bool, sigma: float) -> np.ndarray:
        """``_contact_rates`` of a contact state ``y``: chi'', Omega_a', Omega_b', N, F, eps*', kappa*, 1 - kappa*."""
        return self.functions.rates(np.asarray(y, float), self.p, self._contact_numbers(locked, sigma), locked, sigma,
                                    self.model)

    def _angles(self, chi: float, turned_a: float, x_b: float):
        phi = chi + self.ap.alpha
        return phi - turned_a, phi - x_b / self.ap.b

    def local(self, chi: float, turned_a: float, x_b: float):
        """(kappa*, 1 - kappa*, k_a, k_b) where the line of centres at ``chi`` meets the surfaces."""
        return self.rough.local_at(*self._angles(chi, turned_a, x_b))

    def slip(self, y) -> float:
        """eps (chi' - Omega_b) + a (Omega_a - Omega_b) (m/s) at the contact point of a contact state."""
        off = self.passive_contact
        eps = self.rates(y, True, 0.0)[6] * self.ap.delta
        return eps * (y[off + 1] - y[off + 3]) + self.ap.a * (y[off + 2] - y[off + 3])

    def _free_state(self, y) -> np.ndarray:
        """The free state on the constraint of a contact state, eps' = eps*' (module docstring)."""
        off = self.passive_contact
        chi, chi_dot, turned = y[off], y[off + 1], (y[0] if off else 0.0)
        here = self.rates(y, False, 1.0)
        kappa, omk, eps_dot = here[6], here[7], here[5]
        zeta = math.sqrt(omk * (1.0 + kappa))
        u = kappa / zeta
        speed = kappa * self.ap.delta * chi_dot
        state = [u * math.sin(chi), u * math.cos(chi), speed * math.cos(chi) + eps_dot * math.sin(chi),
                 -speed * math.sin(chi) + eps_dot * math.cos(chi), y[off + 2], y[off + 3], y[off + 4]]
        return np.array(([turned, 0.0] if self.varies else []) + state)

    # the phases ----------------------------------------------------------------------------------
    def free(self, y, *, on_constraint: bool = False, record: bool = True) -> Phase:
        """The free phase from ``y``; ``on_constraint`` on rough surfaces: clearance exactly 0 at its start."""
        y = np.asarray(y, float)
        args = self.free_args_for()
        if on_constraint and self.varies:
            args = self.free_args_for(float(free_events(0.0, y, args)[4]))
        stops = int(self.limits.stops)
        atol = self.rtol * parts(self.free_args)[full.TYPICAL]
        if self.varies:
            atol = np.concatenate(([self.rtol, self.rtol], atol))
        return Phase(FREE, self.functions.free_rhs, self.functions.free_jacobian, free_events, args, y,
                     FREE_EVENTS, (stops, stops, 1, 0, 1), (-1, -1, -1, 0, 1), atol, record=record)

    def _contact_atol(self) -> np.ndarray:
        atol = self.rtol * self.contact_typical
        return np.concatenate(([self.rtol], atol)) if self.varies else atol

    def locked(self, y) -> Phase:
        f = self.functions
        return Phase(LOCKED, f.contact_rhs, f.contact_jacobian, f.contact_events, self.contact_args(True, 0.0),
                     np.asarray(y, float), LOCKED_EVENTS, (1, 1, 1, 1), (-1, -1, -1, -1), self._contact_atol())

    def sliding(self, y, sigma: float) -> Phase:
        stick = int(self.mu_k > 0.0 or self.mu_s > 0.0)
        f = self.functions
        return Phase(SLIDING, f.contact_rhs, f.contact_jacobian, f.contact_events, self.contact_args(False, sigma),
                     np.asarray(y, float), (*SLIDING_EVENTS, ""), (1, 1, stick, 0), (-1, -1, -1, 0),
                     self._contact_atol(), sigma=sigma)

    def compliant(self, y) -> Phase:
        f = self.functions
        stops = int(self.limits.stops)
        atol = self.rtol * parts(self.free_args)[full.TYPICAL]
        if self.varies:
            atol = np.concatenate(([self.rtol, self.rtol], atol))
        return Phase(COMPLIANT, f.compliant_rhs, f.compliant_jacobian, compliant_events, self.compliant_args(),
                     np.asarray(y, float), COMPLIANT_EVENTS, (stops, stops, 1, 0), (-1, -1, -1, 0), atol)

    def enter_contact(self, y, sigma_hint: float = 0.0) -> Phase:
        """As :meth:`dynamics.contact.full.FullContactRun.enter_contact`, with the static bound mu_s."""
        s = self.slip(y)
        lock = self.rates(y, True, 0.0)
        n_lock, f_lock = lock[3], lock[4]
        stuck = abs(s) <= 1e-12 * self.ap.b / self.ap.tau
        if stuck and n_lock > 0.0 and abs(f_lock) < self.mu_s * n_lock:
            return self.locked(y)
        sigma = math.copysign(1.0, s) if not stuck else (sigma_hint or -math.copysign(1.0, f_lock))
        if self.rates(y, False, sigma)[3] <= 0.0 and n_lock <= 0.0:
            return self.free(self._free_state(y), on_constraint=True)
        return self.sliding(y, sigma)

    def impact(self, chi: float, turned_a: float, x_b: float, velocity, omega_a: float, omega_b: float):
        """Velocities just after a plastic impact on the moving constraint (module docstring).

        Returns (velocity r' (m/s), Omega_a, Omega_b, P_N, P_F), the impulses in N s.
        """
        ap, p = self.ap, self.p
        kappa, _, ka, kb = self.local(chi, turned_a, x_b)
        delta, a = ap.delta, ap.a
        eps = kappa * delta
        ex, ez = math.sin(chi), math.cos(chi)
        e_eps, e_chi = np.array([ex, ez]), np.array([ez, -ex])
        tilt = delta * (ka + kb) / eps
        spin = full.spin_state(p, kappa, eps, e_eps @ velocity, (e_chi @ velocity) / eps, omega_a, omega_b)
        normal = np.array(full.force_response(p, eps, ex, ez, -1.0, tilt, 0.0 - delta * ka, spin))
        friction = np.array(full.force_response(p, eps, ex, ez, 0.0, 1.0, a, spin))
        v = np.array([*velocity, omega_a, omega_b], dtype=float)
        radial = np.array([ex - tilt * ez, ez + tilt * ex, delta * ka, delta * kb])  # -grad G
        sliding = np.array([*e_chi, a, -(a + eps)])
        approach, slip0 = radial @ v, sliding @ v
        p_n, p_f = np.linalg.solve([[radial @ normal, radial @ friction], [sliding @ normal, sliding @ friction]],
                                   [-approach, -slip0])
        if abs(p_f) > self.mu_s * p_n:  # the stick impulse lies outside the friction cone
            sigma = math.copysign(1.0, slip0)
            mu = stribeck_mu(slip0, self.mu_k, self.mu_s, self.v_stribeck)
            p_n = -approach / (radial @ normal - sigma * mu * (radial @ friction))
            p_f = -sigma * mu * p_n
        v = v + p_n * normal + p_f * friction
        chi_dot = (e_chi @ v[:2]) / eps
        follow = delta * (ka * (chi_dot - v[2]) + kb * (chi_dot - v[3]))  # eps*' after the impact
        v[:2] -= (e_eps @ v[:2] - follow) * e_eps  # G' = 0 to rounding
        return v[:2], v[2], v[3], p_n, p_f

    def touch(self, y_free, phi: float) -> Phase:
        """The impact on touching, then :meth:`enter_contact`; a graze flies on (rough surfaces)."""
        off = self.passive_free
        core = y_free[off:]
        turned = y_free[0] if off else 0.0
        chi = phi - self.ap.alpha
        velocity, omega_a, omega_b, _, _ = self.impact(chi, turned, core[6], core[2:4], core[4], core[5])
        eps = self.local(chi, turned, core[6]).kappa * self.ap.delta
        chi_dot = (math.cos(chi) * velocity[0] - math.sin(chi) * velocity[1]) / eps
        y = np.array(([turned] if self.varies else []) + [chi, chi_dot, omega_a, omega_b, core[6]])
        return self.enter_contact(y)

    def transition(self, phase: Phase, reason: str, end, phi: float) -> Phase:
        if phase.name == FREE:
            return self.touch(end, phi)
        y = np.array(end, dtype=float)
        off = self.passive_contact
        if reason == "lift":
            return self.free(self._free_state(y), on_constraint=True)
        if reason == "stick":
            eps = self.rates(y, True, 0.0)[6] * self.ap.delta
            y[off + 2] = ((self.ap.a + eps) * y[off + 3] - eps * y[off + 1]) / self.ap.a  # slip = 0 exactly
            return self.enter_contact(y, -phase.sigma)
        # the static bound is reached: slide from zero slip, the way the friction no longer prevents
        return self.sliding(y, -math.copysign(1.0, self.rates(y, True, 0.0)[4]))

    # output ----------------------------------------------------------------------------------------
    def _angles_columns(self, phi, turned_a, x_b_m) -> dict:
        if not self.varies:
            return {}
        return {"theta_a": phi - turned_a, "theta_b": phi - x_b_m / self.ap.b}

    def columns(self, phase: Phase, t, y, kind) -> dict:
        """Scaled columns of one phase's rows (t in tau, rates in 1/tau, X_b in b), and the body angles."""
        ap, n, tau = self.ap, t.size, self.ap.tau
        weight = self.weight
        if phase.name in (FREE, COMPLIANT):
            off = self.passive_free
            obs = full.observables(ap, y[off:], phase.extra["phi0"])
            cols = {"kappa": obs["kappa"], "one_minus_kappa": obs["one_minus_kappa"], "phi": obs["phi"],
                    "kappa_dot": obs["kappa_dot"] * tau, "phi_dot": obs["phi_dot"] * tau,
                    "omega_a": obs["omega_a"] * tau, "omega_b": obs["omega_b"] * tau, "x_b": obs["x_b"] / ap.b,
                    "c_eps": np.zeros(n), "c_chi": np.zeros(n)}
            if phase.name == COMPLIANT and n:
                table = compliant_table(np.ascontiguousarray(y), phase.args)
                cols["c_eps"] = table[0] / weight
                cols["c_chi"] = -table[1] / (ap.delta_over_a * weight)
            return cols | self._angles_columns(obs["phi"], y[0] if off else 0.0, y[-1])
        off = self.passive_contact
        locked = phase.name == LOCKED
        # rows as contiguous arrays, the layout every other call of the rates has: one compiled version
        table = self.functions.contact_table(np.array(y.T), self.p, self._contact_numbers(locked, phase.sigma), locked,
                                             phase.sigma, self.model)
        phi = y[off] + ap.alpha
        return {"kappa": table[:, 6], "one_minus_kappa": table[:, 7], "phi": phi,
                "kappa_dot": table[:, 5] / ap.delta * tau, "phi_dot": y[off + 1] * tau,
                "omega_a": y[off + 2] * tau, "omega_b": y[off + 3] * tau, "x_b": y[off + 4] / ap.b,
                "c_eps": table[:, 3] / weight, "c_chi": -table[:, 4] / (ap.delta_over_a * weight),
                } | self._angles_columns(phi, y[0] if off else 0.0, y[off + 4])


def run_rough_full(apparatus, force_model: KernelModel, rough: RoughContact, initial, t_end: float, *,
                   limits: Limits = Limits(), method: str = "radau", rtol: float = 1e-8, t_eval=None, steps=None,
                   max_steps: int = 2_000_000, max_switches: int = MAX_SWITCHES, progress=None,
                   frame_terms: str = full.DEFAULT_FRAME_TERMS, fluid_spin: str = full.DEFAULT_FLUID_SPIN) -> dict:
    """The full model on rough surfaces from ``initial`` (SI) over ``t_end`` seconds.

    Theta_a starts at 0, so the initial body angles are theta_a = theta_b = phi0.
    A hard contact needs initial.kappa in [0, kappa*(phi0, phi0)] and starts as on
    touching at that kappa*; a compliant one starts free anywhere in [0, 1).

    Returns the fields of :func:`numerics.hybrid.run_phases` with times in tau and the
    columns scaled (rates in 1/tau, X_b in b, and theta_a, theta_b on rough surfaces),
    as :mod:`dynamics.simulation` expects; use :func:`dynamics.simulation.simulate`
    for a :class:`~dynamics.simulation.Trajectory`.
    """
    run = RoughFullRun(apparatus, force_model, rough, limits, rtol, frame_terms, fluid_spin)
    y0 = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                            initial.omega_a, initial.omega_b)  # as dynamics.contact.full
    if run.varies:
        y0 = np.concatenate(([0.0, 0.0], y0))
    if rough.compliance is not None:
        start = run.compliant(y0)
    else:
        kappa_touch = rough.local_at(initial.phi, initial.phi).kappa
        check_range("initial.kappa", initial.kappa, 0.0, kappa_touch, high_open=False,
                    unit="(kappa* where the surfaces meet the line of centres at the release)")
        if initial.kappa >= kappa_touch * (1.0 - 1e-14):
            start = run.touch(y0, initial.phi)
        else:
            start = run.free(y0)
    return phases_in_tau(run, start, apparatus.tau, t_end, initial.phi, method=method, rtol=rtol, t_eval=t_eval,
                         steps=steps, max_steps=max_steps, max_switches=max_switches, progress=progress)
