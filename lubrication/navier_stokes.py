r"""Steady 2-D Navier-Stokes flow in the eccentric annulus: where quasi-steady Stokes fails.

Every force model of the project solves quasi-steady Stokes flow. This module
solves the steady Navier-Stokes equations on the same finite-element
discretisation (:mod:`lubrication.stokes`) to measure what the neglected fluid
inertia does to the force and torque.

Frame. The walls are fixed in shape only in the frame K that rotates with the
line of centres at rate chi' (origin at the outer centre B, e_x from B to A).
There, with eps' = 0, the inner wall turns about A at W_a = Omega_a - chi', the
outer about B at W_b = Omega_b - chi', and the flow is steady when these rates
are. A uniform acceleration of B (rolling) is a uniform pseudo-gravity, the
gradient of rho (g + X_b'') . x: it only adds the buoyancy already in
(2.1)-(2.2). The momentum equation in K is

    rho (u . grad u + 2 chi' e_z x u - chi'^2 x) = -grad p + div(2 mu D(u)),   div u = 0,

with p the true pressure (the same in every frame). Both fictitious forces are
gradients in a plane flow:

* centrifugal: rho chi'^2 x = grad(rho chi'^2 |x|^2 / 2);
* Coriolis: with u = (d psi/dy, -d psi/dx), e_z x u = grad psi, so
  2 rho chi' e_z x u = grad(2 rho chi' psi).

They shift the pressure and leave the velocity unchanged. On a circle a pressure
p' gives the force -oint p' n dl = -int_disc grad p' dA and no torque about its
centre. psi is constant on the outer wall and eps' y + const on the inner one,
so, per unit length,

    inner: -rho pi a^2 chi'^2 eps e_eps + 2 rho pi a^2 chi' eps' e_chi,   outer: 0,

exactly: the displaced fluid's share of the frame's centripetal and Coriolis
accelerations (:func:`frame_forces`). Everything else (the "dynamic" force) is
the force of the same wall velocities in a non-rotating frame, a function of
(eps', W_a, W_b) alone. The rotation rate chi' itself, and with it the absolute
wall speeds Omega b and the rotation number chi' delta^2 / nu, has no other
effect on a plane flow. By default (``frame_terms="exact"``) the solver uses
this: it solves without the fictitious forces and adds their force in closed
form, which is more accurate than discretising them (their pressures are not
Q1 functions). A changing chi' adds the Euler force -rho chi'' e_z x x, which
is not a gradient (it spins the fluid up or down); it is unsteady, and
neglected here with rho du/dt.

What (2.1)-(2.2) miss. Their fluid force f is computed in the non-rotating
frame of the fluid's centre of mass (Appendix A), which lies at
-(m''_a / m_f) eps from B, so the inner centre is at (1 + m''_a/m_f) eps from
it. With Stokes flow there, the pressure of the fluid's rigid rotation at chi'
is missing from f, and f lacks

    Delta f = m''_a (1 + m''_a / m_f) (-eps chi'^2 e_eps + 2 eps' chi' e_chi);

moved to the left of (2.1)-(2.2) it turns m_eff into
m_eff - m''_a (1 + m''_a/m_f) = m'_a in the centripetal and Coriolis terms: the
buoyancy-reduced mass, as for a body in a rotating fluid. This is not an error
estimate but an exact consequence of plane Navier-Stokes flow, steady in K.

Squeeze. A radial motion eps' moves the inner wall in every frame, so no frame
makes it steady. It is solved here quasi-steadily: the instantaneous flow with
the walls' velocities, with the convective term and without rho du/dt. For a
steady eps' the neglected local derivative eps' du/d(eps) is of the same order
as the convective term kept (both ~ rho eps'^2 a / h^2 in the narrow gap), and
an acceleration eps'' adds rho eps'' against mu eps' / h^2, a Stokes number
h^2 / (nu T) for a motion on the time scale T. The squeeze results are
therefore an order-of-magnitude estimate of its inertia, not its value.

Discretisation. The Taylor-Hood Q2-Q1 system of :mod:`lubrication.stokes`
(symmetric-gradient form, one pressure pinned, curved bipolar mesh) plus the
convective form int rho ((u . grad) u) . v and the two fictitious body forces.
Newton's method with the exact Jacobian
rho ((du . grad) u + (u . grad) du), continued in the density from the Stokes
solution, with a secant predictor and step halving when an iteration fails.
Forces and torques come from the residual of the converged discrete equations
at the wall unknowns, convective rows included, exactly as for Stokes: that
is the weak form of the traction, and it still converges at O(h^4) (measured
against the exact small-eccentricity solution at Re = 20). The inertial flow
needs more cells than the Stokes one (:func:`inertial_mesh`).

Lengths are in units of a and mu = 1 inside, with the time unit T = 1 s:
rates keep their values in rad/s, eps' becomes eps'/a, and the density enters
as rho_hat = rho a^2 / (mu T) = a^2 / (nu T). Forces per unit length scale
with mu a / T, torques with mu a^2 / T, pressures with mu / T.

First inertial correction. The generalised reciprocal theorem gives the
force of the Navier-Stokes flow u on the inner wall, for any test motion
U_hat of that wall with Stokes field u_hat, as

    F . U_hat = F_Stokes . U_hat - int rho ((u . grad) u) . u_hat dA,

an identity that the discrete system satisfies exactly (the Stokes matrix is
symmetric). With u = u_Stokes it is the O(rho) term:
:func:`first_inertial_correction` returns its quadratic form in
(eps', W_a, W_b). The reflection y -> -y maps (eps', W_a, W_b) to
(eps', -W_a, -W_b), f_eps to f_eps and f_chi, T_a to -f_chi, -T_a, so at
O(rho) the rotations give f_eps only (quadratic, even) and f_chi, T_a only
through the products eps' W_a and eps' W_b; the squeeze alone gives f_eps.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from .geometry import Annulus, Fluid, FluidForces, Motion, check_finite, check_range
from .inertia import KAPPA_AXIS, TABLE_COLUMNS, frame_forces, relative_reynolds
from .stokes import _check_geometry, _discretisation, _require, default_mesh

__all__ = ["FRAME_TERMS", "MOTIONS", "InertialCoefficients", "InertialSweep", "NavierStokesForces",
           "build_error_table", "first_inertial_correction", "inertial_mesh", "inertial_sweep",
           "navier_stokes_forces", "table_row"]

logger = logging.getLogger(__name__)

#: Newton stops when the free rows' residual falls below this fraction of the
#: wall-driven Stokes load; Newton's quadratic convergence then leaves the
#: forces at rounding level after one more step.
_NEWTON_RTOL = 1e-11
_NEWTON_MAX_ITER = 12
#: Relative step and residual below which a stalled Newton iteration counts as converged.
_STEP_RTOL = 1e-12
_STALL_RTOL = 1e-8
#: A continuation step is halved at most this many times before the sweep stops.
_MAX_HALVINGS = 6


class _NavierStokesSystem:
    """Newton's method for the steady Navier-Stokes equations on a Stokes discretisation.

    ``disc`` is a :class:`lubrication.stokes.Discretisation` (a = 1, mu = 1);
    the density ``rho`` and the frame rate ``chi_dot`` are in its units
    (module docstring).
    """

    def __init__(self, disc):
        import scipy.sparse as sp
        from skfem import BilinearForm, LinearForm, asm
        from skfem.helpers import dot, grad, mul

        self.disc = disc
        self._asm = asm
        self._sp = sp

        @BilinearForm
        def convective_jacobian(du, v, w):
            return dot(mul(grad(du), w["u"]), v) + dot(mul(grad(w["u"]), du), v)

        @LinearForm
        def convective(v, w):
            return dot(mul(grad(w["u"]), w["u"]), v)

        @BilinearForm
        def coriolis(u, v, _):
            # 2 e_z x u = 2 (-u_y, u_x)
            return 2.0 * (u[0] * v[1] - u[1] * v[0])

        @LinearForm
        def centrifugal(v, w):
            return w.x[0] * v[0] + w.x[1] * v[1]

        self._convective_jacobian = convective_jacobian
        self._convective = convective
        n_u, n = disc.n_u, disc.dofs
        self.coriolis = asm(coriolis, disc.ubasis)
        self.centrifugal = asm(centrifugal, disc.ubasis)
        self._pressure_block = sp.csr_matrix((n - n_u, n - n_u))

    def wall_values(self, eps_dot: float, w_a: float, w_b: float) -> np.ndarray:
        """A vector with the rigid wall velocities on the wall unknowns, zero elsewhere."""
        d = self.disc
        x = np.zeros(d.dofs)
        x[d.inner_dofs] = d.inner_motion(eps_dot, 0.0, w_a)
        x[d.outer_dofs] = d.outer_motion(w_b)
        return x

    def inertia_vector(self, x: np.ndarray, rho: float, chi_dot: float) -> np.ndarray:
        """rho int (u.grad u + 2 chi' e_z x u - chi'^2 x) . v over every velocity test function v."""
        d = self.disc
        u = x[:d.n_u]
        out = np.zeros(d.dofs)
        if rho != 0.0:
            field_u = d.ubasis.interpolate(u)
            out[:d.n_u] = rho * (self._asm(self._convective, d.ubasis, u=field_u)
                                 + chi_dot * (self.coriolis @ u) - chi_dot**2 * self.centrifugal)
        return out

    def residual(self, x: np.ndarray, rho: float, chi_dot: float) -> np.ndarray:
        """The full residual: Stokes rows plus the inertia vector."""
        return self.disc.matrix @ x + self.inertia_vector(x, rho, chi_dot)

    def _jacobian_free(self, x: np.ndarray, rho: float, chi_dot: float):
        d, sp = self.disc, self._sp
        field_u = d.ubasis.interpolate(x[:d.n_u])
        block = rho * (self._asm(self._convective_jacobian, d.ubasis, u=field_u) + chi_dot * self.coriolis)
        jac = (d.matrix + sp.block_diag((block, self._pressure_block), format="csr")).tocsr()
        return jac[d.free][:, d.free].tocsc()

    @staticmethod
    def _factorise(jac):
        from scipy.sparse.linalg import splu

        # The Jacobian has the Stokes sparsity pattern: the symmetric-mode
        # ordering that suits the Stokes matrix factorises it faster than
        # column ordering with partial pivoting (measured); Newton
        # absorbs what little accuracy diagonal pivoting may lose.
        try:
            return splu(jac, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True})
        except RuntimeError:
            return splu(jac)

    def newton(self, x0: np.ndarray, rho: float, chi_dot: float,
               rtol: float = _NEWTON_RTOL, max_iter: int = _NEWTON_MAX_ITER) -> tuple[np.ndarray, int, bool]:
        """Newton iterations from ``x0`` (wall values already set); returns (x, iterations, converged).

        Converged when the residual of the free rows is below ``rtol`` times
        the wall-driven load, or when a step has changed the solution by less
        than :data:`_STEP_RTOL` of itself with the residual below
        :data:`_STALL_RTOL` of the load: thin gaps near contact are
        ill-conditioned enough that rounding keeps the residual above ``rtol``.
        """
        d = self.disc
        x = x0.copy()
        scale = np.linalg.norm(d.k_fd @ x[d.fixed]) + np.linalg.norm(
            self.inertia_vector(x, rho, chi_dot)[d.free]) + 1e-300
        first, step = None, math.inf
        for it in range(max_iter + 1):
            r = self.residual(x, rho, chi_dot)[d.free]
            norm = np.linalg.norm(r)
            if not np.isfinite(norm):
                return x0, it, False
            if norm <= rtol * scale or (step <= _STEP_RTOL and norm <= _STALL_RTOL * scale):
                return x, it, True
            first = norm if first is None else first
            if norm > 1e3 * first:  # diverging: leave it to a shorter continuation step
                return x0, it, False
            if it == max_iter:
                break
            jac = self._jacobian_free(x, rho, chi_dot)
            lu = self._factorise(jac)
            dx = lu.solve(r)
            dx += lu.solve(r - jac @ dx)  # one refinement step repairs small diagonal pivots
            x[d.free] -= dx
            step = np.linalg.norm(dx) / (np.linalg.norm(x[d.free]) + 1e-300)
        return x0, max_iter, False

    def loads(self, x: np.ndarray, rho: float, chi_dot: float) -> dict[str, float]:
        """Forces and torques on both walls from the full residual (see ``Discretisation.loads``)."""
        return self.disc.residual_loads(self.residual(x, rho, chi_dot))

    def continuation(self, motion: tuple[float, float, float], rhos, chi_dot: float = 0.0):
        """Solutions along increasing densities ``rhos``, from Stokes, as far as Newton converges.

        Yields ``(rho, x, iterations)`` for each density reached; intermediate
        densities inserted by step halving are solved but not yielded.
        """
        d = self.disc
        x_prev = self.wall_values(*motion)
        x_prev[d.free] = d._solve_free(-(d.k_fd @ x_prev[d.fixed]))
        rho_prev, x_older, rho_older = 0.0, None, None
        for target in rhos:
            target = float(target)
            if target == 0.0:
                x0, its, ok = self.newton(x_prev, 0.0, chi_dot)
                yield 0.0, x0, its
                continue
            rho, halvings, total = target, 0, 0
            while True:
                if x_older is not None and rho_prev > rho_older:
                    slope = (rho - rho_prev) / (rho_prev - rho_older)
                    guess = x_prev + slope * (x_prev - x_older)
                else:
                    guess = x_prev
                x, its, ok = self.newton(guess, rho, chi_dot)
                total += its
                if ok:
                    x_older, rho_older, x_prev, rho_prev = x_prev, rho_prev, x, rho
                    if rho == target:
                        break
                    rho = target
                    continue
                halvings += 1
                if halvings > _MAX_HALVINGS:
                    logger.info("Newton failed to converge at rho_hat %.4g; the sweep stops at %.4g.",
                                rho, rho_prev)
                    return
                rho = 0.5 * (rho_prev + rho)
            yield target, x_prev, total


@dataclass(frozen=True)
class NavierStokesForces:
    """Force and torque of a steady Navier-Stokes flow on both cylinders, whole length.

    Attributes
    ----------
    total : FluidForces
        On the inner cylinder: f_eps, f_chi (N), T_a about A (N m), from the
        true pressure and viscous stress, fictitious-force pressures included.
    frame : FluidForces
        The exact rotating-frame part of ``total`` (:func:`frame_forces`).
    stokes : FluidForces
        The Stokes solution on the same mesh (the project's force models).
    outer : tuple of float
        On the outer cylinder: force along e_eps and e_chi (N) and torque
        about B (N m), fictitious-force pressures included (they exert none).
    reynolds : tuple of float
        Signed relative Reynolds numbers (Re_a, Re_b, Re_sq) =
        (W_a a, W_b b, eps') delta / nu (:func:`lubrication.inertia.relative_reynolds`).
    frame_terms : str
        How the fictitious forces were treated ("exact" or "discretised").
    newton_iterations : int
        Newton iterations of the whole continuation.
    dofs : int
        Unknowns of the discrete system.
    wall_time_s : float
    """

    total: FluidForces
    frame: FluidForces
    stokes: FluidForces
    outer: tuple[float, float, float]
    reynolds: tuple[float, float, float]
    frame_terms: str
    newton_iterations: int
    dofs: int
    wall_time_s: float

    @property
    def dynamic(self) -> FluidForces:
        """``total`` minus ``frame``: the force of the same wall velocities in a non-rotating frame."""
        t, f = self.total, self.frame
        return FluidForces(t.f_eps - f.f_eps, t.f_chi - f.f_chi, t.T_a - f.T_a, model="navier-stokes dynamic")

    @property
    def inertial(self) -> FluidForces:
        """``dynamic`` minus ``stokes``: what the relative flow's inertia adds to the Stokes force."""
        d, s = self.dynamic, self.stokes
        return FluidForces(d.f_eps - s.f_eps, d.f_chi - s.f_chi, d.T_a - s.T_a, model="inertial")


def inertial_mesh(delta_over_a: float) -> tuple[int, int]:
    """Default ``(n_around, n_across)`` of the Navier-Stokes solves.

    The Stokes default (:func:`lubrication.stokes.default_mesh`) resolves the
    Stokes fields but not the inertial flow at Re* = Re delta/a of a few. Across
    the gap its 4-5 cells in thin gaps miss the inertial boundary layers: at
    delta/a = 0.01, kappa = 0.6 the force error came out 34% too large at
    Re* = 3. Around, the Galerkin convective term needs short cells where the
    wall speed is large against nu / delta: at delta/a = 0.01, kappa = 0.9
    Newton's continuation stopped at Re* = 1 with 512 cells around (the
    discrete problem loses its smooth solution branch) and reached Re* = 10
    with 1024. Hence at least 10 cells across and 100 (a/delta)^(1/2) around
    (rounded up to a multiple of 8), or the Stokes default if larger.
    Measured, force error at Re* = 30: 512 and 1024 cells around (8 across)
    agree to 1e-4 of it at delta/a = 0.01, kappa = 0.3 and 0.6; 320, 512 and
    1024 around (10 across) to 1e-5 at delta/a = 0.1, kappa = 0.6 and 0.9;
    288 x 10 and 512 x 10 to 1e-5, and 576 x 20 to 2e-4, at delta/a = 0.406,
    kappa = 0.9.
    """
    n_around, n_across = default_mesh(delta_over_a)
    thin = 8 * math.ceil(100.0 / math.sqrt(delta_over_a) / 8.0)
    return max(n_around, thin), max(n_across, 10)


@lru_cache(maxsize=4)
def _system(b_over_a, kappa, n_around, n_across, clustering):
    """The Navier-Stokes system on the (cached) Stokes discretisation of one geometry, a = 1."""
    return _NavierStokesSystem(_discretisation(b_over_a, kappa * (b_over_a - 1.0), n_around, n_across,
                                               clustering))


def _mesh_or_default(delta_over_a, n_around, n_across):
    auto_around, auto_across = inertial_mesh(delta_over_a)
    return (auto_around if n_around is None else n_around), (auto_across if n_across is None else n_across)


#: Ways of treating the fictitious forces of the rotating frame.
FRAME_TERMS = ("exact", "discretised")


def navier_stokes_forces(annulus: Annulus, motion: Motion, fluid: Fluid, *,
                         n_around: int | None = None, n_across: int | None = None,
                         clustering: float = 0.5, steps: int = 4,
                         frame_terms: str = "exact") -> NavierStokesForces:
    """Steady (quasi-steady for eps' != 0) Navier-Stokes force and torque of one instant.

    Parameters
    ----------
    annulus, motion, fluid
        Geometry, velocities (eps', chi', Omega_a, Omega_b) and fluid
        (:mod:`lubrication.geometry`), SI units.
    n_around, n_across, clustering
        Mesh, as :func:`lubrication.stokes.stokes_resistance`; by default
        :func:`inertial_mesh`.
    steps : int
        Continuation steps in the density from Stokes to ``fluid.rho``
        (equally spaced; each is halved further when Newton fails).
    frame_terms : {"exact", "discretised"}
        "exact": the flow is solved without the fictitious forces, which
        only shift the pressure, and their force (:func:`frame_forces`) is
        added in closed form. "discretised": the Coriolis and centrifugal
        forces are put into the discrete momentum equations. The Q1
        pressure cannot represent their pressures exactly, so this is less
        accurate by an amount that grows with chi' and vanishes under mesh
        refinement (tests/test_navier_stokes.py); it serves as a check.

    Returns
    -------
    NavierStokesForces

    Raises
    ------
    RuntimeError
        If the continuation cannot reach ``fluid.rho``: no steady flow was
        found on this mesh (refine it, or the steady flow may not exist).
    """
    _require("skfem")
    start = time.perf_counter()
    n_around, n_across = _mesh_or_default(annulus.delta_over_a, n_around, n_across)
    a, b, kappa, n_around, n_across, clustering = _check_geometry(
        annulus.a, annulus.b, annulus.kappa, n_around, n_across, clustering)
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        msg = f"steps must be an integer >= 1, got {steps!r}"
        raise ValueError(msg)
    if frame_terms not in FRAME_TERMS:
        msg = f"frame_terms must be one of {', '.join(FRAME_TERMS)}, got {frame_terms!r}"
        raise ValueError(msg)
    system = _system(b / a, kappa, n_around, n_across, clustering)
    # time unit 1 s: rates stay in rad/s, lengths in a (module docstring)
    unit_motion = (motion.eps_dot / a, motion.w_a, motion.w_b)
    chi_dot = motion.chi_dot if frame_terms == "discretised" else 0.0
    rho_hat = a * a / fluid.nu
    rhos = rho_hat * np.arange(1, steps + 1) / steps
    path = list(system.continuation(unit_motion, [0.0, *rhos], chi_dot))
    if len(path) < steps + 1:
        reached = path[-1][0] / rho_hat
        msg = (f"no steady Navier-Stokes flow found: the continuation stopped at {reached:.3g} of the "
               "density (refine the mesh, or the steady flow may not exist at this Reynolds number)")
        raise RuntimeError(msg)
    x_stokes, x = path[0][1], path[-1][1]
    iterations = sum(p[2] for p in path)
    mu, length = fluid.mu, annulus.length
    force_scale, torque_scale = mu * a * length, mu * a * a * length
    frame = frame_forces(annulus, motion, fluid)
    loads = system.loads(x, rho_hat, chi_dot)
    shift = (frame.f_eps, frame.f_chi) if frame_terms == "exact" else (0.0, 0.0)
    total = FluidForces(force_scale * loads["fx"] + shift[0], force_scale * loads["fy"] + shift[1],
                        torque_scale * loads["torque_a"], model="navier-stokes")
    stokes_loads = system.loads(x_stokes, 0.0, 0.0)
    stokes = FluidForces(force_scale * stokes_loads["fx"], force_scale * stokes_loads["fy"],
                         torque_scale * stokes_loads["torque_a"], model="stokes")
    outer = (force_scale * loads["outer_fx"], force_scale * loads["outer_fy"], torque_scale * loads["torque_b"])
    return NavierStokesForces(total=total, frame=frame, stokes=stokes, outer=outer,
                              reynolds=relative_reynolds(annulus, motion, fluid), frame_terms=frame_terms,
                              newton_iterations=iterations, dofs=system.disc.dofs,
                              wall_time_s=time.perf_counter() - start)


@dataclass(frozen=True)
class InertialSweep:
    """Forces against the Reynolds number along one continuation path (dimensionless).

    The motion is scaled so that its reference speed
    V = max(|eps'|, |W_a| a, |W_b| b) is one; Re = V delta / nu.

    Attributes
    ----------
    delta_over_a, kappa : float
    motion : tuple of float
        (eps', W_a, W_b, chi') in units of V and V/a.
    reynolds : ndarray, shape (n,)
        The Reynolds numbers reached (Newton converged), from 0.
    inner, outer : ndarray, shape (n, 3)
        (f_eps, f_chi, T) per unit length in units of mu V (forces) and mu V a
        (torque), on the inner cylinder (T_a about A) and on the outer one
        (along e_eps, e_chi; T_b about B). Fictitious-force pressures included.
    stopped : bool
        True if Newton stopped converging before the last Reynolds number asked for.
    newton_iterations : int
    dofs : int
    wall_time_s : float
    """

    delta_over_a: float
    kappa: float
    motion: tuple[float, float, float, float]
    reynolds: np.ndarray
    inner: np.ndarray
    outer: np.ndarray
    stopped: bool
    newton_iterations: int
    dofs: int
    wall_time_s: float
    n_around: int = field(default=0)
    n_across: int = field(default=0)

    def frame(self) -> np.ndarray:
        """The rotating-frame part of ``inner``, shape (n, 3) (:func:`frame_forces`, dimensionless)."""
        eps_dot, _, _, chi_dot = self.motion
        eps_hat = self.kappa * self.delta_over_a
        # rho a^2 V / mu = Re / delta_hat in these units
        rho_hat = self.reynolds / self.delta_over_a
        out = np.zeros((self.reynolds.size, 3))
        out[:, 0] = -rho_hat * math.pi * chi_dot**2 * eps_hat
        out[:, 1] = 2.0 * rho_hat * math.pi * chi_dot * eps_dot
        return out

    def relative_error(self) -> np.ndarray:
        """|F - F_Stokes| / |F_Stokes| for the inner force vector (f_eps, f_chi), frame part removed."""
        dyn = self.inner[:, :2] - self.frame()[:, :2]
        stokes = self.inner[0, :2]
        return np.linalg.norm(dyn - stokes, axis=1) / np.linalg.norm(stokes)

    def torque_error(self) -> np.ndarray:
        """|T_a - T_a,Stokes| / |T_a,Stokes|."""
        return np.abs(self.inner[:, 2] - self.inner[0, 2]) / abs(self.inner[0, 2])


def _unit_motion(b, eps_dot, w_a, w_b, chi_dot):
    for name, value in (("eps_dot", eps_dot), ("w_a", w_a), ("w_b", w_b), ("chi_dot", chi_dot)):
        check_finite(name, value)
    speed = max(abs(eps_dot), abs(w_a), abs(w_b) * b)
    if speed == 0.0:
        msg = "the motion must move a wall: eps_dot, w_a and w_b are all zero"
        raise ValueError(msg)
    return eps_dot / speed, w_a / speed, w_b / speed, chi_dot / speed


def inertial_sweep(delta_over_a: float, kappa: float, reynolds, *, eps_dot: float = 0.0,
                   w_a: float = 0.0, w_b: float = 0.0, chi_dot: float = 0.0,
                   n_around: int | None = None, n_across: int | None = None,
                   clustering: float = 0.5) -> InertialSweep:
    """Continue the steady flow of one motion in the Reynolds number, as far as Newton converges.

    Parameters
    ----------
    delta_over_a, kappa : float
        Geometry: (b - a)/a > 0 and eps/(b - a) in [0, 1).
    reynolds : array_like
        Increasing Reynolds numbers Re = V delta / nu >= 0, V the reference
        speed of the motion (:class:`InertialSweep`); 0 is prepended if absent.
    eps_dot, w_a, w_b, chi_dot : float
        The motion's direction (eps' in units of a per time unit, rates per
        time unit; only ratios matter): radial speed, inner and outer
        rotation relative to the line of centres, and the frame's rate.
    n_around, n_across, clustering
        Mesh, as :func:`lubrication.stokes.stokes_resistance`; by default
        :func:`inertial_mesh`.

    Returns
    -------
    InertialSweep
    """
    _require("skfem")
    start = time.perf_counter()
    d = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    n_around, n_across = _mesh_or_default(d, n_around, n_across)
    _, b, kappa, n_around, n_across, clustering = _check_geometry(
        1.0, 1.0 + d, kappa, n_around, n_across, clustering)
    reynolds = np.asarray(reynolds, dtype=float)
    if reynolds.ndim != 1 or reynolds.size == 0 or np.any(~np.isfinite(reynolds)) or np.any(reynolds < 0) \
            or np.any(np.diff(reynolds) <= 0):
        msg = "reynolds must be a non-empty increasing 1-D array of finite numbers >= 0"
        raise ValueError(msg)
    if reynolds[0] != 0.0:
        reynolds = np.concatenate([[0.0], reynolds])
    motion = _unit_motion(b, eps_dot, w_a, w_b, chi_dot)
    system = _system(b, kappa, n_around, n_across, clustering)
    rhos = reynolds / d
    reached, inner, outer, iterations = [], [], [], 0
    for rho, x, its in system.continuation(motion[:3], rhos, motion[3]):
        loads = system.loads(x, rho, motion[3])
        reached.append(rho * d)
        inner.append((loads["fx"], loads["fy"], loads["torque_a"]))
        outer.append((loads["outer_fx"], loads["outer_fy"], loads["torque_b"]))
        iterations += its
    return InertialSweep(delta_over_a=d, kappa=kappa, motion=motion, reynolds=np.array(reached),
                         inner=np.array(inner), outer=np.array(outer),
                         stopped=len(reached) < reynolds.size, newton_iterations=iterations,
                         dofs=system.disc.dofs, wall_time_s=time.perf_counter() - start,
                         n_around=n_around, n_across=n_across)


#: Order of the driving motions in :class:`InertialCoefficients`.
MOTIONS = ("eps_dot", "w_a", "w_b")


@dataclass(frozen=True)
class InertialCoefficients:
    """The first inertial correction of one geometry, per unit length, a = 1, from the Stokes fields.

    To first order in the density, with m = (eps'/a, W_a, W_b) in rad/s-like
    units (time unit T) and rho_hat = rho a^2 / (mu T),

        f_eps^(1) = rho_hat mu a/T  m . C_eps m,   f_chi^(1) = rho_hat mu a/T  m . C_chi m,
        T_a^(1)   = rho_hat mu a^2/T  m . C_t m,

    i.e. dimensionally f^(1) = rho a^3 (m . C m) and T_a^(1) = rho a^4 (m . C_t m),
    with symmetric 3 x 3 matrices C in the order of :data:`MOTIONS`. The
    Stokes resistance (first order, ``stokes``: rows f_eps, f_chi, T_a,
    columns as C, per unit rate, forces in mu a / T, torque in mu a^2 / T)
    is returned alongside, from the same fields.

    Attributes
    ----------
    delta_over_a, kappa : float
    c_eps, c_chi, c_t : ndarray, shape (3, 3)
    stokes : ndarray, shape (3, 3)
    dofs : int
    wall_time_s : float
    """

    delta_over_a: float
    kappa: float
    c_eps: np.ndarray
    c_chi: np.ndarray
    c_t: np.ndarray
    stokes: np.ndarray
    dofs: int
    wall_time_s: float


def first_inertial_correction(delta_over_a: float, kappa: float, *, n_around: int | None = None,
                              n_across: int | None = None, clustering: float = 0.5) -> InertialCoefficients:
    """O(Re) force and torque corrections by the reciprocal theorem (module docstring).

    Three driving Stokes solves (eps', W_a, W_b) and one more test field (a
    translation along e_chi); each coefficient is the integral
    -int ((u_i . grad) u_j) . u_hat_k dA, symmetrised in (i, j). The
    identity holds for the discrete system, so these are the exact
    derivatives at rho = 0 of the finite-element Navier-Stokes forces on the
    same mesh.

    Returns
    -------
    InertialCoefficients
    """
    _require("skfem")
    from skfem import Functional, asm
    from skfem.helpers import dot, grad, mul

    start = time.perf_counter()
    d = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    _, b, kappa, n_around, n_across, clustering = _check_geometry(
        1.0, 1.0 + d, kappa, n_around, n_across, clustering)
    disc = _discretisation(b, kappa * d, n_around, n_across, clustering)
    fields = [disc.solve(1.0, 0.0, 0.0), disc.solve(0.0, 1.0, 0.0), disc.solve(0.0, 0.0, 1.0)]
    tests = {"eps": fields[0], "chi": disc.solve(0.0, 0.0, 0.0, v_y=1.0), "t": fields[1]}
    n_u = disc.n_u
    interp = [disc.ubasis.interpolate(x[:n_u]) for x in fields]

    @Functional
    def advection(w):
        return dot(mul(grad(w["target"]), w["carrier"]), w["test"])

    out = {}
    for key, test in tests.items():
        test_field = disc.ubasis.interpolate(test[:n_u])
        c = np.zeros((3, 3))
        for i in range(3):
            for j in range(3):
                # (u_i . grad) u_j = grad(u_j) u_i
                c[i, j] = -asm(advection, disc.ubasis, target=interp[j], carrier=interp[i], test=test_field)
        out[key] = 0.5 * (c + c.T)
    stokes = np.array([[disc.loads(x)[k] for x in fields] for k in ("fx", "fy", "torque_a")])
    return InertialCoefficients(delta_over_a=d, kappa=kappa, c_eps=out["eps"], c_chi=out["chi"],
                                c_t=out["t"], stokes=stokes, dofs=disc.dofs,
                                wall_time_s=time.perf_counter() - start)


# -- the table of the first inertial correction ------------------------------------------------------

def table_row(coefficients) -> np.ndarray:
    """The :data:`lubrication.inertia.TABLE_COLUMNS` of one :class:`InertialCoefficients`."""
    k, d = coefficients.kappa, coefficients.delta_over_a
    b = 1.0 + d
    zeta = math.sqrt(1.0 - k * k)
    r, c = coefficients.stokes, coefficients.c_eps
    chi_scale = (2.0 + k * k) * zeta * d * d / k
    return np.array([r[1, 1] * chi_scale, r[1, 2] * chi_scale / b,
                     c[1, 1] / k, c[1, 2] / (k * b), c[2, 2] / (k * b * b)])


def build_error_table(kappa_nodes, delta_nodes, **mesh) -> np.ndarray:
    """Solve :func:`first_inertial_correction` on a grid; shape (nk, nd, 5): the table of
    :mod:`lubrication.inertia_table`, which ``generators/inertia_table.py`` writes.

    A node at kappa = 0 is solved at :data:`lubrication.inertia.KAPPA_AXIS`. ``mesh`` goes to the solver.
    """
    table = np.zeros((len(kappa_nodes), len(delta_nodes), len(TABLE_COLUMNS)))
    for i, k in enumerate(kappa_nodes):
        for j, d in enumerate(delta_nodes):
            table[i, j] = table_row(first_inertial_correction(d, max(k, KAPPA_AXIS), **mesh))
    return table
