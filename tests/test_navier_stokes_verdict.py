"""The Navier-Stokes verdict (validation/navier_stokes_verdict.py): its stored numbers, its page, and a rerun.

The study's conclusions are checks (:func:`validation.navier_stokes_verdict.checks_of`) judged from the
numbers in docs/navier_stokes/verdict.json: they are judged again from the stored file, docs/navier_stokes.md
must be the page those numbers write, and the slow test runs the cheapest case again to see that the
stored numbers are what the code computes. The rerun is deterministic on one machine; across BLAS
builds the flow solver's adaptive steps may differ at rounding, which moves its results by about its
tolerance: the rerun's errors must agree with the stored ones to within the reference's own error
(its difference from the same run at a quarter of the tolerance, stored with it) plus 1e-9.
"""

import json
import math

import pytest

from validation import navier_stokes_verdict as study
from validation.checks import verdict
from validation.reports import navier_stokes_verdict as report


@pytest.fixture(scope="module")
def stored():
    return json.loads(study.RESULTS.read_text())


def test_the_stored_numbers_carry_the_conclusions(stored):
    assert [c["label"] for c in stored["cases"]] == [c.label for c in study.CASES]
    for case, spec in zip(stored["cases"], study.CASES):
        assert case["horizon_s"] == spec.horizon
        assert case["navier_stokes"]["status"] == "completed"
        assert case["navier_stokes"]["t_last"] == pytest.approx(spec.horizon, rel=1e-12)
        assert set(case["models"]) == set(study.MODELS)
    failed = [c.name for c in study.checks_of(stored) if not verdict(c.kind, c.measured, c.reference, c.tolerance)]
    assert not failed


def test_the_page_is_the_stored_numbers(stored):
    assert report.PAGE.read_text() == report.markdown(stored)


@pytest.mark.slow
def test_a_rerun_gives_the_stored_numbers(stored):
    """Case (b), the cheapest (a minute): its errors again."""
    case = next(c for c in study.CASES if c.label == "b")
    again = study.run_case(case, log=lambda _: None)
    kept = next(c for c in stored["cases"] if c["label"] == "b")
    for measure in study.MEASURES:
        slack = study.reference_error(kept, measure) + 1e-9
        for label in study.MODELS:
            assert again["models"][label][measure] == pytest.approx(kept["models"][label][measure], abs=slack), \
                (label, measure)
    assert again["ode_regime_over_10_s"] == kept["ode_regime_over_10_s"]
    assert math.isclose(again["max_reduced_reynolds"], kept["max_reduced_reynolds"], rel_tol=1e-2)
