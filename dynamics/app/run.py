"""A scene in, a trajectory out: the modelling choices a scene asks for, and nothing else."""

from __future__ import annotations

from dataclasses import replace

from dynamics.app.auto import resolve_model
from dynamics.contact.reduced import ContactParams
from dynamics.contact.roughness import RoughContact
from dynamics.equations.forces import force_model
from dynamics.scenes import Scene, SceneError
from dynamics.simulate import (
    Trajectory,
    simulate_contact,
    simulate_full,
    simulate_full_contact,
    simulate_reduced,
)

__all__ = ["run_scene"]


def _refuse(key: str, why: str) -> SceneError:
    return SceneError(f"{key}: {why}")


def run_scene(scene: Scene, *, method: str = "LSODA", progress: str | None = None) -> Trajectory:
    """Integrate ``scene`` with the equations and forces it names.

    Raises
    ------
    SceneError
        For a choice this version cannot model (a varying minimum gap in the
        full equations, cavitation without the Reynolds solver).
    """
    model = scene.model
    rough = scene.contact
    if rough is not None and model.equations == "full" and rough.roughness_amplitude > 0:
        raise _refuse("contact.roughness_amplitude",
                      "a minimum gap that varies along the surfaces is modelled in the reduced equations "
                      "only; set model.equations = 'reduced' or contact.roughness_amplitude = 0")
    cavitation = scene.cavitation
    if cavitation is not None and model.forces != "reynolds":
        raise _refuse("model.forces", "a cavitating film needs the Reynolds solver: set "
                                      "model.forces = 'reynolds' or remove the [cavitation] section")
    if model.equations == "auto" or model.forces == "auto":
        # choose from the stored speed-accuracy study, run the concrete scene, record why
        resolved, choices = resolve_model(scene)
        trajectory = run_scene(replace(scene, model=resolved), method=method, progress=progress)
        trajectory.info["model_choice"] = choices
        return trajectory
    if model.equations == "reduced" and rough is not None:
        surfaces = ContactParams(rough.kappa_star, rough.psi)
        if rough.roughness_amplitude > 0:
            # the correlation is a distance rolled: metres, or units of b in a dimensionless scene
            a, b = ((scene.apparatus.a, scene.apparatus.b) if scene.apparatus is not None
                    else (1.0 / (1.0 + scene.groups.delta_over_a), 1.0))
            surfaces = RoughContact.from_rolled_length(surfaces, rough.roughness_amplitude,
                                                       rough.roughness_correlation, a, b, rough.seed)
        return simulate_contact(scene.groups.reduced_params, surfaces, scene.initial, scene.t_end_tau,
                                apparatus=scene.apparatus, rtol=scene.run.rtol, method=method,
                                progress=progress)
    if model.equations == "reduced":
        return simulate_reduced(scene.groups.reduced_params, scene.initial, scene.t_end_tau,
                                apparatus=scene.apparatus, rtol=scene.run.rtol, method=method,
                                progress=progress)
    options = {"n": model.n, "grid": model.grid} if model.forces == "reynolds" else {}
    if cavitation is not None:
        options.update(cavitation=cavitation.model, p_cav=cavitation.p_cav, p_ref=cavitation.p_ref)
    forces = force_model(model.forces, **options)
    if rough is not None:
        return simulate_full_contact(scene.apparatus, forces, ContactParams(rough.kappa_star, rough.psi),
                                     scene.initial, scene.run.t_end, rtol=scene.run.rtol, method=method,
                                     progress=progress)
    return simulate_full(scene.apparatus, forces, scene.initial, scene.run.t_end, rtol=scene.run.rtol,
                         method=method, progress=progress)
