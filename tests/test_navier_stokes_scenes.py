"""Scenes with model.equations = "navier-stokes": ``snail run`` writes the coupled run's set, snapshots included.

The reference of a scene run is the API it selects: simulate(..., equations="navier-stokes") with the
same grid, tolerance and snapshot times gives the same numbers (the run is deterministic, so they
agree to the digits written: trajectory.csv holds 17 significant digits). The VTU files read back
with meshio hold the snapshot fields of that run at the times the scene asked for. The run is short
and coarse (0.01 s, 8 points across): what is tested is the plumbing, not the flow, whose checks are
in tests/test_navier_stokes_coupled.py.
"""

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.app.output import CSV_COLUMNS
from dynamics.scenes import SceneError, load_scene, resolved_toml

T_END = 0.01  # s
INTERVAL = 0.005  # s: snapshots at 0, 0.005 and 0.01 s
SCENE = ["model.equations=navier-stokes", "navier_stokes.n_r=8", f"navier_stokes.snapshot_interval={INTERVAL}",
         "navier_stokes.animation=gif", f"run.t_end={T_END}"]
LOADS = ("f_eps", "f_chi", "T_a", "T_b")
#: summary.json's keys of every run (DESIGN.md, "Public contract" and "Scenes").
CONTRACT_KEYS = {"model", "forces", "t_end", "mean_speed", "regime", "wall_time_s", "steps", "tau", "s", "upsilon",
                 "mu", "delta_over_a"}


def read_csv(path: Path) -> tuple[list[str], np.ndarray]:
    lines = path.read_text().splitlines()
    return lines[0].split(","), np.loadtxt([line.rsplit(",", 1)[0] for line in lines[1:]], delimiter=",", ndmin=2)


@pytest.fixture(scope="module")
def scene_run(tmp_path_factory):
    """``snail run`` of the default scene with the coupled flow, snapshots and an animation; and the
    same run through simulate()."""
    from dynamics import simulate
    from dynamics.equations.navier_stokes import NavierStokesOptions

    out = tmp_path_factory.mktemp("ns") / "run"
    code = main(["run", "--no-plot", "-o", str(out), *[a for s in SCENE for a in ("--set", s)]])
    scene = load_scene(None, SCENE)
    direct = simulate(scene.apparatus, scene.initial, T_END, equations="navier-stokes", limits=scene.run.limits,
                      navier_stokes=NavierStokesOptions(n_r=8, snapshot_times=(0.0, INTERVAL, 2 * INTERVAL)))
    return code, out, direct


def test_a_scene_runs_the_coupled_flow_and_writes_its_columns_and_keys(scene_run):
    code, out, direct = scene_run
    assert code == 0
    names, rows = read_csv(out / "trajectory.csv")
    assert names[:len(CSV_COLUMNS)] == list(CSV_COLUMNS) and set(LOADS) <= set(names)
    for name in ("t", "x_b", "one_minus_kappa", "phi", "omega_b", *LOADS):
        np.testing.assert_allclose(rows[:, names.index(name)], direct.columns[name], rtol=1e-15, atol=0.0)
    summary = json.loads((out / "summary.json").read_text())
    assert CONTRACT_KEYS <= set(summary)
    assert summary["model"] == "navier-stokes" and summary["status"] == "completed"
    assert summary["t_end"] == T_END
    assert summary["navier_stokes"]["n_r"] == 8
    assert summary["navier_stokes"]["steps"] == direct.info["navier_stokes"]["steps"]
    assert "[navier_stokes]" in (out / "scene.resolved.toml").read_text()


def test_the_snapshots_read_back_as_the_run_took_them(scene_run):
    import meshio

    _, out, direct = scene_run
    summary = json.loads((out / "summary.json").read_text())["snapshots"]
    assert summary["times"] == [0.0, INTERVAL, 2 * INTERVAL]
    assert summary["animation"] == "flow.gif" and (out / "flow.gif").stat().st_size > 0
    collection = ET.parse(out / "flow.pvd").getroot().find("Collection")
    listed = [(d.get("file"), float(d.get("timestep"))) for d in collection]
    assert listed == list(zip(summary["files"], summary["times"]))
    for name, taken in zip(summary["files"], direct.info["snapshots"]):
        mesh = meshio.read(out / name)
        np.testing.assert_array_equal(mesh.points[:, 0], np.ravel(taken["x"]))
        np.testing.assert_array_equal(mesh.point_data["vorticity"], np.ravel(taken["vorticity"]))
    # the last snapshot is the flow at the end: its outer turn is the distance rolled over b
    ap = load_scene(None, SCENE).apparatus
    assert math.isclose(direct.info["snapshots"][-1]["theta_b"], direct.columns["x_b"][-1] / ap.b, rel_tol=1e-12)


def test_the_progress_is_the_simulated_time():
    from dynamics.app.run import run_scene

    reached = []
    run_scene(load_scene(None, [*SCENE[:2], "run.t_end=0.002"]), progress=reached.append)
    assert reached and np.all(np.diff(reached) > 0) and math.isclose(reached[-1], 0.002, rel_tol=1e-9)


@pytest.mark.parametrize(("overrides", "named"), [
    (["model.forces=closed-form"], "model.forces"),
    (["model.frame_terms=paper"], "model.frame_terms"),
    (["model.inertia=first-order"], "model.inertia"),
    (["model.ends=open"], "model.ends"),
    (["contact.kappa_star=0.99"], "contact.kappa_star"),
    (["cavitation.model=jfo"], "cavitation.model"),
    (["navier_stokes.animation=gif"], "navier_stokes.snapshot_interval"),
    (["navier_stokes.snapshot_interval=1e-5"], "navier_stokes.snapshot_interval"),
    (["navier_stokes.n_r=2"], "navier_stokes.n_r"),
    (["navier_stokes.n_theta=4"], "navier_stokes.n_theta"),
])
def test_what_the_coupled_flow_cannot_take_is_refused_naming_the_key(overrides, named):
    with pytest.raises(SceneError, match=named.replace(".", r"\.")):
        load_scene(None, ["model.equations=navier-stokes", *overrides])


def test_the_section_without_the_coupled_flow_is_refused():
    with pytest.raises(SceneError, match=r"navier_stokes\.n_r: .*model\.equations = 'navier-stokes'"):
        load_scene(None, ["navier_stokes.n_r=8"])


def test_a_refused_scene_exits_2_without_a_traceback_or_files(tmp_path, capsys):
    out = tmp_path / "never"
    code = main(["run", "-o", str(out), "--model", "navier-stokes", "--set", "model.frame_terms=paper"])
    _, err = capsys.readouterr()
    assert code == 2 and "model.frame_terms" in err and "Traceback" not in err
    assert not out.exists()


def test_auto_does_not_choose_the_coupled_flow():
    from dynamics.app.auto import resolve_model

    for overrides in ([], ["model.tolerance=0.5"], ["model.tolerance=1e-6"]):
        resolved, _ = resolve_model(load_scene(None, ["model.equations=auto", *overrides]))
        assert resolved.equations in ("full", "reduced")


def test_other_scenes_are_as_before():
    scene = load_scene(None)
    assert scene.navier_stokes is None and "\n[navier_stokes]" not in resolved_toml(scene)
