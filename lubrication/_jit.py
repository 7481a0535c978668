"""The project's one jit policy: every numba kernel is compiled through :func:`jit`.

Compiled code is cached on disk (``cache=True``), releases the GIL (``nogil``,
so that threads and dask workers run kernels side by side) and keeps IEEE
semantics (``fastmath=False``: a validation code must not trade NaN and
rounding guarantees for speed). ``NUMBA_DISABLE_JIT=1`` runs every kernel as
plain Python, for coverage and debugging.
"""

from __future__ import annotations

from numba import njit

__all__ = ["JIT_OPTIONS", "jit"]

#: Options every kernel is compiled with; a kernel may add ``inline`` or ``parallel``.
JIT_OPTIONS = {"cache": True, "nogil": True, "fastmath": False}


def jit(func=None, **extra):
    """Compile ``func`` with :data:`JIT_OPTIONS` (plus ``extra``); usable as ``@jit`` or ``@jit(...)``."""
    options = {**JIT_OPTIONS, **extra}
    if func is None:
        return njit(**options)
    return njit(**options)(func)
