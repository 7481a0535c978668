r"""
A parameter sweep on dask
=========================

``snail sweep SWEEP.toml`` runs a scene over a grid (or a random sample) of
its keys on dask.distributed and writes one row per point to ``sweep.csv`` as
each arrives, so that the same command finishes a stopped sweep
(:doc:`/sweeps`). The same from Python, on a local cluster of two worker
processes: a sweep over s and the initial kappa, in a temporary folder.

This example starts a cluster and takes some tens of seconds: it runs only when
the documentation is built with ``SNAIL_DOCS_EXAMPLES=all`` (it needs the
``sweep`` extra, dask.distributed).
"""

import tempfile
from pathlib import Path

from dynamics.app.sweeps import parse_sweep, plot_regime_map, read_rows, run_sweep

sweep = parse_sweep("""
[base]
groups = {s = 0.5, upsilon = 1.0, mu = 1.0}
model = {equations = "reduced"}
initial = {kappa = 0.5, phi = 0.0}
run = {t_end_tau = 100.0, rtol = 1e-6}

[axes]
"groups.s" = {start = 0.0, stop = 1.2, num = 25}
"initial.kappa" = {start = 0.0, stop = 0.9, num = 10}
""")

# dask starts its workers as fresh processes, which import this script again:
# the sweep runs only in the main one.
if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as folder:
        result = run_sweep(sweep, folder, workers=2)
        print(f"{result.computed} points in {result.compute_time_s:.1f} s "
              f"({result.points_per_second:.1f} per second): {result.regimes}")
        rows = read_rows(Path(folder) / "sweep.csv")
    fig = plot_regime_map(rows, "groups.s", "initial.kappa", title="s against the initial kappa, Upsilon = mu_ = 1")
