r"""Wall time against accuracy of trajectories, with a plain-Python explicit baseline.

The scene is the default of ``snail run`` (:func:`dynamics.scenes.load.load_scene`): the
steel apparatus in 200 cSt oil on 2.4 degrees, kappa0 = 0.5, phi0 = 0.5 from rest,
10 s. The inner cylinder falls to near contact in about 0.2 s and rocks there
while 1 - kappa closes to about 1e-6: the full model's radial relaxation rate,
~ (1 - kappa^2)^(-3/2) / (tau delta/a), makes it stiff.

Measured:

* the full model (2.1)-(2.4) (jitted right-hand side and Jacobian) and the reduced
  model (2.11), each with LSODA, BDF and Radau over a range of rtol; the error is
  taken at t_end against a run of the same model at rtol 1e-12, as the largest of
  |d phi|, |d X_b|/b, tau |d Omega_a|, tau |d Omega_b| and the relative error of 1 - kappa;
* the baseline: the same full model written in plain Python (closed forms (2.5)-(2.7)
  inline, no numba), integrated by ``solve_ivp``'s RK45 within a wall-time budget;
  its right-hand side must equal the jitted one to rounding. Where RK45 does not
  reach t_end in the budget, the comparison is made over the window it did reach:
  the jitted model is rerun to that time and the fastest (method, rtol) at least as
  accurate as the baseline gives the speed ratio, a lower bound for the whole run.
  The same plain-Python model with LSODA (Jacobian by scipy's finite differences)
  separates the gain of the jit from that of the implicit method;
* ``snail run`` end to end as a subprocess, with the numba cache warm and, once,
  cold (NUMBA_CACHE_DIR pointing at an empty folder: what a fresh install pays).

Run ``python -m benchmarks.trajectories`` (or ``python benchmarks/trajectories.py``)
from the project root; it writes ``benchmarks/results/trajectories.json`` and
``trajectories.md``.
"""

from __future__ import annotations

import datetime
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import RK45, solve_ivp

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.publish import publish  # noqa: E402
from benchmarks.reynolds import _machine  # noqa: E402
from dynamics.equations import full  # noqa: E402
from dynamics.equations.forces import closed_form  # noqa: E402
from dynamics.scenes import load_scene  # noqa: E402
from dynamics.simulate import simulate_full, simulate_reduced  # noqa: E402

__all__ = ["run", "plain_rhs", "to_markdown"]

METHODS = ("LSODA", "BDF", "Radau")
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
REFERENCE_RTOL = 1e-12
REPEATS = 3  # timing samples per configuration; the median is reported
BASELINE_BUDGET = 30.0  # s of wall time for the RK45 baseline
ROOT = Path(__file__).resolve().parents[1]
GOALS = {"speed_ratio": 30.0, "warm_scene_seconds": 1.0, "snail_run_seconds": 10.0}


def plain_rhs(t, y, ap) -> np.ndarray:
    """The right-hand side of :func:`dynamics.equations.full.rhs` in plain Python, forces (2.5)-(2.7) inline.

    Same state (u_x, u_z, v_x, v_z, Omega_a, Omega_b, X_b) and the same
    equations; see the derivation in :mod:`dynamics.equations.full`.
    """
    a, b = ap.a, ap.b
    delta = b - a
    ux, uz, vx, vz, omega_a, omega_b = y[0], y[1], y[2], y[3], y[4], y[5]
    big_u = math.hypot(ux, uz)
    one_plus = 1.0 + big_u * big_u
    kappa = big_u / math.sqrt(one_plus)
    omk = 1.0 / (one_plus * (1.0 + kappa))
    zeta = math.sqrt(omk * (1.0 + kappa))
    if big_u > 0.0:
        ex, ez = ux / big_u, uz / big_u
    else:
        speed = math.hypot(vx, vz)
        ex, ez = (vx / speed, vz / speed) if speed > 0.0 else (0.0, 1.0)
    cx, cz = ez, -ex
    eps = kappa * delta
    eps_dot = ex * vx + ez * vz
    chi_dot = (cx * vx + cz * vz) / eps if eps > 0.0 else 0.0
    w_a, w_b = omega_a - chi_dot, omega_b - chi_dot
    c = 4.0 * math.pi * ap.mu * a**3 * ap.length
    f_eps = -3.0 * c * eps_dot / (delta**3 * zeta**3)
    f_chi = 3.0 * c * kappa * (w_a + w_b) / (delta**2 * (2.0 + kappa * kappa) * zeta)
    t_a = c * (omk * (1.0 + kappa) * w_b - (1.0 + 2.0 * kappa * kappa) * w_a) / (delta * (2.0 + kappa * kappa) * zeta)
    fx, fz = f_eps * ex + f_chi * cx, f_eps * ez + f_chi * cz
    m_eff, m_r = ap.m_eff, ap.m_a_reduced
    gs, gc = ap.g * math.sin(ap.alpha), ap.g * math.cos(ap.alpha)
    inertia_b = (ap.M + ap.m_b) * b * b - (m_r * b) ** 2 / m_eff
    omega_b_dot = (ap.M * gs * b - t_a - eps * f_chi - (m_r * b / m_eff) * (fx + m_r * gs)) / inertia_b
    scale = 1.0 / (delta * zeta)
    stretch = big_u * big_u * eps_dot
    return np.array([(vx + stretch * ex) * scale, (vz + stretch * ez) * scale,
                     (fx + m_r * gs - m_r * b * omega_b_dot) / m_eff, (fz - m_r * gc) / m_eff,
                     t_a / (0.5 * ap.m_a * a * a), omega_b_dot, b * omega_b])


def _rhs_agreement(apparatus, rng) -> float:
    """Largest relative difference, component by component, of the plain and the jitted right-hand side."""
    p = full.params_array(apparatus)
    model = full.model_arguments(closed_form())
    worst = 0.0
    for _ in range(200):
        y = full.initial_state(apparatus, rng.uniform(0.0, 0.9999), rng.uniform(0, 2 * math.pi),
                               rng.normal(0, 5), rng.normal(0, 5), rng.normal(0, 20), rng.normal(0, 20))
        jit, plain = full.rhs(0.0, y, p, *model), plain_rhs(0.0, y, apparatus)
        worst = max(worst, float(np.max(np.abs(plain - jit) / (np.abs(jit) + 1e-300 + 1e-12 * np.max(np.abs(jit))))))
    return worst


def _end_state(columns, apparatus) -> np.ndarray:
    """phi, X_b/b, tau Omega_a, tau Omega_b and log(1 - kappa) at the last sample."""
    tau = apparatus.tau
    return np.array([columns["phi"][-1], columns["x_b"][-1] / apparatus.b, tau * columns["omega_a"][-1],
                     tau * columns["omega_b"][-1], math.log(columns["one_minus_kappa"][-1])])


def _error(state, ref) -> float:
    """Largest difference of two end states; phi modulo 2 pi (a single state cannot be unwrapped)."""
    diff = state - ref
    diff[0] = (diff[0] + math.pi) % (2.0 * math.pi) - math.pi
    # a difference of log(1 - kappa) is the relative error of 1 - kappa
    return float(np.max(np.abs(diff)))


def _timed(fn, repeats=REPEATS):
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return float(np.median(times)), float(min(times)), result


def _sweep(simulate, apparatus, ref, rtols, repeats) -> list[dict]:
    rows = []
    for method in METHODS:
        for rtol in rtols:
            seconds, fastest, traj = _timed(lambda: simulate(rtol, method), repeats)
            rows.append({"method": method, "rtol": rtol, "seconds": seconds, "fastest": fastest,
                         "steps": traj.steps, "nfev": traj.nfev, "njev": traj.njev, "status": traj.status,
                         "error": _error(_end_state(traj.columns, apparatus), ref)})
    return rows


def _baseline_rk45(apparatus, initial, t_end, budget):
    """Plain-Python RK45 stepped until t_end or the wall-time budget; (t reached, state, steps, nfev, seconds)."""
    y0 = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                            initial.omega_a, initial.omega_b)
    typical = full.typical_scales(apparatus)
    rtol = 1e-8
    solver = RK45(lambda t, y: plain_rhs(t, y, apparatus), 0.0, y0, t_end, rtol=rtol, atol=rtol * typical)
    start = time.perf_counter()
    steps = 0
    while solver.status == "running" and time.perf_counter() - start < budget:
        solver.step()
        steps += 1
    return solver.t, solver.y.copy(), steps, solver.nfev, time.perf_counter() - start, rtol


def _snail_run(env_extra: dict) -> tuple[float, float]:
    """Wall and CPU (user + system) seconds of ``snail run`` as a subprocess.

    On a shared machine the wall time carries other jobs' load; the CPU time does not.
    """
    with tempfile.TemporaryDirectory() as out:
        env = {**os.environ, **env_extra, "PYTHONPATH": str(ROOT)}
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", out], cwd=ROOT, env=env,
                       check=True, capture_output=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def run(rtols=RTOLS, repeats=REPEATS, baseline_budget=BASELINE_BUDGET, subprocesses=True, seed=0) -> dict:
    """Times and errors of every configuration, the baseline, and ``snail run`` as a subprocess.

    Returns plain data (JSON-serialisable). Raises AssertionError if the
    plain-Python right-hand side departs from the jitted one by more than 1e-12.
    """
    started = time.perf_counter()
    scene = load_scene()
    ap, initial, t_end = scene.apparatus, scene.initial, scene.run.t_end
    model = closed_form()
    agreement = _rhs_agreement(ap, np.random.default_rng(seed))
    assert agreement <= 1e-12, f"plain-Python right-hand side differs from the jitted one by {agreement:.2e}"

    def full_run(rtol, method, t=t_end):
        return simulate_full(ap, model, initial, t, rtol=rtol, method=method)

    def reduced_run(rtol, method):
        return simulate_reduced(ap.reduced_params, initial, t_end / ap.tau, apparatus=ap, rtol=rtol, method=method)

    full_run(1e-8, "LSODA")  # warm-up: numba's cache (or compilation) is not timed
    full_ref = _end_state(full_run(REFERENCE_RTOL, "Radau").columns, ap)
    full_ref_lsoda = _end_state(full_run(REFERENCE_RTOL, "LSODA").columns, ap)
    reduced_ref = _end_state(reduced_run(REFERENCE_RTOL, "Radau").columns, ap)
    full_rows = _sweep(full_run, ap, full_ref, rtols, repeats)
    reduced_rows = _sweep(lambda rtol, method: reduced_run(rtol, method), ap, reduced_ref, rtols, repeats)
    default_seconds, default_fastest, _ = _timed(lambda: full_run(scene.run.rtol, "LSODA"), 5)

    # baseline: RK45 on the plain-Python model, then the jitted model over the same window
    t_reached, y_reached, steps, nfev, seconds, base_rtol = _baseline_rk45(ap, initial, t_end, baseline_budget)
    window_ref = _end_state(full_run(REFERENCE_RTOL, "Radau", t_reached).columns, ap)
    base_error = _error(_end_state(full.observables(ap, y_reached[:, None]), ap), window_ref)
    window = []
    for method in METHODS:
        for rtol in (*rtols, 1e-12):
            secs, fastest, traj = _timed(lambda: full_run(rtol, method, t_reached), repeats)
            window.append({"method": method, "rtol": rtol, "seconds": secs, "fastest": fastest,
                           "error": _error(_end_state(traj.columns, ap), window_ref)})
    matching = [w for w in window if w["error"] <= base_error]
    best = min(matching, key=lambda w: w["seconds"]) if matching else None
    y0 = full.initial_state(ap, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                            initial.omega_a, initial.omega_b)
    typical = full.typical_scales(ap)
    plain_lsoda_seconds, _, sol = _timed(lambda: solve_ivp(lambda t, y: plain_rhs(t, y, ap), (0.0, t_end), y0,
                                                           method="LSODA", rtol=1e-8, atol=1e-8 * typical), 1)
    plain_lsoda_error = _error(_end_state(full.observables(ap, sol.y[:, -1:]), ap), full_ref)
    jit_lsoda = next(r for r in full_rows if r["method"] == "LSODA" and r["rtol"] == 1e-8)

    snail = {}
    if subprocesses:
        _snail_run({})  # fills the default cache
        warm = np.array([_snail_run({}) for _ in range(3)])
        snail["warm_seconds"], snail["warm_cpu_seconds"] = (float(x) for x in np.median(warm, axis=0))
        with tempfile.TemporaryDirectory() as cache:
            snail["cold_seconds"], snail["cold_cpu_seconds"] = _snail_run({"NUMBA_CACHE_DIR": cache})
    return {
        "machine": _machine(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "scene": {"apparatus": "steel", "nu": ap.nu, "alpha_deg": math.degrees(ap.alpha), "kappa0": initial.kappa,
                  "phi0": initial.phi, "t_end": t_end, "tau": ap.tau, "delta_over_a": ap.delta_over_a},
        "settings": {"rtols": list(rtols), "reference_rtol": REFERENCE_RTOL, "repeats": repeats,
                     "baseline_budget": baseline_budget},
        "reference_radau_vs_lsoda": _error(full_ref_lsoda, full_ref),
        "rhs_agreement": agreement,
        "full": full_rows,
        "reduced": reduced_rows,
        "default_scene_seconds": default_seconds,
        "default_scene_fastest": default_fastest,
        "baseline": {"method": "RK45", "rtol": base_rtol, "t_reached": float(t_reached), "steps": steps,
                     "nfev": nfev, "seconds": seconds, "error": base_error,
                     "completed": bool(t_reached >= t_end)},
        "window": window,
        "equal_accuracy": None if best is None else {**best, "speed_ratio": seconds / best["seconds"]},
        "plain_lsoda": {"seconds": plain_lsoda_seconds, "error": plain_lsoda_error,
                        "jit_seconds": jit_lsoda["seconds"], "ratio": plain_lsoda_seconds / jit_lsoda["seconds"]},
        "snail_run": snail,
        "run_seconds": time.perf_counter() - started,
    }


def _table(header, lines) -> list[str]:
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
            *("| " + " | ".join(map(str, line)) + " |" for line in lines), ""]


def to_markdown(results: dict) -> str:
    m, sc, base, eq = results["machine"], results["scene"], results["baseline"], results["equal_accuracy"]
    snail, plain = results["snail_run"], results["plain_lsoda"]
    out = ["# Trajectories: wall time against accuracy", "",
           f"{m['cpu']}, {m['cores']} cores; Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, "
           f"numba {m['numba']}. {results['date']}; the run took {results['run_seconds']:.0f} s.", "",
           f"Default scene: steel, nu = {sc['nu']:g} m^2/s, {sc['alpha_deg']:g} deg, kappa0 = {sc['kappa0']}, "
           f"phi0 = {sc['phi0']}, from rest, {sc['t_end']:g} s (tau = {sc['tau']:.4g} s, delta/a = "
           f"{sc['delta_over_a']:.3f}). Error at t_end against the same model at rtol {REFERENCE_RTOL:g}: the "
           "largest of |d phi|, |d X_b|/b, tau |d Omega_a|, tau |d Omega_b| and the relative error of 1 - kappa. "
           f"Times are medians of {results['settings']['repeats']} runs, JIT cache warm. The two references "
           f"(Radau, LSODA at {REFERENCE_RTOL:g}) differ by {results['reference_radau_vs_lsoda']:.1e}.", ""]
    goal_lines = []
    if eq is not None:
        goal_lines.append([f">= {GOALS['speed_ratio']:g}x faster than the plain-Python RK45 baseline at equal accuracy",
                           f"{eq['speed_ratio']:.0f}x over the first {base['t_reached']:.3g} s "
                           f"({eq['method']}, rtol {eq['rtol']:g}: {eq['seconds']:.3g} s, error {eq['error']:.1e})",
                           "yes" if eq["speed_ratio"] >= GOALS["speed_ratio"] else "no"])
    goal_lines.append([f"default scene < {GOALS['warm_scene_seconds']:g} s, cache warm",
                       f"{results['default_scene_seconds']:.3f} s (fastest {results['default_scene_fastest']:.3f} s)",
                       "yes" if results["default_scene_seconds"] < GOALS["warm_scene_seconds"] else "no"])
    if snail:
        goal_lines.append([f"`snail run` end to end < {GOALS['snail_run_seconds']:g} s",
                           f"{snail['warm_seconds']:.2f} s warm (CPU {snail['warm_cpu_seconds']:.2f} s); "
                           f"{snail['cold_seconds']:.1f} s with an empty numba cache "
                           f"(CPU {snail['cold_cpu_seconds']:.1f} s)",
                           "yes" if snail["warm_seconds"] < GOALS["snail_run_seconds"] else "no"])
    out += ["## Goals", ""] + _table(["goal", "measured", "met"], goal_lines)
    for key, title in (("full", "Full model (2.1)-(2.4), jitted"), ("reduced", "Reduced model (2.11)")):
        out += [f"## {title}", ""]
        out += _table(["method", "rtol", "wall s", "steps", "nfev", "njev", "error"],
                      [[r["method"], f"{r['rtol']:g}", f"{r['seconds']:.3g}", r["steps"], r["nfev"], r["njev"],
                        f"{r['error']:.1e}"] for r in results[key]])
    out += ["## Baseline: plain Python, RK45", "",
            f"The plain-Python right-hand side equals the jitted one to {results['rhs_agreement']:.1e} (relative, "
            f"200 random states). RK45 at rtol {base['rtol']:g} was given {base['seconds']:.0f} s of wall time: "
            + (f"it completed the {sc['t_end']:g} s." if base["completed"] else
               f"it reached t = {base['t_reached']:.4g} s of {sc['t_end']:g} s in {base['steps']} steps "
               f"({base['nfev']} evaluations), with error {base['error']:.1e} there. The stiffness (the radial "
               "relaxation rate grows as (1 - kappa^2)^(-3/2) near contact) bounds its step.")
            + " The jitted model over the same window:", ""]
    out += _table(["method", "rtol", "wall s", "error", "baseline / this"],
                  [[w["method"], f"{w['rtol']:g}", f"{w['seconds']:.3g}", f"{w['error']:.1e}",
                    f"{base['seconds'] / w['seconds']:.0f}"] for w in results["window"]])
    out += [f"The same plain-Python model with LSODA (scipy's finite-difference Jacobian) runs the whole scene at "
            f"rtol 1e-8 in {plain['seconds']:.2f} s (error {plain['error']:.1e}), {plain['ratio']:.1f} times the "
            f"jitted LSODA's {plain['jit_seconds']:.3f} s: this ratio is the jit's share of the gain over the "
            "baseline, the rest is the implicit method's.", ""]
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("trajectories", results, to_markdown(results))


if __name__ == "__main__":
    main()
