"""Where an event function crosses zero inside a step: Brent's method on the dense output.

Within the last step [t_a, t_b] the solution is the step's collocation polynomial
u(t) (:func:`numerics.engine.radau.dense_eval`), so event i is the root of the scalar
function g_i(t) = events(t, u(t))[i], which changes sign over the step. Brent's
method (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973,
chapter 4) keeps a bracket [b, c] with g(b) g(c) <= 0 and b the better end, and
takes an inverse quadratic (or secant) step when it falls well inside the bracket
and shrinks it fast enough, a bisection otherwise; it needs at most about the
square of the bisection count and usually a handful of evaluations. It stops when
the bracket is below 4 eps |t| + 2 eps |b| (so the root is resolved to rounding
in t), or on an exact zero.
"""

from __future__ import annotations

from numerics.jit import jit

from .radau import EPS, dense_eval, evaluate
from .state import T

__all__ = ["event_root"]

MAX_ITERATIONS = 200  # far beyond what a bracket of doubles can need


# Both inlined where they are called: a call of a compiled function copies the run's state, 36
# arrays, onto the stack and counts a reference to each (no-ops on the loop's borrowed views, but calls
# all the same), a cost a regime map's integration paid at every root.
@jit(cache=False, inline="always")
def _g(events, args, s, i, t, y, g):
    """Event i at time t on the last step's dense output (y (n,) and g (m,) are scratch)."""
    if t == s.scalars[T]:
        evaluate(events, t, s.y, args, g)  # the step's end point itself, not its interpolant
    else:
        dense_eval(s, t, y)
        evaluate(events, t, y, args, g)
    return g[i]


@jit(cache=False, inline="always")
def event_root(events, args, s, i, t_a, t_b, g_a, g_b, y, g):
    """Root of event ``i`` in [t_a, t_b], where g_a = g_i(t_a) and g_b = g_i(t_b) differ in sign (or g_b = 0).

    Parameters
    ----------
    events, args
        The event function and its parameters, called as ``events(t, y, args)``.
    s : State
        The run, whose last step spans [t_a, t_b].
    i : int
        Index of the event.
    y, g : ndarray, shape (n,) and (m,)
        Scratch.

    Returns
    -------
    float
        The root, to within 4 eps max(|t_a|, |t_b|).
    """
    if g_b == 0.0:
        return t_b
    if g_a == 0.0:
        return t_a
    xtol = 4.0 * EPS * max(abs(t_a), abs(t_b))
    a, b, c = t_a, t_b, t_a
    fa, fb, fc = g_a, g_b, g_a
    d = e = b - a
    for _ in range(MAX_ITERATIONS):
        if (fb > 0.0) == (fc > 0.0):  # keep the root between b and c
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):  # b is the best estimate so far
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 2.0 * EPS * abs(b) + 0.5 * xtol
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return b
        if abs(e) < tol or abs(fa) <= abs(fb):
            d = e = m  # bisection
        else:
            ratio = fb / fa
            if a == c:  # secant
                p = 2.0 * m * ratio
                q = 1.0 - ratio
            else:  # inverse quadratic interpolation through a, b, c
                qa = fa / fc
                rb = fb / fc
                p = ratio * (2.0 * m * qa * (qa - rb) - (b - a) * (rb - 1.0))
                q = (qa - 1.0) * (rb - 1.0) * (ratio - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                e = d
                d = p / q
            else:
                d = e = m
        a, fa = b, fb
        b += d if abs(d) > tol else (tol if m > 0.0 else -tol)
        fb = _g(events, args, s, i, b, y, g)
    return b
