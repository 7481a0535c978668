"""What a trajectory shows when measured: its energy, its envelope, its mean rolling, the mass its rows imply.

Functions of a run's columns (:class:`dynamics.trajectory.Trajectory`) that the checks and the studies
use to read a trajectory against the physics: each states the balance or the quantity it measures.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["centripetal_mass", "mechanical_energy", "rocking_envelope", "rolling_statistics"]


def mechanical_energy(apparatus, columns: dict) -> np.ndarray:
    """Kinetic plus potential energy of the full model (J) along a trajectory's columns.

    KE = (1/2)(M + m_b) b^2 Omega_b^2 + m'_a b Omega_b x' + (1/2) m_eff |r'|^2 + (1/4) m_a a^2 Omega_a^2
    and PE = m'_a g eps cos(phi) - M g sin(alpha) X_b, r = (x, z) = eps (sin chi, cos chi): the
    energy whose rate of change (2.1)-(2.4) equate to the power of the fluid forces. r' is
    differentiated along the integrator's steps (hundreds per turn), whose second-order error
    is far below the energy lost in the film.
    """
    ap = apparatus
    t, eps, chi = columns["t"], columns["eps"], columns["chi"]
    x_dot = np.gradient(eps * np.sin(chi), t, edge_order=2)
    z_dot = np.gradient(eps * np.cos(chi), t, edge_order=2)
    omega_a, omega_b = columns["omega_a"], columns["omega_b"]
    kinetic = (0.5 * (ap.M + ap.m_b) * ap.b**2 * omega_b**2 + ap.m_a_reduced * ap.b * omega_b * x_dot
               + 0.5 * ap.m_eff * (x_dot**2 + z_dot**2) + 0.25 * ap.m_a * ap.a**2 * omega_a**2)
    potential = ap.m_a_reduced * ap.g * eps * np.cos(columns["phi"]) - ap.M * ap.g * math.sin(ap.alpha) * columns["x_b"]
    return kinetic + potential


def centripetal_mass(apparatus, columns: dict, t1: float, t2: float) -> float:
    """The mass m on the centripetal term of (2.2) that a run's rows imply over [t1, t2].

    Along e_eps, (2.2) with the squeeze force (2.5) of the closed forms reads

        m_eff eps'' - m eps chi'^2 = -(12 nu a m''_a / delta^2) q' - m'_a g cos(phi) - m'_a b Omega_b' sin(chi),

    q = kappa / zeta. Integrated over the window with the trajectory's own rows
    (trapezoids; the rolling term as a Stieltjes sum over Omega_b) it gives m:
    m_eff for (2.1)-(2.2) as printed, m'_a with ``frame_terms = "quasi-steady"``
    (while chi' lies between the wall rates). The rows must resolve a turn.
    """
    ap = apparatus
    keep = (columns["t"] >= t1) & (columns["t"] <= t2)
    t, kappa = columns["t"][keep], columns["kappa"][keep]
    q = kappa / np.sqrt(columns["one_minus_kappa"][keep] * (1.0 + kappa))
    eps_dot = columns["kappa_dot"][keep] * ap.delta
    squeeze = 12.0 * ap.nu * ap.a * ap.m_a_displaced / ap.delta**2 * (q[-1] - q[0])
    gravity = -ap.m_a_reduced * ap.g * np.trapezoid(np.cos(columns["phi"][keep]), t)
    chi = columns["chi"][keep]
    rolling = -ap.m_a_reduced * ap.b * np.sum(0.5 * (np.sin(chi[1:]) + np.sin(chi[:-1]))
                                              * np.diff(columns["omega_b"][keep]))
    centripetal = np.trapezoid(columns["eps"][keep] * columns["phi_dot"][keep] ** 2, t)
    return float((ap.m_eff * (eps_dot[-1] - eps_dot[0]) + squeeze - gravity - rolling) / centripetal)


def rocking_envelope(t: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Times and heights of the peaks of |x|, a parabola through each sampled maximum (uniform t)."""
    ax = np.abs(x)
    i = np.nonzero((ax[1:-1] >= ax[:-2]) & (ax[1:-1] > ax[2:]))[0] + 1
    y0, y1, y2 = ax[i - 1], ax[i], ax[i + 1]
    shift = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2)
    return t[i] + shift * (t[1] - t[0]), y1 - 0.25 * (y0 - y2) * shift


def rolling_statistics(trajectory, t_settle: float) -> tuple[float, float, float]:
    """Mean rolling rate, time standard deviation of Omega_b and switches per unit time after ``t_settle``.

    Parameters
    ----------
    trajectory : dynamics.simulation.Trajectory
        A dimensionless contact run (``simulate`` with :class:`~dynamics.equations.reduced.ReducedParams`),
        whose X_b is in b: times in tau, rates in 1/tau.
    t_settle : float
        Start of the average (tau), before the end of the run.

    Returns
    -------
    mean, fluctuation, switch_rate : float
        (X_b(t_end) - X_b(t_settle)) / (t_end - t_settle) (1/tau); the
        time-weighted (trapezoidal) standard deviation of Omega_b about it over
        the rows (1/tau); phase switches per tau.
    """
    if not trajectory.dimensionless:
        msg = ("rolling_statistics needs a dimensionless trajectory (simulate with ReducedParams), where X_b "
               "is the angle turned")
        raise ValueError(msg)
    cols = trajectory.columns
    t, omega_b, x_b = cols["t"], cols["omega_b"], cols["x_b"]
    span = t[-1] - t_settle
    if not span > 0.0:
        msg = f"t_settle must be before the end of the run, t = {t[-1]:.6g}; got {t_settle!r}"
        raise ValueError(msg)
    mean = (x_b[-1] - np.interp(t_settle, t, x_b)) / span
    late = t >= t_settle
    variance = np.trapezoid((omega_b[late] - mean) ** 2, t[late]) / span
    switches = sum(sw["t"] >= t_settle for sw in trajectory.info.get("switches", ()))
    return float(mean), math.sqrt(max(float(variance), 0.0)), switches / span
