"""The snail cylinder's equations of motion, scenes, trajectories and the ``snail`` command.

Load a scene and simulate it::

    from dynamics import load_scene, run_scene
    trajectory = run_scene(load_scene())          # the embedded default scene
    trajectory.columns["kappa"], trajectory.status
"""

from dynamics.app.run import run_scene
from dynamics.apparatus import ALUMINIUM, PRESETS, STEEL, Apparatus, preset
from dynamics.equations.forces import FORCE_MODELS, ForceModel, force_model
from dynamics.equations.reduced import ReducedParams
from dynamics.scenes import Initial, Scene, SceneError, load_scene, parse_scene
from dynamics.simulate import (
    Trajectory,
    simulate_contact,
    simulate_full,
    simulate_full_contact,
    simulate_reduced,
)

__all__ = [
    "ALUMINIUM",
    "FORCE_MODELS",
    "PRESETS",
    "STEEL",
    "Apparatus",
    "ForceModel",
    "Initial",
    "ReducedParams",
    "Scene",
    "SceneError",
    "Trajectory",
    "force_model",
    "load_scene",
    "parse_scene",
    "preset",
    "run_scene",
    "simulate_contact",
    "simulate_full",
    "simulate_full_contact",
    "simulate_reduced",
]
