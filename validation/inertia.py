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

The figures and the markdown are :mod:`validation.reports.inertia`'s: run
``python -m validation.reports.inertia`` to write ``docs/inertia/`` (figures,
``inertia.json``, ``inertia.md``); ``python generators/inertia_table.py`` rebuilds
:mod:`lubrication.inertia_table` (generators/README.md).
"""

from __future__ import annotations

import math
import time

import numpy as np

from dynamics.analysis import centripetal_mass

from .checks import Check, at_least, at_most, relative

__all__ = ["APPARATUS", "DELTAS", "DIRECTIONS", "KAPPAS", "LEVELS", "OILS", "RUNAWAY_MODELS", "RUNAWAY_SLOPES",
           "SWEEP_REDUCED", "TABLE_PROBES", "apparatus_frame_force",
           "centripetal_mass", "checks_of", "continuation_sweeps", "corrected_model_error",
           "first_order_survey", "run", "runaway_check", "runaway_comparison", "runaway_trajectories",
           "small_kappa_comparison", "stokes_numbers", "sweep_plan", "table_accuracy", "thresholds"]

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
    sweep alone cost more than the rest of the study (it reached Re* = 10,
    the first-order error holding to 1e-3 up to Re* = 3). The first-order survey covers every
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
    """Every number of the study, and the wall time of each part (``wall_time_s``)."""
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
