"""The inertia study (validation/inertia.py): its cheap parts, and the whole run when slow tests are asked for."""

import math

import numpy as np
import pytest

pytest.importorskip("skfem")

from dynamics.apparatus import PRESETS  # noqa: E402
from validation import inertia  # noqa: E402


def test_worst_first_order_error_tends_to_the_thin_gap_co_rotation():
    """The largest G over kappa and motions is the kappa -> 0 co-rotation, 1/10 in a thin gap.

    G = (U_a^2 + 4 U_a U_b + U_b^2)/(30 (U_a + U_b) V) at U_a = U_b (thin-gap
    closed form); at delta/a = 0.01 the tabulated value departs by O(delta/a).
    """
    survey = inertia.first_order_survey()
    assert survey["g_max"][0] == pytest.approx(0.1, rel=0.02)
    # thinner gaps are worse per Re*: G falls with delta/a
    assert np.all(np.diff(survey["g_max"]) < 0.0)
    limits = inertia.thresholds(survey)
    for row in limits.values():
        assert row["reduced_0.01"] * row["g_max"] == pytest.approx(0.01, rel=1e-12)


def test_missing_frame_force_factor_is_m_eff_less_m_reduced():
    """m''_a (1 + m''_a/m_f) = m_eff - m'_a: the centripetal mass of (2.2) becomes m'_a."""
    for ap in PRESETS.values():
        factor = ap.m_a_displaced * (1.0 + ap.m_a_displaced / ap.m_f)
        assert factor == pytest.approx(ap.m_eff - ap.m_a_reduced, rel=1e-12)
    rows = inertia.apparatus_frame_force()
    for row in rows:
        ap = PRESETS[row["apparatus"]]
        force = (ap.m_eff - ap.m_a_reduced) * row["kappa"] * ap.delta * row["chi_dot"] ** 2
        assert force == pytest.approx(row["level"] * ap.m_a_reduced * ap.g, rel=1e-12)


def test_crossing_interpolates_log_log():
    """A power law error = c Re^p crosses its level where the formula says."""
    re = np.array([1.0, 2.0, 4.0, 8.0])
    err = 0.01 * re**2
    assert inertia._crossing(re, err, 0.1) == pytest.approx(math.sqrt(10.0), rel=1e-12)
    assert math.isnan(inertia._crossing(re, err, 10.0))


@pytest.mark.slow
def test_the_study_passes_its_checks(tmp_path):
    """The whole study (about four minutes): every check passes and the outputs are written."""
    result = inertia.run()
    failed = [c["name"] for c in result["checks"] if not c["passed"]]
    assert not failed
    paths = inertia.write_outputs(result, tmp_path)
    assert all(p.exists() and p.stat().st_size > 0 for p in paths)
