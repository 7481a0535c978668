"""What a run leaves on disk: trajectory.csv, summary.json and trajectory.png, each written whole."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from dynamics.app.figures import trajectory_figure
from dynamics.app.folder import OutputFolder
from dynamics.app.regime import classify
from dynamics.simulate import Trajectory
from lubrication.files import save_figure, write_json, write_text

__all__ = ["CSV_COLUMNS", "summary", "trajectory_csv", "write_outputs"]

CSV_COLUMNS = ("t", "t_tau", "x_b", "eps", "chi", "kappa", "one_minus_kappa", "phi", "omega_a", "omega_b")


def trajectory_csv(trajectory: Trajectory) -> str:
    """CSV text with a header row; SI units (or scaled ones for a dimensionless run).

    The contract's columns come first, then any a model adds (the contact phase and forces).
    """
    names = list(CSV_COLUMNS) + [k for k in trajectory.columns if k not in CSV_COLUMNS]
    data = np.column_stack([trajectory.columns[name] for name in names])
    buf = io.StringIO()
    np.savetxt(buf, data, delimiter=",", header=",".join(names), comments="", fmt="%.17g")
    return buf.getvalue()


def summary(trajectory: Trajectory, **extra) -> dict:
    """The run in numbers: model, forces, t_end, mean_speed, regime, wall time, steps, status."""
    c = trajectory.columns
    t_end = float(c["t"][-1])
    regime, evidence = classify(trajectory)
    out = {
        "model": trajectory.equations,
        "forces": trajectory.forces,
        "method": trajectory.method,
        "status": "completed" if trajectory.status == "completed" else trajectory.status,
        "reason": trajectory.reason,
        "stop_event": trajectory.event,
        "t_end": t_end,
        "mean_speed": float(c["x_b"][-1] / t_end) if t_end > 0 else 0.0,
        "regime": regime,
        "regime_evidence": evidence,
        "final": {name: float(c[name][-1]) for name in ("kappa", "one_minus_kappa", "phi", "omega_a",
                                                         "omega_b", "x_b")},
        "wall_time_s": trajectory.wall_time_s,
        "steps": trajectory.steps,
        "nfev": trajectory.nfev,
        "njev": trajectory.njev,
        "tau": trajectory.tau,
        "dimensionless": trajectory.dimensionless,
        "units": ("times and rates in tau, eps in delta, x_b in b" if trajectory.dimensionless
                  else "SI: s, m, rad, rad/s; mean_speed in m/s"),
        **trajectory.groups,
        **trajectory.info,
    }
    out.update(extra)
    return out


def write_outputs(folder: OutputFolder | str | Path, trajectory: Trajectory, *, resolved_scene: str = "",
                  **extra) -> dict:
    """Write trajectory.csv, summary.json, trajectory.png (and scene.resolved.toml) as one set.

    ``folder`` is an entered :class:`~dynamics.app.folder.OutputFolder` (the
    command line opens it before the run, so that a bad path is refused before
    anything is computed), or a path, which is opened here. The files go into
    its staging folder and are moved into place together; the summary is returned.
    """
    if not isinstance(folder, OutputFolder):
        with OutputFolder(folder) as opened:
            return write_outputs(opened, trajectory, resolved_scene=resolved_scene, **extra)
    staging = folder.staging
    info = summary(trajectory, **extra)
    write_text(staging / "trajectory.csv", trajectory_csv(trajectory))
    save_figure(staging / "trajectory.png", trajectory_figure(trajectory), dpi=110)
    if resolved_scene:
        write_text(staging / "scene.resolved.toml", resolved_scene)
    write_json(staging / "summary.json", info)
    folder.commit()
    return info
