"""Step a scipy ODE solver, locate terminal events, and keep what was computed when a run stops early.

:func:`scipy.integrate.solve_ivp` returns nothing when it is interrupted; this
driver steps the same scipy solvers (Radau, BDF, LSODA, ...) itself so that an
interrupted or failed run still hands back every step it took, with the reason.
Events are located on the solver's dense output with ``brentq``, as
``solve_ivp`` does, never by stepping past them.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK23, RK45, Radau
from scipy.optimize import brentq

__all__ = ["METHODS", "Event", "Integration", "integrate"]

METHODS = {"Radau": Radau, "BDF": BDF, "LSODA": LSODA, "RK45": RK45, "RK23": RK23, "DOP853": DOP853}
_IMPLICIT = ("Radau", "BDF", "LSODA")


@dataclass(frozen=True)
class Event:
    """A terminal event: the run stops where ``g(t, y)`` crosses zero in ``direction``.

    ``describe(t)`` returns the stop reason written into the result.
    """

    name: str
    g: Callable[[float, np.ndarray], float]
    direction: float
    describe: Callable[[float], str]


@dataclass
class Integration:
    """Every accepted step of a run, and how it ended.

    ``status`` is "completed" (reached ``t_end``), "stopped" (an event; ``event``
    names it), "failed" (the solver or the model failed) or "interrupted".
    """

    t: np.ndarray
    y: np.ndarray
    status: str
    reason: str
    event: str = ""
    steps: int = 0
    nfev: int = 0
    njev: int = 0
    wall_time_s: float = 0.0


def _progress_bar(t_end: float, label: str):
    """A tqdm bar on a terminal, refreshed at most once a second; None when piped."""
    if not sys.stderr.isatty():
        return None
    from tqdm import tqdm

    return tqdm(total=t_end, desc=label, unit="t", mininterval=1.0, leave=False,
                bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} [{elapsed}<{remaining}]")


def integrate(fun, y0, t_end: float, *, jac=None, rtol: float = 1e-8, atol=1e-10,
              method: str = "LSODA", events: tuple[Event, ...] = (), t_eval=None,
              max_steps: int = 2_000_000, progress: str | None = None) -> Integration:
    """Integrate ``y' = fun(t, y)`` from 0 to ``t_end``.

    Parameters
    ----------
    fun, jac : callable
        Right-hand side and (for implicit methods) its Jacobian.
    y0 : array_like, shape (n,)
    t_end : float
    rtol, atol : float or array_like
        Tolerances of the scipy solver.
    method : str
        One of :data:`METHODS`.
    events : tuple of Event
        Terminal events.
    t_eval : array_like, optional
        Increasing output times in [0, t_end], sampled from the dense output; by
        default every accepted step is kept. The state where an event stops the
        run is appended either way.
    max_steps : int
        A run that needs more steps than this is stopped with that reason, so
        that no run hangs.
    progress : str, optional
        Label of a progress bar shown on a terminal.
    """
    if method not in METHODS:
        msg = f"method must be one of {', '.join(METHODS)}, got {method!r}"
        raise ValueError(msg)
    options = {"rtol": rtol, "atol": atol}
    if method in _IMPLICIT and jac is not None:
        options["jac"] = jac
    start = time.perf_counter()
    y0 = np.asarray(y0, dtype=float)
    samples = None if t_eval is None else np.asarray(t_eval, dtype=float)
    ts, ys = ([0.0], [y0.copy()]) if samples is None else ([], [])
    next_sample = 0
    status, reason, event_name = "completed", f"reached t_end = {t_end:.6g}", ""
    bar = _progress_bar(t_end, progress) if progress else None
    solver = None
    steps = 0
    try:
        solver = METHODS[method](fun, 0.0, y0, t_end, **options)
        g_old = [ev.g(0.0, y0) for ev in events]
        while solver.status == "running":
            if steps >= max_steps:
                status, reason = "stopped", f"more than max_steps = {max_steps} steps by t = {solver.t:.6g}"
                event_name = "max_steps"
                break
            message = solver.step()
            steps += 1
            if solver.status == "failed":
                status, reason = "failed", f"the {method} solver failed at t = {solver.t:.6g}: {message}"
                break
            t_new, y_new = solver.t, solver.y.copy()
            if not np.all(np.isfinite(y_new)):
                status, reason = "failed", f"the state became non-finite at t = {t_new:.6g}"
                break
            hit = _first_event(events, g_old, solver, t_new, y_new)
            t_kept = t_new if hit is None else hit[1]
            if samples is None:
                ts.append(t_kept)
                ys.append(y_new if hit is None else hit[2])
            else:
                stop = np.searchsorted(samples, t_kept, side="right")
                if stop > next_sample:
                    dense = solver.dense_output()
                    ts.extend(samples[next_sample:stop])
                    ys.extend(dense(samples[next_sample:stop]).T)
                    next_sample = stop
                if hit is not None and (not ts or ts[-1] < t_kept):
                    ts.append(t_kept)
                    ys.append(hit[2])
            if hit is not None:
                status, event_name = "stopped", events[hit[0]].name
                reason = events[hit[0]].describe(hit[1])
                break
            g_old = [ev.g(t_new, y_new) for ev in events]
            if bar is not None:
                bar.update(t_new - bar.n)
    except KeyboardInterrupt as err:
        by = f" by {err}" if str(err) else ""
        status, reason = "interrupted", f"interrupted{by} at t = {_now(solver):.6g}"
    except (ArithmeticError, ValueError, np.linalg.LinAlgError) as err:
        status, reason = "failed", f"{type(err).__name__} at t = {_now(solver):.6g}: {err}"
    finally:
        if bar is not None:
            bar.close()
    return Integration(
        t=np.array(ts), y=np.array(ys).reshape(-1, y0.size).T, status=status, reason=reason,
        event=event_name, steps=steps, nfev=int(getattr(solver, "nfev", 0)), njev=int(getattr(solver, "njev", 0)),
        wall_time_s=time.perf_counter() - start)


def _now(solver) -> float:
    return 0.0 if solver is None else solver.t


def _first_event(events, g_old, solver, t_new, y_new):
    """The earliest event crossed in the last step, located on the dense output; or None."""
    found = None
    for i, ev in enumerate(events):
        g_new = ev.g(t_new, y_new)
        crossed = (g_old[i] > 0 >= g_new) if ev.direction < 0 else (
            (g_old[i] < 0 <= g_new) if ev.direction > 0 else g_old[i] * g_new <= 0 and g_old[i] != 0)
        if not crossed:
            continue
        dense = solver.dense_output()
        t_hit = brentq(lambda t, ev=ev: ev.g(t, dense(t)), solver.t_old, t_new,
                       xtol=4 * np.finfo(float).eps * max(1.0, abs(t_new)), rtol=4 * np.finfo(float).eps)
        if found is None or t_hit < found[1]:
            found = (i, t_hit, dense(t_hit))
    return found
