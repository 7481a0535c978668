"""Rough surfaces that turn with the cylinders in the full equations (dynamics.contact.rough_full).

The device is tests/test_full_contact.py's: the groups of figures 7-8 (s = 1/4,
Upsilon = 1) with mu_ = 1.5 (a physical outer cylinder) at delta/a = 0.01, closed-form
forces, asperities at kappa*_mean = 0.98, released from rest at kappa = 0.5, phi = 0.3.
Each check has an independent reference: the uniform contact's own code, the
reduced rough model, the hard contact as the compliant one stiffens, the energy
identity of (2.1)-(2.4), a closed form or a quadrature.
"""

import functools
import math
import re

import numpy as np
import pytest
from scipy import integrate as si
from scipy.special import gamma

from dynamics.app.run import run_scene
from dynamics.apparatus import Apparatus
from dynamics.contact.laws import (
    Compliance,
    Stribeck,
    friction_coefficient,
    gw_integral,
    gw_load,
    gw_potential,
    height_scale,
)
from dynamics.contact.reduced import ContactParams
from dynamics.contact.rough_full import RoughFullRun, fluid_dissipation
from dynamics.contact.roughness import (
    CLIP_FLOOR,
    CLIP_KNEE,
    RoughContact,
    Spectrum,
    SurfaceHeights,
    _local2_kernel,
    _local_kernel,
    soft_floor,
)
from dynamics.equations import full
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.scenes import SceneError
from dynamics.scenes.load import parse_scene
from dynamics.simulation import Initial, simulate
from dynamics.trajectory import PHASE_CODES
from lubrication.registry import kernel_model

FORCES = kernel_model("closed-form")
AP = Apparatus.from_groups(s=0.25, upsilon=1.0, mu_ratio=1.5, delta_over_a=0.01)
RELEASE = Initial(kappa=0.5, phi=0.3)
KAPPA_STAR = 0.98
CORRELATION = 0.3  # rad on both surfaces
WEIGHT = AP.m_a_reduced * AP.g  # N, the unit of the contact forces
SIGMA = AP.delta * (1.0 - KAPPA_STAR)  # m, the mean minimum gap
FREE, SLIDING, LOCKED = PHASE_CODES["free"], PHASE_CODES["sliding"], PHASE_CODES["locked"]


def surfaces(amplitude, psi=0.05, seed=0, kappa_star=KAPPA_STAR, **laws):
    return RoughContact.from_seed(ContactParams(kappa_star, psi), amplitude, CORRELATION, CORRELATION, seed, **laws)


def compliance(stiffness_over=1000.0, heights="exponential", slip=1e-5):
    """A compliant contact of stiffness ``stiffness_over`` W/sigma."""
    return Compliance(heights=heights, stiffness=stiffness_over * WEIGHT / SIGMA, slip_velocity=slip)


@functools.cache
def rough_run(amplitude, psi, t_tau, *, seed=0, rtol=1e-9, stiffness=None, heights="exponential", slip=1e-5,
              psi_static=None, samples=0, fluid_spin=full.DEFAULT_FLUID_SPIN):
    """A cached rough full-model run (several tests read the same runs); ``samples`` > 0: rows at that many times."""
    laws = {}
    if stiffness is not None:
        laws["compliance"] = compliance(stiffness, heights, slip)
    if psi_static is not None:
        laws["friction"] = Stribeck(psi_static, 1e-3 * AP.b / AP.tau)
    t_eval = np.linspace(0.0, t_tau * AP.tau, samples) if samples else None
    return simulate(AP, RELEASE, t_tau * AP.tau, forces=FORCES, contact=surfaces(amplitude, psi, seed, **laws),
                    rtol=rtol, t_eval=t_eval, fluid_spin=fluid_spin)


def sampled(trajectory, names=("phi", "omega_a", "omega_b", "x_b")):
    """The requested rows of ``names`` in the reduced units (rates times tau, X_b over b)."""
    rows = np.array(["sample" in r for r in trajectory.rows])
    c = trajectory.columns
    scale = {"omega_a": AP.tau, "omega_b": AP.tau, "x_b": 1.0 / AP.b}
    return np.array([c[k][rows] * scale.get(k, 1.0) for k in names])


# -- the field: curvatures and the self-affine spectrum --------------------------------------

@pytest.mark.parametrize("spectrum", [Spectrum(), Spectrum("self-affine", 0.6, 8.0)])
def test_curvatures_are_the_derivatives_of_the_slopes(spectrum, rng):
    """k_aa, k_ab, k_bb against central differences of the slopes, and the compiled field against its twin.

    At amplitude 0.9 and kappa*_mean = 0.6 both clipping floors act somewhere on the torus, so the
    chain rule through them is tested. Step 1e-6 rad: truncation (h^2/6) k'''' and rounding
    eps |k'|/h both ~1e-9 of the largest curvature; tolerance 1e-7 of it. The floors are C^2,
    their third derivative jumps at the knee, so a stencil across a knee errs by O(h): points
    within 1e-3 of a knee are left out. The compiled first four values are those of the reduced
    model's kernel to the bit.
    """
    rough = RoughContact.from_seed(ContactParams(0.6, 0.1), 0.9, 0.3, 0.45, 3, spectrum=spectrum)
    theta_a, theta_b = rng.uniform(-20.0, 20.0, (2, 400))
    bend = rough.curvature(theta_a, theta_b)
    h = 1e-6
    up_a, down_a = rough.local(theta_a + h, theta_b), rough.local(theta_a - h, theta_b)
    up_b, down_b = rough.local(theta_a, theta_b + h), rough.local(theta_a, theta_b - h)
    x = rough.gap_ratio(theta_a, theta_b)[0]
    ratio = 1.0 - 0.4 * (soft_floor(x, CLIP_FLOOR, CLIP_KNEE)[0] - 1.0) / 0.6
    away = (np.abs(x - CLIP_KNEE) > 1e-3) & (np.abs(ratio - CLIP_KNEE) > 1e-3)
    scale = max(np.max(np.abs(b)) for b in bend)
    pairs = ((bend.kappa_aa, up_a.dkappa_a, down_a.dkappa_a), (bend.kappa_ab, up_a.dkappa_b, down_a.dkappa_b),
             (bend.kappa_ab, up_b.dkappa_a, down_b.dkappa_a), (bend.kappa_bb, up_b.dkappa_b, down_b.dkappa_b))
    for got, up, down in pairs:
        np.testing.assert_allclose(got[away], ((up - down) / (2 * h))[away], rtol=0.0, atol=1e-7 * scale)
    assert np.min(x) < CLIP_KNEE and np.sum(~away) <= 3  # the gap's floor is in play
    coefficients = (rough.inner.jets, rough.outer.jets, rough.amplitude, 0.6, 0.4)
    compiled = np.array([_local2_kernel(a, b, *coefficients) for a, b in zip(theta_a, theta_b)]).T
    first = np.array([_local_kernel(a, b, *coefficients) for a, b in zip(theta_a, theta_b)]).T
    assert np.array_equal(compiled[:4], first)
    np.testing.assert_allclose(compiled[4:], np.array(bend), rtol=0.0, atol=1e-11 * scale)


def test_self_affine_spectrum_is_flat_below_the_roll_off_and_falls_as_k_to_the_minus_1_plus_2h():
    """The mean periodogram of 60 surfaces: slope -(1 + 2H) above k = 1/lambda, flat below, cut at K.

    Each mode's mean power is its weight times (A^2 + B^2)/2, a chi-squared mean of 120 degrees
    of freedom (relative scatter 0.13 per mode): the log-log slope fitted over 1960 modes is
    within 0.02 of -(1 + 2H), that over the 20 flat modes within 0.1 of 0, and the two parts
    meet at the roll-off to 10% (measured 6.5% apart: a scatter of 3% over the 1200 flat
    draws, and a bias, as each surface is scaled by its own mean square, which the flat modes
    dominate).
    A surface has zero mean and unit mean square to rounding, and is 2 pi-periodic.
    """
    hurst, lam = 0.7, 0.05  # roll-off at k = 20, cutoff at K = bandwidth/lambda = 2000
    spectrum = Spectrum("self-affine", hurst, 100.0)
    power = np.zeros(2000)
    theta = np.linspace(0.0, 2.0 * math.pi, 4096, endpoint=False)
    for seed in range(60):
        surface = SurfaceHeights.from_rng(lam, np.random.default_rng(seed), spectrum)
        assert surface.modes == 2000
        power += surface.cos_coefficients**2 + surface.sin_coefficients**2
        if seed < 3:  # 4096 points integrate the 2000 modes exactly
            f, _ = surface(theta)
            assert abs(f.mean()) < 1e-13 and np.mean(f * f) == pytest.approx(1.0, rel=1e-12)
    k = np.arange(1, 2001)
    above = k > 40
    slope = np.polyfit(np.log(k[above]), np.log(power[above]), 1)[0]
    assert slope == pytest.approx(-(1.0 + 2.0 * hurst), abs=0.02)
    assert np.polyfit(np.log(k[:20]), np.log(power[:20]), 1)[0] == pytest.approx(0.0, abs=0.1)
    weights = spectrum.amplitudes(lam, 2000) ** 2  # 1 up to k = 20, then (k lambda)^-(1 + 2H)
    flat, tail = np.mean(power[:20] / weights[:20]), np.mean(power[above] / weights[above])
    assert flat == pytest.approx(tail, rel=0.1)
    surface = SurfaceHeights.from_rng(lam, np.random.default_rng(1), spectrum)
    f0, s0 = surface(np.array([0.3]))
    f1, s1 = surface(np.array([0.3 + 6.0 * math.pi]))
    assert f1 == pytest.approx(f0, abs=1e-12) and s1 == pytest.approx(s0, abs=1e-9)


def test_the_spectra_share_the_seeded_draw_and_its_correlation():
    """Same seed, same normal draws: the self-affine and Gaussian coefficients differ by their weights only."""
    gauss = RoughContact.from_seed(ContactParams(0.98, 0.1), 0.5, 0.3, 0.3, 4)
    affine = RoughContact.from_seed(ContactParams(0.98, 0.1), 0.5, 0.3, 0.3, 4, spectrum=Spectrum("self-affine"))
    n = min(gauss.inner.modes, affine.inner.modes)
    ratio = (gauss.inner.cos_coefficients[:n] / affine.inner.cos_coefficients[:n]
             / (Spectrum().amplitudes(0.3, n) / Spectrum("self-affine").amplitudes(0.3, n)))
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)  # one common scaling (each's own mean square)
    delta = np.linspace(0.0, 1.0, 11)
    c = affine.inner.correlation_function(delta)
    assert c[0] == pytest.approx(1.0) and np.all(np.diff(c[:4]) < 0.0)


# -- the uniform limit ----------------------------------------------------------------------

@pytest.mark.parametrize(("psi", "start"), [(0.05, RELEASE), (0.5, RELEASE), (0.13, RELEASE),
                                            (0.5, Initial(kappa=KAPPA_STAR, phi=3.5))])
def test_amplitude_zero_reproduces_the_uniform_full_contact_bit_for_bit(psi, start):
    """Sliding (psi 0.05), locked (0.5), stick-slip near the onset (0.13), and a start on the asperities.

    On uniform surfaces the rough phases carry the uniform contact's states and evaluate its
    formulas plus terms that are exactly 0 (dynamics.contact.rough_full), so the runs of
    dynamics.contact.full come back to the bit: every column, switch, step and evaluation count.
    Only the sign of a zero could differ, which array_equal does not see.
    """
    contact = ContactParams(KAPPA_STAR, psi)
    uniform = simulate(AP, start, 100.0 * AP.tau, forces=FORCES, contact=contact, rtol=1e-9)
    rough = simulate(AP, start, 100.0 * AP.tau, forces=FORCES, contact=RoughContact.uniform(contact), rtol=1e-9)
    assert uniform.status == rough.status == "completed"
    assert uniform.info["switches"] == rough.info["switches"] and len(uniform.info["switches"]) >= 1
    assert (uniform.steps, uniform.nfev, uniform.njev, uniform.nlu) == (rough.steps, rough.nfev, rough.njev, rough.nlu)
    assert set(uniform.columns) == set(rough.columns)
    for name, column in uniform.columns.items():
        assert np.array_equal(column, rough.columns[name]), name


def impact_momentum(chi, eps, v, omega_a, omega_b):
    """The (2.4) angular momentum that an impulse between the cylinders cannot change (tests/test_full_contact.py)."""
    x, z = eps * math.sin(chi), eps * math.cos(chi)
    return (0.5 * AP.m_a * AP.a**2 * omega_a + (AP.M + AP.m_b) * AP.b**2 * omega_b
            + AP.m_eff * (z * v[0] - x * v[1]) + AP.m_a_reduced * AP.b * (v[0] + z * omega_b))


def kinetic(v, omega_a, omega_b):
    return (0.5 * (AP.M + AP.m_b) * AP.b**2 * omega_b**2 + AP.m_a_reduced * AP.b * omega_b * v[0]
            + 0.5 * AP.m_eff * (v @ v) + 0.25 * AP.m_a * AP.a**2 * omega_a**2)


@pytest.mark.parametrize("fluid_spin", full.FLUID_SPIN)
@pytest.mark.parametrize(("psi", "sticks"), [(1.2, True), (0.3, False)])
def test_the_impact_on_the_moving_constraint_conserves_angular_momentum_and_loses_energy(psi, sticks, fluid_spin):
    """A touch where the asperities' gap is steep (|d kappa*/d theta| ~ 1): the impulse P_N grad G.

    It stops the approach G' (not eps'), keeps (2.4)'s angular momentum with the fluid's own
    (the impulses are internal, with no net torque about B: to 1e-12), loses kinetic energy
    (without the fluid's spin, whose kinetic energy the closure does not define), and stops the slip
    if the static cone holds the stick impulse, else slides through with |P_F| = mu P_N against the slip.
    """
    run = RoughFullRun(AP, FORCES, surfaces(0.9, psi, seed=5), Limits(), 1e-9, fluid_spin=fluid_spin)
    chi, turned, x_b = math.pi + 0.3, 0.7, 0.3 * AP.b
    kappa, _, ka, kb = run.local(chi, turned, x_b)
    assert max(abs(ka), abs(kb)) > 0.1 * (1.0 - kappa)  # steep: the tilt of grad G is not small
    eps, delta = kappa * AP.delta, AP.delta
    e_eps, e_chi = np.array([math.sin(chi), math.cos(chi)]), np.array([math.cos(chi), -math.sin(chi)])
    v = (0.2 * e_eps + 0.3 * e_chi) * delta / AP.tau
    omega_b = 0.1 / AP.tau
    slip_before = (0.01 if sticks else 100.0) * 0.2 * delta / AP.tau
    omega_a = (slip_before - e_chi @ v + (AP.a + eps) * omega_b) / AP.a

    def approach(v, omega_a, omega_b):  # -G'
        chi_dot = (e_chi @ v) / eps
        return e_eps @ v - delta * (ka * (chi_dot - omega_a) + kb * (chi_dot - omega_b))

    assert approach(v, omega_a, omega_b) > 0.0
    v1, wa1, wb1, p_n, p_f = run.impact(chi, turned, x_b, v, omega_a, omega_b)
    assert p_n > 0.0
    assert abs(approach(v1, wa1, wb1)) < 1e-12 * delta / AP.tau
    j_a, j_b, big_k, _ = full.spin_state(run.p, kappa, eps, 0.0, 0.0, 0.0, 0.0)

    def momentum(velocity, w_a, w_b):
        return impact_momentum(chi, eps, velocity, w_a, w_b) + j_a * w_a + j_b * w_b + big_k * eps * (e_chi @ velocity)

    assert momentum(v1, wa1, wb1) == pytest.approx(momentum(v, omega_a, omega_b), rel=1e-12)
    if fluid_spin == "none":
        assert kinetic(v1, wa1, wb1) < kinetic(v, omega_a, omega_b)
    slip_after = e_chi @ v1 + AP.a * wa1 - (AP.a + eps) * wb1
    if sticks:
        assert abs(slip_after) < 1e-12 * AP.b / AP.tau and abs(p_f) <= run.mu_s * p_n
    else:
        assert abs(p_f) == pytest.approx(run.mu_k * p_n, rel=1e-12)
        assert p_f < 0.0 < slip_after


# -- the compliant contact tends to the hard one ---------------------------------------------------

STIFFNESSES = (400.0, 1600.0, 6400.0, 25600.0)  # W/sigma


@pytest.mark.parametrize("heights", ["exponential", "gaussian"])
def test_compliant_contact_tends_to_the_hard_one_at_first_order_without_friction(heights):
    """Uniform frictionless surfaces: max over 201 times of |phi|, |Omega tau|, |X_b/b| falls as 1/k.

    A stiff contact sits a depth l ln(W/N) = O(1/k) inside the asperities' mean plane, and a
    critically damped touch that stops the approach is plastic in the limit. Slope of the
    log-log fit over k = 400 ... 25600 W/sigma: 1 +- 0.05 (measured 1.005 exponential,
    1.003 Gaussian; 3.1e-6 at the stiffest); the hard run's own error (rtol 1e-10) is far
    below the smallest difference.
    """
    hard = sampled(rough_run(0.0, 0.0, 30.0, rtol=1e-10, samples=201))
    errors = [np.max(np.abs(sampled(rough_run(0.0, 0.0, 30.0, rtol=1e-10, stiffness=k, heights=heights,
                                              samples=201)) - hard)) for k in STIFFNESSES]
    slope = np.polyfit(np.log(STIFFNESSES), np.log(errors), 1)[0]
    assert slope == pytest.approx(-1.0, abs=0.05)
    assert errors[-1] < 1e-5  # measured 3.1e-6


def test_on_rough_surfaces_with_friction_the_impacts_add_a_slower_term():
    """Rough surfaces (amplitude 0.5), sliding friction psi = 0.05: X_b over 201 times.

    Touches now stop the slip too, with an impulse the compliant contact spreads over its
    contact time ~ sqrt(m_eff/k): that adds a term of order k^-1/2 to the first-order offset,
    and the convergence slows from 1 towards 1/2 as k grows. Measured slopes between
    successive stiffnesses 100 ... 25600 W/sigma: 0.97, 0.91, 0.90, 0.91 (fit 0.91; 1.1e-4 b
    at the stiffest): asserted in [0.75, 1.05], each fourfold stiffness dividing the error by
    more than 2 (faster than k^-1/2 in this range).
    """
    hard = sampled(rough_run(0.5, 0.05, 30.0, rtol=1e-10, samples=201), ("x_b",))
    errors = [np.max(np.abs(sampled(rough_run(0.5, 0.05, 30.0, rtol=1e-10, stiffness=k, slip=1e-9, samples=201),
                                    ("x_b",)) - hard)) for k in (100.0, *STIFFNESSES)]
    slope = np.polyfit(np.log(STIFFNESSES), np.log(errors[1:]), 1)[0]
    assert -1.05 < slope < -0.75
    assert all(e1 < e0 / 2.0 for e0, e1 in zip(errors, errors[1:]))


# -- energy ------------------------------------------------------------------------------------

def energy_budget(trajectory, rough: RoughContact, stiffness_over=None):
    """(residuals, dissipated, impact losses) of work of gravity = KE + elastic energy + dissipation.

    From the output rows (every integrator step): the kinetic and potential energy of
    validation.dynamics_checks.mechanical_energy, with r' from kappa' and phi' (no
    differencing); the fluid's dissipation from the force kernel (fluid_dissipation);
    the friction's -F s; the compliant contact's damping c_d d'^2 and elastic energy
    W l e^(-d/l), all recomputed here from the columns and the surfaces. The quasi-steady
    frame terms (the run's ``frame_terms``) add the force full.frame_force to the fluid's,
    which is not a gradient: its power, that of a fluid force with T_a = 0, is a source
    of the budget. The runs leave the fluid's spin out of (2.4) (``fluid_spin = "none"``), whose
    kinetic energy this budget does not hold. Each smooth
    phase is integrated by Simpson's rule on its steps, and has its own residual; the
    energy lost at each switch (an impact) is returned apart.
    """
    c, t = trajectory.columns, trajectory.t
    ap, a, b, delta = AP, AP.a, AP.b, AP.delta
    eps, chi, phi, kd, pd = c["eps"], c["chi"], c["phi"], c["kappa_dot"], c["phi_dot"]
    oa, ob = c["omega_a"], c["omega_b"]
    ex, ez = np.sin(chi), np.cos(chi)
    x_dot, z_dot = ex * delta * kd + ez * eps * pd, ez * delta * kd - ex * eps * pd
    kinetic = (0.5 * (ap.M + ap.m_b) * b * b * ob**2 + ap.m_a_reduced * b * ob * x_dot
               + 0.5 * ap.m_eff * (x_dot**2 + z_dot**2) + 0.25 * ap.m_a * a * a * oa**2)
    potential = ap.m_a_reduced * ap.g * eps * np.cos(phi) - ap.M * ap.g * math.sin(ap.alpha) * c["x_b"]
    fluid = np.array([fluid_dissipation(*FORCES.kernel(FORCES.data, a, b, ap.mu, ap.length, c["kappa"][i],
                                                       c["one_minus_kappa"][i], delta * kd[i], oa[i] - pd[i],
                                                       ob[i] - pd[i]), eps[i], delta * kd[i], pd[i], oa[i], ob[i])
                      for i in range(t.size)])
    p = full.params_array(ap, trajectory.info["frame_terms"])
    frame = np.array([full.frame_force(p, eps[i], delta * kd[i], pd[i], oa[i], ob[i]) for i in range(t.size)])
    frame_power = -np.array([fluid_dissipation(*frame[i], 0.0, eps[i], delta * kd[i], pd[i], oa[i], ob[i])
                             for i in range(t.size)])
    slip = eps * pd + a * oa - (a + eps) * ob
    friction = c["c_chi"] * ap.delta_over_a * WEIGHT * slip  # -F s, F = -c_chi (delta/a) W
    damping, elastic = np.zeros(t.size), np.zeros(t.size)
    if stiffness_over is not None:
        ell, _ = height_scale("exponential", WEIGHT, stiffness_over * WEIGHT / SIGMA)
        here = rough.local(c["theta_a"], c["theta_b"])
        d = delta * (c["one_minus_kappa"] - here.one_minus_kappa)
        d_dot = delta * (here.dkappa_a * (pd - oa) + here.dkappa_b * (pd - ob) - kd)
        load = WEIGHT * np.exp(-d / ell)
        damping = 2.0 * rough.compliance.damping_ratio * np.sqrt(ap.m_eff * load / ell) * d_dot**2
        elastic = WEIGHT * ell * np.exp(-d / ell)
    power = WEIGHT * AP.b / AP.tau  # W, the scale of the contact's power
    assert np.all(fluid >= -1e-15 * power) and np.all(friction >= -1e-12 * power)  # rounding at the switches
    energy = kinetic + potential + elastic
    cuts = [0, *np.flatnonzero(np.diff(t) == 0.0) + 1, t.size]  # a switch repeats its time
    dissipated, losses, residuals = 0.0, [], []
    for start, stop in zip(cuts, cuts[1:]):
        if start > 0:
            losses.append((trajectory.rows[start - 1], energy[start - 1] - energy[start]))
        here = si.simpson((fluid + friction + damping - frame_power)[start:stop], x=t[start:stop])
        residuals.append(energy[stop - 1] - energy[start] + here)
        dissipated += here
    return np.array(residuals), dissipated, losses


@pytest.mark.parametrize("rtol", [1e-8, 1e-10])
def test_energy_balance_of_a_hard_rough_run(rtol):
    """Stribeck friction (psi 0.1, static 0.3), amplitude 0.5: touches, sliding, locking, lift-offs.

    On each smooth phase the work of gravity equals the change of kinetic energy plus the
    film's and the friction's dissipation: the reaction N grad G does no work on the moving
    constraint (G' = 0). Energy is lost only at the touches (plastic impacts: 2.1e-8 and
    1.1e-9 of the energy dissipated), none at lift, stick or slip. Each of the 8 phases'
    residuals is below 10 rtol of the energy dissipated over the run (measured at most 2.0
    rtol at 1e-8, 2.1 rtol at 1e-10, 1.9 rtol at 1e-12): it follows the tolerance, as the
    integrator's global error does.
    """
    run = rough_run(0.5, 0.1, 100.0, rtol=rtol, psi_static=0.3, fluid_spin="none")
    switches = [sw["to"] for sw in run.info["switches"]]
    assert {"locked", "sliding", "free"} <= set(switches)
    residuals, dissipated, losses = energy_budget(run, surfaces(0.5, 0.1, friction=Stribeck(0.3, 1.0)))
    assert np.max(np.abs(residuals)) < 10.0 * rtol * dissipated
    for row, loss in losses:
        if "touch" in row:
            assert loss >= 0.0
        else:
            assert abs(loss) < 1e-9 * dissipated, row


@pytest.mark.parametrize("rtol", [1e-8, 1e-10])
def test_energy_balance_of_a_compliant_rough_run(rtol):
    """The compliant contact with Stribeck friction: one smooth phase, no impact losses.

    Work of gravity = kinetic + elastic energy + the film's, the friction's and the damping's
    dissipation, residual below 10 rtol of the energy dissipated (measured 0.34 rtol at 1e-8,
    1.4 rtol at 1e-10: it follows the tolerance).
    """
    run = rough_run(0.5, 0.1, 30.0, rtol=rtol, stiffness=1000.0, psi_static=0.3, fluid_spin="none")
    rough = surfaces(0.5, 0.1, friction=Stribeck(0.3, 1.0), compliance=compliance(1000.0))
    residuals, dissipated, losses = energy_budget(run, rough, stiffness_over=1000.0)
    assert losses == [] and np.all(run.columns["phase"] == PHASE_CODES["compliant"])
    assert np.max(run.columns["c_eps"]) > 0.5  # it did touch, with a load of the weight's order (1.6)
    assert abs(residuals[0]) < 10.0 * rtol * dissipated


# -- seeds ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("stiffness", [None, 1000.0])
def test_a_seed_gives_the_same_run_and_another_seed_another(stiffness):
    one = rough_run(0.5, 0.05, 60.0, seed=1, stiffness=stiffness)
    law = {} if stiffness is None else {"compliance": compliance(stiffness)}
    again = simulate(AP, RELEASE, 60.0 * AP.tau, forces=FORCES, contact=surfaces(0.5, 0.05, 1, **law), rtol=1e-9)
    other = rough_run(0.5, 0.05, 60.0, seed=2, stiffness=stiffness)
    assert one.info["switches"] == again.info["switches"]
    for name, column in one.columns.items():
        assert np.array_equal(column, again.columns[name]), name
    assert one.columns["x_b"][-1] != other.columns["x_b"][-1]
    assert one.info["switches"] != other.info["switches"] or stiffness is not None


# -- the limit delta/a -> 0 ---------------------------------------------------------------------------

def test_full_rough_model_tends_to_the_reduced_rough_model_at_first_order_in_delta_over_a():
    """(s, Upsilon, mu_) = (1/4, 1, 1.5) held, the same surfaces, 20 tau from the release.

    The full model (closed forms) against dynamics.contact.rough: max over 401 times of
    |kappa|, |phi|, |Omega tau| and |X_b/b|. Friction psi = 0.05 slides through every
    touch, where the two models agree (a locking touch makes Omega_a jump in section 5's
    model but not in the impact law). Slope 1 +- 0.05 over delta/a = 0.02 ... 0.0025
    (measured 0.998), difference below 2 delta/a (measured 1.26 delta/a at 0.0025).
    """
    s, upsilon, mu = 0.25, 1.0, 1.5
    rough = surfaces(0.5, 0.05)
    t = np.linspace(0.0, 20.0, 401)
    names = ("kappa", "phi", "omega_a", "omega_b", "x_b")
    reduced = simulate(ReducedParams(s, upsilon, mu), RELEASE, 20.0, contact=rough, rtol=1e-10,
                       limits=Limits(max_turns=1e6))
    reference = np.array([np.interp(t, reduced.columns["t_tau"], reduced.columns[k]) for k in names])
    ratios = np.array([0.02, 0.01, 0.005, 0.0025])
    diffs = []
    for ratio in ratios:
        ap = Apparatus.from_groups(s, upsilon, mu, ratio)
        run = simulate(ap, RELEASE, 20.0 * ap.tau, forces=FORCES, contact=rough, rtol=1e-10,
                       limits=Limits(max_gap_reynolds=None, max_turns=1e6))
        assert run.status == "completed"
        scale = {"omega_a": ap.tau, "omega_b": ap.tau, "x_b": 1.0 / ap.b}
        got = np.array([np.interp(t, run.columns["t_tau"], run.columns[k] * scale.get(k, 1.0)) for k in names])
        diffs.append(np.max(np.abs(got - reference)))
    slope = np.polyfit(np.log(ratios), np.log(diffs), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.05)
    assert diffs[-1] < 2.0 * ratios[-1]


# -- the contact laws -------------------------------------------------------------------------------

def test_hard_contact_keeps_the_constraint_and_the_friction_laws():
    """Stribeck friction on rough surfaces: every contact row on the local kappa*, N >= 0,
    sliding friction mu(|s|) N against the slip, locked friction inside mu_s N and the slip
    held at 0 (to 1e-10 b/tau; measured 1e-12), lift-offs where N vanishes."""
    run = rough_run(0.5, 0.1, 100.0, psi_static=0.3)
    c = run.columns
    rough = surfaces(0.5, 0.1)
    touching = c["phase"] != FREE
    here = rough.local(c["theta_a"], c["theta_b"])
    np.testing.assert_allclose(c["one_minus_kappa"][touching], here.one_minus_kappa[touching], rtol=1e-13)
    assert np.all(c["one_minus_kappa"][~touching] >= here.one_minus_kappa[~touching] * (1.0 - 1e-7))
    n, f = c["c_eps"] * WEIGHT, -c["c_chi"] * AP.delta_over_a * WEIGHT
    slip = c["eps"] * c["phi_dot"] + AP.a * c["omega_a"] - (AP.a + c["eps"]) * c["omega_b"]
    mu_k, mu_s = AP.delta_over_a * math.tan(0.1), AP.delta_over_a * math.tan(0.3)
    sliding, locked = c["phase"] == SLIDING, c["phase"] == LOCKED
    assert np.all(n[touching] >= -1e-12 * WEIGHT)
    mu = np.array([friction_coefficient(s, mu_k, mu_s, 1e-3 * AP.b / AP.tau) for s in slip[sliding]])
    np.testing.assert_allclose(np.abs(f[sliding]), mu * n[sliding], rtol=1e-12, atol=1e-15 * WEIGHT)
    assert np.all(f[sliding] * slip[sliding] <= 1e-12 * WEIGHT * AP.b / AP.tau)  # rounding at stick, lift rows
    assert np.all(np.abs(f[locked]) <= mu_s * n[locked] * (1.0 + 1e-9))
    assert np.max(np.abs(slip[locked])) < 1e-10 * AP.b / AP.tau
    assert friction_coefficient(0.0, mu_k, mu_s, 1.0) == mu_s
    assert friction_coefficient(1e3, mu_k, mu_s, 1.0) == mu_k
    assert friction_coefficient(-4.0, mu_k, mu_s, 2.0) == pytest.approx(mu_k + (mu_s - mu_k) * math.exp(-4.0), rel=1e-15)
    assert friction_coefficient(0.3, mu_k, mu_k, 1e-3) == mu_k  # Coulomb, exactly
    for sw in run.info["switches"]:
        if sw["to"] == "free":
            i = np.flatnonzero(c["t"] == sw["t"])[0]
            assert abs(c["c_eps"][i]) < 1e-9


@pytest.mark.parametrize("x", [-20.0, -3.0, -0.5, 0.0, 1.0, 2.5])
@pytest.mark.parametrize("power", [0.5, 1.5, 2.5])
def test_gw_integrals_against_quadrature_and_closed_forms(x, power):
    """F_n(x) = int_0^inf u^n phi(x + u) du: Gaussian against scipy's quad (where it resolves the
    integrand: 1e-10), at x = 0 the closed form 2^((n-1)/2) Gamma((n+1)/2)/sqrt(2 pi) (1e-13),
    d/dx F_n = -n F_(n-1) by central differences; exponential Gamma(n + 1) e^-x exactly."""
    exact = si.quad(lambda u: u**power * math.exp(-0.5 * (x + u) ** 2) / math.sqrt(2 * math.pi), 0.0, math.inf,
                    epsabs=0.0, epsrel=1e-13, limit=200)[0]
    assert gw_integral(x, power, True) == pytest.approx(exact, rel=1e-10)
    if x == 0.0:
        closed = 2.0 ** ((power - 1.0) / 2.0) * gamma((power + 1.0) / 2.0) / math.sqrt(2.0 * math.pi)
        assert gw_integral(0.0, power, True) == pytest.approx(closed, rel=1e-13)
    h = 1e-4
    slope = (gw_integral(x + h, power, True) - gw_integral(x - h, power, True)) / (2 * h)
    assert slope == pytest.approx(-power * gw_integral(x, power - 1.0, True), rel=1e-7)
    assert gw_integral(x, power, False) == pytest.approx(gamma(power + 1.0) * math.exp(-x), rel=1e-15)


@pytest.mark.parametrize("heights", ["exponential", "gaussian"])
def test_stiffness_and_potential_of_the_compliant_law(heights):
    """-dP/dd at d = 0 is the stiffness asked for (to 1e-8, central differences), P(0) = W, and the
    elastic potential's derivative is -P (1e-8), so the load is conservative."""
    k = 3e6
    ell, norm = height_scale(heights, WEIGHT, k)
    gaussian = heights == "gaussian"
    load = lambda d: WEIGHT * gw_load(d / ell, gaussian, norm)  # noqa: E731
    h = 1e-5 * ell  # truncation (h/l)^2/6 ~ 2e-11, rounding eps l/h ~ 2e-11
    assert load(0.0) == pytest.approx(WEIGHT, rel=1e-14)
    assert -(load(h) - load(-h)) / (2 * h) == pytest.approx(k, rel=1e-8)
    x = np.array([-2.0, -0.3, 0.0, 0.7, 3.0])
    potential = WEIGHT * ell * gw_potential(x, heights)
    slope = WEIGHT * ell * (gw_potential(x + 1e-5, heights) - gw_potential(x - 1e-5, heights)) / (2e-5 * ell)
    np.testing.assert_allclose(slope, -np.array([load(v * ell) for v in x]), rtol=1e-8)
    assert np.all(potential > 0.0)


# -- scenes ----------------------------------------------------------------------------------------

SCENE = """
[groups]
s = 0.25
upsilon = 1.0
mu = 1.5
delta_over_a = 0.01
[initial]
kappa = 0.5
phi = 0.3
[model]
equations = "{equations}"
forces = "closed-form"
[contact]
kappa_star = 0.98
psi = 0.05
roughness_amplitude = 0.5
roughness_correlation = {correlation}
seed = 3
{extra}
[run]
t_end_tau = 20
"""


@pytest.mark.parametrize("extra", ["", 'law = "compliant"', 'roughness_spectrum = "self-affine"\nroughness_hurst = 0.6',
                                   'friction_law = "stribeck"\npsi_static = 0.2\nstribeck_velocity = "1 mm/s"'])
def test_a_rough_scene_runs_in_the_full_equations(extra):
    """roughness_amplitude > 0 with equations = 'full' runs (it was refused), with every new option."""
    trajectory = run_scene(parse_scene(SCENE.format(equations="full", extra=extra, correlation='"2.4 mm"')))
    assert trajectory.status == "completed" and trajectory.equations == "full"
    assert {"theta_a", "theta_b", "phase", "c_eps"} <= set(trajectory.columns)
    assert np.max(trajectory.columns["c_eps"]) > 0.1


@pytest.mark.parametrize(("extra", "message"), [
    ("roughness_hurst = 1.0", "contact.roughness_hurst must be in (0, 1)"),
    ("roughness_bandwidth = 0.5", "contact.roughness_bandwidth must be in [1, 10000]"),
    ('roughness_spectrum = "fractal"', "contact.roughness_spectrum must be one of 'gaussian', 'self-affine'"),
    ('law = "soft"', "contact.law must be one of 'hard', 'compliant'"),
    ('heights = "uniform"', "contact.heights must be one of 'exponential', 'gaussian'"),
    ('stiffness = "-1 N/m"', "contact.stiffness must be in (0, inf) N/m"),
    ('stiffness = "3 m"', "contact.stiffness"),
    ("damping_ratio = 200", "contact.damping_ratio must be in [0, 100]"),
    ('slip_velocity = "0 m/s"', "contact.slip_velocity must be in (0, inf) m/s"),
    ('friction_law = "viscous"', "contact.friction_law must be one of 'coulomb', 'stribeck'"),
    ('friction_law = "stribeck"', "contact.psi_static is missing"),
    ("psi_static = 0.01", "contact.psi_static must be in [psi, 90) deg"),
    ('stribeck_velocity = "-1 mm/s"', "contact.stribeck_velocity must be in (0, inf) m/s"),
    ('static_friction_angle = "1 deg"\npsi_static = 0.2', "say the same thing"),
])
def test_bad_contact_keys_are_refused_with_the_key_and_range(extra, message):
    with pytest.raises(SceneError, match=re.escape(message)):
        parse_scene(SCENE.format(equations="full", extra=extra, correlation='"2.4 mm"'))


@pytest.mark.parametrize(("extra", "key"), [('law = "compliant"', "contact.law"),
                                            ('friction_law = "stribeck"\npsi_static = 0.2', "contact.friction_law")])
def test_the_reduced_equations_refuse_the_full_models_contact_laws(extra, key):
    with pytest.raises(SceneError, match=re.escape(key) + ".*full equations only"):
        run_scene(parse_scene(SCENE.format(equations="reduced", extra=extra, correlation=0.3)))


def test_bad_arguments_are_refused_with_the_name_and_range():
    mean = ContactParams(KAPPA_STAR, 0.1)
    with pytest.raises(ValueError, match=re.escape("psi_static must be in [psi, pi/2)")):
        RoughContact.from_seed(mean, 0.5, 0.3, 0.3, 0, friction=Stribeck(0.05, 1e-3))
    with pytest.raises(ValueError, match=re.escape("stribeck_velocity must be in (0, inf) m/s")):
        Stribeck(0.2, 0.0)
    with pytest.raises(ValueError, match=re.escape("stiffness must be in (0, inf) N/m")):
        Compliance(stiffness=-1.0)
    with pytest.raises(ValueError, match=re.escape("heights must be one of 'exponential', 'gaussian'")):
        Compliance(heights="lognormal")
    with pytest.raises(ValueError, match=re.escape("damping_ratio must be in [0, 100]")):
        Compliance(damping_ratio=-0.1)
    with pytest.raises(ValueError, match=re.escape("slip_velocity must be in (0, inf) m/s")):
        Compliance(slip_velocity=0.0)
    with pytest.raises(ValueError, match=re.escape("hurst must be in (0, 1)")):
        Spectrum("self-affine", 1.0)
    with pytest.raises(ValueError, match=re.escape("bandwidth must be in [1, 10000]")):
        Spectrum("self-affine", 0.5, 0.5)
    with pytest.raises(ValueError, match="spectrum must be one of"):
        Spectrum("pink")
    with pytest.raises(ValueError, match="correlation must be at least"):
        RoughContact.from_seed(mean, 0.5, 1e-4, 0.3, 0, spectrum=Spectrum("self-affine", 0.5, 100.0))
    with pytest.raises(TypeError, match="compliance must be a Compliance"):
        RoughContact.from_seed(mean, 0.5, 0.3, 0.3, 0, compliance="soft")
    with pytest.raises(ValueError, match="full equations only"):
        simulate(ReducedParams(0.25, 1.0, 1.5), RELEASE, 1.0, contact=surfaces(0.5, compliance=compliance()))
    rough = surfaces(0.5)
    phi0 = math.pi + 0.2
    touch = rough.local_at(phi0, phi0).kappa
    with pytest.raises(ValueError, match=re.escape("initial.kappa must be in [0, ")):
        simulate(AP, Initial(min(touch + 1e-3, 0.999), phi0), AP.tau, forces=FORCES, contact=rough)
    start = simulate(AP, Initial(touch, phi0), 5.0 * AP.tau, forces=FORCES, contact=rough)
    assert start.status == "completed" and start.columns["phase"][0] != FREE
