"""The rough surfaces against the experiments (validation/rough_experiments.py): its numbers, page and spectrum.

The study's claims are checks judged from docs/rough_experiments/rough_experiments.json; the page must be
what those numbers write; the spectrum's density is tested on records whose spectrum is known; the slow
test reruns the showcase's rough run and compares its numbers with the stored ones.
"""

import json
import math

import numpy as np
import pytest

from validation import rough_experiments as study
from validation.checks import verdict
from validation.reports import rough_experiments as report


@pytest.fixture(scope="module")
def stored():
    return json.loads(study.RESULTS.read_text())


def test_the_stored_numbers_carry_the_claims(stored):
    assert stored["scene"] == study.SCENE and stored["seeds"] == study.SEEDS
    assert len(stored["realisations"]) == study.SEEDS
    assert [s["slope_deg"] for s in stored["slopes"]] == list(study.SLOPES)
    failed = [c.name for c in study.checks_of(stored) if not verdict(c.kind, c.measured, c.reference, c.tolerance)]
    assert not failed


def test_the_page_is_the_stored_numbers(stored):
    assert report.PAGE.read_text() == report.markdown(stored)


def _record(wavelength: float, depth: float, seed: int = 0):
    """X_b(t) at a mean speed of 4 mm/s whose speed is modulated with ``wavelength`` of distance, plus noise."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 300.0, 30001)
    x = 0.004 * t
    for _ in range(3):  # the speed as a function of the distance rolled: solve x' = v(x) by fixed point
        x = np.concatenate(([0.0], np.cumsum(np.diff(t) * 0.004 * (1.0 + depth * np.sin(2 * np.pi * x[:-1] /
                                                                                          wavelength)))))
    return t, x + 1e-7 * rng.standard_normal(t.size)


def test_a_modulation_in_distance_is_a_peak_at_its_wavelength():
    """A speed modulated every 5 cm of distance: the density there exceeds that at 3.5 cm a hundredfold."""
    t, x = _record(0.05, 0.2)
    at, off = study.relative_density(t, x, (0.05, 0.035))
    assert at > 100.0 * off  # all its power within the band would make it 3000: some leaks to harmonics
    flat_t, flat_x = _record(0.05, 0.0)
    assert study.relative_density(flat_t, flat_x, (0.05,))[0] < 10.0  # noise alone: no peak


def test_a_run_that_does_not_roll_has_no_spectrum():
    t = np.linspace(0.0, 10.0, 200)
    assert all(math.isnan(d) for d in study.relative_density(t, 1e-4 * np.sin(t), (0.05,)))


@pytest.mark.slow
def test_a_rerun_of_the_rough_showcase_gives_the_stored_numbers(stored):
    run, ap = study._run(["contact.seed=0"])
    again = study._numbers(run, ap)
    kept = stored["showcase"]["rough"]
    for name in ("mean_speed_late", "phi_mean_late", "locked_fraction_late", "quarter_ratio"):
        assert again[name] == pytest.approx(kept[name], rel=1e-6), name
