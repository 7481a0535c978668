"""How well snail fit recovers the roughness (validation/fit_coverage.py): its numbers and page.

The study's claims are checks judged from docs/fit_coverage/fit_coverage.json; the page must be what those
numbers write; the summary of a parameter is tested on intervals whose coverage and widths are known.
"""

import json
import math

import pytest

from validation import fit_coverage as study
from validation.checks import verdict
from validation.reports import fit_coverage as report


@pytest.fixture(scope="module")
def stored():
    return json.loads(study.RESULTS.read_text())


def test_the_stored_numbers_carry_the_claims(stored):
    assert stored["scene"] == study.SCENE and stored["records"] == study.RECORDS
    assert (stored["draws"], stored["accept"], stored["rate_hz"]) == (study.DRAWS, study.ACCEPT, study.RATE)
    assert all(len(p["truth"]) == study.RECORDS for p in stored["parameters"])
    failed = [c.name for c in study.checks_of(stored) if not verdict(c.kind, c.measured, c.reference, c.tolerance)]
    assert not failed


def test_the_page_is_the_stored_numbers(stored):
    assert report.PAGE.read_text() == report.markdown(stored)


def test_coverage_and_widths_are_read_as_stated():
    """Four records: three intervals hold the truth; widths of a quarter and a half of a uniform prior's range
    (median 0.375), and a factor 2 of a log prior's 16 (a quarter of its logarithm)."""
    uniform = {"key": "x", "low": 0.0, "high": 1.0, "log": False, "truth": [0.5] * 4, "estimate": [0.5, 0.5, 0.6, 0.4],
               "interval": [[0.4, 0.65], [0.3, 0.8], [0.3, 0.8], [0.0, 0.25]], "contained": [True, True, True, False]}
    summary = study._summary(uniform)
    assert summary["coverage"] == 0.75 and summary["width"] == pytest.approx(0.375)
    assert summary["error"] == pytest.approx(0.1) and summary["se"] == pytest.approx(math.sqrt(0.09 / 4))
    log = {**uniform, "low": 1.0, "high": 16.0, "log": True, "truth": [2.0] * 4, "estimate": [2.0] * 4,
           "interval": [[1.5, 3.0]] * 4}
    assert study._summary(log)["width"] == pytest.approx(0.25)
    # a fifth record that did not roll has no fit, and counts neither way
    held = {key: [*value, None] if isinstance(value, list) else value for key, value in uniform.items()}
    held["truth"][-1] = 0.5
    assert study._summary(held) == summary
