r"""Wall time against accuracy of trajectories: the compiled Radau IIA engine against scipy's best.

The scene is the default of ``snail run`` (:func:`dynamics.scenes.load.load_scene`): the
steel apparatus in 200 cSt oil on 2.4 degrees, kappa0 = 0.5, phi0 = 0.5 from rest,
10 s. The inner cylinder falls to near contact in about 0.2 s and rocks there
while 1 - kappa closes to about 1e-6: the full model's radial relaxation rate,
~ (1 - kappa^2)^(-3/2) / (tau delta/a), makes it stiff, and an explicit method
is no fair baseline (RK45 needs some 1e5 steps per second of it).

Solvers, each on the full model (2.1)-(2.4) with the closed forms (2.5)-(2.7) and
on the reduced model (2.11), with the same state, tolerances (atol = rtol times
:func:`dynamics.equations.full.typical_scales`; atol = rtol for the scaled
reduced model) and one output row per step:

``lsoda-python``
    scipy's LSODA (``solve_ivp``) on the right-hand side written in plain Python
    (:func:`plain_rhs`, :func:`plain_reduced_rhs`; no numba), with scipy's
    finite-difference Jacobian: what a careful user writes without this package;
``lsoda-jit``, ``radau-jit``
    scipy's LSODA and Radau on the compiled right-hand side and Jacobian of
    :mod:`dynamics.equations` (called from Python once per evaluation);
``engine``
    the compiled Radau IIA integrator, :func:`numerics.engine.integrate`, on the
    same compiled functions: no Python per step.

The plain-Python right-hand sides must equal the compiled ones to 1e-12
(asserted). Every (model, solver, rtol) is timed ``REPEATS`` times, the repeats
interleaved (each round visits every configuration in a shuffled order, so that
the load of a shared machine falls on all alike), and the median wall time is
reported, with the median CPU time in the JSON. The error is taken at t_end
against the engine at rtol 1e-12, as the largest of |d phi|, |d X_b|/b,
tau |d Omega_a|, tau |d Omega_b| and the relative error of 1 - kappa; the two
references (the engine and scipy's LSODA, jitted, both at 1e-12) are compared.

Reported: per model, the table of times and errors; the ratio of each baseline's
time to the engine's at the same rtol, and at equal accuracy (the baseline's
cheapest run at least as accurate as the engine's at that rtol); and
:func:`dynamics.simulation.simulate` on the default scene end to end (events,
output columns). Run ``python -m benchmarks.trajectories`` from the project
root; it writes ``benchmarks/results/trajectories.json`` and ``trajectories.md``.
"""

from __future__ import annotations

import datetime
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import interleave, machine, publish
from dynamics.equations import full, reduced
from dynamics.equations.limits import GAP_FLOOR
from dynamics.scenes import load_scene
from dynamics.simulation import simulate
from lubrication.registry import kernel_model
from numerics import engine

__all__ = ["plain_reduced_rhs", "plain_rhs", "run", "to_markdown"]

SOLVERS = ("lsoda-python", "lsoda-jit", "radau-jit", "engine")
BASELINES = SOLVERS[:-1]
LABELS = {"lsoda-python": "scipy LSODA, plain-Python right-hand side",
          "lsoda-jit": "scipy LSODA, compiled right-hand side and Jacobian",
          "radau-jit": "scipy Radau, compiled right-hand side and Jacobian",
          "engine": "compiled Radau IIA engine"}
MODELS = ("full", "reduced")
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-11)
HEADLINE_RTOL = 1e-8  # the scene's
REFERENCE_RTOL = 1e-12
REPEATS = 5
GOALS = {"warm_scene_seconds": 1.0}


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


def plain_reduced_rhs(t, y, s, upsilon, mu_ratio) -> np.ndarray:
    """(2.11a-d) in the stretched variables (xi, eta, Omega_a, Omega_b, X_b) of
    :mod:`dynamics.equations.reduced`, in plain Python: rho^2 = 1 + xi^2 + eta^2,
    W = (Omega_a + Omega_b)/2, D = Omega_b - Omega_a."""
    xi, eta, omega_a, omega_b = y[0], y[1], y[2], y[3]
    rho2 = 1.0 + xi * xi + eta * eta
    rho = math.sqrt(rho2)
    w, d = 0.5 * (omega_a + omega_b), omega_b - omega_a
    return np.array([eta * w + 0.5 * xi * eta / rho2, -xi * w - 1.0 - 0.5 * xi * xi / rho2,
                     (d * rho / 3.0 + xi / rho) / upsilon,
                     (s + 0.5 * xi / rho - d * rho / 6.0) / (mu_ratio * upsilon), omega_b])


class _Problem:
    """One model of the scene as every solver sees it: compiled and plain functions, y0, atol, end state."""

    def __init__(self, model: str, scene):
        ap, initial = scene.apparatus, scene.initial
        self.name, self.apparatus, self.phi0 = model, ap, initial.phi
        if model == "full":
            model = kernel_model("closed-form")
            self.args = full.run_args(ap, model, gap_floor=GAP_FLOOR)
            self.fun, self.jac = full.model_functions(model)[:2]
            self.plain = lambda t, y: plain_rhs(t, y, ap)
            self.y0 = full.initial_state(ap, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                                         initial.omega_a, initial.omega_b)
            self.typical = full.typical_scales(ap)
            self.t_end = scene.run.t_end
        else:
            params = ap.reduced_params
            self.args = params.args
            self.fun, self.jac = reduced.rhs, reduced.jacobian
            self.plain = lambda t, y: plain_reduced_rhs(t, y, params.s, params.upsilon, params.mu_ratio)
            self.y0 = reduced.initial_state(initial.kappa, initial.phi, initial.omega_a * ap.tau,
                                            initial.omega_b * ap.tau)
            self.typical = np.ones(self.y0.size)
            self.t_end = scene.run.t_end / ap.tau

    def agreement(self, rng, samples: int = 200) -> float:
        """Largest relative difference, component by component, of the plain and the compiled right-hand side."""
        worst = 0.0
        for _ in range(samples):
            y = self.y0 + rng.normal(0.0, 1.0, self.y0.size) * np.maximum(np.abs(self.y0), self.typical) * 3.0
            compiled, plain = self.fun(0.0, y, self.args), self.plain(0.0, y)
            size = np.abs(compiled) + 1e-12 * np.max(np.abs(compiled)) + 1e-300
            worst = max(worst, float(np.max(np.abs(plain - compiled) / size)))
        return worst

    def solve(self, solver: str, rtol: float) -> dict:
        """One run to t_end; the end state and the counts."""
        atol = rtol * self.typical
        span = (0.0, self.t_end)
        if solver == "engine":
            run = engine.integrate(self.fun, self.jac, span, self.y0, args=self.args, rtol=rtol, atol=atol,
                                   max_steps=10_000_000)
            return {"t": float(run.t[-1]), "y": run.y[:, -1].copy(), "steps": run.steps, "nfev": run.nfev,
                    "njev": run.njev, "success": bool(run.success)}
        if solver == "lsoda-python":
            sol = solve_ivp(self.plain, span, self.y0, method="LSODA", rtol=rtol, atol=atol)
        else:
            args = self.args
            sol = solve_ivp(lambda t, y: self.fun(t, y, args), span, self.y0,
                            method="LSODA" if solver == "lsoda-jit" else "Radau", rtol=rtol, atol=atol,
                            jac=lambda t, y: self.jac(t, y, args))
        return {"t": float(sol.t[-1]), "y": sol.y[:, -1].copy(), "steps": sol.t.size - 1, "nfev": int(sol.nfev),
                "njev": int(sol.njev), "success": bool(sol.success)}

    def end_state(self, y) -> np.ndarray:
        """phi, X_b/b, tau Omega_a, tau Omega_b and log(1 - kappa) of a state."""
        y = np.asarray(y, dtype=float)[:, None]
        if self.name == "full":
            ap = self.apparatus
            o = full.observables(ap, y, self.phi0)
            return np.array([o["phi"][0], o["x_b"][0] / ap.b, ap.tau * o["omega_a"][0], ap.tau * o["omega_b"][0],
                             math.log(o["one_minus_kappa"][0])])
        _, omk = reduced.stretched_to_kappa(math.hypot(y[0, 0], y[1, 0]))
        return np.array([math.atan2(y[0, 0], y[1, 0]), y[4, 0], y[2, 0], y[3, 0], math.log(omk)])


def _error(state, ref) -> float:
    """Largest difference of two end states; phi modulo 2 pi (a single state cannot be unwrapped).

    A difference of log(1 - kappa) is the relative error of 1 - kappa.
    """
    diff = state - ref
    diff[0] = (diff[0] + math.pi) % (2.0 * math.pi) - math.pi
    return float(np.max(np.abs(diff)))


def _timed(fn, *args) -> tuple[float, float, object]:
    """(wall s, CPU s, result) of one call ``fn(*args)``."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = fn(*args)
    return time.perf_counter() - wall, time.process_time() - cpu, result


def _equal_accuracy(rows: list[dict], rtol: float) -> dict:
    """Per baseline, its cheapest run at least as accurate as the engine's at ``rtol``, and the time ratio."""
    engine_row = next(r for r in rows if r["solver"] == "engine" and r["rtol"] == rtol)
    out = {"engine_rtol": rtol, "engine_error": engine_row["error"], "engine_seconds": engine_row["seconds"]}
    for solver in BASELINES:
        good = [r for r in rows if r["solver"] == solver and r["success"] and r["error"] <= engine_row["error"]]
        best = min(good, key=lambda r: r["seconds"]) if good else None
        out[solver] = None if best is None else {"rtol": best["rtol"], "seconds": best["seconds"],
                                                 "error": best["error"],
                                                 "ratio": best["seconds"] / engine_row["seconds"]}
    return out


def run(rtols=RTOLS, repeats: int = REPEATS, models=MODELS, seed: int = 0) -> dict:
    """Times and errors of every (model, solver, rtol), interleaved; plain data (JSON-serialisable).

    Raises AssertionError if a plain-Python right-hand side departs from the compiled one by more than 1e-12.
    """
    started = time.perf_counter()
    rng = np.random.default_rng(seed)
    scene = load_scene()
    problems = {m: _Problem(m, scene) for m in models}
    agreement = {m: p.agreement(rng) for m, p in problems.items()}
    for m, worst in agreement.items():
        assert worst <= 1e-12, f"plain-Python {m} right-hand side differs from the compiled one by {worst:.2e}"
    references, reference_check = {}, {}
    for m, p in problems.items():
        p.solve("engine", 1e-8)  # warm-up: numba's cache (or compilation) is not timed
        references[m] = p.end_state(p.solve("engine", REFERENCE_RTOL)["y"])
        reference_check[m] = _error(p.end_state(p.solve("lsoda-jit", REFERENCE_RTOL)["y"]), references[m])
    configs = [(m, s, r) for m in models for s in SOLVERS for r in rtols]
    outcome = {}  # each configuration's last result

    def timed(config):
        m, s, r = config
        wall, cpu, outcome[config] = _timed(problems[m].solve, s, r)
        return wall, cpu

    samples = interleave(configs, repeats, rng, timed)
    rows = {m: [] for m in models}
    for (m, s, r), times in samples.items():
        result, p = outcome[m, s, r], problems[m]
        reached = result["t"] >= p.t_end * (1.0 - 1e-12)
        error = _error(p.end_state(result["y"]), references[m]) if reached else math.nan
        rows[m].append({"solver": s, "rtol": r, "seconds": float(np.median([w for w, _ in times])),
                        "cpu_seconds": float(np.median([c for _, c in times])),
                        "fastest": float(min(w for w, _ in times)), "steps": result["steps"],
                        "nfev": result["nfev"], "njev": result["njev"], "success": result["success"] and reached,
                        "error": error})
    headline = {}
    for m in models:
        by = {(r["solver"], r["rtol"]): r for r in rows[m]}
        engine_seconds = by["engine", HEADLINE_RTOL]["seconds"] if HEADLINE_RTOL in rtols else math.nan
        headline[m] = {
            "same_rtol": {s: {"seconds": by[s, HEADLINE_RTOL]["seconds"], "error": by[s, HEADLINE_RTOL]["error"],
                              "ratio": by[s, HEADLINE_RTOL]["seconds"] / engine_seconds}
                          for s in SOLVERS} if HEADLINE_RTOL in rtols else {},
            "equal_accuracy": _equal_accuracy(rows[m], HEADLINE_RTOL) if HEADLINE_RTOL in rtols else {},
        }
    scene_runs = []
    ap, initial, settings = scene.apparatus, scene.initial, scene.run
    for _ in range(repeats):
        wall, _, trajectory = _timed(lambda: simulate(ap, initial, settings.t_end, forces=kernel_model("closed-form"),
                                                      rtol=settings.rtol, limits=settings.limits))
        scene_runs.append(wall)
    return {
        "machine": machine(),
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "scene": {"apparatus": "steel", "nu": ap.nu, "alpha_deg": math.degrees(ap.alpha), "kappa0": initial.kappa,
                  "phi0": initial.phi, "t_end": settings.t_end, "tau": ap.tau, "delta_over_a": ap.delta_over_a},
        "settings": {"rtols": list(rtols), "headline_rtol": HEADLINE_RTOL, "reference_rtol": REFERENCE_RTOL,
                     "repeats": repeats, "solvers": LABELS},
        "rhs_agreement": agreement,
        "reference_engine_vs_lsoda": reference_check,
        **rows,
        "headline": headline,
        "simulate_scene": {"seconds": float(np.median(scene_runs)), "fastest": float(min(scene_runs)),
                           "steps": trajectory.steps, "status": trajectory.status},
        "run_seconds": time.perf_counter() - started,
    }


def _table(header, lines) -> list[str]:
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
            *("| " + " | ".join(map(str, line)) + " |" for line in lines), ""]


def _headline_lines(results: dict, model: str) -> list[list]:
    head = results["headline"][model]
    same, equal = head["same_rtol"], head["equal_accuracy"]
    lines = []
    for s in SOLVERS:
        row = same[s]
        match = equal.get(s)
        if s == "engine":
            at_equal = "-"
        elif match is None:
            at_equal = "not reached"
        else:
            at_equal = f"{match['ratio']:.1f} (rtol {match['rtol']:g}, {match['seconds']:.3g} s)"
        lines.append([LABELS[s], f"{row['seconds']:.3g}", f"{row['error']:.1e}",
                      "1" if s == "engine" else f"{row['ratio']:.1f}", at_equal])
    return lines


def to_markdown(results: dict) -> str:
    m, sc, st = results["machine"], results["scene"], results["settings"]
    rtol = st["headline_rtol"]
    out = ["# Trajectories: the compiled engine against scipy's solvers", "",
           (f"{m['cpu']}, {m['cores']} cores; Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, "
            f"numba {m['numba']}. {results['date']}; the run took {results['run_seconds']:.0f} s."), "",
           f"Default scene: steel, nu = {sc['nu']:g} m^2/s, {sc['alpha_deg']:g} deg, kappa0 = {sc['kappa0']}, "
           f"phi0 = {sc['phi0']}, from rest, {sc['t_end']:g} s (tau = {sc['tau']:.4g} s, delta/a = "
           f"{sc['delta_over_a']:.3f}), closed forms (2.5)-(2.7). Error at t_end against the engine at rtol "
           f"{st['reference_rtol']:g}: the largest of |d phi|, |d X_b|/b, tau |d Omega_a|, tau |d Omega_b| and "
           "the relative error of 1 - kappa. Wall times are medians of "
           f"{st['repeats']} interleaved repeats, numba cache warm, one output row per step. The references "
           "(engine and scipy LSODA, both at rtol 1e-12) differ by "
           + ", ".join(f"{v:.1e} ({k})" for k, v in results["reference_engine_vs_lsoda"].items())
           + "; the plain-Python right-hand sides equal the compiled ones to "
           + ", ".join(f"{v:.1e} ({k})" for k, v in results["rhs_agreement"].items()) + " (relative).", ""]
    for model, title in (("full", "Full model (2.1)-(2.4)"), ("reduced", "Reduced model (2.11)")):
        if model not in results["headline"] or not results["headline"][model]["same_rtol"]:
            continue
        out += [f"## Headline, {title}, rtol {rtol:g}", ""]
        out += _table(["solver", "wall s", "error", "time / engine's, same rtol",
                       "time / engine's, equal accuracy"], _headline_lines(results, model))
    for model, title in (("full", "Full model (2.1)-(2.4)"), ("reduced", "Reduced model (2.11)")):
        if model not in results:
            continue
        out += [f"## {title}, every rtol", ""]
        out += _table(["solver", "rtol", "wall s", "CPU s", "steps", "nfev", "njev", "error"],
                      [[r["solver"], f"{r['rtol']:g}", f"{r['seconds']:.3g}", f"{r['cpu_seconds']:.3g}", r["steps"],
                        r["nfev"], r["njev"], f"{r['error']:.1e}"] for r in results[model]])
    scene = results["simulate_scene"]
    out += ["## The scene through `dynamics.simulation.simulate`", "",
            f"The default scene through `simulate` (the engine with the validity and turn events and the output "
            f"columns) at rtol {rtol:g}: {scene['seconds']:.3f} s (fastest {scene['fastest']:.3f} s, "
            f"{scene['steps']} steps, {scene['status']}); goal < {GOALS['warm_scene_seconds']:g} s warm: "
            + ("met." if scene["seconds"] < GOALS["warm_scene_seconds"] else "not met."), ""]
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("trajectories", results, to_markdown(results))


if __name__ == "__main__":
    main()
