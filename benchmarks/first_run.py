"""What the first `snail run` after installing costs, and what the build pays for it.

The build compiles the kernels of a default run into the wheel (``setup.py``,
:mod:`dynamics.app.precompile`). This benchmark builds the wheel once (timed),
installs it into a fresh virtual environment, and then, for each repeat,
reinstalls it (so the package's files are new), times the first ``snail run``
of the embedded default scene in a fresh process and then warm ones (the
kernels loaded from numba's cache), each after timing the imports that any
process running compiled numpy code pays (numba and its array functions, which
import scipy.linalg): the floor under a warm run, which shows how fast the
machine is at that moment (its speed drifts by up to 1.7x from minute to
minute). For comparison it also times a run that compiles everything itself, with
NUMBA_CACHE_DIR pointed at an empty folder (what an editable install, or a
wheel built for another CPU, sees the first time). Reported: medians over the
interleaved repeats. Run from the project root with
``python -m benchmarks.first_run``; writes ``benchmarks/results/first_run.json``
and ``.md``.
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

from benchmarks.harness import machine, publish

REPEATS = 3
#: Warm runs per repeat, each after a timing of :data:`FLOOR`.
WARM_RUNS = 3
#: The imports under any warm run: numba's array functions, which import scipy.linalg.
FLOOR = "import numba.np.arraymath"
ROOT = Path(__file__).resolve().parents[1]


def _timed(command: list[str], **kwargs) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, **kwargs)
    return time.perf_counter() - start


def _snail_run(snail: Path, outdir: Path, env: dict) -> float:
    """Wall seconds of one `snail run` of the default scene in a fresh process."""
    return _timed([str(snail), "run", "-o", str(outdir)], env=env, cwd=outdir.parent)


def run(repeats: int = REPEATS) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    first, second, floor, compiling = [], [], [], []
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        build_s = _timed([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-w", str(scratch)])
        wheel = next(scratch.glob("*.whl"))
        subprocess.run([sys.executable, "-m", "venv", str(scratch / "venv")], check=True)
        python, snail = scratch / "venv" / "bin" / "python", scratch / "venv" / "bin" / "snail"
        subprocess.run([str(python), "-m", "pip", "install", "-q", str(wheel)], check=True, capture_output=True)
        for i in range(repeats):
            subprocess.run([str(python), "-m", "pip", "install", "-q", "--force-reinstall", "--no-deps", str(wheel)],
                           check=True, capture_output=True)
            first.append(_snail_run(snail, scratch / f"first{i}", env))
            for j in range(WARM_RUNS):
                floor.append(_timed([str(python), "-c", FLOOR], env=env))
                second.append(_snail_run(snail, scratch / f"warm{i}_{j}", env))
            compiling.append(_snail_run(snail, scratch / f"compiling{i}",
                                        {**env, "NUMBA_CACHE_DIR": str(scratch / f"numba{i}")}))
    med = {name: float(np.median(v))
           for name, v in (("first", first), ("second", second), ("floor", floor), ("compiling", compiling))}
    return {"machine": machine(), "repeats": repeats, "warm_runs": WARM_RUNS, "floor_command": FLOOR,
            "wheel_build_s": build_s, "first_s": first, "second_s": second, "floor_s": floor,
            "compiling_s": compiling, "first_median_s": med["first"], "second_median_s": med["second"],
            "floor_median_s": med["floor"], "compiling_median_s": med["compiling"],
            "first_over_second": med["first"] / med["second"],
            "second_over_floor": float(np.median(np.array(second) / np.array(floor)))}


def to_markdown(results: dict) -> str:
    return "\n".join([
        "# The first `snail run` after installing", "",
        (f"Default scene, whole command in a fresh process; medians of {results['repeats']} interleaved repeats, "
         f"each after reinstalling the wheel, with {results['warm_runs']} warm runs each."), "",
        "| run | wall time (s) | range (s) |", "|---|---|---|",
        (f"| first after `pip install` (kernels compiled by the build) | {results['first_median_s']:.2f} "
         f"| {min(results['first_s']):.2f}-{max(results['first_s']):.2f} |"),
        (f"| warm (the kernels in numba's cache) | {results['second_median_s']:.2f} "
         f"| {min(results['second_s']):.2f}-{max(results['second_s']):.2f} |"),
        (f"| `python -c \"{results['floor_command']}\"` before each warm run | {results['floor_median_s']:.2f} "
         f"| {min(results['floor_s']):.2f}-{max(results['floor_s']):.2f} |"),
        (f"| compiling every kernel itself (empty NUMBA_CACHE_DIR) | {results['compiling_median_s']:.2f} "
         f"| {min(results['compiling_s']):.2f}-{max(results['compiling_s']):.2f} |"), "",
        (f"First run / warm run: {results['first_over_second']:.2f}; warm run / its floor's imports: "
         f"{results['second_over_floor']:.2f} (median of the pairs). Building the wheel, "
         f"which compiles the kernels, took {results['wheel_build_s']:.0f} s.")])


def main() -> None:
    results = run()
    publish("first_run", results, to_markdown(results))


if __name__ == "__main__":
    main()
