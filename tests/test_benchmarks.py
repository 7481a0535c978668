"""The benchmarks: every script imports, and the harness they share times, interleaves and writes as it says.

The harness runs here on trivial functions with a clock that the test advances
itself, so that medians, extremes and calibration are exact numbers.
"""

from __future__ import annotations

import ast
import importlib
import json
import pkgutil
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import benchmarks
from benchmarks import harness

MODULES = sorted(m.name for m in pkgutil.iter_modules(benchmarks.__path__))


class FakeClock:
    """A clock that moves only when told: ``advance(seconds)``; the same reading for wall and thread time."""

    def __init__(self):
        self.now = 0.0

    def __call__(self) -> float:
        return self.now

    def advance(self, seconds: float) -> None:
        self.now += seconds


@pytest.fixture
def clock(monkeypatch) -> FakeClock:
    fake = FakeClock()
    monkeypatch.setattr(harness, "time", SimpleNamespace(perf_counter=fake, thread_time=fake))
    return fake


@pytest.mark.parametrize("name", MODULES)
def test_every_benchmark_imports(name):
    module = importlib.import_module(f"benchmarks.{name}")
    assert name == "harness" or callable(getattr(module, "run", None)) or callable(getattr(module, "run_map", None))


def test_no_benchmark_imports_another_benchmarks_private_names():
    """Timing and publishing come from the public harness, read from the sources (a lazy import counts too)."""
    wrong = []
    for path in sorted(Path(benchmarks.__file__).parent.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("benchmarks"):
                wrong += [(path.name, node.module, a.name) for a in node.names
                          if a.name.startswith("_") or node.module.split(".")[-1].startswith("_")]
    assert not wrong


def test_repeat_warms_up_once_then_reports_median_and_extremes(clock):
    durations = iter([100.0, 3.0, 1.0, 2.0, 5.0, 4.0])  # the first is the warm-up's, never reported
    calls = []

    def call():
        calls.append(len(calls))
        clock.advance(next(durations))
        return len(calls)

    timed = harness.repeat(call, 5)
    assert len(calls) == 6
    assert timed.seconds == [3.0, 1.0, 2.0, 5.0, 4.0]
    assert (timed.median, timed.fastest, timed.slowest) == (3.0, 1.0, 5.0)
    assert timed.result == 6  # what the last timed call returned


def test_repeat_takes_a_cheaper_warm_up(clock):
    warmed = []
    timed = harness.repeat(lambda: clock.advance(2.0), 3, warm_up=lambda: warmed.append(True))
    assert warmed == [True] and timed.seconds == [2.0, 2.0, 2.0]


def test_spread():
    assert harness.spread([4.0, 1.0, 3.0, 2.0]) == {"median": 2.5, "min": 1.0, "max": 4.0}


def test_interleave_visits_every_configuration_once_per_round_in_the_seeded_order():
    configs = ["a", "b", "c", "d"]
    order = []

    def call(config):
        order.append(config)
        return len(order)

    results = harness.interleave(configs, 3, np.random.default_rng(7), call)
    shuffled = np.random.default_rng(7)
    expected = [configs[i] for _ in range(3) for i in shuffled.permutation(len(configs))]
    assert order == expected
    for k in range(3):  # every round is a permutation of all configurations
        assert sorted(order[4 * k:4 * k + 4]) == configs
    # each configuration's results in the order of its rounds: the positions at which it was called, plus one
    assert results == {c: [i + 1 for i, o in enumerate(order) if o == c] for c in configs}


def test_timer_calibrates_batches_and_time_all_summarises_per_call(clock):
    per_call = {"fast": 1e-4, "slow": 1e-3}
    timers = []
    for key, cost in per_call.items():
        def batch(calls, cost=cost):
            clock.advance(cost * calls)
            return [0.25 * cost * calls, 0.75 * cost * calls]
        timers.append(harness.Timer(key, batch, stages=("setup", "solve")))
    times = harness.time_all(timers, rounds=5, batch_seconds=0.01, rng=np.random.default_rng(0))
    assert set(times) == {"fast", "slow"}
    for key, cost in per_call.items():
        summary = times[key]
        assert summary["calls_per_sample"] * cost >= 0.01  # a sample lasts at least batch_seconds
        assert summary["total"] == pytest.approx(cost, rel=1e-12)
        assert summary["fastest"] == pytest.approx(cost, rel=1e-12)
        assert summary["slowest"] == pytest.approx(cost, rel=1e-12)
        assert summary["setup"] == pytest.approx(0.25 * cost, rel=1e-12)
        assert summary["solve"] == pytest.approx(0.75 * cost, rel=1e-12)
        assert summary["cpu"] == pytest.approx(cost, rel=1e-12)  # the fake thread clock moved with the wall
    assert all(len(t.wall) == 5 for t in timers)


def test_timer_median_is_of_the_samples(clock):
    per_call = iter([1.0, 9.0, 2.0])
    timer = harness.Timer("t", lambda calls: [next(per_call) * calls])
    timer.calls = 2
    for _ in range(3):
        timer.sample()
    summary = timer.summary()
    assert (summary["total"], summary["fastest"], summary["slowest"]) == (2.0, 1.0, 9.0)


def test_publish_writes_the_json_and_the_markdown_whole(tmp_path, capsys):
    results = {"machine": harness.machine(), "rows": [{"n": 8, "seconds": 1.5e-6}]}
    harness.publish("trivial", results, "| n | us |\n|---|---|\n| 8 | 1.5 |", folder=tmp_path)
    assert json.loads((tmp_path / "trivial.json").read_text()) == results
    assert (tmp_path / "trivial.md").read_text() == "| n | us |\n|---|---|\n| 8 | 1.5 |\n"
    assert "| 8 | 1.5 |" in capsys.readouterr().out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["trivial.json", "trivial.md"]  # nothing half-written


def test_machine_and_speed_gauge():
    assert {"cpu", "cores", "platform", "python", "numpy", "scipy", "numba"} <= set(harness.machine())
    assert harness.speed_gauge_ms(10_000) > 0.0


def test_the_ensembles_tolerance_changes_pair_realisations_by_seed(tmp_path):
    """Per statistic: the largest change of one realisation in units of the spread across realisations, and the
    change of the ensemble's mean in units of its standard error, seeds paired whatever the rows' order."""
    from benchmarks.ensemble import _tolerance_changes
    from dynamics.ensemble import UNSTEADINESS

    default, fast = {0: 1.0, 1: 2.0, 2: 4.0, 3: 5.0}, {3: 5.1, 1: 2.5, 0: 1.0, 2: 4.0}
    for folder, values in (("default", default), ("fast", fast)):
        (tmp_path / folder / "out").mkdir(parents=True)
        lines = ["contact.seed," + ",".join(UNSTEADINESS)]
        lines += [f"{seed}," + ",".join([str(value)] * len(UNSTEADINESS)) for seed, value in values.items()]
        (tmp_path / folder / "out" / "sweep.csv").write_text("\n".join(lines) + "\n")
    changes = _tolerance_changes(tmp_path / "default", tmp_path / "fast")
    sd = np.sqrt((2.0**2 + 1.0**2 + 1.0**2 + 2.0**2) / 3.0)  # about the mean 3
    for name in UNSTEADINESS:
        assert changes[name]["sd"] == pytest.approx(sd)
        assert changes[name]["largest_change"] == pytest.approx(0.5)  # seed 1
        assert changes[name]["in_sd"] == pytest.approx(0.5 / sd)
        assert changes[name]["mean_change_in_se"] == pytest.approx((0.5 + 0.1) / 4.0 / (sd / 2.0))
