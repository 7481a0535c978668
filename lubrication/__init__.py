"""Fluid force and torque on the inner of two eccentric cylinders.

Geometry + motion + fluid -> (f_eps, f_chi, T_a), by the lubrication closed
forms (2.5)-(2.7) of Balmforth, Bush, Vener & Young (J. Fluid Mech. 2007) or by
solving the Reynolds equation numerically.
"""

from .cavitation import CAVITATION_MODELS, cavitating_forces, cavitating_pressure
from .closed_form import closed_form_forces, lubrication_forces
from .forces import MODELS, Resistance, fluid_forces, resistance
from .geometry import Annulus, Fluid, FluidForces, Motion
from .reynolds import GapProfile, ReynoldsPressure, reynolds_forces, reynolds_pressure

__all__ = [
    "CAVITATION_MODELS",
    "MODELS",
    "Annulus",
    "Fluid",
    "FluidForces",
    "GapProfile",
    "Motion",
    "Resistance",
    "ReynoldsPressure",
    "cavitating_forces",
    "cavitating_pressure",
    "closed_form_forces",
    "fluid_forces",
    "lubrication_forces",
    "reynolds_forces",
    "reynolds_pressure",
    "resistance",
]
