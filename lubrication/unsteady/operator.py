r"""The implicit operator of one time step: stream function and vorticity, coupled.

Unknowns and equations
----------------------
For every Fourier mode k (|k| <= K) the unknowns are psi_k(x_j) and omega_k(x_j) at
the n_r Chebyshev points, in the order [psi_k(x_0..), omega_k(x_0..)] (block size
2 n_r, blocks ordered by k). With the per-mode Laplacian in the computational
variables,

    L_k = (2/tau)^2 d^2/dx^2 - k^2,      Lap_zeta f -> sum_m g_m(x) L_{k-m} f_{k-m}

(:mod:`lubrication.unsteady.mapping`: the metric g has five Fourier coefficients), the
rows of block k are

* psi rows. x_0 (outer wall): psi_k = data; interior points:
  sum_m g_m L_{k-m} psi_{k-m} + omega_k = 0 (omega = -Lap psi); x_{n_r-1} (inner wall):
  psi_k = data.
* omega rows. x_0: (2/tau) d psi_k/dx = data (no-slip, tangential); interior points:
  c0 omega_k - nu sum_m g_m L_{k-m} omega_{k-m} = rhs (the time step, c0 = alpha_0/dt
  of the BDF formula); x_{n_r-1}: (2/tau) d psi_k/dx = data.

The two wall conditions on psi replace the vorticity equation at the walls: the
vorticity there is whatever no-slip requires, the classical coupled
psi-omega collocation. The operator couples block k to blocks k +- 1, k +- 2 only
(block-pentadiagonal, dense blocks): a banded matrix of half-bandwidth
3 (2 n_r) - 1, factorised by LAPACK's banded LU with partial pivoting (zgbtrf).
Rows are scaled to unit maximum before factorising (the wall rows and the
interior rows differ by powers of tau and n_r).

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

    # ------------------------------------------------------------------ apply

    def laplacian(self, f_hat: np.ndarray) -> np.ndarray:
        """Coefficients of Lap_zeta f at the nodes (Galerkin-truncated to |k| <= K)."""
        kk = self.grid.K
        lf = f_hat @ self.lap0.T - (self.grid.k**2)[:, None] * f_hat
        out = self.g[2][None, :] * lf
        for m in (-2, -1, 1, 2):
            gm = self.g[m + 2][None, :]
            if m > 0:
                out[m:] += gm * lf[:-m]
            else:
                out[:m] += gm * lf[-m:]
        del kk
        return out

    def matvec(self, psi: np.ndarray, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The rows of the operator applied to (psi, omega), each of shape (n_modes, n_r)."""
        d1 = self.grid.d1
        r_psi = self.laplacian(psi) + omega
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
        for d in range(-2, 3):
            kc = k + d                       # column mode
            gm = self.g[-d + 2][interior]    # g_{k - k'} = g_{-d}
            # L_{k'} restricted to interior rows, for every k
            lap = self.lap0[interior][None, :, :] - (kc**2)[:, None, None] * np.eye(n)[interior][None, :, :]
            coupled = gm[None, :, None] * lap
            out[:, d + 2, interior, :n] = coupled
            out[:, d + 2, n + 1:2 * n - 1, n:] = -self.nu * coupled
        eye = np.eye(n)
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
        row_scale, col_scale = _equilibrate(blocks)
        kl = ku = 3 * s - 1
        nn = mm * s
        ab = np.zeros((2 * kl + ku + 1, nn), dtype=complex, order="F")
        r = np.arange(s)
        kb = np.arange(mm)
        for d in range(-2, 3):
            valid = (kb + d >= 0) & (kb + d < mm)
            kv = kb[valid]
            rows = kl + ku - d * s + r[:, None] - r[None, :]          # (s, s): r - c
            cols = (kv[:, None, None] + d) * s + r[None, None, :]     # (k, 1, s)
            ab[np.broadcast_to(rows[None], (kv.size, s, s)), np.broadcast_to(cols, (kv.size, s, s))] = \
                blocks[kv, d + 2]
        return BandedLU(ab, kl, ku, row_scale, col_scale)

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
    mm = blocks.shape[0]
    for d in range(-2, 3):
        lo, hi = max(0, -d), min(mm, mm - d)
        blocks[lo:hi, d + 2] *= col[lo + d:hi + d, None, :]


def _equilibrate(blocks: np.ndarray, sweeps: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """Scale the blocks in place to R A C with every row and column maximum near 1 (Ruiz's iteration).

    Rows and columns are scaled alternately by the inverse square roots of their
    maxima (D. Ruiz, RAL-TR-2001-034). One row scaling alone left the vorticity's
    coefficient in the stream-function rows, 1 against (2/tau)^2 g n_r^4 ~ 1e17
    at 1 - kappa = 1e-4 in SI units, below the rounding of the row, and the LU
    returned garbage; scaled both ways the same system solves to 1e-7.
    """
    mm, _, s, _ = blocks.shape
    row = np.ones((mm, s))
    col = np.ones((mm, s))
    for _ in range(sweeps):
        absb = np.abs(blocks)
        r = 1.0 / np.sqrt(absb.max(axis=(1, 3)))
        blocks *= r[:, None, :, None]
        row *= r
        c = 1.0 / np.sqrt(_column_max(np.abs(blocks)))
        _scale_columns(blocks, c)
        col *= c
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
