"""The tilted inner cylinder (``dynamics.tilt``): strip theory against the Reynolds equation on (theta, z),
the film's whirl, the spinning body's nutation, and a tilt along a release.

References, each independent of the strips: the (theta, z) Reynolds solver with sealed ends, whose gap
carries the tilt and whose axial flow the strips leave out; the zero-force whirl of an aligned journal,
found from the forces of the plane problem alone (a circular orbit at the rate where f_chi = 0); the free
nutation of a symmetric top; scipy's Radau on the same tilt equation.
"""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from dynamics import Initial, Limits, ValidityWarning, preset, simulate
from dynamics.contact.reduced import ContactParams
from dynamics.contact.roughness import RoughContact
from dynamics.tilt import KAPPA_MIN, _matrix, flights, strip_forces, tilt_coefficients, tilt_history, tilt_in_flights
from lubrication import Annulus, Fluid, Motion
from lubrication.kernels import KernelModel
from lubrication.registry import kernel_model
from lubrication.reynolds2d import reynolds2d_pressure, tilted_gap

from apparatus import A, B, L, OIL, STEEL

DELTA = B - A
MOTION = Motion(eps_dot=1e-5, chi_dot=0.2, omega_a=1.0, omega_b=0.5)
STEEL_FLUID = Fluid(nu=STEEL.nu, rho=STEEL.rho)


def _moments(kappa, length):
    """The moment int z f dz (along e_eps, e_chi) of a tilt in the plane of the line of centres that closes
    0.3 of the gap at the ends: (strips of the closed forms, Reynolds on (theta, z) with sealed ends)."""
    tilt = 0.3 * (1.0 - kappa) * DELTA / (0.5 * length)
    annulus = Annulus.from_kappa(A, B, kappa, length=length)
    # fixed in the frame of the line of centres, as tilted_gap's tilt is: gamma' = chi' J gamma
    _, strips = strip_forces(kernel_model("closed-form"), annulus, MOTION, OIL, (tilt, 0.0),
                             (0.0, MOTION.chi_dot * tilt))
    film = reynolds2d_pressure(annulus, MOTION, OIL, n=128, n_axial=int(64 * length / L), ends="sealed",
                               profile=tilted_gap(annulus, tilt, eps_dot=MOTION.eps_dot))
    z = film.z
    reynolds = np.array([np.trapezoid(z * film.f_eps_per_length, z), np.trapezoid(z * film.f_chi_per_length, z)])
    return strips, reynolds


@pytest.mark.parametrize("kappa", [0.5, 0.9])
def test_strips_miss_the_tilted_films_moment_by_the_axial_flow_second_order_in_a_over_l(kappa):
    """The strips leave out the axial pressure gradient, (a/L)^2 of the azimuthal one: the moment's error
    falls by 4 when L doubles (measured 3.8-3.9; the (theta, z) grid's own error, O(dz^2) on grids refined with
    L, is below 1e-3 of it), and at the apparatus' L/a = 12.9 it is 4% (kappa 0.5) and 0.7% (kappa 0.9)."""
    errors = []
    for length in (L, 2.0 * L):
        strips, reynolds = _moments(kappa, length)
        errors.append(abs(strips[1] - reynolds[1]) / abs(reynolds[1]))
    assert errors[0] < 0.05
    assert 3.5 < errors[0] / errors[1] < 4.5


@pytest.mark.parametrize(("kappa", "ratio"), [(0.5, 0.73), (0.9, 0.91), (0.99, 0.97)])
def test_open_ends_lower_a_tilts_moment_from_the_strips_by_the_stated_ratio(kappa, ratio):
    """The device's gap opens into end regions: the moment of a tilt in a turning film on (theta, z) with open
    ends, over the strips', as the force models' page states it (to 0.02)."""
    tilt = 0.1 * (1.0 - kappa) * DELTA / (0.5 * L)
    annulus, motion = Annulus.from_kappa(A, B, kappa, length=L), Motion(omega_a=1.0, omega_b=0.3)
    _, strips = strip_forces(kernel_model("closed-form"), annulus, motion, OIL, (tilt, 0.0))
    film = reynolds2d_pressure(annulus, motion, OIL, n=128, n_axial=64, ends="open",
                               profile=tilted_gap(annulus, tilt))
    assert np.trapezoid(film.z * film.f_chi_per_length, film.z) / strips[1] == pytest.approx(ratio, abs=0.02)


def test_strips_of_an_untilted_cylinder_are_the_plane_forces_times_the_length():
    model = kernel_model("stokes-exact")
    annulus = Annulus.from_kappa(A, B, 0.9, length=L)
    total, moment = strip_forces(model, annulus, MOTION, OIL, (0.0, 0.0))
    plane = model.forces(annulus, MOTION, OIL)
    np.testing.assert_allclose(total.as_tuple(), plane.as_tuple(), rtol=1e-13)
    assert np.all(np.abs(moment) < 1e-13 * abs(plane.f_chi) * L)


@pytest.mark.parametrize("kappa", [0.3, 0.95])
def test_a_small_tilts_moment_is_the_linear_one_to_third_order(kappa):
    """M = (L^3/12)(K gamma + C gamma') up to O(gamma^3), so 4 times closer relative to M at half the tilt: the
    gamma^2 term is odd in z and integrates to zero."""
    model = kernel_model("stokes-exact")
    annulus = Annulus.from_kappa(A, B, kappa, length=L)
    k, c = tilt_coefficients(model, annulus, MOTION, OIL)
    direction, rate = np.array([0.6, 0.8]), np.array([-0.3, 0.5])
    misfit = []
    for size in (1e-3, 5e-4):
        tilt = size * (1.0 - kappa) * DELTA / L * direction
        tilt_rate = size * np.abs(MOTION.omega_a) * (1.0 - kappa) * DELTA / L * rate
        _, moment = strip_forces(model, annulus, MOTION, OIL, tilt, tilt_rate)
        linear = L**3 / 12.0 * (k @ tilt + c @ tilt_rate)
        misfit.append(np.linalg.norm(moment - linear) / np.linalg.norm(linear))
    assert misfit[0] < 1e-6
    assert 3.5 < misfit[0] / misfit[1] < 4.5  # relative to the linear moment: O(gamma^2)


def test_the_tilt_equation_turns_the_strips_moment_into_angular_acceleration():
    """I_t gamma'' = M for a tilt released without a rate from a cylinder that does not spin up: the moment of
    the strips, at a small tilt, over the transverse moment of inertia (the sections' effective mass and the
    cross-sections' own), in the plane's components (x down the slope, z along its normal)."""
    model = kernel_model("stokes-exact")
    kappa, chi = 0.8, 2.9
    row = {"one_minus_kappa": 1.0 - kappa, "phi": chi + STEEL.alpha, "kappa_dot": MOTION.eps_dot / DELTA,
           "phi_dot": MOTION.chi_dot, "omega_a": MOTION.omega_a, "omega_b": MOTION.omega_b}
    a_mat = _matrix(model, STEEL, STEEL_FLUID, row, 0.0)
    e_eps, e_chi = np.array([math.sin(chi), math.cos(chi)]), np.array([math.cos(chi), -math.sin(chi)])
    tilt = 1e-4 * (1.0 - kappa) * DELTA / L
    _, moment = strip_forces(model, Annulus.from_kappa(A, B, kappa, length=L), MOTION, STEEL_FLUID, (tilt, 0.0))
    inertia = STEEL.m_eff * L**2 / 12.0 + STEEL.m_a * A**2 / 4.0
    expected = (moment[0] * e_eps + moment[1] * e_chi) / inertia
    np.testing.assert_allclose(a_mat[2:, :2] @ (tilt * e_eps), expected, rtol=1e-6)
    np.testing.assert_array_equal(a_mat[:2], np.hstack((np.zeros((2, 2)), np.eye(2))))


def _zero_force_whirl(model, kappa, omega_a, omega_b):
    """The whirl rate chi' at which f_chi vanishes for a journal on a circular orbit (eps' = 0), from two
    evaluations of the plane forces (f_chi is affine in chi')."""
    annulus = Annulus.from_kappa(A, B, kappa)
    f = [model.forces(annulus, Motion(chi_dot=w, omega_a=omega_a, omega_b=omega_b), OIL).f_chi for w in (0.0, 1.0)]
    return f[0] / (f[0] - f[1])


def _inertialess_whirl(model, kappa):
    k, c = tilt_coefficients(model, Annulus.from_kappa(A, B, kappa), Motion(omega_a=1.0, omega_b=0.3), OIL)
    return np.linalg.eigvals(-np.linalg.solve(c, k))


@pytest.mark.parametrize("name", ["closed-form", "stokes-exact"])
@pytest.mark.parametrize("kappa", [0.01, 0.5, 0.99])
def test_without_inertia_an_aligned_journal_whirls_undamped(name, kappa):
    """C gamma' + K gamma = 0 at a journal whose walls turn: reversing the motion reverses K, and a reflection
    in the line of centres maps the problem to the reversed one, so the eigenvalues come in pairs -lambda,
    lambda: the trace of C^-1 K vanishes, and the whirl is neither damped nor driven."""
    eigen = _inertialess_whirl(kernel_model(name), kappa)
    assert np.all(np.abs(eigen.real) < 1e-7 * np.abs(eigen.imag))
    assert np.all(np.abs(eigen.imag) > 0.3)


@pytest.mark.parametrize("name", ["closed-form", "stokes-exact"])
def test_near_the_centre_the_whirl_is_the_zero_force_orbit_to_second_order(name):
    """Near the centre the small circle the section runs is an orbit about the outer axis, on which the forces
    vanish at chi'*: the whirl tends to chi'* as kappa^2. For the thin film chi'* = (Omega_a + Omega_b)/2,
    the half-frequency whirl of journal bearings."""
    model = kernel_model(name)
    misfit = []
    for kappa in (0.02, 0.01):
        rate = _zero_force_whirl(model, kappa, 1.0, 0.3)
        misfit.append(abs(np.max(_inertialess_whirl(model, kappa).imag) - rate) / rate)
    assert misfit[1] < 2e-4
    assert 3.5 < misfit[0] / misfit[1] < 4.5
    if name == "closed-form":
        assert _zero_force_whirl(model, 0.01, 1.0, 0.3) == pytest.approx(0.65, rel=1e-12)


def _still(kappa, omega_a=1.0, omega_b=0.3):
    return {"one_minus_kappa": 1.0 - kappa, "phi": 1.0, "kappa_dot": 0.0, "phi_dot": 0.0,
            "omega_a": omega_a, "omega_b": omega_b}


def test_with_inertia_the_whirl_grows_and_without_rotation_a_tilt_stays():
    """The inertia of the cylinder makes the undamped whirl grow, slowly (oil whip); with neither cylinder
    turning the film only resists the tilt's rate, so a tilt neither grows nor returns: two zero eigenvalues."""
    model = kernel_model("stokes-exact")
    whirl = np.linalg.eigvals(_matrix(model, STEEL, STEEL_FLUID, _still(0.5), 0.0))
    worst = whirl[np.argmax(whirl.real)]
    assert 0.0 < worst.real < 1e-2 * abs(worst.imag)
    still = np.sort_complex(np.linalg.eigvals(_matrix(model, STEEL, STEEL_FLUID, _still(0.5, 0.0, 0.0), 0.0)))
    assert np.all(still.real[:2] < 0.0)
    np.testing.assert_allclose(still[2:], 0.0, atol=1e-9 * abs(still[0]))


def test_without_the_film_the_spinning_cylinder_nutates_the_way_it_spins():
    """A free symmetric top: the tilt's rate turns the way of the spin at I_a Omega_a / I_t."""
    free = KernelModel("no film", lambda *args: (0.0, 0.0, 0.0), "no-film")
    omega_a = 3.0
    a_mat = _matrix(free, STEEL, STEEL_FLUID, _still(0.5, omega_a, 0.0), 0.0)
    nutation = (STEEL.m_a * A**2 / 2.0) * omega_a / (STEEL.m_eff * L**2 / 12.0 + STEEL.m_a * A**2 / 4.0)
    chi = 1.0 - STEEL.alpha
    e_eps, e_chi = np.array([math.sin(chi), math.cos(chi)]), np.array([math.cos(chi), -math.sin(chi)])
    t = 0.7 / nutation
    y = solve_ivp(lambda _, y: a_mat @ y, (0.0, t), np.concatenate(([0.0, 0.0], e_eps)), rtol=1e-11,
                  atol=1e-13).y[:, -1]
    np.testing.assert_allclose(y[2:], math.cos(0.7) * e_eps + math.sin(0.7) * e_chi, atol=1e-8)


@pytest.fixture(scope="module")
def release():
    """The default scene's release on smooth walls, 10 s."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return simulate(STEEL, Initial(kappa=0.5, phi=0.5), t_end=10.0, limits=Limits(on_invalid="warn"))


def test_the_tilts_exponentials_agree_with_radau_on_the_same_equation(release):
    """Between rows the tilt equation's matrix is linear; scipy's Radau at rtol 1e-8 integrates that same
    equation. The product of exponentials is second order in its substeps: 1e-3 of the gain with 8."""
    history = tilt_history(release, STEEL, t_span=(0.05, 0.6))
    cols = {name: release.columns[name] for name in ("t", "one_minus_kappa", "kappa_dot", "phi", "phi_dot",
                                                     "omega_a", "omega_b")}
    t_rows, unique = np.unique(cols["t"], return_index=True)
    inside = np.flatnonzero((t_rows >= 0.05) & (t_rows <= 0.6))
    spin = np.gradient(cols["omega_a"][unique], t_rows)
    model = kernel_model("stokes-exact")
    matrices = np.array([_matrix(model, STEEL, STEEL_FLUID,
                                 {name: values[unique][i] for name, values in cols.items()}, spin[i])
                         for i in inside])
    t = t_rows[inside]

    def a_at(time):
        i = min(max(int(np.searchsorted(t, time)), 1), t.size - 1)
        w = (time - t[i - 1]) / (t[i] - t[i - 1])
        return (1.0 - w) * matrices[i - 1] + w * matrices[i]

    y0 = np.eye(4)[:, :2].ravel()  # unit tilts along x and z, released without a rate
    solution = solve_ivp(lambda time, y: (a_at(time) @ y.reshape(4, 2)).ravel(), (t[0], t[-1]), y0, method="Radau",
                         rtol=1e-8, atol=1e-11, jac=lambda time, y: np.kron(a_at(time), np.eye(2)))
    radau = np.linalg.norm(solution.y[:, -1].reshape(4, 2)[:2], 2)
    assert history.gain[-1] == pytest.approx(radau, rel=2e-3)


def test_a_tilt_decays_along_the_release_on_smooth_walls(release):
    """The default release rocks towards contact; a unit tilt at 0.05 s is below 1% of itself by 10 s, though
    the matrix frozen at about half the instants has a growing mode."""
    history = tilt_history(release, STEEL, t_span=(0.05, 10.0))
    assert history.gain[-1] < 1e-2
    assert history.largest_gain == pytest.approx(1.0)
    assert 0.2 < np.mean(history.frozen_growth > 0.0) < 0.8


def test_a_tilt_grows_along_a_runaway():
    """In a runaway the cylinders spin up, and the tilt whirls at about their rate and grows (oil whip): the
    aluminium device at 5 degrees multiplies a unit tilt at 0.05 s by 191 in 2 s (bound: 20), its frozen whirl
    then at the spin rate within 10%."""
    aluminium = preset("aluminium", nu=2e-4, alpha=math.radians(5.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        runaway = simulate(aluminium, Initial(kappa=0.5, phi=0.5), t_end=2.0, limits=Limits(on_invalid="warn"))
    assert runaway.regime == "runaway"
    history = tilt_history(runaway, aluminium, t_span=(0.05, 2.0))
    assert history.gain[-1] > 20.0
    assert history.frozen_frequency[-1] == pytest.approx(runaway.columns["omega_a"][-1], rel=0.1)


def test_out_of_range_inputs_are_refused_naming_them(release):
    model = kernel_model("stokes-exact")
    with pytest.raises(ValueError, match="kappa"):
        tilt_coefficients(model, Annulus.from_kappa(A, B, 0.5 * KAPPA_MIN), MOTION, OIL)
    with pytest.raises(ValueError, match="ends"):
        strip_forces(kernel_model("stokes-exact", ends="open", length_over_a=L / A), Annulus.from_kappa(A, B, 0.5,
                     length=L), MOTION, OIL, (0.0, 0.0))
    with pytest.raises(ValueError, match="t_span"):
        tilt_history(release, STEEL, t_span=(20.0, 30.0))


@pytest.fixture(scope="module")
def rough_run():
    """The apparatus on rough surfaces that turn with the cylinders (the rough-surface study's scene), 8 s, every
    step: free flights between contacts."""
    rough = RoughContact.from_rolled_length(ContactParams(1.0 - 50e-6 / (STEEL.b - STEEL.a), math.radians(5.0)),
                                            0.5, 1e-3, STEEL.a, STEEL.b, seed=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        return simulate(STEEL, Initial(kappa=0.5, phi=0.5), t_end=8.0, contact=rough,
                        limits=Limits(on_invalid="warn", max_gap_reynolds=None))


def test_a_flights_tilt_is_that_of_the_free_run_from_its_lift_off(rough_run):
    """Each flight is the free motion from its lift-off until the touch: the free run of smooth walls from the
    lift-off's state, whose rows are other steps, gives the same gain over the flight. The product of
    exponentials on the matrix linear between rows is second order in the rows' spacing: 1e-3 here."""
    tilts = tilt_in_flights(rough_run, STEEL)
    spans = flights(rough_run)
    lifts = sum(event["name"] == "lift" for event in rough_run.events)
    assert len(spans) == lifts + 1 and tilts.start.size == len(spans)  # the release falls free to the first touch
    assert spans[0][0] == 0.0 and np.all(tilts.end > tilts.start)
    cols = rough_run.columns
    for i in (1, int(np.argmax(tilts.gain))):
        start, end = spans[i]
        row = np.flatnonzero(cols["t"] == start)[-1]  # the flight's first row, after the contact phase's last
        assert cols["phase"][row] == 0
        initial = Initial(kappa=cols["kappa"][row], phi=cols["phi"][row], kappa_dot=cols["kappa_dot"][row],
                          phi_dot=cols["phi_dot"][row], omega_a=cols["omega_a"][row], omega_b=cols["omega_b"][row])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            free = simulate(STEEL, initial, t_end=end - start, limits=Limits(on_invalid="warn", max_gap_reynolds=None))
        assert free.columns["kappa"][-1] == pytest.approx(cols["kappa"][cols["t"] == end][0], rel=1e-6)
        assert tilt_history(free, STEEL).largest_gain == pytest.approx(tilts.gain[i], rel=1e-3)


def test_a_span_across_contact_and_a_run_without_flights_are_refused(rough_run, release):
    start, end = flights(rough_run)[1]
    with pytest.raises(ValueError, match="t_span.*contact phases"):
        tilt_history(rough_run, STEEL, t_span=(start, end + 0.5))
    with pytest.raises(ValueError, match="contact phases"):
        tilt_in_flights(release, STEEL)
