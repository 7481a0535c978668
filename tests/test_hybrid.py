"""Hybrid runs (numerics.hybrid): a signal received between two phases stops the run at the switch."""

from __future__ import annotations

import os
import signal

import numpy as np

from numerics.engine import END, INTERRUPTED
from numerics.hybrid import Phase, run_phases
from numerics.jit import jit


@jit
def _climb(t, y, args):
    return np.array([1.0])


@jit
def _climb_jac(t, y, args):
    return np.zeros((1, 1))


@jit
def _top(t, y, args):
    return np.array([y[0] - 1.0])


def _phase(y0) -> Phase:
    """y' = 1 until y = 1, where the "touch" switch starts the next phase from 0."""
    return Phase("free", _climb, _climb_jac, _top, np.zeros(1), np.array([y0]), ("touch",), (1,), (1,),
                 np.array([1e-12]))


def test_a_signal_between_two_phases_stops_the_run_at_the_switch(ctrl_c):
    phases = []

    def columns(phase, t, y, kind):
        phases.append(phase)
        if len(phases) == 2:  # the second phase is done: Ctrl-C before the third starts
            os.kill(os.getpid(), signal.SIGINT)
        return {"phi": y[0]}

    run = run_phases(_phase(0.0), lambda phase, name, t, y, phi: _phase(0.0), columns, 10.0, phi0=0.0,
                     method="radau", rtol=1e-10, max_steps=10_000)
    assert len(phases) == 2 and len(run["switches"]) == 1
    assert run["status"] == -1 and run["code"] == INTERRUPTED and run["stop_event"] == ""
    assert run["message"].startswith("interrupted by SIGINT at t = 2")
    assert abs(run["t"][-1] - 2.0) < 1e-9 and run["kind"][-1] & END
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # the run's handler is gone
