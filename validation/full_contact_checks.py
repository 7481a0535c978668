r"""Rough contact in the full model (2.1)-(2.4): its limit to section 5, and the paper's apparatus.

The full model carries contact as a unilateral constraint with Coulomb friction
(:mod:`dynamics.contact.full`). Section 5 is its leading order in delta/a, so:

* Steady rolling. The full model's own fixed points in contact (chi' = 0,
  rates constant, found by Newton's method on its contact equations) must
  approach the reduced fixed points (5.6), (5.10) and (5.11) as corrected
  (erratum 6) at first order in delta/a: the log-log slope of the difference
  over delta/a = 1e-2, 3e-3, 1e-3 is checked to be 1 within 0.05, for the
  locked (psi = 0.5) and the sliding (psi = 0.05) branches of figure 8.
* Release. Figure 7's release at rest from (kappa, phi) = (0.5, 0.3) on a
  distinguished-limit apparatus (delta/a = 0.01, mu_ = 1.5: a real device has
  mu_ > 1) must settle on that fixed point, to 1e-6 of the rate scale
  3 zeta* s, after the free approach, a plastic impact and, for psi = 0.5,
  locking.
* Stick-slip. Just above the onset of sliding (psi = 0.13 > psi_c = 0.1286),
  the rocking pair alternates locked and sliding phases; each switch is a
  located event, so the run must cost no more steps than one that locks once.

The paper's apparatus. Section 6 applies (6.1) to the steel cylinder at
delta/a = 0.41. The full model with contact there (500 cSt, 2.4 degrees,
sigma = 50 micrometres, the smooth cylinder of Table 3) rolls at its own
steady speed, reported against (6.1) with closed-form and with the exact
Stokes forces; that ratio is the finite-gap correction to the speed law.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from dynamics.apparatus import Apparatus, preset
from dynamics.contact.full import steady_full_contact
from dynamics.contact.reduced import LOCKED, ContactParams
from dynamics.contact.steady import steady_state
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import simulate
from dynamics.trajectory import Trajectory
from lubrication.registry import kernel_model

from .checks import Check, absolute, at_least, at_most, relative
from .contact_checks import (
    KAPPA_STAR,
    PSI_EXPERIMENT,
    RELEASE,
    SANDPAPER,
    SANDPAPER_OIL,
    SANDPAPER_SLOPE_DEG,
)

__all__ = ["compute", "limit_errors", "reduced_releases"]

S = 0.25  # figures 7-9
MU_RATIO = 1.5  # a real device has mu_ > 1 (figures 7-9 use mu_ = 1, which only the reduced model allows)
RATIOS = (1e-2, 3e-3, 1e-3)
BRANCHES = {"locked": 0.5, "sliding": 0.05}
STICK_SLIP_PSI = 0.13
T_END_TAU = 400.0  # figure 7's release settles to e^-30 well within this at delta/a = 0.01 (rate 0.23/tau)
STEADY_TOLERANCE = 1e-6
RTOL = 1e-10


def device(delta_over_a: float) -> Apparatus:
    return Apparatus.from_groups(s=S, upsilon=1.0, mu_ratio=MU_RATIO, delta_over_a=delta_over_a)


def _steady(apparatus, forces, surfaces: ContactParams, reduced) -> np.ndarray:
    """The full model's fixed point, from the reduced one as the first guess."""
    return steady_full_contact(apparatus, forces, surfaces, reduced.phase == LOCKED,
                               [reduced.phi - apparatus.alpha, reduced.omega_a / apparatus.tau,
                                reduced.omega_b / apparatus.tau])


def limit_errors(psi: float) -> list[float]:
    """max |full - reduced| of (phi, Omega_a/Omega_a*, Omega_b/Omega_b*) at each delta/a of RATIOS."""
    reduced = steady_state(S, KAPPA_STAR, psi)
    errors = []
    for ratio in RATIOS:
        ap = device(ratio)
        chi, omega_a, omega_b = _steady(ap, kernel_model("closed-form"), ContactParams(KAPPA_STAR, psi), reduced)
        errors.append(max(abs(chi + ap.alpha - reduced.phi), abs(omega_a * ap.tau / reduced.omega_a - 1.0),
                          abs(omega_b * ap.tau / reduced.omega_b - 1.0)))
    return errors


def release(psi: float, delta_over_a: float = RATIOS[0], t_end_tau: float = T_END_TAU) -> Trajectory:
    ap = device(delta_over_a)
    return simulate(ap, RELEASE, t_end_tau * ap.tau, forces=kernel_model("closed-form"), contact=ContactParams(KAPPA_STAR, psi),
                    rtol=RTOL)


def _release_error(trajectory: Trajectory, psi: float) -> float:
    """max |rate - fixed point| at the end, over the rate scale 3 zeta* s; chi error in rad."""
    ap = device(trajectory.groups["delta_over_a"])
    reduced = steady_state(S, KAPPA_STAR, psi)
    chi, omega_a, omega_b = _steady(ap, kernel_model("closed-form"), ContactParams(KAPPA_STAR, psi),
                                    reduced)
    c = trajectory.columns
    scale = 3.0 * ContactParams(KAPPA_STAR, psi).zeta_star * S / ap.tau
    return max(abs(c["chi"][-1] - chi), abs(c["omega_a"][-1] - omega_a) / scale, abs(c["omega_b"][-1] - omega_b) / scale)


def apparatus_speeds(quick: bool) -> dict:
    """Steady speed of the steel apparatus in contact, full model, against (6.1) (module docstring)."""
    ap = preset("steel", nu=SANDPAPER_OIL, alpha=math.radians(SANDPAPER_SLOPE_DEG))
    kappa_star = 1.0 - SANDPAPER["smooth"] / ap.delta
    rough = ContactParams(kappa_star, PSI_EXPERIMENT)
    reduced = steady_state(ap.s, kappa_star, PSI_EXPERIMENT)
    out = {"delta_over_a": ap.delta_over_a, "kappa_star": kappa_star, "v_reduced": ap.b * reduced.omega_b / ap.tau,
           "phase_reduced": reduced.phase}
    models = {"closed-form": kernel_model("closed-form")}
    if not quick:
        models["stokes"] = kernel_model("stokes-exact")
    for name, forces in models.items():
        run = simulate(ap, Initial(kappa=kappa_star, phi=math.pi), 3000.0 * ap.tau, forces=forces, contact=rough,
                       rtol=1e-9)
        c = run.columns  # the fixed point of the phase the run ends in, from its final state
        fixed = steady_full_contact(ap, forces, ContactParams(kappa_star, PSI_EXPERIMENT),
                                    run.info["final_phase"] == LOCKED,
                                    [c["chi"][-1], c["omega_a"][-1], c["omega_b"][-1]])
        out[name] = {"v": ap.b * float(c["omega_b"][-1]), "v_fixed": ap.b * fixed[2],
                     "phase": run.info["final_phase"], "status": run.status}
    return out


def reduced_releases() -> dict[str, Trajectory]:
    """Figure 7's release on each branch in the reduced model with contact (section 5), over 60 tau:
    what the figure draws the full model's releases against."""
    return {branch: simulate(ReducedParams(S, 1.0, MU_RATIO), RELEASE, 60.0, contact=ContactParams(KAPPA_STAR, psi))
            for branch, psi in BRANCHES.items()}


def compute(quick: bool = False) -> dict:
    """Every run of the group and its checks; the figure and the paragraph read the runs by name.

    Returns ``checks``, the log-log ``slopes`` of the limit, the figure 7 releases ``runs`` per branch
    and delta/a, the ``stick_slip`` run with its ``phases`` and a run that locks ``once``, the
    apparatus' ``speeds``, and (full form only) the section 5 runs of the figure, ``reduced``.
    """
    checks: list[Check] = []
    slopes = {}
    for branch, psi in BRANCHES.items():
        errors = limit_errors(psi)
        slopes[branch] = (float(np.polyfit(np.log(RATIOS), np.log(errors), 1)[0]), errors[-1])
        checks.append(relative(f"full contact, {branch} steady state vs section 5: slope in delta/a",
                               slopes[branch][0], 1.0, 0.05, f"psi = {psi:g}, delta/a = 1e-2 ... 1e-3"))

    runs = {branch: {RATIOS[0]: release(psi)} for branch, psi in BRANCHES.items()}
    if not quick:
        for branch, psi in BRANCHES.items():
            runs[branch][0.1] = release(psi, 0.1, 60.0)
    for branch, psi in BRANCHES.items():
        trajectory = runs[branch][RATIOS[0]]
        checks.append(absolute(f"full contact, figure 7 release (psi = {psi:g}): final phase is {branch} "
                               "(1 if so)", float(trajectory.info["final_phase"] == branch), 1.0, 0.0,
                               trajectory.info["final_phase"]))
        checks.append(at_most(f"full contact, figure 7 release (psi = {psi:g}): end state vs its fixed point",
                              _release_error(trajectory, psi), STEADY_TOLERANCE,
                              "relative to 3 zeta* s; delta/a = 0.01"))

    stick_slip = release(STICK_SLIP_PSI, t_end_tau=300.0)
    once = release(BRANCHES["locked"], t_end_tau=300.0)
    phases = [sw["to"] for sw in stick_slip.info["switches"]]
    alternating = all(p != q for p, q in itertools.pairwise(phases))
    checks.append(absolute(f"full contact, stick-slip at psi = {STICK_SLIP_PSI}: phases alternate at every switch "
                           "(1 if so)", float(alternating), 1.0, 0.0, f"{len(phases)} switches"))
    checks.append(at_least(f"full contact, stick-slip at psi = {STICK_SLIP_PSI}: switches", len(phases), 4.0))
    checks.append(at_most(f"full contact, stick-slip at psi = {STICK_SLIP_PSI}: steps over a run that locks once",
                          stick_slip.steps / once.steps, 1.5, "no step-size collapse at the switches"))

    speeds = apparatus_speeds(quick)
    for name in ("closed-form", "stokes"):
        if name in speeds:
            row = speeds[name]
            checks.append(relative(f"full contact, steel apparatus ({name} forces): speed vs its fixed point",
                                   row["v"], row["v_fixed"], STEADY_TOLERANCE, row["phase"]))
    if "stokes" in speeds:  # Stokes resists more than (2.5)-(2.7) at this gap (1 + c delta/a, c > 0): slower
        checks.append(at_most("full contact, steel apparatus: speed with Stokes forces over (6.1)",
                              speeds["stokes"]["v"] / speeds["v_reduced"], 1.0,
                              f"(6.1) with the exact fixed point: {1e3 * speeds['v_reduced']:.3g} mm/s"))

    result = {"checks": checks, "slopes": slopes, "runs": runs, "stick_slip": stick_slip, "phases": phases,
              "once": once, "speeds": speeds}
    if not quick:
        result["reduced"] = reduced_releases()
    return result
