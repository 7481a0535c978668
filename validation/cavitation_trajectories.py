r"""Does cavitation stop the inner cylinder sinking? Trajectories of the full model with a rupturing film.

Section 7 of the paper reports two things about bubbles and cavitation: truncating
the pressure where it falls too low "did not provide sufficient lift to counter
gravity and allow steady rolling", and runs with bubbles in the gap were up to
20% faster. Here the full model (2.1)-(2.4) of the steel apparatus (200 cSt oil)
is integrated from kappa = 0.5, phi = 0.5 at rest, on the paper's slopes, with
the Reynolds film forces of :mod:`lubrication.cavitation` under each cavitation
model: none (full film), half-Sommerfeld, Swift-Stieber and JFO.

Which pressures matter
----------------------
Only the difference p_ref - p_cav enters the forces: p_ref holds at the widest gap,
where the trapped bubble sits (the paper's figure 4), and the film ruptures where the
pressure falls to p_cav. Four levels are run:

* a few Pa to a few kPa: a gas bubble is at the pressure of the gas it holds plus
  its Laplace pressure 2 sigma / r (sigma ~ 0.02 N/m for silicone oil: 40 Pa for a
  1 mm bubble, ~4 kPa for one squeezed into a 10 um gap). Air bubbles carried into
  the gap, or air coming out of air-saturated oil, open a cavity as soon as the
  film falls a little below the pressure of the trapped bubble; in a sealed annulus
  whose bubble holds only vapour, the drop is the bubble's Laplace pressure alone.
  This is the experiment with bubbles in the gap;
* 1 atm: a bubble of air at ambient pressure and clean, degassed oil that
  cavitates only at its vapour pressure (~0). This is the bubble-free experiment,
  in which the paper saw no cavities.

Measured over ``T_END`` = 40 s (the full film takes ~30 s to sink to
1 - kappa ~ 1e-6 here):

* every cavitating model, at every level and slope, stops the sinking: 1 - kappa
  settles to a constant (it changes by less than 1e-7 over [20, 40] s) and the
  device rolls steadily with a cavity over a third to a half of the film;
* the half-Sommerfeld truncation gives that lift as well, contrary to the paper's
  claim, but with p_ref - p_cav = 1 atm the steady gap is a fraction of a micron,
  (0.2-1.6 um on 1-4 degrees), below the roughness of machined surfaces, so in
  practice contact comes first; at 3 Pa it is 6-195 um;
* the full film keeps decelerating (the gap closes as t^-2), so the speed ratio is
  not a fixed number: over [T/2, T] it is 12-530 rather than the paper's 1.2. The
  experiment's reference state was itself rolling steadily (rough contact, section
  5); against a decelerating film no finite ratio can be compared with it.

Validity. With a film that ruptures at a few Pa to 100 Pa below p_ref, the release
lets the inner cylinder swing past the outer one within 20 ms, and the reduced
gap Reynolds number Re* of the flow relative to the line of centres
(:mod:`dynamics.equations.limits`) passes 10 there, where quasi-steady Stokes
forces are not even a first approximation. The runs go on past that limit
(``on_invalid = "warn"``): the question here is the state they settle into, a
fixed point of the quasi-steady model that the transient does not move. How many
runs passed it, and the largest Re* of all, are reported with the checks.

A cavity's extent along a run is counted on the nodal film of
:func:`lubrication.cavitation.cavitating_pressure` at every output time, with
eps' and chi' from central differences of the output (second order, enough to
count cavitated nodes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dynamics.apparatus import preset
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.simulation import simulate as run_trajectory
from dynamics.trajectory import Trajectory
from lubrication import Annulus, Fluid, Motion
from lubrication.cavitation import CAVITATION_MODELS, cavitating_pressure
from lubrication.registry import kernel_model

from .checks import Finding, absolute, at_least, at_most

__all__ = ["SLOPES_DEG", "PRESSURE_DROPS", "Run", "simulate", "cavitated_fraction", "checks_of", "compute", "mean_speed"]

SLOPES_DEG = (1.0, 2.4, 4.0)  # the steel runs of figure 5 span 1-4 degrees
NU = 2.0e-4  # 200 cSt silicone oil, m^2/s
P_REF = 101325.0  # pressure at the widest gap, Pa (only p_ref - p_cav matters)
PRESSURE_DROPS = (3.0, 100.0, 3000.0, 101325.0)  # p_ref - p_cav, Pa: see the module docstring
BUBBLE_DROP = 3.0  # the level of a bubble-laden film, Pa
INITIAL = Initial(kappa=0.5, phi=0.5)  # from rest, the default scene of ``snail run``
N_CELLS = 128  # steady 1 - kappa within 0.2% of N = 64
RTOL = 1e-8
T_END, T_END_QUICK = 40.0, 10.0  # s
UNREACHABLE_DROP = 1e15  # Pa: no film pressure of these runs comes near it
RECOVERY_T_END = 2.0  # s of the full-film comparison
# past the release's transient Re* > 10 (module docstring); a steady roll on 4 degrees at 3 Pa turns the
# outer cylinder some 150 times in T_END, which the default runaway limit of 100 turns would cut short
LIMITS = Limits(on_invalid="warn", max_turns=1000.0)


@dataclass(frozen=True)
class Run:
    """One trajectory and what it says about the gap and the speed.

    Attributes
    ----------
    slope_deg : float
        Inclination of the plane (degrees).
    model : str
        Cavitation model, one of :data:`lubrication.cavitation.CAVITATION_MODELS`.
    pressure_drop : float
        p_ref - p_cav (Pa); 0 for the full film.
    trajectory : Trajectory
        The run.
    cavitated : ndarray
        Cavitated fraction of the film nodes at every output time (0 for the full film).
    """

    slope_deg: float
    model: str
    pressure_drop: float
    trajectory: Trajectory
    cavitated: np.ndarray

    @property
    def finite(self) -> bool:
        """Whether the run reached its end with every sample finite."""
        return self.trajectory.status == "completed" and all(
            bool(np.all(np.isfinite(col))) for col in self.trajectory.columns.values())

    def gap(self, t: float) -> float:
        """1 - kappa at time ``t`` (interpolated in log, as it varies over decades)."""
        c = self.trajectory.columns
        return float(np.exp(np.interp(t, c["t"], np.log(c["one_minus_kappa"]))))

    @property
    def late_gap_ratio(self) -> float:
        """(1 - kappa) at the end over (1 - kappa) half way: 1 for a steady gap, < 1 while it closes."""
        t_end = self.trajectory.t[-1]
        return self.gap(t_end) / self.gap(0.5 * t_end)

    @property
    def late_speed(self) -> float:
        """Mean speed of the outer cylinder over the second half (m/s)."""
        return mean_speed(self.trajectory, 0.5 * self.trajectory.t[-1])

    @property
    def cavity_changes(self) -> tuple[int, int]:
        """(appearances, disappearances) of a cavity between output times."""
        present = self.cavitated > 0.0
        return int(np.count_nonzero(~present[:-1] & present[1:])), int(np.count_nonzero(present[:-1] & ~present[1:]))


def simulate(slope_deg: float, model: str, pressure_drop: float, t_end: float, n: int = N_CELLS,
             output_interval: float | None = None) -> Trajectory:
    """The steel apparatus on ``slope_deg`` with ``model`` at p_ref - p_cav = ``pressure_drop`` (Pa)."""
    apparatus = preset("steel", nu=NU, alpha=math.radians(slope_deg))
    forces = kernel_model("reynolds", n=n, cavitation=model, p_cav=P_REF - pressure_drop, p_ref=P_REF)
    return run_trajectory(apparatus, INITIAL, t_end, forces=forces, rtol=RTOL, limits=LIMITS,
                          output_interval=output_interval)


def cavitated_fraction(trajectory: Trajectory, slope_deg: float, model: str, pressure_drop: float,
                       n: int = N_CELLS) -> np.ndarray:
    """Fraction of the film nodes at p_cav at each output time of ``trajectory``."""
    if model == "none":
        return np.zeros(trajectory.t.size)
    apparatus = preset("steel", nu=NU, alpha=math.radians(slope_deg))
    fluid = Fluid(nu=apparatus.nu, rho=apparatus.rho)
    c = trajectory.columns
    eps_dot = np.gradient(c["eps"], c["t"])
    chi_dot = np.gradient(c["chi"], c["t"])
    p_cav = P_REF - pressure_drop
    fraction = np.empty(c["t"].size)
    for k in range(fraction.size):
        annulus = Annulus(a=apparatus.a, b=apparatus.b, length=apparatus.length,
                          one_minus_kappa=float(c["one_minus_kappa"][k]))
        motion = Motion(eps_dot=eps_dot[k], chi_dot=chi_dot[k], omega_a=c["omega_a"][k], omega_b=c["omega_b"][k])
        film = cavitating_pressure(annulus, motion, fluid, model, p_cav=p_cav, p_ref=P_REF, n=n)
        fraction[k] = np.count_nonzero(film.p <= p_cav) / n
    return fraction


def mean_speed(trajectory: Trajectory, start: float) -> float:
    """Mean speed X_b' of the outer cylinder from ``start`` to the end of the run (m/s)."""
    t, x_b = trajectory.t, trajectory.columns["x_b"]
    return float((x_b[-1] - np.interp(start, t, x_b)) / (t[-1] - start))


def trajectories(slopes_deg, drops, t_end: float) -> list[Run]:
    """The full film and every cavitation model at every p_ref - p_cav in ``drops``, on each slope."""
    cases = [("none", 0.0)] + [(model, drop) for model in CAVITATION_MODELS[1:] for drop in drops]
    runs = []
    for slope in slopes_deg:
        for model, drop in cases:
            trajectory = simulate(slope, model, drop, t_end)
            runs.append(Run(slope, model, drop, trajectory, cavitated_fraction(trajectory, slope, model, drop)))
    return runs


def full_film_recovery(slope_deg: float = 2.4) -> float:
    """Largest relative difference of 1 - kappa between a JFO run that cannot rupture and the full film,
    compared at common times from each run's dense output (their steps differ: the full film, smooth, is
    carried in polar velocity near contact, the cavitating one in Cartesian, dynamics.simulation)."""
    interval = RECOVERY_T_END / 200
    cavitating = simulate(slope_deg, "jfo", UNREACHABLE_DROP, RECOVERY_T_END, output_interval=interval)
    full = simulate(slope_deg, "none", 0.0, RECOVERY_T_END, output_interval=interval)
    pick = [np.array(["sample" in row for row in run.rows]) for run in (cavitating, full)]
    ratio = cavitating.columns["one_minus_kappa"][pick[0]] / full.columns["one_minus_kappa"][pick[1]]
    return float(np.max(np.abs(ratio - 1.0)))


def _first_passage(trajectory: Trajectory) -> float:
    """Time (s) at which a run first passed the Reynolds limit."""
    return min(p["t"] for p in trajectory.info["limits_passed"] if p["name"] == "reynolds")


def _label(model: str, drop: float) -> str:
    return "full film" if model == "none" else f"{model}, {drop:g} Pa"


def compute(quick: bool = False) -> list[Run]:
    """The releases of the group: one slope and two levels of p_ref - p_cav in the quick form."""
    slopes = (2.4,) if quick else SLOPES_DEG
    drops = (BUBBLE_DROP, P_REF) if quick else PRESSURE_DROPS
    return trajectories(slopes, drops, T_END_QUICK if quick else T_END)


def checks_of(runs: list[Run]) -> list:
    """The statements of the module docstring on ``runs``, the recovery of the full film, and the validity
    passages as findings."""
    bad = [f"{r.slope_deg:g} deg {_label(r.model, r.pressure_drop)}" for r in runs if not r.finite]
    checks: list = [absolute("trajectories not completed or with non-finite samples", len(bad), 0, 0,
                                    "; ".join(bad) or f"{len(runs)} runs, N={N_CELLS}, rtol={RTOL:g}")]
    for r in runs:
        where = f"{r.slope_deg:g} deg"
        if r.model == "none":
            checks.append(at_most(f"full film: gap still closing, (1-kappa)(T)/(1-kappa)(T/2), {where}",
                                  r.late_gap_ratio, 0.5, "t^-2 closure gives 1/4"))
            continue
        checks.append(absolute(f"{_label(r.model, r.pressure_drop)}: steady gap, (1-kappa)(T)/(1-kappa)(T/2) - 1, "
                               f"{where}", r.late_gap_ratio - 1.0, 0.0, 1e-3, "a cavity holds the cylinder up"))
        if r.pressure_drop == BUBBLE_DROP:
            appear, disappear = r.cavity_changes
            changes = min(appear, disappear)
            checks.append(at_least(f"{_label(r.model, r.pressure_drop)}: cavity appears and disappears, {where}",
                                   changes, 1.0,
                                   f"fewer of {appear} appearances and {disappear} disappearances along the run"))
    full = {r.slope_deg: r.late_speed for r in runs if r.model == "none"}
    slowest = min(r.late_speed / full[r.slope_deg] for r in runs if r.model != "none")
    checks.append(at_least("smallest speed ratio to the full film over [T/2, T]", slowest, 1.0,
                           "every cavitating run is faster"))
    checks.append(at_most("JFO with p_cav far below the film's pressures vs the full film, max rel. 1-kappa",
                          full_film_recovery(), 1e-6, f"p_ref - p_cav = {UNREACHABLE_DROP:g} Pa, "
                          f"{RECOVERY_T_END:g} s, rtol={RTOL:g}"))
    passed = [r for r in runs if any(p["name"] == "reynolds" for p in r.trajectory.info.get("limits_passed", []))]
    largest = max(r.trajectory.info["inertia"]["max_reduced_reynolds"] for r in runs)
    checks.append(Finding(f"runs of {len(runs)} that passed the Reynolds limit Re* = {LIMITS.reynolds:g}",
                          len(passed), "; ".join(f"{r.slope_deg:g} deg {_label(r.model, r.pressure_drop)} at t = "
                                                 f"{_first_passage(r.trajectory):.3g} s" for r in passed) or "none"))
    checks.append(Finding("largest reduced gap Reynolds number Re* of all runs", largest,
                          "the release's swing past the outer centre; see the module docstring"))
    return checks
