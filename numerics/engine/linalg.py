"""Dense LU factorisation with partial pivoting, real or complex, for the Newton matrices.

The simplified Newton iteration of the three-stage Radau IIA method solves, at
every iteration, one real and one complex n x n system,

    (mu_real / h  I - J) x = b,        (mu_complex / h  I - J) x = b,

whose matrices change only with the step size h or the Jacobian J; so they are
factored once, P A = L U (L unit lower triangular, U upper triangular, row
interchanges P), and the factors serve many solves. U's diagonal is kept as its
reciprocals, so that the solves, about four a step, multiply where they would divide.
The pivot of column k is the entry of largest |Re a| + |Im a| on or below the
diagonal, as LAPACK's getrf chooses it. The systems are small (n of a few to a few
tens), where plain loops beat any call into LAPACK. One code serves float64 and
complex128 arrays: numba compiles a version per dtype.
"""

from __future__ import annotations

from numerics.jit import jit

__all__ = ["lu_factor", "lu_solve"]


@jit(cache=False)
def lu_factor(a, piv):
    """Factor ``a`` in place as P a = L U; return False if a pivot is exactly zero.

    Parameters
    ----------
    a : ndarray, shape (n, n), float64 or complex128
        Overwritten by U (above the diagonal), the reciprocals of U's diagonal
        (on it) and the multipliers of L (below it; L's unit diagonal is implied).
    piv : ndarray of int64, shape (n,)
        Overwritten: row k was interchanged with row ``piv[k]`` at stage k.

    Returns
    -------
    bool
        True if the matrix is non-singular in floating point (every pivot is
        non-zero); the factors are then usable by :func:`lu_solve`.
    """
    n = a.shape[0]
    regular = True
    for k in range(n):
        p = k
        largest = abs(a[k, k].real) + abs(a[k, k].imag)
        for i in range(k + 1, n):
            size = abs(a[i, k].real) + abs(a[i, k].imag)
            if size > largest:
                largest = size
                p = i
        piv[k] = p
        if p != k:
            for j in range(n):
                a[k, j], a[p, j] = a[p, j], a[k, j]
        if not largest > 0.0:  # zero (or NaN) column below the diagonal
            regular = False
            continue
        inverse = 1.0 / a[k, k]
        a[k, k] = inverse
        for i in range(k + 1, n):
            multiplier = a[i, k] * inverse
            a[i, k] = multiplier
            if multiplier != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= multiplier * a[k, j]
    return regular


@jit(cache=False, inline="always")
def lu_solve(lu, piv, b):
    """Overwrite ``b`` (shape (n,)) with the solution x of A x = b, given :func:`lu_factor`'s output."""
    n = lu.shape[0]
    for k in range(n):  # apply the interchanges in the order they were made
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(1, n):  # L y = P b
        acc = b[i]
        for j in range(i):
            acc -= lu[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):  # U x = y
        acc = b[i]
        for j in range(i + 1, n):
            acc -= lu[i, j] * b[j]
        b[i] = acc * lu[i, i]
