r"""Three-dimensional Stokes flow in an eccentric annulus of finite length, open at its ends.

A check of the finite-length model: the five resistance coefficients of the
inner cylinder over its whole length L, from the full Stokes equations

    -div(2 mu D(u)) + grad p = 0,   div u = 0

in the gap between the cylinders, 0 <= z <= L/2 by the mid-plane symmetry, in
the frame of the line of centres (as :mod:`lubrication.stokes`): the walls move
rigidly, inner u = eps' e_x + W_a e_z x (x - x_A), outer u = W_b e_z x x, with
no axial velocity.

Boundaries
----------
* Mid-plane z = 0: mirror symmetry, w = 0 and no tangential stress (natural).
* Gap end z = L/2 (``ends="open"``): no stress, sigma n = -p_end n with p_end = 0,
  the natural condition of the symmetric-gradient form. The gap opens there
  into the end regions of the tube, which are wider than the gap in every
  direction (radius b, 1.7 cm long against delta = 0.325 cm), so their
  pressure is nearly uniform. The condition leaves out the exit (entrance)
  pressure drop where the gap flow spreads into the end region, which adds
  an O(delta) length to each end of the bearing, and the stress on the inner
  cylinder's end faces, which turn relative to the end regions' walls: a disc
  of radius a turning in unbounded fluid feels (16/3) mu a^3 (Omega_b - Omega_a)
  per face, which for both faces is (32/3) delta/(2 pi L) = 5 % of the
  thin-gap lateral torque at kappa = 0 (an estimate, not computed here).
  Meshing a reservoir would need the region in front of the end face,
  r < a, which the bipolar mesh of the gap does not cover.
* ``ends="sealed"``: a second mirror plane at z = L/2 (w = 0, no tangential
  stress): the flow is the two-dimensional one, which checks the 3-D solve
  against :func:`lubrication.stokes.stokes_resistance` on the same cross-section.

Discretisation
--------------
The structured bipolar mesh of :mod:`lubrication.stokes_mesh` extruded in z:
27-node hexahedra with their nodes on the true circles, nodes graded toward the
gap end geometrically (:func:`lubrication.reynolds2d.axial_grid`, end layer
``end_layer``); Taylor-Hood Q2-Q1; the symmetric-gradient form; one sparse LU;
loads from the residual at the inner-wall unknowns contracted with unit rigid
motions (as the 2-D solver). Lengths in units of a and mu = 1 inside, units
restored as :func:`lubrication.stokes.stokes_resistance` does.

It is slow (a minute or more per geometry for 1e-3): a check, not a force model.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass

import numpy as np

from .geometry import check_range
from .reynolds2d import axial_grid

__all__ = ["Stokes3DResistance", "extruded_mesh", "stokes3d_resistance"]

logger = logging.getLogger(__name__)

_INTORDER = 4
_RESIDUAL_TOL = 1e-6
ENDS_3D = ("open", "sealed")


def extruded_mesh(a: float, b: float, eps: float, n_around: int, n_across: int, z: np.ndarray,
                  clustering: float = 0.5):
    """27-node hexahedral mesh of the eccentric annulus between the planes z[0] and z[-1].

    The cross-section is that of :func:`lubrication.stokes_mesh.build_mesh`
    (uniform in the across-gap parameter s and the mesh angle psi); every node,
    mid-edge, mid-face and centre nodes included, is the image of its
    (s, psi, z) position, so the walls' nodes lie on the true circles.

    Returns
    -------
    mesh : skfem.MeshHex2
    s_nodes : ndarray
        The across-gap parameter of every node (0 on the inner wall, 1 on the outer).
    """
    from skfem import ElementHex2, MeshHex1, MeshHex2
    from skfem.assembly import Dofs

    from .stokes_mesh import annulus_map

    z = np.asarray(z, dtype=float)
    psi = -np.pi + 2.0 * np.pi * np.arange(n_around + 1) / n_around
    box = MeshHex1.init_tensor(np.linspace(0.0, 1.0, n_across + 1), psi, z)
    # (s, psi, z) of the 27 local nodes of every cell, through the box's own trilinear map
    local = box.mapping().F(ElementHex2.doflocs.T)
    # identify psi = pi with psi = -pi: a periodic linear mesh with the box's cell orientation
    i = np.rint(box.p[0] * n_across).astype(int)
    j = np.rint((box.p[1] + np.pi) / (2.0 * np.pi) * n_around).astype(int) % n_around
    k = np.searchsorted(z, box.p[2] - 1e-12 * max(1.0, abs(z[-1])))
    key = (i * n_around + j) * z.size + k
    unique, inverse = np.unique(key, return_inverse=True)
    points = np.zeros((3, unique.size))
    points[:, inverse] = box.p
    t = inverse[box.t]
    dofs = Dofs(MeshHex1(points, t), ElementHex2())
    s_loc, psi_loc, z_loc = local
    x_loc, y_loc = annulus_map(s_loc, psi_loc, a, b, eps, clustering)
    doflocs = np.zeros((3, dofs.N))
    s_nodes = np.zeros(dofs.N)
    for row, values in enumerate((x_loc, y_loc, z_loc)):
        doflocs[row, dofs.element_dofs] = values.T
    s_nodes[dofs.element_dofs] = s_loc.T
    return MeshHex2(doflocs, t), s_nodes


@dataclass(frozen=True)
class Stokes3DResistance:
    """The five resistance coefficients of an annulus of length L, over the whole length.

    Attributes
    ----------
    a, b, kappa, length, mu : float
        Radii, eccentricity ratio, length (m) and dynamic viscosity (Pa s).
    f_eps_per_eps_dot : float
        N s/m.
    f_chi_per_w_a, f_chi_per_w_b : float
        N s.
    t_a_per_w_a, t_a_per_w_b : float
        N m s.
    ends : str
        "open" or "sealed".
    n_around, n_across, n_axial : int
        Cells around, across and along the half length.
    dofs : int
        Unknowns of the discrete system.
    wall_time_s : float
        Meshing, assembly, factorisation and three solves.
    """

    a: float
    b: float
    kappa: float
    length: float
    mu: float
    f_eps_per_eps_dot: float
    f_chi_per_w_a: float
    t_a_per_w_a: float
    f_chi_per_w_b: float
    t_a_per_w_b: float
    ends: str
    n_around: int
    n_across: int
    n_axial: int
    dofs: int
    wall_time_s: float

    def as_tuple(self) -> tuple[float, ...]:
        return (self.f_eps_per_eps_dot, self.f_chi_per_w_a, self.t_a_per_w_a, self.f_chi_per_w_b,
                self.t_a_per_w_b)


class _Discretisation3D:
    """Assembled and factorised Stokes system of the half annulus, a = 1, mu = 1."""

    def __init__(self, b, eps, n_around, n_across, z, sealed, clustering):
        import scipy.sparse as sp
        from skfem import (
            Basis,
            BilinearForm,
            ElementHex1,
            ElementHex2,
            ElementVector,
            asm,
        )
        from skfem.helpers import ddot, div, sym_grad

        mesh, s_nodes = extruded_mesh(1.0, b, eps, n_around, n_across, z, clustering)
        self.eps = eps
        ubasis = Basis(mesh, ElementVector(ElementHex2()), intorder=_INTORDER)
        pbasis = ubasis.with_element(ElementHex1())

        @BilinearForm
        def viscous(u, v, _):
            return 2.0 * ddot(sym_grad(u), sym_grad(v))

        @BilinearForm
        def divergence(u, q, _):
            return div(u) * q

        a_uu = asm(viscous, ubasis)
        b_pu = asm(divergence, ubasis, pbasis)
        self.n_u = a_uu.shape[0]
        self.matrix = sp.bmat([[a_uu, -b_pu.T], [-b_pu, None]], format="csr")

        table = np.concatenate([ubasis.nodal_dofs, ubasis.edge_dofs, ubasis.facet_dofs, ubasis.interior_dofs],
                               axis=1)
        xyz = mesh.doflocs
        inner = np.flatnonzero(s_nodes == 0.0)
        outer = np.flatnonzero(s_nodes == 1.0)
        self.inner_dofs = table[:, inner]
        self.outer_dofs = table[:, outer]
        self.inner_xy = xyz[:2, inner]
        self.outer_xy = xyz[:2, outer]
        tol = 1e-12 * max(1.0, z[-1])
        planes = [np.flatnonzero(np.abs(xyz[2]) <= tol)]
        if sealed:
            planes.append(np.flatnonzero(np.abs(xyz[2] - z[-1]) <= tol))
        walls = np.concatenate([self.inner_dofs.ravel(), self.outer_dofs.ravel()])
        mirror = np.setdiff1d(table[2, np.concatenate(planes)], walls)
        # sealed: the pressure is defined up to a constant; pin one value
        pinned = [self.n_u] if sealed else []
        self.fixed = np.concatenate([walls, mirror, np.array(pinned, dtype=np.int64)])
        self.free = np.setdiff1d(np.arange(self.matrix.shape[0]), self.fixed)
        self.k_ff = self.matrix[self.free][:, self.free].tocsc()
        self.k_fd = self.matrix[self.free][:, self.fixed].tocsr()
        self._factorise(cautious=False)

    @property
    def dofs(self) -> int:
        return self.matrix.shape[0]

    def _factorise(self, cautious):
        from scipy.sparse.linalg import splu

        if cautious:
            self.lu = splu(self.k_ff)
        else:
            self.lu = splu(self.k_ff, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                           options={"SymmetricMode": True})
        self.cautious = cautious

    def _solve_free(self, rhs):
        norm = np.linalg.norm(rhs)
        x = self.lu.solve(rhs)
        x += self.lu.solve(rhs - self.k_ff @ x)
        res = np.linalg.norm(rhs - self.k_ff @ x) / norm
        if res > _RESIDUAL_TOL:
            if not self.cautious:
                logger.info("3-D Stokes: residual %.1e after refinement; refactorising with partial pivoting.", res)
                self._factorise(cautious=True)
                return self._solve_free(rhs)
            logger.warning("3-D Stokes solve: relative residual %.1e after refinement.", res)
        return x

    def inner_motion(self, u_x, u_y, w):
        x, y = self.inner_xy
        return np.array([u_x - w * y, u_y + w * (x - self.eps), np.zeros_like(x)])

    def outer_motion(self, w):
        x, y = self.outer_xy
        return np.array([-w * y, w * x, np.zeros_like(x)])

    def solve(self, eps_dot, w_a, w_b):
        x = np.zeros(self.dofs)
        x[self.inner_dofs] = self.inner_motion(eps_dot, 0.0, w_a)
        x[self.outer_dofs] = self.outer_motion(w_b)
        x[self.free] = self._solve_free(-(self.k_fd @ x[self.fixed]))
        return x

    def loads(self, x):
        """Force along e_x, e_y and torque about A on the inner wall of the half length (residual method)."""
        r = (self.matrix @ x)[self.inner_dofs]

        def contract(motion):
            return -float(np.sum(r * motion))

        return (contract(self.inner_motion(1.0, 0.0, 0.0)), contract(self.inner_motion(0.0, 1.0, 0.0)),
                contract(self.inner_motion(0.0, 0.0, 1.0)))


def stokes3d_resistance(a: float, b: float, kappa: float, length: float, *, n_around: int = 32,
                        n_across: int = 2, n_axial: int = 12, ends: str = "open",
                        end_layer: float | None = None, clustering: float = 0.5,
                        mu: float = 1.0) -> Stokes3DResistance:
    """The five resistance coefficients of the inner cylinder of length L, from 3-D Stokes flow.

    Parameters
    ----------
    a, b : float
        Radii (m), 0 < a < b.
    kappa : float
        Eccentricity ratio in [0, 1).
    length : float
        L (m).
    n_around, n_across : int
        Cross-section cells (:func:`lubrication.stokes.stokes_resistance`).
    n_axial : int
        Cells from the mid-plane to the gap end.
    ends : {"open", "sealed"}
        Stress-free gap end, or a mirror plane there (the 2-D flow).
    end_layer : float, optional
        l_end (m) of the geometric axial grading; default the narrowest gap
        (b - a)(1 - kappa), at least (b - a)/8.
    clustering : float
        Angular clustering of the cross-section (:mod:`lubrication.stokes_mesh`).
    mu : float
        Dynamic viscosity (Pa s).

    Returns
    -------
    Stokes3DResistance
        Over the whole length: twice the half computed.
    """
    a = check_range("a", a, 0.0, math.inf, low_open=True, unit="m")
    b = check_range("b", b, a, math.inf, low_open=True, unit="m (b > a)")
    kappa = check_range("kappa", kappa, 0.0, 1.0)
    length = check_range("length", length, 0.0, math.inf, low_open=True, unit="m")
    mu = check_range("mu", mu, 0.0, math.inf, low_open=True, unit="Pa s")
    if ends not in ENDS_3D:
        msg = f"ends must be one of {', '.join(ENDS_3D)}, got {ends!r}"
        raise ValueError(msg)
    for name, n, low in (("n_around", n_around, 8), ("n_across", n_across, 1), ("n_axial", n_axial, 1)):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < low:
            msg = f"{name} must be an integer >= {low}, got {n!r}"
            raise ValueError(msg)
    start = time.perf_counter()
    delta_hat = b / a - 1.0
    if end_layer is None:
        layer = max(delta_hat * (1.0 - kappa), delta_hat / 8.0)
    else:
        layer = check_range("end_layer", end_layer, 0.0, math.inf, low_open=True, unit="m") / a
    sealed = ends == "sealed"
    z = axial_grid(0.5 * length / a, n_axial, None if sealed else layer)
    disc = _Discretisation3D(b / a, kappa * delta_hat, n_around, n_across, z, sealed, clustering)
    radial = disc.loads(disc.solve(1.0, 0.0, 0.0))
    inner = disc.loads(disc.solve(0.0, 1.0, 0.0))
    outer = disc.loads(disc.solve(0.0, 0.0, 1.0))
    wall = time.perf_counter() - start
    logger.info("3-D Stokes: kappa %g, L/a %g, %d x %d x %d cells, %d unknowns, %.1f s.", kappa, length / a,
                n_around, n_across, n_axial, disc.dofs, wall)
    # a = 1, mu = 1 inside: forces per velocity scale with mu a, per rotation rate with mu a^2,
    # torques per rotation rate with mu a^3 (whole length: lengths carry one more a); both halves
    two = 2.0
    return Stokes3DResistance(
        a=a, b=b, kappa=kappa, length=length, mu=mu,
        f_eps_per_eps_dot=two * mu * a * radial[0],
        f_chi_per_w_a=two * mu * a * a * inner[1],
        t_a_per_w_a=two * mu * a**3 * inner[2],
        f_chi_per_w_b=two * mu * a * a * outer[1],
        t_a_per_w_b=two * mu * a**3 * outer[2],
        ends=ends, n_around=n_around, n_across=n_across, n_axial=n_axial, dofs=disc.dofs, wall_time_s=wall)
