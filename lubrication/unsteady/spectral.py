r"""Fourier x Chebyshev discretisation of the computational annulus.

A field f(x, theta) on x in [-1, 1] (Chebyshev-Gauss-Lobatto points
x_j = cos(pi j/(n_r - 1)), j = 0 .. n_r - 1, so that x_0 = 1 is the outer wall and
x_{n_r - 1} = -1 the inner one) and theta in [0, 2 pi) is stored as its complex
Fourier coefficients

    f(x_j, theta) = sum_{k=-K..K} f_k(x_j) e^{i k theta},

an array of shape (2K + 1, n_r) indexed by k + K. A real field has
f_{-k} = conj(f_k). Products are formed on a uniform theta grid of ``n_pad`` points
and truncated back to |k| <= K (pseudo-spectral with the 3/2 rule when n_pad is
at least 3K + 3, enough for a quadratic product times a metric factor of degree 2).
"""

from __future__ import annotations

import numpy as np
import scipy.fft

__all__ = ["chebyshev", "Grid"]


def chebyshev(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev-Gauss-Lobatto points x_j = cos(pi j/(n - 1)) and the differentiation matrix.

    The off-diagonal entries are the classical c_i (-1)^(i+j) / (c_j (x_i - x_j))
    (c = 2 at the ends, 1 inside); the diagonal is minus the row sum, which
    differentiates constants exactly and limits rounding (Trefethen, Spectral
    Methods in MATLAB, 2000, ch. 6).
    """
    if n < 3:
        msg = f"n_r must be an integer >= 3, got {n!r}"
        raise ValueError(msg)
    j = np.arange(n)
    x = np.cos(np.pi * j / (n - 1))
    # sin form of x_i - x_j: no cancellation near the ends
    diff = 2.0 * np.sin(0.5 * np.pi * (j[None, :] + j[:, None]) / (n - 1)) * \
        np.sin(0.5 * np.pi * (j[None, :] - j[:, None]) / (n - 1))
    c = np.ones(n)
    c[0] = c[-1] = 2.0
    c *= (-1.0) ** j
    np.fill_diagonal(diff, 1.0)
    d = np.outer(c, 1.0 / c) / diff
    np.fill_diagonal(d, 0.0)
    np.fill_diagonal(d, -d.sum(axis=1))
    return x, d


class Grid:
    """The discrete spaces of one resolution: Chebyshev operators, Fourier indices, transforms.

    Parameters
    ----------
    n_theta : int
        Points of the physical theta grid; the Fourier modes kept are
        |k| <= K = (n_theta - 1) // 2.
    n_r : int
        Chebyshev-Lobatto points across the gap, walls included.
    dealias : bool
        Form products on a padded grid of at least 3K + 3 points.
    """

    def __init__(self, n_theta: int, n_r: int, dealias: bool = True):
        self.n_theta = int(n_theta)
        self.n_r = int(n_r)
        self.K = (self.n_theta - 1) // 2
        self.n_modes = 2 * self.K + 1
        self.k = np.arange(-self.K, self.K + 1)
        self.x, self.d1 = chebyshev(self.n_r)
        self.d2 = self.d1 @ self.d1
        need = 3 * self.K + 3 if dealias else self.n_theta
        self.n_pad = scipy.fft.next_fast_len(max(need, self.n_theta))
        self.theta = 2.0 * np.pi * np.arange(self.n_theta) / self.n_theta
        self.theta_pad = 2.0 * np.pi * np.arange(self.n_pad) / self.n_pad

    def to_physical(self, f_hat: np.ndarray, n: int | None = None) -> np.ndarray:
        """Values on the (x, theta) grid, shape (n_r, n) with n = n_pad by default; real part."""
        n = self.n_pad if n is None else n
        kk = self.K
        full = np.zeros((f_hat.shape[1], n), dtype=complex)
        full[:, :kk + 1] = f_hat[kk:].T
        full[:, n - kk:] = f_hat[:kk].T
        return scipy.fft.ifft(full, axis=1, norm="forward").real

    def to_spectral(self, f: np.ndarray) -> np.ndarray:
        """Fourier coefficients |k| <= K of real values on a uniform theta grid (any size >= n_modes)."""
        n = f.shape[1]
        full = scipy.fft.fft(f, axis=1, norm="forward")
        kk = self.K
        out = np.empty((self.n_modes, f.shape[0]), dtype=complex)
        out[kk:] = full[:, :kk + 1].T
        out[:kk] = full[:, n - kk:].T
        return out

    def d_theta(self, f_hat: np.ndarray) -> np.ndarray:
        """Coefficients of df/dtheta."""
        return 1j * self.k[:, None] * f_hat

    def d_x(self, f_hat: np.ndarray) -> np.ndarray:
        """Coefficients of df/dx (Chebyshev differentiation at the nodes)."""
        return f_hat @ self.d1.T

    @staticmethod
    def symmetrise(f_hat: np.ndarray) -> np.ndarray:
        """Impose f_{-k} = conj(f_k) (a real field), averaging away rounding."""
        return 0.5 * (f_hat + np.conj(f_hat[::-1]))
