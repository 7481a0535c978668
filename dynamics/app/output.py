"""What a run leaves on disk: trajectory.csv, summary.json and trajectory.png, each written whole, and a
Navier-Stokes run's flow snapshots (flow_NNNN.vtu, flow.pvd, flow.gif) in the same set."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from dynamics.app.figures import figure_png
from dynamics.trajectory import Trajectory
from numerics.files import write_bytes, write_json, write_text
from numerics.folder import OUTPUT_NAMES, OutputFolder

__all__ = ["CSV_COLUMNS", "MAX_ROWS", "SNAPSHOT_STEM", "output_names", "summary", "thinning", "trajectory_csv",
           "write_outputs", "write_snapshots"]

CSV_COLUMNS = ("t", "t_tau", "x_b", "eps", "chi", "kappa", "one_minus_kappa", "phi", "omega_a", "omega_b")


#: Largest number of rows trajectory.csv holds by default (the scene's ``run.max_rows``); a longer
#: every-step output is thinned to every k-th integrator step (event rows and the last row always
#: kept), and summary.json says so. Rows at a requested output interval are never thinned: the scene
#: refuses an interval that would give more.
MAX_ROWS = 200_000


#: The stem of a Navier-Stokes run's snapshot files, as ``snail flow``'s: flow_0000.vtu, ..., flow.pvd, flow.gif.
SNAPSHOT_STEM = "flow"


def output_names() -> frozenset[str]:
    """Every file a run's set may hold: trajectory.csv, summary.json, trajectory.png, scene.resolved.toml and
    the flow snapshots of a Navier-Stokes run (:func:`lubrication.unsteady.snapshots.output_files`)."""
    from lubrication.unsteady.snapshots import output_files

    return OUTPUT_NAMES | output_files(SNAPSHOT_STEM)


def write_snapshots(folder: Path, snapshots: list[dict], animation: str = "none") -> dict:
    """Write a Navier-Stokes run's flow snapshots into ``folder`` and return their record for summary.json.

    The VTU series and its ParaView collection flow.pvd (:func:`lubrication.unsteady.snapshots.write_vtu_series`,
    the fields in the frame translating with B); with ``animation = "gif"`` also flow.gif, the vorticity and the
    streamlines in the frame of the outer cylinder (:func:`lubrication.unsteady.snapshots.animate`, from each
    snapshot's ``theta_b`` and ``omega_b``).
    """
    from lubrication.unsteady.snapshots import animate, write_vtu_series

    paths, pvd = write_vtu_series(snapshots, folder, SNAPSHOT_STEM)
    record = {"count": len(snapshots), "times": [float(s["t"]) for s in snapshots], "files": [p.name for p in paths],
              "collection": pvd.name, "animation": None, "frame": "outer"}
    if animation == "gif":
        gif = animate(snapshots, Path(folder) / f"{SNAPSHOT_STEM}.gif", frame="outer",
                      theta_b=[s["theta_b"] for s in snapshots], omega_b=[s["omega_b"] for s in snapshots])
        record["animation"] = gif.name
    return record


def thinning(trajectory: Trajectory, max_rows: int = MAX_ROWS) -> np.ndarray:
    """Indices of the rows to write: all of them, or every k-th step plus every event row and the last."""
    n = trajectory.t.size
    if n <= max_rows or not np.any(trajectory.rows == "step"):
        return np.arange(n)
    every = int(np.ceil(n / max_rows))
    marked = np.array(["event" in row or "end" in row or "start" in row for row in trajectory.rows])
    keep = (np.arange(n) % every == 0) | marked
    return np.nonzero(keep)[0]


def trajectory_csv(trajectory: Trajectory, rows: np.ndarray | None = None) -> str:
    """CSV text with a header row; SI units (or scaled ones for a dimensionless run).

    The contract's columns come first, then any a model adds (the contact phase and
    forces), then ``row``: what the row is ("step", "sample", "event:touch", "end", ...).
    ``rows`` selects rows (:func:`thinning`); all by default.
    """
    names = list(CSV_COLUMNS) + [k for k in trajectory.columns if k not in CSV_COLUMNS]
    rows = np.arange(trajectory.t.size) if rows is None else rows
    buf = io.StringIO()
    buf.write(",".join([*names, "row"]) + "\n")
    data = np.column_stack([trajectory.columns[name][rows] for name in names])
    for values, label in zip(data, trajectory.rows[rows]):
        buf.write(",".join(f"{x:.17g}" for x in values) + f",{label}\n")
    return buf.getvalue()


def summary(trajectory: Trajectory, **extra) -> dict:
    """The run in numbers: model, forces, t_end, mean_speed, regime, wall time, steps, status."""
    c = trajectory.columns
    t_end = float(c["t"][-1])
    out = {
        "model": trajectory.equations,
        "forces": trajectory.forces,
        "method": trajectory.method,
        "status": trajectory.status,
        "reason": trajectory.message,
        "success": trajectory.success,
        "stop_event": trajectory.event,
        "t_end": t_end,
        "mean_speed": trajectory.mean_speed,
        "late_mean_speed": trajectory.late_mean_speed,
        "regime": trajectory.regime,
        "regime_evidence": trajectory.evidence,
        "final": {name: float(c[name][-1]) for name in ("kappa", "one_minus_kappa", "phi", "omega_a",
                                                         "omega_b", "x_b")},
        "events": trajectory.events,
        "wall_time_s": trajectory.wall_time_s,
        "compile_time_s": trajectory.compile_time_s,
        "steps": trajectory.steps,
        "nfev": trajectory.nfev,
        "njev": trajectory.njev,
        "nlu": trajectory.nlu,
        "tau": trajectory.tau,
        "dimensionless": trajectory.dimensionless,
        "units": ("times and rates in tau, eps in delta, x_b in b" if trajectory.dimensionless
                  else "SI: s, m, rad, rad/s; mean_speed in m/s"),
        "mean_speed_note": "mean_speed is X_b/t from the release, the transient included; late_mean_speed is the "
                           "mean over the second half, where the regime is judged",
        **trajectory.groups,
        **{k: v for k, v in trajectory.info.items() if k != "snapshots"},  # fields: write_snapshots' files
    }
    out.update(extra)
    return _json_numbers(out)


def _json_numbers(value):
    """``value`` with every non-finite float (an overflowed estimate, say) as None: JSON has no inf or NaN."""
    if isinstance(value, dict):
        return {k: _json_numbers(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_numbers(v) for v in value]
    if isinstance(value, (float, np.floating)):
        return float(value) if np.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    return value


def write_outputs(folder: OutputFolder | str | Path, trajectory: Trajectory, *, resolved_scene: str = "",
                  plot: bool = True, max_rows: int = MAX_ROWS, draw=figure_png, animation: str = "none",
                  **extra) -> dict:
    """Write trajectory.csv, summary.json, trajectory.png (and scene.resolved.toml) as one set, with the flow
    snapshots a Navier-Stokes run took (:func:`write_snapshots`; ``animation = "gif"`` adds flow.gif).

    ``folder`` is an entered :class:`~numerics.folder.OutputFolder` (the
    command line opens it before the run, so that a bad path is refused before
    anything is computed), or a path, which is opened here. The files go into
    its staging folder and are moved into place together; the summary is returned.
    ``plot`` False leaves out the figure, which ``draw(trajectory)`` returns as
    PNG bytes (:func:`~dynamics.app.figures.figure_png`, or a
    :class:`~dynamics.app.figure_process.FigureProcess`'s ``png``); a run of more than
    ``max_rows`` steps is thinned in the CSV (:func:`thinning`).
    """
    if not isinstance(folder, OutputFolder):
        with OutputFolder(folder, output_names()) as opened:
            return write_outputs(opened, trajectory, resolved_scene=resolved_scene, plot=plot,
                                 max_rows=max_rows, draw=draw, animation=animation, **extra)
    staging = folder.staging
    rows = thinning(trajectory, max_rows)
    if rows.size < trajectory.t.size:
        extra["rows_thinned"] = {"written": int(rows.size), "steps": int(trajectory.t.size),
                                 "reason": f"more than {max_rows} rows: every "
                                           f"{int(np.ceil(trajectory.t.size / max_rows))}-th step written, "
                                           "with every event row"}
    if trajectory.info.get("snapshots"):
        extra["snapshots"] = write_snapshots(staging, trajectory.info["snapshots"], animation)
    info = summary(trajectory, **extra)
    write_text(staging / "trajectory.csv", trajectory_csv(trajectory, rows))
    if plot:
        write_bytes(staging / "trajectory.png", draw(trajectory))
    if resolved_scene:
        write_text(staging / "scene.resolved.toml", resolved_scene)
    write_json(staging / "summary.json", info)
    folder.commit()
    return info
