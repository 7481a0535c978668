"""`snail run` end to end: outputs, exit codes, bad scenes, and runs that stop early."""

import json

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.integrate import integrate

SHORT = ["--t-end", "2 s"]


def test_default_scene_writes_the_contract_outputs(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", "-o", str(out), *SHORT, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    for key in ("model", "forces", "t_end", "mean_speed", "regime", "wall_time_s", "steps", "tau",
                "s", "upsilon", "mu", "delta_over_a"):
        assert key in summary
    assert summary["status"] == "completed" and summary["t_end"] == pytest.approx(2.0)
    header = (out / "trajectory.csv").read_text().splitlines()[0].split(",")
    assert {"t", "x_b", "eps", "chi", "kappa", "phi", "omega_a", "omega_b", "t_tau"} <= set(header)
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
    out = tmp_path / "run"
    code = main(["run", "-o", str(out), "--set", "apparatus.preset='aluminium'",
                 "--set", "incline.alpha='12 deg'", "--t-end", "30 s", "--json"])
    summary = json.loads(capsys.readouterr().out)
    assert code == 1
    assert summary["status"] == "stopped" and "Reynolds number" in summary["reason"]
    assert summary["regime"] == "runaway"
    rows = (out / "trajectory.csv").read_text().splitlines()
    assert len(rows) > 100


def test_an_interrupted_integration_keeps_every_step_it_took():
    calls = {"n": 0}

    def fun(t, y):
        calls["n"] += 1
        if calls["n"] > 200:
            raise KeyboardInterrupt
        return -y

    run = integrate(fun, np.array([1.0]), 100.0, method="RK45", rtol=1e-10)
    assert run.status == "interrupted" and "interrupted at t" in run.reason
    assert run.t.size > 5 and np.allclose(run.y[0], np.exp(-run.t), rtol=1e-8)


def test_a_failing_right_hand_side_is_reported_not_raised():
    def fun(t, y):
        if t > 1.0:
            raise ZeroDivisionError("float division by zero")
        return np.ones(1)

    run = integrate(fun, np.zeros(1), 5.0, method="RK45")
    assert run.status == "failed" and "ZeroDivisionError" in run.reason
    assert run.t[-1] <= 1.0 + 1e-12 and run.t.size > 1


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
    header = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()[0]
    assert header.endswith("phase,c_eps,c_chi")


def test_contact_in_the_full_model_runs_from_the_default_scene(tmp_path, capsys):
    """The steel apparatus with asperities at kappa* = 0.98 touches, then rolls in sliding contact."""
    assert main(["run", "-o", str(tmp_path / "out"), "--set", "contact.kappa_star=0.98",
                 "--set", "contact.psi=0.1", "--t-end", "3", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["model"] == "full" and summary["status"] == "completed"
    assert summary["switches"][0]["from"] == "free" and summary["final"]["kappa"] == 0.98
    header = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()[0]
    assert header.endswith("phase,c_eps,c_chi")


def test_a_varying_minimum_gap_in_the_full_model_is_refused(tmp_path, capsys):
    assert main(["run", "-o", str(tmp_path / "out"), "--set", "contact.kappa_star=0.98",
                 "--set", "contact.roughness_amplitude=0.3", "--set", "contact.roughness_correlation=0.01"]) == 2
    assert "contact.roughness_amplitude" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


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
    header = (tmp_path / "one" / "trajectory.csv").read_text().splitlines()[0]
    assert header.endswith("theta_a,theta_b")


@pytest.mark.parametrize("cavitation", ["half-sommerfeld", "swift-stieber", "jfo"])
def test_steady_rolling_on_a_cavitating_film_is_recognised(cavitation):
    """Section 7: a film that ruptures a few pascals below the bubble's pressure stops the sinking.

    From about 2 s the gap, the angle and the speed stay constant; the classifier
    says so, with the spreads that decided it (the full film of the same scene keeps
    closing and is not steady).
    """
    from dynamics.app.regime import STEADY_SPREAD, classify
    from dynamics.app.run import run_scene
    from dynamics.scenes import load_scene

    base = ["model.forces=reynolds", "model.n=128", "run.t_end=20"]
    scene = load_scene(overrides=[*base, f"cavitation.model={cavitation}", "cavitation.p_cav=101320"])
    regime, evidence = classify(run_scene(scene))
    assert regime == "steady rolling"
    assert evidence["one_minus_kappa_relative_spread_late"] < STEADY_SPREAD
    full_film, evidence = classify(run_scene(load_scene(overrides=base)))
    assert full_film != "steady rolling" and evidence["one_minus_kappa_relative_spread_late"] > 0.3
