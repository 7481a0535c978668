"""Rough surfaces (dynamics.contact.roughness) and contact on a moving constraint (dynamics.contact.rough)."""

import dataclasses
import functools
import math
import re

import numpy as np
import pytest
from scipy.optimize import brentq

from dynamics.analysis import rolling_statistics
from dynamics.apparatus import STEEL
from dynamics.contact import reduced as uniform_contact
from dynamics.contact.laws import Stribeck
from dynamics.contact.reduced import ContactParams
from dynamics.contact.rough import (
    RoughContactRun,
    contact_state,
    free_events,
    free_jacobian,
    free_rhs,
    locked_events,
    locked_jacobian,
    locked_rhs,
    normal_reaction,
    phase_args,
    sliding_events,
    sliding_jacobian,
    sliding_rhs,
)
from dynamics.contact.roughness import (
    CLIP_FLOOR,
    CLIP_KNEE,
    JET_ORDER,
    RoughContact,
    SurfaceHeights,
    _heights_kernel,
    soft_floor,
)
from dynamics.contact.steady import steady_state
from dynamics.equations import reduced
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import simulate
from dynamics.trajectory import PHASE_CODES
from validation.reports.rough_speeds import speed_table_markdown
from validation.rough_speeds import speed_table

from apparatus import A, B

FIG7 = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)  # figures 7 and 8: Upsilon = mu_ = 1, s = 1/4
KAPPA_STAR = 0.98  # figures 7 and 8
RELEASE = Initial(kappa=0.5, phi=0.3)  # figure 2's release, at rest
CORRELATION = 0.3  # rad on both surfaces: a distance 0.3 b rolled
ENDLESS = Limits(max_turns=1e6)  # the runs roll on; no runaway stops them
FREE, SLIDING, LOCKED = PHASE_CODES["free"], PHASE_CODES["sliding"], PHASE_CODES["locked"]


def _rough(amplitude, psi, seed=0, kappa_star=KAPPA_STAR, correlation=CORRELATION):
    return RoughContact.from_seed(ContactParams(kappa_star, psi), amplitude, correlation, correlation, seed)


@functools.cache
def _run(amplitude, psi, seed, t_end, rtol=1e-8):
    """A cached rough run from figure 2's release (several tests read the same runs)."""
    return simulate(FIG7, RELEASE, t_end, contact=_rough(amplitude, psi, seed), limits=ENDLESS, rtol=rtol)


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


@pytest.mark.parametrize("correlation", [0.3, 0.01])
@pytest.mark.parametrize("amplitude", [0.0, 0.3, 0.9])
@pytest.mark.parametrize("kappa_star", [0.3, 0.98, 0.999999])
def test_compiled_local_gap_matches_its_numpy_twin(amplitude, kappa_star, correlation, rng):
    """The compiled field turns cos(k theta), sin(k theta) by rotations (40 and 1200 modes here).

    Both twins round k theta by ~K eps |theta|: the slopes agree to 1e-12 of
    their largest value (measured 8e-14 at 1200 modes), kappa* to 1e-12.
    """
    rough = _rough(amplitude, 0.1, seed=7, kappa_star=kappa_star, correlation=correlation)
    theta_a, theta_b = rng.uniform(-40.0, 40.0, (2, 50))
    vectorised = rough.local(theta_a, theta_b)
    scalar = np.array([rough.local_at(a, b) for a, b in zip(theta_a, theta_b)]).T
    np.testing.assert_allclose(scalar[:2], vectorised[:2], rtol=1e-12, atol=1e-14)
    slope_scale = np.max(np.abs(vectorised[2:]))
    np.testing.assert_allclose(scalar[2:], vectorised[2:], rtol=0.0, atol=1e-12 * slope_scale)


@pytest.mark.parametrize("modes", [1, 136, 2000, 20000])
def test_compiled_heights_are_the_series_to_rounding(modes, rng):
    """f, f' and f'' of the compiled field against the series summed in extended precision.

    The errors are measured against the sum of the terms' magnitudes (each series
    cancels). The table's Taylor remainder is below 2.3e-17 of it (module docstring); what
    is left is the rounding of the inverse FFTs that build the table, random in sign over
    its nodes and modes: it grows as sqrt(K) eps, measured 24 eps at 136 modes (the outer
    cylinder's at 1 mm correlation), 71 at 2000 and 300 at 20000. The test holds
    4 sqrt(K) + 8 eps. At 1 mode the nodes' spacing is a whole 2 pi/16, and only the
    Taylor remainder's bound keeps the error down.
    """
    cos_c, sin_c = rng.normal(size=(2, modes)) / math.sqrt(modes)
    jets = SurfaceHeights(0.1, cos_c, sin_c).jets
    k = np.arange(1, modes + 1, dtype=np.longdouble)
    magnitudes = np.abs(cos_c) + np.abs(sin_c)
    size = np.array([magnitudes.sum(), (k * magnitudes).sum(), (k * k * magnitudes).sum()], dtype=np.longdouble)
    tolerance = (4.0 * math.sqrt(modes) + 8.0) * np.finfo(float).eps
    # anywhere on the circle, at nodes, half-way between them, and at both ends of the period
    h = 2.0 * math.pi * (JET_ORDER + 1) / jets.size  # the nodes' spacing
    for theta in [*rng.uniform(-40.0, 40.0, 40), 3 * h, 3.5 * h, 3.5 * h + 1e-13, 0.0, -1e-300, 2 * math.pi - 1e-15]:
        phase = k * (np.longdouble(theta) % (2 * np.longdouble(math.pi)))
        cos, sin = np.cos(phase), np.sin(phase)
        even = cos * cos_c + sin * sin_c
        exact = np.array([even.sum(), (k * (cos * sin_c - sin * cos_c)).sum(), -(k * k * even).sum()])
        error = np.abs(np.array(_heights_kernel(theta, jets), dtype=np.longdouble) - exact) / size
        assert np.all(error < tolerance), (theta, error / np.finfo(float).eps)


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
    rough = RoughContact.from_rolled_length(mean, 0.5, 0.001, A, B, seed=2)
    assert rough.inner.correlation == pytest.approx(0.001 / A) and rough.outer.correlation == pytest.approx(0.001 / B)


# -- the contact equations on the moving constraint ----------------------------------------

SLIDING_STATES = [(2.5, 0.07, 0.15, 3.0, 1.0), (4.0, 0.3, -0.25, -1.0, 7.0), (3.3, -0.03, 0.1, 0.0, -2.0)]
X_B_LIMIT, X_B0 = 50.0, 0.5  # a runaway limit and origin for the guards


def _args(rough, sigma=0.0):
    return phase_args(FIG7, rough, sigma, x_b_limit=X_B_LIMIT, x_b0=X_B0)


def _locked(y):
    """The locked state (phi, Omega, X_b, Theta_a) of a sliding one, Omega = Omega_a."""
    return np.asarray(y)[[0, 1, 3, 4]]


@pytest.mark.parametrize("y", SLIDING_STATES)
@pytest.mark.parametrize("sigma", [1.0, -1.0, 0.0])
def test_amplitude_zero_gives_the_uniform_phases_bit_for_bit(y, sigma):
    """Right-hand sides, reactions and guards of dynamics.contact.reduced, to the last bit."""
    rough = _rough(0.0, 0.3)
    y = np.array(y)
    args = _args(rough, sigma)
    uniform = (*uniform_contact.phase_args(FIG7, rough.mean, sigma), X_B_LIMIT, X_B0)
    assert np.array_equal(sliding_rhs(0.0, y, args)[:4], uniform_contact.sliding_rhs(0.0, y[:4], uniform))
    here = contact_state(0.0, y, args)
    assert here[3] == -math.cos(y[0]) and here[5] == KAPPA_STAR and here[6] == rough.mean.one_minus_kappa_star
    # lift-off: C_e = -cos(phi) falling through 0 is the uniform guard cos(phi) rising through it
    assert np.array_equal(sliding_events(0.0, y, args), uniform_contact.sliding_events(0.0, y[:4], uniform)
                          * [1.0, -1.0, 1.0])
    locked = _locked(y)
    assert np.array_equal(locked_rhs(0.0, locked, args)[:3], uniform_contact.locked_rhs(0.0, locked[:3], uniform))
    assert np.array_equal(locked_events(0.0, locked, args), uniform_contact.locked_events(0.0, locked[:3], uniform)
                          * [1.0, -1.0, 1.0, 1.0])
    # free flight and its touch of the circle r = r*
    free = np.array([y[1], -y[0], y[1], y[2], y[3], y[4], 0.0])
    assert np.array_equal(free_rhs(0.0, free, args)[:5], reduced.rhs(0.0, free[:5], FIG7.args))
    reduced_args = reduced.run_args(FIG7, gap_floor=1e-9, x_b_limit=X_B_LIMIT, x_b0=X_B0, r_star=rough.mean.r_star)
    assert np.array_equal(free_events(0.0, free, args), reduced.events(0.0, free[:5], reduced_args)[[2, 3, 4]])


@pytest.mark.parametrize("y", SLIDING_STATES)
@pytest.mark.parametrize("sigma", [1.0, -1.0, None], ids=["sliding+", "sliding-", "locked"])
@pytest.mark.parametrize("amplitude", [0.3, 0.9])
def test_contact_rates_satisfy_the_constrained_equations(y, sigma, amplitude):
    """(5.1) on the moving constraint, (2.11b) with the tilted reaction, (5.2) with its torque, (2.11d).

    r*' is a central difference of r*(theta_a, theta_b) along theta' = phi' - Omega
    (step 1e-6: error ~1e-12 x third derivatives); the rest is rounding. Locked,
    (5.2) is what C_lock must satisfy for Omega_a' = Omega_b'.
    """
    rough = _rough(amplitude, 0.2, seed=1)
    state = np.array(y) if sigma is not None else _locked(y)
    phi, omega_a = state[0], state[1]
    omega_b = state[2] if sigma is not None else omega_a
    here = contact_state(0.0, state, _args(rough, sigma or 0.0))
    phi_dot, omega_a_dot, omega_b_dot, c_e, c_x = here[:5]
    theta_a, theta_b = phi - state[-1], phi - state[-2]
    local = rough.local_at(theta_a, theta_b)
    assert here[5] == local.kappa and here[6] == local.one_minus_kappa
    k, z = local.kappa, float(local.zeta)
    h = 1e-6
    r_star_dot = (rough.local_at(theta_a + h * (phi_dot - omega_a), theta_b + h * (phi_dot - omega_b)).r_star
                  - rough.local_at(theta_a - h * (phi_dot - omega_a), theta_b - h * (phi_dot - omega_b)).r_star
                  ) / (2.0 * h)
    assert r_star_dot == pytest.approx(-math.cos(phi) - c_e, abs=1e-7)  # (5.1), kappa'/zeta^3 = r'
    slope = local.dkappa_a + local.dkappa_b
    assert k * (omega_a + omega_b - 2.0 * phi_dot) / ((2.0 + k * k) * z) + math.sin(phi) + c_e * slope / k \
        == pytest.approx(0.0, abs=1e-13)  # (2.11b) with the reaction's e_chi component
    torque = (z * z * (omega_b - phi_dot) - (1.0 + 2.0 * k * k) * (omega_a - phi_dot)) / (3.0 * (2.0 + k * k) * z)
    assert torque - 0.5 * FIG7.upsilon * omega_a_dot - c_x - c_e * local.dkappa_a \
        == pytest.approx(0.0, abs=1e-13)  # (5.2) with the reaction's torque
    assert FIG7.mu_ratio * FIG7.upsilon * omega_b_dot + 0.5 * FIG7.upsilon * omega_a_dot \
        == pytest.approx(FIG7.s + k * math.sin(phi), abs=1e-14)  # (2.11d)
    if sigma is None:
        assert omega_a_dot == omega_b_dot
        rates = locked_rhs(0.0, state, _args(rough))
        assert rates[2] == omega_b and rates[3] == omega_a
    else:
        assert c_x == pytest.approx(-sigma * math.tan(0.2) * c_e, rel=1e-15)  # Coulomb, sliding
        rates = sliding_rhs(0.0, state, _args(rough, sigma))
        assert rates[3] == omega_b and rates[4] == omega_a


def test_reaction_is_the_free_approach_rate_reduced():
    """C_e has the sign of c_0 = d(r - r*)/dt of the free motion, so touching means pushing."""
    rough = _rough(0.9, 0.2, seed=4)
    local = rough.local_at(0.4, -1.0)
    for phi, omega_a, omega_b in ((3.0, 0.1, 0.2), (0.5, -2.0, 3.0), (1.4, 2.0, 0.0)):
        phi_dot_0 = 0.3
        c_e, _, _ = normal_reaction(*local, phi, phi_dot_0, omega_a, omega_b)
        approach = -math.cos(phi) - (local.dkappa_a * (phi_dot_0 - omega_a) + local.dkappa_b
                                     * (phi_dot_0 - omega_b)) / float(local.zeta) ** 3
        assert math.copysign(1.0, c_e) == math.copysign(1.0, approach) and abs(c_e) <= abs(approach)


def test_free_flight_is_the_reduced_model_and_its_sentinel_is_finite_at_the_centre():
    """S' = kappa^2 r*' against a central difference of r* along the flight (step 1e-6)."""
    rough = _rough(0.9, 0.2)
    args = _args(rough)
    y = np.array([0.3, -1.2, 0.4, 0.1, 2.0, -1.0, 0.0])
    f = free_rhs(0.0, y, args)
    assert np.array_equal(f[:5], reduced.rhs(0.0, y[:5], FIG7.args)) and f[5] == y[2]
    r2 = y[0] ** 2 + y[1] ** 2
    phi, phi_dot = math.atan2(y[0], y[1]), (y[1] * f[0] - y[0] * f[1]) / r2
    h = 1e-6
    r_star_dot = (rough.local_at(phi - y[5] + h * (phi_dot - y[2]), phi - y[4] + h * (phi_dot - y[3])).r_star
                  - rough.local_at(phi - y[5] - h * (phi_dot - y[2]), phi - y[4] - h * (phi_dot - y[3])).r_star
                  ) / (2.0 * h)
    assert f[6] == pytest.approx(r2 / (1.0 + r2) * r_star_dot, rel=1e-8)
    at_centre = free_rhs(0.0, np.array([0.0, 0.0, 0.4, 0.1, 2.0, -1.0, 0.0]), args)
    assert np.all(np.isfinite(at_centre)) and at_centre[6] == 0.0
    # The Jacobian is exact but for the row of S, on which nothing depends.
    numeric = np.column_stack([(free_rhs(0.0, y + h * e, args) - free_rhs(0.0, y - h * e, args)) / (2.0 * h)
                               for e in np.eye(7)])
    np.testing.assert_allclose(free_jacobian(0.0, y, args)[:6], numeric[:6], rtol=1e-7, atol=1e-7)
    assert np.all(numeric[:, 6] == 0.0) and np.all(free_jacobian(0.0, y, args)[6] == 0.0)


def _richardson_jacobian(fun, y, args, h=1e-3):
    """(4 D(h/2) - D(h))/3 of central differences D: error O(h^4), independent of the compiled step."""
    def central(step):
        return np.column_stack([(fun(0.0, y + step * e, args) - fun(0.0, y - step * e, args)) / (2.0 * step)
                                for e in np.eye(y.size)])
    return (4.0 * central(0.5 * h) - central(h)) / 3.0


@pytest.mark.parametrize("y", SLIDING_STATES)
@pytest.mark.parametrize("locked", [False, True], ids=["sliding", "locked"])
def test_contact_jacobians_are_the_derivatives(y, locked):
    """The compiled central differences (step eps^(1/3): error ~1e-10) against Richardson's, to 1e-7."""
    rough = _rough(0.9, 0.2, seed=1)
    args = _args(rough, 1.0)
    state = _locked(y) if locked else np.array(y)
    fun, jac = (locked_rhs, locked_jacobian) if locked else (sliding_rhs, sliding_jacobian)
    np.testing.assert_allclose(jac(0.0, state, args), _richardson_jacobian(fun, state, args), rtol=1e-7, atol=1e-7)


@pytest.mark.parametrize("y", SLIDING_STATES)
@pytest.mark.parametrize("sigma", [1.0, -1.0])
def test_the_stiff_friction_term_is_in_the_sliding_jacobian(y, sigma):
    """d D'/d D at fixed W moves with tan(psi) by -sigma Delta tan(psi) (2 + 1/mu_)/Upsilon dC_e/dD.

    dC_e/dD = (k_b - k_a)/(2 zeta^3 (1 + A P^2/(kappa zeta^3))) (module docstring):
    the term that makes large friction stiff, absent from the uniform contact's Jacobian.
    """
    rough_low, rough_high = _rough(0.9, 0.2, seed=1), _rough(0.9, 1.4, seed=1)
    y = np.array(y)
    along_d = np.array([0.0, -0.5, 0.5, 0.0, 0.0])  # D up by 1 at fixed W

    def d_dot_by_d(rough):
        rates = sliding_jacobian(0.0, y, _args(rough, sigma)) @ along_d
        return rates[2] - rates[1]

    local = rough_low.local_at(y[0] - y[4], y[0] - y[3])
    k, zeta3, slope = local.kappa, float(local.zeta) ** 3, local.dkappa_a + local.dkappa_b
    lever = (2.0 + k * k) * float(local.zeta) / (2.0 * k)
    dc_e = (local.dkappa_b - local.dkappa_a) / (2.0 * zeta3 * (1.0 + lever * slope * slope / (k * zeta3)))
    ups, mu_ = FIG7.upsilon, FIG7.mu_ratio
    predicted = -sigma * (math.tan(1.4) - math.tan(0.2)) * (2.0 / ups + 1.0 / (mu_ * ups)) * dc_e
    assert abs(predicted) > 0.05  # a term that matters at these states
    assert d_dot_by_d(rough_high) - d_dot_by_d(rough_low) == pytest.approx(predicted, rel=1e-6)


# -- switches that start on a guard ----------------------------------------------------

def test_free_phases_that_start_on_the_constraint_start_at_clearance_zero(rng):
    """After a lift-off the clearance is exactly 0, although r - r* itself rounds to either sign."""
    rough = _rough(0.9, 0.2, seed=1)
    run = RoughContactRun(FIG7, rough, ENDLESS, 1e-8, 0.0)
    rounded = 0
    for phi, omega_a, omega_b, x_b, turned_a in rng.uniform(-10.0, 10.0, (300, 5)):
        end = np.array([phi, omega_a, omega_b, x_b, turned_a])
        free = run.transition(run.sliding(end, 1.0), "lift", end, phi)
        assert free.name == "free" and free.record and free.y0[6] == 0.0
        assert free_events(0.0, free.y0, free.args)[2] == 0.0
        local = rough.local_at(phi - turned_a, phi - x_b)
        assert math.atan2(free.y0[0], free.y0[1]) == pytest.approx(phi - 2.0 * math.pi * round(phi / (2.0 * math.pi)),
                                                                  abs=1e-14)
        # r - r* without the shift: rounding of r* and of the angles (|phi| eps) times dr*/dtheta
        raw = free_events(0.0, free.y0, _args(rough))[2]
        r_star_slope = (abs(local.dkappa_a) + abs(local.dkappa_b)) / float(local.zeta) ** 3
        assert abs(raw) <= 16.0 * np.finfo(float).eps * (float(local.r_star) + 10.0 * r_star_slope)
        rounded += raw != 0.0
    assert rounded > 30  # rounding alone would choose the sign of the first guard value


def _graze(rough, c_e, omega_a=0.05, omega_b=0.3, x_b=1.0, turned_a=-0.5):
    """A touching free state whose reaction is ``c_e``: phi solved by brentq near the horizontal."""
    run = RoughContactRun(FIG7, rough, ENDLESS, 1e-8, 0.0)

    def reaction(phi):
        return run.state([phi, omega_a, omega_b, x_b, turned_a])[3] - c_e

    phi = brentq(reaction, 0.5 * math.pi - 1.0, 0.5 * math.pi + 1.0, xtol=1e-15)
    local = rough.local_at(phi - turned_a, phi - x_b)
    r_star = float(local.r_star)
    return phi, np.array([r_star * math.sin(phi), r_star * math.cos(phi), omega_a, omega_b, x_b, turned_a, 3.0])


@pytest.mark.parametrize(("c_e", "graze"), [(0.5e-8, True), (2e-8, False)])
def test_a_touch_with_a_reaction_below_rtol_is_a_graze(c_e, graze):
    """C_e <= rtol: the run flies on from the touch, unrecorded, at clearance 0; above it, contact."""
    rough = _rough(0.9, 0.2, seed=2)
    run = RoughContactRun(FIG7, rough, ENDLESS, 1e-8, 0.0)
    phi, touching = _graze(rough, c_e)
    after = run.transition(run.free(touching), "touch", touching, phi)
    if graze:
        assert after.name == "free" and not after.record
        assert np.array_equal(after.y0[:6], touching[:6]) and after.y0[6] == 0.0
        assert free_events(0.0, after.y0, after.args)[2] == 0.0
    else:
        assert after.name in ("sliding", "locked") and after.record


def test_start_on_the_constraint_moving_away_is_free_at_clearance_zero():
    rough = _rough(0.5, 0.5)
    phi0 = 0.2  # above B: the free motion leaves the asperities at once
    kappa0 = rough.local_at(phi0, phi0).kappa
    traj = simulate(FIG7, Initial(kappa0, phi0), 2.0, contact=rough)
    assert traj.status == "completed" and traj.columns["phase"][0] == FREE
    assert traj.info["switches"] == [] and np.all(traj.columns["phase"] == FREE)
    assert traj.columns["kappa"][-1] < kappa0


# -- hybrid runs -------------------------------------------------------------------------

@pytest.mark.parametrize("psi", [0.05, 0.5, 0.13])
def test_amplitude_zero_reproduces_the_uniform_contact(psi):
    """Figures 7 and 8 and stick-slip near the onset (psi = 0.13), 300 tau, rtol 1e-8.

    The right-hand sides, guards and resets are those of dynamics.contact.reduced
    bit for bit; only the error control sees two more components, and the
    contact Jacobian is a difference quotient. Same switches; switch times to
    1e-5 (measured 1.4e-9, 1.4e-9 and 8.2e-8: the stick-slip times are
    sensitive, as in tests/test_contact.py), final state to 1e-7 (measured
    <= 1.3e-9).
    """
    uniform = simulate(FIG7, RELEASE, 300.0, contact=ContactParams(KAPPA_STAR, psi), limits=ENDLESS)
    rough = _run(0.0, psi, 0, 300.0)
    assert rough.status == "completed"
    switches, expected = rough.info["switches"], uniform.info["switches"]
    assert [(sw["from"], sw["to"]) for sw in switches] == [(sw["from"], sw["to"]) for sw in expected]
    np.testing.assert_allclose([sw["t"] for sw in switches], [sw["t"] for sw in expected], atol=1e-5)
    for name in ("phi", "omega_a", "omega_b", "x_b", "c_eps", "c_chi"):
        assert rough.columns[name][-1] == pytest.approx(uniform.columns[name][-1], abs=1e-7), name
    assert np.all(rough.columns["kappa"][rough.columns["phase"] != FREE] == KAPPA_STAR)


def test_a_seed_gives_the_same_run():
    one = _run(0.6, 0.05, 1, 100.0)
    again = simulate(FIG7, RELEASE, 100.0, contact=_rough(0.6, 0.05, 1), limits=ENDLESS)
    assert one.info["switches"] == again.info["switches"] and len(one.info["switches"]) > 1
    for name in ("t", "phi", "omega_a", "omega_b", "x_b", "kappa", "c_eps", "theta_a", "theta_b", "phase"):
        assert np.array_equal(one.columns[name], again.columns[name]), name


@pytest.mark.parametrize(("amplitude", "psi"), [(0.6, 0.05), (0.9, 0.5)])
def test_rough_runs_rock_irregularly_and_keep_the_contact_laws(amplitude, psi):
    """Rough surfaces: lift-offs and re-contacts, and Omega_b that keeps fluctuating.

    The uniform runs settle on a fixed point (one switch, Omega_b steady to
    1e-6 by t = 300: tests/test_contact.py). Measured here: 15 and 25
    switches, 7 and 6 of them lift-offs, and after t = 100 Omega_b fluctuating
    by 0.02-0.04 about a mean of 0.05 (the uniform steady rate is 0.12 and 0.15).
    """
    traj = _run(amplitude, psi, 0, 300.0)
    cols = traj.columns
    assert traj.status == "completed" and traj.event == ""
    switches = traj.info["switches"]
    lifts = [sw for sw in switches if sw["to"] == "free"]
    assert len(lifts) >= 3 and len(switches) >= 10
    _, fluctuation, _ = rolling_statistics(traj, 100.0)
    uniform = steady_state(FIG7.s, KAPPA_STAR, psi)
    assert fluctuation > 0.05 * uniform.omega_b
    phase = cols["phase"]
    touching = phase != FREE
    # The constraint holds: kappa is the local kappa* in contact and never beyond it when free.
    local = _rough(amplitude, psi).local(cols["theta_a"], cols["theta_b"])
    np.testing.assert_allclose(cols["kappa"][touching], local.kappa[touching], rtol=1e-15)
    assert np.all(cols["one_minus_kappa"][~touching] >= local.one_minus_kappa[~touching] * (1.0 - 1e-6))
    # A pushing reaction and Coulomb's bound at every row in contact (rounding allowed).
    assert np.all(cols["c_eps"][touching] >= -1e-12)
    assert np.all(np.abs(cols["c_chi"]) <= cols["c_eps"] * math.tan(psi) + 1e-12)
    # phi is continuous through every phase (no 2 pi jumps at the switches or the vertical)
    assert np.max(np.abs(np.diff(cols["phi"]))) < 0.5
    # Touches are located on the constraint, lift-offs where the reaction vanishes.
    for sw in switches:
        i = np.flatnonzero((cols["t"] == sw["t"]) & (phase == PHASE_CODES[sw["to"]]))[0]
        assert phase[i - 1] == PHASE_CODES[sw["from"]] and cols["t"][i - 1] == sw["t"]
        if sw["from"] == "free":
            assert cols["one_minus_kappa"][i - 1] == pytest.approx(local.one_minus_kappa[i - 1], rel=1e-9)
        if sw["to"] == "free":
            assert abs(cols["c_eps"][i - 1]) < 1e-9


def test_output_at_requested_times_keeps_phi_continuous():
    """Rows every 0.5 tau: the same switches as every-step output, and phi on the same branch.

    The crossings of the vertical are located as events (and not output), so phi
    is unwrapped right across phi = pi however far it turns between rows;
    against the every-step rows interpolated linearly (steps of ~0.1 tau) it
    agrees to 0.05 rad, far from the 2 pi of a wrong branch.
    """
    every = _run(0.9, 0.5, 0, 300.0)
    sampled = simulate(FIG7, RELEASE, 300.0, contact=_rough(0.9, 0.5), limits=ENDLESS, output_interval=0.5)
    assert sampled.info["switches"] == every.info["switches"]
    rows = np.array(["sample" in row for row in sampled.rows])
    assert rows.sum() == 601
    t, cols = sampled.t[rows], {k: v[rows] for k, v in sampled.columns.items()}
    assert np.max(np.abs(cols["phi"] - np.interp(t, every.t, every.columns["phi"]))) < 0.05
    free = cols["phase"] == FREE  # free rows hold (xi, eta): atan2's branch cut is phi = pi, below B
    assert np.any(free & (cols["phi"] > math.pi)) and np.any(free & (cols["phi"] < math.pi))
    np.testing.assert_allclose(cols["theta_b"], cols["phi"] - cols["x_b"], rtol=0.0, atol=1e-12)


@pytest.mark.parametrize("amplitude", [0.3, 0.9])
@pytest.mark.parametrize("psi", [0.0, 1.4])
def test_no_nan_or_stall_from_no_friction_to_strong_friction(amplitude, psi):
    """psi = 0 and tan(psi) = 5.8, up to amplitude 0.9: 200 tau, finite, few steps.

    Measured 1,600-3,900 steps (about 8-20 a tau); a collapsed step would
    need millions, so 30,000 bounds it. (tan(psi) -> infinity is the known limit in
    dynamics.contact.rough.)
    """
    traj = _run(amplitude, psi, 2, 200.0)
    assert traj.status == "completed" and traj.steps < 30_000
    for name in ("t", "kappa", "one_minus_kappa", "phi", "omega_a", "omega_b", "x_b", "c_eps", "c_chi"):
        assert np.all(np.isfinite(traj.columns[name])), name
    assert np.all(np.diff(traj.t) >= 0.0)


def test_start_in_contact_on_the_local_kappa_star():
    rough = _rough(0.5, 0.5)
    phi0 = math.pi + 0.2
    kappa0 = rough.local_at(phi0, phi0).kappa
    traj = simulate(FIG7, Initial(kappa0, phi0, omega_a=0.1, omega_b=0.1), 5.0, contact=rough)
    assert traj.columns["phase"][0] != FREE and traj.status == "completed"
    assert traj.columns["kappa"][0] == kappa0
    with pytest.raises(ValueError, match=re.escape("kappa0 must be in [0, ")):
        simulate(FIG7, Initial(min(kappa0 + 1e-3, 0.999), phi0), 5.0, contact=rough)


def test_compiled_run_is_scipys_radau():
    """The compiled Radau IIA against scipy's Radau at rtol 1e-12 through touch, slip, stick and lift.

    Both follow the same algorithm, so the switches agree far inside the
    tolerance: switch times to 1e-10 relative (measured 8e-15), the final
    state to 1e-9 (measured 1e-14).
    """
    rough = _rough(0.9, 0.5, seed=0)
    start = Initial(kappa=0.9, phi=1.5)
    runs = [simulate(FIG7, start, 11.5, contact=rough, limits=ENDLESS, rtol=1e-12, method=method)
            for method in ("radau", "Radau")]
    compiled, scipy = (run.info["switches"] for run in runs)
    assert [(sw["from"], sw["to"]) for sw in compiled] == [(sw["from"], sw["to"]) for sw in scipy]
    assert {(sw["from"], sw["to"]) for sw in compiled} >= {("free", "locked"), ("locked", "sliding"),
                                                          ("sliding", "locked"), ("sliding", "free")}
    np.testing.assert_allclose([sw["t"] for sw in compiled], [sw["t"] for sw in scipy], rtol=1e-10, atol=0.0)
    for name in ("phi", "omega_a", "omega_b", "x_b", "kappa", "c_eps"):
        assert runs[0].columns[name][-1] == pytest.approx(runs[1].columns[name][-1], abs=1e-9), name
    assert all(run.status == "completed" for run in runs)


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
    0.7: 0.564, 0.15; 0.9: 0.467, 0.10. The rough runs roll more slowly,
    and the seed matters more as the amplitude grows.
    """
    _, rows = speed_table(FIG7, ContactParams(KAPPA_STAR, 0.05), CORRELATION,
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
        simulate(FIG7, RELEASE, 1.0, contact=_rough(0.5, 0.1), method="RK45")
    with pytest.raises(ValueError, match="full equations only"):
        simulate(STEEL, RELEASE, 1.0, equations="reduced",
                 contact=dataclasses.replace(_rough(0.5, 0.1), friction=Stribeck(0.2, 1e-3)))
    with pytest.raises(ValueError, match="t_settle"):
        rolling_statistics(_run(0.0, 0.05, 0, 300.0), 400.0)
    in_seconds = simulate(STEEL, RELEASE, 0.5, equations="reduced", contact=_rough(0.5, 0.1))
    with pytest.raises(ValueError, match="dimensionless trajectory"):
        rolling_statistics(in_seconds, 0.1)
