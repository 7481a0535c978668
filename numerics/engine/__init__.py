"""A compiled stiff integrator: Radau IIA of order 5 with dense output and events, in numba.

Solves y' = fun(t, y, args), y(t0) = y0, on [t0, t_end] with the method of Hairer &
Wanner's RADAU5 as scipy's ``scipy.integrate.Radau`` implements it (the same steps
up to rounding), compiled whole: the steps, the Newton iterations, the LU
factorisations, the event search and the output rows never return to Python.

Use::

    from numerics.jit import jit
    from numerics.engine import integrate

    @jit
    def rhs(t, y, args):                 # -> float64 array (n,)
        ...
    @jit
    def rhs_jacobian(t, y, args):        # -> float64 array (n, n)
        ...
    @jit
    def contact(t, y, args):             # -> float64 array (m,); m = 0 for none
        ...

    run = integrate(rhs, rhs_jacobian, (0.0, t_end), y0, args=params, rtol=1e-8, atol=1e-10,
                    events=contact, terminal=[True], direction=[-1], t_eval=None,
                    chunk_steps=10_000, progress=bar_update)
    run.t, run.y, run.kind, run.t_events, run.status, run.message, run.nfev, run.steps

Compilation. The model's functions reach the driver as first-class functions,
typed by their signature, not by their identity: the driver is compiled once per
numba type of ``args`` (float64 array, or a tuple of floats and arrays, ...),
for every model at once, and kept in numba's disk cache
(:mod:`numerics.engine.compiled`). A model's first run compiles only its own
functions. Give all models the same type of ``args`` to share one driver.

Modules, one concept each, in the order a step uses them:

``state``
    :class:`State`, the resumable state of a run (a named tuple of arrays),
    its indices and the status codes.
``borrow``
    Views of the state's arrays that numba counts no references to, for the loop.
``linalg``
    LU factorisation with partial pivoting and solves, real and complex.
``radau``
    The method: coefficients, the simplified Newton iteration, the error
    estimate, the step-size controller, the first step, the dense output, and
    ``step``, one accepted step.
``roots``
    Brent's method for an event's root on a step's dense output.
``driver``
    The loop (``init``, ``advance``): events, output rows and their
    kinds, stop reasons, counts, pausing and resuming. Generic in the model's
    functions; compiled code may call them directly (they are then compiled for
    that model inside the caller, in every process: not cached).
``compiled``
    :func:`engine_for`: ``init`` and ``advance`` compiled for a type of ``args``.
``ivp``
    The Python face: :func:`check_inputs`, :func:`integrate` (scipy-like, in
    chunks with progress and Ctrl-C) and its :class:`Result`.

This package imports nothing of the project but its jit policy.
"""

from .compiled import Engine, engine_for
from .driver import END, EVENT, SAMPLE, START, STEP, no_events
from .ivp import INTERRUPTED, Interrupts, Result, check_inputs, integrate, stop_message
from .state import (
    MAX_STEPS_REACHED,
    NEWTON_FAILED,
    NON_FINITE,
    PAUSED,
    REACHED_END,
    RUNNING,
    STEP_TOO_SMALL,
    TERMINAL_EVENT,
    State,
)

__all__ = [
    "END", "EVENT", "INTERRUPTED", "Interrupts", "MAX_STEPS_REACHED", "NEWTON_FAILED", "NON_FINITE", "PAUSED",
    "REACHED_END", "RUNNING", "SAMPLE", "START", "STEP", "STEP_TOO_SMALL", "TERMINAL_EVENT",
    "Engine", "Result", "State", "check_inputs", "engine_for", "integrate", "no_events", "stop_message",
]
