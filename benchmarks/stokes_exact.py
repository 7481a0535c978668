r"""Cost of the exact Stokes forces, and the accuracy of the table and of the finite elements against them.

Cost. The exact force kernel :func:`lubrication.stokes_exact.stokes_exact_forces`
is timed from a jitted loop over a spread of states (kappa in [0, 0.999],
1 - kappa given apart, random eps', W_a, W_b; delta/a = 0.40625), the total
divided by the number of calls; median of several rounds. In the same run and
the same loop: the lubrication closed forms (2.5)-(2.7)
(:func:`lubrication.closed_form.lubrication_forces`, the cheapest force model)
and the Stokes table lookup (:func:`lubrication.stokes_tables.table_forces`,
16 Chebyshev nodes, the model the exact one can replace). From Python: the
faces :func:`lubrication.stokes_exact.exact_forces`,
:func:`lubrication.closed_form.closed_form_forces` and
:meth:`lubrication.stokes_tables.StokesTable.forces`, and the bare jitted
kernel called with floats. One warm-up call precedes every timing.

Accuracy. For delta/a = 0.01 and 0.40625 (the apparatus) and kappa on a grid
up to 0.99, the maximum relative error per coefficient against the exact
model of (i) the Stokes table (``StokesTable.load``: finite-element solves on
the default mesh at 16 nodes, interpolated; 200 kappas) and (ii) a
finite-element solve on the default mesh (:func:`lubrication.stokes.default_mesh`;
9 kappas). T_a per W_b, an O(zeta) difference near contact, is also given
against its row, max(|T_a per W_a|, |T_a per W_b|); at kappa = 0 the f_chi
coefficients vanish and their finite-element error is measured against
|T_a per W_a| / a. The table's blend beyond kappa_max = 0.99 is reported on
kappa in (0.99, 0.9999].

Run ``python -m benchmarks.stokes_exact`` from the project root (about a
minute, half of it building the two tables unless ``$SNAIL_CACHE`` has them);
it writes ``benchmarks/results/stokes_exact.json`` and ``stokes_exact.md``.
"""

from __future__ import annotations

import datetime
import sys
import time
import timeit
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from lubrication.stokes_tables import StokesTable, table_forces

from benchmarks.publish import publish
from benchmarks.reynolds import _machine
from lubrication._jit import jit
from lubrication.closed_form import closed_form_forces, lubrication_forces
from lubrication.geometry import RESISTANCE_NAMES, Annulus, Fluid, Motion
from lubrication.stokes_exact import (
    exact_forces,
    stokes_exact_forces,
    stokes_exact_ratios,
    stokes_exact_resistance,
)

APPARATUS_GAP = 0.40625  # Table 2: a = 0.8 cm, b = 1.125 cm
DELTAS = (0.01, APPARATUS_GAP)
CALLS = 200_000
ROUNDS = 7
N_STATES = 1024
PYTHON_CALLS = 2000
TABLE_KAPPAS = np.linspace(0.0, 0.99, 200)
BLEND_KAPPAS = 1.0 - np.geomspace(1e-2, 1e-4, 20)[1:]
FE_KAPPAS = (0.0, 0.1, 0.3, 0.5, 0.7, 0.8, 0.9, 0.95, 0.99)
GOAL_SECONDS = 1e-6


@jit
def _loop_exact(kappas, omks, motions, calls):
    total = 0.0
    m = kappas.size
    for i in range(calls):
        j = i % m
        f = stokes_exact_forces(0.008, 0.00325, 0.2, 0.1, kappas[j], omks[j],
                                motions[j, 0], motions[j, 1], motions[j, 2])
        total += f[0] + f[1] + f[2]
    return total


@jit
def _loop_closed_form(kappas, omks, motions, calls):
    total = 0.0
    m = kappas.size
    for i in range(calls):
        j = i % m
        f = lubrication_forces(0.008, 0.00325, 0.2, 0.1, kappas[j], omks[j],
                               motions[j, 0], motions[j, 1], motions[j, 2])
        total += f[0] + f[1] + f[2]
    return total


@jit
def _loop_table(zeta_nodes, node_ratios, contact, kappas, omks, motions, calls):
    total = 0.0
    m = kappas.size
    for i in range(calls):
        j = i % m
        f = table_forces(zeta_nodes, node_ratios, contact, 0.008, 0.00325, 0.2, 0.1, kappas[j],
                         omks[j], motions[j, 0], motions[j, 1], motions[j, 2])
        total += f[0] + f[1] + f[2]
    return total


def _median_per_call(fn, calls, rounds):
    fn(10)  # compile and warm up
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        fn(calls)
        times.append((time.perf_counter() - t0) / calls)
    return float(np.median(times)), float(min(times))


def _python_per_call(fn, calls, rounds):
    fn()
    times = [t / calls for t in timeit.repeat(fn, number=calls, repeat=rounds)]
    return float(np.median(times)), float(min(times))


def _timing(table: StokesTable, calls, rounds) -> dict:
    rng = np.random.default_rng(20070523)
    kappas = np.sort(rng.uniform(0.0, 0.999, N_STATES))
    omks = 1.0 - kappas
    motions = rng.normal(size=(N_STATES, 3)) * np.array([1e-4, 1.0, 1.0])
    zn, nr, ct = table.arrays
    jitted = {
        "exact": lambda n: _loop_exact(kappas, omks, motions, n),
        "closed-form": lambda n: _loop_closed_form(kappas, omks, motions, n),
        "table": lambda n: _loop_table(zn, nr, ct, kappas, omks, motions, n),
    }
    annulus = Annulus.from_kappa(0.008, 0.01125, 0.7, length=0.1)
    motion = Motion(eps_dot=1e-4, chi_dot=0.3, omega_a=1.1, omega_b=-0.4)
    fluid = Fluid(nu=2e-4, rho=960.0)
    python = {
        "exact": lambda: exact_forces(annulus, motion, fluid),
        "closed-form": lambda: closed_form_forces(annulus, motion, fluid),
        "table": lambda: table.forces(annulus, motion, fluid),
        "exact kernel, floats": lambda: stokes_exact_forces(0.008, 0.00325, 0.2, 0.1, 0.7, 0.3,
                                                            1e-4, 0.8, -0.7),
    }
    out = {"jit": {}, "python": {}}
    for name, fn in jitted.items():
        med, best = _median_per_call(fn, calls, rounds)
        out["jit"][name] = {"seconds_per_call": med, "seconds_per_call_min": best}
    for name, fn in python.items():
        med, best = _python_per_call(fn, PYTHON_CALLS, rounds)
        out["python"][name] = {"seconds_per_call": med, "seconds_per_call_min": best}
    ex = out["jit"]["exact"]["seconds_per_call"]
    for name in jitted:
        out["jit"][name]["ratio_to_exact"] = out["jit"][name]["seconds_per_call"] / ex
    out["calls"], out["rounds"], out["states"] = calls, rounds, N_STATES
    out["goal_met"] = ex < GOAL_SECONDS
    return out


def _exact_ratios(d, kappas):
    return np.array([stokes_exact_ratios(d, float(k), 1.0 - float(k)) for k in kappas]).T


def _table_accuracy(table: StokesTable, d: float) -> dict:
    """Max relative error per coefficient of the table's ratios against the exact ones."""
    out = {}
    for label, kappas in (("kappa <= 0.99", TABLE_KAPPAS), ("0.99 < kappa <= 0.9999", BLEND_KAPPAS)):
        tab, exact = table.ratios(kappas), _exact_ratios(d, kappas)
        err = np.abs(tab / exact - 1.0)
        # T_a per W_b against its row: scale by R_t_b / max(|R_t_a|, |R_t_b|)
        coeffs = np.array([stokes_exact_resistance(1.0, d, 1.0, float(k), 1.0 - float(k)) for k in kappas])
        share = np.abs(coeffs[:, 4]) / np.maximum(np.abs(coeffs[:, 2]), np.abs(coeffs[:, 4]))
        out[label] = {"max_relative_error": {n: float(err[k].max()) for k, n in enumerate(RESISTANCE_NAMES)},
                      "t_a_per_w_b_row": float(np.max(err[4] * share)),
                      "worst_kappa": {n: float(kappas[np.argmax(err[k])]) for k, n in enumerate(RESISTANCE_NAMES)}}
    return out


def _fe_accuracy(d: float) -> dict:
    from lubrication.stokes import default_mesh, stokes_resistance

    n_around, n_across = default_mesh(d)
    errs, rows, times = [], [], []
    for kappa in FE_KAPPAS:
        r = stokes_resistance(1.0, 1.0 + d, kappa)
        fe = np.array([getattr(r, n) for n in RESISTANCE_NAMES])
        exact = np.array(stokes_exact_resistance(1.0, d, 1.0, kappa, 1.0 - kappa)[:5])
        scale = np.abs(exact).copy()
        if exact[1] == 0.0:
            scale[1] = scale[3] = abs(exact[2])
        errs.append(np.abs(fe - exact) / scale)
        rows.append(abs(fe[4] - exact[4]) / max(abs(exact[2]), abs(exact[4])))
        times.append(r.wall_time_s)
    errs = np.array(errs)
    return {"mesh": [n_around, n_across], "kappas": list(FE_KAPPAS),
            "max_relative_error": {n: float(errs[:, k].max()) for k, n in enumerate(RESISTANCE_NAMES)},
            "worst_kappa": {n: FE_KAPPAS[int(np.argmax(errs[:, k]))] for k, n in enumerate(RESISTANCE_NAMES)},
            "t_a_per_w_b_row": float(max(rows)), "median_solve_seconds": float(np.median(times))}


def run(calls=CALLS, rounds=ROUNDS, deltas=DELTAS) -> dict:
    """Times per call (jitted and Python) and accuracy of table and default FE mesh against exact."""
    tables, build = {}, {}
    for d in deltas:
        t0 = time.perf_counter()
        tables[d] = StokesTable.load(d)
        build[d] = time.perf_counter() - t0
    results = {
        "date": datetime.date.today().isoformat(),
        "machine": _machine(),
        "timing": _timing(tables[APPARATUS_GAP], calls, rounds),
        "table_seconds": {str(d): build[d] for d in deltas},
        "accuracy": {str(d): {"table": _table_accuracy(tables[d], d), "fe_default_mesh": _fe_accuracy(d)}
                     for d in deltas},
    }
    return results


def _e(x) -> str:
    return f"{x:.1e}"


def to_markdown(results: dict) -> str:
    t = results["timing"]
    lines = ["# Exact Stokes forces: cost, and the accuracy of the table and the finite elements", "",
             f"{results['date']}, {results['machine']['cpu']}, {results['machine']['cores']} cores.", "",
             "## Time per evaluation (f_eps, f_chi, T_a)", "",
             (f"From a jitted loop over {t['states']} states (median of {t['rounds']} rounds of "
             f"{t['calls']} calls; delta/a = 0.40625):"), "",
             "| model | ns per call | best ns | time / exact |", "|---|---|---|---|"]
    for name, v in t["jit"].items():
        lines.append(f"| {name} | {v['seconds_per_call'] * 1e9:.1f} | {v['seconds_per_call_min'] * 1e9:.1f} "
                     f"| {v['ratio_to_exact']:.2f} |")
    lines += ["", "From Python (median of rounds of 2000 calls):", "", "| call | us per call | best us |",
              "|---|---|---|"]
    for name, v in t["python"].items():
        lines.append(f"| {name} | {v['seconds_per_call'] * 1e6:.2f} | {v['seconds_per_call_min'] * 1e6:.2f} |")
    lines += ["", (f"Goal: at most 1 us per exact evaluation from jitted code: "
              f"{'met' if t['goal_met'] else 'not met'}."), ""]
    for d, acc in results["accuracy"].items():
        fe = acc["fe_default_mesh"]
        lines += [f"## Accuracy against the exact model, delta/a = {float(d):g}", "",
                  "Maximum relative error per coefficient (T_a per W_b also against its row).", "",
                  "| source | " + " | ".join(RESISTANCE_NAMES) + " | T_a per W_b (row) |",
                  "|---|" + "---|" * (len(RESISTANCE_NAMES) + 1)]
        for label, v in acc["table"].items():
            lines.append(f"| table, {label} | " + " | ".join(_e(v["max_relative_error"][n]) for n in RESISTANCE_NAMES)
                         + f" | {_e(v['t_a_per_w_b_row'])} |")
        lines.append(f"| FE default mesh {fe['mesh'][0]} x {fe['mesh'][1]}, kappa <= 0.99 | "
                     + " | ".join(_e(fe["max_relative_error"][n]) for n in RESISTANCE_NAMES)
                     + f" | {_e(fe['t_a_per_w_b_row'])} |")
        lines += ["", f"FE kappas: {', '.join(f'{k:g}' for k in fe['kappas'])}; worst at "
                  + ", ".join(f"{n} {fe['worst_kappa'][n]:g}" for n in RESISTANCE_NAMES)
                  + f"; median solve {fe['median_solve_seconds']:.2f} s.", ""]
    return "\n".join(lines)


def main() -> None:
    results = run()
    publish("stokes_exact", results, to_markdown(results))


if __name__ == "__main__":
    main()
