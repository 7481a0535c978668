"""The trajectory figure: what a physicist wants to see of a run, drawn without pyplot's state machine.

Panels: the path of the inner centre in the frame of the outer cylinder,
coloured by the logarithm of time (so a long run stays readable); the gap 1 - kappa on a log
axis (it spans decades as the cylinders approach, and a linear kappa sits at 1);
the angle of the line of centres from the downward vertical, where rocking
shows as a swing about the resting angle (or the turns, for a winding run);
the spins Omega_a and Omega_b; the distance rolled X_b. Time is in the scene's
units, with tau stated; the title names the model in the paper's terms and
says how the run ended.

Run as ``python -m dynamics.app.figures``, this module is the child of
:class:`dynamics.app.figure_process.FigureProcess`: it imports matplotlib and
builds and renders the panels that do not depend on the run (``_frame``)
while the run computes, then reads the trajectory from stdin, draws it into
them (``_plot``) and writes the PNG to stdout.
"""

from __future__ import annotations

import io
import math
import pickle
import sys
from types import SimpleNamespace

import numpy as np

__all__ = ["DPI", "figure_png", "trajectory_figure"]

#: Resolution of trajectory.png.
DPI = 110

_EQUATIONS = {"full": "full equations (2.1)-(2.4)", "reduced": "reduced equations (2.11)"}
_FORCES = {"closed-form": "lubrication forces (2.5)-(2.7)", "reynolds": "Reynolds-equation forces",
           "stokes": "exact Stokes forces", "stokes-exact": "exact Stokes forces"}


_SUPERSCRIPT = str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079")


def _decade(value, _position=None) -> str:
    """A log axis's label 10^k in plain text with superscript digits.

    Matplotlib's default writes it in mathtext, parsed label by label: a tenth to a sixth
    of the drawing time, as profiled.
    """
    if not value > 0.0:
        return ""
    exponent = round(math.log10(value))
    if not math.isclose(value, 10.0 ** exponent, rel_tol=1e-9):
        return f"{value:.3g}"
    return "10" + str(exponent).translate(_SUPERSCRIPT)


def _forces_label(name: str) -> str:
    """The forces in words: "stokes-exact/open-ends+inertia" is "exact Stokes forces, open ends, first inertial
    correction"; "reynolds/jfo" the Reynolds-equation forces with JFO cavitation."""
    base, _, inertia = name.partition("+")
    base, _, variant = base.partition("/")
    words = [_FORCES.get(base, base)]
    if variant:
        words.append("open ends" if variant == "open-ends" else f"{variant} cavitation")
    if inertia:
        words.append("first inertial correction")
    return ", ".join(words)


def _title(trajectory) -> str:
    equations = _EQUATIONS.get(trajectory.equations, trajectory.equations)
    forces = _forces_label(trajectory.forces)
    line1 = f"{equations}, {forces}"
    line2 = f"{trajectory.status}: {trajectory.message}"
    g = trajectory.groups
    names = {"s": "s", "upsilon": "Upsilon", "mu": "mu", "delta_over_a": "delta/a"}
    groups = ", ".join(f"{names[k]} = {g[k]:.3g}" for k in names if k in g)
    tau = "" if trajectory.dimensionless else f", tau = {trajectory.tau:.3g} s"
    return f"{line1}\n{line2}\n{groups}{tau}"


def _angle_panel(ax, t, phi):
    """Rocking about the bottom: phi - pi in degrees; winding: phi in turns."""
    turns = (phi.max() - phi.min()) / (2.0 * math.pi) if phi.size else 0.0
    if turns > 1.0:
        ax.plot(t, phi / (2.0 * math.pi), lw=0.8)
        ax.set_ylabel("phi (turns)")
        return
    # centre the swing on the downward vertical nearest to the run's end
    bottom = math.pi + 2.0 * math.pi * round((phi[-1] - math.pi) / (2.0 * math.pi)) if phi.size else math.pi
    ax.plot(t, np.degrees(phi - bottom), lw=0.8)
    ax.axhline(0.0, color="k", lw=0.4)
    ax.set_ylabel("phi - pi (deg)")


def _frame() -> SimpleNamespace:
    """The figure's panels and artists before any data: what does not depend on the run.

    The child of :class:`~dynamics.app.figure_process.FigureProcess` builds this while the run computes. Made
    here rather than with the data, the colorbar and the legends (with their
    artists, empty) take 20 ms, a ninth, off the drawing that the run waits for.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.colors import LogNorm
    from matplotlib.figure import Figure
    from matplotlib.ticker import FuncFormatter

    # Fixed margins, not a layout engine: the labels are known, and constrained layout
    # would cost more than drawing the figure. At the PNG's resolution from the start, so
    # that rendering it reuses the renderer of any earlier rendering.
    fig = Figure(figsize=(10.5, 7.0), dpi=DPI)
    grid = fig.add_gridspec(4, 2, width_ratios=(1.0, 1.35), left=0.075, right=0.985, bottom=0.075,
                            top=0.865, wspace=0.2, hspace=0.12)
    ax_path = fig.add_subplot(grid[:, 0])
    circle = np.linspace(0.0, 2.0 * math.pi, 400)
    ax_path.plot(np.sin(circle), np.cos(circle), "k", lw=0.5)
    ax_path.set_xlim(-1.08, 1.08)
    ax_path.set_ylim(-1.08, 1.08)
    ax_path.set_aspect("equal")
    ax_path.set_xlabel("kappa sin(phi)  (down the slope)")
    ax_path.set_ylabel("kappa cos(phi)  (up)")
    ax_path.set_title("path of the inner centre A relative to B", fontsize=9)
    # the path, coloured by log time: the motion slows by decades as the gap closes
    path = LineCollection([], cmap="viridis", linewidths=0.9, norm=LogNorm(vmin=0.1, vmax=1.0))
    path.set_array(np.empty(0))
    ax_path.add_collection(path, autolim=False)
    start, = ax_path.plot([], [], "o", ms=4, color="C1", label="start")
    end, = ax_path.plot([], [], "s", ms=4, color="C3", label="end")
    ax_path.legend(fontsize=8, loc="upper right")
    bar = fig.colorbar(path, ax=ax_path, orientation="horizontal", fraction=0.05, pad=0.1)
    bar.minorticks_off()  # some fifty of them on a long run: a tenth of the drawing time
    bar.formatter = FuncFormatter(_decade)
    ax_gap = fig.add_subplot(grid[0, 1])
    ax_gap.set_yscale("log")
    ax_gap.yaxis.set_major_formatter(_decade)
    ax_gap.set_ylabel("1 - kappa")
    ax_phi = fig.add_subplot(grid[1, 1], sharex=ax_gap)
    ax_w = fig.add_subplot(grid[2, 1], sharex=ax_gap)
    omega_a, = ax_w.plot([], [], lw=0.8, label="Omega_a (inner)")
    omega_b, = ax_w.plot([], [], lw=0.8, label="Omega_b (outer)")
    ax_w.legend(fontsize=8)
    ax_x = fig.add_subplot(grid[3, 1], sharex=ax_gap)
    for ax in (ax_gap, ax_phi, ax_w):
        ax.tick_params(labelbottom=False)
    return SimpleNamespace(fig=fig, path=ax_path, gap=ax_gap, phi=ax_phi, spins=ax_w, x_b=ax_x, lines=path,
                           start=start, end=end, bar=bar, omega_a=omega_a, omega_b=omega_b)


def _plot(frame: SimpleNamespace, trajectory):
    """Draw ``trajectory`` into the panels of :func:`_frame`; returns the figure."""
    c = trajectory.columns
    dimless = trajectory.dimensionless
    t = c["t"]
    t_label = "t / tau" if dimless else "t (s)"
    rate_unit = "1/tau" if dimless else "rad/s"
    kappa, phi, gap = c["kappa"], c["phi"], c["one_minus_kappa"]

    x, z = kappa * np.sin(phi), kappa * np.cos(phi)
    points = np.column_stack([x, z]).reshape(-1, 1, 2)
    frame.lines.set_segments(np.concatenate([points[:-1], points[1:]], axis=1))
    t_end = float(t[-1]) if t.size else 0.0
    if not t_end > 0.0:  # a run that never left t = 0 (it failed at once): any positive scale
        t_end = 1.0
    t_low = max(t_end * 1e-4, float(t[1]) if t.size > 1 else t_end * 1e-4)
    frame.lines.set_array(np.clip(t[1:], t_low, None))
    frame.lines.set_clim(t_low, max(t_end, t_low * 10))
    if t.size:
        frame.start.set_data(x[:1], z[:1])
        frame.end.set_data(x[-1:], z[-1:])
    frame.bar.set_label(f"{t_label}, log scale")

    frame.gap.plot(t, np.maximum(gap, 1e-300), lw=0.8)
    _angle_panel(frame.phi, t, phi)
    frame.omega_a.set_data(t, c["omega_a"])
    frame.omega_b.set_data(t, c["omega_b"])
    frame.spins.relim()
    frame.spins.autoscale_view()
    frame.spins.set_ylabel(f"spin ({rate_unit})")
    frame.x_b.plot(t, c["x_b"], color="C3", lw=0.8)
    frame.x_b.set_ylabel("X_b / b" if dimless else "X_b (m)")
    frame.x_b.set_xlabel(t_label)
    frame.fig.suptitle(_title(trajectory), fontsize=9)
    return frame.fig


def trajectory_figure(trajectory):
    """A :class:`matplotlib.figure.Figure` of ``trajectory`` (no pyplot, no global state)."""
    return _plot(_frame(), trajectory)


def _png(fig) -> bytes:
    """``fig`` as the bytes of a PNG file.

    zlib's fastest level: 9% larger than its default, and 8% less drawing time.
    """
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI, pil_kwargs={"compress_level": 1})
    return buf.getvalue()


def figure_png(trajectory) -> bytes:
    """trajectory.png of ``trajectory``, as the bytes of the file."""
    return _png(trajectory_figure(trajectory))


if __name__ == "__main__":  # the child of dynamics.app.figure_process.FigureProcess
    import os

    from matplotlib.backends.backend_agg import FigureCanvasAgg

    # While the parent runs: the panels, rendered once at the figure's resolution, so that
    # the fonts are loaded and the renderer, with its cache of text sizes, is ready.
    frame = _frame()
    FigureCanvasAgg(frame.fig).draw()
    try:
        view = pickle.load(sys.stdin.buffer)
    except EOFError:  # the parent ended without a trajectory
        sys.exit(0)
    sys.stdout.buffer.write(_png(_plot(frame, view)))
    sys.stdout.flush()
    # The parent waits for this process to end: skip the interpreter's teardown of matplotlib, 0.1 s.
    os._exit(0)
