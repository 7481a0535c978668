r"""Exact solutions of the unsteady flow in a concentric annulus, derived here for the tests.

Conventions as the project: rotations and torques clockwise positive; the force on
the inner cylinder per unit length; a < r < b.

Couette spin-up
---------------
The outer wall is set turning at Omega_b at t = 0 with the fluid at rest and the
inner wall held. The clockwise azimuthal velocity v(r, t) obeys
v_t = nu (v_rr + v_r/r - v/r^2), v(a) = 0, v(b) = Omega_b b, v(r, 0) = 0. The steady
state is v_s = A r + B/r with A = Omega_b b^2/(b^2 - a^2), B = -Omega_b a^2 b^2/(b^2 - a^2);
the rest, v - v_s, vanishes on both walls and expands in the eigenfunctions of
the operator, phi_n(r) = J1(l r) Y1(l a) - Y1(l r) J1(l a) with phi_n(b) = 0
(l = l_n, orthogonal with weight r):

    v = v_s - sum_n c_n phi_n(r) exp(-nu l_n^2 t),   c_n = int v_s phi_n r dr / int phi_n^2 r dr.

The shear stress on a wall is mu r d(v/r)/dr; the clockwise torque of the fluid on
the inner wall is 2 pi a^2 mu v_r(a) (v(a) = 0), on the outer wall
-2 pi b^2 mu (v_r - v/r)(b). As t -> infinity they tend to -4 pi mu B = 4 pi mu Omega_b
a^2 b^2/(b^2 - a^2) and its opposite: the fluid drags the held inner wall the way
the outer one turns, and brakes the outer one. With the inner wall turning as
well the same series holds with v(a) = Omega_a a in the steady state.

Free cylinder after an impulse
------------------------------
:func:`free_cylinder_velocity`: the oscillating cylinder's force, continued to the
Laplace variable s = i w, closes Newton's law of a free cylinder.

Oscillating inner cylinder
--------------------------
The inner cylinder, concentric, moves along x with the velocity Re(U e^{i w t}), of
small amplitude (linear, the geometry frozen at the concentric position, no
convection). With the polar angle phi from the x axis towards z and
u_x = psi_z, u_z = -psi_x (u_r = psi_phi / r, u_phi = -psi_r), take
psi = Re(F(r) sin(phi) e^{i w t}). The vorticity omega = -Lap psi = W(r) sin(phi)
e^{i w t} with W = -(F'' + F'/r - F/r^2) satisfies the unsteady Stokes equation
i w W = nu (W'' + W'/r - W/r^2), so W = C I1(k r) + D K1(k r) with k^2 = i w / nu,
and F = A r + B/r - W/k^2 (r and 1/r are the harmonic part). No-slip: on r = a,
psi = U a sin(phi) + const, so F(a) = U a, F'(a) = U; on r = b, F = F' = 0.
Force along x: with sigma_rr = -p + 2 mu d(u_r)/dr, sigma_rphi = mu (r (u_phi/r)_r + u_r,phi / r),
u_r = (F/r) cos(phi), u_phi = -F' sin(phi), and the pressure P cos(phi) from the
azimuthal momentum balance at r = a, rho u_phi,t = -p_phi / r + mu omega_r
(the phi-component of Lap u is d omega/dr): P = -a (rho i w F'(a) + mu W'(a)),

    F_x / (pi a) = -P + 2 mu (F/r)'(a) + mu (F''(a) - F'(a)/a + F(a)/a^2),

per unit length, times e^{i w t}. Limits: w -> 0 gives the steady Stokes drag
-4 pi mu U / (ln(b/a) - (b^2 - a^2)/(b^2 + a^2)); w -> infinity the inviscid added mass
-rho pi a^2 (b^2 + a^2)/(b^2 - a^2) i w U (the potential flow between the walls).
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy import optimize, special


@functools.lru_cache(maxsize=4)
def _gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights (scipy's tridiagonal eigenproblem; leggauss's dense one took seconds)."""
    return special.roots_legendre(n)


@functools.lru_cache(maxsize=8)
def couette_eigenvalues(a: float, b: float, n: int) -> np.ndarray:
    """The first ``n`` roots l of J1(l b) Y1(l a) - Y1(l b) J1(l a) = 0."""
    f = lambda x: special.j1(x * b) * special.y1(x * a) - special.y1(x * b) * special.j1(x * a)  # noqa: E731
    step = math.pi / (b - a) / 20.0
    roots, x0 = [], 1e-9 / (b - a)
    f0 = f(x0)
    while len(roots) < n:
        x1 = x0 + step
        f1 = f(x1)
        if f0 * f1 < 0.0:
            roots.append(optimize.brentq(f, x0, x1, xtol=1e-15 / (b - a), rtol=1e-15))
        x0, f0 = x1, f1
    return np.array(roots)


def couette_spinup_torques(a: float, b: float, nu: float, rho: float, omega_b: float, t, n_terms: int = 80,
                           omega_a: float = 0.0):
    """Clockwise torques (T_a on the inner wall about its axis, T_b on the outer) per unit length at times t.

    Both walls may start: v(a) = omega_a a, v(b) = omega_b b for t > 0, and the steady state has
    A = (omega_b b^2 - omega_a a^2)/(b^2 - a^2), B = (omega_a - omega_b) a^2 b^2/(b^2 - a^2); the
    transient is expanded as above (v - v_s vanishes on both walls)."""
    mu = rho * nu
    big_a = (omega_b * b * b - omega_a * a * a) / (b * b - a * a)
    big_b = (omega_a - omega_b) * a * a * b * b / (b * b - a * a)
    lam = couette_eigenvalues(a, b, n_terms)
    # Gauss-Legendre on [a, b]: 400 nodes integrate the 80th eigenfunction's products to rounding
    xg, wg = _gauss_legendre(400)
    r = 0.5 * (b - a) * xg + 0.5 * (a + b)
    wg = 0.5 * (b - a) * wg
    t = np.atleast_1d(np.asarray(t, dtype=float))
    t_a = np.full(t.shape, -4.0 * math.pi * mu * big_b)
    t_b = -t_a.copy()
    for ln in lam:
        phi = special.j1(ln * r) * special.y1(ln * a) - special.y1(ln * r) * special.j1(ln * a)
        dphi = lambda r, ln=ln: ln * (special.jvp(1, ln * r) * special.y1(ln * a) -  # noqa: E731
                                      special.yvp(1, ln * r) * special.j1(ln * a))
        c = np.sum(wg * (big_a * r + big_b / r) * phi * r) / np.sum(wg * phi**2 * r)
        decay = np.exp(-nu * ln * ln * t)
        # v - v_s = -c phi exp(..): torque terms; phi(a) = phi(b) = 0
        t_a += 2.0 * math.pi * a * a * mu * (-c * dphi(a)) * decay
        t_b += -2.0 * math.pi * b * b * mu * (-c * dphi(b)) * decay
    return t_a, t_b


def oscillating_cylinder_force(a: float, b: float, nu: float, rho: float, w: float) -> complex:
    """Complex force per unit length per unit complex velocity amplitude, F_x = Re(Z U e^{i w t})."""
    mu = rho * nu
    k = np.sqrt(1j * w / nu)
    i1, k1 = special.iv, special.kv

    def basis(r):
        """F and its first two derivatives for the unknowns (A, B, C, D)."""
        kr = k * r
        iv1, kv1 = i1(1, kr), k1(1, kr)
        div1 = k * special.ivp(1, kr)
        dkv1 = k * special.kvp(1, kr)
        d2iv1 = k * k * special.ivp(1, kr, 2)
        d2kv1 = k * k * special.kvp(1, kr, 2)
        f = np.array([r, 1.0 / r, -iv1 / k**2, -kv1 / k**2])
        df = np.array([1.0, -1.0 / r**2, -div1 / k**2, -dkv1 / k**2])
        d2f = np.array([0.0, 2.0 / r**3, -d2iv1 / k**2, -d2kv1 / k**2])
        w_ = np.array([0.0, 0.0, iv1, kv1])
        dw = np.array([0.0, 0.0, div1, dkv1])
        return f, df, d2f, w_, dw

    fa, dfa, d2fa, wa, dwa = basis(a)
    fb, dfb, _, _, _ = basis(b)
    mat = np.array([fa, dfa, fb, dfb], dtype=complex)
    coef = np.linalg.solve(mat, np.array([a, 1.0, 0.0, 0.0], dtype=complex))  # U = 1
    f_a, df_a, d2f_a, dw_a = fa @ coef, dfa @ coef, d2fa @ coef, dwa @ coef
    p = -a * (rho * 1j * w * df_a + mu * dw_a)
    d_f_over_r = df_a / a - f_a / a**2
    return math.pi * a * (-p + 2.0 * mu * d_f_over_r + mu * (d2f_a - df_a / a + f_a / a**2))


def steady_drag(a: float, b: float, mu: float) -> float:
    """Concentric steady Stokes drag per unit length per unit velocity (negative)."""
    return -4.0 * math.pi * mu / (math.log(b / a) - (b * b - a * a) / (b * b + a * a))


def inviscid_added_mass(a: float, b: float, rho: float) -> float:
    """rho pi a^2 (b^2 + a^2)/(b^2 - a^2), per unit length."""
    return rho * math.pi * a * a * (b * b + a * a) / (b * b - a * a)


def oscillating_spin_torque(a: float, b: float, nu: float, rho: float, w: float) -> complex:
    """Clockwise torque on the inner wall per unit clockwise spin Omega_a = Re(e^{i w t}), outer wall held.

    The clockwise azimuthal velocity Re(V(r) e^{i w t}) obeys i w V = nu (V'' + V'/r - V/r^2):
    V = C I1(k r) + D K1(k r), k^2 = i w / nu, V(a) = a, V(b) = 0; the torque of the fluid on the inner
    wall is 2 pi a^2 mu (V' - V/r) at r = a (the shear stress mu r (V/r)').
    """
    mu = rho * nu
    k = np.sqrt(1j * w / nu)
    mat = np.array([[special.iv(1, k * a), special.kv(1, k * a)], [special.iv(1, k * b), special.kv(1, k * b)]])
    c, d = np.linalg.solve(mat, np.array([a, 0.0], dtype=complex))
    dv = k * (c * special.ivp(1, k * a) + d * special.kvp(1, k * a))
    return 2.0 * math.pi * a * a * mu * (dv - 1.0)


def _scaled_bessel(k: complex, r: float, kind: str, ref: float):
    """Z1(k r) and its first two r-derivatives, divided by Z1(k ref): Z1 = I1 (ref = b) or K1 (ref = a).

    The exponentially scaled ive, kve keep the ratio finite for any |k| (Re k >= 0): the I1 ratio
    is ~ exp(Re(k) (r - b)), the K1 ratio ~ exp(-k (r - a)). Derivatives from I1' = I0 - I1/z,
    K1' = -K0 - K1/z and Bessel's equation Z1'' = (1 + 1/z^2) Z1 - Z1'/z."""
    z, z0 = k * r, k * ref
    if kind == "I":
        factor = np.exp(k.real * (r - ref)) / special.ive(1, z0)
        v0, v1 = special.ive(0, z) * factor, special.ive(1, z) * factor
        d1 = v0 - v1 / z
    else:
        factor = np.exp(-k * (r - ref)) / special.kve(1, z0)
        v0, v1 = special.kve(0, z) * factor, special.kve(1, z) * factor
        d1 = -v0 - v1 / z
    d2 = (1.0 + 1.0 / z**2) * v1 - d1 / z
    return v1, k * d1, k * k * d2


def impedance(a: float, b: float, nu: float, rho: float, s: complex) -> complex:
    """Laplace-domain force per unit velocity on the inner cylinder, concentric: F(s) = Z(s) U(s).

    The oscillating-cylinder solution above with i w -> s (k^2 = s/nu, Re k >= 0), written with
    exponentially scaled Bessel functions so that it holds for every s of an inversion contour."""
    mu = rho * nu
    k = np.sqrt(complex(s) / nu)

    def basis(r):
        i1 = _scaled_bessel(k, r, "I", b)
        k1 = _scaled_bessel(k, r, "K", a)
        f = np.array([r, 1.0 / r, -i1[0] / k**2, -k1[0] / k**2])
        df = np.array([1.0, -1.0 / r**2, -i1[1] / k**2, -k1[1] / k**2])
        d2f = np.array([0.0, 2.0 / r**3, -i1[2] / k**2, -k1[2] / k**2])
        dw = np.array([0.0, 0.0, i1[1], k1[1]])
        return f, df, d2f, dw

    fa, dfa, d2fa, dwa = basis(a)
    fb, dfb, _, _ = basis(b)
    coef = np.linalg.solve(np.array([fa, dfa, fb, dfb], dtype=complex), np.array([a, 1.0, 0.0, 0.0], dtype=complex))
    f_a, df_a, d2f_a, dw_a = fa @ coef, dfa @ coef, d2fa @ coef, dwa @ coef
    p = -a * (rho * s * df_a + mu * dw_a)
    return math.pi * a * (-p + 2.0 * mu * (df_a / a - f_a / a**2) + mu * (d2f_a - df_a / a + f_a / a**2))


def talbot(transform, t: float, m: int = 32) -> float:
    """Inverse Laplace transform of a real function at t > 0 by the fixed Talbot contour.

    f(t) = (r/M) [exp(r t) F(r)/2 + sum_{k=1}^{M-1} Re(exp(t s_k) F(s_k) (1 + i sigma_k))],
    s_k = r th (cot th + i), sigma_k = th + (th cot th - 1) cot th, th = k pi/M, r = 2M/(5t)
    (Abate and Valko, Int. J. Numer. Meth. Eng. 60, 2004). The terms reach exp(2M/5) ~ 4e5 at
    M = 32, so about 1e-10 of f is left to rounding in double precision.
    """
    r = 2.0 * m / (5.0 * t)
    total = 0.5 * math.exp(r * t) * transform(complex(r)).real
    for k in range(1, m):
        th = k * math.pi / m
        cot = math.cos(th) / math.sin(th)
        s = r * th * complex(cot, 1.0)
        sigma = th + (th * cot - 1.0) * cot
        total += (np.exp(t * s) * transform(s) * complex(1.0, sigma)).real
    return r / m * total


def free_cylinder_velocity(a: float, b: float, nu: float, rho: float, m_a: float, v0: float, t):
    r"""Velocity of a free inner cylinder set moving at v0 in a fluid at rest, concentric, outer wall held.

    Per unit length, small amplitude (linear: the geometry frozen at the concentric position,
    no convection), no other force. At t = 0 the body moves at v0 and the fluid rests (the state
    just after an impulse m_a v0 on the body that the fluid has not yet felt). Newton's law
    m_a U' = F with F(s) = Z(s) U(s) (:func:`impedance`) gives, Laplace-transformed,

        m_a (s U - v0) = Z(s) U,       U(s) = m_a v0 / (m_a s - Z(s)).

    Limits (checked in the tests): as s -> infinity, Z(s) -> -m_added s, the inviscid added mass
    m_added = rho pi a^2 (b^2 + a^2)/(b^2 - a^2) (:func:`inviscid_added_mass`), so
    U(0+) = v0 m_a/(m_a + m_added): the pressure impulse that sets the fluid moving takes that
    share of the body's momentum at once. As s -> 0, Z(0) = -R, the steady drag
    (:func:`steady_drag`), so the body comes to rest after the displacement
    X(infinity) = lim s X(s) = U(0) = m_a v0 / R.
    """
    def transform(s):
        return m_a * v0 / (m_a * s - impedance(a, b, nu, rho, s))

    return np.array([talbot(transform, float(ti)) for ti in np.atleast_1d(t)])


def free_cylinder_displacement(a: float, b: float, nu: float, rho: float, m_a: float, v0: float, t):
    """Displacement X(t) of :func:`free_cylinder_velocity`: the transform U(s)/s."""
    def transform(s):
        return m_a * v0 / ((m_a * s - impedance(a, b, nu, rho, s)) * s)

    return np.array([talbot(transform, float(ti)) for ti in np.atleast_1d(t)])
