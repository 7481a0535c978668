r"""The rigid walls: the boundary data they impose and the loads the fluid exerts on them.

Velocities are q = (U_x, U_z, Omega_a, Omega_b): the inner centre's velocity
U = U_x + i U_z = (z_A)' and the clockwise spins of the inner wall about A and of the
outer wall about B, in the frame translating with B. Internally the stream function
psi and the vorticity omega are those of the plane (x, z) with its own orientation:
u_x = d psi/dz, u_z = -d psi/dx and omega = du_z/dx - du_x/dz = -Lap psi, which is
counterclockwise-positive (a clockwise rigid rotation Omega has omega = -2 Omega and
psi = Omega |zeta|^2 / 2).

Boundary data
-------------
A rigid motion of the inner wall has the stream function
psi_A = Im(conj(U) zeta) + Omega_a |zeta - z_A|^2 / 2 (check: d psi_A/dz = U_x + Omega_a (z - z_A,z)),
and no-slip means psi - psi_A is constant on the wall and grad psi = grad psi_A
there. So, on |w| = r0 (x = -1, s = -tau),

    psi = Im(conj(U) zeta) + C_in,
    d psi/ds = Im(conj(U) zeta_sigma) + Omega_a Re(conj(zeta - z_A) zeta_sigma)
             = Im(conj(U) zeta_sigma) + Omega_a a |zeta_sigma|,

(zeta_sigma = d zeta/d sigma is along the normal into the fluid, zeta - z_A = a n), with
the unknown constant C_in (the constant Omega_a a^2/2 is absorbed in it). On |w| = 1,
psi = Omega_b (|zeta|^2 - b^2)/2 gives psi = 0 and d psi/ds = Omega_b b |zeta_sigma|.
The solver's unknown is Psi = H psi (H = |1 + conj(p) w|^2/|w| > 0, mapping.py), so
the conditions are imposed on Psi and D Psi = H_s psi + H psi_s. With
H zeta = b [e^{i theta} + p (rho + 1/rho) + p^2 e^{-i theta}] and H |zeta_sigma| = b (1 - |p|^2),
both exact, on |w| = r0 (rho + 1/rho = 2 cosh(tau), rho - 1/rho = -2 sinh(tau)):

    Psi   = Im(conj(U) H zeta) + C_in H,
    D Psi = Im(conj(U) D(H zeta)) + C_in H_0' + Omega_a a b (1 - |p|^2),
            D(H zeta) = b p (rho - 1/rho),

and on |w| = 1, Psi = 0 and D Psi = Omega_b b^2 (1 - |p|^2): trigonometric
polynomials of degree 1 (the exact Stokes flows' Psi is of the same degree).
Im(conj(U) f) has the coefficients (conj(U) f_k - U conj(f_{-k}))/(2 i). The loads
below use the closed-form series of zeta, zeta_sigma and |zeta_sigma| on the walls
(:meth:`AnnulusMap.wall_series`).

The circulation condition
-------------------------
C_in is fixed by a single-valued pressure around the inner wall. At a no-slip wall
the fluid's material acceleration is the wall's, a_w, so the momentum equation's
tangential component there is (1/rho) dp/ds = -a_w . t + nu (Lap u) . t, and with
Lap u = (-omega_z, omega_x), (Lap u) . t = d omega/dn for t counterclockwise and n
into the fluid. Around the inner wall oint dp = 0, and of the rigid acceleration
a_w = U' + (rotation) only the angular acceleration is tangential on average:
oint a_w . t ds = 2 pi a^2 d(Omega_ccw)/dt. With Omega_ccw = -Omega_a,

    nu oint d omega/dn ds = -2 pi a^2 d Omega_a/dt,

and oint d omega/dn ds = int omega_s d theta = 2 pi (2/tau) d omega_0/dx at x = -1
(the normal derivative times the arclength is conformally invariant).

Loads
-----
Traction on a wall with normal n into the fluid: -p n + 2 mu D n. On a rigid
no-slip wall the velocity relative to the rigid motion vanishes, its gradient is
(d u'/dn) n^T with d u'/dn tangential (incompressibility), and 2 mu D n =
i mu (omega - 2 Omega_ccw) n in complex notation (the rigid rotation has no strain).

* Force on the inner wall. Along the wall (counterclockwise, n ds = -i d zeta),
  -oint p n ds = i oint p d zeta = -i oint (zeta - z_A) (dp/ds) ds, and
  dp/ds = mu d omega/dn - rho a_w . t. The acceleration term integrates to
  -i rho oint (zeta - z_A)(-(a_w . t)) ds = rho pi a^2 U' (only the translation
  survives), so

      F = rho pi a^2 U' - i mu int (zeta - z_A) omega_s d theta + i mu int omega zeta_sigma d theta
          - rho pi a^2 g_eff,

  using n ds = zeta_sigma d theta and d omega/dn ds = omega_s d theta; the 2 Omega_ccw part
  of the viscous traction integrates to zero. The last term is the uniform body
  force g_eff (gravity less the acceleration of B) of the frame: a pressure
  rho g_eff . zeta whose force on the inner wall is -rho pi a^2 g_eff.
* Torque on the inner wall about A (pressure has none on a circle about its
  centre): (zeta - z_A) x (i mu omega' n) = mu a omega' with omega' = omega - 2 Omega_ccw,
  so clockwise T_a = -mu a int omega |zeta_sigma| d theta - 4 pi mu a^2 Omega_a.
* Torque on the outer wall about B (n = -zeta/b): counterclockwise -mu b oint omega' ds,
  so clockwise T_b = mu b int omega |zeta_sigma| d theta + 4 pi mu b^2 Omega_b.

Every integral is a product of the kept Fourier modes of omega with the exact
coefficients of the weight: int f h d theta = 2 pi sum_k f_{-k} h_k, exact for the
discrete field. A real load from the complex coefficients of a real field is a
complex-linear functional: Re sum c_k h_k = sum (c_k + conj(c_{-k}))/2 h_k when
h_{-k} = conj(h_k).
"""

from __future__ import annotations

import math

import numpy as np

from .mapping import AnnulusMap
from .spectral import Grid

__all__ = ["WallData", "wall_data"]


def _im_conj_u(f: np.ndarray, u: complex) -> np.ndarray:
    """Coefficients of Im(conj(u) f(theta)) from those of f (index k + K)."""
    return (np.conj(u) * f - u * np.conj(f[::-1])) / 2j


def _re_weights(c: np.ndarray) -> np.ndarray:
    return 0.5 * (c + np.conj(c[::-1]))


def _im_weights(c: np.ndarray) -> np.ndarray:
    return (c - np.conj(c[::-1])) / 2j


class WallData:
    """Boundary data per unit wall velocity and load functionals of one geometry.

    Attributes
    ----------
    psi_in : ndarray, shape (3, n_modes)
        Coefficients of Psi = H psi on the inner wall per unit U_x, U_z and C_in
        (rows in that order).
    dpsi_in : ndarray, shape (4, n_modes)
        Coefficients of D Psi on the inner wall per unit U_x, U_z, Omega_a and C_in.
    dpsi_out : ndarray, shape (n_modes,)
        Coefficients of D Psi on the outer wall per unit Omega_b.
    force_omega, force_omega_s : ndarray, shape (2, n_modes)
        F_x and F_z (per unit length) = force_omega . omega_k(x = -1)
        + force_omega_s . omega_s,k(x = -1), the viscous and vorticity-flux part.
    torque_in, torque_out : ndarray, shape (n_modes,)
        T_a and T_b: the vorticity part, on omega_k at x = -1 and x = 1.
    """

    def __init__(self, grid: Grid, geometry: AnnulusMap, mu: float):
        kk = grid.K
        mm = grid.n_modes
        series = geometry.wall_series(mm)
        dz_in = series["dzeta_in"]
        a, b, p = geometry.a, geometry.b, geometry.p
        omp2 = geometry.one_minus_p2
        h0, dh0, h1 = geometry.stream_weight_coefficients(np.array([-1.0]))
        # H zeta and D(H zeta) on |w| = r0
        hz = np.zeros(mm, dtype=complex)
        hz[kk + 1] = b
        hz[kk] = 2.0 * b * p * math.cosh(geometry.tau)
        hz[kk - 1] = b * p * p
        dhz = np.zeros(mm, dtype=complex)
        dhz[kk] = -2.0 * b * p * geometry._sinh_tau
        self.psi_in = np.zeros((3, mm), dtype=complex)
        self.psi_in[0] = _im_conj_u(hz, 1.0)
        self.psi_in[1] = _im_conj_u(hz, 1j)
        self.psi_in[2, kk] = h0[0]
        self.psi_in[2, kk + 1] = h1
        self.psi_in[2, kk - 1] = np.conj(h1)
        self.dpsi_in = np.zeros((4, mm), dtype=complex)
        self.dpsi_in[0] = _im_conj_u(dhz, 1.0)
        self.dpsi_in[1] = _im_conj_u(dhz, 1j)
        self.dpsi_in[2, kk] = a * b * omp2
        self.dpsi_in[3, kk] = dh0[0]
        self.dpsi_out = np.zeros(mm, dtype=complex)
        self.dpsi_out[kk] = b * b * omp2
        two_pi = 2.0 * math.pi
        # complex force F = sum c_k omega_k + sum d_k omega_s,k, then its real and imaginary parts
        c = 1j * mu * two_pi * dz_in[::-1]
        d = -1j * mu * two_pi * series["zeta_in"][::-1]
        self.force_omega = np.array([_re_weights(c), _im_weights(c)])
        self.force_omega_s = np.array([_re_weights(d), _im_weights(d)])
        self.torque_in = -mu * a * two_pi * series["abs_dzeta_in"][::-1]
        self.torque_out = mu * b * two_pi * series["abs_dzeta_out"][::-1]


def wall_data(grid: Grid, geometry: AnnulusMap, mu: float) -> WallData:
    """The :class:`WallData` of one geometry."""
    return WallData(grid, geometry, mu)
