"""The delta/a correction study (:mod:`validation.corrections`): its CSV, JSON, figure and paragraph.

:func:`run` is the group of ``snail validate`` and the work of ``snail corrections``.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

from numerics.files import write_json, write_text

from ..checks import Check
from ..corrections import (
    APPARATUS,
    EXACT_THIN,
    LABELS,
    RATIO_NAMES,
    REYNOLDS_CELLS,
    THIN,
    checks_of,
    exact_ratios,
    study,
)

__all__ = ["figure", "run", "to_csv", "to_json"]


def _apparatus_index(result: dict) -> int:
    return result["deltas"].index(APPARATUS["delta_over_a"])


def to_csv(result: dict) -> str:
    """One row per (model, delta/a, kappa): the five ratios to (2.5)-(2.7)."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(["model", "delta_over_a", "kappa", *RATIO_NAMES])
    for model in ("stokes", "reynolds"):
        label = "stokes" if model == "stokes" else "reynolds-eccentric"
        for i, d in enumerate(result["deltas"]):
            for j, kappa in enumerate(result["kappas"]):
                writer.writerow([label, f"{d:.10g}", f"{kappa:.10g}",
                                 *(f"{x:.10g}" for x in result[model][i, :, j])])
    return buf.getvalue()


def to_json(result: dict, checks: list[Check]) -> dict:
    """JSON-ready summary: ratios, c(kappa), the apparatus' headline numbers, table settings."""
    names = list(RATIO_NAMES)
    kappas = [float(k) for k in result["kappas"]]

    def per_name(arr):
        return {n: [float(x) for x in arr[k]] for k, n in enumerate(names)}

    i = _apparatus_index(result)
    headline = {}
    for model in ("stokes", "reynolds"):
        r = result[model][i]
        headline[model] = {n: {"min": float(r[k].min()), "max": float(r[k].max()),
                               "at_kappa": dict(zip((f"{k:.6g}" for k in kappas), map(float, r[k])))}
                           for k, n in enumerate(names)}
    b_over_a = 1.0 + APPARATUS["delta_over_a"]
    headline["stokes"]["contact_limit"] = dict(zip(names, (b_over_a**p for p in (1.5, 0.5, 0.5, 2.5, 1.5))))
    return {
        "names": names, "kappa": kappas,
        "delta_over_a": [float(d) for d in result["deltas"]],
        "stokes_ratio": {f"{d:.10g}": per_name(result["stokes"][i_])
                         for i_, d in enumerate(result["deltas"])},
        "reynolds_eccentric_ratio": {f"{d:.10g}": per_name(result["reynolds"][i_])
                                     for i_, d in enumerate(result["deltas"])},
        "thin_gap_coefficient": {"fit_delta_over_a": {"stokes": list(EXACT_THIN), "reynolds_eccentric": list(THIN)},
                                 "stokes": per_name(result["c_stokes"]),
                                 "reynolds_eccentric": per_name(result["c_reynolds"])},
        "apparatus": {**APPARATUS, "ratio": headline},
        "finite_element_check": result["fe"],
        "reynolds_cells": REYNOLDS_CELLS,
        "checks": [c.as_dict() for c in checks],
        "wall_time_s": result["wall_time_s"],
    }


def figure(result: dict, path) -> None:
    """Ratio to (2.5)-(2.7) against kappa for every coefficient and gap, and c(kappa)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fine = np.linspace(0.0, 0.999, 300)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for k, (ax, name) in enumerate(zip(axes.flat, RATIO_NAMES)):
        for i, d in enumerate(result["deltas"]):
            colour = f"C{i}"
            ax.plot(fine, exact_ratios(d, fine)[k], "-", color=colour, label=f"Stokes, {d:.3g}")
            ax.plot(result["kappas"], result["reynolds"][i, k], "--o", color=colour, ms=3,
                    label=f"Reynolds exact gap, {d:.3g}")
        ax.set_title(LABELS[name], fontsize=10)
        ax.set_xlabel("kappa")
        ax.set_ylabel("exact / lubrication")
        if name == "t_a_per_w_b":
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
    axes.flat[0].legend(fontsize=6, ncol=2, title="delta/a", title_fontsize=7)
    ax = axes.flat[5]
    for k, name in enumerate(RATIO_NAMES):
        ax.plot(result["kappas"], result["c_stokes"][k], "-o", color=f"C{k}", ms=3, label=f"Stokes, {name}")
        ax.plot(result["kappas"], result["c_reynolds"][k], "--s", color=f"C{k}", ms=3, label=f"Reynolds, {name}")
    ax.set_ylim(-0.5, 4.0)
    ax.set_title("c(kappa) in ratio = 1 + c delta/a + ...", fontsize=10)
    ax.set_xlabel("kappa")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    fig.suptitle("Full Stokes and Reynolds-on-the-exact-gap against the lubrication forms (2.5)-(2.7)")
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def _paragraph(result: dict) -> str:
    i = _apparatus_index(result)
    r = result["stokes"][i]
    parts = ", ".join(f"{LABELS[n].split(' (')[0]} x{r[k].min():.3f}..{r[k].max():.3f}"
                      for k, n in enumerate(RATIO_NAMES))
    c = result["c_stokes"]
    cs = ", ".join(f"{n} {c[k].min():.3f}..{c[k].max():.3f}" for k, n in enumerate(RATIO_NAMES))
    return (f"Full Stokes resistance against the lubrication forms (2.5)-(2.7). At the paper's apparatus "
            f"(delta/a = {APPARATUS['delta_over_a']:.4g}) the exact coefficients are the closed forms times: "
            f"{parts} (kappa from 0 to 0.99). The thin-gap correction ratio = 1 + c delta/a has, over "
            f"kappa in [0, 0.99], c = {cs}. The Reynolds equation on the exact gap carries only part of it.")


def run(outdir, quick: bool = False):
    """The study as a validation group: (checks, figure names, paragraph); writes CSV and JSON too."""
    outdir = Path(outdir)
    result = study(quick=quick)
    checks = checks_of(result)
    write_text(outdir / "corrections.csv", to_csv(result))
    write_json(outdir / "corrections.json", to_json(result, checks))
    figure(result, outdir / "corrections.png")
    return checks, ["corrections.png"], _paragraph(result)
