"""Validation records are re-verifiable: each verdict follows from the record's own numbers."""

import json
import math
from pathlib import Path

import pytest

from validation.checks import (
    KINDS,
    Check,
    Finding,
    absolute,
    at_least,
    at_most,
    relative,
    verdict,
)

REPORT = Path(__file__).resolve().parents[1] / "docs" / "validation" / "validation.json"


@pytest.mark.parametrize(("kind", "measured", "reference", "tolerance", "expected"), [
    ("relative", 1.01, 1.0, 0.02, True), ("relative", 1.03, 1.0, 0.02, False),
    ("relative", -0.99, -1.0, 0.02, True),
    ("absolute", 0.5, 0.0, 0.5, True), ("absolute", 0.51, 0.0, 0.5, False),
    ("at-most", 0.9, 1.0, 0.0, True), ("at-most", 1.05, 1.0, 0.1, True), ("at-most", 1.2, 1.0, 0.1, False),
    ("at-least", 1.1, 1.0, 0.0, True), ("at-least", 0.95, 1.0, 0.0, False),
    ("relative", math.nan, 1.0, 1.0, False), ("at-most", math.nan, 1.0, 0.0, False),
    ("at-least", math.inf, 1.0, 0.0, False),
])
def test_verdict(kind, measured, reference, tolerance, expected):
    assert verdict(kind, measured, reference, tolerance) is expected


def test_a_check_cannot_be_told_it_passed():
    c = relative("x", 2.0, 1.0, 0.5)
    assert not c.passed and c.as_dict()["passed"] is False
    with pytest.raises(TypeError):
        Check("x", 2.0, 1.0, 0.5, "relative", "note", True)  # no `passed` argument exists
    with pytest.raises(ValueError, match="tolerance"):
        relative("x", 1.0, 1.0, math.nan)
    with pytest.raises(ValueError, match="kind"):
        Check("x", 1.0, 1.0, 0.0, "open-interval")


def test_helpers_build_the_kinds():
    assert [absolute("a", 0, 0, 1).kind, at_most("b", 0, 1).kind, at_least("c", 1, 0).kind] == [
        "absolute", "at-most", "at-least"]
    assert "passed" not in Finding("share", 0.6).as_dict()


def test_the_stored_report_is_verified_again_from_its_numbers():
    """Every row of docs/validation/validation.json: its kind is known and its verdict follows from it."""
    rows = json.loads(REPORT.read_text())
    assert rows
    for row in rows:
        assert row["kind"] in KINDS, row
        measured = float(row["measured"])
        assert row["passed"] is verdict(row["kind"], measured, row["reference"], row["tolerance"]), row
        assert math.isfinite(row["tolerance"]) and row["tolerance"] >= 0.0, row
