"""``snail flow``: unsteady Navier-Stokes flow in the annulus for prescribed wall motions (a MOTION file)."""

from __future__ import annotations

import argparse
import json

from dynamics.app.command import UsageError, progress_bar

__all__ = ["register"]

_DESCRIPTION = """\
Unsteady Navier-Stokes flow in the gap for prescribed motions of both walls, from a fluid at
rest at t = 0 (lubrication.unsteady). MOTION.toml has [apparatus] (a preset, or a, b,
length), [fluid] (nu, rho), [run] (t_end; rtol, n_theta, n_r; snapshot_times or
snapshot_interval; animation; frame) and [motion]: x_a, z_a (m, A relative to B; x down
the slope, z normal to it) and omega_a, omega_b (rad/s, clockwise), each a number or a
table {mean, amplitude, omega, phase} meaning mean + amplitude sin(omega t + phase).
Writes into DIR forces.csv (t, x_a, z_a, F_x, F_z, T_a, T_b: the fluid's force on the
inner cylinder and its torques on both, N and N m over the length, clockwise) and
summary.json; with snapshots, flow_NNNN.vtu and flow.pvd (for ParaView) and flow.gif.

Without MOTION, runs the shipped example: the steel apparatus' inner cylinder swinging
below the centre while the outer one rolls, one period (1.26 s) with 51 snapshots, about
half a minute. `snail flow --example > motion.toml` prints it to start from."""


def register(subparsers) -> None:
    """Add ``snail flow``."""
    p = subparsers.add_parser("flow", help="unsteady flow in the gap for prescribed wall motions",
                              description=_DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("motion", nargs="?", metavar="MOTION.toml",
                   help="motion file (default: the shipped example, which --example prints)")
    p.add_argument("-o", "--output", default="snail-flow", metavar="DIR", help="output folder (default snail-flow)")
    p.add_argument("--json", action="store_true", help="print summary.json to stdout")
    p.add_argument("--example", action="store_true", help="print the example motion file and exit")
    p.set_defaults(run=_run)


def _run(args) -> int:
    from importlib.resources import files

    from dynamics.app.flow_run import flow_folder, run_flow, write_flow_outputs
    from dynamics.app.flow_spec import EXAMPLE, load_motion
    from dynamics.scenes import SceneError
    from lubrication.unsteady.snapshots import require_meshio
    from numerics.folder import FolderError

    if args.example:
        print((files("dynamics.app") / EXAMPLE).read_text(encoding="utf-8"), end="")
        return 0
    try:
        spec = load_motion(args.motion)
        if spec.snapshot_times:
            require_meshio()  # before the run, not after it
        folder = flow_folder(args.output).__enter__()  # checked and locked before anything runs
    except (SceneError, FolderError, ImportError) as err:
        raise UsageError(str(err)) from err
    try:
        bar = progress_bar(spec.t_end, "s", "snail flow")
        try:
            run = run_flow(spec, progress=bar)
        finally:
            if bar is not None:
                bar.close()
        info = write_flow_outputs(folder, spec, run)
    finally:
        folder.__exit__(None, None, None)
    if args.json:
        print(json.dumps(info, indent=2))
    else:
        grid = info["resolution"]
        print(f"{info['status']}: {info['reason']}")
        print(f"{info['steps']} steps on {grid['n_theta']} x {grid['n_r']} points in {info['wall_time_s']:.2f} s; "
              f"Stokes number {info['stokes_number']:.3g}, Reynolds number {info['reynolds_number']:.3g}; "
              f"{info['snapshots']['count']} snapshots; outputs in {folder.path}/")
    return 0 if info["status"] == "completed" else 1
