"""Cavitation in transients (:mod:`validation.cavitation_transient`): table, figure, paragraph and report.

:func:`run` is the group of ``snail validate``; ``python -m validation.reports.cavitation_transient
[--quick] [FOLDER]`` writes ``report.md`` and ``cavitation_transient.json`` (default
``docs/cavitation_transient``).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from numerics.files import write_json, write_text

from ..cavitation_transient import PRESSURE_DROP, SAMPLE_TIMES, TITLE, Run, compute, largest_gap_difference
from ..checks import Check, Finding

__all__ = ["figure", "main", "paragraph", "run", "table"]


def table(runs: list[Run]) -> str:
    """Markdown: 1 - kappa at :data:`SAMPLE_TIMES` for every run, and its late speed."""
    t_end = max(r.t_end for r in runs)
    times = [t for t in SAMPLE_TIMES if t <= t_end]
    lines = ["| slope (deg) | film | " + " | ".join(f"t = {t:g} s" for t in times)
             + " | mean speed over [T/2, T] (mm/s) | cavity at T (share of nodes) |",
             "|---|---|" + "---|" * (len(times) + 2)]
    for r in runs:
        c = r.trajectory.columns
        cavity = f"{c['cavitated_fraction'][-1]:.2f}" if "cavitated_fraction" in c else "-"
        lines.append(f"| {r.slope_deg:g} | {r.model} | " + " | ".join(f"{g:.4g}" for g in r.gap(times))
                     + f" | {r.late_speed * 1e3:.4g} | {cavity} |")
    return "\n".join(lines)


def figure(path, runs: list[Run]) -> None:
    """1 - kappa(t) of the three models on each slope, side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    slopes = sorted({r.slope_deg for r in runs})
    fig, axes = plt.subplots(1, len(slopes), figsize=(5.5 * len(slopes), 4.2), squeeze=False)
    styles = {"old": ("k", "-", "quasi-static JFO (feed)"), "feed": ("C0", "--", "transported JFO, feed"),
              "bubble": ("C3", "-", "transported JFO, bubble and ends")}
    for ax, slope in zip(axes[0], slopes):
        for r in runs:
            if r.slope_deg == slope and r.model in styles:
                colour, style, label = styles[r.model]
                c = r.trajectory.columns
                ax.loglog(c["t"][1:], c["one_minus_kappa"][1:], style, color=colour, lw=1.2, label=label)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("1 - kappa")
        ax.set_title(f"steel, 200 cSt, {slope:g} degrees, p_ref - p_cav = {PRESSURE_DROP:g} Pa", fontsize=9)
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(path, fig, dpi=120)
    plt.close(fig)


def run(outdir, quick: bool = False):
    """The transient cavitation study; returns (records, figure file names, a markdown paragraph).

    The figure is drawn whenever ``outdir`` is given, in the quick run too.
    """
    runs, records = compute(quick)
    figures = []
    if outdir is not None:
        figure(Path(outdir) / "cavitation_transient.png", runs)
        figures.append("cavitation_transient.png")
    text = paragraph(runs, records) + "\n\n" + table(runs)
    return records, figures, text


def paragraph(runs: list[Run], records: list) -> str:
    """The findings in words, with the numbers of this run."""
    slopes = sorted({r.slope_deg for r in runs})
    by = {(r.slope_deg, r.model): r for r in runs}
    lines = []
    for slope in slopes:
        old, feed = by[slope, "old"], by[slope, "feed"]
        largest, when = largest_gap_difference(feed, old)
        line = (f"On {slope:g} degrees the transported film's gap differs from the quasi-static one by up to "
                f"{100 * largest:.1f}% (at t = {when:.2g} s) and ends within "
                f"{abs(feed.gap(feed.t_end) / old.gap(old.t_end) - 1):.1e} of it")
        if (slope, "bubble") in by:
            bubble = by[slope, "bubble"]
            line += (f"; with the bubble the gap ends {bubble.gap(bubble.t_end) / feed.gap(feed.t_end):.2f} times "
                     f"the feed's and the device rolls {bubble.late_speed / feed.late_speed:.2f} times as fast")
        lines.append(line)
    worst = max(r.mass_residual for r in runs if r.model != "old")
    return ("The steel apparatus released at kappa = 0.5, phi = 0.5 (200 cSt, the film rupturing 3 Pa below 1 atm), "
            "with the quasi-static JFO force law and with the film's content in the state (mass-conserving in "
            "the transient). The transported film conserves its liquid to "
            f"{worst:.1e} of what crossed its faces. " + ". ".join(lines) + ". The quasi-static model is "
            "therefore right about where the release ends and off by a few percent on the way; the gauge changes "
            "the end state itself: measured from the end reservoirs, whose trapped bubble the film's cavities "
            "compress, the film no longer rectifies the squeeze, and the leak through the ends lowers its "
            "full-film forces as a finite length does.")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    quick = "--quick" in argv
    args = [a for a in argv if a != "--quick"]
    out = Path(args[0]) if args else Path("docs/cavitation_transient")
    start = time.perf_counter()
    records, figures, text = run(out, quick=quick)
    wall = time.perf_counter() - start
    checks = [r.as_dict() for r in records if isinstance(r, Check)]
    findings = [r.as_dict() for r in records if isinstance(r, Finding)]
    write_json(out / "cavitation_transient.json", {"title": TITLE, "quick": quick, "wall_time_s": wall,
                                                   "checks": checks, "findings": findings})
    rows = ["| check | measured | reference | tolerance | kind | passed |", "|---|---|---|---|---|---|"]
    rows += [f"| {c['name']} | {c['measured']:.3g} | {c['reference']:.3g} | {c['tolerance']:.3g} | {c['kind']} "
             f"| {c['passed']} |" for c in checks]
    found = ["| finding | value | note |", "|---|---|---|"]
    found += [f"| {f['name']} | {f['value']:.4g} | {f['note']} |" for f in findings]
    report = (f"# {TITLE}\n\n{text}\n\n" + "".join(f"![{name}]({name})\n\n" for name in figures)
              + "## Checks\n\n" + "\n".join(rows) + "\n\n## Findings\n\n" + "\n".join(found)
              + f"\n\nRun {'quick' if quick else 'full'} in {wall:.0f} s (`python -m validation.reports.cavitation_transient`).\n")
    write_text(out / "report.md", report)
    print(json.dumps({"passed": sum(c["passed"] for c in checks), "checks": len(checks), "wall_time_s": wall}))
    return 0 if all(c["passed"] for c in checks) else 1


if __name__ == "__main__":
    raise SystemExit(main())
