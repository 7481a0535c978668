r"""Speed against accuracy of every way of getting the fluid forces, and of getting a trajectory.

Part A: forces at one instant. For delta/a in {0.003, 0.01, 0.03, 0.1,
0.40625 (the paper's apparatus, a = 0.8 cm, b = 1.125 cm), 1} and kappa in
{0.1, 0.5, 0.9, 0.98, 0.99}, the five resistance coefficients of
:class:`lubrication.geometry.Resistance` are computed by

* the closed forms (2.5)-(2.7);
* the Reynolds solver on each grid (sommerfeld, uniform), profile (thin
  gap (B1), exact eccentric gap) and N in {8, ..., 1024}, one Gauss point per
  cell (what a trajectory's "reynolds" model uses);
* the finite-element Stokes solve on the default mesh
  (:func:`lubrication.stokes.default_mesh`) scaled by 0.25 ... 2 in both
  directions;
* the exact 2-D Stokes solution (:mod:`lubrication.stokes_exact`).

Error. The truth at finite delta/a is the exact 2-D Stokes solution of the
eccentric annulus (:mod:`lubrication.stokes_exact`, 15 significant digits
over this whole range, checked against a 100-digit evaluation), so every
other model, the finite elements included, is measured against an
independent reference. Each coefficient's error is relative to its own
size, except T_a per W_b, which is measured against |T_a per W_a| (the row
convention of ``benchmarks/README.md``: near contact it is a small O(zeta)
difference of O(1/zeta) parts); the error of a model is the largest of the
five.

Cost. The median wall time of one force evaluation (one motion), from
Python through the public face :func:`lubrication.fluid_forces` (for the
finite elements the whole solve with its factorisation, cache cleared) and,
for the models the equations of motion can call, from a numba loop over
the model's compiled kernel (:mod:`lubrication.kernels`): what one right-hand side pays.
Samples of at least 2 ms, interleaved over all models in shuffled rounds, JIT
compilation excluded by a warm-up.

Part B: trajectories. The full model (2.1)-(2.4) with each force model
(closed form, Reynolds N = 16 on the Sommerfeld grid, exact Stokes) and the
reduced model (2.11), each with the compiled Radau IIA engine and scipy's
LSODA, BDF and Radau at rtol 1e-4 ... 1e-10,
released at rest from kappa = 0.5, phi = 0.5 and run for 200 tau, at
delta/a = 0.01 (the distinguished-limit apparatus of
:meth:`dynamics.apparatus.Apparatus.from_groups` with the steel
apparatus' s, Upsilon and mu_) and 0.40625 (the steel apparatus itself).
The observables are X_b and the gap 1 - kappa at t_end (about 1e-5, near
contact: the relative error of kappa itself would hide any error in it); the
error is the larger of their relative errors against a reference run: the
full model with the exact Stokes forces, the compiled engine at rtol 1e-12. The
relative error of kappa is recorded too. At the other delta/a of part A only
the reduced model and the full model with closed forms and with the exact
Stokes forces are run (the engine, rtol 1e-10), to measure how the error of the
equations grows with delta/a.
RK45 is not run: the full model is stiff (NUMERICS.md), and at
delta/a = 0.01 RK45 at rtol 1e-4 took 2 million steps (300 s) to cover
less than half the run (measured while writing this script).

Outputs: ``benchmarks/results/accuracy.json`` (all numbers), ``accuracy.md``
(tables), ``accuracy_pareto.png``, and the compact study
``dynamics/data/model_choice.json`` that :mod:`dynamics.app.auto` chooses from
(:func:`model_choice`; ``generators/model_choice.py`` writes it).
Run ``python -m benchmarks.accuracy`` from the project root (about 10 minutes
on 2 cores); ``--trajectories`` runs part B again and keeps part A's stored
numbers (after a change to the equations of motion, which the forces do not see).
"""

from __future__ import annotations

import datetime
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import RESULTS, Timer, interleave, machine, publish, time_all
from dynamics.apparatus import Apparatus, preset
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.simulation import simulate
from lubrication.geometry import Annulus, Fluid, Motion, Resistance
from lubrication.kernels import KernelModel
from lubrication.registry import fluid_forces, kernel_model, resistance
from lubrication.stokes import clear_cache, default_mesh
from numerics.files import save_figure, write_text

DELTAS = (0.003, 0.01, 0.03, 0.1, 0.40625, 1.0)
KAPPAS = (0.1, 0.5, 0.9, 0.98, 0.99)
REYNOLDS_CELLS = (8, 16, 32, 64, 128, 256, 512, 1024)
REYNOLDS_GRIDS = ("sommerfeld", "uniform")
REYNOLDS_PROFILES = ("thin", "eccentric")
FEM_SCALES = (0.25, 0.5, 1.0, 1.5, 2.0)
ROUNDS = 5
BATCH_SECONDS = 2e-3
FEM_ROUNDS = 2

#: Geometry and fluid of part A: the steel apparatus' inner radius, length and oil.
A, LENGTH, FLUID = 0.008, 0.1035, Fluid(nu=2.0e-4, rho=960.0)
#: The motion timed: every resistance coefficient contributes.
TIMED_MOTION = Motion(eps_dot=1e-6, chi_dot=0.1, omega_a=1.0, omega_b=0.5)

TRAJECTORY_DELTAS = (0.01, 0.40625)
EQUATION_DELTAS = DELTAS
METHODS = ("radau", "LSODA", "BDF", "Radau")  # the compiled engine, then scipy's
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
REFERENCE_RTOL = 1e-12
T_END_TAU = 200.0
RELEASE = Initial(kappa=0.5, phi=0.5)
TRAJECTORY_REPEATS = 3
EQUATIONS_RTOL = 1e-10
EQUATIONS_METHOD = REFERENCE_METHOD = "radau"



# -- part A: forces at one instant ---------------------------------------------------------------

def _label(model: str, options: dict) -> str:
    return model + "".join(f" {k}={v}" for k, v in options.items())


def _candidates() -> list[dict]:
    """Every (model, options) of part A; ``eom`` marks those the equations of motion can call."""
    out = [{"model": "closed-form", "options": {}, "eom": True}]
    for grid in REYNOLDS_GRIDS:
        for profile in REYNOLDS_PROFILES:
            for n in REYNOLDS_CELLS:
                out.append({"model": "reynolds", "options": {"n": n, "grid": grid, "profile": profile},
                            "eom": True})
    out.append({"model": "stokes-exact", "options": {}, "eom": True})
    for scale in FEM_SCALES:
        out.append({"model": "stokes-fem", "options": {"mesh_scale": scale}, "eom": False})
    return out


def _fem_mesh(delta: float, scale: float) -> dict:
    """The default mesh of ``delta`` with both counts scaled by ``scale``."""
    n_around, n_across = default_mesh(delta)
    return {"n_around": max(8, round(scale * n_around)), "n_across": max(1, round(scale * n_across))}


def _row_errors(got: Resistance, truth: Resistance) -> dict:
    """Relative error per coefficient; T_a per W_b against |T_a per W_a|; ``row`` the largest."""
    g, t = got.as_tuple(), truth.as_tuple()
    rel = {name: abs(g[i] - t[i]) / abs(t[i]) for i, name in enumerate(Resistance.NAMES)}
    rel["t_a_per_w_b"] = abs(g[4] - t[4]) / abs(t[2])
    return {**rel, "row": max(rel.values())}


@njit(cache=False, nogil=True)
def _evaluate_loop(calls, kernel, data, a, b, mu, length, kappa, omk):
    """``calls`` evaluations of a model's compiled kernel, with inputs that change from call to call."""
    total = 0.0
    for i in range(calls):
        s = 1.0 + 1e-9 * i
        f_eps, f_chi, t_a = kernel(data, a, b, mu, length, kappa, omk, 1e-6 * s, 0.9 * s, 0.4 * s)
        total += f_eps + f_chi + t_a
    return total


def _jit_batch(model: KernelModel, annulus: Annulus):
    args = (model.kernel, model.data, annulus.a, annulus.b, FLUID.mu, annulus.length, annulus.kappa, annulus.one_minus_kappa)

    def batch(calls):
        start = time.perf_counter()
        _evaluate_loop(calls, *args)
        return [time.perf_counter() - start]
    return batch


def _python_batch(evaluate):
    def batch(calls):
        start = time.perf_counter()
        for _ in range(calls):
            evaluate()
        return [time.perf_counter() - start]
    return batch


def _fem_seconds(annulus: Annulus, mesh: dict, rounds: int) -> float:
    """Median wall time of one uncached finite-element force evaluation (mesh, factorisation, solve)."""
    times = []
    for _ in range(rounds):
        clear_cache()
        start = time.perf_counter()
        fluid_forces(annulus, TIMED_MOTION, FLUID, "stokes", **mesh)
        times.append(time.perf_counter() - start)
    clear_cache()
    return float(np.median(times))


def _eom_model(c: dict) -> KernelModel | None:
    if c["model"] in ("closed-form", "reynolds", "stokes-exact"):
        return kernel_model(c["model"], **c["options"])
    return None


def force_case(delta: float, kappa: float, *, rounds=ROUNDS, batch_seconds=BATCH_SECONDS,
               fem_rounds=FEM_ROUNDS, seed=0) -> dict:
    """Errors against the exact Stokes solution and costs of every candidate at one (delta/a, kappa)."""
    annulus = Annulus.from_kappa(A, A * (1.0 + delta), kappa, length=LENGTH)
    truth = resistance(annulus, FLUID, "stokes-exact")
    rows, timers = [], []
    for c in _candidates():
        row = {"model": c["model"], "options": c["options"], "label": _label(c["model"], c["options"]),
               "eom": c["eom"]}
        if c["model"] == "stokes-fem":
            row["mesh"] = _fem_mesh(delta, c["options"]["mesh_scale"])
            got = resistance(annulus, FLUID, "stokes", **row["mesh"])
        else:
            opts = dict(c["options"], points_per_cell=1) if c["model"] == "reynolds" else {}
            got = resistance(annulus, FLUID, c["model"], **opts)
            timers.append(Timer((row["label"], "python"), _python_batch(
                lambda m=c["model"], o=opts: fluid_forces(annulus, TIMED_MOTION, FLUID, m, **o))))
        model = _eom_model(c)
        if model is not None:
            timers.append(Timer((row["label"], "jit"), _jit_batch(model, annulus)))
        row["errors"] = _row_errors(got, truth)
        row["error"] = row["errors"]["row"]
        rows.append(row)
    times = time_all(timers, rounds, batch_seconds, np.random.default_rng(seed))
    for row in rows:
        for face in ("python", "jit"):
            if (row["label"], face) in times:
                row[f"{face}_s"] = times[(row["label"], face)]["total"]
                row[f"{face}_cpu_s"] = times[(row["label"], face)]["cpu"]
        if row["model"] == "stokes-fem":
            row["python_s"] = _fem_seconds(annulus, row["mesh"], fem_rounds)
    return {"delta_over_a": delta, "kappa": kappa, "truth": dict(zip(Resistance.NAMES, truth.as_tuple())),
            "models": rows}


# -- part B: trajectories ------------------------------------------------------------------------

def _apparatus(delta: float) -> Apparatus:
    steel = preset("steel")
    if _is_steel(delta):
        return steel
    return Apparatus.from_groups(steel.s, steel.upsilon, steel.mu_ratio, delta)


def _is_steel(delta: float) -> bool:
    return math.isclose(delta, preset("steel").delta_over_a, rel_tol=1e-9)


#: The study compares models of one motion: the inertial guard, a statement about the fluid, is lifted (the
#: release's swing passes Re* = 1 at every delta/a).
LIMITS = Limits(max_gap_reynolds=None)


def _run(app: Apparatus, equations: str, forces: str, method: str, rtol: float):
    if equations == "reduced":
        return simulate(app, RELEASE, T_END_TAU * app.tau, equations="reduced", rtol=rtol, method=method,
                        limits=LIMITS)
    model = kernel_model({"stokes": "stokes-exact"}.get(forces, forces))
    return simulate(app, RELEASE, T_END_TAU * app.tau, forces=model, rtol=rtol, method=method, limits=LIMITS)


def _final(tr) -> dict:
    c = tr.columns
    return {"t": float(c["t"][-1]), "x_b": float(c["x_b"][-1]), "kappa": float(c["kappa"][-1]),
            "one_minus_kappa": float(c["one_minus_kappa"][-1])}


def _trajectory_error(final: dict, ref: dict) -> dict:
    ex = abs(final["x_b"] - ref["x_b"]) / abs(ref["x_b"])
    ek = abs(final["kappa"] - ref["kappa"]) / ref["kappa"]
    eg = abs(final["one_minus_kappa"] - ref["one_minus_kappa"]) / ref["one_minus_kappa"]
    return {"x_b": ex, "kappa": ek, "one_minus_kappa": eg, "error": max(ex, eg)}


def trajectory_study(delta: float, *, methods=METHODS, rtols=RTOLS, repeats=TRAJECTORY_REPEATS,
                     full=True, seed=0) -> dict:
    """Wall time and error at t_end of each (equations, forces, method, rtol) at one delta/a.

    With ``full`` False only the reduced model and the full model with closed
    forms and with the exact Stokes forces run, with EQUATIONS_METHOD at EQUATIONS_RTOL.
    """
    app = _apparatus(delta)
    ref_run = _run(app, "full", "stokes", REFERENCE_METHOD, REFERENCE_RTOL)
    ref = _final(ref_run)
    if full:
        configs = [("reduced", "closed-form", m, r) for m in methods for r in rtols]
        configs += [("full", f, m, r) for f in ("closed-form", "reynolds", "stokes") for m in methods for r in rtols]
    else:
        configs = [(e, f, EQUATIONS_METHOD, EQUATIONS_RTOL)
                   for e, f in (("reduced", "closed-form"), ("full", "closed-form"), ("full", "stokes"))]
    for equations, forces in {(c[0], c[1]) for c in configs}:  # warm-up: compile each right-hand side
        _run(app, equations, forces, "radau", 1e-4)
    finals = {}  # each configuration's last run and its final state

    def timed(c):
        tr = _run(app, *c)
        finals[c] = (tr, _final(tr))
        return tr.wall_time_s

    walls = interleave(configs, repeats, np.random.default_rng(seed), timed)
    rows = []
    for c in configs:
        tr, fin = finals[c]
        rows.append({"equations": c[0], "forces": c[1], "method": c[2], "rtol": c[3], "status": tr.status,
                     "wall_s": float(np.median(walls[c])), "steps": tr.steps, "nfev": tr.nfev,
                     "final": fin, **_trajectory_error(fin, ref)})
    return {"delta_over_a": delta, "apparatus": "steel preset" if _is_steel(delta) else
            "Apparatus.from_groups with the steel groups", "tau": app.tau, "t_end_tau": T_END_TAU,
            "reference": {"equations": "full", "forces": "stokes", "method": REFERENCE_METHOD, "rtol": REFERENCE_RTOL,
                          "status": ref_run.status, "wall_s": ref_run.wall_time_s, "final": ref},
            "runs": rows}


# -- the study, the stored choice file -----------------------------------------------------------

def run(deltas=DELTAS, kappas=KAPPAS, trajectory_deltas=TRAJECTORY_DELTAS, equation_deltas=EQUATION_DELTAS,
        rounds=ROUNDS, fem_rounds=FEM_ROUNDS, repeats=TRAJECTORY_REPEATS) -> dict:
    """Part A over (deltas x kappas) and part B at ``trajectory_deltas`` (full matrix) and
    ``equation_deltas`` (reduced and full closed-form only); returns plain data."""
    started = time.perf_counter()
    forces = []
    for delta in deltas:
        for kappa in kappas:
            forces.append(force_case(delta, kappa, rounds=rounds, fem_rounds=fem_rounds))
            print(f"forces delta/a {delta} kappa {kappa}: {time.perf_counter() - started:.0f} s", file=sys.stderr)
    trajectories = trajectory_part(trajectory_deltas, equation_deltas, repeats, started)
    return {
        "machine": machine(),
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "settings": {"deltas": list(deltas), "kappas": list(kappas), "a": A, "length": LENGTH,
                     "nu": FLUID.nu, "rho": FLUID.rho, "reynolds_cells": list(REYNOLDS_CELLS),
                     "fem_scales": list(FEM_SCALES), "truth": "stokes-exact",
                     "rounds": rounds, "batch_seconds": BATCH_SECONDS,
                     "fem_rounds": fem_rounds, "trajectory_deltas": list(trajectory_deltas),
                     "equation_deltas": list(equation_deltas), "t_end_tau": T_END_TAU,
                     "release": {"kappa": RELEASE.kappa, "phi": RELEASE.phi}, "repeats": repeats,
                     "equations_method": EQUATIONS_METHOD},
        "forces": forces,
        "trajectories": trajectories,
        "run_seconds": time.perf_counter() - started,
    }


def _up(x):
    """``x`` to 3 significant digits, never below it (stored errors stay conservative)."""
    return None if x is None else float(f"{x * 1.006:.3g}")


def _sig(x):
    return None if x is None else float(f"{x:.3g}")


def model_choice(results: dict) -> dict:
    """The compact study :mod:`dynamics.app.auto` chooses from: errors and costs on the (delta/a, kappa) grid.

    Errors are rounded up to 3 significant digits, costs rounded to 3.
    """
    s = results["settings"]
    deltas, kappas = s["deltas"], s["kappas"]
    cases = {(c["delta_over_a"], c["kappa"]): {r["label"]: r for r in c["models"]} for c in results["forces"]}
    first = results["forces"][0]["models"]
    entries = []
    for proto in first:
        label = proto["label"]

        def grid(key, rounded, label=label):
            return [[rounded(cases[(d, k)][label].get(key)) for k in kappas] for d in deltas]
        entry = {"model": proto["model"], "options": proto["options"], "equations_of_motion": proto["eom"],
                 "error": grid("error", _up), "jit_s": grid("jit_s", _sig), "python_s": grid("python_s", _sig)}
        entries.append(entry)
    # studies written before the compiled engine ran the equations with LSODA
    method = s.get("equations_method", "LSODA")
    eq_deltas, reduced, reduced_s, full, full_s = [], [], [], {}, {}
    for t in results["trajectories"]:
        d = t["delta_over_a"]
        eq_deltas.append(d)
        pick = [r for r in t["runs"] if r["method"] == method and r["rtol"] == EQUATIONS_RTOL]
        red = next(r for r in pick if r["equations"] == "reduced")
        reduced.append(_up(red["error"]))
        reduced_s.append(_sig(red["wall_s"]))
        for r in pick:
            if r["equations"] == "full":
                full.setdefault(r["forces"], {})[d] = _up(r["error"])
                full_s.setdefault(r["forces"], {})[d] = _sig(r["wall_s"])
    return {
        "version": 1,
        "study": {"script": "benchmarks/accuracy.py", "date": results["date"], "machine": results["machine"],
                  "force_error": "largest relative error of the five resistance coefficients against the "
                                 "exact 2-D Stokes solution (lubrication.stokes_exact); T_a per W_b "
                                 "against |T_a per W_a|",
                  "jit_s": "median wall seconds of one force evaluation from a numba loop over "
                           "the model's compiled kernel (null: not callable from the equations of motion)",
                  "python_s": "median wall seconds of one force evaluation through the Python face",
                  "trajectory_error": f"larger relative error of X_b and 1 - kappa after {T_END_TAU:g} tau from "
                                      f"kappa = {RELEASE.kappa:g}, phi = {RELEASE.phi:g} at rest, against the "
                                      "full model with the exact Stokes forces at rtol "
                                      f"{REFERENCE_RTOL:g}; method {method} at rtol {EQUATIONS_RTOL:g}"},
        "deltas": deltas, "kappas": kappas,
        "forces": entries,
        "equations": {"deltas": eq_deltas, "reduced": reduced, "reduced_s": reduced_s,
                      "full": {f: [v.get(d) for d in eq_deltas] for f, v in full.items()},
                      "full_s": {f: [v.get(d) for d in eq_deltas] for f, v in full_s.items()}},
    }


# -- report --------------------------------------------------------------------------------------

def _e(x) -> str:
    return "-" if x is None else f"{x:.1e}"


def _us(x) -> str:
    return "-" if x is None else (f"{x * 1e6:.3g}" if x < 0.1 else f"{x:.3g} s")


def to_markdown(results: dict, choice: dict) -> str:
    m = results["machine"]
    lines = ["# Forces and trajectories: cost against accuracy", "",
             (f"{m['cpu']}, {m['cores']} cores; Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, "
              f"numba {m['numba']}; {results['date']}; run {results['run_seconds']:.0f} s."
              + ("" if "trajectories_rerun" not in results else
                 f" The trajectories run again on {results['trajectories_rerun']['date']} "
                 f"({results['trajectories_rerun']['machine']['cpu']}, "
                 f"{results['trajectories_rerun']['run_seconds']:.0f} s)."))
             , "",
             "## Forces at one instant", "",
             "Error: largest relative error of the five resistance coefficients against the exact 2-D Stokes "
             "solution (T_a per W_b against |T_a per W_a|), largest over kappa in "
             + ", ".join(f"{k:g}" for k in results["settings"]["kappas"])
             + ". Cost: median microseconds per force evaluation, largest over kappa, from a numba loop "
               "(jit) and through the Python face (python; finite elements: the whole solve in seconds). "
               "Reynolds: one Gauss point per cell.", ""]
    deltas = choice["deltas"]
    lines += ["| model | " + " | ".join(f"err d/a={d:g}" for d in deltas) + " | jit us | python us |",
              "|---|" + "---|" * (len(deltas) + 2)]
    for e in choice["forces"]:
        if e["model"] == "reynolds" and e["options"]["n"] not in (8, 16, 64, 256, 1024):
            continue
        errs = [max(row) for row in e["error"]]
        jit = [x for row in e["jit_s"] for x in row if x is not None]
        py = [x for row in e["python_s"] for x in row if x is not None]
        lines.append(f"| {_label(e['model'], e['options'])} | " + " | ".join(_e(x) for x in errs)
                     + f" | {_us(max(jit)) if jit else '-'} | {_us(max(py)) if py else '-'} |")
    lines += ["", "Reynolds rows for N = 32, 128 and 512 are in the JSON. The exact solution's own error is "
              "rounding: below 2e-15 of every coefficient (tests/test_stokes_exact.py).", ""]
    lines += ["## Trajectories", "",
              (f"Release at rest from kappa = 0.5, phi = 0.5, {T_END_TAU:g} tau. Error: larger relative error of "
               "X_b and of the gap 1 - kappa at t_end against the full model with the exact Stokes forces "
               f"(the compiled engine, rtol {REFERENCE_RTOL:g}); each is also shown apart. Method radau is the "
               "compiled engine, the others scipy's. Wall time: median of the repeats."), ""]
    for t in results["trajectories"]:
        ref = t["reference"]
        lines += [f"### delta/a = {t['delta_over_a']:g} ({t['apparatus']}, tau = {t['tau']:.4g} s)", "",
                  (f"Reference: X_b = {ref['final']['x_b']:.6g} m, kappa = {ref['final']['kappa']:.9g}, "
                   f"1 - kappa = {ref['final']['one_minus_kappa']:.4g}, {ref['wall_s']:.2f} s."), "",
                  "| equations | forces | method | rtol | wall s | steps | error | X_b | 1 - kappa |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for r in t["runs"]:
            lines.append(f"| {r['equations']} | {r['forces']} | {r['method']} | {r['rtol']:g} | {r['wall_s']:.3g} "
                         f"| {r['steps']} | {_e(r['error'])} | {_e(r['x_b'])} | {_e(r['one_minus_kappa'])} |")
        lines.append("")
    eq = choice["equations"]
    lines += ["## The stored study: what `dynamics.app.auto` chooses from", "",
              f"Trajectory error of the equations ({EQUATIONS_METHOD}, rtol {EQUATIONS_RTOL:g}) against delta/a:", "",
              "| delta/a | reduced (2.11) | " + " | ".join(f"full, {f}" for f in eq["full"]) + " |",
              "|---|---|" + "---|" * len(eq["full"])]
    for i, d in enumerate(eq["deltas"]):
        lines.append(f"| {d:g} | {_e(eq['reduced'][i])} | " + " | ".join(_e(v[i]) for v in eq["full"].values()) + " |")
    lines += ["", _choices_table()]
    return "\n".join(lines)


def _choices_table() -> str:
    """What the automatic choice makes of the stored study for a scene, at a few tolerances and gaps."""
    from dynamics.app.auto import choose_equations, choose_forces

    lines = [("Automatic choices for a scene with `equations = \"auto\"` and `forces = \"auto\"` "
              "(`dynamics.app.auto.resolve_model`, kappa up to 0.99): the equations first (the reduced ones against "
              "the full ones with the exact Stokes forces), then, for the full equations, the cheapest forces whose "
              "force error and measured trajectory error both meet the tolerance. The reduced equations have the "
              "closed forms built in."),
             "",
             "| tolerance | delta/a | equations | measured error | forces | measured error | jit us |",
             "|---|---|---|---|---|---|---|"]
    for tol in (1e-1, 5e-2, 3e-2, 1e-2, 1e-3, 1e-4, 1e-6):
        for d in (0.01, 0.40625):
            q = choose_equations(tol, d)
            if q.model == "reduced":
                lines.append(f"| {tol:g} | {d:g} | reduced | {_e(q.error)} | closed-form (built in) | - | - |")
                continue
            f = choose_forces(tol, d, 0.99, trajectory=True)
            lines.append(f"| {tol:g} | {d:g} | full | {_e(q.error)} | {_label(f.model, f.options)} | {_e(f.error)} "
                         f"| {_us(f.cost_s)} |")
    return "\n".join(lines)


def pareto_figure(results: dict, choice: dict):
    """Error against cost: forces at delta/a = 0.01 and 0.40625, trajectories at both."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    markers = {"closed-form": "*", "reynolds": "o", "stokes-exact": "s", "stokes-fem": "^"}
    for ax, delta in zip(axes[0], (0.01, 0.40625)):
        i = choice["deltas"].index(delta)
        points = []
        for e in choice["forces"]:
            cost = e["jit_s"][i] if e["jit_s"][i][0] is not None else e["python_s"][i]
            x, y = max(cost), max(e["error"][i])
            family = e["model"] + (f" {e['options'].get('grid', '')} {e['options'].get('profile', '')}"
                                   if e["model"] == "reynolds" else "")
            points.append((x, y, family))
        for family in dict.fromkeys(p[2] for p in points):
            xs = [p[0] for p in points if p[2] == family]
            ys = [p[1] for p in points if p[2] == family]
            ax.loglog(xs, ys, markers.get(family.split()[0], "x"), ms=5, label=family, alpha=0.8)
        front, best = [], math.inf
        for x, y, _ in sorted(points):
            if y < best:
                front.append((x, y))
                best = y
        ax.loglog(*zip(*front), "k-", lw=0.8, drawstyle="steps-post", label="Pareto front")
        ax.set_xlabel("seconds per force evaluation (jit where callable, else Python)")
        ax.set_ylabel("largest error over kappa <= 0.99")
        ax.set_title(f"forces, delta/a = {delta:g}")
        ax.legend(fontsize=6)
    matrix = [t for t in results["trajectories"] if t["delta_over_a"] in results["settings"]["trajectory_deltas"]]
    for ax, t in zip(axes[1], matrix):
        for (equations, forces) in dict.fromkeys((r["equations"], r["forces"]) for r in t["runs"]):
            for method, mk in zip(METHODS, "osdv"):
                rows = [r for r in t["runs"] if (r["equations"], r["forces"], r["method"]) == (equations, forces, method)]
                ax.loglog([r["wall_s"] for r in rows], [max(r["error"], 1e-16) for r in rows], mk + "-", ms=4,
                          lw=0.6, label=f"{equations} {forces} {method}")
        ax.set_xlabel("wall seconds per run")
        ax.set_ylabel("relative error of (X_b, 1 - kappa) at t_end")
        ax.set_title(f"trajectories, delta/a = {t['delta_over_a']:g}")
        ax.legend(fontsize=5, ncol=2)
    fig.tight_layout()
    return fig


def trajectory_part(trajectory_deltas=TRAJECTORY_DELTAS, equation_deltas=EQUATION_DELTAS,
                    repeats=TRAJECTORY_REPEATS, started: float | None = None) -> list[dict]:
    """Part B: :func:`trajectory_study` at every delta/a of either tuple."""
    started = time.perf_counter() if started is None else started
    trajectories = []
    for delta in sorted(set(trajectory_deltas) | set(equation_deltas)):
        full = delta in trajectory_deltas
        trajectories.append(trajectory_study(delta, repeats=repeats if full else 1, full=full))
        print(f"trajectories delta/a {delta}: {time.perf_counter() - started:.0f} s", file=sys.stderr)
    return trajectories


def rerun_trajectories(results: dict) -> dict:
    """Stored results with part B run again (after a change to the equations of motion, which part A's
    forces do not see); when and where is recorded beside the forces' date."""
    started = time.perf_counter()
    results["trajectories"] = trajectory_part(started=started)
    results["trajectories_rerun"] = {"date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
                                     "machine": machine(), "run_seconds": time.perf_counter() - started}
    return results


def rederive(results: dict) -> dict:
    """Stored results with every trajectory error recomputed from the stored final states.

    Lets the error measure change without repeating the ten-minute study.
    """
    for t in results["trajectories"]:
        for r in t["runs"]:
            r.update(_trajectory_error(r["final"], t["reference"]["final"]))
    return results


def main(argv=None) -> None:
    """Run the study and publish it; ``--from-json`` republishes the stored results instead, ``--trajectories``
    with part B run again."""
    import argparse

    import matplotlib.pyplot as plt

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--from-json", action="store_true",
                        help="re-derive the errors and republish from results/accuracy.json, without running")
    parser.add_argument("--trajectories", action="store_true",
                        help="run the trajectories again and keep the stored forces (results/accuracy.json)")
    args = parser.parse_args(argv)
    stored = json.loads((RESULTS / "accuracy.json").read_text()) if args.from_json or args.trajectories else None
    results = rederive(stored) if args.from_json else rerun_trajectories(stored) if args.trajectories else run()
    write_text(RESULTS / "accuracy.json", json.dumps(results, indent=1) + "\n")  # first: ten minutes of numbers
    choice = model_choice(results)
    fig = pareto_figure(results, choice)
    save_figure(RESULTS / "accuracy_pareto.png", fig, dpi=110)
    plt.close(fig)
    publish("accuracy", results, to_markdown(results, choice))


if __name__ == "__main__":
    main()
