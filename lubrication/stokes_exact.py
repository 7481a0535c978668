r"""The exact 2-D Stokes resistance of the eccentric annulus, in closed form.

For rigid-body motions of two circular walls the quasi-steady Stokes problem
(the one :mod:`lubrication.stokes` solves by finite elements) has an exact
solution, found by Jeffery (1922) for rotating cylinders, Wannier (1950) for the
journal bearing and Finn & Cox (2001) for a translating inner cylinder. It is
derived here in complex form, and its loads are evaluated without loss of
digits from the thin gap to contact.

Result
------
Per unit length, with b = a + delta, eps = kappa delta and the bipolar
parameter tau > 0 of the annulus,

    cosh(tau) = (a^2 + b^2 - eps^2) / (2 a b),  i.e.  2 a b (cosh(tau) - 1) = delta^2 (1 - kappa^2),

    D = tau (a^2 + b^2) - 2 a b sinh(tau),    G = tau coth(tau) - 1,

the fluid loads on the walls are

    f_eps = R_eps eps',                    R_eps   = -4 pi mu / (tau - tanh(tau)),
    f_chi = R_chi_a W_a + R_chi_b W_b,     R_chi_a =  4 pi mu eps a^2 / D,
                                           R_chi_b =  4 pi mu eps b^2 / D,
    T_a   = R_t_a W_a + R_t_b W_b,         R_t_a   = -4 pi mu a^2 (b^2 G + eps^2) / D,
                                           R_t_b   =  4 pi mu a^2 b^2 G / D,
    T_b   = R_b_a W_a + R_b_b W_b,         R_b_a   =  R_t_b,
                                           R_b_b   = -4 pi mu b^2 (a^2 G + eps^2) / D,

with T_b the torque on the outer wall about B (same sense as T_a). Hence
R_chi_b = (b/a)^2 R_chi_a, and the radial drag depends on tau alone.

Derivation
----------
Frame and variables. Complex z = x + i y with the origin at B, e_x = e_eps
(from B to A, so A is at z = eps) and e_y = e_chi; positive rotations turn e_x
towards e_y, as in :mod:`lubrication.geometry`. The velocity is U = u + i v;
in the frame of the line of centres the walls move rigidly,

    inner |z - eps| = a:  U = U_A + i W_a (z - eps),     outer |z| = b:  U = i W_b z,

with U_A = eps' for the radial motion (U_A = i V translates A along e_chi).

Goursat form. Every incompressible 2-D Stokes flow is

    U = phi(z) - z conj(phi'(z)) + conj(omega(z)),    p - i mu Omega = -4 mu phi'(z),

with phi, omega analytic in the fluid (Omega the vorticity): dU/dz = phi' -
conj(phi') has no real part (div u = 0), and mu Lap U = 4 mu d2U/dz dzbar =
-4 mu conj(phi'') = 2 dp/dzbar. (The stream-function form
psi = Im[conj(z) f + g], u = psi_y, v = -psi_x, is the same with phi = -f,
omega = g'.) The traction on a
wall with unit normal n (complex, pointing into the fluid) is
t = -p n + 2 mu conj(n) dU/dzbar; along a contour traversed with the fluid on
its right, n ds = -i dz, and the force on the wall is the change of

    F_x + i F_y = -2 i mu [phi + z conj(phi') - conj(omega)]

around it, its torque about B  M = -2 mu Re oint conj(z) d[...] = 2 mu Re oint z omega'(z) dz
(the real part of the phi terms of conj(z) d[...] is the exact differential
d Re(|z|^2 phi')). If
phi contains A log(z - p) for a point p inside the inner wall, a single-valued U
needs conj(omega) to contain the conjugate log with A, so that

    F = 8 pi mu A,      M_B = -4 pi mu Im sum Res[z omega'(z)]       (inner wall, residues inside it).

Boundary conditions as functional equations. On |z - z0| = r (z0 real),
conj(z) = S(z) = z0 + r^2/(z - z0). Conjugating U = V on the wall and
continuing analytically off it,

    omega(z) = conj(V)(z) - phibar(S(z)) + S(z) phi'(z),

where phibar has the conjugated coefficients of phi and conj(V) =
conj(U_A) - i W r^2/(z - z0). Writing this for both walls (S_a(z) = eps +
a^2/(z - eps), S_b(z) = b^2/z) and equating the two omegas gives one equation
for phi,

    phibar(S_b) - phibar(S_a) + (S_a - S_b) phi' = -conj(U_A) + i W_a a^2/(z - eps) - i W_b b^2/z.   (E)

Limit points. S_a and S_b both exchange the two real points p < q with
p q = b^2, (p - eps)(q - eps) = a^2 (the limit points of the two circles: p
inside the inner one, q outside the outer one), and
S_a - S_b = eps (z - p)(z - q) / (z (z - eps)). With
L(z) = log((z - p)/(z - q)), L(S_b(z)) = -2 beta - L(z) and
L(S_a(z)) = -2 alpha - L(z), where alpha = ln(a/(p - eps)) > beta = ln(b/p) > 0
are the bipolar coordinates of the walls, tau = alpha - beta, and
c = (q - p)/2 = a sinh(alpha) = b sinh(beta). Useful relations:
eps = a b sinh(tau)/c, p eps = b^2 - a b e^tau, eps^2 = a^2 + b^2 - 2 a b cosh(tau).

Ansatz. phi = A L(z) + a1/(z - p) + a2/(z - q) + i g z with g real (a real
multiple of z, or a constant, carries no flow). In (E) the logarithms cancel,
leaving a rational function with simple poles at p, q, 0, eps and a limit at
infinity; (E) holds if these match (pp' = a b e^-(alpha+beta), qq' = a b e^(alpha+beta)
with p' = p - eps, q' = q - eps):

    p, q:      a2 = conj(a1) e^(2 (alpha + beta)),
    0:        -2 i g b^2 + 2 c A + a1 e^(2 beta) + conj(a1) e^(2 alpha) = -i W_b b^2,
    eps:       2 i g a^2 - 2 c A - a1 e^(2 alpha) - conj(a1) e^(2 beta) =  i W_a a^2,
    infinity:  2 tau conj(A) + 2 Re(a1) eps e^(alpha + beta)/(a b) + 2 i g eps = -conj(U_A).

omega then follows from the inner wall's formula; its singularities p, eps
(inside the inner wall) and q (outside the outer one) leave it analytic in the
fluid, and (E) makes it satisfy the outer wall's condition too. Stokes flow
being unique, this is the solution. Two cases, by the mirror symmetry y -> -y:

* Radial translation (U_A = eps' real, W = 0): A and a1 real, g = 0. The
  conditions at 0 and eps coincide, a1 = -2 c A / (e^(2 alpha) + e^(2 beta)),
  and with e^(alpha+beta)/(e^(2 alpha) + e^(2 beta)) = 1/(2 cosh(tau)) and
  c eps/(a b) = sinh(tau) the condition at infinity reads
  2 A (tau - tanh(tau)) = -eps'; F = 8 pi mu A gives R_eps.
* Rotations, and translation along e_chi (U_A = i V): A = i A'', a1 = i e1 with
  A'', e1 real. At infinity -2 tau A'' + 2 g eps = V; the difference of the
  conditions at 0 and eps is 2 g (a^2 + b^2) - 4 c A'' = W_a a^2 + W_b b^2, and
  the condition at eps fixes e1 (e^(2 beta) - e^(2 alpha)) = W_a a^2 - 2 g a^2 + 2 c A''.
  With c eps = a b sinh(tau),

      A'' = [eps (a^2 W_a + b^2 W_b) - (a^2 + b^2) V] / (2 D),    F_y = 8 pi mu A'',

  which gives R_chi_a, R_chi_b and the drag along e_chi, -4 pi mu (a^2 + b^2)/D.

Torque. omega' from the inner wall's formula has poles at p and eps inside
the inner wall; integrating the parts of omega = conj(V) - phibar(S_a) + S_a phi'
separately (z d(S_a phi') by parts), the residues of z omega' there sum to

    i W_a a^2 - a^2 phi'(eps) - q A - a1 e^(2 alpha) + p conj(A) - conj(a2) e^(-2 alpha) - i g a^2,

which for the second case is i [W_a a^2 - 2 p A'' - 2 e1 e^(2 beta) - 2 g a^2], so

    M_B = -4 pi mu [W_a a^2 - 2 p A'' - 2 e1 e^(2 beta) - 2 g a^2],    T_a = M_B - eps F_y.

With p eps = b^2 - a b e^tau and 2/(e^(2 tau) - 1) = e^(-tau)/sinh(tau), for V = 0
this collapses to

    T_a = -4 pi mu a^2 [W_a coth(tau) - (a^2 W_a + b^2 W_b) G / D],

equal to the form of the result by eps^2 = a^2 + b^2 - 2 a b cosh(tau), which
writes each torque as a sum of positive terms. For V alone it gives
T_a = 4 pi mu eps a^2 V / D and M_B = -4 pi mu eps b^2 V / D. The fluid carries
no net torque, so T_b = -M_B = -(T_a + eps F_y).

Checks and identities
---------------------
* Concentric (tau = ln(b/a), tanh(tau) = (b^2 - a^2)/(b^2 + a^2)):
  R_eps = -4 pi mu / (ln(b/a) - (b^2 - a^2)/(b^2 + a^2)), R_t_a = -R_t_b =
  -4 pi mu a^2 b^2 / (b^2 - a^2) (Couette), R_chi = O(kappa).
* Reciprocity (symmetric resistance matrix of the generalised velocities
  (eps', V = eps chi', Omega_a, Omega_b), whose W_a = Omega_a - V/eps,
  W_b = Omega_b - V/eps): dT_b/dOmega_a = dT_a/dOmega_b gives R_b_a = R_t_b;
  dF_y/dOmega_a = dT_a/dV gives eps R_chi_a = -(R_t_a + R_t_b); dF_y/dOmega_b =
  dT_b/dV gives eps R_chi_b = -(R_b_a + R_b_b). All hold above.
* Torque balance on the fluid about B: T_a + T_b + eps f_chi = 0 for W_a and W_b.
* R_chi_b = (b/a)^2 R_chi_a: by reciprocity the two are the torques on A and on
  B when A translates along e_chi, which the solution gives as 4 pi mu eps a^2 V/D
  and 4 pi mu eps b^2 V/D.

Thin gap
--------
With x = cosh(tau) - 1 = delta^2 zeta^2/(2 a b) exactly (zeta^2 = 1 - kappa^2),
tau^2 = delta^2 zeta^2/(a b) (1 + O(tau^2)) and tau^2 <= (delta/a)^2 uniformly in
kappa. Expanding tau - tanh(tau) = tau^3/3 (1 + O(tau^2)), G = tau^2/3 (1 + O(tau^2))
and, with 2 a b = delta^2 zeta^2 / x,
D = tau delta^2 - 2 a b (sinh(tau) - tau) = tau delta^2 (1 - zeta^2/3)(1 + O(tau^2))
  = tau delta^2 (2 + kappa^2)/3 (1 + O(tau^2)):

    R_eps   = -12 pi mu (a b)^(3/2) / (delta^3 zeta^3)                 -> ratio to (2.5)  (b/a)^(3/2)
    R_chi_a =  12 pi mu kappa a^2 (a b)^(1/2) / (delta^2 (2+kappa^2) zeta)  -> ratio to (2.6) (b/a)^(1/2)
    R_chi_b =  (b/a)^2 R_chi_a                                         -> (b/a)^(5/2)
    R_t_b   =   4 pi mu (a b)^(3/2) zeta / (delta (2 + kappa^2))        -> ratio to (2.7) (b/a)^(3/2)
    R_t_a   =  -4 pi mu a^2 (a b)^(1/2) [(b/a) zeta^2 + 3 kappa^2] / (delta zeta (2 + kappa^2))
               -> ratio (b/a)^(1/2) [1 + 2 kappa^2 + (1 - kappa^2) delta/a] / (1 + 2 kappa^2),

each times 1 + O((delta/a)^2). With b/a = 1 + delta/a every ratio is
1 + c delta/a + O((delta/a)^2) with

    c = 3/2 (f_eps),  1/2 (f_chi per W_a),  5/2 (f_chi per W_b),
        1/2 + (1 - kappa^2)/(1 + 2 kappa^2) = (3/2)/(1 + 2 kappa^2) (T_a per W_a),  3/2 (T_a per W_b),

the values the project measured from finite-element solves. At contact
(zeta -> 0, fixed delta/a) the same expansions give the limits of the ratios:
(b/a)^(3/2), (b/a)^(1/2), (b/a)^(1/2), (b/a)^(5/2) and, for T_a per W_b, (b/a)^(3/2).

Numerics
--------
Near contact and in thin gaps tau -> 0 and tanh, coth, sinh cancel against
tau; at kappa -> 0 the bipolar parameters alpha, beta diverge, but only tau
enters. The kernel therefore works with

    x = delta^2 (1 - kappa)(1 + kappa) / (2 a b),  sinh(tau) = sqrt(x (x + 2)),
    tau = log1p(x + sinh(tau)),
    P = (tau cosh(tau) - sinh(tau)) / tau^3,   Q = (sinh(tau) - tau) / tau^3,

P and Q by their Taylor series in tau^2 (all terms positive) for tau <= 2.5
(which covers delta/a <= 10: tau <= ln(b/a)), directly beyond. Then
tau - tanh(tau) = tau^3 P/(1 + x), G = tau^3 P/sinh(tau),
D = tau delta^2 m with m = 1 - zeta^2 Q tau^2/x in [2/3, 1], and every
coefficient is a product and sum of positive terms. Measured against a
100-digit evaluation of the unsimplified formulas (alpha, beta, p, the
coefficients A'', e1, g and the residues; tests/test_stokes_exact.py), over
kappa in [0, 1 - 1e-9] and delta/a in [1e-4, 10], every coefficient keeps
its relative error below 2e-15 (about 15 significant digits, uniformly: no
loss near contact, in thin gaps or at kappa -> 0). Measured maxima over a
grid and 600 random states: 1.3e-15 for R_eps (its tau^-3 triples the
rounding of tau, itself that of the inputs), 1.0e-15 for the others; medians
1e-16 to 2e-16.

References: G. B. Jeffery, Proc. R. Soc. A 101 (1922) 169; G. H. Wannier,
Q. Appl. Math. 8 (1950) 1; M. D. Finn & S. M. Cox, J. Eng. Math. 41 (2001) 75.
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass

from numerics.jit import jit

from .geometry import Annulus, Fluid, FluidForces, Motion, Resistance
from .spec import ForceModelSpec

__all__ = ["DELTA_OVER_A_RANGE", "EXACT_NAMES", "MIN_ONE_MINUS_KAPPA_EXACT", "ExactResistance", "check_domain",
           "exact_ratios", "exact_resistance", "stokes_exact_forces", "stokes_exact_ratios", "stokes_exact_resistance"]

#: Order of the coefficients returned by :func:`stokes_exact_resistance`: the five of
#: :data:`lubrication.geometry.RESISTANCE_NAMES`, then the torque on the outer wall
#: (about B) per W_a and per W_b.
EXACT_NAMES = ("f_eps_per_eps_dot", "f_chi_per_w_a", "t_a_per_w_a", "f_chi_per_w_b", "t_a_per_w_b",
               "t_b_per_w_a", "t_b_per_w_b")

#: delta/a range over which the digits of the module docstring are measured and
#: :func:`exact_resistance` accepts an annulus.
DELTA_OVER_A_RANGE = (1e-4, 10.0)

#: Smallest 1 - kappa :func:`exact_resistance` accepts (the formulas hold closer, untested).
MIN_ONE_MINUS_KAPPA_EXACT = 1e-9

# Taylor coefficients in u = tau^2 of P = (tau cosh - sinh)/tau^3 = sum 2k u^(k-1)/(2k+1)!
# and Q = (sinh - tau)/tau^3 = sum u^(k-1)/(2k+1)!, k >= 1, highest first for Horner.
# 15 terms: the first one left out is below 1e-19 of the sum for u <= _U_SERIES.
_N_TERMS = 15
_P_COEFFS = tuple(2.0 * k / math.factorial(2 * k + 1) for k in range(_N_TERMS, 0, -1))
_Q_COEFFS = tuple(1.0 / math.factorial(2 * k + 1) for k in range(_N_TERMS, 0, -1))
#: tau^2 up to which P and Q are summed as series; beyond, tau > 2.5 and the direct
#: differences lose less than half a digit.
_U_SERIES = 6.25

_FOUR_PI = 4.0 * math.pi


@jit(inline="always")
def _bipolar(a, delta, kappa, omk):
    """tau, x = cosh(tau) - 1, sinh(tau), P, Q and m of the module docstring."""
    b = a + delta
    zeta2 = omk * (1.0 + kappa)
    x = delta * delta * zeta2 / (2.0 * a * b)
    sh = math.sqrt(x * (x + 2.0))
    tau = math.log1p(x + sh)
    u = tau * tau
    if u <= _U_SERIES:
        p = 0.0
        q = 0.0
        for c in _P_COEFFS:
            p = p * u + c
        for c in _Q_COEFFS:
            q = q * u + c
    else:
        t3 = u * tau
        p = (tau * (1.0 + x) - sh) / t3
        q = (sh - tau) / t3
    m = 1.0 - zeta2 * q * u / x
    return tau, x, sh, p, m


@jit
def stokes_exact_resistance(a, delta, mu, kappa, omk):
    """The exact Stokes resistance coefficients per unit length, :data:`EXACT_NAMES` order.

    Parameters
    ----------
    a, delta : float
        Inner radius and mean gap b - a (m), both > 0.
    mu : float
        Dynamic viscosity (Pa s).
    kappa, omk : float
        Eccentricity ratio and 1 - kappa (given apart, for precision near contact).

    Returns
    -------
    tuple of 7 floats
        R_eps (N s/m^2), R_chi_a (N s/m), R_t_a (N s), R_chi_b (N s/m), R_t_b (N s),
        then T_b per W_a and per W_b (N s): f_eps = R_eps eps', f_chi = R_chi_a W_a +
        R_chi_b W_b, T_a = R_t_a W_a + R_t_b W_b, T_b likewise, per unit length.
    """
    tau, x, sh, p, m = _bipolar(a, delta, kappa, omk)
    b = a + delta
    a2 = a * a
    b2 = b * b
    four_pi_mu = _FOUR_PI * mu
    r_eps = -four_pi_mu * (1.0 + x) / (tau * tau * tau * p)
    k = four_pi_mu / (delta * tau * m)   # 4 pi mu delta / D
    g_over_delta = tau * tau * tau * p / (sh * delta)   # (tau coth(tau) - 1) / delta
    ecc = kappa * kappa * delta   # eps^2 / delta
    r_t_b = k * a2 * b2 * g_over_delta
    return (r_eps, k * kappa * a2, -k * a2 * (b2 * g_over_delta + ecc), k * kappa * b2, r_t_b,
            r_t_b, -k * b2 * (a2 * g_over_delta + ecc))


@jit
def stokes_exact_ratios(delta_over_a, kappa, omk):
    """The five coefficients over their lubrication forms (2.5)-(2.7), RESISTANCE_NAMES order.

    The f_chi ratios are evaluated with kappa cancelled analytically, so they
    keep their finite limit at kappa = 0, where both the force and (2.6) vanish.
    """
    d = delta_over_a
    tau, x, sh, p, m = _bipolar(1.0, d, kappa, omk)
    b = 1.0 + d
    zeta = math.sqrt(omk * (1.0 + kappa))
    k2 = 2.0 + kappa * kappa
    s = d * zeta / tau   # -> sqrt(b/a) in the thin gap
    c = tau * p / sh     # (tau coth(tau) - 1) / tau^2 -> 1/3
    r_eps = (1.0 + x) * s * s * s / (3.0 * p)
    r_chi_a = k2 * s / (3.0 * m)
    r_t_a = k2 * (b * b * zeta * zeta * c / s + kappa * kappa * s) / (m * (1.0 + 2.0 * kappa * kappa))
    r_t_b = k2 * b * b * c / (s * m)
    return r_eps, r_chi_a, r_t_a, r_chi_a * b * b, r_t_b


@dataclass(frozen=True)
class ExactResistance:
    """The exact Stokes resistance of one annulus, whole length.

    Attributes
    ----------
    f_eps_per_eps_dot : float
        N s/m: f_eps per eps'.
    f_chi_per_w_a, f_chi_per_w_b : float
        N s: f_chi per rad/s of W_a, W_b.
    t_a_per_w_a, t_a_per_w_b : float
        N m s: torque on the inner cylinder about A per rad/s of W_a, W_b.
    t_b_per_w_a, t_b_per_w_b : float
        N m s: torque on the outer wall about B, same sense, per rad/s of W_a, W_b.
    """

    f_eps_per_eps_dot: float
    f_chi_per_w_a: float
    t_a_per_w_a: float
    f_chi_per_w_b: float
    t_a_per_w_b: float
    t_b_per_w_a: float
    t_b_per_w_b: float

    NAMES = EXACT_NAMES

    def as_tuple(self) -> tuple[float, ...]:
        return astuple(self)

    def resistance(self) -> Resistance:
        """The five coefficients of the inner cylinder, as every force model gives them."""
        return Resistance(*self.as_tuple()[:5])


def check_domain(annulus: Annulus) -> None:
    """Refuse an annulus outside the range where the digits of the module docstring were measured."""
    lo, hi = DELTA_OVER_A_RANGE
    d = annulus.delta_over_a
    # slack for rounding: (b - a)/a of b = 11 a may exceed 10 by an ulp, and
    # 1 - kappa of kappa = 1 - 1e-9 carries an absolute error of ~1e-16
    if not lo * (1.0 - 1e-12) <= d <= hi * (1.0 + 1e-12):
        msg = f"delta_over_a must be in [{lo:g}, {hi:g}] for the exact Stokes model, got {d!r}"
        raise ValueError(msg)
    omk = annulus.one_minus_kappa
    if not omk >= MIN_ONE_MINUS_KAPPA_EXACT * (1.0 - 1e-6):
        msg = (f"one_minus_kappa = 1 - kappa must be in [{MIN_ONE_MINUS_KAPPA_EXACT:g}, 1] for the exact Stokes "
               f"model (kappa at most 1 - {MIN_ONE_MINUS_KAPPA_EXACT:g}), got {omk:.6g}")
        raise ValueError(msg)


def exact_resistance(annulus: Annulus, fluid: Fluid) -> ExactResistance:
    """Exact Stokes resistance coefficients of ``annulus``, whole length.

    Parameters
    ----------
    annulus : Annulus
        delta/a in :data:`DELTA_OVER_A_RANGE`, 1 - kappa >= :data:`MIN_ONE_MINUS_KAPPA_EXACT`.
    fluid : Fluid

    Returns
    -------
    ExactResistance
    """
    check_domain(annulus)
    r = stokes_exact_resistance(annulus.a, annulus.delta, fluid.mu, annulus.kappa,
                                annulus.one_minus_kappa)
    return ExactResistance(*(annulus.length * c for c in r))


def stokes_exact_forces(annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
    """Exact Stokes force and torque on the inner cylinder, whole length (the Python face of the
    "stokes-exact" model; the kernel trajectories call is :func:`lubrication.registry.kernel_model`'s).

    Returns
    -------
    FluidForces
        f_eps, f_chi (N) and T_a (N m), ``model="stokes-exact"``.
    """
    r = exact_resistance(annulus, fluid)
    return FluidForces(r.f_eps_per_eps_dot * motion.eps_dot,
                       r.f_chi_per_w_a * motion.w_a + r.f_chi_per_w_b * motion.w_b,
                       r.t_a_per_w_a * motion.w_a + r.t_a_per_w_b * motion.w_b, model="stokes-exact")


def exact_ratios(annulus: Annulus) -> tuple[float, ...]:
    """The five exact coefficients over (2.5)-(2.7), RESISTANCE_NAMES order (finite at kappa = 0)."""
    check_domain(annulus)
    return stokes_exact_ratios(annulus.delta_over_a, annulus.kappa, annulus.one_minus_kappa)


#: The model as the registry knows it (:mod:`lubrication.registry`).
MODEL = ForceModelSpec(
    "stokes-exact", "the exact 2-D Stokes forces of the eccentric annulus (closed form), any delta/a in [1e-4, 10]: "
    "the default", stokes_exact_forces, resistance=stokes_exact_resistance, check=check_domain)
