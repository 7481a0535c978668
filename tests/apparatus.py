"""The paper's apparatus as the tests use it: each number defined here once.

Balmforth, Bush, Vener & Young (2007), Table 2, as :mod:`dynamics.apparatus`
reconciles it. Test modules import these names (``from apparatus import A, B,
L, OIL``); a test that needs other numbers writes them out where it uses them.
"""

from __future__ import annotations

from dynamics.apparatus import preset
from lubrication import Fluid

__all__ = ["ALUMINIUM", "A", "B", "CLI_GEOMETRY", "L", "OIL", "PRESET_FLUID", "STEEL"]

#: Inner radius a, outer radius b and length L of the inner cylinder (Table 2), m.
A, B, L = 0.008, 0.01125, 0.1035
#: The 200 cSt silicone oil of the paper's figures: nu in m^2/s, rho in kg/m^3.
OIL = Fluid(nu=2e-4, rho=960.0)
#: The presets' fluid, and ``snail forces``' default: 200 cSt at 1000 kg/m^3.
PRESET_FLUID = Fluid(nu=2e-4, rho=1000.0)
#: The steel apparatus on the 2.4 degree slope of figure 5(a), and the aluminium one on the 5 degrees of
#: figure 6 (frozen dataclasses: a test derives others with ``dataclasses.replace`` or ``preset``).
STEEL = preset("steel")
ALUMINIUM = preset("aluminium")
#: ``--a`` and ``--b`` of ``snail forces`` for this apparatus.
CLI_GEOMETRY = ["--a", str(A), "--b", str(B)]
