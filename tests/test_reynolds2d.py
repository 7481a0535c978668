"""The Reynolds solver on (theta, z): limits, an independent spectral solution, convergence orders, symmetries.

Expected accuracy (lubrication.reynolds2d): the scheme is second order in the
theta cells and in the axial cells, O(dpsi^2) + O(ds^2) on smooth maps, and the
Richardson combination of a grid and its half is fourth order. Sealed ends
reproduce the one-dimensional solver to rounding. The independent reference
for an open finite bearing is a spectral solution of the same equation: the
exact axial modes cos((2j+1) pi z/L) (h does not depend on z) and, per mode,
Fourier collocation in theta, plus the sum of the tail of the mode series from
its large-mode expansion (_spectral_reference).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import zeta as hurwitz_zeta

from lubrication import (
    Annulus,
    Fluid,
    GapProfile,
    Motion,
    closed_form_forces,
    reynolds_forces,
)
from lubrication.finite_length import short_bearing_forces, small_eccentricity_factor
from lubrication.reynolds import _theta_of_psi, psi_rule
from lubrication.reynolds2d import (
    NARROW_SCALE,
    GapProfile2D,
    _sommerfeld_angle,
    _theta_rule,
    axial_grid,
    default_clustering,
    grading,
    grid_parameter,
    reynolds2d_forces,
    reynolds2d_pressure,
    tilted_gap,
)
from lubrication.reynolds_kernels import THIN, film_forces

from apparatus import A, B, L, OIL

UNIT = Fluid(nu=1.0, rho=1.0)
MOTIONS = {
    "squeeze": Motion(eps_dot=1e-4),
    "inner": Motion(omega_a=1.0),
    "outer": Motion(omega_b=1.0),
    "combined": Motion(eps_dot=-3e-5, chi_dot=0.4, omega_a=1.5, omega_b=-0.7),
}


def _rel(x, y):
    return abs(x - y) / abs(y)


def _fourier_derivative(m):
    """Periodic spectral differentiation matrix on m equispaced points (m even)."""
    i, k = np.meshgrid(np.arange(m), np.arange(m), indexing="ij")
    diff = i - k
    with np.errstate(divide="ignore"):
        d = 0.5 * (-1.0) ** diff / np.tan(diff * math.pi / m)
    d[diff == 0] = 0.0
    return d


def _spectral_reference(kappa, length_over_a, eps_dot, w, m=128, modes=30):
    """(f_eps, f_chi, Poiseuille torque) of the thin gap, a = delta = mu = 1, open ends, whole length.

    phi = p/(12 mu a) = sum_j psi_j(theta) cos(alpha_j z), alpha_j = (2j+1) pi/L, with
    1 = sum_j c_j cos(alpha_j z), c_j = 4 (-1)^j/((2j+1) pi); each psi_j solves
    (h^3 psi')' - alpha_j^2 h^3 psi = c_j R(theta), R = (U/2) h_theta + a h_t, by
    Fourier collocation. int cos(alpha_j z) dz = 2 (-1)^j/alpha_j, so a functional G
    of psi sums to L sum_j omega_j G[psi_j / c_j], omega_j = 8/((2j+1) pi)^2. For
    large alpha, psi/c = R1/alpha^2 + R2/alpha^4 + ..., R1 = -R/h^3,
    R2 = (h^3 R1')'/h^3: the tail j >= modes is summed with Hurwitz zeta values.
    """
    theta = -math.pi + 2.0 * math.pi * np.arange(m) / m
    h = 1.0 - kappa * np.cos(theta)
    load = 0.5 * w * kappa * np.sin(theta) - eps_dot * np.cos(theta)
    d = _fourier_derivative(m)
    cube = np.diag(h**3)
    stiffness = d @ cube @ d
    step = 2.0 * math.pi / m

    def functionals(psi):
        return np.array([-step * np.sum(psi * np.cos(theta)), -step * np.sum(psi * np.sin(theta)),
                         -6.0 * step * np.sum((d @ psi) * h)])

    total = np.zeros(3)
    for j in range(modes):
        alpha_sq = ((2 * j + 1) * math.pi / length_over_a) ** 2
        psi = np.linalg.solve(stiffness - alpha_sq * cube, load)
        total += 8.0 / ((2 * j + 1) * math.pi) ** 2 * functionals(psi)
    r1 = -load / h**3
    r2 = (d @ (h**3 * (d @ r1))) / h**3
    for power, r in ((1, r1), (2, r2)):
        tail = 2.0 ** (-2 - 2 * power) * hurwitz_zeta(2 + 2 * power, modes + 0.5)
        total += 8.0 / math.pi**2 * (length_over_a / math.pi) ** (2 * power) * tail * functionals(r)
    return 12.0 * length_over_a * total[0], 12.0 * length_over_a * total[1], length_over_a * total[2]


def _unit_annulus(kappa, length_over_a):
    return Annulus.from_kappa(1.0, 2.0, kappa, length_over_a)


def _couette_torque(annulus, motion):
    zeta = math.sqrt(annulus.one_minus_kappa * (1.0 + annulus.kappa))
    return UNIT.mu * annulus.a**3 * annulus.length * (motion.w_b - motion.w_a) * 2.0 * math.pi / (
        annulus.delta * zeta)


# ---------------------------------------------------------------- the independent spectral solution

@pytest.mark.parametrize("kappa", [0.5, 0.9])
@pytest.mark.parametrize("kind", ["squeeze", "rotation"])
def test_open_bearing_matches_the_spectral_solution(kappa, kind):
    length_over_a = 4.0
    eps_dot, w = (1.0, 0.0) if kind == "squeeze" else (0.0, 1.0)
    ref = _spectral_reference(kappa, length_over_a, eps_dot, w)
    annulus = _unit_annulus(kappa, length_over_a)
    motion = Motion(eps_dot=eps_dot, omega_a=w)
    got = reynolds2d_forces(annulus, motion, UNIT, n=256, n_axial=128, extrapolate=True)
    # after extrapolation: measured 2.6e-7 or less (kappa = 0.9, squeeze)
    if kind == "squeeze":
        assert _rel(got.f_eps, ref[0]) < 1e-6
    else:
        assert _rel(got.f_chi, ref[1]) < 1e-6
        assert _rel(got.T_a - _couette_torque(annulus, motion), ref[2]) < 1e-6


@pytest.mark.parametrize("direction", ["theta", "z"])
def test_second_order_in_each_direction(direction):
    """Log-log slope of the error against the spectral solution: -2 +- 0.1 in either direction."""
    kappa, length_over_a = 0.9, 4.0
    ref = _spectral_reference(kappa, length_over_a, 0.0, 1.0)[1]
    annulus = _unit_annulus(kappa, length_over_a)
    sizes = (16, 32, 64)
    if direction == "theta":  # the axial error at 512 cells is below 2e-6, 1/100 of the smallest here
        errors = [_rel(reynolds2d_forces(annulus, Motion(omega_a=1.0), UNIT, n=s, n_axial=512).f_chi, ref)
                  for s in sizes]
    else:
        errors = [_rel(reynolds2d_forces(annulus, Motion(omega_a=1.0), UNIT, n=1024, n_axial=s).f_chi, ref)
                  for s in sizes]
    slope = np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    assert abs(slope + 2.0) < 0.1


@pytest.mark.parametrize("direction", ["theta", "z"])
def test_richardson_is_fourth_order_in_each_direction(direction):
    """At kappa = 0 the squeeze factor is 1 - tanh(l/2)/(l/2) exactly (lubrication.finite_length).

    The other direction is resolved far beyond (its error below 3e-8); the
    Richardson combination of each size and its half has slope -4 +- 0.2.
    """
    length_over_a = 1.0
    annulus = Annulus.from_kappa(A, B, 0.0, length_over_a * A)
    exact = small_eccentricity_factor(length_over_a) * closed_form_forces(annulus, Motion(eps_dot=1.0), OIL).f_eps

    def error(size):
        grid = {"n": size, "n_axial": 2048} if direction == "theta" else {"n": 4096, "n_axial": size}
        return reynolds2d_forces(annulus, Motion(eps_dot=1.0), OIL, **grid).f_eps / exact - 1.0

    sizes = np.array([16, 32, 64, 128]) if direction == "theta" else np.array([8, 16, 32, 64])
    plain = np.array([error(s) for s in sizes])
    richardson = np.abs((4.0 * plain[1:] - plain[:-1]) / 3.0)
    assert abs(np.polyfit(np.log(sizes), np.log(np.abs(plain)), 1)[0] + 2.0) < 0.1
    assert abs(np.polyfit(np.log(sizes[1:]), np.log(richardson), 1)[0] + 4.0) < 0.2


def test_extrapolated_error_at_the_apparatus():
    """Both directions at once, L/a = 12.9, kappa = 0: measured 5e-7 at (128, 64), 5e-8 at (256, 128)."""
    annulus = Annulus.from_kappa(A, B, 0.0, L)
    exact = small_eccentricity_factor(L / A) * closed_form_forces(annulus, Motion(eps_dot=1.0), OIL).f_eps
    got = reynolds2d_forces(annulus, Motion(eps_dot=1.0), OIL, n=128, n_axial=64, extrapolate=True).f_eps
    assert _rel(got, exact) < 1e-6


# ---------------------------------------------------------------- limits

@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.99, 1 - 1e-6])
@pytest.mark.parametrize("motion", MOTIONS.values(), ids=MOTIONS.keys())
@pytest.mark.parametrize("length", [0.1 * A, L, 100 * L])
def test_sealed_ends_give_the_one_dimensional_solution(kappa, motion, length):
    annulus = Annulus.from_kappa(A, B, kappa, length)
    one_d = np.array(reynolds_forces(annulus, motion, OIL, n=64).as_tuple())
    two_d = np.array(reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=8, ends="sealed").as_tuple())
    scale = np.abs(one_d).max()  # the zero entries (by symmetry) are rounding against the others
    assert np.all(np.abs(two_d - one_d) <= 1e-12 * scale)


@pytest.mark.parametrize("kappa", [0.5, 0.99])
@pytest.mark.parametrize("motion", MOTIONS.values(), ids=MOTIONS.keys())
def test_sealed_ends_on_the_clustered_grid_are_the_one_dimensional_scheme(kappa, motion):
    """On any theta grid the sealed solution is that grid's one-dimensional solution."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    kappa_g, omk_g = grid_parameter(kappa, annulus.one_minus_kappa, 0.5)
    rule, _ = psi_rule(64, 2)
    empty = np.empty(0)
    ref = np.array(film_forces(THIN, A, B, OIL.mu, L, kappa, annulus.one_minus_kappa, motion.eps_dot,
                               motion.w_a, motion.w_b, kappa_g, omk_g, *rule, 2, empty, empty, 1.0, 0.0, empty))
    got = np.array(reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=8, ends="sealed",
                                     clustering=0.5).as_tuple())
    assert np.all(np.abs(got - ref) <= 1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("kappa", [0.3, 0.9])
def test_sealed_ends_through_the_sparse_solver(kappa):
    """A z-independent gap given as h(theta, z) takes the general sparse path: its solution is still 1-D."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    delta, eps, eps_dot = annulus.delta, annulus.eps, 2e-5
    one = GapProfile(h=lambda t: delta - eps * np.cos(t), h_dot=lambda t: -eps_dot * np.cos(t))
    two = GapProfile2D(h=lambda t, z: delta - eps * np.cos(t) + 0.0 * z,
                       h_dot=lambda t, z: -eps_dot * np.cos(t) + 0.0 * z)
    motion = Motion(omega_a=0.8, omega_b=-0.3)
    ref = np.array(reynolds_forces(annulus, motion, OIL, n=64, profile=one).as_tuple())
    got = np.array(reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=16, ends="sealed",
                                     profile=two).as_tuple())
    assert np.all(np.abs(got - ref) <= 1e-10 * np.abs(ref).max())


def test_sparse_and_modal_solvers_agree():
    """One discrete system, two solvers: z-modes for a 1-D user gap, sparse LU for the same gap as h(theta, z)."""
    annulus = Annulus.from_kappa(A, B, 0.7, L)
    delta, eps = annulus.delta, annulus.eps
    one = GapProfile(h=lambda t: delta - eps * np.cos(t) + 0.1 * delta * np.sin(2 * t),
                     h_dot=lambda t: -2e-5 * np.cos(t))
    two = GapProfile2D(h=lambda t, z: one.h(t) + 0.0 * z, h_dot=lambda t, z: one.h_dot(t) + 0.0 * z)
    motion = Motion(omega_a=0.8, omega_b=-0.3)
    modal = np.array(reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=32, profile=one).as_tuple())
    sparse = np.array(reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=32, profile=two).as_tuple())
    assert np.all(np.abs(sparse - modal) <= 1e-10 * np.abs(modal).max())


def test_user_gap_is_the_thin_gap():
    """The thin gap as a user profile: rotation to rounding, the squeeze to its tabulated flux's O(dpsi^4)."""
    annulus = Annulus.from_kappa(A, B, 0.7, L)
    delta, eps = annulus.delta, annulus.eps
    still = GapProfile2D(h=lambda t, z: delta - eps * np.cos(t) + 0.0 * z)
    rotation = Motion(omega_a=0.8, omega_b=-0.3)
    thin = np.array(reynolds2d_forces(annulus, rotation, OIL, n=64, n_axial=32).as_tuple())
    user = np.array(reynolds2d_forces(annulus, rotation, OIL, n=64, n_axial=32, profile=still).as_tuple())
    assert np.all(np.abs(user - thin) <= 1e-10 * np.abs(thin).max())
    moving = GapProfile2D(h=still.h, h_dot=lambda t, z: -2e-5 * np.cos(t) + 0.0 * z)
    thin = reynolds2d_forces(annulus, Motion(eps_dot=2e-5), OIL, n=64, n_axial=32).f_eps
    user = reynolds2d_forces(annulus, Motion(), OIL, n=64, n_axial=32, profile=moving).f_eps
    assert user == pytest.approx(thin, rel=1e-7)  # measured 1.6e-8


@pytest.mark.parametrize("kappa", [0.0, 0.6, 0.99])
@pytest.mark.parametrize("motion", MOTIONS.values(), ids=MOTIONS.keys())
def test_long_bearing_limit_is_the_one_dimensional_solver(kappa, motion):
    """L/a = 1e12: the end corrections are O(a/L) = 1e-12; the modal solve must not lose it to rounding."""
    annulus = Annulus.from_kappa(A, B, kappa, 1e12 * A)
    one_d = np.array(reynolds_forces(annulus, motion, OIL, n=64).as_tuple())
    two_d = np.array(reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=32).as_tuple())
    assert np.all(np.abs(two_d - one_d) <= 1e-10 * np.abs(one_d).max())


@pytest.mark.parametrize("kappa", [0.3, 0.9])
def test_long_bearing_ends_remove_a_fixed_amount(kappa):
    """1 - F ~ C a/L for L >> a: slope -1 +- 0.02 over L/a from 25 to 200."""
    lengths = np.array([25.0, 50.0, 100.0, 200.0])
    deficit = []
    for length_over_a in lengths:
        annulus = Annulus.from_kappa(A, B, kappa, length_over_a * A)
        inf = reynolds_forces(annulus, Motion(omega_a=1.0), OIL).f_chi
        fin = reynolds2d_forces(annulus, Motion(omega_a=1.0), OIL, n=128, n_axial=64, extrapolate=True).f_chi
        deficit.append(1.0 - fin / inf)
    assert abs(np.polyfit(np.log(lengths), np.log(deficit), 1)[0] + 1.0) < 0.02


@pytest.mark.parametrize("kappa", [0.0, 0.4, 0.8])
@pytest.mark.parametrize("motion", MOTIONS.values(), ids=MOTIONS.keys())
def test_short_bearing_limit(kappa, motion):
    """L/a = 0.2: Ocvirk's closed form to O((L/(a zeta))^2), measured 0.15 (L/(a zeta))^2 or less.

    The by-parts rule's intra-cell flux has an O(dpsi^4 (a/L)^2) error in this
    limit (lubrication.reynolds2d), 1e-3 at n = 256 and L/a = 0.2: shorter
    bearings need finer cells.
    """
    length_over_a = 0.2
    annulus = Annulus.from_kappa(A, B, kappa, length_over_a * A)
    ref = np.array(short_bearing_forces(annulus, motion, OIL).as_tuple())
    got = np.array(reynolds2d_forces(annulus, motion, OIL, n=256, n_axial=16, extrapolate=True).as_tuple())
    bound = 0.3 * length_over_a**2 / (1.0 - kappa**2)
    assert np.all(np.abs(got - ref) <= bound * np.abs(ref) + 1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("kind", ["squeeze", "rotation"])
def test_short_bearing_correction_is_second_order(kind):
    """F / F_short - 1 ~ (L/(a zeta))^2: slope 2 +- 0.05 over L/a = 0.2 .. 0.45."""
    kappa = 0.5
    lengths = np.array([0.2, 0.3, 0.45])
    motion = Motion(eps_dot=1.0) if kind == "squeeze" else Motion(omega_a=1.0)
    index = 0 if kind == "squeeze" else 1
    dev = []
    for length_over_a in lengths:
        annulus = Annulus.from_kappa(A, B, kappa, length_over_a * A)
        ref = short_bearing_forces(annulus, motion, OIL).as_tuple()[index]
        got = reynolds2d_forces(annulus, motion, OIL, n=256, n_axial=16, extrapolate=True).as_tuple()[index]
        dev.append(abs(got / ref - 1.0))
    assert abs(np.polyfit(np.log(lengths), np.log(dev), 1)[0] - 2.0) < 0.05


def test_short_bearing_integrals():
    """The two integrals behind the closed form, by quadrature."""
    for kappa in (0.3, 0.9):
        zeta = math.sqrt(1 - kappa**2)
        sin2 = quad(lambda t, k=kappa: math.sin(t) ** 2 / (1 - k * math.cos(t)) ** 3, 0, 2 * math.pi, limit=200)[0]
        cos2 = quad(lambda t, k=kappa: math.cos(t) ** 2 / (1 - k * math.cos(t)) ** 3, 0, 2 * math.pi, limit=200)[0]
        assert sin2 == pytest.approx(math.pi / zeta**3, rel=1e-10)
        assert cos2 == pytest.approx(math.pi * (1 + 2 * kappa**2) / zeta**5, rel=1e-10)


@pytest.mark.parametrize("length_over_a", [2.0, 4.0, L / A, 60.0])
def test_small_eccentricity_closed_form(length_over_a):
    """kappa -> 0: both factors are 1 - tanh(l/2)/(l/2); the squeeze exactly at kappa = 0."""
    exact = small_eccentricity_factor(length_over_a)
    for kappa, motion, index in ((0.0, Motion(eps_dot=1.0), 0), (1e-4, Motion(omega_a=1.0), 1)):
        annulus = Annulus.from_kappa(A, B, kappa, length_over_a * A)
        inf = closed_form_forces(annulus, motion, OIL).as_tuple()[index]
        fin = reynolds2d_forces(annulus, motion, OIL, n=128, n_axial=64, extrapolate=True).as_tuple()[index]
        # extrapolated: measured 1e-6 or less at (128, 64); kappa = 1e-4 adds O(kappa^2)
        assert abs(fin / inf - exact) < 2e-6


# ---------------------------------------------------------------- identities and symmetries

@pytest.mark.parametrize("kappa", [0.2, 0.9, 0.999])
def test_poiseuille_torque_is_minus_half_eps_f_chi(kappa):
    """Thin gap, any length: -(a/2) int oint h p_theta = (a/2) int oint h_theta p = -(eps/2) f_chi."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    motion = Motion(omega_a=1.3, omega_b=0.4)
    f = reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=32)
    zeta = math.sqrt(annulus.one_minus_kappa * (1 + kappa))
    couette = OIL.mu * A**3 * L * (motion.w_b - motion.w_a) * 2 * math.pi / (annulus.delta * zeta)
    assert f.T_a - couette == pytest.approx(-0.5 * annulus.eps * f.f_chi, rel=1e-11)


@pytest.mark.parametrize("kappa", [0.3, 0.95])
def test_linear_in_the_velocities(kappa, rng):
    annulus = Annulus.from_kappa(A, B, kappa, L)
    units = [np.array(reynolds2d_forces(annulus, m, OIL, n=32, n_axial=16).as_tuple())
             for m in (Motion(eps_dot=1.0), Motion(omega_a=1.0), Motion(omega_b=1.0))]
    for _ in range(3):
        eps_dot, chi_dot, omega_a, omega_b = rng.normal(size=4) * (1e-4, 1.0, 1.0, 1.0)
        motion = Motion(eps_dot=eps_dot, chi_dot=chi_dot, omega_a=omega_a, omega_b=omega_b)
        got = np.array(reynolds2d_forces(annulus, motion, OIL, n=32, n_axial=16).as_tuple())
        want = eps_dot * units[0] + motion.w_a * units[1] + motion.w_b * units[2]
        assert np.all(np.abs(got - want) <= 1e-12 * np.abs(want).max())


def test_rigid_rotation_carries_no_load():
    annulus = Annulus.from_kappa(A, B, 0.7, L)
    f = reynolds2d_forces(annulus, Motion(chi_dot=2.0, omega_a=2.0, omega_b=2.0), OIL)
    assert f.as_tuple() == (0.0, 0.0, 0.0)


def test_pressure_is_mirror_symmetric_and_theta_antisymmetric():
    """Rotation of the thin gap: p(theta, z) = p(theta, -z) and p(-theta, z) = -p(theta, z) (p_end = 0)."""
    annulus = Annulus.from_kappa(A, B, 0.6, L)
    film = reynolds2d_pressure(annulus, Motion(omega_a=1.0), OIL, n=64, n_axial=32, clustering=0.0)
    scale = np.abs(film.p).max()
    assert np.allclose(film.p, film.p[::-1], atol=1e-13 * scale, rtol=0)
    assert np.allclose(film.z, -film.z[::-1], atol=1e-15, rtol=0)
    # nodes at psi_j = -pi + 2 pi j/N: theta -> -theta maps node j to node N - j
    mirrored = film.p[:, (-np.arange(64)) % 64]
    assert np.allclose(mirrored, -film.p, atol=1e-12 * scale, rtol=0)
    assert np.all(film.p[[0, -1]] == 0.0)  # the open ends hold p_end
    # the lines integrate to the totals (trapezoid rule)
    assert np.trapezoid(film.f_chi_per_length, film.z) == pytest.approx(film.forces.f_chi, rel=1e-12)


def test_tilt_one_way_or_the_other_is_the_mirror_image():
    """z -> -z maps a tilt to its opposite: same forces, mirrored pressure."""
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    tilt = 0.3 * annulus.delta / L
    up = reynolds2d_pressure(annulus, Motion(omega_a=1.0), OIL, n=32, n_axial=16, profile=tilted_gap(annulus, tilt))
    down = reynolds2d_pressure(annulus, Motion(omega_a=1.0), OIL, n=32, n_axial=16,
                               profile=tilted_gap(annulus, -tilt))
    scale = np.abs(up.forces.as_tuple()).max()
    assert np.allclose(up.forces.as_tuple(), down.forces.as_tuple(), rtol=0, atol=1e-11 * scale)
    assert np.allclose(up.p, down.p[::-1], rtol=0, atol=1e-11 * np.abs(up.p).max())


def test_small_tilt_changes_the_forces_at_second_order():
    """The force is even in the tilt (the mirror image above): the change from a tilt t is O(t^2)."""
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    base = reynolds2d_forces(annulus, Motion(omega_a=1.0), OIL, n=32, n_axial=16,
                             profile=tilted_gap(annulus, 0.0)).f_chi
    changes = []
    tilts = np.array([0.05, 0.1, 0.2]) * annulus.delta / L
    for t in tilts:
        f = reynolds2d_forces(annulus, Motion(omega_a=1.0), OIL, n=32, n_axial=16, profile=tilted_gap(annulus, t))
        changes.append(abs(f.f_chi - base))
    assert abs(np.polyfit(np.log(tilts), np.log(changes), 1)[0] - 2.0) < 0.05


def test_untilted_profile_is_the_thin_gap():
    """Rotation to rounding; the squeeze to its tabulated flux's O(dpsi^4) (measured 4e-7 at N = 32)."""
    annulus = Annulus.from_kappa(A, B, 0.8, L)
    rotation = Motion(omega_a=1.0, omega_b=0.3)
    thin = np.array(reynolds2d_forces(annulus, rotation, OIL, n=32, n_axial=16).as_tuple())
    tilted = np.array(reynolds2d_forces(annulus, rotation, OIL, n=32, n_axial=16,
                                        profile=tilted_gap(annulus, 0.0)).as_tuple())
    assert np.all(np.abs(tilted - thin) <= 1e-10 * np.abs(thin).max())
    thin = reynolds2d_forces(annulus, Motion(eps_dot=1e-5), OIL, n=32, n_axial=16).f_eps
    tilted = reynolds2d_forces(annulus, Motion(), OIL, n=32, n_axial=16,
                               profile=tilted_gap(annulus, 0.0, eps_dot=1e-5)).f_eps
    assert tilted == pytest.approx(thin, rel=2e-6)


# ---------------------------------------------------------------- near contact and the grid

def test_ends_matter_less_as_the_gap_closes():
    """Near contact the end layer is a zeta wide: 1 - F_eps ~ C zeta (slope 1 +- 0.02); the rotation's
    dipole reaches further, 1 - F_chi ~ zeta (A + B log(1/zeta)), so (1 - F_chi)/zeta grows by the same
    amount per halving of zeta (within 5 per cent; measured B log 2 = 0.058 at L/a = 12.9)."""
    zetas = np.array([0.04, 0.02, 0.01, 0.005])
    squeeze, rotation = [], []
    for zeta in zetas:
        annulus = Annulus(a=A, b=B, length=L, one_minus_kappa=zeta**2 / (1 + math.sqrt(1 - zeta**2)))
        for motion, index, out in ((Motion(eps_dot=1.0), 0, squeeze), (Motion(omega_a=1.0), 1, rotation)):
            inf = closed_form_forces(annulus, motion, OIL).as_tuple()[index]
            fin = reynolds2d_forces(annulus, motion, OIL, n=256, n_axial=32, extrapolate=True).as_tuple()[index]
            out.append(1.0 - fin / inf)
    assert abs(np.polyfit(np.log(zetas), np.log(squeeze), 1)[0] - 1.0) < 0.02
    steps = np.diff(np.array(rotation) / zetas)
    assert np.all(steps > 0) and np.ptp(steps) < 0.05 * steps.mean()


def test_finite_and_bounded_at_extreme_eccentricity():
    """1 - kappa = 1e-12: the deficit is O(zeta) = 1.4e-6 (1.8e-6 for the rotation, by its log); the graded
    grid's error at N = 64 was measured below 1e-6, so the factor must lie in (1 - 1e-5, 1)."""
    annulus = Annulus(a=A, b=B, length=L, one_minus_kappa=1e-12)
    for motion, index in ((Motion(eps_dot=1.0), 0), (Motion(omega_a=1.0), 1)):
        ratio = (reynolds2d_forces(annulus, motion, OIL, n=64, n_axial=16).as_tuple()[index]
                 / closed_form_forces(annulus, motion, OIL).as_tuple()[index])
        assert 1.0 - 1e-5 < ratio < 1.0


def _near_contact_factor(motion, index, **grid):
    annulus = Annulus(a=A, b=B, length=L, one_minus_kappa=1e-6)
    return (reynolds2d_forces(annulus, motion, OIL, **grid).as_tuple()[index]
            / closed_form_forces(annulus, motion, OIL).as_tuple()[index])


@pytest.mark.parametrize(("motion", "index"), [(Motion(eps_dot=1.0), 0), (Motion(omega_a=1.0), 1)],
                         ids=["squeeze", "rotation"])
def test_graded_grid_is_second_order_near_contact(motion, index):
    """1 - kappa = 1e-6, n_axial = 64 throughout (the axial error is common to all): the default graded
    theta grid against an independent one, the single-scale grid clustering = 1/2 at N = 16384, which
    converged to 2e-8 (N = 8192 against 32768). Slope -2 +- 0.1 over N = 64, 128, 256."""
    reference = _near_contact_factor(motion, index, n=16384, n_axial=64, clustering=0.5)
    sizes = np.array([64, 128, 256])
    errors = [abs(_near_contact_factor(motion, index, n=int(n), n_axial=64) - reference) for n in sizes]
    assert abs(np.polyfit(np.log(sizes), np.log(errors), 1)[0] + 2.0) < 0.1


@pytest.mark.parametrize(("motion", "index"), [(Motion(eps_dot=1.0), 0), (Motion(omega_a=1.0), 1)],
                         ids=["squeeze", "rotation"])
def test_default_extrapolated_solve_near_contact(motion, index):
    """1 - kappa = 1e-6: the finite-length factors' default, (128, 64) extrapolated, against the single-scale
    grid at (16384, 256) extrapolated (its error below 1e-8 in either direction). Measured: 1.6e-7
    (squeeze) and 1.2e-6 (rotation), the fourth-order remainder; the deficits 1 - F are 1.4e-4 and 9.3e-4,
    so this is their size to 1 per cent. Single-scale grids with N = 128 are off by 2e-3 (clustering 0.68)
    to 1.5e-2 (clustering 1/2)."""
    reference = _near_contact_factor(motion, index, n=16384, n_axial=256, clustering=0.5, extrapolate=True)
    got = _near_contact_factor(motion, index, n=128, n_axial=64, extrapolate=True)
    assert abs(got - reference) < 3e-6


def test_default_clustering():
    """Single-scale (1/2, 1/2) up to beta = 1/25 (kappa = 0.99681); beyond, the grid's scale at the narrow
    gap, beta^narrow, is NARROW_SCALE beta and at the wide side, beta^wide, 1/NARROW_SCALE."""
    assert default_clustering(0.99, 0.01) == (0.5, 0.5)
    assert default_clustering(0.9968, 0.0032) == (0.5, 0.5)
    for omk in (1e-3, 1e-6, 1e-12):
        narrow, wide = default_clustering(1 - omk, omk)
        beta = math.sqrt(omk / (2 - omk))
        assert narrow + wide == pytest.approx(1.0, rel=1e-15)
        assert beta**narrow == pytest.approx(NARROW_SCALE * beta, rel=1e-12)
        assert beta**wide == pytest.approx(1.0 / NARROW_SCALE, rel=1e-12)


@pytest.mark.parametrize("omk", [0.3, 1e-6])
def test_graded_map_is_the_stated_one(omk):
    """Node angles against tan(theta/2) = beta^c(xi) tan(xi/2), c(xi) = wide + (narrow - wide) cos^2(xi/2),
    and the rule's dpsi/dxi against a centred difference of psi(xi) (error O(h^2) = 1e-10 relative)."""
    kappa = 1.0 - omk
    narrow, wide = 0.9, 0.2
    beta = math.sqrt(omk / (2.0 - omk))
    kappa_g, _ = grid_parameter(kappa, omk, narrow)
    gamma = grading(kappa, omk, narrow, wide)
    rule, nodes = _theta_rule(64, 2, gamma)
    xi = -math.pi + 2 * math.pi * np.arange(64) / 64
    c = wide + (narrow - wide) * np.cos(0.5 * xi) ** 2
    theta = 2 * np.arctan2(beta**c * np.sin(0.5 * xi), np.cos(0.5 * xi))
    # theta from psi near +-pi carries the rounding of tan(psi/2) times dtheta/dpsi: 1e-10 at 1 - kappa = 1e-6
    assert np.allclose(_theta_of_psi(nodes, kappa_g), theta, rtol=0, atol=1e-9)
    psi, stretch = _sommerfeld_angle(xi[1:], gamma)
    step = 1e-5
    numeric = (_sommerfeld_angle(xi[1:] + step, gamma)[0] - _sommerfeld_angle(xi[1:] - step, gamma)[0]) / (2 * step)
    assert np.allclose(stretch, numeric, rtol=1e-8)
    assert np.all(stretch > 0) and np.all(np.diff(psi) > 0)
    assert np.sum(rule[4]) == pytest.approx(2 * math.pi, rel=1e-12)  # the weights integrate dpsi over a period


def test_grid_parameter_limits():
    assert grid_parameter(0.9, 0.1, 1.0) == pytest.approx((0.9, 0.1), rel=1e-15)
    assert grid_parameter(0.9, 0.1, 0.0) == (0.0, 1.0)
    _, omk_g = grid_parameter(1 - 1e-12, 1e-12, 0.5)
    beta_sq = omk_g / (2 - omk_g)
    assert beta_sq**2 == pytest.approx(1e-12 / (2 - 1e-12), rel=1e-12)  # beta_g = sqrt(beta)


def test_axial_grid_is_graded_toward_the_end():
    z = axial_grid(6.0, 16, 0.1)
    steps = np.diff(z)
    assert z[0] == 0.0 and z[-1] == 6.0
    assert np.all(np.diff(steps) < 0)  # smaller toward the end
    assert steps[-1] == pytest.approx(0.1 * math.expm1(math.log1p(60.0) / 16), rel=1e-12)


# ---------------------------------------------------------------- cavitation

def test_half_sommerfeld_above_the_film_is_the_full_film():
    annulus = Annulus.from_kappa(A, B, 0.6, L)
    full = reynolds2d_forces(annulus, MOTIONS["combined"], OIL)
    cav = reynolds2d_forces(annulus, MOTIONS["combined"], OIL, cavitation="half-sommerfeld", p_end=1e6,
                            p_cav=-1e6)
    assert cav.as_tuple() == pytest.approx(full.as_tuple(), rel=1e-13)


def test_half_sommerfeld_short_bearing_is_the_pi_film():
    """Short bearing, p_cav = p_end: p = -R (L^2/4 - z^2)/(2 h^3) is kept where R < 0, theta in (-pi, 0).

    f_eps = (a L^3/12) int R cos/h^3 over the kept half, f_chi likewise with sin;
    the integrals by quadrature.
    """
    kappa, length_over_a = 0.6, 0.2
    annulus = Annulus.from_kappa(A, B, kappa, length_over_a * A)
    delta, mu = annulus.delta, OIL.mu
    got = reynolds2d_forces(annulus, Motion(omega_a=1.0), OIL, n=256, n_axial=16, cavitation="half-sommerfeld",
                            extrapolate=True)

    def r_over_h3(t):  # R/h^3 for W_a = 1: 6 mu h_theta / h^3
        return 6 * mu * delta * kappa * math.sin(t) / (delta * (1 - kappa * math.cos(t))) ** 3

    scale = A * annulus.length**3 / 12
    f_eps = scale * quad(lambda t: r_over_h3(t) * math.cos(t), -math.pi, 0, limit=200)[0]
    f_chi = scale * quad(lambda t: r_over_h3(t) * math.sin(t), -math.pi, 0, limit=200)[0]
    # the next order in (L/(a zeta))^2: measured 0.39 and 0.19 of it for f_eps, f_chi (and 1/4 of that at L/2)
    bound = 0.6 * length_over_a**2 / (1 - kappa**2)
    assert got.f_eps == pytest.approx(f_eps, rel=bound)
    assert got.f_chi == pytest.approx(f_chi, rel=bound)
    assert abs(f_eps) > 0.5 * abs(f_chi)  # the pi-film has a radial force, the full film none


def test_half_sommerfeld_is_second_order_when_the_film_ruptures_inside_cells():
    """p_cav below p_end: the rupture line crosses cells and moves along z. Counting each straddling
    cell by its fraction above p_cav keeps f_chi second order in N (slope -2 +- 0.15 against N = 4096)."""
    annulus = Annulus.from_kappa(A, B, 0.6, L)
    motion = Motion(omega_a=1.0)
    p_cav = -0.3 * np.abs(reynolds2d_pressure(annulus, motion, OIL, n=128, n_axial=32).p).max()
    options = {"n_axial": 32, "cavitation": "half-sommerfeld", "p_cav": p_cav}
    ref = reynolds2d_forces(annulus, motion, OIL, n=4096, **options).f_chi
    sizes = np.array([32, 64, 128, 256])
    errors = [abs(reynolds2d_forces(annulus, motion, OIL, n=n, **options).f_chi / ref - 1) for n in sizes]
    assert abs(np.polyfit(np.log(sizes), np.log(errors), 1)[0] + 2.0) < 0.15


# ---------------------------------------------------------------- bad input

@pytest.mark.parametrize(("options", "match"), [
    ({"n": 4}, "n must be"),
    ({"n_axial": 15}, "n_axial must be an even"),
    ({"n_axial": 2}, "n_axial must be"),
    ({"ends": "closed"}, "ends must be"),
    ({"cavitation": "jfo"}, "cavitation must be"),
    ({"cavitation": "half-sommerfeld", "ends": "sealed"}, "needs open ends"),
    ({"cavitation": "half-sommerfeld", "p_cav": 1.0}, "p_cav must not exceed"),
    ({"clustering": 1.5}, "clustering must be"),
    ({"clustering": (0.3, 0.6)}, "0 <= wide <= narrow <= 1"),
    ({"clustering": (0.9, 0.1, 0.0)}, "clustering must be"),
    ({"profile": "wavy"}, "profile must be"),
    ({"end_layer": -1.0}, "end_layer must be"),
    ({"extrapolate": True, "n_axial": 18}, "multiple of 4"),
])
def test_bad_input(options, match):
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    with pytest.raises(ValueError, match=match):
        reynolds2d_forces(annulus, Motion(omega_a=1.0), OIL, **options)


def test_area_changing_rate_is_refused():
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    bad = GapProfile2D(h=lambda t, z: annulus.delta - annulus.eps * np.cos(t) + 0 * z,
                       h_dot=lambda t, z: 1e-5 + 0 * t + 0 * z)
    with pytest.raises(ValueError, match="conserve each cross-section"):
        reynolds2d_forces(annulus, Motion(), OIL, profile=bad)


def test_tilt_that_touches_is_refused():
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    with pytest.raises(ValueError, match="tilt must keep the ends apart"):
        tilted_gap(annulus, 1.1 * annulus.delta / L)
