"""The force-model interface the equations of motion call, with one adapter per lubrication model.

A :class:`ForceModel` is plain data: a kind and the arrays its kernel needs
(empty arrays for what it does not use), packed into one float64 array
(:attr:`ForceModel.data`), so that the compiled equations of motion take any
model as the same numba type, and the compiled integrator serves them all. Each
kind's forces are a compiled kernel of their own (:data:`KERNELS`). The equations
of motion are compiled once per kernel (:func:`dynamics.equations.full.model_functions`),
so that a run loads the code of its own model only; :func:`evaluate` tells the
kinds apart at run time, for the functions that serve every model. With the
four kernels compiled into every function of a run, each of the full model's
right-hand sides and Jacobians was a 0.58 MB library for numba to load: a warm
``snail run`` of the default scene spent about 0.1 s more loading them. Passed
as the tuple of its eleven arrays, the model cost more at each call of the
right-hand side (copying them and counting their references) than the closed
forms themselves: 0.28 against 0.09 us a call, 11.3 against 6.4 ms for the
default scene's trajectory.

Fluid inertia. ``closed_form(inertia=True, rho=...)`` and
``stokes_exact(inertia=True, rho=...)`` add the first inertial correction of
the flow relative to the line of centres (:mod:`lubrication.inertia`): the
force rho a^3 L kappa (C_aa W_a^2 + 2 C_ab b W_a W_b + C_bb b^2 W_b^2) along
e_eps, with the coefficients C(kappa, delta/a) of steady Navier-Stokes solves
tabulated in :mod:`lubrication._inertia_table`. It removes the O(Re*) part of
the inertial error of the wall rotations; what remains is O(Re*^2). Measured
against full Navier-Stokes solves (docs/inertia/inertia.md), the corrected force
is off by at most 9e-5 of the Stokes force at Re* = 1, 8e-4 at Re* = 3 and
9e-3 at Re* = 10 (uncorrected: 7%, 22% and 73%) at the table's nodes; between
them add the interpolation error, below 3% of the correction (1.5% measured).
The force of
the rotating frame is the equations' business
(:func:`dynamics.equations.full.frame_force`, ``frame_terms``), and the
squeeze's inertia is not covered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from lubrication import _cavitation_kernels, _kernels
from lubrication._jit import jit, sources_hash
from lubrication.cavitation import CAVITATION_MODELS
from lubrication.closed_form import lubrication_resistance
from lubrication.finite_length import finite_length_factor_kernel
from lubrication.geometry import Annulus, Fluid, FluidForces, Motion, check_range
from lubrication.inertia import _first_order_f_eps
from lubrication.reynolds import PROFILES, _check_discretisation, _psi_rule
from lubrication.stokes_exact import stokes_exact_resistance

__all__ = ["FORCE_MODELS", "KERNELS", "KIND_NAMES", "ForceModel", "closed_form", "evaluate", "force_model",
           "reynolds", "stokes_exact"]

FORCE_MODELS = ("closed-form", "reynolds", "stokes-exact", "stokes")
ENDS = ("infinite", "open")

#: Kinds of force model, indices of :data:`KERNELS`.
CLOSED, REYNOLDS, CAVITATING, EXACT = range(4)

# The header of ForceModel.data: the scalars (factors: 5 entries, cavitation: 3), then where
# each array starts in the data and its shape.
_KIND, _PROFILE, _SOMMERFELD, _POINTS_PER_CELL, _FACTORS = range(5)
_CAVITATION, _LENGTH_OVER_A, _ZETA_MIN, _X0, _RHO = 9, 12, 13, 14, 15
_RULE, _RULE_SIZE, _LENGTHS, _LENGTH_ROWS, _LENGTH_COLS = range(16, 21)
_INERTIA, _N_KAPPA, _N_DELTA, _N_COLUMNS = range(21, 25)
_HEADER = 25


@dataclass(frozen=True)
class ForceModel:
    """A fluid-force model as the jitted equations of motion see it.

    Attributes
    ----------
    name : str
        "closed-form", "reynolds", "reynolds/<cavitation model>" or "stokes-exact".
    kind : int
        :data:`CLOSED`, :data:`REYNOLDS`, :data:`CAVITATING` or :data:`EXACT`.
    profile : int
        Gap profile of the Reynolds kernel (thin or eccentric).
    sommerfeld : bool
        Reynolds grid uniform in the Sommerfeld angle (True) or in theta.
    rule : tuple of 5 ndarray
        cos, sin, 1 - cos, 1 + cos of psi and the weights at the Gauss points
        of the Reynolds grid; empty for the other kinds.
    points_per_cell : int
        Gauss points per cell of the Reynolds grid.
    factors : ndarray, shape (5,)
        For the exact Stokes forces: factors on the five resistance coefficients
        (:data:`lubrication.geometry.RESISTANCE_NAMES` order), ones for an
        annulus of infinite length.
    cavitation : tuple
        (model code in CAVITATION_MODELS, p_cav, p_ref) of a cavitating Reynolds film.
    length_over_a : float
        L/a of an annulus whose gap opens at both ends into end regions
        (:mod:`lubrication.finite_length`); inf for an infinitely long one.
        The closed forms and the exact Stokes forces are then scaled,
        coefficient by coefficient, by the thin-gap finite-length factors.
    length_table : tuple
        ``lubrication.finite_length.factor_table().args`` (empty arrays when infinite).
    inertia : tuple
        (rho, kappa nodes, delta/a nodes, table) of the first inertial
        correction (:mod:`lubrication._inertia_table`): rho (kg/m^3) > 0 adds
        it; rho = 0 with empty arrays for a model without it.
    options : dict
        The options the model was built with, for the record.
    """

    name: str
    kind: int = 0
    profile: int = _kernels.THIN
    sommerfeld: bool = True
    rule: tuple = field(default_factory=lambda: tuple(np.empty(0) for _ in range(5)))
    points_per_cell: int = 1
    factors: np.ndarray = field(default_factory=lambda: np.ones(5))
    cavitation: tuple = (0, 0.0, 0.0)
    length_over_a: float = math.inf
    length_table: tuple = field(default_factory=lambda: (np.empty((0, 0)), np.empty((0, 0)), 1.0, 1.0))
    inertia: tuple = field(default_factory=lambda: (0.0, np.empty(0), np.empty(0), np.empty((0, 0, 0))))
    options: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.kind not in (CLOSED, EXACT) and (self.inertia[0] > 0.0 or not math.isinf(self.length_over_a)):
            msg = (f"{self.name}: the inertial correction and open ends are modelled with the closed forms and "
                   "the exact Stokes forces only, not with the Reynolds solver's film")
            raise ValueError(msg)

    @cached_property
    def data(self) -> np.ndarray:
        """The model's numbers as its kernel (:data:`KERNELS`) takes them: one float64 array.

        The header (25 entries: the scalars, and where each array starts and its
        shape) is followed by the rule's five arrays, the two finite-length tables and the
        inertial correction's nodes and table, each flattened in C order.
        """
        rho, kappa_nodes, delta_nodes, table = self.inertia
        coef_eps, coef_chi, zeta_min, x0 = self.length_table
        rule = np.concatenate(self.rule)
        lengths = np.concatenate([np.ravel(coef_eps), np.ravel(coef_chi)])
        inertia = np.concatenate([kappa_nodes, delta_nodes, np.ravel(table)])
        header = np.zeros(_HEADER)
        header[:_FACTORS] = (self.kind, self.profile, float(self.sommerfeld), self.points_per_cell)
        header[_FACTORS:_FACTORS + 5] = self.factors
        header[_CAVITATION:_CAVITATION + 3] = self.cavitation
        header[_LENGTH_OVER_A], header[_ZETA_MIN], header[_X0], header[_RHO] = self.length_over_a, zeta_min, x0, rho
        header[_RULE], header[_RULE_SIZE] = _HEADER, self.rule[0].size
        header[_LENGTHS], header[_LENGTH_ROWS], header[_LENGTH_COLS] = _HEADER + rule.size, *np.shape(coef_eps)
        header[_INERTIA] = _HEADER + rule.size + lengths.size
        header[_N_KAPPA], header[_N_DELTA] = kappa_nodes.size, delta_nodes.size
        header[_N_COLUMNS] = table.shape[2] if table.size else 0
        return np.concatenate([header, rule, lengths, inertia])

    def forces(self, annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
        """The same evaluation from Python (for checks and single instants)."""
        f = KERNELS[self.kind](self.data, annulus.a, annulus.b, fluid.mu, annulus.length, annulus.kappa,
                               annulus.one_minus_kappa, motion.eps_dot, motion.w_a, motion.w_b)
        return FluidForces(*f, model=self.name)


def _ends(ends: str, length_over_a: float | None) -> dict:
    """The fields of a force model for the annulus' ends: "infinite" or "open" (needs L/a)."""
    if ends not in ENDS:
        msg = f"ends must be one of {', '.join(ENDS)}, got {ends!r}"
        raise ValueError(msg)
    if ends == "infinite":
        return {}
    if length_over_a is None:
        msg = "ends = 'open' needs the annulus' length over its inner radius, length_over_a"
        raise ValueError(msg)
    from lubrication.finite_length import factor_table

    length_over_a = check_range("length_over_a", length_over_a, 0.0, math.inf, low_open=True)
    return {"length_over_a": length_over_a, "length_table": factor_table().args}


def _inertia(inertia: bool, rho: float | None, ends: str) -> dict:
    """The fields of a force model for the first inertial correction (module docstring)."""
    if not isinstance(inertia, (bool, np.bool_)):
        msg = f"inertia must be True or False, got {inertia!r}"
        raise ValueError(msg)
    if not inertia:
        return {}
    if rho is None:
        msg = "inertia = True needs the fluid density rho (kg/m^3)"
        raise ValueError(msg)
    rho = check_range("rho", rho, 0.0, math.inf, low_open=True, unit="kg/m^3")
    if ends != "infinite":
        msg = ("inertia = True needs ends = 'infinite': the first inertial correction is tabulated for plane "
               "flow, and its finite-length factors are not known")
        raise ValueError(msg)
    from lubrication._inertia_table import DELTA_NODES, KAPPA_NODES, TABLE

    return {"inertia": (float(rho), KAPPA_NODES, DELTA_NODES, TABLE)}


def _name(base: str, ends: str, inertia: bool) -> str:
    return base + ("" if ends == "infinite" else "/open-ends") + ("+inertia" if inertia else "")


def closed_form(ends: str = "infinite", length_over_a: float | None = None, inertia: bool = False,
                rho: float | None = None) -> ForceModel:
    """Lubrication closed forms (2.5)-(2.7); with ``ends = "open"`` times the finite-length factors.

    With ``inertia=True`` (and the fluid density ``rho``, kg/m^3) plus the first inertial
    correction of the wall rotations (module docstring).
    """
    extra = _inertia(inertia, rho, ends)
    return ForceModel(_name("closed-form", ends, inertia), **_ends(ends, length_over_a), **extra,
                      options={"ends": ends, **({"inertia": True, "rho": rho} if inertia else {})})


def reynolds(n: int = 16, grid: str = "sommerfeld", profile: str = "thin", points_per_cell: int = 1,
             cavitation: str = "none", p_cav: float = 0.0, p_ref: float = 101325.0) -> ForceModel:
    """The numerical Reynolds solver; on the Sommerfeld grid its thin-gap forces are exact to
    rounding from N = 8, so a trajectory with it tracks the closed-form one to the integrator's
    tolerance. With ``cavitation`` (see :mod:`lubrication.cavitation`) the film may rupture;
    its forces are then only piecewise smooth in the state and converge as dpsi^2."""
    _check_discretisation(n, grid, points_per_cell)
    if cavitation not in CAVITATION_MODELS:
        msg = f"cavitation must be one of {', '.join(CAVITATION_MODELS)}, got {cavitation!r}"
        raise ValueError(msg)
    if profile not in PROFILES:
        msg = f"profile must be one of {', '.join(PROFILES)}, got {profile!r}"
        raise ValueError(msg)
    # the rule's cached arrays are read-only, which numba types apart: copies keep one type for every model
    rule = tuple(np.array(r) for r in _psi_rule(n, points_per_cell)[0])
    gap = _kernels.THIN if profile == "thin" else _kernels.ECCENTRIC
    options = {"n": n, "grid": grid, "profile": profile, "points_per_cell": points_per_cell}
    if cavitation == "none":
        return ForceModel("reynolds", REYNOLDS, gap, grid == "sommerfeld", rule, points_per_cell, options=options)
    if not p_cav <= p_ref:
        msg = f"p_cav must not exceed p_ref = {p_ref:g} Pa, got {p_cav:g} Pa"
        raise ValueError(msg)
    return ForceModel(f"reynolds/{cavitation}", CAVITATING, gap, grid == "sommerfeld", rule, points_per_cell,
                      cavitation=(CAVITATION_MODELS.index(cavitation), float(p_cav), float(p_ref)),
                      options={**options, "cavitation": cavitation, "p_cav": p_cav, "p_ref": p_ref})


def stokes_exact(ends: str = "infinite", length_over_a: float | None = None, inertia: bool = False,
                 rho: float | None = None) -> ForceModel:
    """The exact 2-D Stokes forces of circular walls (:mod:`lubrication.stokes_exact`), at any delta/a.

    With ``ends = "open"`` (and the annulus' L/a) each coefficient is scaled by the
    thin-gap finite-length factor of :mod:`lubrication.finite_length`: the gap opens
    into end regions at both ends, which lowers the squeeze and rotation forces.
    With ``inertia=True`` (and the fluid density ``rho``, kg/m^3) plus the first
    inertial correction of the wall rotations (module docstring): the steady
    Navier-Stokes force to O(Re*^2).
    """
    extra = _inertia(inertia, rho, ends)
    return ForceModel(_name("stokes-exact", ends, inertia), EXACT, **_ends(ends, length_over_a), **extra,
                      options={"ends": ends, **({"inertia": True, "rho": rho} if inertia else {})})


def force_model(name: str, **options) -> ForceModel:
    """The adapter for ``name`` (:data:`FORCE_MODELS`).

    "stokes" names the full Stokes forces, which for circular walls are known
    exactly: it is "stokes-exact" (the finite-element solver, too slow for an
    integrator step, checks them; :mod:`lubrication.stokes`).
    """
    if name == "closed-form":
        return closed_form(**options)
    if name == "reynolds":
        if options.pop("inertia", False):
            msg = ("inertia = True is available with the forces 'closed-form' and 'stokes-exact'; the Reynolds "
                   "solver's film has no inertial correction")
            raise ValueError(msg)
        options.pop("rho", None)
        if options.get("ends", "infinite") != "infinite":
            msg = ("ends = 'open' is modelled in trajectories with the closed forms or the exact Stokes forces "
                   "times the finite-length factors; the Reynolds solver on (theta, z) is for single instants "
                   "(snail forces --ends open)")
            raise ValueError(msg)
        options.pop("ends", None)
        return reynolds(**options)
    if name in ("stokes-exact", "stokes"):
        return stokes_exact(**options)
    msg = f"forces must be one of {', '.join(FORCE_MODELS)}, got {name!r}"
    raise ValueError(msg)


@jit(inline="always")
def _rule(model):
    """The five arrays of the Reynolds grid's rule (views of ``model``)."""
    start, m = int(model[_RULE]), int(model[_RULE_SIZE])
    return (model[start:start + m], model[start + m:start + 2 * m], model[start + 2 * m:start + 3 * m],
            model[start + 3 * m:start + 4 * m], model[start + 4 * m:start + 5 * m])


@jit(inline="always")
def _length_tables(model):
    """The two finite-length tables (views of ``model``)."""
    start, rows, cols = int(model[_LENGTHS]), int(model[_LENGTH_ROWS]), int(model[_LENGTH_COLS])
    size = rows * cols
    return (model[start:start + size].reshape((rows, cols)),
            model[start + size:start + 2 * size].reshape((rows, cols)))


@jit(inline="always")
def _inertia_tables(model):
    """The kappa and delta/a nodes and the table of the inertial correction (views of ``model``)."""
    start, nk, nd, nc = int(model[_INERTIA]), int(model[_N_KAPPA]), int(model[_N_DELTA]), int(model[_N_COLUMNS])
    table = start + nk + nd
    return (model[start:start + nk], model[start + nk:table],
            model[table:table + nk * nd * nc].reshape((nk, nd, nc)))


@jit(inline="always")
def _scaled(model, r, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi, T_a of the five resistance coefficients ``r``, times the model's factors and ends."""
    length_over_a = model[_LENGTH_OVER_A]
    if math.isinf(length_over_a):
        ends = (1.0, 1.0, 1.0, 1.0, 1.0)
    else:
        coef_eps, coef_chi = _length_tables(model)
        ends = finite_length_factor_kernel(kappa, omk, length_over_a, coef_eps, coef_chi, model[_ZETA_MIN],
                                           model[_X0])
    factors = model[_FACTORS:_FACTORS + 5]
    f_eps = length * factors[0] * ends[0] * r[0] * eps_dot
    f_chi = length * (factors[1] * ends[1] * r[1] * w_a + factors[3] * ends[3] * r[3] * w_b)
    t_a = length * (factors[2] * ends[2] * r[2] * w_a + factors[4] * ends[4] * r[4] * w_b)
    return f_eps, f_chi, t_a


@jit(inline="always")
def _inertial_f_eps(model, a, b, length, kappa, w_a, w_b):
    """The first inertial correction to f_eps (module docstring); zero for a model without it."""
    rho = model[_RHO]
    if not rho > 0.0:
        return 0.0
    kappa_nodes, delta_nodes, table = _inertia_tables(model)
    return _first_order_f_eps(kappa, (b - a) / a, a, rho, length, w_a, w_b, kappa_nodes, delta_nodes, table)


@jit
def closed_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m) of a :data:`CLOSED` model: the closed forms (2.5)-(2.7)."""
    f_eps, f_chi, t_a = _scaled(model, lubrication_resistance(a, b - a, mu, kappa, omk), length, kappa, omk,
                                eps_dot, w_a, w_b)
    return f_eps + _inertial_f_eps(model, a, b, length, kappa, w_a, w_b), f_chi, t_a


@jit
def exact_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m) of an :data:`EXACT` model: the exact 2-D Stokes forces."""
    f_eps, f_chi, t_a = _scaled(model, stokes_exact_resistance(a, b - a, mu, kappa, omk)[:5], length, kappa,
                                omk, eps_dot, w_a, w_b)
    return f_eps + _inertial_f_eps(model, a, b, length, kappa, w_a, w_b), f_chi, t_a


@jit
def reynolds_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m) of a :data:`REYNOLDS` model: the Reynolds solver's full film."""
    kappa_g, omk_g = (kappa, omk) if model[_SOMMERFELD] != 0.0 else (0.0, 1.0)
    cpsi, spsi, vpsi, ppsi, wpsi = _rule(model)
    none = np.empty(0)  # no tabulated profile, no pressure wanted (a global would be read-only)
    return _kernels.film_forces(int(model[_PROFILE]), a, b, mu, length, kappa, omk, eps_dot, w_a, w_b,
                                kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, int(model[_POINTS_PER_CELL]),
                                none, none, 1.0, 0.0, none)


@jit
def cavitating_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m) of a :data:`CAVITATING` model: the Reynolds solver's ruptured film."""
    kappa_g, omk_g = (kappa, omk) if model[_SOMMERFELD] != 0.0 else (0.0, 1.0)
    cpsi, spsi, vpsi, ppsi, wpsi = _rule(model)
    points_per_cell = int(model[_POINTS_PER_CELL])
    n = spsi.size // points_per_cell
    none = np.empty(0)
    code, p_cav, p_ref = int(model[_CAVITATION]), model[_CAVITATION + 1], model[_CAVITATION + 2]
    f_eps, f_chi, t_a, _ = _cavitation_kernels.cavitating_film_forces(
        int(model[_PROFILE]), a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, kappa_g, omk_g,
        cpsi, spsi, vpsi, ppsi, wpsi, points_per_cell, none, none, 1.0, 0.0,
        code, p_cav, p_ref, np.empty(n), np.empty(n), np.empty(n))
    return f_eps, f_chi, t_a


#: The compiled forces of each kind of model, indexed by :data:`CLOSED`, :data:`REYNOLDS`, ...
KERNELS = (closed_forces, reynolds_forces, cavitating_forces, exact_forces)
#: The name each kind's compiled functions are filed under (:func:`lubrication._jit.specialise`): the kind,
#: and a hash of the kernels' sources (this module and the lubrication package), so that editing a kernel
#: compiles the equations of motion that carry it anew.
KERNELS_HASH = sources_hash(Path(__file__), *sorted(Path(_kernels.__file__).parent.glob("*.py")))
KIND_NAMES = tuple(f"{kind}_{KERNELS_HASH}" for kind in ("closed", "reynolds", "cavitating", "exact"))


@jit
def evaluate(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m) of a model of any kind (:attr:`ForceModel.data`), told apart at run time."""
    kind = int(model[_KIND])
    if kind == CLOSED:
        return closed_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b)
    if kind == EXACT:
        return exact_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b)
    if kind == CAVITATING:
        return cavitating_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b)
    return reynolds_forces(model, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b)
