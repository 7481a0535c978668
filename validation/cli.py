"""``snail validate``: registered into the ``snail`` command through the ``snail.commands`` entry point."""

from __future__ import annotations

__all__ = ["register"]


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "validate", help="run the validation checks and write the report",
        description="Run every validation check; write report.md, figures and validation.json "
                    "(a list of {name, measured, reference, tolerance, passed}).")
    p.add_argument("-o", "--output", default="validation-report", help="output folder (default validation-report)")
    p.add_argument("--quick", action="store_true", help="a fast subset, without figures")
    p.set_defaults(run=_run)


def _run(args) -> int:
    from dynamics.app.folder import writable_folder

    from .suite import run_all

    writable_folder(args.output)  # an unusable path is bad input, found before any check runs
    checks, seconds = run_all(args.output, quick=args.quick)
    failed = [c for c in checks if not c.passed]
    print(f"{len(checks) - len(failed)} of {len(checks)} checks passed in {seconds:.1f} s; "
          f"report in {args.output}/report.md")
    for c in failed:
        print(f"FAILED: {c.name}: measured {c.measured:.6g}, reference {c.reference:.6g}, "
              f"tolerance {c.tolerance:.3g} ({c.kind})")
    return 1 if failed else 0
