"""The inertia study (validation/inertia.py): its cheap parts, and the whole run when slow tests are asked for."""

import math

import numpy as np
import pytest

pytest.importorskip("skfem")

from dynamics.apparatus import PRESETS  # noqa: E402
from validation import inertia  # noqa: E402
from validation.reports import inertia as inertia_report  # noqa: E402


def test_worst_first_order_error_tends_to_the_thin_gap_co_rotation():
    """The largest G over kappa and every direction of (W_a, W_b) is at kappa -> 0, equal wall speeds.

    Against the non-cancelling scale |f_chi,a| + |f_chi,b| the thin-gap closed form gives
    G = |U_a^2 + 4 U_a U_b + U_b^2| / (30 (|U_a| + |U_b|) V), largest (1/10) at U_a = U_b;
    at delta/a = 0.01 the tabulated value departs by O(delta/a). The direction scan has
    720 steps in angle, so the maximum is found to 1e-5 of G.
    """
    survey = inertia.first_order_survey()
    assert survey["g_max"][0] == pytest.approx(0.1, rel=0.02)
    assert survey["g_max"][0] <= 0.1
    for at in survey["g_max_at"]:
        assert at["kappa"] == 0.0 and at["u_b_over_u_a"] == pytest.approx(1.0, rel=1e-9)
    # thinner gaps are worse per Re*: G falls with delta/a
    assert np.all(np.diff(survey["g_max"]) < 0.0)
    # no single motion exceeds the scan
    for name in ("inner", "outer", "rolling", "co-rotating"):
        assert np.all(np.array(survey[name]).max(axis=1) <= np.array(survey["g_max"]) * (1.0 + 1e-12))
    limits = inertia.thresholds(survey)
    for row in limits.values():
        assert row["reduced_0.01"] * row["g_max"] == pytest.approx(0.01, rel=1e-12)


def test_counter_rotation_has_a_bounded_error_at_small_kappa():
    """U_b = -U_a: the thin-gap Stokes f_chi cancels, the error against |f_chi,a| + |f_chi,b| does not blow up.

    The closed form gives G = 1/30 (thin gap); finite elements and the exact ODE agree to 1e-3
    at every gap, and the stored ratio f_chi / scale shows how nearly f_chi cancels (delta/a
    times a number of order one).
    """
    rows = [r for r in inertia.small_kappa_comparison() if r["motion"] == "counter-rotating"]
    assert len(rows) == len(inertia.DELTAS)
    for row in rows:
        assert row["thin_gap"] == pytest.approx(1.0 / 30.0, rel=1e-12)
        assert row["finite_elements"] == pytest.approx(row["exact"], rel=1e-3)
        assert row["stokes_f_chi_over_scale"] < row["delta_over_a"]
    assert rows[0]["exact"] == pytest.approx(1.0 / 30.0, rel=3.0 * rows[0]["delta_over_a"])


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


def test_stored_study_passes_its_checks():
    """docs/inertia/inertia.json, as written by the study: every check there passes (judged again from
    its numbers), and the runaways reached the end of their runs past the Reynolds limit."""
    import json
    from pathlib import Path

    from validation.checks import verdict

    stored = json.loads((Path(__file__).resolve().parents[1] / "docs" / "inertia" / "inertia.json").read_text())
    for check in stored["checks"]:
        measured = float(check["measured"])
        assert verdict(check["kind"], measured, check["reference"], check["tolerance"]), check["name"]
    runs = stored["runaway_trajectories"]
    assert {(r["slope_deg"], r["model"]) for r in runs} == {
        (deg, label) for deg in inertia.RUNAWAY_SLOPES for label, _, _ in inertia.RUNAWAY_MODELS}
    for run in runs:
        assert run["t_last"] == pytest.approx(inertia.RUNAWAY_T_END, rel=1e-12)
        assert run["limits_passed"]  # the first swing passes Re* = 1 and the run goes on
        assert run["inertia"]["estimated_force_error_at_max_reduced_reynolds"] <= \
            run["inertia"]["max_estimated_force_error"]


@pytest.mark.slow
def test_the_study_passes_its_checks(tmp_path):
    """The whole study (about six minutes): every check passes and the outputs are written."""
    result = inertia.run()
    failed = [c["name"] for c in result["checks"] if not c["passed"]]
    assert not failed
    paths = inertia_report.write_outputs(result, tmp_path)
    assert all(p.exists() and p.stat().st_size > 0 for p in paths)
