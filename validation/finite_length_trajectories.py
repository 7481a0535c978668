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
The table, the paragraph and the figure are
:mod:`validation.reports.finite_length_trajectories`'s: run
``python -m validation.reports.finite_length_trajectories [DIR]`` from the project
root (default ``docs/finite_length``) to write ``trajectories.{json,md,png}``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

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

from .checks import Finding, absolute, at_most
from .contact_checks import PSI_EXPERIMENT, SANDPAPER
from .stokes_trajectories import APPARATUS_SLOPES_DEG, OILS

__all__ = ["BASES", "ENDS", "Case", "compute", "locked_speed", "records_of", "simulate_case", "summary"]

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


def compute(quick: bool = False) -> list[Case]:
    """Every case of the group: one apparatus, one oil and one slope in the quick form (:data:`QUICK`)."""
    return [simulate_case(*case) for case in _cases(quick)]
