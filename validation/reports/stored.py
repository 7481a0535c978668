"""What the reports of studies with stored numbers share: the checks' table, and rewriting a page from its file.

A study that stores its numbers under ``docs/`` (the Navier-Stokes verdict, the Stokes-number limit, the rough
surfaces against the experiments) is run once by its module in :mod:`validation`; its report module here words
and draws it from the stored file, without running anything.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..checks import verdict

__all__ = ["checks_table", "rewrite"]


def checks_table(checks) -> list[str]:
    """A markdown table of ``checks``, each passed or not as :func:`validation.checks.verdict` judges it (a name's
    bars, as in |x_b error|, escaped: they would split its cell)."""
    lines = ["| check | measured | reference | tolerance | passed |", "|---|---|---|---|---|"]
    for c in checks:
        passed = verdict(c.kind, c.measured, c.reference, c.tolerance)
        name = c.name.replace("|", "\\|")
        lines.append(f"| {name} | {c.measured:.4g} | {c.reference:.4g} | {c.tolerance:.3g} | "
                     f"{'yes' if passed else 'no'} |")
    return lines


def rewrite(results: Path, write_outputs, checks_of) -> None:
    """Write a study's page and figures from its stored ``results``, print their paths, and exit with the
    names of the checks that fail."""
    stored = json.loads(Path(results).read_text())
    for path in write_outputs(stored):
        print(path)
    failed = [c.name for c in checks_of(stored) if not verdict(c.kind, c.measured, c.reference, c.tolerance)]
    if failed:
        raise SystemExit(f"failed checks: {failed}")
