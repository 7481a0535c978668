"""Lookup in the package's tables of solves on nodes (:mod:`lubrication.inertia_table`, :mod:`lubrication.spin_table`)."""

from __future__ import annotations

from numerics.jit import jit

__all__ = ["cell"]


@jit(inline="always")
def cell(nodes, x):
    """The index i of the cell [nodes[i], nodes[i + 1]] of increasing ``nodes`` that holds x; the first or the
    last cell for x beyond them."""
    i = 0
    while i < nodes.size - 2 and x > nodes[i + 1]:
        i += 1
    return i
