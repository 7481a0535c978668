"""The numerical Reynolds solver: closed forms, convergence, identities, symmetries, bad input.

Expected accuracy (see lubrication.reynolds_kernels): on the Sommerfeld grid every
thin-gap integrand is a trigonometric polynomial in psi, so forces are exact up
to rounding once N m exceeds its degree; tolerances are rounding level times the
coefficient's condition number (validation.lubrication_checks.condition). On
the uniform grid the error decays as N^p exp(-N acosh(1/kappa)); nodal
pressures converge as dpsi^(2 m).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lubrication import (
    Annulus,
    Fluid,
    GapProfile,
    Motion,
    closed_form_forces,
    reynolds_forces,
    reynolds_pressure,
)
from lubrication.reynolds import psi_rule
from validation import lubrication_checks as checks

from apparatus import A, B, L, OIL

KAPPAS = (0.0, 1e-8, 0.1, 0.5, 0.9, 0.99, 0.999999)
MOTIONS = {
    "squeeze": Motion(eps_dot=1e-4),
    "inner": Motion(omega_a=1.0),
    "outer": Motion(omega_b=1.0),
    "orbit": Motion(chi_dot=0.3, omega_b=0.1),
    "combined": Motion(eps_dot=-3e-5, chi_dot=0.4, omega_a=1.5, omega_b=-0.7),
}


def _term_sizes(annulus, motion):
    """Size of the terms that make up each component, (2.5)-(2.7) with kappa -> 1 in the numerators.

    Rounding errors are relative to these, not to the result, which can be a small
    difference of them (f_chi as kappa -> 0, the W_b torque as kappa -> 1).
    """
    delta, c = annulus.delta, 4 * math.pi * OIL.mu * annulus.a**3 * annulus.length
    zeta = math.sqrt(annulus.one_minus_kappa * (1 + annulus.kappa))
    w = abs(motion.w_a) + abs(motion.w_b)
    # the rotation's f_eps vanishes by symmetry, from sums of sin(theta) h^-2 of size 1/(delta zeta)^2
    force = 3 * c * (abs(motion.eps_dot) / (delta**3 * zeta**3) + w / (delta * zeta) ** 2)
    # the squeeze pressure's torque vanishes by symmetry, from terms of size 6 mu a^3 L |eps'| oint |sin| h^-2
    torque = 3 * c * w / (delta * zeta) + 2 * c * abs(motion.eps_dot) / (delta * zeta) ** 2
    return np.array([force, force, torque])


def _scales(f):
    """Forces against the size of the force, the torque against itself."""
    force = math.hypot(f[0], f[1])
    return np.array([force, force, abs(f[2])])


@pytest.mark.parametrize("kappa", KAPPAS)
@pytest.mark.parametrize("motion", MOTIONS.values(), ids=MOTIONS.keys())
@pytest.mark.parametrize("n", [16, 64])
def test_reproduces_closed_forms(kappa, motion, n):
    annulus = Annulus.from_kappa(A, B, kappa, L)
    exact = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    got = np.array(reynolds_forces(annulus, motion, OIL, n=n).as_tuple())
    sizes = _term_sizes(annulus, motion)
    assert np.all(np.abs(got - exact) <= checks.ROUNDING_TOLERANCE * sizes)


def test_every_resistance_coefficient_within_its_conditioned_tolerance():
    failed = [c for c in checks.reynolds_against_closed_forms() if not c.passed]
    assert not failed, failed


@pytest.mark.parametrize("kappa", [0.5, 0.9])
def test_uniform_grid_decays_at_the_rate_set_by_the_poles(kappa):
    rate, _, errors = checks.uniform_grid_rate(kappa)
    assert errors[-1] < 1e-7
    assert rate == pytest.approx(math.acosh(1.0 / kappa), rel=0.1)


@pytest.mark.parametrize("kappa", [0.9, 0.99, 0.9999, 0.999999])
def test_sommerfeld_grid_accuracy_does_not_depend_on_kappa(kappa):
    """Eight cells suffice at any kappa: the error is flat as kappa -> 1."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    motion = MOTIONS["combined"]
    exact = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    got = np.array(reynolds_forces(annulus, motion, OIL, n=8, points_per_cell=1).as_tuple())
    assert np.max(np.abs(got - exact) / _scales(exact)) < 1e-13


@pytest.mark.parametrize("points_per_cell", [1, 2])
def test_nodal_pressure_converges_at_order_2m(points_per_cell):
    order, errors = checks.pressure_order(0.9, points_per_cell)
    assert order == pytest.approx(2 * points_per_cell, abs=0.2)
    assert errors[-1] < 1e-4 ** points_per_cell


def test_pressure_formula_is_an_antiderivative_of_the_reynolds_flux():
    """The closed-form pressure used above, checked against p' = 12 mu a (h U/2 - qhat + Q)/h^3 by differences."""
    kappa = 0.6
    annulus = Annulus.from_kappa(A, B, kappa, L)
    motion = Motion(eps_dot=2e-4, omega_a=1.0)
    delta, mu, u = B - A, OIL.mu, A * motion.w_a
    theta = np.linspace(-3.0, 3.0, 13)
    dt = 1e-5
    dp = (checks.sommerfeld_pressure(theta + dt, annulus, motion, OIL)
          - checks.sommerfeld_pressure(theta - dt, annulus, motion, OIL)) / (2 * dt)
    h = delta * (1 - kappa * np.cos(theta))
    zeta2 = 1 - kappa**2
    qhat = 0.5 * u * delta * 2 * zeta2 / (2 + kappa**2)  # (U/2) oint h^-2 / oint h^-3, (B8)-(B9)
    flux = 12 * mu * A * (0.5 * u * h - qhat - A * motion.eps_dot * np.sin(theta)) / h**3
    np.testing.assert_allclose(dp, flux, rtol=1e-8, atol=1e-8 * np.abs(flux).max())


@pytest.mark.parametrize("n", [8, 32])
@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.99])
def test_quadrature_reproduces_integrals_b8_b9(n, kappa):
    """oint (1 - kappa cos)^-k with the solver's own rule on its own grid, k = 1, 2, 3."""
    (cpsi, spsi, vpsi, ppsi, w), _ = psi_rule(n, 1)
    zeta = math.sqrt(1 - kappa**2)
    d = 1 + kappa * cpsi
    jac, big_h = zeta / d, zeta**2 / d  # dtheta/dpsi and 1 - kappa cos(theta) on the Sommerfeld grid
    exact = (2 * math.pi / zeta, 2 * math.pi / zeta**3, math.pi * (2 + kappa**2) / zeta**5)
    for k, ref in zip((1, 2, 3), exact):
        assert np.sum(w * jac * big_h**-k) == pytest.approx(ref, rel=1e-14)


@pytest.mark.parametrize("kappa", [0.3, 0.97])
def test_linear_and_superposing_in_the_velocities(kappa):
    annulus = Annulus.from_kappa(A, B, kappa, L)
    parts = [Motion(eps_dot=2e-5), Motion(omega_a=0.9), Motion(omega_b=-0.4), Motion(chi_dot=0.25)]
    total = Motion(eps_dot=2e-5, omega_a=0.9, omega_b=-0.4, chi_dot=0.25)
    summed = sum(np.array(reynolds_forces(annulus, m, OIL).as_tuple()) for m in parts)
    whole = np.array(reynolds_forces(annulus, total, OIL).as_tuple())
    np.testing.assert_allclose(whole, summed, rtol=1e-13, atol=1e-13 * np.abs(summed).max())
    scaled = np.array(reynolds_forces(annulus, Motion(eps_dot=-7e-5, omega_a=-3.15, omega_b=1.4,
                                                      chi_dot=-0.875), OIL).as_tuple())
    np.testing.assert_allclose(scaled, -3.5 * whole, rtol=1e-13, atol=1e-13 * np.abs(whole).max())


@pytest.mark.parametrize("kappa", [0.2, 0.9])
def test_reflection_flips_f_chi_and_torque(kappa):
    """Mirroring about the line of centres reverses rotations: f_eps stays, f_chi and T_a change sign."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    m = Motion(eps_dot=1e-5, chi_dot=0.2, omega_a=1.1, omega_b=-0.3)
    mirror = Motion(eps_dot=1e-5, chi_dot=-0.2, omega_a=-1.1, omega_b=0.3)
    f, g = (np.array(reynolds_forces(annulus, x, OIL).as_tuple()) for x in (m, mirror))
    np.testing.assert_allclose(g, f * np.array([1, -1, -1]), rtol=1e-13, atol=1e-15 * np.abs(f).max())


def test_user_profile_equal_to_the_thin_gap_gives_the_same_forces():
    kappa = 0.8
    annulus = Annulus.from_kappa(A, B, kappa, L)
    eps, delta = annulus.eps, annulus.delta
    motion = Motion(eps_dot=3e-5, omega_a=1.0, omega_b=0.5)
    thin = GapProfile(h=lambda t: delta - eps * np.cos(t), h_dot=lambda t: -motion.eps_dot * np.cos(t))
    exact = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    got = np.array(reynolds_forces(annulus, motion, OIL, profile=thin, n=64, points_per_cell=4).as_tuple())
    # the squeeze flux of a user profile is integrated cell by cell: O(dpsi^8) here
    np.testing.assert_allclose(got, exact, rtol=1e-10)


def test_rotating_a_user_profile_rotates_the_force():
    kappa, angle = 0.6, 0.9
    annulus = Annulus.from_kappa(A, B, kappa, L)
    eps, delta = annulus.eps, annulus.delta
    motion = Motion(omega_a=1.0)
    turned = GapProfile(h=lambda t: delta - eps * np.cos(t - angle))
    f = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    g = np.array(reynolds_forces(annulus, motion, OIL, profile=turned, n=64, points_per_cell=3).as_tuple())
    c, s = math.cos(angle), math.sin(angle)
    np.testing.assert_allclose(g, [c * f[0] - s * f[1], s * f[0] + c * f[1], f[2]], rtol=1e-10,
                               atol=1e-10 * abs(f[1]))


def test_wavy_profile_differs_from_the_smooth_one_and_converges():
    """A wavy outer wall: a case no closed form covers; the forces converge spectrally with N."""
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    delta, eps = annulus.delta, annulus.eps
    wavy = GapProfile(h=lambda t: delta - eps * np.cos(t) + 0.05 * delta * np.cos(7 * t))
    motion = Motion(omega_a=1.0)
    forces = [np.array(reynolds_forces(annulus, motion, OIL, profile=wavy, n=n).as_tuple())
              for n in (16, 32, 64, 256)]
    finest = forces[-1]
    errors = [np.abs(f - finest).max() / np.abs(finest).max() for f in forces[:-1]]
    # measured: 1.1e-3, 2.5e-6, 4.8e-10: each doubling gains more than the last (exponential)
    assert errors[0] > 100 * errors[1] > 1e4 * errors[2]
    assert errors[2] < 1e-8
    smooth = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    assert np.abs(finest - smooth).max() > 1e-3 * np.abs(smooth).max()


def test_eccentric_gap_tends_to_the_thin_gap_at_first_order_in_delta_over_a():
    ratios = np.array([0.1, 0.03, 0.01, 0.003])
    diffs = []
    for r in ratios:
        annulus = Annulus.from_kappa(A, A * (1 + r), 0.7, L)
        motion = Motion(eps_dot=1e-6, omega_a=1.0, omega_b=0.3)
        thin = np.array(reynolds_forces(annulus, motion, OIL).as_tuple())
        exact_gap = np.array(reynolds_forces(annulus, motion, OIL, profile="eccentric", n=64).as_tuple())
        diffs.append(np.max(np.abs(exact_gap - thin) / _scales(thin)))
    slope = np.polyfit(np.log(ratios), np.log(diffs), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.1)


@settings(max_examples=300, deadline=None)
@given(
    kappa=st.floats(0.0, 1.0 - 1e-12),
    delta_over_a=st.floats(1e-4, 10.0),
    velocities=st.tuples(*[st.floats(-1e3, 1e3)] * 4),
    n=st.integers(8, 256),
    grid=st.sampled_from(["sommerfeld", "uniform"]),
    profile=st.sampled_from(["thin", "eccentric"]),
)
def test_finite_everywhere_in_the_valid_domain(kappa, delta_over_a, velocities, n, grid, profile):
    annulus = Annulus.from_kappa(A, A * (1 + delta_over_a), kappa, L)
    motion = Motion(*velocities)
    f = reynolds_forces(annulus, motion, OIL, n=n, grid=grid, profile=profile)
    assert all(math.isfinite(x) for x in f.as_tuple())


@settings(max_examples=200, deadline=None)
# velocities below 1e-100 would take the products into subnormal numbers, where relative precision ends
@given(kappa=st.floats(0.0, 1.0 - 1e-9),
       velocities=st.tuples(*[st.floats(-10.0, 10.0).filter(lambda v: v == 0 or abs(v) > 1e-100)] * 4))
def test_agrees_with_closed_forms_over_the_domain(kappa, velocities):
    annulus = Annulus.from_kappa(A, B, kappa, L)
    motion = Motion(velocities[0] * 1e-4, *velocities[1:])
    exact = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    got = np.array(reynolds_forces(annulus, motion, OIL).as_tuple())
    sizes = _term_sizes(annulus, motion)
    assert np.all(np.abs(got - exact) <= checks.ROUNDING_TOLERANCE * sizes)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"n": 4}, r"n \(cells around the gap\) must be an integer in \[8,"),
        ({"n": 16.5}, "n .* must be an integer"),
        ({"grid": "chebyshev"}, "grid must be one of sommerfeld, uniform"),
        ({"profile": "wobbly"}, "profile must be one of thin, eccentric or a GapProfile"),
        ({"points_per_cell": 0}, r"points_per_cell must be an integer in \[1, 8\]"),
    ],
)
def test_bad_discretisation_is_refused(kwargs, message):
    with pytest.raises(ValueError, match=message):
        reynolds_forces(Annulus.from_kappa(A, B, 0.5, L), Motion(), OIL, **kwargs)


@pytest.mark.parametrize(
    ("profile", "message"),
    [
        (GapProfile(h=lambda t: 0.001 * np.cos(t)), "gap profile h must stay positive"),
        (GapProfile(h=lambda t: 0.001 * (1 - np.cos(t))), "gap profile h must stay positive"),
        (GapProfile(h=lambda t: np.full_like(t, np.nan)), "gap profile h must be finite"),
        (GapProfile(h=lambda t: 1e-3), "gap profile h must return an array shaped like theta"),
        (GapProfile(h=lambda t: 1e-3 + 0 * t, h_dot=lambda t: 1e-6 + 0 * t), "must conserve the gap area"),
    ],
)
def test_bad_profile_is_refused(profile, message):
    with pytest.raises(ValueError, match=message):
        reynolds_forces(Annulus.from_kappa(A, B, 0.5, L), Motion(omega_a=1.0), OIL, profile=profile)


def test_pressure_has_zero_mean_and_the_right_nodes():
    annulus = Annulus.from_kappa(A, B, 0.95, L)
    sol = reynolds_pressure(annulus, Motion(omega_a=1.0), OIL, n=64, grid="uniform")
    np.testing.assert_allclose(sol.theta, -np.pi + 2 * np.pi * np.arange(64) / 64, atol=1e-15)
    assert abs(np.mean(sol.p)) < 1e-12 * np.abs(sol.p).max()


@pytest.mark.parametrize("kappa", [0.5, 0.9, 0.99, 0.999])
def test_uniform_grid_error_estimate_bounds_the_measured_error(kappa):
    """The estimate 1.5 (n alpha)^2 exp(-n alpha), alpha = acosh(1/kappa), lies above the largest measured
    error of the five coefficients against (2.5)-(2.7) (T_a per W_b against its row) wherever that error is
    above rounding, within a factor 10 of it once n alpha >= 4; and the cells it asks for meet the tolerance."""
    from lubrication import resistance
    from lubrication.reynolds import uniform_grid_cells, uniform_grid_error

    def measured(n):
        annulus = Annulus.from_kappa(a=A, b=B, kappa=kappa, length=0.1)
        fluid = Fluid(nu=2e-4, rho=960.0)
        got = resistance(annulus, fluid, "reynolds", n=n, grid="uniform").as_tuple()
        want = resistance(annulus, fluid, "closed-form").as_tuple()
        row = max(abs(want[2]), abs(want[4]))
        return max(*(abs(got[i] / want[i] - 1.0) for i in range(4)), abs(got[4] - want[4]) / row)

    for n in (8, 16, 32, 64, 128, 256, 512):
        err, estimate = measured(n), uniform_grid_error(n, kappa)
        if err > 1e-12:
            assert err <= estimate, (n, err, estimate)
            if n * math.acosh(1.0 / kappa) >= 4.0:  # the asymptotic regime: a sharp estimate
                assert estimate <= 10.0 * err, (n, err, estimate)
    for tolerance in (1e-2, 1e-6):
        assert measured(uniform_grid_cells(kappa, tolerance)) <= tolerance
