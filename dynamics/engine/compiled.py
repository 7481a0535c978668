"""The engine compiled once per type of ``args``, for every model: first-class function arguments.

Numba types a compiled function passed as an argument by its identity, so the
driver would be compiled anew for every model, and (from Python) in every new
process: tens of seconds each time. Typed instead as a first-class function,
``FunctionType(float64[::1](float64, float64[::1], type(args)))``, the model's
functions are called through a pointer (a few nanoseconds more per call), and
one compiled driver, kept in numba's disk cache, serves every model whose
``args`` have the same numba type. :func:`engine_for` builds (or loads) that
driver for a type of ``args``: compiled for exactly that signature and closed to
other specialisations, so that calls from Python always take it.

The model's functions must return C-contiguous float64 arrays: ``fun`` and
``events`` of shape (n,) and (m,), ``jac`` of shape (n, n) (``np.array([...])``,
``np.empty``, ``np.zeros`` and arithmetic on them all do).
"""

from __future__ import annotations

from collections import namedtuple

import numba
from numba import types

from lubrication._jit import jit

from . import driver
from .state import STATE_TYPE

__all__ = ["Engine", "engine_for", "function_types"]

#: The compiled ``driver.init`` and ``driver.advance`` for one type of ``args``.
Engine = namedtuple("Engine", ["init", "advance"])

_VECTOR = types.float64[::1]
_MATRIX = types.float64[:, ::1]
_INDICES = types.int64[::1]
_ENGINES: dict = {}


def function_types(args_type):
    """First-class function types of ``fun``, ``jac`` and ``events`` for ``args`` of numba type ``args_type``."""
    fun = types.FunctionType(_VECTOR(types.float64, _VECTOR, args_type))
    jac = types.FunctionType(_MATRIX(types.float64, _VECTOR, args_type))
    return fun, jac, fun


def _closed(py_func, signature):
    """A dispatcher of ``py_func`` compiled (or loaded from the cache) for ``signature`` only."""
    dispatcher = jit(py_func)
    dispatcher.compile(signature)
    dispatcher.disable_compile()
    return dispatcher


def engine_for(args) -> Engine:
    """The :class:`Engine` for ``args`` (any numba-typable value), compiled on first use."""
    args_type = numba.typeof(args)
    engine = _ENGINES.get(args_type)
    if engine is None:
        fun, jac, events = function_types(args_type)
        f8, i8 = types.float64, types.int64
        init = _closed(driver.init.py_func, (fun, jac, events, args_type, f8, _VECTOR, f8, f8, _VECTOR, f8,
                                             f8, i8, _VECTOR, types.boolean, _INDICES, _INDICES))
        advance = _closed(driver.advance.py_func, (fun, jac, events, args_type, STATE_TYPE, i8))
        engine = _ENGINES[args_type] = Engine(init, advance)
    return engine
