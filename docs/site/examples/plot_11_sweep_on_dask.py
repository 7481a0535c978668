r"""
A parameter sweep on dask
=========================

``snail sweep SWEEP.toml`` runs a scene over a grid (or a random sample) of
its keys on dask.distributed and writes one row per point to ``sweep.csv`` as
each arrives, so that the same command finishes a stopped sweep
(:doc:`/sweeps`). The same from Python: a sweep over s and the initial kappa
of the reduced model, in a temporary folder. It needs the ``sweep`` extra
(dask.distributed).

``run_sweep(sweep, folder)`` starts a local cluster of worker processes
(``workers=2``, as ``snail sweep`` does) and closes it at the end;
``scheduler="tcp://host:8786"`` sends the points to a running cluster instead.
Here the cluster is a small one inside this process, one worker with two
threads, which starts in a fraction of a second where worker processes take
seconds: the compiled kernels release the GIL, so the threads integrate points
side by side.
"""

import tempfile
from pathlib import Path

from dask.distributed import LocalCluster

from dynamics.app.sweeps import parse_sweep, plot_regime_map, read_rows, run_sweep

sweep = parse_sweep("""
[base]
groups = {s = 0.5, upsilon = 1.0, mu = 1.0}
model = {equations = "reduced"}
initial = {kappa = 0.5, phi = 0.0}
run = {t_end_tau = 100.0, rtol = 1e-6}

[axes]
"groups.s" = {start = 0.0, stop = 1.2, num = 16}
"initial.kappa" = {start = 0.0, stop = 0.9, num = 8}
""")

with (LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=":0") as cluster,
      tempfile.TemporaryDirectory() as folder):
    result = run_sweep(sweep, folder, scheduler=cluster.scheduler_address)
    print(f"{result.computed} points in {result.compute_time_s:.1f} s: {result.regimes}")
    rows = read_rows(Path(folder) / "sweep.csv")

# %%
# Each row of ``sweep.csv`` holds the point's values, its regime and the numbers
# that decided it (:func:`dynamics.regime.classify`), here those of a point that
# runs away; the map draws the regime in the plane of two axes.
runaway = next(row for row in rows if row["regime"] == "runaway")
for key, value in runaway.items():
    print(f"{key:>24}: {value}")
fig = plot_regime_map(rows, "groups.s", "initial.kappa", title="s against the initial kappa, Upsilon = mu_ = 1")
