"""Rough surfaces (dynamics.contact.roughness) and contact on a moving constraint (dynamics.contact.rough)."""

import functools
import math
import re

import numpy as np
import pytest

from dynamics.contact.reduced import (
    FREE,
    LOCKED,
    SLIDING,
    ContactParams,
    locked_rhs,
    phase_args,
    simulate_contact,
    sliding_rhs,
)
from dynamics.contact.rough import (
    _free_jacobian,
    contact_state,
    free_rhs,
    normal_reaction,
    rolling_statistics,
    simulate_rough_contact,
    speed_table,
    speed_table_markdown,
)
from dynamics.contact.roughness import (
    CLIP_FLOOR,
    CLIP_KNEE,
    RoughContact,
    SurfaceHeights,
    soft_floor,
)
from dynamics.contact.steady import steady_state
from dynamics.equations.reduced import ReducedParams, reduced_rhs

FIG7 = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)  # figures 7 and 8: Upsilon = mu_ = 1, s = 1/4
KAPPA_STAR = 0.98  # figures 7 and 8
RELEASE = (0.5, 0.3)  # (kappa0, phi0) of figure 2, at rest
CORRELATION = 0.3  # rad on both surfaces: a distance 0.3 b rolled


def _rough(amplitude, psi, seed=0, kappa_star=KAPPA_STAR, correlation=CORRELATION):
    return RoughContact.from_seed(ContactParams(kappa_star, psi), amplitude, correlation, correlation, seed)


@functools.cache
def _run(amplitude, psi, seed, t_end, rtol=1e-8):
    """A cached rough run from figure 2's release (several tests read the same runs)."""
    return simulate_rough_contact(FIG7, _rough(amplitude, psi, seed), t_end, *RELEASE, rtol=rtol,
                                  atol=rtol * 1e-2, max_turns=1e6)


# -- the field -------------------------------------------------------------------------

def test_soft_floor_is_the_identity_above_the_knee_and_c2_at_it():
    x = np.array([CLIP_KNEE, 0.5, 1.0, 7.0])
    value, slope = soft_floor(x, CLIP_FLOOR, CLIP_KNEE)
    assert np.array_equal(value, x) and np.all(slope == 1.0)
    # Below: monotone, above the floor; value, slope and curvature continuous at the knee.
    below = np.linspace(-50.0, CLIP_KNEE, 2001)
    value, slope = soft_floor(below, CLIP_FLOOR, CLIP_KNEE)
    assert np.all(value > CLIP_FLOOR) and np.all(np.diff(value) > 0.0) and np.all(slope > 0.0)
    h = 1e-4
    left = soft_floor(CLIP_KNEE - h, CLIP_FLOOR, CLIP_KNEE)
    # 1/(1 + v + v^2) = 1 - v + v^3 + ..., v = h/(knee - floor) = 1e-3: value error
    # (knee - floor) v^3 = 1e-10 (no v^2 term: curvature 0), slope 1 - 3 v^2.
    assert left[0] == pytest.approx(CLIP_KNEE - h, abs=1.1e-10)
    assert left[1] == pytest.approx(1.0 - 3e-6, abs=1e-8)


@pytest.mark.parametrize("amplitude", [0.0, 0.3, 0.9])
@pytest.mark.parametrize("kappa_star", [0.3, 0.98, 0.999999])
def test_compiled_local_gap_matches_its_numpy_twin(amplitude, kappa_star, rng):
    rough = _rough(amplitude, 0.1, seed=7, kappa_star=kappa_star)
    theta_a, theta_b = rng.uniform(-40.0, 40.0, (2, 50))
    vectorised = rough.local(theta_a, theta_b)
    for i in range(theta_a.size):
        scalar = rough.local_at(theta_a[i], theta_b[i])
        np.testing.assert_allclose(scalar, [v[i] for v in vectorised], rtol=1e-12, atol=1e-14)


def test_slopes_are_derivatives_and_kappa_stays_inside(rng):
    """d kappa*/d theta against central differences; kappa* in (kappa*/10, 1 - sigma/10) (clip rule)."""
    rough = _rough(0.9, 0.1, seed=3, kappa_star=0.6)
    theta_a, theta_b = rng.uniform(0.0, 2.0 * math.pi, (2, 200))
    here = rough.local(theta_a, theta_b)
    h = 1e-6
    da = (rough.local(theta_a + h, theta_b).kappa - rough.local(theta_a - h, theta_b).kappa) / (2.0 * h)
    db = (rough.local(theta_a, theta_b + h).kappa - rough.local(theta_a, theta_b - h).kappa) / (2.0 * h)
    np.testing.assert_allclose(here.dkappa_a, da, atol=1e-7)
    np.testing.assert_allclose(here.dkappa_b, db, atol=1e-7)
    grid = np.linspace(0.0, 2.0 * math.pi, 200)
    everywhere = rough.local(*np.meshgrid(grid, grid))
    assert everywhere.kappa.min() > 0.1 * 0.6 and everywhere.one_minus_kappa.min() > 0.1 * 0.4
    assert np.allclose(everywhere.kappa + everywhere.one_minus_kappa, 1.0, rtol=0.0, atol=1e-15)
    # At this amplitude and kappa*_mean = 0.6, both floors are reached somewhere on the torus.
    x = rough.gap_ratio(*np.meshgrid(grid, grid))[0]
    assert x.min() < CLIP_KNEE and (1.0 - 0.4 * x).min() < CLIP_KNEE * 0.6


@pytest.mark.parametrize("correlation", [0.05, 0.3, 2.0])
def test_each_surface_has_zero_mean_and_unit_mean_square(correlation):
    """Exactly (to rounding): the scaling is by the series' own Parseval mean square."""
    surface = SurfaceHeights.from_rng(correlation, np.random.default_rng(11))
    theta = np.linspace(0.0, 2.0 * math.pi, 8 * surface.modes + 64, endpoint=False)  # exact quadrature
    f, _ = surface(theta)
    assert abs(f.mean()) < 1e-14 and np.mean(f * f) == pytest.approx(1.0, rel=1e-13)
    rough = _rough(0.4, 0.1, correlation=max(correlation, 0.3))  # <= 40 modes: an exact 128^2 torus grid
    torus = np.linspace(0.0, 2.0 * math.pi, 128, endpoint=False)
    sa, sb = np.meshgrid(torus, torus)
    x, _, _ = rough.gap_ratio(sa, sb)  # sigma/sigma_mean on the torus
    assert x.mean() == pytest.approx(1.0, abs=1e-13) and x.std() == pytest.approx(0.4, rel=1e-12)


def test_correlation_length_measured_over_many_surfaces():
    """The sample correlation, averaged over 200 surfaces, is the Gaussian of length lambda.

    Measured by FFT on 1024 points, lambda = 0.1. Against the exact
    correlation of the series: a deviation below 0.03 (measured 0.009). The average has a
    standard error of about sqrt(2 lambda/sqrt(pi))/sqrt(200) ~ 0.02, and
    scaling each surface to unit mean square adds a bias of O(1/K). The
    e^-1/2 crossing is where the series puts it, to 2% (measured 1.2%). That
    crossing is not lambda itself: dropping the k = 0 mode lowers the Gaussian
    by c = lambda/sqrt(2 pi) and rescales it by 1/(1 - c), which moves the
    crossing to lambda sqrt(-2 ln(c + (1 - c) e^-1/2)) = 0.974 lambda here.
    The measured crossing is lambda to 5% (measured 3.7%).
    """
    lam, n, surfaces = 0.1, 1024, 200
    theta = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    sums = np.zeros(n)
    for seed in range(surfaces):
        f, _ = SurfaceHeights.from_rng(lam, np.random.default_rng(seed))(theta)
        spectrum = np.fft.rfft(f)
        sums += np.fft.irfft(spectrum * spectrum.conj(), n) / n
    measured = sums / surfaces
    near = slice(0, n // 8)
    exact = SurfaceHeights.from_rng(lam, np.random.default_rng(0)).correlation_function(theta[near])
    assert measured[0] == pytest.approx(1.0, rel=1e-12)
    assert np.max(np.abs(measured[near] - exact)) < 0.03

    def crossing(c):
        i = np.flatnonzero(c < math.exp(-0.5))[0]
        return np.interp(math.exp(-0.5), c[[i, i - 1]], theta[[i, i - 1]])

    c = lam / math.sqrt(2.0 * math.pi)
    shifted = lam * math.sqrt(-2.0 * math.log(c + (1.0 - c) * math.exp(-0.5)))
    assert crossing(exact) == pytest.approx(shifted, rel=2e-3)  # the grid step is 0.006 = 6% of lambda
    assert crossing(measured[near]) == pytest.approx(shifted, rel=0.02)
    assert crossing(measured[near]) == pytest.approx(lam, rel=0.05)


def test_a_seed_gives_the_same_surfaces_and_another_seed_others():
    one, again, other = _rough(0.5, 0.1, seed=5), _rough(0.5, 0.1, seed=5), _rough(0.5, 0.1, seed=6)
    for name in ("inner", "outer"):
        assert np.array_equal(getattr(one, name).cos_coefficients, getattr(again, name).cos_coefficients)
        assert not np.array_equal(getattr(one, name).cos_coefficients, getattr(other, name).cos_coefficients)
    assert not np.array_equal(one.inner.cos_coefficients, one.outer.cos_coefficients)  # independent surfaces


def test_rolled_length_is_an_angle_on_each_surface():
    mean = ContactParams(KAPPA_STAR, 0.1)
    rough = RoughContact.from_rolled_length(mean, 0.5, 0.001, 0.008, 0.01125, seed=2)
    assert rough.inner.correlation == pytest.approx(0.001 / 0.008) and rough.outer.correlation == pytest.approx(
        0.001 / 0.01125)


# -- the contact equations on the moving constraint ----------------------------------------

SLIDING_STATES = [(2.5, 0.07, 0.15, 3.0, 1.0), (4.0, 0.3, -0.25, -1.0, 7.0), (3.3, -0.03, 0.1, 0.0, -2.0)]


@pytest.mark.parametrize("y", SLIDING_STATES)
@pytest.mark.parametrize("sigma", [1.0, -1.0, 0.0])
def test_amplitude_zero_gives_the_uniform_phases_bit_for_bit(y, sigma):
    rough = _rough(0.0, 0.3)
    contact = rough.mean
    y = np.array(y)
    sliding = contact_state(SLIDING, sigma, y, FIG7, rough)
    assert np.array_equal(sliding.rates[:4], sliding_rhs(0.0, y[:4], phase_args(FIG7, contact, sigma)))
    assert sliding.c_eps == -math.cos(y[0]) and sliding.local.kappa == KAPPA_STAR
    locked = contact_state(LOCKED, 0.0, y[[0, 1, 3, 4]], FIG7, rough)
    assert np.array_equal(locked.rates[:3], locked_rhs(0.0, y[[0, 1, 3]], phase_args(FIG7, contact)))


@pytest.mark.parametrize("y", SLIDING_STATES)
@pytest.mark.parametrize("sigma", [1.0, -1.0])
@pytest.mark.parametrize("amplitude", [0.3, 0.9])
def test_contact_rates_satisfy_the_constrained_equations(y, sigma, amplitude):
    """(5.1) on the moving constraint, (2.11b) with the tilted reaction, (5.2) with its torque, (2.11d).

    r*' is a central difference of r*(theta_a, theta_b) along theta' = phi' - Omega
    (step 1e-6: error ~1e-12 x third derivatives); the rest is rounding.
    """
    rough = _rough(amplitude, 0.2, seed=1)
    y = np.array(y)
    here = contact_state(SLIDING, sigma, y, FIG7, rough)
    phi_dot, omega_a_dot, omega_b_dot = here.rates[:3]
    phi, omega_a, omega_b = y[:3]
    local = here.local
    k, z = local.kappa, float(local.zeta)
    theta_a, theta_b = phi - y[4], phi - y[3]
    h = 1e-6
    r_star_dot = (rough.local_at(theta_a + h * (phi_dot - omega_a), theta_b + h * (phi_dot - omega_b)).r_star
                  - rough.local_at(theta_a - h * (phi_dot - omega_a), theta_b - h * (phi_dot - omega_b)).r_star
                  ) / (2.0 * h)
    assert r_star_dot == pytest.approx(-math.cos(phi) - here.c_eps, abs=1e-7)  # (5.1), kappa'/zeta^3 = r'
    slope = local.dkappa_a + local.dkappa_b
    assert k * (omega_a + omega_b - 2.0 * phi_dot) / ((2.0 + k * k) * z) + math.sin(phi) + here.c_eps * slope / k \
        == pytest.approx(0.0, abs=1e-13)  # (2.11b) with the reaction's e_chi component
    torque = (z * z * (omega_b - phi_dot) - (1.0 + 2.0 * k * k) * (omega_a - phi_dot)) / (3.0 * (2.0 + k * k) * z)
    assert torque - 0.5 * FIG7.upsilon * omega_a_dot - here.c_chi - here.c_eps * local.dkappa_a \
        == pytest.approx(0.0, abs=1e-13)  # (5.2) with the reaction's torque
    assert FIG7.mu_ratio * FIG7.upsilon * omega_b_dot + 0.5 * FIG7.upsilon * omega_a_dot \
        == pytest.approx(FIG7.s + k * math.sin(phi), abs=1e-14)  # (2.11d)
    assert here.c_chi == pytest.approx(-sigma * math.tan(0.2) * here.c_eps, rel=1e-15)  # Coulomb, sliding
    assert here.rates[3] == omega_b and here.rates[4] == omega_a


def test_reaction_is_the_free_approach_rate_reduced():
    """C_e has the sign of c_0 = d(r - r*)/dt of the free motion, so touching means pushing."""
    rough = _rough(0.9, 0.2, seed=4)
    local = rough.local_at(0.4, -1.0)
    for phi, omega_a, omega_b in ((3.0, 0.1, 0.2), (0.5, -2.0, 3.0), (1.4, 2.0, 0.0)):
        phi_dot_0 = 0.3
        c_e, _, _ = normal_reaction(local, phi, phi_dot_0, omega_a, omega_b)
        approach = -math.cos(phi) - (local.dkappa_a * (phi_dot_0 - omega_a) + local.dkappa_b
                                     * (phi_dot_0 - omega_b)) / float(local.zeta) ** 3
        assert math.copysign(1.0, c_e) == math.copysign(1.0, approach) and abs(c_e) <= abs(approach)


def test_free_flight_is_the_reduced_model_and_its_sentinel_is_finite_at_the_centre():
    rough = _rough(0.9, 0.2)
    y = np.array([0.3, -1.2, 0.4, 0.1, 2.0, -1.0, 0.0])
    f = free_rhs(0.0, y, FIG7, rough)
    assert np.array_equal(f[:5], reduced_rhs(0.0, y[:5], FIG7)) and f[5] == y[2]
    at_centre = free_rhs(0.0, np.array([0.0, 0.0, 0.4, 0.1, 2.0, -1.0, 0.0]), FIG7, rough)
    assert np.all(np.isfinite(at_centre)) and at_centre[6] == 0.0
    # The Jacobian is exact but for the row of S, on which nothing depends.
    h = 1e-6
    numeric = np.column_stack([(free_rhs(0.0, y + h * e, FIG7, rough) - free_rhs(0.0, y - h * e, FIG7, rough))
                               / (2.0 * h) for e in np.eye(7)])
    np.testing.assert_allclose(_free_jacobian(0.0, y, FIG7)[:6], numeric[:6], rtol=1e-7, atol=1e-7)
    assert np.all(numeric[:, 6] == 0.0)


# -- hybrid runs -------------------------------------------------------------------------

@pytest.mark.parametrize("psi", [0.05, 0.5, 0.13])
def test_amplitude_zero_reproduces_the_uniform_contact(psi):
    """Figures 7 and 8 and stick-slip near the onset (psi = 0.13), 300 tau, rtol 1e-8.

    The right-hand sides, guards and resets are those of dynamics.contact.reduced
    bit for bit; only the error control sees two more components. Same
    switches; switch times to 1e-5 (measured 1.4e-8, 1.4e-8 and 1.4e-6: the
    stick-slip times are sensitive, as in tests/test_contact.py), final
    state to 1e-7 (measured <= 5e-9).
    """
    uniform = simulate_contact(FIG7, ContactParams(KAPPA_STAR, psi), 300.0, *RELEASE, rtol=1e-8, atol=1e-10,
                               max_turns=1e6)
    rough = _run(0.0, psi, 0, 300.0)
    assert rough.status == 0
    assert [(sw.old, sw.new) for sw in rough.switches] == [(sw.old, sw.new) for sw in uniform.switches]
    np.testing.assert_allclose([sw.t for sw in rough.switches], [sw.t for sw in uniform.switches], atol=1e-5)
    for name in ("phi", "omega_a", "omega_b", "x_b", "c_eps", "c_chi"):
        assert getattr(rough, name)[-1] == pytest.approx(getattr(uniform, name)[-1], abs=1e-7), name
    assert np.all(rough.kappa[rough.phase != FREE] == KAPPA_STAR)


def test_a_seed_gives_the_same_run():
    one, again = _run(0.6, 0.05, 1, 100.0), simulate_rough_contact(FIG7, _rough(0.6, 0.05, 1), 100.0, *RELEASE,
                                                                   rtol=1e-8, atol=1e-10, max_turns=1e6)
    assert one.switches == again.switches
    for name in ("t", "phi", "omega_a", "omega_b", "x_b", "kappa", "c_eps"):
        assert np.array_equal(getattr(one, name), getattr(again, name)), name


@pytest.mark.parametrize(("amplitude", "psi"), [(0.6, 0.05), (0.9, 0.5)])
def test_rough_runs_rock_irregularly_and_keep_the_contact_laws(amplitude, psi):
    """Rough surfaces: lift-offs and re-contacts, and Omega_b that keeps fluctuating.

    The uniform runs settle on a fixed point (one switch, Omega_b steady to
    1e-6 by t = 300: tests/test_contact.py). Measured here: 15 and 25
    switches, 6-7 of them lift-offs, and after t = 100 Omega_b fluctuating by
    0.02-0.04 about a mean of 0.05 (the uniform steady rate is 0.12 and 0.15).
    """
    traj = _run(amplitude, psi, 0, 300.0)
    assert traj.status == 0 and traj.stop_reason == "t_end"
    lifts = [sw for sw in traj.switches if sw.new == FREE]
    assert len(lifts) >= 3 and len(traj.switches) >= 10
    _, fluctuation, _ = rolling_statistics(traj, 100.0)
    uniform = steady_state(FIG7.s, KAPPA_STAR, psi)
    assert fluctuation > 0.05 * uniform.omega_b
    touching = traj.phase != FREE
    # The constraint holds: kappa is the local kappa* in contact and never beyond it when free.
    local = _rough(amplitude, psi).local(traj.theta_a, traj.theta_b)
    np.testing.assert_allclose(traj.kappa[touching], local.kappa[touching], rtol=1e-15)
    assert np.all(traj.one_minus_kappa[~touching] >= local.one_minus_kappa[~touching] * (1.0 - 1e-6))
    # A pushing reaction and Coulomb's bound at every sample in contact (rounding allowed).
    assert np.all(traj.c_eps[touching] >= -1e-12)
    assert np.all(np.abs(traj.c_chi) <= traj.c_eps * math.tan(psi) + 1e-12)
    # Touches are located on the constraint, lift-offs where the reaction vanishes.
    for sw in traj.switches:
        i = np.flatnonzero((traj.t == sw.t) & (traj.phase == sw.new))[0]
        if sw.old == FREE:
            assert traj.one_minus_kappa[i - 1] == pytest.approx(local.one_minus_kappa[i - 1], rel=1e-9)
        if sw.new == FREE:
            assert abs(traj.c_eps[i - 1]) < 1e-9


@pytest.mark.parametrize("amplitude", [0.3, 0.9])
@pytest.mark.parametrize("psi", [0.0, 1.4])
def test_no_nan_or_stall_from_no_friction_to_strong_friction(amplitude, psi):
    """psi = 0 and tan(psi) = 5.8, up to amplitude 0.9: 200 tau, finite, few steps.

    Measured 2,200-5,400 steps (about 10-30 a tau); a collapsed step would need
    millions, so 30,000 bounds it. (tan(psi) -> infinity is the known limit
    in dynamics.contact.rough.)
    """
    traj = _run(amplitude, psi, 2, 200.0)
    assert traj.status == 0 and traj.steps < 30_000
    for name in ("t", "kappa", "one_minus_kappa", "phi", "omega_a", "omega_b", "x_b", "c_eps", "c_chi"):
        assert np.all(np.isfinite(getattr(traj, name))), name
    assert np.all(np.diff(traj.t) >= 0.0)


def test_start_in_contact_on_the_local_kappa_star():
    rough = _rough(0.5, 0.5)
    phi0 = math.pi + 0.2
    kappa0 = rough.local_at(phi0, phi0).kappa
    traj = simulate_rough_contact(FIG7, rough, 5.0, kappa0, phi0, 0.1, 0.1)
    assert traj.phase[0] != FREE and traj.status == 0
    with pytest.raises(ValueError, match=re.escape("kappa0 must be in [0, ")):
        simulate_rough_contact(FIG7, rough, 5.0, min(kappa0 + 1e-3, 0.999), phi0)


def test_speed_table_against_the_uniform_speed():
    """Amplitude 0 rolls at the uniform (6.1) rate whatever the seed; roughness changes it.

    300 tau, averaged over [150, 300]: the uniform rocking has decayed by
    e^-20 by then (tests/test_contact.py), so amplitude 0 gives (6.1) to 1e-4.
    """
    uniform, rows = speed_table(FIG7, ContactParams(KAPPA_STAR, 0.05), CORRELATION, (0.0, 0.5), (0, 1),
                                t_end=300.0, t_settle=150.0)
    assert uniform == pytest.approx(steady_state(FIG7.s, KAPPA_STAR, 0.05).omega_b)
    smooth, rough = rows
    # Amplitude 0 ignores the surfaces: every seed gives the same run, bit for bit.
    assert smooth.ratio == pytest.approx(1.0, abs=1e-4) and smooth.spread < 1e-15 and smooth.switch_rate == 0.0
    assert rough.switch_rate > 0.0 and rough.fluctuation > 10.0 * smooth.fluctuation
    assert np.isfinite(rough.mean) and rough.mean > 0.0
    table = speed_table_markdown(uniform, rows)
    assert table.count("\n| ") == 3 and f"{uniform:.5g}" in table


@pytest.mark.slow
def test_speed_table_over_amplitudes_and_seeds():
    """The reported table: amplitudes 0-0.9, six seeds, 1000 tau averaged over [200, 1000].

    Measured (psi = 0.05, the sliding branch of figure 7; uniform (6.1) rate
    0.1224/tau), mean / uniform and spread over seeds / uniform:
    amplitude 0.1: 0.993, 0.001; 0.3: 0.932, 0.02; 0.5: 0.657, 0.11;
    0.7: 0.564, 0.15; 0.9: 0.467, 0.11. The rough runs roll more slowly,
    and the seed matters more as the amplitude grows.
    """
    uniform, rows = speed_table(FIG7, ContactParams(KAPPA_STAR, 0.05), CORRELATION,
                                (0.0, 0.1, 0.3, 0.5, 0.7, 0.9), range(6), t_end=1000.0, t_settle=200.0)
    ratios = [row.ratio for row in rows]
    assert ratios[0] == pytest.approx(1.0, abs=1e-6)
    assert ratios[-1] < ratios[1] and all(np.isfinite(ratios))
    assert rows[-1].spread > rows[1].spread


# -- arguments ------------------------------------------------------------------------

def test_invalid_arguments():
    mean = ContactParams(KAPPA_STAR, 0.1)
    with pytest.raises(ValueError, match=re.escape("amplitude must be in [0, 1)")):
        RoughContact.from_seed(mean, 1.0, 0.3, 0.3, 0)
    with pytest.raises(ValueError, match="correlation must be in"):
        RoughContact.from_seed(mean, 0.5, 0.0, 0.3, 0)
    with pytest.raises(ValueError, match="correlation must be at least"):
        RoughContact.from_seed(mean, 0.5, 1e-5, 0.3, 0)
    with pytest.raises(ValueError, match="seed must be an integer"):
        RoughContact.from_seed(mean, 0.5, 0.3, 0.3, -1)
    with pytest.raises(ValueError, match="b must be in"):
        RoughContact.from_rolled_length(mean, 0.5, 1e-3, 0.01, 0.008, 0)
    with pytest.raises(ValueError, match="method"):
        simulate_rough_contact(FIG7, _rough(0.5, 0.1), 1.0, 0.5, 0.0, method="RK45")
    with pytest.raises(ValueError, match="t_settle"):
        rolling_statistics(_run(0.0, 0.05, 0, 300.0), 400.0)
