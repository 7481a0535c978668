"""Rough contact in the reduced model (section 5): phases, switching, steady rolling (5.6)-(5.12), (6.1)-(6.4)."""

import functools
import math
import re

import numpy as np
import pytest

from dynamics.apparatus import STEEL
from dynamics.contact.reduced import (
    FREE,
    LOCKED,
    SLIDING,
    ContactParams,
    locked_friction,
    locked_jacobian,
    locked_rhs,
    phase_args,
    run_contact,
    sliding_jacobian,
    sliding_rhs,
)
from dynamics.contact.steady import (
    compact_steady_rates,
    onset_of_sliding,
    steady_locked,
    steady_sliding,
    steady_speed,
    steady_state,
)
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.simulation import Initial, simulate
from dynamics.trajectory import PHASE_CODES

FIG7 = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)  # figures 7 and 8: Upsilon = mu_ = 1, s = 1/4
KAPPA_STAR = 0.98  # figures 7 and 8
RELEASE = (0.5, 0.3)  # (kappa0, phi0) of figure 2, which figure 7 repeats; at rest
FREE_CODE, SLIDING_CODE, LOCKED_CODE = PHASE_CODES[FREE], PHASE_CODES[SLIDING], PHASE_CODES[LOCKED]


def contact_run(params, contact, t_end, kappa0, phi0, omega_a0=0.0, omega_b0=0.0, **options):
    """:func:`dynamics.simulation.simulate` of the reduced model with rough contact (scaled units)."""
    return simulate(params, Initial(kappa0, phi0, omega_a=omega_a0, omega_b=omega_b0), t_end, contact=contact,
                    **options)


@functools.cache
def _run(s, kappa_star, psi, t_end, kappa0=RELEASE[0], phi0=RELEASE[1], rtol=1e-8, method="radau"):
    """A cached hybrid run from figure 2's release (several tests read the same runs)."""
    return contact_run(ReducedParams(s, 1.0, 1.0), ContactParams(kappa_star, psi), t_end, kappa0, phi0,
                       rtol=rtol, method=method, limits=Limits(max_turns=1e6))


def _switches(traj):
    """(from, to) of each phase switch."""
    return [(sw["from"], sw["to"]) for sw in traj.info["switches"]]


def _angle_error(phi, phi_ref):
    return (phi - phi_ref + math.pi) % (2.0 * math.pi) - math.pi


def _polar_residuals(params, contact, phi, omega_a, omega_b, phi_dot, omega_a_dot, omega_b_dot, c_x):
    """Residuals of (2.11b), (5.2) and (2.11d) as printed, at kappa = kappa*."""
    k, z = contact.kappa_star, contact.zeta_star
    ups, mu_ = params.upsilon, params.mu_ratio
    torque = (z * z * (omega_b - phi_dot) - (1.0 + 2.0 * k * k) * (omega_a - phi_dot)) / (3.0 * (2.0 + k * k) * z)
    return (k * (omega_a + omega_b - 2.0 * phi_dot) / ((2.0 + k * k) * z) + math.sin(phi),
            torque - 0.5 * ups * omega_a_dot - c_x,
            mu_ * ups * omega_b_dot + 0.5 * ups * omega_a_dot - params.s - k * math.sin(phi))


# -- the phase equations ------------------------------------------------------------

CONTACT_STATES = [(2.5, 0.7, -1.2, 3.0), (4.0, 3.0, 2.5, -1.0), (3.3, -0.3, 0.1, 0.0)]


@pytest.mark.parametrize("sigma", [1.0, -1.0, 0.0])
@pytest.mark.parametrize(("phi", "omega_a", "omega_b", "x_b"), CONTACT_STATES)
@pytest.mark.parametrize("kappa_star", [0.3, 0.98, 0.999999])
def test_sliding_rhs_satisfies_the_printed_equations(phi, omega_a, omega_b, x_b, sigma, kappa_star):
    """(2.11b), (5.2) with C_x = sigma tan(psi) cos(phi), (2.11d), at kappa = kappa*.

    Residuals relative to the largest term: the torque carries 1/zeta* (700
    at kappa* = 0.999999), so rounding is amplified to ~1e-13 there.
    """
    params, contact = ReducedParams(0.4, 0.7, 2.0), ContactParams(kappa_star, 0.3)
    f = sliding_rhs(0.0, np.array([phi, omega_a, omega_b, x_b]), phase_args(params, contact, sigma))
    c_x = sigma * math.tan(0.3) * math.cos(phi)
    scale = 1.0 + abs(omega_b - omega_a) / contact.zeta_star
    residuals = _polar_residuals(params, contact, phi, omega_a, omega_b, *f[:3], c_x)
    np.testing.assert_allclose(residuals, 0.0, atol=1e-13 * scale)
    assert f[3] == omega_b


@pytest.mark.parametrize(("phi", "omega", "x_b"), [(2.5, 0.7, 3.0), (4.0, -2.0, 0.0)])
@pytest.mark.parametrize("kappa_star", [0.3, 0.98])
def test_locked_rhs_and_friction_5_4(phi, omega, x_b, kappa_star):
    """Locked: (2.11b), (2.11d) with Omega_a = Omega_b, and (5.2) closed by the friction (5.4)."""
    params, contact = ReducedParams(0.4, 0.7, 2.0), ContactParams(kappa_star, 0.3)
    f = locked_rhs(0.0, np.array([phi, omega, x_b]), phase_args(params, contact))
    c_lock = locked_friction(params, kappa_star, phi)
    residuals = _polar_residuals(params, contact, phi, omega, omega, f[0], f[1], f[1], c_lock)
    np.testing.assert_allclose(residuals, 0.0, atol=1e-14)
    assert f[2] == omega


@pytest.mark.parametrize("kappa_star", [0.3, 0.98, 0.999999])
@pytest.mark.parametrize("sigma", [1.0, -1.0])
def test_jacobians_against_finite_differences(kappa_star, sigma):
    """Central differences, step 1e-6: truncation ~1e-12 x third derivatives (<= 1/zeta* ~ 1e3)."""
    params, contact = ReducedParams(0.4, 0.7, 2.0), ContactParams(kappa_star, 0.6)
    for fun, jac, y in ((lambda y: sliding_rhs(0.0, y, phase_args(params, contact, sigma)),
                         sliding_jacobian(0.0, np.array([2.5, 0.7, -1.2, 3.0]), phase_args(params, contact, sigma)),
                         np.array([2.5, 0.7, -1.2, 3.0])),
                        (lambda y: locked_rhs(0.0, y, phase_args(params, contact)),
                         locked_jacobian(0.0, np.array([4.0, -2.0, 1.0]), phase_args(params, contact)),
                         np.array([4.0, -2.0, 1.0]))):
        h = 1e-6
        numeric = np.column_stack([(fun(y + h * e) - fun(y - h * e)) / (2.0 * h) for e in np.eye(y.size)])
        np.testing.assert_allclose(jac, numeric, rtol=1e-7, atol=1e-7)


# -- steady rolling (5.6)-(5.12) --------------------------------------------------------

@pytest.mark.parametrize("kappa_star", [0.5, 0.98, 0.999999])
@pytest.mark.parametrize("s", [0.05, 0.25, 0.45, -0.25])
@pytest.mark.parametrize("psi", [0.0, 0.05, 0.5, 1.5])
def test_steady_states_are_fixed_points(s, kappa_star, psi):
    """Both branches zero the contact right-hand sides; the friction obeys its phase's law."""
    params, contact = ReducedParams(s, 1.3, 1.7), ContactParams(kappa_star, psi)
    locked = steady_locked(s, kappa_star)
    assert math.sin(locked.phi) == pytest.approx(-s / kappa_star, abs=1e-15)  # (5.6)
    assert locked.c_eps == pytest.approx(-math.cos(locked.phi), abs=1e-15) and locked.c_eps > 0.0
    assert locked.c_chi == pytest.approx(locked_friction(params, kappa_star, locked.phi), abs=1e-15)
    # Rates are O(zeta*); 1e-13 relative to their scale 3 zeta* |s| and 1/zeta* amplification.
    tol = 1e-13 * (1.0 + 3.0 * contact.zeta_star * abs(s)) / contact.zeta_star
    f = locked_rhs(0.0, np.array([locked.phi, locked.omega_a, 0.0]), phase_args(params, contact))
    np.testing.assert_allclose(f[:2], 0.0, atol=tol)
    # The sliding fixed point, of the phase with sigma = sgn(s); it is consistent
    # (sgn(D) = sigma) exactly where (5.5) fails and steady_state picks it.
    sliding = steady_sliding(s, kappa_star, psi)
    sigma = math.copysign(1.0, s)
    slides = abs(locked.c_chi) >= locked.c_eps * math.tan(psi)
    assert (steady_state(s, kappa_star, psi).phase == SLIDING) == slides
    assert (sigma * (sliding.omega_b - sliding.omega_a) >= 0.0) == slides
    assert sliding.c_chi == pytest.approx(sigma * math.tan(psi) * math.cos(sliding.phi), rel=1e-15)
    f = sliding_rhs(0.0, np.array([sliding.phi, sliding.omega_a, sliding.omega_b, 0.0]),
                    phase_args(params, contact, sigma))
    np.testing.assert_allclose(f[:3], 0.0, atol=tol)


def test_printed_5_11_is_not_a_fixed_point():
    """Erratum 6: (5.11) as printed (an extra 1/2 in both first terms) leaves phi' != 0."""
    s, kappa_star, psi = 0.25, KAPPA_STAR, 0.05
    contact = ContactParams(kappa_star, psi)
    z = contact.zeta_star
    phi = steady_sliding(s, kappa_star, psi).phi
    omega_a = s * z**3 / (2 * kappa_star**2) - 3.0 * z * math.cos(phi) * math.tan(psi)
    omega_b = s * (2.0 + kappa_star**2) * z / (2.0 * kappa_star**2) - omega_a
    f = sliding_rhs(0.0, np.array([phi, omega_a, omega_b, 0.0]), phase_args(FIG7, contact, 1.0))
    assert abs(f[0]) > 0.1 * 3.0 * z * s  # phi' = -(Omega_a + Omega_b)/2 of the printed form
    corrected = steady_sliding(s, kappa_star, psi)
    assert corrected.omega_a + corrected.omega_b == pytest.approx(
        s * (2.0 + kappa_star**2) * z / kappa_star**2, rel=1e-14)


@pytest.mark.parametrize("kappa_star", [0.5, 0.98, 0.9999])
@pytest.mark.parametrize("s", [0.1, 0.25, 0.45])
def test_locking_test_uses_tan_psi(s, kappa_star):
    """Erratum 7: locked iff s < 2 sqrt(1 - s^2/kappa*^2) tan(psi), i.e. psi > onset_of_sliding(s, kappa*)."""
    psi_c = onset_of_sliding(s, kappa_star)
    assert math.tan(psi_c) == pytest.approx(s / (2.0 * math.sqrt(1.0 - (s / kappa_star) ** 2)), rel=1e-14)
    assert steady_state(s, kappa_star, psi_c * 1.001).phase == LOCKED
    assert steady_state(s, kappa_star, psi_c * 0.999).phase == SLIDING
    # The branches meet at the threshold: the rates are continuous in psi.
    np.testing.assert_allclose(steady_sliding(s, kappa_star, psi_c)[2:4], steady_locked(s, kappa_star)[2:4],
                               rtol=1e-13)


@pytest.mark.parametrize(("s", "psi"), [(0.25, 0.5), (0.25, 0.05), (0.25, 0.0), (0.6, 0.2), (0.1, 0.02)])
def test_compact_forms_5_12_to_second_order(s, psi):
    """(5.12) against the exact fixed point, errors relative to the scale 3 zeta* s: O(zeta*^2).

    zeta* from 1e-3 to 3e-2, where the O(zeta*^4) terms are < 1e-3 of the
    leading error; the fitted order is 2 to within 0.02 (measured 2.000).
    """
    zetas = np.geomspace(1e-3, 3e-2, 6)
    errors = []
    for z in zetas:
        kappa_star = math.sqrt(1.0 - z * z)
        exact = steady_state(s, kappa_star, psi)
        compact = compact_steady_rates(s, kappa_star, psi)
        errors.append(max(abs(exact.omega_a - compact[0]), abs(exact.omega_b - compact[1])) / (3.0 * z * s))
    order = np.polyfit(np.log(zetas), np.log(errors), 1)[0]
    assert order == pytest.approx(2.0, abs=0.02)


def test_onset_6_4_is_the_compact_limit_of_the_locking_test():
    """(6.4) tan(psi) = s/(2 sqrt(1 - s^2)) is the exact threshold at zeta* -> 0, off by O(zeta*^2)."""
    s = 0.25
    assert math.tan(onset_of_sliding(s)) == pytest.approx(s / (2.0 * math.sqrt(1.0 - s * s)), rel=1e-15)
    zetas = np.geomspace(1e-3, 3e-2, 5)
    gaps = [onset_of_sliding(s, math.sqrt(1.0 - z * z)) - onset_of_sliding(s) for z in zetas]
    assert np.polyfit(np.log(zetas), np.log(gaps), 1)[0] == pytest.approx(2.0, abs=0.02)


def test_steady_speed_6_1():
    """(6.1) is b Omega_b / tau with Omega_b of (5.12); exact=True uses the exact Omega_b."""
    app, kappa_star = STEEL, 0.98
    s = app.s
    for psi in (0.02, 0.5):  # sliding and locked on the steel apparatus' slope s = 0.17
        v = steady_speed(app.v_star, app.alpha, s, kappa_star, psi)
        assert v == pytest.approx(app.b * compact_steady_rates(s, kappa_star, psi)[1] / app.tau, rel=1e-12)
        v_exact = steady_speed(app.v_star, app.alpha, s, kappa_star, psi, exact=True)
        assert v_exact == pytest.approx(app.b * steady_state(s, kappa_star, psi).omega_b / app.tau, rel=1e-12)
    # Locked on small slopes: V = V* zeta* sin(alpha) / 2.
    zeta = math.sqrt(1.0 - kappa_star**2)
    assert steady_speed(app.v_star, app.alpha, s, kappa_star, 0.5) == pytest.approx(
        app.v_star * zeta * math.sin(app.alpha) / 2.0, rel=1e-14)


# -- simulations: figures 7 and 8, convergence, onset -------------------------------

@pytest.mark.parametrize(("psi", "branch"), [(0.5, LOCKED), (0.05, SLIDING), (0.0, SLIDING)])
def test_figure8_runs_settle_on_the_steady_state(psi, branch):
    """Figure 8 (and 7, psi = 0.05): free -> contact, then the fixed point to 1e-6 by t = 300.

    The contact rocking decays at about (3/4) zeta* |cos(phi)| = 0.14 per
    tau, so 300 tau leave e^-40 of it: what remains is the integration error,
    measured <= 2.1e-13 at rtol 1e-8 (a fixed point is integrated exactly).
    """
    traj = _run(0.25, KAPPA_STAR, psi, 300.0)
    c = traj.columns
    assert traj.status == "completed" and traj.event == ""
    assert c["phase"][0] == FREE_CODE and traj.info["switches"][0]["from"] == FREE
    assert traj.info["final_phase"] == branch and c["phase"][-1] == PHASE_CODES[branch]
    steady = steady_state(0.25, KAPPA_STAR, psi)
    assert steady.phase == branch
    assert abs(_angle_error(c["phi"][-1], steady.phi)) < 1e-6
    assert c["omega_a"][-1] == pytest.approx(steady.omega_a, abs=1e-6)
    assert c["omega_b"][-1] == pytest.approx(steady.omega_b, abs=1e-6)
    assert c["c_chi"][-1] == pytest.approx(steady.c_chi, abs=1e-6)
    assert np.all(np.isfinite(c["omega_a"])) and np.all(np.diff(traj.t) >= 0.0)
    # In contact kappa is kappa* exactly; when free it never exceeds it.
    touching = c["phase"] != FREE_CODE
    assert np.all(c["kappa"][touching] == KAPPA_STAR) and np.all(c["kappa"][~touching] <= KAPPA_STAR)
    # Coulomb (5.3) and a pushing reaction at every sample (rounding allowed).
    assert np.all(c["c_eps"][touching] > 0.0)
    assert np.all(np.abs(c["c_chi"]) <= c["c_eps"] * math.tan(psi) + 1e-15)
    if psi == 0.0:
        assert np.all(c["c_chi"] == 0.0)


def test_figure7_sliding_settles():
    """Figure 7 (psi = 0.05): one touch, sliding ever after, with sgn(D) > 0 as (5.11) has it."""
    traj = _run(0.25, KAPPA_STAR, 0.05, 300.0)
    c = traj.columns
    assert _switches(traj) == [(FREE, SLIDING)]
    assert [e["name"] for e in traj.events] == ["touch"]
    late = traj.t > 50.0
    assert np.all(c["omega_b"][late] > c["omega_a"][late])
    # The jump-free touch: Omega_a is continuous when the contact slides.
    i = np.flatnonzero(c["phase"] == SLIDING_CODE)[0]
    assert traj.t[i] == traj.t[i - 1] and c["omega_a"][i] == c["omega_a"][i - 1]
    assert traj.rows[i - 1] == "event:touch" and traj.rows[i] == "start"


def test_locking_on_touch_makes_omega_a_jump():
    """Figure 8, psi = 0.5: (5.5) holds on touching, so Omega_a jumps to Omega_b (the paper's rule)."""
    traj = _run(0.25, KAPPA_STAR, 0.5, 300.0)
    c = traj.columns
    assert _switches(traj) == [(FREE, LOCKED)]
    i = np.flatnonzero(c["phase"] == LOCKED_CODE)[0]
    assert traj.t[i] == traj.t[i - 1] == traj.info["switches"][0]["t"]
    assert abs(c["omega_b"][i - 1] - c["omega_a"][i - 1]) > 0.1  # a real jump here
    assert c["omega_a"][i] == c["omega_b"][i] == c["omega_b"][i - 1]
    assert c["phi"][i] == c["phi"][i - 1]


def test_contact_is_located_to_the_tolerance():
    """kappa of a tight free-flight reference at the located touch is kappa* to ~rtol.

    The event is a root of r - r* on the dense output to 4 eps; what is left
    is the global error of the free flight, measured 0.03, 0.02, 0.04 rtol in
    (1 - kappa) at rtol 1e-6, 1e-8, 1e-10: bounded here by 10 rtol.
    """
    for rtol in (1e-6, 1e-8, 1e-10):
        traj = _run(0.25, KAPPA_STAR, 0.05, 10.0, rtol=rtol)
        c = traj.columns
        t_touch = traj.info["switches"][0]["t"]
        i = np.flatnonzero(c["phase"] != FREE_CODE)[0]
        assert traj.t[i - 1] == t_touch
        assert c["kappa"][i - 1] == pytest.approx(KAPPA_STAR, abs=1e-15)  # on the dense output
        ref = simulate(FIG7, Initial(*RELEASE), t_touch, t_eval=[t_touch], rtol=1e-13)
        assert ref.columns["one_minus_kappa"][-1] == pytest.approx(1.0 - KAPPA_STAR, rel=10.0 * rtol)


def test_sedimentation_touches_at_the_closed_form_time():
    """(3.3): r = t + r0 exactly, so the touch is at t* = r* - r0; then locked at rest at phi = pi."""
    contact = ContactParams(0.999, 0.1)
    traj = contact_run(ReducedParams(0.0, 1.0, 1.0), contact, 100.0, 0.5, math.pi)
    c = traj.columns
    t_star = contact.r_star - 0.5 / math.sqrt(0.75)
    assert _switches(traj) == [(FREE, LOCKED)]
    assert traj.info["switches"][0]["t"] == pytest.approx(t_star, rel=1e-14)  # the integrator is exact on a line
    # At rest: (2.11d) gives Omega' = 0 and (2.11b) phi' = Omega; 1e-10 allows rtol-sized drift.
    assert c["phi"][-1] == pytest.approx(math.pi, abs=1e-10)
    assert abs(c["omega_a"][-1]) < 1e-10 and c["c_chi"][-1] == pytest.approx(0.0, abs=1e-10)


@pytest.mark.parametrize("psi", [0.0, 0.3, 1.4, 0.5 * math.pi - 1e-6])
def test_lift_off_where_the_reaction_would_pull(psi):
    """Swung up the side (s = 0, phi from pi/2 + 0.3 downwards): contact ends at cos(phi) = 0.

    With psi = 1.4 and pi/2 - 1e-6 the contact starts locked, and the
    vanishing bound |cos(phi)| tan(psi) unlocks it just before lift-off.
    """
    contact = ContactParams(KAPPA_STAR, psi)
    traj = contact_run(ReducedParams(0.0, 1.0, 1.0), contact, 3.0, KAPPA_STAR, 0.5 * math.pi + 0.3, -3.0, -3.0)
    c = traj.columns
    switches = traj.info["switches"]
    assert switches[-1]["to"] == FREE and switches[-1]["from"] == SLIDING
    if psi > 1.0:
        assert c["phase"][0] == LOCKED_CODE
    i = np.flatnonzero(c["phase"] == FREE_CODE)[0]
    # The event is a root of cos(phi) to 4 eps in time; |phi'| ~ 3.
    assert abs(math.cos(c["phi"][i])) < 1e-13
    assert np.all(c["c_eps"][:i] >= -1e-13)  # the reaction never pulled
    # Free again: (2.11a) kappa' = -zeta^3 cos(phi) < 0 just after.
    assert np.all(np.diff(c["kappa"][i:i + 20]) <= 0.0) and c["kappa"][-1] < KAPPA_STAR - 1e-3
    assert c["c_eps"][-1] == 0.0


@pytest.mark.parametrize(("kappa_star", "psi_c"), [(KAPPA_STAR, onset_of_sliding(0.25, KAPPA_STAR)),
                                                  (0.9999, onset_of_sliding(0.25))])
@pytest.mark.parametrize("factor", [0.98, 1.02])
def test_simulated_branch_switches_at_the_onset(kappa_star, psi_c, factor):
    """2% either side of the onset the run settles on the sliding / the locked branch.

    At kappa* = 0.9999 (zeta* = 0.014) the exact threshold is (6.4) to
    2e-5, far inside the 2%; its rocking decays at ~0.01 per tau, so
    1500 tau bring it to within 1e-5 of the fixed point (measured 1.4e-6 by t = 1000,
    5e-13 by 1500).
    """
    psi = factor * psi_c
    traj = _run(0.25, kappa_star, psi, 1500.0)
    c = traj.columns
    steady = steady_state(0.25, kappa_star, psi)
    assert steady.phase == (SLIDING if factor < 1.0 else LOCKED)
    assert traj.info["final_phase"] == steady.phase
    assert c["omega_b"][-1] == pytest.approx(steady.omega_b, abs=1e-5)
    assert c["omega_a"][-1] == pytest.approx(steady.omega_a, abs=1e-5)
    # Near the onset the rocking sticks and slips, each switch an exact event,
    # and the steps stay those of the rocking (measured <= 3,830).
    assert 1 < len(traj.info["switches"]) < 50 and traj.steps < 30_000


@pytest.mark.parametrize("psi", [0.0, 0.5 * math.pi - 1e-6])
def test_extremes_near_contact_and_friction(psi):
    """kappa* = 0.999999 with no friction or tan(psi) = 1e6: finite, and no step-size collapse.

    1500 tau: the rocking free approach (3.9) reaches kappa* at t = 731, then
    contact. Measured 8,900 steps, about 6 a tau over rocking periods of 8;
    a collapsed step would need millions, so 40,000 bounds it.
    """
    traj = _run(0.25, 0.999999, psi, 1500.0)
    c = traj.columns
    assert traj.status == "completed" and traj.steps < 40_000
    assert _switches(traj) == [(FREE, LOCKED if psi > 0.0 else SLIDING)]
    for name in ("t", "kappa", "one_minus_kappa", "phi", "omega_a", "omega_b", "x_b", "c_eps", "c_chi"):
        assert np.all(np.isfinite(c[name])), name
    touching = c["phase"] != FREE_CODE
    assert np.all(c["one_minus_kappa"][touching] == pytest.approx(1e-6, rel=1e-9))
    assert np.all(np.abs(c["c_chi"]) <= c["c_eps"] * math.tan(psi) * (1.0 + 1e-12))


@pytest.mark.slow
@pytest.mark.parametrize("psi", [0.0, 0.5 * math.pi - 1e-6])
def test_extremes_settle_on_the_steady_state(psi):
    """kappa* = 0.999999 over 2e4 tau: within 1e-6 of the fixed point.

    The contact rocking decays at about (3/4) zeta* |cos(phi)| = 1e-3 per
    tau, so 2e4 tau after the touch at 731 leave ~e^-19 of it (measured
    errors <= 5e-16, rates being 3 zeta* s = 1e-3).
    """
    traj = _run(0.25, 0.999999, psi, 2e4)
    c = traj.columns
    steady = steady_state(0.25, 0.999999, psi)
    assert traj.status == "completed" and traj.info["final_phase"] == steady.phase
    assert abs(_angle_error(c["phi"][-1], steady.phi)) < 1e-6
    assert c["omega_a"][-1] == pytest.approx(steady.omega_a, abs=1e-6)
    assert c["omega_b"][-1] == pytest.approx(steady.omega_b, abs=1e-6)


@pytest.mark.parametrize("method", ["Radau", "BDF", "LSODA"])
def test_methods_agree(method):
    """Stick-slip (psi = 0.13, near the onset): switches and state at t = 20 agree across solvers.

    Switch times and states to 1e-6, against the compiled Radau IIA, all at
    rtol = atol = 1e-10. The multistep methods' global error at rtol 1e-8
    (a few 1e-7 in the state) is amplified some thousandfold in the times of
    the stick and slip events, whose guards D and (5.5) cross zero slowly
    near the onset (BDF's last slip is 1.2e-5 off at rtol 1e-8); at 1e-10
    measured 3.5e-7 (BDF), 5e-9 (LSODA), 1e-10 (Radau); states at t = 20
    within 7e-9.
    """
    ref = _run(0.25, KAPPA_STAR, 0.13, 20.0, rtol=1e-10)
    traj = _run(0.25, KAPPA_STAR, 0.13, 20.0, rtol=1e-10, method=method)
    assert len(_switches(ref)) >= 3 and _switches(traj) == _switches(ref)
    np.testing.assert_allclose([sw["t"] for sw in traj.info["switches"]], [sw["t"] for sw in ref.info["switches"]],
                               atol=1e-6)
    for name in ("phi", "omega_a", "omega_b", "x_b"):
        assert traj.columns[name][-1] == pytest.approx(ref.columns[name][-1], abs=1e-6), name


# -- arguments ------------------------------------------------------------------------

@pytest.mark.parametrize(("kwargs", "words"), [
    ({"kappa_star": 1.0, "psi": 0.1}, "kappa_star must be in (0, 1)"),
    ({"kappa_star": 0.0, "psi": 0.1}, "kappa_star must be in (0, 1)"),
    ({"kappa_star": 0.9, "psi": 0.5 * math.pi}, "psi must be in [0, 1.5708) rad"),
    ({"kappa_star": 0.9, "psi": -0.1}, "psi must be in"),
    ({"kappa_star": float("nan"), "psi": 0.1}, "kappa_star"),
])
def test_invalid_contact_params(kwargs, words):
    with pytest.raises(ValueError, match=re.escape(words)):
        ContactParams(**kwargs)


def test_invalid_simulation_arguments():
    contact = ContactParams(0.9, 0.1)
    with pytest.raises(ValueError, match=re.escape("initial.kappa must be in [0, kappa_star] = [0, 0.9]")):
        contact_run(FIG7, contact, 1.0, 0.95, 0.0)
    with pytest.raises(ValueError, match="method must be one of"):
        contact_run(FIG7, contact, 1.0, 0.5, 0.0, method="RK45")
    with pytest.raises(ValueError, match=re.escape("t_end must be in (0, inf) tau")):
        contact_run(FIG7, contact, 0.0, 0.5, 0.0)
    with pytest.raises(ValueError, match="s must be in"):
        steady_state(0.95, 0.9, 0.1)  # no contact fixed point for s >= kappa*: the pendulum winds


def test_budgets_stop_the_run_with_a_reason():
    fields = run_contact(FIG7, ContactParams(KAPPA_STAR, 0.13), 100.0, *RELEASE, max_switches=2)
    assert fields["status"] == -1 and fields["stop_event"] == "max_switches" and len(fields["switches"]) == 2
    assert "max_switches = 2" in fields["message"]
    traj = contact_run(FIG7, ContactParams(KAPPA_STAR, 0.13), 100.0, *RELEASE, max_steps=50)
    assert traj.status == "failed" and not traj.success and traj.event == ""
    assert "max_steps" in traj.message and traj.steps <= 51
