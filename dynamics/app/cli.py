"""The ``snail`` command: a thin layer that parses, calls the Python API and reports.

Exit status: 0 success, 1 a failed computation, 2 bad input (with a message that
names the offending value, and no traceback). Subcommands that live in packages
above ``dynamics`` (``validation``) register through the ``snail.commands``
entry-point group, so that ``dynamics`` never imports them.
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import re
import sys
import time
from importlib.metadata import entry_points, version
from pathlib import Path

from dynamics.app.folder import FolderError
from dynamics.app.sweeps.cli import register as _add_sweep

__all__ = ["UsageError", "main"]

# A value that argparse would otherwise take for an option: -1e-6, -.5, -inf ...
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.IGNORECASE)

# The steel apparatus of the paper (Table 1): 200 cSt silicone oil, inner length 10.35 cm.
STEEL_OIL_NU = 2.0e-4  # m^2/s
STEEL_OIL_RHO = 960.0  # kg/m^3
STEEL_LENGTH = 0.1035  # m


class UsageError(ValueError):
    """Bad input from the command line; reported with exit status 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        self.print_usage(sys.stderr)
        self.exit(2, f"{self.prog}: error: {message}\n")


def _join_negative_values(argv: list[str]) -> list[str]:
    """Turn ``--flag -1e-6`` into ``--flag=-1e-6``: argparse reads -1e-6 as an option."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        token = argv[i]
        if (token.startswith("--") and "=" not in token and i + 1 < len(argv)
                and _NEGATIVE_NUMBER.match(argv[i + 1])):
            out.append(f"{token}={argv[i + 1]}")
            i += 2
        else:
            out.append(token)
            i += 1
    return out


def _number(text: str) -> float:
    """A finite number (every numeric option is a length, a rate, a pressure or a tolerance)."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        msg = f"not a finite number: {text!r}"
        raise argparse.ArgumentTypeError(msg)
    return value


def _add_forces(subparsers) -> None:
    p = subparsers.add_parser(
        "forces", help="fluid force and torque on the inner cylinder",
        description="Fluid force f_eps, f_chi (N) and torque T_a (N m) on the inner cylinder, "
                    "whole length, for one instant. SI units throughout.")
    p.add_argument("--model", default="closed-form",
                   choices=["closed-form", "reynolds", "stokes-exact", "stokes", "all", "auto"],
                   help="force model (default closed-form): the lubrication forms (2.5)-(2.7), the Reynolds "
                        "solver, the exact 2-D Stokes solution, or Stokes by finite elements (needs the fem "
                        "extra); all: every model and its differences from the exact Stokes forces (with --ends "
                        "open: closed-form, reynolds and stokes-exact, all with open ends); auto: the cheapest "
                        "whose measured error meets --tolerance (infinite length only)")
    p.add_argument("--tolerance", type=_number, default=1e-2,
                   help="auto: largest acceptable relative error of the forces, in (0, 1), default 1e-2")
    p.add_argument("--a", type=_number, required=True, help="inner radius (m)")
    p.add_argument("--b", type=_number, required=True, help="outer radius (m)")
    p.add_argument("--kappa", type=_number, required=True, help="eccentricity eps/(b - a), in [0, 1)")
    p.add_argument("--eps-dot", type=_number, default=0.0, help="d eps/dt (m/s), default 0")
    p.add_argument("--chi-dot", type=_number, default=0.0, help="d chi/dt (rad/s), default 0")
    p.add_argument("--omega-a", type=_number, default=0.0, help="Omega_a (rad/s), default 0")
    p.add_argument("--omega-b", type=_number, default=0.0, help="Omega_b (rad/s), default 0")
    p.add_argument("--nu", type=_number, default=STEEL_OIL_NU,
                   help=f"kinematic viscosity (m^2/s), default {STEEL_OIL_NU:g} (200 cSt)")
    p.add_argument("--rho", type=_number, default=STEEL_OIL_RHO,
                   help=f"fluid density (kg/m^3), default {STEEL_OIL_RHO:g}")
    p.add_argument("--length", type=_number, default=STEEL_LENGTH,
                   help=f"axial length (m), default {STEEL_LENGTH:g}")
    p.add_argument("--n", type=int, default=32,
                   help="Reynolds: cells around the gap (default 32; use a few hundred with cavitation)")
    p.add_argument("--grid", choices=["sommerfeld", "uniform"],
                   help="Reynolds with --ends infinite: grid uniform in the Sommerfeld angle (default) or in "
                        "theta")
    p.add_argument("--ends", default="infinite", choices=["infinite", "open", "sealed"],
                   help="per unit length of an infinitely long annulus times --length (default), or the gap of "
                        "--length opening into end regions at both ends (open) or closed there (sealed). open: "
                        "the Reynolds solver on (theta, z), or the closed forms and the exact Stokes forces "
                        "times the thin-gap finite-length factors; sealed: the Reynolds solver only")
    p.add_argument("--n-axial", type=int,
                   help="Reynolds with --ends open|sealed: cells along the whole length, even, half of them "
                        "from the mid-plane to each end (default 64)")
    p.add_argument("--profile", default="thin", choices=["thin", "eccentric"],
                   help="Reynolds: thin-gap profile (B1) or the exact eccentric gap")
    p.add_argument("--cavitation", default="none", choices=["none", "half-sommerfeld", "swift-stieber", "jfo"],
                   help="Reynolds: cavitation model (default none: full film)")
    p.add_argument("--p-cav", type=_number, default=0.0, help="Reynolds: cavitation pressure (Pa), default 0")
    p.add_argument("--p-ref", type=_number, default=101325.0,
                   help="Reynolds: absolute reference pressure (Pa), at the widest gap with --ends infinite, "
                        "in the end regions with --ends open; default 101325")
    p.add_argument("--n-around", type=int, help="Stokes: cells around the annulus (default by delta/a)")
    p.add_argument("--n-across", type=int, help="Stokes: cells across the gap (default by delta/a)")
    p.add_argument("--flow", metavar="DIR",
                   help="Stokes: write the flow field to DIR/flow.vtu (velocity, pressure, vorticity) "
                        "and a picture DIR/flow.png")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_forces)


def _timed(fn, warm_up: bool):
    """Result of ``fn()`` and its wall time; ``warm_up`` first loads the compiled kernels."""
    if warm_up:
        fn()
    start = time.perf_counter()
    result = fn()
    return result, time.perf_counter() - start


def _has_fem() -> bool:
    from importlib.util import find_spec

    return find_spec("skfem") is not None and find_spec("meshio") is not None


def _relative_differences(f, ref) -> dict[str, float]:
    """Each component's difference from ``ref``, relative to that component of ``ref``.

    A component the reference makes zero (f_chi at kappa = 0, by symmetry) is
    judged against the size of the force, or of the torque's own terms, instead.
    """
    force_scale = math.hypot(ref.f_eps, ref.f_chi)
    out = {}
    for name in ("f_eps", "f_chi", "T_a"):
        own = abs(getattr(ref, name))
        fallback = force_scale if name != "T_a" else 0.0
        scale = own if own > 1e-12 * fallback else fallback
        diff = abs(getattr(f, name) - getattr(ref, name))
        out[name] = diff / scale if scale > 0 else diff
    return out


def _check_cavitation_options(args) -> None:
    """Cavitation belongs to the Reynolds solver, and its pressures are absolute, as in scenes."""
    from lubrication.geometry import check_range

    if args.cavitation == "none":
        return
    if args.model not in ("reynolds", "all"):
        msg = f"--cavitation {args.cavitation} needs the Reynolds solver: --model reynolds (or all)"
        raise ValueError(msg)
    check_range("--p-ref", args.p_ref, 0.0, math.inf, low_open=True, unit="Pa (absolute)")
    check_range("--p-cav", args.p_cav, 0.0, args.p_ref, high_open=False,
                unit=f"Pa (absolute, at most --p-ref = {args.p_ref:g} Pa)")


def _check_ends_options(args) -> None:
    """What each model can do with the annulus' ends; a ValueError naming the options otherwise."""
    if args.ends == "infinite":
        if args.n_axial is not None:
            raise ValueError("--n-axial is for the Reynolds solver on (theta, z): it needs --ends open or sealed")
        return
    ends = f"--ends {args.ends}"
    if args.grid is not None:
        raise ValueError(f"--grid is the one-dimensional Reynolds solver's (--ends infinite); with {ends} the "
                         "(theta, z) solver grades its own grid (lubrication.reynolds2d)")
    if args.model == "auto":
        raise ValueError(f"{ends} with --model auto: the automatic choice rests on errors measured per unit "
                         "length of an infinitely long annulus; choose --model closed-form, stokes-exact or "
                         "reynolds")
    if args.model == "stokes":
        raise ValueError(f"{ends} with --model stokes: the finite-element Stokes solve is per unit length of an "
                         "infinitely long annulus; --model stokes-exact takes --ends open (times the "
                         "finite-length factors)")
    if args.ends == "sealed" and args.model != "reynolds":
        raise ValueError(f"{ends} needs --model reynolds: the closed forms and the exact Stokes forces take "
                         "--ends infinite or open")
    if args.cavitation in ("swift-stieber", "jfo"):
        raise ValueError(f"--cavitation {args.cavitation} with {ends}: on (theta, z) only half-sommerfeld "
                         "carries over; use --ends infinite for this model")
    if args.cavitation != "none" and args.ends == "sealed":
        raise ValueError(f"--cavitation {args.cavitation} with {ends}: sealed ends leave the pressure level "
                         "undetermined; use --ends open (the end regions fix it at --p-ref) or infinite")
    if args.flow is not None:
        raise ValueError(f"--flow draws the two-dimensional Stokes flow: it needs --ends infinite, not {ends}")


def _run_forces(args) -> int:
    from dynamics.equations.forces import force_model
    from lubrication import Annulus, Fluid, Motion, fluid_forces

    try:
        _check_ends_options(args)
        annulus = Annulus.from_kappa(args.a, args.b, args.kappa, length=args.length)
        motion = Motion(eps_dot=args.eps_dot, chi_dot=args.chi_dot,
                        omega_a=args.omega_a, omega_b=args.omega_b)
        fluid = Fluid(nu=args.nu, rho=args.rho)
        # with open ends the (theta, z) solver's reference pressure is that of the end regions
        reference = "p_ref" if args.ends == "infinite" else "p_end"
        options = {"closed-form": {}, "stokes-exact": {},
                   "reynolds": {"n": args.n, "profile": args.profile,
                                **({"grid": args.grid or "sommerfeld"} if args.ends == "infinite" else
                                   {"ends": args.ends, "n_axial": 64 if args.n_axial is None else args.n_axial}),
                                **({"cavitation": args.cavitation, "p_cav": args.p_cav, reference: args.p_ref}
                                   if args.cavitation != "none" else {})},
                   "stokes": {k: v for k, v in (("n_around", args.n_around), ("n_across", args.n_across))
                              if v is not None}}
        _check_cavitation_options(args)
        if args.model == "auto":
            return _run_auto_forces(args, annulus, motion, fluid)
        models = [args.model] if args.model != "all" else ["closed-form", "reynolds"] + (
            ["stokes"] if _has_fem() and args.ends == "infinite" else []) + ["stokes-exact"]
        evaluators = {m: (lambda m=m: fluid_forces(annulus, motion, fluid, m, **options[m])) for m in models}
        if args.ends == "open":
            # the closed forms and the exact Stokes forces times the thin-gap finite-length factors
            for name in [m for m in models if m in ("closed-form", "stokes-exact")]:
                scaled = force_model(name, ends="open", length_over_a=annulus.length / annulus.a)
                evaluators[name] = lambda scaled=scaled: scaled.forces(annulus, motion, fluid)
        results = []
        for model in models:
            # Stokes caches its factorisation: a warm-up call would hide its real cost
            f, seconds = _timed(evaluators[model], warm_up=model != "stokes")
            row = {"model": model, "ends": args.ends, "f_eps": f.f_eps, "f_chi": f.f_chi, "T_a": f.T_a,
                   "wall_time_s": seconds, **options[model]}
            results.append((f, row))
        if args.flow is not None and "stokes" not in models:
            raise ValueError("--flow needs the Stokes model (--model stokes or all)")
    except (ValueError, ImportError) as err:
        raise UsageError(str(err)) from err
    if args.flow is not None:
        _write_flow(args.flow, annulus, motion, fluid, options["stokes"])
    if len(results) == 1:
        out = results[0][1]
    else:
        # the exact Stokes forces are the reference: every other model approximates them
        ref = results[-1][0]
        for f, row in results:
            row["relative_difference"] = _relative_differences(f, ref)
        out = dict(results[-1][1])
        out.update(model="all", reference=results[-1][1]["model"],
                   wall_time_s=sum(r["wall_time_s"] for _, r in results), models=[row for _, row in results])
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        _print_forces_table(annulus, [row for _, row in results])
    return 0


def _run_auto_forces(args, annulus, motion, fluid) -> int:
    """``--model auto``: the choice of :func:`dynamics.app.auto.choose_forces` at this kappa, evaluated."""
    from dynamics.app.auto import choose_forces
    from dynamics.equations.forces import force_model

    choice = choose_forces(args.tolerance, annulus.delta_over_a, annulus.kappa)
    model = force_model(choice.model, **choice.options)
    f, seconds = _timed(lambda: model.forces(annulus, motion, fluid), warm_up=True)
    out = {"model": "auto", "chosen_model": choice.model, "options": choice.options, "reason": choice.reason,
           "tolerance": args.tolerance, "measured_error": choice.error,
           "f_eps": f.f_eps, "f_chi": f.f_chi, "T_a": f.T_a, "wall_time_s": seconds}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        _print_forces_table(annulus, [dict(out, model=choice.model)])
        print(f"chosen: {choice.model}: {choice.reason}.")
    return 0


def _write_flow(outdir, annulus, motion, fluid, mesh_options) -> None:
    import matplotlib.pyplot as plt

    from lubrication.files import save_figure
    from lubrication.stokes import plot_flow, stokes_flow, write_vtu

    flow = stokes_flow(annulus, motion, fluid, **mesh_options)
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    write_vtu(outdir / "flow.vtu", flow)
    fig = plot_flow(flow)
    save_figure(outdir / "flow.png", fig, dpi=120)
    plt.close(fig)


def _print_forces_table(annulus, rows) -> None:
    print(f"a = {annulus.a:g} m, b = {annulus.b:g} m, kappa = {annulus.kappa:.12g}, "
          f"delta/a = {annulus.delta_over_a:.4g}, length = {annulus.length:g} m, "
          f"ends {rows[0].get('ends', 'infinite')}")
    print(f"{'model':<12} {'f_eps (N)':>16} {'f_chi (N)':>16} {'T_a (N m)':>16} {'time (s)':>10}")
    for row in rows:
        print(f"{row['model']:<12} {row['f_eps']:>16.9e} {row['f_chi']:>16.9e} {row['T_a']:>16.9e} "
              f"{row['wall_time_s']:>10.2e}")
    for row in rows[:-1]:
        diff = row.get("relative_difference")
        if diff:
            print(f"{row['model']} vs {rows[-1]['model']}: " + ", ".join(f"{k} {v:.2e}" for k, v in diff.items()))


def _add_run(subparsers) -> None:
    p = subparsers.add_parser(
        "run", help="run a scene and write its trajectory",
        description="Integrate a scene (the embedded default when none is given) and write "
                    "trajectory.csv, summary.json, trajectory.png and scene.resolved.toml into DIR.")
    p.add_argument("scene", nargs="?", help="scene TOML file (default: the embedded steel scene)")
    p.add_argument("-o", "--output", default="snail-output", help="output folder (default snail-output)")
    p.add_argument("--t-end", help="run length: seconds, or a string with units such as '2 min'")
    p.add_argument("--model", choices=["full", "reduced", "auto"], help="equations of motion, overriding the scene")
    p.add_argument("--forces", choices=["closed-form", "reynolds", "stokes-exact", "stokes", "auto"],
                   help="force model, overriding the scene (stokes-exact: the exact 2-D Stokes forces, which "
                        "'stokes' also names in a run; auto: the cheapest meeting model.tolerance)")
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


class _Progress:
    """A tqdm bar on a terminal, refreshed at most once a second; called with the time reached."""

    def __init__(self, total: float, unit: str):
        from tqdm import tqdm

        self.bar = tqdm(total=total, desc="snail run", unit=unit, mininterval=1.0, leave=False,
                        bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} " + unit + " [{elapsed}<{remaining}]")

    def __call__(self, t: float) -> None:
        self.bar.update(t - self.bar.n)

    def close(self) -> None:
        self.bar.close()


def _progress_bar(total: float, unit: str):
    """A :class:`_Progress` on a terminal; None when stderr is piped."""
    return _Progress(total, unit) if sys.stderr.isatty() else None


def _run_scene(args) -> int:
    if args.no_plot:
        return _run_scene_drawing(args, None)
    from dynamics.app.figure_process import FigureProcess

    with FigureProcess() as figures:  # matplotlib imports in the child while the scene runs here
        return _run_scene_drawing(args, figures)


def _run_scene_drawing(args, figures) -> int:
    from dynamics.app.folder import FolderError, OutputFolder
    from dynamics.app.output import write_outputs
    from dynamics.app.run import run_scene
    from dynamics.scenes import SceneError, load_scene, resolved_toml

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
        folder = OutputFolder(args.output).__enter__()  # checked and locked before anything runs
    except (SceneError, FolderError) as err:
        raise UsageError(str(err)) from err
    bar = _progress_bar(scene.run.t_end, "s" if scene.apparatus is not None else "tau")
    try:
        try:
            trajectory = run_scene(scene, method=args.method, progress=bar)
        except SceneError as err:
            raise UsageError(str(err)) from err
        finally:
            if bar is not None:
                bar.close()
        if figures is not None:
            figures.send(trajectory)  # drawn while the other outputs are written
        for passed in trajectory.info.get("limits_passed", []):
            print(f"snail run: warning: {passed['reason']}", file=sys.stderr)
        warning = _inertia_warning(trajectory.info.get("inertia", {}))
        if warning:
            print(f"snail run: warning: fluid inertia: {warning}; see summary.json 'inertia'", file=sys.stderr)
        info = write_outputs(folder, trajectory, resolved_scene=resolved_toml(scene), scene=scene.source,
                             plot=figures is not None, max_rows=scene.run.max_rows,
                             draw=figures.png if figures is not None else None)
    finally:
        folder.__exit__(None, None, None)
    if args.json:
        print(json.dumps(info, indent=2))
    else:
        print(f"{info['status']}: {info['reason']}")
        print(f"regime {info['regime']}, mean speed {info['mean_speed']:.4g} "
              f"({'b/tau' if info['dimensionless'] else 'm/s'}), {info['steps']} steps in "
              f"{info['wall_time_s']:.2f} s; outputs in {folder.path}/")
    return 0 if trajectory.status == "completed" else 1


def _inertia_warning(inertia: dict) -> str:
    """What a run's inertia report (:func:`dynamics.equations.limits.inertia_report`) warns of, or "".

    The forces the run used are judged: the quasi-steady Stokes forces by their
    first-order error, forces with the first inertial correction by what that
    leaves, and by whether the run went past the Reynolds numbers at which it was measured.
    """
    from dynamics.equations.limits import WARN_FORCE_ERROR

    corrected = inertia.get("corrected_forces")
    if corrected is not None:
        beyond = inertia["max_reduced_reynolds"] > corrected["measured_to_reduced_reynolds"]
        if corrected["max_estimated_force_error"] <= WARN_FORCE_ERROR and not beyond:
            return ""
        past = (f"; Re* reached {inertia['max_reduced_reynolds']:.3g} (t = {inertia['t_at_max_reduced_reynolds']:.3g}"
                f" s), past Re* = {corrected['measured_to_reduced_reynolds']:g}, the largest at which the "
                "correction was compared with Navier-Stokes solutions") if beyond else ""
        return (f"the inertia-corrected forces may be in error by up to {corrected['max_estimated_force_error']:.0%} "
                f"(at t = {corrected['t_at_max_estimated_force_error']:.3g} s){past}")
    if inertia.get("max_estimated_force_error", 0.0) <= WARN_FORCE_ERROR:
        return ""
    return (f"the quasi-steady Stokes forces may be in error by up to {inertia['max_estimated_force_error']:.0%} "
            f"(at t = {inertia['t_at_max_estimated_force_error']:.3g} s; at the largest gap Reynolds number, "
            f"Re* = {inertia['max_reduced_reynolds']:.2g} at t = {inertia['t_at_max_reduced_reynolds']:.3g} s, by "
            f"{inertia['estimated_force_error_at_max_reduced_reynolds']:.0%})")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="snail", description="The snail cylinder: fluid forces, trajectories, validation.")
    parser.add_argument("--version", action="version", version=f"snail {version('snail-cylinder')}")
    subparsers = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _add_forces(subparsers)
    _add_run(subparsers)
    _add_sweep(subparsers)
    for ep in entry_points(group="snail.commands"):
        ep.load()(subparsers)
    return parser


def main(argv: list[str] | None = None) -> int:
    argv = _join_negative_values(sys.argv[1:] if argv is None else list(argv))
    args = build_parser().parse_args(argv)
    try:
        return args.run(args)
    except (UsageError, FolderError) as err:
        print(f"snail {args.command}: error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"snail {args.command}: interrupted", file=sys.stderr)
        return 130
    except Exception as err:  # a failed computation: say what failed, keep the exit status apart
        print(f"snail {args.command}: computation failed: {type(err).__name__}: {err}", file=sys.stderr)
        return 1


def console() -> int:
    """The ``snail`` command: :func:`main` on the command line's arguments, then a quick exit.

    Everything a command loads lives until the process ends, and Python's last
    collections at exit would walk it all: 0.2 s of a 2 s ``snail run`` with
    numba's and matplotlib's objects loaded. Frozen, they are left to the
    operating system.
    """
    status = main()
    gc.freeze()
    return status


if __name__ == "__main__":
    sys.exit(console())
