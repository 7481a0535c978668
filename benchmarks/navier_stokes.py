r"""The coupled Navier-Stokes run of the snail cylinder: wall seconds per simulated second.

Reuse. The default release (steel, 200 cSt, 2.4 deg, kappa = 0.5, phi = 0.5 rad, from
rest; :func:`dynamics.simulation.simulate` with ``equations = "navier-stokes"``) at the
default resolution (16 points across, the grid around chosen for the gap as it moves)
and tolerance (:data:`dynamics.simulation.NAVIER_STOKES_RTOL`), over :data:`T_END`,
with the factorisations reused across steps and corrections (the solver as it is) and
with every solve factorised anew (``reuse_factorisations=False``), in :data:`PAIRS`
interleaved pairs whose order alternates: medians, spreads and their ratio.

Growth. The same release against the points across (n_r = 8, 16, 24), and released
nearer the wall (kappa = 0.9 and 0.99, where the default grid around is finer and
the squeeze film stiffer), each timed :data:`REPEATS` times: medians.

The cost is the run's own wall time (``info["navier_stokes"]["wall_time_s"]``, the
stepping: neither the steady start nor the assembly of the trajectory), over the
simulated time. A warm-up run first, so that numba's compilation is never timed. BLAS
runs on one thread inside the steps (the solver's own setting). The machine (2 cores) is shared: the load
average and a fixed Python loop's time are recorded at the start and at the end
(:func:`benchmarks.harness.speed_gauge_ms`). Run ``python -m benchmarks.navier_stokes``
(a few minutes); it writes ``benchmarks/results/navier_stokes.json`` and ``.md``.
"""

from __future__ import annotations

import datetime
import math
import os
import sys
from pathlib import Path

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import machine, publish, speed_gauge_ms, spread
from dynamics.apparatus import preset
from dynamics.equations.limits import Limits
from dynamics.equations.navier_stokes import NavierStokesOptions
from dynamics.initial import Initial
from dynamics.simulation import NAVIER_STOKES_RTOL, simulate

__all__ = ["GAPS", "N_R", "PAIRS", "REPEATS", "T_END", "main", "release", "run", "to_markdown"]

#: Simulated time of each run (s): the release's start, in which the inner cylinder swings round the outer one.
T_END = 0.1
PAIRS = 7
REPEATS = 3
N_R = (8, 16, 24)
#: Initial kappa of the releases nearer the wall.
GAPS = (0.9, 0.99)
ALPHA_DEG = 2.4


def release(kappa: float = 0.5, n_r: int = 16, reuse: bool = True) -> dict:
    """One coupled run of the default release from ``kappa``: its cost per simulated second and its counts."""
    apparatus = preset("steel", alpha=math.radians(ALPHA_DEG))
    run = simulate(apparatus, Initial(kappa, 0.5), T_END, equations="navier-stokes",
                   limits=Limits(on_invalid="warn"),
                   navier_stokes=NavierStokesOptions(n_r=n_r, reuse_factorisations=reuse))
    if run.status != "completed":  # a cost per simulated second needs the whole run
        raise RuntimeError(f"the release from kappa = {kappa:g} stopped: {run.message}")
    info = run.info["navier_stokes"]
    return {"per_simulated_second_s": info["wall_time_s"] / T_END, **{k: info[k] for k in (
        "n_theta", "n_r", "steps", "rejected", "factorisations", "solves")}}


def _conditions() -> dict:
    return {"load_average": os.getloadavg()[0], "python_loop_ms": speed_gauge_ms()}


def run(pairs: int = PAIRS, repeats: int = REPEATS, n_rs=N_R, gaps=GAPS) -> dict:
    """Every timing of the module docstring, as plain data (no files written)."""
    results = {"date": datetime.date.today().isoformat(), "machine": machine(), "at_start": _conditions(),
               "t_end_s": T_END, "rtol": NAVIER_STOKES_RTOL, "pairs_count": pairs, "repeats": repeats}
    release()  # warm-up: compiles the kernels
    timed = {"reuse": [], "baseline": []}
    for i in range(pairs):
        for reuse in ((True, False) if i % 2 == 0 else (False, True)):
            timed["reuse" if reuse else "baseline"].append(release(reuse=reuse))
    growth = {"n_r": [], "gap": []}
    for n_r in n_rs:
        runs = [release(n_r=n_r) for _ in range(repeats)]
        growth["n_r"].append({"kappa0": 0.5, "n_r": n_r, "runs": runs,
                              **spread([r["per_simulated_second_s"] for r in runs])})
    for kappa in gaps:
        runs = [release(kappa=kappa) for _ in range(repeats)]
        growth["gap"].append({"kappa0": kappa, "n_r": 16, "runs": runs,
                              **spread([r["per_simulated_second_s"] for r in runs])})
    reuse = {key: spread([r["per_simulated_second_s"] for r in runs]) for key, runs in timed.items()}
    results.update(pairs=timed, reuse=reuse, growth=growth, at_end=_conditions(),
                   ratio_baseline_over_reuse=reuse["baseline"]["median"] / reuse["reuse"]["median"])
    return results


def main() -> None:
    results = run()
    publish("navier_stokes", results, to_markdown(results))


def to_markdown(results: dict) -> str:
    m = results["machine"]
    reuse, pairs = results["reuse"], results["pairs"]
    lines = ["# Coupled Navier-Stokes run: cost per simulated second", "",
             f"{results['date']}, {m['cpu']}, {m['cores']} cores (shared: load average "
             f"{results['at_start']['load_average']:.1f} at the start, {results['at_end']['load_average']:.1f} at the "
             f"end; a fixed Python loop {results['at_start']['python_loop_ms']:.0f} ms, then "
             f"{results['at_end']['python_loop_ms']:.0f} ms).", "",
             f"The default release (steel, 200 cSt, {ALPHA_DEG} deg, kappa = 0.5, phi = 0.5 rad, from rest), "
             f"{results['t_end_s']:g} s simulated, rtol {results['rtol']:g}; wall seconds of the stepping per "
             "simulated second.", "",
             "## Factorisations reused against factorised every solve "
             f"({results['pairs_count']} interleaved pairs)", "",
             "| solver | median | fastest | slowest | steps | rejected | factorisations | solves |",
             "|---|---|---|---|---|---|---|---|"]
    for key, label in (("reuse", "factorisations reused"), ("baseline", "factorised every solve")):
        r0 = pairs[key][0]
        lines.append(f"| {label} | {reuse[key]['median']:.1f} | {reuse[key]['min']:.1f} | "
                     f"{reuse[key]['max']:.1f} | {r0['steps']} | {r0['rejected']} | {r0['factorisations']} | "
                     f"{r0['solves']} |")
    lines += ["", f"Ratio of the medians, baseline over reuse: {results['ratio_baseline_over_reuse']:.2f}.", "",
              f"## Against the points across and the gap (median of {results['repeats']})", "",
              "| kappa0 | n_r | n_theta at the end | median | fastest | slowest | steps | factorisations |",
              "|---|---|---|---|---|---|---|---|"]
    for row in (*results["growth"]["n_r"], *results["growth"]["gap"]):
        r0 = row["runs"][0]
        lines.append(f"| {row['kappa0']:g} | {row['n_r']} | {r0['n_theta']} | {row['median']:.1f} | "
                     f"{row['min']:.1f} | {row['max']:.1f} | {r0['steps']} | {r0['factorisations']} |")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
