r"""Where quasi-steady Stokes fails: steady Navier-Stokes forces against the Reynolds number.

The force models assume quasi-steady Stokes flow. This study solves the steady
Navier-Stokes equations in the frame of the line of centres
(:mod:`lubrication.navier_stokes`) and measures the relative error
|F - F_Stokes| / |F_Stokes| of the force on the inner cylinder, and of its
torque, for

(i) inner rotation W_a, (ii) outer rotation W_b,
(iii) the runaway: Omega_a ~ Omega_b ~ chi', a near-rigid rotation of the
      whole device at chi' plus a slow relative flow (W_a, W_b),
(iv) the steady rolling state (3.2): W_a / W_b = (1 - kappa^2)/(1 + 2 kappa^2), chi' = 0,

W = Omega - chi' the wall rotations relative to the line of centres.

* First order, every motion: the O(Re) correction (a pure f_eps) from the
  reciprocal theorem, tabulated (:mod:`lubrication._inertia_table`) for
  kappa in [0, 0.999] and delta/a in [0.01, 1]; its kappa -> 0 limit
  against the thin-gap closed form (the regime of DiPrima & Stuart 1972) and
  the exact small-eccentricity solution (:mod:`lubrication.inertia`).
* Newton continuation in Re up to Re* = Re delta/a = 30 (:func:`sweep_plan`):
  delta/a = 0.1 and the apparatus' 0.406 (Table 2) at kappa = 0.3, 0.6, 0.9
  for (i), (ii), (iv), and delta/a = 0.01 for (iv) at kappa = 0.3; where the
  error reaches 1% and 10%, and how far the first-order error holds.
* (iii): in the frame of the line of centres the fictitious forces only
  shift the pressure, so the runaway is (W_a, W_b) plus the exact force
  -m''_a chi'^2 eps e_eps; checked with the fictitious forces discretised at
  chi' = 0, 3 and 10 W, and the force that (2.1)-(2.2) therefore miss is
  sized for the apparatus against its buoyant weight.
* The unsteady inertia that no steady solve sees, by its Stokes number.

Run ``python -m validation.inertia`` to write ``docs/inertia/`` (figure,
``inertia.json``, ``inertia.md``; about four minutes on two cores);
``python -m validation.inertia --table`` rebuilds
:mod:`lubrication._inertia_table` (about two minutes).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from .checks import Check, at_most, relative

__all__ = ["APPARATUS", "DELTAS", "KAPPAS", "LEVELS", "OILS", "SWEEP_REDUCED", "TABLE_DELTAS", "TABLE_KAPPAS",
           "TABLE_PROBES", "apparatus_frame_force", "build_table", "checks_of", "continuation_sweeps", "figure",
           "first_order_survey", "run", "runaway_check", "small_kappa_comparison", "stokes_numbers",
           "sweep_plan", "table_accuracy", "thresholds", "write_outputs"]

#: Table 2: a = 0.8 cm, b = 1.125 cm.
APPARATUS = {"a_m": 0.008, "b_m": 0.01125, "delta_over_a": 0.325 / 0.8}
DELTAS = (0.01, 0.1, APPARATUS["delta_over_a"])
KAPPAS = (0.3, 0.6, 0.9)

#: Nodes of :mod:`lubrication._inertia_table`: dense near contact, where the
#: normalised coefficients change fastest, and across the gaps of interest.
TABLE_KAPPAS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999)
TABLE_DELTAS = (0.01, 0.03, 0.1, 0.2, 0.3, APPARATUS["delta_over_a"], 0.6, 1.0)
#: Off-node points where the interpolated table is compared with fresh solves.
TABLE_PROBES = ((0.05, 0.05), (0.45, 0.15), (0.65, 0.35), (0.85, 0.5), (0.93, 0.8), (0.97, 0.25), (0.75, 0.02))

_TABLE_MODULE = Path(__file__).resolve().parents[1] / "lubrication" / "_inertia_table.py"


def _motions(kappa: float) -> dict[str, tuple[float, float]]:
    """(W_a, W_b) of the study's motions, relative to the line of centres."""
    return {"inner": (1.0, 0.0), "outer": (0.0, 1.0),
            "rolling": ((1.0 - kappa**2) / (1.0 + 2.0 * kappa**2), 1.0)}


def _format_array(values: np.ndarray) -> str:
    return np.array2string(np.asarray(values), separator=", ", precision=17, floatmode="unique",
                           threshold=100000, max_line_width=100)


def build_table(path: str | Path = _TABLE_MODULE) -> Path:
    """Solve the first inertial correction on the table's nodes and write the table module."""
    from lubrication.files import write_text
    from lubrication.inertia import TABLE_COLUMNS, build_error_table

    start = time.perf_counter()
    table = build_error_table(TABLE_KAPPAS, TABLE_DELTAS)
    elapsed = time.perf_counter() - start
    text = f'''"""Tabulated first inertial correction of the wall rotations (generated; do not edit).

Written by ``python -m validation.inertia --table`` in {elapsed:.0f} s: one
:func:`lubrication.navier_stokes.first_inertial_correction` per node, on the
default mesh (:func:`lubrication.stokes.default_mesh`; coefficient error about
1e-4, measured against the exact small-kappa solution). Columns:
:data:`lubrication.inertia.TABLE_COLUMNS`. Used by
:func:`lubrication.inertia.inertial_error_estimate` with bilinear
interpolation in (kappa, delta/a); its measured accuracy against fresh solves
off the nodes is in ``docs/inertia/inertia.md``. Outside the nodes the
normalised columns are held at the nearest edge (kappa > {TABLE_KAPPAS[-1]},
delta/a < {TABLE_DELTAS[0]} or > {TABLE_DELTAS[-1]}).
"""

import numpy as np

KAPPA_NODES = np.array({_format_array(np.array(TABLE_KAPPAS))})
DELTA_NODES = np.array({_format_array(np.array(TABLE_DELTAS))})
#: shape (len(KAPPA_NODES), len(DELTA_NODES), {len(TABLE_COLUMNS)})
TABLE = np.array({_format_array(table)})
'''
    return write_text(path, text)



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


def first_order_survey() -> dict:
    """G = (relative force error) / Re* at first order, at the table's nodes (finite-element values)."""
    from lubrication._inertia_table import DELTA_NODES, KAPPA_NODES

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
    g = np.array([out[n] for n in ("inner", "outer", "rolling", "co-rotating")])
    out["g_max"] = [float(v) for v in g.max(axis=(0, 2))]
    return out


def small_kappa_comparison() -> list[dict]:
    """kappa -> 0: thin-gap closed form, exact small-eccentricity solution and finite elements."""
    from lubrication.inertia import small_eccentricity_forces, thin_gap_small_kappa

    rows = []
    for d in DELTAS:
        b = 1.0 + d
        for name, (w_a, w_b) in (("inner", (1.0, 0.0)), ("outer", (0.0, 1.0)), ("co-rotating", (1.0, 1.0))):
            speed = max(abs(w_a), abs(w_b) * b)
            re = 1e-3
            f0 = small_eccentricity_forces(d, 0.0, w_a, w_b)
            f1 = small_eccentricity_forces(d, re, w_a, w_b)
            exact = (f1[0] - f0[0]) / (re * d) / f0[1]
            f_eps1, f_chi0 = thin_gap_small_kappa(w_a, w_b * b, delta=d)
            thin = f_eps1 / f_chi0 / (speed * d * d)
            fe = _g_of(0.0, d, w_a, w_b * b)
            rows.append({"delta_over_a": d, "motion": name, "thin_gap": thin, "exact": exact,
                         "finite_elements": fe})
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
            "force_error": error[1:].tolist(), "torque_error": torque[1:].tolist(),
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


def table_accuracy() -> dict:
    """The interpolated error estimate against fresh solves at off-node points."""
    from lubrication.inertia import inertial_error_estimate
    from lubrication.navier_stokes import first_inertial_correction

    worst_rel, worst_abs, rows = 0.0, 0.0, []
    for kappa, d in TABLE_PROBES:
        c = first_inertial_correction(d, kappa)
        for re_a, re_b in ((1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, -0.3)):
            m = np.array([0.0, re_a, re_b / (1.0 + d)])
            direct = float(np.hypot(m @ c.c_eps @ m, m @ c.c_chi @ m)
                           / (d * np.linalg.norm((c.stokes @ m)[:2])))
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
    return checks


def run() -> dict:
    """Every number of the study (a few minutes on two cores)."""
    start = time.perf_counter()
    timings = {}
    result = {}
    for key, func in (("first_order", first_order_survey), ("small_kappa", small_kappa_comparison),
                      ("sweeps", continuation_sweeps), ("runaway", runaway_check),
                      ("apparatus_frame_force", apparatus_frame_force), ("stokes_numbers", stokes_numbers),
                      ("table_accuracy", table_accuracy)):
        t = time.perf_counter()
        result[key] = func()
        timings[key] = time.perf_counter() - t
    result["thresholds"] = thresholds(result["first_order"])
    result["checks"] = [c.as_dict() for c in checks_of(result)]
    result["wall_time_s"] = {**timings, "total": time.perf_counter() - start}
    return result


def thresholds(first_order: dict) -> dict:
    """Re* (and Re = Re* a/delta) where the worst first-order error over kappa and motion is 1% and 10%."""
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

    from lubrication.files import save_figure

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
             "line of centres, G(kappa, motion) Re* relative to the Stokes force; f_chi and T_a change "
             "only at O(Re^2)."), "",
             "| delta/a | max G over kappa and motion | Re* at 1% | Re* at 10% | Re at 1% | Re at 10% |",
             "|---|---|---|---|---|---|"]
    for d, row in th.items():
        lines.append(f"| {d} | {row['g_max']:.4f} | {row['reduced_0.01']:.3g} | {row['reduced_0.1']:.3g} | "
                     f"{row['relative_0.01']:.3g} | {row['relative_0.1']:.3g} |")
    lines += ["", ("Re = max(|W_a| a, |W_b| b) delta / nu (relative wall Reynolds number). "
              f"For the apparatus (delta/a = {app}): Re* = {float(app):.3f} Re."), "",
              "## kappa -> 0: thin-gap closed form (the DiPrima & Stuart regime), exact, finite elements", "",
              ("G = d(f_eps)/d(Re*) / f_chi at kappa -> 0. Thin-gap closed form "
              "(U_a^2 + 4 U_a U_b + U_b^2) / (30 (U_a + U_b) V)."), "",
              "| delta/a | motion | thin gap | exact (ODE) | finite elements |", "|---|---|---|---|---|"]
    for r in result["small_kappa"]:
        lines.append(f"| {r['delta_over_a']:g} | {r['motion']} | {r['thin_gap']:.5f} | {r['exact']:.5f} | "
                     f"{r['finite_elements']:.5f} |")
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
              "wall Reynolds number chi' b delta / nu there (the run guard's present measure)."), "",
              "| apparatus | kappa | level | chi' (rad/s) | m_eff / m'_a | Re_abs for nu = "
              + ", ".join(f"{nu:g}" for nu in OILS) + " m^2/s |", "|---|---|---|---|---|---|"]
    for r in result["apparatus_frame_force"]:
        res = ", ".join(f"{v:.3g}" for v in r["reynolds_absolute"].values())
        lines.append(f"| {r['apparatus']} | {r['kappa']:g} | {r['level']:g} | {r['chi_dot']:.3g} | "
                     f"{r['m_eff_over_m_reduced']:.3f} | {res} |")
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
    """Write inertia.json, inertia.md and inertia.png into ``outdir``."""
    from lubrication.files import write_json, write_text

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
            Path(figure(result, outdir / "inertia.png"))]


if __name__ == "__main__":
    import sys

    if "--table" in sys.argv[1:]:
        print(f"wrote {build_table()}")
    else:
        outdir = Path(__file__).resolve().parents[1] / "docs" / "inertia"
        result = run()
        for path in write_outputs(result, outdir):
            print(f"wrote {path}")
        failed = [c["name"] for c in result["checks"] if not c["passed"]]
        print(f"{len(result['checks']) - len(failed)} of {len(result['checks'])} checks passed")
        for name in failed:
            print(f"FAILED: {name}")
