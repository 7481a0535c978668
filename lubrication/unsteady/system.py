r"""The monolithic linear system of one time step: flow, inner-wall constant and wall velocities.

Unknowns: the flow x (coefficients of Psi = H psi and omega, :mod:`lubrication.unsteady.operator`)
and s = (C_in, U_x, U_z, Omega_a, Omega_b), the inner wall's stream-function constant
and the new wall velocities q. Equations:

    A x = b + D s                     (flow; D s are the wall data of the velocities, walls.py)
    E x + G s = h                     (5 rows: the circulation condition and the 4 wall equations)

with, for the wall equations M q - C loads = r given by the caller and the loads
loads = Lambda x + Lambda_s s + lambda_0 at the new level (linear: the added-mass
pressure rho pi a^2 U' enters through the BDF derivative of U, i.e. through s),

    E = [circ; -C Lambda],   G = [[0, 0, 0, a^2 c0, 0]; [0 | M] - C Lambda_s],
    h = [-a^2 (history of Omega_a'); r + C lambda_0].

Elimination: x = y0 + Y s with A y0 = b, A Y = D (six solves with one LU), then the
5 x 5 system (G + E Y) s = h - E y0. All complex arithmetic on Hermitian-symmetric
data gives real s up to rounding; its real part is kept.

Reuse of a factorisation. A step's system changes with the geometry (the metric,
tau, the wall data) and with c0 = alpha_0/dt. Solving the system of one step with
the factors of another's (preconditioner P) by defect correction,
X <- X + P^-1 (RHS - K X) with the exact residual of the new system K, converges
at the rate ||P^-1 (K - P)||, small when the geometry has moved little: the
solver refactorises only when this iteration does not reach its tolerance
within a few sweeps (:class:`StepSystem.solve`).
"""

from __future__ import annotations

import math

import numpy as np

from .mapping import AnnulusMap
from .operator import ImplicitOperator, pack, unpack
from .spectral import Grid
from .timestepping import Bdf
from .walls import WallData

__all__ = ["StepSystem", "flow_rhs", "one_blas_thread"]

_CONTROLLER = []


def one_blas_thread():
    """A context in which BLAS runs on one thread (a no-op without threadpoolctl).

    The banded LU and its solves are many small updates: measured on two cores,
    factorising at 128 x 16 points took 0.11 s on one OpenBLAS thread and 0.49 s
    on the default threads (2048 x 12: 0.89 s against 6.2 s).
    """
    import contextlib
    if not _CONTROLLER:
        try:
            from threadpoolctl import ThreadpoolController
            _CONTROLLER.append(ThreadpoolController())
        except ImportError:  # pragma: no cover - optional
            _CONTROLLER.append(None)
    controller = _CONTROLLER[0]
    if controller is None:  # pragma: no cover
        return contextlib.nullcontext()
    return controller.limit(limits=1, user_api="blas")


class StepSystem:
    """Everything linear about one step at one geometry and one BDF coefficient.

    Parameters
    ----------
    grid : Grid
    geometry : AnnulusMap
    nu, rho : float
        Kinematic viscosity (m^2/s) and density (kg/m^3).
    c0 : float
        alpha_0/dt of the step (1/s).
    """

    def __init__(self, grid: Grid, geometry: AnnulusMap, nu: float, rho: float, c0: float):
        self.grid, self.geometry, self.nu, self.rho, self.c0 = grid, geometry, nu, rho, c0
        self.mu = rho * nu
        self.op = ImplicitOperator(grid, geometry, nu, c0)
        self.walls = WallData(grid, geometry, self.mu)
        n, mm, kk = grid.n_r, grid.n_modes, grid.K
        a, b = geometry.a, geometry.b
        w = self.walls
        # wall data per unit s = (C_in, U_x, U_z, Omega_a, Omega_b), in row layout
        d = np.zeros((mm, 2, n, 5), dtype=complex)
        d[:, 0, n - 1, 0] = w.psi_in[2]
        d[:, 1, n - 1, 0] = w.dpsi_in[3]
        d[:, 0, n - 1, 1] = w.psi_in[0]
        d[:, 0, n - 1, 2] = w.psi_in[1]
        d[:, 1, n - 1, 1] = w.dpsi_in[0]
        d[:, 1, n - 1, 2] = w.dpsi_in[1]
        d[:, 1, n - 1, 3] = w.dpsi_in[2]
        d[:, 1, 0, 4] = w.dpsi_out
        self.data = d.reshape(-1, 5)
        # loads = lam x + lam_s s + lam_0
        scale = 2.0 / geometry.tau
        d1 = grid.d1
        lam = np.zeros((4, mm, 2, n), dtype=complex)
        for i in range(2):
            lam[i, :, 1, :] = w.force_omega_s[i][:, None] * scale * d1[-1][None, :]
            lam[i, :, 1, n - 1] += w.force_omega[i]
        lam[2, :, 1, n - 1] = w.torque_in
        lam[3, :, 1, 0] = w.torque_out
        self.lam = lam.reshape(4, -1)
        self.added_mass = rho * math.pi * a * a  # per unit length
        self.lam_s = np.zeros((4, 5))
        self.lam_s[0, 1] = self.added_mass * c0
        self.lam_s[1, 2] = self.added_mass * c0
        self.lam_s[2, 3] = -4.0 * math.pi * self.mu * a * a
        self.lam_s[3, 4] = 4.0 * math.pi * self.mu * b * b
        circ = np.zeros((mm, 2, n), dtype=complex)
        circ[kk, 1, :] = nu * scale * d1[-1]
        self.circ = circ.reshape(-1)
        self.lu = None
        self.responses = None

    # ------------------------------------------------------------------ pieces

    def factorise(self):
        """LU of the flow operator and the responses Y = A^-1 D."""
        self.lu = self.op.factorise()
        self.responses = self.lu.solve(self.data)
        return self

    def apply(self, x: np.ndarray) -> np.ndarray:
        """A x (the flow rows)."""
        n = self.grid.n_r
        psi, om = unpack(x, n)
        rp, ro = self.op.matvec(psi, om)
        return pack(rp, ro)

    def borders(self, bdf: Bdf, wall, q_hist: np.ndarray, g_eff: complex):
        """E, G, h and lambda_0 for the wall equations ``wall`` = (M, C, r).

        ``q_hist`` is the known part of the BDF derivative of q, (alpha1 q_n + alpha2 q_{n-1})/dt.
        """
        m_, c_, r_ = wall
        a = self.geometry.a
        lam0 = np.zeros(4)
        lam0[0] = self.added_mass * (q_hist[0] - g_eff.real)
        lam0[1] = self.added_mass * (q_hist[1] - g_eff.imag)
        e = np.empty((5, self.circ.size), dtype=complex)
        e[0] = self.circ
        e[1:] = -c_ @ self.lam
        g = np.zeros((5, 5))
        g[0, 3] = a * a * self.c0
        g[1:, 1:] = m_
        g[1:] -= c_ @ self.lam_s
        h = np.empty(5)
        h[0] = -a * a * q_hist[2]
        h[1:] = r_ + c_ @ lam0
        return e, g, h, lam0

    def loads(self, x: np.ndarray, s: np.ndarray, lam0: np.ndarray) -> np.ndarray:
        """(F_x, F_z, T_a, T_b) per unit length at the solution."""
        return (self.lam @ x).real + self.lam_s @ s + lam0

    # ------------------------------------------------------------------ solve

    def _direct(self, rhs_flow, e, g, h):
        """Solve with own factors: returns (x, s)."""
        y0 = self.lu.solve(rhs_flow)
        schur = g + e @ self.responses
        s = np.linalg.solve(schur, h - e @ y0)
        return y0 + self.responses @ s, s

    def solve(self, rhs_flow: np.ndarray, e, g, h, factors: StepSystem | None = None, *,
              tol: float = 1e-11, max_sweeps: int = 16, guess=None):
        """Solve the bordered system; with ``factors`` (another step's factorised system) by defect correction.

        Returns (x, s, sweeps) with sweeps = 0 for a direct solve, or None if the
        defect correction will not reach ``tol`` (relative change of x and s) in
        ``max_sweeps`` sweeps: it gives up as soon as the rate of its last two
        sweeps says so. A sweep (a matrix-free product and a banded solve) costs a
        tenth of a factorisation (measured, 8 x 12 to 512 x 12 points). ``guess`` = (x, s)
        starts the iteration (zero by default): the extrapolated solution saves sweeps.
        """
        if factors is None or factors is self:
            if self.lu is None:
                self.factorise()
            x, s = self._direct(rhs_flow, e, g, h)
            return x, s.real, 0
        p = factors
        # the border rows of the preconditioner are the new ones, its flow part the old factors
        schur = g + e @ p.responses
        if guess is None:
            x = np.zeros_like(rhs_flow)
            s = np.zeros(5, dtype=complex)
        else:
            x = np.array(guess[0], dtype=complex)
            s = np.array(guess[1], dtype=complex)
        previous = math.inf
        for sweep in range(1, max_sweeps + 1):
            r_flow = rhs_flow + self.data @ s - self.apply(x)
            r_ext = h - e @ x - g @ s
            y0 = p.lu.solve(r_flow)
            ds = np.linalg.solve(schur, r_ext - e @ y0)
            dx = y0 + p.responses @ ds
            x += dx
            s += ds
            change = max(np.linalg.norm(dx) / max(np.linalg.norm(x), 1e-300),
                         np.linalg.norm(ds) / max(np.linalg.norm(s), 1e-300))
            if not np.isfinite(change):
                return None
            if change <= tol:
                return x, s.real, sweep
            if sweep >= 2:
                rate = change / previous
                if rate >= 1.0 or sweep + math.log(tol / change) / math.log(rate) > max_sweeps:
                    return None
            previous = change
        return None


def flow_rhs(grid: Grid, interior: np.ndarray) -> np.ndarray:
    """The flow right-hand side with ``interior`` (n_modes, n_r) on the vorticity equation's interior rows."""
    n = grid.n_r
    out = np.zeros((grid.n_modes, 2, n), dtype=complex)
    out[:, 1, 1:n - 1] = interior[:, 1:n - 1]
    return out.reshape(-1)

