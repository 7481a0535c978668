r"""The fluid turning with the line of centres: (2.1)-(2.2) as printed and with the frame terms.

Independent derivation. Let the whole device turn about B at the rate Omega with
the inner cylinder at rest in the turning fluid (rigid rotation: W_a = W_b = 0,
eps' = 0, no viscous stress). The fluid's pressure rho Omega^2 r^2/2 pushes the
inner cylinder towards B with its displaced mass, m''_a Omega^2 eps (buoyancy in
the centrifugal field); an acceleration eps'' of A relative to the turning fluid
brings the added mass m''_a^2/m_f of (2.1)-(2.2). Newton's law along e_eps,

    m_a (eps'' - eps Omega^2) = -m''_a eps Omega^2 - (m''_a^2/m_f) eps'' + (gravity),

so d(eps'')/d(Omega^2) = (m'_a/m_eff) eps. (2.2) as printed gives eps.
On the line of centres pointing straight up (chi = 0) the rolling term of (2.2)
vanishes, so the difference of eps'' between two rates isolates this derivative.
"""

import math

import numpy as np
import pytest

from dynamics.apparatus import preset
from dynamics.equations import full
from dynamics.equations.forces import force_model


def _eps_ddot(ap, frame_terms, omega, kappa=0.5):
    args = full.run_args(ap, force_model("stokes-exact"), gap_floor=1e-9, frame_terms=frame_terms)
    eps = kappa * ap.delta
    zeta = math.sqrt(1.0 - kappa * kappa)
    # chi = 0: e_eps = (0, 1), e_chi = (1, 0); r' = eps Omega e_chi
    y = np.array([0.0, kappa / zeta, eps * omega, 0.0, omega, omega, 0.0])
    dy = full.rhs(0.0, y, args)
    return dy[3] + eps * omega**2  # e_eps . r'' + eps chi'^2


@pytest.mark.parametrize("name", ["steel", "aluminium"])
@pytest.mark.parametrize(("frame_terms", "expected"), [("paper", lambda ap: 1.0),
                                                       ("quasi-steady", lambda ap: ap.m_a_reduced / ap.m_eff)])
def test_centripetal_term_of_a_rigidly_turning_fluid(name, frame_terms, expected):
    ap = preset(name, alpha=0.0)
    kappa = 0.5
    slope = (_eps_ddot(ap, frame_terms, 20.0, kappa) - _eps_ddot(ap, frame_terms, 0.0, kappa)) / 400.0
    # the fade of the frame force at kappa = 0.5: kappa^2/(kappa^2 + 0.05^2)
    fade = kappa**2 / (kappa**2 + 0.0025) if frame_terms != "paper" else 1.0
    want = kappa * ap.delta * (1.0 - fade * (1.0 - expected(ap)))
    assert slope == pytest.approx(want, rel=1e-9)


def test_frame_terms_are_refused_for_the_reduced_equations():
    from dynamics import Initial, simulate
    from dynamics.equations.reduced import ReducedParams

    with pytest.raises(ValueError, match="frame_terms"):
        simulate(preset("steel"), Initial(0.5), 1.0, equations="reduced", frame_terms="quasi-steady")
    with pytest.raises(ValueError, match="frame_terms must be one of"):
        simulate(ReducedParams(0.2, 1.0, 2.0), Initial(0.5), 1.0, frame_terms="exact")
