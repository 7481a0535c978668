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

import numpy as np

from dynamics.apparatus import preset
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.regime import classify
from dynamics.simulation import simulate
from dynamics.trajectory import Trajectory
from lubrication.registry import kernel_model

from .checks import Finding, absolute, at_least, at_most

__all__ = ["APPARATUS_SLOPES_DEG", "OILS", "Pair", "checks_of", "compute", "pairs", "simulate_pair"]

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


def compute(quick: bool = False) -> list[Pair]:
    """Every pair of the group: one apparatus, one oil and two slopes in the quick form (:data:`QUICK`)."""
    return pairs(_cases(quick))
