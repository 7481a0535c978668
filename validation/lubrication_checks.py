r"""The Reynolds solver against the closed forms (2.5)-(2.7), and its convergence.

Three statements are checked.

1. With the thin-gap profile (B1) the numerical solver reproduces all five
   resistance coefficients of (2.5)-(2.7). On the Sommerfeld grid every
   integrand is a trigonometric polynomial in psi, so the error is rounding
   only: N m = 64 terms of relative error of a few eps each, below 1e-13.
   The tolerance is 1e-13 times the coefficient's condition number, 1 except
   for two: the torque from the outer rotation is an O(zeta) difference of
   O(1/zeta) Couette and Poiseuille parts, (2 + kappa^2)/(1 - kappa^2); and
   f_chi depends only on the gap's variation kappa cos(theta), which a float
   gap of order delta carries to an absolute eps, 1/kappa for kappa < 1/2.
2. On the uniform theta grid the integrands are analytic with poles of order
   up to 3 at Im(theta) = +-acosh(1/kappa); the composite rule's error then
   decays as N^p exp(-N acosh(1/kappa)). The rate fitted with p free must
   match within 10%.
3. Nodal pressures carry the cell quadrature error, O(dpsi^(2 m)): the fitted
   order against Sommerfeld's closed-form pressure must be 2 m within 0.2.
"""

from __future__ import annotations

import math

import numpy as np

from lubrication import Annulus, Fluid, Motion, resistance, reynolds_pressure
from lubrication.geometry import Resistance

from .checks import Check, absolute, relative

__all__ = ["CONVERGENCE_KAPPAS", "KAPPAS", "checks_of", "convergence_errors", "sommerfeld_pressure", "uniform_grid_rate",
           "pressure_order"]

A, B, LENGTH = 0.008, 0.01125, 0.1035  # the paper's apparatus (Table 2), m
FLUID = Fluid(nu=2.0e-4, rho=960.0)  # 200 cSt silicone oil
KAPPAS = (0.0, 1e-8, 0.1, 0.5, 0.9, 0.99, 0.999999)
ROUNDING_TOLERANCE = 1e-13


def condition(name: str, kappa: float) -> float:
    """How much rounding in the gap and the quadrature sums is amplified in a coefficient."""
    if name == "t_a_per_w_b":
        return (2.0 + kappa**2) / ((1.0 - kappa) * (1.0 + kappa))
    if name.startswith("f_chi") and kappa < 0.5:
        return 1.0 / kappa
    return 1.0


def reynolds_against_closed_forms(kappas=KAPPAS, n: int = 32) -> list[Check]:
    checks = []
    for kappa in kappas:
        annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
        exact = resistance(annulus, FLUID, "closed-form")
        numeric = resistance(annulus, FLUID, "reynolds", n=n, grid="sommerfeld")
        for name, ref, got in zip(Resistance.NAMES, exact.as_tuple(), numeric.as_tuple()):
            if ref == 0.0:  # f_chi vanishes at kappa = 0 by symmetry
                scale = abs(exact.t_a_per_w_a) / A  # a force scale of the same row
                checks.append(absolute(f"reynolds {name} at kappa={kappa:g} (zero by symmetry)",
                                       got, 0.0, ROUNDING_TOLERANCE * scale, "scale: T_a per W_a / a"))
                continue
            checks.append(relative(f"reynolds {name} vs (2.5)-(2.7) at kappa={kappa:g}", got, ref,
                                   ROUNDING_TOLERANCE * condition(name, kappa),
                                   f"n={n}, Sommerfeld grid, 2 points per cell"))
    return checks


def _max_error(kappa: float, n: int, grid: str, points_per_cell: int) -> float:
    annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
    exact = resistance(annulus, FLUID, "closed-form")
    numeric = resistance(annulus, FLUID, "reynolds", n=n, grid=grid, points_per_cell=points_per_cell)
    # the well-conditioned coefficients; the W_b torque is checked on its own above
    pairs = list(zip(exact.as_tuple(), numeric.as_tuple()))[:4]
    return max(abs(got / ref - 1.0) for ref, got in pairs if ref != 0.0)


def uniform_grid_rate(kappa: float, ns=None) -> tuple[float, np.ndarray, np.ndarray]:
    """Rate ``r`` of the fit error = C N^p exp(-r N), one point per cell, and the data."""
    rate = math.acosh(1.0 / kappa)
    if ns is None:
        # from an error of ~1e-2 down to ~1e-11, above the rounding floor
        ns = np.unique(np.geomspace(max(8, 4.0 / rate), 25.0 / rate, 8).astype(int))
    errors = np.array([_max_error(kappa, int(n), "uniform", 1) for n in ns])
    design = np.column_stack([np.ones(len(ns)), np.log(ns), ns])
    coeffs = np.linalg.lstsq(design, np.log(errors), rcond=None)[0]
    return -coeffs[2], ns, errors


def sommerfeld_pressure(theta: np.ndarray, annulus: Annulus, motion: Motion, fluid: Fluid) -> np.ndarray:
    """Closed-form thin-gap pressure, zero mean over theta (Sommerfeld 1904; Appendix B).

    Rotation: p = -6 mu a U kappa sin(theta) (2 - kappa cos theta) / (delta^2 (2 + kappa^2) H^2),
    U = a (W_a + W_b); squeeze: p = 6 mu a^2 eps' (H^-2 - zeta^-3) / (kappa delta^3),
    H = 1 - kappa cos(theta). Both have zero mean: oint H^-2 = 2 pi zeta^-3 (B8), and the
    rotation part is odd in theta.
    """
    kappa, delta, a, mu = annulus.kappa, annulus.delta, annulus.a, fluid.mu
    big_h = annulus.one_minus_kappa + kappa * (1.0 - np.cos(theta))
    zeta = math.sqrt(annulus.one_minus_kappa * (1.0 + kappa))
    u = a * (motion.w_a + motion.w_b)
    p = -6.0 * mu * a * u * kappa * np.sin(theta) * (2.0 - kappa * np.cos(theta)) / (
        delta**2 * (2.0 + kappa**2) * big_h**2)
    if motion.eps_dot != 0.0:
        p += 6.0 * mu * a * a * motion.eps_dot * (big_h**-2 - zeta**-3) / (kappa * delta**3)
    return p


def pressure_order(kappa: float, points_per_cell: int, ns=(32, 64, 128, 256)) -> tuple[float, np.ndarray]:
    """Fitted order of the nodal pressure error (max norm, relative to max |p|) on the Sommerfeld grid."""
    annulus = Annulus.from_kappa(A, B, kappa, LENGTH)
    motion = Motion(eps_dot=2e-4, omega_a=1.0, omega_b=0.5)
    errors = []
    for n in ns:
        sol = reynolds_pressure(annulus, motion, FLUID, n=n, points_per_cell=points_per_cell)
        exact = sommerfeld_pressure(sol.theta, annulus, motion, FLUID)
        errors.append(np.max(np.abs(sol.p - exact)) / np.max(np.abs(exact)))
    errors = np.array(errors)
    order = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    return order, errors


#: kappa of the convergence figure.
CONVERGENCE_KAPPAS = (0.5, 0.9, 0.99, 0.9999)


def convergence_errors() -> dict:
    """Largest relative error of the resistance coefficients against N on both grids, one Gauss point per
    cell, for each of :data:`CONVERGENCE_KAPPAS`: ``{"ns": ns, "errors": {(kappa, grid): errors}}``
    (errors floored at 1e-17 for a log scale)."""
    ns = np.unique(np.geomspace(8, 4096, 14).astype(int))
    errors = {(kappa, grid): [max(_max_error(kappa, int(n), grid, 1), 1e-17) for n in ns]
              for kappa in CONVERGENCE_KAPPAS for grid in ("sommerfeld", "uniform")}
    return {"ns": ns, "errors": errors}


def checks_of() -> list[Check]:
    """The closed forms, the uniform grid's exponential rate and the nodal pressure's order."""
    checks = reynolds_against_closed_forms()
    for kappa in (0.5, 0.9):
        rate, _, _ = uniform_grid_rate(kappa)
        checks.append(relative(f"uniform-grid error decay rate at kappa={kappa:g}", rate,
                               math.acosh(1.0 / kappa), 0.1, "error ~ exp(-rate N); theory acosh(1/kappa)"))
    for m in (1, 2):
        order, _ = pressure_order(0.9, m)
        checks.append(absolute(f"nodal pressure convergence order, {m} Gauss point(s) per cell",
                               order, 2.0 * m, 0.2, "against Sommerfeld's pressure, kappa=0.9"))
    return checks
