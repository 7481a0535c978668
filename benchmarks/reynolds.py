r"""Speed against accuracy of the Reynolds solver, with two sparse-matrix baselines.

The problem is the leading-order one, h = delta (1 - kappa cos theta), for
which (2.5)-(2.7) are exact; the error of a method is the largest relative
error of the five resistance coefficients (f_eps per eps', f_chi and T_a per
W_a, f_chi and T_a per W_b) against the closed forms. The torque per W_b is
an O(zeta) difference of O(1/zeta) Couette and Poiseuille parts, zeta =
sqrt(1 - kappa^2), so its relative error has a rounding floor ~ N eps / zeta^2
whatever the method; it is also reported against |T_a per W_a|, the scale of
its row (``error_row`` uses that instead of its own size).

Methods, each timed per solve (one motion), with JIT compilation excluded:

* the kernel :func:`lubrication.reynolds_kernels.film_forces`, from a numba loop
  ("jit") and through :func:`lubrication.reynolds_forces` ("python"), on the
  Sommerfeld and the uniform grid with m = 1, 2 Gauss points per cell;
* the same finite-volume problem assembled as a periodic sparse matrix with
  numpy and scipy.sparse and solved by SuperLU (it must reproduce the kernel to
  1e-12; this isolates the cost of the linear algebra the kernel avoids);
* the conventional second-order scheme: uniform theta grid, h^3 at the cell
  faces, central differences, forces by the trapezoid rule on nodal pressures.

Derivation of both sparse systems. With phi = p / (12 mu a), U = a (W_a + W_b)
and Q(theta) = -a eps' sin(theta) (the antiderivative of the squeeze source
a dh/dt = -a eps' cos), the Reynolds equation of the physics notes,
d/dtheta (h^3 p') = 6 mu a^2 (W_a + W_b) h' + 12 mu a^2 dh/dt, says that the
flux q = U h/2 - h^3 phi' satisfies q + Q = qhat, a constant. Hence

    phi' = (U/2) h^-2 + Q h^-3 - qhat h^-3.

Same FV: integrated over cell j, phi_{j+1} - phi_j = (U/2) A_j + B_j - F_j G_j
with A_j = int h^-2, B_j = int Q h^-3, G_j = int h^-3 by the m-point Gauss
rule in psi. With conductance c_j = 1/G_j and s_j = ((U/2) A_j + B_j) c_j the
flux of cell j is F_j = s_j - c_j (phi_{j+1} - phi_j), and conservation at
node j, F_j = F_{j-1}, gives

    c_{j-1} phi_{j-1} - (c_{j-1} + c_j) phi_j + c_j phi_{j+1} = s_j - s_{j-1}.

Forces by parts with phi' at the Gauss points of cell j from F_j:
f_eps = 12 mu a^2 L oint phi' sin, f_chi = 12 mu a^2 L oint phi' (1 - cos),
T_a = mu a^2 L oint [a (W_b - W_a)/h - 6 phi' h].

Conventional: integrating the equation over [theta_{i-1/2}, theta_{i+1/2}] with
h^3 at the faces and the source at the node,

    h_{i-1/2}^3 p_{i-1} - (h_{i-1/2}^3 + h_{i+1/2}^3) p_i + h_{i+1/2}^3 p_{i+1}
        = dtheta [6 mu a^2 (W_a + W_b) (h_{i+1/2} - h_{i-1/2}) - 12 mu a^2 eps' cos(theta_i) dtheta],

then f_eps = -a L dtheta sum p cos, f_chi = -a L dtheta sum p sin and
T_a = mu a^2 L dtheta sum [a (W_b - W_a)/h - h p'/(2 mu a)] with p' by
central differences. Both systems are singular (pressure is defined up to a
constant); node 0, at the widest gap, is pinned to zero.

Run ``python -m benchmarks.reynolds`` (or ``python benchmarks/reynolds.py``)
from the project root; it writes ``benchmarks/results/reynolds.json`` and
``reynolds.md``.
"""

from __future__ import annotations

import datetime
import math
import sys
import time
from functools import lru_cache
from pathlib import Path

import numpy as np
import scipy.sparse as sparse
from numba import njit
from scipy.sparse.linalg import spsolve

if __package__ in (None, ""):  # run as a file: make the project importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import Timer, machine, publish, time_all  # noqa: E402
from lubrication import Annulus, Fluid, Motion, resistance, reynolds_forces  # noqa: E402
from lubrication.closed_form import lubrication_forces  # noqa: E402
from lubrication.geometry import Resistance  # noqa: E402
from lubrication.reynolds import GRIDS, psi_rule  # noqa: E402
from lubrication.reynolds_kernels import THIN, film_forces  # noqa: E402

__all__ = ["run", "conventional_forces", "sparse_fv_forces", "to_markdown"]

A, B, LENGTH = 0.008, 0.01125, 0.1035  # the paper's apparatus (Table 2), m
DELTA = B - A
FLUID = Fluid(nu=2.0e-4, rho=960.0)  # 200 cSt silicone oil
MU = FLUID.mu
# 1 - kappa, given directly so that it is exact: kappa = 0.5, 0.9, 0.99, 1 - 1e-4, 1 - 1e-6
ONE_MINUS_KAPPAS = (0.5, 0.1, 0.01, 1e-4, 1e-6)
POINTS_PER_CELL = (1, 2)
SOMMERFELD_CELLS = tuple(2**k for k in range(3, 11))  # 8 .. 1024
UNIFORM_CELLS = tuple(2**k for k in range(3, 17))  # 8 .. 65536: N ~ zeta^-1 needed
SPARSE_CELLS = SOMMERFELD_CELLS
CONVENTIONAL_CELLS = tuple(2**k for k in range(3, 17))  # 8 .. 65536
TARGETS = (1e-4, 1e-6, 1e-8, 1e-10)
ROUNDS = 15  # timing rounds; every method is timed once per round, in shuffled order
BATCH_SECONDS = 2e-3  # one timing sample repeats a call for at least this long
AGREEMENT = 1e-12  # same-FV sparse solve against the kernel (relative, T_a per W_b row-scaled)
# the three unit motions behind the five coefficients: (eps_dot, w_a, w_b)
UNIT_MOTIONS = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
STAGES = ("assemble", "solve", "forces")  # timed separately for the sparse baselines
GOALS = {"error": 1e-10, "cells": 128, "seconds_per_solve": 5e-6, "closed_form_seconds": 2e-7}

_EMPTY = np.empty(0)


# ---------------------------------------------------------------- jitted timing loops

@njit
def _kernel_loop(repeats, kind, kappa, omk, kappa_g, omk_g, rule, m, empty):
    """Call the kernel 3 * repeats times, cycling over the unit motions; return a checksum."""
    total = 0.0
    for _ in range(repeats):
        for k in range(3):
            eps_dot = 1.0 if k == 0 else 0.0
            w_a = 1.0 if k == 1 else 0.0
            w_b = 1.0 if k == 2 else 0.0
            f_eps, f_chi, t_a = film_forces(kind, A, B, MU, LENGTH, kappa, omk, eps_dot, w_a, w_b,
                                            kappa_g, omk_g, *rule, m, empty, empty, 1.0, 0.0, empty)
            total += f_eps + f_chi + t_a
    return total


@njit
def _closed_form_loop(repeats, kappa, omk, eps_dot, w_a, w_b):
    """Call (2.5)-(2.7) repeats * kappa.size times over varying inputs; return a checksum.

    The inputs change from call to call so that the compiler cannot hoist the
    call out of the loop.
    """
    total = 0.0
    for _ in range(repeats):
        for k in range(kappa.size):
            f_eps, f_chi, t_a = lubrication_forces(A, DELTA, MU, LENGTH, kappa[k], omk[k],
                                                   eps_dot[k], w_a[k], w_b[k])
            total += f_eps + f_chi + t_a
    return total


# ---------------------------------------------------------------- baseline (i): same FV, scipy.sparse

def _west(x: np.ndarray) -> np.ndarray:
    """x_{i-1}, periodically."""
    return np.concatenate((x[-1:], x[:-1]))


def _east(x: np.ndarray) -> np.ndarray:
    """x_{i+1}, periodically."""
    return np.concatenate((x[1:], x[:1]))


@lru_cache(maxsize=64)
def _laplacian_pattern(n: int):
    """CSR column indices and row pointers of a periodic tridiagonal matrix: i-1, i, i+1 in row i."""
    i = np.arange(n)
    return np.column_stack(((i - 1) % n, i, (i + 1) % n)).ravel(), np.arange(0, 3 * n + 1, 3)


def _pinned_laplacian(c: np.ndarray) -> sparse.csr_array:
    """Periodic conductance matrix, row i: c_{i-1} x_{i-1} - (c_{i-1} + c_i) x_i + c_i x_{i+1}.

    Row 0 is replaced by x_0 (pins the free constant). ``c`` has shape (N,),
    ``c[i]`` joining nodes i and i+1.
    """
    c_west = _west(c)
    vals = np.column_stack((c_west, -(c_west + c), c)).ravel()
    vals[:3] = 0.0, 1.0, 0.0
    indices, indptr = _laplacian_pattern(c.size)
    # copy: scipy sorts the indices in place, which would corrupt the cached pattern
    return sparse.csr_array((vals, indices, indptr), shape=(c.size, c.size), copy=True)


@lru_cache(maxsize=64)
def _psi_tables(n: int, m: int):
    """sin psi, 1 - cos psi, 1 + cos psi and the Gauss weights at the N*m points.

    Independent of :func:`lubrication.reynolds.psi_rule`; the versines use half
    angles so that they keep their relative precision.
    """
    x, g = np.polynomial.legendre.leggauss(m)
    dpsi = 2.0 * np.pi / n
    psi = (-np.pi + dpsi * (np.arange(n)[:, None] + 0.5 * (x + 1.0))).ravel()
    return np.sin(psi), 2.0 * np.sin(0.5 * psi) ** 2, 2.0 * np.cos(0.5 * psi) ** 2, np.tile(0.5 * dpsi * g, n)


def sparse_fv_assemble(n, m, kappa, omk, kappa_g, omk_g, eps_dot, w_a, w_b):
    """Cell integrals by the Gauss rule and the pinned sparse system of the same FV scheme.

    Returns
    -------
    matrix : scipy.sparse.csr_array, shape (N, N)
    rhs : ndarray, shape (N,)
    state : tuple
        What :func:`sparse_fv_forces_from` needs.
    """
    sin_psi, vers_psi, pers_psi, weight = _psi_tables(n, m)
    zeta_g = math.sqrt(omk_g * (1.0 + kappa_g))
    d = omk_g + kappa_g * pers_psi  # 1 + kappa_g cos psi
    sin_t = zeta_g * sin_psi / d
    vers_t = omk_g * vers_psi / d  # 1 - cos theta
    w = weight * zeta_g / d  # dtheta
    h = DELTA * (omk + kappa * vers_t)
    q = -A * eps_dot * sin_t
    half_u = 0.5 * A * (w_a + w_b)
    w2 = w / h**2
    w3 = w2 / h
    a_cell = w2.reshape(n, m).sum(axis=1)
    g_cell = w3.reshape(n, m).sum(axis=1)
    b_cell = (q * w3).reshape(n, m).sum(axis=1)
    c = 1.0 / g_cell
    s = (half_u * a_cell + b_cell) * c
    rhs = s - _west(s)
    rhs[0] = 0.0
    return _pinned_laplacian(c), rhs, (m, c, s, sin_t, vers_t, w, h, q, w2, w3, half_u, w_a, w_b)


def sparse_fv_forces_from(phi, state):
    """f_eps, f_chi, T_a from the nodal phi by the per-cell fluxes and the Gauss rule."""
    m, c, s, sin_t, vers_t, w, h, q, w2, w3, half_u, w_a, w_b = state
    flux = s - c * (_east(phi) - phi)
    dphi = half_u * w2 + q * w3 - np.repeat(flux, m) * w3  # phi' dtheta at the points
    scale = 12.0 * MU * A * A * LENGTH
    torque = A * (w_b - w_a) * np.sum(w / h) - 6.0 * np.sum(dphi * h)
    return scale * np.sum(dphi * sin_t), scale * np.sum(dphi * vers_t), MU * A * A * LENGTH * torque


def sparse_fv_forces(n, m, kappa, omk, kappa_g, omk_g, eps_dot, w_a, w_b):
    """Baseline (i): f_eps, f_chi, T_a from the kernel's finite-volume problem as a sparse matrix.

    N cells of m Gauss points on the grid with parameter kappa_g (0: uniform theta).
    """
    matrix, rhs, state = sparse_fv_assemble(n, m, kappa, omk, kappa_g, omk_g, eps_dot, w_a, w_b)
    return sparse_fv_forces_from(spsolve(matrix, rhs, use_umfpack=False), state)


# ---------------------------------------------------------------- baseline (ii): conventional FV

@lru_cache(maxsize=64)
def _theta_tables(n: int):
    """Nodes theta_i = -pi + i dtheta: cos, sin, 1 - cos at the nodes and 1 - cos at faces i + 1/2."""
    dtheta = 2.0 * np.pi / n
    theta = -np.pi + dtheta * np.arange(n)
    return dtheta, np.cos(theta), np.sin(theta), 2.0 * np.sin(0.5 * theta) ** 2, \
        2.0 * np.sin(0.5 * (theta + 0.5 * dtheta)) ** 2


def conventional_assemble(n, kappa, omk, eps_dot, w_a, w_b):
    """Pinned sparse system of the conventional scheme (h^3 at the faces), and its state."""
    dtheta, cos_t, sin_t, vers_t, vers_face = _theta_tables(n)
    h = DELTA * (omk + kappa * vers_t)  # 1 - kappa cos, without cancellation near contact
    h_face = DELTA * (omk + kappa * vers_face)
    rhs = dtheta * (6.0 * MU * A * A * (w_a + w_b) * (h_face - _west(h_face))
                    - 12.0 * MU * A * A * eps_dot * cos_t * dtheta)
    rhs[0] = 0.0
    return _pinned_laplacian(h_face**3), rhs, (dtheta, cos_t, sin_t, h, w_a, w_b)


def conventional_forces_from(p, state):
    """f_eps, f_chi by the trapezoid rule; T_a from the wall shear with central dp/dtheta."""
    dtheta, cos_t, sin_t, h, w_a, w_b = state
    dp = (_east(p) - _west(p)) / (2.0 * dtheta)
    shear = A * (w_b - w_a) / h - h * dp / (2.0 * MU * A)
    return (-A * LENGTH * dtheta * np.sum(p * cos_t), -A * LENGTH * dtheta * np.sum(p * sin_t),
            MU * A * A * LENGTH * dtheta * np.sum(shear))


def conventional_forces(n, kappa, omk, eps_dot, w_a, w_b):
    """Baseline (ii): the conventional second-order scheme on N uniform theta nodes."""
    matrix, rhs, state = conventional_assemble(n, kappa, omk, eps_dot, w_a, w_b)
    return conventional_forces_from(spsolve(matrix, rhs, use_umfpack=False), state)


# ---------------------------------------------------------------- errors and timing

def _coefficients(forces) -> tuple[float, ...]:
    """The five coefficients of :class:`Resistance` from ``forces(eps_dot, w_a, w_b)``."""
    radial, inner, outer = (forces(*motion) for motion in UNIT_MOTIONS)
    return radial[0], inner[1], inner[2], outer[1], outer[2]


def _errors(exact: tuple, got: tuple) -> dict:
    """Relative errors of the five coefficients and their maxima (strict and row-scaled)."""
    rel = [abs(g - e) / abs(e) for e, g in zip(exact, got)]
    t_b_row = abs(got[4] - exact[4]) / abs(exact[2])
    return {"error": max(rel), "error_row": max(rel[:4] + [t_b_row]),
            "t_a_per_w_b_self": rel[4], "t_a_per_w_b_row": t_b_row,
            "relative": dict(zip(Resistance.NAMES, rel))}


def _jit_batch(kappa, omk, kappa_g, omk_g, n, m):
    """Kernel calls from the numba loop, on the grid that :mod:`lubrication.reynolds` would build."""
    rule, _ = psi_rule(n, m)

    def batch(calls):
        repeats = max(1, calls // 3)
        start = time.perf_counter()
        _kernel_loop(repeats, THIN, kappa, omk, kappa_g, omk_g, rule, m, _EMPTY)
        return [(time.perf_counter() - start) * calls / (3 * repeats)]
    return batch


def _python_batch(annulus, n, grid, m):
    """Calls of :func:`lubrication.reynolds_forces`, checks and dataclasses included."""
    motions = [Motion(eps_dot=e, omega_a=wa, omega_b=wb) for e, wa, wb in UNIT_MOTIONS]

    def batch(calls):
        start = time.perf_counter()
        for i in range(calls):
            reynolds_forces(annulus, motions[i % 3], FLUID, n=n, grid=grid, points_per_cell=m)
        return [time.perf_counter() - start]
    return batch


def _staged_batch(assemble, forces_from):
    """Time assembly, the sparse solve and the forces separately, cycling the unit motions."""
    def batch(calls):
        spent = np.zeros(3)
        for i in range(calls):
            t0 = time.perf_counter()
            matrix, rhs, state = assemble(*UNIT_MOTIONS[i % 3])
            t1 = time.perf_counter()
            phi = spsolve(matrix, rhs, use_umfpack=False)
            t2 = time.perf_counter()
            forces_from(phi, state)
            spent += (t1 - t0, t2 - t1, time.perf_counter() - t2)
        return spent
    return batch


def _closed_form_batch(omks):
    """Calls of the jitted closed forms from a numba loop, over every kappa and unit motion."""
    omk = np.repeat(np.asarray(omks), 3)
    kappa = 1.0 - omk
    eps_dot, w_a, w_b = (np.tile(column, len(omks)) for column in np.array(UNIT_MOTIONS).T)

    def batch(calls):
        repeats = max(1, calls // kappa.size)
        start = time.perf_counter()
        _closed_form_loop(repeats, kappa, omk, eps_dot, w_a, w_b)
        return [(time.perf_counter() - start) * calls / (repeats * kappa.size)]
    return batch


def _equal_accuracy(records, omks, targets, measure):
    """Smallest N and its time per method for each target and kappa, and time ratios.

    For the kernel and the same-FV baseline each m gets its smallest N, and the
    faster of the two is kept. Ratios use the kernel's time both through
    :func:`lubrication.reynolds_forces` and from jitted code.
    """
    methods = {
        "kernel_sommerfeld": ([r for r in records["kernel"] if r["grid"] == "sommerfeld"], "seconds_python"),
        "kernel_uniform": ([r for r in records["kernel"] if r["grid"] == "uniform"], "seconds_python"),
        "sparse_fv": ([r for r in records["sparse_fv"] if r["grid"] == "sommerfeld"], "seconds"),
        "conventional": (records["conventional"], "seconds"),
    }
    table = []
    for target in targets:
        for omk in omks:
            entry = {"target": target, "one_minus_kappa": omk, "kappa": 1.0 - omk}
            for method, (rows, time_key) in methods.items():
                # per m the fewest cells that reach the target; then the faster m
                best = None
                for m in {r.get("points_per_cell") for r in rows}:
                    hits = [r for r in rows if r["one_minus_kappa"] == omk and r.get("points_per_cell") == m
                            and r[measure] <= target]
                    hit = min(hits, key=lambda r: r["n"], default=None)
                    if hit is not None and (best is None or hit[time_key] < best[time_key]):
                        best = hit
                entry[method] = None if best is None else {
                    "n": best["n"], "points_per_cell": best.get("points_per_cell"), "error": best[measure],
                    "seconds": best[time_key], "seconds_jit": best.get("seconds_jit")}
            kernel = entry["kernel_sommerfeld"]
            for method in ("sparse_fv", "conventional"):
                other = entry[method]
                ok = kernel is not None and other is not None
                entry[f"{method}_over_kernel_python"] = other["seconds"] / kernel["seconds"] if ok else None
                entry[f"{method}_over_kernel_jit"] = other["seconds"] / kernel["seconds_jit"] if ok else None
            table.append(entry)
    return table


def run(one_minus_kappas=ONE_MINUS_KAPPAS, sommerfeld_cells=SOMMERFELD_CELLS, uniform_cells=UNIFORM_CELLS,
        sparse_cells=SPARSE_CELLS, conventional_cells=CONVENTIONAL_CELLS, targets=TARGETS,
        rounds=ROUNDS, batch_seconds=BATCH_SECONDS, seed=0) -> dict:
    """Errors against (2.5)-(2.7) and median times per solve of every method.

    Parameters
    ----------
    one_minus_kappas : sequence of float
        1 - kappa of the annuli (given directly, so that it keeps its precision).
    sommerfeld_cells, uniform_cells : sequence of int
        Cells N for the kernel on each grid.
    sparse_cells, conventional_cells : sequence of int
        Cells (nodes) N for the two sparse baselines.
    targets : sequence of float
        Errors for the equal-accuracy comparison.
    rounds : int
        Timing samples per method; the median is reported.
    batch_seconds : float
        Minimum duration of one sample (calls are repeated within it).
    seed : int
        Seed of the order in which methods are sampled within a round.

    Returns
    -------
    dict
        Plain data (JSON-serialisable): records per method, the closed-form
        cost, the equal-accuracy table and the goals.

    Raises
    ------
    AssertionError
        If the sparse same-FV solve departs from the kernel by more than
        ``AGREEMENT``.
    """
    started = time.perf_counter()
    cells = {"sommerfeld": sommerfeld_cells, "uniform": uniform_cells}
    kernel, sparse_fv, conventional, timers = [], [], [], []
    for omk in one_minus_kappas:
        kappa = 1.0 - omk
        annulus = Annulus(A, B, length=LENGTH, one_minus_kappa=omk)
        exact = resistance(annulus, FLUID, "closed-form").as_tuple()
        base = {"one_minus_kappa": omk, "kappa": kappa}
        for grid in GRIDS:
            kappa_g, omk_g = (kappa, omk) if grid == "sommerfeld" else (0.0, 1.0)
            for m in POINTS_PER_CELL:
                for n in cells[grid]:
                    key = (omk, grid, m, n)
                    got = resistance(annulus, FLUID, "reynolds", n=n, grid=grid, points_per_cell=m).as_tuple()
                    kernel.append({**base, "grid": grid, "points_per_cell": m, "n": n, **_errors(exact, got)})
                    timers.append(Timer(("jit",) + key, _jit_batch(kappa, omk, kappa_g, omk_g, n, m)))
                    timers.append(Timer(("python",) + key, _python_batch(annulus, n, grid, m)))
                    if n not in sparse_cells:
                        continue
                    args = (n, m, kappa, omk, kappa_g, omk_g)
                    alt = _coefficients(lambda *motion: sparse_fv_forces(*args, *motion))
                    agreement = _errors(got, alt)["error_row"]
                    assert agreement <= AGREEMENT, (
                        f"sparse same-FV solve differs from the kernel by {agreement:.2e} at {key}")
                    sparse_fv.append({**base, "grid": grid, "points_per_cell": m, "n": n,
                                      "agreement_with_kernel": agreement, **_errors(exact, alt)})
                    timers.append(Timer(("sparse_fv",) + key, _staged_batch(
                        lambda *motion, args=args: sparse_fv_assemble(*args, *motion), sparse_fv_forces_from),
                        STAGES))
        for n in conventional_cells:
            got = _coefficients(lambda *motion, n=n: conventional_forces(n, kappa, omk, *motion))
            conventional.append({**base, "n": n, **_errors(exact, got)})
            timers.append(Timer(("conventional", omk, n), _staged_batch(
                lambda *motion, n=n, kappa=kappa, omk=omk: conventional_assemble(n, kappa, omk, *motion),
                conventional_forces_from), STAGES))
    timers.append(Timer(("closed_form",), _closed_form_batch(one_minus_kappas)))
    seconds = time_all(timers, rounds, batch_seconds, np.random.default_rng(seed))

    for row in kernel:
        key = (row["one_minus_kappa"], row["grid"], row["points_per_cell"], row["n"])
        row.update(_timing("jit", seconds[("jit",) + key]))
        row.update(_timing("python", seconds[("python",) + key]))
    for row in sparse_fv:
        row.update(_timing("", seconds[("sparse_fv", row["one_minus_kappa"], row["grid"],
                                        row["points_per_cell"], row["n"])]))
    for row in conventional:
        row.update(_timing("", seconds[("conventional", row["one_minus_kappa"], row["n"])]))
    records = {"kernel": kernel, "sparse_fv": sparse_fv, "conventional": conventional}
    closed_form = _timing("", seconds[("closed_form",)])
    return {
        "machine": machine(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "settings": {"a": A, "b": B, "length": LENGTH, "mu": MU, "rounds": rounds,
                     "batch_seconds": batch_seconds, "agreement_tolerance": AGREEMENT},
        **records,
        "closed_form": closed_form,
        "equal_accuracy": _equal_accuracy(records, one_minus_kappas, targets, "error_row"),
        "equal_accuracy_strict": _equal_accuracy(records, one_minus_kappas, targets, "error"),
        "goals": _goals(kernel, closed_form["seconds"]),
        "run_seconds": time.perf_counter() - started,
    }


def _timing(method: str, summary: dict) -> dict:
    """Timer summary as row fields: seconds[_method] (median wall), and its stages, fastest, cpu."""
    suffix = f"_{method}" if method else ""
    return {(f"seconds{suffix}" if name == "total" else f"seconds_{name}{suffix}"): value
            for name, value in summary.items() if name != "calls_per_sample"}


def _goals(kernel, closed_form_seconds) -> dict:
    """How close the measurements come to the project's three goals, per m on the Sommerfeld grid.

    Times at N = 128 are the median over kappa (the work does not depend on it).
    """
    n_goal, error_goal, time_goal = GOALS["cells"], GOALS["error"], GOALS["seconds_per_solve"]
    goals = {"targets": dict(GOALS)}
    for m in POINTS_PER_CELL:
        rows = [r for r in kernel if r["grid"] == "sommerfeld" and r["points_per_cell"] == m]
        ns = sorted({r["n"] for r in rows if r["n"] <= n_goal})
        entry = {}
        for measure in ("error", "error_row"):
            worst = {n: max(r[measure] for r in rows if r["n"] == n) for n in ns}
            entry[f"worst_{measure}_by_n"] = worst
            entry[f"n_meeting_{measure}"] = [n for n in ns if worst[n] <= error_goal]
        at_goal = [r for r in rows if r["n"] == n_goal]
        for field in ("seconds_jit", "seconds_cpu_jit", "seconds_python"):
            entry[f"{field}_at_{n_goal}"] = float(np.median([r[field] for r in at_goal]))
        entry["met_time_jit"] = entry[f"seconds_jit_at_{n_goal}"] <= time_goal
        goals[f"m={m}"] = entry
    goals["closed_form"] = {"seconds": closed_form_seconds,
                            "met": closed_form_seconds <= GOALS["closed_form_seconds"]}
    return goals


# ---------------------------------------------------------------- report

def _us(seconds) -> str:
    return "-" if seconds is None else f"{seconds * 1e6:.3g}"


def _both(row) -> str:
    """'strict / row-scaled' error of a record."""
    return f"{row['error']:.1e} / {row['error_row']:.1e}"


def _kappa_label(omk: float) -> str:
    return f"1-{omk:g}" if omk < 1e-3 else f"{1.0 - omk:g}"


def _median_over_kappa(rows, field):
    return float(np.median([r[field] for r in rows]))


def _table(header, lines) -> list[str]:
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
            *("| " + " | ".join(map(str, line)) + " |" for line in lines), ""]


def to_markdown(results: dict) -> str:
    """The tables of ``results`` (from :func:`run`) as markdown."""
    machine, goals = results["machine"], results["goals"]
    kernel, sparse_fv, conventional = results["kernel"], results["sparse_fv"], results["conventional"]
    omks = sorted({r["one_minus_kappa"] for r in kernel}, reverse=True)
    kappa_cols = [f"kappa={_kappa_label(omk)}" for omk in omks]
    out = ["# Reynolds solver: speed against accuracy", "",
           f"{machine['cpu']}, {machine['cores']} cores; Python {machine['python']}, numpy {machine['numpy']}, "
           f"scipy {machine['scipy']}, numba {machine['numba']}. {results['date']}; the run took "
           f"{results['run_seconds']:.0f} s.", "",
           "Errors are against the closed forms (2.5)-(2.7), written `strict / row`: the largest relative "
           "error of the five resistance coefficients, with T_a per W_b measured against itself (strict) "
           "or against |T_a per W_a| (row). Times are medians of "
           f"{results['settings']['rounds']} interleaved samples, microseconds per solve (one motion), "
           "JIT compilation excluded; 'jit' calls the kernel from a numba loop, 'Python' through "
           "`reynolds_forces`. The machine is shared: the JSON also has the fastest sample and the "
           "thread CPU time.", ""]

    out += ["## Goals", ""]
    lines = []
    for m in POINTS_PER_CELL:
        g = goals[f"m={m}"]
        for measure, label in (("error", "strict"), ("error_row", "row")):
            worst = g[f"worst_{measure}_by_n"]
            meeting = g[f"n_meeting_{measure}"]
            lines.append([f"error <= 1e-10, every kappa <= 1-1e-6, N <= 128 ({label})", m,
                          f"worst over kappa at N = 128: {worst[GOALS['cells']]:.1e}; "
                          f"N meeting it: {', '.join(map(str, meeting)) or 'none'}",
                          "yes" if meeting else "no"])
        lines.append(["<= 5 us per solve at N = 128 (jit)", m,
                      f"{_us(g['seconds_jit_at_128'])} us (CPU {_us(g['seconds_cpu_jit_at_128'])} us; "
                      f"Python call {_us(g['seconds_python_at_128'])} us)", "yes" if g["met_time_jit"] else "no"])
    cf = goals["closed_form"]
    lines.append(["closed form < 0.2 us (jit)", "-", f"{cf['seconds'] * 1e9:.3g} ns per call",
                  "yes" if cf["met"] else "no"])
    out += _table(["goal", "m", "measured", "met"], lines)

    out += ["## Kernel: error and time against N", ""]
    for grid in GRIDS:
        for m in POINTS_PER_CELL:
            rows = [r for r in kernel if r["grid"] == grid and r["points_per_cell"] == m]
            lines = []
            for n in sorted({r["n"] for r in rows}):
                at_n = sorted((r for r in rows if r["n"] == n), key=lambda r: -r["one_minus_kappa"])
                lines.append([n, _us(_median_over_kappa(at_n, "seconds_jit")),
                              _us(_median_over_kappa(at_n, "seconds_python")), *map(_both, at_n)])
            out += [f"### {grid} grid, m = {m}", ""]
            out += _table(["N", "jit us", "Python us", *kappa_cols], lines)

    out += ["## T_a per W_b on the Sommerfeld grid: relative error against itself / against |T_a per W_a|", "",
            "An O(zeta) difference of O(1/zeta) parts: its own relative error has a rounding floor "
            "growing like N eps / zeta^2.", ""]
    for m in POINTS_PER_CELL:
        rows = [r for r in kernel if r["grid"] == "sommerfeld" and r["points_per_cell"] == m]
        lines = []
        for n in sorted({r["n"] for r in rows}):
            at_n = sorted((r for r in rows if r["n"] == n), key=lambda r: -r["one_minus_kappa"])
            lines.append([n, *(f"{r['t_a_per_w_b_self']:.1e} / {r['t_a_per_w_b_row']:.1e}" for r in at_n)])
        out += [f"### m = {m}", ""] + _table(["N", *kappa_cols], lines)

    out += ["## Baseline (i): the same finite-volume problem with scipy.sparse", "",
            "Same cells, Gauss points and exact-cell conductances, assembled as a periodic sparse matrix "
            "(one node pinned) and solved by `spsolve` (SuperLU); forces by the same flux quadrature. "
            f"Largest departure from the kernel over all cases: "
            f"{max(r['agreement_with_kernel'] for r in sparse_fv):.1e} (asserted <= {AGREEMENT:g}). "
            "Times on the Sommerfeld grid, median over kappa.", ""]
    lines = []
    for m in POINTS_PER_CELL:
        rows = [r for r in sparse_fv if r["grid"] == "sommerfeld" and r["points_per_cell"] == m]
        for n in sorted({r["n"] for r in rows}):
            at_n = [r for r in rows if r["n"] == n]
            kernel_py = [r for r in kernel if r["grid"] == "sommerfeld" and r["points_per_cell"] == m
                         and r["n"] == n]
            lines.append([n, m, *(_us(_median_over_kappa(at_n, f"seconds_{s}")) for s in STAGES),
                          _us(_median_over_kappa(at_n, "seconds")),
                          f"{_median_over_kappa(at_n, 'seconds') / _median_over_kappa(kernel_py, 'seconds_python'):.0f}"])
    out += _table(["N", "m", "assemble us", "solve us", "forces us", "total us", "/ kernel (Python)"], lines)

    out += ["## Baseline (ii): conventional second-order finite volumes", "",
            "Uniform theta grid, h^3 at the faces, central differences, scipy.sparse `spsolve`; forces "
            "by the trapezoid rule on nodal pressures, torque from the wall shear with a central dp/dtheta.", ""]
    lines = []
    for n in sorted({r["n"] for r in conventional}):
        at_n = sorted((r for r in conventional if r["n"] == n), key=lambda r: -r["one_minus_kappa"])
        lines.append([n, *(_us(_median_over_kappa(at_n, f"seconds_{s}")) for s in STAGES),
                      _us(_median_over_kappa(at_n, "seconds")), *map(_both, at_n)])
    out += _table(["N", "assemble us", "solve us", "forces us", "total us", *kappa_cols], lines)

    for key, label in (("equal_accuracy", "row"), ("equal_accuracy_strict", "strict")):
        out += [f"## Equal accuracy ({label} error)", "",
                "Smallest N reaching the target (for each m; the faster m is kept) and its time per solve in us; "
                "ratios are baseline time / Sommerfeld-kernel time. '-': not reached up to the largest N.", ""]
        lines = []
        for e in results[key]:
            def cell(method):
                x = e[method]
                return "-" if x is None else f"{x['n']}" + (f" (m={x['points_per_cell']})" if x["points_per_cell"] else "")

            def ratio(name):
                x = e[name]
                return "-" if x is None else f"{x:.3g}"
            ks, ku, sf, cv = (e[k] for k in ("kernel_sommerfeld", "kernel_uniform", "sparse_fv", "conventional"))
            lines.append([f"{e['target']:.0e}", _kappa_label(e["one_minus_kappa"]),
                          cell("kernel_sommerfeld"), _us(ks and ks["seconds_jit"]), _us(ks and ks["seconds"]),
                          cell("kernel_uniform"), _us(ku and ku["seconds_jit"]),
                          cell("sparse_fv"), _us(sf and sf["seconds"]), cell("conventional"), _us(cv and cv["seconds"]),
                          ratio("conventional_over_kernel_python"), ratio("conventional_over_kernel_jit"),
                          ratio("sparse_fv_over_kernel_python")])
        out += _table(["target", "kappa", "kernel N", "jit us", "Python us", "uniform N", "jit us",
                       "same FV N", "us", "conventional N", "us", "conv / kernel (Python)",
                       "conv / kernel (jit)", "same FV / kernel (Python)"], lines)
    return "\n".join(out)


def main() -> None:
    results = run()
    publish("reynolds", results, to_markdown(results))


if __name__ == "__main__":
    main()
