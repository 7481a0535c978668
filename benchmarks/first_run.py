"""What the first `snail run` after installing costs: numba compiling against a warm cache.

Each sample runs ``snail run`` on the embedded default scene (steel, closed-form
forces, full equations, 10 s) in a fresh process. A cold sample points
NUMBA_CACHE_DIR at an empty folder, so every kernel the run needs is compiled,
as on the first run after installing; a warm sample reuses the folder the cold
one filled. Reported: the median wall time of each over interleaved repeats,
and their ratio. Run from the project root with ``python -m benchmarks.first_run``;
writes ``benchmarks/results/first_run.json`` and ``.md``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.publish import publish
from benchmarks.reynolds import _machine

REPEATS = 3


def _snail_run(numba_cache: str, outdir: str) -> float:
    """Wall seconds of one `snail run` of the default scene in a fresh process."""
    env = {**os.environ, "NUMBA_CACHE_DIR": numba_cache}
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", outdir], env=env, check=True,
                   capture_output=True)
    return time.perf_counter() - start


def run(repeats: int = REPEATS) -> dict:
    cold, warm = [], []
    with tempfile.TemporaryDirectory() as scratch:
        for i in range(repeats):
            cache = os.path.join(scratch, f"numba{i}")
            cold.append(_snail_run(cache, os.path.join(scratch, f"cold{i}")))
            warm.append(_snail_run(cache, os.path.join(scratch, f"warm{i}")))
    c, w = float(np.median(cold)), float(np.median(warm))
    return {"machine": _machine(), "repeats": repeats, "cold_s": cold, "warm_s": warm,
            "cold_median_s": c, "warm_median_s": w, "ratio": c / w}


def to_markdown(results: dict) -> str:
    return "\n".join([
        "# The first `snail run` after installing", "",
        f"Default scene, whole command in a fresh process; median of {results['repeats']} interleaved pairs.", "",
        "| numba cache | wall time (s) |", "|---|---|",
        f"| empty (first run) | {results['cold_median_s']:.2f} |",
        f"| filled by the run before | {results['warm_median_s']:.2f} |", "",
        f"First run / later runs: {results['ratio']:.2f}."])


def main() -> None:
    results = run()
    publish("first_run", results, to_markdown(results))


if __name__ == "__main__":
    main()
