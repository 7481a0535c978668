"""Borrowed views: the run's arrays without reference counting, for the integration loop.

Numba counts references to every array a compiled function binds: each
assignment, argument and tuple member read is an atomic increment, paired with
an atomic decrement where the variable dies. LLVM's reference-count pruning
removes the pairs only in simple control flow; in the branchy code of a Radau
step (Newton exits, rejected steps, events) it cannot. Counted on Van der Pol
(mu = 1e3, rtol 1e-6): 466 atomic operations per step, most of the loop's time
under perf, so the loop runs without them (the engine's timings:
``docs/site/performance.md``; the driver's output rows are kept out of the loop's
references likewise).

:func:`borrow` returns views of the same memory with no owner (a null
``meminfo``): numba's increments and decrements of them are no-ops. The views
are valid only while the arrays they come from are alive, so the loop borrows
the :class:`~numerics.engine.state.State` it was handed, which its caller keeps,
and never lets a borrowed array escape: rows and results are copied out.
"""

from __future__ import annotations

from numba import types
from numba.extending import intrinsic

__all__ = ["borrow"]


def _borrowed(context, builder, typ, value):
    """The value of ``typ`` with every array in it (at any depth of tuples) replaced by an ownerless view."""
    if isinstance(typ, types.Array):
        source = context.make_array(typ)(context, builder, value=value)
        view = context.make_array(typ)(context, builder)
        context.populate_array(view, data=source.data, shape=source.shape, strides=source.strides,
                               itemsize=source.itemsize, meminfo=None)
        return view._getvalue()
    if isinstance(typ, types.BaseTuple):
        for i, member in enumerate(typ):
            value = builder.insert_value(value, _borrowed(context, builder, member, builder.extract_value(value, i)), i)
        return value
    context.nrt.incref(builder, typ, value)  # anything else is shared, as a new reference
    return value


@intrinsic
def borrow(typingctx, value):
    """``value`` with its arrays borrowed: an array, or the arrays in a tuple or named tuple (nested).

    Other values (numbers, and anything else in a tuple) are passed through.
    """
    def codegen(context, builder, signature, args):
        return _borrowed(context, builder, value, args[0])

    return value(value), codegen
