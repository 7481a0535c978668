"""Scenes: TOML files that say what to simulate, read into validated dataclasses.

    schema.py    every section and key: unit, range, help (stated once)
    units.py     strings with units, read by pint
    load.py      TOML in, a validated Scene out; the resolved scene written back
    default.toml the embedded default scene
"""

from dynamics.initial import Initial
from dynamics.scenes.load import load_scene, parse_scene, resolved_toml
from dynamics.scenes.schema import (
           SECTIONS,
           Cavitation,
           Contact,
           Groups,
           Model,
           NavierStokes,
           Run,
           Scene,
           SceneError,
)

__all__ = ["SECTIONS", "Cavitation", "Contact", "Groups", "Initial", "Model", "NavierStokes", "Run", "Scene", "SceneError",
           "load_scene", "parse_scene", "resolved_toml"]
