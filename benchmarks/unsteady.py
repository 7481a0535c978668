r"""The unsteady Navier-Stokes solver: accuracy against resolution, cost per step, cost per simulated second.

Accuracy. At kappa = 0.5, 0.99 and 0.9999 (a = 8 mm, b = 11.25 mm) the steady loads of
the solver at Re ~ 1e-12 (four fixed steps of 100 viscous times, as in
tests/test_unsteady_stokes.py) against :mod:`lubrication.stokes_exact`: the largest
relative error of f_eps per eps', f_chi and T_a per W_a, against n_theta (n_r = 16) and
against n_r (n_theta at its converged value). Reported: the smallest measured grid
reaching 1e-3 and 1e-6, and the cost of one step there (a step that factorises; a
step that reuses a factorisation by defect correction).

Finite elements. The Taylor-Hood solver :func:`lubrication.stokes.stokes_resistance`
on its bipolar mesh (meshing, assembly, factorisation and three solves), at the
meshes that reach the same errors: the cost an ALE finite-element step would at
least pay.

Cost per simulated second. The apparatus's inner cylinder (a = 8 mm, b = 11.25 mm,
nu = 2e-4 m^2/s, rho = 1000 kg/m^3) moving like a released one: x_a = 0.5 delta sin(5 t),
z_a = -0.5 delta + 0.2 delta sin(5 t + 1), Omega_a = 2 + sin(5 t), Omega_b = 1 (kappa
between 0.5 and 0.8), from rest, rtol = 1e-4, default resolution, over 0.3 s; median
of three runs of the solver as it is (factorisations reused) and of the baseline
that re-assembles and re-factorises every solve (``StepControl(reuse=False)``), in
the same run. One step of a dense-matrix baseline (dense assembly, dense LU) is timed
at the same resolution.

BLAS runs on one thread inside the steps (threadpoolctl). Run
``python -m benchmarks.unsteady`` (several minutes); it writes
``benchmarks/results/unsteady.json`` and ``unsteady.md``.
"""

from __future__ import annotations

import datetime
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.publish import publish
from lubrication.stokes_exact import stokes_exact_resistance
from lubrication.unsteady import (
    AnnulusMap,
    PrescribedMotion,
    Resolution,
    StepControl,
    UnsteadySolver,
    default_resolution,
    prescribed_wall,
    run_prescribed,
)
from lubrication.unsteady.system import StepSystem, one_blas_thread

A, B, NU, RHO = 0.008, 0.01125, 2e-4, 1000.0
MU = RHO * NU
DELTA = B - A
T_VISC = DELTA**2 / NU
V = 1e-13
KAPPAS = (0.5, 0.99, 0.9999)
N_THETA = {0.5: (8, 12, 16, 24, 32, 48), 0.99: (64, 128, 192, 256, 384),
           0.9999: (512, 1024, 1536, 2048, 3072)}
N_R = (6, 8, 10, 12, 16, 24)


def steady_errors(kappa: float, resolution: Resolution) -> tuple[float, float]:
    """Largest relative error of f_eps, f_chi(W_a), T_a(W_a), and the wall time of the two runs."""
    e_eps = complex(math.sin(0.4), math.cos(0.4))
    z0 = kappa * DELTA * e_eps
    start = time.perf_counter()
    errs = []
    for motion in ("radial", "w_a"):
        w = 1e-6
        u = V * e_eps if motion == "radial" else 0j
        spec = {"x_a": (z0.real, u.real / w, w, 0.0) if u else z0.real,
                "z_a": (z0.imag, u.imag / w, w, 0.0) if u else z0.imag,
                "omega_a": V / A if motion == "w_a" else 0.0}
        run = run_prescribed(A, B, NU, RHO, PrescribedMotion(**spec), 400 * T_VISC, resolution=resolution,
                             dt_fixed=100 * T_VISC)
        z = complex(run.x_a[-1], run.z_a[-1])
        omk = (DELTA - abs(z)) / DELTA
        r = stokes_exact_resistance(A, DELTA, MU, 1.0 - omk, omk)
        f = complex(run.F_x[-1], run.F_z[-1])
        if motion == "radial":
            errs.append(abs((f * np.conj(e_eps)).real / (V * r[0]) - 1.0))
        else:
            errs.append(abs((f * np.conj(-1j * e_eps)).real / (r[1] * V / A) - 1.0))
            errs.append(abs(run.T_a[-1] / (r[2] * V / A) - 1.0))
    return max(errs), time.perf_counter() - start


def step_costs(kappa: float, resolution: Resolution, repeats: int = 3) -> dict:
    """Median wall time of a step that factorises and of one that reuses the factors."""
    z0 = kappa * DELTA * 1j
    solver = UnsteadySolver(A, B, NU, RHO, resolution, control=StepControl(adaptive=False))
    solver.start(z0, (0.0, 0.0, 1.0, 0.0))
    q = (0.0, 0.0, 1.0, 0.0)
    dt = 1e-3 * T_VISC
    for _ in range(3):
        solver.step(dt, prescribed_wall(q), z0)
    fact, reuse = [], []
    for _ in range(repeats):
        solver._factors = None
        t0 = time.perf_counter()
        solver.step(dt, prescribed_wall(q), z0 + 1e-9 * DELTA)
        fact.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        solver.step(dt, prescribed_wall(q), z0 + 2e-9 * DELTA)
        reuse.append(time.perf_counter() - t0)
    return {"factorising_step_s": statistics.median(fact), "reusing_step_s": statistics.median(reuse)}


def dense_baseline_step(kappa: float, resolution: Resolution) -> float:
    """One dense assembly (entry by entry from the blocks) and dense LU of the flow operator."""
    import scipy.linalg as sl

    geo = AnnulusMap(A / B, 1.0, kappa * DELTA / B * 1j)
    solver = UnsteadySolver(A, B, NU, RHO, resolution)
    solver.start(kappa * DELTA * 1j)
    with one_blas_thread():
        t0 = time.perf_counter()
        system = StepSystem(solver.grid, geo, NU / B**2, RHO * B**3, 1e3)
        dense = system.op.dense()
        lu = sl.lu_factor(dense, check_finite=False)
        sl.lu_solve(lu, system.data, check_finite=False)
        return time.perf_counter() - t0


def fe_costs(kappa: float, targets=(1e-3, 1e-6)) -> list[dict]:
    """Finite-element resistance: error and cost along a sequence of meshes."""
    from lubrication.stokes import clear_cache, default_mesh, stokes_resistance

    r = stokes_exact_resistance(A, DELTA, 1.0, kappa, 1.0 - kappa)
    n0, m0 = default_mesh(DELTA / A)
    rows = []
    for f in (0.25, 0.5, 1.0, 2.0):
        n_around, n_across = max(8, int(8 * round(n0 * f / 8))), max(2, int(round(m0 * f)))
        clear_cache()
        res = stokes_resistance(A, B, kappa, n_around=n_around, n_across=n_across, mu=1.0)
        err = max(abs(res.f_eps_per_eps_dot / r[0] - 1.0), abs(res.f_chi_per_w_a / r[1] - 1.0),
                  abs(res.t_a_per_w_a / r[2] - 1.0))
        rows.append({"n_around": n_around, "n_across": n_across, "dofs": res.dofs, "error": err,
                     "wall_time_s": res.wall_time_s})
        if err < min(targets) * 0.5:
            break
    return rows


def representative(reuse: bool) -> dict:
    w = 5.0
    motion = PrescribedMotion(x_a=(0.0, 0.5 * DELTA, w, 0.0), z_a=(-0.5 * DELTA, 0.2 * DELTA, w, 1.0),
                              omega_a=(2.0, 1.0, w, 0.0), omega_b=1.0)
    t_end = 0.3
    run = run_prescribed(A, B, NU, RHO, motion, t_end, control=StepControl(rtol=1e-4, reuse=reuse))
    return {"wall_time_s": run.wall_time_s, "per_simulated_second_s": run.wall_time_s / t_end,
            "steps": run.steps, "rejected": run.rejected, "factorisations": run.factorisations,
            "sweeps": run.sweeps, "resolution": [run.resolution.n_theta, run.resolution.n_r],
            "kappa_max": float(np.max(np.hypot(run.x_a, run.z_a)) / DELTA)}


def main() -> dict:
    results = {"date": datetime.date.today().isoformat(), "accuracy": {}, "fe": {}, "representative": {}}
    lines = ["# Unsteady Navier-Stokes solver", "",
             "Steady loads at Re ~ 1e-12 against the exact Stokes loads (largest relative error of f_eps, "
             "f_chi and T_a per W_a); a = 8 mm, b = 11.25 mm.", ""]
    for kappa in KAPPAS:
        rows = []
        for nt in N_THETA[kappa]:
            err, wall = steady_errors(kappa, Resolution(nt, 16))
            rows.append({"n_theta": nt, "n_r": 16, "error": err, "run_s": wall})
        best = min(rows, key=lambda r: r["error"])["n_theta"]
        for nr in N_R:
            err, wall = steady_errors(kappa, Resolution(best, nr))
            rows.append({"n_theta": best, "n_r": nr, "error": err, "run_s": wall})
        for target in (1e-3, 1e-6):
            ok = [r for r in rows if r["error"] <= target]
            if ok:
                pick = min(ok, key=lambda r: r["n_theta"] * r["n_r"])
                pick[f"step_costs_at_{target:g}"] = step_costs(kappa, Resolution(pick["n_theta"], pick["n_r"]))
        results["accuracy"][str(kappa)] = rows
        lines += [f"## kappa = {kappa}", "", "| n_theta | n_r | error | step (factorise) s | step (reuse) s |",
                  "|---|---|---|---|---|"]
        for r in rows:
            costs = next((v for k, v in r.items() if k.startswith("step_costs")), None)
            cost = f"{costs['factorising_step_s']:.3g} | {costs['reusing_step_s']:.3g}" if costs else " | "
            lines.append(f"| {r['n_theta']} | {r['n_r']} | {r['error']:.2e} | {cost} |")
        lines.append("")
    for kappa in (0.5, 0.99):
        try:
            results["fe"][str(kappa)] = fe_costs(kappa)
        except ImportError:  # pragma: no cover - the fem extra
            results["fe"][str(kappa)] = "scikit-fem not installed"
            continue
        lines += [f"## Finite elements (Taylor-Hood, bipolar mesh), kappa = {kappa}", "",
                  "| n_around | n_across | dofs | error | mesh+assembly+LU+3 solves s |", "|---|---|---|---|---|"]
        lines += [f"| {r['n_around']} | {r['n_across']} | {r['dofs']} | {r['error']:.2e} | {r['wall_time_s']:.3g} |"
                  for r in results["fe"][str(kappa)]]
        lines.append("")
    res = default_resolution(AnnulusMap(A, B, 0.8 * DELTA * 1j))
    results["dense_step_s"] = dense_baseline_step(0.8, res)
    for reuse in (True, False):
        runs = [representative(reuse) for _ in range(3)]
        med = statistics.median(r["per_simulated_second_s"] for r in runs)
        results["representative"]["reuse" if reuse else "baseline"] = {"runs": runs, "median_per_simulated_second_s": med}
    rep = results["representative"]
    lines += ["## Representative motion (released-cylinder-like, kappa 0.5-0.8, rtol 1e-4, 0.3 s simulated)", "",
              "| solver | wall s per simulated s (median of 3) | steps | factorisations |", "|---|---|---|---|",
              f"| factorisations reused | {rep['reuse']['median_per_simulated_second_s']:.3g} | "
              f"{rep['reuse']['runs'][0]['steps']} | {rep['reuse']['runs'][0]['factorisations']} |",
              f"| re-factorise every solve | {rep['baseline']['median_per_simulated_second_s']:.3g} | "
              f"{rep['baseline']['runs'][0]['steps']} | {rep['baseline']['runs'][0]['factorisations']} |", "",
              f"Dense assembly + dense LU of one step at {res.n_theta} x {res.n_r}: {results['dense_step_s']:.3g} s.", ""]
    publish("unsteady", results, "\n".join(lines))
    return results


if __name__ == "__main__":
    main()
