"""A run's outputs form one consistent set: concurrent runs, Ctrl-C, a second Ctrl-C, SIGTERM.

These run ``snail run`` in subprocesses and send real signals. A long run is
made long by the run length: the default scene over 2e4 s at rtol 1e-10, with
the gap floor lowered to 1e-15 so that the closing gap does not end it early
(it would reach the default floor 1e-9 at t = 648 s, a few seconds of work); it
takes a minute or more. The run's stderr is a terminal (a pseudo-terminal), so
it draws its progress bar, and a signal is sent only once the bar shows time
advancing: the run is then inside the integration, whatever the time spent
loading compiled code. Every wait is bounded.
"""

import fcntl
import json
import os
import re
import signal
import struct
import subprocess
import sys
import termios
import threading
import time
from pathlib import Path

import pytest

LONG = ["--t-end", "20000", "--set", "run.rtol=1e-10", "--set", "run.gap_floor=1e-10"]


class _Snail:
    """``snail run`` in a subprocess, its stderr on a pseudo-terminal read by a thread."""

    def __init__(self, *args, preexec_fn):
        master, slave = os.openpty()
        # a terminal of 160 columns: with none set the bar is drawn zero columns wide, without its numbers
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 160, 0, 0))
        self.proc = subprocess.Popen([sys.executable, "-m", "dynamics.app.cli", "run", *args],
                                     stdout=subprocess.PIPE, stderr=slave, text=True,
                                     preexec_fn=preexec_fn)
        os.close(slave)
        self._master = master
        self._chunks = []
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        while True:
            try:
                data = os.read(self._master, 4096)
            except OSError:  # the child closed its end
                break
            if not data:
                break
            self._chunks.append(data.decode(errors="replace"))

    @property
    def err(self) -> str:
        return "".join(self._chunks)

    def reached(self) -> float:
        """The largest time the progress bar has shown (s), 0 before it moved."""
        return max((float(n) for n in re.findall(r"\| *([0-9.]+(?:e[+-]?[0-9]+)?)/", self.err)), default=0.0)

    def wait_for_integration(self, timeout=180.0):
        """Return once the progress bar shows the integration past t = 0 (cold compilation included)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.reached() > 0.0:
                return
            assert self.proc.poll() is None, (self.proc.returncode, self.err)
            time.sleep(0.05)
        pytest.fail(f"the run did not start integrating within {timeout} s: {self.err}")

    def finish(self, timeout=120.0) -> str:
        """Wait for the process; its stderr."""
        self.proc.communicate(timeout=timeout)
        self._reader.join(timeout=10.0)
        os.close(self._master)
        return self.err


def _set(folder: Path) -> dict:
    names = sorted(p.name for p in folder.iterdir())
    assert names == ["scene.resolved.toml", "summary.json", "trajectory.csv", "trajectory.png"]
    summary = json.loads((folder / "summary.json").read_text())
    rows = (folder / "trajectory.csv").read_text().splitlines()
    # every-step output: the start and one row per step (no event ends these runs)
    assert len(rows) - 1 == summary["steps"] + 1 or summary["status"] != "completed"
    assert len(rows) > 2
    return summary


def test_a_second_run_into_the_same_folder_is_refused(tmp_path, terminal_child):
    out = tmp_path / "out"
    first = _Snail("-o", str(out), *LONG, preexec_fn=terminal_child)
    try:
        first.wait_for_integration()
        second = subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", str(out)],
                                capture_output=True, text=True, timeout=120, check=False)
        assert second.returncode == 2
        assert "another run is writing to" in second.stderr and "Traceback" not in second.stderr
    finally:
        first.proc.send_signal(signal.SIGINT)
        first.finish()
    summary = _set(out)
    assert summary["status"] == "interrupted" and 0.0 < summary["t_end"] < 20000


@pytest.mark.parametrize(("signals", "by"), [
    pytest.param([signal.SIGINT], "SIGINT", id="ctrl-c"),
    pytest.param([signal.SIGTERM], "SIGTERM", id="sigterm"),
    pytest.param([signal.SIGINT, signal.SIGINT], "SIGINT", id="ctrl-c twice"),
])
def test_an_interrupted_run_leaves_one_complete_set(tmp_path, signals, by, terminal_child):
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "dynamics.app.cli", "run", "-o", str(out), "--t-end", "1"],
                          capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert _set(out)["status"] == "completed"
    run = _Snail("-o", str(out), *LONG, preexec_fn=terminal_child)
    run.wait_for_integration()
    for sig in signals:
        run.proc.send_signal(sig)
        time.sleep(0.2)
    err = run.finish()
    assert "Traceback" not in err
    assert not list(tmp_path.glob(".out.staging-*")) and not list(tmp_path.glob(".out.previous-*"))
    summary = _set(out)
    if len(signals) == 1:  # caught inside the integration: the new set says what happened
        assert summary["status"] == "interrupted" and run.proc.returncode == 1
        assert 0.0 < summary["t_end"] < 20000
        assert by in summary["reason"]
    else:  # a second signal may come after the integration: the previous set, or the new one
        assert summary["status"] in ("completed", "interrupted")
        if summary["status"] == "interrupted":
            assert 0.0 < summary["t_end"] < 20000


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
                          capture_output=True, text=True, timeout=300, cwd=tmp_path, check=False)
    assert done.returncode == 2, done.stderr
    assert words in done.stderr and "Traceback" not in done.stderr
    assert (tmp_path / "full" / "thesis.tex").read_text() == "precious"
    assert sorted(p.name for p in tmp_path.iterdir() if not p.name.startswith(".")) == ["file", "full"]
