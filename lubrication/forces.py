"""One entry point for every force model: geometry + motion + fluid -> (f_eps, f_chi, T_a)."""

from __future__ import annotations

from .cavitation import cavitating_forces
from .closed_form import closed_form_forces
from .geometry import Annulus, Fluid, FluidForces, Motion, Resistance
from .reynolds import reynolds_forces
from .stokes_exact import exact_forces

__all__ = ["MODELS", "Resistance", "fluid_forces", "resistance"]

MODELS = ("closed-form", "reynolds", "stokes-exact", "stokes")


def fluid_forces(annulus: Annulus, motion: Motion, fluid: Fluid, model: str = "closed-form",
                 **options) -> FluidForces:
    """Force and torque on the inner cylinder with the chosen model.

    Parameters
    ----------
    model : {"closed-form", "reynolds", "stokes-exact", "stokes"}
        Lubrication closed forms (2.5)-(2.7), the numerical Reynolds solver
        (``options`` go to :func:`lubrication.reynolds.reynolds_forces`; with
        ``cavitation`` other than "none", and ``p_cav``, ``p_ref``, to
        :func:`lubrication.cavitation.cavitating_forces`; with ``ends`` "open" or
        "sealed", and ``n_axial``, to :func:`lubrication.reynolds2d.reynolds2d_forces`,
        the annulus of finite length), the exact 2-D
        Stokes solution for circular walls (:mod:`lubrication.stokes_exact`,
        no options), or the finite-element Stokes solve at any gap width (``options`` set its mesh,
        see :func:`lubrication.stokes.stokes_forces`; needs the ``fem`` extra).
    """
    if model == "closed-form":
        if options:
            msg = f"the closed-form model takes no options, got {', '.join(sorted(options))}"
            raise ValueError(msg)
        return closed_form_forces(annulus, motion, fluid)
    if model == "reynolds":
        ends = options.pop("ends", "infinite")
        if ends != "infinite":
            from .reynolds2d import reynolds2d_forces

            return reynolds2d_forces(annulus, motion, fluid, ends=ends, **options)
        cavitation = options.pop("cavitation", "none")
        if cavitation != "none":
            return cavitating_forces(annulus, motion, fluid, cavitation, **options)
        return reynolds_forces(annulus, motion, fluid, **options)
    if model == "stokes-exact":
        if options:
            msg = f"the stokes-exact model takes no options, got {', '.join(sorted(options))}"
            raise ValueError(msg)
        return exact_forces(annulus, motion, fluid)
    if model == "stokes":
        from .stokes import stokes_forces  # scikit-fem is an optional extra

        return stokes_forces(annulus, motion, fluid, **options)
    msg = f"model must be one of {', '.join(MODELS)}, got {model!r}"
    raise ValueError(msg)


def resistance(annulus: Annulus, fluid: Fluid, model: str = "closed-form", **options) -> Resistance:
    """The five coefficients of :class:`Resistance`, from three unit motions of ``model``."""
    radial = fluid_forces(annulus, Motion(eps_dot=1.0), fluid, model, **options)
    inner = fluid_forces(annulus, Motion(omega_a=1.0), fluid, model, **options)
    outer = fluid_forces(annulus, Motion(omega_b=1.0), fluid, model, **options)
    return Resistance(radial.f_eps, inner.f_chi, inner.T_a, outer.f_chi, outer.T_a)
