"""The conformal map of the unsteady solver: circles, regularity at eps = 0, the metric, the mesh velocity, refusals."""

import cmath
import math

import numpy as np
import pytest

from lubrication.stokes_exact import stokes_exact_resistance  # noqa: F401  (sign conventions below)
from lubrication.unsteady import (
    AnnulusMap,
    PrescribedMotion,
    Resolution,
    UnsteadySolver,
    default_resolution,
    run_prescribed,
)
from lubrication.unsteady.spectral import Grid

A, B = 0.008, 0.01125
DELTA = B - A
THETA = np.linspace(0.0, 2.0 * np.pi, 257)[:-1]


@pytest.mark.parametrize("omk", [1.0, 0.5, 0.01, 1e-4])
def test_walls_map_onto_the_two_circles(omk):
    """|w| = 1 goes to |zeta| = b and |w| = r0 to |zeta - z_A| = a, to rounding, at any eccentricity."""
    geo = AnnulusMap(A, B, (1.0 - omk) * DELTA * cmath.exp(0.7j))
    z = geo.zeta(geo.w(np.array([1.0, -1.0]), THETA))
    # rounding grows as 1/(1 - |p|) near contact
    assert np.max(np.abs(np.abs(z[0]) - B)) < 2e-14 * B
    assert np.max(np.abs(np.abs(z[1] - geo.z_a) - A)) < 4e-14 * A
    # the limit points of the circles are the images of w = 0 and w = infinity
    p_pt, q_pt = B * geo.p, B / np.conj(geo.p) if geo.p != 0 else math.inf
    if geo.p != 0:
        assert abs(abs(p_pt) * abs(q_pt) - B * B) < 1e-13 * B * B
        assert abs(abs(p_pt - geo.z_a) * abs(q_pt - geo.z_a) - A * A) < 1e-11 * A * A


def test_map_is_regular_through_the_concentric_position():
    """p -> 0 linearly in z_A (slope b/(b^2 - a^2)), r0 -> a/b, and the map is b w at eps = 0."""
    for eps in (1e-3 * DELTA, 1e-6 * DELTA, 1e-9 * DELTA):
        geo = AnnulusMap(A, B, eps * cmath.exp(0.3j))
        slope = B / (B * B - A * A)
        assert abs(geo.p / geo.z_a - slope) < (2.0 * (eps / DELTA) ** 2 + 1e-15) * slope
        assert abs(geo.r0 - A / B) < 2.0 * (eps / DELTA) ** 2 + 1e-15
    geo = AnnulusMap(A, B, 0j)
    assert geo.p == 0 and abs(geo.r0 - A / B) < 1e-15
    w = geo.w(np.array([0.3]), THETA)
    assert np.allclose(geo.zeta(w), B * w, rtol=1e-15, atol=0)


@pytest.mark.parametrize("omk", [0.5, 0.1, 0.01])
def test_metric_is_a_trigonometric_polynomial_of_degree_two(omk):
    """g = 1/|d zeta/d sigma|^2: five Fourier coefficients; the FFT of the directly evaluated g has nothing beyond |k| = 2."""
    geo = AnnulusMap(A, B, (1.0 - omk) * DELTA * cmath.exp(-1.1j))
    x = np.array([1.0, 0.2, -1.0])
    n = 64
    theta = 2.0 * np.pi * np.arange(n) / n
    direct = geo.metric(geo.w(x, theta))
    coef = np.fft.fft(direct, axis=1) / n
    big = np.abs(coef).max()
    # rounding of the direct formula (1 + conj(p) w cancels in the wide gap) bounds what is left
    assert np.abs(coef[:, 3:n - 2]).max() < 1e-13 * big
    g = geo.metric_coefficients(x)
    for m in range(-2, 3):
        assert np.allclose(coef[:, m % n], g[m + 2], rtol=0, atol=1e-13 * big)


@pytest.mark.parametrize("omk", [0.7, 0.05])
def test_wall_series_are_the_fourier_coefficients(omk):
    geo = AnnulusMap(A, B, (1.0 - omk) * DELTA * cmath.exp(2.0j))
    n = 512
    series = geo.wall_series(n - 1)
    theta = 2.0 * np.pi * np.arange(n) / n
    w_in = geo.w(np.array([-1.0]), theta)[0]
    w_out = geo.w(np.array([1.0]), theta)[0]
    for key, f in (("zeta_in", geo.zeta(w_in) - geo.z_a), ("dzeta_in", geo.dzeta_dsigma(w_in)),
                   ("abs_dzeta_in", np.abs(geo.dzeta_dsigma(w_in))), ("abs_dzeta_out", np.abs(geo.dzeta_dsigma(w_out)))):
        kk = np.arange(-(n // 2 - 1), n // 2)
        rebuilt = (series[key][None, :] * np.exp(1j * np.outer(theta, kk))).sum(axis=1)
        assert np.max(np.abs(rebuilt - f)) < 1e-13 * np.max(np.abs(f)), key


@pytest.mark.parametrize("omk", [1.0, 0.4, 0.02])
def test_frozen_field_seen_by_the_moving_grid(omk):
    """Geometric conservation: a field fixed in space, sampled at the moving grid points, changes
    at the rate x_t . grad f (the ALE term), with x_t the map's mesh velocity, to O(dt^2)."""
    rng = np.random.default_rng(3)
    u = complex(*rng.normal(size=2)) * 0.01
    z0 = (1.0 - omk) * DELTA * cmath.exp(0.4j)
    x = np.cos(np.pi * np.arange(9) / 8)
    theta = 2.0 * np.pi * np.arange(16) / 16
    k = np.array([3.0 / B, -2.0 / B])

    def f(z):
        return np.sin(k[0] * z.real) * np.cos(k[1] * z.imag) + (z.real * z.imag) / B**2

    def grad(z):
        gx = k[0] * np.cos(k[0] * z.real) * np.cos(k[1] * z.imag) + z.imag / B**2
        gz = -k[1] * np.sin(k[0] * z.real) * np.sin(k[1] * z.imag) + z.real / B**2
        return gx + 1j * gz

    geo = AnnulusMap(A, B, z0)
    zeta = geo.zeta(geo.w(x, theta))
    mu = geo.mesh_velocity(u, x, theta)
    xt = mu * geo.dzeta_dsigma(geo.w(x, theta))  # mesh velocity in the plane
    ale = (np.conj(xt) * grad(zeta)).real
    errs = []
    steps = (1e-4, 5e-5, 2.5e-5)
    for h in steps:
        fp = f(AnnulusMap(A, B, z0 + u * h).zeta(AnnulusMap(A, B, z0 + u * h).w(x, theta)))
        fm = f(AnnulusMap(A, B, z0 - u * h).zeta(AnnulusMap(A, B, z0 - u * h).w(x, theta)))
        errs.append(np.max(np.abs((fp - fm) / (2 * h) - ale)) / np.max(np.abs(ale)))
    order = np.polyfit(np.log(steps), np.log(errs), 1)[0]
    # central differences: O(h^2); rounding (1e-16 / h relative) is far below at these steps
    assert errs[-1] < 1e-4
    assert abs(order - 2.0) < 0.1


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"a": 0.0, "b": 0.01}, "a must be in (0, inf)"),
    ({"a": 0.01, "b": 0.008}, "b must be greater than a"),
    ({"a": 0.008, "b": 0.01, "z_a": 0.002}, "eps must be in [0, 0.002)"),
    ({"a": 0.008, "b": 0.01, "z_a": complex(math.nan, 0.0)}, "x_a must be a finite number"),
])
def test_map_refuses_bad_geometry(kwargs, words):
    with pytest.raises(ValueError) as err:
        AnnulusMap(**kwargs)
    assert words in str(err.value)


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"nu": 0.0}, "nu must be in (0, inf)"),
    ({"rho": -1.0}, "rho must be in (0, inf)"),
    ({"nu": math.inf}, "nu must be a finite number"),
])
def test_solver_refuses_bad_fluid(kwargs, words):
    args = {"a": A, "b": B, "nu": 2e-4, "rho": 1000.0, **kwargs}
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        UnsteadySolver(**args)


def test_resolution_refuses_too_few_points():
    with pytest.raises(ValueError, match="n_r must be an integer >= 4"):
        Resolution(32, 3)


def test_run_refuses_a_gap_below_the_reach_and_names_it():
    """A motion that closes the gap below the solver's reach is refused before it starts, naming 1 - kappa and when."""
    motion = PrescribedMotion(x_a=(0.0, DELTA * (1.0 - 1e-7), 5.0, 0.0))
    with pytest.raises(ValueError, match=r"one_minus_kappa = 1 - kappa must stay at least 1e-05 .* reaches 1e-07 .* at t = 0.942"):
        run_prescribed(A, B, 2e-4, 1000.0, motion, t_end=1.0)
    with pytest.raises(ValueError, match="t_end must be in"):
        run_prescribed(A, B, 2e-4, 1000.0, PrescribedMotion(), t_end=-1.0)


def test_grid_transforms_round_trip(rng):
    grid = Grid(24, 6)
    f = rng.normal(size=(grid.n_modes, 6)) + 1j * rng.normal(size=(grid.n_modes, 6))
    f = grid.symmetrise(f)
    assert np.allclose(grid.to_spectral(grid.to_physical(f)), f, atol=1e-14)


@pytest.mark.parametrize("omk", [1.0, 0.5, 0.05])
def test_stream_weight_is_a_trigonometric_polynomial_of_degree_one(omk):
    """H = |1 + conj(p) w|^2/|w|: its coefficients H_0, conj(p), p rebuild the directly evaluated H."""
    geo = AnnulusMap(A, B, (1.0 - omk) * DELTA * cmath.exp(0.9j))
    x = np.array([1.0, 0.3, -1.0])
    direct = geo.stream_weight(geo.w(x, THETA))
    h, h_s, h_t = geo.stream_weight_fields(x, THETA)
    assert np.max(np.abs(h - direct)) < 1e-13 * np.max(direct)
    # derivatives against central differences of the direct formula (O(d^2) ~ 1e-10)
    d = 1e-5
    w_x = geo.w(x, THETA)
    ds = (geo.stream_weight(w_x * math.exp(d)) - geo.stream_weight(w_x * math.exp(-d))) / (2 * d)
    dt = (geo.stream_weight(w_x * cmath.exp(1j * d)) - geo.stream_weight(w_x * cmath.exp(-1j * d))) / (2 * d)
    assert np.max(np.abs(h_s - ds)) < 1e-8 * np.max(direct)
    assert np.max(np.abs(h_t - dt)) < 1e-8 * np.max(direct)


@pytest.mark.parametrize("omk", [1.0, 0.5, 0.2])
def test_laplacian_through_the_weighted_stream_function(omk):
    """Lap_zeta psi from the coefficients of Psi = H psi (the tridiagonal form) against the closed form,
    psi = |zeta|^4 + Re(zeta^3) - x z^2 (Lap = 16 |zeta|^2 - 2 x), lengths in units of b. Psi is
    analytic, its coefficients below rounding at |k| = 47 (beta >= 0.6 here); what is left is the
    rounding of the Chebyshev second derivative, eps n_r^4 (2/tau)^2 |Psi| ~ 1e-9 (measured 2e-11 to
    7e-10, as for the plain metric Laplacian of psi)."""
    from lubrication.unsteady.operator import ImplicitOperator

    geo = AnnulusMap(A / B, 1.0, (1.0 - omk) * DELTA / B * cmath.exp(-0.6j))
    grid = Grid(96, 16)
    zeta = geo.zeta(geo.w(grid.x, grid.theta))
    psi = np.abs(zeta) ** 4 + (zeta**3).real - zeta.real * zeta.imag**2
    exact = 16.0 * np.abs(zeta) ** 2 - 2.0 * zeta.real
    h = geo.stream_weight_fields(grid.x, grid.theta)[0]
    op = ImplicitOperator(grid, geo, 1.0, 0.0)
    lap = grid.to_physical(op.stream_laplacian(grid.to_spectral(h * psi)), grid.n_theta)
    rounding = np.finfo(float).eps * grid.n_r**4 * (2.0 / geo.tau) ** 2
    assert np.max(np.abs(lap - exact)) < 10.0 * rounding * np.max(np.abs(exact))


@pytest.mark.parametrize("omk", [1.0, 0.3, 1e-4])
def test_assembled_operator_is_the_applied_one(rng, omk):
    """The banded matrix (blocks) and the matrix-free rows (matvec) are the same operator: the
    defect correction relies on it. Random complex coefficients, 12 x 6 points."""
    from lubrication.unsteady.operator import ImplicitOperator, pack

    geo = AnnulusMap(A / B, 1.0, (1.0 - omk) * DELTA / B * cmath.exp(2.2j))
    grid = Grid(12, 6)
    op = ImplicitOperator(grid, geo, 0.7, 3.0)
    shape = (grid.n_modes, grid.n_r)
    psi = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    omega = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    rows = pack(*op.matvec(psi, omega))
    product = op.dense() @ pack(psi, omega)
    assert np.max(np.abs(rows - product)) < 1e-13 * np.max(np.abs(product))
    # and the banded LU solves it, backward stably: each row's residual is at rounding of its terms
    dense = op.dense()
    x = op.factorise().solve(rows)
    size = np.abs(dense) @ np.abs(x) + np.abs(rows)
    assert np.max(np.abs(dense @ x - rows) / size) < 1e-13


@pytest.mark.parametrize("omk", [0.5, 1e-5])
def test_equilibrated_operator_is_well_conditioned_near_contact(omk):
    """The scaled operator's condition number stays far from 1/eps to the reach: the stream function is
    measured in units of the vorticity times its second-derivative coefficient (operator.py). Measured at
    16 x 12 points: 1.2e4 (kappa = 0.5) and 2.6e7 (1 - kappa = 1e-5); from unit scales 2.3e5 and 4e14."""
    from lubrication.unsteady.operator import ImplicitOperator, _equilibrate
    from lubrication.unsteady.system import one_blas_thread

    geo = AnnulusMap(A / B, 1.0, (1.0 - omk) * DELTA / B * 1j)
    grid = Grid(16, 12)
    op = ImplicitOperator(grid, geo, 2e-4 / B**2, 1.0)
    blocks = op.blocks()
    _equilibrate(blocks, op.initial_column_scale())
    s = 2 * grid.n_r
    dense = np.zeros((grid.n_modes * s, grid.n_modes * s), dtype=complex)
    for kb in range(grid.n_modes):
        for d in range(-2, 3):
            if 0 <= kb + d < grid.n_modes:
                dense[kb * s:(kb + 1) * s, (kb + d) * s:(kb + d + 1) * s] = blocks[kb, d + 2]
    with one_blas_thread():  # a small dense SVD: threads only contend
        assert np.linalg.cond(dense) < 1e9


def test_default_resolution_resolves_the_wide_gap_or_leaves_it_out():
    """beta K >= 4 where that takes at most 512 points; the least grid (16) beyond and for quasi-steady flow."""
    from lubrication.unsteady.resolution import FOURIER_DECAY_MODES, MAX_DEFAULT_N_THETA, MIN_N_THETA

    assert default_resolution(AnnulusMap(A, B, 0j)).n_theta == MIN_N_THETA
    for kappa in (0.5, 0.9, 0.99, 0.999):
        geo = AnnulusMap(A, B, kappa * DELTA * 1j)
        res = default_resolution(geo)
        k_max = (res.n_theta - 1) // 2
        assert geo.beta * k_max >= FOURIER_DECAY_MODES and MIN_N_THETA <= res.n_theta <= MAX_DEFAULT_N_THETA
        assert default_resolution(geo, quasi_steady=True).n_theta == MIN_N_THETA
    near = AnnulusMap(A, B, (1.0 - 1e-4) * DELTA * 1j)
    assert 2 * FOURIER_DECAY_MODES / near.beta > MAX_DEFAULT_N_THETA
    assert default_resolution(near, 12) == Resolution(MIN_N_THETA, 12)
