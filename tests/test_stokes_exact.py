r"""The exact Stokes resistance of the eccentric annulus against independent computations.

References, each independent of the kernel's simplified formulas:

* classical concentric closed forms (Couette torques, drag of a translating
  cylinder), derived in the docstrings below;
* a 100-digit evaluation (Python's ``decimal``; mpmath is not installed) of the
  unsimplified solution of the derivation: the limit points p, q, the bipolar
  coordinates alpha, beta, the coefficients A'', g, e1 and the residue sum of
  the torque;
* a NumPy twin that builds the Goursat functions phi, omega of the derivation,
  checks the no-slip conditions on both walls and the Stokes equations, and
  integrates the traction over the walls by the trapezoid rule (spectrally
  accurate for these periodic analytic integrands);
* the finite-element solver :mod:`lubrication.stokes`, at meshes whose
  discretisation error (~ h^4) is below the stated tolerances.
"""

import math
from decimal import Decimal, localcontext

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lubrication.closed_form import lubrication_forces
from lubrication.geometry import (
    MIN_ONE_MINUS_KAPPA,
    RESISTANCE_NAMES,
    Annulus,
    Fluid,
    Motion,
)
from lubrication.registry import kernel_model
from lubrication.stokes_exact import (
    DELTA_OVER_A_RANGE,
    EXACT_NAMES,
    ExactResistance,
    exact_ratios,
    exact_resistance,
    stokes_exact_forces,
    stokes_exact_ratios,
    stokes_exact_resistance,
)

from apparatus import A, B, L, OIL

# ---------------------------------------------------------------------------
# High-precision reference: the unsimplified solution, in decimal arithmetic
# ---------------------------------------------------------------------------


def _d_pi():
    """pi = 16 atan(1/5) - 4 atan(1/239) (Machin), to the context's precision."""
    def atan_inv(n):
        x = Decimal(1) / n
        x2, term, total, k = x * x, x, x, 1
        while True:
            term = -term * x2
            new = total + term / (2 * k + 1)
            if new == total:
                return total
            total, k = new, k + 1
    return 16 * atan_inv(5) - 4 * atan_inv(239)


def reference(a, delta, omk, prec=100):
    """The seven coefficients (EXACT_NAMES order, mu = 1, per unit length) at ``prec`` digits.

    Follows the derivation step by step, not the kernel's final forms: p from
    p q = b^2 and (p - eps)(q - eps) = a^2; alpha = ln(a/(p - eps)),
    beta = ln(b/p), c = (q - p)/2; radial drag 8 pi A with
    A = -1/(2 (tau - tanh tau)); for each rotation A'' from
    2 g (a^2 + b^2) - 4 c A'' = W_a a^2 + W_b b^2 and g eps = tau A'', e1 from
    the pole condition at eps, the torque about B from the residue sum
    -4 pi [W_a a^2 - 2 p A'' - 2 e1 e^(2 beta) - 2 g a^2], then
    T_a = M_B - eps F_y and T_b = -M_B. kappa = 1 - omk exactly (kappa > 0).
    """
    with localcontext() as ctx:
        ctx.prec = prec
        a, delta, omk = Decimal(a), Decimal(delta), Decimal(omk)
        pi = _d_pi()
        b = a + delta
        eps = (1 - omk) * delta
        s = (b * b - a * a + eps * eps) / (2 * eps)
        p = b * b / (s + (s * s - b * b).sqrt())
        q = b * b / p
        alpha, beta = (a / (p - eps)).ln(), (b / p).ln()
        tau, c = alpha - beta, (q - p) / 2
        e2t = (2 * tau).exp()
        tanh = (e2t - 1) / (e2t + 1)
        out = [-4 * pi / (tau - tanh)]
        torques = []
        for w_a, w_b in ((1, 0), (0, 1)):
            n = w_a * a * a + w_b * b * b
            a_pp = n / (2 * tau * (a * a + b * b) / eps - 4 * c)
            g = tau * a_pp / eps
            e1 = (w_a * a * a - 2 * g * a * a + 2 * c * a_pp) / ((2 * beta).exp() - (2 * alpha).exp())
            m_b = -4 * pi * (w_a * a * a - 2 * p * a_pp - 2 * e1 * (2 * beta).exp() - 2 * g * a * a)
            f_y = 8 * pi * a_pp
            torques.append((f_y, m_b - eps * f_y, -m_b))
        (f_a, t_a_a, t_b_a), (f_b, t_a_b, t_b_b) = torques
        return [float(v) for v in (out[0], f_a, t_a_a, f_b, t_a_b, t_b_a, t_b_b)], \
            [v for v in (out[0], f_a, t_a_a, f_b, t_a_b, t_b_a, t_b_b)]


def reference_concentric(a, delta, prec=60):
    """kappa = 0 at ``prec`` digits: the classical forms of the concentric tests below."""
    with localcontext() as ctx:
        ctx.prec = prec
        a, delta = Decimal(a), Decimal(delta)
        pi = _d_pi()
        b = a + delta
        a2, b2 = a * a, b * b
        couette = 4 * pi * a2 * b2 / (b2 - a2)
        drag = -4 * pi / ((b / a).ln() - (b2 - a2) / (b2 + a2))
        return [float(v) for v in (drag, 0, -couette, 0, couette, couette, -couette)]


def kernel(a, delta, omk, kappa=None):
    """The kernel's seven coefficients, mu = 1; kappa = 1 - omk unless given (as when omk = 1 - kappa)."""
    kappa = 1.0 - omk if kappa is None else kappa
    return np.array(stokes_exact_resistance(a, delta, 1.0, kappa, omk))


#: Grid of the digits test: delta/a over the domain, 1 - kappa from kappa = 1e-6 to 1 - 1e-9.
DIGIT_DELTAS = (1e-4, 1e-3, 1e-2, 0.1, 0.40625, 1.0, 3.0, 10.0)
DIGIT_OMKS = (1.0 - 1e-6, 0.9, 0.5, 0.1, 1e-2, 1e-4, 1e-6, 1e-9)
#: Claimed relative accuracy of every coefficient over the domain (module docstring).
DIGITS_TOL = 2e-15


def test_reference_is_good_to_50_digits():
    """The decimal reference at 100 and 130 digits agrees to 1e-50 at the corners of the domain.

    The unsimplified formulas cancel up to ~30 digits there (tau - tanh tau at
    tau ~ 1e-9, e^(2 beta) - e^(2 alpha), s^2 - b^2 at kappa = 1e-6).
    """
    for d in (1e-4, 10.0):
        for omk in (1.0 - 1e-6, 1e-9):
            lo, hi = reference(1.0, d, omk, 100)[1], reference(1.0, d, omk, 130)[1]
            for x, y in zip(lo, hi):
                assert abs(x / y - 1) < Decimal("1e-50")


@pytest.mark.parametrize("d", DIGIT_DELTAS)
def test_digits_against_high_precision(d):
    """Every coefficient matches the 100-digit reference to DIGITS_TOL, kappa = 1e-6 ... 1 - 1e-9."""
    worst = 0.0
    for omk in DIGIT_OMKS:
        exact = np.array(reference(0.8, 0.8 * d, omk)[0])
        got = kernel(0.8, 0.8 * d, omk)
        worst = max(worst, float(np.max(np.abs(got / exact - 1.0))))
    assert worst < DIGITS_TOL, worst


@pytest.mark.parametrize("d", [20.0, 100.0])
def test_kernel_beyond_the_domain(d):
    """delta/a > 10 (tau > 2.5 at small kappa): the direct differences replace the series, to 1e-14."""
    for omk in (1.0 - 1e-3, 0.5, 1e-6):
        exact = np.array(reference(1.0, d, omk)[0])
        np.testing.assert_allclose(kernel(1.0, d, omk), exact, rtol=1e-14)


@pytest.mark.parametrize("d", DIGIT_DELTAS)
def test_digits_concentric(d):
    """At kappa = 0 the kernel matches the concentric closed forms to DIGITS_TOL (f_chi exactly 0)."""
    exact = np.array(reference_concentric(1.0, d))
    got = kernel(1.0, d, 1.0)
    assert got[1] == 0.0 and got[3] == 0.0
    nz = [0, 2, 4, 5, 6]
    np.testing.assert_allclose(got[nz], exact[nz], rtol=DIGITS_TOL, atol=0.0)


@settings(max_examples=60, deadline=None)
@given(log_d=st.floats(math.log10(DELTA_OVER_A_RANGE[0]), math.log10(DELTA_OVER_A_RANGE[1])),
       log_omk=st.floats(-9.0, -1e-7))
def test_digits_hypothesis(log_d, log_omk):
    """Random states of the whole domain: the kernel keeps DIGITS_TOL against the reference."""
    d, omk = 10.0**log_d, 10.0**log_omk
    exact = np.array(reference(1.0, d, omk)[0])
    got = kernel(1.0, d, omk)
    assert np.all(np.isfinite(got))
    assert np.max(np.abs(got / exact - 1.0)) < DIGITS_TOL


# ---------------------------------------------------------------------------
# Concentric closed forms (kappa = 0)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("d", [1e-3, 0.40625, 10.0])
def test_concentric_couette_torques(d):
    """Couette flow: T_a = -4 pi mu a^2 b^2 (W_a - W_b)/(b^2 - a^2), T_b = -T_a, per unit length.

    u_theta = C r + E/r meets the walls' speeds W_a a and W_b b when
    C = (W_b b^2 - W_a a^2)/(b^2 - a^2) and E = (W_a - W_b) a^2 b^2/(b^2 - a^2).
    The shear stress sigma_r_theta = mu r d(u_theta/r)/dr = -2 mu E/r^2 acts on the
    inner wall (normal +e_r into the fluid) with torque 2 pi a^2 sigma_r_theta(a)
    = -4 pi mu E, and the fluid carries no net torque. No force at kappa = 0.
    """
    a, mu = 0.8, 1.7
    delta = a * d
    b = a + delta
    couette = 4.0 * math.pi * mu * a**2 * b**2 / (delta * (a + b))
    r = stokes_exact_resistance(a, delta, mu, 0.0, 1.0)
    np.testing.assert_allclose([r[2], r[4], r[5], r[6]], [-couette, couette, couette, -couette],
                               rtol=1e-14)
    assert r[1] == 0.0 and r[3] == 0.0


@pytest.mark.parametrize("d", [1e-3, 0.40625, 10.0])
def test_concentric_translation_drag(d):
    """Drag on the inner cylinder translating at U in a fixed concentric one.

    psi = g(r) sin(theta) (u_r = psi_theta/r, u_theta = -psi_r) with the
    biharmonic g = A r^3 + B r ln r + C r + D/r; no slip is g = U r, g' = U at a
    and g = g' = 0 at b. Subtracting g/r from g' at each wall gives
    2 A r^2 + B - 2 D/r^2 = 0 at r = a, b, hence A = -D/(a^2 b^2) and
    B = 2 D (a^2 + b^2)/(a^2 b^2); then g(a)/a - g(b)/b = U gives
    B = -U / (ln(b/a) - (b^2 - a^2)/(b^2 + a^2)). Only the Stokeslet term
    B r ln r sin(theta) carries a net force, F = 4 pi mu B e_x, so

        F/U = -4 pi mu / (ln(b/a) - (b^2 - a^2)/(b^2 + a^2))   per unit length.

    The 4x4 system is also solved numerically as a check of this algebra. In
    double precision the denominator cancels to ~ (delta/a)^3/3 from terms
    ~ delta/a: the tolerance grows like (a/delta)^2 (the kernel's own digits at
    kappa = 0 are checked against a 60-digit evaluation above).
    """
    a, mu = 0.8, 1.7
    delta = a * d
    b = a + delta
    closed = -4.0 * math.pi * mu / (math.log1p(d) - delta * (a + b) / (b * b + a * a))
    m = np.array([[a**3, a * math.log(a), a, 1 / a], [3 * a * a, math.log(a) + 1, 1, -1 / a**2],
                  [b**3, b * math.log(b), b, 1 / b], [3 * b * b, math.log(b) + 1, 1, -1 / b**2]])
    coef = np.linalg.solve(m, [a, 1.0, 0.0, 0.0])
    rounding = 1e-15 / min(1.0, d) ** 2
    assert 4.0 * math.pi * mu * coef[1] == pytest.approx(closed, rel=1e4 * rounding)
    assert stokes_exact_resistance(a, delta, mu, 0.0, 1.0)[0] == pytest.approx(closed, rel=rounding)


# ---------------------------------------------------------------------------
# NumPy twin: the Goursat functions of the derivation
# ---------------------------------------------------------------------------


class Goursat:
    """phi, omega of the module docstring for one annulus and one rigid motion, mu = 1.

    The lab-frame motion: A moves with complex velocity ``u_a`` = eps' + i V, the
    walls turn at ``w_a`` (about A) and ``w_b`` (about B). Coefficients are those
    the derivation solves for; nothing here uses the kernel's final formulas.
    """

    def __init__(self, a, b, eps, u_a=0.0, w_a=0.0, w_b=0.0):
        s = (b * b - a * a + eps * eps) / (2.0 * eps)
        p = b * b / (s + math.sqrt(s * s - b * b))
        q = b * b / p
        alpha, beta = math.log(a / (p - eps)), math.log(b / p)
        tau, c = alpha - beta, 0.5 * (q - p)
        d = tau * (a * a + b * b) - 2.0 * a * b * math.sinh(tau)
        u_a = complex(u_a)
        a_r = -u_a.real / (2.0 * (tau - math.tanh(tau)))
        a1_r = -2.0 * c * a_r / (math.exp(2 * alpha) + math.exp(2 * beta))
        v = u_a.imag
        a_pp = (eps * (w_a * a * a + w_b * b * b) - (a * a + b * b) * v) / (2.0 * d)
        g = (v + 2.0 * tau * a_pp) / (2.0 * eps)
        e1 = (w_a * a * a - 2 * g * a * a + 2 * c * a_pp) / (math.exp(2 * beta) - math.exp(2 * alpha))
        self.A, self.a1 = complex(a_r, a_pp), complex(a1_r, e1)
        self.a2 = self.a1.conjugate() * math.exp(2 * (alpha + beta))
        self.a3 = 1j * g
        self.a, self.b, self.eps, self.p, self.q, self.alpha = a, b, eps, p, q, alpha
        self.u_a, self.w_a, self.w_b = u_a, w_a, w_b

    def dphi(self, z, k):
        """k-th derivative of phi, k = 0, 1, 2."""
        p, q, A, a1, a2, a3 = self.p, self.q, self.A, self.a1, self.a2, self.a3
        if k == 0:
            return A * np.log((z - p) / (z - q)) + a1 / (z - p) + a2 / (z - q) + a3 * z
        if k == 1:
            return A * (1 / (z - p) - 1 / (z - q)) - a1 / (z - p) ** 2 - a2 / (z - q) ** 2 + a3
        return A * (1 / (z - q) ** 2 - 1 / (z - p) ** 2) + 2 * a1 / (z - p) ** 3 + 2 * a2 / (z - q) ** 3

    def omega(self, z, derivative=False):
        """omega = conj(U_A) - i W_a a^2/(z - eps) - phibar(S_a(z)) + S_a(z) phi'(z), or its derivative.

        phibar(S_a) takes its logarithm as -2 alpha - L(z), the continuation
        the derivation uses; L's jumps then cancel in U.
        """
        a, eps, p, q = self.a, self.eps, self.p, self.q
        A, a1, a2, a3 = (np.conj(x) for x in (self.A, self.a1, self.a2, self.a3))
        s = eps + a * a / (z - eps)
        ds = -a * a / (z - eps) ** 2
        lz = np.log((z - p) / (z - q))
        if not derivative:
            phibar = A * (-2 * self.alpha - lz) + a1 / (s - p) + a2 / (s - q) + a3 * s
            return (np.conj(self.u_a) - 1j * self.w_a * a * a / (z - eps) - phibar
                    + s * self.dphi(z, 1))
        dphibar = -A * (1 / (z - p) - 1 / (z - q)) + (-a1 / (s - p) ** 2 - a2 / (s - q) ** 2 + a3) * ds
        return (1j * self.w_a * a * a / (z - eps) ** 2 - dphibar + ds * self.dphi(z, 1)
                + s * self.dphi(z, 2))

    def term_size(self, z):
        """Largest size of the separate terms of U at z: the scale of its rounding error."""
        p, q = self.p, self.q
        return np.max(np.abs(z) * (abs(self.A) * (abs(1 / (z - p)) + abs(1 / (z - q)))
                                   + abs(self.a1) / abs(z - p) ** 2 + abs(self.a2) / abs(z - q) ** 2)
                      + abs(self.A) * abs(np.log((z - p) / (z - q))) + abs(self.a3) * np.abs(z))

    def velocity(self, z):
        return self.dphi(z, 0) - z * np.conj(self.dphi(z, 1)) + np.conj(self.omega(z))

    def pressure(self, z):
        return -4.0 * np.real(self.dphi(z, 1))

    def loads(self, n=4096):
        """(F_x + i F_y on A, T_a about A, T_b about B) by the trapezoid rule on each wall.

        Traction t = -p n + 2 conj(n) dU/dzbar (n the wall normal into the fluid),
        with dU/dzbar = -z conj(phi'') + conj(omega').
        """
        theta = 2.0 * np.pi * np.arange(n) / n
        e = np.exp(1j * theta)
        out = []
        for centre, r, normal in ((self.eps, self.a, e), (0.0, self.b, -e)):
            z = centre + r * e
            strain = -z * np.conj(self.dphi(z, 2)) + np.conj(self.omega(z, derivative=True))
            t = -self.pressure(z) * normal + 2.0 * np.conj(normal) * strain
            out.append((r * np.mean(t) * 2 * np.pi, r * r * np.mean(np.imag(np.conj(e) * t)) * 2 * np.pi))
        (force, t_a), (_, t_b) = out
        return force, t_a, t_b


TWIN_CASES = [(0.40625, 0.3), (0.40625, 0.9), (0.01, 0.6), (3.0, 0.5), (0.40625, 0.99)]
TWIN_MOTIONS = {"radial": {"u_a": 1.0}, "inner": {"w_a": 1.0}, "outer": {"w_b": 1.0},
                "along_e_chi": {"u_a": 1j}}


def twin(d, kappa, **motion):
    a = 1.0
    return Goursat(a, a + d, kappa * d, **motion)


@pytest.mark.parametrize("motion", TWIN_MOTIONS.values(), ids=TWIN_MOTIONS.keys())
@pytest.mark.parametrize("d, kappa", TWIN_CASES)
def test_twin_meets_no_slip(d, kappa, motion):
    """The derivation's phi, omega give the rigid wall velocities on both circles.

    The inner wall's condition is built into omega; the outer one holds only if
    the residue conditions of the derivation were solved right. U is a small sum
    of large terms in thin gaps and near contact (the image coefficients grow
    like tau^-3): the tolerance is 1e-14 of the largest term.
    """
    g = twin(d, kappa, **motion)
    theta = np.linspace(0.0, 2.0 * np.pi, 721)
    z_in = g.eps + g.a * np.exp(1j * theta)
    z_out = g.b * np.exp(1j * theta)
    wall_in = g.u_a + 1j * g.w_a * (z_in - g.eps)
    wall_out = 1j * g.w_b * z_out
    for z, wall in ((z_in, wall_in), (z_out, wall_out)):
        assert np.max(np.abs(g.velocity(z) - wall)) < 1e-14 * g.term_size(z)


@pytest.mark.parametrize("motion", TWIN_MOTIONS.values(), ids=TWIN_MOTIONS.keys())
def test_twin_solves_stokes(motion):
    """Finite differences of the twin's velocity: div u = 0 and Lap u = grad p (mu = 1).

    Central differences with step h have error O(h^2); at h = 1e-3 delta the
    residuals must be below 1e-5 of |grad p| and |grad u| at points across the gap.
    """
    g = twin(0.40625, 0.6, **motion)
    delta = g.b - g.a
    h = 1e-3 * delta
    for z in (g.eps - g.a - 0.3 * (1 + 0.6) * delta, 1j * (g.b - 0.4 * delta), 0.7j * g.b - 0.2):
        u = g.velocity
        lap = (u(z + h) + u(z - h) + u(z + 1j * h) + u(z - 1j * h) - 4 * u(z)) / h**2
        grad_p = ((g.pressure(z + h) - g.pressure(z - h)) + 1j * (g.pressure(z + 1j * h)
                                                                  - g.pressure(z - 1j * h))) / (2 * h)
        div = (np.real(u(z + h) - u(z - h)) + np.imag(u(z + 1j * h) - u(z - 1j * h))) / (2 * h)
        grad_u = (abs(u(z + h) - u(z - h)) + abs(u(z + 1j * h) - u(z - 1j * h))) / (2 * h)
        assert abs(lap - grad_p) < 1e-5 * abs(grad_p)
        assert abs(div) < 1e-5 * grad_u


def twin_loads(d, kappa, n=4096, **motion):
    """(F_x, F_y, T_a, T_b) of the twin by quadrature of the traction."""
    force, t_a, t_b = twin(d, kappa, **motion).loads(n)
    return np.array([force.real, force.imag, t_a, t_b])


@pytest.mark.parametrize("d, kappa", TWIN_CASES)
def test_twin_loads_match_kernel(d, kappa):
    """Traction integrated over the walls of the twin's flow gives the kernel's seven coefficients.

    The trapezoid rule converges like exp(-N alpha') for the wall's distance
    alpha' to the nearest image point; N = 4096 is past convergence for every
    case (checked against N = 2048). The loads are differences of terms ~ the
    image coefficients: tolerance 1e-10 of each row's largest entry.
    """
    r = stokes_exact_resistance(1.0, d, 1.0, kappa, 1.0 - kappa)
    radial = twin_loads(d, kappa, u_a=1.0)
    inner = twin_loads(d, kappa, w_a=1.0)
    outer = twin_loads(d, kappa, w_b=1.0)
    assert radial[0] == pytest.approx(r[0], rel=1e-10)
    assert max(abs(radial[1]), abs(radial[2]), abs(radial[3])) < 1e-10 * abs(r[0])
    for loads, (f, t_a, t_b) in ((inner, (r[1], r[2], r[5])), (outer, (r[3], r[4], r[6]))):
        scale = max(abs(f), abs(t_a), abs(t_b))
        assert abs(loads[0]) < 1e-10 * scale
        np.testing.assert_allclose(loads[1:], [f, t_a, t_b], rtol=0.0, atol=1e-10 * scale)
    np.testing.assert_allclose(twin_loads(d, kappa, n=2048, w_a=1.0), inner, rtol=0, atol=1e-10 * scale)


@pytest.mark.parametrize("d, kappa", TWIN_CASES)
def test_twin_reciprocity(d, kappa):
    """Lorentz reciprocity on the twin's own loads, and its agreement with the kernel.

    For rigid wall motions the reciprocal theorem makes the resistance matrix
    of the generalised velocities (U_x, V, Omega_a, Omega_b) of the lab frame
    symmetric, V = eps chi' being A's speed along e_chi. Its entries
    are computed here from three independent twin flows (V, Omega_a, Omega_b):
    dT_b/dOmega_a = dT_a/dOmega_b, dF_y/dOmega_a = dT_a/dV, dF_y/dOmega_b = dT_b/dV.
    In the line-of-centres frame a unit V is chi' = 1/eps, i.e.
    W_a = W_b = -1/eps plus a rigid rotation, so dT_a/dV = -(R_t_a + R_t_b)/eps:
    the kernel's symmetric pair is R_chi_a = -(R_t_a + R_t_b)/eps, and likewise
    R_chi_b = -(R_b_a + R_b_b)/eps and R_t_b = R_b_a; and the drag along e_chi is
    -(R_chi_a + R_chi_b)/eps. Each flow also balances its torques about B:
    T_a + T_b + eps F_y = 0.
    """
    _, f_a, t_aa, t_ba = twin_loads(d, kappa, w_a=1.0)
    _, f_b, t_ab, t_bb = twin_loads(d, kappa, w_b=1.0)
    _, f_v, t_av, t_bv = twin_loads(d, kappa, u_a=1j)
    scale = max(abs(f_a), abs(t_aa), abs(f_b))
    assert abs(t_ba - t_ab) < 1e-10 * scale
    assert abs(f_a - t_av) < 1e-10 * scale
    assert abs(f_b - t_bv) < 1e-10 * scale
    eps = kappa * d
    r = stokes_exact_resistance(1.0, d, 1.0, kappa, 1.0 - kappa)
    assert -(r[2] + r[4]) / eps == pytest.approx(t_av, rel=1e-9)
    assert -(r[5] + r[6]) / eps == pytest.approx(t_bv, rel=1e-9)
    # the drag along e_chi: V with W_a = W_b = -V/eps is a rigid rotation, no load
    assert -(r[1] + r[3]) / eps == pytest.approx(f_v, rel=1e-9)
    # no net torque on the fluid about B, for each of the three flows
    for f_y, t_a, t_b in ((f_a, t_aa, t_ba), (f_b, t_ab, t_bb), (f_v, t_av, t_bv)):
        assert abs(t_a + t_b + eps * f_y) < 1e-10 * scale


@pytest.mark.parametrize("d, kappa", TWIN_CASES)
def test_twin_rigid_rotation_about_b(d, kappa):
    """Everything turning about B at Omega (V = eps Omega, Omega_a = Omega_b = Omega): U = i Omega z, no load.

    The twin's coefficients for this lab-frame motion are computed, not assumed
    zero; the kernel sees W_a = W_b = 0 through the face.
    """
    omega = 1.3
    eps = kappa * d
    g = twin(d, kappa, u_a=1j * eps * omega, w_a=omega, w_b=omega)
    z = np.array([eps - 1.0 - 0.5 * (1 + kappa) * d, 1j * (1 + d - 0.3 * d), 0.2 - 1.1j])
    np.testing.assert_allclose(g.velocity(z), 1j * omega * z, rtol=0, atol=1e-12 * g.term_size(z))
    force, t_a, t_b = g.loads()
    assert max(abs(force), abs(t_a), abs(t_b)) < 1e-10 * abs(twin_loads(d, kappa, w_a=omega)[2])
    annulus = Annulus.from_kappa(0.01, 0.01 * (1 + d), kappa, length=0.2)
    f = stokes_exact_forces(annulus, Motion(chi_dot=omega, omega_a=omega, omega_b=omega), Fluid(1e-4, 900.0))
    assert f.as_tuple() == (0.0, 0.0, 0.0)


# ---------------------------------------------------------------------------
# Limits, power laws, signs and identities of the kernel
# ---------------------------------------------------------------------------


def lubrication_coefficients(d, kappa):
    """The five forms (2.5)-(2.7) per unit length (a = mu = 1), RESISTANCE_NAMES order."""
    args = (1.0, d, 1.0, 1.0, kappa, 1.0 - kappa)
    f_eps = lubrication_forces(*args, 1.0, 0.0, 0.0)[0]
    _, f_a, t_a = lubrication_forces(*args, 0.0, 1.0, 0.0)
    _, f_b, t_b = lubrication_forces(*args, 0.0, 0.0, 1.0)
    return np.array([f_eps, f_a, t_a, f_b, t_b])


def ratios_to_lubrication(d, kappa):
    """Kernel coefficients over (2.5)-(2.7); at kappa = 0 the f_chi ratios from their limit kernel."""
    if kappa == 0.0:
        return np.array(stokes_exact_ratios(d, 0.0, 1.0))
    return kernel(1.0, d, 1.0 - kappa, kappa)[:5] / lubrication_coefficients(d, kappa)


#: c in ratio = 1 + c delta/a + O(delta/a)^2, derived in the module docstring.
def thin_gap_c(kappa):
    return np.array([1.5, 0.5, 1.5 / (1.0 + 2.0 * kappa**2), 2.5, 1.5])


@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.9, 1.0 - 1e-6])
def test_thin_gap_expansion(kappa):
    """ratio - 1 - c delta/a = O((delta/a)^2): log-log slope 2 +- 0.1 for every coefficient.

    (At kappa ~ 0.7 the second-order term of T_a per W_a changes sign, where
    the slope would read 3; the kappas here avoid it.)
    """
    ds = np.geomspace(1e-3, 3.2e-2, 6)
    rest = np.array([ratios_to_lubrication(d, kappa) - 1.0 - thin_gap_c(kappa) * d for d in ds])
    for k, name in enumerate(RESISTANCE_NAMES):
        slope = np.polyfit(np.log(ds), np.log(np.abs(rest[:, k])), 1)[0]
        assert abs(slope - 2.0) < 0.1, (name, slope)


def test_ratio_kernel():
    """stokes_exact_ratios equals coefficient / (2.5)-(2.7), and its f_chi ratios are continuous at kappa = 0.

    Both f_chi ratios are even in kappa: at kappa = 1e-4 they differ from the
    kappa = 0 value by O(1e-8).
    """
    for d in (1e-4, 0.40625, 10.0):
        for kappa in (1e-4, 0.3, 0.9, 1.0 - 1e-9):
            direct = kernel(1.0, d, 1.0 - kappa, kappa)[:5] / lubrication_coefficients(d, kappa)
            np.testing.assert_allclose(stokes_exact_ratios(d, kappa, 1.0 - kappa), direct, rtol=1e-14)
        near = kernel(1.0, d, 1.0 - 1e-4, 1e-4)[:5] / lubrication_coefficients(d, 1e-4)
        np.testing.assert_allclose(stokes_exact_ratios(d, 0.0, 1.0), near, rtol=1e-7)


@pytest.mark.parametrize("d", [1e-4, 0.40625, 10.0])
def test_contact_limits(d):
    """At contact each ratio tends to a power of b/a, linearly in 1 - kappa.

    From the module docstring: (b/a)^(3/2), (b/a)^(1/2), (b/a)^(1/2), (b/a)^(5/2),
    (b/a)^(3/2); the corrections are O(zeta^2) = O(1 - kappa).
    """
    b = 1.0 + d
    limit = b ** np.array([1.5, 0.5, 0.5, 2.5, 1.5])
    for omk in (1e-7, 1e-9, 1e-30, MIN_ONE_MINUS_KAPPA):   # the kernel holds to the Annulus' limit
        dev = np.array(stokes_exact_ratios(d, 1.0 - omk, omk)) / limit - 1.0
        assert np.all(np.abs(dev) < 100.0 * omk + 1e-14), (omk, dev)


@pytest.mark.parametrize("d", [1e-4, 0.40625, 10.0])
def test_power_laws_near_contact(d):
    """Slopes of log|R| against log(1 - kappa) at 1 - kappa = 1e-9 ... 1e-7.

    R_eps ~ zeta^-3 ~ (1-kappa)^(-3/2); R_chi_a, R_t_a, R_chi_b, T_b per W_b
    ~ zeta^-1; R_t_b = T_b per W_a ~ zeta. Corrections O(zeta^2) move the
    slopes by < 1e-6.
    """
    omks = np.array([1e-9, 1e-8, 1e-7])
    values = np.array([kernel(1.0, d, omk) for omk in omks])
    expected = [-1.5, -0.5, -0.5, -0.5, 0.5, 0.5, -0.5]
    for k, name in enumerate(EXACT_NAMES):
        slope = np.polyfit(np.log(omks), np.log(np.abs(values[:, k])), 1)[0]
        assert abs(slope - expected[k]) < 1e-4, (name, slope)


@pytest.mark.parametrize("d", [1e-4, 0.40625, 10.0])
def test_power_laws_near_concentric(d):
    """f_chi ~ kappa, and every other coefficient departs from its kappa = 0 value like kappa^2."""
    kappas = np.array([1e-3, 10**-2.5, 1e-2])
    values = np.array([kernel(1.0, d, 1.0 - k, k) for k in kappas])
    at_zero = kernel(1.0, d, 1.0)
    for k, name in enumerate(EXACT_NAMES):
        if name.startswith("f_chi"):
            slope = np.polyfit(np.log(kappas), np.log(values[:, k]), 1)[0]
            assert abs(slope - 1.0) < 1e-3, (name, slope)
        else:
            slope = np.polyfit(np.log(kappas), np.log(np.abs(values[:, k] - at_zero[k])), 1)[0]
            assert abs(slope - 2.0) < 1e-2, (name, slope)


@settings(max_examples=200, deadline=None)
@given(log_d=st.floats(math.log10(DELTA_OVER_A_RANGE[0]), math.log10(DELTA_OVER_A_RANGE[1])),
       kappa=st.one_of(st.just(0.0), st.floats(-12.0, -0.1).map(lambda x: 10.0**x),
                       st.floats(1e-12, 1.0 - 1e-9), st.floats(-9.0, -0.1).map(lambda x: 1.0 - 10.0**x)),
       a=st.floats(1e-3, 1e2))
def test_signs_and_identities(log_d, kappa, a):
    """Over the whole domain: finite values, physical signs, and the exact identities.

    Signs: the fluid resists radial motion and inner rotation (R_eps, R_t_a < 0)
    and the outer wall's own rotation (T_b per W_b < 0); rotation of either wall
    drives A along e_chi (R_chi >= 0) and the other wall forward (R_t_b > 0).
    Identities: R_chi_b = (b/a)^2 R_chi_a; torque balance on the fluid about B,
    T_a + T_b + eps f_chi = 0, for W_a and for W_b; |R_t_b| <= |R_t_a|.
    """
    delta = a * 10.0**log_d
    omk = 1.0 - kappa
    r = np.array(stokes_exact_resistance(a, delta, 1.0, kappa, omk))
    assert np.all(np.isfinite(r))
    r_eps, r_chi_a, r_t_a, r_chi_b, r_t_b, r_b_a, r_b_b = r
    assert r_eps < 0.0 and r_t_a < 0.0 and r_b_b < 0.0 and r_t_b > 0.0 and r_b_a > 0.0
    assert r_chi_a >= 0.0 and r_chi_b >= 0.0 and (r_chi_a > 0.0) == (kappa > 0.0)
    assert abs(r_t_b) <= abs(r_t_a) * (1.0 + 1e-15)   # equal at kappa = 0
    b, eps = a + delta, kappa * delta
    assert r_chi_b == pytest.approx((b / a) ** 2 * r_chi_a, rel=1e-14, abs=0.0)
    assert abs(r_t_a + r_b_a + eps * r_chi_a) < 1e-14 * abs(r_t_a)
    assert abs(r_t_b + r_b_b + eps * r_chi_b) < 1e-14 * abs(r_b_b)


# ---------------------------------------------------------------------------
# The Python face
# ---------------------------------------------------------------------------

ANNULUS = Annulus.from_kappa(A, B, 0.7, length=L)


def test_forces_combine_the_coefficients():
    """stokes_exact_forces = length x coefficients x (eps', W_a, W_b); chi' enters through W_a, W_b only."""
    motion = Motion(eps_dot=-3e-5, chi_dot=0.4, omega_a=1.5, omega_b=-0.7)
    f = stokes_exact_forces(ANNULUS, motion, OIL)
    assert f.model == "stokes-exact"
    r = exact_resistance(ANNULUS, OIL)
    assert isinstance(r, ExactResistance) and r.NAMES == EXACT_NAMES
    w_a, w_b = 1.5 - 0.4, -0.7 - 0.4
    expected = (r.f_eps_per_eps_dot * motion.eps_dot, r.f_chi_per_w_a * w_a + r.f_chi_per_w_b * w_b,
                r.t_a_per_w_a * w_a + r.t_a_per_w_b * w_b)
    np.testing.assert_allclose(f.as_tuple(), expected, rtol=1e-14)
    unit = stokes_exact_resistance(ANNULUS.a, ANNULUS.delta, OIL.mu, ANNULUS.kappa,
                                   ANNULUS.one_minus_kappa)
    np.testing.assert_allclose(r.as_tuple(), np.array(unit) * ANNULUS.length, rtol=1e-15)
    assert r.resistance().as_tuple() == r.as_tuple()[:5]
    np.testing.assert_allclose(exact_ratios(ANNULUS), ratios_to_lubrication(ANNULUS.delta_over_a,
                                                                           ANNULUS.kappa), rtol=1e-13)


def test_kernel_agrees_with_the_closed_forms_to_first_order_in_the_gap():
    """The model's kernel (the registry's) and the closed forms' agree to O(delta/a) in a thin gap."""
    a, delta = 0.01, 1e-5
    state = (a, a + delta, 0.3, 0.2, 0.6, 0.4, 2e-7, 0.8, -0.3)
    exact = kernel_model("stokes-exact").kernel(kernel_model("stokes-exact").data, *state)
    lub = lubrication_forces(a, delta, *state[2:])
    for e, lb in zip(exact, lub):
        assert e == pytest.approx(lb, rel=5.0 * delta / a)
        assert e != pytest.approx(lb, rel=0.1 * delta / a)


@pytest.mark.parametrize("annulus, match", [
    (Annulus(a=1.0, b=1.00005), "delta_over_a"),
    (Annulus(a=1.0, b=11.5), "delta_over_a"),
    (Annulus.from_kappa(1.0, 1.4, 1.0 - 1e-10), r"one_minus_kappa = 1 - kappa .* \(kappa at most 1 - 1e-09\), got 1e-10"),
])
def test_bad_input(annulus, match):
    with pytest.raises(ValueError, match=match):
        stokes_exact_forces(annulus, Motion(), OIL)
    with pytest.raises(ValueError, match=match):
        exact_resistance(annulus, OIL)


def test_domain_edges_accepted():
    """The ends of the stated domain are accepted (b = 11 a rounds (b - a)/a to 10 + 1 ulp for some a)."""
    for annulus in (Annulus(a=0.1, b=1.1), Annulus(a=1.0, b=1.0001),
                    Annulus.from_kappa(1.0, 1.4, 1.0 - 1e-9)):
        assert np.all(np.isfinite(exact_resistance(annulus, OIL).as_tuple()))


# ---------------------------------------------------------------------------
# The finite-element solver against the exact solution
# ---------------------------------------------------------------------------


def fe_coefficients(d, kappa, n_around, n_across):
    """The seven coefficients (a = mu = 1) from lubrication.stokes on the given mesh."""
    pytest.importorskip("skfem")
    from lubrication.stokes import _discretisation, stokes_resistance

    r = stokes_resistance(1.0, 1.0 + d, kappa, n_around=n_around, n_across=n_across)
    disc = _discretisation(1.0 + d, kappa * d, n_around, n_across, 0.5)
    t_b = [disc.loads(disc.solve(0.0, 1.0, 0.0))["torque_b"], disc.loads(disc.solve(0.0, 0.0, 1.0))["torque_b"]]
    return np.array([getattr(r, n) for n in RESISTANCE_NAMES] + t_b)


def fe_errors(fe, exact):
    """Relative error per coefficient, EXACT_NAMES order.

    The torques per outer rotation (T_a per W_b, T_b per W_a: the same
    number by reciprocity) are O(zeta) differences of O(1/zeta) parts near
    contact; they are measured against the larger entry of their row,
    max(|T_a per W_a|, |T_a per W_b|). At kappa = 0 the f_chi coefficients vanish
    and are measured against |T_a per W_a| / a.
    """
    scale = np.abs(exact).copy()
    row = max(abs(exact[2]), abs(exact[4]))
    scale[4] = scale[5] = row
    if exact[1] == 0.0:
        scale[1] = scale[3] = abs(exact[2])
    return np.abs(fe - exact) / scale


def test_fe_cheap():
    """One fast finite-element case: delta/a = 0.01, kappa = 0.9, mesh 512 x 8 (about 1 s).

    Measured error 2.4e-8 at most (R_chi_a); h^4 convergence of the solver
    puts the default mesh (256 x 4) at ~5e-7, this one 16 times lower.
    """
    d, kappa = 0.01, 0.9
    fe = fe_coefficients(d, kappa, 512, 8)
    err = fe_errors(fe, kernel(1.0, d, 1.0 - kappa, kappa))
    assert np.all(err < 1e-7), dict(zip(EXACT_NAMES, err))


def doubled_default_mesh(d):
    pytest.importorskip("skfem")
    from lubrication.stokes import default_mesh

    na, nc = default_mesh(d)
    return 2 * na, 2 * nc


@pytest.mark.slow
@pytest.mark.parametrize("d", [0.01, 0.40625, 1.0])
@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.9])
def test_fe_agrees_to_1e7(d, kappa):
    """kappa <= 0.9: the finite-element coefficients agree to 1e-7 on twice the default mesh.

    Mesh (n_around, n_across) = 2 x default_mesh(delta/a): (512, 8), (576, 18),
    (896, 28) for delta/a = 0.01, 0.40625, 1; 1-18 s per case. Measured errors
    5e-11 .. 6.7e-8 (T_a per W_b and T_b per W_a measured against their row).
    """
    fe = fe_coefficients(d, kappa, *doubled_default_mesh(d))
    err = fe_errors(fe, kernel(1.0, d, 1.0 - kappa, kappa))
    assert np.all(err < 1e-7), dict(zip(EXACT_NAMES, err))


@pytest.mark.slow
@pytest.mark.parametrize("d", [0.01, 0.40625, 1.0])
def test_fe_agrees_near_contact(d):
    """kappa = 0.99: agreement to 1e-5 on twice the default mesh, every coefficient against itself.

    Measured: T_a per W_b 4.9e-6, 2.2e-6, 2.0e-6 of itself (2e-8 .. 3e-8 of its
    row) for delta/a = 0.01, 0.40625, 1; the others below 1.5e-7.
    """
    kappa = 0.99
    exact = kernel(1.0, d, 1.0 - kappa, kappa)
    fe = fe_coefficients(d, kappa, *doubled_default_mesh(d))
    err = np.abs(fe / exact - 1.0)
    assert np.all(err < 1e-5), dict(zip(EXACT_NAMES, err))


def test_docs_table_matches_kernel():
    """docs/stokes_exact.md quotes the apparatus' ratios to 4 digits: they must be the kernel's."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "docs" / "stokes_exact.md").read_text()
    rows = [line.split("|")[1:-1] for line in text.splitlines() if line.startswith("| 0")]
    assert [float(r[0]) for r in rows] == [0.0, 0.3, 0.6, 0.9, 0.99]
    for r in rows:
        kappa = float(r[0])
        quoted = [float(x) for x in r[1:]]
        np.testing.assert_allclose(stokes_exact_ratios(0.40625, kappa, 1.0 - kappa), quoted, rtol=0,
                                   atol=5.01e-5)
