"""trajectory.png: drawn in a child process exactly as in this one, and a failure there is reported."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from dynamics.app.figure_process import FigureProcess
from dynamics.app.figures import figure_png


def _trajectory(n=200):
    t = np.linspace(0.0, 2.0, n)
    phi = np.pi + 0.3 * np.sin(5.0 * t)
    kappa = 1.0 - 0.5 * np.exp(-t)
    columns = {"t": t, "kappa": kappa, "phi": phi, "one_minus_kappa": 1.0 - kappa, "omega_a": np.cos(t),
               "omega_b": np.sin(t), "x_b": 0.01 * t}
    return SimpleNamespace(columns=columns, dimensionless=False, equations="full", forces="closed-form",
                           status="completed", message="reached t_end = 2 s", groups={"s": 0.3, "mu": 1.2},
                           tau=0.1)


def test_the_child_draws_the_same_png_as_this_process():
    trajectory = _trajectory()
    with FigureProcess() as figures:
        drawn = figures.png(trajectory)
    assert drawn[:8] == b"\x89PNG\r\n\x1a\n"
    assert drawn == figure_png(trajectory)


def test_a_trajectory_sent_early_is_drawn_while_this_process_works_on():
    """send() returns before the child has drawn; png() then collects that figure, and only that one."""
    trajectory = _trajectory()
    with FigureProcess() as figures:
        figures.send(trajectory)
        with pytest.raises(ValueError, match="another trajectory"):
            figures.png(_trajectory())
        drawn = figures.png(trajectory)
    assert drawn == figure_png(trajectory)


def test_leaving_while_the_child_draws_stops_it():
    with FigureProcess() as figures:
        figures.send(_trajectory())
        child = figures._child
    assert child.returncode is not None


def test_a_run_that_never_left_t0_is_drawn():
    """A run that failed at its first step has rows at t = 0 only: the log colour scale must still exist."""
    for rows in (1, 2):
        trajectory = _trajectory(rows)
        trajectory.columns = {name: values[:1].repeat(rows) for name, values in trajectory.columns.items()}
        with FigureProcess() as figures:
            drawn = figures.png(trajectory)
        assert drawn == figure_png(trajectory)


def test_a_failure_in_the_child_is_reported_with_its_cause():
    broken = _trajectory()
    del broken.columns["x_b"]
    with FigureProcess() as figures, pytest.raises(RuntimeError, match="drawing trajectory.png failed.*x_b"):
        figures.png(broken)


def test_leaving_without_a_trajectory_stops_the_child():
    with FigureProcess() as figures:
        child = figures._child
    assert child.returncode is not None


@pytest.mark.parametrize(("value", "label"), [(1e-6, "10\u207b\u2076"), (1.0, "10\u2070"), (100.0, "10\u00b2"),
                                              (1e-12, "10\u207b\u00b9\u00b2"), (3e-3, "0.003"), (0.0, "")])
def test_log_axis_labels_are_decades_in_superscript(value, label):
    from dynamics.app.figures import _decade

    assert _decade(value) == label
