"""What an ensemble of rough runs costs: realisations per second on the sweep machinery, against ``snail run``.

The apparatus of the paper's Table 3 runs (steel, 500 cSt, 2.4 degrees), its surfaces rough
(amplitude 0.5, correlation 1 mm, the paper's friction angle, sigma = 50 um) and turning with
both cylinders, in the full equations (2.1)-(2.4) with the exact Stokes forces, released at
kappa = 0.5, phi = 0.5 and run for ``T_END``; one realisation per seed. Two ways:

* a sweep over a ``contact.seed`` axis on a local cluster of two worker processes
  (:func:`dynamics.app.sweeps.run.run_sweep`, which also writes ``ensemble.csv``): wall
  time from the call to its return, cluster start included, after one sweep that leaves the
  kernels compiled in numba's cache; of ``SEEDS`` and of ``LARGE`` realisations, whose
  difference is the marginal cost of a realisation, which a large ensemble pays;
* the same realisations one by one through ``snail run --no-plot`` in a new process each, as a
  user would without the sweep.

Reported: the medians of ``ROUNDS`` interleaved rounds, realisations per second, the ratio, and
1,000 realisations projected from the large sweep's fixed and marginal costs.
Run from the project root with ``python -m benchmarks.ensemble``; writes
``benchmarks/results/ensemble.json`` and ``.md``.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import machine, publish, speed_gauge_ms, spread

T_END = "60 s"
SEEDS = 8  # realisations of the small sweep
LARGE = 64  # and of the large one: their difference is the cost of a realisation once the cluster runs
ONE_BY_ONE = 4  # realisations run through snail run (each a new process)
ROUNDS = 3
GOAL_SECONDS = 120.0  # 1,000 realisations of 60 s on 2 cores
SCENE = f"""[apparatus]
preset = "steel"
[fluid]
nu = "500 cSt"
[incline]
alpha = "2.4 deg"
[initial]
kappa = 0.5
phi = 0.5
[contact]
sigma = "50 um"
friction_angle = "5 deg"
roughness_amplitude = 0.5
roughness_correlation = "1 mm"
[run]
t_end = "{T_END}"
max_gap_reynolds = "none"
output_interval = "0.1 s"
"""


def _sweep_seconds(folder: Path, seeds: int) -> float:
    from dynamics.app.sweeps.run import run_sweep
    from dynamics.app.sweeps.spec import parse_sweep

    (folder / "scene.toml").write_text(SCENE)
    sweep = parse_sweep(f'base = "scene.toml"\n[axes]\n"contact.seed" = {{start = 0, stop = {seeds - 1}, '
                        f'num = {seeds}}}\n', base_dir=folder)
    start = time.perf_counter()
    result = run_sweep(sweep, folder / "out", workers=2, progress=False)
    seconds = time.perf_counter() - start
    if result.regimes.get("failed"):
        msg = f"{result.regimes['failed']} realisations failed"
        raise RuntimeError(msg)
    return seconds


def _one_by_one_seconds(folder: Path, count: int) -> float:
    (folder / "scene.toml").write_text(SCENE)
    start = time.perf_counter()
    for seed in range(count):
        subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", str(folder / "scene.toml"), "--no-plot",
                        "--set", f"contact.seed={seed}", "-o", str(folder / f"run{seed}")], check=True,
                       capture_output=True)
    return time.perf_counter() - start


def _row(how: str, count: int, wall: dict, per: dict) -> str:
    return (f"| {how} | {count} | {wall['median']:.1f} ({wall['min']:.1f}-{wall['max']:.1f}) | {per['median']:.2f} | "
            f"{1.0 / per['median']:.2f} |")


def run() -> dict:
    results = {"machine": machine(), "speed_gauge_ms_at_start": speed_gauge_ms(), "t_end": T_END,
               "seeds": SEEDS, "one_by_one": ONE_BY_ONE}
    with tempfile.TemporaryDirectory() as tmp:
        warm = Path(tmp) / "warm"
        warm.mkdir()
        _sweep_seconds(warm, 2)  # the kernels compiled into numba's cache
        sweep, large, single = [], [], []
        for r in range(ROUNDS):
            for kind in (("sweep", "large", "single") if r % 2 == 0 else ("single", "large", "sweep")):
                folder = Path(tmp) / f"{kind}{r}"
                folder.mkdir()
                if kind == "single":
                    single.append(_one_by_one_seconds(folder, ONE_BY_ONE))
                else:
                    (sweep if kind == "sweep" else large).append(_sweep_seconds(folder, SEEDS if kind == "sweep"
                                                                                else LARGE))
    per_sweep = spread([s / SEEDS for s in sweep])
    per_single = spread([s / ONE_BY_ONE for s in single])
    marginal = spread([(big - small) / (LARGE - SEEDS) for big, small in zip(large, sweep, strict=True)])
    fixed = float(np.median(sweep)) - SEEDS * marginal["median"]
    thousand = fixed + 1000 * marginal["median"]
    results.update(sweep_seconds=spread(sweep), large_sweep_seconds=spread(large), one_by_one_seconds=spread(single),
                   seconds_per_realisation_sweep=per_sweep, seconds_per_realisation_one_by_one=per_single,
                   marginal_seconds_per_realisation=marginal, fixed_seconds=fixed,
                   projected_seconds_for_1000=thousand, goal_seconds_for_1000=GOAL_SECONDS,
                   realisations_per_second_sweep=1.0 / per_sweep["median"],
                   ratio_one_by_one_over_sweep=per_single["median"] / per_sweep["median"],
                   speed_gauge_ms_at_end=speed_gauge_ms())
    lines = ["# Ensembles of rough full-model runs", "",
             f"Steel, 500 cSt, 2.4 deg, rough surfaces turning with both cylinders (amplitude 0.5, correlation 1 mm, "
             f"sigma 50 um, friction angle 5 deg), full equations with the exact Stokes forces, {T_END} each; "
             f"{ROUNDS} interleaved rounds, medians (fastest-slowest). {results['machine']['cpu']}, "
             f"{results['machine']['cores']} cores.", "",
             "| how | realisations | wall (s) | s per realisation | realisations per second |", "|---|---|---|---|---|",
             _row("sweep on 2 workers (cluster start included)", SEEDS, results["sweep_seconds"], per_sweep),
             _row("sweep on 2 workers (cluster start included)", LARGE, results["large_sweep_seconds"],
                  spread([s / LARGE for s in large])),
             _row("`snail run --no-plot`, one process each", ONE_BY_ONE, results["one_by_one_seconds"], per_single),
             "",
             f"One by one takes {results['ratio_one_by_one_over_sweep']:.2f} times as long per realisation as the "
             f"small sweep. Once the cluster runs, a realisation costs {marginal['median']:.3f} s of wall time on the "
             f"2 workers ({marginal['min']:.3f}-{marginal['max']:.3f}; the large sweep less the small one, pair by "
             f"pair), and the start {fixed:.1f} s: 1,000 realisations would take {thousand / 60:.1f} min. Goal: "
             f"{GOAL_SECONDS / 60:.0f} min, " + ("met." if thousand <= GOAL_SECONDS else "not met."), "",
             "This machine's speed drifts from minute to minute: a fixed pure-Python loop "
             f"(`benchmarks.harness.speed_gauge_ms`) took {results['speed_gauge_ms_at_start']:.0f} ms at the start "
             f"of this run and {results['speed_gauge_ms_at_end']:.0f} ms at its end."]
    publish("ensemble", results, "\n".join(lines))
    return results


if __name__ == "__main__":
    run()
