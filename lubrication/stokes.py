"""Quasi-steady 2-D Stokes flow in the eccentric annulus by finite elements.

The lubrication forms (2.5)-(2.7) are leading order in delta/a. Here the full
Stokes problem

    -div(2 mu D(u)) + grad p = 0,   div u = 0,

is solved in the frame that co-rotates with the line of centres (origin at the
outer centre B, e_x from B to the inner centre A at (eps, 0), rotations
positive from e_x to e_y), with the rigid wall velocities

    inner:  u = eps' e_x + W_a z x (x - x_A),     outer:  u = W_b z x x,

W_a = Omega_a - chi', W_b = Omega_b - chi' (a rigid rotation of everything
about B carries no stress, so chi' enters only through them). By linearity and
the mirror symmetry y -> -y the fluid force and torque on the inner cylinder,
per unit length, are

    f_eps = R_eps eps',
    f_chi = R_chi_a W_a + R_chi_b W_b,
    T_a   = R_t_a W_a + R_t_b W_b,

five resistance functions of (kappa, delta/a) (:class:`StokesResistance`).

Discretisation (each choice measured against its alternatives on this
problem): a structured biquadratic mesh in bipolar coordinates
(:mod:`lubrication.stokes_mesh`) with nodes on the true circles; Taylor-Hood
Q2-Q1 elements; the symmetric-gradient form 2 mu D(u):D(v), whose natural
boundary term is the true traction (the vector-Laplacian form gives the same
velocity and a torque wrong by 2 pi mu a^2 Omega_a); one pressure value pinned
to remove the constant; one sparse LU per geometry, reused for every rigid
motion. Force and torque come from the residual of the assembled system at
the wall unknowns: with every wall value prescribed, the residual row of a
wall unknown is the weak traction, so contracting it with a unit rigid motion
of the wall gives the force or torque on it exactly as the discrete problem
sees it. This functional converges at O(h^4); integrating the traction over
the boundary converges at O(h^2) to the same values (tests/test_stokes.py).

scikit-fem (and meshio, for :func:`write_vtu`) are imported only when a
solve is asked for; they are the ``fem`` extra of the package.
"""

from __future__ import annotations

import logging
import math
import time
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from numerics.keys import Key

from .closed_form import lubrication_forces
from .geometry import Annulus, Fluid, FluidForces, Motion, check_range
from .spec import ForceModelSpec

__all__ = ["StokesResistance", "StokesFlow", "default_mesh", "stokes_resistance",
           "stokes_forces", "stokes_flow", "fluid_angular_momentum", "write_vtu", "plot_flow"]

logger = logging.getLogger(__name__)

_INSTALL_HINT = 'pip install "snail-cylinder[fem]"'

#: Quadrature order on the reference cell; the isoparametric integrands are
#: rational, and raising it from 4 to 6 moved the forces by less than 1e-8.
_INTORDER = 4

#: After one step of iterative refinement the relative residual of the
#: factorised system must be below this, else the factorisation is redone
#: with SuperLU's cautious defaults. A poor pivot sequence shows as residuals
#: of 1e-4 and more; the conditioning of thin gaps near contact alone leaves
#: up to about 5e-8 (delta/a = 0.001, kappa = 0.999), which no pivoting improves.
_RESIDUAL_TOL = 1e-6


def _require(module: str):
    """Import an optional dependency, or say how to install it."""
    try:
        return __import__(module)
    except ImportError as err:
        msg = (f"the Stokes solver needs {module}, which is not installed; "
               f"install the finite-element extra with: {_INSTALL_HINT}")
        raise ImportError(msg) from err


def default_mesh(delta_over_a: float) -> tuple[int, int]:
    """Default ``(n_around, n_across)`` for a gap ``delta_over_a``.

    Chosen from measured convergence: relative error of each resistance
    function about 1e-6 or less for kappa <= 0.9 and delta/a in [0.01, 0.41]
    at the lowest cost (``benchmarks/results/stokes.md``). Across the gap the error falls like
    n_across^-4 with a constant that grows with delta/a; 32 cells around per
    cell across balances the two directions. Around, the error of the
    quadratic circles relative to the gap grows like a/delta, hence
    n_around ~ (a/delta)^(1/4) on thin gaps.
    """
    d = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    n_across = max(4, math.ceil(14.0 * math.sqrt(d)))
    n_around = max(256, 32 * n_across, 8 * math.ceil(32.0 * (0.01 / d) ** 0.25))
    return n_around, n_across


@dataclass(frozen=True)
class StokesResistance:
    """The five Stokes resistance functions of one geometry, per unit length.

    Attributes
    ----------
    a, b, kappa, mu : float
        Radii (m), eccentricity ratio and dynamic viscosity (Pa s).
    f_eps_per_eps_dot : float
        R_eps, N s/m^2: f_eps per unit length per unit eps' (negative: the
        fluid resists the radial motion).
    f_chi_per_w_a, f_chi_per_w_b : float
        R_chi_a, R_chi_b, N s/m: f_chi per unit length per rad/s of W_a, W_b.
    t_a_per_w_a, t_a_per_w_b : float
        R_t_a, R_t_b, N s: T_a per unit length per rad/s of W_a, W_b.
    n_around, n_across : int
        Mesh cells around and across.
    dofs : int
        Unknowns of the discrete system (velocity and pressure).
    wall_time_s : float
        Time of the call: meshing, assembly, factorisation and three solves,
        or the solves alone when the factorisation of the same mesh was cached.
    """

    a: float
    b: float
    kappa: float
    mu: float
    f_eps_per_eps_dot: float
    f_chi_per_w_a: float
    f_chi_per_w_b: float
    t_a_per_w_a: float
    t_a_per_w_b: float
    n_around: int
    n_across: int
    dofs: int
    wall_time_s: float

    @property
    def delta_over_a(self) -> float:
        return (self.b - self.a) / self.a

    def forces(self, eps_dot: float, w_a: float, w_b: float,
               length: float = 1.0) -> tuple[float, float, float]:
        """(f_eps, f_chi, T_a) in N, N, N m for the whole ``length`` (m)."""
        return (length * self.f_eps_per_eps_dot * eps_dot,
                length * (self.f_chi_per_w_a * w_a + self.f_chi_per_w_b * w_b),
                length * (self.t_a_per_w_a * w_a + self.t_a_per_w_b * w_b))

    def lubrication(self) -> dict[str, float]:
        """The same five coefficients from the closed forms (2.5)-(2.7)."""
        delta = self.b - self.a
        k, omk = self.kappa, 1.0 - self.kappa
        args = (self.a, delta, self.mu, 1.0, k, omk)
        f_eps = lubrication_forces(*args, 1.0, 0.0, 0.0)[0]
        _, f_chi_a, t_a_a = lubrication_forces(*args, 0.0, 1.0, 0.0)
        _, f_chi_b, t_a_b = lubrication_forces(*args, 0.0, 0.0, 1.0)
        return {"f_eps_per_eps_dot": f_eps, "f_chi_per_w_a": f_chi_a,
                "f_chi_per_w_b": f_chi_b, "t_a_per_w_a": t_a_a, "t_a_per_w_b": t_a_b}

    def lubrication_ratios(self) -> dict[str, float]:
        """Each coefficient divided by its lubrication form (2.5)-(2.7).

        The ratios tend to 1 as delta/a -> 0 and differ from it by O(delta/a):
        smooth O(1) functions of (kappa, delta/a), fit for tabulation. Both
        f_chi coefficients are odd in kappa and vanish at kappa = 0, where
        the lubrication form (2.6) vanishes too; their ratio is even in kappa
        and has a finite limit, which one solve at kappa = 0 cannot give:
        they are returned as NaN there (a solve at kappa = 1e-4 gives the
        limit to about 1e-8).
        """
        lub = self.lubrication()
        out = {}
        for name, value in lub.items():
            if value == 0.0:
                out[name] = math.nan
            else:
                out[name] = getattr(self, name) / value
        return out


@dataclass(frozen=True)
class StokesFlow:
    """A Stokes velocity and pressure field in the eccentric annulus.

    Attributes
    ----------
    mesh : skfem.MeshQuad2
        The isoparametric mesh in m (origin at B, e_x towards A).
    velocity_basis, pressure_basis : skfem.CellBasis
        Q2 vector and Q1 scalar bases on ``mesh``.
    velocity : ndarray, shape (n_u,)
        Velocity dofs in m/s (layout of ``velocity_basis``).
    pressure : ndarray, shape (n_p,)
        Pressure dofs in Pa, defined up to a constant (zero at one node).
    forces : FluidForces
        Force and torque on the inner cylinder, whole length.
    """

    mesh: object
    velocity_basis: object
    pressure_basis: object
    velocity: np.ndarray
    pressure: np.ndarray
    forces: FluidForces

    def nodal_velocity(self) -> np.ndarray:
        """Velocity at every mesh node, shape (2, n_nodes), m/s."""
        basis = self.velocity_basis
        table = np.concatenate([basis.nodal_dofs, basis.facet_dofs, basis.interior_dofs], axis=1)
        return self.velocity[table]

    def nodal_pressure(self) -> np.ndarray:
        """Pressure at every mesh node, shape (n_nodes,), Pa.

        The bilinear pressure is linear along each edge in reference
        coordinates, so a mid-side value is the mean of the edge's ends and a
        centre value the mean of the four corners.
        """
        mesh = self.mesh
        p = self.pressure
        return np.concatenate([p, p[mesh.facets].mean(axis=0), p[mesh.t].mean(axis=0)])

    def moment_of_momentum(self) -> float:
        """The integral of x u_y - y u_x over the annulus (m^4/s): about B, in the frame of the field.

        Times rho L it is the fluid's angular momentum about B in that frame
        (:func:`fluid_angular_momentum` adds the frame's own turning).
        """
        from skfem import Functional, asm

        @Functional
        def moment(w):
            return w.x[0] * w["u"][1] - w.x[1] * w["u"][0]

        basis = self.velocity_basis
        return float(asm(moment, basis, u=basis.interpolate(self.velocity)))

    def nodal_vorticity(self) -> np.ndarray:
        """Vorticity dv/dx - du/dy at every mesh node, shape (n_nodes,), 1/s.

        L2 projection of the curl of the Q2 velocity onto scalar Q2.
        """
        from scipy.sparse.linalg import splu
        from skfem import BilinearForm, ElementQuad2, LinearForm, asm
        from skfem.helpers import curl

        scalar = self.velocity_basis.with_element(ElementQuad2())

        @BilinearForm
        def mass(u, v, _):
            return u * v

        @LinearForm
        def curl_load(v, w):
            return curl(w["u"]) * v

        m = asm(mass, scalar).tocsc()
        rhs = asm(curl_load, scalar, u=self.velocity_basis.interpolate(self.velocity))
        # scalar Q2 dofs are numbered like the mesh nodes: vertices, facets, cells
        return splu(m).solve(rhs)


class Discretisation:
    """Assembled and factorised Stokes system of one annulus with a = 1, mu = 1.

    Lengths are in units of a, so the system is a function of (b/a, eps/a)
    alone; :func:`stokes_resistance` restores the units.
    """

    def __init__(self, b: float, eps: float, n_around: int, n_across: int,
                 clustering: float):
        import scipy.sparse as sp
        from skfem import (
            Basis,
            BilinearForm,
            ElementQuad1,
            ElementQuad2,
            ElementVector,
            asm,
        )
        from skfem.helpers import ddot, div, sym_grad

        from .stokes_mesh import build_mesh

        grid = build_mesh(1.0, b, eps, n_around, n_across, clustering)
        self.mesh = grid.mesh
        self.eps = eps
        self.ubasis = Basis(grid.mesh, ElementVector(ElementQuad2()), intorder=_INTORDER)
        self.pbasis = self.ubasis.with_element(ElementQuad1())

        @BilinearForm
        def viscous(u, v, _):
            return 2.0 * ddot(sym_grad(u), sym_grad(v))

        @BilinearForm
        def divergence(u, q, _):
            return div(u) * q

        a_uu = asm(viscous, self.ubasis)
        b_pu = asm(divergence, self.ubasis, self.pbasis)
        self.n_u = a_uu.shape[0]
        self.matrix = sp.bmat([[a_uu, -b_pu.T], [-b_pu, None]], format="csr")

        # Velocity dofs of each mesh node, component by row.
        table = np.concatenate([self.ubasis.nodal_dofs, self.ubasis.facet_dofs,
                                self.ubasis.interior_dofs], axis=1)
        self.inner_dofs = table[:, grid.inner_nodes]
        self.outer_dofs = table[:, grid.outer_nodes]
        self.inner_xy = grid.mesh.doflocs[:, grid.inner_nodes]
        self.outer_xy = grid.mesh.doflocs[:, grid.outer_nodes]

        # Wall values are prescribed, and one pressure value (at a vertex of
        # the inner wall) is pinned to zero: the pressure is otherwise defined
        # up to a constant, which exerts no net force or torque on a closed wall.
        fixed = np.concatenate([self.inner_dofs.ravel(), self.outer_dofs.ravel(), [self.n_u]])
        self.fixed = fixed
        self.free = np.setdiff1d(np.arange(self.matrix.shape[0]), fixed)
        self.k_ff = self.matrix[self.free][:, self.free].tocsc()
        self.k_fd = self.matrix[self.free][:, fixed].tocsr()
        self._factorise(cautious=False)

    @property
    def dofs(self) -> int:
        return self.matrix.shape[0]

    @property
    def nbytes(self) -> int:
        """Memory held by the matrices, the LU factors and the bases' tabulated values (bytes)."""
        sparse = sum(m.data.nbytes + m.indices.nbytes + m.indptr.nbytes
                     for m in (self.matrix, self.k_ff, self.k_fd))
        factors = 12 * self.lu.nnz  # a float64 value and an int32 index per nonzero
        tables = sum(a.nbytes for basis in (self.ubasis, self.pbasis) for values in basis.basis
                     for a in values if isinstance(a, np.ndarray))
        return sparse + factors + tables

    def _factorise(self, cautious: bool):
        from scipy.sparse.linalg import splu

        # The matrix is symmetric: a minimum-degree ordering of A + A^T with
        # diagonal pivots gave 5-12 times less fill and time than SuperLU's
        # default column ordering with partial pivoting, at equal residuals.
        # splu, not spsolve: spsolve may hand over to UMFPACK, whose default
        # pivoting is poor on this saddle-point system.
        if cautious:
            self.lu = splu(self.k_ff)
        else:
            self.lu = splu(self.k_ff, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                           options={"SymmetricMode": True})
        self.cautious = cautious

    def _solve_free(self, rhs: np.ndarray) -> np.ndarray:
        norm = np.linalg.norm(rhs)
        if norm == 0.0:
            return np.zeros_like(rhs)
        # One step of iterative refinement: diagonal pivoting may leave
        # small pivots, which the refinement repairs at the cost of one solve.
        x = self.lu.solve(rhs)
        x += self.lu.solve(rhs - self.k_ff @ x)
        res = np.linalg.norm(rhs - self.k_ff @ x) / norm
        if res > _RESIDUAL_TOL:
            if not self.cautious:
                logger.info("Residual %.1e after refinement; refactorising with "
                            "partial pivoting.", res)
                self._factorise(cautious=True)
                return self._solve_free(rhs)
            logger.warning("Stokes solve: relative residual %.1e after refinement.", res)
        return x

    def inner_motion(self, u_x: float, u_y: float, w: float) -> np.ndarray:
        """Nodal values on the inner wall of u_x e_x + u_y e_y + w z x (x - x_A)."""
        x, y = self.inner_xy
        return np.array([u_x - w * y, u_y + w * (x - self.eps)])

    def outer_motion(self, w: float) -> np.ndarray:
        """Nodal values on the outer wall of w z x x."""
        x, y = self.outer_xy
        return np.array([-w * y, w * x])

    def solve(self, eps_dot: float, w_a: float, w_b: float, v_y: float = 0.0) -> np.ndarray:
        """Velocity-pressure vector for the rigid wall motion (eps', W_a, W_b).

        ``v_y`` translates the inner cylinder along e_y as well; it is zero
        for the motions of the line-of-centres frame and serves the checks of
        the resistance matrix.
        """
        x = np.zeros(self.dofs)
        x[self.inner_dofs] = self.inner_motion(eps_dot, v_y, w_a)
        x[self.outer_dofs] = self.outer_motion(w_b)
        x[self.free] = self._solve_free(-(self.k_fd @ x[self.fixed]))
        return x

    def loads(self, x: np.ndarray) -> dict[str, float]:
        """Fluid force and torque on both walls from the residual of ``x``.

        The residual row of a wall unknown is the weak form of -(sigma n) with
        n the outward normal of the fluid, i.e. minus the fluid's traction on
        the wall. Its contraction with a unit rigid motion of the wall is minus
        the force (translation) or torque (rotation) of the fluid on the wall.
        """
        return self.residual_loads(self.matrix @ x)

    def residual_loads(self, r: np.ndarray) -> dict[str, float]:
        """Force and torque on both walls from a residual vector ``r`` (see :meth:`loads`).

        Any discretisation that shares these unknowns (the Navier-Stokes
        residual, with its convective rows) gets its wall loads the same way.
        """
        r_in, r_out = r[self.inner_dofs], r[self.outer_dofs]

        def contract(res, motion):
            return -float(np.sum(res * motion))

        return {
            "fx": contract(r_in, self.inner_motion(1.0, 0.0, 0.0)),
            "fy": contract(r_in, self.inner_motion(0.0, 1.0, 0.0)),
            "torque_a": contract(r_in, self.inner_motion(0.0, 0.0, 1.0)),
            "outer_fx": -float(np.sum(r_out[0])),
            "outer_fy": -float(np.sum(r_out[1])),
            "torque_b": contract(r_out, self.outer_motion(1.0)),
        }


def _check_geometry(a, b, kappa, n_around, n_across, clustering):
    a = check_range("a", a, 0.0, math.inf, low_open=True, unit="m")
    b = check_range("b", b, a, math.inf, low_open=True, unit="m (b > a)")
    kappa = check_range("kappa", kappa, 0.0, 1.0)
    clustering = check_range("clustering", clustering, 0.0, 1.0, high_open=False)
    auto_around, auto_across = default_mesh((b - a) / a)
    n_around = auto_around if n_around is None else n_around
    n_across = auto_across if n_across is None else n_across
    for name, n, low in (("n_around", n_around, 8), ("n_across", n_across, 1)):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < low:
            msg = f"{name} must be an integer >= {low}, got {n!r}"
            raise ValueError(msg)
    return a, b, kappa, int(n_around), int(n_across), clustering


#: Memory the cached factorised systems may hold together (bytes); the least recently
#: used go first. A system of the default mesh at delta/a = 0.41 holds about 60 MB:
#: one such is kept (its flow field and forces share it); solves of ever new
#: geometries, as along a trajectory, gain nothing from more.
CACHE_BYTES = 64e6

_CACHE: OrderedDict = OrderedDict()


def clear_cache() -> None:
    """Drop every cached factorised system."""
    _CACHE.clear()


def _discretisation(b_over_a, eps_over_a, n_around, n_across, clustering):
    """The factorised system of one geometry and mesh, reused while it stays in the cache."""
    key = (b_over_a, eps_over_a, n_around, n_across, clustering)
    disc = _CACHE.pop(key, None)
    if disc is None:
        _require("skfem")
        # Make room before building, taking the new system to be as large as the largest
        # cached: evicted only afterwards, the old systems and the new one's assembly and
        # factorisation would be held together (measured: 168 MB against 100 MB at the peak).
        while _CACHE and sum(d.nbytes for d in _CACHE.values()) + max(d.nbytes for d in _CACHE.values()) > CACHE_BYTES:
            _CACHE.popitem(last=False)
        disc = Discretisation(*key)
    _CACHE[key] = disc
    while len(_CACHE) > 1 and sum(d.nbytes for d in _CACHE.values()) > CACHE_BYTES:
        _CACHE.popitem(last=False)
    return disc


def stokes_resistance(a: float, b: float, kappa: float, *, n_around: int | None = None,
                      n_across: int | None = None, clustering: float = 0.5,
                      mu: float = 1.0) -> StokesResistance:
    """The five Stokes resistance functions of one eccentric annulus.

    Parameters
    ----------
    a, b : float
        Inner and outer radius (m), ``0 < a < b``.
    kappa : float
        Eccentricity ratio eps/(b - a) in [0, 1).
    n_around, n_across : int, optional
        Mesh cells around the annulus and across the gap; by default
        :func:`default_mesh` of delta/a. The cost grows about like their
        product; the error falls like the fourth power of each.
    clustering : float
        Angular clustering of the cells into the narrow gap, in [0, 1]
        (:mod:`lubrication.stokes_mesh`).
    mu : float
        Dynamic viscosity (Pa s).

    Returns
    -------
    StokesResistance

    Notes
    -----
    Three solves share one factorisation: radial translation (R_eps), inner
    rotation (R_chi_a, R_t_a) and outer rotation (R_chi_b, R_t_b). The
    problem is solved with lengths in units of a and mu = 1; per unit
    length, forces per velocity scale with mu, forces per rotation rate with
    mu a, torques per rotation rate with mu a^2.
    """
    a, b, kappa, n_around, n_across, clustering = _check_geometry(
        a, b, kappa, n_around, n_across, clustering)
    mu = check_range("mu", mu, 0.0, math.inf, low_open=True, unit="Pa s")
    start = time.perf_counter()
    delta_hat = b / a - 1.0
    disc = _discretisation(b / a, kappa * delta_hat, n_around, n_across, clustering)
    radial = disc.loads(disc.solve(1.0, 0.0, 0.0))
    inner = disc.loads(disc.solve(0.0, 1.0, 0.0))
    outer = disc.loads(disc.solve(0.0, 0.0, 1.0))
    wall = time.perf_counter() - start
    logger.info("Stokes resistance: kappa %g, delta/a %g, %d x %d cells, %d unknowns, %.2f s.",
                kappa, delta_hat, n_around, n_across, disc.dofs, wall)
    return StokesResistance(
        a=a, b=b, kappa=kappa, mu=mu,
        f_eps_per_eps_dot=mu * radial["fx"],
        f_chi_per_w_a=mu * a * inner["fy"],
        f_chi_per_w_b=mu * a * outer["fy"],
        t_a_per_w_a=mu * a * a * inner["torque_a"],
        t_a_per_w_b=mu * a * a * outer["torque_a"],
        n_around=n_around, n_across=n_across, dofs=disc.dofs, wall_time_s=wall)


def stokes_forces(annulus: Annulus, motion: Motion, fluid: Fluid, **mesh_opts) -> FluidForces:
    """Exact (Stokes) force and torque on the inner cylinder, whole length.

    Parameters
    ----------
    annulus, motion, fluid
        Geometry, instantaneous velocities and fluid (:mod:`lubrication.geometry`).
    **mesh_opts
        ``n_around``, ``n_across``, ``clustering`` of :func:`stokes_resistance`.

    Returns
    -------
    FluidForces
        f_eps, f_chi (N) and T_a (N m), ``model="stokes"``.
    """
    r = stokes_resistance(annulus.a, annulus.b, annulus.kappa, mu=fluid.mu, **mesh_opts)
    f = r.forces(motion.eps_dot, motion.w_a, motion.w_b, annulus.length)
    return FluidForces(*f, model="stokes")


def stokes_flow(annulus: Annulus, motion: Motion, fluid: Fluid, *,
                n_around: int | None = None, n_across: int | None = None,
                clustering: float = 0.5) -> StokesFlow:
    """Velocity and pressure of the Stokes flow for one instant, in SI units.

    Parameters are those of :func:`stokes_forces`. The fields are in the
    frame of the line of centres (origin at B, e_x towards A), where the walls
    move with eps' e_x + W_a z x (x - x_A) and W_b z x x.

    Returns
    -------
    StokesFlow
    """
    from skfem import Basis, ElementQuad1, ElementQuad2, ElementVector

    a, b, kappa, n_around, n_across, clustering = _check_geometry(
        annulus.a, annulus.b, annulus.kappa, n_around, n_across, clustering)
    disc = _discretisation(b / a, kappa * (b / a - 1.0), n_around, n_across, clustering)
    # In units of a the wall speeds stay in m/s: rotation rates become a W.
    x = disc.solve(motion.eps_dot, a * motion.w_a, a * motion.w_b)
    loads = disc.loads(x)
    mu, length = fluid.mu, annulus.length
    forces = FluidForces(mu * length * loads["fx"], mu * length * loads["fy"],
                         mu * length * a * loads["torque_a"], model="stokes")
    mesh = disc.mesh.scaled(a)
    ubasis = Basis(mesh, ElementVector(ElementQuad2()), intorder=_INTORDER)
    pbasis = ubasis.with_element(ElementQuad1())
    # p = mu p_hat / a: stresses scale with mu and with one inverse length.
    return StokesFlow(mesh=mesh, velocity_basis=ubasis, pressure_basis=pbasis,
                      velocity=x[:disc.n_u].copy(), pressure=(mu / a) * x[disc.n_u:],
                      forces=forces)


def fluid_angular_momentum(annulus: Annulus, motion: Motion, fluid: Fluid, **mesh_opts) -> float:
    """Angular momentum about B of the quasi-steady Stokes flow in the gap, whole length (kg m^2/s).

    In the frame that moves with B without turning: rho L (M + chi' I_B), with M
    the moment of momentum of the flow of the walls' velocities relative to the
    line of centres (:meth:`StokesFlow.moment_of_momentum`) and
    I_B = pi (b^4 - a^4)/2 - pi a^2 eps^2 the polar moment of area of the
    annulus about B, which turns with the line of centres at chi'.

    It is linear in (Omega_a, Omega_b, chi'); eps' adds nothing (the squeeze
    flow is odd about the line of centres). In the concentric annulus it is
    that of the circular Couette flow, m_f (a^2 Omega_a + b^2 Omega_b)/2
    exactly, the term ``fluid_spin = "couette"`` adds to (2.4); a fluid turning
    rigidly with both walls (Omega_a = Omega_b = chi') carries rho L I_B chi' at any
    eccentricity. As the gap closes the pinch between the walls blocks the
    circulation that their rotations relative to the line of centres drive, and
    those rotations carry less than Couette flow: with lubrication theory's flux,
    2 (1 - kappa^2)/(2 + kappa^2) of it in a thin gap.

    ``mesh_opts``: ``n_around``, ``n_across``, ``clustering`` of :func:`stokes_flow`.
    """
    flow = stokes_flow(annulus, motion, fluid, **mesh_opts)
    a, b, eps = annulus.a, annulus.b, annulus.eps
    polar = 0.5 * math.pi * (b**4 - a**4) - math.pi * a * a * eps * eps
    return fluid.rho * annulus.length * (flow.moment_of_momentum() + motion.chi_dot * polar)


def write_vtu(path: str | Path, flow: StokesFlow) -> Path:
    """Write a :class:`StokesFlow` as a VTK unstructured grid for ParaView.

    The cells are biquadratic quadrilaterals (VTK type 28, meshio
    ``quad9``) with point data ``velocity`` (m/s, third component zero),
    ``pressure`` (Pa) and ``vorticity`` (1/s). The file is written under a
    temporary name and renamed, so it appears whole or not at all.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    meshio = _require("meshio")
    path = Path(path)
    mesh = flow.mesh
    points = np.vstack([mesh.doflocs, np.zeros(mesh.doflocs.shape[1])]).T
    velocity = np.vstack([flow.nodal_velocity(), np.zeros(points.shape[0])]).T
    # skfem's local node order (corners, edges 01 12 23 30, centre) is VTK's.
    cells = [("quad9", mesh.dofs.element_dofs.T)]
    out = meshio.Mesh(points, cells, point_data={
        "velocity": velocity,
        "pressure": flow.nodal_pressure(),
        "vorticity": flow.nodal_vorticity(),
    })
    tmp = path.with_name(path.name + ".tmp")
    meshio.write(tmp, out, file_format="vtu")
    tmp.replace(path)
    return path


def plot_flow(flow: StokesFlow):
    """A figure of the flow: pressure in colour, velocity arrows, and the two walls.

    The quadratic cells are drawn through their corner nodes split into two
    triangles each, which is enough for a picture; the VTU file keeps the full
    field.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.tri import Triangulation

    mesh = flow.mesh
    xy = 1e3 * mesh.doflocs  # mm
    corners = mesh.t  # the first nodes are the cell corners
    triangles = np.vstack([corners[[0, 1, 2]].T, corners[[0, 2, 3]].T])
    tri = Triangulation(xy[0], xy[1], triangles)
    pressure = flow.nodal_pressure()
    velocity = flow.nodal_velocity()
    fig, ax = plt.subplots(figsize=(6.4, 5.6))
    levels = np.linspace(pressure.min(), pressure.max(), 41)
    shade = ax.tricontourf(tri, pressure, levels=levels, cmap="RdBu_r")
    fig.colorbar(shade, ax=ax, label="pressure (Pa, up to a constant)")
    pick = np.arange(0, xy.shape[1], max(1, xy.shape[1] // 1500))
    ax.quiver(xy[0, pick], xy[1, pick], velocity[0, pick], velocity[1, pick], width=0.002)
    boundary = xy[:, mesh.boundary_nodes()]
    ax.plot(boundary[0], boundary[1], "k.", ms=0.8)
    f = flow.forces
    ax.set_title(f"Stokes flow: f_eps = {f.f_eps:.3e} N, f_chi = {f.f_chi:.3e} N, T_a = {f.T_a:.3e} N m",
                 fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm), towards the inner centre")
    ax.set_ylabel("y (mm)")
    fig.tight_layout()
    return fig


#: The gaps over which the default mesh's accuracy was measured against the exact solution
#: (benchmarks/accuracy.py): delta/a in [0.003, 1], kappa up to 0.99, where the five coefficients
#: err by at most 2.5e-6. Closer to contact the mesh does not resolve the gap (at 1 - kappa = 1e-9
#: f_chi came out 71 % low) and the exact forces of "stokes-exact" are the answer.
MEASURED_DELTA_OVER_A = (0.003, 1.0)
MEASURED_KAPPA = 0.99


def check_measured(annulus: Annulus) -> None:
    """Refuse an annulus outside the range where the finite elements' accuracy was measured."""
    lo, hi = MEASURED_DELTA_OVER_A
    if not lo <= annulus.delta_over_a <= hi:
        msg = (f"delta_over_a must be in [{lo:g}, {hi:g}] for the finite-element Stokes model, where its accuracy "
               f"was measured, got {annulus.delta_over_a:.6g}; the model 'stokes-exact' holds for [1e-4, 10]")
        raise ValueError(msg)
    if annulus.kappa > MEASURED_KAPPA:
        msg = (f"kappa must be in [0, {MEASURED_KAPPA:g}] for the finite-element Stokes model, whose mesh does not "
               f"resolve a narrower gap (measured to kappa = {MEASURED_KAPPA:g}), got 1 - kappa = "
               f"{annulus.one_minus_kappa:.3g}; the model 'stokes-exact' is exact to 1 - kappa = 1e-9")
        raise ValueError(msg)


#: The model as the registry knows it (:mod:`lubrication.registry`).
MODEL = ForceModelSpec(
    "stokes", "2-D Stokes flow by finite elements (the flow field, a check of stokes-exact): delta/a in "
    "[0.003, 1], kappa <= 0.99; in a trajectory the exact forces stand in for it", stokes_forces,
    options={"n_around": Key("finite elements: cells around the annulus (default by delta/a)", low=8, high=1 << 16,
                             integer=True),
             "n_across": Key("finite elements: cells across the gap (default by delta/a)", low=1, high=1024,
                             integer=True)},
    in_trajectories="stokes-exact", extra="fem", check=check_measured)
