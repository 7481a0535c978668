r"""The full model (2.1)-(2.4) with a transported cavitating film: the film's voids join the state.

The state is that of :mod:`dynamics.equations.full` (u_x, u_z, v_x, v_z, Omega_a,
Omega_b, X_b), then the void (gas) area v_j of each of the film's N dual cells
and the liquid R the reservoir has taken from the film, both per unit length
(m^2), as :mod:`lubrication.film_transport` defines them: 7 + N + 1 components.
Its right-hand side composes the full model's pieces (the geometry of the state,
the frame force, the responses to a force and to gravity) with the film's rates
and forces, and the film's liquid changes exactly by what the reservoir takes,
sum_j (V_j - v_j) + R = const (the gap area sum_j V_j = 2 pi a delta of the thin
gap does not depend on kappa), a linear invariant of the state that Radau IIA
keeps to rounding; :func:`mass_balance` measures it against the liquid that
crossed the cells' faces along a run. The stops are those of the full model
(:func:`dynamics.equations.full.events`, which reads only the first seven components).

The film's right-hand side is Lipschitz and piecewise smooth (a node's switch
between cavitated and pressed is a kink), and stiff: the relaxation of a pressed
node's void, 1/tau_r, and the film's own Poiseuille modes. The Jacobian is by
central differences (as the ``jacobian`` of :func:`dynamics.equations.full.model_functions`); a void's step
is a fixed tiny area, so that a probe of a pressed node (v = 0) stays on the
smooth side of its switch.

:func:`rock` drives the film alone through a prescribed motion, kappa = kappa0 +
A sin(omega t) at fixed spins: the tests' rocking film.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dynamics.apparatus import Apparatus
from dynamics.equations import full
from dynamics.equations.full import _A, _B, _LEN, _MU, central_differences
from dynamics.initial import Initial
from dynamics.trajectory import Recorder, Trajectory, event_names
from lubrication.film_kernels import film_rates as film_kernel
from lubrication.film_transport import TransportedFilm, dual_areas, film_rates
from lubrication.geometry import Annulus, Fluid, Motion, check_finite, check_range
from lubrication.registry import kernel_model
from numerics.engine import EVENT
from numerics.integrate import integrate
from numerics.jit import jit
from numerics.packed import pack, part, parts

__all__ = ["MassBalance", "Rocking", "events", "initial_state", "jacobian", "mass_balance", "rhs", "rock", "rocking_jacobian",
           "film_run", "rocking_rhs", "run_args", "void_scale"]

#: A void's finite-difference step and absolute-tolerance floor, as a fraction of a mean dual cell's area:
#: small enough that a probe of a pressed node does not cross its switch (module docstring).
VOID_FLOOR = 1e-6


@jit(inline="always")
def _film(film, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, void, reservoir, d_void):
    """:func:`lubrication.film_kernels.film_rates` with the model's data as one tuple; d_void receives dvoid/dt.

    Returns f_eps, f_chi, T_a and dR/dt.
    """
    cpsi, spsi, vpsi, ppsi, wpsi, m, faces, node_p, gauge, p_cav, p_ref, bubble, eps_end, relaxation = film
    n = void.size
    f_eps, f_chi, t_a, d_reservoir, _, _ = film_kernel(
        a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m, faces, node_p, gauge, p_cav,
        p_ref, bubble, eps_end, relaxation, void, reservoir, d_void, np.empty(n), np.empty(n), np.empty(n))
    return f_eps, f_chi, t_a, d_reservoir


@jit
def rhs(t, y, args):
    """dy/dt; ``args`` from :func:`run_args` (the motion's packed numbers, the film's data)."""
    p, film = part(args[0], full.PARAMETERS), args[1]
    a, b = p[_A], p[_B]
    delta = b - a
    kappa, omk, zeta, eps, big_u, ex, ez = full._geometry(y, delta)
    vx, vz, omega_a, omega_b = y[2], y[3], y[4], y[5]
    eps_dot = ex * vx + ez * vz
    chi_dot = (ez * vx - ex * vz) / eps if eps > 0.0 else 0.0
    n = y.size - 8
    dy = np.empty(y.size)
    f_eps, f_chi, t_a, d_reservoir = _film(film, a, b, p[_MU], p[_LEN], kappa, omk, eps_dot, omega_a - chi_dot,
                                           omega_b - chi_dot, y[7:7 + n], y[7 + n], dy[7:7 + n])
    frame_eps, frame_chi = full.frame_force(p, eps, eps_dot, chi_dot, omega_a, omega_b)
    spin = full.spin_state(p, kappa, eps, eps_dot, chi_dot, omega_a, omega_b)
    fluid = full.force_response(p, eps, ex, ez, f_eps + frame_eps, f_chi + frame_chi, t_a, spin)
    gravity = full.gravity_response(p, eps, ex, ez, spin)
    scale = 1.0 / (delta * zeta)
    stretch = big_u * big_u * eps_dot
    dy[0] = (vx + stretch * ex) * scale
    dy[1] = (vz + stretch * ez) * scale
    for i in range(4):
        dy[2 + i] = fluid[i] + gravity[i]
    dy[6] = b * omega_b
    dy[7 + n] = d_reservoir
    return dy


@jit
def jacobian(t, y, args):
    """d(rhs)/dy by central differences (module docstring)."""
    return central_differences(rhs, t, y, args, part(args[0], full.TYPICAL))


@jit
def events(t, y, args):
    """The full model's events (:func:`dynamics.equations.full.events`, on the first seven components)."""
    return full.events(t, y, args[0])


def void_scale(apparatus_or_annulus, n: int) -> float:
    """:data:`VOID_FLOOR` times the mean dual cell's gap area 2 pi a delta / N (m^2)."""
    ap = apparatus_or_annulus
    return VOID_FLOOR * 2.0 * math.pi * ap.a * (ap.b - ap.a) / n


def run_args(apparatus: Apparatus, film: TransportedFilm, *, gap_floor: float, max_reynolds: float = math.inf,
             max_turns: float = math.inf, frame_terms: str = full.DEFAULT_FRAME_TERMS,
             fluid_spin: str = full.DEFAULT_FLUID_SPIN) -> tuple:
    """The ``args`` of :func:`rhs`, :func:`jacobian` and :func:`events`.

    (the motion's numbers, the film's data): the first packed as the full model's
    (:func:`dynamics.equations.full.run_args`), with the film's typical scales appended to the motion's.
    """
    base = full.run_args(apparatus, kernel_model("closed-form"), gap_floor=gap_floor, max_reynolds=max_reynolds,
                         max_turns=max_turns, frame_terms=frame_terms, fluid_spin=fluid_spin)
    floor = void_scale(apparatus, film.n)
    p, model, typical, ev = parts(base)
    typical = np.concatenate((typical, np.full(film.n + 1, floor)))
    return pack(p, model, typical, ev), film.kernel_data(apparatus.a, apparatus.length)


def initial_state(apparatus: Apparatus, initial: Initial, film: TransportedFilm) -> np.ndarray:
    """The full model's state from ``initial``, a full film (no void) and a reservoir at its start."""
    motion = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                                initial.omega_a, initial.omega_b, one_minus_kappa=initial.gap)
    return np.concatenate((motion, np.zeros(film.n + 1)))


def film_run(run: Recorder, initial: Initial, film: TransportedFilm) -> Trajectory:
    """The full model with the transported ``film`` from ``initial`` (SI), over the run's settings: the case
    of :func:`dynamics.simulation.simulate` whose ``forces`` is a :class:`~lubrication.film_transport.TransportedFilm`.

    The :class:`~dynamics.trajectory.Trajectory`'s columns add, per row, ``liquid`` (the film's liquid per
    unit length, sum_j (V_j - v_j), m^2), ``cavity_area`` (its gas, sum_j v_j, m^2), ``cavitated_fraction``
    (share of the nodes holding gas), ``reservoir`` (R, m^2) and ``reservoir_pressure`` (Pa);
    ``info["void"]`` holds the voids (N, rows) and ``info["film"]`` the model. :func:`mass_balance` checks the
    film's liquid against what crossed its faces.
    """
    apparatus, limits = run.system, run.limits
    args = run_args(apparatus, film, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                    max_turns=limits.max_turns, frame_terms=run.frame_terms, fluid_spin=run.fluid_spin)
    stops = int(limits.stops)
    result = integrate(rhs, jacobian, (0.0, run.t_end), initial_state(apparatus, initial, film), args=args,
                       method=run.method, rtol=run.rtol, atol=run.rtol * parts(args[0])[full.TYPICAL], events=events,
                       terminal=(stops, stops, 1, 0, 0), direction=(-1, -1, -1, 0, 1), t_eval=run.t_eval,
                       max_steps=run.max_steps, progress=run.progress)
    tau = apparatus.tau
    obs = full.observables(apparatus, result.y[:7], initial.phi)
    fields = {"t": result.t / tau, "kind": result.kind, "event_names": event_names(result.event, full.EVENT_NAMES),
              "kappa": obs["kappa"], "one_minus_kappa": obs["one_minus_kappa"], "phi": obs["phi"],
              "kappa_dot": obs["kappa_dot"] * tau, "phi_dot": obs["phi_dot"] * tau,
              "omega_a": obs["omega_a"] * tau, "omega_b": obs["omega_b"] * tau, "x_b": obs["x_b"] / apparatus.b,
              "stop": full.EVENT_NAMES[result.stop_event] if result.stop_event >= 0 else "",
              "code": result.code, "status_code": result.status, "message": result.message,
              "steps": result.steps, "nfev": result.nfev, "njev": result.njev, "nlu": result.nlu}
    trajectory = run.trajectory(fields, "full", film.name, apparatus.reduced_params)
    keep = run.keep(fields)
    void = result.y[7:7 + film.n, keep]
    reservoir = result.y[7 + film.n, keep]
    areas = _areas(apparatus, film.n, obs["one_minus_kappa"][keep])
    # a filled node's void decays as exp(-t/tau_r) rather than vanishing: count the nodes whose gas is more
    # than a rounding-level share of their cell as holding gas
    trajectory.columns.update(liquid=np.sum(areas - void, axis=0), cavity_area=void.sum(axis=0),
                              cavitated_fraction=np.mean(void > 1e-9 * areas, axis=0),
                              reservoir=reservoir,
                              reservoir_pressure=film.reservoir_pressure(apparatus.length, reservoir))
    trajectory.info.update(void=void, film=film)
    return trajectory


def _areas(annulus_or_apparatus, n: int, one_minus_kappa) -> np.ndarray:
    """V_j at each of the gaps ``one_minus_kappa``: shape (N, rows)."""
    ap = annulus_or_apparatus
    return np.array([dual_areas(Annulus(ap.a, ap.b, length=ap.length, one_minus_kappa=float(omk)), n)
                     for omk in one_minus_kappa]).reshape(-1, n).T


@dataclass(frozen=True)
class MassBalance:
    """The film's liquid along a run against the liquid that crossed its faces.

    Attributes
    ----------
    content : ndarray, shape (k,)
        sum_j (V_j - v_j) + R at the output rows: the film's liquid and what the
        reservoir took from it, per unit length (m^2); constant in exact arithmetic.
    turnover : float
        int sum_j |qbar_j| dt, the liquid that crossed the faces (and, where the
        feed or the ends exchange it, the exchange), by the trapezoidal rule over the
        output rows (m^2 per unit length).
    """

    content: np.ndarray
    turnover: float

    @property
    def residual(self) -> float:
        """max_t |content(t) - content(0)| / turnover."""
        return float(np.max(np.abs(self.content - self.content[0])) / self.turnover)


def _mass_balance(annulus: Annulus, fluid: Fluid, film: TransportedFilm, t, one_minus_kappa, motions, void,
                  reservoir) -> MassBalance:
    """:class:`MassBalance` from the rows of a run: gaps, (eps', W_a, W_b) per row, voids (N, rows), R."""
    areas = _areas(annulus, film.n, one_minus_kappa)
    gross = np.empty(t.size)
    for k in range(t.size):
        row = Annulus(annulus.a, annulus.b, length=annulus.length, one_minus_kappa=float(one_minus_kappa[k]))
        eps_dot, w_a, w_b = motions[k]
        # an emptied cell's void may pass its area by rounding
        rates = film_rates(row, Motion(eps_dot=eps_dot, omega_a=w_a, omega_b=w_b), fluid, film,
                           void=np.minimum(void[:, k], areas[:, k]), reservoir=reservoir[k])
        gross[k] = np.sum(np.abs(rates.flux)) + abs(rates.d_reservoir)
    turnover = float(np.sum(0.5 * (gross[1:] + gross[:-1]) * np.diff(t)))
    return MassBalance(np.sum(areas - void, axis=0) + reservoir, turnover)


def mass_balance(apparatus: Apparatus, trajectory) -> MassBalance:
    """The film's mass balance along a run with a transported film (:func:`film_run`)."""
    film, void = trajectory.info["film"], trajectory.info["void"]
    c = trajectory.columns
    motions = np.column_stack((apparatus.delta * c["kappa_dot"], c["omega_a"] - c["phi_dot"],
                               c["omega_b"] - c["phi_dot"]))
    annulus = Annulus(apparatus.a, apparatus.b, length=apparatus.length, one_minus_kappa=0.5)
    return _mass_balance(annulus, Fluid(nu=apparatus.nu, rho=apparatus.rho), film, c["t"], c["one_minus_kappa"],
                         motions, void, c["reservoir"])


# -- the film alone, through a prescribed rocking ---------------------------------------------

# entries of the rocking motion's array (args[0])
_RA, _RB, _RMU, _RLEN, _KAPPA0, _AMPLITUDE, _OMEGA, _WA, _WB = range(9)


@jit
def rocking_rhs(t, y, args):
    """d(void, R)/dt of the film under kappa = kappa0 + A sin(omega t) and fixed W_a, W_b."""
    k = args[0]
    a, b = k[_RA], k[_RB]
    phase = k[_OMEGA] * t
    kappa = k[_KAPPA0] + k[_AMPLITUDE] * math.sin(phase)
    eps_dot = (b - a) * k[_AMPLITUDE] * k[_OMEGA] * math.cos(phase)
    n = y.size - 1
    dy = np.empty(y.size)
    dy[n] = _film(args[1], a, b, k[_RMU], k[_RLEN], kappa, 1.0 - kappa, eps_dot, k[_WA], k[_WB], y[:n], y[n],
                  dy[:n])[3]
    return dy


@jit
def rocking_jacobian(t, y, args):
    """d(rocking_rhs)/dy by central differences."""
    return central_differences(rocking_rhs, t, y, args, args[2])


@jit
def _no_events(t, y, args):
    return np.empty(0)


@dataclass(frozen=True)
class Rocking:
    """The film through a prescribed rocking (:func:`rock`).

    Attributes
    ----------
    t : ndarray, shape (k,)
        Output times (s).
    kappa : ndarray, shape (k,)
    void : ndarray, shape (N, k)
        Gas area of each dual cell per unit length (m^2).
    reservoir : ndarray, shape (k,)
        Liquid the reservoir has taken from the film per unit length (m^2).
    area : ndarray, shape (N, k)
        Gap area V_j of each dual cell (m^2).
    balance : MassBalance
        The film's liquid against what crossed its faces, over the output rows.
    steps, nfev, njev : int
    message : str
    """

    t: np.ndarray
    kappa: np.ndarray
    void: np.ndarray
    reservoir: np.ndarray
    area: np.ndarray
    balance: MassBalance
    steps: int
    nfev: int
    njev: int
    message: str

    @property
    def content(self) -> np.ndarray:
        """The film's liquid per unit length, sum_j (V_j - v_j) (m^2)."""
        return np.sum(self.area - self.void, axis=0)


def rock(annulus: Annulus, fluid: Fluid, film: TransportedFilm, *, amplitude: float, omega: float, w_a: float,
         w_b: float, t_end: float, void0=None, rtol: float = 1e-8, t_eval=None, method: str = "radau") -> Rocking:
    """The film from ``void0`` (None: full) under kappa = annulus.kappa + amplitude sin(omega t).

    ``w_a``, ``w_b`` are the spins relative to the line of centres (rad/s), which does
    not turn; ``annulus.length`` is the film's length. ``void0`` (m^2 per cell) must
    lie in [0, V_j] at kappa = annulus.kappa.
    """
    kappa0 = annulus.kappa
    amplitude, omega = check_finite("amplitude", amplitude), check_finite("omega", omega)
    w_a, w_b = check_finite("w_a", w_a), check_finite("w_b", w_b)
    if not (0.0 <= kappa0 - abs(amplitude) and kappa0 + abs(amplitude) < 1.0):
        msg = f"kappa0 +- amplitude must stay in [0, 1), got kappa0 = {kappa0:g} and amplitude = {amplitude:g}"
        raise ValueError(msg)
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True, unit="s")
    n = film.n
    area0 = dual_areas(annulus, n)
    y0 = np.zeros(n + 1)
    if void0 is not None:
        y0[:n] = np.asarray(void0, dtype=float)
        if np.shape(void0) != (n,) or not np.all((y0[:n] >= 0.0) & (y0[:n] <= area0)):
            msg = f"void0 must have shape ({n},) and lie in [0, V_j] (the gap area of each cell)"
            raise ValueError(msg)
    motion = np.array([annulus.a, annulus.b, fluid.mu, annulus.length, kappa0, amplitude, omega, w_a, w_b],
                      dtype=float)
    typical = np.full(n + 1, void_scale(annulus, n))
    args = (motion, film.kernel_data(annulus.a, annulus.length), typical)
    result = integrate(rocking_rhs, rocking_jacobian, (0.0, t_end), y0, args=args, method=method, rtol=rtol,
                       atol=rtol * typical, events=_no_events, t_eval=t_eval)
    if not result.success:
        raise RuntimeError(f"the rocking film failed: {result.message}")
    rows = (result.kind & EVENT) == 0
    t = result.t[rows]
    kappa = kappa0 + amplitude * np.sin(omega * t)
    eps_dot = (annulus.b - annulus.a) * amplitude * omega * np.cos(omega * t)
    void, reservoir = result.y[:n, rows], result.y[n, rows]
    motions = np.column_stack((eps_dot, np.full(t.size, w_a), np.full(t.size, w_b)))
    balance = _mass_balance(annulus, fluid, film, t, 1.0 - kappa, motions, void, reservoir)
    return Rocking(t, kappa, void, reservoir, _areas(annulus, n, 1.0 - kappa), balance, result.steps, result.nfev,
                   result.njev, result.message)
