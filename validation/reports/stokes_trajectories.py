"""Lubrication against Stokes along trajectories (:mod:`validation.stokes_trajectories`): table, figure, paragraph.

:func:`run` is the group of ``snail validate``.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..stokes_trajectories import OILS, T_END, Pair, checks_of, compute

__all__ = ["figure", "run", "table"]


def _seconds(t: float) -> str:
    return "not reached" if math.isnan(t) else f"{t:.3g}"


def table(results: list[Pair]) -> str:
    """Markdown table of the comparison, lubrication (L) against Stokes (S)."""
    header = ("| apparatus | nu (cSt) | slope (deg) | time compared (s) | mean speed L (mm/s) | speed ratio S/L "
              "| regime L | regime S | t at 1-kappa=1e-3, L (s) | same, S (s) | 1-kappa at end L | 1-kappa at end S "
              "| phi at end L | phi at end S |")
    lines = [header, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in results:
        lines.append(
            f"| {p.apparatus} | {p.nu * 1e6:g} | {p.slope_deg:g} | {p.t_common:.3g} "
            f"| {p.mean_speed('closed-form') * 1e3:.4g} | {p.speed_ratio:.3f} "
            f"| {p.regime('closed-form')} | {p.regime('stokes')} "
            f"| {_seconds(p.thin_gap_time('closed-form'))} | {_seconds(p.thin_gap_time('stokes'))} "
            f"| {p.final('closed-form', 'one_minus_kappa'):.3g} | {p.final('stokes', 'one_minus_kappa'):.3g} "
            f"| {p.final('closed-form', 'phi'):.3g} | {p.final('stokes', 'phi'):.3g} |")
    return "\n".join(lines)


def figure(path, results: list[Pair]) -> None:
    """Speed ratio Stokes / lubrication against slope, one line per apparatus and oil."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    groups = sorted({(p.apparatus, p.nu) for p in results})
    for k, (name, nu) in enumerate(groups):
        group = sorted((p for p in results if (p.apparatus, p.nu) == (name, nu)), key=lambda p: p.slope_deg)
        colour, style = f"C{OILS.index(nu) if nu in OILS else k}", "-" if name == "steel" else "--"
        ax.plot([p.slope_deg for p in group], [p.speed_ratio for p in group], style, color=colour,
                label=f"{name}, {nu * 1e6:g} cSt")
        # filled: both runs rock; open: at least one runs away
        for p in group:
            ax.plot(p.slope_deg, p.speed_ratio, "o" if name == "steel" else "s", color=colour, ms=5,
                    mfc=colour if p.both_rock else "none")
    ax.set_yscale("log")  # a regime change gives a ratio of tens
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("slope (degrees)")
    ax.set_ylabel("mean speed, Stokes / lubrication (2.5)-(2.7)")
    ax.set_title("delta/a = 0.406; filled: both rock, open: a runaway", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    save_figure(path, fig, dpi=120)
    plt.close(fig)


def _paragraph(results: list[Pair]) -> str:
    changed = [p for p in results if p.regime("closed-form") != p.regime("stokes")]
    rocking = [p for p in results if p.both_rock]
    lines = [(f"Full-model trajectories of the paper's apparatus (delta/a = 0.406) from kappa = 0.5, phi = 0.5 at "
             f"rest, with the lubrication closed forms (2.5)-(2.7) (L) and with the exact Stokes forces "
             f"(S), for {T_END:g} s or until a runaway's turn limit. The release's first swing passes the gap "
             f"Reynolds guard (quasi-steady Stokes forces are then an approximation, reported below); the runs go "
             f"on past it. The speed ratio is that of the mean speeds over the time both runs cover.")]
    if rocking:
        ratios = [p.speed_ratio for p in rocking]
        lines.append(f"Where both rock, Stokes forces change the mean speed by a factor {min(ratios):.2f} to "
                     f"{max(ratios):.2f} and leave the gap at the end wider, so the sinking to contact is slower.")
        faster = [p for p in rocking if p.speed_ratio >= 1.0]
        if faster:
            lines.append("The Stokes run is nonetheless the faster in " + "; ".join(
                f"{p.apparatus}, {p.nu * 1e6:g} cSt, {p.slope_deg:g} deg" for p in faster)
                + ", where the Stokes gap does not close to 1e-3 within the run (not checked).")
    if changed:
        lines.append("The regime changes in " + "; ".join(
            f"{p.apparatus}, {p.nu * 1e6:g} cSt, {p.slope_deg:g} deg ({p.regime('closed-form')} with L, "
            f"{p.regime('stokes')} with S)" for p in changed) + ".")
    else:
        lines.append("The regime is the same with both force models in every case.")
    return " ".join(lines) + "\n\n" + table(results)


def run(outdir, quick: bool = False):
    """The comparison; returns (checks, figure file names, a markdown paragraph).

    Parameters
    ----------
    outdir : path-like
        Where the figure is written (full mode only).
    quick : bool
        One apparatus, one oil and two slopes (:data:`QUICK`).

    Returns
    -------
    checks : list of Check
    figures : list of str
        File names in ``outdir``.
    paragraph : str
        Markdown text with the table.
    """
    results = compute(quick)
    figures = []
    if not quick:
        figure(Path(outdir) / "stokes_trajectories.png", results)
        figures.append("stokes_trajectories.png")
    return checks_of(results), figures, _paragraph(results)
