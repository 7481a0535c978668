"""Finite length against 3-D Stokes (:mod:`validation.finite_length`): its tables and files.

Run ``python -m validation.reports.finite_length [FOLDER]`` from the project root to write
``factors.{json,md}`` and ``stokes3d.{json,md}`` (default ``docs/finite_length``).
"""

from __future__ import annotations

import sys
from pathlib import Path

from lubrication.finite_length import FACTOR_NAMES
from numerics.files import write_json, write_text

from ..finite_length import LABELS, MODELS, factors_at_the_apparatus, run

__all__ = ["factors_markdown", "main", "to_markdown"]


def factors_markdown(factors: dict) -> str:
    lines = [(f"Reynolds factors at L/a = {factors['length_over_a']:.3f} (L/2a = {factors['length_over_a'] / 2:.3f}), "
             "open ends: thin gap (solver, extrapolated (128, 64)), and in brackets the exact eccentric gap at "
             "delta/a = 0.406; last column: the table kernel's largest difference from the thin-gap solver."), "",
             "| kappa | " + " | ".join(LABELS[n] for n in FACTOR_NAMES) + " | table - solver |",
             "|---|" + "---|" * (len(FACTOR_NAMES) + 1)]
    for row in factors["rows"]:
        cells = [f"{row['thin'][n]:.5f} ({row['eccentric'][n]:.5f})" for n in FACTOR_NAMES]
        diff = max(abs(row["table"][n] - row["thin"][n]) for n in FACTOR_NAMES[:2])
        lines.append(f"| {row['kappa']} | " + " | ".join(cells) + f" | {diff:.1e} |")
    return "\n".join(lines) + "\n"


def _pct(x: float) -> str:
    return f"{100.0 * x:+.2f}%"


def to_markdown(study: dict) -> str:
    lines = [(f"L/a = {study['length_over_a']:.3f}, delta/a = {study['delta_over_a']:.4f}; "
             f"3-D meshes (around x across x along half) {[r['mesh'] for r in study['results'][0]['meshes']]}, "
             f"run {study['wall_time_s']:.0f} s."), ""]
    header = ("| kappa | coefficient | F3 (3-D) | +- | F_thin | F_ecc | r_S = 2D/lub | "
              + " | ".join(f"err {m}" for m in MODELS) + " |")
    lines += [header, "|---|---|---|---|---|---|---|" + "---|" * len(MODELS)]
    for res in study["results"]:
        for name in FACTOR_NAMES:
            row = res["rows"][name]
            errs = [(_pct(row["errors"][m]) + (f" ({_pct(row['errors_row'][m])})" if name == "t_a_per_w_b" else ""))
                    if m in row["errors"] else "" for m in MODELS]
            lines.append(f"| {res['kappa']} | {LABELS[name]} | {row['F3']:.4f} | {row['F3_error']:.1e} | "
                         f"{row['F_thin']:.4f} | {row['F_ecc']:.4f} | {row['r_stokes']:.4f} | " + " | ".join(errs) + " |")
    lines += ["", "Errors are model / R_3D - 1; for T_a / W_b also, in brackets, against |T_a / W_a| (its row)."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    out = Path(argv[0]) if argv else Path("docs/finite_length")
    factors = factors_at_the_apparatus()
    write_json(out / "factors.json", factors)
    write_text(out / "factors.md", "# Finite-length factors at the apparatus\n\n" + factors_markdown(factors))
    print(factors_markdown(factors))
    study = run()
    write_json(out / "stokes3d.json", study)
    text = to_markdown(study)
    write_text(out / "stokes3d.md", "# 3-D Stokes against 2-D Stokes x finite-length factor\n\n" + text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
