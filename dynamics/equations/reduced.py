r"""The reduced model (2.11a-d) in variables regular at kappa = 0 and near contact.

Time is in units of tau (2.9) and rotation rates in units of 1/tau. With
zeta = sqrt(1 - kappa^2) the model reads

    (2.11a)  kappa' = -zeta^3 cos(phi)
    (2.11b)  kappa (Omega_a + Omega_b - 2 phi') = -(2 + kappa^2) zeta sin(phi)
    (2.11c)  (1/2) Upsilon Omega_a' = T,
             T = [zeta^2 (Omega_b - phi') - (1 + 2 kappa^2)(Omega_a - phi')]
                 / (3 (2 + kappa^2) zeta)
    (2.11d)  mu_ Upsilon Omega_b' + (1/2) Upsilon Omega_a' = s + kappa sin(phi)

plus the passive X_b' = Omega_b (X_b in units of b: the angle the outer
cylinder has turned through).

Variables
---------
Solved for phi', (2.11b) gives phi' = W + (2 + kappa^2) zeta sin(phi) / (2 kappa)
with W = (Omega_a + Omega_b)/2: singular at kappa = 0, where phi is undefined.
And kappa loses all relative precision in 1 - kappa near contact. Both are
cured by the stretched radius r = kappa / zeta in [0, inf), for which (2.11a)
is simply r' = kappa'/zeta^3 = -cos(phi), and its Cartesian components

    xi = r sin(phi),  eta = r cos(phi),   rho = sqrt(1 + xi^2 + eta^2) = 1/zeta,

so that kappa = r/rho and 1 - kappa = 1/(rho (rho + r)) without cancellation.
(r grows linearly in the sedimentation (3.3): r = t + r(0).)

Derivation of the right-hand side. With sin = xi/r, cos = eta/r and
(2 + kappa^2) zeta / (2 kappa) = (2 + kappa^2)/(2 r),

    xi'  = r' sin + r cos phi' = -xi eta/r^2 + eta W + (2 + kappa^2) xi eta/(2 r^2)
         = eta W + (kappa^2/2) xi eta / r^2 = eta W + xi eta / (2 rho^2),
    eta' = r' cos - r sin phi' = -eta^2/r^2 - xi W - (2 + kappa^2) xi^2/(2 r^2)
         = -xi W - 1 - xi^2 / (2 rho^2),

using xi^2 + eta^2 = r^2 and kappa^2/r^2 = zeta^2 = 1/rho^2. In the torque
(2.11c) phi' enters as phi' (1 + 2 kappa^2 - zeta^2) = 3 kappa^2 phi', and
3 kappa^2 phi' = 3 kappa^2 W + (3/2)(2 + kappa^2) zeta kappa sin(phi) is
regular; then with D = Omega_b - Omega_a and kappa sin(phi) = xi/rho,

    T = [(1 + kappa^2/2) D + (3/2)(2 + kappa^2) zeta kappa sin(phi)] / (3 (2 + kappa^2) zeta)
      = D rho / 6 + xi / (2 rho).

Hence the system integrated here, smooth everywhere including r = 0:

    xi'      = eta W + xi eta / (2 rho^2)
    eta'     = -xi W - 1 - xi^2 / (2 rho^2)
    Omega_a' = (D rho / 3 + xi / rho) / Upsilon
    Omega_b' = (s + xi / (2 rho) - D rho / 6) / (mu_ Upsilon)
    X_b'     = Omega_b

The coupling D rho/(3 Upsilon) that locks Omega_a to Omega_b grows like
1/zeta near contact: the system is stiff there, and is integrated with an
implicit method (the compiled Radau IIA by default) and the analytic Jacobian
:func:`reduced_jacobian`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubrication.geometry import check_finite, check_range
from numerics.jit import jit

__all__ = [
    "EVENT_NAMES",
    "STATE_NAMES",
    "ReducedParams",
    "columns",
    "event_values",
    "events",
    "initial_state",
    "jacobian",
    "polar_rates",
    "position_columns",
    "reduced_jacobian",
    "reduced_rhs",
    "rhs",
    "rhs_values",
    "run_args",
    "stretched_to_kappa",
]

STATE_NAMES = ("xi", "eta", "omega_a", "omega_b", "x_b")
"""Components of the state: xi = r sin(phi), eta = r cos(phi) with r = kappa/sqrt(1 - kappa^2)."""


@dataclass(frozen=True)
class ReducedParams:
    """Groups of the reduced model (2.12).

    Parameters
    ----------
    s : float
        Slope group (a sin(alpha)/delta)(M/m'_a); any finite value.
    upsilon : float
        Upsilon, inertia over lubrication, in (0, inf).
    mu_ratio : float
        The paper's mu = (M + m_b)/m_a, in (0, inf). A physical apparatus has
        mu_ > 1; the paper's figures use mu_ = 1, which the reduced model allows.
    """

    s: float
    upsilon: float
    mu_ratio: float

    def __post_init__(self):
        object.__setattr__(self, "s", check_finite("s", self.s))
        object.__setattr__(self, "upsilon", check_range("upsilon", self.upsilon, 0.0, math.inf,
                                                        low_open=True))
        object.__setattr__(self, "mu_ratio", check_range("mu_ratio", self.mu_ratio, 0.0, math.inf,
                                                         low_open=True))

    @property
    def args(self) -> np.ndarray:
        """(s, Upsilon, mu_): the groups as the compiled right-hand side takes them.

        Every model's ``args`` is a float64 array, so that one compiled integrator serves them all.
        """
        return np.array([self.s, self.upsilon, self.mu_ratio])


def stretched_to_kappa(r):
    """kappa and 1 - kappa from the stretched radius r = kappa / sqrt(1 - kappa^2).

    Parameters
    ----------
    r : float or array_like
        Non-negative.

    Returns
    -------
    kappa, one_minus_kappa : float or ndarray
        1 - kappa = 1/(rho (rho + r)) with rho = sqrt(1 + r^2) keeps full
        relative precision as kappa -> 1.
    """
    rho = np.sqrt(1.0 + np.square(r))
    return r / rho, 1.0 / (rho * (rho + r))


def initial_state(kappa0: float | None, phi0: float, omega_a0: float = 0.0, omega_b0: float = 0.0,
                  x_b0: float = 0.0, *, one_minus_kappa0: float | None = None) -> np.ndarray:
    """State vector (xi, eta, Omega_a, Omega_b, X_b) for an initial (kappa, phi, ...).

    Parameters
    ----------
    kappa0 : float or None
        Eccentricity in [0, 1); ``kappa0 = 0`` is exact (xi = eta = 0).
        Ignored (may be None) when ``one_minus_kappa0`` is given.
    phi0 : float
        Angle of the line of centres from the upward vertical (rad).
    omega_a0, omega_b0 : float
        Rotation rates in units of 1/tau.
    x_b0 : float
        Initial position in units of b.
    one_minus_kappa0 : float, optional
        1 - kappa0 in (0, 1], for initial states too close to contact for
        kappa0 to carry the gap; overrides ``kappa0`` when given.
    """
    if one_minus_kappa0 is None:
        kappa0 = check_range("kappa0", kappa0, 0.0, 1.0)
        omk = 1.0 - kappa0
    else:
        omk = check_range("one_minus_kappa0", one_minus_kappa0, 0.0, 1.0,
                          low_open=True, high_open=False)
        kappa0 = 1.0 - omk
    phi0 = check_finite("phi0", phi0)
    r0 = kappa0 / math.sqrt(omk * (1.0 + kappa0))
    return np.array([r0 * math.sin(phi0), r0 * math.cos(phi0),
                     check_finite("omega_a0", omega_a0), check_finite("omega_b0", omega_b0),
                     check_finite("x_b0", x_b0)])


@jit(inline="always")
def rhs_values(t, y, args):
    """:func:`rhs` as a tuple of five floats, for compiled callers: a tuple needs no allocation.

    The engine's driver (:mod:`numerics.engine.driver`) takes either form; called
    directly from compiled code, as the sweeps' batch loop does, the tuple saves
    an array's allocation and release at each of the about seven evaluations a step.
    """
    s, ups, mu_ = args[0], args[1], args[2]
    xi, eta, omega_a, omega_b = y[0], y[1], y[2], y[3]
    rho2 = 1.0 + xi * xi + eta * eta
    rho = math.sqrt(rho2)
    half_xi_over_rho2 = 0.5 * xi / rho2
    xi_over_rho = 2.0 * half_xi_over_rho2 * rho  # a multiplication for a division: about seven calls a step
    w = 0.5 * (omega_a + omega_b)
    d = omega_b - omega_a
    return (eta * w + half_xi_over_rho2 * eta,
            -xi * w - 1.0 - half_xi_over_rho2 * xi,
            (d * rho / 3.0 + xi_over_rho) / ups,
            (s + 0.5 * xi_over_rho - d * rho / 6.0) / (mu_ * ups),
            omega_b)


@jit
def rhs(t, y, args):
    """Right-hand side of (2.11a-d) in the stretched Cartesian variables (module docstring).

    Parameters
    ----------
    t : float
        Time in units of tau (the system is autonomous).
    y : ndarray, shape (5,)
        State (xi, eta, Omega_a, Omega_b, X_b), see :data:`STATE_NAMES`.
    args : ndarray
        (s, Upsilon, mu_, ...): :meth:`ReducedParams.args` and what the run's
        events need after them (:func:`run_args`).

    Returns
    -------
    ndarray, shape (5,)
    """
    return np.array(rhs_values(t, y, args))


@jit
def jacobian(t, y, args):
    """Analytic Jacobian d(rhs)/dy of :func:`rhs`, shape (5, 5).

    With rho^2 = 1 + xi^2 + eta^2: d rho/d xi = xi/rho, d(1/rho^2)/d xi = -2 xi/rho^4,
    and likewise for eta.
    """
    ups, mu_ = args[1], args[2]
    xi, eta, omega_a, omega_b = y[0], y[1], y[2], y[3]
    rho2 = 1.0 + xi * xi + eta * eta
    rho = math.sqrt(rho2)
    rho3 = rho2 * rho
    rho4 = rho2 * rho2
    w = 0.5 * (omega_a + omega_b)
    d = omega_b - omega_a
    mu_ups = mu_ * ups
    jac = np.zeros((5, 5))
    jac[0, 0] = 0.5 * eta / rho2 - xi * xi * eta / rho4
    jac[0, 1] = w + 0.5 * xi / rho2 - xi * eta * eta / rho4
    jac[0, 2] = 0.5 * eta
    jac[0, 3] = 0.5 * eta
    jac[1, 0] = -w - xi / rho2 + xi**3 / rho4
    jac[1, 1] = xi * xi * eta / rho4
    jac[1, 2] = -0.5 * xi
    jac[1, 3] = -0.5 * xi
    jac[2, 0] = (d * xi / (3.0 * rho) + (1.0 + eta * eta) / rho3) / ups
    jac[2, 1] = (d * eta / (3.0 * rho) - xi * eta / rho3) / ups
    jac[2, 2] = -rho / (3.0 * ups)
    jac[2, 3] = rho / (3.0 * ups)
    jac[3, 0] = (0.5 * (1.0 + eta * eta) / rho3 - d * xi / (6.0 * rho)) / mu_ups
    jac[3, 1] = (-0.5 * xi * eta / rho3 - d * eta / (6.0 * rho)) / mu_ups
    jac[3, 2] = rho / (6.0 * mu_ups)
    jac[3, 3] = -rho / (6.0 * mu_ups)
    jac[4, 3] = 1.0
    return jac


def reduced_rhs(t: float, y, params: ReducedParams) -> np.ndarray:
    """:func:`rhs` from Python, with the groups as a :class:`ReducedParams`."""
    return rhs(float(t), np.asarray(y, dtype=float), params.args)


def reduced_jacobian(t: float, y, params: ReducedParams) -> np.ndarray:
    """:func:`jacobian` from Python, with the groups as a :class:`ReducedParams`."""
    return jacobian(float(t), np.asarray(y, dtype=float), params.args)


#: The components of :func:`events`, in order: the validity limits, the line of centres
#: crossing an axis (xi eta = 0: every quarter turn, which keeps phi continuous between output
#: rows however far apart, since consecutive rows are then less than a half turn apart), and
#: the touch of rough walls (r = r*, contact runs only).
EVENT_NAMES = ("gap_floor", "reynolds", "runaway", "turn", "touch")

# args of a run: the groups, then what the events need
_LOG_FLOOR, _MAX_RE, _RE_A, _RE_B, _XB_LIMIT, _XB0, _R_STAR = range(3, 10)


def run_args(params: ReducedParams, *, gap_floor: float, max_reynolds: float = math.inf,
             reynolds_per_rate: tuple[float, float] = (0.0, 0.0), x_b_limit: float = math.inf,
             x_b0: float = 0.0, r_star: float = math.inf) -> np.ndarray:
    """The ``args`` of :func:`rhs`, :func:`jacobian` and :func:`events` for a run.

    Parameters
    ----------
    gap_floor : float
        1 - kappa at which the gap-floor event fires.
    max_reynolds : float
        Reduced Reynolds number Re* of the Reynolds event; ``reynolds_per_rate`` =
        (1, b/a) delta^2/(nu tau) turns the scaled relative rates W = Omega - phi' into it
        (zero without an apparatus).
    x_b_limit, x_b0 : float
        The runaway event fires when |X_b - x_b0| reaches ``x_b_limit`` (units of b).
    r_star : float
        Stretched radius kappa*/zeta* of the touch event (inf without contact).
    """
    return np.array([*params.args, math.log(gap_floor), max_reynolds, reynolds_per_rate[0],
                     reynolds_per_rate[1], x_b_limit, x_b0, r_star], dtype=float)


@jit(inline="always")
def event_values(t, y, args):
    """:func:`events` as a tuple of five floats, for compiled callers (as :func:`rhs_values`)."""
    r2 = y[0] * y[0] + y[1] * y[1]  # not hypot, 2% of a sweep batch's time (perf); r is far from overflow
    r = math.sqrt(r2)
    rho = math.sqrt(1.0 + r2)
    omk = 1.0 / (rho * (rho + r))
    reynolds = args[_MAX_RE]
    if args[_MAX_RE] < math.inf and r > 0.0:
        # Re* of the flow relative to the line of centres (dynamics.equations.full.reduced_reynolds)
        f = rhs_values(t, y, args)
        phi_dot = (y[1] * f[0] - y[0] * f[1]) / (r * r)
        kappa = r / rho
        fade = kappa * kappa / (kappa * kappa + 1e-6)
        reynolds -= fade * max(abs(y[2] - phi_dot) * args[_RE_A], abs(y[3] - phi_dot) * args[_RE_B])
    return (math.log(omk) - args[_LOG_FLOOR], reynolds, args[_XB_LIMIT] - abs(y[4] - args[_XB0]), y[0] * y[1],
            r - args[_R_STAR])


@jit
def events(t, y, args):
    """The event values of :data:`EVENT_NAMES` at state ``y``; each fires as it falls through (or rises to) 0."""
    return np.array(event_values(t, y, args))


@jit
def polar_rates(y, args):
    """kappa' and phi' (1/tau) of states ``y`` (shape (5, k)), from the right-hand side.

    r' = kappa'/zeta^3 and r^2 phi' = eta xi' - xi eta' (module docstring); at r = 0,
    where phi is undefined, phi' is reported as 0 and kappa' = |(xi', eta')|.
    """
    k = y.shape[1]
    kappa_dot = np.empty(k)
    phi_dot = np.empty(k)
    state = np.empty(5)
    for j in range(k):
        for i in range(5):
            state[i] = y[i, j]
        f = rhs_values(0.0, state, args)
        xi, eta = state[0], state[1]
        r2 = xi * xi + eta * eta
        if r2 > 0.0:
            zeta3 = (1.0 + r2) ** -1.5
            kappa_dot[j] = (xi * f[0] + eta * f[1]) / math.sqrt(r2) * zeta3
            phi_dot[j] = (eta * f[0] - xi * f[1]) / r2
        else:
            kappa_dot[j] = math.hypot(f[0], f[1])
            phi_dot[j] = 0.0
    return kappa_dot, phi_dot


@jit
def _position(y, phi0):
    """kappa, 1 - kappa and phi of states with (xi, eta) = ``y`` (shape (2, k)).

    phi is unwrapped as :func:`numpy.unwrap` does, and is phi0 where r = 0. One
    pass, compiled: a sweep's batch classifies every run from these.
    """
    k = y.shape[1]
    kappa, omk, phi = np.empty(k), np.empty(k), np.empty(k)
    shift = previous = 0.0
    for j in range(k):
        xi, eta = y[0, j], y[1, j]
        r = math.hypot(xi, eta)
        rho = math.sqrt(1.0 + r * r)
        kappa[j] = r / rho
        omk[j] = 1.0 / (rho * (rho + r))
        angle = math.atan2(xi, eta) if r > 0.0 else phi0
        jump = angle - previous
        if j > 0 and abs(jump) >= math.pi:
            # numpy.unwrap: a jump of at least pi becomes the equivalent jump in [-pi, pi]
            wrapped = (jump + math.pi) % (2.0 * math.pi) - math.pi
            if wrapped == -math.pi and jump > 0.0:
                wrapped = math.pi
            shift += wrapped - jump
        previous = angle
        phi[j] = angle + shift
    return kappa, omk, phi


def position_columns(y: np.ndarray, phi0: float) -> dict[str, np.ndarray]:
    """kappa, 1 - kappa and phi of states ``y`` (shape (5, k)), as :func:`columns` gives them."""
    kappa, omk, phi = _position(np.ascontiguousarray(y[:2], dtype=float), float(phi0))
    if phi.size:
        phi += 2.0 * math.pi * round((phi0 - phi[0]) / (2.0 * math.pi))
    return {"kappa": kappa, "one_minus_kappa": omk, "phi": phi}


def columns(y: np.ndarray, phi0: float, args: np.ndarray) -> dict[str, np.ndarray]:
    """kappa, 1 - kappa, phi, their rates, Omega_a, Omega_b, X_b of states ``y`` (shape (5, k)), scaled units.

    phi is unwrapped to be continuous between rows (the rows must include the
    quarter-turn "turn" events, for that to hold whatever the spacing)
    and starts at the turn of ``phi0``; where kappa = 0 exactly phi is undefined
    and ``phi0`` is reported. ``args`` are the run's (:func:`run_args`).
    """
    kappa_dot, phi_dot = polar_rates(np.ascontiguousarray(y[:5]), args)
    return {**position_columns(y, phi0), "kappa_dot": kappa_dot, "phi_dot": phi_dot,
            "omega_a": y[2], "omega_b": y[3], "x_b": y[4]}
