"""How well ``snail fit`` recovers the roughness (:mod:`validation.fit_coverage`): figure and page.

Run ``python -m validation.reports.fit_coverage`` to write ``docs/fit_coverage.md`` and its figure from the
stored numbers (``docs/fit_coverage/fit_coverage.json``, written by ``python -m validation.fit_coverage``);
nothing is run again.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..fit_coverage import RESULTS, checks_of, findings, fitted_records
from .stored import checks_table, rewrite

__all__ = ["figures", "markdown", "write_outputs"]

PAGE = RESULTS.parents[1] / "fit_coverage.md"
ESTIMATES = RESULTS.with_name("estimates.png")
_TITLES = {"contact.roughness_amplitude": ("amplitude (rms of sigma over its mean)", 1.0),
           "contact.roughness_correlation": ("correlation length (mm)", 1e3),
           "contact.friction_angle": ("friction angle (deg)", math.degrees(1.0))}


def figures(result: dict) -> list[Path]:
    """Each parameter's estimates and 90 % intervals against the truth of each record."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

    from numerics.files import save_figure

    parameters = result["parameters"]
    fig, axes = plt.subplots(1, len(parameters), figsize=(4.2 * len(parameters), 4.0), layout="constrained")
    for ax, p in zip(np.atleast_1d(axes), parameters):
        title, scale = _TITLES.get(p["key"], (p["key"], 1.0))
        truth, estimate, interval, inside = fitted_records(p)
        truth, estimate, interval = scale * truth, scale * estimate, scale * interval
        for mask, color, label in ((inside, "C0", "interval contains the truth"), (~inside, "C3", "it does not")):
            ax.errorbar(truth[mask], estimate[mask], yerr=[estimate[mask] - interval[mask, 0],
                                                          interval[mask, 1] - estimate[mask]],
                        fmt="o", ms=3, color=color, elinewidth=0.8, label=label)
        bounds = [scale * p["low"], scale * p["high"]]
        ax.plot(bounds, bounds, color="0.5", lw=0.8)
        if p["log"]:
            ax.set_xscale("log")
            ax.set_yscale("log")
            for axis in (ax.xaxis, ax.yaxis):  # plain numbers at 1, 2, 5 of each decade
                axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
                axis.set_major_formatter(FormatStrFormatter("%g"))
                axis.set_minor_formatter(NullFormatter())
        ax.set_xlabel(f"truth: {title}")
        ax.set_ylabel("estimate and 90 % interval")
        ax.legend(fontsize=8, loc="upper left")
    return [save_figure(ESTIMATES, fig)]


def markdown(result: dict) -> str:
    keys = ", ".join(f"`{p['key']}`" for p in result["parameters"])
    lines = ["# How well the roughness is recovered", "",
             f"Records made by the model itself, fitted by `snail fit`'s method with its defaults: {result['records']} "
             f"descents of 60 s of the device of Table 3 (steel, 500 cSt, 4 degrees, the full equations with the "
             "exact Stokes forces, surfaces that turn with both cylinders), sampled at "
             f"{result['rate_hz']:g} Hz as a camera would, each with its unknowns ({keys}) drawn from the priors "
             "of the scene's `[fit]` section below and surfaces of its own; each fitted against one reference table "
             f"of {result['draws']} runs ({result['table_size']} usable), keeping the nearest "
             f"{result['accept']:.0%} ({result['accepted']} runs). Every number is in "
             "`fit_coverage/fit_coverage.json`, written by `python -m validation.fit_coverage` "
             f"({result['wall_time_s'] / 60.0:.1f} min on 2 worker processes); this page by "
             "`python -m validation.reports.fit_coverage`.", "",
             "```toml", result["scene"].rstrip(), "```", "",
             "![Estimates against the truth](fit_coverage/estimates.png)", ""]
    lines += [f"* {f['name']}: {f['text']}." for f in findings(result)]
    lines += ["", "## Checks", "", *checks_table(checks_of(result))]
    return "\n".join(lines) + "\n"


def write_outputs(result: dict) -> list[Path]:
    """Write the page and the figure (the numbers are already stored)."""
    from numerics.files import write_text

    return [write_text(PAGE, markdown(result)), *figures(result)]


if __name__ == "__main__":
    rewrite(RESULTS, write_outputs, checks_of)
