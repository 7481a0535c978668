r"""How much do trajectories change when the lubrication forms are replaced by full Stokes forces?

The paper's apparatus is not thin: delta/a = 0.406 for both the steel and the
aluminium device. The closed forms (2.5)-(2.7) are the leading order in delta/a;
the exact 2-D Stokes forces of :func:`lubrication.stokes_exact.stokes_exact_forces` hold at
any delta/a. Here the
full model (2.1)-(2.4) is integrated with both, from the same start (kappa = 0.5,
phi = 0.5, at rest), for the paper's oils (50, 200 and 500 cSt) and slopes, for
``T_END`` seconds or until a runaway reaches its turn limit. The release swings the
inner cylinder round the outer one, and the flow relative to the line of centres
passes the gap Reynolds limit Re* = 1 in that first swing: the runs go on past it
(``on_invalid = "warn"``), since the question is the motion the quasi-steady model
settles into, and how many passed it, with the largest estimated inertial error, is
reported with the checks.

Reported per case: the mean speed of the outer cylinder over the time both runs
cover and its ratio Stokes / lubrication, the regime with each force model, the time
at which 1 - kappa reaches ``THIN_GAP``, and the angle phi at the end of each run.

Checked, as robust statements only:

* every run ends finite, either at ``T_END`` or at the runaway's turn limit;
* where both runs rock, the Stokes run ends with the wider gap: Stokes forces
  resist the squeeze more than (2.5)-(2.7), so the cylinder sinks more slowly;
* where both runs rock and reach the thin gap 1 - kappa = ``THIN_GAP``, the Stokes
  run is the slower one (speed ratio < 1): there the viscous drag limits the speed.
  Where the Stokes gap stays wider (aluminium, 500 cSt, 1 degree) the ratio is 1.045;
  that case is reported, not checked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from dynamics.apparatus import preset
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.regime import classify
from dynamics.simulation import simulate
from dynamics.trajectory import Trajectory
from lubrication.registry import kernel_model

from .checks import Finding, absolute, at_least, at_most

__all__ = ["APPARATUS_SLOPES_DEG", "OILS", "Pair", "figure", "pairs", "run", "simulate_pair", "table"]

# the paper's slopes per apparatus (degrees); the aluminium device was also run at 5
APPARATUS_SLOPES_DEG = {"steel": (1.0, 2.4, 4.0), "aluminium": (1.0, 2.4, 4.0, 5.0)}
OILS = (5.0e-5, 2.0e-4, 5.0e-4)  # kinematic viscosities of the silicone oils, m^2/s
QUICK = ("steel", 2.0e-4, (1.0, 4.0))  # apparatus, oil and slopes of the quick mode
INITIAL = Initial(kappa=0.5, phi=0.5)  # from rest
T_END = 10.0  # s
THIN_GAP = 1e-3  # 1 - kappa taken as a thin gap
RTOL = 1e-8
FORCES = ("closed-form", "stokes")
LIMITS = Limits(on_invalid="warn")  # past the release's first swing (module docstring)


@dataclass(frozen=True)
class Pair:
    """The lubrication and the Stokes run of one case.

    Attributes
    ----------
    apparatus : str
        "steel" or "aluminium".
    nu : float
        Kinematic viscosity of the oil (m^2/s).
    slope_deg : float
        Inclination of the plane (degrees).
    runs : dict of str to Trajectory
        The runs by force model, keys :data:`FORCES`.
    """

    apparatus: str
    nu: float
    slope_deg: float
    runs: dict

    @property
    def t_common(self) -> float:
        """The time both runs cover (s)."""
        return min(float(r.t[-1]) for r in self.runs.values())

    def mean_speed(self, forces: str) -> float:
        """Mean speed X_b' of the outer cylinder over [0, t_common] (m/s)."""
        c, t = self.runs[forces].columns, self.t_common
        return float((np.interp(t, c["t"], c["x_b"]) - c["x_b"][0]) / t)

    @property
    def speed_ratio(self) -> float:
        """Mean speed with Stokes forces over that with the closed forms."""
        return self.mean_speed("stokes") / self.mean_speed("closed-form")

    def regime(self, forces: str) -> str:
        """Regime of the run with ``forces`` (:func:`dynamics.regime.classify`)."""
        return classify(self.runs[forces])[0]

    @property
    def both_rock(self) -> bool:
        return all(self.regime(f) == "rocking" for f in FORCES)

    def thin_gap_time(self, forces: str) -> float:
        """First time 1 - kappa reaches :data:`THIN_GAP` (s, interpolated in log); nan if never."""
        c = self.runs[forces].columns
        log_gap = np.log(c["one_minus_kappa"])
        below = np.flatnonzero(log_gap <= math.log(THIN_GAP))
        if below.size == 0:
            return math.nan
        k = below[0]
        if k == 0:
            return float(c["t"][0])
        return float(np.interp(math.log(THIN_GAP), log_gap[[k, k - 1]], c["t"][[k, k - 1]]))

    def final(self, forces: str, name: str) -> float:
        """Column ``name`` at the end of the run with ``forces``."""
        return float(self.runs[forces].columns[name][-1])

    def ended_cleanly(self, forces: str) -> bool:
        """Finite samples, and the run reached T_END or stopped at the runaway's turn limit."""
        r = self.runs[forces]
        clean_end = r.status == "completed" or r.event == "runaway"
        return clean_end and all(bool(np.all(np.isfinite(col))) for col in r.columns.values())


def simulate_pair(name: str, nu: float, slope_deg: float, models: dict, t_end: float = T_END) -> Pair:
    """Both runs of ``name`` with oil ``nu`` on ``slope_deg``; ``models`` maps :data:`FORCES` to force models."""
    apparatus = preset(name, nu=nu, alpha=math.radians(slope_deg))
    runs: dict[str, Trajectory] = {f: simulate(apparatus, INITIAL, t_end, forces=models[f], rtol=RTOL,
                                               limits=LIMITS) for f in FORCES}
    return Pair(name, nu, slope_deg, runs)


def pairs(cases) -> list[Pair]:
    """One :class:`Pair` per (apparatus, nu, slope) in ``cases``."""
    models = {"closed-form": kernel_model("closed-form"), "stokes": kernel_model("stokes-exact")}
    return [simulate_pair(name, nu, slope, models) for name, nu, slope in cases]


def _cases(quick: bool) -> list[tuple[str, float, float]]:
    if quick:
        name, nu, slopes = QUICK
        return [(name, nu, s) for s in slopes]
    return [(name, nu, s) for name, slopes in APPARATUS_SLOPES_DEG.items() for nu in OILS for s in slopes]


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


def checks_of(results: list[Pair]) -> list:
    """The robust statements of the module docstring, and the validity passages as findings."""
    bad = [f"{p.apparatus} {p.nu * 1e6:g} cSt {p.slope_deg:g} deg {f}" for p in results for f in FORCES
           if not p.ended_cleanly(f)]
    checks = [absolute("runs not finite or stopped for another reason than T_END or the runaway limit",
                       len(bad), 0, 0, "; ".join(bad) or f"{2 * len(results)} runs, rtol={RTOL:g}")]
    rocking = [p for p in results if p.both_rock]
    if rocking:
        widest = min(p.final("stokes", "one_minus_kappa") / p.final("closed-form", "one_minus_kappa")
                     for p in rocking)
        checks.append(at_least("both rock: smallest (1-kappa) at the end, Stokes / lubrication", widest, 1.0,
                               f"{len(rocking)} cases; Stokes resists the squeeze more"))
    thin = [p for p in rocking if not any(math.isnan(p.thin_gap_time(f)) for f in FORCES)]
    if thin:
        fastest = max(p.speed_ratio for p in thin)
        checks.append(at_most("both rock to 1-kappa=1e-3: largest mean speed ratio Stokes / lubrication", fastest,
                              1.0, f"{len(thin)} cases; Stokes drag is larger"))
    runs = [r for p in results for r in p.runs.values()]
    passed = [r for r in runs if r.info.get("limits_passed")]
    checks.append(Finding(f"runs of {len(runs)} that passed the Reynolds guard Re* = {LIMITS.reynolds:g}",
                          len(passed), "in the release's first swing; they go on past it (module docstring)"))
    checks.append(Finding("largest estimated inertial force error of all runs",
                          max(r.info["inertia"]["max_estimated_force_error"] for r in runs),
                          "first order in Re* (lubrication.inertia), at the release's swing"))
    return checks


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
    results = pairs(_cases(quick))
    figures = []
    if not quick:
        figure(Path(outdir) / "stokes_trajectories.png", results)
        figures.append("stokes_trajectories.png")
    return checks_of(results), figures, _paragraph(results)
