"""The force-model interface the equations of motion call, with one adapter per lubrication model.

A :class:`ForceModel` is plain data (the arrays its kernel needs, None for
what it does not use), so that the right-hand side of the equations of motion
is jitted and calls :func:`evaluate` for any model without Python in the loop.
The model is told apart by which data are None: numba prunes the branches of
the other models when it compiles, so a run compiles (and caches) only the
kernel it uses, not every kernel of the project.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from lubrication import _cavitation_kernels, _kernels
from lubrication._jit import jit
from lubrication.cavitation import CAVITATION_MODELS
from lubrication.closed_form import lubrication_forces
from lubrication.geometry import Annulus, Fluid, FluidForces, Motion
from lubrication.reynolds import PROFILES, _check_discretisation, _psi_rule
from lubrication.stokes_exact import stokes_exact_resistance

__all__ = ["FORCE_MODELS", "ForceModel", "closed_form", "evaluate", "force_model", "reynolds", "stokes_exact"]

FORCE_MODELS = ("closed-form", "reynolds", "stokes-exact", "stokes")


@dataclass(frozen=True)
class ForceModel:
    """A fluid-force model as the jitted equations of motion see it.

    Attributes
    ----------
    name : str
        "closed-form", "reynolds", "reynolds/<cavitation model>" or "stokes-exact".
    profile : int
        Gap profile of the Reynolds kernel (thin or eccentric).
    sommerfeld : bool
        Reynolds grid uniform in the Sommerfeld angle (True) or in theta.
    rule : tuple of ndarray or None
        cos, sin, 1 - cos, 1 + cos of psi and the weights at the Gauss points
        of the Reynolds grid; None for the closed forms and Stokes.
    points_per_cell : int
        Gauss points per cell of the Reynolds grid.
    exact : ndarray or None
        For the exact Stokes forces: factors on the five resistance coefficients
        (:data:`lubrication.geometry.RESISTANCE_NAMES` order), ones for an
        annulus of infinite length.
    cavitation : tuple or None
        (model code in CAVITATION_MODELS, p_cav, p_ref) of a cavitating Reynolds film.
    options : dict
        The options the model was built with, for the record.
    """

    name: str
    profile: int = _kernels.THIN
    sommerfeld: bool = True
    rule: tuple | None = None
    points_per_cell: int = 1
    exact: np.ndarray | None = None
    cavitation: tuple | None = None
    options: dict = field(default_factory=dict)

    def forces(self, annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
        """The same evaluation from Python (for checks and single instants)."""
        f = evaluate(self.profile, self.sommerfeld, self.rule, self.points_per_cell, self.exact, self.cavitation,
                     annulus.a, annulus.b, fluid.mu, annulus.length, annulus.kappa,
                     annulus.one_minus_kappa, motion.eps_dot, motion.w_a, motion.w_b)
        return FluidForces(*f, model=self.name)


def closed_form() -> ForceModel:
    """Lubrication closed forms (2.5)-(2.7)."""
    return ForceModel("closed-form")


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
    rule, _ = _psi_rule(n, points_per_cell)
    gap = _kernels.THIN if profile == "thin" else _kernels.ECCENTRIC
    options = {"n": n, "grid": grid, "profile": profile, "points_per_cell": points_per_cell}
    if cavitation == "none":
        return ForceModel("reynolds", gap, grid == "sommerfeld", rule, points_per_cell, options=options)
    if not p_cav <= p_ref:
        msg = f"p_cav must not exceed p_ref = {p_ref:g} Pa, got {p_cav:g} Pa"
        raise ValueError(msg)
    return ForceModel(f"reynolds/{cavitation}", gap, grid == "sommerfeld", rule, points_per_cell,
                      cavitation=(CAVITATION_MODELS.index(cavitation), float(p_cav), float(p_ref)),
                      options={**options, "cavitation": cavitation, "p_cav": p_cav, "p_ref": p_ref})


def stokes_exact() -> ForceModel:
    """The exact 2-D Stokes forces of circular walls (:mod:`lubrication.stokes_exact`), at any delta/a."""
    return ForceModel("stokes-exact", exact=np.ones(5))


def force_model(name: str, **options) -> ForceModel:
    """The adapter for ``name`` (:data:`FORCE_MODELS`).

    "stokes" names the full Stokes forces, which for circular walls are known
    exactly: it is "stokes-exact" (the finite-element solver, too slow for an
    integrator step, checks them; :mod:`lubrication.stokes`).
    """
    if name == "closed-form":
        return closed_form()
    if name == "reynolds":
        return reynolds(**options)
    if name in ("stokes-exact", "stokes"):
        if options:
            msg = f"the {name} forces take no options, got {', '.join(sorted(options))}"
            raise ValueError(msg)
        return stokes_exact()
    msg = f"forces must be one of {', '.join(FORCE_MODELS)}, got {name!r}"
    raise ValueError(msg)


@jit
def evaluate(profile, sommerfeld, rule, points_per_cell, exact, cavitation, a, b, mu, length,
             kappa, omk, eps_dot, w_a, w_b):
    """f_eps, f_chi (N) and T_a (N m) of the model whose data are given; see :class:`ForceModel`.

    The exact Stokes forces if ``exact`` is given (scaled coefficient by
    coefficient), else the closed forms if ``rule`` is None, else the Reynolds
    film, cavitating if ``cavitation`` is given. The tests are on None, which
    numba resolves when it compiles.
    """
    if exact is not None:
        r = stokes_exact_resistance(a, b - a, mu, kappa, omk)
        f_eps = length * exact[0] * r[0] * eps_dot
        f_chi = length * (exact[1] * r[1] * w_a + exact[3] * r[3] * w_b)
        t_a = length * (exact[2] * r[2] * w_a + exact[4] * r[4] * w_b)
        return f_eps, f_chi, t_a
    if rule is None:
        return lubrication_forces(a, b - a, mu, length, kappa, omk, eps_dot, w_a, w_b)
    kappa_g, omk_g = (kappa, omk) if sommerfeld else (0.0, 1.0)
    cpsi, spsi, vpsi, ppsi, wpsi = rule
    none = np.empty(0)  # no tabulated profile, no pressure wanted (a global would be read-only)
    if cavitation is not None:
        n = spsi.size // points_per_cell
        model, p_cav, p_ref = cavitation
        f_eps, f_chi, t_a, _ = _cavitation_kernels.cavitating_film_forces(
            profile, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b, kappa_g, omk_g,
            cpsi, spsi, vpsi, ppsi, wpsi, points_per_cell, none, none, 1.0, 0.0,
            model, p_cav, p_ref, np.empty(n), np.empty(n), np.empty(n))
        return f_eps, f_chi, t_a
    return _kernels.film_forces(profile, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b,
                                kappa_g, omk_g, cpsi, spsi, vpsi, ppsi, wpsi, points_per_cell,
                                none, none, 1.0, 0.0, none)
