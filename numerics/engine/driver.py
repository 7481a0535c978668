"""The integration loop: output rows, events, stop reasons, counts, pausing and resuming.

:func:`init` sets up a :class:`~numerics.engine.state.State` at (t0, y0);
:func:`advance` takes Radau steps (:func:`numerics.engine.radau.step`) from it
until the run ends or ``chunk_steps`` steps are taken, and returns the output
rows of those steps. They take the model's ``fun``, ``jac`` and ``events`` as
arguments. From Python, call them through
:func:`numerics.engine.compiled.engine_for`, compiled once for all models and
cached. Compiled code may call them directly,

    @jit
    def run_model(y0, t_end, args):
        s = init(rhs, rhs_jacobian, contact_events, args, 0.0, y0, t_end, ...)
        return advance(rhs, rhs_jacobian, contact_events, args, s, 0)

which compiles the whole loop for that model inside the caller. Call both from
that one function: numba optimises the code of every function a compiled
function calls once more with it, so each layer of callers around the loop
costs the loop's optimisation again. A compiled function handed on as a value
is a pointer to a Python object, which numba does not write to its disk cache:
such a caller compiles again in every process.

Output rows. Each row is (t, y, kind, event); ``kind`` is a sum of flags: START
(the initial state, when every step is output or t0 is a requested time), STEP
(an accepted step, when every step is output), SAMPLE (a requested time, from the
dense output), EVENT (``event`` is its index; -1 on other rows) and END (where the
run stopped). Steps and requested times may be output together. Rows come in time
order; at a common time a sample precedes an event, and both precede the step
they fall in. The
end flag is set on the last row when the run reached ``t_end`` or a terminal event
there; a run that fails (or reaches ``max_steps``) gets an extra END row at its
last accepted point, so in every-step output that state appears twice.

Events. Event i fires in a step (t_old, t_new] when g_i goes from negative to
zero or positive (``direction`` >= 0) or from positive to zero or negative
(``direction`` <= 0); so a g_i that is exactly zero at the start of a step cannot
fire in it: not at t0, and not twice for a root that fell on a step's end. The
root is found on the step's dense output (:mod:`numerics.engine.roots`); events
of one step are handled earliest first. Event i is terminal when ``terminal[i]``
> 0: its ``terminal[i]``-th occurrence ends the run there, with the state at the
event. (scipy's ``solve_ivp`` instead lets an event that starts at zero fire at
t0.)
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from numerics.jit import jit

from .borrow import borrow
from .radau import (
    copy_into,
    dense_eval,
    evaluate,
    evaluate_jacobian,
    initial_step,
    newton_tolerance,
    step,
)
from .roots import event_root
from .state import (
    CURRENT_JAC,
    EVERY_STEP,
    H_ABS,
    MAX_STEP,
    MAX_STEPS,
    MAX_STEPS_REACHED,
    NEWTON_TOL,
    NFEV,
    NJEV,
    NON_FINITE,
    PAUSED,
    REACHED_END,
    RTOL,
    RUNNING,
    STARTED,
    STATUS,
    STEPS,
    STOP_EVENT,
    T_END,
    T_EVAL_POS,
    T_OLD,
    TERMINAL_EVENT,
    T,
    new_state,
)

__all__ = ["END", "EVENT", "SAMPLE", "START", "STEP", "advance", "init", "no_events"]

# Row kinds (flags, a row may carry several). Numpy integers, so that numba does not
# compile a separate version of every function they are passed to for each value.
START = np.int64(1)
STEP = np.int64(2)
SAMPLE = np.int64(4)
EVENT = np.int64(8)
END = np.int64(16)
NO_EVENT = np.int64(-1)
FIRST_CAPACITY = np.int64(64)

#: Output rows being collected; ``count[0]`` rows are filled. Room is made before a
#: step's rows are written (a larger copy between passes of :func:`advance`), so that
#: writing never reallocates.
Rows = namedtuple("Rows", ["t", "y", "kind", "event", "count"])


@jit
def no_events(t, y, args):
    """The event function of a run without events: m = 0."""
    return np.empty(0)


@jit(cache=False)
def _new_rows(n, capacity):
    return Rows(np.empty(capacity), np.empty((capacity, n)), np.zeros(capacity, dtype=np.int64),
                np.full(capacity, -1, dtype=np.int64), np.zeros(1, dtype=np.int64))


@jit(cache=False)
def _grown(rows, more):
    """A copy of ``rows`` with room for ``more`` rows besides those filled, at least twice the capacity."""
    k = rows.count[0]
    bigger = _new_rows(rows.y.shape[1], max(2 * rows.t.shape[0], k + more))
    for r in range(k):
        bigger.t[r] = rows.t[r]
        bigger.kind[r] = rows.kind[r]
        bigger.event[r] = rows.event[r]
        for j in range(rows.y.shape[1]):
            bigger.y[r, j] = rows.y[r, j]
    bigger.count[0] = k
    return bigger


@jit(cache=False, inline="always")
def _push(rows, t, y, kind, event):
    """Append a row (there is room: see :func:`_rows_needed`)."""
    k = rows.count[0]
    rows.t[k] = t
    for j in range(rows.y.shape[1]):
        rows.y[k, j] = y[j]
    rows.kind[k] = kind
    rows.event[k] = event
    rows.count[0] = k + 1


@jit(cache=False, inline="always")
def _rows_needed(s, found):
    """The most rows that the step just accepted, with ``found`` events, writes: samples, events, step, end."""
    t_eval = s.t_eval
    last = s.counters[T_EVAL_POS]
    while last < t_eval.shape[0] and t_eval[last] <= s.scalars[T]:
        last += 1
    return last - s.counters[T_EVAL_POS] + found + 2


@jit(cache=False, inline="always")
def _emit_samples(s, rows, t_upto, y):
    """Rows at the requested times up to ``t_upto`` inside the last step (y (n,) is scratch)."""
    t_eval = s.t_eval
    pos = s.counters[T_EVAL_POS]
    while pos < t_eval.shape[0] and t_eval[pos] <= t_upto:
        if t_eval[pos] == s.scalars[T]:
            _push(rows, t_eval[pos], s.y, SAMPLE, NO_EVENT)
        else:
            dense_eval(s, t_eval[pos], y)
            _push(rows, t_eval[pos], y, SAMPLE, NO_EVENT)
        pos += 1
    s.counters[T_EVAL_POS] = pos


@jit(cache=False, inline="always")
def _crosses(g_old, g_new, direction):
    """Whether an event with values g_old, g_new at a step's ends fires in it."""
    up = g_old < 0.0 and g_new >= 0.0
    down = g_old > 0.0 and g_new <= 0.0
    return (up and direction >= 0) or (down and direction <= 0)


@jit(cache=False, inline="always")
def _locate_events(events, args, s):
    """Find the events that fire in the step just accepted; returns their number.

    Their times and indices go to ``s.work.roots`` and ``s.work.which``, in time
    order (ties keep the event order); ``s.g`` moves on to the step's end.
    """
    m = s.g.shape[0]
    if m == 0:
        return 0
    w = s.work
    roots, which, g_new = w.roots, w.which, w.g_new
    t_new = s.scalars[T]
    evaluate(events, t_new, s.y, args, g_new)
    found = 0
    for i in range(m):
        if _crosses(s.g[i], g_new[i], s.direction[i]):
            root = event_root(events, args, s, i, s.scalars[T_OLD], t_new, s.g[i], g_new[i], w.y_dense, w.g_root)
            k = found  # insertion in time order
            while k > 0 and roots[k - 1] > root:
                roots[k] = roots[k - 1]
                which[k] = which[k - 1]
                k -= 1
            roots[k] = root
            which[k] = i
            found += 1
    copy_into(s.g, g_new)
    return found


@jit(cache=False, inline="always")
def _output_due(s, found):
    """Whether the step just accepted, with ``found`` events, writes a row or ends the run."""
    t_new = s.scalars[T]
    pos = s.counters[T_EVAL_POS]
    return (found > 0 or s.counters[EVERY_STEP] != 0 or t_new >= s.scalars[T_END]
            or (pos < s.t_eval.shape[0] and s.t_eval[pos] <= t_new))


@jit(cache=False, inline="always")
def _rows_of_step(s, rows, found):
    """Output rows of the step just accepted and of its ``found`` events; sets the status when the run ends.

    Called only when :func:`_output_due`, with room for :func:`_rows_needed` rows.
    """
    w = s.work
    y, y_event = w.y_dense, w.y_event
    t_new = s.scalars[T]
    for r in range(found):
        t_event, i = w.roots[r], w.which[r]
        _emit_samples(s, rows, t_event, y)
        if t_event == t_new:
            copy_into(y_event, s.y)
        else:
            dense_eval(s, t_event, y_event)
        _push(rows, t_event, y_event, EVENT, i)
        s.event_count[i] += 1
        if s.terminal[i] > 0 and s.event_count[i] >= s.terminal[i]:
            s.counters[STATUS] = TERMINAL_EVENT
            s.counters[STOP_EVENT] = i
            s.scalars[T] = t_event  # the run ends at the event, with the state there
            copy_into(s.y, y_event)
            return
    _emit_samples(s, rows, t_new, y)
    if s.counters[EVERY_STEP] != 0:
        _push(rows, t_new, s.y, STEP, NO_EVENT)
    if t_new >= s.scalars[T_END]:
        s.counters[STATUS] = REACHED_END


@jit(cache=False)
def init(fun, jac, events, args, t0, y0, t_end, rtol, atol, first_step, max_step, max_steps,
         t_eval, every_step, terminal, direction):
    """A new run at (t0, y0), ready for :func:`advance`.

    Parameters
    ----------
    fun, jac, events : compiled functions
        ``fun(t, y, args)`` -> dy/dt, shape (n,); ``jac(t, y, args)`` -> d fun / d y,
        shape (n, n); ``events(t, y, args)`` -> event values, shape (m,), m >= 0
        (:func:`no_events` for none). Called from compiled code with the functions
        themselves, ``fun`` and ``events`` may return tuples of floats instead of
        arrays, which saves an allocation per evaluation.
    args : any numba-typable value
        Passed through to the three functions.
    t0, t_end : float
        Start and end, t_end > t0.
    y0 : ndarray, shape (n,)
    rtol : float
        Relative tolerance, in [100 eps, 1).
    atol : ndarray, shape (n,)
        Absolute tolerances, positive.
    first_step : float
        Size of the first step; 0 chooses it (HW I, section II.4, as scipy).
    max_step : float
        Largest step size (inf for none).
    max_steps : int
        The run stops (MAX_STEPS_REACHED) after this many accepted steps.
    t_eval : ndarray, shape (k,)
        Increasing output times in [t0, t_end] (empty for none).
    every_step : bool
        Output every accepted step too (the times ``t_eval`` are output either way).
    terminal : ndarray of int, shape (m,)
        0: event i is recorded and the run goes on; k > 0: its k-th occurrence
        ends the run. Its length is the number of events m that ``events`` returns.
    direction : ndarray of int, shape (m,)
        +1: only rising crossings count, -1: only falling ones, 0: both.

    Returns
    -------
    State
        Status RUNNING, or NON_FINITE if f or J is not finite at (t0, y0).
        The inputs are not checked here: :func:`numerics.engine.check_inputs` does that.
    """
    n = y0.shape[0]
    s = new_state(n, terminal.shape[0], t_eval)
    sc, counters = s.scalars, s.counters
    sc[T] = t0
    sc[T_OLD] = t0
    sc[RTOL] = rtol
    sc[T_END] = t_end
    sc[MAX_STEP] = max_step
    sc[NEWTON_TOL] = newton_tolerance(rtol)
    copy_into(s.y, y0)
    copy_into(s.atol, atol)
    copy_into(s.terminal, terminal)
    copy_into(s.direction, direction)
    counters[EVERY_STEP] = 1 if every_step else 0
    counters[MAX_STEPS] = max_steps
    evaluate(events, t0, s.y, args, s.g)
    counters[NFEV] += 1
    if not evaluate(fun, t0, s.y, args, s.f):
        counters[STATUS] = NON_FINITE
        return s
    if first_step > 0.0:
        sc[H_ABS] = first_step
    else:
        sc[H_ABS] = initial_step(fun, args, t0, s.y, s.f, t_end, max_step, rtol, s.atol, counters)
    counters[NJEV] += 1
    if not evaluate_jacobian(jac, t0, s.y, args, s.jac):
        counters[STATUS] = NON_FINITE
        return s
    counters[CURRENT_JAC] = 1
    return s


@jit(cache=False)
def advance(fun, jac, events, args, s, chunk_steps):
    """Step the run ``s`` until it ends, or for ``chunk_steps`` accepted steps (> 0) and pause.

    ``s`` is updated in place; a paused run (status PAUSED) continues with
    another call, exactly as if it had not paused.

    Returns
    -------
    t : ndarray, shape (k,)
    y : ndarray, shape (n, k)
    kind : ndarray of int64, shape (k,)
        Sum of the flags START, STEP, SAMPLE, EVENT, END.
    event : ndarray of int64, shape (k,)
        Event index of EVENT rows, -1 elsewhere.
        The rows written in this call only.
    """
    # (the caller keeps the state and args alive; nothing borrowed leaves this function)
    s = borrow(s)
    args = borrow(args)
    n = s.y.shape[0]
    counters = s.counters
    owned = _new_rows(n, FIRST_CAPACITY)
    status = counters[STATUS]
    if counters[STARTED] and status != RUNNING and status != PAUSED:
        return _trimmed(owned)  # nothing left to do
    if status == PAUSED:
        counters[STATUS] = RUNNING
    if not counters[STARTED]:
        counters[STARTED] = 1
        kind = START if counters[EVERY_STEP] else np.int64(0)
        if counters[T_EVAL_POS] < s.t_eval.shape[0] and s.t_eval[counters[T_EVAL_POS]] <= s.scalars[T]:
            kind |= START | SAMPLE
            counters[T_EVAL_POS] += 1
        if kind != 0:
            _push(borrow(owned), s.scalars[T], s.y, kind, NO_EVENT)
    taken = 0
    # The steps run in passes, one per size of the output arrays: they are replaced only
    # between passes, so that within one the loop holds nothing numba counts references to.
    while counters[STATUS] == RUNNING:
        rows = borrow(owned)
        waiting = -1  # the events of a step whose rows wait for room
        while counters[STATUS] == RUNNING:
            if counters[STEPS] >= counters[MAX_STEPS]:
                counters[STATUS] = MAX_STEPS_REACHED
                break
            if chunk_steps > 0 and taken >= chunk_steps:
                counters[STATUS] = PAUSED
                break
            code = step(fun, jac, args, s)
            if code != RUNNING:
                counters[STATUS] = code
                break
            taken += 1
            found = _locate_events(events, args, s)
            if _output_due(s, found):
                if rows.count[0] + _rows_needed(s, found) > rows.t.shape[0]:
                    waiting = found
                    break
                _rows_of_step(s, rows, found)
        if waiting >= 0:
            owned = _grown(owned, _rows_needed(s, waiting))
            _rows_of_step(s, borrow(owned), waiting)
    status = counters[STATUS]
    if status != PAUSED:  # (every pass leaves room for this row)
        k = owned.count[0]
        if (status == REACHED_END or status == TERMINAL_EVENT) and k > 0 and owned.t[k - 1] == s.scalars[T]:
            owned.kind[k - 1] |= END
        else:
            _push(borrow(owned), s.scalars[T], s.y, END, NO_EVENT)
    return _trimmed(owned)


@jit(cache=False)
def _trimmed(rows):
    k = rows.count[0]
    return (rows.t[:k].copy(), np.ascontiguousarray(rows.y[:k].T), rows.kind[:k].copy(),
            rows.event[:k].copy())
