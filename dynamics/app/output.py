"""What a run leaves on disk: trajectory.csv, summary.json and trajectory.png, each written whole."""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np

from dynamics.app.regime import classify
from dynamics.simulate import Trajectory
from dynamics.app.folder import OutputFolder
from lubrication.files import save_figure, write_json, write_text

__all__ = ["CSV_COLUMNS", "summary", "trajectory_csv", "write_outputs", "plot_trajectory"]

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


def plot_trajectory(trajectory: Trajectory):
    """Panels like the paper's figure 2: path of A in the (kappa, phi) plane, kappa(t), phi(t),
    Omega_a and Omega_b, X_b(t)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = trajectory.columns
    t = c["t_tau"]
    rate = trajectory.tau  # rates shown in 1/tau
    fig = plt.figure(figsize=(10, 6.2))
    grid = fig.add_gridspec(3, 2, width_ratios=(1, 1.4))
    ax_path = fig.add_subplot(grid[:, 0])
    kappa, phi = c["kappa"], c["phi"]
    ax_path.plot(kappa * np.sin(phi), kappa * np.cos(phi), lw=0.8)
    ax_path.plot(kappa[0] * math.sin(phi[0]), kappa[0] * math.cos(phi[0]), "o", ms=4, label="start")
    circle = np.linspace(0, 2 * math.pi, 200)
    ax_path.plot(np.sin(circle), np.cos(circle), "k", lw=0.5)
    ax_path.set_aspect("equal")
    ax_path.set_xlabel("kappa sin(phi)")
    ax_path.set_ylabel("kappa cos(phi)  (up)")
    ax_path.set_title("path of the inner centre")
    ax_path.legend(fontsize=8, loc="lower right")
    ax_k = fig.add_subplot(grid[0, 1])
    ax_k.plot(t, kappa, lw=0.8)
    ax_k.set_ylabel("kappa")
    ax_p = fig.add_subplot(grid[1, 1], sharex=ax_k)
    ax_p.plot(t, phi, lw=0.8)
    ax_p.set_ylabel("phi (rad)")
    ax_w = fig.add_subplot(grid[2, 1], sharex=ax_k)
    ax_w.plot(t, c["omega_a"] * rate, lw=0.8, label="Omega_a")
    ax_w.plot(t, c["omega_b"] * rate, lw=0.8, label="Omega_b")
    ax_w.set_ylabel("rate x tau")
    ax_w.set_xlabel("t / tau")
    ax_w.legend(fontsize=8)
    ax_x = ax_k.twinx()
    ax_x.plot(t, c["x_b"], color="C3", lw=0.8)
    ax_x.set_ylabel("X_b" + (" / b" if trajectory.dimensionless else " (m)"), color="C3")
    title = f"{trajectory.equations} model, {trajectory.forces} forces: {trajectory.status}"
    if trajectory.groups:
        title += " (" + ", ".join(f"{k} = {v:.3g}" for k, v in trajectory.groups.items()) + ")"
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


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
    import matplotlib.pyplot as plt

    staging = folder.staging
    info = summary(trajectory, **extra)
    write_text(staging / "trajectory.csv", trajectory_csv(trajectory))
    fig = plot_trajectory(trajectory)
    save_figure(staging / "trajectory.png", fig, dpi=110)
    plt.close(fig)
    if resolved_scene:
        write_text(staging / "scene.resolved.toml", resolved_scene)
    write_json(staging / "summary.json", info)
    folder.commit()
    return info
