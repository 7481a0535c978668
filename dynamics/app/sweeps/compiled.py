"""The compiled loop of the sweeps' batch runner: many runs of the reduced equations (2.11) in one call.

:func:`integrate_points` integrates point after point with the engine's driver
(:func:`numerics.engine.driver.init` and :func:`~numerics.engine.driver.advance`) called directly on
the reduced model's :func:`~dynamics.equations.reduced.rhs_values`,
:func:`~dynamics.equations.reduced.jacobian` and
:func:`~dynamics.equations.reduced.event_values`, compiled into the loop: no Python
per step or per point, no calls through function pointers, and the right-hand side
and events as tuples, which unlike arrays need no allocation. It returns each
run's rows as the driver makes them; :mod:`dynamics.app.sweeps.batch` sets the
runs up and reads their rows.

One point after another, not ``prange`` across them: a sweep already runs one
single-threaded dask worker per core, and threads in each would only compete
for the same cores.

Compilation. The loop compiles with the whole engine inside it (one to two minutes), once
per machine: numba's disk cache keeps it. Numba checks a cached function against
its own file only, so the loop is filed under a name carrying a hash of the other
sources compiled into it (the engine and the reduced model): an edit to any of
them compiles it afresh rather than loading a stale one. :func:`warm` compiles
(or loads) it ahead, so that a sweep's workers only load it.
"""

from __future__ import annotations

import hashlib
import time
import types as pytypes
import warnings
from pathlib import Path

import numpy as np
from numba import objmode, types
from numba.typed import List

from dynamics.equations import reduced
from numerics import engine
from numerics.engine.driver import advance, init
from numerics.engine.state import STATUS, STEPS, STOP_EVENT
from numerics.jit import compile_shared, jit

__all__ = ["RAISED", "integrate_points", "warm"]

#: The status code of a run that raised an exception (the driver's codes are small integers).
RAISED = -100
_MAX_STEPS = 2_000_000  # simulate()'s default, which run_scene keeps


def _loop(y0, args, t_end, rtol, terminal, direction, max_steps):
    """:func:`integrate_points`, compiled; ``max_steps`` per run."""
    count, n = y0.shape
    runs = List()
    status = np.full(count, RAISED, dtype=np.int64)
    stop_event = np.full(count, -1, dtype=np.int64)
    steps = np.zeros(count, dtype=np.int64)
    clock = np.empty(count + 1)
    t_eval = np.zeros(0)
    atol = np.empty(n)
    for i in range(count + 1):
        with objmode(now="float64"):
            now = time.perf_counter()
        clock[i] = now
        if i == count:
            break
        atol[:] = rtol[i]
        try:
            # the model's functions through their module: named here, numba would pass them on as pointers to
            # Python objects, which it does not write to its disk cache
            state = init(reduced.rhs_values, reduced.jacobian, reduced.event_values, args[i], 0.0, y0[i], t_end[i],
                         rtol[i], atol, 0.0, np.inf, max_steps, t_eval, True, terminal[i], direction)
            t, y, kind, event = advance(reduced.rhs_values, reduced.jacobian, reduced.event_values, args[i], state, 0)
            runs.append((t, y, kind, event))
            status[i] = state.counters[STATUS]
            stop_event[i] = state.counters[STOP_EVENT]
            steps[i] = state.counters[STEPS]
        # a point fails alone: the loop goes on
        except Exception:  # noqa: BLE001
            runs.append((np.zeros(0), np.zeros((n, 0)), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)))
    return runs, status, stop_event, steps, clock


def _sources_hash() -> str:
    """A hash of the sources compiled into the loop besides this module: the engine and the reduced model."""
    digest = hashlib.sha256()
    for path in [*sorted(Path(engine.__file__).parent.glob("*.py")), Path(reduced.__file__)]:
        digest.update(path.read_bytes())
    return digest.hexdigest()[:12]


_MATRIX, _VECTOR = types.float64[:, ::1], types.float64[::1]
_SIGNATURE = (_MATRIX, _MATRIX, _VECTOR, _VECTOR, types.int64[:, ::1], types.int64[::1], types.int64)
_COMPILED = []  # the dispatcher, or the exception that stopped its compilation
# Numba's note that the clock's object-mode block takes the GIL: for a moment per point, not during the runs.
_GIL_NOTE = "Code running in object mode won't allow parallel execution"


def warm():
    """The compiled loop, compiled for its one signature or loaded from numba's disk cache.

    Raises
    ------
    Exception
        Whatever stopped the compilation; again at once on later calls, rather than compiling anew.
    """
    if not _COMPILED:
        named = pytypes.FunctionType(_loop.__code__, _loop.__globals__, _loop.__name__)
        named.__qualname__ = f"{_loop.__qualname__}_{_sources_hash()}"
        named.__doc__ = _loop.__doc__
        dispatcher = jit(named)
        try:
            with warnings.catch_warnings():
                warnings.filterwarnings("ignore", message=_GIL_NOTE)
                compile_shared(dispatcher, _SIGNATURE)
        except Exception as err:
            _COMPILED.append(err)
            raise
        dispatcher.disable_compile()
        _COMPILED.append(dispatcher)
    if isinstance(_COMPILED[0], Exception):
        raise _COMPILED[0]
    return _COMPILED[0]


def integrate_points(y0, args, t_end, rtol, terminal, direction) -> tuple:
    """Integrate point i of the reduced equations from ``y0[i]`` over [0, ``t_end[i]``] with ``args[i]``.

    Each run is :func:`numerics.engine.driver.init` and :func:`~numerics.engine.driver.advance` from t = 0 with
    atol = rtol, the first step chosen by the driver, at most 2,000,000 steps,
    and one output row per step.

    Parameters
    ----------
    y0 : ndarray, shape (points, 5)
        Initial states (:func:`dynamics.equations.reduced.initial_state`).
    args : ndarray, shape (points, k)
        :func:`dynamics.equations.reduced.run_args` of each point.
    t_end, rtol : ndarray, shape (points,)
    terminal : ndarray of int, shape (points, 5)
        Per point and event, as :func:`numerics.engine.driver.init` takes it.
    direction : ndarray of int, shape (5,)
        Per event, the same for every point.

    Returns
    -------
    runs : list of (t, y, kind, event)
        Each run's rows, as :func:`numerics.engine.driver.advance` returns them (none if it raised).
    status, stop_event, steps : ndarray of int, shape (points,)
        The driver's status code (:data:`RAISED` if the run raised), the index of the
        event that stopped the run (-1 if none), and the accepted steps.
    clock : ndarray, shape (points + 1,)
        ``time.perf_counter()`` before each run and after the last.
    """
    loop = warm()
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=_GIL_NOTE)  # on the first call: the clock's block compiles
        return loop(np.ascontiguousarray(y0, dtype=float), np.ascontiguousarray(args, dtype=float),
                    np.ascontiguousarray(t_end, dtype=float), np.ascontiguousarray(rtol, dtype=float),
                    np.ascontiguousarray(terminal, dtype=np.int64), np.ascontiguousarray(direction, dtype=np.int64),
                    _MAX_STEPS)
