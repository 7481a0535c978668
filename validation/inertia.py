r"""Where quasi-steady Stokes fails: steady Navier-Stokes forces against the Reynolds number.

The force models assume quasi-steady Stokes flow. This study solves the steady
Navier-Stokes equations in the frame of the line of centres
(:mod:`lubrication.navier_stokes`) and measures the relative error of the
force on the inner cylinder, |F - F_Stokes| over the Stokes force scale of the
wall rotations |R_chi_a W_a| + |R_chi_b W_b| (|f_chi| when the walls turn in
the same sense; it cannot cancel when they do not), and of its torque, for

(i) inner rotation W_a, (ii) outer rotation W_b,
(iii) the runaway: Omega_a ~ Omega_b ~ chi', a near-rigid rotation of the
      whole device at chi' plus a slow relative flow (W_a, W_b),
(iv) the steady rolling state (3.2): W_a / W_b = (1 - kappa^2)/(1 + 2 kappa^2), chi' = 0,

W = Omega - chi' the wall rotations relative to the line of centres.

* First order, every motion: the O(Re) correction (a pure f_eps) from the
  reciprocal theorem, tabulated (:mod:`lubrication.inertia_table`) for
  kappa in [0, 0.999] and delta/a in [0.01, 1]; its largest value per Re*
  over every direction of (W_a, W_b), which sets the run guard; its
  kappa -> 0 limit against the thin-gap closed form (the regime of DiPrima &
  Stuart 1972) and the exact small-eccentricity solution
  (:mod:`lubrication.inertia`).
* Newton continuation in Re up to Re* = Re delta/a = 30 (:func:`sweep_plan`):
  delta/a = 0.1 and the apparatus' 0.406 (Table 2) at kappa = 0.3, 0.6, 0.9
  for (i), (ii), (iv), and delta/a = 0.01 for (iv) at kappa = 0.3; where the
  error reaches 1% and 10%, how far the first-order error holds, and what the
  inertia-corrected force model (:mod:`lubrication.registry`,
  ``inertia="first-order"``) leaves.
* (iii): in the frame of the line of centres the fictitious forces only
  shift the pressure, so the runaway is (W_a, W_b) plus the exact force
  -m''_a chi'^2 eps e_eps; checked with the fictitious forces discretised at
  chi' = 0, 3 and 10 W, and the force that (2.1)-(2.2) therefore miss is
  sized for the apparatus against its buoyant weight.
* The paper's aluminium runaway (figure 6) at 5 and 10 degrees followed to
  3 s past the Reynolds limit (``on_invalid = "warn"``), with the estimated
  inertial error along it, under (2.1)-(2.2) as printed, with the frame terms
  (``frame_terms = "quasi-steady"``) and with the first inertial correction
  (:func:`runaway_trajectories`).
* The unsteady inertia that no steady solve sees, by its Stokes number.

Run ``python -m validation.inertia`` to write ``docs/inertia/`` (figures,
``inertia.json``, ``inertia.md``; about nine minutes on two cores);
``python generators/inertia_table.py`` rebuilds
:mod:`lubrication.inertia_table` (generators/README.md).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from dynamics.analysis import centripetal_mass

from .checks import Check, at_least, at_most, relative

__all__ = ["APPARATUS", "DELTAS", "DIRECTIONS", "KAPPAS", "LEVELS", "OILS", "RUNAWAY_MODELS", "RUNAWAY_SLOPES",
           "SWEEP_REDUCED", "TABLE_PROBES", "apparatus_frame_force",
           "centripetal_mass", "checks_of", "continuation_sweeps", "corrected_model_error", "figure",
           "first_order_survey", "run", "runaway_check", "runaway_comparison", "runaway_figure",
           "runaway_trajectories", "small_kappa_comparison", "stokes_numbers", "sweep_plan", "table_accuracy",
           "thresholds", "write_outputs"]

#: Table 2: a = 0.8 cm, b = 1.125 cm.
APPARATUS = {"a_m": 0.008, "b_m": 0.01125, "delta_over_a": 0.325 / 0.8}
DELTAS = (0.01, 0.1, APPARATUS["delta_over_a"])
KAPPAS = (0.3, 0.6, 0.9)

#: Off-node points where the interpolated table is compared with fresh solves.
TABLE_PROBES = ((0.05, 0.05), (0.45, 0.15), (0.65, 0.35), (0.85, 0.5), (0.93, 0.8), (0.97, 0.25), (0.75, 0.02))

def _motions(kappa: float) -> dict[str, tuple[float, float]]:
    """(W_a, W_b) of the study's motions, relative to the line of centres."""
    return {"inner": (1.0, 0.0), "outer": (0.0, 1.0),
            "rolling": ((1.0 - kappa**2) / (1.0 + 2.0 * kappa**2), 1.0)}


#: Reduced Reynolds numbers Re* = Re delta/a of the continuation sweeps.
SWEEP_REDUCED = (0.1, 0.3, 1.0, 3.0, 10.0, 30.0)


def sweep_plan() -> list[tuple[float, float, str]]:
    """(delta/a, kappa, motion) of the continuation sweeps.

    Every motion and kappa at delta/a = 0.1 and the apparatus' gap. At
    delta/a = 0.01, whose inertial mesh is three times larger, the rolling
    state (both walls turning) at kappa = 0.3 only: at kappa = 0.9 that
    sweep alone took 100 s (it reached Re* = 10, the first-order error
    holding to 1e-3 up to Re* = 3). The first-order survey covers every
    motion and kappa there.
    """
    plan = [(DELTAS[0], KAPPAS[0], "rolling")]
    plan += [(d, kappa, name) for d in DELTAS[1:] for kappa in KAPPAS for name in _motions(kappa)]
    return plan
#: Frame rates of the runaway check, in units of the relative rotation W.
RUNAWAY_SPINS = (0.0, 3.0, 10.0)
#: The four silicone oils of Table 1 (m^2/s).
OILS = (5e-5, 2e-4, 3.5e-4, 5e-4)
#: Relative error levels whose Reynolds numbers are reported.
LEVELS = (0.01, 0.1)


def _g_of(kappa: float, d: float, re_a: float, re_b: float) -> float:
    """First-order relative error per unit Re* (the table's, exact at its nodes)."""
    from lubrication.inertia import inertial_error_estimate

    return inertial_error_estimate(kappa, d, re_a, re_b) / (d * max(abs(re_a), abs(re_b)))


#: Directions of (Re_a, Re_b) scanned for the largest G: (cos t, sin t), t in [0, pi)
#: (G is even in the motion).
DIRECTIONS = 720


def first_order_survey() -> dict:
    """G = (relative force error) / Re* at first order, at the table's nodes (finite-element values).

    Per motion (inner, outer, rolling, co-rotating W_a = W_b), and the largest G
    over every direction of (W_a, W_b) and every kappa, for each delta/a
    (``g_max``, with the kappa and the ratio U_b/U_a = W_b b / (W_a a) where it occurs).
    """
    from lubrication.inertia import inertial_error_estimate
    from lubrication.inertia_table import DELTA_NODES, KAPPA_NODES

    out = {"kappa": [float(k) for k in KAPPA_NODES], "delta_over_a": [float(d) for d in DELTA_NODES]}
    for name in ("inner", "outer", "rolling", "co-rotating"):
        rows = []
        for d in DELTA_NODES:
            row = []
            for k in KAPPA_NODES:
                w_a, w_b = _motions(k).get(name, (1.0, 1.0))
                # Re_a = W_a a delta/nu, Re_b = W_b b delta/nu with a = 1
                row.append(_g_of(k, d, w_a, w_b * (1.0 + d)))
            rows.append(row)
        out[name] = rows
    angle = np.pi * np.arange(DIRECTIONS) / DIRECTIONS
    re_a, re_b = np.cos(angle), np.sin(angle)
    g_max, where = [], []
    for d in DELTA_NODES:
        g = np.array([inertial_error_estimate(np.full(angle.size, k), d, re_a, re_b)
                      / (d * np.maximum(np.abs(re_a), np.abs(re_b))) for k in KAPPA_NODES])
        i, j = np.unravel_index(int(np.argmax(g)), g.shape)
        g_max.append(float(g[i, j]))
        where.append({"kappa": float(KAPPA_NODES[i]), "u_b_over_u_a": float(re_b[j] / re_a[j])})
    out["g_max"] = g_max
    out["g_max_at"] = where
    return out


def small_kappa_comparison() -> list[dict]:
    """kappa -> 0: thin-gap closed form, exact small-eccentricity solution and finite elements.

    G against the scale |f_chi,a| + |f_chi,b| (the Stokes f_chi of each wall's
    rotation, which do not cancel); the counter-rotating motion U_b = -U_a, whose
    thin-gap Stokes f_chi vanishes, shows why.
    """
    from lubrication.inertia import small_eccentricity_forces, thin_gap_small_kappa

    rows = []
    for d in DELTAS:
        b = 1.0 + d
        motions = (("inner", (1.0, 0.0)), ("outer", (0.0, 1.0)), ("co-rotating", (1.0, 1.0)),
                   ("counter-rotating", (1.0, -1.0 / b)))
        for name, (w_a, w_b) in motions:
            speed = max(abs(w_a), abs(w_b) * b)
            re = 1e-3
            f0 = small_eccentricity_forces(d, 0.0, w_a, w_b)
            f1 = small_eccentricity_forces(d, re, w_a, w_b)
            # each wall's Stokes f_chi in the units of f0 (mu V, V = speed)
            scale = sum(abs(small_eccentricity_forces(d, 0.0, *wall)[1]) * s_wall / speed
                        for wall, s_wall in (((w_a, 0.0), abs(w_a)), ((0.0, w_b), abs(w_b) * b)) if s_wall > 0.0)
            exact = (f1[0] - f0[0]) / (re * d) / scale
            f_eps1, _ = thin_gap_small_kappa(w_a, w_b * b, delta=d)
            _, f_chi_abs = thin_gap_small_kappa(abs(w_a), abs(w_b) * b, delta=d)
            thin = abs(f_eps1) / f_chi_abs / (speed * d * d)
            fe = _g_of(0.0, d, w_a, w_b * b)
            rows.append({"delta_over_a": d, "motion": name, "thin_gap": thin, "exact": abs(exact),
                         "finite_elements": fe, "stokes_f_chi_over_scale": abs(f0[1]) / scale})
    return rows


def _crossing(reynolds: np.ndarray, error: np.ndarray, level: float) -> float:
    """Re at which ``error`` first reaches ``level``, log-log interpolated; NaN if never."""
    above = np.flatnonzero(error >= level)
    if above.size == 0 or above[0] == 0:
        return math.nan
    i = above[0]
    x0, x1 = math.log(reynolds[i - 1]), math.log(reynolds[i])
    y0, y1 = math.log(error[i - 1]), math.log(error[i])
    return math.exp(x0 + (math.log(level) - y0) * (x1 - x0) / (y1 - y0))


def _corrected_error(sweep) -> np.ndarray:
    """|F - F_Stokes - F^(1)| / |F_Stokes|: what the inertia-corrected force model leaves.

    F^(1) is the tabulated first inertial correction (lubrication.inertia.first_order_f_eps,
    exact at the table's nodes, where every sweep lies), in the sweep's units: a = 1,
    mu = 1, V = 1, so rho = Re / (delta/a) per unit length.
    """
    from lubrication.inertia import first_order_f_eps

    d = sweep.delta_over_a
    first = first_order_f_eps(sweep.kappa, d, 1.0, sweep.reynolds / d, 1.0, sweep.motion[1], sweep.motion[2])
    residual = sweep.inner[:, :2] - sweep.frame()[:, :2] - sweep.inner[0, :2]
    residual[:, 0] -= first
    return np.linalg.norm(residual, axis=1) / np.linalg.norm(sweep.inner[0, :2])


def continuation_sweeps() -> list[dict]:
    """Newton continuation in Re for each (delta/a, kappa, motion) of :func:`sweep_plan`."""
    from lubrication.navier_stokes import inertial_sweep

    out = []
    for d, kappa, name in sweep_plan():
        reynolds = np.array(SWEEP_REDUCED) / d
        w_a, w_b = _motions(kappa)[name]
        sweep = inertial_sweep(d, kappa, reynolds, w_a=w_a, w_b=w_b)
        error, torque = sweep.relative_error(), sweep.torque_error()
        re_a, re_b = sweep.motion[1], sweep.motion[2] * (1.0 + d)
        g = _g_of(kappa, d, re_a, re_b)
        reduced = sweep.reynolds * d
        out.append({
            "delta_over_a": d, "kappa": kappa, "motion": name, "w_a": w_a, "w_b": w_b,
            "reynolds": sweep.reynolds[1:].tolist(), "reduced_reynolds": reduced[1:].tolist(),
            "force_error": error[1:].tolist(), "corrected_error": _corrected_error(sweep)[1:].tolist(),
            "torque_error": torque[1:].tolist(),
            "first_order_g": g, "first_order_ratio": (error[1:] / (g * reduced[1:])).tolist(),
            "stopped": bool(sweep.stopped), "mesh": [sweep.n_around, sweep.n_across],
            "max_reduced_reynolds": float(reduced[-1]),
            "crossings": {str(level): _crossing(reduced[1:], error[1:], level) for level in LEVELS},
            "newton_iterations": sweep.newton_iterations, "dofs": sweep.dofs,
            "wall_time_s": sweep.wall_time_s})
    return out


def runaway_check(re_rel: float = 10.0) -> list[dict]:
    """(iii): the same relative co-rotation W in frames turning at chi' = s W, fictitious forces discretised.

    The dynamic force (total less -m''_a chi'^2 eps e_eps) must not depend on
    s; the absolute, shear and rotation Reynolds numbers grow with s.
    """
    from lubrication.navier_stokes import inertial_sweep

    d, kappa = APPARATUS["delta_over_a"], 0.6
    rows = []
    for spin in RUNAWAY_SPINS:
        sweep = inertial_sweep(d, kappa, [re_rel], w_a=1.0, w_b=1.0, chi_dot=spin)
        b = 1.0 + d
        # units: V = W b = 1 (a = 1), Re = V delta / nu, so nu = delta / Re
        nu = d / re_rel
        w = 1.0 / b
        chi = spin * w
        rows.append({"spin": spin, "relative_error": float(sweep.relative_error()[-1]),
                     "dynamic": (sweep.inner[-1, :2] - sweep.frame()[-1, :2]).tolist(),
                     "reynolds_relative": re_rel,
                     "reynolds_absolute": (chi + w) * b * d / nu,
                     "reynolds_shear": abs((chi + w) * (1.0 - b)) * d / nu,
                     "rotation_number": chi * d * d / nu})
    return rows


def apparatus_frame_force() -> list[dict]:
    """Size of the rotating-frame force that (2.1)-(2.2) miss, against the buoyant weight m'_a g.

    Delta f = m''_a (1 + m''_a/m_f) eps chi'^2 (lubrication.navier_stokes). For
    kappa = 0.5 and 0.9: the orbit rates chi' at which it is 1% and 10% of
    m'_a g, and the absolute wall Reynolds number Omega b delta / nu there for
    each oil (with Omega = chi', the runaway's near-rigid rotation).
    """
    from dynamics.apparatus import PRESETS

    rows = []
    for name, ap in PRESETS.items():
        factor = ap.m_a_displaced * (1.0 + ap.m_a_displaced / ap.m_f)
        for kappa in (0.5, 0.9):
            eps = kappa * ap.delta
            for level in LEVELS:
                chi = math.sqrt(level * ap.m_a_reduced * ap.g / (factor * eps))
                rows.append({"apparatus": name, "kappa": kappa, "level": level, "chi_dot": chi,
                             "m_eff_over_m_reduced": ap.m_eff / ap.m_a_reduced,
                             "reynolds_absolute": {f"{nu:g}": chi * ap.b * ap.delta / nu for nu in OILS}})
    return rows


def stokes_numbers() -> list[dict]:
    """Unsteady inertia: the Stokes number delta^2 / (nu tau) of each apparatus and oil."""
    from dynamics.apparatus import preset

    rows = []
    for name in ("steel", "aluminium"):
        for nu in OILS:
            ap = preset(name, nu=nu)
            rows.append({"apparatus": name, "nu": nu, "tau_s": ap.tau,
                         "stokes_number": ap.delta**2 / (nu * ap.tau)})
    return rows


#: The paper's aluminium runaway (figure 6) on two slopes.
RUNAWAY_SLOPES = (5.0, 10.0)
#: (label, frame_terms, inertia-corrected forces) of each run; the forces are the closed forms (2.5)-(2.7).
RUNAWAY_MODELS = (("paper", "paper", False), ("quasi-steady", "quasi-steady", False),
                  ("quasi-steady+inertia", "quasi-steady", True))
RUNAWAY_T_END = 3.0
#: Rows of the stored runs (s), and the times of the report's tables.
RUNAWAY_OUTPUT = 1e-3
RUNAWAY_TIMES = (0.02, 0.06, 0.1, 0.25, 0.5, 1.0, 2.0, 3.0)
#: Window of the centripetal-mass balance (s): late, where the line of centres turns fast.
RUNAWAY_WINDOW = (2.0, 3.0)
#: The late acceleration is fitted to X_b from this time on (s), after the first swing.
RUNAWAY_FIT_START = 1.0


def _runaway_series(apparatus, columns: dict) -> dict:
    """The run's columns and its inertia measures (dynamics.equations.limits), on a grid for the record."""
    from dynamics.equations import limits

    t, index = np.unique(columns["t"], return_index=True)
    values = {"x_b": columns["x_b"], "one_minus_kappa": columns["one_minus_kappa"],
              "omega_b": columns["omega_b"], "phi_dot": columns["phi_dot"],
              "reduced_reynolds": limits.reduced_reynolds(apparatus, columns),
              "estimated_force_error": limits.estimated_force_error(apparatus, columns),
              "frame_force_over_weight": limits.frame_force_over_weight(apparatus, columns),
              "first_order_force_over_weight": limits.first_order_force_over_weight(apparatus, columns)}
    grid = np.unique(np.concatenate([np.geomspace(2e-3, RUNAWAY_T_END, 90), np.linspace(0.0, RUNAWAY_T_END, 61),
                                     RUNAWAY_TIMES]))
    grid = grid[grid <= t[-1]]
    return {"t": grid.tolist(), **{k: np.interp(grid, t, v[index]).tolist() for k, v in values.items()}}


def runaway_trajectories() -> list[dict]:
    """The aluminium runaway at 5 and 10 degrees followed to 3 s past the Reynolds limit, with its inertial error.

    The aluminium apparatus (Table 2, nu = 2e-4 m^2/s as in figure 6) released from
    rest at kappa = 0.5, phi = 0.5 rad (the default scene's start), full equations
    with the closed forms (2.5)-(2.7), the default Reynolds limit with
    ``on_invalid = "warn"``; three treatments of the fluid's inertia
    (:data:`RUNAWAY_MODELS`): (2.1)-(2.2) as printed, with the frame terms, and with
    the frame terms plus the first inertial correction of the relative flow.
    """
    from dynamics import Initial, simulate
    from dynamics.apparatus import preset
    from dynamics.equations.limits import Limits
    from lubrication.registry import kernel_model

    out = []
    for deg in RUNAWAY_SLOPES:
        ap = preset("aluminium", alpha=math.radians(deg))
        for label, frame_terms, inertia in RUNAWAY_MODELS:
            model = kernel_model("closed-form", inertia="first-order" if inertia else "none", rho=ap.rho)
            run = simulate(ap, Initial(0.5, 0.5), RUNAWAY_T_END, forces=model, frame_terms=frame_terms,
                           limits=Limits(on_invalid="warn", max_turns=1000.0), output_interval=RUNAWAY_OUTPUT)
            c = run.columns
            late = c["t"] >= RUNAWAY_FIT_START
            accel = 2.0 * np.polyfit(c["t"][late], c["x_b"][late], 2)[0]
            last = c["t"] >= RUNAWAY_T_END - 0.5
            omega_b_mean = float(np.trapezoid(c["omega_b"][last], c["t"][last]) / (c["t"][-1] - c["t"][last][0]))
            out.append({"slope_deg": deg, "model": label, "forces": run.forces, "frame_terms": frame_terms,
                        "status": run.status, "message": run.message, "t_last": float(c["t"][-1]),
                        "steps": run.steps, "wall_time_s": run.wall_time_s,
                        "limits_passed": [{"t": p["t"], "reason": p["reason"]}
                                          for p in run.info.get("limits_passed", [])],
                        "inertia": run.info["inertia"], "acceleration": float(accel),
                        "omega_b_mean_last_half_second": omega_b_mean,
                        "omega_b_swing_last_half_second": float(np.ptp(c["omega_b"][last]) / omega_b_mean),
                        "acceleration_observed_law": 2.0 * ap.g * math.sin(ap.alpha) / 3.0,
                        "acceleration_311": ap.M * ap.g * math.sin(ap.alpha) / (ap.M + ap.m_b + 0.5 * ap.m_a),
                        "centripetal_mass": centripetal_mass(ap, c, *RUNAWAY_WINDOW),
                        "m_eff": ap.m_eff, "m_a_reduced": ap.m_a_reduced,
                        "series": _runaway_series(ap, c)})
    return out


def runaway_comparison(runs: list[dict]) -> list[dict]:
    """Per slope, at 3 s: what the frame terms (against the printed equations) and the first inertial
    correction (against the frame terms alone) change: X_b, the mean Omega_b over the last 0.5 s
    (Omega_b itself swings within each turn), the late acceleration, and 1 - kappa (as a ratio)."""
    out = []
    for deg in RUNAWAY_SLOPES:
        by = {r["model"]: r for r in runs if r["slope_deg"] == deg}

        def change(new, old):
            a, b = by[new], by[old]
            return {"x_b": a["series"]["x_b"][-1] / b["series"]["x_b"][-1] - 1.0,
                    "omega_b_mean": a["omega_b_mean_last_half_second"] / b["omega_b_mean_last_half_second"] - 1.0,
                    "omega_b_final": a["series"]["omega_b"][-1] / b["series"]["omega_b"][-1] - 1.0,
                    "acceleration": a["acceleration"] / b["acceleration"] - 1.0,
                    "gap_ratio": a["series"]["one_minus_kappa"][-1] / b["series"]["one_minus_kappa"][-1]}

        out.append({"slope_deg": deg, "frame_terms": change("quasi-steady", "paper"),
                    "first_order_inertia": change("quasi-steady+inertia", "quasi-steady"),
                    "m_eff_over_m_reduced_squared": (by["paper"]["m_eff"] / by["paper"]["m_a_reduced"]) ** 2})
    return out


def table_accuracy() -> dict:
    """The interpolated error estimate against fresh solves at off-node points."""
    from lubrication.inertia import inertial_error_estimate
    from lubrication.navier_stokes import first_inertial_correction

    worst_rel, worst_abs, rows = 0.0, 0.0, []
    for kappa, d in TABLE_PROBES:
        c = first_inertial_correction(d, kappa)
        for re_a, re_b in ((1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, -0.3), (1.0, -1.0)):
            # (eps'/a, W_a, W_b) in units nu/(a delta); scale |R_chi_a W_a| + |R_chi_b W_b|
            m = np.array([0.0, re_a, re_b / (1.0 + d)])
            scale = abs(c.stokes[1, 1] * m[1]) + abs(c.stokes[1, 2] * m[2])
            direct = float(np.hypot(m @ c.c_eps @ m, m @ c.c_chi @ m) / (d * scale))
            estimate = inertial_error_estimate(kappa, d, re_a, re_b)
            reduced = d * max(abs(re_a), abs(re_b))
            worst_abs = max(worst_abs, abs(estimate - direct) / reduced)
            if direct > 1e-2 * reduced:  # relative error where G is not near a sign change
                worst_rel = max(worst_rel, abs(estimate / direct - 1.0))
            rows.append({"kappa": kappa, "delta_over_a": d, "re_a": re_a, "re_b": re_b,
                         "direct": direct, "estimate": estimate})
    return {"probes": rows, "max_relative": worst_rel, "max_absolute_g": worst_abs}


def checks_of(result: dict) -> list[Check]:
    """The study's headline numbers as checks."""
    checks = []
    for row in result["small_kappa"]:
        d, name = row["delta_over_a"], row["motion"]
        checks.append(relative(f"kappa -> 0, delta/a = {d:g}, {name}: finite elements against the exact "
                               "small-eccentricity solution", row["finite_elements"], row["exact"], 1e-3,
                               "G = first-order relative force error per Re*; FE at kappa = 1e-4"))
        if d == DELTAS[0]:
            checks.append(relative(f"kappa -> 0, delta/a = {d:g}, {name}: exact solution against the "
                                   "thin-gap closed form", row["exact"], row["thin_gap"], 3.0 * d,
                                   "departure O(delta/a)"))
    for row in result["sweeps"]:
        ratio = np.array(row["first_order_ratio"])
        small = np.array(row["reduced_reynolds"]) <= 1.0 + 1e-9
        checks.append(at_most(
            f"first order against Newton for Re* <= 1: delta/a = {row['delta_over_a']:g}, "
            f"kappa = {row['kappa']:g}, {row['motion']}", float(np.max(np.abs(ratio[small] - 1.0))), 0.01,
            "max over Re* <= 1 of |error / (G Re*) - 1|"))
    for level, cap in ((1.0, 1e-3), (3.0, 5e-3)):
        worst = max(e for row in result["sweeps"] for e, r in zip(row["corrected_error"], row["reduced_reynolds"])
                    if r <= level + 1e-9)
        checks.append(at_most(f"inertia-corrected forces against Newton for Re* <= {level:g}, every sweep", worst,
                              cap, "|F - F_Stokes - F^(1)| / |F_Stokes|: what the forces with inertia 'first-order' leave"))
    for run in result["runaway_trajectories"]:
        name = f"aluminium runaway at {run['slope_deg']:g} deg, {run['model']}"
        checks.append(at_least(f"{name}: followed past the Reynolds limit to t (s)", run["t_last"], RUNAWAY_T_END,
                               "on_invalid = 'warn'", slack=1e-9))
        if run["forces"] != "closed-form":  # the balance has the squeeze force alone along e_eps
            continue
        mass = run["m_eff"] if run["frame_terms"] == "paper" else run["m_a_reduced"]
        checks.append(relative(f"{name}: centripetal mass of (2.2) from the rows, {RUNAWAY_WINDOW[0]:g}-"
                               f"{RUNAWAY_WINDOW[1]:g} s", run["centripetal_mass"], mass, 2e-3,
                               "m_eff as printed, m'_a with the frame terms; trapezoids over rows 1 ms apart "
                               "(20-50 rows a turn)"))
    spread = [r["relative_error"] for r in result["runaway"]]
    checks.append(at_most("runaway: dynamic force error independent of the frame rate chi' = 0, 3, 10 W",
                          (max(spread) - min(spread)) / max(spread), 0.01,
                          "fictitious forces discretised; the exact statement is that they only shift "
                          "the pressure (the difference is their Q1 pressure error)"))
    acc = result["table_accuracy"]
    checks.append(at_most("error estimate: interpolation against fresh solves, relative", acc["max_relative"],
                          0.03, f"{len(acc['probes'])} probe motions off the nodes, where G > 0.01"))
    checks.append(at_most("error estimate: interpolation against fresh solves, absolute in G",
                          acc["max_absolute_g"], 1e-3, "G = relative error / Re*; G <= 0.1"))
    g_max = result["first_order"]["g_max"]
    checks.append(at_most("largest G over every wall motion, kappa and delta/a >= 0.01", max(g_max), 0.1,
                          "thin-gap limit 1/10 at U_a = U_b (closed form)"))
    return checks


def run() -> dict:
    """Every number of the study (a few minutes on two cores)."""
    start = time.perf_counter()
    timings = {}
    result = {}
    for key, func in (("first_order", first_order_survey), ("small_kappa", small_kappa_comparison),
                      ("sweeps", continuation_sweeps), ("runaway", runaway_check),
                      ("runaway_trajectories", runaway_trajectories),
                      ("apparatus_frame_force", apparatus_frame_force), ("stokes_numbers", stokes_numbers),
                      ("table_accuracy", table_accuracy)):
        t = time.perf_counter()
        result[key] = func()
        timings[key] = time.perf_counter() - t
    result["thresholds"] = thresholds(result["first_order"])
    result["runaway_comparison"] = runaway_comparison(result["runaway_trajectories"])
    result["corrected_model_error"] = corrected_model_error(result["sweeps"])
    result["checks"] = [c.as_dict() for c in checks_of(result)]
    result["wall_time_s"] = {**timings, "total": time.perf_counter() - start}
    return result


def corrected_model_error(sweeps: list[dict]) -> dict:
    """The largest error the inertia-corrected force model leaves, over the sweeps, at each Re* reached."""
    out = {}
    for level in SWEEP_REDUCED:
        values = [e for row in sweeps for e, r in zip(row["corrected_error"], row["reduced_reynolds"])
                  if abs(r - level) < 1e-9 * level]
        plain = [e for row in sweeps for e, r in zip(row["force_error"], row["reduced_reynolds"])
                 if abs(r - level) < 1e-9 * level]
        if values:
            out[f"{level:g}"] = {"corrected": max(values), "plain": max(plain)}
    return out


def thresholds(first_order: dict) -> dict:
    """Re* (and Re = Re* a/delta) where the worst first-order error over kappa and wall motion is 1% and 10%."""
    out = {}
    for d, g in zip(first_order["delta_over_a"], first_order["g_max"]):
        out[f"{d:g}"] = {"g_max": g, **{f"reduced_{lv:g}": lv / g for lv in LEVELS},
                         **{f"relative_{lv:g}": lv / (g * d) for lv in LEVELS}}
    return out


def figure(result: dict, path: str | Path):
    """Four panels: error against Re* and against Re, G(kappa), torque error."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    colours = {d: c for d, c in zip(DELTAS, ("tab:blue", "tab:orange", "tab:green"))}
    markers = {"inner": "o", "outer": "s", "rolling": "^"}
    for row in result["sweeps"]:
        c, m = colours[row["delta_over_a"]], markers[row["motion"]]
        label = f"delta/a={row['delta_over_a']:.3g}, {row['motion']}" if row["kappa"] == KAPPAS[0] else None
        err = np.array(row["force_error"])
        axes[0, 0].loglog(row["reduced_reynolds"], err, m + "-", color=c, ms=3, lw=0.6, label=label)
        axes[0, 1].loglog(row["reynolds"], err, m + "-", color=c, ms=3, lw=0.6)
        if row["motion"] != "rolling":  # the rolling state is torque-free at leading order
            axes[1, 1].loglog(row["reduced_reynolds"], np.maximum(row["torque_error"], 1e-16), m + "-",
                              color=c, ms=3, lw=0.6)
    x = np.logspace(-2, 2, 10)
    axes[0, 0].loglog(x, 0.1 * x, "k--", lw=1, label="0.1 Re* (thin-gap co-rotation, kappa -> 0)")
    for ax in (axes[0, 0], axes[0, 1]):
        for level in LEVELS:
            ax.axhline(level, color="grey", lw=0.5, ls=":")
        ax.set_ylabel("|F - F_Stokes| / |F_Stokes|")
    axes[0, 0].set_xlabel("Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a)")
    axes[0, 1].set_xlabel("Re = max(|W_a| a, |W_b| b) delta / nu")
    axes[0, 0].legend(fontsize=6)
    axes[0, 0].set_title("force error: collapses on Re*", fontsize=9)
    axes[0, 1].set_title("the same against Re: a factor a/delta apart", fontsize=9)
    fo = result["first_order"]
    kap = np.array(fo["kappa"])
    styles = {"inner": "-", "outer": "--", "rolling": "-.", "co-rotating": ":"}
    for j, d in enumerate(fo["delta_over_a"]):
        if not any(abs(d - dd) < 1e-12 for dd in DELTAS):
            continue
        for name, ls in styles.items():
            axes[1, 0].plot(kap, fo[name][j], ls, color=colours[min(DELTAS, key=lambda q: abs(q - d))],
                            label=f"{name}" if j == 0 else None)
    axes[1, 0].plot([0, 0], [1 / 30, 1 / 10], "kx", label="thin gap, kappa -> 0: 1/30, 1/10")
    axes[1, 0].set_xlabel("kappa")
    axes[1, 0].set_ylabel("G = first-order error / Re*")
    axes[1, 0].legend(fontsize=6)
    axes[1, 0].set_title("first inertial correction (a pure f_eps) per Re*; blue, orange, green: "
                         "delta/a = 0.01, 0.1, 0.406", fontsize=8)
    axes[1, 1].set_xlabel("Re*")
    axes[1, 1].set_ylabel("|T_a - T_a,Stokes| / |T_a,Stokes|")
    axes[1, 1].set_title("torque (inner, outer rotation): second order in Re", fontsize=9)
    fig.suptitle("Steady Navier-Stokes against quasi-steady Stokes, eccentric annulus (kappa = 0.3, 0.6, 0.9)",
                 fontsize=10)
    fig.tight_layout()
    save_figure(path, fig, dpi=90)
    plt.close(fig)
    return path


def runaway_figure(result: dict, path: str | Path):
    """The runaways of :func:`runaway_trajectories`: X_b, 1 - kappa, Re* and the estimated error, the forces."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from dynamics.equations.limits import MAX_REYNOLDS
    from numerics.files import save_figure

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    colours = dict(zip(RUNAWAY_SLOPES, ("tab:blue", "tab:orange")))
    styles = {"paper": "-", "quasi-steady": "--", "quasi-steady+inertia": ":"}
    for r in result["runaway_trajectories"]:
        sr, c, ls = r["series"], colours[r["slope_deg"]], styles[r["model"]]
        t = np.array(sr["t"])
        label = f"{r['slope_deg']:g} deg, {r['model']}"
        axes[0, 0].plot(t, sr["x_b"], ls, color=c, lw=1, label=label)
        axes[0, 1].semilogy(t, sr["one_minus_kappa"], ls, color=c, lw=1)
        if r["model"] == "paper":
            axes[1, 0].semilogy(t, sr["reduced_reynolds"], "-", color=c, lw=1, label=f"Re*, {r['slope_deg']:g} deg")
            axes[1, 0].semilogy(t, sr["estimated_force_error"], "--", color=c, lw=1,
                                label=f"estimated force error, {r['slope_deg']:g} deg")
            axes[1, 1].semilogy(t, sr["frame_force_over_weight"], "-", color=c, lw=1,
                                label=f"frame force, {r['slope_deg']:g} deg")
            axes[1, 1].semilogy(t, sr["first_order_force_over_weight"], "--", color=c, lw=1,
                                label=f"first inertial correction, {r['slope_deg']:g} deg")
            axes[0, 0].plot(t, t**2 * r["acceleration_observed_law"] / 2.0, color=c, lw=3, alpha=0.25)
    axes[0, 0].set_ylabel("X_b (m)")
    axes[0, 0].legend(fontsize=6)
    axes[0, 0].set_title("distance rolled; thick: the observed law g t^2 sin(alpha)/3", fontsize=9)
    axes[0, 1].set_ylabel("1 - kappa")
    axes[0, 1].set_title("the gap: pressed shut by the centripetal force", fontsize=9)
    axes[1, 0].axhline(MAX_REYNOLDS, color="grey", lw=0.6, ls=":")
    axes[1, 0].set_ylabel("Re*, estimated relative force error")
    axes[1, 0].legend(fontsize=6)
    axes[1, 0].set_title("relative flow: Re* and the first-order force error ('paper')", fontsize=9)
    axes[1, 1].set_ylabel("force / m'_a g")
    axes[1, 1].legend(fontsize=6)
    axes[1, 1].set_title("frame force (left out as printed) and first inertial correction", fontsize=9)
    for ax in axes.flat:
        ax.set_xlabel("t (s)")
    fig.suptitle("Aluminium runaway (nu = 2e-4 m^2/s, closed forms) followed past the Reynolds limit", fontsize=10)
    fig.tight_layout()
    save_figure(path, fig, dpi=90)
    plt.close(fig)
    return path


def _frame_terms_markdown(result: dict) -> list[str]:
    comp = {c["slope_deg"]: c for c in result["runaway_comparison"]}
    five, ten = comp[RUNAWAY_SLOPES[0]]["frame_terms"], comp[RUNAWAY_SLOPES[1]]["frame_terms"]
    masses = {(r["slope_deg"], r["model"]): r["centripetal_mass"] / (r["m_eff"] if r["frame_terms"] == "paper"
                                                                        else r["m_a_reduced"])
              for r in result["runaway_trajectories"] if r["model"] != "quasi-steady+inertia"}
    worst_mass = max(abs(v - 1.0) for v in masses.values())
    square = comp[RUNAWAY_SLOPES[0]]["m_eff_over_m_reduced_squared"]
    papers = [r for r in result["runaway_trajectories"] if r["model"] == "paper"]
    frame = " and ".join(f"{r['inertia']['max_frame_force_over_weight']:.0f}" for r in papers)
    late_re = max(max(v for t, v in zip(r["series"]["t"], r["series"]["reduced_reynolds"])
                      if t >= RUNAWAY_FIT_START) for r in papers)
    end_re = " and ".join(f"{r['series']['reduced_reynolds'][-1]:.2g}" for r in papers)
    stokes = papers[0]["inertia"]["stokes_number"]
    gaps = [r["series"]["one_minus_kappa"][-1] for r in result["runaway_trajectories"]]
    return ["", "## frame_terms: the force of the fluid turning with the line of centres", "",
            ("`simulate(..., frame_terms=...)` and `[model] frame_terms` choose how the full equations treat it "
             "(dynamics.equations.full.frame_force). **\"paper\"** is (2.1)-(2.2) as printed: m_eff on every "
             "term of r'', the fluid force being quasi-steady Stokes flow in the non-rotating frame of the "
             "fluid's centre of mass. **\"quasi-steady\"** takes the flow as steady in a frame turning at the "
             "rate Omega, where the centrifugal and Coriolis forces of a plane flow only shift the pressure "
             "(sections above); their pressure pushes the inner cylinder with (m_eff - m'_a)(eps Omega (Omega - "
             "2 chi') e_eps + 2 Omega eps' e_chi), which for Omega = chi' puts m'_a instead of m_eff on the "
             "centripetal and Coriolis terms of (2.1)-(2.2)."), "",
            ("The frame rate is chi' clipped to the range of the wall rates [min(Omega_a, Omega_b), "
             "max(Omega_a, Omega_b)], no free constant: every part of the fluid turns at a rate between its "
             "walls', and where chi' leaves that range (A swinging past B while the walls are slow, chi' = "
             "(e_chi . r')/eps -> infinity) the line of centres is no frame the fluid turns with. The clipped "
             "force is chi''s wherever chi' lies between the wall rates (the runaway, the approach to contact), "
             "tends to the Coriolis force 2 (m_eff - m'_a) Omega J r' of a disc crossing a rigidly turning "
             "fluid as eps -> 0 where the chi' form diverges like |r'|^2/eps, and elsewhere differs from the "
             "chi' form by at most (1 + m''_a/m_f)(delta/a) Re*/6 of the nearer wall's Stokes force, the order "
             "of the relative flow's own inertial error (tests/test_frame_terms.py)."), "",
            ("**Where it matters, and a claim against the paper's equations.** The force is radial. In the "
             "aluminium runaway below (closed forms, nu = 2e-4 m^2/s, released from rest at kappa = 0.5) it "
             f"reaches {frame} times the buoyant weight m'_a g by {RUNAWAY_T_END:g} s "
             f"({' and '.join(f'{d:g}' for d in RUNAWAY_SLOPES)} degrees), while the "
             f"relative flow is slow (Re* <= {late_re:.2g} after {RUNAWAY_FIT_START:g} s, {end_re} at the end). "
             "It presses A into the outer wall against the "
             "squeeze film: in (2.2), (12 nu a m''_a / delta^2) q' ~ m eps chi'^2, q = kappa/zeta, with m = m_eff "
             "as printed and m'_a with the frame terms. The rows of each run reproduce m to "
             f"{worst_mass:.0e} (centripetal_mass, over {RUNAWAY_WINDOW[0]:g}-{RUNAWAY_WINDOW[1]:g} s). Hence "
             f"1 - kappa at {RUNAWAY_T_END:g} s is "
             f"{five['gap_ratio']:.1f} and {ten['gap_ratio']:.1f} times larger with the frame terms "
             f"(5 and 10 degrees; (m_eff/m'_a)^2 = {square:.2f} from the growth of q alone), while the rolling "
             f"hardly changes: X_b by {100 * five['x_b']:+.1f}% and {100 * ten['x_b']:+.1f}%, the late "
             f"acceleration by {100 * five['acceleration']:+.1f}% and {100 * ten['acceleration']:+.1f}%, the "
             f"mean Omega_b over the last 0.5 s by {100 * five['omega_b_mean']:+.1f}% and "
             f"{100 * ten['omega_b_mean']:+.1f}% (Omega_b swings within each turn, so its value at one instant, "
             f"{100 * five['omega_b_final']:+.1f}% and {100 * ten['omega_b_final']:+.1f}% at the end, mostly "
             "measures a phase). The printed (2.1)-(2.2) are right given the true fluid force; they "
             "understate the centripetal push only when that force is taken as quasi-steady Stokes flow in "
             "the frame of the fluid's centre of mass while the fluid turns with the line of centres. The "
             "claim holds under those conditions: plane, steady flow in the turning frame (Stokes number "
             f"delta^2/(nu tau) small: {stokes:.2g} here, so only roughly), chi' between the wall rates. The "
             f"gaps at stake, 1 - kappa = {min(gaps):.1g} to {max(gaps):.1g}, are below the asperity scale of "
             "the real walls (section 5: 1 - kappa* ~ 0.015), where a contact model takes over.")]


def _runaway_markdown(result: dict) -> list[str]:
    lines = ["", f"## The aluminium runaway followed to {RUNAWAY_T_END:g} s, with its inertial error", "",
             ("Figure 6's apparatus (aluminium, Table 2, nu = 2e-4 m^2/s), released from rest at kappa = 0.5, "
              "phi = 0.5 rad (the default scene's start), on 5 and 10 degree slopes; full equations with the "
              "closed forms, `on_invalid = \"warn\"` and the default Reynolds limit Re* = 1 (crossed, and "
              "recorded, in the first swing). Three treatments of the fluid's inertia: 'paper' ((2.1)-(2.2) as "
              "printed), 'quasi-steady' (with frame_terms), 'quasi-steady+inertia' (also the forces' first "
              "inertial correction, `model.inertia = 'first-order'`). Columns of the tables: Re*; the estimated "
              "relative force error (first order, against |f_chi,a| + |f_chi,b|); the first inertial "
              "correction and the frame force over m'_a g."), "",
             "![The aluminium runaway followed past the Reynolds limit](runaway.png)", ""]
    for deg in RUNAWAY_SLOPES:
        runs = {r["model"]: r for r in result["runaway_trajectories"] if r["slope_deg"] == deg}
        paper = runs["paper"]
        inertia = paper["inertia"]
        lines += [f"### {deg:g} degrees", "",
                  (f"'paper': {paper['status']} at t = {paper['t_last']:g} s ({paper['steps']} steps); "
                   f"largest Re* {inertia['max_reduced_reynolds']:.3g} at t = "
                   f"{inertia['t_at_max_reduced_reynolds']:.3g} s with an estimated force error of "
                   f"{100 * inertia['estimated_force_error_at_max_reduced_reynolds']:.1f}% there; largest "
                   f"estimated error {100 * inertia['max_estimated_force_error']:.1f}% at t = "
                   f"{inertia['t_at_max_estimated_force_error']:.3g} s. Limits passed: "
                   + "; ".join(f"Re* = 1 at t = {p['t']:.3g} s" for p in paper["limits_passed"]) + "."), "",
                  "| t (s) | X_b (m) | 1 - kappa | Omega_b (rad/s) | Re* | est. error | F^(1) / m'_a g | "
                  "frame / m'_a g |", "|---|---|---|---|---|---|---|---|"]
        series = paper["series"]
        for t in RUNAWAY_TIMES:
            i = series["t"].index(min(series["t"], key=lambda x: abs(x - t)))
            lines.append(f"| {series['t'][i]:.3g} | {series['x_b'][i]:.4g} | {series['one_minus_kappa'][i]:.3g} | "
                         f"{series['omega_b'][i]:.4g} | {series['reduced_reynolds'][i]:.3g} | "
                         f"{100 * series['estimated_force_error'][i]:.2g}% | "
                         f"{series['first_order_force_over_weight'][i]:.2g} | "
                         f"{series['frame_force_over_weight'][i]:.3g} |")
        end = f"{RUNAWAY_T_END:g} s"
        lines += ["", f"| run | X_b at {end} (m) | acceleration, t > {RUNAWAY_FIT_START:g} s (m/s^2) | "
                  f"1 - kappa at {end} | "
                  "largest Re* | largest est. error | largest frame / m'_a g |", "|---|---|---|---|---|---|---|"]
        for label, _, _ in RUNAWAY_MODELS:
            r = runs[label]
            lines.append(f"| {label} | {r['series']['x_b'][-1]:.4g} | {r['acceleration']:.4g} | "
                         f"{r['series']['one_minus_kappa'][-1]:.3g} | {r['inertia']['max_reduced_reynolds']:.3g} | "
                         f"{100 * r['inertia']['max_estimated_force_error']:.1f}% | "
                         f"{r['inertia']['max_frame_force_over_weight']:.3g} |")
        comp = next(c for c in result["runaway_comparison"] if c["slope_deg"] == deg)["first_order_inertia"]
        lines += ["", (f"Observed law X = g t^2 sin(alpha)/3: acceleration {paper['acceleration_observed_law']:.4g} "
                       f"m/s^2; (3.11): {paper['acceleration_311']:.4g} m/s^2. The first inertial correction, "
                       f"added to the forces, moves X_b at {end} by {100 * comp['x_b']:+.2f}%, the mean Omega_b over "
                       f"the last 0.5 s by {100 * comp['omega_b_mean']:+.2f}% and 1 - kappa by a factor "
                       f"{comp['gap_ratio']:.3f}: the trajectory-level size of the O(Re*) error, most of which "
                       f"is made in the first swing (Re* up to {inertia['max_reduced_reynolds']:.2g}, estimated "
                       f"error up to {100 * inertia['max_estimated_force_error']:.0f}%)."), ""]
    return lines


def _markdown(result: dict) -> str:
    th = result["thresholds"]
    app = f"{APPARATUS['delta_over_a']:g}"
    lines = ["# Fluid inertia: where quasi-steady Stokes fails", "",
             "Generated by `python -m validation.inertia` (lubrication.navier_stokes, lubrication.inertia).", "",
             "## Headline", "",
             ("In the frame of the line of centres the fictitious forces of a plane flow only shift the "
             "pressure: the rotation rate chi' adds the exact force -m''_a chi'^2 eps e_eps + "
             "2 m''_a chi' eps' e_chi and nothing else. The rest of the inertial error depends on the "
             "wall rotations relative to that frame, W = Omega - chi', through the reduced Reynolds number "
             "Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a). Its first correction is a force along the "
             "line of centres, G(kappa, motion) Re* relative to the Stokes force of the wall rotations; "
             "f_chi and T_a change only at O(Re^2)."), "",
             ("**The error scale.** Every relative force error here is |F - F_Stokes| over "
             "|R_chi_a W_a| + |R_chi_b W_b|, the sum of the magnitudes of the two rotational terms of the "
             "Stokes force f_chi = R_chi_a W_a + R_chi_b W_b. For walls turning in the same sense that is "
             "|f_chi| itself; for counter-rotating walls f_chi can vanish (R_chi_a W_a = -R_chi_b W_b) while "
             "the inertial f_eps does not, and a ratio to |f_chi| would be unbounded. Against this scale the "
             "first-order error is below Re*/10 for every wall motion (the largest G below, over every "
             "direction of (W_a, W_b) and every kappa)."), "",
             ("| delta/a | max G over kappa and wall motion | at kappa, U_b/U_a | Re* at 1% | Re* at 10% | "
              "Re at 1% | Re at 10% |"),
             "|---|---|---|---|---|---|---|"]
    for (d, row), at in zip(th.items(), result["first_order"]["g_max_at"]):
        lines.append(f"| {d} | {row['g_max']:.4f} | {at['kappa']:g}, {at['u_b_over_u_a']:.3g} | "
                     f"{row['reduced_0.01']:.3g} | {row['reduced_0.1']:.3g} | "
                     f"{row['relative_0.01']:.3g} | {row['relative_0.1']:.3g} |")
    lines += ["", ("Re = max(|W_a| a, |W_b| b) delta / nu (relative wall Reynolds number), U = W a or W b (wall "
              f"speeds). For the apparatus (delta/a = {app}): Re* = {float(app):.3f} Re."), "",
              ("**The run guard.** `[run] max_gap_reynolds` defaults to Re* = 1 "
               "(dynamics/equations/limits.py): there the estimated first-order error is at most 10% for every "
               "gap and wall motion (9.95% at delta/a = 0.01, "
               f"{100 * th[app]['g_max']:.1f}% at the apparatus' gap), and the Newton solutions below agree "
               "with the first-order error to 1% of it up to Re* = 1. A run reports in summary.json "
               "`inertia` the largest Re* and the estimated error there, and the largest estimated error, "
               "each with its time (dynamics.equations.limits.inertia_report)."), "",
              "## kappa -> 0: thin-gap closed form (the DiPrima & Stuart regime), exact, finite elements", "",
              ("G = d(f_eps)/d(Re*) over |f_chi,a| + |f_chi,b| at kappa -> 0. Thin-gap closed form "
              "|U_a^2 + 4 U_a U_b + U_b^2| / (30 (|U_a| + |U_b|) V), the project's own derivation "
              "(lubrication.inertia.thin_gap_small_kappa): the coefficients of DiPrima & Stuart (1972) were "
              "not available to compare with. What is quoted of their theory agrees in kind: the first "
              "inertial correction changes the direct stiffness d f_eps / d eps linearly in Re and leaves the "
              "cross-coupled stiffness and the load magnitude unchanged at that order (\"Approximations in "
              "hydrodynamic lubrication\", J. Tribol. 114, 14-25, 1992). Here, for the journal alone "
              "(inner, U_b = 0), the correction is perpendicular to the Stokes load f_chi: the attitude angle "
              "turns by Re*/30 and d f_eps/d eps gains (pi/5) rho a U_a^2 / delta per unit length. The last "
              "column is |f_chi| over the scale: small for counter-rotation (U_b = -U_a), where f_chi "
              "nearly cancels."), "",
              "| delta/a | motion | thin gap | exact (ODE) | finite elements | f_chi / scale |",
              "|---|---|---|---|---|---|"]
    for r in result["small_kappa"]:
        lines.append(f"| {r['delta_over_a']:g} | {r['motion']} | {r['thin_gap']:.5f} | {r['exact']:.5f} | "
                     f"{r['finite_elements']:.5f} | {r['stokes_f_chi_over_scale']:.3g} |")
    fo = result["first_order"]
    j = min(range(len(fo["delta_over_a"])), key=lambda i: abs(fo["delta_over_a"][i] - float(app)))
    lines += ["", f"## First-order G(kappa) at the apparatus gap (delta/a = {app})", "",
              ("Relative force error per unit Re*, from the table (finite-element values at its nodes); "
              "co-rotating: W_a = W_b."), "",
              "| kappa | inner | outer | rolling | co-rotating |", "|---|---|---|---|---|"]
    for i, k in enumerate(fo["kappa"]):
        lines.append(f"| {k:g} | " + " | ".join(f"{fo[n][j][i]:.4f}" for n in ("inner", "outer", "rolling",
                                                                                "co-rotating")) + " |")
    lines += ["", "## Continuation sweeps", "",
              ("Newton continuation in Re on the meshes of `lubrication.navier_stokes.inertial_mesh`. "
              "Columns: first-order G; Re* where the Newton solution's force error reaches 1% and 10%; "
              "the ratio of the Newton error to the first-order G Re* at Re* = 1, 3, 10, 30; the largest "
              "Re* reached (Newton stops when the continuation step has been halved six times)."), "",
              ("| delta/a | kappa | motion | G | Re* at 1% | Re* at 10% | ratio at 1 | 3 | 10 | 30 | "
              "Re* reached | mesh | s |"), "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in result["sweeps"]:
        red = np.array(r["reduced_reynolds"])
        ratio = np.array(r["first_order_ratio"])
        at = [ratio[np.isclose(red, x)] for x in (1.0, 3.0, 10.0, 30.0)]
        cells = " | ".join(f"{v[0]:.3f}" if v.size else "-" for v in at)
        lines.append(f"| {r['delta_over_a']:.3g} | {r['kappa']:g} | {r['motion']} | {r['first_order_g']:.4f} | "
                     f"{float(r['crossings']['0.01']):.3g} | {float(r['crossings']['0.1']):.3g} | {cells} | "
                     f"{r['max_reduced_reynolds']:.3g} | {r['mesh'][0]} x {r['mesh'][1]} | {r['wall_time_s']:.1f} |")
    lines += ["", "![Force error against the Reynolds number; first-order G; torque error](inertia.png)", "",
              "## The inertia-corrected force model", "",
              ("The closed forms and the exact Stokes forces with `inertia = 'first-order'` "
               "(lubrication.registry) add the tabulated first inertial correction f_eps^(1) "
               "to the Stokes forces, inside the compiled right-hand side. Its error is what the Newton "
               "solutions leave after it, |F - F_Stokes - F^(1)| / |F_Stokes|, largest over the sweeps "
               "above (at the table's nodes; between them add the interpolation error, below 3% of the "
               "correction: see 'The tabulated estimate'). The squeeze's inertia and the unsteady inertia "
               "are not in it."), "",
              "| Re* | plain Stokes error | corrected error |", "|---|---|---|"]
    for level, row in result["corrected_model_error"].items():
        lines.append(f"| {level} | {row['plain']:.3g} | {row['corrected']:.3g} |")
    lines += ["", "## The runaway: the same relative flow in faster-turning frames", "",
              ("Relative co-rotation W_a = W_b (Re = 10), apparatus gap, kappa = 0.6; chi' = s W with the "
              "fictitious forces discretised."), "",
              "| s | dynamic force error | Re (relative) | Re (absolute wall) | shear Re | rotation number |",
              "|---|---|---|---|---|---|"]
    for r in result["runaway"]:
        lines.append(f"| {r['spin']:g} | {r['relative_error']:.5f} | {r['reynolds_relative']:g} | "
                     f"{r['reynolds_absolute']:.3g} | {r['reynolds_shear']:.3g} | {r['rotation_number']:.3g} |")
    lines += ["", "## The force (2.1)-(2.2) miss: m''_a (1 + m''_a/m_f) eps chi'^2", "",
              ("Orbit rate chi' at which it reaches 1% / 10% of the buoyant weight m'_a g, and the absolute "
              "wall Reynolds number chi' b delta / nu there: large or small, it does not measure this force, "
              "which is exact in the frame of the line of centres (the run guard measures Re*)."), "",
              "| apparatus | kappa | level | chi' (rad/s) | m_eff / m'_a | Re_abs for nu = "
              + ", ".join(f"{nu:g}" for nu in OILS) + " m^2/s |", "|---|---|---|---|---|---|"]
    for r in result["apparatus_frame_force"]:
        res = ", ".join(f"{v:.3g}" for v in r["reynolds_absolute"].values())
        lines.append(f"| {r['apparatus']} | {r['kappa']:g} | {r['level']:g} | {r['chi_dot']:.3g} | "
                     f"{r['m_eff_over_m_reduced']:.3f} | {res} |")
    lines += _frame_terms_markdown(result) + _runaway_markdown(result)
    lines += ["", "## Unsteady inertia (not computed): Stokes numbers delta^2 / (nu tau)", "",
              "| apparatus | nu (m^2/s) | tau (s) | delta^2 / (nu tau) |", "|---|---|---|---|"]
    for r in result["stokes_numbers"]:
        lines.append(f"| {r['apparatus']} | {r['nu']:g} | {r['tau_s']:.3g} | {r['stokes_number']:.3g} |")
    acc = result["table_accuracy"]
    lines += ["", "## The tabulated estimate", "",
              (f"`lubrication.inertia.inertial_error_estimate` against fresh solves at {len(TABLE_PROBES)} "
              f"off-node points x 4 motions: max relative error {acc['max_relative']:.3g} (where G > 0.01), "
              f"max absolute error in G {acc['max_absolute_g']:.2g} (G <= 0.1)."), "",
              "## Checks", "", "| check | measured | reference | tolerance | passed |", "|---|---|---|---|---|"]
    for c in result["checks"]:
        lines.append(f"| {c['name']} | {c['measured']:.4g} | {c['reference']:.4g} | {c['tolerance']:.3g} | "
                     f"{c['passed']} |")
    wt = result["wall_time_s"]
    lines += ["", "Wall time (s): " + ", ".join(f"{k} {v:.0f}" for k, v in wt.items()), ""]
    return "\n".join(lines)


def write_outputs(result: dict, outdir: str | Path) -> list[Path]:
    """Write inertia.json, inertia.md, inertia.png and runaway.png into ``outdir``."""
    from numerics.files import write_json, write_text

    outdir = Path(outdir)

    def clean(obj):
        if isinstance(obj, dict):
            return {k: clean(v) for k, v in obj.items()}
        if isinstance(obj, (list, tuple)):
            return [clean(v) for v in obj]
        if isinstance(obj, float) and not math.isfinite(obj):
            return str(obj)
        if isinstance(obj, np.generic):
            return clean(obj.item())
        return obj

    return [write_json(outdir / "inertia.json", clean(result)), write_text(outdir / "inertia.md", _markdown(result)),
            Path(figure(result, outdir / "inertia.png")), Path(runaway_figure(result, outdir / "runaway.png"))]


if __name__ == "__main__":
    outdir = Path(__file__).resolve().parents[1] / "docs" / "inertia"
    result = run()
    for path in write_outputs(result, outdir):
        print(f"wrote {path}")
    failed = [c["name"] for c in result["checks"] if not c["passed"]]
    print(f"{len(result['checks']) - len(failed)} of {len(result['checks'])} checks passed")
    for name in failed:
        print(f"FAILED: {name}")
