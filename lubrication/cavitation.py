r"""Cavitation in the Reynolds solver: half-Sommerfeld, Swift-Stieber and the mass-conserving JFO model.

The liquid cannot sustain a pressure below the cavitation pressure p_cav: where
the full-film pressure of :mod:`lubrication.reynolds` would fall below it, the
film ruptures into a cavity of gas and liquid striations at p = p_cav. Section 7
of the paper reports that truncating the pressure in this way did not give the
inner cylinder enough lift, while bubbles made the device up to 20% faster;
these models let the equations of motion test that.

The reference pressure
----------------------
The annulus is sealed and the liquid incompressible, so the full-film pressure
is fixed only up to a constant, which cavitation makes matter. The choice here:
**p = p_ref at the node opposite the narrowest gap** (theta = pi for the built-in
profiles, the widest gap), the node psi = -pi of every grid. It acts as a feed,
the way a journal bearing's supply groove does: the trapped air bubble of the
experiment (the paper's figure 4) rises to the top of the annulus, which is the
widest gap while the inner cylinder lies low, and exchanges liquid with the film
at the ambient pressure. Its supply is reported (``feed_supply``); in a steady
rotation of the mass-conserving model it vanishes. With p_ref = p_cav this is
the classical journal-bearing convention (pressure p_cav at the widest gap,
Hamrock, *Fundamentals of Fluid Film Lubrication*, 1994, ch. 10), and the
half-Sommerfeld and Swift-Stieber forces reduce to the classical long-bearing
results. p_cav <= p_ref is required.

The discrete problem
--------------------
Everything lives on the cells and cell integrals of :mod:`lubrication.reynolds_kernels`
(vertex-centred finite volumes, N cells, nodes psi_j). With phi = p/(12 mu a) and,
in cell j, the conductance g_j = 1/G_j, the Couette flux k_j = (U/2) A_j/G_j and
the h^-3-weighted mean squeeze antiderivative <Q>_j = B_j/G_j, the exact
full-film cell relation reads: the cell carries the flux

    qbar_j = k_j - g_j (phi_{j+1} - phi_j),

and node j balances its dual cell (from the weighted centre of cell j-1 to that
of cell j), whose squeeze storage is s_j = <Q>_j - <Q>_{j-1} (= int a h_t):

    R_j = qbar_j - qbar_{j-1} + s_j = 0.

With every R_j = 0 this is exactly the full-film scheme (c_j = qbar_j + <Q>_j is
one constant). The models change it as follows; node 0 is the feed, phi_0 fixed.

* ``"none"``: the full film, R_j = 0, with the reference above.
* ``"half-sommerfeld"`` (Guembel): the full film, then p = max(p, p_cav). The
  force integrals (by parts, oint p' sin and oint p' omega, :mod:`lubrication.reynolds_kernels`)
  count a cell whose nodes straddle p_cav with the fraction of it above p_cav by
  linear interpolation, so that the kept pressure rises end at p_cav exactly: second
  order where the truncation point lies inside a cell, exact (the full-film rule)
  where it falls on a node. The Couette shear is kept in the cavity.
* ``"swift-stieber"`` (Reynolds conditions): the linear complementarity problem
  x_j = phi_j - phi_cav >= 0, w_j = R_j >= 0, x_j w_j = 0 (j = 1..N-1), the
  discrete form of the variational inequality whose solution has p = p_cav and
  p' = 0 at rupture. R_j >= 0 in a cavity: the diverging film would need more
  liquid than arrives (the model creates it; it does not conserve mass). The
  matrix dR/dx is a nonsingular M-matrix (a principal submatrix of the periodic
  Laplacian with conductances g), so the solution is unique.
* ``"jfo"`` (Jakobsson-Floberg-Olsson, in Elrod-Adams form): a film fraction F_j in
  [0, 1] per node, complementary to the pressure, (phi_j - phi_cav)(1 - F_j) = 0; the
  Couette flux carries F from the upwind node, qbar_j = F_up k_j - g_j (phi_{j+1} - phi_j)
  (F_up = F_j for U >= 0, F_{j+1} otherwise), the squeeze storage is F_j s_j, and
  every R_j = 0: liquid is conserved through rupture and reformation, and the
  reformation front carries a pressure gradient. **Quasi-static**: the equation
  a (F h)_t + (content flux)_theta = 0 is taken with (F h)_t = F h_t, dropping
  h F_t, the content's own time derivative. The film then follows the
  instantaneous velocities with no state of its own, which is what lets it serve
  as a force law in the equations of motion; the price is that a cavity has no
  memory: its content is whatever the present Couette transport and squeeze
  supply, so a cavity that no flux crosses (U = 0) holds no liquid (F = 0 where
  s_j != 0), and the delay with which a real cavity refills is lost.

Forces use the by-parts integrals of :mod:`lubrication.reynolds_kernels` cell by cell: a
cell that is not cavitated at both ends carries the full-film pressure through
its nodal values (flux constant c_j = ((U/2) A_j + B_j - (phi_{j+1} - phi_j))/G_j),
a cavitated cell carries p_cav; the JFO Couette shear is weighted by the film
fraction upwind of the cell (second order on any grid; the cell mean was first order on
the grid uniform in theta).

The solver
----------
If the full-film solution nowhere falls below p_cav it is returned as it is
(every model then gives the full film bit for bit). Otherwise Swift-Stieber and
JFO are solved by the primal-dual active-set method (semismooth Newton on the
min-function form of the complementarity; Hintermueller, Ito & Kunisch, SIAM J.
Optim. 13, 2002). Each pass solves one tridiagonal system (partial pivoting)
for one unknown per node: x_j at a full node, F_j (JFO) or the residual w_j
(Swift-Stieber) at a cavitated one, the feed's known values on the right; nodes
whose solution violates its sign condition switch (x_j < 0 -> cavitated;
w_j < 0 or F_j > 1 -> full; F_j < 0 -> full once nothing else switches), with a
tolerance of 1e-12 times the problem's scale so that rounding cannot cycle. The
iteration stops, exactly, when no node switches: the result satisfies the
discrete complementarity to rounding.

* Multilevel start: summing pairs of cell integrals gives the same exact scheme
  on the even nodes, so the problem is solved first on a hierarchy down to 16
  cells and each level starts from the coarser set. The passes per level stay
  at 2-5 (from the fine full film they grew as N: a pass moves a free boundary
  by about one node); measured 5 to 15 passes in all for N = 32 to 2048.
* Swift-Stieber: dR/dx is an M-matrix, for which the method terminates in
  finitely many passes from any start (the reference above).
* JFO: the matrix is not an M-matrix where a cavity's squeeze storage outweighs
  its Couette transport (a gap closing under a cavity), and sets of nodes can
  then cycle. After 8 passes a level switches one node per pass, the first
  violating one downstream of the feed (a least-index rule in the direction of
  the content's transport); a node that has switched back and forth fills its
  upstream neighbour as well (the film must reform upstream of it). If a level
  still does not settle within 2 N + 16 passes, the squeeze, which enters the
  cell integrals linearly, is switched on by continuation from rotation alone,
  each step started from the last solution, halving a step that fails down to
  1/4096 of the squeeze. Only then is RuntimeError raised; 2000 random cases over
  kappa in [0, 0.999], delta/a in [0.001, 2], speeds and pressures (the slow
  property test) and 3000 more settled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from numerics.jit import jit

from . import cavitation_kernels as _ck
from .geometry import Annulus, Fluid, FluidForces, Motion, check_finite
from .kernels import model_block
from .reynolds import (
    _CAVITATION,
    _P_CAV,
    _P_REF,
    _PROFILE,
    GapProfile,
    _theta_of_psi,
    film_rule,
    film_setup,
)

__all__ = ["CAVITATION_MODELS", "CavitatingPressure", "cavitating_forces", "cavitating_kernel", "cavitating_pressure"]

CAVITATION_MODELS = ("none", "half-sommerfeld", "swift-stieber", "jfo")


@dataclass(frozen=True)
class CavitatingPressure:
    """The film at the N nodes of the grid.

    Attributes
    ----------
    theta : ndarray, shape (N,)
        Node angles (rad); ``theta[0]`` is the reference (feed) node opposite the narrowest gap.
    p : ndarray, shape (N,)
        Absolute pressure (Pa), >= p_cav except for model "none"; ``p[0]`` = p_ref.
    film_fraction : ndarray, shape (N,)
        JFO: the liquid fraction F in [0, 1]. The other models do not track the
        content: 1 where the film is full, 0 at cavitated nodes.
    mass_residual : ndarray, shape (N,)
        R_j of the module docstring (m^2/s per unit length): net content outflow of
        node j's dual cell plus its storage rate. Zero to rounding wherever liquid
        is conserved (every node of "none" and "jfo"); >= 0 in a Swift-Stieber
        cavity; at node 0 it is the feed's supply.
    forces : FluidForces
        f_eps, f_chi (N) and T_a (N m) over the length.
    passes : int
        Active-set passes (0 when the full film does not cavitate).
    """

    theta: np.ndarray
    p: np.ndarray
    film_fraction: np.ndarray
    mass_residual: np.ndarray
    forces: FluidForces
    passes: int

    @property
    def feed_supply(self) -> float:
        """Liquid the reference node takes from the reservoir (m^2/s per unit length)."""
        return float(self.mass_residual[0])


def _check_pressures(model: str, p_cav: float, p_ref: float) -> tuple[float, float]:
    if model not in CAVITATION_MODELS:
        msg = f"cavitation model must be one of {', '.join(CAVITATION_MODELS)}, got {model!r}"
        raise ValueError(msg)
    p_cav = check_finite("p_cav", p_cav)
    p_ref = check_finite("p_ref", p_ref)
    if not p_cav <= p_ref:
        msg = (f"p_cav must not exceed p_ref (the reference node is in the film), got p_cav = {p_cav:g} Pa "
               f"and p_ref = {p_ref:g} Pa")
        raise ValueError(msg)
    return p_cav, p_ref


def _solve(annulus: Annulus, motion: Motion, fluid: Fluid, model: str, p_cav: float, p_ref: float,
           n: int, grid: str, points_per_cell: int, profile) -> CavitatingPressure:
    p_cav, p_ref = _check_pressures(model, p_cav, p_ref)
    kind, kappa, omk, kappa_g, omk_g, centre, h_tab, q_tab, rule, nodes = film_setup(
        annulus, profile, n, grid, points_per_cell)
    p, film, residual = np.empty(n), np.empty(n), np.empty(n)
    *f, passes = _ck.cavitating_film_forces(
        kind, annulus.a, annulus.b, fluid.mu, annulus.length, kappa, omk, motion.eps_dot,
        motion.w_a, motion.w_b, kappa_g, omk_g, *rule, points_per_cell,
        h_tab, q_tab, math.cos(centre), math.sin(centre), CAVITATION_MODELS.index(model),
        p_cav, p_ref, p, film, residual)
    if passes < 0:
        msg = ("the cavitation active set did not settle (2 N + 16 passes per grid level, then a continuation "
               "in the squeeze down to steps of 1/4096)")
        raise RuntimeError(msg)
    theta = centre + _theta_of_psi(nodes, kappa_g)
    return CavitatingPressure(theta, p, film, residual, FluidForces(*f, model=f"reynolds/{model}"), passes)


def cavitating_forces(annulus: Annulus, motion: Motion, fluid: Fluid, model: str = "jfo", *,
                      p_cav: float = 0.0, p_ref: float = 101325.0, n: int = 256,
                      grid: str = "sommerfeld", points_per_cell: int = 2,
                      profile: str | GapProfile = "thin") -> FluidForces:
    """Force and torque on the inner cylinder from the Reynolds equation with cavitation.

    Parameters
    ----------
    annulus, motion, fluid
        Geometry, velocities and fluid.
    model : {"none", "half-sommerfeld", "swift-stieber", "jfo"}
        The cavitation model (see the module docstring).
    p_cav, p_ref : float
        Cavitation pressure and the reference pressure at the node opposite the
        narrowest gap (Pa, absolute), p_cav <= p_ref.
    n, grid, points_per_cell, profile
        As for :func:`lubrication.reynolds.reynolds_forces`. The full-film parts are
        as accurate as there; the cavitation boundary brings a second-order error
        in 1/N (see ``validation.cavitation_checks``), hence the larger default N.

    Returns
    -------
    FluidForces
        f_eps, f_chi (N) and T_a (N m) over the length, (B13)-(B15).

    Raises
    ------
    RuntimeError
        If the active-set iteration does not settle (JFO, after its safeguards; see above).
    """
    return _solve(annulus, motion, fluid, model, p_cav, p_ref, n, grid, points_per_cell, profile).forces


def cavitating_pressure(annulus: Annulus, motion: Motion, fluid: Fluid, model: str = "jfo", *,
                        p_cav: float = 0.0, p_ref: float = 101325.0, n: int = 256,
                        grid: str = "sommerfeld", points_per_cell: int = 2,
                        profile: str | GapProfile = "thin") -> CavitatingPressure:
    """Nodal pressure, film fraction, mass balance and forces; arguments as :func:`cavitating_forces`."""
    return _solve(annulus, motion, fluid, model, p_cav, p_ref, n, grid, points_per_cell, profile)


@jit
def cavitating_kernel(data, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """The "reynolds" model's kernel with cavitation (:mod:`lubrication.kernels`): the ruptured film on the
    block's grid (:func:`lubrication.reynolds.film_block`). Where the active set does not settle the forces
    are NaN, which the integrator answers with a shorter step (:mod:`lubrication.cavitation_kernels`)."""
    block = model_block(data)
    sommerfeld, m, cpsi, spsi, vpsi, ppsi, wpsi = film_rule(block)
    kappa_g, omk_g = (kappa, omk) if sommerfeld else (0.0, 1.0)
    n = spsi.size // m
    none = np.empty(0)
    f_eps, f_chi, t_a, _ = _ck.cavitating_film_forces(
        int(block[_PROFILE]), a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, kappa_g, omk_g,
        cpsi, spsi, vpsi, ppsi, wpsi, m, none, none, 1.0, 0.0,
        int(block[_CAVITATION]), block[_P_CAV], block[_P_REF], np.empty(n), np.empty(n), np.empty(n))
    return f_eps, f_chi, t_a
