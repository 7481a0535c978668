"""Run every group of validation checks and write ``validation.json`` and ``report.md``."""

from __future__ import annotations

import os
import shutil
import tempfile
import time
import warnings
from pathlib import Path

from dynamics.equations.limits import ValidityWarning
from lubrication.stokes import clear_cache
from numerics.files import write_json, write_text
from numerics.folder import held_signals

from .checks import Check, Finding
from .reports import (
    cavitation_checks,
    cavitation_trajectories,
    cavitation_transient,
    contact_checks,
    corrections,
    dynamics_checks,
    finite_length_trajectories,
    full_contact_checks,
    lubrication_checks,
    model_choice_checks,
    stokes_trajectories,
    table3,
)
from .reports.paper_claims import claims_table

__all__ = ["GROUPS", "run_all"]

# title -> the group's module in validation.reports, with run(outdir, quick) -> (checks, figure names,
# paragraph); it presents the study of the module of the same name in validation, which computes and checks
GROUPS = {
    "Reynolds solver against the lubrication closed forms": lubrication_checks,
    "Equations of motion: figures 2 and 3, section 3, the distinguished limit and the runaway":
        dynamics_checks,
    "Cavitation models in the Reynolds solver": cavitation_checks,
    "Cavitation in the equations of motion: does a rupturing film stop the sinking? (section 7)":
        cavitation_trajectories,
    "Cavitation in transients: the JFO film's content in the state, and the bubble gauge": cavitation_transient,
    "Lubrication against full Stokes at finite delta/a": corrections,
    "Lubrication against full Stokes forces along trajectories of the paper's apparatus":
        stokes_trajectories,
    "Rough contact: figures 7-10 and Table 3 from simulations": contact_checks,
    "Rough contact in the full model: the limit to section 5 and the paper's apparatus": full_contact_checks,
    "Table 3 re-inferred with the full model and exact finite-gap forces": table3,
    "Finite length: trajectories of the apparatus with the gap open at both ends": finite_length_trajectories,
    "The automatic model choice against fresh reference solves": model_choice_checks,
}


# The groups that solve finite-element systems run first, while the process is smallest: every group
# leaves compiled kernels and tables behind (the process holds 150 MB at the start, 350 MB after all), and the
# peak is the largest finite-element solve (50-90 MB) on top of what is held by then. The report keeps
# the order above.
_RUN_FIRST = (corrections, model_choice_checks)


def _fmt(x) -> str:
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def run_all(outdir: str | Path, quick: bool = False, progress=None) -> tuple[list, float]:
    """Run all groups; write ``validation.json`` (the comparisons), ``findings.json`` and ``report.md``.

    Only comparisons (:class:`~validation.checks.Check`) are counted; findings,
    numbers reported without a verdict, are listed apart. The report and its
    figures are written into a staging folder beside ``outdir`` and moved into it
    together at the end (signals held meanwhile): an interrupted run leaves the
    previous report as it was, never part of a new one. ``progress(title, passed,
    total, seconds)`` is called as each group ends.
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(dir=outdir.parent, prefix=f".{outdir.name}.staging-"))
    try:
        checks, seconds = _run_groups(staging, quick, progress)
        with held_signals():
            for path in staging.iterdir():
                os.replace(path, outdir / path.name)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return checks, seconds


def _run_groups(outdir: Path, quick: bool, progress) -> tuple[list, float]:
    start = time.perf_counter()
    checks, findings, sections, summary = [], [], [], []
    results = {}
    for title, module in sorted(GROUPS.items(), key=lambda group: group[1] not in _RUN_FIRST):
        group_start = time.perf_counter()
        with warnings.catch_warnings():
            # the studies run past the validity limits on purpose, and record where
            warnings.simplefilter("ignore", ValidityWarning)
            results[title] = (*module.run(outdir, quick=quick), time.perf_counter() - group_start)
        clear_cache()  # a group's finite-element systems are not the next group's: free them
        if progress is not None:
            group_checks = [r for r in results[title][0] if isinstance(r, Check)]
            progress(title, sum(c.passed for c in group_checks), len(group_checks), results[title][-1])
    for title in GROUPS:
        records, figures, text, group_seconds = results[title]
        group_checks = [r for r in records if isinstance(r, Check)]
        group_findings = [r for r in records if isinstance(r, Finding)]
        summary.append((title, sum(c.passed for c in group_checks), len(group_checks), group_seconds))
        checks.extend(group_checks)
        findings.extend(group_findings)
        lines = [f"## {title}", "", text, "",
                 "| check | kind | measured | reference | tolerance | passed |",
                 "|---|---|---|---|---|---|"]
        lines += [f"| {c.name} | {c.kind} | {_fmt(c.measured)} | {_fmt(c.reference)} | {_fmt(c.tolerance)} | "
                  f"{'yes' if c.passed else '**NO**'} |" for c in group_checks]
        if group_findings:
            lines += ["", "Reported, not judged:", "", "| finding | value | note |", "|---|---|---|"]
            lines += [f"| {f.name} | {_fmt(f.value)} | {f.note} |" for f in group_findings]
        lines += [""] + [f"![{name}]({name})" for name in figures]
        sections.append("\n".join(lines))
    seconds = time.perf_counter() - start
    failed = sum(not c.passed for c in checks)
    passed = (f"{len(checks) - failed} of {len(checks)} comparisons passed in {seconds:.1f} s"
              f"{' (quick subset)' if quick else ''}; {len(findings)} further numbers are reported without a "
              "verdict. Each comparison's verdict follows from its kind, measured value, reference and "
              "tolerance (validation.checks.verdict), so validation.json can be checked again from its "
              "numbers alone.")
    head = ["# Validation report", "", passed, "",
            "| group | comparisons passed | seconds |", "|---|---|---|"]
    head += [f"| {title} | {ok} of {total} | {secs:.1f} |" for title, ok, total, secs in summary]
    intro = ("Each row paraphrases the paper (section and equation numbers of Balmforth, Bush, Vener & Young "
             "2007) and fills the measured column from this run's checks, listed in the sections below.")
    head += ["", "## The paper's statements and what this tool finds", "", intro, "",
             claims_table(checks + findings, quick=quick), ""]
    write_json(outdir / "validation.json", [c.as_dict() for c in checks])
    write_json(outdir / "findings.json", [f.as_dict() for f in findings])
    write_text(outdir / "report.md", "\n".join(head + sections) + "\n")
    return checks, seconds
