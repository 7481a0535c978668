r"""The exact-gap Reynolds model against an independent solution of the same equation.

The model (lubrication.reynolds_kernels, profile "eccentric"): along the ray from the
inner centre A at angle theta from the narrowest point, the outer circle lies at

    r(theta) = sqrt(b^2 - eps^2 sin^2 theta) - eps cos theta,   h = r - a,

the fluid in a sector of angle dtheta has the area (r^2 - a^2)/2 dtheta, so the
flux q around the gap obeys dq/dtheta = -d/dt (r^2/2) = -r dr/d(eps) eps', and
the lubrication flux q = h U/2 - h^3 p'/(12 mu a) (U = a W_a + b W_b) gives

    phi' = p'/(12 mu a) = (U/2) h^-2 + (Q - qhat) h^-3,   Q(theta) = int_0^theta r dr/d(eps) eps',

with qhat fixed by periodicity of p. Forces and torque (B13)-(B15):
f_eps = 12 mu a^2 L oint phi' sin, f_chi = -12 mu a^2 L oint phi' cos,
T_a = mu a^2 L oint [(U_b - U_a)/h - 6 h phi'].

Here every integral is computed by scipy's adaptive quadrature, and Q by a
second, inner quadrature of the squeeze source r dr/d(eps) eps' written from
the geometry above: nothing is shared with the kernel (its grid, its
Sommerfeld map, its closed-form antiderivative of the source). Mass
conservation of the profile is the statement that the source integrates to zero
over a period: the area inside the outer circle, oint r^2/2 dtheta = pi b^2,
does not change as the inner circle moves.

Tolerance: quad is asked for 1e-13 relative and the kernel is exact to rounding
for these smooth profiles (its error decays spectrally in N); the comparison is
made at 1e-10 of each row's scale.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from lubrication import Annulus, Motion, reynolds_forces
from lubrication.reynolds_kernels import eccentric_gap

from apparatus import A, B, OIL

# quad warns when rounding stops it short of 1e-13 on integrands that vanish by symmetry;
# the comparisons, at 1e-10, are what decide
pytestmark = pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")

QUAD = {"epsabs": 0.0, "epsrel": 1e-13, "limit": 400}


def _ray(theta, a, b, eps):
    """r(theta) and dr/d(eps) from |A + r e(theta)| = b."""
    root = math.sqrt(b * b - (eps * math.sin(theta)) ** 2)
    return root - eps * math.cos(theta), -math.cos(theta) - eps * math.sin(theta) ** 2 / root


def _source(theta, a, b, eps, eps_dot):
    """d/dt (r^2 / 2): the rate at which the sector's area grows."""
    r, dr = _ray(theta, a, b, eps)
    return r * dr * eps_dot


def _Q(theta, a, b, eps, eps_dot):
    return quad(_source, 0.0, theta, args=(a, b, eps, eps_dot), **QUAD)[0]


def reference_forces(a, b, kappa, mu, length, eps_dot, w_a, w_b):
    """(f_eps, f_chi, T_a) of the exact-gap Reynolds model by nested adaptive quadrature.

    Also returns the size of the terms each is made of (the integrals of the
    absolute integrands), against which rounding is judged: a component that
    vanishes by symmetry is a sum of terms of that size.
    """
    eps = kappa * (b - a)
    u_a, u_b = a * w_a, b * w_b
    half_u = 0.5 * (u_a + u_b)

    def h(theta):
        return _ray(theta, a, b, eps)[0] - a

    def Q(theta):
        return _Q(theta, a, b, eps, eps_dot) if eps_dot else 0.0

    def integral(fn):
        # split at the narrowest and widest gaps, where the integrands peak
        return sum(quad(fn, lo, hi, **QUAD)[0] for lo, hi in ((-math.pi, 0.0), (0.0, math.pi)))

    g2 = integral(lambda t: h(t) ** -2)
    g3 = integral(lambda t: h(t) ** -3)
    gq3 = integral(lambda t: Q(t) * h(t) ** -3)
    qhat = (half_u * g2 + gq3) / g3

    def phi_prime(t):
        return half_u * h(t) ** -2 + (Q(t) - qhat) * h(t) ** -3

    c = mu * a * a * length
    f_eps = 12 * c * integral(lambda t: phi_prime(t) * math.sin(t))
    f_chi = -12 * c * integral(lambda t: phi_prime(t) * math.cos(t))
    t_a = c * integral(lambda t: (u_b - u_a) / h(t) - 6 * h(t) * phi_prime(t))
    force_terms = 12 * c * integral(lambda t: abs(half_u) * h(t) ** -2 + abs(Q(t) - qhat) * h(t) ** -3)
    torque_terms = c * integral(lambda t: (abs(u_b - u_a) + 6 * abs(half_u)) / h(t)
                                + 6 * abs(Q(t) - qhat) * h(t) ** -2)
    return np.array([f_eps, f_chi, t_a]), np.array([force_terms, force_terms, torque_terms])


GEOMETRIES = [(A, B, 0.0), (A, B, 0.3), (A, B, 0.9), (A, B, 0.99), (1.0, 1.01, 0.6), (1.0, 3.0, 0.8)]
MOTIONS = {"squeeze": (1e-4, 0.0, 0.0), "inner": (0.0, 1.0, 0.0), "outer": (0.0, 0.0, 1.0),
           "combined": (-3e-5, 1.5, -0.7)}


@pytest.mark.parametrize("motion", MOTIONS, ids=list(MOTIONS))
@pytest.mark.parametrize(("a", "b", "kappa"), GEOMETRIES)
def test_exact_gap_kernel_matches_adaptive_quadrature(a, b, kappa, motion):
    eps_dot, w_a, w_b = MOTIONS[motion]
    annulus = Annulus.from_kappa(a, b, kappa, length=0.1)
    got = np.array(reynolds_forces(annulus, Motion(eps_dot=eps_dot, omega_a=w_a, omega_b=w_b), OIL,
                                   profile="eccentric", n=128, points_per_cell=2).as_tuple())
    ref, terms = reference_forces(a, b, kappa, OIL.mu, 0.1, eps_dot, w_a, w_b)
    err = np.abs(got - ref) / terms
    assert np.all(err < 1e-10), (err, got, ref)


@pytest.mark.parametrize(("a", "b", "kappa"), GEOMETRIES)
def test_exact_gap_conserves_the_fluid_area(a, b, kappa):
    """The squeeze source integrates to zero over a period (oint r^2/2 = pi b^2 for any eps)."""
    eps = kappa * (b - a)
    total = sum(quad(_source, lo, hi, args=(a, b, eps, 1.0), **QUAD)[0]
                for lo, hi in ((-math.pi, 0.0), (0.0, math.pi)))
    scale = quad(lambda t: abs(_source(t, a, b, eps, 1.0)), -math.pi, math.pi, **QUAD)[0]
    assert abs(total) <= 1e-13 * max(scale, b)
    # and the area itself: oint r^2/2 dtheta = pi b^2
    area = quad(lambda t: 0.5 * _ray(t, a, b, eps)[0] ** 2, -math.pi, math.pi, **QUAD)[0]
    assert area == pytest.approx(math.pi * b * b, rel=1e-13)


@pytest.mark.parametrize(("a", "b", "kappa"), GEOMETRIES)
@pytest.mark.parametrize("theta", [-2.9, -1.0, 0.3, 1.7, 3.1])
def test_kernel_squeeze_flux_is_the_antiderivative_of_the_area_rate(a, b, kappa, theta):
    """The kernel's closed-form Q(theta) against the quadrature of d/dt (r^2/2) from 0 to theta."""
    delta = b - a
    eps = kappa * delta
    h, q = eccentric_gap(a, b, eps, 1.0 - kappa, math.sin(theta), 1.0 - math.cos(theta), 1.0)
    assert h == pytest.approx(_ray(theta, a, b, eps)[0] - a, rel=1e-13)
    expected = _Q(theta, a, b, eps, 1.0)
    assert abs(q - expected) <= 1e-12 * b * max(eps, delta)
