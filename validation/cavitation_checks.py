r"""Cavitation models against classical long-bearing results, mass conservation and convergence.

References, for the thin gap h = delta (1 - kappa cos theta) in pure rotation
(U = a (W_a + W_b)), with the pressure p_cav at the widest gap (p_ref = p_cav):

* Half-Sommerfeld: the full-film pressure p - p_cav = -K sin(theta) (2 - kappa cos theta)
  / (1 - kappa cos theta)^2, K = 6 mu a U kappa / (delta^2 (2 + kappa^2)), is kept on
  -pi < theta < 0. With x = cos(theta) and y = 1 - kappa x the half-period integrals
  are elementary, int_{-1}^{1} x (2 - kappa x)/(1 - kappa x)^2 dx = 2 kappa/(1 - kappa^2),
  and the sin^2 one is half of its period (B8)-(B9), so per length L
      f_eps = -12 mu a^2 U kappa^2 L / (delta^2 (2 + kappa^2) (1 - kappa^2)),
      f_chi =   6 pi mu a^2 U kappa L / (delta^2 (2 + kappa^2) sqrt(1 - kappa^2)),
  the classical half-Sommerfeld long-bearing load components (Hamrock,
  *Fundamentals of Fluid Film Lubrication*, 1994, ch. 10: W_r and W_t with the
  journal speed U): the radial one pulls the inner cylinder back to the centre.
* Swift-Stieber: p' = 12 mu a (U/2) delta^-2 (H^-2 - H_r H^-3) on (-pi, theta_r), H = h/delta,
  with p' = 0 at the rupture angle theta_r fixed by int_{-pi}^{theta_r} p' = 0. It is
  solved here independently of the solver: brentq on theta_r with scipy quad, and
  by parts f_eps = a L int p' sin, f_chi = -a L int p' cos.

Measured (and checked): half-Sommerfeld is exact when the truncation points
theta = 0, pi are nodes (even N) up to the half-period Gauss rule, O(dpsi^(2 m)),
and second order when theta = 0 is inside a cell (odd N). The Swift-Stieber
rupture is a node, within one cell of the true angle (first order, erratic as
the angle moves through the cells), and the force error is C offset^2 with C
nearly constant (0.7 at kappa = 0.6): an O(dpsi^2) envelope. JFO equals Swift-Stieber bit for bit at a
steady rupture fed at p_cav and conserves liquid through rupture and reformation
to rounding.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
from scipy import integrate, optimize

from lubrication import Annulus, Fluid, Motion, reynolds_forces
from lubrication.cavitation import cavitating_forces, cavitating_pressure

from .checks import Check, absolute, at_most, relative

__all__ = ["checks_of", "half_sommerfeld_errors", "half_sommerfeld_forces", "observed_order", "solve_times",
           "swift_stieber_errors", "swift_stieber_reference"]

A, B, LENGTH = 0.008, 0.01125, 0.1035  # the paper's apparatus (Table 2), m
FLUID = Fluid(nu=2.0e-4, rho=960.0)  # 200 cSt silicone oil
ROTATION = Motion(omega_a=1.0)


def half_sommerfeld_forces(annulus: Annulus, motion: Motion, fluid: Fluid) -> tuple[float, float]:
    """Classical long-bearing half-Sommerfeld (f_eps, f_chi) for pure rotation, p_ref = p_cav."""
    kappa, delta, a, mu = annulus.kappa, annulus.delta, annulus.a, fluid.mu
    u = a * (motion.w_a + motion.w_b)
    zeta2 = annulus.one_minus_kappa * (1.0 + kappa)
    f_eps = -12.0 * mu * a * a * u * kappa**2 * annulus.length / (delta**2 * (2.0 + kappa**2) * zeta2)
    f_chi = 6.0 * math.pi * mu * a * a * u * kappa * annulus.length / (
        delta**2 * (2.0 + kappa**2) * math.sqrt(zeta2))
    return f_eps, f_chi


def swift_stieber_reference(annulus: Annulus, motion: Motion, fluid: Fluid) -> tuple[float, float, float]:
    """Rupture angle and (f_eps, f_chi) of the long bearing under Reynolds conditions, by shooting."""
    kappa = annulus.kappa

    def big_h(t):
        return 1.0 - kappa * np.cos(t)

    def quad(f, upper):
        with warnings.catch_warnings():  # quad warns when it reaches rounding before 1e-12
            warnings.simplefilter("ignore", integrate.IntegrationWarning)
            return integrate.quad(f, -math.pi, upper, epsabs=0.0, epsrel=1e-12, limit=400)[0]

    def net_rise(theta_r):
        return quad(lambda t: big_h(t) ** -2 - big_h(theta_r) * big_h(t) ** -3, theta_r)

    # net_rise > 0 at theta_r = 0 (H >= H_r) and < 0 at pi (H <= H_r): one root between
    theta_r = optimize.brentq(net_rise, 0.0, math.pi, xtol=1e-14, rtol=1e-14)
    h_r = big_h(theta_r)
    i_sin = quad(lambda t: (big_h(t) ** -2 - h_r * big_h(t) ** -3) * np.sin(t), theta_r)
    i_cos = quad(lambda t: (big_h(t) ** -2 - h_r * big_h(t) ** -3) * np.cos(t), theta_r)
    u = annulus.a * (motion.w_a + motion.w_b)
    scale = 6.0 * fluid.mu * annulus.a**2 * u * annulus.length / annulus.delta**2
    return theta_r, scale * i_sin, -scale * i_cos


def observed_order(ns, errors) -> float:
    """Slope of log(error) against log(1/N)."""
    return -float(np.polyfit(np.log(ns), np.log(errors), 1)[0])


def _relative_force_error(f, f_eps, f_chi) -> float:
    return max(abs(f.f_eps - f_eps), abs(f.f_chi - f_chi)) / math.hypot(f_eps, f_chi)


def half_sommerfeld_errors(kappa: float, ns, points_per_cell: int = 2) -> np.ndarray:
    annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
    ref = half_sommerfeld_forces(annulus, ROTATION, FLUID)
    return np.array([_relative_force_error(
        cavitating_forces(annulus, ROTATION, FLUID, "half-sommerfeld", p_cav=0.0, p_ref=0.0, n=int(n),
                          points_per_cell=points_per_cell), *ref) for n in ns])


def swift_stieber_errors(kappa: float, ns) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Relative force errors, rupture-node offsets (rad) from the shooting reference, and the cell widths there."""
    annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
    theta_r, f_eps, f_chi = swift_stieber_reference(annulus, ROTATION, FLUID)
    forces, offsets, widths = [], [], []
    for n in ns:
        sol = cavitating_pressure(annulus, ROTATION, FLUID, "swift-stieber", p_cav=0.0, p_ref=0.0, n=int(n))
        forces.append(_relative_force_error(sol.forces, f_eps, f_chi))
        first = np.nonzero((sol.film_fraction == 0.0) & (sol.theta > 0.0))[0][0]
        offsets.append(sol.theta[first] - theta_r)
        widths.append(sol.theta[first] - sol.theta[first - 1])
    return np.array(forces), np.array(offsets), np.array(widths)


def solve_times(ns=(64, 256, 1024), kappa: float = 0.9, repeats: int = 20) -> dict:
    """Microseconds per solve, squeeze plus rotation with a cavity, after a warm-up call."""
    annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
    motion = Motion(eps_dot=-2e-5, omega_a=1.0, omega_b=0.3)
    table = {}
    for model in ("full film", "half-sommerfeld", "swift-stieber", "jfo"):
        for n in ns:
            if model == "full film":
                def call(n=n):
                    return reynolds_forces(annulus, motion, FLUID, n=n, points_per_cell=2)
            else:
                def call(n=n, model=model):
                    return cavitating_forces(annulus, motion, FLUID, model, p_cav=0.0, p_ref=2.0, n=n)
            call()
            start = time.perf_counter()
            for _ in range(repeats):
                call()
            table[(model, n)] = 1e6 * (time.perf_counter() - start) / repeats
    return table


def checks_of(quick: bool = False) -> list[Check]:
    """The cavitation checks; the quick form leaves out the order of the rupture node's offset."""
    checks: list[Check] = []
    for kappa in (0.3, 0.9):
        annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
        f_eps, f_chi = half_sommerfeld_forces(annulus, ROTATION, FLUID)
        f = cavitating_forces(annulus, ROTATION, FLUID, "half-sommerfeld", p_cav=0.0, p_ref=0.0, n=256)
        checks.append(relative(f"half-Sommerfeld f_eps vs long-bearing formula, kappa={kappa:g}", f.f_eps, f_eps,
                               1e-9, "n=256: truncation points on nodes; half-period Gauss error O(dpsi^4)"))
        checks.append(relative(f"half-Sommerfeld f_chi vs long-bearing formula, kappa={kappa:g}", f.f_chi, f_chi,
                               1e-12, "half of (2.6): exact by symmetry"))
    ns = np.array([33, 65, 129, 257])
    order = observed_order(ns, half_sommerfeld_errors(0.6, ns))
    checks.append(absolute("half-Sommerfeld order, truncation inside a cell (odd N)", order, 2.0, 0.1,
                           "kappa=0.6; linear interpolation of the crossing"))
    for kappa in (0.5, 0.9, 0.99):
        annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
        _, f_eps, f_chi = swift_stieber_reference(annulus, ROTATION, FLUID)
        ss = cavitating_forces(annulus, ROTATION, FLUID, "swift-stieber", p_cav=0.0, p_ref=0.0, n=512)
        err = _relative_force_error(ss, f_eps, f_chi)
        checks.append(at_most(f"Swift-Stieber force error vs shooting reference, kappa={kappa:g}", err,
                              0.1 * (2 * math.pi / 512) ** 2, "n=512; envelope 0.1 dpsi^2"))
        jfo = cavitating_forces(annulus, ROTATION, FLUID, "jfo", p_cav=0.0, p_ref=0.0, n=512)
        checks.append(absolute(f"JFO - Swift-Stieber at steady rupture, kappa={kappa:g}",
                               _relative_force_error(jfo, ss.f_eps, ss.f_chi), 0.0, 1e-14, "n=512, same nodes"))
    annulus = Annulus.from_kappa(A, B, 0.6, LENGTH)
    sol = cavitating_pressure(annulus, ROTATION, FLUID, "jfo", p_cav=0.0, p_ref=3.0, n=512)
    flux = 0.5 * annulus.a * ROTATION.w_a * annulus.delta
    checks.append(at_most("JFO mass residual through rupture and reformation (relative to U delta/2)",
                          float(np.max(np.abs(sol.mass_residual))) / flux, 1e-12,
                          "kappa=0.6, p_ref - p_cav = 3 Pa, every node including the feed"))
    checks.append(at_most("JFO smallest film fraction (a cavity forms and reforms)", float(np.min(sol.film_fraction)),
                          0.9, "below 1 inside the cavity"))
    if not quick:
        # N not nested, so that the rupture falls anywhere in its cell
        ns = np.array([41, 67, 109, 177, 287, 465, 753])
        errors, offsets, widths = swift_stieber_errors(0.6, ns)
        checks.append(absolute("Swift-Stieber force error order in the rupture-node offset", observed_order(
            1.0 / np.abs(offsets), errors), 2.0, 0.2, "kappa=0.6; error ~ C offset^2"))
        checks.append(at_most("Swift-Stieber rupture-node offset over the cell width", float(np.max(
            np.abs(offsets) / widths)), 1.0, "kappa=0.6; the boundary is resolved to a cell: first order"))
    return checks
