"""The full dimensional model (2.1)-(2.4): its limits, its force models and its extremes."""

import math

import numpy as np
import pytest

from dynamics.apparatus import Apparatus, preset
from dynamics.equations import full
from dynamics.equations.forces import closed_form, reynolds
from dynamics.equations.reduced import ReducedParams
from dynamics.simulate import Initial, simulate_full, simulate_reduced
from validation.dynamics_checks import inertial_time

RTOL = 1e-10


def _on_grid(trajectory, names, t_tau):
    c = trajectory.columns
    return {k: np.interp(t_tau, c["t_tau"], c[k] * (trajectory.tau if k.startswith("omega") else 1.0))
            for k in names}


def test_approaches_the_reduced_model_at_first_order_in_delta_over_a():
    """At fixed (s, Upsilon, mu_) the full model differs from (2.11) by O(delta/a).

    The neglected terms are the inner cylinder's inertia relative to the
    lubrication force and the O(delta/a) slope (sin alpha ~ s delta/a): the
    difference over a fixed window must fall with slope 1 in log-log.
    """
    s, upsilon, mu = 0.5, 1.0, 2.0
    t_tau = np.linspace(0.0, 10.0, 401)
    names = ("kappa", "phi", "omega_a", "omega_b")
    ref = _on_grid(simulate_reduced(ReducedParams(s, upsilon, mu), Initial(0.3, 0.5), 10.0, rtol=RTOL),
                   names, t_tau)
    ratios = np.array([0.1, 0.03, 0.01, 0.003])
    diffs = []
    for r in ratios:
        apparatus = Apparatus.from_groups(s, upsilon, mu, r)
        run = simulate_full(apparatus, closed_form(), Initial(0.3, 0.5), 10.0 * apparatus.tau, rtol=RTOL)
        assert run.status == "completed"
        got = _on_grid(run, names, t_tau)
        diffs.append(max(np.max(np.abs(got[k] - ref[k])) for k in names))
    slope = np.polyfit(np.log(ratios), np.log(diffs), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.1)  # measured 0.996
    assert diffs[-1] < 0.01


def test_reynolds_forces_give_the_closed_form_trajectory():
    """The Reynolds solver's forces equal (2.5)-(2.7) to rounding, so swapping them changes the
    trajectory by no more than the integrator's own error (measured against rtol / 100)."""
    apparatus = preset("steel")
    t_end = 20.0
    t = np.linspace(0, t_end, 400)

    def sample(model, rtol):
        run = simulate_full(apparatus, model, Initial(0.5, 0.5), t_end, rtol=rtol)
        return np.array([np.interp(t, run.columns["t"], run.columns[k]) for k in ("kappa", "phi", "x_b")])

    closed = sample(closed_form(), RTOL)
    integration_error = np.max(np.abs(closed - sample(closed_form(), RTOL / 100)), axis=1)
    swap = np.max(np.abs(closed - sample(reynolds(n=16), RTOL)), axis=1)
    assert np.all(swap <= 3 * integration_error + 1e-14)


def _sedimentation_deviation(apparatus, kappa0, t_from_tau=0.0):
    run = simulate_full(apparatus, closed_form(), Initial(kappa0, math.pi), 8 * apparatus.tau, rtol=RTOL)
    t = run.columns["t_tau"]
    big_t = t + kappa0 / math.sqrt(1 - kappa0**2)
    late = t >= t_from_tau
    assert np.max(np.abs(run.columns["phi"] - math.pi)) == 0.0  # straight down, no swing
    return np.max(np.abs(run.columns["kappa"][late] - big_t[late] / np.sqrt(1 + big_t[late] ** 2)))


@pytest.mark.parametrize("ratio", [0.03, 0.01, 0.003])
def test_level_plane_sediments_as_3_3_up_to_the_inertial_lag(ratio):
    """alpha = 0, from rest: kappa(t) = T/sqrt(1 + T^2), T = t/tau + kappa0/zeta0 (3.3), with the
    full model lagging by about the inertial time: measured deviation 0.74-0.75 t_i/tau."""
    apparatus = Apparatus.from_groups(0.0, 1.0, 2.0, ratio)
    deviation = _sedimentation_deviation(apparatus, 0.3)
    assert 0.5 * inertial_time(apparatus) < deviation < inertial_time(apparatus)


def test_steel_apparatus_on_a_level_plane_sediments_as_3_3_after_its_inertial_time():
    steel = preset("steel", alpha=0.0)
    # t_i = 0.55 tau here (delta/a = 0.41); measured deviation after 3 t_i: 0.0058
    assert _sedimentation_deviation(steel, 0.3, t_from_tau=3 * inertial_time(steel)) < 0.01


def test_starts_exactly_at_the_centre():
    apparatus = preset("steel")
    run = simulate_full(apparatus, closed_form(), Initial(0.0, 0.0), 10.0)
    assert run.status == "completed"
    for values in run.columns.values():
        assert np.all(np.isfinite(values))
    assert run.columns["kappa"][-1] > 0.5


def test_close_approach_to_contact_keeps_the_gap_precision():
    """1 - kappa is carried without cancellation to 1e-10 and below; the floor stops the run.

    On a level plane the gap closes as 1 - kappa ~ 1/(2 T^2) (3.3), with no rocking to resolve.
    """
    apparatus = preset("steel", alpha=0.0)
    run = simulate_full(apparatus, closed_form(), Initial(0.99, math.pi), 1e5 * apparatus.tau,
                        gap_floor=1e-10)
    omk = run.columns["one_minus_kappa"]
    assert run.status == "stopped" and run.event == "gap_floor"
    assert omk[-1] == pytest.approx(1e-10, rel=1e-6)
    assert np.all(np.isfinite(omk)) and np.all(omk > 0)


def test_runaway_stops_where_stokes_flow_ends():
    apparatus = preset("aluminium", alpha=math.radians(12.0))
    assert apparatus.s > 1  # no rocking state exists: it must run away
    run = simulate_full(apparatus, closed_form(), Initial(0.5, 0.5), 100.0)
    assert run.status == "stopped" and run.event == "reynolds"
    assert "Reynolds number" in run.reason


def test_rhs_is_regular_through_the_centre():
    """The right-hand side is continuous at eps = 0 for any direction of approach."""
    apparatus = preset("steel")
    p = full.params_array(apparatus)
    model = full.model_arguments(closed_form())
    v = np.array([1e-4, -2e-4])
    at_centre = full.rhs(0.0, np.array([0.0, 0.0, *v, 0.3, 0.2, 0.0]), p, *model)
    for angle in np.linspace(0, 2 * math.pi, 7):
        tiny = 1e-9 * np.array([math.sin(angle), math.cos(angle)])
        near = full.rhs(0.0, np.array([*tiny, *v, 0.3, 0.2, 0.0]), p, *model)
        np.testing.assert_allclose(near[2:], at_centre[2:], rtol=1e-6, atol=1e-9 * np.abs(at_centre).max())


def test_jacobian_matches_a_finer_difference():
    apparatus = preset("steel")
    p = full.params_array(apparatus)
    model = full.model_arguments(closed_form())
    typical = full.typical_scales(apparatus)
    y = full.initial_state(apparatus, 0.8, 0.4, 0.01, 0.02, 0.1, 0.05)
    jac = full.jacobian(0.0, y, p, *model, typical)
    finer = full.jacobian(0.0, y, p, *model, typical * 1e-2)
    np.testing.assert_allclose(jac, finer, rtol=1e-6, atol=1e-9 * np.abs(jac).max())
