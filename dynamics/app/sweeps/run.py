"""Running a sweep: its points in batches on dask.distributed, each row appended to ``sweep.csv`` as it arrives.

:func:`run_sweep` sends the points in batches to a dask.distributed cluster (a
:class:`~distributed.LocalCluster` of single-threaded worker processes, or the
scheduler at a given address). Each batch is one task,
:func:`dynamics.app.sweeps.batch.run_batch`, which integrates the points of the
reduced equations together in one compiled call and every other point alone.
Each finished point is appended to ``sweep.csv`` as its batch arrives, flushed
to disk (:class:`dynamics.app.sweeps.store.Table`): a crash loses at most the
batches in flight. Each row is keyed by
:func:`~dynamics.app.sweeps.spec.point_key`, so a sweep started again in the
same folder runs only the points it lacks. ``sweep.json`` holds the fingerprint
of the base scene and axes (a folder is resumed only by the same sweep) and, at
the end, the counts and the wall time.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import sys
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

from dynamics.app.sweeps.batch import problem, run_batch
from dynamics.app.sweeps.compiled import warm
from dynamics.app.sweeps.spec import Sweep, SweepError, point_key
from dynamics.app.sweeps.store import (
    CSV_NAME,
    ENSEMBLE_NAME,
    MANIFEST_NAME,
    REALISATION,
    Table,
    check_manifest,
    read_rows,
    write_ensemble,
)
from dynamics.scenes import parse_scene
from numerics.files import write_json
from numerics.folder import held_signals

__all__ = ["BATCHES_PER_WORKER", "MAX_BATCH", "SweepResult", "max_workers", "run_sweep"]

logger = logging.getLogger(__name__)

# Points per dask task: large enough that the scheduler's few milliseconds per task
# vanish against a batch (a reduced run takes 1-200 ms), small enough that a batch
# in flight costs little when a sweep is stopped, and that workers share the tail.
MAX_BATCH = 200
BATCHES_PER_WORKER = 8


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


def _warm_batch(sweep: Sweep, point: dict) -> str | None:
    """Compile (or load) the batch's loop, if the sweep's points take it, on the worker this runs on, once,
    before the others load it from numba's cache; why it could not, or None.

    On a worker, not here: a compile cannot be stopped inside LLVM, and stopped between its passes it
    leaves numba's state broken; a worker is closed with its cluster on Ctrl-C.
    """
    try:
        batched = problem(parse_scene(sweep.base, sweep.source, point)) is not None
    except Exception:  # noqa: BLE001 - the point fails in its batch, with its reason
        return None
    if batched:
        try:
            warm()
        except Exception as err:  # noqa: BLE001 - the points still run, each alone
            return f"{type(err).__name__}: {err}"
    return None


def max_workers() -> int:
    """Most worker processes of a local cluster: one per core (more only share the cores)."""
    return max(os.cpu_count() or 1, 1)


def _output_folder(outdir) -> Path:
    """``outdir`` as a folder that exists or can be made, else SweepError (before any work)."""
    outdir = Path(outdir)
    if str(outdir) == "":
        raise SweepError("the output folder must be a path, got an empty string")
    if outdir.exists() and not outdir.is_dir():
        msg = f"the output folder {outdir} is a file, not a folder; choose another with -o DIR"
        raise SweepError(msg)
    parent = next((p for p in (outdir, *outdir.parents) if p.exists()), Path("."))
    if not parent.is_dir() or not os.access(parent, os.W_OK | os.X_OK):
        msg = f"cannot write the output folder {outdir}: {parent} is not a writable folder"
        raise SweepError(msg)
    return outdir


def _client(scheduler: str | None, workers: int):
    """A dask client of the scheduler at ``scheduler``, or of a new local cluster, and that cluster.

    A scheduler that cannot be reached within 10 s (a malformed address, none listening) is a SweepError.
    """
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            return Client(scheduler, timeout=10), None
        except (OSError, ValueError, TypeError) as err:
            msg = f"--scheduler {scheduler!r}: cannot reach a dask scheduler there ({type(err).__name__}: {err})"
            raise SweepError(msg) from err
    # dashboard on any free port: 8787 may belong to another cluster on this machine; the workers' own
    # logs stay quiet (a point's failure is a row, a lost worker an exception here), so that a worker busy
    # compiling when Ctrl-C closes the scheduler prints no traceback of its missed heartbeat
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.CRITICAL)
    return Client(cluster), cluster


def _progress_bar(total: int, initial: int, progress: bool | None):
    """A bar of points refreshed at most once a second (tqdm's, a widget in a notebook): with ``progress``
    True, or None on a terminal; no bar when False or piped."""
    if not (progress if progress is not None else sys.stderr.isatty()):
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, initial=initial, desc="snail sweep", unit="pt", mininterval=1.0)


def run_sweep(sweep: Sweep, outdir: str | os.PathLike, *, scheduler: str | None = None, workers: int = 2,
              batch_size: int | None = None, max_points: int | None = None,
              progress: bool | None = None, say=None) -> SweepResult:
    """Run the points of ``sweep`` that ``outdir/sweep.csv`` lacks, appending a row as each arrives.

    Parameters
    ----------
    sweep : Sweep
    outdir : path-like
        Gets ``sweep.csv`` (columns: the axis keys, ``point``, then
        :data:`~dynamics.app.sweeps.store.NUMBERS`) and ``sweep.json``. A folder
        holding part of the same sweep is completed.
    scheduler : str, optional
        Address of a running dask scheduler (``tcp://host:8786``); by default a
        local cluster of ``workers`` single-threaded processes is started and closed.
    workers : int
        Worker processes of the local cluster, >= 1 (ignored with ``scheduler``).
    batch_size : int, optional
        Points per dask task; by default about 8 tasks per worker, at most :data:`MAX_BATCH` points.
    max_points : int, optional
        Stop after this many new points (whole batches are finished), to run a sweep in parts.
    progress : bool, optional
        A bar of the points done: True (a widget in a notebook), False, or by default on a terminal only.
        The stages before the first point (starting the cluster, compiling) are said on the bar.
    say : callable, optional
        ``say(text)`` is called with each stage as it begins (the command line writes them to standard error).

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
    if isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= max_workers():
        msg = f"workers must be an integer in [1, {max_workers()}] (this machine's cores), got {workers!r}"
        raise SweepError(msg)
    outdir = _output_folder(outdir)
    csv_path, manifest_path = outdir / CSV_NAME, outdir / MANIFEST_NAME
    manifest = check_manifest(manifest_path, sweep)
    points = sweep.points()
    done = {row["point"] for row in read_rows(csv_path)}
    missing = [p for p in points if point_key(p) not in done]
    todo = missing if max_points is None else missing[:max_points]
    logger.info("%s: %d points, %d already in %s, %d to run", sweep.source, len(points),
                len(points) - len(missing), csv_path, len(todo))
    computed, compute_time, n_workers = 0, 0.0, 0
    with contextlib.ExitStack() as stack:
        bar = _progress_bar(len(points), len(points) - len(missing), progress) if todo else None
        if bar is not None:
            stack.callback(bar.close)

        def stage(text: str) -> None:
            if bar is not None:
                bar.set_description(f"snail sweep: {text}")
            if say is not None:
                say(text)

        if todo:  # the cluster before any file: a scheduler that cannot be reached leaves the folder untouched
            stage(f"connecting to {scheduler}" if scheduler else f"starting {workers} workers")
            with held_signals():  # Ctrl-C once the cluster is up, to close it: half started, dask cannot
                client, cluster = _client(scheduler, workers)
            if cluster is not None:
                stack.callback(cluster.close)
            stack.callback(client.close)  # the client first, then its cluster (callbacks run last in, first out)
        outdir.mkdir(parents=True, exist_ok=True)
        manifest.update(source=sweep.source, fingerprint=sweep.fingerprint(), points=len(points),
                        axes={a.key: ("random" if a.random else "grid", len(a.values)) for a in sweep.axes},
                        seed=sweep.seed)
        write_json(manifest_path, manifest)
        table = stack.enter_context(Table(csv_path, sweep.keys))
        if todo:
            stage("loading the batch runner (compiled on the first run after an install or an edit: a minute "
                  "or two)")
            why = client.submit(_warm_batch, sweep, todo[0], pure=False).result()
            if why is not None:
                logger.warning("the batch runner could not be compiled (%s): every point runs alone", why)
            n_workers = len(client.scheduler_info()["workers"]) or workers
            stage(f"{len(todo)} points on {n_workers} workers")
            compute_start = time.perf_counter()
            futures = [client.submit(run_batch, sweep.base, sweep.source, batch, pure=False)
                       for batch in _batches(todo, n_workers, batch_size)]
            for future in as_completed(futures):
                rows = future.result()
                future.release()
                table.append(rows)
                computed += len(rows)
                if bar is not None:
                    bar.update(len(rows))
            compute_time = time.perf_counter() - compute_start
    rows = read_rows(csv_path)
    if REALISATION in sweep.keys:
        write_ensemble(outdir / ENSEMBLE_NAME, rows, sweep.keys)
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
