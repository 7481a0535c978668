"""The transported (mass-conserving) JFO film: full film, steady end state, transport, mass balance, gauges.

Independent references: the closed forms (2.5)-(2.7) and a quadrature of the
thin-gap Reynolds pressure gradient (full film); the finite-length factor at
kappa -> 0 (the end reservoirs); the steady JFO solver of
:mod:`lubrication.cavitation` (the end state of a steady motion); the exact
solutions of a cavity, where the content is carried at the mean wall speed
(a rigid rotation of a h F) or, without rotation, stays where it is while the
gap changes under it; the exact gap areas of the moving dual cells.
"""

import math
from itertools import pairwise

import numpy as np
import pytest
from scipy.integrate import quad

from dynamics.apparatus import preset
from dynamics.equations.film import mass_balance, rock
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.simulation import simulate
from lubrication import Annulus, Motion
from lubrication import film_kernels as fk
from lubrication.cavitation import cavitating_forces, cavitating_pressure
from lubrication.closed_form import closed_form_forces
from lubrication.film_transport import (
    Bubble,
    Feed,
    TransportedFilm,
    dual_areas,
    end_conductance,
    film_rates,
    leaky_half_sommerfeld_forces,
)
from lubrication.finite_length import small_eccentricity_factor

from apparatus import A, B, L, OIL, STEEL

DELTA = B - A
P_ATM = 101325.0
UNREACHABLE = 1e12  # Pa: p_cav = -UNREACHABLE lies far below every film pressure here (no cavitation)


def _observed_order(ns, errors):
    return -np.polyfit(np.log(ns), np.log(errors), 1)[0]


def _face_angles(n, kappa):
    """theta of the dual-cell faces (psi midpoints of the cells), independently of the kernels."""
    psi_f = -np.pi + 2.0 * np.pi / n * (np.arange(n) + 0.5)
    return 2.0 * np.arctan(math.sqrt((1.0 - kappa) / (1.0 + kappa)) * np.tan(0.5 * psi_f))


def _cell_integrals_of(antiderivative, faces):
    """int over dual cell j (from face j-1 to face j; cell 0 across theta = +-pi) of a density."""
    upper = faces.copy()
    lower = np.roll(faces, 1)
    lower[0] -= 2.0 * np.pi
    return antiderivative(upper) - antiderivative(lower)


# -- (a) a full film is the Reynolds solver's, at any motion -------------------------------------

MOTIONS = [Motion(eps_dot=2e-5), Motion(omega_a=1.3, omega_b=-0.2, chi_dot=0.1),
           Motion(eps_dot=-3e-5, omega_a=1.3, omega_b=-0.2, chi_dot=0.1)]


@pytest.mark.parametrize("kappa", [0.1, 0.6, 0.95, 0.999])
@pytest.mark.parametrize("motion", MOTIONS)
def test_a_full_film_gives_the_closed_forms_and_no_void_rate(kappa, motion):
    """Sommerfeld grid: every thin-gap integrand is a trigonometric polynomial, exact to rounding from N = 8."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    rates = film_rates(annulus, motion, OIL, TransportedFilm(n=32, p_cav=-UNREACHABLE, gauge=Feed(P_ATM)))
    exact = closed_form_forces(annulus, motion, OIL)
    scale = max(abs(exact.f_eps), abs(exact.f_chi))
    assert rates.forces.f_eps == pytest.approx(exact.f_eps, rel=1e-10, abs=1e-12 * scale)
    assert rates.forces.f_chi == pytest.approx(exact.f_chi, rel=1e-10, abs=1e-12 * scale)
    assert rates.forces.T_a == pytest.approx(exact.T_a, rel=1e-10)
    # a full film stays full: no void opens, the feed supplies nothing (the gap area is constant)
    flux = A * (abs(motion.w_a) + abs(motion.w_b)) * DELTA + A * abs(motion.eps_dot)
    assert np.max(np.abs(rates.d_void)) <= 1e-13 * flux
    assert abs(rates.d_reservoir) <= 1e-13 * flux
    assert np.all(rates.film_fraction == 1.0)


def test_full_film_pressure_is_the_quadrature_of_the_reynolds_gradient_fourth_order():
    """p(theta) - p(pi) = 12 mu a int_pi^theta [U/(2h^2) - qhat/h^3 + Q/h^3], qhat from periodicity.

    The nodal pressures carry the error of the 2-point Gauss rule in each cell, O(dpsi^4).
    """
    kappa, motion = 0.7, Motion(eps_dot=-4e-5, omega_a=0.9, omega_b=0.3)
    annulus = Annulus.from_kappa(A, B, kappa, L)
    zeta = math.sqrt(1.0 - kappa**2)
    half_u = 0.5 * A * (motion.w_a + motion.w_b)
    # oint h^-2 = 2 pi/(delta^2 zeta^3), oint h^-3 = pi (2 + kappa^2)/(delta^3 zeta^5) (B8)-(B9); oint Q h^-3 = 0
    qhat = half_u * (2.0 / (DELTA**2 * zeta**3)) / ((2.0 + kappa**2) / (DELTA**3 * zeta**5))

    def gradient(theta):
        h = DELTA * (1.0 - kappa * math.cos(theta))
        return (half_u * h - qhat - A * motion.eps_dot * math.sin(theta)) / h**3

    ns = np.array([16, 32, 64])
    errors = []
    for n in ns:
        rates = film_rates(annulus, motion, OIL, TransportedFilm(n=int(n), p_cav=-UNREACHABLE, gauge=Feed(P_ATM)))
        # from theta = pi (node 0) round through -pi, node to node
        edges = np.concatenate(([-np.pi], rates.theta[1:]))
        pieces = [quad(gradient, lo, hi, epsabs=0.0, epsrel=1e-13)[0] for lo, hi in pairwise(edges)]
        expected = 12.0 * OIL.mu * A * np.concatenate(([0.0], np.cumsum(pieces)))
        errors.append(np.max(np.abs(rates.p - P_ATM - expected)) / np.max(np.abs(expected)))
    assert _observed_order(ns, errors) == pytest.approx(4.0, abs=0.3)
    assert errors[-1] < 1e-6


# -- the end reservoirs (bubble gauge) ---------------------------------------------------------

def test_end_reservoirs_give_the_finite_length_factor_at_small_kappa_second_order_in_n():
    """eps_end = 1/F_0 - 1: at kappa -> 0 the mode-1 pressure is the infinite one over 1 + eps_end.

    The exchange is lumped on the dual cells (a midpoint rule), so the factor carries an
    O(dtheta^2) error, and an O(kappa^2) one from the gap's variation.
    """
    annulus = Annulus.from_kappa(A, B, 1e-4, L)
    factor = small_eccentricity_factor(L / A)
    assert 1.0 / factor - 1.0 == pytest.approx(end_conductance(L / A), rel=1e-15)
    ns = np.array([16, 32, 64, 128])
    errors = {}
    for name, motion in (("f_eps", Motion(eps_dot=1e-5)), ("f_chi", Motion(omega_a=1.0))):
        exact = getattr(closed_form_forces(annulus, motion, OIL), name)
        errors[name] = np.array([abs(getattr(film_rates(annulus, motion, OIL, TransportedFilm(
            n=int(n), p_cav=-UNREACHABLE, gauge=Bubble())).forces, name) / exact - factor) for n in ns])
        assert _observed_order(ns, errors[name]) == pytest.approx(2.0, abs=0.15)
        assert errors[name][-1] < 1e-4 * factor


@pytest.mark.parametrize("kappa", [0.3, 0.9])
def test_end_reservoirs_measure_the_film_from_its_weighted_mean(kappa):
    """A full film with ends exchanges nothing in total (its gap area is constant), and forces do not see p_res."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    motion = Motion(eps_dot=3e-5, omega_a=1.0)
    low = film_rates(annulus, motion, OIL, TransportedFilm(n=64, p_cav=-UNREACHABLE, gauge=Bubble(pressure=1e3)))
    high = film_rates(annulus, motion, OIL, TransportedFilm(n=64, p_cav=-UNREACHABLE, gauge=Bubble(pressure=1e6)))
    flux = A * DELTA * abs(motion.w_a) + A * abs(motion.eps_dot)
    assert abs(low.d_reservoir) <= 1e-13 * flux and np.max(np.abs(low.d_void)) <= 1e-13 * flux
    np.testing.assert_allclose(high.p - 1e6, low.p - 1e3, rtol=0, atol=1e-9 * np.ptp(low.p))
    np.testing.assert_allclose(high.forces.as_tuple(), low.forces.as_tuple(), rtol=1e-9)
    assert np.min(low.p) < 1e3 < np.max(low.p)  # the reference lies inside the film's range


def test_the_bubble_is_an_isothermal_gas_that_cannot_hold_tension():
    film = TransportedFilm(n=16, p_cav=2e4, gauge=Bubble(pressure=1e5, volume=2e-6))
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    for reservoir in (0.0, 5e-6, -5e-6, -1.5e-5):
        expected = max(1e5 * 2e-6 / (2e-6 - L * reservoir), 2e4)  # p V = const; not below p_cav
        assert film.reservoir_pressure(L, reservoir) == pytest.approx(expected, rel=1e-15)
        rates = film_rates(annulus, Motion(omega_a=1.0), OIL, film, reservoir=reservoir)
        assert rates.reservoir_pressure == pytest.approx(expected, rel=1e-15)


# -- (b) the steady end state is the steady JFO solver's -------------------------------------------

@pytest.mark.parametrize(("kappa", "omega_a", "omega_b"), [(0.3, 4.0, 0.0), (0.6, 1.0, 0.0), (0.9, -0.4, 0.1)])
def test_the_steady_jfo_film_is_a_fixed_point_of_the_transport(kappa, omega_a, omega_b):
    """At a steady motion (eps' = 0) the transported balances and complementarity are the steady ones."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    motion = Motion(omega_a=omega_a, omega_b=omega_b)
    n = 64
    steady = cavitating_pressure(annulus, motion, OIL, "jfo", p_cav=0.0, p_ref=3.0, n=n, points_per_cell=2)
    assert np.any(steady.film_fraction < 0.9)  # a cavity
    void = dual_areas(annulus, n) * (1.0 - steady.film_fraction)
    rates = film_rates(annulus, motion, OIL, TransportedFilm(n=n, p_cav=0.0, gauge=Feed(3.0)), void=void)
    flux = 0.5 * DELTA * (abs(A * omega_a) + abs(B * omega_b))
    assert np.max(np.abs(rates.d_void)) <= 1e-13 * flux
    np.testing.assert_allclose(rates.p, steady.p, rtol=0, atol=1e-12 * np.max(steady.p))
    np.testing.assert_allclose(rates.forces.as_tuple(), steady.forces.as_tuple(), rtol=1e-12)


@pytest.mark.slow  # compiles the prescribed rocking's kernels (a minute and a half)
def test_a_full_film_released_into_a_steady_rotation_settles_on_the_steady_jfo_film():
    """The transient ends: after a few transits of the cavity the film is the steady solver's to the tolerance."""
    annulus = Annulus.from_kappa(A, B, 0.6, L)
    n = 32
    film = TransportedFilm(n=n, p_cav=0.0, gauge=Feed(3.0))
    run = rock(annulus, OIL, film, amplitude=0.0, omega=1.0, w_a=1.0, w_b=0.0, t_end=60.0,
               t_eval=np.array([0.0, 5.0, 60.0]))
    steady = cavitating_pressure(annulus, Motion(omega_a=1.0), OIL, "jfo", p_cav=0.0, p_ref=3.0, n=n,
                                 points_per_cell=2)
    expected = dual_areas(annulus, n) * (1.0 - steady.film_fraction)
    scale = np.max(expected)
    assert np.max(np.abs(run.void[:, 1] - expected)) > 1e-3 * scale  # after 5 s, still on its way
    assert np.max(np.abs(run.void[:, -1] - expected)) < 1e-9 * scale


# -- the moving cells, and what a cavity does with its content -----------------------------------

def _areas_by_hand(n, kappa):
    """V_j = a delta [theta - kappa sin theta] between the faces; valid for kappa < 0 too (a mirrored gap)."""
    return _cell_integrals_of(lambda t: A * DELTA * (t - kappa * np.sin(t)), _face_angles(n, kappa))


@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.99])
def test_dual_cells_hold_the_exact_gap_area_and_its_rate(kappa):
    """V_j' = Q~_j - Q~_{j-1} against central differences of the exact areas in kappa (O(dk^2), dk = 1e-6)."""
    n, eps_dot, dk = 24, 1e-4, 1e-6
    annulus = Annulus.from_kappa(A, B, kappa, L)
    np.testing.assert_allclose(dual_areas(annulus, n), _areas_by_hand(n, kappa), rtol=1e-13)
    assert np.sum(dual_areas(annulus, n)) == pytest.approx(2.0 * np.pi * A * DELTA, rel=1e-14)
    psi_f = -np.pi + 2.0 * np.pi / n * (np.arange(n) + 0.5)
    faces = (np.sin(psi_f), 1.0 + np.cos(psi_f), np.sin(0.5 * psi_f), np.cos(0.5 * psi_f))
    node_p = 1.0 + np.cos(-np.pi + 2.0 * np.pi / n * np.arange(n))
    out = [np.empty(n) for _ in range(5)]
    fk.film_geometry(A, B, kappa, 1.0 - kappa, eps_dot, faces, node_p, *out)
    derivative = (_areas_by_hand(n, kappa + dk) - _areas_by_hand(n, kappa - dk)) / (2.0 * dk)
    np.testing.assert_allclose(out[1], derivative * eps_dot / DELTA, rtol=0, atol=1e-6 * np.max(np.abs(out[1])))


def _cavity(n, kappa, mean, swing, p_cav=1e3):
    """A film all in cavity (F = mean + swing cos theta < 1) with the reservoir at p_cav: no pressure anywhere."""
    annulus = Annulus.from_kappa(A, B, kappa, L)
    film = TransportedFilm(n=n, p_cav=p_cav, gauge=Bubble(pressure=p_cav))

    def content(t):  # int a h F dtheta, h = delta (1 - kappa cos)
        return A * DELTA * (mean * t + (swing - mean * kappa) * np.sin(t)
                            - swing * kappa * (0.5 * t + 0.25 * np.sin(2.0 * t)))

    return annulus, film, content


@pytest.mark.slow  # compiles the prescribed rocking's kernels (a minute and a half)
def test_a_cavity_carries_its_content_at_the_mean_wall_speed_first_order_upwind():
    """d(a h F)/dt + (U/(2a)) d(a h F)/dtheta = 0: the content turns rigidly at (W_a + W_b)/2."""
    w_a, w_b, t_end = 1.5, 0.5, 1.0
    ns = np.array([32, 64, 128])
    errors = []
    for n in ns:
        annulus, film, content = _cavity(int(n), 0.3, 0.5, 0.3)
        void0 = dual_areas(annulus, n) - _cell_integrals_of(content, _face_angles(n, 0.3))
        run = rock(annulus, OIL, film, amplitude=0.0, omega=1.0, w_a=w_a, w_b=w_b, t_end=t_end,
                   t_eval=np.array([0.0, t_end]), void0=void0)
        turned = 0.5 * (w_a + w_b) * t_end
        exact = _cell_integrals_of(lambda t, c=content, s=turned: c(t - s), _face_angles(n, 0.3))
        liquid = run.area[:, -1] - run.void[:, -1]
        errors.append(np.sum(np.abs(liquid - exact)) / np.sum(exact))
        assert np.all(run.void > 0.0) and abs(run.reservoir[-1]) < 1e-12 * np.sum(exact)
        assert np.sum(liquid) == pytest.approx(np.sum(exact), rel=1e-12)
        assert void0 == pytest.approx(run.void[:, 0], rel=1e-14)
    assert _observed_order(ns, errors) == pytest.approx(1.0, abs=0.15)
    assert errors[-1] < 0.02


@pytest.mark.slow  # compiles the prescribed rocking's kernels (a minute and a half)
def test_without_rotation_a_cavity_keeps_its_content_while_the_gap_moves_under_it():
    """U = 0: a h F does not move; each moving dual cell holds the content between its faces."""
    kappa0, amplitude, omega = 0.5, 0.2, 2.0
    t_end = 0.5 * math.pi / omega  # kappa: 0.5 -> 0.7
    ns = np.array([32, 64, 128])
    errors = []
    for n in ns:
        annulus, film, content = _cavity(int(n), kappa0, 0.3, 0.1)
        run = rock(annulus, OIL, film, amplitude=amplitude, omega=omega, w_a=0.0, w_b=0.0, t_end=t_end,
                   t_eval=np.array([0.0, t_end]),
                   void0=dual_areas(annulus, n) - _cell_integrals_of(content, _face_angles(n, kappa0)))
        exact = _cell_integrals_of(content, _face_angles(n, kappa0 + amplitude))
        liquid = run.area[:, -1] - run.void[:, -1]
        errors.append(np.sum(np.abs(liquid - exact)) / np.sum(exact))
    assert _observed_order(ns, errors) >= 0.9
    assert errors[-1] < 0.01


@pytest.mark.slow  # compiles the prescribed rocking's kernels (a minute and a half)
def test_a_cavity_rocked_for_four_periods_gets_its_content_back_within_the_upwind_diffusion():
    """After whole periods the faces are back: the exact content is the initial one.

    First-order upwinding smears it by O(dtheta) per period (9% over four periods at N = 32,
    6% at N = 64, measured); a downwind squeeze flux would amplify the grid-scale modes instead.
    """
    kappa0, amplitude, omega, n = 0.5, 0.2, 2.0, 32
    annulus, film, content = _cavity(n, kappa0, 0.3, 0.1)
    initial = _cell_integrals_of(content, _face_angles(n, kappa0))
    run = rock(annulus, OIL, film, amplitude=amplitude, omega=omega, w_a=0.0, w_b=0.0,
               t_end=4 * 2 * math.pi / omega, void0=dual_areas(annulus, n) - initial)
    fraction = 1.0 - run.void / run.area
    assert np.all((fraction > 0.1) & (fraction < 0.7))  # F0 in [0.2, 0.4], times the gap's change (0.5/0.3)
    assert np.sum(np.abs(run.area[:, -1] - run.void[:, -1] - initial)) < 0.15 * np.sum(initial)


def test_the_shear_of_a_cavity_is_its_liquid_share():
    """T_a = mu a^2 L (U_b - U_a) oint F/h (B15); no pressure, no force. Second order (the cell's mean fraction)."""
    kappa, mean, swing = 0.6, 0.5, 0.3
    motion = Motion(omega_a=1.0, omega_b=-0.5)
    zeta = math.sqrt(1.0 - kappa**2)
    # oint 1/(1 - k cos) = 2 pi/zeta, oint cos/(1 - k cos) = (2 pi/zeta - 2 pi)/k
    integral = (mean * 2 * np.pi / zeta + swing * (2 * np.pi / zeta - 2 * np.pi) / kappa) / DELTA
    exact = OIL.mu * A**2 * L * A * (motion.w_b - motion.w_a) * integral  # U = a W in the thin gap
    ns = np.array([16, 32, 64, 128])
    errors = []
    for n in ns:
        annulus, film, content = _cavity(int(n), kappa, mean, swing)
        void = dual_areas(annulus, n) - _cell_integrals_of(content, _face_angles(n, kappa))
        rates = film_rates(annulus, motion, OIL, film, void=void)
        assert rates.forces.f_eps == 0.0 and rates.forces.f_chi == 0.0
        assert np.all(rates.p == film.p_cav)
        errors.append(abs(rates.forces.T_a / exact - 1.0))
    assert _observed_order(ns, errors) == pytest.approx(2.0, abs=0.15)


# -- (c) mass balance along rocking films and a coupled trajectory --------------------------------

@pytest.mark.slow  # compiles the prescribed rocking's kernels (a minute and a half)
@pytest.mark.parametrize("gauge", [Feed(P_ATM), Bubble(P_ATM)])
def test_the_rocking_film_conserves_its_liquid(gauge):
    """kappa = 0.5 +- 0.4 at omega = 20 rad/s, one period: cavities open and close; liquid + R is invariant."""
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    film = TransportedFilm(n=32, p_cav=P_ATM - 3.0, gauge=gauge)
    run = rock(annulus, OIL, film, amplitude=0.4, omega=20.0, w_a=2.0, w_b=0.5, t_end=2 * math.pi / 20.0)
    cavity = np.sum(run.void, axis=0)
    assert np.max(cavity) > 1e-4 * np.sum(run.area[:, 0])  # the film did cavitate
    assert run.balance.residual < 1e-10
    assert np.min(run.void) > -1e-12 * np.max(run.area)  # gas areas stay non-negative up to rounding


@pytest.mark.slow  # compiles the coupled film model's own kernels (a minute and a half)
def test_the_coupled_release_conserves_the_film_liquid():
    """The steel apparatus released at kappa = 0.5, phi = 0.5: it swings, cavitates, and no liquid is lost."""
    apparatus = preset("steel", nu=2e-4, alpha=math.radians(2.4))
    film = TransportedFilm(n=16, p_cav=P_ATM - 3.0, gauge=Feed(P_ATM))
    run = simulate(apparatus, Initial(kappa=0.5, phi=0.5), 0.3, forces=film, limits=Limits(on_invalid="warn"))
    assert run.status == "completed"
    c = run.columns
    assert np.count_nonzero(np.diff(np.sign(c["kappa_dot"][1:])) != 0) >= 2  # it rocks
    assert np.max(c["cavitated_fraction"]) > 0.2
    balance = mass_balance(apparatus, run)
    assert balance.turnover > 0.0 and balance.residual < 1e-10
    np.testing.assert_allclose(c["liquid"] + c["reservoir"], 2 * np.pi * A * DELTA, rtol=1e-13)


@pytest.mark.slow  # compiles the coupled film model's own kernels (a minute and a half)
def test_a_film_that_cannot_cavitate_moves_the_apparatus_as_the_closed_forms_do():
    """The coupling to (2.1)-(2.4): a full transported film is the Reynolds film, exact on the Sommerfeld grid."""
    apparatus = preset("steel", nu=2e-4, alpha=math.radians(2.4))
    initial = Initial(kappa=0.5, phi=0.5, omega_a=1.0, omega_b=-0.5)
    t = np.linspace(0.0, 0.3, 31)
    film = TransportedFilm(n=16, p_cav=-UNREACHABLE, gauge=Feed(P_ATM))
    run = simulate(apparatus, initial, 0.3, forces=film, t_eval=t, rtol=1e-10, limits=Limits(on_invalid="warn"))
    reference = simulate(apparatus, initial, 0.3, forces="closed-form", t_eval=t, rtol=1e-10,
                         limits=Limits(on_invalid="warn"))
    assert np.max(np.abs(run.columns["cavity_area"])) < 1e-18 * 2 * np.pi * A * DELTA  # rounding
    for name in ("one_minus_kappa", "phi", "omega_a", "omega_b", "x_b"):
        a, b = run.columns[name], reference.columns[name]
        np.testing.assert_allclose(a, b, rtol=1e-8, atol=1e-8 * np.max(np.abs(b)), err_msg=name)  # 100 rtol


# -- (d) the gauge: separation and approach alike ----------------------------------------------------

def _squeeze_forces(gauge, p_cav, eps_dot, kappa=0.2, n=64):
    annulus = Annulus.from_kappa(A, B, kappa, L)
    return film_rates(annulus, Motion(eps_dot=eps_dot), OIL, TransportedFilm(n=n, p_cav=p_cav, gauge=gauge))


def test_a_small_squeeze_is_resisted_alike_both_ways_with_either_gauge():
    for gauge in (Feed(P_ATM), Bubble(P_ATM)):
        approach, separation = (_squeeze_forces(gauge, 0.0, s * 1e-5) for s in (1.0, -1.0))
        assert separation.forces.f_eps == pytest.approx(-approach.forces.f_eps, rel=1e-12)
        assert approach.forces.f_eps < 0.0


def test_the_bubble_keeps_a_separation_full_where_the_feed_cavitates_it():
    """Squeeze pressure of amplitude dp about the widest-gap (feed) or the weighted-mean (bubble) level.

    The feed puts the whole separating film below p_ref (down to -2 dp), the bubble only
    half of it (down to about -dp): with p_res - p_cav = 1.5 dp the bubble's film stays full
    and its responses are symmetric, the feed's separation cavitates and is resisted less.
    """
    eps_dot = 1e-3
    feed_full = _squeeze_forces(Feed(P_ATM), -UNREACHABLE, -eps_dot)
    dp = 0.5 * np.ptp(feed_full.p)
    margin = 1.5 * dp
    bubble = [_squeeze_forces(Bubble(P_ATM), P_ATM - margin, s * eps_dot) for s in (1.0, -1.0)]
    feed = [_squeeze_forces(Feed(P_ATM), P_ATM - margin, s * eps_dot) for s in (1.0, -1.0)]
    assert all(np.all(r.p > P_ATM - margin) for r in bubble)
    assert bubble[1].forces.f_eps == pytest.approx(-bubble[0].forces.f_eps, rel=1e-12)
    assert np.any(feed[1].p == P_ATM - margin) and np.all(feed[0].p > P_ATM - margin)
    assert feed[1].forces.f_eps < 0.9 * -feed[0].forces.f_eps


def test_a_pure_separation_at_the_reference_is_free_with_the_feed_and_resisted_with_the_ends():
    """p_cav = p_ref: the feed's separating film lies wholly below p_ref (half-Sommerfeld f_eps = 0)."""
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    separation, approach = Motion(eps_dot=-1e-4), Motion(eps_dot=1e-4)
    feed_hs = cavitating_forces(annulus, separation, OIL, "half-sommerfeld", p_cav=P_ATM, p_ref=P_ATM, n=64)
    ends_hs = leaky_half_sommerfeld_forces(annulus, separation, OIL, p_cav=P_ATM, p_res=P_ATM, n=64)
    resisted = -cavitating_forces(annulus, approach, OIL, "half-sommerfeld", p_cav=P_ATM, p_ref=P_ATM, n=64).f_eps
    assert feed_hs.f_eps == 0.0
    assert ends_hs.f_eps > 0.03 * resisted  # the part of the film above the weighted mean (7.6% here)
    # the transported film from a full film: with the feed an approach stays full and a separation opens voids
    # (0.03 of the approach's resistance left); with the ends both open voids, and the separation keeps 0.3
    rates = {(gauge.__class__.__name__, sign): film_rates(
        annulus, Motion(eps_dot=sign * 1e-4), OIL, TransportedFilm(n=64, p_cav=P_ATM, gauge=gauge))
        for gauge in (Feed(P_ATM), Bubble(P_ATM)) for sign in (1.0, -1.0)}
    flux = A * 1e-4  # the squeeze flux a eps'
    assert np.all(rates["Feed", 1.0].film_fraction == 1.0) and np.max(rates["Feed", 1.0].d_void) <= 1e-13 * flux
    assert rates["Feed", 1.0].forces.f_eps == pytest.approx(-resisted, rel=1e-12)
    assert all(np.max(rates[key].d_void) > 1e-3 * flux for key in (("Feed", -1.0), ("Bubble", 1.0), ("Bubble", -1.0)))
    assert rates["Feed", -1.0].forces.f_eps < 0.1 * resisted
    assert rates["Bubble", -1.0].forces.f_eps > 3.0 * rates["Feed", -1.0].forces.f_eps


def test_the_leaky_truncation_of_a_film_above_p_cav_is_the_bubble_full_film():
    annulus = Annulus.from_kappa(A, B, 0.7, L)
    motion = Motion(eps_dot=2e-5, omega_a=0.7, omega_b=0.1)
    truncated = leaky_half_sommerfeld_forces(annulus, motion, OIL, p_cav=-UNREACHABLE, p_res=P_ATM, n=64)
    full = film_rates(annulus, motion, OIL, TransportedFilm(n=64, p_cav=-UNREACHABLE, gauge=Bubble(P_ATM)))
    np.testing.assert_allclose(truncated.as_tuple(), full.forces.as_tuple(), rtol=1e-12)


# -- (e) bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"n": 4}, ValueError, r"n \(cells around the gap\) must be an integer"),
        ({"points_per_cell": 0}, ValueError, "points_per_cell must be an integer"),
        ({"relaxation": 0.0}, ValueError, "relaxation"),
        ({"p_cav": float("nan")}, ValueError, "p_cav must be a finite number"),
        ({"p_cav": 2e5}, ValueError, "p_cav must not exceed the feed's p_ref"),
        ({"gauge": Bubble(pressure=-1.0)}, ValueError, "bubble pressure"),
        ({"gauge": Bubble(volume=0.0)}, ValueError, "bubble volume"),
        ({"gauge": Bubble(end_conductance=0.0)}, ValueError, "end_conductance"),
        ({"gauge": "bubble"}, TypeError, "gauge must be a Feed or a Bubble"),
    ],
)
def test_bad_film_models_are_refused(kwargs, error, message):
    with pytest.raises(error, match=message):
        TransportedFilm(**kwargs)


def test_bad_states_and_runs_are_refused():
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    film = TransportedFilm(n=16)
    area = dual_areas(annulus, 16)
    with pytest.raises(ValueError, match=r"void must be a finite array of shape \(16,\)"):
        film_rates(annulus, Motion(), OIL, film, void=np.zeros(15))
    with pytest.raises(ValueError, match="void must be a finite array"):
        film_rates(annulus, Motion(), OIL, film, void=np.full(16, np.nan))
    with pytest.raises(ValueError, match="void must not exceed the gap area"):
        film_rates(annulus, Motion(), OIL, film, void=1.01 * area)
    with pytest.raises(ValueError, match="reservoir must be a finite number"):
        film_rates(annulus, Motion(), OIL, film, reservoir=math.inf)
    rocking = {"amplitude": 0.1, "omega": 1.0, "w_a": 1.0, "w_b": 0.0, "t_end": 1.0}
    with pytest.raises(ValueError, match=r"kappa0 \+- amplitude must stay in \[0, 1\)"):
        rock(annulus, OIL, film, **{**rocking, "amplitude": 0.6})
    with pytest.raises(ValueError, match="t_end must be"):
        rock(annulus, OIL, film, **{**rocking, "t_end": 0.0})
    with pytest.raises(ValueError, match="omega must be a finite number"):
        rock(annulus, OIL, film, **{**rocking, "omega": math.nan})
    with pytest.raises(ValueError, match=r"void0 must have shape \(16,\) and lie in \[0, V_j\]"):
        rock(annulus, OIL, film, **rocking, void0=-area)
    apparatus = STEEL
    with pytest.raises(ValueError, match="model must be one of .*got 'jfo'"):
        simulate(apparatus, Initial(kappa=0.5), 1.0, forces="jfo")
    with pytest.raises(ValueError, match="t_end must be"):
        simulate(apparatus, Initial(kappa=0.5), -1.0, forces=film)
    with pytest.raises(ValueError, match="transported film .* full equations without contact"):
        simulate(apparatus, Initial(kappa=0.5), 1.0, forces=film, equations="reduced")
    with pytest.raises(ValueError, match="end_conductance"):
        leaky_half_sommerfeld_forces(annulus, Motion(), OIL, eps_end=-1.0)


# -- slow: the coupled model over seconds, both gauges ------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("gauge", [Feed(P_ATM), Bubble(P_ATM)])
def test_the_coupled_model_conserves_the_film_liquid_over_seconds(gauge):
    apparatus = preset("steel", nu=2e-4, alpha=math.radians(2.4))
    film = TransportedFilm(n=32, p_cav=P_ATM - 3.0, gauge=gauge)
    run = simulate(apparatus, Initial(kappa=0.5, phi=0.5), 5.0, forces=film, limits=Limits(on_invalid="warn"))
    assert run.status == "completed"
    assert mass_balance(apparatus, run).residual < 1e-10


