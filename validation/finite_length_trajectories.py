r"""Trajectories of the paper's apparatus with the finite length of the annulus, and without.

The inner cylinder is L = 10.35 cm long (L/a = 12.94) and its gap opens at both
ends into the oil of the end regions. The force models of the equations of
motion take that into account with ``ends = "open"``: each resistance
coefficient times its thin-gap finite-length factor
(:mod:`lubrication.finite_length`; against 3-D Stokes the product is within
0.1-4.7 % at this apparatus, ``docs/finite_length.md``). Here the full model
(2.1)-(2.4) of both devices (steel and aluminium, :func:`dynamics.apparatus.preset`)
runs with the closed forms (2.5)-(2.7) and with the exact 2-D Stokes forces,
each with and without the ends, for the paper's oils and slopes (those of
:mod:`validation.stokes_trajectories`):

* smooth walls, from kappa = 0.5, phi = 0.5 at rest, for ``T_SMOOTH`` seconds
  or until a runaway reaches its turn limit: the mean speed over the time both
  runs of a pair cover, 1 - kappa at the end, the regime;
* rough walls with the minimum gap sigma = 50 micrometres of the smooth cylinder
  (Table 3, kappa* = 1 - sigma/delta = 0.985) and the scaled friction angle of
  :data:`validation.contact_checks.PSI_EXPERIMENT` (the onset of sliding at 3
  degrees for the steel cylinder), from the same start for ``T_ROUGH_TAU`` tau,
  long enough to settle on steady rolling: the final speed.

The release swings the inner cylinder round the outer one, and the flow relative
to the line of centres passes the gap Reynolds guard Re* = 1 in that first swing:
as in :mod:`validation.stokes_trajectories` the runs go on past it
(``on_invalid = "warn"``), since the question is the motion the quasi-steady model
settles into; how many passed it, and the largest estimated inertial error, are
reported.

Steady rolling in contact, by hand. With chi' = 0 and constant rates, the
contact force is internal to (2.4), which then reads
0 = M g b sin(alpha) + m'_a g eps* sin(phi): the angle is set by the slope alone.
(2.1) and (2.3) carry the friction F on A, 0 = f_chi + F + m'_a g sin(phi) and
0 = T_a + a F, so f_chi - T_a/a = M g b sin(alpha)/eps*. Locked, the pair rolls
at the contact point, a Omega_a = (a + eps*) Omega_b, and the fluid terms are
Omega_b D with

    D = f_chi - T_a/a   at W_a = (a + eps*)/a, W_b = 1,

so V = b Omega_b = M g b^2 sin(alpha)/(eps* D): D is proportional to the
viscosity, which the ratio of the speeds with and without the ends,
D_infinite/D_open, therefore does not contain: a number of the geometry alone. The
runs are checked against this formula (locked) and against the full model's
fixed point (:func:`dynamics.contact.full.steady_full_contact`, either phase).

Checked:

* every run ends finite, at its end time or at a runaway's turn limit;
* every rough run that does not run away ends on its steady state, to 1e-6 of
  the speed (rtol = 1e-9; the slowest case, aluminium at 1 degree, comes within
  1e-3 of it in about 150 tau, a tenth of the run);
* locked rough runs roll at M g b^2 sin(alpha)/(eps* D) to 1e-6;
* smooth runs where all four models rock end with the smaller gap with the ends
  open: F_eps < 1 lowers the squeeze resistance, most where the gap is wide.

Reported: the speed ratios with the ends open against infinite, and the finite-gap
ratio (exact Stokes against the closed forms) they are to be weighed against.
Run ``python -m validation.finite_length_trajectories [DIR]`` from the project
root (a few minutes; default ``docs/finite_length``): it writes
``trajectories.{json,md,png}``.
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from dynamics.apparatus import Apparatus, preset
from dynamics.contact.full import steady_full_contact
from dynamics.contact.reduced import LOCKED, ContactParams
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.regime import classify
from dynamics.simulation import simulate
from dynamics.trajectory import Trajectory
from lubrication.geometry import Annulus, Fluid, Motion
from lubrication.kernels import KernelModel
from lubrication.registry import kernel_model

from .checks import Check, Finding, absolute, at_most
from .contact_checks import PSI_EXPERIMENT, SANDPAPER
from .stokes_trajectories import APPARATUS_SLOPES_DEG, OILS

__all__ = ["BASES", "ENDS", "Case", "locked_speed", "main", "run", "simulate_case", "to_markdown"]

BASES = ("closed-form", "stokes-exact")
ENDS = ("infinite", "open")
QUICK = ("steel", 2.0e-4, (2.4,))  # apparatus, oil and slopes of the quick mode
INITIAL = Initial(kappa=0.5, phi=0.5)  # from rest, as validation.stokes_trajectories
T_SMOOTH = 10.0  # s
#: Rough runs, in tau: the slowest case (aluminium, 500 cSt, 1 degree) settles to 1e-3 in about 150 tau.
T_ROUGH_TAU = 1500.0
SIGMA = SANDPAPER["smooth"]  # m, the smooth cylinder of Table 3
LIMITS = Limits(on_invalid="warn")  # past the release's first swing (module docstring)
RTOL_SMOOTH = 1e-8
RTOL_ROUGH = 1e-9
STEADY_TOLERANCE = 1e-6


def _model(base: str, ends: str, apparatus: Apparatus) -> KernelModel:
    if ends == "infinite":
        return kernel_model(base)
    return kernel_model(base, ends="open", length_over_a=apparatus.length / apparatus.a)


def contact_of(apparatus: Apparatus) -> ContactParams:
    """sigma = 50 micrometres and the scaled friction angle PSI_EXPERIMENT."""
    return ContactParams(1.0 - SIGMA / apparatus.delta, PSI_EXPERIMENT)


def locked_speed(apparatus: Apparatus, forces: KernelModel, kappa_star: float) -> float:
    """Steady locked rolling speed V = M g b^2 sin(alpha)/(eps* D) of the module docstring (m/s)."""
    ap = apparatus
    eps_star = kappa_star * ap.delta
    annulus = Annulus(a=ap.a, b=ap.b, length=ap.length, one_minus_kappa=1.0 - kappa_star)
    f = forces.forces(annulus, Motion(omega_a=(ap.a + eps_star) / ap.a, omega_b=1.0), Fluid(nu=ap.nu, rho=ap.rho))
    drag = f.f_chi - f.T_a / ap.a
    return ap.M * ap.g * ap.b**2 * math.sin(ap.alpha) / (eps_star * drag)


@dataclass(frozen=True)
class Case:
    """The eight runs of one (apparatus, oil, slope): smooth and rough, two force models, two kinds of ends.

    ``smooth`` and ``rough`` map (base, ends) to a :class:`Trajectory`.
    """

    apparatus: str
    nu: float
    slope_deg: float
    device: Apparatus
    smooth: dict
    rough: dict

    @property
    def label(self) -> str:
        return f"{self.apparatus}, {self.nu * 1e6:g} cSt, {self.slope_deg:g} deg"

    def t_common(self, base: str) -> float:
        """The time both smooth runs of ``base`` cover (s)."""
        return min(float(self.smooth[base, e].t[-1]) for e in ENDS)

    def mean_speed(self, base: str, ends: str) -> float:
        """Mean X_b' of the smooth run over :meth:`t_common` (m/s)."""
        c, t = self.smooth[base, ends].columns, self.t_common(base)
        return float((np.interp(t, c["t"], c["x_b"]) - c["x_b"][0]) / t)

    def smooth_ratio(self, base: str) -> float:
        """Mean speed with the ends open over that without, smooth walls."""
        return self.mean_speed(base, "open") / self.mean_speed(base, "infinite")

    def gap_ratio(self, base: str) -> float:
        """1 - kappa at the end of the smooth run, open over infinite."""
        return (float(self.smooth[base, "open"].columns["one_minus_kappa"][-1])
                / float(self.smooth[base, "infinite"].columns["one_minus_kappa"][-1]))

    def regime(self, kind: str, base: str, ends: str) -> str:
        runs = self.smooth if kind == "smooth" else self.rough
        return classify(runs[base, ends])[0]

    def all_rock(self) -> bool:
        """All four smooth runs went the whole T_SMOOTH and rock."""
        return all(self.regime("smooth", b, e) == "rocking" for b in BASES for e in ENDS)

    def settles(self, base: str, ends: str) -> bool:
        """The rough run went the whole T_ROUGH_TAU and ends in steady rolling."""
        return (self.rough[base, ends].status == "completed"
                and self.regime("rough", base, ends) in ("locked rolling", "sliding rolling"))

    def all_settle(self, base: str | None = None) -> bool:
        """The rough runs (of ``base``, or all four) settle."""
        bases = BASES if base is None else (base,)
        return all(self.settles(b, e) for b in bases for e in ENDS)

    def final_speed(self, base: str, ends: str) -> float:
        """b Omega_b at the end of the rough run (m/s)."""
        return self.device.b * float(self.rough[base, ends].columns["omega_b"][-1])

    def rough_ratio(self, base: str) -> float:
        """Final rough speed with the ends open over that without."""
        return self.final_speed(base, "open") / self.final_speed(base, "infinite")

    def phase(self, base: str, ends: str) -> str:
        return self.rough[base, ends].info.get("final_phase", "")

    def fixed_speed(self, base: str, ends: str) -> float:
        """The full model's steady speed in the phase the rough run ends in (m/s)."""
        run, ap = self.rough[base, ends], self.device
        c = run.columns
        fixed = steady_full_contact(ap, _model(base, ends, ap), contact_of(ap), self.phase(base, ends) == LOCKED,
                                    [c["chi"][-1], c["omega_a"][-1], c["omega_b"][-1]])
        return ap.b * float(fixed[2])


def simulate_case(name: str, nu: float, slope_deg: float, quick_rough: bool = False) -> Case:
    """The eight runs of ``name`` with oil ``nu`` on ``slope_deg``."""
    ap = preset(name, nu=nu, alpha=math.radians(slope_deg))
    smooth, rough = {}, {}
    for base in BASES:
        for ends in ENDS:
            model = _model(base, ends, ap)
            smooth[base, ends] = simulate(ap, INITIAL, T_SMOOTH, forces=model, rtol=RTOL_SMOOTH, limits=LIMITS)
            rough[base, ends] = simulate(ap, INITIAL, T_ROUGH_TAU * ap.tau, forces=model, contact=contact_of(ap),
                                         rtol=RTOL_ROUGH, limits=LIMITS)
    return Case(name, nu, slope_deg, ap, smooth, rough)


def _cases(quick: bool) -> list[tuple[str, float, float]]:
    if quick:
        name, nu, slopes = QUICK
        return [(name, nu, s) for s in slopes]
    return [(name, nu, s) for name, slopes in APPARATUS_SLOPES_DEG.items() for nu in OILS for s in slopes]


def _ended_cleanly(run: Trajectory) -> bool:
    clean_end = run.status == "completed" or run.event == "runaway"
    return clean_end and all(bool(np.all(np.isfinite(col))) for col in run.columns.values())


def _range(records: list, name: str, values: list[float], note: str = "") -> None:
    """Findings for the smallest and largest of ``values`` (none if empty)."""
    if values:
        records.append(Finding(f"{name}, smallest", min(values), note))
        records.append(Finding(f"{name}, largest", max(values), note))


def records_of(cases: list[Case]) -> list:
    """The checks and findings of the module docstring."""
    bad = [f"{c.label} {kind} {base}/{ends}" for c in cases for kind, runs in (("smooth", c.smooth), ("rough", c.rough))
           for (base, ends), run in runs.items() if not _ended_cleanly(run)]
    records: list = [absolute("finite length: runs not finite or stopped for another reason than their end or "
                              "the runaway limit", len(bad), 0, 0, "; ".join(bad) or f"{8 * len(cases)} runs")]
    settled = [(abs(c.final_speed(b, e) / c.fixed_speed(b, e) - 1.0), f"{c.label} {b}/{e}")
               for c in cases for b in BASES for e in ENDS if c.settles(b, e)]
    if settled:
        worst = max(settled)
        records.append(at_most("finite length, rough: largest |final speed / steady speed - 1|", worst[0],
                               STEADY_TOLERANCE, f"{len(settled)} runs; worst {worst[1]}"))
    for base in BASES:
        locked = [(c, e) for c in cases for e in ENDS if c.phase(base, e) == LOCKED and c.settles(base, e)]
        if locked:
            errors = [abs(c.final_speed(base, e) / locked_speed(c.device, _model(base, e, c.device),
                                                                 contact_of(c.device).kappa_star) - 1.0)
                      for c, e in locked]
            records.append(at_most(f"finite length, rough, {base}: largest |locked speed / M g b^2 sin(alpha)/"
                                   "(eps* D) - 1|", max(errors), STEADY_TOLERANCE, f"{len(locked)} runs"))
    rocking = [c for c in cases if c.all_rock()]
    if rocking:
        widest = max(c.gap_ratio(b) for c in rocking for b in BASES)
        records.append(at_most("finite length, smooth, all four rock: largest (1 - kappa) at the end, open / "
                               "infinite", widest, 1.0, f"{len(rocking)} cases x 2 force models"))
    runaway = [c for c in cases if not c.all_rock()]
    for base in BASES:
        _range(records, f"finite length, smooth, all rock, {base}: mean speed open / infinite",
               [c.smooth_ratio(base) for c in rocking], f"{len(rocking)} cases, {T_SMOOTH:g} s")
        _range(records, f"finite length, smooth, all rock, {base}: 1 - kappa at the end, open / infinite",
               [c.gap_ratio(base) for c in rocking])
        _range(records, f"finite length, smooth, runaway, {base}: mean speed open / infinite",
               [c.smooth_ratio(base) for c in runaway if c.regime("smooth", base, "infinite") == "runaway"],
               "over the time both runs cover")
        _range(records, f"finite length, rough, {base}: steady speed open / infinite",
               [c.rough_ratio(base) for c in cases if c.all_settle(base)])
    _range(records, "finite gap, smooth, all rock: mean speed exact Stokes / closed forms",
           [c.mean_speed("stokes-exact", "infinite") / c.mean_speed("closed-form", "infinite") for c in rocking],
           "the delta/a correction the ends are weighed against")
    _range(records, "finite gap, rough: steady speed exact Stokes / closed forms",
           [c.final_speed("stokes-exact", "infinite") / c.final_speed("closed-form", "infinite")
            for c in cases if c.all_settle()])
    runs = [run for c in cases for kind in (c.smooth, c.rough) for run in kind.values()]
    records.append(Finding(f"runs of {len(runs)} that passed the Reynolds guard Re* = {LIMITS.reynolds:g}",
                           sum(bool(run.info.get("limits_passed")) for run in runs),
                           "in the release's first swing; they go on past it (module docstring)"))
    records.append(Finding("largest estimated inertial force error of all runs",
                           max(float(run.info.get("inertia", {}).get("max_estimated_force_error", math.nan))
                               for run in runs), "first order in Re* (lubrication.inertia), at the release's swing"))
    return records


def summary(cases: list[Case]) -> dict:
    """The numbers of every case, JSON-ready."""
    rows = []
    for c in cases:
        row = {"apparatus": c.apparatus, "nu_m2_s": c.nu, "slope_deg": c.slope_deg, "tau_s": c.device.tau,
               "kappa_star": contact_of(c.device).kappa_star, "smooth": {}, "rough": {}}
        for base in BASES:
            row["smooth"][base] = {
                "t_compared_s": c.t_common(base), "speed_ratio": c.smooth_ratio(base),
                "one_minus_kappa_ratio": c.gap_ratio(base),
                **{ends: {"mean_speed_m_s": c.mean_speed(base, ends), "regime": c.regime("smooth", base, ends),
                          "one_minus_kappa_end": float(c.smooth[base, ends].columns["one_minus_kappa"][-1]),
                          "t_end_s": float(c.smooth[base, ends].t[-1]), "event": c.smooth[base, ends].event}
                   for ends in ENDS}}
            row["rough"][base] = {
                "speed_ratio": c.rough_ratio(base),
                **{ends: {"final_speed_m_s": c.final_speed(base, ends), "regime": c.regime("rough", base, ends),
                          "phase": c.phase(base, ends), "t_end_s": float(c.rough[base, ends].t[-1]),
                          "steady_speed_m_s": c.fixed_speed(base, ends) if c.settles(base, ends) else None}
                   for ends in ENDS}}
        rows.append(row)
    return {"initial": {"kappa": INITIAL.kappa, "phi": INITIAL.phi}, "t_smooth_s": T_SMOOTH,
            "t_rough_tau": T_ROUGH_TAU, "sigma_m": SIGMA, "psi": PSI_EXPERIMENT,
            "max_gap_reynolds": LIMITS.reynolds, "on_invalid": LIMITS.on_invalid, "cases": rows}


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
    cases = [simulate_case(*case) for case in _cases(quick)]
    records = records_of(cases)
    figures = []
    if not quick:
        figure(Path(outdir) / "finite_length_trajectories.png", cases)
        figures.append("finite_length_trajectories.png")
    return records, figures, _paragraph(cases, records)


def main(argv=None) -> int:
    from numerics.files import write_json, write_text

    from .checks import comparisons

    out = Path(argv[0]) if argv else Path("docs/finite_length")
    start = time.perf_counter()
    cases = [simulate_case(*case) for case in _cases(False)]
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
