"""Trajectories with the finite length (:mod:`validation.finite_length_trajectories`): table, paragraph, figure.

:func:`run` is the group of ``snail validate``; ``python -m validation.reports.finite_length_trajectories
[FOLDER]`` writes ``trajectories.md``, ``trajectories.json`` and ``trajectories.png`` (default
``docs/finite_length``).
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

from numerics.files import write_json, write_text

from ..checks import Check, Finding, comparisons
from ..contact_checks import PSI_EXPERIMENT
from ..finite_length_trajectories import (
    BASES,
    LIMITS,
    SIGMA,
    T_SMOOTH,
    Case,
    compute,
    records_of,
    summary,
)
from ..stokes_trajectories import OILS

__all__ = ["figure", "main", "run", "to_markdown"]


def _pct(x: float) -> str:
    return f"{100.0 * (x - 1.0):+.2f} %"


def _smooth_regime(c: Case, base: str) -> str:
    run = c.smooth[base, "infinite"]
    if run.event == "runaway":
        return f"runaway at {float(run.t[-1]):.2g} s"
    return c.regime("smooth", base, "infinite")


def _rough_state(c: Case, base: str) -> str:
    if not c.settles(base, "infinite"):
        return c.regime("rough", base, "infinite")
    return f"{1e3 * c.final_speed(base, 'infinite'):.4g} ({c.phase(base, 'infinite')})"


def to_markdown(cases: list[Case]) -> str:
    """One row per case: each model's own regime or steady speed, and the changes with the ends open."""
    header = ("| apparatus | nu (cSt) | slope (deg) | smooth regime, L / S | smooth speed, open vs inf, L / S "
              "| smooth 1-kappa at end, open vs inf, L / S | smooth speed S / L (inf) "
              "| rough steady speed (mm/s), L / S | rough speed, open vs inf, L / S | rough speed S / L (inf) |")
    lines = [header, "|---|---|---|---|---|---|---|---|---|---|"]
    for c in cases:
        smooth = " / ".join(_pct(c.smooth_ratio(b)) for b in BASES)
        gap = " / ".join(_pct(c.gap_ratio(b)) for b in BASES)
        delta = f"{c.mean_speed('stokes-exact', 'infinite') / c.mean_speed('closed-form', 'infinite'):.3f}"
        rough = " / ".join(_pct(c.rough_ratio(b)) if c.all_settle(b) else "-" for b in BASES)
        rough_delta = (f"{c.final_speed('stokes-exact', 'infinite') / c.final_speed('closed-form', 'infinite'):.3f}"
                       if c.all_settle() else "-")
        lines.append(f"| {c.apparatus} | {c.nu * 1e6:g} | {c.slope_deg:g} "
                     f"| {' / '.join(_smooth_regime(c, b) for b in BASES)} | {smooth} | {gap} | {delta} "
                     f"| {' / '.join(_rough_state(c, b) for b in BASES)} | {rough} | {rough_delta} |")
    return "\n".join(lines)


def _paragraph(cases: list[Case], records: list) -> str:
    find = {r.name: r.value for r in records if isinstance(r, Finding)}

    def span(name: str, digits: int = 3) -> str:
        if f"{name}, smallest" not in find:
            return "(no case)"
        low, high = find[f"{name}, smallest"], find[f"{name}, largest"]
        return f"{low:.{digits}f} to {high:.{digits}f}" if low != high else f"{low:.{digits}f}"

    changed = sorted({c.label for c in cases for b in BASES for kind in ("smooth", "rough")
                      if c.regime(kind, b, "infinite") != c.regime(kind, b, "open")})
    runaway = "finite length, smooth, runaway, stokes-exact: mean speed open / infinite"
    guard = next(name for name in find if name.startswith("runs of "))

    def largest_change(names: list[str]) -> float:
        return max((abs(find[f"{n}, {end}"] - 1.0) for n in names for end in ("smallest", "largest")
                    if f"{n}, {end}" in find), default=math.nan)

    length_change = largest_change(["finite length, smooth, all rock, stokes-exact: mean speed open / infinite",
                                    "finite length, rough, stokes-exact: steady speed open / infinite"])
    gap_change = largest_change(["finite gap, smooth, all rock: mean speed exact Stokes / closed forms",
                                 "finite gap, rough: steady speed exact Stokes / closed forms"])
    text = (
        "Full-model runs of the paper's apparatus (L/a = 12.94, delta/a = 0.41) from kappa = 0.5, phi = 0.5 at "
        "rest, with the closed forms (L) and with the exact Stokes forces (S), each per unit length of an "
        "infinitely long annulus times L (inf) and times the finite-length factors of open ends (open). "
        f"Smooth walls, {T_SMOOTH:g} s: where every run rocks, opening the ends changes the mean speed by a factor "
        f"{span('finite length, smooth, all rock, stokes-exact: mean speed open / infinite')} with S and "
        f"{span('finite length, smooth, all rock, closed-form: mean speed open / infinite')} with L, and 1 - kappa "
        f"at the end by {span('finite length, smooth, all rock, stokes-exact: 1 - kappa at the end, open / infinite')}"
        " (S), against a factor "
        f"{span('finite gap, smooth, all rock: mean speed exact Stokes / closed forms')} in the speed between S "
        "and L. "
        + (f"In a runaway the ends change the mean speed by a factor {span(runaway)} (S). "
           if f"{runaway}, smallest" in find else "")
        + f"Rough walls (sigma = {SIGMA * 1e6:g} micrometres, psi = {PSI_EXPERIMENT:.4f}), steady rolling: the ends "
        f"raise the speed by a factor {span('finite length, rough, stokes-exact: steady speed open / infinite', 4)}"
        f" with S ({span('finite length, rough, closed-form: steady speed open / infinite', 4)} with L; locked, "
        "the factor is D_inf/D_open, a number of the geometry alone), against a factor "
        f"{span('finite gap, rough: steady speed exact Stokes / closed forms')} between S and L. "
        + f"{find[guard]:.0f} of {8 * len(cases)} runs passed the gap Reynolds guard Re* = {LIMITS.reynolds:g} in "
        f"the release's first swing and went on past it; the largest estimated inertial force error on the way "
        f"was {100 * find['largest estimated inertial force error of all runs']:.0f} %. "
        + ("The regime is the same with and without the ends in every case. " if not changed else
           "The regime changes with the ends in " + "; ".join(changed) + ". ")
        + f"Over these cases the finite gap changes the speeds by up to {100 * gap_change:.0f} %, the finite "
        f"length (with S) by up to {100 * length_change:.1f} %.")
    return text + "\n\n" + to_markdown(cases)


def figure(path, cases: list[Case]) -> None:
    """Speed ratio, ends open over infinite, against slope: smooth (mean) and rough (steady)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    groups = sorted({(c.apparatus, c.nu) for c in cases})
    for k, (name, nu) in enumerate(groups):
        group = sorted((c for c in cases if (c.apparatus, c.nu) == (name, nu)), key=lambda c: c.slope_deg)
        colour = f"C{OILS.index(nu) if nu in OILS else k}"
        style = "-" if name == "steel" else "--"
        for base, marker in zip(BASES, ("s", "o")):
            axes[0].plot([c.slope_deg for c in group], [c.smooth_ratio(base) for c in group], style + marker,
                         color=colour, mfc="none" if base == "closed-form" else colour, ms=4,
                         label=f"{name}, {nu * 1e6:g} cSt, {base}")
            steady = [c for c in group if c.all_settle(base)]
            axes[1].plot([c.slope_deg for c in steady], [c.rough_ratio(base) for c in steady], style + marker,
                         color=colour, mfc="none" if base == "closed-form" else colour, ms=4)
    for ax, title in zip(axes, ("smooth walls: mean speed over 10 s", "rough walls (sigma = 50 um): steady speed")):
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_xlabel("slope (degrees)")
        ax.set_title(title, fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("speed, ends open / infinite")
    axes[1].legend(*axes[0].get_legend_handles_labels(), fontsize=6, loc="lower left", ncol=2)
    fig.suptitle("Finite length (L/a = 12.94, open ends) in the full model; filled: exact Stokes, open: closed "
                 "forms", fontsize=9)
    fig.tight_layout()
    save_figure(path, fig, dpi=120)
    plt.close(fig)


def run(outdir, quick: bool = False):
    """The comparison; returns (records, figure file names, a markdown paragraph).

    Parameters
    ----------
    outdir : path-like
        Where the figure is written (full mode only).
    quick : bool
        One apparatus, one oil and one slope (:data:`QUICK`).
    """
    cases = compute(quick)
    records = records_of(cases)
    figures = []
    if not quick:
        figure(Path(outdir) / "finite_length_trajectories.png", cases)
        figures.append("finite_length_trajectories.png")
    return records, figures, _paragraph(cases, records)


def main(argv=None) -> int:
    out = Path(argv[0]) if argv else Path("docs/finite_length")
    start = time.perf_counter()
    cases = compute(False)
    records = records_of(cases)
    figure(out / "trajectories.png", cases)
    checks = comparisons(records)
    write_json(out / "trajectories.json", {**summary(cases), "wall_time_s": time.perf_counter() - start,
                                           "records": [r.as_dict() for r in records]})
    table = ["| record | value | reference | tolerance | passed |", "|---|---|---|---|---|"]
    table += [f"| {r.name} | {r.measured:.6g} | {r.reference:g} | {r.tolerance:g} | {'yes' if r.passed else 'NO'} |"
              if isinstance(r, Check) else f"| {r.name} | {r.value:.6g} | | | |" for r in records]
    text = ("# Trajectories with the finite length of the annulus\n\n" + _paragraph(cases, records) + "\n\n"
            + "\n".join(table) + f"\n\n![speed ratios](trajectories.png)\n\n{len(cases)} cases, "
            f"{8 * len(cases)} runs, {time.perf_counter() - start:.0f} s.\n")
    write_text(out / "trajectories.md", text)
    print(text)
    return 0 if all(c.passed for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
