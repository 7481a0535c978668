"""``snail sweep``: the sweep file, the table on a two-worker dask cluster, resuming, failures, bad input."""

import csv
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.app.sweeps.plot import plot_regime_map, slope_limits
from dynamics.app.sweeps.point import classify_point, run_point
from dynamics.app.sweeps.run import run_sweep
from dynamics.app.sweeps.spec import SweepError, load_sweep, parse_sweep, point_key
from dynamics.app.sweeps.store import NUMBERS, Table, read_rows
from dynamics.scenes import parse_scene
from dynamics.trajectory import Trajectory

# mu_ = 1 and Upsilon = 1 as in the paper's figures 2 (s = 1/4 rocks) and 3 (s = 0.9 runs away).
BASE = """
[base.groups]
s = 0.25
upsilon = 1.0
mu = 1.0
[base.model]
equations = "reduced"
[base.initial]
kappa = 0.5
[base.run]
t_end_tau = 100.0
rtol = 1e-6
"""


@pytest.fixture(scope="module")
def scheduler():
    """The address of a local cluster of two single-threaded worker processes, shared by the module."""
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster:
        yield cluster.scheduler_address


def write_sweep(tmp_path, axes: str, base: str = BASE):
    path = tmp_path / "sweep.toml"
    path.write_text(base + "\n[axes]\n" + axes, encoding="utf-8")
    return path


def test_tiny_sweep_on_two_workers_writes_the_table(tmp_path, scheduler, capsys):
    path = write_sweep(tmp_path, '"groups.s" = [0.25, 1.1]\n"initial.kappa" = {start = 0.3, stop = 0.6, num = 2}\n')
    out = tmp_path / "out"
    assert main(["sweep", str(path), "-o", str(out), "--scheduler", scheduler]) == 0
    assert "4 points computed" in capsys.readouterr().out
    with (out / "sweep.csv").open(encoding="utf-8") as fh:
        header = next(csv.reader(fh))
    assert header == ["groups.s", "initial.kappa", "point", *NUMBERS]
    rows = read_rows(out / "sweep.csv")
    assert sorted((float(r["groups.s"]), float(r["initial.kappa"])) for r in rows) == [
        (0.25, 0.3), (0.25, 0.6), (1.1, 0.3), (1.1, 0.6)]
    for r in rows:
        # no rocking equilibrium sin(phi) = -s exists for s >= 1 (3.5): only runaway is left
        assert r["regime"] == ("rocking" if float(r["groups.s"]) < 1 else "runaway")
        assert r["status"] in ("completed", "stopped")
        assert float(r["wall_time_s"]) > 0 and int(r["steps"]) > 0 and r["reason"] == ""
    rocking = [r for r in rows if r["regime"] == "rocking"]
    assert all(int(r["phi_reversals_late"]) >= 2 and float(r["final_kappa"]) > 0.95 for r in rocking)
    assert slope_limits(rows) == {"lowest_runaway_s": 1.1, "highest_rocking_s": 0.25}
    assert (out / "regime_map.png").stat().st_size > 0


def test_a_stopped_sweep_resumes_without_duplicate_or_missing_rows(tmp_path, scheduler):
    path = write_sweep(tmp_path, '"groups.s" = [0.0, 0.1, 0.2]\n"initial.kappa" = [0.2, 0.5, 0.8]\n'
                                 '"run.t_end_tau" = [20.0]\n')
    sweep = load_sweep(path)
    expected = {point_key(p) for p in sweep.points()}
    first = run_sweep(sweep, tmp_path, scheduler=scheduler, batch_size=2, max_points=4)
    assert (first.computed, first.complete) == (4, False)
    kept = read_rows(tmp_path / "sweep.csv")
    # a crash in the middle of writing a row leaves it cut short; it is dropped and run again
    with (tmp_path / "sweep.csv").open("a", encoding="utf-8") as fh:
        fh.write("0.2,0.8,20.0,deadbeef,compl")
    second = run_sweep(sweep, tmp_path, scheduler=scheduler, batch_size=2)
    assert (second.already_done, second.computed, second.complete) == (4, 5, True)
    rows = read_rows(tmp_path / "sweep.csv")
    keys = [r["point"] for r in rows]
    assert len(keys) == len(set(keys)) == 9 and set(keys) == expected
    assert rows[:4] == kept  # the rows from before the stop are kept, not recomputed
    assert run_sweep(sweep, tmp_path, scheduler=scheduler).computed == 0
    other = load_sweep(write_sweep(tmp_path, '"groups.s" = [0.3]\n'))
    with pytest.raises(SweepError, match="holds the results of another sweep"):
        run_sweep(other, tmp_path, scheduler=scheduler)


def test_a_failing_point_is_recorded_and_the_sweep_goes_on(tmp_path, scheduler):
    # Each value is valid alone; together, the reduced model refuses kappa' != 0 (2.11a).
    base = BASE.replace('equations = "reduced"', 'equations = "full"').replace("mu = 1.0", "mu = 2.0\n"
                                                                                "delta_over_a = 0.05")
    path = write_sweep(tmp_path, '"model.equations" = ["reduced", "full"]\n"initial.kappa_dot" = [0.0, 0.1]\n'
                                 '"run.t_end_tau" = [2.0]\n', base)
    result = run_sweep(load_sweep(path), tmp_path, scheduler=scheduler)
    assert result.complete and result.regimes["failed"] == 1
    rows = {(r["model.equations"], r["initial.kappa_dot"]): r for r in read_rows(tmp_path / "sweep.csv")}
    failed = rows["reduced", "0.1"]
    assert (failed["status"], failed["regime"]) == ("failed", "failed")
    assert "SceneError: initial.kappa_dot must be 0" in failed["reason"]
    assert all(r["status"] in ("completed", "stopped") for key, r in rows.items() if key != ("reduced", "0.1"))


def test_the_table_keeps_every_digit_of_the_axes_and_refuses_other_columns(tmp_path):
    path = tmp_path / "sweep.csv"
    kappa = 0.1 + 0.7 * np.random.default_rng(3).random()  # a random axis's value: all 17 digits
    row = {"initial.kappa": kappa, "point": "p", "status": "completed", "final_kappa": 2.0 / 3.0}
    with Table(path, ["initial.kappa"]) as table:
        table.append([row])
    (read,) = read_rows(path)
    assert float(read["initial.kappa"]) == kappa  # the point's value, not a rounding of it
    assert read["final_kappa"] == "0.6666667"  # numbers to 7 digits
    with pytest.raises(SweepError, match="has the columns initial.kappa, point"):
        Table(path, ["groups.s"])


def test_a_failed_trajectory_is_failed_with_the_numbers_it_reached():
    columns = {"t_tau": [0.0, 1.0, 2.0], "phi": [0.0, 0.1, 0.2], "kappa": [0.5, 0.6, 0.7],
               "one_minus_kappa": [0.5, 0.4, 0.3], "omega_b": [0.0, 0.1, 0.2]}
    trajectory = Trajectory(columns={k: np.array(v) for k, v in columns.items()},
                            rows=np.array(["start", "step", "end"], dtype=object), equations="reduced",
                            forces="closed-form", method="radau", status="failed", message="step failed",
                            event="", events=[], steps=2, nfev=9, njev=1, nlu=1, wall_time_s=0.0, tau=1.0,
                            dimensionless=True)
    regime, numbers = classify_point(trajectory)
    assert regime == "failed" and numbers["t_end_tau"] == 2.0 and numbers["final_kappa"] == 0.7


def test_steady_rolling_in_contact_is_a_regime_with_its_numbers():
    # rough walls hold the gap at kappa_star: the cylinders lock and roll steadily (section 5)
    base = tomllib.loads(BASE)["base"] | {"contact": {"kappa_star": 0.9, "psi": 0.5}}
    row = run_point(base, {"groups.s": 0.3})
    assert (row["status"], row["regime"]) == ("completed", "locked rolling")
    assert row["omega_b_change_late"] < 0.01 and row["omega_b_tau_final"] > 0


@pytest.mark.parametrize(
    ("sweep", "words"),
    [
        ('[axes]\n"groups.s" = [0.1]\n[axis]\nx = 1\n', "unknown key 'axis'"),
        ('[axes]\n"groups.slope" = [0.1]\n', "unknown key groups.slope"),
        ('[axes]\n"initial.kappa" = [0.2, 1.2]\n', "axes.initial.kappa = 1.2: initial.kappa must be in [0, 1)"),
        ('[axes]\n"initial.kappa" = {start = 0.1, stop = 0.9}\n', "axes.initial.kappa: num missing"),
        ('[axes]\n"groups.s" = {start = 0.1, stop = 0.9, num = 0}\n', "axes.groups.s.num must be an integer in [1, 10,000,000]"),
        ('[axes]\n"groups.s" = {random = "normal", low = 0, high = 1, num = 3}\n', "axes.groups.s.random"),
        ('[axes]\n"groups.s" = {random = "uniform", low = 0, high = 1, num = 3}\n'
         '"initial.kappa" = {random = "uniform", low = 0, high = 0.9, num = 4}\n', "axes.initial.kappa.num = 4"),
        ('[axes]\n"groups.s" = []\n', "axes.groups.s is an empty list"),
        ("[axes]\n", "axes must be a table of at least one axis"),
    ],
)
def test_a_bad_sweep_file_exits_2_naming_the_key(tmp_path, capsys, sweep, words):
    path = tmp_path / "bad.toml"
    path.write_text(BASE + sweep, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["sweep", str(path), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err
    assert not out.exists()  # nothing written


def test_base_scene_file_and_random_axes(tmp_path):
    (tmp_path / "scene.toml").write_text(BASE.replace("[base.", "["), encoding="utf-8")
    text = ('base = "scene.toml"\nseed = 7\n[axes]\n"groups.s" = [0.1, 0.2]\n'
            '"initial.kappa" = {random = "uniform", low = 0.1, high = 0.9, num = 3}\n'
            '"groups.upsilon" = {random = "log-uniform", low = 0.1, high = 10, num = 3}\n')
    sweep = parse_sweep(text, base_dir=tmp_path)
    points = sweep.points()
    assert len(points) == 6  # the grid (2 values) crossed with 3 joint random samples
    assert points == parse_sweep(text, base_dir=tmp_path).points()  # the seed fixes the samples
    assert all(0.1 <= p["initial.kappa"] <= 0.9 and 0.1 <= p["groups.upsilon"] <= 10 for p in points)
    assert len({point_key(p) for p in points}) == 6
    assert parse_sweep(text.replace("seed = 7", "seed = 8"), base_dir=tmp_path).points() != points
    with pytest.raises(SweepError, match="base = 'missing.toml'"):
        parse_sweep(text.replace("scene.toml", "missing.toml"), base_dir=tmp_path)


def legend(fig):
    return [t.get_text() for t in fig.axes[0].get_legend().get_texts()]


def test_regime_map_pools_the_other_axes():
    rows = [{"groups.s": str(s), "initial.kappa": str(k), "groups.upsilon": str(u),
             "regime": "runaway" if s > 0.5 + 0.1 * u else "rocking"}
            for s in (0.2, 0.4, 0.6, 0.8) for k in (0.1, 0.5) for u in (0.0, 2.0)]
    fig = plot_regime_map(rows, "groups.s", "initial.kappa")
    assert "mixed: depends on the pooled axes" in legend(fig)
    fixed = plot_regime_map(rows, "groups.s", "initial.kappa", where={"groups.upsilon": 2.1})
    assert legend(fixed) == ["rocking", "runaway", "edge of rocking", "edge of runaway"]
    assert math.isnan(slope_limits([])["lowest_runaway_s"])


@pytest.mark.parametrize("stage", ["starting 2 workers", "loading the batch runner"])
def test_ctrl_c_stops_a_sweep_at_each_stage_without_a_traceback(tmp_path, stage, terminal_child):
    """Ctrl-C while the cluster starts (dask cannot close a half-started one) and while the batch runner
    compiles (on a worker: numba cannot be stopped inside a compile): exit 130 within seconds, no traceback."""
    import signal
    import subprocess
    import sys
    import time

    examples = Path(__file__).resolve().parents[1] / "dynamics" / "app" / "sweeps" / "examples"
    proc = subprocess.Popen([sys.executable, "-m", "dynamics.app.cli", "sweep", str(examples / "slope_kappa.toml"),
                             "-o", str(tmp_path / "out"), "--workers", "2"],
                            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True,
                            preexec_fn=terminal_child)
    try:
        for line in proc.stderr:
            if stage in line:
                break
        time.sleep(0.5)  # inside the stage, past its first imports
        proc.send_signal(signal.SIGINT)
        start = time.perf_counter()
        err = proc.stderr.read()
        proc.wait(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert time.perf_counter() - start < 30


def test_every_shipped_sweep_parses_and_its_base_scene_is_valid():
    """The examples of docs/site/sweeps.md, the Navier-Stokes resolution study among them."""
    examples = Path(__file__).resolve().parents[1] / "dynamics" / "app" / "sweeps" / "examples"
    for path in sorted(examples.glob("*.toml")):
        text = path.read_text()
        if "[axes]" not in text:
            continue  # a base scene
        sweep = load_sweep(path)
        first = next(iter(sweep.points()))
        parse_scene(sweep.base, sweep.source, first)
    ns = load_sweep(examples / "navier_stokes_resolution.toml")
    assert len(list(ns.points())) == 6
    assert parse_scene(ns.base, ns.source).model.equations == "navier-stokes"


def test_the_stored_sandpaper_ensemble_needs_a_steeper_slope_for_a_coarser_grade():
    """docs/sweeps/README.md's reading of the stored sandpaper sweep: at the amplitude 0.05, the lowest slope at
    which every realisation rolls (mean speed over the second half at least 0.1 mm/s) does not fall from one
    grade to the next coarser, and the coarsest grade needs a steeper slope than the smooth cylinder."""
    stored = Path(__file__).resolve().parents[1] / "docs" / "sweeps" / "sandpaper" / "sweep.csv"
    cells: dict = {}
    for row in csv.DictReader(stored.open()):
        if float(row["contact.roughness_amplitude"]) == 0.05:
            sigma, slope = float(row["contact.sigma"].split()[0]), float(row["incline.alpha"].split()[0])
            rolls = row["status"] == "completed" and float(row["mean_speed_late"]) >= 1e-4
            cells.setdefault(sigma, {}).setdefault(slope, []).append(rolls)
    lowest = [min((slope for slope, rolls in by_slope.items() if all(rolls)), default=math.inf)
              for _, by_slope in sorted(cells.items())]
    assert len(lowest) == 6 and all(len(r) == 4 for by in cells.values() for r in by.values())
    assert lowest == sorted(lowest) and lowest[-1] > lowest[0]
