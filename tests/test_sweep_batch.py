"""The sweeps' batch runner: the reduced points integrated together give the rows of one point at a time.

The batch (:mod:`dynamics.app.sweeps.batch`) runs the same driver on the same
functions with the same settings as :func:`dynamics.simulation.simulate`, so each
run takes the same steps and its rows are equal to rounding: the regimes, the
step counts and the integers exactly, the numbers to 1e-12 relative (far below
rtol = 1e-6, where a different step sequence would show).
"""

import math
import tomllib

import numpy as np
import pytest

from dynamics.app.run import run_scene
from dynamics.app.sweeps import batch
from dynamics.app.sweeps.point import classify_point, run_point
from dynamics.app.sweeps.spec import overrides, point_key
from dynamics.scenes import SceneError, parse_scene

# mu_ = 1 and Upsilon = 1 as in the paper's figures 2 (s = 1/4 rocks) and 3 (s = 0.9 runs away).
DIMENSIONLESS = tomllib.loads("""
[groups]
s = 0.25
upsilon = 1.0
mu = 1.0
[model]
equations = "reduced"
[initial]
kappa = 0.5
[run]
t_end_tau = 100.0
rtol = 1e-6
""")

# The reduced equations on a physical device: rates in 1/s, times in s, and a Reynolds limit that can stop the run.
PHYSICAL = tomllib.loads("""
[apparatus]
preset = "steel"
[fluid]
nu = "200 cSt"
[incline]
alpha = "2.4 deg"
[initial]
kappa = 0.5
phi = 0.5
[model]
equations = "reduced"
[run]
t_end = "3 s"
rtol = 1e-7
""")

# (point, what the per-point path makes of it (None: any), which path the batch takes): "loop", the compiled loop;
# "alone", run_point; "loop, then alone": a run that failed in the loop, run again alone to say why.
DIMENSIONLESS_POINTS = [
    ({"groups.s": 0.25}, "rocking", "loop"),
    ({"groups.s": 0.25, "groups.upsilon": 10.0, "initial.kappa": 0.9}, "rocking", "loop"),
    ({"groups.s": 0.0, "initial.kappa": 0.2}, "sedimenting", "loop"),
    ({"groups.s": 1.1, "initial.kappa": 0.3}, "runaway", "loop"),  # stopped after max_turns
    ({"groups.s": 1.1, "groups.upsilon": 10.0}, "runaway", "loop"),  # still accelerating at t_end
    ({"groups.s": 0.25, "run.t_end_tau": 2.0}, "transient", "loop"),
    ({"groups.s": 1e300}, "failed", "loop, then alone"),  # the engine raises
    ({"initial.omega_b": 1e308, "initial.omega_a": -1e308}, "failed", "alone"),  # refused by the scene's range
    ({"initial.kappa_dot": 0.1}, "failed", "alone"),  # refused by the scene
    ({"initial.one_minus_kappa": 1e-10}, "failed", "alone"),  # refused by simulate: below the gap floor
    ({"run.output_interval_tau": 1.0}, "rocking", "alone"),  # sampled output
    ({"groups.s": 0.3, "contact.kappa_star": 0.9, "contact.psi": 0.5}, "locked rolling", "alone"),  # contact
]
PHYSICAL_POINTS = [
    ({"fluid.nu": "1000 cSt"}, "rocking", "loop"),
    ({"fluid.nu": "1000 cSt", "initial.omega_a": -0.5, "initial.omega_b": 0.5}, "rocking", "loop"),
    ({"fluid.nu": "1000 cSt", "incline.alpha": "15 deg"}, "runaway", "loop"),  # stopped after max_turns
    # stopped at max_gap_reynolds: its regime is the classification's call on a run cut short
    ({"fluid.nu": "500 cSt", "incline.alpha": "15 deg"}, None, "loop"),
    ({"fluid.nu": "20 cSt", "run.on_invalid": "warn"}, "rocking", "loop"),  # goes on past max_gap_reynolds
    ({}, "failed", "alone"),  # past max_gap_reynolds at the start: refused by simulate
]


def assert_same_rows(got: list[dict], expected: list[dict]) -> None:
    for row, alone in zip(got, expected, strict=True):
        assert row.keys() == alone.keys()
        for key, value in alone.items():
            if key == "wall_time_s":
                assert row[key] > 0
            elif isinstance(value, float) and not isinstance(value, bool):
                assert math.isclose(row[key], value, rel_tol=1e-12, abs_tol=1e-12) or (
                    math.isnan(value) and math.isnan(row[key])), (key, row, alone)
            else:
                assert row[key] == value, (key, row, alone)


def batchable(base, point) -> bool:
    try:
        return batch.problem(parse_scene(base, "[base]", overrides(point))) is not None
    except SceneError:
        return False


@pytest.fixture
def alone_calls(monkeypatch):
    """The points the batch hands to run_point."""
    calls = []

    def recorded(base, point, source="[base]"):
        calls.append(point)
        return run_point(base, point, source)

    monkeypatch.setattr(batch, "run_point", recorded)
    return calls


@pytest.mark.parametrize(("base", "cases"), [(DIMENSIONLESS, DIMENSIONLESS_POINTS), (PHYSICAL, PHYSICAL_POINTS)])
def test_the_batch_gives_the_rows_of_one_point_at_a_time(base, cases, alone_calls):
    points = [point for point, _, _ in cases]
    expected = [run_point(base, point) for point in points]
    assert [r["regime"] for r in expected] == [regime or r["regime"] for r, (_, regime, _) in zip(expected, cases)]
    rows = batch.run_batch(base, "[base]", points)
    assert_same_rows(rows, expected)
    assert sorted(map(point_key, alone_calls)) == sorted(point_key(point) for point, _, path in cases if path != "loop")
    assert [batchable(base, point) for point in points] == [path != "alone" for _, _, path in cases]


@pytest.mark.parametrize(("base", "point"), [
    # phi from a start at kappa = 0, where it is undefined, through many quarter turns
    (DIMENSIONLESS, {"groups.s": 1.1, "initial.kappa": 0.0, "initial.phi": 7.0}),
    (PHYSICAL, {"fluid.nu": "1000 cSt", "initial.phi": -4.0, "initial.omega_a": -0.5, "initial.omega_b": 0.5}),
])
def test_the_batch_classifies_the_columns_of_simulate(base, point, monkeypatch):
    seen = []

    def spy(trajectory):
        seen.append(trajectory)
        return classify_point(trajectory)

    monkeypatch.setattr(batch, "classify_point", spy)
    batch.run_batch(base, "[base]", [point])
    trajectory = run_scene(parse_scene(base, "[base]", overrides(point)))
    (batched,) = seen
    assert (batched.tau, batched.status, batched.event) == (trajectory.tau, trajectory.status, trajectory.event)
    for name, column in batched.columns.items():
        np.testing.assert_allclose(column, trajectory.columns[name], rtol=1e-12, atol=1e-12, err_msg=name)


def test_the_sample_covers_every_ending():
    rows = [*batch.run_batch(PHYSICAL, "[base]", [point for point, _, _ in PHYSICAL_POINTS]),
            *batch.run_batch(DIMENSIONLESS, "[base]", [point for point, _, _ in DIMENSIONLESS_POINTS])]
    endings = {(r["status"], r["stop_event"]) for r in rows if r["status"] != "failed"}
    assert endings == {("completed", ""), ("stopped", "runaway"), ("stopped", "reynolds")}
    assert all(r["steps"] > 0 and r["reason"] == "" for r in rows if r["status"] != "failed")
    assert all(r["reason"] for r in rows if r["status"] == "failed")


def test_when_the_compiled_loop_fails_every_point_runs_alone(monkeypatch, alone_calls):
    def broken(*inputs):
        raise MemoryError("no room for the rows")

    monkeypatch.setattr(batch, "integrate_points", broken)
    points = [point for point, _, _ in DIMENSIONLESS_POINTS[:3]]
    rows = batch.run_batch(DIMENSIONLESS, "[base]", points)
    assert alone_calls == points
    assert [r["regime"] for r in rows] == ["rocking", "rocking", "sedimenting"]
