r"""The closed forms (2.5)-(2.7) against an independent quadrature of Appendix B.

Integrating the thin-gap Reynolds equation once,
h^3 p' = 6 mu a^2 (W_a + W_b) h - 12 mu a^2 eps' sin(theta) + C, with C fixed by
periodicity; the forces are f_eps = a L oint p' sin, f_chi = -a L oint p' cos and
the torque T_a = a^2 mu L oint [a (W_b - W_a)/h - p' h/(2 a mu)] (B13)-(B15).
Here every integral is done by scipy's adaptive quadrature, independent of the
project's solver.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from lubrication import Annulus, Motion, closed_form_forces, lubrication_forces
from lubrication.geometry import MIN_ONE_MINUS_KAPPA

from apparatus import A, B, L, OIL



def oint(f):
    return quad(f, -math.pi, math.pi, epsabs=0.0, epsrel=1e-12, limit=400, points=[0.0])[0]


def quadrature_forces(kappa, motion):
    delta, mu = B - A, OIL.mu

    def h(t):
        return delta * (1.0 - kappa * math.cos(t))

    w = motion.w_a + motion.w_b
    i2, i3 = oint(lambda t: h(t) ** -2), oint(lambda t: h(t) ** -3)
    c = -6.0 * mu * A**2 * w * i2 / i3  # the squeeze term is odd and drops out of C

    def dp(t):
        return (6.0 * mu * A**2 * w * h(t) - 12.0 * mu * A**2 * motion.eps_dot * math.sin(t) + c) / h(t) ** 3

    f_eps = A * L * oint(lambda t: dp(t) * math.sin(t))
    f_chi = -A * L * oint(lambda t: dp(t) * math.cos(t))
    t_a = A**2 * mu * L * oint(lambda t: A * (motion.w_b - motion.w_a) / h(t) - dp(t) * h(t) / (2 * A * mu))
    return np.array([f_eps, f_chi, t_a])


MOTIONS = {
    "squeeze": Motion(eps_dot=1e-4),
    "inner": Motion(omega_a=1.0),
    "outer": Motion(omega_b=1.0),
    "orbit": Motion(chi_dot=1.0),
    "combined": Motion(eps_dot=-3e-5, chi_dot=0.4, omega_a=1.5, omega_b=-0.7),
}


# at kappa = 0 quad warns that rounding limits it; the tolerance below allows for that
@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("kappa", [0.0, 0.3, 0.7, 0.95])
@pytest.mark.parametrize("motion", MOTIONS.values(), ids=MOTIONS.keys())
def test_closed_forms_match_quadrature_of_appendix_b(kappa, motion):
    annulus = Annulus.from_kappa(A, B, kappa, L)
    got = np.array(closed_form_forces(annulus, motion, OIL).as_tuple())
    ref = quadrature_forces(kappa, motion)
    # quad's relative tolerance 1e-12, amplified by the cancellations in f_chi and T_a
    scale = np.array([np.hypot(*ref[:2]), np.hypot(*ref[:2]), abs(ref[2])])
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-10 * scale.max())


@pytest.mark.parametrize("kappa", [0.0, 0.2, 0.6, 0.9, 0.999])
def test_integrals_b8_b9(kappa):
    """(B8)-(B9): oint H^-1, H^-2, H^-3 with H = 1 - kappa cos(theta)."""
    zeta = math.sqrt(1.0 - kappa**2)
    for n, exact in ((1, 2 * math.pi / zeta), (2, 2 * math.pi / zeta**3),
                     (3, math.pi * (2 + kappa**2) / zeta**5)):
        assert oint(lambda t, n=n: (1.0 - kappa * math.cos(t)) ** -n) == pytest.approx(exact, rel=1e-12)


def test_torque_form_2_7_is_the_one_from_b15():
    """Erratum 5: T_a = c [(1 - kappa^2) W_b - (1 + 2 kappa^2) W_a] / (3 (2 + kappa^2) zeta)."""
    kappa = 0.6
    annulus = Annulus.from_kappa(A, B, kappa, L)
    zeta = math.sqrt(1 - kappa**2)
    c = 12.0 * OIL.nu * A * (math.pi * A**2 * L * OIL.rho) / (B - A)
    motion = Motion(omega_a=0.8, omega_b=-0.3, chi_dot=0.1)
    expected = c * ((1 - kappa**2) * motion.w_b - (1 + 2 * kappa**2) * motion.w_a) / (3 * (2 + kappa**2) * zeta)
    assert closed_form_forces(annulus, motion, OIL).T_a == pytest.approx(expected, rel=1e-14)


def test_signs_follow_the_physics():
    """Squeezing the gap shut is resisted; a spinning inner cylinder is pushed across the line of centres."""
    annulus = Annulus.from_kappa(A, B, 0.5, L)
    closing = closed_form_forces(annulus, Motion(eps_dot=1e-4), OIL)
    spinning = closed_form_forces(annulus, Motion(omega_a=1.0), OIL)
    assert closing.f_eps < 0 and closing.f_chi == 0 and closing.T_a == 0
    assert spinning.f_chi > 0 and spinning.T_a < 0 and spinning.f_eps == 0


def test_rigid_rotation_with_the_line_of_centres_gives_nothing():
    annulus = Annulus.from_kappa(A, B, 0.7, L)
    f = closed_form_forces(annulus, Motion(chi_dot=2.0, omega_a=2.0, omega_b=2.0), OIL)
    assert f.as_tuple() == (0.0, 0.0, 0.0)


def test_finite_up_to_the_smallest_allowed_gap_and_regular_at_the_centre():
    """1 - kappa down to the floor the annulus allows keeps its precision; kappa = 0 is regular."""
    f_contact = lubrication_forces(A, B - A, OIL.mu, L, 1.0, MIN_ONE_MINUS_KAPPA, 1.0, 1.0, 1.0)
    assert all(math.isfinite(x) and x != 0.0 for x in f_contact)
    assert lubrication_forces(A, B - A, OIL.mu, L, 0.0, 1.0, 1.0, 1.0, 1.0)[1] == 0.0
