"""The snail cylinder's equations of motion, contact, scenes, trajectories and the ``snail`` command.

Simulate a device, or load a scene and run it::

    from dynamics import Initial, preset, simulate
    trajectory = simulate(preset("steel"), Initial(kappa=0.5, phi=0.5), t_end=10.0, forces="stokes-exact")

    from dynamics import load_scene, run_scene
    trajectory = run_scene(load_scene())          # the embedded default scene

The package, from the bottom up::

    equations/   the full (2.1)-(2.4) and reduced (2.11) equations, the cylinders coupled to the
                 unsteady Navier-Stokes flow, special solutions and validity limits (the force
                 models are lubrication's, the integrator numerics')
    contact/     rough contact (section 5): the phases, the hybrid driver, steady states
    simulation.py one simulation API; trajectory.py the one result type of every model
    scenes/      scene files: schema, units, reading
    app/         a scene in, files out; the automatic model choice; sweeps; the command line

Names below are imported on first use, so that ``import dynamics`` is cheap.
"""

from importlib import import_module

from numerics.stamps import stamp_kernels

stamp_kernels(__name__, "lubrication", "numerics")

_WHERE = {
    "ALUMINIUM": "apparatus", "PRESETS": "apparatus", "STEEL": "apparatus", "Apparatus": "apparatus",
    "preset": "apparatus",
    "ContactParams": "contact.reduced", "RoughContact": "contact.roughness", "Spectrum": "contact.roughness",
    "Compliance": "contact.laws", "Stribeck": "contact.laws",
    "Limits": "equations.limits", "NavierStokesOptions": "equations.navier_stokes", "ReducedParams": "equations.reduced",
    "Initial": "initial",
    "Trajectory": "trajectory", "simulate": "simulation", "ValidityWarning": "equations.limits",
    "Scene": "scenes", "SceneError": "scenes", "load_scene": "scenes", "parse_scene": "scenes",
    "run_scene": "app.run",
}

__all__ = sorted(_WHERE)


def __getattr__(name):
    if name in _WHERE:
        value = getattr(import_module(f"dynamics.{_WHERE[name]}"), name)
        globals()[name] = value
        return value
    msg = f"module {__name__!r} has no attribute {name!r}"
    raise AttributeError(msg)


def __dir__():
    return sorted(set(globals()) | set(__all__))
