"""The rough surfaces against the experiments (:mod:`validation.rough_experiments`): figures and page.

Run ``python -m validation.reports.rough_experiments`` to write ``docs/rough_experiments.md`` and its
figures from the stored numbers (``docs/rough_experiments/rough_experiments.json``, written by
``python -m validation.rough_experiments``); nothing is run again.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..rough_experiments import RESULTS, checks_of, findings
from .stored import checks_table, rewrite

__all__ = ["figures", "markdown", "write_outputs"]

PAGE = RESULTS.parents[1] / "rough_experiments.md"
TRAJECTORIES = RESULTS.with_name("trajectories.png")
SPECTRUM = RESULTS.with_name("spectrum.png")
SLOPES = RESULTS.with_name("slopes.png")
_LABELS = {"smooth": "smooth walls", "uniform": "uniform kappa* (sigma = 50 um)", "rough": "rough surfaces, seed 0"}


def figures(result: dict) -> list[Path]:
    """The showcase runs, the spectrum against distance rolled, and the slopes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from numerics.files import save_figure

    fig, axes = plt.subplots(3, 1, figsize=(7.0, 7.5), sharex=True)
    for k, (label, run) in enumerate(result["showcase"].items()):
        s = run["series"]
        axes[0].plot(s["t"], [100.0 * x for x in s["x_b"]], color=f"C{k}", label=_LABELS[label])
        axes[1].plot(s["t"], [p - math.pi for p in s["phi"]], color=f"C{k}", lw=0.8)
        axes[2].semilogy(s["t"], s["one_minus_kappa"], color=f"C{k}", lw=0.8)
    late = [p - math.pi for run in result["showcase"].values()
            for t, p in zip(run["series"]["t"], run["series"]["phi"]) if t > 5.0]
    axes[1].set_ylim(min(late) - 0.02, max(late) + 0.02)  # the release's first swing is off the scale
    axes[0].set_ylabel("X_b (cm)")
    axes[1].set_ylabel("phi - pi (rad)\n> 0: up the rear side")
    axes[2].set_ylabel("1 - kappa")
    axes[2].set_xlabel("t (s)")
    axes[0].legend(fontsize=7)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    save_figure(TRAJECTORIES, fig, dpi=110)
    plt.close(fig)

    spec = result["spectrum"]
    fig, axes = plt.subplots(2, 1, figsize=(7.0, 6.4), sharex=True)
    w = np.array(spec["wavelengths"]) * 100.0
    for ax, record, against in zip(axes, ("outer", "inner"),
                                   ("the outer cylinder's speed against the distance rolled",
                                    "the inner surface's speed past the contact against its arc")):
        mean, se = (np.array(spec[record][k], dtype=float) for k in ("mean", "se"))  # null: nan
        ax.loglog(w, mean, "k-", lw=1.0, label=f"mean of {result['seeds']} realisations")
        ax.fill_between(w, np.maximum(mean - 2 * se, 1e-2 * np.nanmin(mean)), mean + 2 * se, color="0.8",
                        label="2 standard errors")
        for turn, name, color in ((spec["turn_a"], "2 pi a", "C0"), (spec["turn_b"], "2 pi b", "C3")):
            ax.axvline(100.0 * turn, color=color, lw=1.0, label=f"{name} = {100.0 * turn:.2f} cm")
            for harmonic in (2, 3):
                ax.axvline(100.0 * turn / harmonic, color=color, lw=0.6, ls=":")
        ax.set_title(against, fontsize=8, loc="left")
        ax.set_ylabel("power density\nover a flat spectrum's")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[1].set_xlabel("wavelength (cm)")
    fig.tight_layout()
    save_figure(SPECTRUM, fig, dpi=110)
    plt.close(fig)

    fig, (left, right) = plt.subplots(1, 2, figsize=(9.0, 3.6))
    slopes = result["slopes"]
    sin = [math.sin(math.radians(s["slope_deg"])) for s in slopes]
    left.plot(sin, [1e3 * s["uniform"]["mean_speed_late"] for s in slopes], "o-", label="uniform kappa*")
    left.errorbar(sin, [1e3 * s["rough"]["mean_speed_late_mean"] for s in slopes],
                  yerr=[2e3 * (s["rough"]["mean_speed_late_se"] or 0.0) for s in slopes], fmt="s-",
                  label=f"rough, mean of {result['slope_seeds']}")
    left.set_xlabel("sin(alpha)")
    left.set_ylabel("late mean speed (mm/s)")
    left.legend(fontsize=7)
    right.plot([s["slope_deg"] for s in slopes], [s["uniform"]["locked_fraction_late"] for s in slopes], "o-",
               label="uniform kappa*")
    right.plot([s["slope_deg"] for s in slopes], [s["rough"]["locked_fraction_late_mean"] for s in slopes], "s-",
               label="rough")
    right.set_xlabel("slope (deg)")
    right.set_ylabel("share of the late half locked")
    right.legend(fontsize=7)
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    save_figure(SLOPES, fig, dpi=110)
    plt.close(fig)
    return [TRAJECTORIES, SPECTRUM, SLOPES]


def _stat(block: dict, name: str, scale: float = 1.0, digits: str = ".3g") -> str:
    mean, se = block[f"{name}_mean"], block[f"{name}_se"]
    text = format(scale * mean, digits)
    return text if se is None else f"{text} ± {format(scale * se, '.2g')}"


def _tilt_section(tilt: dict) -> list[str]:
    """A tilt of the inner cylinder's axis over the free flights of the ensemble's realisations."""
    import numpy as np

    runs = tilt["realisations"]
    gain = np.concatenate([run["gain"] for run in runs])
    duration = np.concatenate([run["duration"] for run in runs])
    growth = np.concatenate([run["frozen_growth"] for run in runs])
    return ["## A tilt between contacts", "",
            "Can the inner cylinder's axis leaning out of line make the motion irregular? In the hard contact the "
            "asperities touch along the whole generator, and a tilt would carry an end through them, so in contact "
            "the axis stays parallel: a tilt lives in the free flights between a lift-off and the next touch "
            "(`dynamics.tilt.tilt_in_flights`, the linear tilt equation of the force models' page with the exact "
            "Stokes forces, from unit tilts at the lift-off).",
            "",
            f"The {len(runs)} realisations above, run again with a row at every step, fly {gain.size} times "
            f"({gain.size / len(runs):.0f} a run), for {1e3 * np.median(duration):.0f} ms (median; the "
            f"longest {np.max(duration):.2f} s). Over a flight a unit tilt at the lift-off grows at most "
            f"{np.median(gain):.2f} times (median of the flights), {np.quantile(gain, 0.9):.2f} times in nine "
            f"flights of ten and {np.max(gain):.2f} times in the worst, although in {np.mean(growth <= 0.0):.0%} "
            "of the flights the tilt equation frozen at any of their instants has no growing mode: the growth is "
            "mostly transient, as a sum of decaying modes that are not orthogonal can give.",
            "",
            "So a tilt is amplified within a flight by a few times and then realigned by the touch, and does not "
            "accumulate from one flight to the next; and the film's force on the cylinder, the sum over sections "
            "displaced by plus and minus z gamma, changes only at second order in the tilt. A tilt does not by "
            "itself make the rocking irregular. What it can do is carry a misalignment of the device, amplified a "
            "few times, to the asperities at one end before the touch: then the contact is no longer along a line, "
            "which the plane equations (2.1)-(2.4) leave out."]


def markdown(result: dict) -> str:
    """The page."""
    show, ens, spec = result["showcase"], result["ensemble"], result["spectrum"]
    rolling = ens["rolling"]
    lines = [
        "# Rough surfaces against the experiments", "",
        "Section 4 of the paper reports what its smooth-wall theory cannot give: on shallow slopes the cylinders "
        "roll at a steady mean speed, rocking irregularly, the inner cylinder near its lowest point but dragged "
        "slightly up the rear side; the speeds steepen with the slope, and a transition from locked to sliding "
        "contact appears gradual, near 3 degrees (figures 5, 10, 11). This page runs the full equations "
        "(2.1)-(2.4) with the exact Stokes forces and surfaces whose minimum gap varies along both cylinders and "
        "turns with them (`dynamics.contact.rough_full`), for the device of Table 3: the scene below, 60 s from "
        "the release. Every number is in `rough_experiments/rough_experiments.json`, written by `python -m "
        f"validation.rough_experiments` ({result['wall_time_s']:.0f} s); this page by `python -m "
        "validation.reports.rough_experiments`.", "", "```toml", result["scene"].rstrip(), "```", "",
        "![Smooth, uniform and rough runs](rough_experiments/trajectories.png)", "",
        "## (a), (b): a steady mean speed, irregular rocking", "",
        "| run | late mean speed (mm/s) | speed 4th quarter / 3rd | phi - pi (rad) | rocking, phi rms (rad) "
        "| locked share | contact switches per s |",
        "|---|---|---|---|---|---|---|"]
    for label, run in show.items():
        locked = "-" if run["locked_fraction_late"] is None else f"{run['locked_fraction_late']:.2f}"
        lines.append(f"| {_LABELS[label]} | {1e3 * run['mean_speed_late']:.3g} | {run['quarter_ratio']:.3f} | "
                     f"{run['phi_mean_late'] - math.pi:+.4f} | {run['phi_rms_late']:.2g} | {locked} | "
                     f"{run['switch_rate_late']:.2g} |")
    lines += ["", f"Over {result['seeds']} realisations of the surfaces (mean ± standard error), {ens['halted']} "
              f"came to rest (late mean speed below {1e3 * ens['halt_speed']:.2g} mm/s, a tenth of the uniform "
              f"kappa*'s): rough surfaces can hold the device on a shallow slope, as the paper reports for its "
              f"sandpapers. The {rolling['realisations']} that roll:", "",
              "| number | mean ± standard error | standard deviation |", "|---|---|---|"]
    for name, title, scale in (("mean_speed_late", "late mean speed (mm/s)", 1e3),
                               ("quarter_ratio", "speed 4th quarter / 3rd", 1.0),
                               ("speed_spread_late", "speed spread (mm/s)", 1e3),
                               ("phi_rms_late", "rocking, phi rms (rad)", 1.0),
                               ("locked_fraction_late", "locked share", 1.0),
                               ("switch_rate_late", "contact switches per s", 1.0)):
        lines.append(f"| {title} | {_stat(rolling, name, scale)} | {format(scale * rolling[name + '_sd'], '.2g')} |")
    lines.append(f"| phi - pi (rad) | {rolling['phi_mean_late_mean'] - math.pi:+.4f} ± "
                 f"{rolling['phi_mean_late_se']:.1g} | {rolling['phi_mean_late_sd']:.2g} |")
    lines += ["", "## The spectrum against the distance rolled: 2 pi a and 2 pi b", "",
              "A surface fixed to a cylinder brings the same features back to the contact after each turn of that "
              "cylinder: against the distance rolled, the kicks recur with the wavelengths 2 pi a "
              f"({100 * spec['turn_a']:.2f} cm) and 2 pi b ({100 * spec['turn_b']:.2f} cm), and with their "
              "harmonics. A minimum gap that varies at random in time (the paper's 'slight stochastic variations "
              "in kappa*') would give a spectrum without them. The speed, resampled at equal distances rolled, of "
              f"{result['seeds']} realisations of {spec['t_end_s']:g} s on {spec['slope_deg']:g} degrees (where "
              "every realisation rolls, over many turns): its power within 10 % of each wavelength over the share "
              "a flat spectrum would give there. Below it, the same for the inner surface's speed past the contact "
              "against its own arc (the inner cylinder's turned angle relative to the line of centres, which a "
              "mark on it shows).", "",
              "![Spectrum against distance rolled](rough_experiments/spectrum.png)", ""]
    lines += [f"* {f['name']}: {f['text']}" for f in findings(result)]
    lines += ["", "The outer cylinder rolls on the plane without slipping, so its features recur at exactly 2 pi b "
              "of distance rolled: a sharp peak there, and at its half. The inner's recur at 2 pi a of distance "
              "rolled only while the surfaces are locked (a Omega_a = b Omega_b); sliding, the inner turns more "
              "slowly and the period stretches, which smears that peak. Against the inner cylinder's own arc they "
              "recur at 2 pi a again.", "",
              "The test for an experimenter: mark both cylinders, film a descent of many turns, and take the "
              "spectrum of the outer cylinder's speed against the distance rolled, and of the inner mark's "
              "speed against its own arc. A peak at 2 pi b in the first and at 2 pi a in the second say that the "
              "unsteadiness comes from the surfaces turning with the bodies (an inner cylinder of another radius "
              "moves the second with it); a minimum gap varying at random in time gives neither.", "",
              "## (c), (d): speeds against slope, and the friction transition", "",
              "![Speeds and locked share against slope](rough_experiments/slopes.png)", "",
              "| slope (deg) | uniform: speed (mm/s) | uniform: locked share | rough: speed (mm/s) "
              "| rough: locked share | rough: phi rms (rad) |", "|---|---|---|---|---|---|"]
    for s in result["slopes"]:
        r = s["rough"]
        lines.append(f"| {s['slope_deg']:g} | {1e3 * s['uniform']['mean_speed_late']:.3g} | "
                     f"{s['uniform']['locked_fraction_late']:.2f} | {_stat(r, 'mean_speed_late', 1e3)} | "
                     f"{_stat(r, 'locked_fraction_late', 1.0, '.2f')} | {_stat(r, 'phi_rms_late', 1.0, '.2g')} |")
    slopes = [s["slope_deg"] for s in result["slopes"]]
    rough_locked = [s["rough"]["locked_fraction_late_mean"] for s in result["slopes"]]
    uniform_locked = [s["uniform"]["locked_fraction_late"] for s in result["slopes"]]
    half = next((a + (0.5 - la) * (b - a) / (lb - la) for a, b, la, lb in
                 zip(slopes, slopes[1:], rough_locked, rough_locked[1:]) if la >= 0.5 > lb), None)
    lines += ["", ("The uniform kappa* stays locked on every slope here (its switch to sliding is abrupt, and with "
                   "this friction angle lies beyond them)" if min(uniform_locked) == 1.0 else
                   "The uniform kappa*'s locked share: " + ", ".join(f"{x:.2f}" for x in uniform_locked))
              + "; on rough surfaces the locked share falls steadily with the slope"
              + ("" if half is None else f", through one half near {half:.1f} degrees")
              + ", and the speeds steepen: a gradual transition, as the experiments suggest (the paper puts it "
                "near 3 degrees)."]
    lines += ["", *_tilt_section(result["tilt"])]
    sigma = result["sigma_effective"]
    lines += ["", "## What it means for the paper's kappa*", "",
              "The uniform minimum gap that rolls at the rolling realisations' mean speed, interpolated among "
              + ", ".join(f"{1e6 * x:g}" for x in result["sigmas"]) + " um: "
              + ("outside that range." if sigma is None else
                 f"{1e6 * sigma:.3g} um, where the surfaces' mean minimum gap is 50 um. A sigma fitted to measured "
                 "speeds with a uniform kappa* (the paper's Table 3) is an effective value, not the mean "
                 "roughness: rough contact holds the cylinders locked less, and loses energy in the kicks."), "",
              "## Checks", "", *checks_table(checks_of(result))]
    return "\n".join(lines) + "\n"


def write_outputs(result: dict) -> list[Path]:
    """Write the page and the figures (the numbers are already stored)."""
    from numerics.files import write_text

    return [write_text(PAGE, markdown(result)), *figures(result)]


if __name__ == "__main__":
    rewrite(RESULTS, write_outputs, checks_of)
