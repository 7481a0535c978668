"""``snail validate`` and ``snail corrections``: registered into the ``snail`` command through the
``snail.commands`` entry point.

Registering a command imports nothing of the checks: every ``snail`` command
builds the whole parser, and the checks' imports (finite elements, figures)
would cost every one of them.
"""

from __future__ import annotations

import ctypes
import sys

__all__ = ["register", "register_corrections"]

#: glibc's mallopt parameter for the size from which a block is mapped on its own (malloc.h).
_M_MMAP_THRESHOLD = -3


def register(subparsers) -> None:
    """Add ``snail validate``."""
    p = subparsers.add_parser(
        "validate", help="run the validation checks and write the report",
        description="Run every validation check; write report.md, figures and validation.json "
                    "(a list of {name, measured, reference, tolerance, passed}).")
    p.add_argument("-o", "--output", default="validation-report", help="output folder (default validation-report)")
    p.add_argument("--quick", action="store_true", help="a fast subset, without figures")
    p.set_defaults(run=_validate)


def register_corrections(subparsers) -> None:
    """Add ``snail corrections``."""
    p = subparsers.add_parser(
        "corrections", help="delta/a correction study: lubrication and Reynolds against Stokes",
        description="Ratio of the full-Stokes and the exact-gap Reynolds resistance coefficients to "
                    "the lubrication forms (2.5)-(2.7) against kappa for delta/a from 0.01 to 1, the "
                    "thin-gap correction coefficients and the paper's apparatus. Writes "
                    "corrections.csv, corrections.json and corrections.png.")
    p.add_argument("-o", "--output", default="corrections", help="output folder (default corrections)")
    p.add_argument("--quick", action="store_true",
                   help="only the four gaps the checks need and one finite-element case")
    p.set_defaults(run=_corrections)


def _return_freed_blocks_to_the_system() -> None:
    """Have glibc map every block of 1 MiB or more on its own, so that freeing it returns it.

    The groups of checks run one after another in this process. A group's large
    arrays (finite-element systems and their factors, long trajectories) are
    freed when it ends, but glibc keeps blocks below a threshold it raises as
    it goes (up to 32 MiB) inside its heap, where later small allocations pin
    them. Measured on ``snail validate --quick``: a peak of 412 MB without this
    and 394 MB with it (set before the checks' imports), at a small cost in
    time. Elsewhere than glibc, nothing changes.
    """
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return
    mallopt(_M_MMAP_THRESHOLD, 1 << 20)


def _validate(args) -> int:
    _return_freed_blocks_to_the_system()
    from dynamics.app.command import announce_compiling
    from numerics.folder import writable_folder

    from .suite import GROUPS, run_all

    writable_folder(args.output)  # an unusable path is bad input, found before any check runs
    groups, done = len(GROUPS), []

    def progress(title, passed, total, seconds):
        done.append(title)
        print(f"snail validate: [{len(done)}/{groups}] {title}: {passed} of {total} in {seconds:.0f} s",
              file=sys.stderr, flush=True)

    print(f"snail validate: {groups} groups of checks{' (the quick subset)' if args.quick else ''}; a line as "
          "each ends", file=sys.stderr, flush=True)
    with announce_compiling("validate"):
        checks, seconds = run_all(args.output, quick=args.quick, progress=progress)
    failed = [c for c in checks if not c.passed]
    print(f"{len(checks) - len(failed)} of {len(checks)} checks passed in {seconds:.1f} s; "
          f"report in {args.output}/report.md")
    for c in failed:
        print(f"FAILED: {c.name}: measured {c.measured:.6g}, reference {c.reference:.6g}, "
              f"tolerance {c.tolerance:.3g} ({c.kind})")
    return 1 if failed else 0


def _corrections(args) -> int:
    """Run the study, write CSV, JSON and figure into ``args.output``."""
    from numerics.folder import writable_folder

    from .checks import Check
    from .reports.corrections import run

    writable_folder(args.output)  # an unusable path is bad input, found before the study runs
    records, _, text = run(args.output, quick=args.quick)
    checks = [c for c in records if isinstance(c, Check)]
    failed = [c for c in checks if not c.passed]
    print(text)
    print(f"{len(checks) - len(failed)} of {len(checks)} checks passed; "
          f"corrections.csv, corrections.json and corrections.png in {args.output}")
    return 1 if failed else 0
