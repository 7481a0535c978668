"""The rough-contact validation group (figures 7-10, Table 3): its quick run, and its two helpers."""

import cmath
import math

import pytest

from dynamics.contact.reduced import ContactParams
from dynamics.contact.steady import onset_of_sliding, steady_state
from dynamics.equations.reduced import ReducedParams
from validation import contact_checks


@pytest.mark.parametrize(("s", "upsilon", "mu_ratio"), [(0.25, 1.0, 1.0), (0.07, 46.8, 1.75), (0.16, 0.04, 3.15)])
def test_settling_rate_of_the_locked_phase(s, upsilon, mu_ratio):
    """Locked, linearised at (5.6), (5.10): lambda^2 + A |cos phi| lambda + kappa* |cos phi|/((mu_ + 1/2) Upsilon) = 0.

    From phi' = Omega + A sin(phi), A = (2 + kappa*^2) zeta* / (2 kappa*) (2.11b), and
    (mu_ + 1/2) Upsilon Omega' = s + kappa* sin(phi) (2.11d). The three cases: figure 8's
    psi = 0.5 (underdamped), steel in 50 cSt oil (overdamped), aluminium in 500 cSt (underdamped).
    """
    contact = ContactParams(0.98, 1.0)  # friction enough to lock
    assert steady_state(s, contact.kappa_star, contact.psi).phase == "locked"
    cos = abs(math.cos(steady_state(s, contact.kappa_star, contact.psi).phi))
    damping = (2.0 + contact.kappa_star**2) * contact.zeta_star / (2.0 * contact.kappa_star) * cos
    stiffness = contact.kappa_star * cos / ((mu_ratio + 0.5) * upsilon)
    slowest = 0.5 * (damping - cmath.sqrt(damping**2 - 4.0 * stiffness).real)
    rate = contact_checks.settling_rate(ReducedParams(s, upsilon, mu_ratio), contact)
    assert rate == pytest.approx(slowest, rel=1e-12)


@pytest.mark.parametrize("kappa_star", [1.0, 0.98, 0.5])
@pytest.mark.parametrize("psi", [0.05, 0.15, 1.0])
def test_onset_slope_inverts_the_onset_of_sliding(psi, kappa_star):
    s_c = contact_checks.onset_slope(psi, kappa_star)
    assert 0.0 < s_c < kappa_star
    assert onset_of_sliding(s_c, kappa_star) == pytest.approx(psi, rel=1e-13)
