r"""Steady rolling in contact (5.6)-(5.12), the onset of sliding (6.4) and the speed law (6.1).

Setting phi' = Omega_a' = Omega_b' = 0 in contact: (2.11d) gives
kappa* sin(phi) = -s (5.6), with cos(phi) = -sqrt(1 - s^2/kappa*^2) < 0 for
contact, so phi = pi + arcsin(s/kappa*); (2.11b) gives

    Omega_a + Omega_b = s (2 + kappa*^2) zeta* / kappa*^2       (5.7)

and (5.2) gives T = C_x (5.9), that is D/(6 zeta*) - s/2 = C_x. Locked
(D = 0): C_x = -s/2 (equal to (5.4) at (5.6)), so locking needs
s < 2 sqrt(1 - s^2/kappa*^2) tan(psi) (the text below (5.9) prints tan(phi),
erratum 7), and Omega_a = Omega_b = s (2 + kappa*^2) zeta* / (2 kappa*^2)
(5.10). Sliding: C_x = sigma tan(psi) cos(phi) with sigma = sgn(s), so
D = 3 zeta* (s + 2 sigma cos(phi) tan(psi)) and

    Omega_a = s zeta*^3/kappa*^2 - 3 sigma zeta* cos(phi) tan(psi),
    Omega_b = s (2 + kappa*^2) zeta*/kappa*^2 - Omega_a,

(5.11) without the factor 1/2 the text prints in both first terms (erratum 6;
the printed form is not a fixed point). For zeta* -> 0 both branches become
the compact (5.12), with relative errors O(zeta*^2).
"""

from __future__ import annotations

import math
from typing import NamedTuple

from dynamics.contact.reduced import LOCKED, SLIDING
from lubrication.geometry import check_range

__all__ = ["ContactSteadyState", "compact_steady_rates", "onset_of_sliding", "steady_locked", "steady_sliding",
           "steady_speed", "steady_state"]


class ContactSteadyState(NamedTuple):
    """A steadily rolling state in contact: kappa = kappa*, phi' = Omega_a' = Omega_b' = 0."""

    phase: str
    phi: float
    omega_a: float
    omega_b: float
    c_eps: float
    c_chi: float


class _Steady(NamedTuple):
    """What both branches share: phi of (5.6), its cosine, zeta*, and Omega_a + Omega_b of (5.7)."""

    phi: float
    cos: float
    zeta: float
    total: float


def _steady_common(s: float, kappa_star: float) -> _Steady:
    """kappa* sin(phi) = -s (5.6) on the pushing side cos(phi) < 0, and (5.7)."""
    q = s / kappa_star
    zeta = math.sqrt((1.0 - kappa_star) * (1.0 + kappa_star))
    return _Steady(phi=math.pi + math.asin(q), cos=-math.sqrt((1.0 - q) * (1.0 + q)), zeta=zeta,
                   total=s * (2.0 + kappa_star**2) * zeta / kappa_star**2)


def _check_steady(s: float, kappa_star: float) -> tuple[float, float]:
    kappa_star = check_range("kappa_star", kappa_star, 0.0, 1.0, low_open=True)
    return check_range("s", s, -kappa_star, kappa_star, low_open=True), kappa_star


def steady_locked(s: float, kappa_star: float) -> ContactSteadyState:
    """The locked fixed point (5.6), (5.10): Omega_a = Omega_b = s (2 + kappa*^2) zeta* / (2 kappa*^2).

    Parameters
    ----------
    s : float
        Slope group, |s| < kappa* (beyond, no contact fixed point: the pushed
        pendulum winds).
    kappa_star : float
        In (0, 1).

    Returns
    -------
    ContactSteadyState
        phi = pi + arcsin(s/kappa*); the friction C_x = -s/2 ((5.4) at (5.6))
        that holds it, whether or not (5.5) allows it.
    """
    s, kappa_star = _check_steady(s, kappa_star)
    common = _steady_common(s, kappa_star)
    return ContactSteadyState(LOCKED, common.phi, 0.5 * common.total, 0.5 * common.total, -common.cos, -0.5 * s)


def steady_sliding(s: float, kappa_star: float, psi: float) -> ContactSteadyState:
    """The sliding fixed point (5.6), (5.7), (5.9): (5.11) as corrected (erratum 6).

    Omega_a = s zeta*^3/kappa*^2 - 3 sigma zeta* cos(phi) tan(psi),
    Omega_b = s (2 + kappa*^2) zeta*/kappa*^2 - Omega_a, sigma = sgn(s),
    with cos(phi) = -sqrt(1 - s^2/kappa*^2). Meaningful when (5.5) fails.
    """
    s, kappa_star = _check_steady(s, kappa_star)
    tan_psi = math.tan(check_range("psi", psi, 0.0, 0.5 * math.pi, unit="rad"))
    common = _steady_common(s, kappa_star)
    sigma = math.copysign(1.0, s) if s != 0.0 else 0.0
    c_x = sigma * tan_psi * common.cos
    omega_a = s * common.zeta**3 / kappa_star**2 - 3.0 * common.zeta * c_x
    return ContactSteadyState(SLIDING, common.phi, omega_a, common.total - omega_a, -common.cos, c_x)


def steady_state(s: float, kappa_star: float, psi: float) -> ContactSteadyState:
    """The steady rolling state: locked if |s| < 2 sqrt(1 - s^2/kappa*^2) tan(psi) (erratum 7), else sliding."""
    locked = steady_locked(s, kappa_star)
    tan_psi = math.tan(check_range("psi", psi, 0.0, 0.5 * math.pi, unit="rad"))
    return locked if abs(locked.c_chi) < locked.c_eps * tan_psi else steady_sliding(s, kappa_star, psi)


def onset_of_sliding(s: float, kappa_star: float = 1.0) -> float:
    """Friction angle psi_c below which the steady state slides: (6.4) tan(psi_c) = s / (2 sqrt(1 - s^2)).

    With ``kappa_star`` < 1 the exact threshold of the locking test,
    tan(psi_c) = s / (2 sqrt(1 - s^2/kappa*^2)); the default kappa* = 1 is
    its zeta* -> 0 limit, (6.4). 0 <= s < kappa*.
    """
    kappa_star = check_range("kappa_star", kappa_star, 0.0, 1.0, low_open=True, high_open=False)
    s = check_range("s", s, 0.0, kappa_star)
    q = s / kappa_star
    return math.atan(0.5 * s / math.sqrt((1.0 - q) * (1.0 + q)))


def compact_steady_rates(s: float, kappa_star: float, psi: float) -> tuple[float, float]:
    """(Omega_a, Omega_b) of the compact forms (5.12), leading order in zeta* << 1.

    Omega_a = 3 zeta* s Min(1/2, sqrt(1 - s^2) tan(psi)/s),
    Omega_b = 3 zeta* s Max(1/2, 1 - sqrt(1 - s^2) tan(psi)/s); 0 < s < 1.
    """
    kappa_star = check_range("kappa_star", kappa_star, 0.0, 1.0, low_open=True)
    s = check_range("s", s, 0.0, 1.0, low_open=True)
    tan_psi = math.tan(check_range("psi", psi, 0.0, 0.5 * math.pi, unit="rad"))
    ratio = math.sqrt((1.0 - s) * (1.0 + s)) * tan_psi / s
    scale = 3.0 * math.sqrt((1.0 - kappa_star) * (1.0 + kappa_star)) * s
    return scale * min(0.5, ratio), scale * max(0.5, 1.0 - ratio)


def steady_speed(v_star: float, alpha: float, s: float, kappa_star: float, psi: float, *,
                 exact: bool = False) -> float:
    """Steady rolling speed of the outer cylinder (6.1), in the units of ``v_star``.

    V = V* sin(alpha) zeta* Max(1/2, 1 - sqrt(1 - s^2) tan(psi)/s), with
    V* = b M delta g / (4 nu m''_a) (6.2) (:attr:`dynamics.apparatus.Apparatus.v_star`).
    It is b Omega_b / tau with Omega_b of (5.12): 3 s b / tau = V* sin(alpha).

    Parameters
    ----------
    v_star : float
        Speed scale V* (6.2), positive.
    alpha : float
        Slope angle (rad), in (0, pi/2).
    s : float
        Slope group of the same apparatus and alpha, in (0, 1) (in (0, kappa*)
        when ``exact``).
    kappa_star, psi : float
        Contact parameters, see :class:`ContactParams`.
    exact : bool
        Use the exact Omega_b of :func:`steady_state` instead of (5.12):
        V = V* sin(alpha) Omega_b / (3 s).
    """
    v_star = check_range("v_star", v_star, 0.0, math.inf, low_open=True)
    alpha = check_range("alpha", alpha, 0.0, 0.5 * math.pi, low_open=True, unit="rad")
    s = check_range("s", s, 0.0, 1.0, low_open=True)
    omega_b = steady_state(s, kappa_star, psi).omega_b if exact else compact_steady_rates(s, kappa_star, psi)[1]
    return v_star * math.sin(alpha) * omega_b / (3.0 * s)
