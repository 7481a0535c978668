"""Table 3 re-inferred: the inverse solve on the steady speed, its bracket, its input, the full model's states."""

import math
from functools import partial

import numpy as np
import pytest

from dynamics.apparatus import Apparatus
from dynamics.contact.full import friction_coefficient
from dynamics.contact.reduced import ContactParams
from lubrication.registry import kernel_model
from validation import table3

STEEL = table3.the_apparatus()  # steel, 500 cSt, 2.4 degrees


def test_paper_ratios_are_about_four_by_the_criterion():
    """The paper's own Table 3 (0.3/0.07 ... 1.6/0.36 = 4.17-5.00) must count as 'about four'."""
    ratios = [table3.SANDPAPER[g] / d for g, d in table3.PARTICLE_SIZE.items()]
    assert min(ratios) == pytest.approx(0.5 / 0.12) and max(ratios) == pytest.approx(1.0 / 0.2)
    assert all(abs(r / table3.PAPER_RATIO - 1.0) <= table3.ABOUT for r in ratios)


@pytest.mark.parametrize("sigma", [5e-5, 3e-4, 1.6e-3])
def test_inverse_of_the_locked_speed_law_in_closed_form(sigma):
    """(6.1) on its locked branch, V = V* sin(alpha) zeta*/2, inverted by hand through (6.3).

    zeta* = 2 V/(V* sin alpha), and sigma/delta = 1 - kappa* = zeta*^2/(1 + sqrt(1 - zeta*^2))
    (no cancellation). brentq stops within ROOT_RTOL = 1e-13 of sigma.
    """
    v = table3.paper_speed(STEEL, sigma)
    zeta = 2.0 * v / (STEEL.v_star * math.sin(STEEL.alpha))
    by_hand = STEEL.delta * zeta**2 / (1.0 + math.sqrt(1.0 - zeta**2))
    assert by_hand == pytest.approx(sigma, rel=1e-13)  # the locked branch is the one in play at 2.4 degrees
    found = table3.infer_sigma(partial(table3.paper_speed, STEEL), v, 0.37 * sigma, table3.sigma_bounds(STEEL))
    assert found == pytest.approx(by_hand, rel=1e-12)


@pytest.mark.parametrize(("sigma", "phase"), [(1e-4, "locked"), (1.6e-3, "sliding")])
def test_forward_then_inverse_recovers_sigma_with_the_full_model(sigma, phase):
    """The full model's own speed at a known sigma, on either branch, gives that sigma back.

    Newton leaves the rates within 1e-12, brentq sigma within 1e-13; over the
    elasticity d ln V/d ln sigma >= 0.5 that is about 2e-12.
    """
    forces = kernel_model("stokes-exact")
    assert table3.full_steady_state(STEEL, forces, sigma).phase == phase
    speed = partial(table3.full_speed, STEEL, forces)
    found = table3.infer_sigma(speed, speed(sigma), 0.5 * sigma, table3.sigma_bounds(STEEL))
    assert found == pytest.approx(sigma, rel=1e-11)


def test_full_model_tends_to_the_reduced_inverse_at_first_order_in_delta_over_a():
    """sigma inferred with the full model (closed forms, and exact Stokes) from section 5's own speed.

    The full model's steady states approach (5.6), (5.10) at O(delta/a)
    (dynamics.contact.full), so the sigma it infers from a speed of the reduced
    fixed point approaches that fixed point's sigma as c delta/a: the log-log
    slope over delta/a = 1e-2 ... 1e-3 is 1 (measured 0.978 for the closed forms).
    """
    ratios = (1e-2, 3e-3, 1e-3)
    errors = {"closed-form": [], "stokes-exact": []}
    for ratio in ratios:
        ap = Apparatus.from_groups(s=0.25, upsilon=1.0, mu_ratio=1.5, delta_over_a=ratio)
        sigma = 0.1 * ap.delta
        v = table3.reduced_speed(ap, sigma, psi=0.5)  # psi = 0.5 locks both models
        for name, forces in (("closed-form", kernel_model("closed-form")), ("stokes-exact", kernel_model("stokes-exact"))):
            found = table3.infer_sigma(partial(table3.full_speed, ap, forces, psi=0.5), v, sigma,
                                       table3.sigma_bounds(ap))
            errors[name].append(abs(found / sigma - 1.0))
    for name, errs in errors.items():
        slope = np.polyfit(np.log(ratios), np.log(errs), 1)[0]
        assert slope == pytest.approx(1.0, abs=0.05), name
        assert errs[-1] < 5.0 * ratios[-1], name


def test_locked_speed_is_proportional_to_sin_alpha_and_sliding_breaks_it():
    """Locked, (2.4) ties sin(phi) to sin(alpha) and (2.1), (2.3) are linear in the rates: V/sin(alpha) is fixed.

    Sliding, the friction bound tan(psi_hat) N brings in cos(phi): the ratio moves.
    """
    forces = kernel_model("stokes-exact")

    def per_sin(slope, sigma):
        ap = table3.the_apparatus(slope)
        state = table3.full_steady_state(ap, forces, sigma)
        return state.phase, state.speed / math.sin(ap.alpha)

    low, mid = per_sin(1.5, 3e-4), per_sin(2.4, 3e-4)
    assert low[0] == mid[0] == "locked"
    assert low[1] == pytest.approx(mid[1], rel=1e-11)
    slid, locked = per_sin(2.8, 1.2e-3), per_sin(2.4, 1.2e-3)
    assert (slid[0], locked[0]) == ("sliding", "locked")
    assert slid[1] > 1.01 * locked[1]  # sliding lets the outer cylinder run ahead (section 6.2)


def test_sliding_state_sits_on_the_friction_cone_against_its_slip():
    """Sliding: |F| = tan(psi_hat) N, F opposing the slip a Omega_a - (a + eps*) Omega_b; locked: inside the cone."""
    forces = kernel_model("stokes-exact")
    contact = ContactParams(1.0 - 1.6e-3 / STEEL.delta, table3.PSI_EXPERIMENT)
    mu_f = friction_coefficient(STEEL, contact)
    slide = table3.full_steady_state(STEEL, forces, 1.6e-3)
    slip = STEEL.a * slide.omega_a - (STEEL.a + contact.kappa_star * STEEL.delta) * slide.omega_b
    assert slide.phase == "sliding" and slide.normal > 0.0
    assert abs(slide.friction) == pytest.approx(mu_f * slide.normal, rel=1e-12)
    assert math.copysign(1.0, slide.friction) == -math.copysign(1.0, slip)
    lock = table3.full_steady_state(STEEL, forces, 3e-4)
    assert lock.phase == "locked" and abs(lock.friction) < mu_f * lock.normal


def _square(sigma):
    return sigma * sigma


@pytest.mark.parametrize("guess", [1e-4, 3e-3, 0.1])
def test_bracket_holds_the_root_one_step_wide_inside_the_bounds(guess):
    """speed = sigma^2 has the root sqrt(v); the bracket is one growth step wide and never leaves the bounds."""
    bounds = (1e-5, 0.2)
    lo, hi = table3.bracket_sigma(_square, 1e-6, guess, bounds, factor=2.0)
    assert bounds[0] <= lo <= 1e-3 <= hi <= bounds[1]
    assert hi / lo <= 2.0 * (1.0 + 1e-15)
    assert table3.infer_sigma(_square, 1e-6, guess, bounds) == pytest.approx(1e-3, rel=1e-13)


def test_bracket_clipped_by_a_bound():
    lo, hi = table3.bracket_sigma(_square, 1e-6, 0.9e-3, (1e-5, 1.2e-3), factor=2.0)
    assert (lo, hi) == (0.9e-3, 1.2e-3)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"v_target": 0.0}, "v_target must be in"),
    ({"v_target": math.nan}, "v_target"),
    ({"v_target": 1.0}, r"v_target must be in \(V\(low\), V\(high\)\)"),  # beyond speed(high) = 0.04
    ({"v_target": 1e-12}, r"v_target must be in \(V\(low\), V\(high\)\)"),  # below speed(low) = 1e-10
    ({"sigma_guess": 0.5}, "sigma_guess must be in"),
    ({"bounds": (0.2, 1e-5)}, "bounds must satisfy"),
    ({"bounds": (0.0, 0.2)}, "bounds must satisfy"),
    ({"factor": 1.0}, "factor must be in"),
])
def test_bad_input_names_the_parameter(kwargs, match):
    args = {"v_target": 1e-6, "sigma_guess": 1e-3, "bounds": (1e-5, 0.2), "factor": 1.5, **kwargs}
    with pytest.raises(ValueError, match=match):
        table3.bracket_sigma(_square, **args)


@pytest.mark.parametrize("sigma", [0.0, -1e-4, STEEL.delta, math.inf])
def test_bad_sigma_for_the_models(sigma):
    for speed in (table3.paper_speed, table3.reduced_speed, partial(table3.full_speed, forces=kernel_model("stokes-exact"))):
        with pytest.raises(ValueError, match="sigma must be"):
            speed(STEEL, sigma=sigma)


def test_bad_slope():
    with pytest.raises(ValueError, match="slope_deg must be in"):
        table3.the_apparatus(0.0)


def test_open_ends_carry_the_apparatus_length():
    """Table 2: L = 10.35 cm, a = 0.8 cm."""
    models = table3.force_models(STEEL)
    assert list(models) == list(table3.MODELS)
    assert models["stokes-exact"].length_table is None
    assert models["stokes-exact/open-ends"].length_table[0] == pytest.approx(10.35 / 0.8, rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("grade", ["smooth", "50"])
def test_trajectory_settles_at_the_target_speed(grade):
    """Released at rest on the asperities at the bottom at the re-inferred sigma: it rolls at V_(6.1)(sigma paper)."""
    forces = table3.force_models(STEEL)["stokes-exact/open-ends"]
    v_target = table3.paper_speed(STEEL, table3.SANDPAPER[grade])
    sigma = table3.infer_sigma(partial(table3.full_speed, STEEL, forces), v_target, table3.SANDPAPER[grade],
                               table3.sigma_bounds(STEEL))
    run = table3.trajectory_run(STEEL, forces, sigma)
    assert run["status"] == "completed" and run["phase"] == run["fixed_phase"]
    assert run["speed"] == pytest.approx(v_target, rel=table3.TRAJECTORY_TOLERANCE)


@pytest.mark.parametrize("sigma", [5e-5, 3e-4, 1.6e-3])
def test_the_elasticity_is_that_of_the_paper_law_where_it_is_known(sigma):
    """d ln V / d ln sigma, which docs/table3 reports and which sizes the recovery tolerance, against the paper's
    locked law V = V* sin(alpha) zeta*/2 (6.1), where zeta*^2 = s (2 - s) with s = sigma/delta gives it in
    closed form: d ln V / d ln sigma = (1 - s)/(2 - s). The central difference of table3 errs by O(h^2) = 1e-8."""
    s_ratio = sigma / STEEL.delta
    locked = partial(table3.paper_speed, STEEL, psi=0.5 * math.pi - 1e-9)  # locked whatever the slope
    assert table3._elasticity(locked, sigma) == pytest.approx((1.0 - s_ratio) / (2.0 - s_ratio), rel=1e-7)
