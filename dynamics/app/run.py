"""A scene in, a trajectory out: the modelling choices a scene asks for, and nothing else."""

from __future__ import annotations

from dataclasses import replace

from dynamics.app.auto import resolve_model
from dynamics.contact.laws import Compliance, Stribeck
from dynamics.contact.reduced import ContactParams
from dynamics.contact.roughness import RoughContact, Spectrum
from dynamics.equations import full
from dynamics.scenes import NavierStokes, Scene, SceneError
from dynamics.simulation import simulate
from dynamics.trajectory import Trajectory
from lubrication import registry
from lubrication.kernels import check_end_gap
from lubrication.reynolds import uniform_grid_cells, uniform_grid_reach

__all__ = ["run_scene"]


def _refuse(key: str, why: str) -> SceneError:
    return SceneError(f"{key}: {why}")


def run_scene(scene: Scene, *, method: str = "radau", progress=None) -> Trajectory:
    """Integrate ``scene`` with the equations, forces, contact and limits it names.

    ``progress(t)``, if given, is called now and then with the time reached
    (s, or tau in a dimensionless scene).

    ``model.equations = "navier-stokes"`` runs the coupled flow with the scene's
    ``[navier_stokes]`` grid and tolerance; its snapshots come back in
    ``trajectory.info["snapshots"]`` (:func:`dynamics.app.output.write_outputs` writes them).

    Raises
    ------
    SceneError
        For a choice this version cannot model (a compliant contact or Stribeck
        friction in the reduced equations, cavitation without the Reynolds solver).
    """
    model = scene.model
    rough = scene.contact
    if rough is not None and model.equations == "reduced":
        for key, given, default in (("contact.law", rough.law, "hard"),
                                    ("contact.friction_law", rough.friction_law, "coulomb")):
            if given != default:
                raise _refuse(key, f"{given!r} is modelled in the full equations only; the reduced equations "
                                   f"(2.11) keep section 5's hard contact and Coulomb friction: set "
                                   f"model.equations = 'full' or {key} = {default!r}")
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
    contact = None
    if rough is not None:
        contact = _contact(scene)
    system = scene.apparatus if scene.apparatus is not None else scene.groups.reduced_params
    forces = "closed-form"
    if model.equations == "full":
        forces = _force_model(scene)
    elif model.equations == "reduced" and (model.ends != "infinite" or model.frame_terms != full.DEFAULT_FRAME_TERMS
                                           or model.inertia != "none" or model.end_gap is not None
                                           or model.fluid_spin != full.DEFAULT_FLUID_SPIN):
        key = next(k for k, v in (("model.ends", model.ends != "infinite"), ("model.inertia", model.inertia != "none"),
                                  ("model.end_gap", model.end_gap is not None),
                                  ("model.fluid_spin", model.fluid_spin != full.DEFAULT_FLUID_SPIN),
                                  ("model.frame_terms", True)) if v)
        raise _refuse(key, "the reduced equations (2.11) are leading order: per unit length of an infinitely long "
                           "annulus, in Stokes flow, without the O(delta/a) frame terms; this needs "
                           "model.equations = 'full'")
    run = scene.run
    rtol, navier_stokes = run.rtol, None
    if model.equations == "navier-stokes":
        from dynamics.equations.navier_stokes import NavierStokesOptions

        settings = scene.navier_stokes or NavierStokes()  # a Scene built in Python may leave it out
        rtol = settings.rtol
        navier_stokes = NavierStokesOptions(n_r=settings.n_r, n_theta=settings.n_theta,
                                            snapshot_times=settings.snapshot_times(run.t_end))
    limits, reach = run.limits, None
    if model.equations == "full" and model.forces == "reynolds" and model.grid == "uniform":
        # the grid resolves the film only so near contact: closer, its forces err beyond model.tolerance
        reach = uniform_grid_reach(model.n, model.tolerance)
        if 1.0 - reach > limits.gap_floor:
            limits = replace(limits, gap_floor=1.0 - reach)
        else:
            reach = None
    try:
        trajectory = simulate(system, scene.initial, run.t_end, equations=model.equations, forces=forces,
                              contact=contact, limits=limits, method=method, rtol=rtol,
                              output_interval=run.output_interval, max_steps=run.max_steps, progress=progress,
                              frame_terms=model.frame_terms, fluid_spin=model.fluid_spin, navier_stokes=navier_stokes)
    except ValueError as err:
        raise SceneError(_resolution_reason(model, reach) if reach is not None and "gap floor" in str(err)
                         else str(err)) from err
    if reach is not None:
        _report_resolution(trajectory, model, reach)
    return trajectory


def _contact(scene: Scene) -> ContactParams | RoughContact:
    """The scene's contact: section 5's uniform one, or surfaces with the laws the scene names."""
    rough = scene.contact
    mean = ContactParams(rough.kappa_star, rough.psi)
    friction = None if rough.friction_law == "coulomb" else Stribeck(rough.psi_static, rough.stribeck_velocity)
    compliance = None if rough.law == "hard" else Compliance(rough.heights, rough.stiffness, rough.damping_ratio,
                                                             rough.slip_velocity)
    laws = {"friction": friction, "compliance": compliance}
    if rough.roughness_amplitude > 0:
        # the correlation is a distance rolled: metres, or units of b in a dimensionless scene
        a, b = ((scene.apparatus.a, scene.apparatus.b) if scene.apparatus is not None
                else (1.0 / (1.0 + scene.groups.delta_over_a), 1.0))
        spectrum = Spectrum(rough.roughness_spectrum, rough.roughness_hurst, rough.roughness_bandwidth)
        try:
            return RoughContact.from_rolled_length(mean, rough.roughness_amplitude, rough.roughness_correlation, a,
                                                   b, rough.seed, spectrum=spectrum, **laws)
        except ValueError as err:
            if str(err).startswith("correlation"):
                raise _refuse("contact.roughness_correlation", str(err)) from err
            raise
    if friction is None and compliance is None:
        return mean
    return RoughContact.uniform(mean, **laws)


#: The scene key of each option of the force-model registry (:mod:`lubrication.registry`).
_SCENE_KEYS = {"n": "model.n", "grid": "model.grid", "ends": "model.ends", "inertia": "model.inertia",
               "end_gap": "model.end_gap", "cavitation": "cavitation.model", "p_cav": "cavitation.p_cav",
               "p_ref": "cavitation.p_ref"}


def _force_model(scene: Scene):
    """The scene's force model for the full equations (:func:`lubrication.registry.kernel_model`): the model's
    own options the [model] section holds, and the compositions the scene asks for; a SceneError names the key."""
    model, apparatus = scene.model, scene.apparatus
    spec = registry.get(model.forces)
    options = {name: getattr(model, name) for name in spec.options if name in ("n", "grid")}
    if model.ends != "infinite":
        options["ends"] = model.ends
    if model.inertia != "none":
        options["inertia"] = model.inertia
    if model.end_gap is not None:
        options["end_gap"] = model.end_gap
    if scene.cavitation is not None:
        options.update(cavitation=scene.cavitation.model, p_cav=scene.cavitation.p_cav, p_ref=scene.cavitation.p_ref)
    try:
        check_end_gap(model.end_gap, apparatus.a)
        return registry.kernel_model(model.forces, length_over_a=apparatus.length / apparatus.a, rho=apparatus.rho,
                                     **options)
    except ValueError as err:
        option = str(err).split(":")[0]
        raise _refuse(_SCENE_KEYS.get(option, "model.forces"), str(err).partition(": ")[2] or str(err)) from err


def _resolution_reason(model, reach: float) -> str:
    """Why a Reynolds grid uniform in theta bounds the run, and what would not."""
    needs = ", ".join(f"{uniform_grid_cells(1.0 - gap, model.tolerance)} cells to 1 - kappa = {gap:g}"
                      for gap in (1e-3, 1e-6))
    return (f"model.n = {model.n} cells uniform in theta resolve the film (forces within model.tolerance = "
            f"{model.tolerance:g}) only to kappa = {reach:.6g} (1 - kappa = {1.0 - reach:.3g}); "
            f"model.grid = 'sommerfeld' is exact from 8 cells, or raise model.n ({needs})")


def _report_resolution(trajectory: Trajectory, model, reach: float) -> None:
    """Where the run met the grid's reach: its stop (or, with on_invalid = 'warn', its passage) says why."""
    met = trajectory.event == "gap_floor" or any(e["name"] == "gap_floor" for e in trajectory.events)
    if not met:
        return
    reason = _resolution_reason(model, reach)
    trajectory.info["resolution"] = {"cells": model.n, "grid": "uniform", "tolerance": model.tolerance,
                                     "kappa_reach": reach, "reason": reason}
    if trajectory.event == "gap_floor":
        trajectory.message = f"the gap closed past the grid's reach at t = {trajectory.t[-1]:.6g} s: {reason}"
    for passed in trajectory.info.get("limits_passed", []):
        if passed["name"] == "gap_floor":
            passed["reason"] = f"passed at t = {passed['t']:.6g} s: {reason}"
