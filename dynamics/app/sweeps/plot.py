"""Reading a sweep's table as a map: regimes in the plane of two axes, and the edges of rocking and runaway.

Section 3 of the paper: a cylinder released on a slope s < 1 may rock towards
contact (3.9) or run away (3.11), depending on s, Upsilon and its initial
state; for s >= 1 no rocking equilibrium sin(phi) = -s exists (3.5). The map
shows which regime each point settled into (:mod:`dynamics.app.sweeps.point`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import numpy as np

from dynamics.app.sweeps.spec import Sweep
from dynamics.app.sweeps.store import read_rows

__all__ = ["plot_regime_map", "save_regime_map", "slope_limits"]

def slope_limits(rows: Iterable[Mapping[str, str]], slope: str = "groups.s") -> dict[str, float]:
    """Where runaway starts and rocking ends along the slope axis.

    Returns
    -------
    dict
        ``lowest_runaway_s``: the smallest s with a runaway (below it runaway did
        not occur); ``highest_rocking_s``: the largest s that rocked or sedimented
        (above it rocking did not occur); ``nan`` where the regime never occurred.
    """
    runaway, rocking = [], []
    for row in rows:
        if row["regime"] == "runaway":
            runaway.append(float(row[slope]))
        elif row["regime"] in _ROCKING:
            rocking.append(float(row[slope]))
    return {"lowest_runaway_s": min(runaway, default=math.nan),
            "highest_rocking_s": max(rocking, default=math.nan)}


# The inner cylinder sinks to the wall in both; rocking swings on the way.
_ROCKING = ("rocking", "sedimenting")
# Colours of the regimes, and of cells where the regime depends on the axes not shown.
_COLOURS = {"rocking": "#4c72b0", "sedimenting": "#8fb0e0", "runaway": "#dd5a4a", "locked rolling": "#55a868",
            "sliding rolling": "#a0d080", "steady rolling": "#2a9d8f", "transient": "#c8c8c8", "failed": "#222222",
            "mixed": "#f0b050"}
_LABELS = {"mixed": "mixed: depends on the pooled axes"}


def plot_regime_map(rows: str | os.PathLike | Sequence[Mapping[str, str]], x: str, y: str, *,
                    where: Mapping[str, float] | None = None, log_x: bool = False, log_y: bool = False,
                    title: str = ""):
    """A regime map in the plane of axes ``x`` and ``y``, with the edges of rocking and of runaway.

    Parameters
    ----------
    rows : path-like or sequence of mappings
        ``sweep.csv`` or its rows (:func:`read_rows`).
    x, y : str
        Axis keys, e.g. ``"groups.s"`` and ``"initial.kappa"``.
    where : mapping, optional
        Fixed values of other axes; rows are kept whose value is the nearest
        value present. The remaining axes are pooled: a cell whose points do not
        share one regime is "mixed" (the regime depends on the pooled axes); a
        cell that only rocks and sediments counts as rocking.
    log_x, log_y : bool
        Logarithmic axes, e.g. for Upsilon.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Cells coloured by regime. Two black lines run half-way between cells:
        dashed, the edge of the cells where some point ran away; solid, the edge
        of the cells where some point rocked (or sedimented). Without pooled axes
        they coincide on the rocking/runaway boundary; with pooled axes the band
        between them is where the initial state decides.
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    if isinstance(rows, (str, os.PathLike)):
        rows = read_rows(rows)
    for key, value in (where or {}).items():
        nearest = min({float(r[key]) for r in rows}, key=lambda v: abs(v - value))
        rows = [r for r in rows if float(r[key]) == nearest]
    xs = np.array(sorted({float(r[x]) for r in rows}))
    ys = np.array(sorted({float(r[y]) for r in rows}))
    cells: dict[tuple[int, int], list[str]] = {}
    for r in rows:
        cell = (int(np.searchsorted(ys, float(r[y]))), int(np.searchsorted(xs, float(r[x]))))
        cells.setdefault(cell, []).append(r["regime"])
    names = list(_COLOURS)
    code = np.full((ys.size, xs.size), np.nan)
    runaway = np.zeros((ys.size, xs.size))
    rocking = np.zeros((ys.size, xs.size))
    for (i, j), regimes in cells.items():
        kinds = set(regimes) - {"sedimenting"} if set(regimes) > {"sedimenting"} else set(regimes)
        code[i, j] = names.index(kinds.pop() if len(kinds) == 1 else "mixed")
        runaway[i, j] = "runaway" in regimes
        rocking[i, j] = any(r in _ROCKING for r in regimes)
    fig = Figure(figsize=(8.5, 5))
    ax = fig.subplots()
    cmap = ListedColormap(list(_COLOURS.values()))
    ax.pcolormesh(_edges(xs, log_x), _edges(ys, log_y), code, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5)
    handles = [Patch(color=_COLOURS[n], label=_LABELS.get(n, n)) for n in names if names.index(n) in code]
    if xs.size > 1 and ys.size > 1:
        for field, style, label in ((rocking, "-", "edge of rocking"), (runaway, "--", "edge of runaway")):
            if 0 < field.mean() < 1:
                ax.contour(xs, ys, field, levels=[0.5], colors="k", linestyles=style, linewidths=1.5)
                handles.append(Line2D([], [], color="k", linestyle=style, label=label))
    if log_x:
        ax.set_xscale("log")
    if log_y:
        ax.set_yscale("log")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fixed = ", ".join(f"{k} = {float(rows[0][k]):.3g}" for k in (where or {}))
    ax.set_title(title or f"regimes, {len(rows)} points" + (f" ({fixed})" if fixed else ""), fontsize=10)
    fig.tight_layout()
    return fig


def save_regime_map(sweep: Sweep, csv_path: str | os.PathLike) -> Path | None:
    """``regime_map.png`` beside ``csv_path``, in the plane of the first two numeric axes that vary.

    Returns
    -------
    Path or None
        The figure's path; None (nothing drawn) without two such axes.
    """
    from numerics.files import save_figure

    csv_path = Path(csv_path)
    rows = read_rows(csv_path)
    plane = [a for a in sweep.axes if len({r[a.key] for r in rows}) > 1]
    if len(plane) < 2 or not all(isinstance(v, (int, float)) for a in plane[:2] for v in a.values):
        return None
    x, y = plane[:2]
    fig = plot_regime_map(rows, x.key, y.key, log_x=x.log, log_y=y.log)
    return save_figure(csv_path.parent / "regime_map.png", fig, dpi=120)


def _edges(centres: np.ndarray, log: bool = False) -> np.ndarray:
    """Cell edges half-way between grid values (geometrically on a log axis)."""
    if centres.size == 1:
        return np.array([centres[0] * 0.9, centres[0] * 1.1]) if log else centres[0] + np.array([-0.5, 0.5])
    v = np.log(centres) if log else centres
    edges = np.concatenate([[1.5 * v[0] - 0.5 * v[1]], 0.5 * (v[1:] + v[:-1]), [1.5 * v[-1] - 0.5 * v[-2]]])
    return np.exp(edges) if log else edges
