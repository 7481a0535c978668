"""``snail flow``'s run and its output set: a :class:`FlowSpec` stepped, then forces.csv, summary.json, snapshots.

:func:`run_flow` steps :class:`lubrication.unsteady.UnsteadySolver` through the prescribed
motion with the loop of :func:`lubrication.unsteady.run_prescribed`
(:func:`lubrication.unsteady.prescribed.march`: the same first step, largest step and
landing on the snapshot times), and adds what a command needs and that driver does not: the time reached reported as it goes, and a stop on Ctrl-C or SIGTERM
(or a failed step) that keeps everything computed so far. :func:`write_flow_outputs`
writes the set through an :class:`~numerics.folder.OutputFolder`: whole, or not at all.
"""

from __future__ import annotations

import io
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from dynamics.app.flow_spec import FlowSpec, turned_angle
from lubrication.unsteady import (
    LOAD_NAMES,
    PrescribedRun,
    StepControl,
    UnsteadySolver,
    first_steps,
    march,
)
from numerics.engine import Interrupts
from numerics.files import write_json, write_text
from numerics.folder import OutputFolder, held_signals

__all__ = ["COLUMNS", "FlowRun", "flow_folder", "forces_csv", "output_names", "run_flow", "write_flow_outputs"]

#: The columns of forces.csv (DESIGN.md): s, m, m, N, N, N m, N m.
COLUMNS = ("t", "x_a", "z_a", "F_x", "F_z", "T_a", "T_b")
#: The summary file, and the keys that mark a folder as holding a previous flow set.
SUMMARY = ("summary.json", frozenset({"status", "stokes_number", "reynolds_number"}))
STEM = "flow"


@dataclass
class FlowRun(PrescribedRun):
    """A run of :func:`run_flow`: the series of :class:`PrescribedRun` (per unit length), and how it ended.

    Each snapshot carries, besides the fields and ``t``, the outer cylinder's angle
    ``theta_b`` (rad, clockwise, the integral of Omega_b from 0) and spin ``omega_b`` (rad/s).

    Attributes
    ----------
    status : str
        "completed", "interrupted" (Ctrl-C or SIGTERM) or "failed".
    reason : str
        A sentence with the time reached.
    """

    status: str = "completed"
    reason: str = ""


def run_flow(spec: FlowSpec, *, progress=None) -> FlowRun:
    """Step the flow of ``spec`` from rest to ``spec.t_end``, or until interrupted or failed.

    ``progress(t)``, if given, is called after every accepted step with the time reached (s).
    Ctrl-C and SIGTERM (:class:`numerics.engine.Interrupts`) stop the run after the step under
    way; a step that fails (an arithmetic, linear-algebra or step-size failure) stops it too.
    Either way the series and snapshots up to the last accepted step are returned, with the
    status and the reason.
    """
    start = time.perf_counter()
    motion, t_end = spec.motion, spec.t_end
    solver = UnsteadySolver(spec.a, spec.b, spec.nu, spec.rho, spec.resolution, control=StepControl(rtol=spec.rtol))
    solver.start(motion.position(0.0), motion.velocities(0.0))
    dt, dt_max = first_steps(spec.delta, spec.nu, motion)
    targets = list(spec.snapshot_times)
    series = {name: [] for name in COLUMNS}
    snapshots = []

    def record(level):
        for name, value in zip(COLUMNS, (level.t, level.z_a.real, level.z_a.imag, *level.loads)):
            series[name].append(value)
        while targets and targets[0] <= level.t + 1e-12 * t_end:  # the steps land on them
            targets.pop(0)
            snapshots.append({"t": level.t, **solver.fields(), "theta_b": float(turned_angle(motion.omega_b, level.t)),
                              "omega_b": float(motion.omega_b.value(level.t))})
        if progress is not None and level.t > 0.0:
            progress(level.t)

    record(solver.state)
    status, reason = "completed", f"reached t_end = {t_end:.6g} s"
    with Interrupts() as interrupts:
        try:
            why = march(solver, motion, t_end, dt=dt, dt_max=dt_max, targets=targets, on_step=record,
                        stop=lambda: interrupts.received and
                        f"interrupted by {interrupts.received} at t = {solver.state.t:.6g} s")
            if why:
                status, reason = "interrupted", why
        except (ArithmeticError, ValueError, RuntimeError) as err:
            status = "failed"
            reason = f"{type(err).__name__} at t = {solver.state.t:.6g} s: {err}"
    c = solver.counters
    return FlowRun(**{name: np.array(values) for name, values in series.items()}, resolution=solver.resolution,
                   snapshots=snapshots, steps=c.steps, rejected=c.rejected, factorisations=c.factorisations,
                   sweeps=c.sweeps, wall_time_s=time.perf_counter() - start, status=status, reason=reason)


def output_names() -> frozenset[str]:
    """Every file a flow set may hold: forces.csv, summary.json, and the snapshots' VTU series (up to
    :data:`~lubrication.unsteady.snapshots.MAX_SNAPSHOTS` files), flow.pvd and flow.gif."""
    from lubrication.unsteady.snapshots import output_files

    return frozenset({"forces.csv", "summary.json", *output_files(STEM)})


def flow_folder(path: str | Path) -> OutputFolder:
    """The output folder of a flow set (to be entered): it replaces only a previous flow set."""
    return OutputFolder(path, output_names(), SUMMARY)


def forces_csv(spec: FlowSpec, run: FlowRun) -> str:
    """forces.csv: the loads over the apparatus' length (N, N m), clockwise torques; a header row."""
    buf = io.StringIO()
    buf.write(",".join(COLUMNS) + "\n")
    whole = {name: getattr(run, name) * spec.length for name in LOAD_NAMES}
    data = np.column_stack([run.t, run.x_a, run.z_a, *(whole[name] for name in LOAD_NAMES)])
    for row in data:
        buf.write(",".join(f"{x:.17g}" for x in row) + "\n")
    return buf.getvalue()


def _summary(spec: FlowSpec, run: FlowRun, snapshots: dict) -> dict:
    return {
        "status": run.status,
        "reason": run.reason,
        "success": run.status == "completed",
        "t_end": float(run.t[-1]),
        "t_end_requested": spec.t_end,
        "source": spec.source,
        "inputs": spec.resolved(),
        "resolution": {"n_theta": run.resolution.n_theta, "n_r": run.resolution.n_r,
                       "chosen_by": "motion file" if spec.resolution_given else
                       "the solver's default for the most eccentric position"},
        "steps": run.steps,
        "rejected_steps": run.rejected,
        "factorisations": run.factorisations,
        "defect_correction_sweeps": run.sweeps,
        "wall_time_s": run.wall_time_s,
        "stokes_number": spec.stokes_number,
        "reynolds_number": spec.reynolds_number,
        "numbers_note": "stokes_number = delta^2 omega/nu with omega the motion's fastest angular frequency "
                        "(0: steady walls); reynolds_number = V delta/nu with V the largest wall speed in the "
                        "frame of B (|U_A|, |Omega_a| a, |Omega_b| b); delta = b - a",
        "largest_eccentricity": {"eps": spec.eps_max, "kappa": spec.eps_max / spec.delta, "t": spec.t_eps_max},
        "snapshots": snapshots,
        "units": "SI: s, m, rad, rad/s; forces.csv's F_x, F_z (N) and T_a, T_b (N m, clockwise) over the "
                 "length, in the frame translating with B",
    }


def write_flow_outputs(folder: OutputFolder, spec: FlowSpec, run: FlowRun) -> dict:
    """Write forces.csv, the snapshots (VTU series, flow.pvd, flow.gif) and summary.json; commit them as one set.

    ``folder`` is an entered :class:`OutputFolder` (:func:`flow_folder`). Ctrl-C or SIGTERM while the
    snapshots are written (drawing the animation takes a while) leaves them out of the set, which
    then says "interrupted"; at any other moment they wait until the set is in place. Returns the summary.
    """
    from dynamics.app.cli import Terminated
    from lubrication.unsteady.snapshots import animate, write_vtu_series

    staging = folder.staging
    with held_signals():
        write_text(staging / "forces.csv", forces_csv(spec, run))
    taken = run.snapshots
    snapshots = {"count": len(taken), "times": [float(s["t"]) for s in taken], "files": [], "collection": None,
                 "animation": None, "frame": spec.frame}
    if taken:
        try:
            paths, pvd = write_vtu_series(taken, staging, STEM)
            snapshots.update(files=[p.name for p in paths], collection=pvd.name)
            if spec.animation == "gif":
                gif = animate(taken, staging / f"{STEM}.gif", frame=spec.frame, theta_b=[s["theta_b"] for s in taken],
                              omega_b=[s["omega_b"] for s in taken])
                snapshots["animation"] = gif.name
        except KeyboardInterrupt as err:  # SIGTERM too (the command line raises it as Ctrl-C)
            for path in staging.iterdir():
                if path.name != "forces.csv":
                    path.unlink()
            by = "SIGTERM" if isinstance(err, Terminated) else "SIGINT"
            run.status = "interrupted"
            run.reason = f"{run.reason}; interrupted by {by} while writing the snapshots, which are left out"
            snapshots.update(files=[], collection=None, animation=None, left_out="interrupted while written")
    info = _summary(spec, run, snapshots)
    with held_signals():  # the set is written whole: a signal meanwhile takes effect after
        write_json(staging / "summary.json", info)
        folder.commit()
    return info


