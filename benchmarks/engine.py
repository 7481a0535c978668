"""The compiled Radau IIA engine against scipy's Radau, BDF and LSODA on stiff problems.

Problems (every model takes its parameters as one float64 array, so one compiled
driver serves them all):

- Van der Pol, y'' - mu (1 - y^2) y' + y = 0, mu = 1e3, from (2, 0) over [0, 2000]
  (two relaxation jumps); reference: scipy's Radau at rtol = atol = 1e-12.
- Robertson's kinetics over [0, 1e5], atol = (1e-4, 1e-8, 1e-4) rtol; reference:
  scipy's Radau at rtol 1e-12, atol (1e-16, 1e-20, 1e-16).
- A 5-state stiff nonlinear problem with a known solution (a coupled
  Prothero-Robinson problem): y' = -L (y - g(t)) + g'(t) + N(y) - N(g(t)) with
  L = diag(1, 1e2, 1e3, 1e4, 1e5), N_i(y) = y_i y_(i+1) (cyclic), so y = g(t) =
  (sin t, cos t, sin 2t, cos 3t, 1 + sin(t)/2) from y(0) = g(0), over [0, 100].

Each at rtol 1e-6 and 1e-10 (atol = rtol unless said). Every method gets the same
numba-compiled right-hand side and Jacobian: scipy calls them from Python, the
strongest fair baseline for a solver stepped in Python. The engine is timed through
its compiled, cached entry point (``engine_for(args).init`` and ``.advance``, inputs
checked beforehand) and through the Python wrapper ``integrate``. Reported: median
wall time of the repeats (after one warm-up call each), steps and evaluation counts,
time per step, the largest error at the sample times in tolerance units
e = |y - y_ref| / (atol + rtol |y_ref|), and each method's time over the engine's.
Also: the cost of one call to the model's functions (so the engine's own share of a
step), and the one-time compilation of the driver (cold, in a fresh numba cache) and
its load from the cache, in fresh processes.

If CyRK is importable (not a dependency), its compiled (C++) Radau, BDF and LSODA
are timed on the same problems too, called through its numba interface with the
same right-hand side; they take no user Jacobian (finite differences instead).

Run from the project root: ``python -m benchmarks.engine``; writes
``benchmarks/results/engine.json`` and ``.md``.
"""

from __future__ import annotations

import datetime
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np
from numba import types
from scipy.integrate import solve_ivp

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import machine, publish, repeat
from numerics.engine import SAMPLE, check_inputs, engine_for, integrate, no_events
from numerics.engine.compiled import first_class, function_types
from numerics.jit import jit

RTOLS = (1e-6, 1e-10)
REPEATS = 5
SCIPY_REPEATS = 3
SCIPY_METHODS = ("Radau", "BDF", "LSODA")


@jit
def vdp(t, y, args):
    mu = args[0]
    return np.array([y[1], mu * (1.0 - y[0] ** 2) * y[1] - y[0]])


@jit
def vdp_jac(t, y, args):
    mu = args[0]
    return np.array([[0.0, 1.0], [-2.0 * mu * y[0] * y[1] - 1.0, mu * (1.0 - y[0] ** 2)]])


@jit
def robertson(t, y, args):
    return np.array([-0.04 * y[0] + 1e4 * y[1] * y[2],
                     0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2,
                     3e7 * y[1] ** 2])


@jit
def robertson_jac(t, y, args):
    return np.array([[-0.04, 1e4 * y[2], 1e4 * y[1]],
                     [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
                     [0.0, 6e7 * y[1], 0.0]])


@jit
def _g(t):
    """The solution of the 5-state problem and its derivative."""
    s1, c1 = math.sin(t), math.cos(t)
    g = np.array([s1, c1, math.sin(2.0 * t), math.cos(3.0 * t), 1.0 + 0.5 * s1])
    dg = np.array([c1, -s1, 2.0 * math.cos(2.0 * t), -3.0 * math.sin(3.0 * t), 0.5 * c1])
    return g, dg


@jit
def coupled(t, y, args):
    """Coupled Prothero-Robinson problem; args = L (5,)."""
    g, dg = _g(t)
    dy = np.empty(5)
    for i in range(5):
        k = (i + 1) % 5
        dy[i] = -args[i] * (y[i] - g[i]) + dg[i] + y[i] * y[k] - g[i] * g[k]
    return dy


@jit
def coupled_jac(t, y, args):
    jac = np.zeros((5, 5))
    for i in range(5):
        k = (i + 1) % 5
        jac[i, i] = -args[i] + y[k]
        jac[i, k] += y[i]
    return jac


def exact_coupled(t):
    t = np.asarray(t)
    return np.array([np.sin(t), np.cos(t), np.sin(2 * t), np.cos(3 * t), 1 + 0.5 * np.sin(t)])


def problems() -> dict:
    """Name -> (fun, jac, args, y0, t_end, sample times, atol factor per component, reference)."""
    vdp_times = np.array([200.0, 400.0, 600.0, 800.0, 1000.0, 1500.0, 2000.0])
    rob_times = np.array([1e-2, 1.0, 1e2, 1e4, 1e5])
    coupled_times = np.linspace(10.0, 100.0, 10)
    mu = np.array([1000.0])

    def vdp_ref():
        return solve_ivp(vdp, (0.0, 2000.0), [2.0, 0.0], method="Radau", rtol=1e-12, atol=1e-12, jac=vdp_jac,
                         args=(mu,), t_eval=vdp_times).y

    def rob_ref():
        return solve_ivp(robertson, (0.0, 1e5), [1.0, 0.0, 0.0], method="Radau", rtol=1e-12,
                         atol=[1e-16, 1e-20, 1e-16], jac=robertson_jac, args=(mu,), t_eval=rob_times).y

    return {
        "Van der Pol, mu = 1e3 (n = 2)": (vdp, vdp_jac, mu, np.array([2.0, 0.0]), 2000.0, vdp_times,
                                          np.ones(2), vdp_ref),
        "Robertson (n = 3)": (robertson, robertson_jac, mu, np.array([1.0, 0.0, 0.0]), 1e5, rob_times,
                              np.array([1e-4, 1e-8, 1e-4]), rob_ref),
        "coupled Prothero-Robinson (n = 5)": (coupled, coupled_jac, np.array([1.0, 1e2, 1e3, 1e4, 1e5]),
                                              exact_coupled(0.0), 100.0, coupled_times, np.ones(5),
                                              lambda: exact_coupled(coupled_times)),
    }


def _median(call, repeats):
    """(median, fastest, last result) of ``repeats`` timed calls after a warm-up (:func:`harness.repeat`)."""
    timed = repeat(call, repeats)
    return timed.median, timed.fastest, timed.result


def _scaled_error(y, y_ref, rtol, atol):
    return float(np.max(np.abs(y - y_ref) / (atol[:, None] + rtol * np.abs(y_ref))))


def _engine_rows(fun, jac, args, y0, t_end, times, rtol, atol, y_ref, repeats):
    inputs = check_inputs(fun, jac, no_events, (0.0, t_end), y0, args=args, rtol=rtol, atol=atol, t_eval=times)
    engine = engine_for(args)
    functions = first_class(fun, jac, no_events, args)  # as integrate() passes them

    def compiled():
        state = engine.init(*functions, args, **inputs)
        return state, engine.advance(*functions, args, state, 0)

    seconds, fastest, (state, rows) = _median(compiled, repeats)
    keep = (rows[2] & SAMPLE) != 0
    counters = state.counters
    steps = int(counters[3])
    common = {"steps": steps, "nfev": int(counters[0]), "njev": int(counters[1]), "nlu": int(counters[2]),
              "error": _scaled_error(rows[1][:, keep], y_ref, rtol, atol)}
    out = {"engine (compiled entry)": {"seconds": seconds, "fastest": fastest, **common}}
    seconds, fastest, _ = _median(lambda: integrate(fun, jac, (0.0, t_end), y0, args=args, rtol=rtol,
                                                      atol=atol, t_eval=times), repeats)
    out["engine (integrate)"] = {"seconds": seconds, "fastest": fastest, **common}
    return out


def _scipy_row(method, fun, jac, args, y0, t_end, times, rtol, atol, y_ref, repeats):
    def call():
        return solve_ivp(fun, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, jac=jac, args=(args,),
                         t_eval=times)

    seconds, fastest, sol = _median(call, repeats)
    # t_eval hides the steps: count them in one more (untimed) run without it
    steps = int(solve_ivp(fun, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, jac=jac,
                          args=(args,)).t.size - 1)
    return {"seconds": seconds, "fastest": fastest, "steps": steps, "nfev": int(sol.nfev), "njev": int(sol.njev),
            "nlu": int(sol.nlu), "error": _scaled_error(sol.y, y_ref, rtol, atol) if sol.success else None,
            "status": int(sol.status)}


def _cyrk_rows(fun, args, y0, t_end, times, rtol, atol, y_ref, repeats) -> dict:
    """CyRK's compiled Radau, BDF and LSODA (C++, Jacobians by finite differences), if CyRK is importable."""
    try:
        import numba
        from CyRK import cyjit, nbsolve2_ivp
    except ImportError:
        return {}
    n, k = y0.size, args.size

    @cyjit
    def diffeq(dy, t, y, a):
        out = fun(t, numba.carray(y, (n,)), numba.carray(a, (k,)))
        for i in range(n):
            dy[i] = out[i]

    rows = {}
    for method in ("RADAU", "BDF", "LSODA"):
        def call(method=method):
            sol = nbsolve2_ivp(diffeq.address, (0.0, t_end), y0, method=method, t_eval=times, args=args,
                               rtol=rtol, atols=atol)
            result = (bool(sol.success), int(sol.steps_taken), np.array(sol.y))
            sol.free()
            return result

        seconds, fastest, (ok, steps, y) = _median(call, repeats)
        rows[f"CyRK {method}"] = {"seconds": seconds, "fastest": fastest, "steps": steps, "nfev": None,
                                  "njev": None, "nlu": None, "status": 0 if ok else -1,
                                  "error": _scaled_error(y, y_ref, rtol, atol) if ok else None}
    return rows


def _function_cost(fun, jac, args, y0, calls=200_000):
    """Seconds per call of fun and of jac through a function pointer, as the engine calls them."""
    fun_type, jac_type, _ = function_types(numba.typeof(args))
    vector, args_type = types.float64[::1], numba.typeof(args)

    @jit(cache=False)
    def loop(function, y, a, count):
        total = 0.0
        for k in range(count):
            total += function(1e-9 * k, y, a)[0]
        return total

    @jit(cache=False)
    def loop_jac(function, y, a, count):
        total = 0.0
        for k in range(count):
            total += function(1e-9 * k, y, a)[0, 0]
        return total

    loop.compile((fun_type, vector, args_type, types.int64))
    loop_jac.compile((jac_type, vector, args_type, types.int64))
    loop.disable_compile()
    loop_jac.disable_compile()
    return (_median(lambda: loop(fun, y0, args, calls), 3)[0] / calls,
            _median(lambda: loop_jac(jac, y0, args, calls), 3)[0] / calls)


_COMPILE_SCRIPT = """
import time
start = time.perf_counter()
import numpy as np
from numerics.engine import engine_for
imported = time.perf_counter()
engine_for(np.zeros(1))
print(imported - start, time.perf_counter() - imported)
"""


def compile_times() -> dict:
    """Import and driver-compile seconds in fresh processes: with an empty numba cache, then with it filled."""
    root = Path(__file__).resolve().parents[1]
    out = {}
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(root)}
        for label in ("cold", "cached"):
            result = subprocess.run([sys.executable, "-c", _COMPILE_SCRIPT], env=env, capture_output=True,
                                    text=True, check=True, cwd=root)
            imported, driver = (float(v) for v in result.stdout.split())
            out[label] = {"import_seconds": imported, "driver_seconds": driver}
    return out


def run(rtols=RTOLS, repeats=REPEATS, scipy_repeats=SCIPY_REPEATS, measure_compile=True) -> dict:
    started = time.perf_counter()
    records = []
    for name, (fun, jac, args, y0, t_end, times, atol_factor, reference) in problems().items():
        y_ref = reference()
        f_cost, j_cost = _function_cost(fun, jac, args, y0)
        for rtol in rtols:
            atol = atol_factor * rtol
            rows = _engine_rows(fun, jac, args, y0, t_end, times, rtol, atol, y_ref, repeats)
            for method in SCIPY_METHODS:
                rows[f"scipy {method}"] = _scipy_row(method, fun, jac, args, y0, t_end, times, rtol, atol, y_ref,
                                                     scipy_repeats)
            rows.update(_cyrk_rows(fun, args, y0, t_end, times, rtol, atol, y_ref, repeats))
            base = rows["engine (compiled entry)"]
            model_share = (base["nfev"] * f_cost + base["njev"] * j_cost) / base["steps"]
            for row in rows.values():
                row["ratio"] = row["seconds"] / base["seconds"]
                row["us_per_step"] = 1e6 * row["seconds"] / row["steps"] if row.get("steps") else None
            records.append({"problem": name, "rtol": rtol, "fun_seconds": f_cost, "jac_seconds": j_cost,
                            "engine_us_per_step_without_model": 1e6 * (base["seconds"] / base["steps"]
                                                                        - model_share),
                            "rows": rows})
    return {
        "machine": machine(),
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "repeats": repeats, "scipy_repeats": scipy_repeats,
        "records": records,
        "compile": compile_times() if measure_compile else None,
        "run_seconds": time.perf_counter() - started,
    }


def _fmt(value, spec):
    return "-" if value is None else format(value, spec)


def to_markdown(results: dict) -> str:
    out = ["# Compiled Radau IIA engine against scipy", "",
           (f"Median wall time of {results['repeats']} runs (engine) and {results['scipy_repeats']} (scipy), "
            "after a warm-up; all methods call the same numba-compiled right-hand side and Jacobian. "
            "Error: largest |y - y_ref| / (atol + rtol |y_ref|) at the sample times. Ratio: time over the "
            "engine's (compiled entry)."), ""]
    for record in results["records"]:
        out += [f"## {record['problem']}, rtol = {record['rtol']:g}", "",
                "| method | time (ms) | ratio | steps | f evals | J evals | LU | us/step | error (tol) |",
                "|---|---|---|---|---|---|---|---|---|"]
        for method, r in record["rows"].items():
            out.append(f"| {method} | {1e3 * r['seconds']:.2f} | {r['ratio']:.1f} | {_fmt(r['steps'], 'd')} | "
                       f"{_fmt(r['nfev'], 'd')} | {_fmt(r['njev'], 'd')} | {_fmt(r['nlu'], 'd')} | "
                       f"{_fmt(r['us_per_step'], '.2f')} | {_fmt(r['error'], '.2g')} |")
        out += ["", (f"One call of the model's fun: {1e9 * record['fun_seconds']:.0f} ns, of jac: "
                     f"{1e9 * record['jac_seconds']:.0f} ns; the engine's own cost per step (without them): "
                     f"{record['engine_us_per_step_without_model']:.2f} us."), ""]
    compiled = results.get("compile")
    if compiled:
        out += ["## Compilation of the driver (fresh processes)", "",
                "| numba cache | import (s) | driver for one type of args (s) |", "|---|---|---|"]
        for label, c in compiled.items():
            out.append(f"| {label} | {c['import_seconds']:.2f} | {c['driver_seconds']:.2f} |")
    out += ["", (f"Machine: {results['machine']['cpu']}, {results['machine']['cores']} cores; "
                 f"numba {results['machine']['numba']}, scipy {results['machine']['scipy']}.")]
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("engine", results, to_markdown(results))


if __name__ == "__main__":
    main()
