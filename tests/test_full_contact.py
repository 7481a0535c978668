"""Rough contact in the full model: the constraint forces' power, the impact law, and the limit to section 5."""

import itertools
import math

import numpy as np
import pytest

from dynamics.apparatus import Apparatus
from dynamics.contact import full as full_contact
from dynamics.contact import reduced as contact
from dynamics.contact import steady as contact_steady
from dynamics.contact.reduced import ContactParams
from dynamics.equations import full
from dynamics.simulation import Initial, simulate
from lubrication.registry import kernel_model

FORCES = kernel_model("closed-form")
MODEL = full.model_arguments(FORCES)


def device(delta_over_a=0.01, s=0.25):
    return Apparatus.from_groups(s=s, upsilon=1.0, mu_ratio=1.5, delta_over_a=delta_over_a)


def energy_rate(ap, x, z, r_dot, r_ddot, omega_a, omega_b, omega_a_dot, omega_b_dot):
    """d/dt of the full model's mechanical energy (dynamics.analysis.mechanical_energy)."""
    ca, sa = math.cos(ap.alpha), math.sin(ap.alpha)
    return ((ap.M + ap.m_b) * ap.b**2 * omega_b * omega_b_dot
            + ap.m_a_reduced * ap.b * (omega_b_dot * r_dot[0] + omega_b * r_ddot[0])
            + ap.m_eff * (r_dot @ r_ddot) + 0.5 * ap.m_a * ap.a**2 * omega_a * omega_a_dot
            + ap.m_a_reduced * ap.g * (r_dot[1] * ca - r_dot[0] * sa) - ap.M * ap.g * sa * ap.b * omega_b)


@pytest.mark.parametrize("locked", [True, False])
def test_contact_forces_do_the_work_of_friction_only(locked):
    """dE/dt in contact minus dE/dt of the free model at the same state = F * slip (0 when locked).

    The normal reaction does no work (eps' = 0); a wrong torque arm or sign of
    the friction would break the identity at O(1). Without the fluid's spin in (2.4), whose kinetic
    energy the closure does not define.
    """
    ap = device()
    surfaces = ContactParams(0.98, 0.3)
    p = full.params_array(ap, fluid_spin="none")
    free_args = full.run_args(ap, FORCES, gap_floor=1e-9, fluid_spin="none")
    rng = np.random.default_rng(3)
    eps = surfaces.kappa_star * ap.delta
    for _ in range(5):
        # A below B (chi near pi), where the wall pushes: N > 0
        chi, chi_dot, omega_a, omega_b = math.pi + rng.uniform(-1, 1), *(rng.uniform(-2, 2, 3) / ap.tau)
        if locked:
            omega_a = ((ap.a + eps) * omega_b - eps * chi_dot) / ap.a
        y = np.array([chi, chi_dot, omega_a, omega_b, 0.0])
        sigma = math.copysign(1.0, full_contact.slip(ap, surfaces.kappa_star, y))
        rates = full_contact.contact_functions(FORCES).rates(y, p, surfaces.kappa_star, surfaces.one_minus_kappa_star, locked,
                                           sigma, full_contact.friction_coefficient(ap, surfaces), MODEL)
        e_eps, e_chi = np.array([math.sin(chi), math.cos(chi)]), np.array([math.cos(chi), -math.sin(chi)])
        r, r_dot = eps * e_eps, eps * chi_dot * e_chi
        r_ddot = eps * (rates[0] * e_chi - chi_dot**2 * e_eps)
        free = full.model_functions(FORCES).rhs(0.0, full_contact._free_state(ap, surfaces, y), free_args)
        in_contact = energy_rate(ap, *r, r_dot, r_ddot, omega_a, omega_b, rates[1], rates[2])
        without = energy_rate(ap, *r, r_dot, free[2:4], omega_a, omega_b, free[4], free[5])
        friction_power = rates[4] * full_contact.slip(ap, surfaces.kappa_star, y)
        scale = ap.m_a_reduced * ap.g * ap.b / ap.tau
        assert in_contact - without == pytest.approx(friction_power, abs=1e-9 * scale)
        if locked:
            assert abs(friction_power) < 1e-9 * scale
        else:
            assert rates[3] > 0.0 and friction_power < 0.0
            assert rates[4] == pytest.approx(-sigma * full_contact.friction_coefficient(ap, surfaces) * rates[3])


def impact_momentum(ap, chi, v, omega_a, omega_b, eps):
    """The (2.4) angular momentum an impulse between the cylinders cannot change (plane impulses act at its pivot)."""
    x, z = eps * math.sin(chi), eps * math.cos(chi)
    return (0.5 * ap.m_a * ap.a**2 * omega_a + (ap.M + ap.m_b) * ap.b**2 * omega_b
            + ap.m_eff * (z * v[0] - x * v[1]) + ap.m_a_reduced * ap.b * (v[0] + z * omega_b))


def kinetic(ap, v, omega_a, omega_b):
    return (0.5 * (ap.M + ap.m_b) * ap.b**2 * omega_b**2 + ap.m_a_reduced * ap.b * omega_b * v[0]
            + 0.5 * ap.m_eff * (v @ v) + 0.25 * ap.m_a * ap.a**2 * omega_a**2)


@pytest.mark.parametrize("fluid_spin", full.FLUID_SPIN)
@pytest.mark.parametrize("psi, sticks", [(1.2, True), (0.3, False)])
def test_plastic_impact_conserves_angular_momentum_and_loses_energy(psi, sticks, fluid_spin):
    """The angular momentum of (2.4) about the pivot, with the fluid's own, L = J_a Omega_a + J_b Omega_b +
    K eps^2 chi' (full.spin_state), is kept; kinetic energy is lost (without the fluid's spin, whose
    kinetic energy the closure does not define)."""
    ap = device()
    surfaces = ContactParams(0.98, psi)
    mu = full_contact.friction_coefficient(ap, surfaces)
    eps = surfaces.kappa_star * ap.delta
    chi = 0.3 + math.pi
    e_eps, e_chi = np.array([math.sin(chi), math.cos(chi)]), np.array([math.cos(chi), -math.sin(chi)])
    v = (0.2 * e_eps + 0.3 * e_chi) * ap.delta / ap.tau
    omega_b = 0.1 / ap.tau
    # a slip of 1/100 of the approach speed can be stopped by friction, of 100 times it cannot
    slip_before = (0.01 if sticks else 100.0) * 0.2 * ap.delta / ap.tau
    omega_a = (slip_before - e_chi @ v + (ap.a + eps) * omega_b) / ap.a
    after = full_contact.impact(ap, surfaces, chi, v, omega_a, omega_b, fluid_spin)
    v1, wa1, wb1, p_n, p_f = after
    assert p_n > 0.0
    assert e_eps @ v1 == pytest.approx(0.0, abs=1e-15 * ap.delta / ap.tau)
    j_a, j_b, big_k, _ = full.spin_state(full.params_array(ap, fluid_spin=fluid_spin), surfaces.kappa_star, eps,
                                         0.0, 0.0, 0.0, 0.0)

    def momentum(velocity, w_a, w_b):
        return (impact_momentum(ap, chi, velocity, w_a, w_b, eps)
                + j_a * w_a + j_b * w_b + big_k * eps * (e_chi @ velocity))

    assert momentum(v1, wa1, wb1) == pytest.approx(momentum(v, omega_a, omega_b), rel=1e-12)
    if fluid_spin == "none":
        assert kinetic(ap, v1, wa1, wb1) < kinetic(ap, v, omega_a, omega_b)
    slip_after = e_chi @ v1 + ap.a * wa1 - (ap.a + eps) * wb1
    if sticks:
        assert abs(slip_after) < 1e-12 * ap.b / ap.tau and abs(p_f) <= mu * p_n
    else:  # slides through the impact: friction at its bound and against the slip, which keeps its sign
        assert abs(p_f) == pytest.approx(mu * p_n, rel=1e-12)
        assert p_f < 0.0 < slip_after


@pytest.mark.parametrize("psi", [0.05, 0.5])  # sliding and locked branches at s = 1/4, kappa* = 0.98
def test_steady_rolling_approaches_section_5_at_first_order_in_delta_over_a(psi):
    """|full - (5.6)-(5.11)| ~ C delta/a: log-log slope 1 over delta/a = 1e-2 ... 1e-3."""
    reduced = contact_steady.steady_state(0.25, 0.98, psi)
    ratios, errors = [0.01, 0.003, 0.001], []
    for d in ratios:
        ap = device(d)
        surfaces = ContactParams(0.98, psi)
        chi, omega_a, omega_b = full_contact.steady_full_contact(
            ap, FORCES, surfaces, reduced.phase == contact.LOCKED,
            [reduced.phi - ap.alpha, reduced.omega_a / ap.tau, reduced.omega_b / ap.tau])
        errors.append(max(abs(chi + ap.alpha - reduced.phi), abs(omega_b * ap.tau / reduced.omega_b - 1.0),
                          abs(omega_a * ap.tau / reduced.omega_a - 1.0)))
    slope = np.polyfit(np.log(ratios), np.log(errors), 1)[0]
    assert slope == pytest.approx(1.0, abs=0.03)
    assert errors[-1] < 3e-3


def test_a_steady_state_is_accepted_only_where_its_accelerations_vanish():
    """Newton's answer is judged by its residual: x^2 + 1 has no real root, x^2 - 2 does."""
    assert full_contact._solve(lambda x: [x[0] ** 2 - 2.0], [1.0])[0] == pytest.approx(math.sqrt(2.0), rel=1e-12)
    with pytest.raises(ValueError, match="no steady contact state"):
        full_contact._solve(lambda x: [x[0] ** 2 + 1.0], [1.0])


def run(ap, kappa_star, psi, t_end_tau, kappa0=0.5):
    return simulate(ap, Initial(kappa=kappa0, phi=0.3), t_end_tau * ap.tau, forces=FORCES,
                    contact=ContactParams(kappa_star, psi), rtol=1e-9)


@pytest.mark.parametrize("psi, phase", [(0.05, contact.SLIDING), (0.5, contact.LOCKED)])
def test_a_release_settles_on_the_full_models_own_steady_state(psi, phase):
    """Figure 7's release (s = 1/4, kappa* = 0.98) at delta/a = 0.01 reaches the fixed point to 1e-6."""
    ap = device()
    traj = run(ap, 0.98, psi, 400.0)
    c = traj.columns
    assert traj.status == "completed" and traj.info["final_phase"] == phase
    reduced = contact_steady.steady_state(0.25, 0.98, psi)
    steady = full_contact.steady_full_contact(
        ap, FORCES, ContactParams(0.98, psi), phase == contact.LOCKED,
        [reduced.phi - ap.alpha, reduced.omega_a / ap.tau, reduced.omega_b / ap.tau])
    assert c["chi"][-1] == pytest.approx(steady[0], abs=1e-6)
    assert c["omega_a"][-1] * ap.tau == pytest.approx(steady[1] * ap.tau, rel=1e-6)
    assert c["omega_b"][-1] * ap.tau == pytest.approx(steady[2] * ap.tau, rel=1e-6)
    assert np.all(c["kappa"] <= 0.98) and np.all(c["c_eps"] >= -1e-12)
    in_contact = c["phase"] > 0
    assert c["c_eps"][in_contact][-1] == pytest.approx(reduced.c_eps, rel=0.03)  # O(delta/a) from (5.1)
    if phase == contact.LOCKED:  # rolling without slip at the contact point, chi' -> 0
        arm = ap.a + 0.98 * ap.delta
        assert c["omega_a"][-1] * ap.a == pytest.approx(c["omega_b"][-1] * arm, rel=1e-9)


@pytest.mark.parametrize("kappa_star, psi, phase", [
    (0.999999, 0.05, contact.SLIDING),
    (0.98, 0.0, contact.SLIDING),
    (0.98, 0.5 * math.pi - 1e-6, contact.LOCKED),
])
def test_extremes_of_contact_run_cleanly(kappa_star, psi, phase):
    """kappa* = 1 - 1e-6 and friction angles 0 and pi/2 - 1e-6: finite, in contact, the expected phase."""
    ap = device()
    traj = run(ap, kappa_star, psi, 10_000.0 if kappa_star > 0.99 else 300.0)  # settles over ~1/zeta* tau
    c = traj.columns
    assert traj.status == "completed", traj.message
    assert traj.info["final_phase"] == phase
    assert all(np.all(np.isfinite(v)) for v in c.values())
    assert traj.steps < 100_000
    reduced = contact_steady.steady_state(0.25, kappa_star, psi)
    assert c["omega_b"][-1] * ap.tau == pytest.approx(reduced.omega_b, rel=0.02)  # O(delta/a) = 1%


def test_a_release_at_the_contact_gap_starts_in_contact():
    ap = device()
    traj = simulate(ap, Initial(kappa=0.98, phi=3.5), 50.0 * ap.tau, forces=FORCES, contact=ContactParams(0.98, 0.5))
    assert traj.status == "completed" and traj.equations == "full"
    assert traj.columns["phase"][0] > 0 and np.all(traj.columns["kappa"] == 0.98)


def test_stick_slip_while_rocking_switches_cleanly():
    """Just above the onset of sliding (psi_c = 0.1286 at s = 1/4, kappa* = 0.98) the rocking pair
    alternates locked and sliding: each switch is an event, so the step count stays that of a run
    that locks once (no chattering, no step-size collapse at the switches)."""
    ap = device()
    traj = run(ap, 0.98, 0.13, 300.0)
    phases = [sw["to"] for sw in traj.info["switches"]]
    assert traj.status == "completed" and len(phases) >= 8
    assert all(p != q for p, q in itertools.pairwise(phases))  # a switch always changes the phase
    assert traj.steps < 1.5 * run(ap, 0.98, 0.5, 300.0).steps
