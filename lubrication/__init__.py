"""Fluid force and torque on the inner of two eccentric cylinders.

Geometry + motion + fluid -> (f_eps, f_chi, T_a): by the lubrication closed
forms (2.5)-(2.7) of Balmforth, Bush, Vener & Young (J. Fluid Mech. 2007), by
solving the Reynolds equation numerically (with cavitation if asked), by the
exact 2-D Stokes solution for circular walls, or by finite elements.

    geometry.py        the annulus, the fluid, the motion, the forces
    closed_form.py     (2.5)-(2.7)
    reynolds.py        the Reynolds equation in the gap angle (kernels in reynolds_kernels.py)
    reynolds2d.py      the Reynolds equation on (theta, z): an annulus of finite length (reynolds2d_kernels.py)
    finite_length.py   the finite-length factors of the five coefficients
    cavitation.py      film rupture: half-Sommerfeld, Swift-Stieber, JFO
    stokes_exact.py    the exact Stokes resistance of the eccentric annulus
    stokes.py          Stokes flow by finite elements (flow fields, a check)
    stokes3d.py        3-D Stokes flow in an annulus of finite length, by finite elements (a check)
    navier_stokes.py   steady Navier-Stokes flow in the annulus: where inertia matters
    kernels.py         the compiled kernels' one signature, and the data they read
    registry.py        every model declared once; fluid_forces, the one entry point; the compositions

The names below are imported on first use, so that ``import lubrication`` is cheap.
"""

from importlib import import_module

from numerics.stamps import stamp_kernels

stamp_kernels(__name__, "numerics")

_WHERE = {
    "CAVITATION_MODELS": "cavitation", "cavitating_forces": "cavitation", "cavitating_pressure": "cavitation",
    "closed_form_forces": "closed_form", "lubrication_forces": "closed_form",
    "ForceModelSpec": "registry", "fluid_forces": "registry", "kernel_model": "registry", "register": "registry",
    "resistance": "registry", "KernelModel": "kernels", "Resistance": "geometry",
    "Annulus": "geometry", "Fluid": "geometry", "FluidForces": "geometry", "Motion": "geometry",
    "RESISTANCE_NAMES": "geometry",
    "GapProfile": "reynolds", "ReynoldsPressure": "reynolds", "reynolds_forces": "reynolds",
    "reynolds_pressure": "reynolds",
    "ExactResistance": "stokes_exact", "exact_resistance": "stokes_exact", "stokes_exact_forces": "stokes_exact",
    "GapProfile2D": "reynolds2d", "Reynolds2DPressure": "reynolds2d", "reynolds2d_forces": "reynolds2d",
    "reynolds2d_pressure": "reynolds2d", "tilted_gap": "reynolds2d",
    "finite_length_factors": "finite_length", "finite_length_factor_kernel": "finite_length",
    "factor_table": "finite_length",
}

__all__ = sorted(_WHERE)


def __getattr__(name):
    if name in _WHERE:
        value = getattr(import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    msg = f"module {__name__!r} has no attribute {name!r}"
    raise AttributeError(msg)


def __dir__():
    return sorted(set(globals()) | set(__all__))
