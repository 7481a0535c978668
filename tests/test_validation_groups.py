"""Every group of ``snail validate`` in its quick form, one case per group of :data:`validation.suite.GROUPS`.

Each case runs the group as the suite does (``run(outdir, quick=True)``) and asks
that every comparison passes, that it draws and writes only what its quick form
should, and what that group's paragraph and records must say. The groups whose
quick form takes minutes are marked slow; ``tests/test_cli.py`` runs them all end
to end through ``snail validate --quick``.
"""

from __future__ import annotations

import math

import pytest

from validation import suite
from validation.checks import Finding, comparisons

#: Groups whose quick form takes minutes: run with ``pytest -m slow``.
SLOW = {"finite_length_trajectories", "cavitation_transient", "model_choice_checks", "full_contact_checks"}


def _name(module) -> str:
    return module.__name__.rpartition(".")[2]


def _lubrication_checks(records, text):
    assert "Sommerfeld angle" in text


def _dynamics_checks(records, text):
    assert "runaway" in text
    assert len(comparisons(records)) > 30


def _cavitation_checks(records, text):
    assert "Swift-Stieber" in text


def _cavitation_trajectories(records, text):
    assert "| 2.4 | jfo, 3 Pa |" in text


def _cavitation_transient(records, text):
    assert len(comparisons(records)) >= 5
    assert "| 2.4 | bubble |" in text


def _corrections(records, text):
    names = " ".join(c.name for c in records)
    assert "Stokes: slope" in names and "Reynolds on the exact gap: slope" in names
    assert "share of the Stokes" in names


def _stokes_trajectories(records, text):
    assert len(comparisons(records)) == 3 and len(records) == 5  # and the two findings of the Reynolds passages
    assert "| steel | 200 | 1 |" in text


def _contact_checks(records, text):
    assert len(comparisons(records)) >= 15
    assert "| 220 |" in text and "| 50 |" in text  # Table 3's speeds


def _full_contact_checks(records, text):
    assert "stick-slip" in " ".join(c.name for c in records)


def _table3(records, text):
    assert len(comparisons(records)) >= 11
    assert "| 220 | 0.07 | 0.3 |" in text and "| smooth |" in text


def _finite_length_trajectories(records, text):
    assert len(comparisons(records)) == 4
    assert "| steel | 200 | 2.4 |" in text
    ratio = {r.name: r.value for r in records if isinstance(r, Finding)}
    # the smooth run is slower with the ends open, the rough one faster (validation.finite_length_trajectories)
    assert ratio["finite length, smooth, all rock, stokes-exact: mean speed open / infinite, smallest"] < 1.0
    assert ratio["finite length, rough, stokes-exact: steady speed open / infinite, smallest"] > 1.0
    assert math.isfinite(ratio["largest estimated inertial force error of all runs"])


def _model_choice_checks(records, text):
    assert "closed-form" in text


#: Per group: the figures its quick form draws (the files it writes beside them), and what else it must show.
EXPECTED = {
    "lubrication_checks": ([], [], _lubrication_checks),
    "dynamics_checks": ([], [], _dynamics_checks),
    "cavitation_checks": ([], [], _cavitation_checks),
    "cavitation_trajectories": ([], [], _cavitation_trajectories),
    "cavitation_transient": (["cavitation_transient.png"], [], _cavitation_transient),
    "corrections": (["corrections.png"], ["corrections.csv", "corrections.json"], _corrections),
    "stokes_trajectories": ([], [], _stokes_trajectories),
    "contact_checks": ([], [], _contact_checks),
    "full_contact_checks": ([], [], _full_contact_checks),
    "table3": ([], [], _table3),
    "finite_length_trajectories": ([], [], _finite_length_trajectories),
    "model_choice_checks": ([], [], _model_choice_checks),
}


def test_every_group_has_its_case():
    assert sorted(EXPECTED) == sorted(_name(m) for m in suite.GROUPS.values())
    assert SLOW <= set(EXPECTED)


@pytest.mark.parametrize("name", [
    pytest.param(_name(m), id=_name(m), marks=[pytest.mark.slow] if _name(m) in SLOW else [])
    for m in suite.GROUPS.values()])
def test_quick_group_passes(name, quick_group):
    outdir, records, figures, text = quick_group(name)
    checks = comparisons(records)
    failed = [f"{c.name}: measured {c.measured:.6g}, reference {c.reference:.6g} ({c.kind}, {c.tolerance:g}; "
              f"{c.note})" for c in checks if not c.passed]
    assert checks and not failed, "\n".join(failed)
    drawn, written, show = EXPECTED[name]
    assert figures == drawn
    assert sorted(p.name for p in outdir.iterdir()) == sorted(drawn + written)
    show(records, text)
