"""The automatic model choice against fresh solves (:mod:`validation.model_choice_checks`): the paragraph.

:func:`run` is the group of ``snail validate``.
"""

from __future__ import annotations

from pathlib import Path

from ..checks import Check
from ..model_choice_checks import APPARATUS, EQUATIONS_TOLERANCE, FORCE_TOLERANCE, THIN, compute

__all__ = ["run"]


def run(outdir, quick: bool = False) -> tuple[list[Check], list[str], str]:
    """All checks of the automatic choice; returns (checks, figure file names, a markdown paragraph)."""
    Path(outdir).mkdir(parents=True, exist_ok=True)
    r = compute(quick)
    thin, wide, strict, eq_thin, eq_wide = r["thin"], r["wide"], r["strict"], r["eq_thin"], r["eq_wide"]
    paragraph = (
        "The automatic choice (`dynamics.app.auto`) reads the stored speed-versus-accuracy study "
        "(`benchmarks/accuracy.py`); here each choice is recomputed against the exact Stokes solution (or, "
        "when that is the choice, a fresh finite-element Stokes solve) or a fresh trajectory. "
        f"At a force tolerance of {FORCE_TOLERANCE:g} it picks {thin.model} at delta/a = {THIN:g} "
        f"(largest error now {max(r['thin_errors'].values()):.2e}, stored {thin.error:.2e}) and {wide.model} at "
        f"{APPARATUS:g} (now {max(r['wide_errors'].values()):.2e}); at 1e-4 it picks {strict.model} at {THIN:g} "
        f"(now {max(r['strict_errors'].values()):.2e}). At an equations tolerance of {EQUATIONS_TOLERANCE:g} it "
        f"picks the {eq_thin.model} equations at {THIN:g} (trajectory error now {r['reduced_error']:.2e}, stored "
        f"{eq_thin.error:.2e}) and the {eq_wide.model} equations at {APPARATUS:g}, where the reduced "
        f"equations' error is now {r['reduced_wide_error']:.2e}.")
    return r["checks"], [], paragraph
