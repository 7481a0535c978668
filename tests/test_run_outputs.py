"""A run's outputs form one consistent set: concurrent runs, Ctrl-C, a second Ctrl-C, SIGTERM.

These run ``snail run`` in subprocesses and send real signals. A long run is
made long by the run length (the default scene at 1e4 s takes tens of seconds),
and every wait is bounded.
"""

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

LONG = ["--t-end", "20000", "--set", "run.rtol=1e-10"]


def _snail(*args, **kwargs):
    return subprocess.Popen([sys.executable, "-m", "dynamics.app.cli", "run", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def _wait_for_start(proc, lock_dir: Path, name: str, timeout=60.0):
    """Wait until the run has taken its folder (its staging folder exists)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if list(lock_dir.glob(f".{name}.staging-*")):
            time.sleep(1.0)  # let it get into the integration
            return
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.05)
    pytest.fail("the run did not start")


def _set(folder: Path) -> dict:
    names = sorted(p.name for p in folder.iterdir())
    assert names == ["scene.resolved.toml", "summary.json", "trajectory.csv", "trajectory.png"]
    summary = json.loads((folder / "summary.json").read_text())
    rows = (folder / "trajectory.csv").read_text().splitlines()
    assert len(rows) - 1 == summary["steps"] + 1 or summary["status"] != "completed"
    return summary


def test_a_second_run_into_the_same_folder_is_refused(tmp_path):
    out = tmp_path / "out"
    first = _snail("-o", str(out), *LONG)
    try:
        _wait_for_start(first, tmp_path, "out")
        second = subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", str(out)],
                                capture_output=True, text=True, timeout=120)
        assert second.returncode == 2
        assert "another run is writing to" in second.stderr and "Traceback" not in second.stderr
    finally:
        first.send_signal(signal.SIGINT)
        first.communicate(timeout=120)
    summary = _set(out)
    assert summary["status"] == "interrupted"


@pytest.mark.parametrize(("signals", "by"), [([signal.SIGINT], "SIGINT"), ([signal.SIGTERM], "SIGTERM"),
                                             ([signal.SIGINT, signal.SIGINT], "SIGINT")],
                         ids=["ctrl-c", "sigterm", "ctrl-c twice"])
def test_an_interrupted_run_leaves_one_complete_set(tmp_path, signals, by):
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", str(out), "--t-end", "1"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert _set(out)["status"] == "completed"
    proc = _snail("-o", str(out), *LONG)
    _wait_for_start(proc, tmp_path, "out")
    for sig in signals:
        proc.send_signal(sig)
        time.sleep(0.2)
    _, err = proc.communicate(timeout=120)
    assert "Traceback" not in err
    summary = _set(out)  # the previous complete set, or the new one saying what happened
    if summary["status"] != "completed":
        assert summary["status"] == "interrupted"
        assert summary["t_end"] < 20000
        if len(signals) == 1:
            assert by in summary["reason"]
    assert not list(tmp_path.glob(".out.staging-*")) and not list(tmp_path.glob(".out.previous-*"))


@pytest.mark.parametrize(("where", "words"), [
    ("", "must be a path"),
    ("/proc/snail-output", "cannot write outputs to /proc/snail-output"),
    ("file/inside", "is a file, not a folder"),
    ("file", "is a file, not a folder"),
    ("full", "holds files that are not a run's outputs"),
])
def test_output_paths_that_cannot_be_written_are_bad_input(tmp_path, where, words):
    (tmp_path / "file").write_text("not a folder")
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "thesis.tex").write_text("precious")
    target = where if where.startswith("/") or not where else str(tmp_path / where)
    done = subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", target, "--t-end", "1"],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert words in done.stderr and "Traceback" not in done.stderr
    assert (tmp_path / "full" / "thesis.tex").read_text() == "precious"
    assert sorted(p.name for p in tmp_path.iterdir() if not p.name.startswith(".")) == ["file", "full"]
