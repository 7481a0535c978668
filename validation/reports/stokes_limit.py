"""The Stokes-number study (:mod:`validation.stokes_limit`): its table, figure and page.

Run ``python -m validation.reports.stokes_limit`` to write ``docs/stokes_limit.md`` and
``docs/stokes_limit/stokes_limit.png`` from the stored numbers (``docs/stokes_limit/stokes_limit.json``,
written by ``python -m validation.stokes_limit``); nothing is run again.
"""

from __future__ import annotations

from pathlib import Path

from ..stokes_limit import RESULTS, checks_of
from .stored import checks_table, rewrite

__all__ = ["figure", "markdown", "write_outputs"]

PAGE = RESULTS.parents[1] / "stokes_limit.md"
#: The (frame_terms, fluid_spin) drawn and tabulated: (2.4) as printed with each closure, and the defaults.
SHOWN = (("paper", "none"), ("quasi-steady", "none"), ("quasi-steady", "couette"), ("quasi-steady", "eccentric"))
FIGURE = RESULTS.with_name("stokes_limit.png")


def figure(result: dict, path: str | Path) -> Path:
    """|x_b error| against St for each family, closure and fluid spin but the Couette one, the references' own
    error, and the fluid's spin share that (2.4) as printed leaves out."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for k, family in enumerate(result["families"]):
        st = [p["stokes_number"] for p in family["points"]]
        for (frame, spin), marker in zip((SHOWN[0], SHOWN[1], SHOWN[3]), ("o-", "s--", "^-.")):
            errors = [abs(p["models"][frame][spin]["x_b_relative"]) for p in family["points"]]
            ax.semilogx(st, [100.0 * e for e in errors], marker, color=f"C{k}", mfc="none" if frame == "paper" else
                        f"C{k}", lw=0.8, label=f"{family['title']}, {frame}, fluid spin {spin}")
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
    lines = ["| nu (m^2/s) | St | tau (s) | horizon (s) | max Re* | "
             + " | ".join(f"X_b error, {frame}, spin {spin}" for frame, spin in SHOWN)
             + " | reference's own error | NS wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in family["points"]:
        errors = " | ".join(f"{p['models'][frame][spin]['x_b_relative']:+.2e}" for frame, spin in SHOWN)
        lines.append(f"| {p['nu']:g} | {p['stokes_number']:.3g} | {p['tau_s']:.3g} | {p['horizon_s']:.3g} | "
                     f"{p['max_reduced_reynolds']:.3g} | {errors} | {p['reference_error']:.1e} | "
                     f"{p['navier_stokes_wall_s']:.0f} |")
    return lines


def _spread(family: dict, frame: str, spin: str) -> float:
    """Largest less smallest |x_b error| over the family's points, in percentage points."""
    errors = [100.0 * abs(p["models"][frame][spin]["x_b_relative"]) for p in family["points"]]
    return max(errors) - min(errors)


def _frames(family: dict) -> str:
    """Where the quasi-steady frame terms are closer than the paper's, and by how much, without the fluid's spin."""
    margins = [100.0 * (abs(p["models"]["paper"]["none"]["x_b_relative"])
                        - abs(p["models"]["quasi-steady"]["none"]["x_b_relative"])) for p in family["points"]]
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
             "model, with each choice of `frame_terms` and `fluid_spin`; each reference again at a quarter of its "
             "tolerance "
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

    def worst(family, spin):
        return 100 * max(abs(p["models"]["quasi-steady"][spin]["x_b_relative"]) for p in family["points"])

    def least(family, spin):
        return 100 * min(abs(p["models"]["quasi-steady"][spin]["x_b_relative"]) for p in family["points"])

    lines += ["## What the errors show", "",
              "* Without the fluid's spin, the error does not vanish as St goes to 0. At the smallest St the "
              f"runaway's x_b is {100 * abs(low['models']['paper']['none']['x_b_relative']):.1f}% ahead of the "
              "reference (paper's frame terms; "
              f"{100 * abs(low['models']['quasi-steady']['none']['x_b_relative']):.1f}% "
              f"quasi-steady) at Re* {low['max_reduced_reynolds']:.2g}, and the release's "
              f"{100 * abs(first['models']['paper']['none']['x_b_relative']):.1f}% at Re* "
              f"{first['max_reduced_reynolds']:.2g}. Equation (2.4), as the paper writes it, drops the fluid's own "
              "angular momentum about its centre of mass: a fluid turning with the cylinders has a moment of "
              "inertia m_f (a^2 + b^2)/2 that (2.4) as printed leaves out, and the Navier-Stokes run carries. Over the "
              "device's, with it, that is "
              f"{100 * runaway['spin_share']:.1f}% for the aluminium cylinder and {100 * release['spin_share']:.1f}% "
              "for the steel one: the runaway, which rolls, is ahead by just that share. The release rocks, and "
              "only part of its motion is rolling.",
              "* With the spin in (2.4) (`model.fluid_spin`, quasi-steady frame terms) most of the runaway's error "
              f"is gone: at most {worst(runaway, 'couette'):.1f}% at every St with the concentric Couette flow's spin, "
              f"{worst(runaway, 'eccentric'):.1f}% with the eccentric Stokes flow's (the default). The release's error "
              f"runs from {least(release, 'couette'):.1f}% to {worst(release, 'couette'):.1f}% with the Couette spin, "
              f"from {least(release, 'eccentric'):.1f}% to {worst(release, 'eccentric'):.1f}% with the eccentric one, "
              f"and from {least(release, 'none'):.1f}% to {worst(release, 'none'):.1f}% without.",
              "* On top of that the release's error grows with St, to "
              f"{100 * abs(last['models']['paper']['none']['x_b_relative']):.1f}% at St {last['stokes_number']:.2g} "
              f"(Re* {last['max_reduced_reynolds']:.2g}; paper's frame terms, no spin): the unsteady and inertial "
              "flow the quasi-steady forces leave out. Over the runaway's St its error stays within "
              f"{_spread(runaway, 'paper', 'none'):.1f} percentage points (paper's frame terms; "
              f"{_spread(runaway, 'quasi-steady', 'none'):.1f} quasi-steady; "
              f"{_spread(runaway, 'quasi-steady', 'eccentric'):.1f} with the default spin).",
              *[f"* {family['title']}, without the fluid's spin: {_frames(family)}" for family in result["families"]],
              "",
              "Each run states, in the `inertia` record of its summary.json (`unsteady`), the measured error at its "
              "Stokes number for its `frame_terms`, its `fluid_spin` and the kind of run it turned out to be "
              "(interpolated in log St between the points above, the nearest point's outside them; an error below "
              "the reference's own as that) and warns past the largest St measured; "
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
