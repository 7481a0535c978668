"""The Stokes-number study (:mod:`validation.stokes_limit`): its table, figure and page.

Run ``python -m validation.reports.stokes_limit`` to write ``docs/stokes_limit.md`` and
``docs/stokes_limit/stokes_limit.png`` from the stored numbers (``docs/stokes_limit/stokes_limit.json``,
written by ``python -m validation.stokes_limit``); nothing is run again.
"""

from __future__ import annotations

from pathlib import Path

from ..stokes_limit import FRAME_TERMS, RESULTS, checks_of
from .stored import checks_table, rewrite

__all__ = ["figure", "markdown", "write_outputs"]

PAGE = RESULTS.parents[1] / "stokes_limit.md"
FIGURE = RESULTS.with_name("stokes_limit.png")


def figure(result: dict, path: str | Path) -> Path:
    """|x_b error| against St for each family and closure, the references' own error, and the fluid's spin
    share that (2.4) leaves out."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for k, family in enumerate(result["families"]):
        st = [p["stokes_number"] for p in family["points"]]
        for frame, marker in zip(FRAME_TERMS, ("o-", "s--")):
            errors = [abs(p["models"][frame]["x_b_relative"]) for p in family["points"]]
            ax.semilogx(st, [100.0 * e for e in errors], marker, color=f"C{k}", mfc="none" if frame == "paper" else
                        f"C{k}", lw=0.8, label=f"{family['title']}, {frame}")
        ax.axhline(100.0 * family["spin_share"], color=f"C{k}", lw=0.8, ls=":",
                   label=f"{family['preset']}: the fluid's spin share, m_f (a^2 + b^2)/2 of the device's")
        ax.semilogx(st, [100.0 * p["reference_error"] for p in family["points"]], "x", color=f"C{k}", alpha=0.6,
                    label=f"{family['title']}: the reference's own error")
    ax.set_xlabel("Stokes number delta^2 / (nu tau)")
    ax.set_ylabel("|relative error of X_b| at the horizon (%)")
    ax.set_ylim(bottom=0.0)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)
    return Path(path)


def _points_table(family: dict) -> list[str]:
    lines = ["| nu (m^2/s) | St | tau (s) | horizon (s) | max Re* | X_b error, paper | X_b error, quasi-steady "
             "| X_b error, quasi-steady, with the Couette spin | reference's own error | NS wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for p in family["points"]:
        paper, quasi = (p["models"][frame]["x_b_relative"] for frame in FRAME_TERMS)
        lines.append(f"| {p['nu']:g} | {p['stokes_number']:.3g} | {p['tau_s']:.3g} | {p['horizon_s']:.3g} | "
                     f"{p['max_reduced_reynolds']:.3g} | {paper:+.2e} | {quasi:+.2e} | "
                     f"{p['with_spin']['x_b_relative']:+.2e} | {p['reference_error']:.1e} | "
                     f"{p['navier_stokes_wall_s']:.0f} |")
    return lines


def _spread(family: dict, frame: str) -> float:
    """Largest less smallest |x_b error| over the family's points, in percentage points."""
    errors = [100.0 * abs(p["models"][frame]["x_b_relative"]) for p in family["points"]]
    return max(errors) - min(errors)


def _frames(family: dict) -> str:
    """Where the quasi-steady frame terms are closer than the paper's, and by how much."""
    margins = [100.0 * (abs(p["models"]["paper"]["x_b_relative"]) - abs(p["models"]["quasi-steady"]["x_b_relative"]))
               for p in family["points"]]
    closer = sum(m > 0 for m in margins)
    return (f"the quasi-steady frame terms are closer than the paper's at {closer} of {len(margins)} Stokes numbers; "
            f"|paper's error| less |quasi-steady's| runs from {min(margins):+.2f} to {max(margins):+.2f} percentage "
            "points.")


def markdown(result: dict) -> str:
    """The page: what was run, the errors against St, what they show, the checks."""
    release, runaway = result["families"]
    lines = ["# The Stokes number: how far the quasi-steady models can be trusted", "",
             "Every ODE model here takes the flow in the gap as quasi-steady. The unsteady inertia it leaves out is "
             "measured by the Stokes number St = delta^2/(nu tau); for one device tau grows as nu, so St and Re* "
             "both fall as 1/nu^2. Each family below is one start on one slope run at several viscosities: the "
             "coupled Navier-Stokes run is the reference, the full equations with the exact 2-D Stokes forces the "
             "model, with each choice of `frame_terms`; each reference again at a quarter of its tolerance "
             f"({result['tight_rtol']:g}) gives its own error. Every number is in `stokes_limit/stokes_limit.json`, "
             "written by `python -m validation.stokes_limit` "
             f"({result['wall_time_s'] / 60:.0f} minutes); this page by `python -m validation.reports.stokes_limit`.",
             "", "![|X_b error| against the Stokes number](stokes_limit/stokes_limit.png)", ""]
    for family in result["families"]:
        grid = "the solver's grid from the gap" if family["n_theta"] is None else \
            f"{family['n_theta']} points around, fixed"
        lines += [f"## {family['title']}", "",
                  f"Start kappa = {family['kappa0']:g}, phi = {family['phi0']:g} rad, at rest; horizon "
                  + (f"{family['horizon_tau']:g} tau" if family["horizon_s"] is None else f"{family['horizon_s']:g} s")
                  + f"; the reference on {grid}.", "", *_points_table(family), ""]
    first, last = release["points"][0], release["points"][-1]
    low = runaway["points"][0]
    lines += ["## What the errors show", "",
              "* The error does not vanish as St goes to 0. At the smallest St the runaway's x_b is "
              f"{100 * abs(low['models']['paper']['x_b_relative']):.1f}% ahead of the reference (paper's frame terms; "
              f"{100 * abs(low['models']['quasi-steady']['x_b_relative']):.1f}% quasi-steady) at Re* "
              f"{low['max_reduced_reynolds']:.2g}, and the release's {100 * abs(first['models']['paper']['x_b_relative']):.1f}% "
              f"at Re* {first['max_reduced_reynolds']:.2g}. Equation (2.4), as the paper writes it, drops the fluid's "
              "own angular momentum about its centre of mass: a fluid turning with the cylinders has a moment of "
              "inertia m_f (a^2 + b^2)/2 that (2.4) as printed leaves out, and the Navier-Stokes run carries. Over the "
              "device's, with it, that is "
              f"{100 * runaway['spin_share']:.1f}% for the aluminium cylinder and {100 * release['spin_share']:.1f}% "
              "for the steel one: the runaway, which rolls, is ahead by just that share. The release rocks, and "
              "only part of its motion is rolling. `model.fluid_spin = \"couette\"` adds the spin of the concentric "
              "Couette flow to (2.4) (the tables' last error column): the runaway's error is then at most "
              f"{100 * max(abs(p['with_spin']['x_b_relative']) for p in runaway['points']):.1f}% at every St, and the "
              "release's "
              f"{100 * min(abs(p['with_spin']['x_b_relative']) for p in release['points']):.1f}% to "
              f"{100 * max(abs(p['with_spin']['x_b_relative']) for p in release['points']):.1f}%. The other "
              "columns and the estimate every run states are without it, the default.",
              f"* On top of that the release's error grows with St, to {100 * abs(last['models']['paper']['x_b_relative']):.1f}% "
              f"at St {last['stokes_number']:.2g} (Re* {last['max_reduced_reynolds']:.2g}): the unsteady and inertial "
              "flow the quasi-steady forces leave out. Over the runaway's St its error stays within "
              f"{_spread(runaway, 'paper'):.1f} percentage points (paper's frame terms; "
              f"{_spread(runaway, 'quasi-steady'):.1f} quasi-steady).",
              *[f"* {family['title']}: {_frames(family)}" for family in result["families"]], "",
              "Each run states, in the `inertia` record of its summary.json (`unsteady`), the measured error at its "
              "Stokes number for its `frame_terms` and the kind of run it turned out to be (interpolated in log St "
              "between the points above, the nearest point's outside them) and warns past the largest St measured; "
              "`run.max_stokes_number`, when set, refuses, or with `on_invalid = \"warn\"` flags, a device past it. "
              "The estimate "
              "is that of the full equations with the exact forces over the horizons above; a cheaper force model "
              "adds its own error, and a longer run can accumulate more.", "",
              "## Checks", "", *checks_table(checks_of(result))]
    return "\n".join(lines) + "\n"


def write_outputs(result: dict) -> list[Path]:
    """Write the page and the figure (the numbers are already stored)."""
    from numerics.files import write_text

    return [write_text(PAGE, markdown(result)), figure(result, FIGURE)]


if __name__ == "__main__":
    rewrite(RESULTS, write_outputs, checks_of)
