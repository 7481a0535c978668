"""``snail fit``: the roughness and the friction, with intervals, from a measured descent (:mod:`dynamics.fit`)."""

from __future__ import annotations

import argparse
import io
import json
import sys
from pathlib import Path

from dynamics.app.command import UsageError

__all__ = ["register"]

#: The files of a fit's output set, and the summary that marks a folder as holding one.
NAMES = frozenset({"fit.json", "posterior.csv", "fit.png"})
SUMMARY = ("fit.json", frozenset({"keys", "estimate", "interval_90"}))


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if not 1 <= value <= 1_000_000:
        msg = f"must be an integer in [1, 1000000], got {text!r}"
        raise argparse.ArgumentTypeError(msg)
    return value


def register(subparsers) -> None:
    """Add ``snail fit``."""
    p = subparsers.add_parser(
        "fit", help="infer the roughness and the friction from a measured descent",
        description="Estimate, with 90 %% intervals, the unknowns a scene marks in its [fit] section (its rough "
                    "contact's rms, correlation length, friction, mean gap) from measured times and positions "
                    "(DATA.csv with columns t, x_b in s and m), by approximate Bayesian computation on the "
                    "unsteadiness of the descent. Writes DIR/fit.json, DIR/posterior.csv and DIR/fit.png.")
    p.add_argument("data", help="CSV of the measured descent: columns t (s) and x_b (m)")
    p.add_argument("scene", help="scene TOML with a [fit] section of the unknowns and their priors")
    p.add_argument("-o", "--output", default="snail-fit", help="output folder (default snail-fit)")
    p.add_argument("--draws", type=_count, default=2000, help="runs of the reference table (default 2000)")
    p.add_argument("--accept", type=float, default=0.1, help="share of the table kept (default 0.1)")
    p.add_argument("--seed", type=int, default=0, help="seed of the draws and their surfaces (default 0)")
    p.add_argument("--workers", type=_count, default=1, help="dask worker processes (default 1: this process)")
    p.add_argument("--json", action="store_true", help="print fit.json to stdout")
    p.set_defaults(run=_run)


def _run(args) -> int:
    from dynamics.fit import fit, read_fit_scene, read_record
    from dynamics.scenes import SceneError
    from numerics.folder import FolderError, OutputFolder, held_signals

    try:
        if not 0.0 < args.accept <= 1.0:
            raise UsageError(f"--accept must be in (0, 1], got {args.accept!r}")
        data_path, scene_path = Path(args.data), Path(args.scene)
        times, x_b = read_record(data_path.read_text(encoding="utf-8"), str(data_path))
        scene_raw, priors = read_fit_scene(scene_path.read_text(encoding="utf-8"), str(scene_path))
        folder = OutputFolder(args.output, NAMES, SUMMARY).__enter__()
    except (OSError, ValueError, SceneError, FolderError) as err:
        raise UsageError(str(err)) from err
    try:
        result = _fit(fit, args, times, x_b, scene_raw, priors)
        with held_signals():
            _write(folder, result)
            folder.commit()
    finally:
        folder.__exit__(None, None, None)
    summary = result.as_dict()
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        for key in result.keys:
            low, high = result.interval[key]
            print(f"{key}: {result.estimate[key]:.4g} (90 % interval {low:.4g} .. {high:.4g})")
        print(f"from {result.accepted} of {result.table_size} runs; outputs in {folder.path}/")
    return 0


def _fit(fit, args, times, x_b, scene_raw, priors):
    from tqdm.auto import tqdm

    bar = tqdm(total=args.draws, desc="snail fit", unit="run", mininterval=1.0, disable=not sys.stderr.isatty())

    def progress(done, total):
        bar.update(done - bar.n)

    client = cluster = None
    try:
        if args.workers > 1:
            from dynamics.app.sweeps.run import _client

            client, cluster = _client(None, args.workers)
        return fit(times, x_b, scene_raw, priors, draws=args.draws, accept=args.accept, seed=args.seed,
                   client=client, progress=progress)
    finally:
        bar.close()
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()


def _write(folder, result) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from numerics.files import save_figure, write_json, write_text

    write_json(folder.staging / "fit.json", result.as_dict())
    buf = io.StringIO()
    buf.write(",".join([*result.keys, "weight"]) + "\n")
    for row, weight in zip(result.samples, result.weights):
        buf.write(",".join(f"{x:.10g}" for x in (*row, weight)) + "\n")
    write_text(folder.staging / "posterior.csv", buf.getvalue())
    fig, axes = plt.subplots(1, len(result.keys), figsize=(4 * len(result.keys), 3.2), squeeze=False,
                             layout="constrained")
    for ax, (j, key) in zip(axes[0], enumerate(result.keys)):
        ax.hist(result.samples[:, j], bins=30, weights=result.weights, color="0.6")
        ax.axvline(result.estimate[key], color="k")
        for edge in result.interval[key]:
            ax.axvline(edge, color="k", ls="--", lw=0.8)
        ax.set_xlabel(key)
    axes[0, 0].set_ylabel("posterior weight")
    save_figure(folder.staging / "fit.png", fig, dpi=110)
    plt.close(fig)
