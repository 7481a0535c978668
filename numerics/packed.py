"""Several float arrays as one: the ``args`` that every model of the project hands to the engine.

The engine's driver is compiled once per numba type of ``args``
(:func:`numerics.engine.compiled.engine_for`), at a cost of about half a minute
each. A model whose numbers come in several arrays (its parameters, a force
model's data, typical scales, event thresholds) packs them into one float64
array with :func:`pack`, so that every model runs on the one driver compiled for
``float64[::1]``. Its compiled functions take the arrays back with :func:`part`,
Python with :func:`parts`.

Layout: the parts one after another from index 0, then the k + 1 offsets of the
parts' starts and of their end, then k. The first part starts at index 0, so a
model whose leading numbers sit at fixed indices reads them there unchanged.
"""

from __future__ import annotations

import numpy as np

from numerics.engine.borrow import borrow
from numerics.jit import jit

__all__ = ["pack", "part", "parts"]


def pack(*arrays) -> np.ndarray:
    """One float64 array holding ``arrays`` (each flattened), read back with :func:`part` or :func:`parts`."""
    flat = [np.ascontiguousarray(a, dtype=float).ravel() for a in arrays]
    offsets = np.cumsum([0, *(a.size for a in flat)], dtype=float)
    return np.concatenate([*flat, offsets, [float(len(flat))]])


@jit(inline="always")
def part(args, i):
    """Part ``i`` of an array made by :func:`pack`, for compiled code: a view of ``args`` without an owner.

    The model's functions read their parts at every evaluation, where counting references to
    each view would add two atomic operations; the view is valid while ``args`` is, so it must
    not outlive the call (nor be returned to Python: :func:`parts` is Python's).
    """
    whole = borrow(args)  # views of an ownerless array count no references (numerics.engine.borrow)
    n = whole.shape[0]
    first = n - 2 - int(whole[n - 1])  # where the offsets begin
    return whole[int(whole[first + i]):int(whole[first + i + 1])]


def parts(args) -> list:
    """Every part of an array made by :func:`pack`, as numpy views of ``args``."""
    k = int(args[-1])
    offsets = args[-2 - k:-1].astype(int)
    return [args[offsets[j]:offsets[j + 1]] for j in range(k)]
