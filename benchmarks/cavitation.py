r"""Cost of one film solve with each cavitation model against the full film, versus N.

The case is the one the equations of motion meet while the gap closes: the thin
gap at kappa = 0.99, both cylinders turning (W_a = 1, W_b = 0.5 rad/s) and the
inner cylinder sinking (eps' = 10 um/s), 200 cSt oil, p_ref - p_cav = 100 Pa,
so that a cavity covers about a quarter of the film. The grid is the Sommerfeld
grid with one Gauss point per cell, as :func:`lubrication.reynolds.reynolds_kernel`
builds it by default.

Each solve is timed two ways, JIT compilation excluded:

* "jit": a numba loop calling :func:`lubrication.cavitation_kernels.cavitating_film_forces`
  (the full film: :func:`lubrication.reynolds_kernels.film_forces`) with the arguments that
  :func:`lubrication.reynolds.reynolds_kernel` passes, i.e. what a trajectory pays per
  right-hand side;
* "python": :func:`lubrication.cavitation.cavitating_forces` (the full film:
  :func:`lubrication.reynolds_forces`), validation and dataclasses included.

Timing follows ``benchmarks/reynolds.py``: batches of at least 2 ms, 15 rounds,
every method once per round in shuffled order, median wall time, median thread CPU
time alongside. The active-set passes and the cavitated fraction are recorded per N.

Run ``python -m benchmarks.cavitation`` (or ``python benchmarks/cavitation.py``)
from the project root; it writes ``benchmarks/results/cavitation.json`` and
``cavitation.md``.
"""

from __future__ import annotations

import datetime
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import Timer, machine, publish, time_all  # noqa: E402
from lubrication import Annulus, Fluid, Motion, reynolds_forces  # noqa: E402
from lubrication.cavitation import (  # noqa: E402
    CAVITATION_MODELS,
    cavitating_forces,
    cavitating_pressure,
)
from lubrication.cavitation_kernels import cavitating_film_forces  # noqa: E402
from lubrication.reynolds import psi_rule  # noqa: E402
from lubrication.reynolds_kernels import THIN, film_forces  # noqa: E402

A, B, LENGTH = 0.008, 0.01125, 0.1035  # the paper's apparatus (Table 2), m
FLUID = Fluid(nu=2.0e-4, rho=960.0)  # 200 cSt silicone oil
FLUID_MU = FLUID.mu  # a global the jitted loops freeze at compilation
KAPPA = 0.99
MOTION = Motion(eps_dot=1e-5, omega_a=1.0, omega_b=0.5)  # sinking and turning, m/s and rad/s
P_REF = 101325.0  # Pa
P_CAV = P_REF - 100.0  # a cavity over about a quarter of the film
CELLS = tuple(2**k for k in range(5, 12))  # 32 .. 2048
POINTS_PER_CELL = 1  # as lubrication.reynolds.reynolds_kernel by default
ROUNDS = 15
BATCH_SECONDS = 2e-3


@njit
def _cavitating_loop(repeats, model, kappa, omk, eps_dot, w_a, w_b, rule, m, p_cav, p_ref):
    """Call the cavitating kernel ``repeats`` times as lubrication.reynolds.reynolds_kernel does; return a checksum."""
    cpsi, spsi, vpsi, ppsi, wpsi = rule
    n = spsi.size // m
    none = np.empty(0)  # no tabulated profile (a global array would be read-only)
    total = 0.0
    for _ in range(repeats):
        f_eps, f_chi, t_a, _ = cavitating_film_forces(
            THIN, A, B, FLUID_MU, LENGTH, kappa, omk, eps_dot, w_a, w_b, kappa, omk,
            cpsi, spsi, vpsi, ppsi, wpsi, m, none, none, 1.0, 0.0,
            model, p_cav, p_ref, np.empty(n), np.empty(n), np.empty(n))
        total += f_eps + f_chi + t_a
    return total


@njit
def _full_film_loop(repeats, kappa, omk, eps_dot, w_a, w_b, rule, m):
    """Call the full-film kernel ``repeats`` times as lubrication.reynolds.reynolds_kernel does; return a checksum."""
    cpsi, spsi, vpsi, ppsi, wpsi = rule
    none = np.empty(0)  # no tabulated profile, no pressure wanted
    total = 0.0
    for _ in range(repeats):
        f_eps, f_chi, t_a = film_forces(THIN, A, B, FLUID_MU, LENGTH, kappa, omk, eps_dot, w_a, w_b,
                                        kappa, omk, cpsi, spsi, vpsi, ppsi, wpsi, m, none, none, 1.0, 0.0,
                                        none)
        total += f_eps + f_chi + t_a
    return total


def _jit_batch(model: str, annulus: Annulus, n: int):
    rule, _ = psi_rule(n, POINTS_PER_CELL)
    args = (annulus.kappa, annulus.one_minus_kappa, MOTION.eps_dot, MOTION.w_a, MOTION.w_b, rule, POINTS_PER_CELL)

    def batch(calls):
        start = time.perf_counter()
        if model == "none":
            _full_film_loop(calls, *args)
        else:
            _cavitating_loop(calls, CAVITATION_MODELS.index(model), *args, P_CAV, P_REF)
        return [time.perf_counter() - start]
    return batch


def _python_batch(model: str, annulus: Annulus, n: int):
    def batch(calls):
        start = time.perf_counter()
        for _ in range(calls):
            if model == "none":
                reynolds_forces(annulus, MOTION, FLUID, n=n, points_per_cell=POINTS_PER_CELL)
            else:
                cavitating_forces(annulus, MOTION, FLUID, model, p_cav=P_CAV, p_ref=P_REF, n=n,
                                  points_per_cell=POINTS_PER_CELL)
        return [time.perf_counter() - start]
    return batch


def run(cells=CELLS, rounds=ROUNDS, batch_seconds=BATCH_SECONDS, seed=0) -> dict:
    """Median seconds per solve of every model and path at every N, with passes and cavity size.

    Parameters
    ----------
    cells : sequence of int
        Cells N of the Sommerfeld grid.
    rounds : int
        Timing samples per method, interleaved in shuffled order.
    batch_seconds : float
        Minimum duration of one sample (s).
    seed : int
        Seed of the shuffling.

    Returns
    -------
    dict
        JSON-ready: the case, the machine, and one record per (model, N) with the
        median wall and CPU seconds per solve of both paths.
    """
    annulus = Annulus.from_kappa(A, B, KAPPA, LENGTH)
    timers, records = [], []
    for n in cells:
        for model in CAVITATION_MODELS:
            film = cavitating_pressure(annulus, MOTION, FLUID, model, p_cav=P_CAV, p_ref=P_REF, n=n,
                                       points_per_cell=POINTS_PER_CELL)
            records.append({"model": model, "n": n, "passes": film.passes,
                            "cavitated_fraction": float(np.count_nonzero(film.p <= P_CAV) / n)
                            if model != "none" else 0.0})
            timers += [Timer((model, n, "jit"), _jit_batch(model, annulus, n)),
                       Timer((model, n, "python"), _python_batch(model, annulus, n))]
    start = time.perf_counter()
    times = time_all(timers, rounds, batch_seconds, np.random.default_rng(seed))
    for record in records:
        for path in ("jit", "python"):
            record[path] = times[(record["model"], record["n"], path)]
    return {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "machine": machine(), "timing_seconds": time.perf_counter() - start,
            "case": {"kappa": KAPPA, "eps_dot": MOTION.eps_dot, "omega_a": MOTION.omega_a,
                     "omega_b": MOTION.omega_b, "p_ref": P_REF, "p_cav": P_CAV, "nu": FLUID.nu, "rho": FLUID.rho,
                     "points_per_cell": POINTS_PER_CELL, "rounds": rounds, "batch_seconds": batch_seconds},
            "records": records}


def to_markdown(results: dict) -> str:
    """Tables of the median time per solve (us) and its ratio to the full film, per path."""
    by_key = {(r["model"], r["n"]): r for r in results["records"]}
    cells = sorted({r["n"] for r in results["records"]})
    case, machine = results["case"], results["machine"]
    out = ["# Cost of a solve with cavitation", "",
           f"kappa = {case['kappa']}, eps' = {case['eps_dot']:g} m/s, Omega_a = {case['omega_a']:g}, "
           f"Omega_b = {case['omega_b']:g} rad/s, p_ref - p_cav = {case['p_ref'] - case['p_cav']:g} Pa; "
           f"Sommerfeld grid, {case['points_per_cell']} Gauss point per cell. Median wall time of "
           f"{case['rounds']} interleaved samples. {machine['cpu']}, {machine['cores']} cores, "
           f"numba {machine['numba']}; {results['date']}.", ""]
    for path in ("jit", "python"):
        out += [f"## {path}: us per solve (ratio to the full film)", "",
                "| N | " + " | ".join(CAVITATION_MODELS) + " | passes (SS, JFO) | cavitated (JFO) |",
                "|---|" + "---|" * (len(CAVITATION_MODELS) + 2)]
        for n in cells:
            full = by_key[("none", n)][path]["total"]
            row = [f"{full * 1e6:.3g}"] + [f"{by_key[(m, n)][path]['total'] * 1e6:.3g} "
                                           f"({by_key[(m, n)][path]['total'] / full:.2g})"
                                           for m in CAVITATION_MODELS[1:]]
            out.append(f"| {n} | " + " | ".join(row) + f" | {by_key[('swift-stieber', n)]['passes']}, "
                       f"{by_key[('jfo', n)]['passes']} | {by_key[('jfo', n)]['cavitated_fraction']:.2f} |")
        out.append("")
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("cavitation", results, to_markdown(results))


if __name__ == "__main__":
    main()
