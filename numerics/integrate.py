"""One call for every integrator: the compiled Radau IIA engine, or one of scipy's solvers as a cross-check.

:func:`integrate` takes a model's compiled ``fun``, ``jac`` and ``events``
(``f(t, y, args)``) and returns a :class:`numerics.engine.Result` whichever
method runs it:

``"radau"`` (the default)
    the compiled engine, :func:`numerics.engine.integrate`: no Python per step;
``"Radau"``, ``"BDF"``, ``"LSODA"``
    scipy's solvers stepped from Python, for cross-checks: events are located on
    their dense output with ``brentq`` (to 4 eps), output rows carry the same
    kinds, and a run stopped by Ctrl-C or SIGTERM keeps what it computed.
"""

from __future__ import annotations

import numpy as np

from numerics import engine
from numerics.engine import (
    END,
    EVENT,
    SAMPLE,
    START,
    STEP,
    Interrupts,
    Result,
    check_inputs,
    no_events,
)

__all__ = ["METHODS", "integrate"]

METHODS = ("radau", "Radau", "BDF", "LSODA")


def integrate(fun, jac, t_span, y0, *, args=(), method: str = "radau", rtol=1e-8, atol=1e-10, events=None,
              terminal=0, direction=0, t_eval=None, steps=None, max_steps: int = 2_000_000,
              chunk_steps: int = 20_000, progress=None) -> Result:
    """Integrate y' = fun(t, y, args) with ``method`` (:data:`METHODS`); see :func:`numerics.engine.integrate`."""
    if method not in METHODS:
        msg = f"method must be one of {', '.join(METHODS)}, got {method!r}"
        raise ValueError(msg)
    if method == "radau":
        return engine.integrate(fun, jac, t_span, y0, args=args, rtol=rtol, atol=atol, events=events,
                                terminal=terminal, direction=direction, t_eval=t_eval, steps=steps,
                                max_steps=max_steps, chunk_steps=chunk_steps, progress=progress)
    return _scipy(fun, jac, t_span, y0, args, method, rtol, atol, events or no_events, terminal, direction,
                  t_eval, steps, max_steps, progress)


def _scipy(fun, jac, t_span, y0, args, method, rtol, atol, events, terminal, direction, t_eval, steps, max_steps,
           progress) -> Result:
    from scipy import integrate as si
    from scipy.optimize import brentq

    inputs = check_inputs(fun, jac, events, t_span, y0, args=args, rtol=rtol, atol=atol, t_eval=t_eval,
                          steps=steps, terminal=terminal, direction=direction, max_steps=max_steps)
    t0, t_end, y0 = inputs["t0"], inputs["t_end"], inputs["y0"]
    terminal, direction = inputs["terminal"], inputs["direction"]
    every_step = inputs["every_step"]
    samples = inputs["t_eval"]
    solver = getattr(si, method)(lambda t, y: fun(t, y, args), t0, y0, t_end, rtol=inputs["rtol"],
                                 atol=inputs["atol"], jac=lambda t, y: jac(t, y, args))
    rows_t, rows_y, rows_kind, rows_event = [], [], [], []

    def row(t, y, kind, event=-1):
        rows_t.append(t)
        rows_y.append(np.array(y, dtype=float))
        rows_kind.append(kind)
        rows_event.append(event)

    g_old = np.asarray(events(t0, y0, args), dtype=float)
    counts = np.zeros(g_old.size, dtype=np.int64)
    sampled_at_start = bool(samples.size) and samples[0] == t0
    if every_step or sampled_at_start:  # as the engine: a start row only where rows are asked for
        row(t0, y0, START | (SAMPLE if sampled_at_start else 0))
    next_sample = int(sampled_at_start)
    code, stop_event, steps = engine.REACHED_END, -1, 0
    last_t, last_y = t0, y0.copy()
    interrupts = Interrupts()
    interrupts.__enter__()
    try:
        while solver.status == "running":
            if interrupts.received:
                code = engine.INTERRUPTED
                break
            if steps >= max_steps:
                code = engine.MAX_STEPS_REACHED
                break
            solver.step()
            steps += 1
            if solver.status == "failed":
                code = engine.NEWTON_FAILED
                break
            t_new, y_new = solver.t, solver.y.copy()
            if not np.all(np.isfinite(y_new)):
                code = engine.NON_FINITE
                break
            dense = solver.dense_output()
            g_new = np.asarray(events(t_new, y_new, args), dtype=float)
            hits = []
            for i in range(g_old.size):
                up = g_old[i] < 0.0 <= g_new[i]
                down = g_old[i] > 0.0 >= g_new[i]
                if (up and direction[i] >= 0) or (down and direction[i] <= 0):
                    t_hit = brentq(lambda t, i=i: events(t, dense(t), args)[i], solver.t_old, t_new,
                                   xtol=4.0 * np.finfo(float).eps * max(1.0, abs(t_new)),
                                   rtol=4.0 * np.finfo(float).eps)
                    hits.append((t_hit, i))
            stop_at = t_new
            for t_hit, i in sorted(hits):
                counts[i] += 1
                if terminal[i] and counts[i] >= terminal[i]:
                    stop_at, stop_event = t_hit, i
                    break
            for t_hit, i in sorted(hits):
                if t_hit > stop_at:
                    break
                due = np.searchsorted(samples, t_hit, side="right")
                for ts in samples[next_sample:due]:
                    row(ts, dense(ts), SAMPLE)
                next_sample = due
                row(t_hit, dense(t_hit), EVENT | (END if i == stop_event else 0), i)
            if stop_event >= 0:
                code = engine.TERMINAL_EVENT
                break
            due = np.searchsorted(samples, t_new, side="right")
            for ts in samples[next_sample:due]:
                row(ts, dense(ts), SAMPLE)
            next_sample = due
            if every_step:
                row(t_new, y_new, STEP)
            if t_new >= t_end:
                rows_kind[-1] |= END
            g_old = g_new
            last_t, last_y = t_new, y_new
            if progress is not None:
                progress(t_new)
    except KeyboardInterrupt as err:
        code = engine.INTERRUPTED
        interrupts.received = interrupts.received or str(err) or "SIGINT"
    finally:
        interrupts.__exit__(None, None, None)
    t_stop = rows_t[-1] if code == engine.TERMINAL_EVENT else last_t
    if code not in (engine.REACHED_END, engine.TERMINAL_EVENT):
        row(last_t, last_y, END)  # the last finite state reached
    status = 0 if code == engine.REACHED_END else 1 if code == engine.TERMINAL_EVENT else -1
    message = engine.stop_message(code, t_stop, stop_event, interrupts.received)
    if code == engine.NEWTON_FAILED and solver.status == "failed":
        message = f"the {method} solver failed at t = {t_stop:.17g}"
    t = np.array(rows_t)
    y = np.array(rows_y).T.reshape(len(y0), -1)
    kind = np.array(rows_kind, dtype=np.int64)
    event = np.array(rows_event, dtype=np.int64)
    on_event = (kind & EVENT) != 0
    return Result(t=t, y=y, kind=kind, event=event,
                  t_events=[t[on_event & (event == i)] for i in range(g_old.size)],
                  y_events=[y[:, on_event & (event == i)].T for i in range(g_old.size)],
                  status=status, code=code, message=message, success=status >= 0, stop_event=stop_event,
                  nfev=int(solver.nfev), njev=int(getattr(solver, "njev", 0)), nlu=int(getattr(solver, "nlu", 0)),
                  steps=steps, rejected=0, state=None)
