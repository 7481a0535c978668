"""The Python face of the engine: checked inputs, a run in chunks, and a result like scipy's.

:func:`integrate` checks the inputs (:func:`check_inputs`), takes the driver
compiled for the type of ``args`` (:func:`numerics.engine.compiled.engine_for`),
and runs it in chunks of ``chunk_steps`` steps, between which it reports progress
and notices Ctrl-C; chunks do not change the result.
"""

from __future__ import annotations

import signal
import threading
from dataclasses import dataclass, field

import numba
import numpy as np

from .compiled import engine_for, first_class
from .driver import END, EVENT, no_events
from .state import (
    MAX_STEPS_REACHED,
    NEWTON_FAILED,
    NFEV,
    NJEV,
    NLU,
    NON_FINITE,
    PAUSED,
    REACHED_END,
    REJECTED,
    STATUS,
    STEP_TOO_SMALL,
    STEPS,
    STOP_EVENT,
    TERMINAL_EVENT,
    T,
)

__all__ = ["INTERRUPTED", "Interrupts", "Result", "check_inputs", "integrate", "stop_message"]

EPS = np.finfo(float).eps
#: Status of a run stopped by Ctrl-C between two chunks (set by :func:`integrate` only).
INTERRUPTED = -5


def stop_message(code: int, t: float, event: int = -1, by: str = "") -> str:
    """A sentence saying why a run stopped at time ``t``."""
    messages = {
        REACHED_END: f"reached t_end = {t:.17g}",
        TERMINAL_EVENT: f"terminal event {event} at t = {t:.17g}",
        PAUSED: f"paused at t = {t:.17g}",
        MAX_STEPS_REACHED: f"max_steps accepted steps taken by t = {t:.17g}",
        STEP_TOO_SMALL: f"the step size fell below the rounding level of t at t = {t:.17g}",
        NEWTON_FAILED: f"the Newton iteration failed repeatedly, down to the smallest step, at t = {t:.17g}",
        NON_FINITE: f"the right-hand side or its Jacobian was not finite at t = {t:.17g}",
        INTERRUPTED: f"interrupted{' by ' + by if by else ''} at t = {t:.17g}",
    }
    return messages[code]


@dataclass
class Result:
    """A run of the engine, after scipy's ``OdeResult``.

    Attributes
    ----------
    t : ndarray, shape (k,)
        Times of the output rows.
    y : ndarray, shape (n, k)
        States of the output rows.
    kind : ndarray of int, shape (k,)
        Row flags (``driver.START | STEP | SAMPLE | EVENT | END``).
    event : ndarray of int, shape (k,)
        Event index of EVENT rows, -1 elsewhere.
    t_events : list of ndarray
        For each event, the times it occurred.
    y_events : list of ndarray, shape (occurrences, n)
        For each event, the states there.
    status : int
        As scipy: 0 reached t_end, 1 terminal event, -1 failed or stopped early.
    code : int
        Detailed stop reason (the driver's status codes, or :data:`INTERRUPTED`).
    message : str
    success : bool
        status >= 0.
    stop_event : int
        Index of the terminal event, -1 if none.
    nfev, njev, nlu, steps, rejected : int
        Right-hand side and Jacobian evaluations, LU decompositions, accepted
        and rejected steps.
    state : State
        The final state (``driver.advance`` can continue it if ``code`` is PAUSED).
    """

    t: np.ndarray
    y: np.ndarray
    kind: np.ndarray
    event: np.ndarray
    t_events: list
    y_events: list
    status: int
    code: int
    message: str
    success: bool
    stop_event: int
    nfev: int
    njev: int
    nlu: int
    steps: int
    rejected: int
    state: object = field(repr=False)


def _int_per_event(value, m: int, name: str) -> np.ndarray:
    if type(value) is tuple and len(value) == m and all(type(v) is int for v in value):  # as the hybrid phases give
        return np.array(value, dtype=np.int64)
    array = np.broadcast_to(np.asarray(value), (m,)) if np.ndim(value) == 0 else np.asarray(value)
    if array.shape != (m,):
        msg = f"{name} must be a scalar or have one entry per event ({m}), got shape {array.shape}"
        raise ValueError(msg)
    as_int = array.astype(np.int64)
    if not np.array_equal(as_int, array):
        msg = f"{name} must hold integers (or booleans), got {array}"
        raise ValueError(msg)
    return as_int.copy()


def check_inputs(fun, jac, events, t_span, y0, *, args=None, rtol=1e-6, atol=1e-9, t_eval=None, steps=None,
                 terminal=0, direction=0, first_step=None, max_step=np.inf, max_steps=1_000_000):
    """Check and normalise the inputs of a run; returns the keyword arguments of ``driver.init``.

    Raises
    ------
    ValueError
        Naming the parameter and its allowed range. ``rtol`` below 100 eps is
        refused (scipy raises it with a warning instead): at that level the
        error estimate is rounding noise and the Newton tolerance collapses.
    """
    t0, t_end = (float(v) for v in t_span)
    if not (np.isfinite(t0) and np.isfinite(t_end) and t_end > t0):
        msg = f"t_span must be (t0, t_end) with finite t_end > t0, got {t_span}"
        raise ValueError(msg)
    y0 = np.array(y0, dtype=float)
    if y0.ndim != 1 or y0.size == 0:
        msg = f"y0 must be a non-empty 1-D array, got shape {y0.shape}"
        raise ValueError(msg)
    if not np.isfinite(y0).all():
        msg = "y0 must be finite"
        raise ValueError(msg)
    n = y0.size
    rtol = float(rtol)
    if not 100 * EPS <= rtol < 1.0:
        msg = f"rtol must be in [100 eps, 1) = [{100 * EPS:.3g}, 1), got {rtol}"
        raise ValueError(msg)
    atol = np.array(np.broadcast_to(np.asarray(atol, dtype=float), (n,)) if np.ndim(atol) == 0
                    else np.asarray(atol, dtype=float))
    if atol.shape != (n,) or not np.isfinite(atol).all() or not (atol > 0).all():
        msg = f"atol must be positive and finite, a scalar or of shape ({n},), got {atol}"
        raise ValueError(msg)
    if first_step is None:
        first_step = 0.0
    elif not 0.0 < float(first_step) <= t_end - t0:
        msg = f"first_step must be in (0, t_end - t0] = (0, {t_end - t0:g}], got {first_step}"
        raise ValueError(msg)
    max_step = float(max_step)
    if not max_step > 0.0:
        msg = f"max_step must be positive, got {max_step}"
        raise ValueError(msg)
    if int(max_steps) != max_steps or max_steps < 1:
        msg = f"max_steps must be an integer >= 1, got {max_steps}"
        raise ValueError(msg)
    every_step = t_eval is None if steps is None else bool(steps)
    t_eval = np.zeros(0) if t_eval is None else np.array(t_eval, dtype=float)
    if t_eval.ndim != 1 or not np.isfinite(t_eval).all() or (t_eval[1:] <= t_eval[:-1]).any():
        msg = "t_eval must be a 1-D array of finite, strictly increasing times"
        raise ValueError(msg)
    if t_eval.size and (t_eval[0] < t0 or t_eval[-1] > t_end):
        msg = f"t_eval must lie in [t0, t_end] = [{t0:g}, {t_end:g}]"
        raise ValueError(msg)
    if args is None:
        args = np.zeros(0)
    f0 = np.asarray(fun(t0, y0, args))
    if f0.shape != (n,):
        msg = f"fun must return shape ({n},), got {f0.shape}"
        raise ValueError(msg)
    j0 = np.asarray(jac(t0, y0, args))
    if j0.shape != (n, n):
        msg = f"jac must return shape ({n}, {n}), got {j0.shape}"
        raise ValueError(msg)
    g0 = np.asarray(events(t0, y0, args))
    if g0.ndim != 1:
        msg = f"events must return a 1-D array, got shape {g0.shape}"
        raise ValueError(msg)
    m = g0.size
    terminal = _int_per_event(terminal, m, "terminal")
    if (terminal < 0).any():
        msg = f"terminal must be >= 0 (False, True or a count of occurrences), got {terminal}"
        raise ValueError(msg)
    direction = _int_per_event(direction, m, "direction")
    if not (np.abs(direction) <= 1).all():  # not np.isin, slow on a few entries: a hybrid run checks every phase
        msg = f"direction must be -1, 0 or +1 per event, got {direction}"
        raise ValueError(msg)
    return {"t0": t0, "y0": y0, "t_end": t_end, "rtol": rtol, "atol": atol,
            "first_step": float(first_step), "max_step": max_step, "max_steps": int(max_steps),
            "t_eval": t_eval, "every_step": every_step, "terminal": terminal, "direction": direction}


class Interrupts:
    """Within ``with``: SIGINT (Ctrl-C) and SIGTERM set :attr:`received` instead of ending the process.

    A run checks it between chunks of steps and stops there with what it
    computed. Only in the main thread, and only for a signal whose handler is
    the default one or says it stops a program as Ctrl-C does (an attribute
    ``interrupts_runs`` set true, as the command line's SIGTERM handler has): a
    program that handles a signal otherwise keeps it. Within another
    ``Interrupts`` (a hybrid run around its phases' runs), the outer one notes
    the signal and the inner reads it there, with no handler of its own to set.
    """

    def __init__(self):
        self._received = ""
        self._outer = None
        self._previous = {}

    @property
    def received(self) -> str:
        """The name of the first signal received ("" if none)."""
        return self._received or (self._outer.received if self._outer is not None else "")

    @received.setter
    def received(self, name: str):
        self._received = name

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            for sig, default in ((signal.SIGINT, signal.default_int_handler), (signal.SIGTERM, signal.SIG_DFL)):
                handler = signal.getsignal(sig)
                outer = getattr(handler, "__self__", None)
                if isinstance(outer, Interrupts):
                    self._outer = outer
                elif handler is default or getattr(handler, "interrupts_runs", False):
                    self._previous[sig] = signal.signal(sig, self._note)
        return self

    def _note(self, signum, frame):
        self._received = self._received or signal.Signals(signum).name

    def __exit__(self, *exc):
        for sig, handler in self._previous.items():
            signal.signal(sig, handler)
        return False


_VECTOR_TYPE = numba.typeof(np.zeros(1))


def _args_type(args):
    """numba's type of ``args``: at once for a float64 vector as the models pack theirs (numba.typeof takes
    longer than a short phase's setting up), else looked up."""
    if (type(args) is np.ndarray and args.dtype == np.float64 and args.ndim == 1 and args.flags.c_contiguous
            and args.flags.writeable and args.flags.aligned):
        return _VECTOR_TYPE
    return numba.typeof(args)


def integrate(fun, jac, t_span, y0, *, args=None, rtol=1e-6, atol=1e-9, events=None, terminal=0,
              direction=0, t_eval=None, steps=None, first_step=None, max_step=np.inf, max_steps=1_000_000,
              chunk_steps=10_000, progress=None) -> Result:
    """Integrate y' = fun(t, y, args) over ``t_span`` with the compiled Radau IIA engine.

    Parameters
    ----------
    fun, jac : numba-compiled functions
        ``fun(t, y, args)`` -> ndarray (n,); ``jac(t, y, args)`` -> ndarray (n, n).
    t_span : (float, float)
        (t0, t_end), t_end > t0.
    y0 : array_like, shape (n,)
    args : numba-typable, optional
        Passed to ``fun``, ``jac`` and ``events``; an empty float64 array by
        default. The driver is compiled once per numba type of ``args``: a
        float64 array serves most models.
    rtol : float
        In [100 eps, 1).
    atol : float or array_like, shape (n,)
        Positive. The local error is kept below atol + rtol |y| (RMS over components).
    events : numba-compiled function, optional
        ``events(t, y, args)`` -> ndarray (m,); none by default.
    terminal, direction : int or array_like, shape (m,)
        Per event: the occurrence that ends the run (0: never; True: the first),
        and the sign of crossings that count (+1, -1, 0 for both), as in scipy.
    t_eval : array_like, optional
        Increasing output times in [t0, t_end] from the dense output.
    steps : bool, optional
        Output every accepted step too; by default only when ``t_eval`` is not
        given. Rows carry their kind (``driver.STEP``, ``SAMPLE``, ...).
    first_step, max_step : float, optional
        Initial step (chosen automatically by default) and largest step.
    max_steps : int
        Accepted steps after which the run stops unfinished.
    chunk_steps : int
        Steps per compiled call; between calls ``progress(t)`` is called and
        Ctrl-C stops the run with what it computed (``code`` INTERRUPTED).
        Chunking does not change the result.
    progress : callable, optional

    Returns
    -------
    Result
    """
    if events is None:
        events = no_events
    if args is None:
        args = np.zeros(0)
    if int(chunk_steps) != chunk_steps or chunk_steps < 1:
        msg = f"chunk_steps must be an integer >= 1, got {chunk_steps}"
        raise ValueError(msg)
    inputs = check_inputs(fun, jac, events, t_span, y0, args=args, rtol=rtol, atol=atol, t_eval=t_eval,
                          steps=steps, terminal=terminal, direction=direction, first_step=first_step,
                          max_step=max_step, max_steps=max_steps)
    args_type = _args_type(args)
    engine = engine_for(args, args_type)
    fun, jac, events = first_class(fun, jac, events, args, args_type)
    state = engine.init(fun, jac, events, args, **inputs)
    pieces = []
    with Interrupts() as interrupts:
        while True:
            pieces.append(engine.advance(fun, jac, events, args, state, int(chunk_steps)))
            if state.counters[STATUS] != PAUSED:
                break
            if progress is not None:
                progress(float(state.scalars[T]))
            if interrupts.received:
                break
    code = int(state.counters[STATUS])
    t = np.concatenate([p[0] for p in pieces])
    y = np.concatenate([p[1] for p in pieces], axis=1)
    kind = np.concatenate([p[2] for p in pieces])
    event = np.concatenate([p[3] for p in pieces])
    if code == PAUSED:  # stopped between chunks: mark where
        code = INTERRUPTED
        t = np.append(t, state.scalars[T])
        y = np.concatenate([y, state.y[:, None]], axis=1)
        kind = np.append(kind, END)
        event = np.append(event, -1)
    stop_event = int(state.counters[STOP_EVENT])
    m = state.g.size
    on_event = (kind & EVENT) != 0
    t_events = [t[on_event & (event == i)] for i in range(m)]
    y_events = [y[:, on_event & (event == i)].T for i in range(m)]
    status = 0 if code == REACHED_END else 1 if code == TERMINAL_EVENT else -1
    counters = state.counters
    return Result(t=t, y=y, kind=kind, event=event, t_events=t_events, y_events=y_events,
                  status=status, code=code,
                  message=stop_message(code, float(state.scalars[T]), stop_event, interrupts.received),
                  success=status >= 0, stop_event=stop_event, nfev=int(counters[NFEV]),
                  njev=int(counters[NJEV]), nlu=int(counters[NLU]), steps=int(counters[STEPS]),
                  rejected=int(counters[REJECTED]), state=state)
