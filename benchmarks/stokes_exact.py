r"""Cost of the exact Stokes forces against a table lookup, and the accuracy of both and of the finite elements.

Cost. The exact coefficients :func:`lubrication.stokes_exact.stokes_exact_resistance`
is timed from a jitted loop over a spread of states (kappa in [0, 0.999],
1 - kappa given apart, random eps', W_a, W_b; delta/a = 0.40625), the total
divided by the number of calls; median of several rounds. In the same run and
the same loop: the lubrication closed forms (2.5)-(2.7)
(:func:`lubrication.closed_form.lubrication_forces`, the cheapest force model)
and a table lookup, the fastest way to evaluate a smooth function of one
variable that a model could use instead: the five exact ratios to (2.5)-(2.7)
(:func:`lubrication.stokes_exact.stokes_exact_ratios`) tabulated at
``TABLE_NODES`` = 16 Chebyshev-Lobatto nodes in zeta = sqrt(1 - kappa^2) on
[sqrt(1 - kappa_max^2), 1], kappa_max = 0.999, interpolated by the barycentric
formula (:func:`table_ratios`; below the last node the ratios are held) and
multiplied by the closed-form coefficients (:func:`table_forces`). From Python:
the faces :func:`lubrication.stokes_exact.stokes_exact_forces` and
:func:`lubrication.closed_form.closed_form_forces`, and the bare jitted exact
kernel called with floats. One warm-up call precedes every timing.

Accuracy. For delta/a = 0.01 and 0.40625 (the apparatus) the maximum relative
error per coefficient against the exact model of (i) the table lookup (200
kappas up to kappa_max, and beyond it up to 1 - 1e-5 where the ratios are
held) and (ii) a finite-element solve on the default mesh
(:func:`lubrication.stokes.default_mesh`; 9 kappas up to 0.99). T_a per W_b, an
O(zeta) difference near contact, is also given against its row,
max(|T_a per W_a|, |T_a per W_b|); at kappa = 0 the f_chi coefficients vanish
and their finite-element error is measured against |T_a per W_a| / a.

Run ``python -m benchmarks.stokes_exact`` from the project root (about a
minute); it writes ``benchmarks/results/stokes_exact.json`` and ``stokes_exact.md``.
"""

from __future__ import annotations

import datetime
import math
import sys
import time
import timeit
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import machine, publish, repeat
from lubrication.closed_form import (
    closed_form_forces,
    closed_form_resistance,
    lubrication_forces,
)
from lubrication.geometry import RESISTANCE_NAMES, Annulus, Fluid, Motion
from lubrication.stokes_exact import (
    stokes_exact_forces,
    stokes_exact_ratios,
    stokes_exact_resistance,
)
from numerics.jit import jit

APPARATUS_GAP = 0.40625  # Table 2: a = 0.8 cm, b = 1.125 cm
DELTAS = (0.01, APPARATUS_GAP)
CALLS = 200_000
ROUNDS = 7
N_STATES = 1024
PYTHON_CALLS = 2000
TABLE_NODES = 16
TABLE_KAPPA_MAX = 0.999
TABLE_KAPPAS = np.linspace(0.0, TABLE_KAPPA_MAX, 200)
BEYOND_KAPPAS = 1.0 - np.geomspace(1.0 - TABLE_KAPPA_MAX, 1e-5, 20)[1:]
FE_KAPPAS = (0.0, 0.1, 0.3, 0.5, 0.7, 0.8, 0.9, 0.95, 0.99)
GOAL_SECONDS = 1e-6


def lobatto_zeta(zeta_min: float, n: int) -> np.ndarray:
    """Chebyshev-Lobatto points of [zeta_min, 1], increasing, ends included."""
    return zeta_min + 0.5 * (1.0 - zeta_min) * (1.0 - np.cos(np.pi * np.arange(n) / (n - 1)))


def exact_table(delta_over_a: float, n: int = TABLE_NODES, kappa_max: float = TABLE_KAPPA_MAX):
    """(zeta_nodes, node_ratios): the exact ratios (5, n) at the Lobatto nodes in zeta up to kappa_max."""
    zeta_nodes = lobatto_zeta(math.sqrt((1.0 - kappa_max) * (1.0 + kappa_max)), n)
    kappas = np.sqrt(1.0 - zeta_nodes**2)
    omks = zeta_nodes**2 / (1.0 + kappas)  # 1 - kappa without cancellation
    ratios = np.array([stokes_exact_ratios(delta_over_a, k, o) for k, o in zip(kappas, omks)]).T
    return zeta_nodes, np.ascontiguousarray(ratios)


@jit
def table_ratios(zeta_nodes, node_ratios, zeta):
    """The five ratios at ``zeta`` by the barycentric formula on Chebyshev-Lobatto nodes.

    The weights (-1)^j, halved at both ends, hold for these nodes only; below the
    first node the ratios there are returned.
    """
    n = zeta_nodes.size
    if zeta <= zeta_nodes[0]:
        return (node_ratios[0, 0], node_ratios[1, 0], node_ratios[2, 0], node_ratios[3, 0], node_ratios[4, 0])
    den = 0.0
    r0 = r1 = r2 = r3 = r4 = 0.0
    for j in range(n):
        diff = zeta - zeta_nodes[j]
        if diff == 0.0:
            return (node_ratios[0, j], node_ratios[1, j], node_ratios[2, j], node_ratios[3, j], node_ratios[4, j])
        w = 1.0 if j % 2 == 0 else -1.0
        if j == 0 or j == n - 1:
            w *= 0.5
        c = w / diff
        den += c
        r0 += c * node_ratios[0, j]
        r1 += c * node_ratios[1, j]
        r2 += c * node_ratios[2, j]
        r3 += c * node_ratios[3, j]
        r4 += c * node_ratios[4, j]
    return r0 / den, r1 / den, r2 / den, r3 / den, r4 / den


@jit
def table_forces(zeta_nodes, node_ratios, a, delta, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m): the tabulated ratios times the coefficients of (2.5)-(2.7)."""
    q = table_ratios(zeta_nodes, node_ratios, math.sqrt(omk * (1.0 + kappa)))
    r = closed_form_resistance(a, delta, mu, kappa, omk)
    return (length * q[0] * r[0] * eps_dot, length * (q[1] * r[1] * w_a + q[3] * r[3] * w_b),
            length * (q[2] * r[2] * w_a + q[4] * r[4] * w_b))


@jit
def _loop_exact(kappas, omks, motions, calls):
    total = 0.0
    m = kappas.size
    for i in range(calls):
        j = i % m
        r = stokes_exact_resistance(0.008, 0.00325, 0.2, kappas[j], omks[j])
        total += 0.1 * (r[0] * motions[j, 0] + r[1] * motions[j, 1] + r[3] * motions[j, 2]
                        + r[2] * motions[j, 1] + r[4] * motions[j, 2])
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
def _loop_table(zeta_nodes, node_ratios, kappas, omks, motions, calls):
    total = 0.0
    m = kappas.size
    for i in range(calls):
        j = i % m
        f = table_forces(zeta_nodes, node_ratios, 0.008, 0.00325, 0.2, 0.1, kappas[j], omks[j],
                         motions[j, 0], motions[j, 1], motions[j, 2])
        total += f[0] + f[1] + f[2]
    return total


def _median_per_call(fn, calls, rounds):
    """Median and fastest seconds per call of ``fn(calls)`` over ``rounds``, after ``fn(10)`` compiles it."""
    timed = repeat(lambda: fn(calls), rounds, warm_up=lambda: fn(10))
    return timed.median / calls, timed.fastest / calls


def _python_per_call(fn, calls, rounds):
    fn()
    times = [t / calls for t in timeit.repeat(fn, number=calls, repeat=rounds)]
    return float(np.median(times)), float(min(times))


def _timing(table, calls, rounds) -> dict:
    rng = np.random.default_rng(20070523)
    kappas = np.sort(rng.uniform(0.0, 0.999, N_STATES))
    omks = 1.0 - kappas
    motions = rng.normal(size=(N_STATES, 3)) * np.array([1e-4, 1.0, 1.0])
    zn, nr = table
    jitted = {
        "exact": lambda n: _loop_exact(kappas, omks, motions, n),
        "closed-form": lambda n: _loop_closed_form(kappas, omks, motions, n),
        "table": lambda n: _loop_table(zn, nr, kappas, omks, motions, n),
    }
    annulus = Annulus.from_kappa(0.008, 0.01125, 0.7, length=0.1)
    motion = Motion(eps_dot=1e-4, chi_dot=0.3, omega_a=1.1, omega_b=-0.4)
    fluid = Fluid(nu=2e-4, rho=960.0)
    python = {
        "exact": lambda: stokes_exact_forces(annulus, motion, fluid),
        "closed-form": lambda: closed_form_forces(annulus, motion, fluid),
        "exact coefficients, floats": lambda: stokes_exact_resistance(0.008, 0.00325, 0.2, 0.7, 0.3),
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


def _table_accuracy(table, d: float) -> dict:
    """Max relative error per coefficient of the table's ratios against the exact ones."""
    out = {}
    zn, nr = table
    for label, kappas in ((f"kappa <= {TABLE_KAPPA_MAX:g}", TABLE_KAPPAS),
                          (f"{TABLE_KAPPA_MAX:g} < kappa <= {BEYOND_KAPPAS[-1]:.5g} (held)", BEYOND_KAPPAS)):
        zetas = np.sqrt((1.0 - kappas) * (1.0 + kappas))
        tab = np.array([table_ratios(zn, nr, float(z)) for z in zetas]).T
        exact = _exact_ratios(d, kappas)
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
        tables[d] = exact_table(d)
        build[d] = time.perf_counter() - t0
    results = {
        "date": datetime.date.today().isoformat(),
        "machine": machine(),
        "timing": _timing(tables[APPARATUS_GAP], calls, rounds),
        "table": {"nodes": TABLE_NODES, "kappa_max": TABLE_KAPPA_MAX,
                  "build_seconds": {str(d): build[d] for d in deltas}},
        "accuracy": {str(d): {"table": _table_accuracy(tables[d], d), "fe_default_mesh": _fe_accuracy(d)}
                     for d in deltas},
    }
    for d, acc in results["accuracy"].items():  # 16 nodes interpolate the smooth ratios to about 3e-7
        inside = acc["table"][f"kappa <= {TABLE_KAPPA_MAX:g}"]["max_relative_error"]
        assert max(inside.values()) < 1e-6, f"the table lookup misses the exact ratios at delta/a = {d}: {inside}"
    return results


def _e(x) -> str:
    return f"{x:.1e}"


def to_markdown(results: dict) -> str:
    t = results["timing"]
    lines = ["# Exact Stokes forces: cost, and the accuracy of the table and the finite elements", "",
             f"{results['date']}, {results['machine']['cpu']}, {results['machine']['cores']} cores.", "",
             "## Time per evaluation (f_eps, f_chi, T_a)", "",
             (f"From a jitted loop over {t['states']} states (median of {t['rounds']} rounds of "
             f"{t['calls']} calls; delta/a = 0.40625). The table holds the exact ratios at "
             f"{results['table']['nodes']} Chebyshev-Lobatto nodes in zeta = sqrt(1 - kappa^2), kappa <= "
             f"{results['table']['kappa_max']:g}, looked up by the barycentric formula:"), "",
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
