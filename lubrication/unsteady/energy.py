r"""The flow's kinetic energy and its viscous dissipation, per unit length: the terms of the energy balance.

For the velocity u of a level (in the frame translating with the outer centre B),

    K = (rho/2) int |u|^2 dA,     Phi = 2 mu int D:D dA,   D:D = u_x,x^2 + u_z,z^2 + (u_x,z + u_z,x)^2/2,

over the annulus. The gradients come from the spectral derivatives in the map variables
and the chain rule of the conformal map, f_x + i f_z = (f_s + i f_theta)/conj(zeta_sigma);
the area element is |zeta_sigma|^2 ds dtheta; the integrals are the trapezoidal rule around
(spectral for periodic fields) and Clenshaw-Curtis across. Both converge as the fields do.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["flow_energy"]


def _clenshaw_curtis(n: int) -> np.ndarray:
    """Weights of the Chebyshev-Lobatto points x_j = cos(pi j/(n - 1)) for the integral over [-1, 1]."""
    x = np.cos(np.pi * np.arange(n) / (n - 1))
    coefficients = np.polynomial.chebyshev.chebfit(x, np.eye(n), n - 1)  # column j: the interpolant of e_j
    k = np.arange(n)
    moments = np.where(k % 2 == 0, 2.0 / (1.0 - k.astype(float) ** 2 + (k % 2)), 0.0)
    return moments @ coefficients


def flow_energy(solver, level=None) -> tuple[float, float]:
    """(K, Phi): the kinetic energy (J/m) of a level's flow in the frame of B, and its dissipation (W/m).

    Parameters
    ----------
    solver : UnsteadySolver
    level : FlowLevel, optional
        Default the newest.
    """
    lv = level or solver.state
    grid = solver.grid
    geo = solver.geometry(lv.z_a)
    fields = solver.fields(lv)
    n = grid.n_theta
    zeta_sigma = geo.dzeta_dsigma(geo.w(grid.x, grid.theta)) * solver.b
    to_s = 2.0 / geo.tau

    def gradient(f: np.ndarray) -> np.ndarray:
        f_hat = grid.to_spectral(f)
        f_s = grid.to_physical(to_s * grid.d_x(f_hat), n)
        f_theta = grid.to_physical(grid.d_theta(f_hat), n)
        return (f_s + 1j * f_theta) / np.conj(zeta_sigma)

    u_x, u_z = fields["u_x"], fields["u_z"]
    grad_x, grad_z = gradient(u_x), gradient(u_z)
    strain = grad_x.real**2 + grad_z.imag**2 + 0.5 * (grad_x.imag + grad_z.real) ** 2
    # dA = |zeta_sigma|^2 ds dtheta, ds = (tau/2) dx
    weights = (_clenshaw_curtis(grid.n_r) * 0.5 * geo.tau)[:, None] * (2.0 * math.pi / n) * np.abs(zeta_sigma) ** 2
    kinetic = 0.5 * solver.rho * float(np.sum(weights * (u_x**2 + u_z**2)))
    dissipation = 2.0 * solver.mu * float(np.sum(weights * strain))
    return kinetic, dissipation
