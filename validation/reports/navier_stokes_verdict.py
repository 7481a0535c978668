"""The Navier-Stokes verdict (:mod:`validation.navier_stokes_verdict`): its tables, figure and page.

Run ``python -m validation.reports.navier_stokes_verdict`` to write ``docs/navier_stokes.md`` and
``docs/navier_stokes/verdict.png`` from the stored numbers (``docs/navier_stokes/verdict.json``, written by
``python -m validation.navier_stokes_verdict``); nothing is run again.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..navier_stokes_verdict import (
    CLOSED,
    EXACT,
    FRAME_PAIR,
    MEASURES,
    RESULTS,
    RUNAWAYS,
    SPINS,
    checks_of,
    frame_verdict,
    ranking,
    reference_error,
    spin_verdict,
)
from .stored import rewrite

__all__ = ["figure", "markdown", "write_outputs"]

PAGE = RESULTS.parents[1] / "navier_stokes.md"
FIGURE = RESULTS.with_name("verdict.png")

_MEASURE_TITLES = {"x_b_relative": "relative error of X_b at the horizon",
                   "log10_gap_ratio": "log10 of 1 - kappa over the reference's at the horizon",
                   "max_phi_error": "largest absolute phi error over the horizon (rad)"}


def _number(x: float) -> str:
    return f"{x:+.2e}" if abs(x) < 1e-2 or abs(x) >= 1e3 else f"{x:+.3f}"


def figure(result: dict, path: str | Path) -> Path:
    """phi, 1 - kappa and X_b against time for every case: the reference and the ODE models."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    cases = result["cases"]
    fig, axes = plt.subplots(len(cases), 3, figsize=(11.0, 2.3 * len(cases)), squeeze=False)
    for row, case in zip(axes, cases):
        ref = case["navier_stokes"]["series"]
        for k, (label, model) in enumerate(case["models"].items()):
            s = model["series"]
            style = {"color": f"C{k}", "lw": 1.0, "ls": "--" if "inertia" in label else "-"}
            row[0].plot(s["t"], s["phi"], label=label, **style)
            row[1].semilogy(s["t"], s["one_minus_kappa"], **style)
            row[2].plot(s["t"], [1e3 * x for x in s["x_b"]], **style)
        for ax, name in zip(row, ("phi", "one_minus_kappa", "x_b")):
            values = ref[name]
            if name == "one_minus_kappa":
                ax.semilogy(ref["t"], values, "k", lw=2.0, alpha=0.5, label="Navier-Stokes")
            else:
                ax.plot(ref["t"], [1e3 * v for v in values] if name == "x_b" else values, "k", lw=2.0, alpha=0.5,
                        label="Navier-Stokes")
            ax.grid(True, alpha=0.3)
        row[0].set_ylabel(f"({case['label']}) phi (rad)")
        row[1].set_ylabel("1 - kappa")
        row[2].set_ylabel("X_b (mm)")
        row[0].set_title(case["title"], fontsize=8, loc="left")
    for ax in axes[-1]:
        ax.set_xlabel("t (s)")
    axes[0][0].legend(fontsize=6, loc="best")
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)
    return Path(path)


def _conditions_table(result: dict) -> list[str]:
    lines = ["| case | device | slope (deg) | start kappa, phi (rad) | horizon (s) | s "
             "| Stokes number delta^2/(nu tau) | max Re* | ODE regime over 10 s | NS grid at the end | NS steps "
             "| NS wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in result["cases"]:
        ns = c["navier_stokes"]
        lines.append(f"| ({c['label']}) {c['title']} | {c['preset']} | {c['slope_deg']:g} | {c['kappa0']:g}, "
                     f"{c['phi0']:.3g} | {c['horizon_s']:g} | {c['s']:.3f} | {c['stokes_number']:.3g} | "
                     f"{c['max_reduced_reynolds']:.3g} | {c['ode_regime_over_10_s']} | {ns['n_theta']} x {ns['n_r']} | "
                     f"{ns['steps']} | {ns['wall_time_s']:.0f} |")
    return lines


def _reference_table(result: dict) -> list[str]:
    lines = ["| case | check | X_b relative | log10 gap ratio | max phi (rad) | wall (s) |",
             "|---|---|---|---|---|---|"]
    for c in result["cases"]:
        for name, check in c["reference_error"].items():
            what = {"tight_rtol": f"rtol {check['rtol']:g}", "fine_n_r": f"n_r = {check['n_r']}",
                    "fine_n_theta": f"n_theta = {check['n_theta']}"}[name]
            lines.append(f"| ({c['label']}) | {what} | {_number(check['x_b_relative'])} | "
                         f"{_number(check['log10_gap_ratio'])} | {check['max_phi_error']:.2e} | "
                         f"{check['wall_time_s']:.0f} |")
    lines += ["", "Energy balance of each reference, the largest absolute sum of kinetic, potential and dissipated "
              "energy over the largest work of gravity: " + ", ".join(
                  f"({c['label']}) {c['navier_stokes']['energy_drift_over_work']:.1e}" for c in result["cases"]) + "."]
    return lines


def _error_table(result: dict, measure: str) -> list[str]:
    models = result["models"]
    lines = ["| case | " + " | ".join(models) + " | closest |", "|---|" + "---|" * (len(models) + 1)]
    for c in result["cases"]:
        best = ranking(c, measure)[0][0]
        cells = [_number(c["models"][m][measure]) for m in models]
        lines.append(f"| ({c['label']}) | " + " | ".join(cells) + f" | {best} |")
    return lines


def _frame_table(result: dict) -> list[str]:
    lines = ["| case | measure | paper | quasi-steady | closer | by | reference error | decided |",
             "|---|---|---|---|---|---|---|---|"]
    for c in result["cases"]:
        for measure in MEASURES:
            v = frame_verdict(c, measure)
            paper, quasi = (c["models"][label][measure] for label in FRAME_PAIR)
            lines.append(f"| ({c['label']}) | {measure} | {_number(paper)} | {_number(quasi)} | "
                         f"{v['closer'].split(', ')[1]} | {v['margin']:.2e} | {v['reference_error']:.1e} | "
                         f"{'yes' if v['resolved'] else 'no: within the reference error'} |")
    return lines


def _spin_table(result: dict) -> list[str]:
    lines = ["| case | measure | " + " | ".join(SPINS) + " | closest | farthest | spread | reference error | "
             "decided |", "|---|---|" + "---|" * (len(SPINS) + 5)]
    for c in result["cases"]:
        for measure in MEASURES:
            v = spin_verdict(c, measure)
            cells = " | ".join(_number(c["models"][label][measure]) for label in SPINS.values())
            lines.append(f"| ({c['label']}) | {measure} | {cells} | {v['closest']} | {v['farthest']} | "
                         f"{v['spread']:.2e} | {reference_error(c, measure):.1e} | "
                         f"{'yes' if v['resolved'] else 'no: within the reference error'} |")
    return lines


def _spin_reading(result: dict) -> str:
    """How often each fluid spin is the closest and the farthest, over the decided comparisons."""
    verdicts = [spin_verdict(c, m) for c in result["cases"] for m in MEASURES]
    decided = [v for v in verdicts if v["resolved"]]
    counts = ", ".join(f"{spin} closest in {sum(v['closest'] == spin for v in decided)} and farthest in "
                       f"{sum(v['farthest'] == spin for v in decided)}" for spin in SPINS)
    return (f"Of the {len(verdicts)} comparisons, {len(decided)} are decided (the spread of the three exceeds the "
            f"reference's own error): {counts}.")


def _cost_table(result: dict) -> list[str]:
    import statistics

    lines = ["| model | median abs. X_b error | largest | median abs. log10 gap ratio | largest | median wall per case (s) |",
             "|---|---|---|---|---|---|"]
    for label in result["models"]:
        x = [abs(c["models"][label]["x_b_relative"]) for c in result["cases"]]
        gap = [abs(c["models"][label]["log10_gap_ratio"]) for c in result["cases"]]
        wall = [c["models"][label]["wall_time_s"] for c in result["cases"]]
        lines.append(f"| {label} | {statistics.median(x):.3f} | {max(x):.3f} | {statistics.median(gap):.3g} | "
                     f"{max(gap):.3g} | {statistics.median(wall):.3g} |")
    wall = [c["navier_stokes"]["wall_time_s"] for c in result["cases"]]
    lines.append(f"| Navier-Stokes (the reference) | its own error: at most "
                 f"{max(reference_error(c, 'x_b_relative') for c in result['cases']):.1e} | | at most "
                 f"{max(reference_error(c, 'log10_gap_ratio') for c in result['cases']):.1e} | | "
                 f"{statistics.median(wall):.3g} |")
    return lines


def markdown(result: dict) -> str:
    """The page: what was run, the reference's own error, the error tables, the verdict and the checks."""
    checks = checks_of(result)
    lines = [
        "# Navier-Stokes against the closures of the ODE models", "",
        "The ODE models close the fluid's effect on the cylinders with quasi-steady forces and a treatment of the "
        "fluid turning with the line of centres (`frame_terms`: \"paper\" puts m_eff on the centripetal and Coriolis "
        "terms as (2.1)-(2.2) print them, \"quasi-steady\" m'_a), optionally with the first inertial correction of "
        "the relative flow (`inertia = \"first-order\"`). The coupled Navier-Stokes run "
        "(`simulate(..., equations=\"navier-stokes\")`: the plane flow of the gap and both cylinders' Newton laws, "
        "no closure) is the reference here. Every number on this page is in `navier_stokes/verdict.json`, written "
        "by `python -m validation.navier_stokes_verdict` (the runs) and read by "
        "`python -m validation.reports.navier_stokes_verdict` (this page and the figure).", "",
        "Each case starts at rest. Models: the full equations (2.1)-(2.4) with the exact 2-D Stokes forces "
        "(\"exact\"), frame terms \"paper\" and \"quasi-steady\", each also with the first-order inertial "
        "correction (\"exact+inertia\"), all without the fluid's own angular momentum in (2.4), as the paper "
        "writes it; with the quasi-steady frame terms and that angular momentum, of the concentric Couette flow "
        "(\"Couette spin\") or of the eccentric Stokes flow (\"eccentric spin\", `fluid_spin`'s default); the "
        "full equations with the closed forms (2.5)-(2.7); the reduced equations (2.11). ODE rtol "
        f"{result['ode_rtol']:g}, every run past the Reynolds guard (`on_invalid = \"warn\"`); the Navier-Stokes "
        "runs at the default 16 points across and rtol "
        f"{result['navier_stokes_rtol']:g}, the grid around following the gap, except on the runaways: their "
        "fast flow needs more points than the gap asks for (the default grid left 1.5e-3 of the work of gravity "
        "in the energy balance of the 10-degree runaway and changed its dissipation by 3.5%), and their "
        "references have a fixed grid around (the conditions' table gives it). The horizons are short: the "
        "runs' cost grows steeply once the gap falls below about 1e-3 (the default release took "
        f"{result['cases'][0]['navier_stokes']['wall_time_s']:.0f} s to 1 s here, and 11 minutes to 2 s in a "
        f"trial), and the whole study took {result['wall_time_s'] / 60:.0f} minutes.", "",
        "## Conditions", "", *_conditions_table(result), "",
        "Re* = max(|W_a| a, |W_b| b) delta^2/(nu a) of the reference's motion, W = Omega - phi'. The Stokes "
        "number measures the unsteady inertia that every quasi-steady model leaves out.", "",
        "## The reference's own error", "",
        f"Each reference run again at a quarter of its tolerance, with {result['fine_n_r']} points across, and "
        "with twice the points around that it ended with, fixed; compared on its rows with the same measures:", "",
        *_reference_table(result), "",
    ]
    for measure in MEASURES:
        lines += [f"## {_MEASURE_TITLES[measure].capitalize()}", "", *_error_table(result, measure), ""]
    lines += ["## Accuracy against cost along trajectories", "",
              "Each model's errors over the five cases against the wall time of its runs (the ODEs at rtol "
              f"{result['ode_rtol']:g}, one core, the median over the cases), beside the reference's own: what "
              "a trajectory of each model buys, measured against the first principles rather than against "
              "another quasi-steady model.", "", *_cost_table(result), ""]
    lines += ["## Frame terms: paper against quasi-steady", "",
              "With the exact forces and no inertial correction; \"by\" is the difference of the two |errors|, "
              "\"decided\" says whether it exceeds the reference's own error (the larger of its two checks).", "",
              *_frame_table(result), "",
              "## The fluid's spin in (2.4): none, Couette, eccentric", "",
              "With the exact forces, quasi-steady frame terms and no inertial correction; \"spread\" is the "
              "largest |error| of the three less the smallest. " + _spin_reading(result), "",
              *_spin_table(result), "", "![The cases against time](navier_stokes/verdict.png)", "",
              "## Verdict", "", *_reading(result), "", "Case by case:", "", *_verdict_paragraphs(result), "",
              "## Checks", "", "| check | measured | bound | passed |", "|---|---|---|---|"]
    lines += [f"| {c.name} | {c.measured:.3g} | {c.reference:g} | {'yes' if c.passed else 'NO'} |" for c in checks]
    return "\n".join(lines) + "\n"


def _reading(result: dict) -> list[str]:
    """The conclusions in words, with the numbers the checks judge."""
    cases = result["cases"]
    factors = [abs(c["models"][CLOSED]["log10_gap_ratio"])
               / min(abs(c["models"][m]["log10_gap_ratio"]) for m in EXACT) for c in cases]
    wins: dict[str, int] = {}
    for c in cases:
        for measure in MEASURES:
            label = ranking(c, measure)[0][0]
            wins[label] = wins.get(label, 0) + 1
    runaways = []
    for c in cases:
        if c["label"] in RUNAWAYS:
            paper, quasi = (c["models"][label]["log10_gap_ratio"] for label in FRAME_PAIR)
            runaways.append(f"({c['label']}) {quasi:+.3f} decades against the paper's {paper:+.3f}")
    inertia = []
    for c in cases:
        changes = [abs(c["models"][f"exact+inertia, {f}"]["x_b_relative"])
                   - abs(c["models"][f"exact, {f}"]["x_b_relative"]) for f in ("paper", "quasi-steady")]
        inertia.append(f"({c['label']}) {100 * changes[0]:+.2g} and {100 * changes[1]:+.2g} (reference error "
                       f"{100 * reference_error(c, 'x_b_relative'):.2g})")
    counted = ", ".join(f"{label} {n}" for label, n in sorted(wins.items(), key=lambda item: -item[1]))
    x_b = max(abs(c["models"][m]["x_b_relative"]) for c in cases for m in EXACT)
    verdicts = [frame_verdict(c, m) for c in cases for m in MEASURES]
    undecided = sum(not v["resolved"] for v in verdicts)
    return [
        f"* The forces matter more than any closure of the inertia: the closed forms (2.5)-(2.7) miss the gap at "
        f"the horizon {min(factors):.0f} to {max(factors):.0f} times more (in decades) than the best exact-force "
        f"model; the {len(EXACT)} exact-force models are within {100 * x_b:.1f}% of the reference in X_b in every case.",
        f"* Closest model over the {len(cases) * len(MEASURES)} (case, measure) pairs: {counted}.",
        "* Frame terms: on the aluminium runaways the quasi-steady ones are decisively closer in the gap: "
        + "; ".join(runaways) + ". Elsewhere they differ by less, in either direction, measure by measure "
        f"(table above); {undecided} of the {len(verdicts)} comparisons are within the reference's own error.",
        "* No ODE model follows the line of centres' turning in the runaways: the closest one's phi drifts from "
        "the reference's by " + "; ".join(
            f"({c['label']}) {ranking(c, 'max_phi_error')[0][1]:.2g} rad ({ranking(c, 'max_phi_error')[0][0]}) in "
            f"{c['navier_stokes']['series']['phi'][-1] / (2 * math.pi):.1f} turns" for c in cases
            if c["label"] in RUNAWAYS) + ".",
        "* The first-order inertial correction brings X_b decidedly closer (by more than the reference's error) in "
        "no case; the change of the absolute X_b error it makes, in percentage points (frame terms paper and "
        "quasi-steady): "
        + "; ".join(inertia) + ".",
    ]


def _verdict_paragraphs(result: dict) -> list[str]:
    """Per case, the closest model in each measure with its error, and the frame-term verdict."""
    out = []
    for c in result["cases"]:
        best = {m: ranking(c, m)[0] for m in MEASURES}
        worst = {m: ranking(c, m)[-1] for m in MEASURES}
        frame = [frame_verdict(c, m) for m in MEASURES]
        decided = [f"{m} ({v['closer'].split(', ')[1]} by {v['margin']:.2g})" for m, v in zip(MEASURES, frame)
                   if v["resolved"]]
        out.append(
            f"* ({c['label']}) {c['title']}, {c['horizon_s']:g} s, Stokes number {c['stokes_number']:.2g}, max Re* "
            f"{c['max_reduced_reynolds']:.2g}: closest in X_b {best['x_b_relative'][0]} "
            f"({_number(best['x_b_relative'][1])}), in the gap {best['log10_gap_ratio'][0]} "
            f"({_number(best['log10_gap_ratio'][1])} decades), in phi {best['max_phi_error'][0]} "
            f"({best['max_phi_error'][1]:.2g} rad); farthest in phi {worst['max_phi_error'][0]} "
            f"({worst['max_phi_error'][1]:.2g} rad). Frame terms decided in "
            + (", ".join(decided) if decided else "no measure (their difference is within the reference's error)")
            + ".")
    return out


def write_outputs(result: dict) -> list[Path]:
    """Write the page and the figure (the numbers are already stored)."""
    from numerics.files import write_text

    return [write_text(PAGE, markdown(result)), figure(result, FIGURE)]


if __name__ == "__main__":
    rewrite(RESULTS, write_outputs, checks_of)
