r"""The implicit operator of one time step: scaled stream function and vorticity, coupled.

Unknowns and equations
----------------------
For every Fourier mode k (|k| <= K) the unknowns are Psi_k(x_j) and omega_k(x_j) at
the n_r Chebyshev points, in the order [Psi_k(x_0..), omega_k(x_0..)] (block size
2 n_r, blocks ordered by k). Psi = H psi is the stream function times the weight
H = |1 + conj(p) w|^2/|w| of :mod:`lubrication.unsteady.mapping`, whose exact steady
Stokes values have two Fourier modes at any eccentricity (psi itself needs ~ 1/beta).
With the per-mode Laplacian in the computational variables,

    L_k = (2/tau)^2 d^2/dx^2 - k^2,      Lap_zeta f -> sum_m g_m(x) L_{k-m} f_{k-m}

(the metric g has five Fourier coefficients), and the tridiagonal form of
Lap_zeta psi in terms of Psi (mapping.py),

    (S Psi)_k = (1/k) [H_0 (D^2 - k^2 + 1) Psi_k - 2 H_0' D Psi_k
                       + conj(p) (D^2 - (k - 2)^2) Psi_{k-1} + p (D^2 - (k + 2)^2) Psi_{k+1}],

with k = b^2 (1 - |p|^2)^2 and D = (2/tau) d/dx, the rows of block k are

* Psi rows. x_0 (outer wall): Psi_k = data; interior points: (S Psi)_k + omega_k = 0
  (omega = -Lap psi); x_{n_r-1} (inner wall): Psi_k = data.
* omega rows. x_0: D Psi_k = data (no-slip, tangential); interior points:
  c0 omega_k - nu sum_m g_m L_{k-m} omega_{k-m} = rhs (the time step, c0 = alpha_0/dt
  of the BDF formula); x_{n_r-1}: D Psi_k = data.

Since H > 0 is known on the walls, Psi and D Psi there carry the same conditions as
psi and D psi. The two wall conditions replace the vorticity equation at the walls:
the vorticity there is whatever no-slip requires, the classical coupled
psi-omega collocation. The operator couples block k to blocks k +- 1, k +- 2 only
(block-pentadiagonal, dense blocks): a banded matrix of half-bandwidth
3 (2 n_r) - 1, factorised by LAPACK's banded LU with partial pivoting (zgbtrf),
after scaling rows and columns to unit maxima.

The data on the walls and the right-hand side are set by the caller
(:mod:`lubrication.unsteady.solver`); here the operator is applied
(:meth:`ImplicitOperator.matvec`, the same rows evaluated without a matrix) and
solved (:meth:`ImplicitOperator.factorise`).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack

from .mapping import AnnulusMap
from .spectral import Grid

__all__ = ["ImplicitOperator", "BandedLU"]


class BandedLU:
    """LU factors of the row- and column-scaled banded matrix, and solves with them.

    (R A C) y = R b, x = C y: without the column scaling the stream-function
    unknowns (m^2/s) and the vorticity (1/s) differ by b^2 in size, and the LU of
    the row-scaled matrix lost every digit at 1 - kappa = 1e-4 (measured).
    """

    def __init__(self, ab: np.ndarray, kl: int, ku: int, row_scale: np.ndarray, col_scale: np.ndarray):
        lu, piv, info = lapack.zgbtrf(ab, kl, ku, overwrite_ab=1)
        if info < 0:
            msg = f"zgbtrf: illegal argument {-info}"
            raise RuntimeError(msg)
        if info > 0:
            msg = f"the implicit operator is singular (zero pivot at row {info})"
            raise np.linalg.LinAlgError(msg)
        self.lu, self.piv, self.kl, self.ku = lu, piv, kl, ku
        self.row_scale, self.col_scale = row_scale, col_scale

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve A x = rhs for one (n,) or several (n, m) right-hand sides."""
        one = rhs.ndim == 1
        b = (rhs.reshape(rhs.shape[0], -1) * self.row_scale[:, None]).astype(complex)
        x, info = lapack.zgbtrs(self.lu, self.kl, self.ku, b, self.piv, overwrite_b=1)
        if info != 0:
            msg = f"zgbtrs failed (info = {info})"
            raise RuntimeError(msg)
        x *= self.col_scale[:, None]
        return x[:, 0] if one else x


class ImplicitOperator:
    """The coupled psi-omega operator of one geometry and one BDF coefficient.

    Parameters
    ----------
    grid : Grid
    geometry : AnnulusMap
    nu : float
        Kinematic viscosity (m^2/s).
    c0 : float
        alpha_0 / dt (1/s): the coefficient of the new vorticity.
    """

    def __init__(self, grid: Grid, geometry: AnnulusMap, nu: float, c0: float):
        self.grid, self.geometry, self.nu, self.c0 = grid, geometry, float(nu), float(c0)
        self.scale = 2.0 / geometry.tau  # ds/dx
        self.g = geometry.metric_coefficients(grid.x)  # (5, n_r), m = -2..2
        self.lap0 = self.scale**2 * grid.d2  # L_k = lap0 - k^2 I
        self.h0, self.dh0, self.h1 = geometry.stream_weight_coefficients(grid.x)
        self.k_metric = (geometry.b * geometry.one_minus_p2) ** 2

    # ------------------------------------------------------------------ apply

    def laplacian(self, f_hat: np.ndarray) -> np.ndarray:
        """Coefficients of Lap_zeta f at the nodes (Galerkin-truncated to |k| <= K)."""
        lf = f_hat @ self.lap0.T - (self.grid.k**2)[:, None] * f_hat
        out = self.g[2][None, :] * lf
        for m in (-2, -1, 1, 2):
            gm = self.g[m + 2][None, :]
            if m > 0:
                out[m:] += gm * lf[:-m]
            else:
                out[:m] += gm * lf[-m:]
        return out

    def stream_laplacian(self, big_psi: np.ndarray) -> np.ndarray:
        """Coefficients of Lap_zeta psi from those of Psi = H psi (module docstring; Galerkin-truncated)."""
        k = self.grid.k[:, None]
        d_s = big_psi @ (self.scale * self.grid.d1).T
        d2 = big_psi @ self.lap0.T
        out = self.h0[None, :] * (d2 - (k**2 - 1.0) * big_psi) - 2.0 * self.dh0[None, :] * d_s
        # column k' = k - 1 (rows 1..): conj(p) (D^2 - (k' - 1)^2); column k' = k + 1: p (D^2 - (k' + 1)^2)
        out[1:] += self.h1 * (d2[:-1] - (k[:-1] - 1.0) ** 2 * big_psi[:-1])
        out[:-1] += np.conj(self.h1) * (d2[1:] - (k[1:] + 1.0) ** 2 * big_psi[1:])
        return out / self.k_metric

    def matvec(self, psi: np.ndarray, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The rows of the operator applied to (Psi, omega), each of shape (n_modes, n_r)."""
        d1 = self.grid.d1
        r_psi = self.stream_laplacian(psi) + omega
        r_psi[:, 0] = psi[:, 0]
        r_psi[:, -1] = psi[:, -1]
        r_om = self.c0 * omega - self.nu * self.laplacian(omega)
        r_om[:, 0] = self.scale * (psi @ d1[0])
        r_om[:, -1] = self.scale * (psi @ d1[-1])
        return r_psi, r_om

    # ------------------------------------------------------------------ assemble

    def blocks(self) -> np.ndarray:
        """Dense blocks, shape (n_modes, 5, 2 n_r, 2 n_r): [k, d + 2] couples row block k to column block k + d."""
        grid = self.grid
        n, mm = grid.n_r, grid.n_modes
        k = grid.k
        out = np.zeros((mm, 5, 2 * n, 2 * n), dtype=complex)
        interior = slice(1, n - 1)
        eye = np.eye(n)
        lap_in = self.lap0[interior][None, :, :]
        eye_in = eye[interior][None, :, :]
        for d in range(-2, 3):
            kc = k + d                       # column mode
            gm = self.g[-d + 2][interior]    # g_{k - k'} = g_{-d}
            # L_{k'} restricted to interior rows, for every k
            lap = lap_in - (kc**2)[:, None, None] * eye_in
            out[:, d + 2, n + 1:2 * n - 1, n:] = -self.nu * gm[None, :, None] * lap
        # the stream rows: tridiagonal in k (module docstring)
        h0 = self.h0[interior][None, :, None]
        dh0 = self.dh0[interior][None, :, None]
        ds_in = (self.scale * grid.d1)[interior][None, :, :]
        out[:, 2, interior, :n] = (h0 * (lap_in - (k**2 - 1.0)[:, None, None] * eye_in) - 2.0 * dh0 * ds_in) \
            / self.k_metric
        out[:, 1, interior, :n] = self.h1 * (lap_in - ((k - 2.0) ** 2)[:, None, None] * eye_in) / self.k_metric
        out[:, 3, interior, :n] = np.conj(self.h1) * (lap_in - ((k + 2.0) ** 2)[:, None, None] * eye_in) \
            / self.k_metric
        out[:, 2, interior, n:] += eye[interior]
        out[:, 2, n + 1:2 * n - 1, n:] += self.c0 * eye[interior]
        out[:, 2, 0, :n] = eye[0]
        out[:, 2, n - 1, :n] = eye[n - 1]
        out[:, 2, n, :n] = self.scale * grid.d1[0]
        out[:, 2, 2 * n - 1, :n] = self.scale * grid.d1[-1]
        # blocks outside the kept modes do not exist
        out[:2, 0] = 0.0
        out[:1, 1] = 0.0
        out[-1:, 3] = 0.0
        out[-2:, 4] = 0.0
        return out

    def factorise(self) -> BandedLU:
        """Banded LU of the row-scaled operator."""
        blocks = self.blocks()
        mm, _, s, _ = blocks.shape
        row_scale, col_scale = _equilibrate(blocks, self.initial_column_scale())
        kl = ku = 3 * s - 1
        nn = mm * s
        ldab = 2 * kl + ku + 1
        ab = np.zeros((ldab, nn), dtype=complex, order="F")
        # LAPACK's band storage puts A[i, j] at ab[kl + ku + i - j, j], i.e. at kl + ku + i + j (ldab - 1)
        # of the column-major buffer: block (k, k + d) is a strided view of it
        flat = ab.T.reshape(-1)
        item = flat.itemsize
        for d in range(-2, 3):
            lo, hi = max(0, -d), min(mm, mm - d)
            start = kl + ku + lo * s + (lo + d) * s * (ldab - 1)
            view = np.lib.stride_tricks.as_strided(flat[start:], shape=(hi - lo, s, s),
                                                   strides=(s * ldab * item, item, (ldab - 1) * item))
            view[...] = blocks[lo:hi, d + 2]
        return BandedLU(ab, kl, ku, row_scale, col_scale)

    def initial_column_scale(self) -> np.ndarray:
        """Starting column scales of the equilibration, shape (n_modes, 2 n_r): 1/c for Psi, 1 for omega.

        In a Psi row the coefficient of omega is 1 against c = (2/tau)^2 max(H_0)/k for
        the second derivative of Psi, a ratio ~ tau^4 near contact. Scaling by
        maxima alone (from unit scales) keeps that ratio, and the coupling that
        carries the gap's pressure drowns: the condition number grew like tau^-4
        (2e11 at 1 - kappa = 1e-4, 2e15 at 1e-6, 8 x 8 points). With Psi measured in
        units of c omega it stays at 3e5 and 7e6 (measured, same grids).
        """
        n = self.grid.n_r
        out = np.ones((self.grid.n_modes, 2 * n))
        out[:, :n] = self.k_metric / (self.scale**2 * float(np.max(self.h0)))
        return out

    def dense(self) -> np.ndarray:
        """The full matrix (unscaled), for checks on small grids."""
        blocks = self.blocks()
        mm, _, s, _ = blocks.shape
        a = np.zeros((mm * s, mm * s), dtype=complex)
        for kb in range(mm):
            for d in range(-2, 3):
                kc = kb + d
                if 0 <= kc < mm:
                    a[kb * s:(kb + 1) * s, kc * s:(kc + 1) * s] = blocks[kb, d + 2]
        return a


def _column_max(absb: np.ndarray) -> np.ndarray:
    """Largest entry of each column, shape (n_modes, s): block [k, d + 2] holds columns of block k + d."""
    mm, _, _, s = absb.shape
    part = absb.max(axis=2)
    colmax = np.zeros((mm, s))
    for d in range(-2, 3):
        lo, hi = max(0, -d), min(mm, mm - d)
        colmax[lo + d:hi + d] = np.maximum(colmax[lo + d:hi + d], part[lo:hi, d + 2])
    return colmax


def _scale_columns(blocks: np.ndarray, col: np.ndarray) -> None:
    """Scale block [k, d + 2] by the column scales of block k + d (clipped: blocks outside are zero)."""
    mm = blocks.shape[0]
    index = np.clip(np.arange(mm)[:, None] + np.arange(-2, 3)[None, :], 0, mm - 1)
    blocks *= col[index][:, :, None, :]


def _equilibrate(blocks: np.ndarray, col0: np.ndarray | None = None,
                 sweeps: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """Scale the blocks in place to R A C with every row and column maximum near 1 (Ruiz's iteration).

    Rows and columns are scaled alternately by the inverse square roots of their
    maxima (D. Ruiz, RAL-TR-2001-034), starting from the column scales ``col0``
    (shape (n_modes, s); ones by default). Such scalings are not unique, and
    which one the iteration reaches depends on where it starts
    (:meth:`ImplicitOperator.initial_column_scale`).
    """
    mm, _, s, _ = blocks.shape
    row = np.ones((mm, s))
    col = np.ones((mm, s)) if col0 is None else np.array(col0, dtype=float)
    # the sweeps work on the moduli (|R A C| = R |A| C); the complex blocks are scaled once
    absb = np.abs(blocks)
    _scale_columns(absb, col)
    for _ in range(sweeps):
        r = 1.0 / np.sqrt(absb.max(axis=(1, 3)))
        absb *= r[:, None, :, None]
        row *= r
        c = 1.0 / np.sqrt(_column_max(absb))
        _scale_columns(absb, c)
        col *= c
    blocks *= row[:, None, :, None]
    _scale_columns(blocks, col)
    return row.reshape(-1), col.reshape(-1)


def pack(psi: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """The unknown vector of (psi, omega) coefficients, in the operator's order."""
    return np.concatenate([psi, omega], axis=1).reshape(-1)


def unpack(x: np.ndarray, n_r: int) -> tuple[np.ndarray, np.ndarray]:
    """Inverse of :func:`pack`; works on (n,) and (n, m) arrays."""
    if x.ndim == 1:
        y = x.reshape(-1, 2 * n_r)
        return y[:, :n_r], y[:, n_r:]
    y = x.reshape(-1, 2 * n_r, x.shape[1])
    return y[:, :n_r], y[:, n_r:]
