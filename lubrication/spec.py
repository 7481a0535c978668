"""A force model's declaration: what the registry (:mod:`lubrication.registry`) knows of it.

A model's module declares ``MODEL = ForceModelSpec(...)`` and imports nothing of
the registry: the registry imports the modules of the built-in models, or a
user's code passes its own declaration to :func:`lubrication.registry.register`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from numerics.keys import Key

__all__ = ["ForceModelSpec"]


@dataclass(frozen=True)
class ForceModelSpec:
    """A force model, declared once.

    Parameters
    ----------
    name : str
        What users call it: ``fluid_forces(..., model=name)``, ``snail forces --model name``,
        ``[model] forces = "name"``.
    summary : str
        One line: what it computes and where it holds.
    forces : callable
        The Python face, ``forces(annulus, motion, fluid, **options) -> FluidForces``, for one
        instant; it receives the model's own options and, for a film, the compositions'.
    options : mapping of str to Key
        The model's own options, with units, ranges and help.
    resistance : numba dispatcher, optional
        A linear model's compiled coefficients per unit length, ``resistance(a, delta, mu,
        kappa, omk)`` -> the five of :data:`lubrication.geometry.RESISTANCE_NAMES` (more may
        follow). Its kernel is :func:`lubrication.registry.linear_kernel` of them, and the
        ends and inertia compose with it.
    kernel : callable, optional
        Any other model's ``kernel(**options) -> (compiled kernel, block, smooth)`` for trajectories:
        its kernel, its packed block (:mod:`lubrication.kernels`) and whether its forces are
        smooth in the state.
    in_trajectories : str, optional
        The model a trajectory runs in this one's place (the finite-element Stokes forces
        are known exactly for circular walls: "stokes-exact").
    film : bool
        A Reynolds film: cavitation composes with it.
    extra : str
        The optional extra the face needs (``pip install 'snail-cylinder[extra]'``).
    check : callable, optional
        ``check(annulus)`` raises ValueError for an annulus outside the range where the
        model's accuracy was measured.
    """

    name: str
    summary: str
    forces: Callable
    options: Mapping[str, Key] = field(default_factory=dict)
    resistance: object = None
    kernel: Callable | None = None
    in_trajectories: str = ""
    film: bool = False
    extra: str = ""
    check: Callable | None = None

    @property
    def linear(self) -> bool:
        return self.resistance is not None

    @property
    def for_trajectories(self) -> bool:
        """Whether an integrator step can call it (itself, or the model that stands in for it)."""
        return self.linear or self.kernel is not None or bool(self.in_trajectories)
