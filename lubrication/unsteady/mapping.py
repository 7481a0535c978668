r"""The conformal map of a concentric annulus onto the eccentric one.

Physical plane
--------------
The complex position is zeta = x + i z in the project's coordinates (x down the
slope, z along the plane's upward normal), with the outer centre B at the origin.
The outer wall is |zeta| = b, the inner wall |zeta - z_A| = a with A at the complex
position z_A, eps = |z_A| < b - a. Rotations are clockwise positive: a rotation
Omega about a centre c moves the point zeta with the velocity -i Omega (zeta - c).
The line of centres B -> A has the direction e_eps = (sin chi, cos chi) = z_A/eps,
and e_chi = (cos chi, -sin chi) = -i e_eps.

The map
-------
The disk automorphism

    zeta = b (w + p) / (1 + conj(p) w),        |p| < 1,

maps |w| = 1 onto the outer circle and every circle |w| = r onto a circle whose
pair of inverse points is (b p, b / conj(p)): the images of w = 0 and w = infinity.
The inner circle is such a circle exactly when b p and b/conj(p) are its inverse
points too, i.e. they are the two limit points P, Q of the pair of walls. Both lie
on the line of centres, so p = r_p z_A/eps, and with s = |P| = b r_p,
(s - eps)(b^2/s - eps) = a^2, that is r_p + 1/r_p = S/(eps b) with
S = b^2 - a^2 + eps^2. The root inside the unit disk,

    p = 2 b z_A / (S + D),     D = sqrt(S^2 - 4 eps^2 b^2),

is an analytic function of z_A and conj(z_A) through eps^2: regular through eps = 0,
where p = b z_A/(b^2 - a^2) + O(eps^3) -> 0 and the map is zeta = b w. The grid
slides with z_A; it is never turned by the angle chi, which is undefined at eps = 0.
D^2 = ((b - eps)^2 - a^2)((b + eps)^2 - a^2) is formed from the gap b - a - eps,
so that nothing cancels near contact.

The inner wall is the image of |w| = r0. The annulus r0 < |w| < 1 is conformally
equivalent to the eccentric one, so its modulus ln(1/r0) is the bipolar parameter
tau of :mod:`lubrication.stokes_exact`:

    cosh(tau) = (a^2 + b^2 - eps^2)/(2 a b),   r0 = exp(-tau),

-> a/b as eps -> 0, and tau -> 0 (r0 -> 1) at contact. With |p| = exp(-beta), beta the
bipolar coordinate of the outer wall, sinh(beta + tau) = (b/a) sinh(beta) gives
tanh(beta) = sinh(tau)/(b/a - cosh(tau)), and 1 - |p|^2 = 2 t/(1 + t) with
t = tanh(beta): both without cancellation near contact (beta ~ sqrt(2 a (1 - kappa)/b)).

Log-polar computational coordinates
-----------------------------------
The solver works in sigma = s + i theta = log(w), s in [-tau, 0], theta periodic, and
in the Chebyshev variable x in [-1, 1] with s = -tau (1 - x)/2: x = 1 is the outer
wall, x = -1 the inner one. (sigma is the bipolar coordinate pair up to a shift.)
The plane Laplacian is conformally covariant,

    Lap_zeta = g (d^2/ds^2 + d^2/dtheta^2),    g = 1/|d zeta/d sigma|^2,

and d zeta/d sigma = w zeta'(w) = b (1 - |p|^2) w / (1 + conj(p) w)^2, so

    g = |(1 + conj(p) w)^2 / w|^2 / (b^2 (1 - |p|^2)^2)
      = sum_{m=-2..2} g_m(rho) e^{i m theta},   rho = |w| = e^s,

with, from v = (1 + conj(p) w)^2/w = e^{-i theta}/rho + 2 conj(p) + conj(p)^2 rho e^{i theta},

    g_0 = (rho^-2 + 4 |p|^2 + |p|^4 rho^2) / K,    g_1 = 2 conj(p) (rho^-1 + |p|^2 rho) / K,
    g_2 = conj(p)^2 / K,                          g_-m = conj(g_m),   K = b^2 (1 - |p|^2)^2:

a trigonometric polynomial of degree 2 in theta, represented exactly by five
Fourier coefficients (the implicit operator couples the Fourier index k only
to k +- 1, k +- 2).

The stream-function weight
--------------------------
The exact Stokes flows of rigid walls (Jeffery 1922) have a stream function psi
whose product with the bipolar metric factor cosh(xi) - cos(eta) is a
trigonometric polynomial of degree 1 in the bipolar angle eta. In the map's
variables that factor is, up to a constant,

    H = |1 + conj(p) w|^2 / |w| = H_0(s) + conj(p) e^{i theta} + p e^{-i theta},
    H_0 = e^{-s} + |p|^2 e^{s},        H = 2 |p| (cosh(s - beta) + cos(theta - arg p)),

positive on the closed annulus (|p| < 1 <= 1/|p|), and = e^{-s} at p = 0; it is the
reciprocal of the line element: |d zeta/d sigma| = b (1 - |p|^2)/H, g = H^2/k with
k = b^2 (1 - |p|^2)^2. psi itself is not low-degree: its coefficients fall only
like (|p| rho)^|k| (those of 1/|1 + conj(p) w|^2), slowly near contact, where
the wide part of the gap is squeezed into an angle ~ beta of the computational
circle. The solver therefore works with Psi = H psi. Since H is of the form
c (cosh(xi) + cos(eta)), |grad H|^2 = H Lap H and Lap H = H_0 - conj(p) e^{i theta}
- p e^{-i theta} (H_0'' = H_0), so that

    H^2 Lap_sigma(Psi / H) = H Lap Psi - 2 grad H . grad Psi + (Lap H) Psi,
    Lap_zeta psi = (1/k) [H Lap Psi - 2 grad H . grad Psi + (Lap H) Psi],

whose Fourier coefficients are (D = d/ds, H_0' = -e^{-s} + |p|^2 e^{s})

    (k Lap_zeta psi)_k = H_0 (D^2 - k^2 + 1) Psi_k - 2 H_0' D Psi_k
                         + conj(p) (D^2 - (k - 2)^2) Psi_{k-1} + p (D^2 - (k + 2)^2) Psi_{k+1}:

a tridiagonal coupling in k. The velocity needs no division either:
g psi_theta = (H Psi_theta - H_theta Psi)/k and g psi_s = (H Psi_s - H_s Psi)/k.
The vorticity of those Stokes flows, 4 Im phi'(zeta) in Goursat's form, has poles
only at the limit points, images of w = 0 and w = infinity: a Laurent polynomial
of degree 2 in w. So a few Fourier modes of (Psi, omega) hold the exact steady
Stokes flow at every eccentricity, while psi needs ~ 1/beta of them.

Mesh velocity
-------------
A grid point of fixed (x, theta) moves because p and tau change with z_A. At fixed
w, d zeta/dt = b [p' (1 + conj(p) w) - (w + p) conj(p') w]/(1 + conj(p) w)^2, and
over d zeta/d sigma:

    (d zeta/dt|_w) / (d zeta/d sigma) = [p' e^{-sigma} + 2 i Im(p' conj(p)) - conj(p') e^{sigma}] / (1 - |p|^2),

a Laurent polynomial in w; the radial stretching of the grid with tau adds
ds/dt|_x = -tau' (1 - x)/2. The total, mu_sigma = (d zeta/dt|_{x,theta})/(d zeta/d sigma),
gives the mesh velocity's components in the (s, theta) directions: x_t . grad f =
Re(mu_sigma) f_s + Im(mu_sigma) f_theta for any field f. It is linear in
U = z_A': p' = P1 U + P2 conj(U), tau' = T1 Re(conj(z_A) U), with
p = z_A h(eps^2), h = 2 b/(S + D), P1 = h + eps^2 h', P2 = z_A^2 h',
h' = -2 b (S + D - 2 b^2)/(D (S + D)^2) and T1 = -1/(a b sinh(tau)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry import check_finite, check_range

__all__ = ["AnnulusMap", "MIN_ONE_MINUS_KAPPA_UNSTEADY"]

#: Smallest 1 - kappa at which the unsteady solver accepts a geometry (see
#: :mod:`lubrication.unsteady.resolution` for the measurements behind it).
MIN_ONE_MINUS_KAPPA_UNSTEADY = 1e-5


@dataclass(frozen=True)
class AnnulusMap:
    """The map zeta(w) of one geometry, its metric and its mesh velocity.

    Parameters
    ----------
    a, b : float
        Inner and outer radius (m), 0 < a < b.
    z_a : complex
        Position of the inner centre A relative to B, x + i z (m), |z_a| < b - a.

    Attributes
    ----------
    eps, gap : float
        |z_a| and the narrowest gap b - a - eps (m).
    one_minus_kappa : float
        gap / (b - a).
    tau : float
        Bipolar parameter, ln(1/r0).
    p : complex
        Parameter of the map.
    one_minus_p2 : float
        1 - |p|^2, formed without cancellation.
    beta : float
        -ln|p| (infinite at eps = 0).
    """

    a: float
    b: float
    z_a: complex = 0j

    def __post_init__(self):
        a = check_range("a", self.a, 0.0, math.inf, low_open=True, unit="m")
        b = check_finite("b", self.b)
        if not b > a:
            msg = f"b must be greater than a = {a:g} m (outer radius), got {self.b!r}"
            raise ValueError(msg)
        z = complex(self.z_a)
        check_finite("x_a", z.real)
        check_finite("z_a", z.imag)
        delta = b - a
        eps = abs(z)
        gap = delta - eps
        if not gap > 0.0:
            msg = (f"|z_a| = eps must be in [0, {delta:g}) m (the inner wall inside the outer one), "
                   f"got eps = {eps!r} m")
            raise ValueError(msg)
        x = gap * (delta + eps) / (2.0 * a * b)  # cosh(tau) - 1
        sh = math.sqrt(x * (x + 2.0))
        tau = math.log1p(x + sh)
        s_ = b * b - a * a + eps * eps
        # D^2 = ((b - eps)^2 - a^2)((b + eps)^2 - a^2), the first factor from the gap
        d_ = math.sqrt(gap * (b - eps + a) * (b + eps - a) * (b + eps + a))
        h = 2.0 * b / (s_ + d_)
        p = z * h
        t = min(sh / (delta / a - x), 1.0)  # tanh(beta), |p| = exp(-beta); 1 at eps = 0
        beta = math.atanh(t) if t < 1.0 else math.inf
        one_minus_p2 = 2.0 * t / (1.0 + t)
        dh = -2.0 * b * (s_ + d_ - 2.0 * b * b) / (d_ * (s_ + d_) ** 2)  # dh/d(eps^2)
        for name, value in (("eps", eps), ("gap", gap), ("one_minus_kappa", gap / delta), ("tau", tau),
                            ("p", p), ("one_minus_p2", one_minus_p2), ("beta", beta), ("_sinh_tau", sh),
                            ("_p1", h + eps * eps * dh), ("_p2", z * z * dh), ("z_a", z), ("a", a), ("b", b)):
            object.__setattr__(self, name, value)

    # ------------------------------------------------------------------ scalars

    @property
    def delta(self) -> float:
        """Mean gap b - a (m)."""
        return self.b - self.a

    @property
    def kappa(self) -> float:
        return 1.0 - self.one_minus_kappa

    @property
    def r0(self) -> float:
        """Radius of the inner wall's preimage, exp(-tau)."""
        return math.exp(-self.tau)

    @property
    def e_eps(self) -> complex:
        """Unit vector B -> A (1 at eps = 0 by convention: chi is then undefined)."""
        return self.z_a / self.eps if self.eps > 0.0 else 1.0 + 0j

    def p_dot(self, u: complex) -> complex:
        """dp/dt for the inner centre's velocity ``u`` = (z_a)'."""
        return self._p1 * u + self._p2 * np.conj(u)

    def tau_dot(self, u: complex) -> float:
        """d tau/dt for the inner centre's velocity ``u``: d tau/d(eps^2) = -1/(2 a b sinh tau)."""
        return -float((np.conj(self.z_a) * u).real) / (self.a * self.b * self._sinh_tau)

    # ------------------------------------------------------------------ fields

    def s(self, x):
        """Log-radius s = ln|w| of the Chebyshev variable x (x = 1 outer wall, x = -1 inner wall)."""
        return -0.5 * self.tau * (1.0 - np.asarray(x, dtype=float))

    def w(self, x, theta):
        """w = exp(s + i theta) on the grid (x along the first axis, theta along the second)."""
        s = self.s(x)
        return np.exp(s)[..., None] * np.exp(1j * np.asarray(theta))[None, ...]

    def zeta(self, w):
        """Physical position zeta(w) = b (w + p)/(1 + conj(p) w)."""
        return self.b * (w + self.p) / (1.0 + np.conj(self.p) * w)

    def dzeta_dsigma(self, w):
        """d zeta / d sigma = b (1 - |p|^2) w / (1 + conj(p) w)^2."""
        return self.b * self.one_minus_p2 * w / (1.0 + np.conj(self.p) * w) ** 2

    def metric_coefficients(self, x) -> np.ndarray:
        """g_m(x) for m = -2..2, shape (5, len(x)): g = sum_m g_m e^{i m theta} = 1/|d zeta/d sigma|^2."""
        rho = np.exp(self.s(x))
        p = self.p
        pc = np.conj(p)
        p2 = abs(p) ** 2
        k = (self.b * self.one_minus_p2) ** 2
        g = np.empty((5, rho.size), dtype=complex)
        g[2] = (1.0 / rho**2 + 4.0 * p2 + p2 * p2 * rho**2) / k
        g[3] = 2.0 * pc * (1.0 / rho + p2 * rho) / k
        g[4] = pc * pc / k
        g[1] = np.conj(g[3])
        g[0] = np.conj(g[4])
        return g

    def stream_weight_coefficients(self, x) -> tuple[np.ndarray, np.ndarray, complex]:
        """H_0(x), dH_0/ds(x) and H_1 = conj(p): H = H_0 + H_1 e^{i theta} + conj(H_1) e^{-i theta} (module doc)."""
        rho = np.exp(self.s(x))
        p2 = abs(self.p) ** 2
        return 1.0 / rho + p2 * rho, -1.0 / rho + p2 * rho, complex(np.conj(self.p))

    def stream_weight_fields(self, x, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """H, dH/ds and dH/dtheta on the grid (x along the first axis, theta along the second)."""
        h0, dh0, h1 = self.stream_weight_coefficients(x)
        e = h1 * np.exp(1j * np.asarray(theta))
        return h0[:, None] + 2.0 * e.real[None, :], np.repeat(dh0[:, None], e.size, axis=1), \
            -2.0 * e.imag[None, :].repeat(h0.size, axis=0)

    def stream_weight(self, w):
        """H = |1 + conj(p) w|^2 / |w| evaluated directly (a check on :meth:`stream_weight_coefficients`)."""
        return np.abs(1.0 + np.conj(self.p) * w) ** 2 / np.abs(w)

    def metric(self, w):
        """g = 1/|d zeta/d sigma|^2 evaluated directly (a check on :meth:`metric_coefficients`)."""
        return 1.0 / np.abs(self.dzeta_dsigma(w)) ** 2

    def mesh_velocity(self, u: complex, x, theta):
        """mu_sigma = (d zeta/dt at fixed x, theta)/(d zeta/d sigma) for the centre velocity ``u``.

        Returns a complex array of shape (len(x), len(theta)): its real part is
        ds/dt and its imaginary part d theta/dt of the points that the grid
        point passes (so that x_t . grad f = Re(mu) f_s + Im(mu) f_theta).
        """
        pd = self.p_dot(u)
        w = self.w(x, theta)
        conformal = (pd / w + 2j * (pd * np.conj(self.p)).imag - np.conj(pd) * w) / self.one_minus_p2
        radial = -0.5 * self.tau_dot(u) * (1.0 - np.asarray(x, dtype=float))
        return conformal + radial[:, None]

    def wall_series(self, n_modes: int) -> dict[str, np.ndarray]:
        """Exact Fourier coefficients, k = -K..K (K = n_modes // 2), of the wall weights.

        Keys: ``"zeta_in"`` (zeta - z_A on |w| = r0), ``"dzeta_in"`` (d zeta/d sigma
        on |w| = r0), ``"abs_dzeta_in"`` and ``"abs_dzeta_out"`` (|d zeta/d sigma| on
        the two walls). From the series zeta = b [p + (1 - |p|^2) sum_{n>=1}
        (-conj(p))^(n-1) w^n], w zeta' = b (1 - |p|^2) sum_{n>=1} n (-conj(p))^(n-1) w^n
        and the Poisson kernel 1/|1 + c e^{i theta}|^2 = (1 - |c|^2)^-1
        [sum_{n>=0} (-c)^n e^{i n theta} + sum_{n>=1} (-conj(c))^n e^{-i n theta}].
        """
        kk = n_modes // 2
        n = np.arange(1, kk + 1)
        b, p, omp2 = self.b, self.p, self.one_minus_p2
        pc = np.conj(p)
        r0 = self.r0
        out = {}
        zeta_in = np.zeros(2 * kk + 1, dtype=complex)
        zeta_in[kk] = b * p - self.z_a
        zeta_in[kk + 1:] = b * omp2 * (-pc) ** (n - 1) * r0**n
        out["zeta_in"] = zeta_in
        dz = np.zeros(2 * kk + 1, dtype=complex)
        dz[kk + 1:] = b * omp2 * n * (-pc) ** (n - 1) * r0**n
        out["dzeta_in"] = dz
        for key, rho in (("abs_dzeta_in", r0), ("abs_dzeta_out", 1.0)):
            c = pc * rho
            # 1 - |p|^2 rho^2 = 1 - exp(-2 (beta - ln rho)), without cancellation near contact
            one_minus_c2 = -math.expm1(-2.0 * (self.beta - math.log(rho)))
            coef = np.zeros(2 * kk + 1, dtype=complex)
            coef[kk] = 1.0
            coef[kk + 1:] = (-c) ** n
            coef[:kk][::-1] = (-np.conj(c)) ** n
            out[key] = b * omp2 * rho / one_minus_c2 * coef
        return out
