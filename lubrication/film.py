"""The model "reynolds" of the registry: the thin film of the Reynolds equation, full or cavitating, on the gap
angle or on (theta, z) for an annulus of finite length.

Its face dispatches on the compositions the registry allows it (:mod:`lubrication.registry`): ``ends``
"open" or "sealed" (:mod:`lubrication.reynolds2d`), a ``cavitation`` model (:mod:`lubrication.cavitation`),
or the full film (:mod:`lubrication.reynolds`); a trajectory calls the compiled kernel of the full or the
cavitating film.
"""

from __future__ import annotations

from numerics.keys import Key

from .cavitation import CAVITATION_MODELS, cavitating_forces, cavitating_kernel
from .geometry import Annulus, Fluid, FluidForces, Motion
from .reynolds import (
    GRIDS,
    MAX_CELLS,
    MAX_POINTS_PER_CELL,
    MIN_CELLS,
    PROFILES,
    TRAJECTORY_CELLS,
    film_block,
    reynolds_forces,
    reynolds_kernel,
)
from .reynolds2d import reynolds2d_forces
from .spec import ForceModelSpec

__all__ = ["MODEL", "film_forces"]


def film_forces(annulus: Annulus, motion: Motion, fluid: Fluid, *, ends: str = "infinite", n_axial: int | None = None,
                cavitation: str = "none", p_cav: float = 0.0, p_ref: float = 101325.0, **options) -> FluidForces:
    """The "reynolds" model's face: the Reynolds film at one instant, with the compositions it takes.

    With ``ends`` "open" or "sealed" the Reynolds equation on (theta, z) for the annulus of
    its length (:func:`lubrication.reynolds2d.reynolds2d_forces`, ``p_ref`` the end regions'
    pressure); with ``cavitation`` a ruptured film (:func:`lubrication.cavitation.cavitating_forces`);
    else the full film (:func:`reynolds_forces`). ``options`` are the grid's.
    """
    if ends != "infinite":
        if "grid" in options:
            raise ValueError("grid is the one-dimensional solver's (ends 'infinite'); on (theta, z) the solver "
                             "grades its own grid")
        return reynolds2d_forces(annulus, motion, fluid, ends=ends, n_axial=64 if n_axial is None else n_axial,
                                 p_end=p_ref, cavitation=cavitation, p_cav=p_cav, **options)
    if cavitation != "none":
        return cavitating_forces(annulus, motion, fluid, cavitation, p_cav=p_cav, p_ref=p_ref, **options)
    return reynolds_forces(annulus, motion, fluid, **options)


def _kernel(*, n: int = TRAJECTORY_CELLS, grid: str = "sommerfeld", profile: str = "thin", points_per_cell: int = 1,
            cavitation: str = "none", p_cav: float = 0.0, p_ref: float = 101325.0):
    """The kernel, block and smoothness of the "reynolds" model with these options, for trajectories: a
    cavitating film's forces are only piecewise smooth in the state."""
    if cavitation == "none":
        return reynolds_kernel, film_block(n, grid, profile, points_per_cell), True
    if not p_cav <= p_ref:
        msg = f"p_cav must not exceed p_ref = {p_ref:g} Pa, got {p_cav:g} Pa"
        raise ValueError(msg)
    block = film_block(n, grid, profile, points_per_cell, CAVITATION_MODELS.index(cavitation), p_cav, p_ref)
    return cavitating_kernel, block, False


#: The model as the registry knows it (:mod:`lubrication.registry`).
MODEL = ForceModelSpec(
    "reynolds", "the Reynolds equation of the thin film solved numerically: any gap profile, cavitation, finite "
    "length; leading order in delta/a", film_forces,
    options={
        "n": Key("cells around the gap (default 32 for one instant, 256 with cavitation, 16 in a trajectory)",
                 low=MIN_CELLS, high=MAX_CELLS, integer=True),
        "grid": Key("cells uniform in the Sommerfeld angle (exact thin-gap forces from 8 cells) or in theta",
                    choices=GRIDS),
        "profile": Key("the thin gap (B1) or the exact gap between the eccentric circles", choices=PROFILES),
        "points_per_cell": Key("Gauss points per cell", low=1, high=MAX_POINTS_PER_CELL, integer=True),
    },
    kernel=_kernel, film=True)
