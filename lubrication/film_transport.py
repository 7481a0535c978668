r"""The mass-conserving (JFO / Elrod-Adams) film with its content in the state, and a gauge that does not rectify.

:mod:`lubrication.cavitation` solves the JFO film quasi-statically: every force
evaluation solves a steady complementarity problem for the instantaneous
velocities, so a cavity has no memory, and the reference pressure is a liquid
feed at the widest gap. Both are put right here: the film content of every cell
is part of the state of the equations of motion, and the film may exchange liquid
with the end reservoirs of the closed device, whose trapped bubble sets the
pressure.

The film
--------
In the frame of the line of centres (thin gap h = delta (1 - kappa cos theta),
wall speeds U_a = a W_a, U_b = a W_b, U = U_a + U_b) a fraction F of the gap
holds liquid (JFO: liquid striations at p = p_cav in a cavity). The liquid area
per unit theta is a h F, and

    d/dt (a h F) + d/dtheta [ F h U/2 - h^3 dphi/dtheta ] + e (phi - phi_res) = 0,
    phi = p/(12 mu a),   p >= p_cav,   F <= 1,   (p - p_cav)(1 - F) = 0,

with the Poiseuille flux only where the film is full (phi is constant in a
cavity) and e the exchange with the end reservoirs (the bubble gauge below; 0
with the feed). The quasi-static model of :mod:`lubrication.cavitation` drops
h dF/dt. In a cavity the content is a passive scalar carried at the mean wall
speed U/2: its flux F h U/2 has one direction, from upstream, and a reformation
front is a moving discontinuity of F. So the Couette flux of a cell carries the
film fraction of its upwind node, as the Elrod-Adams scheme does: the scheme is
monotone (F stays in [0, 1] in a cavity without overshoots at the fronts, which a
centred flux would give), exactly conservative, and its steady form is the
discretisation of :mod:`lubrication.cavitation`.

The discrete film
-----------------
The cells are the Reynolds solver's, on the Sommerfeld grid that follows the gap
(kappa_g = kappa, so the nodes theta_j(t) move: theta_j' = -kappa' sin(theta_j)/zeta^2
at fixed psi). Node j owns the dual cell between the faces theta_f at the
psi-midpoints of its two cells; its gap area V_j = a delta [theta - kappa sin theta]
between the faces has the exact rate V_j' = Q~_j - Q~_{j-1}, where Q~ = Q + a h
theta_f' = -a eps' sin(theta_f) (1 + 1/(1 + kappa cos psi_f)) is the area swept
through the moving face (Q = -a eps' sin theta is the squeeze antiderivative).

The state of node j is its void (gas) area v_j = V_j - M_j >= 0, M_j its liquid
area, F_j = 1 - v_j/V_j. Across face j the liquid flux relative to the face is

    qbar_j = F_up(U) k_j + F_up(S_j) S_j - g_j (x_{j+1} - x_j),   S_j = <Q>_j - Q~_j,

with k_j = (U/2) A_j/G_j, g_j = 1/G_j and <Q>_j = B_j/G_j the cell integrals of
:mod:`lubrication.reynolds_kernels` (x = phi - phi_cav). For a full film (F = 1) this is
exactly the full-film flux through the moving face, q - a h theta_f' = c_j - Q~_j with
c_j = k_j + <Q>_j - g_j (x_{j+1} - x_j) the cell's flux constant, so the full-film
pressures are the Reynolds solver's, exactly, at any motion. In a cavity, S_j moves
content with the grid; each part is carried at the film fraction of the node it
comes from. The balance of dual cell j is

    M_j' = qbar_{j-1} - qbar_j - e_j,    v_j' = V_j' - M_j',

so the liquid in the film changes exactly by what the reservoirs take: sum_j M_j
+ R is a linear invariant of the state (R, the liquid the reservoir has taken,
is a state too), kept to rounding by any Runge-Kutta method, Radau IIA included.
At a steady motion V_j' = S_j = 0, and the steady balances and complementarity
are those of the steady JFO solver, which is therefore the end state.

Full cells: an index-1 complementarity at every evaluation
----------------------------------------------------------
In a full cell the content is slaved (v_j = 0) and the pressure is the Lagrange
multiplier of that constraint; in a cavity x_j = 0 and v_j evolves. Which is which
changes along a run, cell by cell. Rather than switching between DAEs at events,
the constraint is imposed on the rates, relaxed towards v = 0 with a time
``relaxation`` (tau_r): at every evaluation of the right-hand side

    x_j >= 0,   w_j = v_j' + v_j/tau_r >= 0,   x_j w_j = 0     (every node).

A cavity (v_j > 0, far from full) has w_j > 0 and x_j = 0; a pressed node holds
v_j' = -v_j/tau_r, so v = 0 is invariant and drift decays; a filling node closes
its last void exponentially in tau_r instead of at an instant, and the
complementarity (p - p_cav)(1 - F) = 0 holds up to F = 1 - O(tau_r v') while
it does. Since v_j' is affine in x through the conductance Laplacian A (plus the
end conductances), w = A x + b is a linear complementarity problem with an
M-matrix: one solution, Lipschitz in b, so the right-hand side is Lipschitz in
the state (piecewise smooth, kinks where a node switches), which the implicit
Radau IIA integrator takes with a finite-difference Jacobian. The void, not
the content, is the state so that a pressed node sits at v = 0 whatever the
gap does, and the stiff relaxation does not turn a perturbation of the
geometry into a switch. tau_r must be far below the time the walls take to
carry liquid across a cell; its effect is O(tau_r) (``validation.cavitation_transient``:
tau_r = 1e-6 s against 1e-7 s moves the gap history of the steel apparatus'
release by 8e-5 of 1 - kappa).

The gauge
---------
``Feed(p_ref)``: node 0 (the widest gap) is held at p_ref and takes or gives
whatever liquid keeps it full: the convention of :mod:`lubrication.cavitation`.
It makes the reference the extreme of a squeeze pressure: approaching, the whole
film is above p_ref; separating, the whole film is below it and cavitates (the
half-Sommerfeld f_eps of a pure separation is 0): a rectifier that comes from the
gauge, not from the physics.

``Bubble(pressure, volume)``: the device is closed and its oil incompressible.
The gap opens at both ends into the end reservoirs (:mod:`lubrication.finite_length`),
which hold the trapped bubble, an ideal gas at ``pressure`` when of ``volume``.
Every cell exchanges liquid with them through the ends,

    e_j = lam_j (x_j - x_res),   lam_j = eps_end h_j^3 dtheta_j,

the Poiseuille flux through the end layers, taken full also beside a cavity (whose
pressure, p_cav < p_res, then draws liquid in from the ends): a film of length L whose pressure
relaxes to p_res over an axial length ell near each end leaks 2 h^3 (p - p_res)/(12 mu ell)
per unit arc, that is (2 a^2/(L ell)) h^3 (phi - phi_res) per radian and unit length,
eps_end = 2a/L for the long bearing's ell = a. The value
taken, eps_end = 1/F_0 - 1 with F_0 = 1 - tanh(l/2)/(l/2) (l = L/a) the exact
finite-length factor at kappa -> 0 (:func:`lubrication.finite_length.small_eccentricity_factor`),
makes the forces of a full film at small kappa exactly those of the annulus of
length L with open ends (0.1829 for the apparatus; 2a/L = 0.155 is its long-bearing
limit). Liquid the reservoirs take compresses the bubble: its volume is
V_b = volume - L R and, isothermally, p_res = pressure volume / V_b (not below
p_cav: the reservoir cavitates rather than hold tension). The reference is then a
weighted mean of the pressure, not its extreme, and approach and separation are
treated alike: a film cavitates where its pressure falls p_res - p_cav below that
mean, on either side, and only as fast as the ends let liquid go (a cavity in a
closed, incompressible film needs its volume of liquid to leave the gap). The
total oil, L (sum_j M_j + R), is conserved exactly. The end layer is the one of
kappa -> 0 at every kappa, so this is a model of the finite length, exact in that
limit only: for the apparatus (N = 128) it lowers the full film's f_eps and f_chi by
15% at small kappa, by 9% and 12% at kappa = 0.5 and by 2% and 6% at kappa = 0.9,
within 3% of the finite-length factors of :mod:`lubrication.finite_length` (0.886 and
0.865 at 0.5, 0.954 and 0.917 at 0.9).

The bubble is what the film's cavities compress: a cavity of sum_j v_j per unit
length raises p_res by about pressure L sum_j v_j / volume (1% of an atmosphere for
1e-8 m^3 in 1 cm^3), while p_cav stays where it is. With a margin p_res - p_cav of a
few Pa it is therefore the bubble's compression, not the margin, that sets where the
film ruptures (the release of ``validation.cavitation_transient`` ends with
p_res - p_cav near 900 Pa after starting at 3 Pa).

Forces
------
The by-parts integrals of :mod:`lubrication.reynolds_kernels` cell by cell, as in
:mod:`lubrication.cavitation`: a cell at p_cav at both ends carries p_cav, the
others the full-film profile through their nodal pressures; the Couette shear is
weighted by the cell's mean film fraction. On the Sommerfeld grid every cell has
the same int h^-1 dtheta = dpsi/(delta zeta), so this torque equals, to rounding,
the one weighted by the upwind node's fraction, the fraction of the liquid the
cell carries.

Limits: the thin gap only; first order where F varies (upwind), second order
at the cavity boundaries, as the steady solver.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import film_kernels as _fk
from .finite_length import small_eccentricity_factor
from .geometry import Annulus, Fluid, FluidForces, Motion, check_finite, check_range
from .reynolds import _check_discretisation, _theta_of_psi, psi_rule

__all__ = ["Bubble", "Feed", "FilmRates", "TransportedFilm", "dual_areas", "end_conductance", "film_rates",
           "leaky_half_sommerfeld_forces"]


@dataclass(frozen=True)
class Feed:
    """A liquid feed holding node 0 (the widest gap) at ``p_ref`` (Pa), as :mod:`lubrication.cavitation` does."""

    p_ref: float = 101325.0


@dataclass(frozen=True)
class Bubble:
    """End reservoirs and their trapped bubble (module docstring).

    Attributes
    ----------
    pressure : float
        Gas pressure (Pa) with the reservoirs holding no liquid from the film (R = 0).
    volume : float
        Gas volume (m^3) at that pressure.
    end_conductance : float or None
        eps_end, dimensionless; None takes 1/F_0 - 1 from the annulus' L/a.
    """

    pressure: float = 101325.0
    volume: float = 1e-6
    end_conductance: float | None = None


@dataclass(frozen=True)
class TransportedFilm:
    """The transported JFO film model (module docstring).

    Attributes
    ----------
    n : int
        Cells around the gap, at least 8.
    points_per_cell : int
        Gauss points per cell.
    p_cav : float
        Cavitation pressure (Pa).
    gauge : Feed or Bubble
        Where the film meets its reservoir.
    relaxation : float
        Time (s) in which a pressed node's void closes; far below a cell's Couette transit time.
    """

    n: int = 128
    points_per_cell: int = 2
    p_cav: float = 0.0
    gauge: Feed | Bubble = Feed()
    relaxation: float = 1e-6

    def __post_init__(self):
        _check_discretisation(self.n, "sommerfeld", self.points_per_cell)
        check_finite("p_cav", self.p_cav)
        check_range("relaxation", self.relaxation, 0.0, math.inf, low_open=True, unit="s")
        if isinstance(self.gauge, Feed):
            check_finite("p_ref", self.gauge.p_ref)
            if not self.p_cav <= self.gauge.p_ref:
                msg = f"p_cav must not exceed the feed's p_ref = {self.gauge.p_ref:g} Pa, got {self.p_cav:g} Pa"
                raise ValueError(msg)
        elif isinstance(self.gauge, Bubble):
            check_range("bubble pressure", self.gauge.pressure, 0.0, math.inf, low_open=True, unit="Pa")
            check_range("bubble volume", self.gauge.volume, 0.0, math.inf, low_open=True, unit="m^3")
            if self.gauge.end_conductance is not None:
                check_range("end_conductance", self.gauge.end_conductance, 0.0, math.inf, low_open=True)
        else:
            msg = f"gauge must be a Feed or a Bubble, got {type(self.gauge).__name__}"
            raise TypeError(msg)

    @property
    def name(self) -> str:
        return "reynolds/jfo-transported/" + ("feed" if isinstance(self.gauge, Feed) else "bubble")

    def reservoir_pressure(self, length: float, reservoir) -> np.ndarray:
        """The pressure the film is measured from (Pa): p_ref of the feed, or the bubble's.

        ``reservoir`` (m^2, scalar or array) is the liquid the reservoir has taken per unit
        length of a film of ``length`` (m): the bubble's volume is then ``volume - length * reservoir``.
        """
        if isinstance(self.gauge, Feed):
            return np.full(np.shape(reservoir), self.gauge.p_ref)
        with np.errstate(divide="ignore"):
            gas = self.gauge.volume - length * np.asarray(reservoir, dtype=float)
            p_gas = np.where(gas > 0.0, self.gauge.pressure * self.gauge.volume / gas, np.inf)
        return np.maximum(p_gas, self.p_cav)

    def kernel_data(self, a: float, length: float) -> tuple:
        """The model's arguments of :func:`lubrication.film_kernels.film_rates`, after the motion's."""
        rule, faces, node_p = _grid(self.n, self.points_per_cell)
        if isinstance(self.gauge, Feed):
            gauge = (_fk.FEED, float(self.p_cav), float(self.gauge.p_ref), 0.0, 0.0)
        else:
            eps_end = self.gauge.end_conductance
            if eps_end is None:
                eps_end = end_conductance(length / a)
            gauge = (_fk.BUBBLE, float(self.p_cav), float(self.gauge.pressure), float(self.gauge.volume),
                     float(eps_end))
        return (*rule, self.points_per_cell, faces, node_p, *gauge, float(self.relaxation))


def end_conductance(length_over_a: float) -> float:
    """eps_end = 1/F_0 - 1: the exchange coefficient whose full film has the exact kappa -> 0 finite-length factor."""
    return 1.0 / small_eccentricity_factor(length_over_a) - 1.0


def _grid(n: int, m: int):
    """The cells' Gauss rule, the faces' (sin psi, 1 + cos psi, sin psi/2, cos psi/2) and the nodes' 1 + cos psi."""
    rule, nodes = psi_rule(n, m)
    psi_f = nodes + np.pi / n
    faces = (np.sin(psi_f), 2.0 * np.cos(0.5 * psi_f) ** 2, np.sin(0.5 * psi_f), np.cos(0.5 * psi_f))
    return rule, faces, 2.0 * np.cos(0.5 * nodes) ** 2


@dataclass(frozen=True)
class FilmRates:
    """The film at one instant, from its state.

    Attributes
    ----------
    theta : ndarray, shape (N,)
        Node angles (rad); ``theta[0]`` = pi, the widest gap.
    p : ndarray, shape (N,)
        Pressure (Pa, absolute), >= p_cav.
    film_fraction : ndarray, shape (N,)
        F_j = 1 - void_j / V_j.
    area : ndarray, shape (N,)
        V_j, the gap area of each dual cell per unit length (m^2).
    d_void : ndarray, shape (N,)
        dvoid_j/dt (m^2/s).
    flux : ndarray, shape (N,)
        Liquid carried across face j, from node j to node j+1, relative to the moving
        face (m^2/s per unit length): qbar_j of the module docstring.
    d_reservoir : float
        Liquid the reservoir takes from the film per unit time and length (m^2/s).
    reservoir_pressure : float
        The pressure the film is measured from (Pa): the feed's p_ref, or the bubble's.
    forces : FluidForces
    passes : int
        Active-set passes of the complementarity problem.
    """

    theta: np.ndarray
    p: np.ndarray
    film_fraction: np.ndarray
    area: np.ndarray
    d_void: np.ndarray
    flux: np.ndarray
    d_reservoir: float
    reservoir_pressure: float
    forces: FluidForces
    passes: int


def dual_areas(annulus: Annulus, n: int) -> np.ndarray:
    """V_j, the thin-gap area a int h dtheta of each dual cell (m^2 per unit length), summing to 2 pi a delta."""
    _, faces, node_p = _grid(n, 1)
    out = [np.empty(n) for _ in range(5)]
    _fk.film_geometry(annulus.a, annulus.b, annulus.kappa, annulus.one_minus_kappa, 0.0, faces, node_p, *out)
    return out[0]


def film_rates(annulus: Annulus, motion: Motion, fluid: Fluid, film: TransportedFilm, void=None,
               reservoir: float = 0.0) -> FilmRates:
    """The film's pressure, rates and forces for a state (``void`` None: a full film).

    Parameters
    ----------
    annulus, motion, fluid
        Geometry, velocities, fluid; ``annulus.length`` is the film's length L.
    film : TransportedFilm
    void : array_like, shape (N,), optional
        Gas area of each dual cell per unit length (m^2), in [0, V_j].
    reservoir : float
        Liquid the reservoir has taken from the film since the bubble was at its stated
        volume, per unit length (m^2).
    """
    n = film.n
    area = dual_areas(annulus, n)
    void = np.zeros(n) if void is None else np.array(void, dtype=float)
    if void.shape != (n,) or not np.all(np.isfinite(void)):
        msg = f"void must be a finite array of shape ({n},), got shape {void.shape}"
        raise ValueError(msg)
    if np.any(void > area):
        msg = "void must not exceed the gap area V_j of its cell (the liquid in a cell cannot be negative)"
        raise ValueError(msg)
    reservoir = check_finite("reservoir", reservoir)
    d_void, y, fraction, flux = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    *f, d_reservoir, p_res, passes = _fk.film_rates(
        annulus.a, annulus.b, fluid.mu, annulus.length, annulus.kappa, annulus.one_minus_kappa, motion.eps_dot,
        motion.w_a, motion.w_b, *film.kernel_data(annulus.a, annulus.length), void, reservoir, d_void, y,
        fraction, flux)
    if passes < 0:
        msg = "the film's complementarity problem could not be solved (a bubble squeezed to nothing?)"
        raise RuntimeError(msg)
    _, nodes = psi_rule(n, film.points_per_cell)
    theta = _theta_of_psi(nodes, annulus.kappa)
    theta[0] = np.pi
    y_cav = (film.p_cav - p_res) / (12.0 * fluid.mu * annulus.a)
    # a cavitated node holds p_cav exactly (the kernel sets y to the level itself, not near it)
    p = np.where(y == y_cav, film.p_cav, p_res + 12.0 * fluid.mu * annulus.a * y)
    return FilmRates(theta, p, fraction, area, d_void, flux, d_reservoir, p_res, FluidForces(*f, model=film.name),
                     passes)


def leaky_half_sommerfeld_forces(annulus: Annulus, motion: Motion, fluid: Fluid, *, p_cav: float = 0.0,
                                 p_res: float = 101325.0, eps_end: float | None = None, n: int = 256,
                                 points_per_cell: int = 2) -> FluidForces:
    """Half-Sommerfeld forces with the end-reservoir gauge instead of the feed.

    The full film exchanges liquid with reservoirs at ``p_res`` (Pa) through the ends
    (``eps_end``, by default :func:`end_conductance` of L/a) and is then truncated at
    ``p_cav``. Against :func:`lubrication.cavitation.cavitating_forces` with
    "half-sommerfeld", whose reference is the widest gap, a pure separation keeps the
    part of its film above p_cav.
    """
    _check_discretisation(n, "sommerfeld", points_per_cell)
    p_cav, p_res = check_finite("p_cav", p_cav), check_finite("p_res", p_res)
    if eps_end is None:
        eps_end = end_conductance(annulus.length / annulus.a)
    eps_end = check_range("end_conductance", eps_end, 0.0, math.inf, low_open=True)
    rule, faces, node_p = _grid(n, points_per_cell)
    f = _fk.leaky_truncated_forces(annulus.a, annulus.b, fluid.mu, annulus.length, annulus.kappa,
                                   annulus.one_minus_kappa, motion.eps_dot, motion.w_a, motion.w_b, *rule,
                                   points_per_cell, faces, node_p, p_cav, p_res, eps_end, np.empty(n))
    return FluidForces(*f, model="reynolds/half-sommerfeld/ends")
