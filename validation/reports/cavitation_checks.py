"""The cavitation models in the Reynolds solver (:mod:`validation.cavitation_checks`): the paragraph.

:func:`run` is the group of ``snail validate``.
"""

from __future__ import annotations

from ..cavitation_checks import checks_of

__all__ = ["run"]


def run(outdir, quick: bool = False):
    """The cavitation checks; returns (checks, figure file names, a markdown paragraph)."""
    checks = checks_of(quick)
    text = ("Half-Sommerfeld truncation reproduces the classical long-bearing load components; "
            "the Swift-Stieber complementarity problem reproduces an independent shooting solution of "
            "the Reynolds-condition problem; the mass-conserving JFO model equals Swift-Stieber at a "
            "steady rupture fed at p_cav and balances liquid to rounding through rupture and reformation.")
    return checks, [], text
