r"""How wrong are the lubrication forms (2.5)-(2.7) at finite delta/a?

The closed forms are leading order in delta/a; the paper's apparatus has
delta/a = 0.325/0.8 = 0.406. For each of the five resistance coefficients
(f_eps per eps', f_chi and T_a per W_a and per W_b) this study computes the
ratio exact / lubrication against kappa,

* with the exact 2-D Stokes solution (:mod:`lubrication.stokes_exact`),
* with the Reynolds equation solved on the exact eccentric gap
  sqrt(b^2 - eps^2 sin^2 theta) - eps cos theta - a instead of (B1),

for delta/a in {0.01, 0.03, 0.1, 0.3, 0.406, 1}, and fits the leading
correction ratio = 1 + c(kappa) delta/a + O(delta/a)^2 (for the Stokes
solution from gaps of 1e-4 to 4e-4, where the fit's truncation is far below
the checked 1e-6; for the Reynolds model from the three thinnest study gaps).

Checked: the exact ratios tend to 1 as delta/a -> 0 with a log-log slope of 1;
the fitted c(kappa) against the coefficients derived analytically from the
exact solution (C_FORMS); the finite-element solver against the exact
solution where scikit-fem is installed (its own test); the Reynolds ratios tend
to 1 at least linearly. Reported: the share of the Stokes correction c that the
exact gap alone accounts for in the Reynolds equation, and the ratios at the
paper's apparatus (Table 2: a = 0.8 cm, b = 1.125 cm).

Its CSV, JSON, figure and paragraph are :mod:`validation.reports.corrections`'s, which
``snail corrections`` and ``snail validate`` run.
"""

from __future__ import annotations

import math
import time

import numpy as np

from lubrication import Annulus, Fluid, resistance
from lubrication.geometry import RESISTANCE_NAMES
from lubrication.stokes_exact import stokes_exact_ratios

from .checks import Check, Finding, absolute, at_least, at_most

__all__ = ["APPARATUS", "DELTAS", "checks_of", "study"]

RATIO_NAMES = RESISTANCE_NAMES

#: Table 2: a = 0.8 cm, b = 1.125 cm, hence delta/a = 0.325/0.8.
APPARATUS = {"a_m": 0.008, "b_m": 0.01125, "delta_over_a": 0.325 / 0.8}
DELTAS = (0.01, 0.03, 0.1, 0.3, APPARATUS["delta_over_a"], 1.0)
#: The three thinnest study gaps, for the fit of the Reynolds model's c(kappa).
THIN = DELTAS[:3]
#: Gaps for the fit of the exact solution's c(kappa): thin enough that the quadratic
#: extrapolation of (ratio - 1)/(delta/a) leaves O((delta/a)^3) ~ 1e-11, thick enough
#: that ratio - 1 ~ 1e-4 keeps twelve digits above rounding.
EXACT_THIN = (1e-4, 2e-4, 4e-4)
#: The kappa of the study: 16 Chebyshev-Lobatto points in zeta = sqrt(1 - kappa^2) up to 0.99.
KAPPAS = np.sqrt(1.0 - (math.sqrt(1.0 - 0.99**2) + 0.5 * (1.0 - math.sqrt(1.0 - 0.99**2))
                        * (1.0 - np.cos(np.pi * np.arange(16) / 15)))**2)[::-1]
#: kappa of the Reynolds model at kappa = 0, where both f_chi forms vanish.
KAPPA_AXIS = 1e-4

#: Reynolds cells on the Sommerfeld grid. The grid is matched to the thin gap,
#: not the exact one, so convergence is slower than for (B1) at kappa = 0.99:
#: 64 cells leave 3e-4, 512 cells below 1e-9 (measured for delta/a up to 1).
REYNOLDS_CELLS = 512

#: The finite-element solver against the exact solution: (delta/a, kappa) pairs, and the tolerance
#: of its default mesh (measured worst 2.5e-6 over kappa <= 0.99, delta/a = 0.01; R_t_b against
#: the larger entry of its row).
FE_CASES = ((0.01, 0.5), (APPARATUS["delta_over_a"], 0.3), (APPARATUS["delta_over_a"], 0.9), (1.0, 0.6))
QUICK_FE_CASES = ((APPARATUS["delta_over_a"], 0.9),)
FE_TOLERANCE = 5e-6

LABELS = {"f_eps_per_eps_dot": "f_eps per eps' (2.5)", "f_chi_per_w_a": "f_chi per W_a (2.6)",
          "t_a_per_w_a": "T_a per W_a (2.7)", "f_chi_per_w_b": "f_chi per W_b (2.6)",
          "t_a_per_w_b": "T_a per W_b (2.7)"}

_FLUID = Fluid(nu=1.0, rho=1.0)  # the ratios are independent of the fluid


def reynolds_ratios(delta_over_a: float, kappas) -> np.ndarray:
    """Reynolds on the exact eccentric gap / (2.5)-(2.7), shape (5, len(kappas)).

    kappa = 0 is evaluated at KAPPA_AXIS, where both f_chi forms vanish.
    """
    out = np.empty((len(RATIO_NAMES), len(kappas)))
    for i, kappa in enumerate(kappas):
        annulus = Annulus.from_kappa(1.0, 1.0 + delta_over_a, max(kappa, KAPPA_AXIS))
        exact = resistance(annulus, _FLUID, "reynolds", n=REYNOLDS_CELLS, profile="eccentric")
        lub = resistance(annulus, _FLUID, "closed-form")
        out[:, i] = np.array(exact.as_tuple()) / np.array(lub.as_tuple())
    return out


def thin_gap_coefficient(deltas, ratios) -> np.ndarray:
    """c in ratio = 1 + c delta/a + ..., from ratios of shape (len(deltas), 5, n_kappa).

    (ratio - 1)/(delta/a) is fitted by the polynomial of degree len(deltas) - 1
    through the points and evaluated at delta/a = 0.
    """
    d = np.asarray(deltas, dtype=float)
    q = (np.asarray(ratios) - 1.0) / d[:, None, None]
    flat = q.reshape(len(d), -1)
    coeffs = np.polyfit(d, flat, len(d) - 1)
    return coeffs[-1].reshape(q.shape[1:])


def log_slope(deltas, ratios) -> np.ndarray:
    """Slope of log|ratio - 1| against log(delta/a) between the two thinnest gaps."""
    r = np.abs(np.asarray(ratios)[:2] - 1.0)
    return np.log(r[1] / r[0]) / math.log(deltas[1] / deltas[0])


def exact_ratios(delta_over_a: float, kappas) -> np.ndarray:
    """Exact Stokes / (2.5)-(2.7), shape (5, len(kappas))."""
    return np.array([stokes_exact_ratios(delta_over_a, k, 1.0 - k) for k in kappas]).T


def fe_errors(cases) -> list[dict]:
    """The finite-element solver's coefficients against the exact ones (default mesh); [] without scikit-fem.

    R_t_b is judged against R_t_a, the larger entry of its row: near contact it is a small
    difference of Couette and Poiseuille torques (lubrication.stokes_exact).
    """
    import importlib.util

    if importlib.util.find_spec("skfem") is None:
        return []
    from lubrication.stokes import stokes_resistance
    from lubrication.stokes_exact import stokes_exact_resistance

    rows = []
    for d, kappa in cases:
        fe = stokes_resistance(1.0, 1.0 + d, kappa)
        exact = stokes_exact_resistance(1.0, d, 1.0, kappa, 1.0 - kappa)[:5]
        found = [getattr(fe, name) for name in RATIO_NAMES]
        scale = [abs(e) for e in exact]
        scale[4] = max(scale[4], abs(exact[2]))
        rows.append({"delta_over_a": d, "kappa": kappa, "seconds": fe.wall_time_s, "dofs": fe.dofs,
                     "error": float(max(abs(f - e) / s_ for f, e, s_ in zip(found, exact, scale)))})
    return rows


def study(quick: bool = False) -> dict:
    """Every number of the study (quick: fewer gaps for the Reynolds model, one finite-element case)."""
    start = time.perf_counter()
    deltas = (*THIN, APPARATUS["delta_over_a"]) if quick else DELTAS
    kappas = KAPPAS
    stokes = np.array([exact_ratios(d, kappas) for d in deltas])
    reynolds = np.array([reynolds_ratios(d, kappas) for d in deltas])
    exact_thin = np.array([exact_ratios(d, kappas) for d in EXACT_THIN])
    thin = [deltas.index(d) for d in THIN]
    return {
        "deltas": deltas, "kappas": kappas,
        "stokes": stokes, "reynolds": reynolds,
        "c_stokes": thin_gap_coefficient(EXACT_THIN, exact_thin),
        "c_stokes_study": thin_gap_coefficient(THIN, stokes[thin]),
        "c_reynolds": thin_gap_coefficient(THIN, reynolds[thin]),
        "slope_stokes": log_slope(EXACT_THIN, exact_thin),
        "slope_reynolds": log_slope(THIN, reynolds[thin]),
        "fe": fe_errors(QUICK_FE_CASES if quick else FE_CASES),
        "wall_time_s": time.perf_counter() - start,
    }


#: The O(delta/a) coefficients derived from the exact solution's expansion
#: (lubrication.stokes_exact, "Thin gap"): ratio = 1 + c delta/a + O((delta/a)^2).
C_FORMS = {"f_eps_per_eps_dot": lambda k: 1.5 + 0.0 * k,
           "f_chi_per_w_a": lambda k: 0.5 + 0.0 * k,
           "t_a_per_w_a": lambda k: 1.5 / (1.0 + 2.0 * k * k),
           "f_chi_per_w_b": lambda k: 2.5 + 0.0 * k,
           "t_a_per_w_b": lambda k: 1.5 + 0.0 * k}


def checks_of(result: dict) -> list[Check | Finding]:
    """Thin-gap limit of both models, c(kappa), the finite-element solver, and the share of the correction."""
    checks = []
    kappas = result["kappas"]
    for k, name in enumerate(RATIO_NAMES):
        slopes = result["slope_stokes"][k]
        worst = int(np.argmax(np.abs(slopes - 1.0)))
        checks.append(absolute(
            f"Stokes: slope of log|ratio - 1| against log(delta/a), {name}", slopes[worst], 1.0, 1e-3,
            f"worst over kappa in [0, 0.99] (kappa={kappas[worst]:g}); delta/a = {EXACT_THIN[0]:g}, "
            f"{EXACT_THIN[1]:g}: 1 + O(delta/a)"))
        checks.append(at_most(
            f"Stokes: max |ratio - 1| over kappa at delta/a = {THIN[0]:g}, {name}",
            float(np.max(np.abs(result["stokes"][0, k] - 1.0))), 3.0 * THIN[0],
            "leading order: O(delta/a), uniformly in kappa"))
        c_err = float(np.max(np.abs(result["c_stokes"][k] - C_FORMS[name](kappas))))
        checks.append(at_most(f"Stokes: fitted c(kappa) against the derived coefficient, {name}", c_err, 1e-6,
                              f"max over kappa; fit from delta/a = {', '.join(f'{d:g}' for d in EXACT_THIN)}; "
                              "C_FORMS"))
    for k, name in enumerate(RATIO_NAMES):
        # where the exact gap carries no O(delta/a) part (f_chi and T_a per W_a at kappa -> 0)
        # ratio - 1 is rounding, and a slope means nothing
        moving = np.abs(result["reynolds"][1, k] - 1.0) > 1e-6
        slope = float(np.min(result["slope_reynolds"][k][moving]))
        checks.append(at_least(
            f"Reynolds on the exact gap: slope of log|ratio - 1| against log(delta/a), {name}",
            slope, 0.9,
            f"min over kappa in [0, 0.99] where |ratio - 1| > 1e-6: the ratio tends to 1 at "
            f"least linearly; max c = {np.max(result['c_reynolds'][k]):.3g} (at kappa = 0.99: "
            "not uniform near contact)"))
    for row in result["fe"]:
        checks.append(at_most(
            f"finite elements against the exact solution, delta/a = {row['delta_over_a']:.4g}, "
            f"kappa = {row['kappa']:g}: largest relative error of the five coefficients",
            row["error"], FE_TOLERANCE, f"default mesh, {row['dofs']} unknowns, {row['seconds']:.2f} s; "
            "R_t_b against R_t_a"))
    share = result["c_reynolds"] / result["c_stokes"]
    for k, name in enumerate(RATIO_NAMES):
        checks.append(Finding(
            f"share of the Stokes O(delta/a) correction carried by the exact gap, {name}",
            float(share[k, 0]),
            f"c_reynolds/c_stokes at kappa=0; over kappa <= 0.99: {share[k].min():.3g} .. {share[k].max():.3g}"))
    return checks
