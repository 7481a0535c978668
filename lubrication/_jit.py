"""The project's one jit policy: every numba kernel is compiled through :func:`jit`.

Compiled code is cached on disk (``cache=True``), releases the GIL (``nogil``,
so that threads and dask workers run kernels side by side) and keeps IEEE
semantics (``fastmath=False``: a validation code must not trade NaN and
rounding guarantees for speed). ``NUMBA_DISABLE_JIT=1`` runs every kernel as
plain Python, for coverage and debugging.
"""

from __future__ import annotations

import hashlib
import types
from pathlib import Path

from numba import njit

__all__ = ["JIT_OPTIONS", "jit", "sources_hash", "specialise"]

#: Options every kernel is compiled with; a kernel may add ``inline`` or ``parallel``.
JIT_OPTIONS = {"cache": True, "nogil": True, "fastmath": False}


def jit(func=None, **extra):
    """Compile ``func`` with :data:`JIT_OPTIONS` (plus ``extra``); usable as ``@jit`` or ``@jit(...)``."""
    options = {**JIT_OPTIONS, **extra}
    if func is None:
        return njit(**options)
    return njit(**options)(func)


#: The globals each (module, template, name) was compiled with, in this process.
_SPECIALISED: dict = {}


def specialise(template, name: str, **bound):
    """:func:`jit` of a copy of the plain function ``template`` in which the globals ``bound`` are given.

    Compiled functions a template calls through a global name (a force kernel, say)
    are compiled into its code: a copy per choice carries only the code it calls.
    Numba files a compiled function under its qualified name, so each copy is named
    ``<template>_<name>`` and keeps its own entry in the disk cache; the cache is
    keyed on the template's source file, so ``name`` must say what ``bound`` holds;
    the same name with other globals is refused (ValueError).
    """
    key = (template.__module__, template.__qualname__, name)
    if _SPECIALISED.setdefault(key, bound) != bound:
        msg = f"{template.__qualname__}_{name} is already compiled with other globals: give these another name"
        raise ValueError(msg)
    namespace = {**template.__globals__, **bound}
    copy = types.FunctionType(template.__code__, namespace, f"{template.__name__}_{name}", template.__defaults__,
                              template.__closure__)
    copy.__qualname__ = f"{template.__qualname__}_{name}"
    copy.__module__ = template.__module__
    copy.__doc__ = template.__doc__
    return jit(copy)


def sources_hash(*paths: Path) -> str:
    """The first 12 hex digits of the sha256 of the files ``paths``, in the order given.

    numba checks only the source file of a function it loads from its cache, not
    of the code compiled into it: a :func:`specialise` copy named with the hash
    of every source it carries is compiled anew when any of them changes.
    """
    digest = hashlib.sha256()
    for path in paths:
        digest.update(Path(path).read_bytes())
    return digest.hexdigest()[:12]
