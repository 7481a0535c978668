"""The full dimensional model (2.1)-(2.4): its limits, its force models and its extremes."""

import math

import numpy as np
import pytest

from dynamics.apparatus import Apparatus, preset
from dynamics.equations import full
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.equations.special import inertial_time
from dynamics.simulation import Initial, simulate
from lubrication.registry import kernel_model

from apparatus import STEEL

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
    ref = _on_grid(simulate(ReducedParams(s, upsilon, mu), Initial(0.3, 0.5), 10.0, rtol=RTOL), names, t_tau)
    ratios = np.array([0.1, 0.03, 0.01, 0.003])
    diffs = []
    for r in ratios:
        apparatus = Apparatus.from_groups(s, upsilon, mu, r)
        # the comparison is of the equations: the inertial guard, a statement about the fluid, is lifted
        run = simulate(apparatus, Initial(0.3, 0.5), 10.0 * apparatus.tau, forces=kernel_model("closed-form"), rtol=RTOL,
                       limits=Limits(max_gap_reynolds=None))
        assert run.status == "completed"
        got = _on_grid(run, names, t_tau)
        diffs.append(max(np.max(np.abs(got[k] - ref[k])) for k in names))
    slope = np.polyfit(np.log(ratios), np.log(diffs), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.1)  # measured 0.996
    assert diffs[-1] < 0.01


def test_reynolds_forces_give_the_closed_form_trajectory():
    """The Reynolds solver's forces equal (2.5)-(2.7) to rounding, so swapping them changes the
    trajectory by no more than the integrator's own error (measured against rtol / 100)."""
    apparatus = STEEL
    t_end = 20.0
    t = np.linspace(0, t_end, 400)

    def sample(model, rtol):
        run = simulate(apparatus, Initial(0.5, 0.5), t_end, forces=model, rtol=rtol)
        return np.array([np.interp(t, run.columns["t"], run.columns[k]) for k in ("kappa", "phi", "x_b")])

    closed = sample(kernel_model("closed-form"), RTOL)
    integration_error = np.max(np.abs(closed - sample(kernel_model("closed-form"), RTOL / 100)), axis=1)
    swap = np.max(np.abs(closed - sample(kernel_model("reynolds", n=16), RTOL)), axis=1)
    assert np.all(swap <= 3 * integration_error + 1e-14)


def _sedimentation_deviation(apparatus, kappa0, t_from_tau=0.0):
    run = simulate(apparatus, Initial(kappa0, math.pi), 8 * apparatus.tau, forces=kernel_model("closed-form"), rtol=RTOL)
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
    # t_i = 0.55 tau here (delta/a = 0.41); measured deviation after 3 t_i: 0.0060
    assert _sedimentation_deviation(steel, 0.3, t_from_tau=3 * inertial_time(steel)) < 0.01


def test_starts_exactly_at_the_centre():
    apparatus = STEEL
    run = simulate(apparatus, Initial(0.0, 0.0), 10.0, forces=kernel_model("closed-form"))
    assert run.status == "completed" and run.equations == "full"
    for values in run.columns.values():
        assert np.all(np.isfinite(values))
    assert run.columns["kappa"][-1] > 0.5


def test_close_approach_to_contact_keeps_the_gap_precision():
    """1 - kappa is carried without cancellation to 1e-10 and below; the floor stops the run.

    On a level plane the gap closes as 1 - kappa ~ 1/(2 T^2) (3.3), with no rocking to resolve.
    """
    apparatus = preset("steel", alpha=0.0)
    run = simulate(apparatus, Initial(0.99, math.pi), 1e5 * apparatus.tau, forces=kernel_model("closed-form"),
                   limits=Limits(gap_floor=1e-10))
    omk = run.columns["one_minus_kappa"]
    assert run.status == "stopped" and run.event == "gap_floor"
    assert omk[-1] == pytest.approx(1e-10, rel=1e-6)
    assert np.all(np.isfinite(omk)) and np.all(omk > 0)


def _reduced_reynolds(apparatus, c, i):
    """Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a), W = Omega - phi', at row ``i`` of columns ``c``."""
    w_a, w_b = c["omega_a"][i] - c["phi_dot"][i], c["omega_b"][i] - c["phi_dot"][i]
    return max(abs(w_a) * apparatus.a, abs(w_b) * apparatus.b) * apparatus.delta**2 / (apparatus.nu * apparatus.a)


def test_a_runaway_runs_on_and_the_reynolds_guard_stops_at_its_limit():
    """s > 1: no rocking state, the cylinders run away, until the turn limit stops the run.

    The guard of quasi-steady Stokes flow is the Reynolds number of the flow relative to the
    line of centres, Re*: it peaks (2.5) in the first swing and falls as the pair co-rotates
    (0.04 after 10 turns), so the runaway itself does not end the Stokes regime. A tighter
    guard, max_gap_reynolds = 1 (a 10% force error), stops the same release in its first
    swing with Re* = 1 at the last row (to 1e-5: the event fades Re* out near kappa = 0 by
    kappa^2 / (kappa^2 + 1e-6)).
    """
    apparatus = preset("aluminium", alpha=math.radians(12.0))
    assert apparatus.s > 1  # no rocking state exists: it must run away
    run = simulate(apparatus, Initial(0.5, 0.5), 100.0, forces=kernel_model("closed-form"),
                   limits=Limits(max_turns=10, max_gap_reynolds=None))
    assert run.status == "stopped" and run.event == "runaway" and run.rows[-1] == "event:runaway+end"
    assert "turned max_turns = 10 times" in run.message
    assert run.columns["x_b"][-1] == pytest.approx(20.0 * math.pi * apparatus.b, rel=1e-12)
    assert run.columns["omega_b"][-1] * apparatus.tau > 10.0
    guarded = simulate(apparatus, Initial(0.5, 0.5), 100.0, forces=kernel_model("closed-form"),
                       limits=Limits(max_gap_reynolds=1.0))
    assert guarded.status == "stopped" and guarded.event == "reynolds"
    assert "Reynolds number Re* reached max_gap_reynolds = 1 at" in guarded.message
    assert guarded.t[-1] < run.t[-1] / 5
    assert _reduced_reynolds(apparatus, guarded.columns, -1) == pytest.approx(1.0, rel=1e-5)


@pytest.mark.parametrize(("frame_terms", "omega_a", "omega_b"), [("paper", 0.3, 0.2), ("quasi-steady", 0.0, 0.0)])
def test_rhs_is_regular_through_the_centre(frame_terms, omega_a, omega_b):
    """The right-hand side is continuous at eps = 0 for any direction of approach: (2.1)-(2.2) as
    printed at any wall rates; with the quasi-steady frame terms where the walls stand still. Their
    frame rate is chi' capped in size at max(|Omega_a|, |Omega_b|) (full.frame_force), and chi' =
    (e_chi . r')/eps runs to +-infinity at the centre with the direction of approach: with turning walls
    the Coriolis force there is that of the one or the other cap (tests/test_frame_terms.py)."""
    apparatus = STEEL
    model = kernel_model("closed-form")
    args = full.run_args(apparatus, model, gap_floor=1e-9, frame_terms=frame_terms)
    rhs = full.model_functions(model).rhs
    v = np.array([1e-4, -2e-4])
    at_centre = rhs(0.0, np.array([0.0, 0.0, *v, omega_a, omega_b, 0.0]), args)
    for angle in np.linspace(0, 2 * math.pi, 7):
        tiny = 1e-9 * np.array([math.sin(angle), math.cos(angle)])
        near = rhs(0.0, np.array([*tiny, *v, omega_a, omega_b, 0.0]), args)
        np.testing.assert_allclose(near[2:], at_centre[2:], rtol=1e-6, atol=1e-9 * np.abs(at_centre).max())


def _richardson_columns(fun, y, args, steps):
    """d(fun)/dy column by column: central differences at h and h/2 combined to O(h^4), from Python."""
    jac = np.empty((y.size, y.size))
    for j, h in enumerate(steps):
        def central(step, j=j):
            e = np.zeros(y.size)
            e[j] = step
            return (fun(0.0, y + e, args) - fun(0.0, y - e, args)) / (2.0 * step)
        jac[:, j] = (4.0 * central(h / 2.0) - central(h)) / 3.0
    return jac


@pytest.mark.parametrize("frame_terms", full.FRAME_TERMS)
@pytest.mark.parametrize(("polar", "kappa"), [(False, 0.8), (True, 0.95)])
def test_jacobian_is_the_derivative_of_the_right_hand_side(polar, kappa, frame_terms):
    """Every column against Richardson-extrapolated differences of the right-hand side taken here, with
    steps 1e-3 of each variable's scale (truncation O(h^4) ~ 1e-12, rounding ~ 1e-13/h ~ 1e-10 relative):
    the X_b column, which the Jacobian does not evaluate, must come out zero here too. chi' = 0.02/s lies
    between the wall rates, and farther from either than the steps move it (about 0.05/s): the quasi-steady
    frame rate, chi' clipped to the wall rates, has a kink where chi' meets one."""
    apparatus = STEEL
    model = kernel_model("closed-form")
    args = full.run_args(apparatus, model, gap_floor=1e-9, frame_terms=frame_terms)
    functions = full.model_functions(model)
    y = full.initial_state(apparatus, kappa, 0.4, 0.01, 0.02, 0.3, -0.2)
    fun, jacobian = functions.rhs, functions.jacobian
    if polar:
        y, fun, jacobian = full.to_polar(apparatus, y), functions.polar_rhs, functions.polar_jacobian
    steps = 1e-3 * np.maximum(np.abs(y), full.typical_scales(apparatus))
    reference = _richardson_columns(fun, y, args, steps)
    jac = jacobian(0.0, y, args)
    assert np.all(reference[:, 6] == 0.0) and np.all(jac[:, 6] == 0.0)
    np.testing.assert_allclose(jac, reference, rtol=1e-6, atol=1e-8 * np.abs(reference).max())


@pytest.mark.parametrize("one_minus_kappa", [0.3, 1e-3, 1e-6])
def test_polar_velocity_carries_the_same_motion(rng, one_minus_kappa):
    """Near contact a free run carries the velocity in the frame of the line of centres (q_r = d|u|/dt,
    q_t = |u| chi'). Independent check of polar_rhs: the Cartesian flow of rhs, mapped by to_polar, has
    the time derivative polar_rhs gives, to the O(h^2) of a central difference along the flow (1e-7
    relative here; at 1 - kappa = 1e-9 the difference itself loses the digits); to_cartesian undoes to_polar
    to rounding."""
    apparatus = STEEL
    model = kernel_model("closed-form")
    args = full.run_args(apparatus, model, gap_floor=1e-12)
    functions = full.model_functions(model)
    kappa = 1.0 - one_minus_kappa
    for _ in range(5):
        phi, kappa_dot, phi_dot, omega_a, omega_b = rng.uniform(-3.0, 3.0, 5)
        y = full.initial_state(apparatus, kappa, phi, kappa_dot * one_minus_kappa**1.5, phi_dot, omega_a,
                               omega_b, one_minus_kappa=one_minus_kappa)
        polar = full.to_polar(apparatus, y)
        np.testing.assert_allclose(full.to_cartesian(apparatus, polar), y, rtol=1e-13, atol=1e-300)
        flow = functions.rhs(0.0, y, args)
        h = 1e-6 * one_minus_kappa * apparatus.tau
        along = (full.to_polar(apparatus, y + h * flow) - full.to_polar(apparatus, y - h * flow)) / (2.0 * h)
        np.testing.assert_allclose(functions.polar_rhs(0.0, polar, args), along, rtol=1e-6,
                                   atol=1e-9 * np.max(np.abs(along)))
