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
1,000 realisations projected from the large sweep's fixed and marginal costs. The sweeps run
again with ``run.rtol = FAST_RTOL`` (the default is 1e-8): an ensemble's answer is its
statistics, whose uncertainty is the spread across realisations, so the benchmark reports each
statistic's largest change between the two tolerances, seed by seed over the large sweeps, in
units of that spread, beside the cost.
Run from the project root with ``python -m benchmarks.ensemble``; writes
``benchmarks/results/ensemble.json`` and ``.md``.
"""

from __future__ import annotations

import math
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
FAST_RTOL = 1e-6  # the looser tolerance measured beside the default
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


def _scene(rtol: float | None = None) -> str:
    return SCENE if rtol is None else SCENE.replace("[run]\n", f"[run]\nrtol = {rtol!r}\n")


def _sweep_seconds(folder: Path, seeds: int, rtol: float | None = None) -> float:
    from dynamics.app.sweeps.run import run_sweep
    from dynamics.app.sweeps.spec import parse_sweep

    (folder / "scene.toml").write_text(_scene(rtol))
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


def _tolerance_changes(default: Path, fast: Path) -> dict:
    """Per statistic of :data:`dynamics.ensemble.UNSTEADINESS` between the sweeps in ``default`` and ``fast``: the
    largest change seed by seed, over the standard deviation across the default's realisations, and the change of
    the ensemble's mean, over its standard error."""
    from dynamics.app.sweeps.store import read_table
    from dynamics.ensemble import UNSTEADINESS

    rows = [{row["contact.seed"]: row for row in read_table(folder / "out" / "sweep.csv")}
            for folder in (default, fast)]
    changes = {}
    for name in UNSTEADINESS:
        base = np.array([rows[0][seed][name] for seed in sorted(rows[0])], dtype=float)
        other = np.array([rows[1][seed][name] for seed in sorted(rows[0])], dtype=float)
        count = int(np.sum(np.isfinite(base)))
        sd = float(np.nanstd(base, ddof=1)) if count > 1 else math.nan
        change = float(np.nanmax(np.abs(other - base))) if count else math.nan
        mean_change = abs(float(np.nanmean(other)) - float(np.nanmean(base))) if count else math.nan
        changes[name] = {"sd": sd, "largest_change": change, "in_sd": change / sd if sd > 0 else math.nan,
                         "mean_change": mean_change,
                         "mean_change_in_se": mean_change / (sd / math.sqrt(count)) if sd > 0 else math.nan}
    return changes


def _row(how: str, rtol: str, count: int, wall: dict, per: dict) -> str:
    return (f"| {how} | {rtol} | {count} | {wall['median']:.1f} ({wall['min']:.1f}-{wall['max']:.1f}) | "
            f"{per['median']:.2f} | {1.0 / per['median']:.2f} |")


def _projection(small: list, large: list) -> tuple[dict, float, float]:
    """A realisation's marginal cost (large sweep less small one, pair by pair), the fixed cost, 1,000's cost."""
    marginal = spread([(big - few) / (LARGE - SEEDS) for big, few in zip(large, small, strict=True)])
    fixed = float(np.median(small)) - SEEDS * marginal["median"]
    return marginal, fixed, fixed + 1000 * marginal["median"]


def run() -> dict:
    results = {"machine": machine(), "speed_gauge_ms_at_start": speed_gauge_ms(), "t_end": T_END,
               "seeds": SEEDS, "one_by_one": ONE_BY_ONE, "fast_rtol": FAST_RTOL}
    kinds = ("sweep", "large", "fast_sweep", "fast_large", "single")
    with tempfile.TemporaryDirectory() as tmp:
        warm = Path(tmp) / "warm"
        warm.mkdir()
        _sweep_seconds(warm, 2)  # the kernels compiled into numba's cache
        wall = {kind: [] for kind in kinds}
        for r in range(ROUNDS):
            for kind in (kinds if r % 2 == 0 else kinds[::-1]):
                folder = Path(tmp) / f"{kind}{r}"
                folder.mkdir()
                if kind == "single":
                    wall[kind].append(_one_by_one_seconds(folder, ONE_BY_ONE))
                else:
                    wall[kind].append(_sweep_seconds(folder, LARGE if kind.endswith("large") else SEEDS,
                                                     FAST_RTOL if kind.startswith("fast") else None))
        changes = _tolerance_changes(Path(tmp) / "large0", Path(tmp) / "fast_large0")
    sweep, large, single = wall["sweep"], wall["large"], wall["single"]
    per_sweep = spread([s / SEEDS for s in sweep])
    per_single = spread([s / ONE_BY_ONE for s in single])
    marginal, fixed, thousand = _projection(sweep, large)
    fast_marginal, fast_fixed, fast_thousand = _projection(wall["fast_sweep"], wall["fast_large"])
    worst = max((c["in_sd"] for c in changes.values() if math.isfinite(c["in_sd"])), default=math.nan)
    worst_mean = max((c["mean_change_in_se"] for c in changes.values() if math.isfinite(c["mean_change_in_se"])),
                     default=math.nan)
    results.update(sweep_seconds=spread(sweep), large_sweep_seconds=spread(large), one_by_one_seconds=spread(single),
                   seconds_per_realisation_sweep=per_sweep, seconds_per_realisation_one_by_one=per_single,
                   marginal_seconds_per_realisation=marginal, fixed_seconds=fixed,
                   projected_seconds_for_1000=thousand, goal_seconds_for_1000=GOAL_SECONDS,
                   realisations_per_second_sweep=1.0 / per_sweep["median"],
                   ratio_one_by_one_over_sweep=per_single["median"] / per_sweep["median"],
                   fast_sweep_seconds=spread(wall["fast_sweep"]), fast_large_sweep_seconds=spread(wall["fast_large"]),
                   fast_marginal_seconds_per_realisation=fast_marginal, fast_fixed_seconds=fast_fixed,
                   fast_projected_seconds_for_1000=fast_thousand, tolerance_changes=changes,
                   largest_change_in_sd=worst, largest_mean_change_in_se=worst_mean,
                   speed_gauge_ms_at_end=speed_gauge_ms())

    def verdict(seconds):
        return "met." if seconds <= GOAL_SECONDS else "not met."

    lines = ["# Ensembles of rough full-model runs", "",
             f"Steel, 500 cSt, 2.4 deg, rough surfaces turning with both cylinders (amplitude 0.5, correlation 1 mm, "
             f"sigma 50 um, friction angle 5 deg), full equations with the exact Stokes forces, {T_END} each; "
             f"{ROUNDS} interleaved rounds, medians (fastest-slowest). {results['machine']['cpu']}, "
             f"{results['machine']['cores']} cores.", "",
             "| how | run.rtol | realisations | wall (s) | s per realisation | realisations per second |",
             "|---|---|---|---|---|---|",
             _row("sweep on 2 workers (cluster start included)", "1e-8 (default)", SEEDS, results["sweep_seconds"],
                  per_sweep),
             _row("sweep on 2 workers (cluster start included)", "1e-8 (default)", LARGE,
                  results["large_sweep_seconds"], spread([s / LARGE for s in large])),
             _row("sweep on 2 workers (cluster start included)", f"{FAST_RTOL:g}", SEEDS,
                  results["fast_sweep_seconds"], spread([s / SEEDS for s in wall["fast_sweep"]])),
             _row("sweep on 2 workers (cluster start included)", f"{FAST_RTOL:g}", LARGE,
                  results["fast_large_sweep_seconds"], spread([s / LARGE for s in wall["fast_large"]])),
             _row("`snail run --no-plot`, one process each", "1e-8 (default)", ONE_BY_ONE,
                  results["one_by_one_seconds"], per_single),
             "",
             f"One by one takes {results['ratio_one_by_one_over_sweep']:.2f} times as long per realisation as the "
             f"small sweep. Once the cluster runs, a realisation costs {marginal['median']:.3f} s of wall time on the "
             f"2 workers ({marginal['min']:.3f}-{marginal['max']:.3f}; the large sweep less the small one, pair by "
             f"pair), and the start {fixed:.1f} s: 1,000 realisations would take {thousand / 60:.1f} min. Goal: "
             f"{GOAL_SECONDS / 60:.0f} min, " + verdict(thousand), "",
             f"With `run.rtol = {FAST_RTOL:g}` a realisation costs {fast_marginal['median']:.3f} s "
             f"({fast_marginal['min']:.3f}-{fast_marginal['max']:.3f}): 1,000 in {fast_thousand / 60:.1f} min, goal "
             + verdict(fast_thousand) + " An ensemble's answer is its statistics, uncertain by their spread across "
             f"realisations. Over the {LARGE} seeds of the large sweeps, between the two tolerances, the ensemble's "
             f"mean of each statistic of `dynamics.ensemble.UNSTEADINESS` moves by at most {worst_mean:.2f} of its "
             f"standard error, and a single realisation's statistic by at most {worst:.2f} of the spread (a run "
             "that passes close to a contact switch may take the other side of it at the other tolerance):", "",
             "| statistic | spread across realisations (sd) | largest change of a realisation | in sd "
             "| change of the ensemble's mean | in standard errors |",
             "|---|---|---|---|---|---|",
             *(f"| `{name}` | {c['sd']:.3g} | {c['largest_change']:.2g} | {c['in_sd']:.1e} | "
               f"{c['mean_change']:.2g} | {c['mean_change_in_se']:.2f} |" if math.isfinite(c["in_sd"])
               else f"| `{name}` | {c['sd']:.3g} | {c['largest_change']:.2g} | (no spread) | | |"
               for name, c in changes.items()),
             "", "sweep.csv keeps 7 significant digits, so a change below a value's last digit reads as that digit.",
             "",
             "This machine's speed drifts from minute to minute: a fixed pure-Python loop "
             f"(`benchmarks.harness.speed_gauge_ms`) took {results['speed_gauge_ms_at_start']:.0f} ms at the start "
             f"of this run and {results['speed_gauge_ms_at_end']:.0f} ms at its end."]
    publish("ensemble", results, "\n".join(lines))
    return results


if __name__ == "__main__":
    run()
