"""The run guard on fluid inertia: its default, its messages, and the inertia report of a run.

References independent of the tabulated estimate: the exact small-eccentricity
Navier-Stokes solution (lubrication.inertia.small_eccentricity_forces, an ODE
solved by collocation), the thin-gap closed form, and the closed-form force of a
rigidly turning fluid.
"""

import math

import numpy as np
import pytest

from dynamics.apparatus import preset
from dynamics.equations import limits
from dynamics.equations.limits import (
    MAX_REYNOLDS,
    Limits,
    inertia_report,
    limit_message,
)
from lubrication.inertia import (
    inertial_error_estimate,
    small_eccentricity_forces,
    thin_gap_small_kappa,
)

from apparatus import ALUMINIUM, STEEL


def _columns(ap, t, kappa, phi_dot, omega_a, omega_b, kappa_dot=0.0):
    """SI columns of a run, as simulate() writes them, from arrays (broadcast)."""
    t, kappa, phi_dot, omega_a, omega_b, kappa_dot = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (t, kappa, phi_dot, omega_a, omega_b, kappa_dot)))
    return {"t": t, "kappa": kappa, "one_minus_kappa": 1.0 - kappa, "eps": kappa * ap.delta, "phi_dot": phi_dot,
            "omega_a": omega_a, "omega_b": omega_b, "kappa_dot": kappa_dot}


def test_default_limit_keeps_the_first_order_error_below_ten_percent():
    """At Re* = MAX_REYNOLDS the first-order error is at most 10% for every wall motion, in the thinnest
    tabulated gap (delta/a = 0.01) and in the thin-gap limit, where the closed form's largest G is 1/10."""
    angle = np.linspace(0.0, math.pi, 721)
    re_a, re_b = np.cos(angle), np.sin(angle)
    # Re* = d max(|Re_a|, |Re_b|) = MAX_REYNOLDS
    scale = MAX_REYNOLDS / (0.01 * np.maximum(np.abs(re_a), np.abs(re_b)))
    errors = inertial_error_estimate(np.zeros(angle.size), 0.01, scale * re_a, scale * re_b)
    assert errors.max() <= 0.1
    u_a, u_b = re_a, re_b  # thin gap: Re_a, Re_b are the wall speeds U_a, U_b in units nu/delta
    f_eps1, _ = thin_gap_small_kappa(u_a, u_b)
    _, f_chi_scale = thin_gap_small_kappa(np.abs(u_a), np.abs(u_b))
    g = np.abs(f_eps1) / f_chi_scale / np.maximum(np.abs(u_a), np.abs(u_b))  # per Re*, a = delta = 1
    assert g.max() == pytest.approx(0.1, rel=1e-6)
    assert MAX_REYNOLDS * g.max() <= 0.1 + 1e-12


def test_reynolds_message_quotes_the_estimate_at_the_event():
    """With the estimate at the event's state the message prints it; without, the bound Re*/10."""
    guard = Limits(max_gap_reynolds=2.0)
    with_error = limit_message("reynolds", guard, "t = 0.5 s", error=0.137)
    assert "max_gap_reynolds = 2 at t = 0.5 s" in with_error and "estimated 13.7%" in with_error
    bound = limit_message("reynolds", guard, "t = 0.5 s")
    assert "up to about 20% (Re*/10" in bound
    # forces with the first inertial correction: the message quotes what they leave, not the plain error
    corrected = limit_message("reynolds", guard, "t = 0.5 s", error=0.137, corrected=0.0021)
    assert "max_gap_reynolds = 2 at t = 0.5 s" in corrected
    assert "first inertial correction, which leaves at most an estimated 0.21% there" in corrected
    assert "quasi-steady Stokes forces by 13.7%" in corrected and "the model's assumption" not in corrected
    with pytest.raises(ValueError, match="not a limit event"):
        limit_message("touch", guard, "t = 0 s")


def test_report_error_against_the_exact_small_eccentricity_solution():
    """Near kappa = 0 the estimated error of a co-rotating state is G Re* with G from the exact ODE.

    kappa = 0.01 (the report's fade kappa^2/(kappa^2 + 1e-6) is 0.9999 there). The table's
    kappa = 0 node agrees with the ODE to 1e-5 (docs/inertia); between its nodes 0 and 0.1 the
    table interpolates linearly, and G (even in kappa, so flat at 0) falls by 1.8% from one
    node to the next: at kappa = 0.01 the interpolant is 0.18% low. Tolerance 3e-3.
    W_a a = W_b b (equal wall speeds, the direction of the largest G).
    """
    ap = ALUMINIUM
    d, b = ap.delta_over_a, 1.0 + ap.delta_over_a
    chi_dot, w = 40.0, 0.8  # frame rate and the inner wall's relative rate (rad/s)
    columns = _columns(ap, [0.0, 1.0], 0.01, chi_dot, chi_dot + w, chi_dot + w * ap.a / ap.b)
    report = inertia_report(ap, columns)
    re_star = w * ap.a * ap.delta**2 / (ap.nu * ap.a)
    assert report["max_reduced_reynolds"] == pytest.approx(re_star * 0.01**2 / (0.01**2 + 1e-6), rel=1e-12)
    # exact: d f_eps / d Re over the walls' Stokes f_chi, in units mu V (V = W_a a), per kappa
    w_a, w_b = 1.0, 1.0 / b
    f0 = small_eccentricity_forces(d, 0.0, w_a, w_b)
    f1 = small_eccentricity_forces(d, 1e-3, w_a, w_b)
    # each wall's Stokes f_chi at unit wall speed (U_a = W_a a = 1, U_b = W_b b = 1)
    scale = abs(small_eccentricity_forces(d, 0.0, 1.0, 0.0)[1]) + abs(small_eccentricity_forces(d, 0.0, 0.0, 1.0)[1])
    g_exact = (f1[0] - f0[0]) / 1e-3 / scale / d
    assert report["max_estimated_force_error"] == pytest.approx(g_exact * report["max_reduced_reynolds"], rel=3e-3)


def test_report_gives_the_error_at_the_worst_reynolds_number_and_the_worst_error_with_times():
    """Two states: the first has the larger Re* (co-rotating walls, kappa = 0.9, where G is small),
    the second the larger error (kappa = 0.2); counter-rotating walls keep it bounded (below Re*/10)
    where their Stokes f_chi cancels."""
    ap = ALUMINIUM
    per = ap.delta**2 / (ap.nu * ap.a)  # Re* per unit wall speed
    w1 = 2.0 / (per * ap.a)  # Re* = 2 from the inner wall
    w2 = 1.0 / (per * ap.a)  # Re* = 1
    # the second state's outer wall cancels the Stokes f_chi at first order: R_a W_a + R_b W_b = 0
    from lubrication.geometry import Annulus, Fluid, Motion
    from lubrication.registry import kernel_model

    annulus = Annulus.from_kappa(ap.a, ap.b, 0.2, length=ap.length)
    fluid = Fluid(nu=ap.nu, rho=ap.rho)
    r_a = kernel_model("stokes-exact").forces(annulus, Motion(omega_a=1.0), fluid).f_chi
    r_b = kernel_model("stokes-exact").forces(annulus, Motion(omega_b=1.0), fluid).f_chi
    w2_b = -r_a * w2 / r_b
    columns = _columns(ap, [0.1, 0.7], [0.9, 0.2], 10.0, [10.0 + w1, 10.0 + w2], [10.0 + w1, 10.0 + w2_b])
    report = inertia_report(ap, columns)
    errors = limits.estimated_force_error(ap, columns)
    assert report["t_at_max_reduced_reynolds"] == 0.1 and report["t_at_max_estimated_force_error"] == 0.7
    assert report["estimated_force_error_at_max_reduced_reynolds"] == errors[0]
    assert report["max_estimated_force_error"] == errors[1] > errors[0]
    re_star = limits.reduced_reynolds(ap, columns)
    assert np.all(errors <= re_star / 10.0)
    assert errors[1] > 0.01 * re_star[1]  # the inertial force does not cancel with f_chi


def test_report_of_corrected_forces_gives_what_the_correction_leaves():
    """With corrected=True the report adds the largest estimated error of the corrected forces
    (lubrication.inertia.corrected_error_estimate of each row's first-order error and Re*) and its
    time; the plain entries are unchanged, and a report without the correction has no such entry."""
    from lubrication.inertia import CORRECTED_MEASURED_TO, corrected_error_estimate

    ap = ALUMINIUM
    per = ap.delta**2 / (ap.nu * ap.a)
    walls = np.array([0.5, 3.0, 1.0]) / (per * ap.a)  # Re* = 0.5, 3, 1 from the inner wall
    columns = _columns(ap, [0.0, 0.2, 0.4], 0.5, 10.0, 10.0 + walls, 10.0)
    plain, corrected = inertia_report(ap, columns), inertia_report(ap, columns, corrected=True)
    assert "corrected_forces" not in plain
    left = corrected.pop("corrected_forces")
    assert corrected == plain
    expected = corrected_error_estimate(limits.estimated_force_error(ap, columns),
                                        limits.reduced_reynolds(ap, columns))
    assert left["max_estimated_force_error"] == expected.max() and left["t_at_max_estimated_force_error"] == 0.2
    assert left["measured_to_reduced_reynolds"] == CORRECTED_MEASURED_TO


def test_a_corrected_run_stopped_at_the_reynolds_limit_quotes_what_its_forces_leave():
    """simulate() with the inertia-corrected forces: the stop message and the report speak of those forces."""

    from dynamics import Initial, simulate
    from lubrication.registry import kernel_model

    ap = preset("aluminium", alpha=math.radians(5.0))
    for forces, corrected in ((kernel_model("stokes-exact"), False),
                              (kernel_model("stokes-exact", inertia="first-order", rho=ap.rho), True)):
        run = simulate(ap, Initial(0.5, 0.5), 0.2, forces=forces, limits=Limits(on_invalid="stop"))
        assert run.status == "stopped" and run.event == "reynolds"
        assert ("first inertial correction" in run.message) is corrected
        assert ("the model's assumption" in run.message) is not corrected
        assert ("corrected_forces" in run.info["inertia"]) is corrected


def test_frame_force_of_a_rigidly_turning_device():
    """Walls and line of centres turning together: the frame force is (m_eff - m'_a) eps chi'^2."""
    ap = STEEL
    columns = _columns(ap, [0.0, 1.0], [0.3, 0.8], [5.0, 30.0], [5.0, 30.0], [5.0, 30.0])
    expected = (ap.m_eff - ap.m_a_reduced) * columns["eps"] * columns["phi_dot"] ** 2 / (ap.m_a_reduced * ap.g)
    np.testing.assert_allclose(limits.frame_force_over_weight(ap, columns), expected, rtol=1e-12)
    report = inertia_report(ap, columns)
    assert report["max_frame_force_over_weight"] == pytest.approx(expected[1], rel=1e-12)
    assert report["t_at_max_frame_force"] == 1.0
    assert report["max_estimated_force_error"] == 0.0  # no relative flow, no error
