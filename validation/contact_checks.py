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
from pathlib import Path

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
    compact_steady_rates,
    onset_of_sliding,
    steady_speed,
    steady_state,
)
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import simulate
from dynamics.trajectory import PHASE_CODES, Trajectory
from numerics.files import save_figure

from .checks import Check, Finding, absolute, at_most, relative

__all__ = [
    "FIGURE7", "KAPPA_STAR", "RELEASE", "PSI_EXPERIMENT", "SANDPAPER",
    "onset_slope", "run", "settled_run", "settling_rate", "steady_rate_error",
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


def sandpaper_table(rows: list[dict]) -> str:
    lines = ["| grade | sigma (mm) | kappa* | zeta* | V (6.1), (5.12) (mm/s) | V simulated (mm/s) | phase |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {r['grade']} | {1e3 * r['sigma']:g} | {r['kappa_star']:.4f} | "
              f"{r['zeta_star']:.3f} | {1e3 * r['v_compact']:.2f} | {1e3 * r['v']:.2f} | {r['phase']} |"
              for r in rows]
    return "\n".join(lines)


# -- figures ------------------------------------------------------------------------

def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def figure7(path, trajectory: Trajectory, unlimited: Trajectory,
            t_plot: float = FIGURE7_T_PLOT) -> None:
    """Figure 7: the path of A in the (kappa, phi) plane, kappa(t), phi(t), Omega_a(t) and Omega_b(t)."""
    plt = _pyplot()
    c, free = trajectory.columns, unlimited.columns
    shown, free_shown = c["t_tau"] <= t_plot, unlimited.t <= t_plot
    fig = plt.figure(figsize=(10, 6.2))
    grid = fig.add_gridspec(3, 2, width_ratios=(1, 1.4))
    ax = fig.add_subplot(grid[:, 0])
    circle = np.linspace(0.0, 2.0 * math.pi, 300)
    ax.plot(np.sin(circle), np.cos(circle), "k", lw=0.5)
    ax.plot(KAPPA_STAR * np.sin(circle), KAPPA_STAR * np.cos(circle), "k--", lw=0.4, label="kappa = kappa*")
    for kappa, phi, style, label in ((c["kappa"], c["phi"], "-", "rough contact"),
                                     (free["kappa"], free["phi"], ":", "unlimited")):
        ax.plot(kappa * np.sin(phi), kappa * np.cos(phi), style, color="C0", lw=0.8, label=label)
    ax.plot(RELEASE.kappa * math.sin(RELEASE.phi), RELEASE.kappa * math.cos(RELEASE.phi), "o", ms=4, label="release")
    ax.set_aspect("equal")
    ax.set_xlabel("kappa sin(phi)")
    ax.set_ylabel("kappa cos(phi)  (up)")
    ax.set_title("(a) path of the inner centre", fontsize=9)
    ax.legend(fontsize=7, loc="upper right")
    panels = (("kappa", "(b) kappa"), ("phi", "(c) phi (rad)"), (None, "(d) Omega x tau"))
    first = None
    for row, (name, label) in enumerate(panels):
        ax = fig.add_subplot(grid[row, 1], sharex=first)
        first = first or ax
        if name is None:
            for key, colour in (("omega_a", "C0"), ("omega_b", "C1")):
                ax.plot(c["t_tau"][shown], c[key][shown], color=colour, lw=0.8, label=key.replace("omega", "Omega"))
                ax.plot(unlimited.t[free_shown], free[key][free_shown], ":", color=colour, lw=0.8)
            ax.legend(fontsize=7)
            ax.set_xlabel("t / tau")
        else:
            ax.plot(c["t_tau"][shown], c[name][shown], lw=0.8)
            ax.plot(unlimited.t[free_shown], free[name][free_shown], ":", color="C0", lw=0.8)
        ax.set_ylabel(label, fontsize=9)
    fig.suptitle(f"Figure 7: s = {FIGURE7.s:g}, Upsilon = mu = 1, kappa* = {KAPPA_STAR:g}, psi = {FIGURE7_PSI:g}; "
                 "dotted: unlimited (smooth walls)", fontsize=9)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def figure8(path, runs: dict[float, Trajectory], t_plot: float = 60.0) -> None:
    """Figure 8: kappa, phi, Omega_a, Omega_b for the three psi, offset for clarity, contact dashed."""
    plt = _pyplot()
    names = (("kappa", 0.0), ("phi", 0.5), ("omega_a", 0.15), ("omega_b", 0.15))  # column, offset per run
    fig, axes = plt.subplots(len(names), 1, figsize=(7.5, 8), sharex=True)
    for k, (psi, trajectory) in enumerate(runs.items()):
        c = trajectory.columns
        shown = c["t_tau"] <= t_plot
        for ax, (name, offset) in zip(axes, names):
            ax.plot(c["t_tau"][shown], c[name][shown] + k * offset, color=f"C{k}", lw=0.8,
                    label=f"psi = {psi:g} ({trajectory.info['final_phase']})")
    t_touch, _ = _touch(next(iter(runs.values())))
    for ax, (name, offset) in zip(axes, names):
        ax.axvline(t_touch, color="k", ls="--", lw=0.6)
        ax.set_ylabel(name.replace("omega", "Omega") + (f" (+{offset:g} per run)" if offset else ""), fontsize=8)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("t / tau")
    fig.suptitle(f"Figure 8: s = {FIGURE7.s:g}, Upsilon = mu = 1, kappa* = {KAPPA_STAR:g}; dashed: contact",
                 fontsize=9)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def figure9(path, runs: dict[float, Trajectory]) -> None:
    """Figure 9: Omega_a/(3 zeta*) and Omega_b/(3 zeta*) against s; exact, compact (5.12), simulated."""
    plt = _pyplot()
    zeta = ContactParams(KAPPA_STAR, FIGURE9_PSI).zeta_star
    s_exact = np.linspace(1e-3, KAPPA_STAR - 1e-3, 400)
    exact = np.array([steady_state(s, KAPPA_STAR, FIGURE9_PSI)[2:4] for s in s_exact]) / (3.0 * zeta)
    s_compact = np.linspace(1e-3, 1.0 - 1e-3, 400)
    compact = np.array([compact_steady_rates(s, KAPPA_STAR, FIGURE9_PSI) for s in s_compact]) / (3.0 * zeta)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for j, (name, colour) in enumerate((("Omega_a", "C0"), ("Omega_b", "C1"))):
        ax.plot(s_exact, exact[:, j], color=colour, lw=1.0, label=f"{name}, fixed point (5.10)/(5.11)")
        ax.plot(s_compact, compact[:, j], "--", color=colour, lw=0.8, label=f"{name}, compact (5.12)")
        settled = [(s, _final(tr)[1 + j]) for s, tr in runs.items() if _settled(tr)]
        ax.plot([p[0] for p in settled], [p[1] / (3.0 * zeta) for p in settled], "o", color=colour, ms=4,
                mfc="none", label=f"{name}, simulated")
    away = [s for s, tr in runs.items() if not _settled(tr)]
    if away:
        ax.plot(away, np.zeros(len(away)), "kx", ms=5, label="runs away from the release")
    ax.axvline(onset_slope(FIGURE9_PSI), color="k", ls=":", lw=0.8, label="onset of sliding (6.4)")
    ax.set_xlabel("s")
    ax.set_ylabel("Omega / (3 zeta*)")
    ax.set_title(f"Figure 9: psi = {FIGURE9_PSI:g} rad, kappa* = {KAPPA_STAR:g}, Upsilon = mu = 1", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    save_figure(path, fig, dpi=120)
    plt.close(fig)


def figure10(path, rows: list[dict]) -> None:
    """Figure 10: (a) the speeds against the slope, (b) V/V* against sin(alpha) with the lines of (6.1)."""
    plt = _pyplot()
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.6))
    markers = dict(zip(OILS, "osD^"))
    colours = {"steel": "C0", "aluminium": "C3"}
    for r in rows:
        if not r["settled"]:
            continue
        style = dict(marker=markers[r["nu"]], color=colours[r["material"]], ms=4, ls="none",
                     mfc="none" if r["zeta_star"] < max(ZETAS) else colours[r["material"]])
        ax_a.semilogy(r["alpha_deg"], 1e3 * r["v"], **style)
        ax_b.plot(r["sin_alpha"], r["v"] / r["v_star"], **style)
    sin_alpha = np.linspace(math.sin(math.radians(0.5)), math.sin(math.radians(5.8)), 200)
    for material, colour in colours.items():
        apparatus = preset(material)
        s_per_sin = apparatus.s / math.sin(apparatus.alpha)  # s is proportional to sin(alpha) (2.12)
        for zeta, style in zip(ZETAS, (":", "-")):
            kappa_star = math.sqrt(1.0 - zeta**2)
            line = [steady_speed(1.0, math.asin(x), s_per_sin * x, kappa_star, PSI_EXPERIMENT) for x in sin_alpha]
            ax_b.plot(sin_alpha, line, style, color=colour, lw=0.8,
                      label=f"{material}, (6.1) zeta* = {zeta:g}")
    for nu, marker in markers.items():
        ax_a.plot([], [], marker, color="grey", ls="none", label=f"nu = {nu:g} m^2/s")
    ax_a.plot([], [], "o", color="grey", mfc="none", ls="none", label=f"open: zeta* = {min(ZETAS):g}")
    ax_a.set_xlabel("slope alpha (degrees)")
    ax_a.set_ylabel("V = b Omega_b (mm/s)")
    ax_a.set_title("(a) simulated steady speeds", fontsize=9)
    ax_a.legend(fontsize=7)
    ax_b.set_xlabel("sin(alpha)")
    ax_b.set_ylabel("V / V*")
    ax_b.set_title(f"(b) scaled by V* (6.2); psi = {PSI_EXPERIMENT:.3g} rad (steel slides above 3 degrees)",
                   fontsize=9)
    ax_b.legend(fontsize=7)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


# -- the group ----------------------------------------------------------------------

def run(outdir, quick: bool = False):
    """All rough-contact checks; returns (checks, figure file names, a markdown paragraph)."""
    outdir = Path(outdir)
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

    figures = []
    if not quick:
        for name, draw, data in (("contact_figure7.png", figure7, (fig7, unlimited)),
                                 ("contact_figure8.png", figure8, (fig8,)),
                                 ("contact_figure9.png", figure9, (fig9,)),
                                 ("contact_figure10.png", figure10, (fig10,))):
            draw(outdir / name, *data)
            figures.append(name)
    return checks, figures, _paragraph(fig8, t_touch, fig9, s_onset, fig10, sandpaper)


def _paragraph(fig8, t_touch, fig9, s_onset, fig10, sandpaper) -> str:
    """The group's summary, every number in it measured by this run."""
    steady = steady_state(FIGURE7.s, KAPPA_STAR, FIGURE7_PSI)
    outcomes = ", ".join(f"psi = {psi:g} {tr.info['final_phase']}" for psi, tr in fig8.items())
    zeta9 = ContactParams(KAPPA_STAR, FIGURE9_PSI).zeta_star
    compact9 = _max_or_nan(
        max(abs(np.subtract(compact_steady_rates(s, KAPPA_STAR, FIGURE9_PSI),
                            steady_state(s, KAPPA_STAR, FIGURE9_PSI)[2:4]))) / (3.0 * zeta9 * s)
        for s, tr in fig9.items() if _settled(tr))
    away9 = [s for s, tr in fig9.items() if not _settled(tr)]
    settled10 = [r for r in fig10 if r["settled"]]
    worst = max(settled10, key=lambda r: abs(r["v"] / r["v_compact"] - 1.0))
    rates = [r["settling_rate"] for r in settled10]
    text = (
        f"Figure 7 (s = 1/4, Upsilon = mu = 1, kappa* = {KAPPA_STAR:g}, psi = {FIGURE7_PSI:g}): released at rest "
        f"from (kappa, phi) = ({RELEASE.kappa:g}, {RELEASE.phi:g}), the inner cylinder touches at t = "
        f"{t_touch:.4g} tau on the unlimited solution and settles on the sliding fixed point Omega_a = "
        f"{steady.omega_a:.5g}, Omega_b = {steady.omega_b:.5g} (1/tau) of (5.11) as corrected (erratum 6; the "
        f"printed form is not a fixed point). Figure 8 ends {outcomes}; on locking Omega_a jumps to Omega_b. "
        f"Figure 9 (psi = {FIGURE9_PSI:g}): the simulated steady rates lie on the exact fixed points and switch "
        f"from locked to sliding at s_c = {s_onset:.4f} (the exact locking test), against "
        f"{onset_slope(FIGURE9_PSI):.4f} from (6.4); the compact (5.12) is off by up to {compact9:.1%} of "
        f"3 zeta* s at zeta* = {zeta9:.3f}."
    )
    if away9:
        text += (f" From this release the runs with s >= {min(away9):g} swing over and run away (section 3.3): "
                 "their fixed point exists but the release is outside its basin.")
    text += (
        f" Figure 10(b): {len(settled10)} of {len(fig10)} dimensional runs (steel and aluminium, nu = "
        f"{', '.join(f'{nu:g}' for nu in sorted({r['nu'] for r in fig10}))} m^2/s, slopes "
        f"{min(r['alpha_deg'] for r in fig10):g}-{max(r['alpha_deg'] for r in fig10):g} degrees, zeta* = "
        f"{', '.join(f'{z:g}' for z in sorted({round(r['zeta_star'], 3) for r in fig10}))}, psi = "
        f"{PSI_EXPERIMENT:.4f} rad) settle, with b Omega_b equal to (6.1) to "
        f"{_max_or_nan(map(_speed_error, settled10)):.1e} and V/V* the same for every oil; (6.1) with the compact "
        f"(5.12) differs from the exact speed by up to {abs(worst['v'] / worst['v_compact'] - 1.0):.1%} (zeta* = "
        f"{worst['zeta_star']:g}). Their slowest modes decay at {min(rates, default=math.nan):.3g} to "
        f"{_max_or_nan(rates):.3g} per tau."
    )
    away10 = {}
    for r in fig10:
        if not r["settled"]:
            away10.setdefault((r["material"], r["alpha_deg"], r["zeta_star"]), []).append(r["nu"])
    if away10:
        text += " Runs that run away instead (the aluminium cylinder did at 5 degrees, figure 6): " + "; ".join(
            f"{m} at {a:.3g} degrees, zeta* = {z:g}, nu = {', '.join(f'{nu:g}' for nu in nus)}"
            for (m, a, z), nus in away10.items()) + "."
    ratio = [r["v"] / r["v_compact"] for r in sandpaper]
    text += (
        f"\n\nTable 3's roughness on the steel cylinder in 500 cSt oil at {SANDPAPER_SLOPE_DEG:g} degrees "
        f"(V* = {sandpaper[0]['v_star']:.3g} m/s, s = {sandpaper[0]['s']:.3f}), kappa* = 1 - sigma/delta (6.3): "
        f"the simulated speed is the exact fixed point's, which the compact (6.1) used to collapse figure 11 "
        f"underestimates by a factor {min(ratio):.3f}-{max(ratio):.3f} as zeta* grows (locked: "
        f"(2 + kappa*^2)/(3 kappa*^2)).\n\n" + sandpaper_table(sandpaper)
    )
    return text
