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
implicit method (Radau by default) and the analytic Jacobian
:func:`reduced_jacobian`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dynamics.equations.limits import (
    GAP_FLOOR,
    MAX_TURNS,
    gap_floor_event,
    runaway_event,
)
from dynamics.integrate import integrate
from lubrication._jit import jit
from lubrication.geometry import check_finite, check_range

__all__ = [
    "ReducedParams",
    "jacobian",
    "rhs",
    "ReducedTrajectory",
    "STATE_NAMES",
    "initial_state",
    "reduced_jacobian",
    "reduced_rhs",
    "simulate_reduced",
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
    def args(self) -> tuple[float, float, float]:
        """(s, Upsilon, mu_): the groups as the compiled right-hand side takes them."""
        return (self.s, self.upsilon, self.mu_ratio)


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


@jit
def rhs(t, y, args):
    """Right-hand side of (2.11a-d) in the stretched Cartesian variables (module docstring).

    Parameters
    ----------
    t : float
        Time in units of tau (the system is autonomous).
    y : ndarray, shape (5,)
        State (xi, eta, Omega_a, Omega_b, X_b), see :data:`STATE_NAMES`.
    args : tuple
        (s, Upsilon, mu_, ...): :meth:`ReducedParams.args` and what the run's
        events need after them.

    Returns
    -------
    ndarray, shape (5,)
    """
    s, ups, mu_ = args[0], args[1], args[2]
    xi, eta, omega_a, omega_b = y[0], y[1], y[2], y[3]
    rho2 = 1.0 + xi * xi + eta * eta
    rho = math.sqrt(rho2)
    w = 0.5 * (omega_a + omega_b)
    d = omega_b - omega_a
    out = np.empty(5)
    out[0] = eta * w + 0.5 * xi * eta / rho2
    out[1] = -xi * w - 1.0 - 0.5 * xi * xi / rho2
    out[2] = (d * rho / 3.0 + xi / rho) / ups
    out[3] = (s + 0.5 * xi / rho - d * rho / 6.0) / (mu_ * ups)
    out[4] = omega_b
    return out


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


@dataclass(frozen=True)
class ReducedTrajectory:
    """A solution of the reduced model; times in tau, rates in 1/tau, x_b in b.

    Attributes
    ----------
    t : ndarray, shape (n,)
    kappa, one_minus_kappa : ndarray, shape (n,)
        Eccentricity and its distance from contact (no cancellation).
    phi : ndarray, shape (n,)
        Angle of the line of centres from the upward vertical, unwrapped to be
        continuous between samples (samples must be closer than half a turn)
        and starting near the requested phi0. Where kappa = 0 exactly the
        direction is undefined and phi0 is reported.
    omega_a, omega_b, x_b : ndarray, shape (n,)
    status : int
        0 reached ``t_end``; 1 stopped by an event; -1 integration failed or was interrupted.
    stop_reason : str
        ``"t_end"``, ``"gap_floor"`` (1 - kappa fell to the floor),
        ``"runaway"`` (the outer cylinder rolled ``max_turns`` turns),
        ``"max_steps"``, ``"failed"`` or ``"interrupted"``.
    message : str
        Human-readable account of the stop.
    nfev, njev, steps : int
        Right-hand-side and Jacobian evaluations, accepted steps.
    wall_time_s : float
    """

    t: np.ndarray
    kappa: np.ndarray
    one_minus_kappa: np.ndarray
    phi: np.ndarray
    omega_a: np.ndarray
    omega_b: np.ndarray
    x_b: np.ndarray
    status: int
    stop_reason: str
    message: str
    nfev: int
    njev: int
    steps: int = 0
    wall_time_s: float = 0.0


def simulate_reduced(params: ReducedParams, t_end: float, kappa0: float, phi0: float,
                     omega_a0: float = 0.0, omega_b0: float = 0.0, x_b0: float = 0.0, *,
                     one_minus_kappa0: float | None = None, t_eval=None,
                     rtol: float = 1e-8, atol: float = 1e-10, method: str = "LSODA",
                     gap_floor: float = GAP_FLOOR, max_turns: float = MAX_TURNS,
                     progress: str | None = None) -> ReducedTrajectory:
    """Integrate the reduced model (2.11) from t = 0 to ``t_end`` (units of tau).

    Parameters
    ----------
    params : ReducedParams
    t_end : float
        Final time in units of tau, positive.
    kappa0, phi0, omega_a0, omega_b0, x_b0, one_minus_kappa0
        Initial state, see :func:`initial_state`.
    t_eval : array_like, optional
        Output times in [0, t_end]; by default the integrator's steps. The
        state at a terminating event is appended.
    rtol, atol : float
        Integrator tolerances, applied to (xi, eta, Omega_a, Omega_b, X_b).
    method : {"Radau", "BDF", "LSODA"}
        Implicit scipy solver; the analytic Jacobian is supplied.
    gap_floor : float
        Stop when 1 - kappa falls to this value, in (0, 1); see
        :mod:`dynamics.equations.limits`. The slow approach (3.9) reaches it after
        about 1/sqrt(2 gap_floor (1 - s^2)) tau.
    max_turns : float
        Stop, as a runaway, when the outer cylinder has turned this many times
        (|X_b - x_b0| = 2 pi max_turns), which bounds the cost of long runs.
    progress : str, optional
        Label of a progress bar shown on a terminal.

    Returns
    -------
    ReducedTrajectory

    Raises
    ------
    ValueError
        For out-of-range arguments, including an initial gap already at or
        below ``gap_floor``.
    """
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True)
    gap_floor = check_range("gap_floor", gap_floor, 0.0, 1.0, low_open=True)
    max_turns = check_range("max_turns", max_turns, 0.0, math.inf, low_open=True)
    check_range("rtol", rtol, 0.0, 1.0, low_open=True)
    check_range("atol", atol, 0.0, math.inf, low_open=True)
    if method not in ("Radau", "BDF", "LSODA"):
        msg = f"method must be one of 'Radau', 'BDF', 'LSODA', got {method!r}"
        raise ValueError(msg)
    y0 = initial_state(kappa0, phi0, omega_a0, omega_b0, x_b0, one_minus_kappa0=one_minus_kappa0)
    _, omk0 = stretched_to_kappa(math.hypot(y0[0], y0[1]))
    if not omk0 > gap_floor:
        msg = f"1 - kappa0 must be in (gap_floor, 1] = ({gap_floor:g}, 1], got {omk0!r}"
        raise ValueError(msg)
    if t_eval is not None:
        t_eval = np.asarray(t_eval, dtype=float)
        if t_eval.ndim != 1 or np.any(t_eval < 0.0) or np.any(t_eval > t_end) or np.any(np.diff(t_eval) <= 0):
            msg = "t_eval must be a 1-D increasing array of times in [0, t_end]"
            raise ValueError(msg)
    events = (gap_floor_event(lambda y: stretched_to_kappa(math.hypot(y[0], y[1]))[1], gap_floor),
              runaway_event(lambda y: y[4] - x_b0, max_turns))
    run = integrate(lambda t, y: reduced_rhs(t, y, params), y0, t_end,
                    jac=lambda t, y: reduced_jacobian(t, y, params), rtol=rtol, atol=atol,
                    method=method, events=events, t_eval=t_eval, progress=progress)
    status = {"completed": 0, "stopped": 1}.get(run.status, -1)
    stop_reason = {"completed": "t_end", "stopped": run.event}.get(run.status, run.status)
    t, y = run.t, run.y
    r = np.hypot(y[0], y[1])
    kappa, omk = stretched_to_kappa(r)
    phi = np.where(r > 0.0, np.arctan2(y[0], y[1]), phi0)
    if phi.size:
        phi = np.unwrap(phi)
        phi += 2.0 * math.pi * round((phi0 - phi[0]) / (2.0 * math.pi))
    return ReducedTrajectory(t=t, kappa=kappa, one_minus_kappa=omk, phi=phi, omega_a=y[2],
                             omega_b=y[3], x_b=y[4], status=status, stop_reason=stop_reason,
                             message=run.reason, nfev=run.nfev, njev=run.njev, steps=run.steps,
                             wall_time_s=run.wall_time_s)
