"""Closed-form special solutions of the reduced model (section 3).

All in the reduced model's units: time in tau, rotation rates in 1/tau.
They are the checks the integrators are held to: steady rolling (3.2),
sedimentation (3.3), the pushed pendulum at contact (3.5), the slow approach to
contact (3.9)-(3.10) and the runaway (3.11).

The angle phi is measured from the upward vertical. The pushed pendulum rocks
about the rest point with sin(phi) = -s and cos(phi) = -sqrt(1 - s^2) (the
inner cylinder near the bottom, dragged up the rear side), that is
phi* = pi + arcsin(s) modulo 2 pi; the text's "phi = -sin^-1 s" names this
point by its sine only (the principal value would be the unstable top).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.special import ellipe

from dynamics.equations import full
from dynamics.equations.reduced import stretched_to_kappa
from lubrication.geometry import check_finite, check_range

__all__ = [
    "RunawayEstimates",
    "SlowApproach",
    "SteadyRolling",
    "contact_equilibrium",
    "critical_slope",
    "decay_exponent",
    "inertial_time",
    "pushed_pendulum_energy",
    "pushed_pendulum_rhs",
    "rocking_frequency",
    "runaway_estimates",
    "runaway_spin_rate",
    "sedimentation",
    "slow_approach",
    "steady_rolling",
]


class SteadyRolling(NamedTuple):
    """The steadily rolling equilibrium (3.2)."""

    kappa: float
    phi: float
    omega_a: float
    omega_b: float


def steady_rolling(s: float) -> SteadyRolling:
    """Steady rolling (3.2): kappa = s, phi = -pi/2, with the rates that balance (3.1).

    Omega_b = sqrt(1 - s^2)(1 + 2 s^2)/s and Omega_a = (1 - s^2)/(1 + 2 s^2) Omega_b.
    Linearly unstable for every s (section 3.1).

    Parameters
    ----------
    s : float
        Slope group, in (0, 1).
    """
    s = check_range("s", s, 0.0, 1.0, low_open=True)
    omega_b = math.sqrt(1.0 - s * s) * (1.0 + 2.0 * s * s) / s
    return SteadyRolling(kappa=s, phi=-0.5 * math.pi,
                         omega_a=(1.0 - s * s) / (1.0 + 2.0 * s * s) * omega_b, omega_b=omega_b)


def sedimentation(t, kappa0: float):
    """Sedimentation from rest on a level plane (3.3): s = 0, phi = pi, no rotation.

    kappa = T / sqrt(1 + T^2) with T = t + kappa0/sqrt(1 - kappa0^2); T is the
    stretched radius r of :mod:`dynamics.equations.reduced`.

    Parameters
    ----------
    t : float or array_like
        Time in units of tau, >= 0.
    kappa0 : float
        Initial eccentricity in [0, 1).

    Returns
    -------
    kappa, one_minus_kappa : float or ndarray
        1 - kappa without cancellation.
    """
    kappa0 = check_range("kappa0", kappa0, 0.0, 1.0)
    r0 = kappa0 / math.sqrt((1.0 - kappa0) * (1.0 + kappa0))  # no cancellation near 1
    return stretched_to_kappa(np.asarray(t, dtype=float) + r0)


def contact_equilibrium(s: float) -> float:
    """Stable rest point phi* = pi + arcsin(s) of the pushed pendulum (3.5), |s| < 1."""
    s = check_range("s", s, -1.0, 1.0, low_open=True)
    return math.pi + math.asin(s)


def pushed_pendulum_rhs(t: float, y, s: float, upsilon: float, mu_ratio: float) -> np.ndarray:
    """The pushed pendulum at contact (3.5), Upsilon (mu_ + 1/2) phi'' = s + sin(phi).

    Valid at contact (kappa = 1, Omega_a = Omega_b = phi'), where (2.11d) is
    all that is left. ``y`` is (phi, phi'); returns its derivative.
    """
    return np.array([y[1], (s + math.sin(y[0])) / (upsilon * (mu_ratio + 0.5))])


def pushed_pendulum_energy(phi, phi_dot, s: float, upsilon: float, mu_ratio: float):
    """First integral of (3.5): (1/2) Upsilon (mu_ + 1/2) phi'^2 + cos(phi) - s phi."""
    return 0.5 * upsilon * (mu_ratio + 0.5) * np.square(phi_dot) + np.cos(phi) - s * phi


def rocking_frequency(s: float, upsilon: float, mu_ratio: float) -> float:
    """Angular frequency omega of small rocking near contact, omega^2 of (3.10)."""
    s = check_range("s", s, -1.0, 1.0, low_open=True)
    return math.sqrt(math.sqrt(1.0 - s * s) / (upsilon * (mu_ratio + 0.5)))


def decay_exponent(mu_ratio: float) -> float:
    """Exponent q = 3 (1 + 4 mu_^2) / (2 (1 + 2 mu_)^2) of the rocking amplitude's decay (3.10).

    Its minimum is 3/4 at mu_ = 1/2; for mu_ >= 1 (every real device has
    mu_ > 1) it rises from 5/6 at mu_ = 1 towards 3/2, the range quoted in
    section 3.2.
    """
    mu_ratio = check_finite("mu_ratio", mu_ratio)
    return 3.0 * (1.0 + 4.0 * mu_ratio**2) / (2.0 * (1.0 + 2.0 * mu_ratio) ** 2)


class SlowApproach(NamedTuple):
    """The multiple-scale solution (3.9) near contact, and the distance it rolls."""

    zeta: np.ndarray
    amplitude: np.ndarray
    x_b: np.ndarray


def slow_approach(t, zeta0: float, s: float, mu_ratio: float) -> SlowApproach:
    """Slow approach to contact (3.9): the gap, the rocking envelope and the distance rolled.

    With c = sqrt(1 - s^2) and T = 1 + t zeta0 c:

    * zeta = sqrt(1 - kappa^2) = zeta0 / T (3.9);
    * the amplitude of phi - phi* decays as T^-q = (zeta/zeta0)^q, q of (3.10);
    * X_b - X_b(0) = (3 s / c) ln T, in units of b.

    The last is not the text's X_b ~ t^(1-q), which integrates the envelope of
    an oscillation of zero mean. Averaged over the rocking, phi' has zero
    mean and Omega_a' is O(zeta^2); near contact (2.11b) gives
    (Omega_a + Omega_b)/2 - phi' = -(3/2) zeta sin(phi) = (3/2) s zeta and
    (2.11c) gives Omega_b - Omega_a = -3 zeta sin(phi) = 3 s zeta, so the mean
    rolling rate is Omega_b = 3 s zeta: the sheared film keeps the outer
    cylinder turning, and X_b grows logarithmically for every mu_ (also for
    q > 1, where the text has the device stop after a finite distance).

    Parameters
    ----------
    t : float or array_like
        Time since zeta was zeta0 (units of tau).
    zeta0 : float
        sqrt(1 - kappa^2) at t = 0, small.
    s : float
        Slope group, |s| < 1.
    mu_ratio : float
        The paper's mu.
    """
    s = check_range("s", s, -1.0, 1.0, low_open=True)
    c = math.sqrt(1.0 - s * s)
    stretch = 1.0 + np.asarray(t, dtype=float) * zeta0 * c
    return SlowApproach(zeta=zeta0 / stretch, amplitude=stretch ** -decay_exponent(mu_ratio),
                        x_b=3.0 * s / c * np.log(stretch))


def runaway_spin_rate(s: float, upsilon: float, mu_ratio: float) -> float:
    """Slope of the runaway (3.11): Omega_a ~ Omega_b ~ phi' ~ s t / ((mu_ + 1/2) Upsilon)."""
    return s / ((mu_ratio + 0.5) * upsilon)


# -- the full model: a rest point at contact, the inertial time, the runaway's acceleration ----------

def critical_slope(apparatus) -> float:
    """Steepest slope (rad) with a rest point at contact: sin(alpha_c) = m'_a delta / (M b)."""
    return math.asin(apparatus.m_a_reduced * apparatus.delta / (apparatus.M * apparatus.b))


def inertial_time(apparatus) -> float:
    """t_i / tau = m_eff / (R_0 tau) = Upsilon (m_eff/m_a)(delta/a)^2, R_0 the (2.5) resistance at kappa = 0."""
    return apparatus.upsilon * (apparatus.m_eff / apparatus.m_a) * apparatus.delta_over_a**2


class RunawayEstimates(NamedTuple):
    """Mean runaway accelerations of the outer cylinder (m/s^2) and the film's share of the work."""

    paper: float  # M g sin(alpha) / (M + m_b + m_a/2), (3.11)
    rigid: float  # M g sin(alpha) b^2 / (m_a a^2/2 + (M + m_b) b^2)
    observed: float  # 2 g sin(alpha)/3, the measured X = g t^2 sin(alpha)/3 (section 4)
    lossless: float  # a_0 = M g sin(alpha) b^2 / <sqrt(I)>^2, rigid co-rotation in the model
    dissipated_fraction: float  # f, the share of the work of gravity lost in the film
    model: float  # (1 - f) a_0


def runaway_estimates(apparatus, samples: int = 4096, frame_terms: str = full.DEFAULT_FRAME_TERMS,
                      fluid_spin: str = full.DEFAULT_FLUID_SPIN) -> RunawayEstimates:
    """The mean runaway accelerations of the full model for ``apparatus`` (:class:`RunawayEstimates`).

    Derived in ``validation.dynamics_checks``'s docstring: with the fluid's dissipation as a
    perturbation of rigid co-rotation, a_0 = M g sin(alpha) b^2/<sqrt(I)>^2 over the turn of the line
    of centres, less the share f of the work of gravity lost in the film. The centrifugal load that
    closes the gap, and so f, carries the centripetal mass of ``frame_terms``: m_eff as (2.2) is
    printed ("paper"), m'_a with the quasi-steady frame terms (the fluid co-rotates, so their frame
    rate is chi'). The fluid's spin of ``fluid_spin`` adds its angular momentum in co-rotation,
    I_s Omega, to the moment of inertia about the contact: I_s = m_f (a^2 + b^2)/2 with "couette",
    and with "eccentric" J_a + J_b + K delta^2 = m_f (a^2 + b^2)/2 - (m_eff - m'_a) delta^2 at contact,
    whatever the shares the walls carry (:func:`dynamics.equations.full.spin_state`: they cancel
    when Omega_a = Omega_b = chi'). f is that of (2.4) without the spin: the spin changes it by
    the spin's share of the inertia, a relative change of a per cent that is itself small.

    ``samples`` equispaced points in chi evaluate the averages behind f, which
    are periodic and smooth, so the rule converges geometrically.
    """
    ap = apparatus
    g_sin = ap.g * math.sin(ap.alpha)
    delta, b = ap.delta, ap.b
    i_a = 0.5 * ap.m_a * ap.a**2
    spin = {"none": 0.0, "couette": 0.5 * ap.m_f * (ap.a**2 + b**2),
            "eccentric": 0.5 * ap.m_f * (ap.a**2 + b**2) - (ap.m_eff - ap.m_a_reduced) * delta**2}[fluid_spin]
    i_0 = i_a + (ap.M + ap.m_b) * b**2 + ap.m_eff * delta**2
    lever = ap.m_a_reduced * b  # m'_a b
    swing = 2.0 * lever * delta  # B
    rolling = i_0 + spin  # the moment of inertia about the contact, less B's swing
    mean_sqrt = 2.0 / math.pi * math.sqrt(rolling + swing) * ellipe(2.0 * swing / (rolling + swing))
    lossless = ap.M * g_sin * b**2 / mean_sqrt**2
    chi = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    inertia = i_0 + swing * np.cos(chi)
    carried = i_a + ap.m_eff * delta**2 + lever * delta * np.cos(chi)  # J
    shear = np.mean(np.sin(chi) ** 2 * (carried**2 + i_a**2) * inertia**-3.5)
    full.check_frame_terms(frame_terms)
    centripetal = ap.m_eff if frame_terms == "paper" else ap.m_a_reduced
    closing = np.mean(inertia**-0.5 * (1.0 - (lever * np.sin(chi)) ** 2 / (centripetal * inertia)))
    fraction = 9.0 * lever**2 / centripetal * shear / closing
    return RunawayEstimates(
        paper=ap.runaway_acceleration,
        rigid=ap.M * g_sin * b**2 / (i_a + (ap.M + ap.m_b) * b**2),
        observed=2.0 * g_sin / 3.0,
        lossless=lossless, dissipated_fraction=float(fraction), model=(1.0 - fraction) * lossless)
