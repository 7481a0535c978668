"""The engine compiled once per type of ``args``, for every model: first-class function arguments.

Numba types a compiled function passed as an argument by its identity, so the
driver would be compiled anew for every model, and (from Python) in every new
process: the whole loop compiled each time. Typed instead as a first-class function,
``FunctionType(float64[::1](float64, float64[::1], type(args)))``, the model's
functions are called through a pointer (an indirect call, timed in
``benchmarks/results/engine.md``), and one
compiled driver, kept in numba's disk cache, serves every model whose ``args``
have the same numba type (the project's models pack theirs into one float64 array,
:mod:`numerics.packed`, but for the transported film, whose data hold integers).
:func:`engine_for` builds (or loads) that driver for a
type of ``args``: compiled for exactly that signature and closed to other
specialisations, so that calls from Python always take it.

Cache and sources. Numba ties a cached function to its own source file only,
while the driver's machine code holds the code of every engine module. So the
engine's inner functions are not cached on their own (``cache=False``: compiled
afresh inside a new driver, from the current sources), and the cached driver is
filed under a name carrying a hash of all the engine's sources: editing any
module compiles a new driver instead of loading a stale one.

The model's functions must return C-contiguous float64 arrays: ``fun`` and
``events`` of shape (n,) and (m,), ``jac`` of shape (n, n) (``np.array([...])``,
``np.empty``, ``np.zeros`` and arithmetic on them all do).
"""

from __future__ import annotations

from collections import namedtuple
from pathlib import Path

import numba
from numba import types
from numba.core.types.function_type import WrapperAddressProtocol
from numba.extending import typeof_impl

from numerics.jit import compile_shared, sources_hash, specialise

from . import driver
from .state import STATE_TYPE

__all__ = ["Engine", "engine_for", "first_class", "function_types"]

#: The compiled ``driver.init`` and ``driver.advance`` for one type of ``args``.
Engine = namedtuple("Engine", ["init", "advance"])

_VECTOR = types.float64[::1]
_MATRIX = types.float64[:, ::1]
_INDICES = types.int64[::1]
_ENGINES: dict = {}


SOURCES_HASH = sources_hash(*sorted(Path(__file__).parent.glob("*.py")))


def function_types(args_type):
    """First-class function types of ``fun``, ``jac`` and ``events`` for ``args`` of numba type ``args_type``."""
    fun = types.FunctionType(_VECTOR(types.float64, _VECTOR, args_type))
    jac = types.FunctionType(_MATRIX(types.float64, _VECTOR, args_type))
    return fun, jac, fun


def _closed(py_func, signature):
    """``py_func`` compiled (or loaded from the cache) for ``signature`` only, filed under the sources' hash."""
    dispatcher = specialise(py_func, SOURCES_HASH)
    compile_shared(dispatcher, signature)
    dispatcher.disable_compile()
    return dispatcher


def engine_for(args, args_type=None) -> Engine:
    """The :class:`Engine` for ``args`` (any numba-typable value), compiled on first use.

    ``args_type``, numba's type of ``args``, saves looking it up again (numba walks a nested tuple to type it).
    """
    args_type = numba.typeof(args) if args_type is None else args_type
    engine = _ENGINES.get(args_type)
    if engine is None:
        fun, jac, events = function_types(args_type)
        f8, i8 = types.float64, types.int64
        init = _closed(driver.init.py_func, (fun, jac, events, args_type, f8, _VECTOR, f8, f8, _VECTOR, f8,
                                             f8, i8, _VECTOR, types.boolean, _INDICES, _INDICES))
        advance = _closed(driver.advance.py_func, (fun, jac, events, args_type, STATE_TYPE, i8))
        engine = _ENGINES[args_type] = Engine(init, advance)
    return engine


class _Address(WrapperAddressProtocol):
    """A compiled function as the driver takes it, its address and numba type looked up once.

    Passed as a dispatcher, a model's function would be resolved to its
    compiled version and address at every call of the driver from Python,
    a cost that would dominate short phases of hybrid runs and sweeps of short
    trajectories.
    """

    def __init__(self, dispatcher, function_type):
        signature = function_type.signature
        compile_shared(dispatcher, signature.args)
        cres = dispatcher.get_compile_result(signature)
        self._address = cres.library.get_pointer_to_function(cres.fndesc.llvm_cfunc_wrapper_name)
        self._signature = signature
        self._numba_type_ = function_type  # read by numba's dispatcher in C, and by typeof below
        self._dispatcher = dispatcher  # keeps the compiled code alive

    def __wrapper_address__(self):
        return self._address

    def signature(self):
        return self._signature


@typeof_impl.register(_Address)
def _typeof_address(value, context):
    # numba's own rule for such objects builds the type afresh from the signature at every call
    # of the driver, which is costly when ``args`` is a nested tuple
    return value._numba_type_


_ADDRESSES: dict = {}


def first_class(fun, jac, events, args, args_type=None) -> tuple:
    """``fun``, ``jac`` and ``events`` as first-class functions for ``args``, resolved once and kept.

    ``args_type`` as for :func:`engine_for`.
    """
    key = (fun, jac, events, numba.typeof(args) if args_type is None else args_type)
    found = _ADDRESSES.get(key)
    if found is None:
        fun_type, jac_type, events_type = function_types(key[3])
        found = _ADDRESSES[key] = (_Address(fun, fun_type), _Address(jac, jac_type), _Address(events, events_type))
    return found
