r"""The Radau IIA method of order 5: coefficients, one step, error estimate, step-size control, dense output.

The method (Hairer & Wanner, *Solving Ordinary Differential Equations II*,
2nd ed., Springer 1996, sections IV.5 and IV.8; their code RADAU5) advances
y' = f(t, y) from (t, y) by a step h through three stages at t + c_i h,

    c = ((4 - sqrt 6)/10, (4 + sqrt 6)/10, 1),
    Z_i = h sum_j a_ij f(t + c_j h, y + Z_j),        y_new = y + Z_3,

with the Radau IIA matrix A (collocation at the c_i: sum_j a_ij c_j^(q-1) = c_i^q / q,
q = 1, 2, 3). Stiffly accurate, L-stable, order 5 (stage order 3).

Simplified Newton. With W = (T^-1 (x) I) Z, where T^-1 A^-1 T is the real block form
of the eigenvalues of A^-1 (one real mu_real, one complex pair; mu_complex below is
the member whose block row pair is (alpha, beta), (-beta, alpha)), the 3n x 3n Newton
system splits into a real and a complex n x n one,

    (mu_real / h I - J) dW_1 = (T^-1 F)_1 - mu_real / h W_1,
    (mu_complex / h I - J) (dW_2 + i dW_3) = (T^-1 F)_2 + i (T^-1 F)_3 - mu_complex / h (W_2 + i W_3),

J the Jacobian at some earlier point, F_i = f(t + c_i h, y + Z_i). The iteration stops
when the contraction rate theta = |dW_k| / |dW_(k-1)| predicts the remaining error
theta / (1 - theta) |dW_k| below ``newton_tol``, gives up when theta >= 1 or when six
iterations cannot reach it; norms are root-mean-square, scaled by atol + rtol |y|.

Error estimate (HW (8.19)-(8.20)): the embedded order-3 formula with the extra
node (t, f(t, y)) and weight gamma_0 = 1 / mu_real gives, filtered by the Newton matrix
to stay bounded for stiff components,

    err = (mu_real / h I - J)^-1 ( f(t, y) + (e_1 Z_1 + e_2 Z_2 + e_3 Z_3) / h ),
    e = (-13 - 7 sqrt 6, -13 + 7 sqrt 6, -1) / 3;

after a rejected step the estimate is refined once more with f(t, y + err).

Step size. With err_n the scaled RMS norm of err and ``safety`` = 0.9 (2 N + 1) / (2 N + k),
N = 6 and k the Newton iterations taken, the new step is h times
safety min(1, h / h_old (err_old / err)^(1/4)) err^(-1/4), the predictive controller
of Gustafsson (HW (8.25)), bounded to [1/5, 10]; growth below 1.2 is refused
(h kept) so that the factors can be reused, unless the Jacobian is re-evaluated
anyway, which happens when Newton needed more than two iterations and contracted
slower than 1e-3.

Dense output: the collocation polynomial u(t + x h) = y + sum_(k=1..3) Q_k x^k,
which passes through y + Z_i at x = c_i; Q = Z^T P with P = (V^-1)^T, V_ik = c_i^k.
It also extrapolates the next step's Newton starting guess.

This is the algorithm of scipy's ``scipy.integrate.Radau`` (itself a reading of
RADAU5), step for step: same controller, same Jacobian and LU reuse rules, same
starting guesses and counts, so that both take the same steps up to rounding. Where
scipy departs from the Fortran RADAU5 (Newton always takes at least two iterations;
steps that would shrink by less than 1/1.2 are kept; the controller remembers the
step proposed, not taken; no refined error estimate after the very first step), this
code follows scipy, so that scipy stays an exact cross-check.
"""

from __future__ import annotations

import math

import numpy as np

from numerics.jit import jit

from .linalg import lu_factor, lu_solve
from .state import (
    CURRENT_JAC,
    ERR_OLD,
    H_ABS,
    H_ABS_OLD,
    HAS_DENSE,
    LU_VALID,
    MAX_STEP,
    NEWTON_FAILED,
    NEWTON_TOL,
    NFEV,
    NJEV,
    NLU,
    NON_FINITE,
    REJECTED,
    RTOL,
    RUNNING,
    STEP_TOO_SMALL,
    STEPS,
    T_END,
    T_OLD,
    T,
)

__all__ = [
    "MU_COMPLEX",
    "MU_REAL",
    "T_INVERSE",
    "T_MATRIX",
    "A",
    "C",
    "E",
    "P",
    "copy_into",
    "dense_eval",
    "evaluate",
    "evaluate_jacobian",
    "initial_step",
    "newton_tolerance",
    "predict_factor",
    "solve_collocation",
    "step",
]

EPS = np.finfo(float).eps
SQRT6 = math.sqrt(6.0)

#: Nodes c_i.
C = np.array([(4.0 - SQRT6) / 10.0, (4.0 + SQRT6) / 10.0, 1.0])
#: The Radau IIA matrix a_ij (HW table IV.5.6).
A = np.array([
    [(88.0 - 7.0 * SQRT6) / 360.0, (296.0 - 169.0 * SQRT6) / 1800.0, (-2.0 + 3.0 * SQRT6) / 225.0],
    [(296.0 + 169.0 * SQRT6) / 1800.0, (88.0 + 7.0 * SQRT6) / 360.0, (-2.0 - 3.0 * SQRT6) / 225.0],
    [(16.0 - SQRT6) / 36.0, (16.0 + SQRT6) / 36.0, 1.0 / 9.0],
])
#: Error-estimate weights e_i (the embedded order-3 formula divided by gamma_0).
E = np.array([-13.0 - 7.0 * SQRT6, -13.0 + 7.0 * SQRT6, -1.0]) / 3.0
#: Eigenvalues of A^-1: the real one and the complex one of the pair used (see above).
MU_REAL = 3.0 + 3.0 ** (2.0 / 3.0) - 3.0 ** (1.0 / 3.0)
MU_COMPLEX = complex(3.0 + 0.5 * (3.0 ** (1.0 / 3.0) - 3.0 ** (2.0 / 3.0)),
                     -0.5 * (3.0 ** (5.0 / 6.0) + 3.0 ** (7.0 / 6.0)))


def _transformation():
    """T with T^-1 A^-1 T = [[mu_real, 0, 0], [0, alpha, beta], [0, -beta, alpha]].

    Columns: the eigenvector of A for 1/mu_real, and the real and imaginary parts
    of the one for 1/conj(mu_complex), each scaled to a last component of 1 (so
    that y_new - y = Z_3 = W_1 + W_2).
    """
    columns = []
    for mu in (MU_REAL, MU_COMPLEX.conjugate()):
        shifted = A - np.eye(3) / mu
        head = np.linalg.solve(shifted[:2, :2], -shifted[:2, 2])
        columns.append(np.append(head, 1.0))
    real, pair = columns
    return np.column_stack([real.real, pair.real, pair.imag])


T_MATRIX = _transformation()
T_INVERSE = np.linalg.inv(T_MATRIX)
#: Rows of T^-1 that form the right-hand sides of the real and the complex system.
TI_REAL = T_INVERSE[0].copy()
TI_COMPLEX = T_INVERSE[1] + 1j * T_INVERSE[2]
#: Dense output: Q = Z^T P gives the coefficients of x, x^2, x^3.
P = np.linalg.inv(C[:, None] ** np.arange(1, 4)[None, :]).T

NEWTON_MAXITER = 6
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
KEEP_STEP_BELOW = 1.2  # a step would grow by less than this: keep it and the factors
JAC_RATE = 1e-3  # Newton contracting slower than this (after > 2 iterations): new Jacobian

@jit(cache=False)
def newton_tolerance(rtol):
    """Tolerance of the Newton iteration on the scaled increments (as RADAU5 and scipy)."""
    return max(10.0 * EPS / rtol, min(0.03, math.sqrt(rtol)))


@jit(cache=False, inline="always")
def _rms(x, weight):
    """Root-mean-square of x * weight, x of shape (n,); weight is 1 / (atol + rtol |y|)."""
    total = 0.0
    for j in range(x.shape[0]):
        r = x[j] * weight[j]
        total += r * r
    return math.sqrt(total / x.shape[0])


@jit(cache=False, inline="always")
def _rms_stages(x, weight):
    """Root-mean-square of x * weight over all entries, x of shape (3, n), weight of each column."""
    total = 0.0
    for i in range(x.shape[0]):
        for j in range(x.shape[1]):
            r = x[i, j] * weight[j]
            total += r * r
    return math.sqrt(total / x.size)


@jit(cache=False)
def copy_into(dst, src):
    """``dst[...] = src`` for arrays of equal shape (n,) or (n, n), without broadcasting."""
    if dst.ndim == 1:
        for j in range(dst.shape[0]):
            dst[j] = src[j]
    else:
        for i in range(dst.shape[0]):
            for j in range(dst.shape[1]):
                dst[i, j] = src[i, j]


# The helpers of a step are inlined where they are called: a step calls them many
# times with few arithmetic operations each.
@jit(cache=False, inline="always")
def evaluate(function, t, y, args, out):
    """``out[:] = function(t, y, args)`` for ``fun`` or ``events``; returns whether every value is finite."""
    value = function(t, y, args)
    finite = True
    for j in range(out.shape[0]):
        out[j] = value[j]
        finite = finite and math.isfinite(value[j])
    return finite


@jit(cache=False, inline="always")
def evaluate_jacobian(jac, t, y, args, out):
    """``out[:, :] = jac(t, y, args)``; returns whether every value is finite."""
    value = jac(t, y, args)
    finite = True
    for i in range(out.shape[0]):
        for j in range(out.shape[1]):
            out[i, j] = value[i, j]
            finite = finite and math.isfinite(value[i, j])
    return finite


@jit(cache=False, inline="always")
def dense_eval(s, t, out):
    """Write the last step's collocation polynomial at time ``t`` into ``out`` (n,)."""
    t_old = s.scalars[T_OLD]
    x = (t - t_old) / (s.scalars[T] - t_old)
    x2 = x * x
    x3 = x2 * x
    q, y_old = s.dense, s.y_old
    for j in range(out.shape[0]):
        out[j] = (q[j, 0] * x + q[j, 1] * x2 + q[j, 2] * x3) + y_old[j]


@jit(cache=False)
def initial_step(fun, args, t0, y0, f0, t_end, max_step, rtol, atol, counters):
    """First step size for an error of order 4 (HW I, section II.4, as scipy chooses it).

    One extra evaluation of ``fun`` at t0 + h0 along the Euler direction estimates
    the second derivative.
    """
    interval = t_end - t0
    n = y0.shape[0]
    weight = np.empty(n)
    for j in range(n):
        weight[j] = 1.0 / (atol[j] + abs(y0[j]) * rtol)
    d0 = _rms(y0, weight)
    d1 = _rms(f0, weight)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, interval)
    y1 = np.empty(n)
    f1 = np.empty(n)
    for j in range(n):
        y1[j] = y0[j] + h0 * f0[j]
    evaluate(fun, t0 + h0, y1, args, f1)
    counters[NFEV] += 1
    total = 0.0
    for j in range(n):
        r = (f1[j] - f0[j]) * weight[j]
        total += r * r
    d2 = math.sqrt(total) / math.sqrt(n) / h0
    if not math.isfinite(d2):  # f is not finite at the trial point: start small
        h1 = h0
    elif d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** 0.25
    return min(100.0 * h0, h1, interval, max_step)


@jit(cache=False, inline="always")
def predict_factor(h_abs, h_abs_old, error_norm, error_norm_old):
    """Step factor err^(-1/4), reduced by Gustafsson's predictive controller when a history exists.

    ``h_abs_old`` and ``error_norm_old`` are NaN when there is no history to use.
    Returns +inf for a zero error.
    """
    if error_norm == 0.0:
        return np.inf
    # fourth roots as two square roots: pow took 3% of a sweep batch's time (perf)
    multiplier = 1.0
    if not (math.isnan(error_norm_old) or math.isnan(h_abs_old)):
        multiplier = h_abs / h_abs_old * math.sqrt(math.sqrt(error_norm_old / error_norm))
    return min(1.0, multiplier) / math.sqrt(math.sqrt(error_norm))


@jit(cache=False, inline="always")
def solve_collocation(fun, args, t, y, h, tol, s):
    """Simplified Newton iteration for the stages, from the starting guess ``s.work.Z0``.

    Returns (converged, iterations, rate, finite): ``s.work.Z`` holds the stages;
    ``rate`` is the last contraction rate (NaN before a second iteration);
    ``finite`` is False if ``fun`` returned a non-finite value.
    """
    n = y.shape[0]
    counters = s.counters
    m_real = MU_REAL / h
    m_complex = MU_COMPLEX / h
    w = s.work
    Z, W, F, dW, Z0, y_stage = w.Z, w.W, w.F, w.dW, w.Z0, w.y_stage
    b_real, b_complex, weight = w.b_real, w.b_complex, w.weight
    for i in range(3):
        for j in range(n):
            Z[i, j] = Z0[i, j]
    for i in range(3):
        for j in range(n):
            W[i, j] = T_INVERSE[i, 0] * Z[0, j] + T_INVERSE[i, 1] * Z[1, j] + T_INVERSE[i, 2] * Z[2, j]
    dw_norm_old = np.nan
    rate = np.nan
    for k in range(NEWTON_MAXITER):
        for i in range(3):
            for j in range(n):
                y_stage[j] = y[j] + Z[i, j]
            counters[NFEV] += 1
            if not evaluate(fun, t + C[i] * h, y_stage, args, F[i]):
                return False, k + 1, rate, False
        for j in range(n):
            b_real[j] = (F[0, j] * TI_REAL[0] + F[1, j] * TI_REAL[1] + F[2, j] * TI_REAL[2]
                           - m_real * W[0, j])
            b_complex[j] = (F[0, j] * TI_COMPLEX[0] + F[1, j] * TI_COMPLEX[1] + F[2, j] * TI_COMPLEX[2]
                              - m_complex * complex(W[1, j], W[2, j]))
        lu_solve(s.lu_real, s.piv_real, b_real)
        lu_solve(s.lu_complex, s.piv_complex, b_complex)
        for j in range(n):
            dW[0, j] = b_real[j]
            dW[1, j] = b_complex[j].real
            dW[2, j] = b_complex[j].imag
        dw_norm = _rms_stages(dW, weight)
        if not math.isnan(dw_norm_old):
            rate = dw_norm / dw_norm_old
        if not math.isnan(rate) and (
                rate >= 1.0 or rate ** (NEWTON_MAXITER - k) / (1.0 - rate) * dw_norm > tol):
            return False, k + 1, rate, True
        for i in range(3):
            for j in range(n):
                W[i, j] += dW[i, j]
        for i in range(3):
            for j in range(n):
                Z[i, j] = T_MATRIX[i, 0] * W[0, j] + T_MATRIX[i, 1] * W[1, j] + T_MATRIX[i, 2] * W[2, j]
        if dw_norm == 0.0 or (not math.isnan(rate) and rate / (1.0 - rate) * dw_norm < tol):
            return True, k + 1, rate, True
        dw_norm_old = dw_norm
    return False, NEWTON_MAXITER, rate, True


@jit(cache=False, inline="always")
def _factor(s, h):
    """Form and factor both Newton matrices for step ``h``; False if one is singular."""
    n = s.y.shape[0]
    m_real = MU_REAL / h
    m_complex = MU_COMPLEX / h
    lu_real, lu_complex, jac = s.lu_real, s.lu_complex, s.jac
    for i in range(n):
        for j in range(n):
            lu_real[i, j] = -jac[i, j]
            lu_complex[i, j] = -jac[i, j]
        lu_real[i, i] += m_real
        lu_complex[i, i] += m_complex
    s.counters[NLU] += 2
    regular = lu_factor(lu_real, s.piv_real)
    return lu_factor(lu_complex, s.piv_complex) and regular


@jit(cache=False, inline="always")
def step(fun, jac, args, s):
    """Take one accepted step from ``s`` (in place), retrying with smaller steps as needed.

    Returns RUNNING after an accepted step, otherwise the failure code
    (STEP_TOO_SMALL, NEWTON_FAILED or NON_FINITE) with ``s`` left at the last
    accepted point.
    """
    sc, counters = s.scalars, s.counters
    n = s.y.shape[0]
    t, y, f = sc[T], s.y, s.f
    rtol, atol = sc[RTOL], s.atol
    w = s.work
    Z0, Z, y_stage, weight, y_new, f_new = w.Z0, w.Z, w.y_stage, w.weight, w.y_new, w.f_new
    err, ze, lu_real, piv_real = w.err, w.ze, s.lu_real, s.piv_real
    min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
    h_abs, h_abs_old, error_norm_old = sc[H_ABS], sc[H_ABS_OLD], sc[ERR_OLD]
    if h_abs > sc[MAX_STEP]:
        h_abs, h_abs_old, error_norm_old = sc[MAX_STEP], np.nan, np.nan
    elif h_abs < min_step:
        h_abs, h_abs_old, error_norm_old = min_step, np.nan, np.nan

    rejected = False
    failure = STEP_TOO_SMALL  # what to report if the step size runs out
    while True:
        if not h_abs >= min_step:  # (also ends a step size gone NaN)
            return failure
        t_new = min(t + h_abs, sc[T_END])
        h = t_new - t
        h_abs = abs(h)

        if counters[HAS_DENSE]:  # extrapolate the last collocation polynomial
            for i in range(3):
                dense_eval(s, t + h * C[i], y_stage)
                for j in range(n):
                    Z0[i, j] = y_stage[j] - y[j]
        else:
            for i in range(3):
                for j in range(n):
                    Z0[i, j] = 0.0
        for j in range(n):
            # reciprocals once a step: the norms then multiply (each Newton iteration took 3 n divisions)
            weight[j] = 1.0 / (atol[j] + abs(y[j]) * rtol)

        converged, finite = False, True
        n_iter, rate = 0, np.nan
        while not converged:
            regular = True
            if not counters[LU_VALID]:
                regular = _factor(s, h)
                counters[LU_VALID] = 1
            if regular:
                converged, n_iter, rate, finite = solve_collocation(fun, args, t, y, h, sc[NEWTON_TOL], s)
            else:
                counters[LU_VALID] = 0
            if not converged:
                if counters[CURRENT_JAC]:
                    break
                counters[NJEV] += 1
                if not evaluate_jacobian(jac, t, y, args, s.jac):
                    return NON_FINITE
                counters[CURRENT_JAC] = 1
                counters[LU_VALID] = 0
        if not converged:
            h_abs *= 0.5
            counters[LU_VALID] = 0
            counters[REJECTED] += 1
            failure = NEWTON_FAILED if finite else NON_FINITE
            continue

        for j in range(n):
            y_new[j] = y[j] + Z[2, j]
            ze[j] = (Z[0, j] * E[0] + Z[1, j] * E[1] + Z[2, j] * E[2]) / h
            err[j] = f[j] + ze[j]
        lu_solve(lu_real, piv_real, err)
        for j in range(n):
            weight[j] = 1.0 / (atol[j] + max(abs(y[j]), abs(y_new[j])) * rtol)
        error_norm = _rms(err, weight)
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
        if rejected and error_norm > 1.0:  # refine: one more filtering by the Newton matrix
            for j in range(n):
                y_stage[j] = y[j] + err[j]
            evaluate(fun, t, y_stage, args, f_new)
            counters[NFEV] += 1
            for j in range(n):
                err[j] = f_new[j] + ze[j]
            lu_solve(lu_real, piv_real, err)
            error_norm = _rms(err, weight)
        if not error_norm <= 1.0:
            if math.isnan(error_norm):
                h_abs *= MIN_FACTOR
                failure = NON_FINITE
            else:
                factor = predict_factor(h_abs, h_abs_old, error_norm, error_norm_old)
                h_abs *= max(MIN_FACTOR, safety * factor)
                failure = STEP_TOO_SMALL
            counters[LU_VALID] = 0
            counters[REJECTED] += 1
            rejected = True
            continue
        break

    recompute_jac = n_iter > 2 and rate > JAC_RATE
    factor = predict_factor(h_abs, h_abs_old, error_norm, error_norm_old)
    factor = min(MAX_FACTOR, safety * factor)
    if not recompute_jac and factor < KEEP_STEP_BELOW:
        factor = 1.0
    else:
        counters[LU_VALID] = 0

    counters[NFEV] += 1
    if not evaluate(fun, t_new, y_new, args, f_new):
        return NON_FINITE
    if recompute_jac:
        counters[NJEV] += 1
        if not evaluate_jacobian(jac, t_new, y_new, args, s.jac):
            return NON_FINITE  # (the run ends here: the state's Jacobian no longer matters)
    counters[CURRENT_JAC] = 1 if recompute_jac else 0

    # Commit: the controller remembers the step size proposed for this step (as scipy).
    sc[H_ABS_OLD] = sc[H_ABS]
    sc[ERR_OLD] = error_norm
    sc[H_ABS] = h_abs * factor
    sc[T_OLD] = t
    sc[T] = t_new
    y_old, dense = s.y_old, s.dense
    for j in range(n):
        y_old[j] = y[j]
        y[j] = y_new[j]
        f[j] = f_new[j]
        for k in range(3):
            dense[j, k] = Z[0, j] * P[0, k] + Z[1, j] * P[1, k] + Z[2, j] * P[2, k]
    counters[HAS_DENSE] = 1
    counters[STEPS] += 1
    return RUNNING
