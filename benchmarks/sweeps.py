r"""Sweeps: the regime map's trajectories one at a time, in the compiled batch and in CyRK; a map end to end.

The regime map is ``dynamics/app/sweeps/examples/regime_map.toml``: the reduced
model (2.11) released from rest, 100 tau at rtol = atol = 1e-6, over the slope s,
the initial kappa and Upsilon (mu_ = 1). Two questions:

(a) What does one trajectory of the map cost? A seeded sample of ``SAMPLE``
points of the 10,000-point map, each through

``per point``
    :func:`dynamics.app.sweeps.point.run_point`: the scene built, run through
    :func:`dynamics.simulation.simulate` (the compiled engine, called from
    Python per run) and classified: every point's path before the batch runner;
``batch``
    :func:`dynamics.app.sweeps.batch.run_batch` on the point alone: the scene
    built in Python, the run in the compiled loop
    (:mod:`dynamics.app.sweeps.compiled`), classified; and on the whole sample
    in one call (its mean per point);
``CyRK Radau``, ``CyRK LSODA``
    CyRK's public ``pysolve_ivp`` (not a dependency of the project: measured
    when it is installed) on the same right-hand side (the compiled
    :func:`dynamics.equations.reduced.rhs`, called from CyRK's C++ loop through
    Python), with the same tolerances, length and the two terminal events that
    end runs of the map (the gap floor and the runaway after 100 turns of the
    outer cylinder) as Python functions; its Jacobian by finite differences.
    The integration alone: no scene, no classification.

Each (point, path) is timed ``REPEATS`` times in thread CPU time (load from
other jobs inflates wall time, not CPU time), the repeats interleaved and the
paths in a shuffled order; a point's time is the median of its repeats. The
batch's rows must equal the per-point rows (asserted: regimes, steps, numbers);
CyRK's trajectories are classified like the others, and their agreement with
the batch's regimes is reported. A fixed pure-Python loop is timed before each
repeat and around each call of the whole sample
(:func:`benchmarks.harness.speed_gauge_ms`): the report says how fast the
machine ran while it measured.

(b) A map end to end: ``run_sweep`` on a local cluster of 2 single-threaded
worker processes, wall time from the start of the cluster to the last row, for
a grid of 1,000, 10,000 (the shipped map) or 100,000 points, then the same
points through the per-point path on 2 workers (``--per-point``, the default
up to 10,000 points). The regimes are compared with the stored map of the old
scipy-based code (``docs/sweeps/regime_map/sweep.csv``, 1,127 s for its 10,000
points) on the points both have. ``--output DIR`` keeps the map's files
(``sweep.csv``, ``sweep.json``, ``regime_map.png``) there; ``--replace`` first
removes a map already in DIR, e.g.

    python -m benchmarks.sweeps --points 10000 --output docs/sweeps/regime_map --replace

Writes ``benchmarks/results/sweeps.json`` and ``sweeps.md`` for the shipped
10,000-point map, ``sweeps_1k.*`` and ``sweeps_100k.*`` for the other grids.
"""

from __future__ import annotations

import argparse
import datetime
import math
import random
import statistics
import sys
import tempfile
import time
import tomllib
from pathlib import Path
from types import SimpleNamespace

import numpy as np

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import machine, publish, speed_gauge_ms
from dynamics.app.sweeps import batch, run
from dynamics.app.sweeps.compiled import integrate_points
from dynamics.app.sweeps.plot import save_regime_map
from dynamics.app.sweeps.point import classify_point, run_point
from dynamics.app.sweeps.spec import load_sweep, parse_sweep, point_key
from dynamics.app.sweeps.store import CSV_NAME, MANIFEST_NAME, read_rows
from dynamics.equations import reduced
from dynamics.scenes import parse_scene

__all__ = ["main", "run_map", "run_trajectories", "to_markdown"]

ROOT = Path(__file__).resolve().parents[1]
MAP = ROOT / "dynamics" / "app" / "sweeps" / "examples" / "regime_map.toml"
STORED = ROOT / "docs" / "sweeps" / "regime_map"
SAMPLE = 200
REPEATS = 5  # medians of five: the machine slows for minutes at a time
WORKERS = 2
PATHS = ("per point", "batch", "CyRK Radau", "CyRK LSODA")
# The grids of (b): (start, stop, num) of s, the initial kappa and Upsilon (log-spaced). 1,000 points are every
# other s and kappa and every third Upsilon of the shipped 10,000, so that all are in the stored map.
GRIDS = {1_000: ((0.0, 1.2, 25), (0.0, 0.9, 10), (0.1, 10.0, 4)),
         10_000: ((0.0, 1.225, 50), (0.0, 0.95, 20), (0.1, 10.0, 10)),
         100_000: ((0.0, 1.225, 100), (0.0, 0.95, 50), (0.1, 10.0, 20))}
# The old scipy-based code on the shipped map (docs/sweeps/regime_map/sweep.json).
OLD_MAP_SECONDS, OLD_MAP_POINTS = 1127.0, 10_000
GOALS = {"trajectory_cpu_ms": 1.0, "map_10000_wall_s": 60.0}


# -- (a) one trajectory ---------------------------------------------------------------------------------------


def _cyrk_events():
    """The terminal events of a map's run (gap floor and runaway, as reduced.events), as CyRK takes them."""

    def gap_floor(t, y, args):
        r = math.hypot(y[0], y[1])
        rho = math.sqrt(1.0 + r * r)
        return math.log(1.0 / (rho * (rho + r))) - args[3]

    def runaway(t, y, args):
        return args[7] - abs(y[4] - args[8])

    for event in (gap_floor, runaway):
        event.terminal, event.direction = True, -1
    return [gap_floor, runaway]


def _cyrk(method: str, prepared, events) -> dict:
    """One point through CyRK's ``pysolve_ivp``; its regime as the sweeps classify it."""
    from CyRK import pysolve_ivp

    result = pysolve_ivp(reduced.rhs, (0.0, prepared.t_end_tau), prepared.y0, method=method, events=events,
                         args=(prepared.args,), rtol=prepared.rtol, atol=prepared.rtol)
    if not result.success:
        return {"regime": "failed", "steps": int(result.steps_taken)}
    stopped = bool(result.event_terminated)
    t, y = np.asarray(result.t), np.ascontiguousarray(result.y)
    columns = reduced.columns(y, prepared.phi0, prepared.args)
    trajectory = SimpleNamespace(columns={"t_tau": t, "phi": columns["phi"], "kappa": columns["kappa"],
                                          "one_minus_kappa": columns["one_minus_kappa"],
                                          "omega_b": columns["omega_b"]},
                                 tau=1.0, status="stopped" if stopped else "completed",
                                 event=("gap_floor", "runaway")[result.event_terminate_index] if stopped else "")
    return {"regime": classify_point(trajectory)[0], "steps": int(result.steps_taken)}


def _cyrk_available() -> str | None:
    try:
        import CyRK
    except ImportError:
        return None
    return CyRK.__version__


def _same_rows(got: dict, expected: dict) -> bool:
    for key, value in expected.items():
        if key == "wall_time_s":
            continue
        if isinstance(value, float) and not (math.isclose(got[key], value, rel_tol=1e-12, abs_tol=1e-12)
                                             or (math.isnan(value) and math.isnan(got[key]))):
            return False
        if not isinstance(value, float) and got[key] != value:
            return False
    return True


def run_trajectories(sample: int = SAMPLE, repeats: int = REPEATS, seed: int = 0) -> dict:
    """(a): CPU time per trajectory of a sample of the regime map through every path; plain data."""
    sweep = load_sweep(MAP)
    rng = random.Random(seed)
    points = rng.sample(sweep.points(), sample)
    cyrk = _cyrk_available()
    paths = [p for p in PATHS if cyrk or not p.startswith("CyRK")]
    events = _cyrk_events()
    problems = [batch.problem(parse_scene(sweep.base, sweep.source, p)) for p in points]
    assert all(p is not None for p in problems), "every point of the regime map is one the batch takes"

    def one(path: str, i: int):
        point = points[i]
        if path == "per point":
            return run_point(sweep.base, point, sweep.source)
        if path == "batch":
            return batch.run_batch(sweep.base, sweep.source, [point])[0]
        return _cyrk(path.split()[1], problems[i], events)

    for path in paths:  # warm-up: numba's cache (or compilation) is not timed
        one(path, 0)
    cpu = {path: [[] for _ in points] for path in paths}
    results = {path: [None] * len(points) for path in paths}
    parse = [[] for _ in points]
    integration = [[] for _ in points]
    whole, in_batch, gauge = [], [[] for _ in points], []
    for _ in range(repeats):
        gauge.append(speed_gauge_ms())
        for i in rng.sample(range(len(points)), len(points)):
            for path in rng.sample(paths, len(paths)):
                start = time.thread_time()
                results[path][i] = one(path, i)
                cpu[path][i].append(time.thread_time() - start)
            start = time.thread_time()
            batch.problem(parse_scene(sweep.base, sweep.source, points[i]))
            parse[i].append(time.thread_time() - start)
            p = problems[i]
            start = time.thread_time()
            integrate_points([p.y0], [p.args], [p.t_end_tau], [p.rtol], [p.terminal], batch.DIRECTION)
            integration[i].append(time.thread_time() - start)
        gauge.append(speed_gauge_ms())
        start = time.thread_time()
        rows = batch.run_batch(sweep.base, sweep.source, points)
        whole.append((time.thread_time() - start) / len(points))
        gauge.append(speed_gauge_ms())
        # each point's own clock inside the call (scene, integration, classification), as sweep.csv records it
        for i, row in enumerate(rows):
            in_batch[i].append(row["wall_time_s"])
    mismatches = [i for i in range(len(points)) if not _same_rows(results["batch"][i], results["per point"][i])
                  or not _same_rows(rows[i], results["per point"][i])]
    assert not mismatches, f"the batch's rows differ from the per-point rows at {len(mismatches)} points"
    regimes = [r["regime"] for r in results["per point"]]
    per_point = {path: [statistics.median(times) for times in cpu[path]] for path in paths}
    summary = {}
    for path in paths:
        times = per_point[path]
        summary[path] = {"median_ms": 1e3 * statistics.median(times), "mean_ms": 1e3 * statistics.fmean(times),
                         "p90_ms": 1e3 * float(np.quantile(times, 0.9)),
                         "median_ms_by_regime": {regime: 1e3 * statistics.median(
                             [t for t, r in zip(times, regimes) if r == regime]) for regime in sorted(set(regimes))}}
    per_point_in_batch = [statistics.median(times) for times in in_batch]
    summary["batch, whole sample in one call"] = {
        "mean_ms": 1e3 * statistics.median(whole), "point_median_ms": 1e3 * statistics.median(per_point_in_batch),
        "point_mean_ms": 1e3 * statistics.fmean(per_point_in_batch),
        # the points' wall clocks against the call's thread CPU time: near 1 when nothing else took the core
        "clocks_over_cpu": statistics.fmean(per_point_in_batch) / statistics.median(whole)}
    reference = per_point["batch"]
    ratios = {path: {"of_medians": summary[path]["median_ms"] / summary["batch"]["median_ms"],
                     "median_of_ratios": statistics.median(t / b for t, b in zip(per_point[path], reference)),
                     "of_means": summary[path]["mean_ms"] / summary["batch"]["mean_ms"]} for path in paths}
    agreement = {path: sum(results[path][i]["regime"] == regimes[i] for i in range(len(points))) / len(points)
                 for path in paths if path.startswith("CyRK")}
    steps = {"engine": [int(r["steps"]) for r in results["per point"]]}
    steps.update({path: [results[path][i]["steps"] for i in range(len(points))] for path in agreement})
    return {"sample": sample, "repeats": repeats, "seed": seed, "paths": paths, "cyrk": cyrk,
            "regimes": {r: regimes.count(r) for r in sorted(set(regimes))}, "summary": summary, "ratios": ratios,
            "scene_building_ms": 1e3 * statistics.median(statistics.median(p) for p in parse),
            "integration_ms": 1e3 * statistics.median(statistics.median(t) for t in integration),
            "cyrk_regime_agreement": agreement, "speed_gauge_ms": gauge,
            "median_steps": {k: statistics.median(v) for k, v in steps.items()},
            "points": [{"point": point_key(p), **p, "regime": regimes[i],
                        **{f"{path} ms": 1e3 * per_point[path][i] for path in paths}}
                       for i, p in enumerate(points)]}


# -- (b) a map end to end ------------------------------------------------------------------------------------


def map_sweep(points: int):
    """The regime map on the grid of ``points`` (:data:`GRIDS`): the shipped map's base, its axes refined or thinned."""
    raw = tomllib.loads(MAP.read_text(encoding="utf-8"))
    (s, kappa, upsilon) = GRIDS[points]
    raw["axes"] = {"groups.s": dict(zip(("start", "stop", "num"), s)),
                   "initial.kappa": dict(zip(("start", "stop", "num"), kappa)),
                   "groups.upsilon": dict(zip(("start", "stop", "num"), upsilon), spacing="log")}
    return parse_sweep(raw, f"{MAP.name} on a {s[2]} x {kappa[2]} x {upsilon[2]} grid", MAP.parent)


def _per_point_task(base, source, points):
    """A batch as every point ran before the batch runner: one run_point after another."""
    return [run_point(base, point, source) for point in points]


def _sweep(sweep, folder: Path, per_point: bool) -> dict:
    task = run.run_batch
    if per_point:
        run.run_batch = _per_point_task
    try:
        result = run.run_sweep(sweep, folder, workers=WORKERS)
    finally:
        run.run_batch = task
    rows = read_rows(result.csv_path)
    busy = sum(float(r["wall_time_s"]) for r in rows)
    return {"points": result.points, "computed": result.computed, "workers": result.workers,
            "wall_s": result.wall_time_s, "compute_s": result.compute_time_s,
            "points_per_second": result.points_per_second, "regimes": result.regimes,
            # the share of the workers' time not spent on points: dask, the tail, start-up
            "idle_fraction": 1.0 - busy / (result.workers * result.compute_time_s), "rows": rows}


def run_map(points: int = 1_000, output: Path | None = None, replace: bool = False,
            per_point: bool | None = None) -> dict:
    """(b): the map of ``points`` on 2 workers through the batch runner (and the per-point path); plain data."""
    sweep = map_sweep(points)
    stored = {r["point"]: r["regime"] for r in read_rows(STORED / CSV_NAME)}
    if output is not None and replace:
        for name in (CSV_NAME, MANIFEST_NAME, "regime_map.png"):
            (output / name).unlink(missing_ok=True)
    if output is not None and (output / CSV_NAME).exists():
        msg = f"{output} already holds a map: --replace to compute it afresh, or another --output"
        raise SystemExit(msg)
    per_point = points <= 10_000 if per_point is None else per_point
    out = {"points": points, "grid": GRIDS[points], "sweep": sweep.source, "fingerprint": sweep.fingerprint()}
    with tempfile.TemporaryDirectory() as scratch:
        folder = output if output is not None else Path(scratch) / "batch"
        out["batch"] = _sweep(sweep, folder, per_point=False)
        if output is not None:
            save_regime_map(sweep, folder / CSV_NAME)
            out["output"] = str(output)
        if per_point:
            out["per point"] = _sweep(sweep, Path(scratch) / "per_point", per_point=True)
    rows = out["batch"].pop("rows")
    if per_point:
        old_rows = {r["point"]: r for r in out["per point"].pop("rows")}
        out["per point"]["same_regimes"] = sum(old_rows[r["point"]]["regime"] == r["regime"] for r in rows)
    both = [r for r in rows if r["point"] in stored]
    out["stored_map"] = {"points_in_common": len(both),
                         "same_regime": sum(stored[r["point"]] == r["regime"] for r in both),
                         "changed": _changes(both, stored)}
    out["old_code_projected_s"] = OLD_MAP_SECONDS * out["batch"]["points"] / OLD_MAP_POINTS
    return out


def _changes(rows: list[dict], stored: dict) -> dict:
    changes = {}
    for r in rows:
        if stored[r["point"]] != r["regime"]:
            key = f"{stored[r['point']]} -> {r['regime']}"
            changes[key] = changes.get(key, 0) + 1
    return changes


# -- report ----------------------------------------------------------------------------------------------------


def _table(header: list[str], rows: list[list]) -> list[str]:
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
            *("| " + " | ".join(str(c) for c in row) + " |" for row in rows), ""]


def to_markdown(results: dict) -> str:
    m = results["machine"]
    out = ["# Sweeps: the regime map per trajectory and end to end", "",
           f"{m['cpu']}, {m['cores']} cores; Python {m['python']}, numpy {m['numpy']}, numba {m['numba']}"
           + (f", CyRK {results['trajectories']['cyrk']}" if results["trajectories"]["cyrk"] else "")
           + f". {results['date']}; the run took {results['seconds']:.0f} s.", ""]
    a = results["trajectories"]
    out += ["## (a) One trajectory of the regime map", "",
            f"{a['sample']} points drawn from the 10,000 of `regime_map.toml` (seed {a['seed']}; "
            + ", ".join(f"{n} {r}" for r, n in a["regimes"].items())
            + f"). Thread CPU time per trajectory, the median of {a['repeats']} interleaved repeats per point; "
            "`per point` and `batch` include building the scene "
            f"(median {a['scene_building_ms']:.2f} ms) and classifying, CyRK the integration only; the batch's "
            f"integration alone (its compiled loop called for the one point) takes a median "
            f"{a['integration_ms']:.2f} ms. "
            "The batch's rows equal the per-point rows at every point (regime, steps, numbers).", ""]
    regimes = list(a["regimes"])
    rows = []
    for path in a["paths"]:
        s, r = a["summary"][path], a["ratios"][path]
        rows.append([path, f"{s['median_ms']:.2f}", f"{s['mean_ms']:.2f}", f"{s['p90_ms']:.2f}",
                     *(f"{s['median_ms_by_regime'][g]:.2f}" for g in regimes),
                     f"{r['of_medians']:.2f}", f"{r['median_of_ratios']:.2f}", f"{r['of_means']:.2f}"])
    out += _table(["path", "median ms", "mean ms", "90% ms", *(f"median ms, {g}" for g in regimes),
                   "median / batch's", "median of ratios to batch", "mean / batch's"], rows)
    whole = a["summary"]["batch, whole sample in one call"]
    out += [f"The whole sample in one call of the batch, as a sweep's task runs its points: {whole['mean_ms']:.2f} ms "
            f"of thread CPU time per trajectory (mean). Each point's own clock inside that call (its scene, "
            f"integration and classification, the `wall_time_s` of sweep.csv): median {whole['point_median_ms']:.2f} "
            f"ms, mean {whole['point_mean_ms']:.2f} ms; the clocks add up to {whole['clocks_over_cpu']:.2f} of the "
            "call's CPU time. A point run alone, as in the table, pays for caches that the points before it leave "
            "warm in a batch. Median steps: "
            + ", ".join(f"{k} {v:g}" for k, v in a["median_steps"].items())
            + ("; CyRK's regimes agree with the engine's at "
               + ", ".join(f"{v:.1%} ({k})" for k, v in a["cyrk_regime_agreement"].items()) + " of the points"
               if a["cyrk_regime_agreement"] else "") + ".", "",
            f"Goal: at most {GOALS['trajectory_cpu_ms']:g} ms CPU per trajectory (median). A point run alone: "
            + ("met" if a["summary"]["batch"]["median_ms"] <= GOALS["trajectory_cpu_ms"] else "not met")
            + f" ({a['summary']['batch']['median_ms']:.2f} ms). A point inside the batch's call, by its own clock: "
            + ("met" if whole["point_median_ms"] <= GOALS["trajectory_cpu_ms"] else "not met")
            + f" ({whole['point_median_ms']:.2f} ms). The old scipy-based path took 56 ms.", "",
            ("This machine's speed moves from minute to minute: a fixed pure-Python loop "
             "(`benchmarks.harness.speed_gauge_ms`), timed before each repeat and before and after each call of the "
             f"whole sample, took {min(a['speed_gauge_ms']):.0f}-{max(a['speed_gauge_ms']):.0f} ms during (a)."), ""]
    b = results["map"]
    out += [f"## (b) A map of {b['batch']['points']:,} points on {WORKERS} workers, end to end", "",
            f"{b['sweep']}: `run_sweep` on a local cluster of {WORKERS} single-threaded worker processes. Wall "
            "time from the start of the cluster to the last row written; compute time from the first batch "
            "submitted. Idle: the share of the workers' time not spent on points (dask, the tail, start-up).", ""]
    rows = []
    for runner in ("batch", "per point"):
        if runner in b:
            r = b[runner]
            rows.append([runner, f"{r['wall_s']:.1f}", f"{r['compute_s']:.1f}", f"{r['points_per_second']:.0f}",
                         f"{r['idle_fraction']:.1%}", ", ".join(f"{n} {g}" for g, n in sorted(r["regimes"].items()))])
    rows.append(["old scipy-based code (stored map)", f"{b['old_code_projected_s']:.0f} (projected)", "",
                 f"{OLD_MAP_POINTS / OLD_MAP_SECONDS:.1f}", "", ""])
    out += _table(["runner", "wall s", "compute s", "points / s", "idle", "regimes"], rows)
    st = b["stored_map"]
    out += [f"Against the stored map of the old code: {st['same_regime']} of the {st['points_in_common']} points "
            "in common have the same regime"
            + (" (" + ", ".join(f"{n} {k}" for k, n in st["changed"].items()) + ")" if st["changed"] else "")
            + "." + (f" The per-point runner gives the same regime at {b['per point']['same_regimes']} points."
                     if "per point" in b else ""), ""]
    wall = b["batch"]["wall_s"]
    projected = wall * 10_000 / b["batch"]["points"]
    out += [f"Goal: the 10,000-point map in at most {GOALS['map_10000_wall_s']:g} s wall on {WORKERS} cores: "
            + (f"{wall:.1f} s, " + ("met" if wall <= GOALS["map_10000_wall_s"] else "not met")
               if b["batch"]["points"] == 10_000 else
               f"{projected:.0f} s projected from {b['batch']['points']:,} points (run `--points 10000`)")
            + f"; the old code took {OLD_MAP_SECONDS:.0f} s. On {WORKERS} otherwise idle cores the batch's mean CPU "
            f"time per trajectory in (a) would make it {a['summary']['batch']['mean_ms'] * 10 / WORKERS:.0f} s of "
            f"integration (10,000 x the mean / {WORKERS} workers), plus the idle share above.", ""]
    return "\n".join(out)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--points", type=int, choices=sorted(GRIDS), default=1_000,
                        help="points of the map end to end (default 1000)")
    parser.add_argument("--output", type=Path, help="keep the map's files here (e.g. docs/sweeps/regime_map)")
    parser.add_argument("--replace", action="store_true", help="remove a map already in --output first")
    parser.add_argument("--per-point", action=argparse.BooleanOptionalAction, default=None,
                        help="also run the map through the per-point path (default: up to 10,000 points)")
    parser.add_argument("--sample", type=int, default=SAMPLE, help=f"points of (a) (default {SAMPLE})")
    args = parser.parse_args(argv)
    started = time.perf_counter()
    results = {"machine": machine(), "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
               "goals": GOALS}
    results["trajectories"] = run_trajectories(args.sample)
    results["map"] = run_map(args.points, args.output, args.replace, args.per_point)
    results["seconds"] = time.perf_counter() - started
    name = "sweeps" if args.points == 10_000 else f"sweeps_{args.points // 1000}k"
    publish(name, results, to_markdown(results))


if __name__ == "__main__":
    main()
