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
keeps to rounding. The stops are those of the full model (:func:`dynamics.equations.full.events`,
which reads only the first seven components).

The film's right-hand side is Lipschitz and piecewise smooth (a node's switch
between cavitated and pressed is a kink), and stiff: the relaxation of a pressed
node's void, 1/tau_r, and the film's own Poiseuille modes. The Jacobian is by
central differences (as :func:`dynamics.equations.full.jacobian`); a void's step
is a fixed tiny area, so that a probe of a pressed node (v = 0) stays on the
smooth side of its switch.

:func:`rock` drives the film alone through a prescribed motion, kappa = kappa0 +
A sin(omega t) at fixed spins: the tests' and the validation's rocking film.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dynamics.apparatus import Apparatus
from dynamics.engine import EVENT
from dynamics.equations import full
from dynamics.equations.forces import closed_form
from dynamics.equations.full import _A, _B, _LEN, _MU
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.integrate import integrate
from lubrication._film_kernels import film_rates
from lubrication._jit import jit
from lubrication.film_transport import TransportedFilm, dual_areas
from lubrication.geometry import Annulus, Fluid, check_range

__all__ = ["Rocking", "initial_state", "jacobian", "rhs", "rock", "rocking_jacobian", "rocking_rhs", "run_args",
           "simulate_film", "void_scale"]

#: A void's finite-difference step and absolute-tolerance floor, as a fraction of a mean dual cell's area:
#: small enough that a probe of a pressed node does not cross its switch (module docstring).
VOID_FLOOR = 1e-6


@jit(inline="always")
def _film(film, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, void, reservoir, d_void, y, fraction):
    """:func:`lubrication._film_kernels.film_rates` with the model's data as one tuple."""
    cpsi, spsi, vpsi, ppsi, wpsi, m, faces, node_p, gauge, p_cav, p_ref, bubble, eps_end, relaxation = film
    return film_rates(a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, cpsi, spsi, vpsi, ppsi, wpsi, m, faces,
                      node_p, gauge, p_cav, p_ref, bubble, eps_end, relaxation, void, reservoir, d_void, y, fraction)


@jit
def rhs(t, y, args):
    """dy/dt; ``args`` from :func:`run_args` (parameters, film data, typical scales, event parameters)."""
    p, film = args[0], args[1]
    a, b = p[_A], p[_B]
    delta = b - a
    kappa, omk, zeta, eps, big_u, ex, ez = full._geometry(y, delta)
    vx, vz, omega_a, omega_b = y[2], y[3], y[4], y[5]
    eps_dot = ex * vx + ez * vz
    chi_dot = (ez * vx - ex * vz) / eps if eps > 0.0 else 0.0
    n = y.size - 8
    dy = np.empty(y.size)
    pressure, fraction = np.empty(n), np.empty(n)
    f_eps, f_chi, t_a, d_reservoir, _ = _film(film, a, b, p[_MU], p[_LEN], kappa, omk, eps_dot, omega_a - chi_dot,
                                              omega_b - chi_dot, y[7:7 + n], y[7 + n], dy[7:7 + n], pressure,
                                              fraction)
    frame_eps, frame_chi = full.frame_force(p, eps, eps_dot, chi_dot)
    fluid = full.force_response(p, eps, ex, ez, f_eps + frame_eps, f_chi + frame_chi, t_a)
    gravity = full.gravity_response(p)
    scale = 1.0 / (delta * zeta)
    stretch = big_u * big_u * eps_dot
    dy[0] = (vx + stretch * ex) * scale
    dy[1] = (vz + stretch * ez) * scale
    for i in range(4):
        dy[2 + i] = fluid[i] + gravity[i]
    dy[6] = b * omega_b
    dy[7 + n] = d_reservoir
    return dy


@jit(inline="always")
def _central_differences(fun, t, y, args):
    """d fun/dy by central differences, steps eps^(1/3) max(|y_j|, typical_j) (``args[2]``)."""
    typical = args[2]
    n = y.size
    jac = np.empty((n, n))
    yp = y.copy()
    for j in range(n):
        h = 6.0554544523933395e-06 * max(abs(y[j]), typical[j])  # eps^(1/3)
        yp[j] = y[j] + h
        up = fun(t, yp, args)
        yp[j] = y[j] - h
        down = fun(t, yp, args)
        yp[j] = y[j]
        for i in range(n):
            jac[i, j] = (up[i] - down[i]) / (2.0 * h)
    return jac


@jit
def jacobian(t, y, args):
    """d(rhs)/dy by central differences (module docstring)."""
    return _central_differences(rhs, t, y, args)


def void_scale(apparatus_or_annulus, n: int) -> float:
    """:data:`VOID_FLOOR` times the mean dual cell's gap area 2 pi a delta / N (m^2)."""
    ap = apparatus_or_annulus
    return VOID_FLOOR * 2.0 * math.pi * ap.a * (ap.b - ap.a) / n


def run_args(apparatus: Apparatus, film: TransportedFilm, *, gap_floor: float, max_reynolds: float = math.inf,
             max_turns: float = math.inf, frame_terms: str = "paper") -> tuple:
    """The ``args`` of :func:`rhs`, :func:`jacobian` and :func:`dynamics.equations.full.events`.

    (parameters, film data, typical scales, event parameters); the parameters and
    the events are the full model's (:func:`dynamics.equations.full.run_args`).
    """
    base = full.run_args(apparatus, closed_form(), gap_floor=gap_floor, max_reynolds=max_reynolds,
                         max_turns=max_turns, frame_terms=frame_terms)
    floor = void_scale(apparatus, film.n)
    typical = np.concatenate((base[2], np.full(film.n + 1, floor)))
    return (base[0], film.kernel_data(apparatus.a, apparatus.length), typical, base[3])


def initial_state(apparatus: Apparatus, initial: Initial, film: TransportedFilm) -> np.ndarray:
    """The full model's state from ``initial``, a full film (no void) and a reservoir at its start."""
    motion = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                                initial.omega_a, initial.omega_b, one_minus_kappa=initial.gap)
    return np.concatenate((motion, np.zeros(film.n + 1)))


def simulate_film(apparatus: Apparatus, initial: Initial, t_end: float, film: TransportedFilm, *,
                  limits: Limits = Limits(), rtol: float = 1e-8, method: str = "radau", t_eval=None,
                  max_steps: int = 2_000_000, progress=None, frame_terms: str = "paper"):
    """Integrate the full model with the transported film; as :func:`dynamics.simulation.simulate`.

    Returns a :class:`dynamics.simulation.Trajectory` whose columns add, per row,
    ``cavity_area`` (the film's gas area per unit length, m^2), ``cavitated_fraction``
    (share of the nodes not full), ``reservoir`` (R, m^2) and ``reservoir_pressure`` (Pa);
    ``info["void"]`` holds the voids (N, rows).
    """
    from dynamics.simulation import _Run

    if not isinstance(film, TransportedFilm):
        msg = f"film must be a TransportedFilm, got {type(film).__name__}"
        raise TypeError(msg)
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True, unit="s")
    run = _Run(apparatus, False, t_end, limits, method, rtol, None if t_eval is None else np.asarray(t_eval, float),
               max_steps, progress)
    run.frame_terms = frame_terms
    args = run_args(apparatus, film, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                    max_turns=limits.max_turns, frame_terms=frame_terms)
    stops = int(limits.stops)
    result = integrate(rhs, jacobian, (0.0, t_end), initial_state(apparatus, initial, film), args=args,
                       method=method, rtol=rtol, atol=rtol * args[2], events=full.events,
                       terminal=(stops, stops, 1, 0, 0), direction=(-1, -1, -1, 0, 1), t_eval=run.t_eval,
                       max_steps=max_steps, progress=progress)
    tau = apparatus.tau
    obs = full.observables(apparatus, result.y[:7], initial.phi)
    names = np.array(("", *full.EVENT_NAMES), dtype=object)[result.event + 1]
    fields = {"t": result.t / tau, "kind": result.kind, "event_names": names,
              "kappa": obs["kappa"], "one_minus_kappa": obs["one_minus_kappa"], "phi": obs["phi"],
              "kappa_dot": obs["kappa_dot"] * tau, "phi_dot": obs["phi_dot"] * tau,
              "omega_a": obs["omega_a"] * tau, "omega_b": obs["omega_b"] * tau, "x_b": obs["x_b"] / apparatus.b,
              "stop": full.EVENT_NAMES[result.stop_event] if result.stop_event >= 0 else "",
              "code": result.code, "status_code": result.status, "message": result.message,
              "steps": result.steps, "nfev": result.nfev, "njev": result.njev, "nlu": result.nlu}
    trajectory = run._trajectory(fields, "full", film.name, apparatus.reduced_params)
    keep = run._keep(fields)
    void = result.y[7:7 + film.n, keep]
    reservoir = result.y[7 + film.n, keep]
    areas = np.array([dual_areas(Annulus(apparatus.a, apparatus.b, length=apparatus.length, one_minus_kappa=omk), film.n)
                      for omk in obs["one_minus_kappa"][keep]]).T
    trajectory.columns.update(cavity_area=void.sum(axis=0),
                              cavitated_fraction=np.mean(void > 1e-9 * areas, axis=0),
                              reservoir=reservoir,
                              reservoir_pressure=film.reservoir_pressure(apparatus.length, reservoir))
    trajectory.info.update(void=void, film=film)
    return trajectory


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
    pressure, fraction = np.empty(n), np.empty(n)
    rates = _film(args[1], a, b, k[_RMU], k[_RLEN], kappa, 1.0 - kappa, eps_dot, k[_WA], k[_WB], y[:n], y[n],
                  dy[:n], pressure, fraction)
    dy[n] = rates[3]
    return dy


@jit
def rocking_jacobian(t, y, args):
    """d(rocking_rhs)/dy by central differences."""
    return _central_differences(rocking_rhs, t, y, args)


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
    steps, nfev, njev : int
    message : str
    """

    t: np.ndarray
    kappa: np.ndarray
    void: np.ndarray
    reservoir: np.ndarray
    area: np.ndarray
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
    not turn; ``annulus.length`` is the film's length.
    """
    kappa0 = annulus.kappa
    if not (0.0 <= kappa0 - abs(amplitude) and kappa0 + abs(amplitude) < 1.0):
        msg = f"kappa0 +- amplitude must stay in [0, 1), got kappa0 = {kappa0:g} and amplitude = {amplitude:g}"
        raise ValueError(msg)
    n = film.n
    motion = np.array([annulus.a, annulus.b, fluid.mu, annulus.length, kappa0, amplitude, omega, w_a, w_b],
                      dtype=float)
    typical = np.full(n + 1, void_scale(annulus, n))
    args = (motion, film.kernel_data(annulus.a, annulus.length), typical)
    y0 = np.concatenate((np.zeros(n) if void0 is None else np.asarray(void0, dtype=float), [0.0]))
    result = integrate(rocking_rhs, rocking_jacobian, (0.0, t_end), y0, args=args, method=method, rtol=rtol,
                       atol=rtol * typical, events=_no_events, t_eval=t_eval)
    if not result.success:
        raise RuntimeError(f"the rocking film failed: {result.message}")
    rows = (result.kind & EVENT) == 0
    t = result.t[rows]
    kappa = kappa0 + amplitude * np.sin(omega * t)
    areas = np.array([dual_areas(Annulus(annulus.a, annulus.b, length=annulus.length, one_minus_kappa=1.0 - k), n)
                      for k in kappa]).T
    return Rocking(t, kappa, result.y[:n, rows], result.y[n, rows], areas, result.steps, result.nfev, result.njev,
                   result.message)
