"""Several float arrays as one: the ``args`` that every model of the project hands to the engine.

The engine's driver is compiled once per numba type of ``args``
(:func:`numerics.engine.compiled.engine_for`), at a cost of about half a minute
each. A model whose numbers come in several arrays (its parameters, a force
model's data, typical scales, event thresholds) packs them into one float64
array with :func:`pack`, so that every model runs on the one driver compiled for
``float64[::1]``, and its compiled functions take the arrays back with
:func:`part`, as views (no copy).

Layout: the parts one after another from index 0, then the k + 1 offsets of the
parts' starts and of their end, then k. The first part starts at index 0, so a
model whose leading numbers sit at fixed indices reads them there unchanged.
"""

from __future__ import annotations

import numpy as np

from numerics.jit import jit

__all__ = ["pack", "part", "parts"]


def pack(*arrays) -> np.ndarray:
    """One float64 array holding ``arrays`` (each flattened), read back with :func:`part`."""
    flat = [np.ascontiguousarray(a, dtype=float).ravel() for a in arrays]
    offsets = np.cumsum([0, *(a.size for a in flat)], dtype=float)
    return np.concatenate([*flat, offsets, [float(len(flat))]])


@jit
def part(args, i):
    """Part ``i`` of an array made by :func:`pack`: a view into ``args``."""
    n = args.shape[0]
    first = n - 2 - int(args[n - 1])  # where the offsets begin
    return args[int(args[first + i]):int(args[first + i + 1])]


def parts(args) -> list:
    """Every part of an array made by :func:`pack`, as views."""
    return [part(args, i) for i in range(int(args[-1]))]
