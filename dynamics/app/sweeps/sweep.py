"""Parameter sweeps: many scenes that differ in a few keys, run on dask, one table row each.

A sweep file is TOML. It names a base scene and the axes along which it varies:

.. code-block:: toml

    base = "scene.toml"          # relative to this file; or an inline [base] table of scene sections
    seed = 1                     # seed of the random axes (default 0)

    [axes]
    "groups.s" = [0.1, 0.5, 0.9]                                  # a list of values
    "initial.kappa" = {start = 0.1, stop = 0.9, num = 5}          # evenly spaced, both ends included
    "groups.upsilon" = {start = 0.1, stop = 10, num = 3, spacing = "log"}
    "initial.phi" = {random = "uniform", low = 0, high = 6.28, num = 100}

An axis key is a dotted scene key, ``section.key``, applied to the base scene as
an override (:func:`dynamics.scenes.load.parse_scene`). The grid axes (lists and
``start/stop/num``) are crossed: the sweep is their Cartesian product. The
random axes are drawn together, ``num`` joint samples from one generator seeded
by ``seed`` (so they must agree on ``num``), and these samples are crossed with
the grid. ``random`` is ``"uniform"`` or ``"log-uniform"``.

The file is validated before anything runs: unknown keys, malformed axes and
axis values that the base scene refuses are :class:`SweepError`, whose message
names the key. A combination of values that only fails together is a failed
point, recorded with its reason.

Running, stopping, resuming
---------------------------
:func:`run_sweep` sends the points in batches to a dask.distributed cluster (a
:class:`~distributed.LocalCluster` of single-threaded worker processes, or the
scheduler at a given address) and appends each finished point to ``sweep.csv``
as its batch arrives, flushed to disk: a crash loses at most the batches in
flight. Each row is keyed by :func:`point_key`, a hash of the point's overrides,
so a sweep started again in the same folder runs only the points it lacks.
``sweep.json`` holds the fingerprint of the base scene and axes (a folder is
resumed only by the same sweep) and, at the end, the counts and the wall time.

Regimes
-------
:func:`classify_point` extends :func:`dynamics.app.regime.classify` (runaway,
rocking, sedimenting, locked and sliding rolling in contact, transient) by
"failed": the run raised or failed, and the row says why. The row carries the
numbers that decided the regime.
"""

from __future__ import annotations

import csv
import hashlib
import itertools
import json
import logging
import math
import os
import sys
import time
import tomllib
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from dynamics.app.regime import REGIMES as _CLASSIFIED
from dynamics.app.regime import classify
from dynamics.scenes import SceneError, parse_scene
from lubrication.files import write_json

__all__ = [
    "CSV_NAME",
    "NUMBERS",
    "REGIMES",
    "Axis",
    "Sweep",
    "SweepError",
    "SweepResult",
    "classify_point",
    "load_sweep",
    "overrides",
    "parse_sweep",
    "plot_regime_map",
    "point_key",
    "read_rows",
    "run_point",
    "run_sweep",
    "slope_limits",
]

logger = logging.getLogger(__name__)

CSV_NAME = "sweep.csv"
MANIFEST_NAME = "sweep.json"
REGIMES = (*_CLASSIFIED, "failed")

# What each row records after the axis values and the point key, in this order.
NUMBERS = (
    "status",  # how the run ended: completed, stopped (an event), failed or interrupted
    "regime",  # one of REGIMES
    "t_end_tau",  # time reached, in tau
    "final_kappa",  # kappa at the end: near 1 when the inner cylinder has sunk to the wall
    "turns_of_phi_late",  # turns of the line of centres over the second half: >= 1 winds round
    "phi_reversals_late",  # swings of phi over the second half: >= 2 rocks
    "omega_b_tau_growth_late",  # change of Omega_b tau over the second half: > 0 accelerates
    "omega_b_tau_final",  # Omega_b tau at the end
    "omega_b_change_late",  # (max - min of Omega_b over the second half) / |Omega_b| at the end: <1% rolls steadily
    "phi_range_late",  # max - min of phi over the second half (rad): ~0 steady
    "stop_event",  # the event that stopped the run: runaway, gap_floor, reynolds, or empty
    "steps",  # accepted integrator steps
    "wall_time_s",  # time spent on this point, building the scene included
    "reason",  # why the point failed; empty otherwise
)

# The evidence of dynamics.app.regime.classify that every row carries.
_EVIDENCE = ("final_kappa", "turns_of_phi_late", "phi_reversals_late", "omega_b_tau_growth_late", "stop_event")

# Points per dask task: large enough that the scheduler's few milliseconds per task
# vanish against a batch (a reduced run takes 1-200 ms), small enough that a batch
# in flight costs little when a sweep is stopped, and that workers share the tail.
MAX_BATCH = 200
BATCHES_PER_WORKER = 8

_TOP_KEYS = ("base", "seed", "axes")
_GRID_KEYS = ("start", "stop", "num", "spacing")
_RANDOM_KEYS = ("random", "low", "high", "num")
_SPACINGS = ("linear", "log")
_DISTRIBUTIONS = ("uniform", "log-uniform")


class SweepError(ValueError):
    """A sweep that cannot run; the message names the key of the sweep file."""


# -- the sweep file ---------------------------------------------------------------

@dataclass(frozen=True)
class Axis:
    """One axis: a scene key and its values (a grid axis), or its samples (a random axis)."""

    key: str  # dotted scene key, "section.key"
    values: tuple  # numbers or strings, as TOML gives them
    random: bool = False  # True: drawn jointly with the other random axes, not crossed with them
    log: bool = False  # spaced or drawn evenly in the logarithm: plot it on a log scale


@dataclass(frozen=True)
class Sweep:
    """A validated sweep: the base scene as a mapping of sections, and the axes.

    Build it with :func:`load_sweep` or :func:`parse_sweep`.
    """

    base: dict  # {section: {key: value}}, the base scene before overrides
    axes: tuple[Axis, ...]
    source: str = "<string>"
    seed: int = 0

    @property
    def keys(self) -> tuple[str, ...]:
        """The axis keys, the first columns of ``sweep.csv``."""
        return tuple(axis.key for axis in self.axes)

    def points(self) -> list[dict[str, Any]]:
        """Every point as ``{axis key: value}``: the grid's product, crossed with the random samples."""
        grid = [a for a in self.axes if not a.random]
        random = [a for a in self.axes if a.random]
        samples = list(zip(*(a.values for a in random))) if random else [()]
        out = []
        for values in itertools.product(*(a.values for a in grid)):
            for sample in samples:
                point = dict(zip((a.key for a in grid), values))
                point.update(zip((a.key for a in random), sample))
                out.append({key: point[key] for key in self.keys})
        return out

    def fingerprint(self) -> str:
        """A hash of the base scene and the axes: a results folder belongs to one sweep."""
        text = json.dumps({"base": self.base, "axes": [[a.key, list(a.values)] for a in self.axes]},
                          sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _value_text(value: Any) -> str:
    """An override's value as TOML: repr keeps every bit of a float, json quotes a string."""
    if isinstance(value, float):
        return repr(value)
    return json.dumps(value)


def overrides(point: Mapping[str, Any]) -> list[str]:
    """The point as ``section.key=value`` overrides of the base scene."""
    return [f"{key}={_value_text(value)}" for key, value in point.items()]


def point_key(point: Mapping[str, Any]) -> str:
    """A stable name of the point: the first 16 hex digits of the SHA-256 of its overrides."""
    return hashlib.sha256("\n".join(overrides(point)).encode()).hexdigest()[:16]


def _grid_axis(key: str, spec: Mapping[str, Any]) -> Axis:
    unknown = [k for k in spec if k not in _GRID_KEYS]
    if unknown:
        msg = f"axes.{key}: unknown key {unknown[0]!r}; a grid axis has {', '.join(_GRID_KEYS)}"
        raise SweepError(msg)
    missing = [k for k in ("start", "stop", "num") if k not in spec]
    if missing:
        msg = f"axes.{key}: {', '.join(missing)} missing; a grid axis is {{start = ..., stop = ..., num = ...}}"
        raise SweepError(msg)
    start, stop = (_number(key, name, spec[name]) for name in ("start", "stop"))
    num = _count(key, spec["num"])
    spacing = spec.get("spacing", "linear")
    if spacing not in _SPACINGS:
        msg = f"axes.{key}.spacing must be one of {', '.join(map(repr, _SPACINGS))}, got {spacing!r}"
        raise SweepError(msg)
    if spacing == "log":
        if not (start > 0 and stop > 0):
            msg = f"axes.{key}: spacing = 'log' needs start > 0 and stop > 0, got {start:g} and {stop:g}"
            raise SweepError(msg)
        return Axis(key, _rounded(np.geomspace(start, stop, num)), log=True)
    return Axis(key, _rounded(np.linspace(start, stop, num)))


def _rounded(values: np.ndarray) -> tuple[float, ...]:
    """Grid values to 12 digits: 0.75 rather than 0.7499999999999999, in overrides and the table."""
    return tuple(float(f"{v:.12g}") for v in values)


def _random_axis(key: str, spec: Mapping[str, Any], rng: np.random.Generator) -> Axis:
    unknown = [k for k in spec if k not in _RANDOM_KEYS]
    missing = [k for k in _RANDOM_KEYS if k not in spec]
    if unknown or missing:
        what = f"unknown key {unknown[0]!r}" if unknown else f"{', '.join(missing)} missing"
        msg = (f"axes.{key}: {what}; a random axis is {{random = 'uniform', low = ..., high = ..., "
               f"num = ...}}")
        raise SweepError(msg)
    if spec["random"] not in _DISTRIBUTIONS:
        msg = f"axes.{key}.random must be one of {', '.join(map(repr, _DISTRIBUTIONS))}, got {spec['random']!r}"
        raise SweepError(msg)
    low, high = (_number(key, name, spec[name]) for name in ("low", "high"))
    num = _count(key, spec["num"])
    if not low < high:
        msg = f"axes.{key}: low must be below high, got low = {low:g}, high = {high:g}"
        raise SweepError(msg)
    if spec["random"] == "log-uniform":
        if not low > 0:
            msg = f"axes.{key}: random = 'log-uniform' needs low > 0, got {low:g}"
            raise SweepError(msg)
        samples = np.exp(rng.uniform(math.log(low), math.log(high), num))
        return Axis(key, tuple(float(v) for v in samples), random=True, log=True)
    return Axis(key, tuple(float(v) for v in rng.uniform(low, high, num)), random=True)


def _number(key: str, name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        msg = f"axes.{key}.{name} must be a finite number, got {value!r}"
        raise SweepError(msg)
    return float(value)


def _count(key: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        msg = f"axes.{key}.num must be an integer >= 1, got {value!r}"
        raise SweepError(msg)
    return value


def _axis(key: str, spec: Any, rng: np.random.Generator) -> Axis:
    if isinstance(spec, list):
        if not spec:
            raise SweepError(f"axes.{key} is an empty list; give at least one value")
        bad = [v for v in spec if isinstance(v, (list, dict))]
        if bad:
            msg = f"axes.{key}: values must be numbers or strings, got {bad[0]!r}"
            raise SweepError(msg)
        return Axis(key, tuple(spec))
    if isinstance(spec, Mapping):
        return _random_axis(key, spec, rng) if "random" in spec else _grid_axis(key, spec)
    msg = (f"axes.{key} must be a list of values, {{start, stop, num}} or {{random, low, high, num}}, "
           f"got {spec!r}")
    raise SweepError(msg)


def _check_values(base: dict, axis: Axis, source: str) -> None:
    """Each value of ``axis`` must make a valid scene with the base; random axes are checked at their extremes."""
    values = (min(axis.values), max(axis.values)) if axis.random else axis.values
    for value in dict.fromkeys(values):
        try:
            parse_scene(base, source, overrides({axis.key: value}))
        except SceneError as err:
            msg = f"axes.{axis.key} = {value!r}: {err}"
            raise SweepError(msg) from err


def _base(raw: Mapping[str, Any], base_dir: Path) -> tuple[dict, str]:
    """The base scene as a mapping of sections, and where it came from."""
    if "base" not in raw:
        raise SweepError("base is missing: a sweep names its base scene, base = \"scene.toml\" or a [base] table")
    given = raw["base"]
    if isinstance(given, Mapping):
        return {name: dict(table) if isinstance(table, Mapping) else table for name, table in given.items()}, "[base]"
    if not isinstance(given, str):
        msg = f"base must be a scene file name or a [base] table, got {given!r}"
        raise SweepError(msg)
    path = base_dir / given
    try:
        return tomllib.loads(path.read_text(encoding="utf-8")), os.fspath(path)
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as err:
        msg = f"base = {given!r}: cannot read the scene file {os.fspath(path)!r}: {err}"
        raise SweepError(msg) from err


def parse_sweep(sweep: str | Mapping[str, Any], source: str = "<string>",
                base_dir: str | os.PathLike = ".") -> Sweep:
    """Read and validate a sweep from TOML text or a mapping.

    Parameters
    ----------
    sweep : str or Mapping
        TOML text, or the mapping ``tomllib`` returns for it.
    source : str, optional
        Where the sweep came from, for messages.
    base_dir : path-like, optional
        The folder a ``base = "scene.toml"`` name is relative to.

    Returns
    -------
    Sweep

    Raises
    ------
    SweepError
        For invalid TOML, an unknown key, a malformed axis, or an axis value the
        base scene refuses; the message names the key.
    """
    if isinstance(sweep, str):
        try:
            raw = tomllib.loads(sweep)
        except tomllib.TOMLDecodeError as err:
            msg = f"{source} is not valid TOML: {err}"
            raise SweepError(msg) from err
    else:
        raw = dict(sweep)
    unknown = [k for k in raw if k not in _TOP_KEYS]
    if unknown:
        msg = f"unknown key {unknown[0]!r} in {source}; a sweep file has {', '.join(_TOP_KEYS)}"
        raise SweepError(msg)
    base, base_source = _base(raw, Path(base_dir))
    seed = raw.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        msg = f"seed must be an integer >= 0, got {seed!r}"
        raise SweepError(msg)
    given = raw.get("axes")
    if not isinstance(given, Mapping) or not given:
        msg = f"axes must be a table of at least one axis, e.g. \"groups.s\" = [0.1, 0.5]; got {given!r}"
        raise SweepError(msg)
    try:
        parse_scene(base, base_source)
    except SceneError as err:
        msg = f"base ({base_source}): {err}"
        raise SweepError(msg) from err
    rng = np.random.default_rng(seed)
    axes = tuple(_axis(key, spec, rng) for key, spec in given.items())
    sizes = {a.key: len(a.values) for a in axes if a.random}
    if len(set(sizes.values())) > 1:
        msg = ("random axes are drawn together and need the same num, got "
               + ", ".join(f"axes.{k}.num = {n}" for k, n in sizes.items()))
        raise SweepError(msg)
    for axis in axes:
        _check_values(base, axis, base_source)
    return Sweep(base=base, axes=axes, source=source, seed=seed)


def load_sweep(path: str | os.PathLike) -> Sweep:
    """Load a sweep file; a ``base`` file name is relative to the sweep file's folder.

    Raises
    ------
    SweepError
        If the file cannot be read, or for any error :func:`parse_sweep` reports.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        msg = f"cannot read the sweep file {os.fspath(path)!r}: {err}"
        raise SweepError(msg) from err
    return parse_sweep(text, os.fspath(path), path.parent)


# -- one point ----------------------------------------------------------------------

def classify_point(trajectory) -> tuple[str, dict[str, Any]]:
    """The regime of a trajectory and the numbers that decided it.

    A failed or interrupted run is "failed"; otherwise the regime is that of
    :func:`dynamics.app.regime.classify` (steady rolling in contact is "locked
    rolling" or "sliding rolling" there).

    Returns
    -------
    regime : str
        One of :data:`REGIMES`.
    numbers : dict
        The keys of :data:`NUMBERS` from ``t_end_tau`` to ``stop_event``.
    """
    c = trajectory.columns
    t, phi = c["t_tau"], c["phi"]
    omega_b = c["omega_b"] * trajectory.tau
    regime, evidence = classify(trajectory)
    late = slice(min(int(np.searchsorted(t, 0.5 * t[-1])), len(t) - 1), None)
    final = float(omega_b[-1])
    numbers = {"t_end_tau": float(t[-1]), **{k: evidence[k] for k in _EVIDENCE},
               "omega_b_tau_final": final,
               # the spread, not the end-to-end change: a rocking Omega_b can end where it began
               "omega_b_change_late": float(np.ptp(omega_b[late])) / abs(final) if final else math.inf,
               "phi_range_late": float(np.ptp(phi[late]))}
    return ("failed" if trajectory.status in ("failed", "interrupted") else regime), numbers


def run_point(base: Mapping[str, Any], point: Mapping[str, Any], source: str = "[base]") -> dict[str, Any]:
    """Build, run and classify one point; a failure becomes a "failed" row with its reason.

    Returns
    -------
    dict
        The axis values, ``point`` (:func:`point_key`) and the keys of :data:`NUMBERS`.
    """
    from dynamics.app.run import run_scene

    start = time.perf_counter()
    row = {**point, "point": point_key(point)}
    try:
        trajectory = run_scene(parse_scene(base, source, overrides(point)))
        regime, numbers = classify_point(trajectory)
        row.update(numbers, status=trajectory.status, regime=regime, steps=trajectory.steps,
                   reason=trajectory.message if regime == "failed" else "")
    # A point fails alone: any error is its reason, and the sweep goes on.
    except Exception as err:  # noqa: BLE001
        row.update(status="failed", regime="failed", reason=f"{type(err).__name__}: {err}")
    row["wall_time_s"] = time.perf_counter() - start
    return row


def _run_batch(base: Mapping[str, Any], source: str, points: Sequence[Mapping[str, Any]]) -> list[dict]:
    """The task a dask worker runs: one row per point."""
    return [run_point(base, point, source) for point in points]


# -- the results table -----------------------------------------------------------------

def _format(value: Any) -> Any:
    """Floats to 7 significant digits (the table stays small); axis values are written separately."""
    if isinstance(value, float):
        return f"{value:.7g}"
    return value


def read_rows(path: str | os.PathLike) -> list[dict[str, str]]:
    """The complete rows of a ``sweep.csv`` (a last line cut short by a crash is left out)."""
    path = Path(path)
    if not path.exists():
        return []
    text = path.read_text(encoding="utf-8")
    if not text.endswith("\n"):
        text = text[:text.rfind("\n") + 1]
    return list(csv.DictReader(text.splitlines()))


def _open_table(path: Path, columns: Sequence[str]):
    """Open ``sweep.csv`` for appending, after dropping a line cut short by a crash."""
    if path.exists() and path.stat().st_size:
        data = path.read_bytes()
        header = next(csv.reader([data.split(b"\n", 1)[0].decode()]))
        if header != list(columns):
            msg = (f"{path} has the columns {', '.join(header)}, not those of this sweep "
                   f"({', '.join(columns)}); write to another folder (-o DIR)")
            raise SweepError(msg)
        if not data.endswith(b"\n"):
            with path.open("r+b") as fh:
                fh.truncate(data.rfind(b"\n") + 1)
        return path.open("a", encoding="utf-8", newline="")
    fh = path.open("w", encoding="utf-8", newline="")
    csv.writer(fh, lineterminator="\n").writerow(columns)
    return fh


def _check_manifest(path: Path, sweep: Sweep) -> dict:
    """The manifest of a folder's sweep, refused if the folder holds a different sweep."""
    if not path.exists():
        return {}
    manifest = json.loads(path.read_text(encoding="utf-8"))
    if manifest.get("fingerprint") != sweep.fingerprint():
        msg = (f"{path.parent} holds the results of another sweep ({manifest.get('source')}, fingerprint "
               f"{manifest.get('fingerprint')}); write to another folder (-o DIR)")
        raise SweepError(msg)
    return manifest


# -- the engine ----------------------------------------------------------------------

@dataclass(frozen=True)
class SweepResult:
    """What :func:`run_sweep` did."""

    csv_path: Path
    points: int  # points in the sweep
    already_done: int  # rows found in sweep.csv at the start
    computed: int  # rows added by this call
    wall_time_s: float  # this call, cluster start and shutdown included
    compute_time_s: float  # from the first submission to the last row
    workers: int
    regimes: dict[str, int]  # rows per regime in the whole table

    @property
    def complete(self) -> bool:
        return self.already_done + self.computed == self.points

    @property
    def points_per_second(self) -> float:
        return self.computed / self.compute_time_s if self.compute_time_s > 0 else 0.0


def _batches(todo: list[dict], workers: int, batch_size: int | None) -> list[list[dict]]:
    if batch_size is None:
        batch_size = min(MAX_BATCH, max(1, math.ceil(len(todo) / (BATCHES_PER_WORKER * workers))))
    return [todo[i:i + batch_size] for i in range(0, len(todo), batch_size)]


def _client(scheduler: str | None, workers: int):
    """A dask client of the scheduler at ``scheduler``, or of a new local cluster, and that cluster."""
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        return Client(scheduler), None
    # dashboard on any free port: 8787 may belong to another cluster on this machine
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.WARNING)
    return Client(cluster), cluster


def _progress_bar(total: int, initial: int):
    """A tqdm bar of points on a terminal, refreshed at most once a second; None when piped."""
    if not sys.stderr.isatty():
        return None
    from tqdm import tqdm

    return tqdm(total=total, initial=initial, desc="snail sweep", unit="pt", mininterval=1.0)


def run_sweep(sweep: Sweep, outdir: str | os.PathLike, *, scheduler: str | None = None, workers: int = 2,
              batch_size: int | None = None, max_points: int | None = None) -> SweepResult:
    """Run the points of ``sweep`` that ``outdir/sweep.csv`` lacks, appending a row as each arrives.

    Parameters
    ----------
    sweep : Sweep
    outdir : path-like
        Gets ``sweep.csv`` (columns: the axis keys, ``point``, then :data:`NUMBERS`)
        and ``sweep.json``. A folder holding part of the same sweep is completed.
    scheduler : str, optional
        Address of a running dask scheduler (``tcp://host:8786``); by default a
        local cluster of ``workers`` single-threaded processes is started and closed.
    workers : int
        Worker processes of the local cluster, >= 1 (ignored with ``scheduler``).
    batch_size : int, optional
        Points per dask task; by default about 8 tasks per worker, at most :data:`MAX_BATCH` points.
    max_points : int, optional
        Stop after this many new points (whole batches are finished), to run a sweep in parts.

    Returns
    -------
    SweepResult

    Raises
    ------
    SweepError
        If ``outdir`` holds the results of a different sweep.
    ImportError
        Without dask.distributed, the optional extra ``sweep``.
    """
    try:
        from dask.distributed import as_completed
    except ImportError as err:
        msg = "sweeps run on dask.distributed, an optional extra: pip install 'snail-cylinder[sweep]'"
        raise ImportError(msg) from err

    start = time.perf_counter()
    if workers < 1:
        msg = f"workers must be an integer >= 1, got {workers!r}"
        raise SweepError(msg)
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    csv_path, manifest_path = outdir / CSV_NAME, outdir / MANIFEST_NAME
    manifest = _check_manifest(manifest_path, sweep)
    columns = [*sweep.keys, "point", *NUMBERS]
    points = sweep.points()
    done = {row["point"] for row in read_rows(csv_path)}
    missing = [p for p in points if point_key(p) not in done]
    todo = missing if max_points is None else missing[:max_points]
    logger.info("%s: %d points, %d already in %s, %d to run", sweep.source, len(points),
                len(points) - len(missing), csv_path, len(todo))
    manifest.update(source=sweep.source, fingerprint=sweep.fingerprint(), points=len(points),
                    axes={a.key: ("random" if a.random else "grid", len(a.values)) for a in sweep.axes},
                    seed=sweep.seed)
    write_json(manifest_path, manifest)
    computed, compute_time = 0, 0.0
    with _open_table(csv_path, columns) as table:
        writer = csv.DictWriter(table, columns, lineterminator="\n")
        if todo:
            client, cluster = _client(scheduler, workers)
            n_workers = len(client.scheduler_info()["workers"]) or workers
            bar = _progress_bar(len(points), len(points) - len(missing))
            try:
                compute_start = time.perf_counter()
                futures = [client.submit(_run_batch, sweep.base, sweep.source, batch, pure=False)
                           for batch in _batches(todo, n_workers, batch_size)]
                for future in as_completed(futures):
                    rows = future.result()
                    future.release()
                    writer.writerows({k: _format(v) if k not in sweep.keys else v for k, v in row.items()}
                                     for row in rows)
                    table.flush()
                    os.fsync(table.fileno())
                    computed += len(rows)
                    if bar is not None:
                        bar.update(len(rows))
                compute_time = time.perf_counter() - compute_start
            finally:
                if bar is not None:
                    bar.close()
                client.close()
                if cluster is not None:
                    cluster.close()
        else:
            n_workers = 0
    rows = read_rows(csv_path)
    regimes = dict(Counter(row["regime"] for row in rows))
    result = SweepResult(csv_path=csv_path, points=len(points), already_done=len(points) - len(missing),
                         computed=computed,
                         wall_time_s=time.perf_counter() - start, compute_time_s=compute_time,
                         workers=n_workers, regimes=regimes)
    manifest.update(rows=len(rows), complete=result.complete, regimes=regimes, last_run={
        "computed": computed, "workers": n_workers, "scheduler": scheduler or "local",
        "wall_time_s": result.wall_time_s, "compute_time_s": compute_time,
        "points_per_second": result.points_per_second})
    write_json(manifest_path, manifest)
    return result


# -- reading the map -------------------------------------------------------------------

def slope_limits(rows: Iterable[Mapping[str, str]], slope: str = "groups.s") -> dict[str, float]:
    """Where runaway starts and rocking ends along the slope axis.

    Returns
    -------
    dict
        ``lowest_runaway_s``: the smallest s with a runaway (below it runaway did
        not occur); ``highest_rocking_s``: the largest s that rocked or sedimented
        (above it rocking did not occur); ``nan`` where the regime never occurred.
    """
    runaway, rocking = [], []
    for row in rows:
        if row["regime"] == "runaway":
            runaway.append(float(row[slope]))
        elif row["regime"] in _ROCKING:
            rocking.append(float(row[slope]))
    return {"lowest_runaway_s": min(runaway, default=math.nan),
            "highest_rocking_s": max(rocking, default=math.nan)}


# The inner cylinder sinks to the wall in both; rocking swings on the way.
_ROCKING = ("rocking", "sedimenting")
# Colours of the regimes, and of cells where the regime depends on the axes not shown.
_COLOURS = {"rocking": "#4c72b0", "sedimenting": "#8fb0e0", "runaway": "#dd5a4a", "locked rolling": "#55a868",
            "sliding rolling": "#a0d080", "transient": "#c8c8c8", "failed": "#222222", "mixed": "#f0b050"}
_LABELS = {"mixed": "mixed: depends on the pooled axes"}


def plot_regime_map(rows: str | os.PathLike | Sequence[Mapping[str, str]], x: str, y: str, *,
                    where: Mapping[str, float] | None = None, log_x: bool = False, log_y: bool = False,
                    title: str = ""):
    """A regime map in the plane of axes ``x`` and ``y``, with the edges of rocking and of runaway.

    Parameters
    ----------
    rows : path-like or sequence of mappings
        ``sweep.csv`` or its rows (:func:`read_rows`).
    x, y : str
        Axis keys, e.g. ``"groups.s"`` and ``"initial.kappa"``.
    where : mapping, optional
        Fixed values of other axes; rows are kept whose value is the nearest
        value present. The remaining axes are pooled: a cell whose points do not
        share one regime is "mixed" (the regime depends on the pooled axes); a
        cell that only rocks and sediments counts as rocking.
    log_x, log_y : bool
        Logarithmic axes, e.g. for Upsilon.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Cells coloured by regime. Two black lines run half-way between cells:
        dashed, the edge of the cells where some point ran away; solid, the edge
        of the cells where some point rocked (or sedimented). Without pooled axes
        they coincide on the rocking/runaway boundary; with pooled axes the band
        between them is where the initial state decides.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    if isinstance(rows, (str, os.PathLike)):
        rows = read_rows(rows)
    for key, value in (where or {}).items():
        nearest = min({float(r[key]) for r in rows}, key=lambda v: abs(v - value))
        rows = [r for r in rows if float(r[key]) == nearest]
    xs = np.array(sorted({float(r[x]) for r in rows}))
    ys = np.array(sorted({float(r[y]) for r in rows}))
    cells: dict[tuple[int, int], list[str]] = {}
    for r in rows:
        cell = (int(np.searchsorted(ys, float(r[y]))), int(np.searchsorted(xs, float(r[x]))))
        cells.setdefault(cell, []).append(r["regime"])
    names = list(_COLOURS)
    code = np.full((ys.size, xs.size), np.nan)
    runaway = np.zeros((ys.size, xs.size))
    rocking = np.zeros((ys.size, xs.size))
    for (i, j), regimes in cells.items():
        kinds = set(regimes) - {"sedimenting"} if set(regimes) > {"sedimenting"} else set(regimes)
        code[i, j] = names.index(kinds.pop() if len(kinds) == 1 else "mixed")
        runaway[i, j] = "runaway" in regimes
        rocking[i, j] = any(r in _ROCKING for r in regimes)
    fig, ax = plt.subplots(figsize=(8.5, 5))
    cmap = matplotlib.colors.ListedColormap(list(_COLOURS.values()))
    ax.pcolormesh(_edges(xs, log_x), _edges(ys, log_y), code, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5)
    handles = [Patch(color=_COLOURS[n], label=_LABELS.get(n, n)) for n in names if names.index(n) in code]
    if xs.size > 1 and ys.size > 1:
        for field, style, label in ((rocking, "-", "edge of rocking"), (runaway, "--", "edge of runaway")):
            if 0 < field.mean() < 1:
                ax.contour(xs, ys, field, levels=[0.5], colors="k", linestyles=style, linewidths=1.5)
                handles.append(Line2D([], [], color="k", linestyle=style, label=label))
    if log_x:
        ax.set_xscale("log")
    if log_y:
        ax.set_yscale("log")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fixed = ", ".join(f"{k} = {float(rows[0][k]):.3g}" for k in (where or {}))
    ax.set_title(title or f"regimes, {len(rows)} points" + (f" ({fixed})" if fixed else ""), fontsize=10)
    fig.tight_layout()
    return fig


def _edges(centres: np.ndarray, log: bool = False) -> np.ndarray:
    """Cell edges half-way between grid values (geometrically on a log axis)."""
    if centres.size == 1:
        return np.array([centres[0] * 0.9, centres[0] * 1.1]) if log else centres[0] + np.array([-0.5, 0.5])
    v = np.log(centres) if log else centres
    edges = np.concatenate([[1.5 * v[0] - 0.5 * v[1]], 0.5 * (v[1:] + v[:-1]), [1.5 * v[-1] - 0.5 * v[-2]]])
    return np.exp(edges) if log else edges
