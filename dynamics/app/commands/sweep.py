"""``snail sweep``: a parameter sweep on dask, one row of ``sweep.csv`` per point."""

from __future__ import annotations

import argparse
import sys

from dynamics.app.command import UsageError

__all__ = ["register"]


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        msg = f"must be an integer >= 1, got {text!r}"
        raise argparse.ArgumentTypeError(msg)
    return value


def register(subparsers) -> None:
    """Add the ``sweep`` subcommand to the ``snail`` command's subparsers."""
    p = subparsers.add_parser(
        "sweep", help="run a parameter sweep of a scene on dask",
        description="Run every point of a sweep file (a base scene and [axes] of dotted scene keys) on "
                    "a dask cluster and write DIR/sweep.csv, one row per point: the axis values, status, "
                    "regime and the numbers that decided it; DIR/sweep.json, the counts and the wall "
                    "time; and DIR/regime_map.png in the plane of the first two axes. Rows are saved as "
                    "they arrive: run the same command again to finish a sweep that was stopped.")
    p.add_argument("sweep", help="sweep TOML file")
    p.add_argument("-o", "--output", default="snail-sweep", help="output folder (default snail-sweep)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="address of a running dask scheduler, e.g. tcp://10.0.0.1:8786 "
                        "(default: start a local cluster)")
    p.add_argument("--workers", type=_positive_int, default=2, metavar="N",
                   help="worker processes of the local cluster, one thread each (default 2)")
    p.add_argument("--max-points", type=_positive_int, metavar="N",
                   help="stop after N new points; the next run goes on from there")
    p.set_defaults(run=_run_sweep)


def _run_sweep(args) -> int:
    from dynamics.app.sweeps.plot import save_regime_map
    from dynamics.app.sweeps.run import run_sweep
    from dynamics.app.sweeps.spec import SweepError, load_sweep
    from dynamics.scenes import SceneError

    try:
        sweep = load_sweep(args.sweep)
        result = run_sweep(sweep, args.output, scheduler=args.scheduler, workers=args.workers,
                           max_points=args.max_points,
                           say=None if sys.stderr.isatty() else lambda text: print(f"snail sweep: {text}",
                                                                                   file=sys.stderr, flush=True))
    except (SweepError, SceneError, ImportError) as err:
        raise UsageError(str(err)) from err
    save_regime_map(sweep, result.csv_path)
    regimes = ", ".join(f"{n} {name}" for name, n in sorted(result.regimes.items(), key=lambda kv: -kv[1]))
    print(f"{result.computed} points computed in {result.compute_time_s:.1f} s "
          f"({result.points_per_second:.1f} points/s on {result.workers} workers), "
          f"{result.already_done} already done; {result.already_done + result.computed} of "
          f"{result.points} in {result.csv_path}")
    print(f"regimes: {regimes or 'none yet'}")
    if not result.complete:
        print(f"{result.points - result.already_done - result.computed} points left: run the same command "
              "again to finish")
    return 0
