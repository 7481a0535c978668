"""What every benchmark shares: the machine it ran on, how it times, where it writes.

A benchmark measures on a machine that other jobs share, so every timing here
is built the same way:

* a warm-up call first, so that numba's compilation and cold caches are never
  timed;
* repeats, reported as their median, with the fastest and the slowest beside it
  (the spread says how much the machine's load moved them);
* repeats of several configurations interleaved: each round visits every
  configuration once, in an order shuffled by a seeded generator, so that a slow
  minute of the machine falls on all of them alike (:func:`interleave`,
  :func:`time_all`);
* thread CPU time next to wall time where a call is timed in batches
  (:class:`Timer`): the other jobs inflate wall time, not CPU time.

:func:`machine` describes the machine for the results, :func:`speed_gauge_ms`
says how fast it ran at a given moment, and :func:`publish` writes a
benchmark's numbers (``results/<name>.json``) and tables (``results/<name>.md``),
each replaced whole.

Example, two functions timed against each other::

    timers = [Timer("sum", lambda calls: [timed_loop(sum, calls)]), ...]
    times = time_all(timers, rounds=15, batch_seconds=2e-3, rng=np.random.default_rng(0))
    times["sum"]["total"]  # median seconds per call
"""

from __future__ import annotations

import json
import os
import platform
import time
from collections.abc import Callable, Hashable, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import numba
import numpy as np
import scipy

from numerics.files import write_text

__all__ = ["RESULTS", "Repeats", "Timer", "interleave", "machine", "publish", "repeat", "speed_gauge_ms",
           "spread", "time_all"]

#: Where :func:`publish` writes.
RESULTS = Path(__file__).resolve().parent / "results"


def machine() -> dict:
    """The CPU model, the core count, the platform and the versions of Python, numpy, scipy and numba."""
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "platform": platform.platform(),
            "python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
            "numba": numba.__version__}


def speed_gauge_ms(loops: int = 1_000_000) -> float:
    """Thread CPU time (ms) of a fixed pure-Python loop: how fast this machine runs at the moment.

    The same code on the same machine drifts from minute to minute; a benchmark
    that times this loop beside its own measurements says in which phase they
    were taken.
    """
    start = time.thread_time()
    total = 0
    for i in range(loops):
        total += i * i
    return 1e3 * (time.thread_time() - start)


def spread(values: Sequence[float]) -> dict:
    """``{"median", "min", "max"}`` of ``values``, as plain floats."""
    return {"median": float(np.median(values)), "min": float(min(values)), "max": float(max(values))}


class Repeats(NamedTuple):
    """Wall seconds of the repeats of one call, and what its last repeat returned."""

    seconds: list[float]
    result: Any

    @property
    def median(self) -> float:
        return float(np.median(self.seconds))

    @property
    def fastest(self) -> float:
        return float(min(self.seconds))

    @property
    def slowest(self) -> float:
        return float(max(self.seconds))


def repeat(call: Callable[[], Any], repeats: int, warm_up: Callable[[], Any] | None = None) -> Repeats:
    """Time ``call()`` ``repeats`` times (wall seconds) after one untimed warm-up call.

    ``warm_up`` replaces the warm-up call where a cheaper one compiles the same
    code (a loop run for a few calls).
    """
    (warm_up or call)()
    seconds, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = call()
        seconds.append(time.perf_counter() - start)
    return Repeats(seconds, result)


def interleave(configs: Sequence[Hashable], rounds: int, rng: np.random.Generator,
               call: Callable[[Hashable], Any]) -> dict[Hashable, list]:
    """``call(config)`` for every configuration once per round, in an order shuffled each round.

    Returns each configuration's results, in the order its rounds ran. The
    shuffles come from ``rng`` (one permutation per round), so that a seeded
    generator repeats the same order. Warm-up calls are the caller's.
    """
    out: dict[Hashable, list] = {c: [] for c in configs}
    for _ in range(rounds):
        for i in rng.permutation(len(configs)):
            out[configs[i]].append(call(configs[i]))
    return out


class Timer:
    """A method to time: ``batch(calls)`` returns the wall seconds of each stage for ``calls`` calls.

    A sample runs one batch of :attr:`calls` calls, enough to last at least the
    ``batch_seconds`` given to :meth:`calibrate`; each sample also records the
    thread's CPU time for the batch, which the other jobs on a shared machine do
    not inflate (they do inflate wall time).
    """

    def __init__(self, key, batch: Callable[[int], Sequence[float]], stages: Sequence[str] = ("total",)):
        self.key, self.batch, self.stages = key, batch, stages
        self.calls = 1
        self.wall, self.cpu = [], []

    def calibrate(self, batch_seconds: float) -> None:
        """One warm-up call (caches, and for jitted code compilation), then the calls a sample needs."""
        self.batch(1)
        calls = 1
        while True:
            elapsed = float(np.sum(self.batch(calls)))
            if elapsed >= batch_seconds or calls >= 1 << 24:
                break
            calls *= max(2, min(16, int(batch_seconds / max(elapsed, 1e-9))))
        self.calls = calls

    def sample(self) -> None:
        start = time.thread_time()
        self.wall.append(np.asarray(self.batch(self.calls)) / self.calls)
        self.cpu.append((time.thread_time() - start) / self.calls)

    def summary(self) -> dict:
        """Per call: the median of each stage and of the total, the fastest and slowest total, the median CPU."""
        stages = np.median(np.array(self.wall), axis=0)
        totals = [float(np.sum(s)) for s in self.wall]
        return {**dict(zip(self.stages, map(float, stages))), "total": float(np.median(totals)),
                "fastest": min(totals), "slowest": max(totals), "cpu": float(np.median(self.cpu)),
                "calls_per_sample": self.calls}


def time_all(timers: Sequence[Timer], rounds: int, batch_seconds: float, rng: np.random.Generator) -> dict:
    """Calibrate every timer, then sample them round-robin in shuffled order; ``{key: summary}``."""
    for timer in timers:
        timer.calibrate(batch_seconds)
    interleave(range(len(timers)), rounds, rng, lambda i: timers[i].sample())
    return {timer.key: timer.summary() for timer in timers}


def publish(name: str, results: dict, markdown: str, folder: Path = RESULTS) -> None:
    """Write ``<folder>/<name>.json`` and ``<folder>/<name>.md``, each replaced whole, and print the markdown."""
    write_text(Path(folder) / f"{name}.json", json.dumps(results, indent=1) + "\n")
    write_text(Path(folder) / f"{name}.md", markdown + "\n")
    print(markdown)
