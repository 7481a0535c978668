"""``snail run``: a scene (the embedded default when none is given) to a trajectory and its files."""

from __future__ import annotations

import json
import sys
import warnings

from dynamics.app.command import UsageError, announce_compiling, progress_bar

__all__ = ["register"]


def register(subparsers) -> None:
    """Add ``snail run``."""
    p = subparsers.add_parser(
        "run", help="run a scene and write its trajectory",
        description="Integrate a scene (the embedded default when none is given) and write "
                    "trajectory.csv, summary.json, trajectory.png and scene.resolved.toml into DIR (and a "
                    "Navier-Stokes run's flow snapshots: flow_NNNN.vtu, flow.pvd, flow.gif).")
    p.add_argument("scene", nargs="?", help="scene TOML file (default: the embedded steel scene)")
    p.add_argument("-o", "--output", default="snail-output", help="output folder (default snail-output)")
    p.add_argument("--t-end", help="run length: seconds, or a string with units such as '2 min'")
    p.add_argument("--model", choices=["full", "reduced", "navier-stokes", "auto"],
                   help="equations of motion, overriding the scene (navier-stokes: the unsteady flow of the gap "
                        "coupled to both cylinders, set by the scene's [navier_stokes] section)")
    p.add_argument("--forces", metavar="MODEL",
                   help="force model, overriding the scene: a registered model (snail forces --help lists them; "
                        "stokes-exact, the scenes' default: the exact 2-D Stokes "
                        "forces, which 'stokes' also names in a run; closed-form: the paper's (2.5)-(2.7); auto: the "
                        "cheapest meeting model.tolerance)")
    p.add_argument("--method", default="radau", choices=["radau", "Radau", "BDF", "LSODA"],
                   help="integrator: the compiled Radau IIA (radau, default) or one of scipy's, for cross-checks")
    p.add_argument("--output-interval", metavar="T",
                   help="rows of trajectory.csv at this interval, from the dense output, and at every event: "
                        "seconds, or a string with units such as '0.1 s' (default: one row per step)")
    p.add_argument("--no-plot", action="store_true", help="do not draw trajectory.png")
    p.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override one scene value (repeatable), e.g. --set initial.kappa=0.3")
    p.add_argument("--json", action="store_true", help="print summary.json to stdout")
    p.set_defaults(run=_run_scene)


def _run_scene(args) -> int:
    if args.no_plot:
        return _run_scene_drawing(args, None)
    from dynamics.app.figure_process import FigureProcess

    with FigureProcess() as figures:  # matplotlib imports in the child while the scene runs here
        return _run_scene_drawing(args, figures)


def _run_scene_drawing(args, figures) -> int:
    from dynamics.app.output import output_names, write_outputs
    from dynamics.app.run import run_scene
    from dynamics.equations.limits import ValidityWarning
    from dynamics.scenes import SceneError, load_scene, resolved_toml
    from numerics.folder import FolderError, OutputFolder, held_signals

    overrides = list(args.set)
    for key, value in (("run.t_end", args.t_end), ("run.output_interval", args.output_interval)):
        if value is not None:
            try:  # a bare number is in seconds, anything else a string with units
                overrides.append(f"{key}={float(value)!r}")
            except ValueError:
                overrides.append(f"{key}={json.dumps(value)}")
    if args.model is not None:
        overrides.append(f'model.equations="{args.model}"')
    if args.forces is not None:
        overrides.append(f'model.forces="{args.forces}"')
    try:
        scene = load_scene(args.scene, overrides)
        folder = OutputFolder(args.output, output_names()).__enter__()  # checked and locked before anything runs
    except (SceneError, FolderError) as err:
        raise UsageError(str(err)) from err
    bar = progress_bar(scene.run.t_end, "s" if scene.apparatus is not None else "tau", "snail run")
    try:
        try:
            with announce_compiling("run"), warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", ValidityWarning)
                trajectory = run_scene(scene, method=args.method, progress=bar)
        except SceneError as err:
            raise UsageError(str(err)) from err
        finally:
            if bar is not None:
                bar.close()
        # a computed run is drawn, reported and written whole: a signal meanwhile (the second Ctrl-C of an
        # interrupted run) takes effect after, rather than in whatever runs when it comes, a finalizer perhaps,
        # where Python cannot raise it and prints it as an ignored exception
        with held_signals():
            if figures is not None:
                figures.send(trajectory)  # drawn while the other outputs are written
            for warning in caught:
                if issubclass(warning.category, ValidityWarning):
                    print(f"snail run: warning: {warning.message}; see summary.json", file=sys.stderr)
                else:
                    warnings.showwarning(warning.message, warning.category, warning.filename, warning.lineno)
            info = write_outputs(folder, trajectory, resolved_scene=resolved_toml(scene), scene=scene.source,
                                 plot=figures is not None, max_rows=scene.run.max_rows,
                                 draw=figures.png if figures is not None else None,
                                 animation=scene.navier_stokes.animation if scene.navier_stokes else "none")
    finally:
        folder.__exit__(None, None, None)
    if args.json:
        print(json.dumps(info, indent=2))
    else:
        print(f"{info['status']}: {info['reason']}")
        compiled = f" (and {info['compile_time_s']:.0f} s compiling)" if info["compile_time_s"] >= 0.5 else ""
        print(f"regime {info['regime']}, mean speed {info['mean_speed']:.4g} "
              f"({'b/tau' if info['dimensionless'] else 'm/s'}; {info['late_mean_speed']:.4g} over the second half), "
              f"{info['forces']} forces, {info['steps']} steps in {info['wall_time_s']:.2f} s{compiled}; "
              f"outputs in {folder.path}/")
    return 0 if trajectory.status == "completed" else 1
