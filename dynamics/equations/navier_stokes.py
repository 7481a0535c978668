r"""The two cylinders coupled to the unsteady Navier-Stokes flow of the gap: the closed problem, no closure in it.

The flow. Plane incompressible Navier-Stokes flow in the annulus, per unit length,
in the frame translating with the outer centre B (:mod:`lubrication.unsteady`): the
inner wall moves with A's velocity U = (z_A)' and spins at Omega_a about A, the
outer spins at Omega_b about B. Gravity and B's acceleration a_B = (b Omega_b', 0)
are uniform body forces there; they only add the linear pressure rho (g - a_B) . x,
whose force on the inner wall is -m''_a (g - a_B) (per the whole length) and whose
torques vanish. The solver's loads (F_x, F_z, T_a, T_b) are the rest, the dynamic
part, from the wall stress.

The bodies, with x down the slope and z along the plane's normal, g = g (sin alpha,
-cos alpha), clockwise spins and torques, masses over the whole length L:

* the inner cylinder, m_a (a_B + U') = L F + m_a g - m''_a (g - a_B), i.e.

      m_a U' + m'_a b Omega_b' e_x = L F + m'_a g,         (1/2) m_a a^2 Omega_a' = L T_a;

* the fluid of the gap, whose momentum in the frame of B is -m''_a U (its centroid
  moves opposite to the displaced volume's), takes from the outer wall the force
  F_B = (m_f + m''_a)(g - a_B) - L F + m''_a U';
* the outer cylinder and what turns with it (the shell m_b b^2 and the fluid of the
  end regions m_ends, a solid disc b^2/2 as it spins with the tube), rolling without
  slip, X_b' = b Omega_b: its two Newton laws with the plane's friction f at the
  contact point eliminated, (m_B b^2 + I_B) Omega_b' = L T_b + b F_B,x + m_B g b sin alpha
  with m_B = m_b + m_ends, give

      [I_B + (m_B + m_f + m''_a) b^2] Omega_b' - m''_a b U_x' = L T_b - b L F_x + (m_B + m_f + m''_a) g b sin alpha.

Per unit length these are four linear equations M_q q' - C loads = f for q = (U_x,
U_z, Omega_a, Omega_b) (:func:`body_laws`); with the BDF derivative of the solver's
step, q' = c0 q_new + history, they are the wall equations M q_new - C loads_new = r
the solver solves together with the flow (:func:`wall_equations`): one linear system
per step, the added mass inside it, stable at any density ratio.

Checks of the laws (tests/test_navier_stokes_coupled.py): everything locked in rigid
rotation rolls as one body of moment I_B + I_f + I_a + M b^2 about the contact line;
with the fluid's density taken to zero they become the full ODE model with the Stokes
forces; the energy balance of :func:`energy_columns` with
:func:`lubrication.unsteady.energy.flow_energy`.

What the ODE models differ in: the fluid's own angular momentum in (2.4) is a closure
(``fluid_spin``: by default that of the Stokes flow at the eccentricity; none as printed), the
end fluid's moment of inertia is left out, and (2.1)-(2.2) close the fluid's inertia with
m_eff and the ``frame_terms`` choice; here nothing is closed.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from dynamics.initial import Initial
from numerics.engine import END, EVENT, INTERRUPTED, SAMPLE, START, STEP, Interrupts

__all__ = ["BodyLaws", "NavierStokesOptions", "body_laws", "energy_columns", "initial_motion", "navier_stokes_run",
           "wall_equations"]


@dataclass(frozen=True)
class BodyLaws:
    """The cylinders' Newton laws per unit length, M_q q' - C loads = f, q = (U_x, U_z, Omega_a, Omega_b).

    Attributes
    ----------
    mass : ndarray, shape (4, 4)
        M_q (kg/m, kg m).
    coupling : ndarray, shape (4, 4)
        C: how the loads (F_x, F_z, T_a, T_b) per unit length enter.
    forcing : ndarray, shape (4,)
        f: gravity and buoyancy (N/m, N m/m).
    """

    mass: np.ndarray
    coupling: np.ndarray
    forcing: np.ndarray


def body_laws(apparatus) -> BodyLaws:
    """:class:`BodyLaws` of an :class:`~dynamics.apparatus.Apparatus` (module docstring)."""
    ap = apparatus
    b, length = ap.b, ap.length
    m_a, m_disp, m_red, m_f = ap.m_a, ap.m_a_displaced, ap.m_a_reduced, ap.m_f
    m_outer = ap.m_b + ap.m_f_ends
    i_outer = ap.m_b * b * b + 0.5 * ap.m_f_ends * b * b
    rolling = m_outer + m_f + m_disp
    mass = np.array([[m_a, 0.0, 0.0, m_red * b],
                     [0.0, m_a, 0.0, 0.0],
                     [0.0, 0.0, 0.5 * m_a * ap.a**2, 0.0],
                     [-m_disp * b, 0.0, 0.0, i_outer + rolling * b * b]]) / length
    coupling = np.array([[1.0, 0.0, 0.0, 0.0],
                         [0.0, 1.0, 0.0, 0.0],
                         [0.0, 0.0, 1.0, 0.0],
                         [-b, 0.0, 0.0, 1.0]])
    sin_a, cos_a = math.sin(ap.alpha), math.cos(ap.alpha)
    forcing = np.array([m_red * ap.g * sin_a, -m_red * ap.g * cos_a, 0.0, rolling * ap.g * b * sin_a]) / length
    return BodyLaws(mass, coupling, forcing)


def wall_equations(laws: BodyLaws, bdf, q_now: np.ndarray, q_before: np.ndarray | None):
    """(M, C, r) of the solver's step: the laws with q' = c0 q_new + (alpha1 q_n + alpha2 q_{n-1})/dt."""
    history = bdf.history(q_now, 0.0 if q_before is None else q_before)
    return laws.mass * bdf.c0, laws.coupling, laws.forcing - laws.mass @ history


def initial_motion(apparatus, initial: Initial) -> tuple[complex, np.ndarray]:
    """The inner centre z_A = x + i z relative to B (m) and q = (U_x, U_z, Omega_a, Omega_b) of a start."""
    eps = (1.0 - initial.gap) * apparatus.delta
    chi = initial.phi - apparatus.alpha
    eps_dot = initial.kappa_dot * apparatus.delta
    e_eps, e_chi = complex(math.sin(chi), math.cos(chi)), complex(math.cos(chi), -math.sin(chi))
    velocity = eps_dot * e_eps + eps * initial.phi_dot * e_chi
    return eps * e_eps, np.array([velocity.real, velocity.imag, initial.omega_a, initial.omega_b])


@dataclass(frozen=True)
class NavierStokesOptions:
    """Settings of the flow solver in a coupled run.

    Attributes
    ----------
    n_r : int
        Chebyshev points across the gap.
    n_theta : int or None
        Points around; None: the solver's default for the current gap, the grid following the gap
        as it narrows or widens (by a factor REGRID apart).
    snapshot_times : tuple of float
        Times (s) at which the run keeps the flow field (steps land on them).
    reuse_factorisations : bool
        Reuse the step's factorisations across steps and corrections (defect correction); False
        factorises every solve (``StepControl(reuse=False)``): the same step control, the baseline of what
        reuse saves (benchmarks/navier_stokes.py).
    """

    n_r: int = 16
    n_theta: int | None = None
    snapshot_times: tuple = ()
    reuse_factorisations: bool = True


#: The default grid is changed when the gap's own default differs from it by this factor.
REGRID = 1.5


def navier_stokes_run(run, initial: Initial, options: NavierStokesOptions = NavierStokesOptions()):
    """The coupled problem from ``initial`` over the run's settings (a :class:`~dynamics.trajectory.Recorder`):
    the case of :func:`dynamics.simulation.simulate` with ``equations = "navier-stokes"``.

    The fluid starts at rest if the bodies do, and otherwise in the steady flow of their initial motion (the
    state every quasi-steady model assumes). The step is the solver's adaptive IMEX BDF2 with its local error
    control at ``run.rtol`` on the vorticity, the wall velocities and A's position. Rows: every accepted
    step (or the requested times, on which the steps land). Stops: ``t_end``; the gap floor (the larger of
    ``limits.gap_floor`` and the solver's reach); a runaway's ``max_turns``; Ctrl-C (interrupted).

    The :class:`~dynamics.trajectory.Trajectory` adds the columns ``f_eps``, ``f_chi`` (N), ``T_a``, ``T_b``
    (N m): the fluid's dynamic loads over the whole length; ``kinetic_energy``, ``potential_energy`` and
    ``dissipated`` (J, :func:`energy_columns`), whose sum stays constant; ``info["navier_stokes"]`` the grid, the counts
    and, with ``snapshot_times``, ``info["snapshots"]``: the fields (:meth:`lubrication.unsteady.solver.UnsteadySolver.fields`) with
    ``t``, the outer cylinder's turn ``theta_b`` (rad) and spin ``omega_b`` (rad/s), clockwise, as
    :func:`lubrication.unsteady.snapshots.in_frame` takes them.
    """
    from lubrication.unsteady import (
        MIN_ONE_MINUS_KAPPA_UNSTEADY,
        AnnulusMap,
        Resolution,
        StepControl,
        UnsteadySolver,
        default_resolution,
    )

    ap, limits, tau = run.system, run.limits, run.system.tau
    floor = max(limits.gap_floor, MIN_ONE_MINUS_KAPPA_UNSTEADY)
    if floor > limits.gap_floor:
        limits = replace(limits, gap_floor=floor)
        run.limits = limits
    if initial.gap <= floor:
        msg = (f"initial 1 - kappa = {initial.gap:.3g} is at or below {floor:g}, the narrowest gap the "
               "Navier-Stokes solver resolves")
        raise ValueError(msg)
    laws = body_laws(ap)
    z_a, q0 = initial_motion(ap, initial)

    def resolution_at(z: complex) -> Resolution:
        if options.n_theta is not None:
            return Resolution(options.n_theta, options.n_r)
        return default_resolution(AnnulusMap(ap.a, ap.b, z), options.n_r)

    solver = UnsteadySolver(ap.a, ap.b, ap.nu, ap.rho, resolution_at(z_a), control=StepControl(rtol=run.rtol, reuse=options.reuse_factorisations))
    solver.start(z_a, q0)
    if np.any(q0 != 0.0):
        _steady_start(solver, z_a, q0)

    def wall(_t_new, bdf):
        levels = solver.levels
        return wall_equations(laws, bdf, levels[0].q, levels[1].q if len(levels) >= 2 else None)

    targets = sorted({float(t) for t in (*(() if run.t_eval is None else run.t_eval), *options.snapshot_times)
                      if 0.0 < float(t) <= run.t_end} | {run.t_end})
    wanted = None if run.t_eval is None else set(float(t) for t in run.t_eval)
    snapshot_times = set(float(t) for t in options.snapshot_times)
    rows = [_row(solver, 0.0)]
    kinds = [START]
    snapshots = [_snapshot(solver, 0.0)] if 0.0 in snapshot_times else []
    x_b, turns_end = 0.0, 2.0 * math.pi * ap.b * limits.max_turns
    dt = 1e-3 * min(ap.delta**2 / ap.nu, tau)
    stop, status_code, message, code = "", 0, "", 0
    start = time.perf_counter()
    with Interrupts() as interrupts:
        while solver.state.t < run.t_end * (1.0 - 1e-12):
            if interrupts.received:
                status_code, code = 2, INTERRUPTED
                message = ("interrupted" if interrupts.received == "SIGINT" else f"interrupted by {interrupts.received}")
                break
            if len(rows) > run.max_steps:
                status_code, message = 2, f"more than max_steps = {run.max_steps} steps"
                break
            now = solver.state
            target = next(t for t in targets if t > now.t * (1.0 + 1e-14))
            h = min(dt, target - now.t)
            if target - now.t - h < 0.05 * h:  # no sliver before a target
                h = target - now.t
            try:
                result = solver.step(h, wall)
            except ValueError as err:  # the corrections took A past the solver's reach
                if "one_minus_kappa" not in str(err):
                    raise
                result = None
            if result is None or not result.accepted:
                dt = 0.5 * h if result is None else result.dt_next
                if dt < 1e-14 * max(run.t_end, tau):
                    status_code = 2
                    message = f"step size underflow at t = {now.t:.6g} s" + ("" if result is None else f" ({result.reason})")
                    break
                continue
            new = solver.state
            x_b += 0.5 * (now.q[3] + new.q[3]) * h * ap.b  # trapezoidal: second order, as the step
            reached = abs(new.t - target) <= 1e-12 * max(target, tau)
            rows.append(_row(solver, x_b))
            if reached:
                rows[-1][0] = target  # the time asked for, not its sum of steps
            kinds.append(STEP | (SAMPLE if reached and wanted is not None and target in wanted else 0))
            if reached and target in snapshot_times:
                snapshots.append(_snapshot(solver, x_b / ap.b))
            if run.progress is not None:
                run.progress(new.t)
            gap = 1.0 - abs(new.z_a) / ap.delta
            if gap <= floor * (1.0 + 1e-9):
                stop, status_code = "gap_floor", 1
                break
            if x_b >= turns_end:
                stop, status_code = "runaway", 1
                break
            dt = max(result.dt_next, dt) if h < dt else result.dt_next
            if options.n_theta is None:
                need = resolution_at(new.z_a)
                ratio = need.n_theta / solver.resolution.n_theta
                if ratio >= REGRID or ratio <= 1.0 / REGRID:
                    solver.regrid(need)
    wall_time = time.perf_counter() - start
    kinds[-1] |= END
    if stop:
        kinds[-1] |= EVENT
    if wanted is not None and 0.0 in wanted:
        kinds[0] |= SAMPLE
    return _trajectory(run, ap, initial, np.array(rows), np.array(kinds), stop, status_code, message, code,
                       solver, snapshots, wall_time)


def _row(solver, x_b: float) -> list[float]:
    from lubrication.unsteady.energy import flow_energy

    level = solver.state
    return [level.t, level.z_a.real, level.z_a.imag, *level.q, x_b, *level.loads, *flow_energy(solver)]


def _snapshot(solver, theta_b: float) -> dict:
    return {"t": solver.state.t, "theta_b": theta_b, "omega_b": float(solver.state.q[3]), **solver.fields()}


def _steady_start(solver, z_a: complex, q: np.ndarray) -> None:
    """Replace the fluid at rest by the steady flow of the walls' initial motion: steps with the walls held,
    doubling from a thousandth of the viscous time to a thousand of them (variable BDF2 is stable for step
    ratios below 1 + sqrt 2), then a start from that field."""
    from lubrication.unsteady import StepControl, prescribed_wall

    control = solver.control
    solver.control = StepControl(**{**control.__dict__, "adaptive": False})
    viscous = (solver.b - solver.a) ** 2 / solver.nu
    dt = 1e-3 * viscous
    while dt < 1e3 * viscous:
        solver.step(dt, prescribed_wall(q), z_a)
        dt *= 2.0
    level = solver.state
    solver.control = control
    solver.start(z_a, q, h_psi=level.h_psi, omega=level.omega, c_in=level.c_in)


def energy_columns(ap, t, x, z, u_x, u_z, omega_a, omega_b, x_b, kinetic_flow, dissipation) -> dict:
    """The energy balance of a coupled run's rows, over the whole length (J): ``kinetic_energy`` of the
    bodies and the gap's fluid (inertial frame), ``potential_energy`` relative to the start, and
    ``dissipated``, the viscous dissipation integrated in time (trapezoidal, second order as the step).
    Their sum is constant in the exact problem (the rolling contact does no work).

    The gap fluid's kinetic energy in the inertial frame is its energy in the frame of B plus
    V_B . P + m_f V_B^2/2, with V_B = b Omega_b along x and its momentum P = -m''_a U in that frame.
    """
    length, b = ap.length, ap.b
    v_b = b * omega_b
    m_outer, i_outer = ap.m_b + ap.m_f_ends, ap.m_b * b * b + 0.5 * ap.m_f_ends * b * b
    kinetic = (0.5 * ap.m_a * ((v_b + u_x) ** 2 + u_z**2) + 0.25 * ap.m_a * ap.a**2 * omega_a**2
               + 0.5 * m_outer * v_b**2 + 0.5 * i_outer * omega_b**2
               + length * kinetic_flow - ap.m_a_displaced * v_b * u_x + 0.5 * ap.m_f * v_b**2)
    g_x, g_z = ap.g * math.sin(ap.alpha), -ap.g * math.cos(ap.alpha)
    potential = -(ap.M * g_x * x_b + ap.m_a_reduced * (g_x * x + g_z * z))
    dissipated = np.concatenate([[0.0], np.cumsum(0.5 * (dissipation[1:] + dissipation[:-1]) * np.diff(t))]) * length
    return {"kinetic_energy": kinetic, "potential_energy": potential - potential[0], "dissipated": dissipated}


def _trajectory(run, ap, initial, table, kinds, stop, status_code, message, code, solver, snapshots, wall_time):
    """The rows as a :class:`~dynamics.trajectory.Trajectory` (:meth:`Recorder.trajectory`'s scaled fields)."""
    tau, delta = ap.tau, ap.delta
    t, x, z, u_x, u_z, omega_a, omega_b, x_b, f_x, f_z, t_a, t_b, kinetic_flow, dissipation = table.T
    eps = np.hypot(x, z)
    chi = np.unwrap(np.arctan2(x, z))
    if chi.size:
        chi += 2.0 * math.pi * round((initial.phi - ap.alpha - chi[0]) / (2.0 * math.pi))
    with np.errstate(divide="ignore", invalid="ignore"):
        phi_dot = np.where(eps > 0.0, (z * u_x - x * u_z) / eps**2, 0.0)
        kappa_dot = np.where(eps > 0.0, (x * u_x + z * u_z) / (eps * delta), 0.0)
    if eps.size and eps[0] == 0.0:  # chi undefined at the centre: that of the start
        chi[0] = initial.phi - ap.alpha
    fields = {"t": t / tau, "kind": kinds, "event_names": np.where((kinds & EVENT) != 0, stop, ""),
              "kappa": eps / delta, "one_minus_kappa": (delta - eps) / delta, "phi": chi + ap.alpha,
              "kappa_dot": kappa_dot * tau, "phi_dot": phi_dot * tau, "omega_a": omega_a * tau,
              "omega_b": omega_b * tau, "x_b": x_b / ap.b, "stop": stop, "code": code, "status_code": status_code,
              "message": message + (f" at t = {t[-1]:.6g} s" if code == INTERRUPTED else ""),
              "steps": solver.counters.steps, "nfev": solver.counters.solves, "njev": 0,
              "nlu": solver.counters.factorisations}
    trajectory = run.trajectory(fields, "navier-stokes", "navier-stokes", ap.reduced_params)
    trajectory.method = "imex-bdf2"  # the flow's own stepping, not the ODE integrator's
    trajectory.info.pop("inertia", None)  # the quasi-steady models' error estimate: none here
    trajectory.columns["t"] = np.minimum(trajectory.columns["t"], run.t_end)  # t/tau*tau may pass t_end by an ulp
    # the loads at the rows the trajectory kept (each a row of the table: interpolation only absorbs rounding)
    e_eps_x, e_eps_z = np.sin(chi), np.cos(chi)
    loads = {"f_eps": f_x * e_eps_x + f_z * e_eps_z, "f_chi": f_x * e_eps_z - f_z * e_eps_x, "T_a": t_a, "T_b": t_b}
    energies = energy_columns(ap, t, x, z, u_x, u_z, omega_a, omega_b, x_b, kinetic_flow, dissipation)
    kept = trajectory.columns["t"]
    trajectory.columns.update({name: ap.length * np.interp(kept, t, value) for name, value in loads.items()})
    trajectory.columns.update({name: np.interp(kept, t, value) for name, value in energies.items()})
    c = solver.counters
    trajectory.info["navier_stokes"] = {
        "n_theta": solver.resolution.n_theta, "n_r": solver.resolution.n_r, "steps": c.steps,
        "rejected": c.rejected, "factorisations": c.factorisations, "solves": c.solves, "wall_time_s": wall_time,
        "stokes_number": ap.delta**2 / (ap.nu * tau)}
    if snapshots:
        trajectory.info["snapshots"] = snapshots
    return trajectory
