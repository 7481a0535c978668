"""`snail run` end to end: outputs, exit codes, bad scenes, and runs that stop early."""

import json
import math
import signal

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.app.output import CSV_COLUMNS
from numerics.engine import INTERRUPTED, NON_FINITE
from numerics.integrate import METHODS, integrate
from numerics.jit import jit

SHORT = ["--t-end", "2 s"]


def _header(folder):
    return (folder / "trajectory.csv").read_text().splitlines()[0].split(",")


def _contract_header(header, extra):
    """The contract's columns first, the model's own ``extra`` ones after them, the row kind last."""
    return (tuple(header[:len(CSV_COLUMNS)]) == CSV_COLUMNS and set(extra) <= set(header[len(CSV_COLUMNS):-1])
            and header[-1] == "row")


def test_default_scene_writes_the_contract_outputs(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", "-o", str(out), *SHORT, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    for key in ("model", "forces", "t_end", "mean_speed", "regime", "wall_time_s", "steps", "tau",
                "s", "upsilon", "mu", "delta_over_a"):
        assert key in summary
    assert summary["status"] == "completed" and summary["t_end"] == pytest.approx(2.0)
    header = _header(out)
    assert {"t", "x_b", "eps", "chi", "kappa", "phi", "omega_a", "omega_b", "t_tau"} <= set(header)
    assert _contract_header(header, ())
    assert (out / "trajectory.png").stat().st_size > 10_000
    assert json.loads((out / "summary.json").read_text()) == summary
    assert "[apparatus]" in (out / "scene.resolved.toml").read_text()


def test_reduced_model_with_reynolds_forces_is_refused_and_nothing_written(tmp_path, capsys):
    out = tmp_path / "run"
    code = main(["run", "-o", str(out), "--model", "reduced", "--forces", "reynolds"])
    assert code == 2
    assert "model.forces" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize(
    ("override", "words"),
    [
        ("initial.kappa=1.0", "initial.kappa"),
        ("fluid.nu=-1e-4", "fluid.nu"),
        ("incline.alpha='2.4 kg'", "incline.alpha"),
        ("apparatus.b=0.005", "apparatus.b"),
        ("bogus.key=1", "bogus"),
    ],
)
def test_bad_scene_values_exit_2_naming_the_key(tmp_path, capsys, override, words):
    out = tmp_path / "run"
    assert main(["run", "-o", str(out), "--set", override]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err
    assert not out.exists()


def test_reynolds_forces_run_from_the_command_line(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", "-o", str(out), "--forces", "reynolds", "--t-end", "0.5", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["forces"] == "reynolds"


def test_a_run_stopped_by_its_validity_limit_exits_1_and_keeps_its_data(tmp_path, capsys):
    """The aluminium runaway (s = 1.9) with the Reynolds guard at Re* = 1 (a 10% force error): the
    relative flow passes it in the first swing (Re* peaks at 2.5, at t = 0.06 s), which ends the run."""
    out = tmp_path / "run"
    code = main(["run", "-o", str(out), "--set", "apparatus.preset='aluminium'", "--set", "incline.alpha='12 deg'",
                 "--set", "run.max_gap_reynolds=1", "--set", "run.on_invalid='stop'", "--t-end", "30 s", "--json"])
    summary = json.loads(capsys.readouterr().out)
    assert code == 1
    assert summary["status"] == "stopped" and summary["stop_event"] == "reynolds"
    assert "Reynolds number" in summary["reason"] and "max_gap_reynolds = 1 " in summary["reason"]
    # stopped in its first swing: too early for the regime to show (a Reynolds stop is no runaway by itself)
    assert summary["regime"] == "transient" and summary["t_end"] < 0.1
    rows = (out / "trajectory.csv").read_text().splitlines()
    assert len(rows) - 1 >= summary["steps"] and rows[-1].endswith(",event:reynolds+end")


def test_a_long_every_step_output_is_thinned_with_its_events_kept(tmp_path, capsys):
    """run.max_rows bounds trajectory.csv: 20 s of the default scene (about 1,900 steps) written as every
    k-th step, with the start, every event row and the end kept, and summary.json saying so."""
    out = tmp_path / "run"
    code = main(["run", "-o", str(out), "--t-end", "20 s", "--set", "run.max_rows=100",
                 "--set", "run.on_invalid='warn'", "--no-plot", "--json"])
    summary = json.loads(capsys.readouterr().out)
    assert code == 0
    lines = (out / "trajectory.csv").read_text().splitlines()[1:]
    labels = [line.rsplit(",", 1)[1] for line in lines]
    thinned = summary["rows_thinned"]
    assert thinned["steps"] > 10 * 100 and thinned["written"] == len(lines)
    every = -(-thinned["steps"] // 100)  # ceil: every k-th step fits the bound
    assert len([label for label in labels if label == "step"]) <= 100
    assert labels[0] == "start" and labels[-1].endswith("end")
    assert sum(label.startswith("event:") for label in labels) == len(summary["events"]) >= 1
    times = np.array([float(line.split(",", 1)[0]) for line in lines])
    assert np.all(np.diff(times) >= 0.0) and f"every {every}-th step" in thinned["reason"]


def test_an_output_interval_beyond_the_row_bound_is_refused_before_the_run(tmp_path, capsys):
    out = tmp_path / "run"
    code = main(["run", "-o", str(out), "--t-end", "10 s", "--output-interval", "1 ms", "--set", "run.max_rows=5000"])
    err = capsys.readouterr().err
    assert code == 2 and "run.output_interval = 0.001 s would write 10001 rows" in err
    assert "run.max_rows = 5000" in err and not out.exists()


@pytest.mark.parametrize(("grid", "n", "stopped"), [("uniform", 8, True), ("uniform", 2048, False),
                                                     ("sommerfeld", 8, False)])
def test_a_reynolds_grid_stops_where_it_no_longer_resolves_the_film(grid, n, stopped):
    """The default scene over 2 s reaches 1 - kappa = 2e-4 (kappa = 0.9998). 8 cells uniform in theta
    resolve the film (forces within model.tolerance = 1e-2) only to kappa = 0.557; closer their forces
    err by orders of magnitude and the inner cylinder crashes into the wall. The run stops where the grid
    stops resolving, and says why and what would do; 2048 cells reach 1 - kappa = 1e-6 and the Sommerfeld
    grid is exact from 8, so those run on."""
    from dynamics.app.run import run_scene
    from dynamics.scenes import load_scene

    scene = load_scene(None, ["run.t_end='2 s'", "model.forces='reynolds'", f"model.grid='{grid}'", f"model.n={n}",
                              "run.on_invalid='warn'"])
    trajectory = run_scene(scene)
    assert ("resolution" in trajectory.info) == stopped
    if stopped:
        reach = trajectory.info["resolution"]["kappa_reach"]
        assert reach == pytest.approx(0.557, abs=1e-3)
        passed = [p for p in trajectory.info["limits_passed"] if p["name"] == "gap_floor"]
        assert len(passed) == 1 and "only to kappa = 0.557" in passed[0]["reason"]
        assert "model.grid = 'sommerfeld' is exact from 8 cells" in trajectory.info["resolution"]["reason"]
        stop = load_scene(None, ["run.t_end='2 s'", "model.forces='reynolds'", "model.grid='uniform'",
                                 "model.n=8", "run.max_gap_reynolds='none'", "run.on_invalid='stop'"])
        halted = run_scene(stop)
        assert halted.status == "stopped" and halted.event == "gap_floor"
        assert halted.columns["kappa"][-1] == pytest.approx(reach, rel=1e-9) and "only to kappa" in halted.message
    else:
        assert trajectory.status == "completed"


def test_the_first_inertial_correction_is_a_scene_choice(tmp_path, capsys):
    """model.inertia = 'first-order' runs the full equations with the corrected exact Stokes forces, and is
    refused (exit 2, the key named) where no correction is tabulated."""
    out = tmp_path / "run"
    code = main(["run", "-o", str(out), *SHORT, "--set", "model.forces='stokes-exact'",
                 "--set", "model.inertia='first-order'", "--no-plot", "--json"])
    summary = json.loads(capsys.readouterr().out)
    assert code == 0 and summary["forces"] == "stokes-exact+inertia"
    assert "inertia = \"first-order\"" in (out / "scene.resolved.toml").read_text()
    for extra in (["--set", "model.equations='reduced'"], ["--set", "model.forces='reynolds'"]):
        code = main(["run", "-o", str(tmp_path / "refused"), *SHORT, "--set", "model.inertia='first-order'", *extra])
        err = capsys.readouterr().err
        assert code == 2 and "model.inertia" in err and not (tmp_path / "refused").exists()


def test_output_interval_rows_from_the_command_line(tmp_path, capsys):
    """snail run --output-interval "0.1 s" on the default scene: 101 rows at k 0.1 s exactly (the event of
    the release's Reynolds passage kept and marked), each on the every-step run's solution to the run's
    tolerance (compared at the sampled times through the dense output of a tighter run), phi unwrapped."""
    from dynamics.scenes import load_scene
    from dynamics.simulation import simulate

    out = tmp_path / "run"
    assert main(["run", "-o", str(out), "--output-interval", "0.1 s", "--no-plot", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    lines = (out / "trajectory.csv").read_text().splitlines()
    header, rows = lines[0].split(","), [line.split(",") for line in lines[1:]]
    labels = [r[-1] for r in rows]
    samples = np.array([[float(x) for x in r[:-1]] for r, label in zip(rows, labels) if "sample" in label])
    assert len(samples) == 101 and labels[0] == "start+sample" and labels[-1] == "sample+end"
    assert {label for label in labels if "sample" not in label} == {"event:reynolds"}
    t = samples[:, header.index("t")]
    np.testing.assert_array_equal(t, 0.1 * np.arange(101))
    scene = load_scene()
    dense = simulate(scene.apparatus, scene.initial, 10.0, rtol=1e-11, limits=scene.run.limits, t_eval=t)
    keep = np.array(["sample" in row for row in dense.rows])
    for name in ("phi", "x_b", "one_minus_kappa"):
        got, want = samples[:, header.index(name)], dense.columns[name][keep]
        # the run's rtol 1e-8 holds the local error of a step, relative to each component or its typical scale,
        # whichever is larger: X_b's is b (full.typical_scales), while X_b is still below it at the first samples
        atol = 1e-8 * scene.apparatus.b if name == "x_b" else 1e-12
        np.testing.assert_allclose(got, want, rtol=1e-8, atol=atol)
    assert np.all(np.abs(np.diff(samples[:, header.index("phi")])) < np.pi)  # continuous, not wrapped
    assert summary["regime"] == "rocking"


@jit
def _decay(t, y, args):
    """y' = -y."""
    return -y


@jit
def _decay_jacobian(t, y, args):
    return -np.eye(y.size)


@jit
def _fails_after_one(t, y, args):
    """y' = 1 up to t = 1, then not a number: a model that breaks down during a run."""
    return np.full(y.size, 1.0 if t <= 1.0 else math.nan)


@jit
def _zero_jacobian(t, y, args):
    return np.zeros((y.size, y.size))


@pytest.mark.parametrize("method", METHODS)
def test_an_interrupted_integration_keeps_every_step_it_took(method, ctrl_c):
    """Ctrl-C (a real SIGINT, sent from the progress callback) ends the run with what it computed."""
    calls = {"n": 0}

    def progress(t):
        calls["n"] += 1
        if calls["n"] == 20:
            signal.raise_signal(signal.SIGINT)

    run = integrate(_decay, _decay_jacobian, (0.0, 100.0), np.array([1.0]), args=np.zeros(1), method=method,
                    rtol=1e-10, atol=1e-12, chunk_steps=5, progress=progress)
    assert run.status == -1 and run.code == INTERRUPTED and not run.success
    assert "interrupted by SIGINT at t" in run.message
    assert 5 < run.t.size and run.t[-1] < 100.0
    # every row is on the solution: the steps taken are kept, not discarded
    np.testing.assert_allclose(run.y[0], np.exp(-run.t), rtol=1e-8)


@pytest.mark.parametrize("method", METHODS)
def test_a_failing_right_hand_side_is_reported_not_raised(method):
    """A right-hand side that turns NaN after t = 1 ends the run as failed, with the steps before it.

    The compiled engine reports the non-finite right-hand side; scipy's Radau and
    BDF see their Newton iteration fail and say so. Either way every row kept is
    a finite state on the solution y = t, the last one at t <= 1.
    """
    run = integrate(_fails_after_one, _zero_jacobian, (0.0, 5.0), np.zeros(1), args=np.zeros(1), method=method)
    assert run.status == -1 and not run.success and run.t.size > 1
    assert run.code == NON_FINITE or (method != "radau" and f"the {method} solver failed" in run.message), \
        run.message
    assert np.all(np.isfinite(run.y)) and run.t[-1] <= 1.0 + 1e-12
    np.testing.assert_allclose(run.y[0], run.t, rtol=1e-12, atol=1e-15)  # y = t up to the failure


FIGURE_7 = """
[groups]
s = 0.25
upsilon = 1.0
mu = 1.0
[initial]
kappa = 0.5
phi = 0.3
[model]
equations = "reduced"
[contact]
kappa_star = 0.98
psi = {psi}
[run]
t_end_tau = 300
"""


@pytest.mark.parametrize(("psi", "regime"), [(0.05, "sliding rolling"), (0.5, "locked rolling")])
def test_a_contact_scene_settles_into_steady_rolling(tmp_path, capsys, psi, regime):
    """The paper's figure 7 and 8 parameters: contact at t = 5.82 tau, then the steady state of (5.6)-(5.11)."""
    from dynamics.contact.steady import steady_state

    scene = tmp_path / "contact.toml"
    scene.write_text(FIGURE_7.format(psi=psi))
    assert main(["run", str(scene), "-o", str(tmp_path / "out"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["regime"] == regime and summary["dimensionless"]
    assert summary["switches"][0]["t"] == pytest.approx(5.8207, abs=1e-4)
    steady = steady_state(0.25, 0.98, psi)
    assert summary["final"]["omega_b"] == pytest.approx(steady.omega_b, rel=1e-6)
    assert _contract_header(_header(tmp_path / "out"), ("phase", "c_eps", "c_chi"))


def test_contact_in_the_full_model_runs_from_the_default_scene(tmp_path, capsys):
    """The steel apparatus with asperities at kappa* = 0.98 touches, then rolls in sliding contact."""
    assert main(["run", "-o", str(tmp_path / "out"), "--set", "contact.kappa_star=0.98",
                 "--set", "contact.psi=0.1", "--t-end", "3", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["model"] == "full" and summary["status"] == "completed"
    assert summary["switches"][0]["from"] == "free" and summary["final"]["kappa"] == 0.98
    assert _contract_header(_header(tmp_path / "out"), ("phase", "c_eps", "c_chi"))


def test_a_varying_minimum_gap_in_the_full_model_runs(tmp_path, capsys):
    """The default scene with asperities whose gap varies along both surfaces (it was refused): the
    full equations run it and write the body angles; a compliant contact in the reduced equations
    is refused, naming the key."""
    assert main(["run", "-o", str(tmp_path / "out"), "--forces", "closed-form", "--set", "contact.kappa_star=0.98",
                 "--set", "contact.roughness_amplitude=0.3", "--set", "contact.roughness_correlation=0.001",
                 "--t-end", "2", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["model"] == "full" and summary["status"] == "completed"
    assert summary["switches"][0]["from"] == "free"
    assert _contract_header(_header(tmp_path / "out"), ("phase", "c_eps", "c_chi", "theta_a", "theta_b"))
    assert main(["run", "-o", str(tmp_path / "reduced"), "--model", "reduced", "--forces", "closed-form",
                 "--set", "contact.kappa_star=0.98",
                 "--set", "contact.law='compliant'"]) == 2
    assert "contact.law" in capsys.readouterr().err
    assert not (tmp_path / "reduced").exists()


def test_a_cavitating_film_runs_through_the_scene(tmp_path, capsys):
    code = main(["run", "-o", str(tmp_path / "out"), "--forces", "reynolds", "--set", "cavitation.model='jfo'",
                 "--set", "model.n=64", "--t-end", "0.3", "--json"])
    assert code == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["forces"] == "reynolds/jfo" and summary["status"] == "completed"


def test_cavitation_with_closed_forms_is_refused(tmp_path, capsys):
    assert main(["run", "-o", str(tmp_path / "out"), "--set", "cavitation.model='jfo'"]) == 2
    assert "needs the Reynolds solver" in capsys.readouterr().err


def test_a_rough_contact_scene_rolls_irregularly_and_deterministically(tmp_path, capsys):
    """A minimum gap varying along both surfaces: more phase switches than uniform kappa*, same seed same run."""
    scene = tmp_path / "rough.toml"
    scene.write_text(FIGURE_7.format(psi=0.05).replace("psi = 0.05", "psi = 0.05\nroughness_amplitude = 0.5\n"
                                                       "roughness_correlation = 0.3\nseed = 7"))
    summaries = []
    for run_dir in ("one", "two"):
        assert main(["run", str(scene), "-o", str(tmp_path / run_dir), "--json"]) == 0
        summaries.append(json.loads(capsys.readouterr().out))
    assert len(summaries[0]["switches"]) > 3
    assert summaries[0]["final"] == summaries[1]["final"]
    assert _contract_header(_header(tmp_path / "one"), ("phase", "c_eps", "c_chi", "theta_a", "theta_b"))


@pytest.mark.parametrize("cavitation", ["half-sommerfeld", "swift-stieber", "jfo"])
def test_steady_rolling_on_a_cavitating_film_is_recognised(cavitation):
    """Section 7: a film that ruptures a few pascals below the bubble's pressure stops the sinking.

    From about 2 s the gap, the angle and the speed stay constant; the classifier
    says so, with the spreads that decided it (the full film of the same scene keeps
    closing and is not steady). As the inner centre swings past the outer one in the
    first 0.02 s, the ruptured film lets the flow relative to the line of centres
    pass the default Reynolds guard Re* = 10: the runs warn there and go on.
    """
    from dynamics.app.run import run_scene
    from dynamics.regime import STEADY_SPREAD, classify
    from dynamics.scenes import load_scene

    base = ["model.forces=reynolds", "model.n=128", "run.t_end=20", "run.on_invalid='warn'"]
    scene = load_scene(overrides=[*base, f"cavitation.model={cavitation}", "cavitation.p_cav=101320"])
    trajectory = run_scene(scene)
    assert trajectory.status == "completed"
    assert [(p["name"], p["t"] < 0.1) for p in trajectory.info["limits_passed"]] == [("reynolds", True)]
    regime, evidence = classify(trajectory)
    assert regime == "steady rolling"
    assert evidence["one_minus_kappa_relative_spread_late"] < STEADY_SPREAD
    full_film, evidence = classify(run_scene(load_scene(overrides=base)))
    assert full_film != "steady rolling" and evidence["one_minus_kappa_relative_spread_late"] > 0.3
