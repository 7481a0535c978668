"""``snail forces``: the force and torque on the inner cylinder at one instant, with any registered model.

The models, their options (with units, ranges and help) and the rules by which
the compositions combine all come from :mod:`lubrication.registry`: a model
registered there is a ``--model`` here, and its options are flags.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

from dynamics.app.command import UsageError, number

__all__ = ["register"]


def _steel():
    from dynamics.apparatus import STEEL

    return STEEL


def register(subparsers) -> None:
    """Add ``snail forces``: the registered models, and a flag for every option of the registry."""
    from lubrication import registry

    steel = _steel()
    models = registry.names()
    p = subparsers.add_parser(
        "forces", help="fluid force and torque on the inner cylinder",
        description="Fluid force f_eps, f_chi (N) and torque T_a (N m) on the inner cylinder, whole length, for "
                    "one instant. SI units throughout. Models: " + "; ".join(
                        f"{name}: {registry.get(name).summary}" for name in models) + ".")
    p.add_argument("--model", default="stokes-exact", choices=[*models, "all", "auto"],
                   help="force model (default stokes-exact, the exact 2-D Stokes forces); all: every model that "
                        "takes the options given, and its differences from the exact Stokes forces; auto: the "
                        "cheapest whose measured error meets --tolerance (infinite length only)")
    p.add_argument("--tolerance", type=number, default=1e-2,
                   help="auto: largest acceptable relative error of the forces, in (0, 1), default 1e-2")
    p.add_argument("--a", type=number, required=True, help="inner radius (m)")
    p.add_argument("--b", type=number, required=True, help="outer radius (m)")
    p.add_argument("--kappa", type=number, required=True, help="eccentricity eps/(b - a), in [0, 1)")
    p.add_argument("--eps-dot", type=number, default=0.0, help="d eps/dt (m/s), default 0")
    p.add_argument("--chi-dot", type=number, default=0.0, help="d chi/dt (rad/s), default 0")
    p.add_argument("--omega-a", type=number, default=0.0, help="Omega_a (rad/s), default 0")
    p.add_argument("--omega-b", type=number, default=0.0, help="Omega_b (rad/s), default 0")
    p.add_argument("--nu", type=number, default=steel.nu,
                   help=f"kinematic viscosity (m^2/s), default {steel.nu:g} (the steel preset's 200 cSt oil)")
    p.add_argument("--rho", type=number, default=steel.rho,
                   help=f"fluid density (kg/m^3), default {steel.rho:g} (the steel preset's)")
    p.add_argument("--length", type=number, default=steel.length,
                   help=f"axial length (m), default {steel.length:g} (the steel preset's)")
    for name, key in registry.option_keys().items():
        kind = (dict(choices=key.options()) if key.choices else dict(type=int) if key.integer else
                dict(type=number))
        unit = f" ({key.unit})" if key.unit else ""
        p.add_argument(f"--{name.replace('_', '-')}", dest=f"option_{name}", **kind,
                       metavar=None if key.choices else name.upper(),
                       help=f"{key.help}{unit}")
    p.add_argument("--flow", metavar="DIR", help="stokes: write the flow field to DIR/flow.vtu (velocity, "
                                                  "pressure, vorticity) and a picture DIR/flow.png")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run)


def _options(args) -> dict:
    """The registry options given on the command line (an option not given is the model's default)."""
    return {k[len("option_"):]: v for k, v in vars(args).items() if k.startswith("option_") and v is not None}


def _for_model(name: str, given: dict) -> dict:
    """The options of ``given`` that the model ``name`` takes: its own and the compositions'."""
    from lubrication import registry

    spec = registry.get(name)
    composed = registry.option_keys(compositions_only=True)
    return {k: v for k, v in given.items() if k in spec.options or k in composed}


def _check_flow_folder(path: str) -> Path:
    """The folder of ``--flow``, writable, checked before anything is solved."""
    folder = Path(path)
    if folder.exists() and not folder.is_dir():
        msg = f"--flow {path}: a file, not a folder"
        raise UsageError(msg)
    parent = next((p for p in (folder, *folder.parents) if p.exists()), Path("."))
    if not parent.is_dir() or not os.access(parent, os.W_OK | os.X_OK) or str(parent.resolve()).startswith("/proc"):
        msg = f"--flow {path}: cannot write there ({parent} is not a writable folder)"
        raise UsageError(msg)
    return folder


def _run(args) -> int:
    from lubrication import Annulus, Fluid, Motion, registry

    given = _options(args)
    try:
        annulus = Annulus.from_kappa(args.a, args.b, args.kappa, length=args.length)
        motion = Motion(eps_dot=args.eps_dot, chi_dot=args.chi_dot, omega_a=args.omega_a, omega_b=args.omega_b)
        fluid = Fluid(nu=args.nu, rho=args.rho)
        if args.model == "auto":
            if given:
                raise UsageError(f"--model auto chooses its model and options itself; drop "
                                 f"{', '.join('--' + k.replace('_', '-') for k in given)}")
            return _run_auto(args, annulus, motion, fluid)
        names = [args.model] if args.model != "all" else _all_models(annulus, given)
        if args.flow is not None and "stokes" not in names:
            raise UsageError("--flow draws the finite-element Stokes flow: it needs --model stokes (or all)")
        flow = _check_flow_folder(args.flow) if args.flow is not None else None
        for name in names:  # every model and option checked before anything is solved
            spec = registry.get(name)
            if spec.check is not None:
                spec.check(annulus)
            registry.check_options(name, **_for_model(name, given))
        results = []
        for name in names:
            options = _for_model(name, given)

            def evaluate(name=name, options=options):
                return registry.fluid_forces(annulus, motion, fluid, name, **options)

            if name != "stokes":  # the finite elements cache their factorisation: a warm-up would hide its cost
                evaluate()
            start = time.perf_counter()
            f = evaluate()
            row = {"model": name, "ends": options.get("ends", "infinite"), "f_eps": f.f_eps, "f_chi": f.f_chi,
                   "T_a": f.T_a, "wall_time_s": time.perf_counter() - start, **options}
            results.append((f, row))
    except (ValueError, ImportError) as err:
        raise UsageError(_as_flags(str(err))) from err
    if flow is not None:
        _write_flow(flow, annulus, motion, fluid, _for_model("stokes", given))
    if len(results) == 1:
        out = results[0][1]
    else:
        ref = results[-1][0]  # the exact Stokes forces are the reference: every other model approximates them
        for f, row in results:
            row["relative_difference"] = _relative_differences(f, ref)
        out = dict(results[-1][1])
        out.update(model="all", reference=results[-1][1]["model"],
                   wall_time_s=sum(r["wall_time_s"] for _, r in results), models=[row for _, row in results])
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        _print_table(annulus, [row for _, row in results])
    return 0


def _as_flags(message: str) -> str:
    """A registry message that opens with an option's name ("p_ref must be ...") opens with its flag here."""
    from lubrication import registry

    for name in registry.option_keys():
        if message.startswith((f"{name} ", f"{name}:")):
            return f"--{name.replace('_', '-')}{message[len(name):]}"
    return message


def _all_models(annulus, given: dict) -> list[str]:
    """The models of ``--model all``: each that takes the options given and whose measured range holds the
    annulus (the finite elements where the extra is installed), the exact Stokes forces last, as the reference."""
    from lubrication import registry

    chosen = []
    for name in registry.names():
        spec = registry.get(name)
        if name == "stokes-exact" or (spec.extra and not _installed(spec.extra)):
            continue
        try:
            if spec.check is not None:
                spec.check(annulus)
            registry.check_options(name, **_for_model(name, given))
        except ValueError:
            continue
        chosen.append(name)
    return [*chosen, "stokes-exact"]


def _installed(extra: str) -> bool:
    from importlib.util import find_spec

    modules = {"fem": ("skfem", "meshio")}.get(extra, ())
    return all(find_spec(m) is not None for m in modules)


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


def _run_auto(args, annulus, motion, fluid) -> int:
    """``--model auto``: the choice of :func:`dynamics.app.auto.choose_forces` at this kappa, evaluated."""
    from dynamics.app.auto import choose_forces
    from lubrication import registry

    choice = choose_forces(args.tolerance, annulus.delta_over_a, annulus.kappa)
    registry.fluid_forces(annulus, motion, fluid, choice.model, **choice.options)  # warm-up
    start = time.perf_counter()
    f = registry.fluid_forces(annulus, motion, fluid, choice.model, **choice.options)
    seconds = time.perf_counter() - start
    out = {"model": "auto", "chosen_model": choice.model, "options": choice.options, "reason": choice.reason,
           "tolerance": args.tolerance, "measured_error": choice.error,
           "f_eps": f.f_eps, "f_chi": f.f_chi, "T_a": f.T_a, "wall_time_s": seconds}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        _print_table(annulus, [dict(out, model=choice.model)])
        print(f"chosen: {choice.model}: {choice.reason}.")
    return 0


def _write_flow(folder: Path, annulus, motion, fluid, mesh_options) -> None:
    import matplotlib.pyplot as plt

    from lubrication.stokes import plot_flow, stokes_flow, write_vtu
    from numerics.files import save_figure

    flow = stokes_flow(annulus, motion, fluid, **mesh_options)
    folder.mkdir(parents=True, exist_ok=True)
    write_vtu(folder / "flow.vtu", flow)
    fig = plot_flow(flow)
    save_figure(folder / "flow.png", fig, dpi=120)
    plt.close(fig)


def _print_table(annulus, rows) -> None:
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
