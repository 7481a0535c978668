"""The resumable state of a run: every number the integrator carries from one step to the next.

A run keeps all it needs between steps in one :class:`State`, a named tuple of
arrays. Compiled code updates the arrays in place, so a run that pauses after a
number of steps hands back the very arrays it was stepping with, and a later
call continues from them exactly, bit for bit: nothing is recomputed at a pause.

Scalars live in two arrays indexed by the constants below:

``scalars`` (float64)
    ``T`` current time; ``T_OLD`` start of the last accepted step; ``H_ABS``
    proposed size of the next step; ``H_ABS_OLD`` and ``ERR_OLD`` the step size
    and error norm the predictive controller remembers (NaN when it must
    forget them); ``NEWTON_TOL`` tolerance of the Newton iteration; ``RTOL``;
    ``T_END``; ``MAX_STEP``.
``counters`` (int64)
    ``NFEV``, ``NJEV``, ``NLU`` evaluations of the right-hand side, of the
    Jacobian, and LU decompositions (a real and a complex one count two);
    ``STEPS`` accepted and ``REJECTED`` rejected step attempts; ``STATUS`` one
    of the codes below; ``STOP_EVENT`` the index of the terminal event (-1 if
    none); ``CURRENT_JAC`` whether ``jac`` was evaluated at the current point;
    ``LU_VALID`` whether the factors match the current step size and Jacobian;
    ``HAS_DENSE`` whether a last step (and its dense output) exists;
    ``T_EVAL_POS`` the next output time; ``EVERY_STEP`` output mode;
    ``MAX_STEPS``; ``STARTED`` whether the rows at the start have been written.

Arrays: ``y``, ``f`` = fun(t, y), ``y_old`` (n,); ``dense`` (n, 3), the
coefficients of the last step's collocation polynomial (its dense output, and
the Newton starting guess of the next step); ``jac`` (n, n); ``lu_real``,
``piv_real`` and ``lu_complex``, ``piv_complex``, the factored Newton matrices;
``atol`` (n,); ``t_eval`` (k,); ``g`` event values at ``T`` (m,);
``event_count``, ``terminal``, ``direction`` (m,).

``work`` (a :class:`Work`) holds the scratch arrays of the loop, whose contents
do not outlive a step. The state owns them so that the loop, which steps with
borrowed views of the state's arrays (:mod:`numerics.engine.borrow`), owns no
memory of its own.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from numerics.jit import jit

__all__ = [
    "CURRENT_JAC",
    "ERR_OLD",
    "EVERY_STEP",
    "HAS_DENSE",
    "H_ABS",
    "H_ABS_OLD",
    "LU_VALID",
    "MAX_STEP",
    "MAX_STEPS",
    "MAX_STEPS_REACHED",
    "NEWTON_FAILED",
    "NEWTON_TOL",
    "NFEV",
    "NJEV",
    "NLU",
    "NON_FINITE",
    "PAUSED",
    "REACHED_END",
    "REJECTED",
    "RTOL",
    "RUNNING",
    "STARTED",
    "STATUS",
    "STEPS",
    "STEP_TOO_SMALL",
    "STOP_EVENT",
    "TERMINAL_EVENT",
    "T_END",
    "T_EVAL_POS",
    "T_OLD",
    "State",
    "T",
    "Work",
    "new_state",
]

State = namedtuple("State", [
    "scalars", "counters", "y", "f", "y_old", "dense", "jac", "lu_real", "piv_real",
    "lu_complex", "piv_complex", "atol", "t_eval", "g", "event_count", "terminal", "direction", "work",
])

#: Scratch of the loop. Of a step (:func:`numerics.engine.radau.step`): the stage
#: quantities ``Z0`` (Newton's starting guess), ``Z``, ``W``, ``F``, ``dW`` (3, n) and
#: ``weight``, ``y_new``, ``f_new``, ``err``, ``ze``, ``y_stage``, ``b_real`` (n,),
#: ``b_complex`` (n,) complex. Of the events and output: ``y_dense``, ``y_event`` (n,),
#: ``g_new``, ``g_root``, ``roots`` (m,) and ``which`` (m,) int.
Work = namedtuple("Work", [
    "Z0", "Z", "W", "F", "dW", "weight", "y_new", "f_new", "err", "ze", "y_stage", "b_real", "b_complex",
    "y_dense", "y_event", "g_new", "g_root", "roots", "which",
])

# Indices into State.scalars.
T, T_OLD, H_ABS, H_ABS_OLD, ERR_OLD, NEWTON_TOL, RTOL, T_END, MAX_STEP = range(9)
N_SCALARS = 9

# Indices into State.counters.
(NFEV, NJEV, NLU, STEPS, REJECTED, STATUS, STOP_EVENT, CURRENT_JAC, LU_VALID, HAS_DENSE,
 T_EVAL_POS, EVERY_STEP, MAX_STEPS, STARTED) = range(14)
N_COUNTERS = 14

# Status codes: running, the two successful ends, a pause, and the failures (negative).
RUNNING = 0
REACHED_END = 1
TERMINAL_EVENT = 2
PAUSED = 3
MAX_STEPS_REACHED = -1
STEP_TOO_SMALL = -2
NEWTON_FAILED = -3
NON_FINITE = -4


@jit(cache=False)
def new_state(n, m, t_eval):
    """Allocate a :class:`State` for ``n`` states and ``m`` events, sampling at ``t_eval``.

    Every number is zero (NaN for the remembered step and error) until the driver fills it.
    """
    scalars = np.zeros(N_SCALARS)
    scalars[H_ABS_OLD] = np.nan
    scalars[ERR_OLD] = np.nan
    counters = np.zeros(N_COUNTERS, dtype=np.int64)
    counters[STOP_EVENT] = -1
    work = Work(np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)), np.zeros((3, n)),
                np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
                np.zeros(n, dtype=np.complex128), np.zeros(n), np.zeros(n), np.zeros(m), np.zeros(m),
                np.zeros(m), np.zeros(m, dtype=np.int64))
    return State(scalars, counters, np.zeros(n), np.zeros(n), np.zeros(n), np.zeros((n, 3)),
                 np.zeros((n, n)), np.zeros((n, n)), np.zeros(n, dtype=np.int64),
                 np.zeros((n, n), dtype=np.complex128), np.zeros(n, dtype=np.int64), np.zeros(n),
                 t_eval.copy(), np.zeros(m), np.zeros(m, dtype=np.int64), np.zeros(m, dtype=np.int64),
                 np.zeros(m, dtype=np.int64), work)


def _state_type():
    """The numba type of every :class:`State` (arrays of fixed dtypes and dimensions)."""
    import numba

    f1, f2, i1 = np.zeros(1), np.zeros((1, 1)), np.zeros(1, dtype=np.int64)
    c1 = np.zeros(1, dtype=np.complex128)
    work = Work(f2, f2, f2, f2, f2, f1, f1, f1, f1, f1, f1, f1, c1, f1, f1, f1, f1, f1, i1)
    return numba.typeof(State(f1, i1, f1, f1, f1, f2, f2, f2, i1, np.zeros((1, 1), dtype=np.complex128), i1,
                              f1, f1, f1, i1, i1, i1, work))


#: Numba type of a :class:`State`, for explicit signatures.
STATE_TYPE = _state_type()
