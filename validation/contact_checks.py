r"""Rough contact (section 5): figures 7-10 and Table 3 regenerated from simulations.

Every number checked here comes from a run of the hybrid model of
:mod:`dynamics.contact.reduced` (through :func:`dynamics.simulation.simulate`),
compared with the paper's formulas as :mod:`dynamics.contact.reduced` implements them:
the fixed points (5.6)-(5.11) with (5.11) corrected (erratum 6) and the locking
test read with tan(psi) (erratum 7), the compact forms (5.12), the onset of
sliding (6.4) and the speed (6.1)-(6.2).

How long a run must be. A run is stopped after ``TRANSIENT_TAU`` plus
``E_FOLDS`` e-folding times of the slowest mode of its final contact phase,
linearised at the fixed point (:func:`settling_rate`): e^-30 = 1e-13 of the
initial offset is left, far below the 1e-6 checked. The rates differ tenfold,
from 0.23 per tau down to 0.020 per tau (steel in 50 cSt oil, Upsilon = 47,
where the rocking is overdamped and creeps), so a fixed t_end would either
waste time or stop short (600 tau leave 1e-6 of the slowest). The tolerance
RTOL = 1e-10 (atol the same, on rates in 1/tau) leaves the steady speeds of
figure 10 within 1e-12 of the fixed points (measured with the compiled Radau
IIA, over both oils, slopes 1-5 degrees and both zeta*; 1e-10 at rtol = 1e-8),
the lightly damped rocking (aluminium in 500 cSt oil: 0.074 per tau against a
frequency of 2.6) included.

The runs
--------
* Figures 7 and 8: Upsilon = mu_ = 1, s = 1/4, kappa* = 0.98, psi = 0.05
  (figure 7) and psi = 0.5, 0.05, 0 (figure 8), released at rest from
  figure 2's (kappa, phi) = (0.5, 0.3). Figure 7 also shows the unlimited
  (smooth-wall) solution from the same release, dotted.
* Figure 9: the same groups and release with psi = 0.15 rad and s from 0.05
  to 0.9, plus s 2% either side of the exact onset of sliding.
* Figure 10(b): dimensional runs of the reduced model with the steel and
  aluminium apparatus (:func:`dynamics.apparatus.preset`), the paper's four
  silicone oils and six slopes from 1 to 5.6 degrees, for zeta* = 0.1 and
  0.2, each released at rest with the inner cylinder on the asperities at
  the bottom (phi = pi, as observed in the experiments of section 4). The
  friction angle is the one that puts the onset of sliding (6.4) of the steel
  cylinder at the 3 degrees suggested by figure 12 (section 6.2).
* Table 3: the steel cylinder in 500 cSt oil (figure 11) on the 2.4 degree
  slope of figure 5(a), with the inferred sandpaper roughness sigma as
  kappa* = 1 - sigma/delta (6.3).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from dynamics.apparatus import preset
from dynamics.contact.reduced import (
    LOCKED,
    SLIDING,
    ContactParams,
    locked_jacobian,
    phase_args,
    sliding_jacobian,
)
from dynamics.contact.steady import (
    onset_of_sliding,
    steady_speed,
    steady_state,
)
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import simulate
from dynamics.trajectory import PHASE_CODES, Trajectory

from .checks import Check, Finding, absolute, at_most, relative

__all__ = [
    "FIGURE7", "KAPPA_STAR", "RELEASE", "PSI_EXPERIMENT", "SANDPAPER",
    "compute", "onset_slope", "settled_run", "settling_rate", "steady_rate_error",
]

FIGURE7 = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)  # figures 7-9: Upsilon = mu_ = 1, s = 1/4
KAPPA_STAR = 0.98  # figures 7-9
FIGURE7_PSI = 0.05
FIGURE8_PSIS = (0.5, 0.05, 0.0)
FIGURE9_PSI = 0.15  # rad, figure 9's caption
RELEASE = Initial(kappa=0.5, phi=0.3)  # figure 2's release, at rest, repeated in figures 7-9

RTOL = 1e-10  # see the module docstring
E_FOLDS = 30.0  # e-folding times of the slowest mode left at the end of a run
TRANSIENT_TAU = 50.0  # free approach and first rocking (figure 7 touches at t = 5.8)
FIGURE7_T_PLOT = 120.0  # tau shown in figure 7, and sampled of the unlimited solution
STEADY_TOLERANCE = 1e-6

OILS = (5e-5, 2e-4, 3.5e-4, 5e-4)  # silicone oils of Table 1, m^2/s
MATERIALS = ("steel", "aluminium")
SLOPES_DEG = tuple(np.linspace(1.0, 5.6, 6))  # the experiments' range of slopes (section 4)
ZETAS = (0.1, 0.2)  # figure 10's theory lines
TRANSITION_DEG = 3.0  # where figure 12 suggests the steel cylinder starts to slide (section 6.2)
PSI_EXPERIMENT = onset_of_sliding(preset("steel", alpha=math.radians(TRANSITION_DEG)).s)

# Table 3: grade -> inferred roughness sigma (m); "smooth" is the bare steel cylinder (section 6.1)
SANDPAPER = {"220": 0.3e-3, "150": 0.4e-3, "120": 0.5e-3, "80": 1.0e-3, "50": 1.6e-3, "smooth": 0.05e-3}
SANDPAPER_OIL = 5e-4  # 500 cSt, figure 11
SANDPAPER_SLOPE_DEG = 2.4  # the steel run of figure 5(a)


# -- runs to the steady state -------------------------------------------------------

def settling_rate(params: ReducedParams, contact: ContactParams) -> float:
    """Slowest decay rate (1/tau) of the steady contact phase, linearised at its fixed point.

    The phase is the one :func:`dynamics.contact.steady.steady_state` selects; the
    Jacobian is that of (2.11b), (5.2), (2.11d) (sliding: phi, Omega_a,
    Omega_b) or of (2.11b), (2.11d) with Omega_a = Omega_b (locked: phi,
    Omega), the passive X_b dropped.
    """
    steady = steady_state(params.s, contact.kappa_star, contact.psi)
    if steady.phase == LOCKED:
        jac = locked_jacobian(0.0, np.array([steady.phi, steady.omega_a, 0.0]), phase_args(params, contact))[:2, :2]
    else:
        state = np.array([steady.phi, steady.omega_a, steady.omega_b, 0.0])
        jac = sliding_jacobian(0.0, state, phase_args(params, contact, math.copysign(1.0, params.s)))[:3, :3]
    return -float(np.max(np.linalg.eigvals(jac).real))


def settled_run(params: ReducedParams, contact: ContactParams, initial: Initial, *,
                apparatus=None) -> Trajectory:
    """A contact run long enough to leave e^-E_FOLDS of the slowest mode (module docstring)."""
    t_end = TRANSIENT_TAU + E_FOLDS / settling_rate(params, contact)
    if apparatus is None:
        return simulate(params, initial, t_end, contact=contact, rtol=RTOL)
    return simulate(apparatus, initial, t_end * apparatus.tau, equations="reduced", contact=contact, rtol=RTOL)


def _final(trajectory: Trajectory) -> tuple[float, float, float]:
    """(phi, Omega_a, Omega_b) at the end of a run, rates in 1/tau."""
    c = trajectory.columns
    return float(c["phi"][-1]), float(c["omega_a"][-1] * trajectory.tau), float(c["omega_b"][-1] * trajectory.tau)


def steady_rate_error(trajectory: Trajectory, s: float, contact: ContactParams) -> float:
    """max |Omega - Omega_steady| at the end of a run, relative to the rate scale 3 zeta* s of (5.12)."""
    steady = steady_state(s, contact.kappa_star, contact.psi)
    _, omega_a, omega_b = _final(trajectory)
    return max(abs(omega_a - steady.omega_a), abs(omega_b - steady.omega_b)) / (3.0 * contact.zeta_star * abs(s))


def _angle_error(phi: float, reference: float) -> float:
    return abs((phi - reference + math.pi) % (2.0 * math.pi) - math.pi)


def _settled(trajectory: Trajectory) -> bool:
    return trajectory.status == "completed"


def _max_or_nan(values) -> float:
    """The largest value, NaN (a failing measurement) when nothing was measured."""
    values = list(values)
    return max(values) if values else math.nan


def onset_slope(psi: float, kappa_star: float = 1.0) -> float:
    """The slope group s at which the steady state starts to slide for friction angle ``psi``.

    Inverts :func:`dynamics.contact.steady.onset_of_sliding`: (6.4) for kappa* = 1,
    the exact locking test (erratum 7) otherwise.
    """
    return brentq(lambda s: onset_of_sliding(s, kappa_star) - psi, 0.0, kappa_star * (1.0 - 1e-12),
                  xtol=1e-15, rtol=1e-15)


# -- figures 7 and 8 ----------------------------------------------------------------

def figure8_runs(psis=FIGURE8_PSIS) -> dict[float, Trajectory]:
    """Figure 8's runs (figure 7's is psi = 0.05), from figure 2's release."""
    return {psi: settled_run(FIGURE7, ContactParams(KAPPA_STAR, psi), RELEASE) for psi in psis}


def unlimited_run(t_eval) -> Trajectory:
    """The smooth-wall solution from the same release (figure 7's dotted lines), sampled at ``t_eval``.

    At 1e-2 RTOL, so that it is a reference for the free flight of the contact runs.
    """
    t_eval = np.asarray(t_eval, dtype=float)
    return simulate(FIGURE7, RELEASE, float(t_eval[-1]), t_eval=t_eval, rtol=1e-2 * RTOL)


def _touch(trajectory: Trajectory) -> tuple[float, int]:
    """Time of the first touch and the index of the first sample in contact."""
    t_touch = trajectory.info["switches"][0]["t"] / trajectory.tau
    return t_touch, int(np.flatnonzero(trajectory.columns["phase"] != PHASE_CODES["free"])[0])


def figure7_checks(trajectory: Trajectory, unlimited: Trajectory, t_touch: float) -> list[Check]:
    """Contact reached on the unlimited solution; sliding to the corrected (5.11)."""
    contact = ContactParams(KAPPA_STAR, FIGURE7_PSI)
    steady = steady_state(FIGURE7.s, KAPPA_STAR, FIGURE7_PSI)
    i = int(np.searchsorted(unlimited.t, t_touch))
    phi, omega_a, omega_b = _final(trajectory)
    zeta = contact.zeta_star
    printed_total = FIGURE7.s * (2.0 + KAPPA_STAR**2) * zeta / (2.0 * KAPPA_STAR**2)
    return [
        relative("figure 7: 1 - kappa of the unlimited solution at the touch vs 1 - kappa*",
                 unlimited.columns["one_minus_kappa"][i], contact.one_minus_kappa_star, 10.0 * RTOL,
                 f"touch at t = {t_touch:.6g} tau: the global error of the free flight at rtol {RTOL:g} "
                 "(measured 0.04 rtol over the 6 tau)"),
        absolute("figure 7: phase at the end (sliding)", PHASE_CODES[trajectory.info["final_phase"]],
                 PHASE_CODES[steady.phase], 0.0,
                 f"codes {PHASE_CODES}; {len(trajectory.info['switches'])} switch(es)"),
        absolute("figure 7: phi at the end vs (5.6) pi + asin(s/kappa*)", _angle_error(phi, steady.phi), 0.0,
                 STEADY_TOLERANCE, "angle difference, rad"),
        relative("figure 7: Omega_a + Omega_b at the end vs (5.7)", omega_a + omega_b,
                 FIGURE7.s * (2.0 + KAPPA_STAR**2) * zeta / KAPPA_STAR**2, STEADY_TOLERANCE,
                 f"(5.11) as printed gives {printed_total:.6g}, half of it (erratum 6)"),
        at_most("figure 7: rates at the end vs corrected (5.11), relative to 3 zeta* s",
                steady_rate_error(trajectory, FIGURE7.s, contact), STEADY_TOLERANCE,
                f"Omega_a = {omega_a:.9g}, Omega_b = {omega_b:.9g} (1/tau)"),
    ]


def figure8_checks(runs: dict[float, Trajectory]) -> list[Check]:
    """Locked (psi = 0.5) or sliding (0) as the locking test says; the fixed points; the jump of Omega_a.

    psi = 0.05 is figure 7's run, checked there.
    """
    checks = []
    for psi, trajectory in runs.items():
        if psi == FIGURE7_PSI:
            continue
        contact = ContactParams(KAPPA_STAR, psi)
        steady = steady_state(FIGURE7.s, KAPPA_STAR, psi)
        checks.append(absolute(f"figure 8, psi = {psi:g}: phase at the end ({steady.phase})",
                               PHASE_CODES[trajectory.info["final_phase"]], PHASE_CODES[steady.phase], 0.0,
                               f"codes {PHASE_CODES}"))
        checks.append(at_most(f"figure 8, psi = {psi:g}: rates at the end vs (5.10)/(5.11), relative to 3 zeta* s",
                              steady_rate_error(trajectory, FIGURE7.s, contact), STEADY_TOLERANCE))
        if trajectory.info["switches"][0]["to"] == LOCKED:
            # "Omega_a must jump discontinuously at the moment of contact" (section 5), to Omega_b.
            c = trajectory.columns
            _, i = _touch(trajectory)
            checks.append(relative(f"figure 8, psi = {psi:g}: jump of Omega_a on locking vs Omega_b - Omega_a before",
                                   c["omega_a"][i] - c["omega_a"][i - 1], c["omega_b"][i - 1] - c["omega_a"][i - 1],
                                   1e-15, "the paper's rule: Omega_b kept, Omega_a set to it"))
    return checks


# -- figure 9 -----------------------------------------------------------------------

def figure9_runs(slopes) -> dict[float, Trajectory]:
    """Runs to the steady state at psi = 0.15 for each s, from figure 2's release."""
    contact = ContactParams(KAPPA_STAR, FIGURE9_PSI)
    return {s: settled_run(ReducedParams(s, FIGURE7.upsilon, FIGURE7.mu_ratio), contact, RELEASE) for s in slopes}


def figure9_checks(runs: dict[float, Trajectory], s_onset: float) -> list[Check]:
    contact = ContactParams(KAPPA_STAR, FIGURE9_PSI)
    settled = {s: tr for s, tr in runs.items() if _settled(tr)}
    errors = [steady_rate_error(tr, s, contact) for s, tr in settled.items()]
    wrong_branch = sum(tr.info["final_phase"] != steady_state(s, KAPPA_STAR, FIGURE9_PSI).phase
                       for s, tr in settled.items())
    below, above = runs[0.98 * s_onset], runs[1.02 * s_onset]
    runaways = sorted(float(s) for s, tr in runs.items() if tr.event == "runaway")
    neither = sorted(float(s) for s, tr in runs.items() if s not in settled and tr.event != "runaway")
    return [
        absolute(f"figure 9: runs of {len(runs)} that neither settled nor ran away", len(neither), 0.0, 0.0,
                 f"each run ends in steady rolling or is stopped as a runaway; neither: {neither or 'none'}"),
        Finding(f"figure 9: runs of {len(runs)} that ran away from figure 2's release instead of settling",
                len(runaways), f"s = {', '.join(f'{s:g}' for s in runaways) or 'none'}: the pushed pendulum "
                "overshoots its rest point from this release"),
        at_most(f"figure 9: steady rates of {len(settled)} runs vs (5.10)/(5.11), relative to 3 zeta* s",
                _max_or_nan(errors), STEADY_TOLERANCE, "largest over s"),
        at_most("figure 9: runs settled on the other branch than the locking test's", wrong_branch, 0.0),
        absolute("figure 9: phase at s = 0.98 s_c (locked)", PHASE_CODES[below.info["final_phase"]],
                 PHASE_CODES[LOCKED], 0.0, f"exact onset s_c = {s_onset:.6g} for psi = {FIGURE9_PSI:g}"),
        absolute("figure 9: phase at s = 1.02 s_c (sliding)", PHASE_CODES[above.info["final_phase"]],
                 PHASE_CODES[SLIDING], 0.0, f"(6.4) gives s_c = {onset_slope(FIGURE9_PSI):.6g}"),
    ]


# -- figure 10 and Table 3: dimensional runs ---------------------------------------

def speed_run(material: str, nu: float, alpha_deg: float, kappa_star: float, psi: float) -> dict:
    """One dimensional run released at rest on the asperities at the bottom; its speed against (6.1).

    Returns
    -------
    dict
        ``v`` = b Omega_b at the end (m/s), ``v_exact`` (6.1) with the exact
        fixed point, ``v_compact`` (6.1) as printed (5.12), ``v_star`` (6.2),
        the groups, ``settling_rate`` (1/tau), the final and the predicted
        ``phase``, the stop ``event``, ``settled``, ``t_end_tau`` and ``steps``.
    """
    apparatus = preset(material, nu=nu, alpha=math.radians(alpha_deg))
    params = apparatus.reduced_params
    contact = ContactParams(kappa_star, psi)
    trajectory = settled_run(params, contact, Initial(kappa=kappa_star, phi=math.pi), apparatus=apparatus)
    speed = dict(v_star=apparatus.v_star, alpha=apparatus.alpha, s=params.s, kappa_star=kappa_star, psi=psi)
    return {"material": material, "nu": nu, "alpha_deg": alpha_deg, "kappa_star": kappa_star,
            "zeta_star": contact.zeta_star, "settling_rate": settling_rate(params, contact),
            "sin_alpha": math.sin(apparatus.alpha), "s": params.s, "upsilon": params.upsilon,
            "v_star": apparatus.v_star, "v": apparatus.b * float(trajectory.columns["omega_b"][-1]),
            "v_exact": steady_speed(**speed, exact=True), "v_compact": steady_speed(**speed),
            "phase": trajectory.info["final_phase"], "steady_phase": steady_state(params.s, kappa_star, psi).phase,
            "event": trajectory.event, "settled": _settled(trajectory),
            "t_end_tau": float(trajectory.columns["t_tau"][-1]), "steps": trajectory.steps}


def figure10_runs(materials=MATERIALS, oils=OILS, slopes=SLOPES_DEG, zetas=ZETAS) -> list[dict]:
    return [speed_run(material, nu, alpha_deg, math.sqrt(1.0 - zeta**2), PSI_EXPERIMENT)
            for material in materials for nu in oils for alpha_deg in slopes for zeta in zetas]


def _speed_error(row: dict) -> float:
    return abs(row["v"] / row["v_exact"] - 1.0)


def figure10_checks(rows: list[dict]) -> list[Check]:
    """(6.1) with the exact fixed point to 1e-6; the collapse across oils; (6.1) as printed to O(zeta*^2)."""
    settled = [r for r in rows if r["settled"]]
    collapse = {}
    for r in settled:
        collapse.setdefault((r["material"], r["alpha_deg"], r["zeta_star"]), []).append(r["v"] / r["v_star"])
    spread = [max(v) / min(v) - 1.0 for v in collapse.values() if len(v) > 1]
    compact = [abs(r["v"] / r["v_compact"] - 1.0) / r["zeta_star"] ** 2 for r in settled]
    runaways = [r for r in rows if r["event"] == "runaway"]
    neither = [f"{r['material']} {r['alpha_deg']:g} deg {r['nu']:g} m^2/s zeta* {r['zeta_star']:g}"
               for r in rows if not r["settled"] and r["event"] != "runaway"]
    return [
        absolute(f"figure 10: runs of {len(rows)} that neither settled nor ran away", len(neither), 0.0, 0.0,
                 "each run ends in steady rolling or is stopped as a runaway; " + ("; ".join(neither) or "none")),
        Finding(f"figure 10: runs of {len(rows)} that ran away instead of settling", len(runaways),
                "; ".join(f"{r['material']} {r['alpha_deg']:g} deg, {r['nu']:g} m^2/s, zeta* {r['zeta_star']:g}"
                          for r in runaways) or "none"),
        at_most(f"figure 10: speeds b Omega_b of {len(settled)} settled runs vs (6.1)-(6.2), relative",
                _max_or_nan(map(_speed_error, settled)), STEADY_TOLERANCE,
                "(6.1) with the exact Omega_b of (5.10)/(5.11)"),
        at_most("figure 10: spread of V/V* across the oils at each material, slope and zeta*, relative",
                _max_or_nan(spread), 2.0 * STEADY_TOLERANCE,
                "V/V* = sin(alpha) Omega_b / (3 s) does not depend on nu; two runs, each within 1e-6"),
        at_most("figure 10: |V / V_(6.1) - 1| / zeta*^2, (6.1) with the compact (5.12)",
                _max_or_nan(compact), 1.0,
                "(5.12) is leading order in zeta*: locked, V/V_(6.1) - 1 = 2 zeta*^2/(3 kappa*^2), 0.69 zeta*^2 "
                "at zeta* = 0.2; sliding, (1/3 + s tan(psi)/(2 sqrt(1 - s^2))) zeta*^2/kappa*^2 over the "
                "Max(1/2, ...) >= 1/2 of (6.1), at most 0.72 zeta*^2 here (at the onset)"),
        at_most("figure 10: settled runs on the other branch than the locking test's",
                sum(r["phase"] != r["steady_phase"] for r in settled), 0.0),
    ]


def sandpaper_runs(grades=tuple(SANDPAPER)) -> list[dict]:
    """Table 3's roughness as kappa* = 1 - sigma/delta (6.3) on the steel apparatus."""
    delta = preset("steel").delta
    rows = []
    for grade in grades:
        row = speed_run("steel", SANDPAPER_OIL, SANDPAPER_SLOPE_DEG, 1.0 - SANDPAPER[grade] / delta, PSI_EXPERIMENT)
        rows.append({"grade": grade, "sigma": SANDPAPER[grade], **row})
    return rows


def sandpaper_checks(rows: list[dict]) -> list[Check]:
    settled = [r for r in rows if r["settled"]]
    return [at_most(f"Table 3: speeds of {len(settled)} sandpaper grades vs (6.1), relative",
                    _max_or_nan(map(_speed_error, settled)) if len(settled) == len(rows) else math.nan,
                    STEADY_TOLERANCE, "steel, 500 cSt, 2.4 degrees; (6.1) with the exact Omega_b")]


# -- the group ----------------------------------------------------------------------

def compute(quick: bool = False) -> dict:
    """Every run of the group and its checks; the figures and the paragraph read the runs by name.

    Returns ``checks``, the runs of figures 7-10 (``fig7``, its ``unlimited`` twin and its touch
    time ``t_touch``, ``fig8``, ``fig9`` with the onset slope ``s_onset``, ``fig10``) and of
    Table 3 (``sandpaper``).
    """
    fig8 = figure8_runs()
    fig7 = fig8[FIGURE7_PSI]
    t_touch, _ = _touch(fig7)
    samples = np.linspace(0.0, FIGURE7_T_PLOT, 1201)
    unlimited = unlimited_run(np.sort(np.append(samples, t_touch)))
    checks = figure7_checks(fig7, unlimited, t_touch) + figure8_checks(fig8)

    s_onset = onset_slope(FIGURE9_PSI, KAPPA_STAR)
    grid = (0.1, 0.5) if quick else tuple(np.round(np.arange(0.05, 0.91, 0.05), 2))
    fig9 = figure9_runs(sorted((*grid, 0.98 * s_onset, 1.02 * s_onset)))
    checks += figure9_checks(fig9, s_onset)

    if quick:
        fig10 = figure10_runs(oils=(OILS[0], OILS[-1]), slopes=(2.0, 5.0), zetas=(0.2,))
        sandpaper = sandpaper_runs(("220", "50"))
    else:
        fig10 = figure10_runs()
        sandpaper = sandpaper_runs()
    checks += figure10_checks(fig10) + sandpaper_checks(sandpaper)
    return {"checks": checks, "fig7": fig7, "unlimited": unlimited, "t_touch": t_touch, "fig8": fig8,
            "fig9": fig9, "s_onset": s_onset, "fig10": fig10, "sandpaper": sandpaper}
