r"""Table 3 re-inferred: the roughness at which the full model rolls at the measured speeds.

The paper's inference
---------------------
Section 6.1 infers the minimum gap sigma of the smooth steel cylinder (about
50 micrometres) and of five sandpaper coatings (Table 3: grades 220, 150, 120,
80, 50 inferred 0.3, 0.4, 0.5, 1 and 1.6 mm) from measured speeds with its
leading-order speed law (6.1)-(6.3):

    V = V* sin(alpha) zeta* Max(1/2, 1 - sqrt(1 - s^2) tan(psi)/s),
    V* = b M delta g / (4 nu m''_a),  zeta* = sqrt(1 - kappa*^2),  kappa* = 1 - sigma/delta,

and finds sigma "about four times the mean particle size in each of the five
cases" (Table 3's "expected" row: 0.07, 0.09, 0.12, 0.2, 0.36 mm, the mean
particle size of the American CAMI standard). Its sigma make (6.1) reproduce
the measured speeds (they were chosen to collapse figure 11 onto it), so (6.1)
with the paper's sigma stands in for the measurements here; the measured
speeds themselves are not tabulated.

The re-inference
----------------
For each grade the target is V_m = (6.1) with the paper's sigma, and the
re-inferred sigma solves V(sigma) = V_m, where V(sigma) = b Omega_b is the
steady rolling speed of the full model (2.1)-(2.4) with rough contact
(:mod:`dynamics.contact.full`: a unilateral constraint at eps* = delta - sigma
with Coulomb friction at the contact point) and with

* the exact 2-D Stokes forces of circular walls (``kernel_model("stokes-exact")``), valid at
  the apparatus' delta/a = 0.41 where (2.5)-(2.7) are only leading order, and
* the same times the thin-gap finite-length factors of an annulus of length L
  whose gap opens into the oil-filled end regions
  (``kernel_model("stokes-exact", ends="open", length_over_a=L/a)``, L/a = 12.9). That
  product differs from a 3-D Stokes solve by up to 4.7% in f_chi, and in T_a
  by under 0.8% of the torque's larger coefficient, at kappa = 0.3-0.99
  (docs/finite_length/stokes3d.md).

V(sigma) is the fixed point of the contact phase (chi' = 0, rates constant),
found by Newton's method (:func:`dynamics.contact.full.steady_full_contact`):
locked (no slip at the contact point) when the locking reaction lies inside
the friction cone, |F| <= tan(psi_hat) N, else sliding with the friction
opposing the slip the locking friction was holding back. The root in sigma is
found by :func:`scipy.optimize.brentq` on a bracket grown geometrically from
the paper's sigma; V(sigma) increases monotonically (checked on a grid), so the
root is unique. Trajectories released at rest on the asperities at the bottom
(phi = pi), integrated until e^-30 of the slowest mode of the fixed point is
left, must end at the target speed: that checks both the fixed point and its
stability.

Conditions: the steel apparatus (:func:`dynamics.apparatus.preset`), 500 cSt
oil (figure 11), on the 2.4 degree slope of figure 5(a), as
:mod:`validation.contact_checks` uses for Table 3. The friction angle is the
paper's: section 6.2 reads the onset of sliding off figure 12 at about 3
degrees, which by (6.4) gives the scaled psi = 0.1097 rad
(:data:`validation.contact_checks.PSI_EXPERIMENT`), tan(psi_hat) =
(delta/a) tan(psi) = 0.0447 (C2). At 2.4 degrees (6.1) is on its locked branch,
V = V* sin(alpha) zeta*/2, and does not depend on psi.

The slope drops out while the pair is locked. In steady contact (2.4) reads
M g b sin(alpha) + m'_a g eps* sin(phi) = 0, so sin(phi) is proportional to
sin(alpha); (2.1) and (2.3) are linear in the rates and the friction with
m'_a g sin(phi) as their only drive, so with the locking constraint Omega_b is
proportional to sin(alpha), like the locked (6.1). The re-inferred sigma is
then the same on every slope on which the full model locks (checked at 1.5 and
2.0 degrees); once it slides (at 2.8 degrees, for most grades) the friction
enters and it is not.

The tables, the paragraph and the figure are :mod:`validation.reports.table3`'s; run
``python -m validation.reports.table3`` from the project root to write
``docs/table3/table3.md``, ``table3.json`` and ``table3.png``.
"""

from __future__ import annotations

import math
from functools import partial
from typing import NamedTuple

import numpy as np
from scipy.optimize import brentq

from dynamics.apparatus import preset
from dynamics.contact.full import (
    FullContactRun,
    contact_functions,
    friction_coefficient,
    steady_full_contact,
)
from dynamics.contact.reduced import LOCKED, SLIDING, ContactParams
from dynamics.contact.steady import steady_locked, steady_speed, steady_state
from dynamics.equations import full
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.simulation import simulate
from dynamics.trajectory import PHASE_CODES
from lubrication.finite_length import TABLE_VERSION
from lubrication.geometry import check_finite, check_range
from lubrication.registry import kernel_model

from .checks import Finding, absolute, at_most, relative
from .contact_checks import (
    PSI_EXPERIMENT,
    SANDPAPER,
    SANDPAPER_OIL,
    SANDPAPER_SLOPE_DEG,
)

__all__ = [
    "GRADES", "MODELS", "PARTICLE_SIZE", "FullSteady", "bracket_sigma", "compute", "force_models", "full_speed",
    "full_steady_state", "infer_sigma", "paper_speed", "records", "reduced_speed", "sigma_bounds", "the_apparatus",
]

GRADES = ("220", "150", "120", "80", "50", "smooth")
#: Table 3's "expected" row: the mean particle size of the CAMI standard for each grit (m).
PARTICLE_SIZE = {"220": 0.07e-3, "150": 0.09e-3, "120": 0.12e-3, "80": 0.2e-3, "50": 0.36e-3}
PAPER_RATIO = 4.0  # "the roughness scale is about four times the mean particle size" (section 6.1)
#: What "about" covers: the paper's own ratios, 4.17-5.00, are all "about four", within 25% of it.
ABOUT = 0.25

MODELS = ("stokes-exact", "stokes-exact/open-ends")
#: The steps between (6.1) and the full model with exact forces (the detail table).
REDUCED, CLOSED_FORMS = "reduced (5.10)/(5.11)", "full, closed forms (2.5)-(2.7)"
LOCKED_SLOPES_DEG = (1.5, 2.0)  # further slopes on which the full model locks at every re-inferred sigma
SLIDING_SLOPE_DEG = 2.8  # below the 3 degree onset of (6.1), above the full model's for the coarse grades

SIGMA_MIN_OVER_DELTA = 1e-3  # a micrometre-scale floor for the bracket
#: The bracket stays below CAP delta (1 - s): contact at rest needs kappa* > s (5.6), and near it
#: the steady speed grows without bound (N -> 0); measured, Newton converges up to 0.8 of that.
CAP = 0.8
BRACKET_FACTOR = 1.5
ROOT_RTOL = 1e-13  # brentq's relative tolerance on sigma
#: The fixed point's residual (chi'', Omega' in 1/tau^2) left by Newton (xtol = 1e-12): measured
#: 1e-14 or less; the drive terms are O(s) = 0.17.
RESIDUAL_TOL = 1e-9
#: Speed at the root against the target: brentq leaves sigma within 1e-13 relative, times the
#: elasticity d ln V / d ln sigma <= 1.3 here, plus the fixed point's own 1e-12 (measured: 5e-15).
SPEED_TOLERANCE = 1e-11
#: sigma recovered from the model's own speed at a known sigma: the same errors over the elasticity
#: >= 0.55, about 2e-12 (measured: 4e-15).
RECOVERY_TOLERANCE = 1e-11
#: Locked slopes: the sigma found agrees exactly in exact arithmetic (module docstring); two root
#: solves, each within about 2e-12 of sigma.
SLOPE_TOLERANCE = 1e-11
TRAJECTORY_RTOL = 1e-10
TRANSIENT_TAU = 50.0  # the impact and first swings after a release on the asperities
E_FOLDS = 30.0  # e-folds of the slowest mode left at the end of a trajectory
#: A settled trajectory against the fixed point: e^-30 = 1e-13 of the initial offset left, and the
#: integrator's rtol = 1e-10 on the rates, a hundredfold margin (measured: 3e-13).
TRAJECTORY_TOLERANCE = 1e-8
QUICK_TRAJECTORIES = (("220", "stokes-exact"),)
SCAN_POINTS = 40


class FullSteady(NamedTuple):
    """A steadily rolling contact state of the full model (SI) and what it rests on."""

    phase: str
    chi: float
    omega_a: float
    omega_b: float
    normal: float  # contact reaction N (N)
    friction: float  # contact friction F along e_chi (N)
    speed: float  # b Omega_b (m/s)
    residual: float  # max |chi''|, |Omega'| tau^2 at the state


# -- the apparatus and the speeds ---------------------------------------------------

def the_apparatus(slope_deg: float = SANDPAPER_SLOPE_DEG):
    """The steel apparatus in 500 cSt oil on a slope of ``slope_deg`` degrees (figure 11's runs)."""
    slope_deg = check_range("slope_deg", slope_deg, 0.0, 90.0, low_open=True, unit="deg")
    return preset("steel", nu=SANDPAPER_OIL, alpha=math.radians(slope_deg))


def force_models(apparatus) -> dict:
    """The two force models of the re-inference, keyed by :data:`MODELS`."""
    return {MODELS[0]: kernel_model("stokes-exact"),
            MODELS[1]: kernel_model("stokes-exact", ends="open", length_over_a=apparatus.length / apparatus.a)}


def sigma_bounds(apparatus) -> tuple[float, float]:
    """The range (m) searched for sigma: [1e-3 delta, CAP delta (1 - s)] (see :data:`CAP`)."""
    return SIGMA_MIN_OVER_DELTA * apparatus.delta, CAP * apparatus.delta * (1.0 - apparatus.s)


def _contact(apparatus, sigma: float, psi: float) -> ContactParams:
    sigma = check_range("sigma", sigma, 0.0, apparatus.delta, low_open=True, unit="m")
    return ContactParams(1.0 - sigma / apparatus.delta, psi)


def paper_speed(apparatus, sigma: float, psi: float = PSI_EXPERIMENT) -> float:
    """(6.1)-(6.3) as the paper applies it: the compact (5.12) with kappa* = 1 - sigma/delta (m/s)."""
    contact = _contact(apparatus, sigma, psi)
    return steady_speed(apparatus.v_star, apparatus.alpha, apparatus.s, contact.kappa_star, psi)


def reduced_speed(apparatus, sigma: float, psi: float = PSI_EXPERIMENT) -> float:
    """b Omega_b / tau of section 5's exact fixed point (5.10)/(5.11) (m/s): (6.1) without the zeta* expansion."""
    contact = _contact(apparatus, sigma, psi)
    return apparatus.b * steady_state(apparatus.s, contact.kappa_star, psi).omega_b / apparatus.tau


def full_steady_state(apparatus, forces, sigma: float, psi: float = PSI_EXPERIMENT) -> FullSteady:
    """The full model's steady rolling state in contact at minimum gap ``sigma`` (m).

    Locked if the locking reaction lies in the friction cone, |F| <= tan(psi_hat) N
    with tan(psi_hat) = (delta/a) tan(psi) (C2); otherwise sliding, the friction
    opposing the slip the locking friction was holding back (sgn(slip) = -sgn(F_lock)).
    Newton's method starts from the locked fixed point (5.6), (5.10) of section 5.

    Raises
    ------
    ValueError
        If sigma is outside (0, delta) or s >= kappa* (no contact at rest).
    RuntimeError
        If Newton's method leaves a residual above :data:`RESIDUAL_TOL`, or the
        sliding state slips the wrong way or pulls (N <= 0).
    """
    contact = _contact(apparatus, sigma, psi)
    reduced = steady_locked(apparatus.s, contact.kappa_star)
    tau, a = apparatus.tau, apparatus.a
    arm = a + contact.kappa_star * apparatus.delta  # B to the contact point
    p, model = full.params_array(apparatus), full.model_arguments(forces)
    mu_f = friction_coefficient(apparatus, contact)

    def rates(x, locked, sigma_slip=0.0):
        y = np.array([x[0], 0.0, x[1], x[2]])
        return contact_functions(forces).rates(y, p, contact.kappa_star, contact.one_minus_kappa_star, locked,
                                               sigma_slip, mu_f, model)

    x = steady_full_contact(apparatus, forces, contact, True,
                            [reduced.phi - apparatus.alpha, reduced.omega_a / tau, reduced.omega_b / tau])
    r = rates(x, True)
    phase, sigma_slip = LOCKED, 0.0
    if not (r[3] > 0.0 and abs(r[4]) <= mu_f * r[3]):
        phase, sigma_slip = SLIDING, -math.copysign(1.0, r[4])
        # from the locked state with a slight slip the chosen way, which fixes the friction's sign
        x = steady_full_contact(apparatus, forces, contact, False, [x[0], x[1] * (1.0 + 1e-3 * sigma_slip), x[2]])
        r = rates(x, False, sigma_slip)
        if not (r[3] > 0.0 and math.copysign(1.0, a * x[1] - arm * x[2]) == sigma_slip):
            msg = (f"no sliding steady state at sigma = {sigma:g} m: N = {r[3]:g} N, slip "
                   f"{a * x[1] - arm * x[2]:g} m/s against the direction {sigma_slip:+g}")
            raise RuntimeError(msg)
    residual = tau * tau * float(np.max(np.abs(r[:3] if phase == SLIDING else r[[0, 2]])))
    if not residual <= RESIDUAL_TOL:
        msg = f"the {phase} fixed point at sigma = {sigma:g} m did not converge: residual {residual:g} (1/tau^2)"
        raise RuntimeError(msg)
    return FullSteady(phase, float(x[0]), float(x[1]), float(x[2]), float(r[3]), float(r[4]),
                      apparatus.b * float(x[2]), residual)


def full_speed(apparatus, forces, sigma: float, psi: float = PSI_EXPERIMENT) -> float:
    """b Omega_b (m/s) of :func:`full_steady_state`."""
    return full_steady_state(apparatus, forces, sigma, psi).speed


# -- the inverse solve ------------------------------------------------------------------

def _check_inverse(v_target: float, sigma_guess: float, bounds) -> tuple[float, float, float, float]:
    v_target = check_range("v_target", v_target, 0.0, math.inf, low_open=True, unit="m/s")
    low, high = (check_finite("bounds", b) for b in bounds)
    if not 0.0 < low < high:
        msg = f"bounds must satisfy 0 < low < high, got ({low!r}, {high!r})"
        raise ValueError(msg)
    sigma_guess = check_range("sigma_guess", sigma_guess, low, high, high_open=False, unit="m")
    return v_target, sigma_guess, low, high


def bracket_sigma(speed, v_target: float, sigma_guess: float, bounds,
                  factor: float = BRACKET_FACTOR) -> tuple[float, float]:
    """(lo, hi) with speed(lo) <= v_target <= speed(hi), grown geometrically from ``sigma_guess``.

    Parameters
    ----------
    speed : callable
        sigma (m) -> steady speed (m/s), increasing in sigma.
    v_target : float
        Speed to reach (m/s), positive.
    sigma_guess : float
        Start (m), in ``bounds``.
    bounds : (float, float)
        0 < low < high: the bracket never leaves them.
    factor : float
        Growth per step, > 1.

    Raises
    ------
    ValueError
        For bad input, or if v_target lies outside (speed(low), speed(high)).
    """
    v_target, sigma_guess, low, high = _check_inverse(v_target, sigma_guess, bounds)
    factor = check_range("factor", factor, 1.0, math.inf, low_open=True)
    lo = hi = sigma_guess
    v = speed(sigma_guess)
    if v < v_target:
        while v < v_target:
            if hi == high:
                msg = (f"v_target must be in (V(low), V(high)) = ({speed(low):.6g}, {v:.6g}) m/s for sigma in "
                       f"[{low:g}, {high:g}] m, got {v_target!r}")
                raise ValueError(msg)
            lo, hi = hi, min(hi * factor, high)
            v = speed(hi)
    else:
        while v > v_target:
            if lo == low:
                msg = (f"v_target must be in (V(low), V(high)) = ({v:.6g}, {speed(high):.6g}) m/s for sigma in "
                       f"[{low:g}, {high:g}] m, got {v_target!r}")
                raise ValueError(msg)
            lo, hi = max(lo / factor, low), lo
            v = speed(lo)
    return lo, hi


def infer_sigma(speed, v_target: float, sigma_guess: float, bounds) -> float:
    """The sigma (m) at which ``speed(sigma)`` equals ``v_target``: brentq on :func:`bracket_sigma`'s bracket.

    The residual is speed/v_target - 1, so the tolerance on sigma is relative
    (:data:`ROOT_RTOL`). Same parameters and errors as :func:`bracket_sigma`.
    """
    lo, hi = bracket_sigma(speed, v_target, sigma_guess, bounds)
    if lo == hi:
        return lo
    return brentq(lambda sigma: speed(sigma) / v_target - 1.0, lo, hi, xtol=1e-300, rtol=ROOT_RTOL)


# -- the runs -----------------------------------------------------------------------

def _elasticity(speed, sigma: float, h: float = 1e-4) -> float:
    """d ln V / d ln sigma by central differences (error O(h^2))."""
    return (math.log(speed(sigma * (1.0 + h))) - math.log(speed(sigma * (1.0 - h)))) / (2.0 * h)


def _gap_reynolds(apparatus, state: FullSteady) -> float:
    """Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a) with W = Omega (chi' = 0) (dynamics.equations.limits)."""
    ap = apparatus
    return max(abs(state.omega_a) * ap.a, abs(state.omega_b) * ap.b) * ap.delta**2 / (ap.nu * ap.a)


def _settling_rate(apparatus, forces, sigma: float, state: FullSteady, psi: float = PSI_EXPERIMENT) -> float:
    """Slowest decay rate (1/tau) of the contact phase linearised at ``state``.

    The locked phase keeps the slip at zero as an invariant: its zero
    eigenvalue (to rounding) is that constraint, not a mode, and is left out.
    """
    contact = _contact(apparatus, sigma, psi)
    locked = state.phase == LOCKED
    sigma_slip = 0.0 if locked else math.copysign(1.0, apparatus.a * state.omega_a - (
        apparatus.a + contact.kappa_star * apparatus.delta) * state.omega_b)
    args = FullContactRun(apparatus, forces, contact, Limits(), TRAJECTORY_RTOL).contact_args(locked, sigma_slip)
    y = np.array([state.chi, 0.0, state.omega_a, state.omega_b, 0.0])
    rates = np.linalg.eigvals(contact_functions(forces).jacobian(0.0, y, args)[:4, :4]) * apparatus.tau
    return -float(np.max(rates.real[np.abs(rates) > 1e-6]))


def trajectory_run(apparatus, forces, sigma: float, psi: float = PSI_EXPERIMENT) -> dict:
    """The full model released at rest on the asperities at the bottom (phi = pi), run until settled."""
    contact = _contact(apparatus, sigma, psi)
    state = full_steady_state(apparatus, forces, sigma, psi)
    rate = _settling_rate(apparatus, forces, sigma, state, psi)
    t_end_tau = TRANSIENT_TAU + E_FOLDS / rate
    run = simulate(apparatus, Initial(kappa=contact.kappa_star, phi=math.pi), t_end_tau * apparatus.tau,
                   forces=forces, contact=contact, rtol=TRAJECTORY_RTOL)
    return {"status": run.status, "phase": run.info["final_phase"], "fixed_phase": state.phase,
            "speed": apparatus.b * float(run.columns["omega_b"][-1]), "fixed_speed": state.speed,
            "settling_rate": rate, "t_end_tau": t_end_tau, "steps": run.steps, "wall_time_s": run.wall_time_s}


def _model_row(apparatus, forces, grade: str, v_target: float, psi: float) -> dict:
    """The re-inferred sigma of one grade with one force model, and what it rests on."""
    sigma_paper = SANDPAPER[grade]
    speed = partial(full_speed, apparatus, forces, psi=psi)
    bounds = sigma_bounds(apparatus)
    sigma = infer_sigma(speed, v_target, sigma_paper, bounds)
    state = full_steady_state(apparatus, forces, sigma, psi)
    # forward then inverse: the model's own speed at the paper's sigma must give the paper's sigma back
    recovered = infer_sigma(speed, speed(sigma_paper), 0.5 * sigma_paper, bounds)
    lock_tan = abs(state.friction) / state.normal / apparatus.delta_over_a  # scaled tan(psi) that just locks
    row = {"sigma": sigma, "phase": state.phase, "speed": state.speed,
           "speed_error": abs(state.speed / v_target - 1.0), "recovered": recovered,
           "recovery_error": abs(recovered / sigma_paper - 1.0), "elasticity": _elasticity(speed, sigma),
           "psi_to_lock": math.atan(lock_tan) if state.phase == LOCKED else math.nan,
           "gap_reynolds": _gap_reynolds(apparatus, state), "residual": state.residual,
           "speed_at_paper_sigma": speed(sigma_paper)}
    if grade in PARTICLE_SIZE:
        row["ratio"] = sigma / PARTICLE_SIZE[grade]
    return row


def _slopes_rows(slopes, psi: float) -> dict:
    """sigma re-inferred on other slopes, per model and grade, with the phase of the full model there."""
    out = {}
    for slope in slopes:
        ap = the_apparatus(slope)
        out[slope] = {}
        for name, forces in force_models(ap).items():
            speed = partial(full_speed, ap, forces, psi=psi)
            cells = {}
            for grade in GRADES:
                sigma = infer_sigma(speed, paper_speed(ap, SANDPAPER[grade], psi), SANDPAPER[grade],
                                    sigma_bounds(ap))
                cells[grade] = {"sigma": sigma, "phase": full_steady_state(ap, forces, sigma, psi).phase}
            out[slope][name] = cells
    return out


def _power_law(sigmas: dict) -> float:
    """Exponent p of a least-squares fit sigma ~ d^p over the five grades (log-log)."""
    grades = list(PARTICLE_SIZE)
    return float(np.polyfit(np.log([PARTICLE_SIZE[g] for g in grades]), np.log([sigmas[g] for g in grades]), 1)[0])


def _scan(apparatus, forces, psi: float) -> dict:
    """V(sigma) on a geometric grid over :func:`sigma_bounds`, for monotonicity and the figure."""
    sigmas = np.geomspace(*sigma_bounds(apparatus), SCAN_POINTS)
    return {"sigma": sigmas.tolist(), "speed": [full_speed(apparatus, forces, s, psi) for s in sigmas]}


def compute(quick: bool = False, psi: float = PSI_EXPERIMENT) -> dict:
    """Every number of the re-inference (module docstring); ``quick`` runs one trajectory and one more slope."""
    ap = the_apparatus()
    models = force_models(ap)
    # name -> (speed, phase) of sigma: the steps from (6.1) to the full model with exact forces
    decomposition = {
        REDUCED: (partial(reduced_speed, ap, psi=psi),
                  lambda sigma: steady_state(ap.s, 1.0 - sigma / ap.delta, psi).phase),
        CLOSED_FORMS: (partial(full_speed, ap, kernel_model("closed-form"), psi=psi),
                       lambda sigma: full_steady_state(ap, kernel_model("closed-form"), sigma, psi).phase)}
    bounds = sigma_bounds(ap)
    rows = []
    for grade in GRADES:
        v_target = paper_speed(ap, SANDPAPER[grade], psi)
        row = {"grade": grade, "particle_size": PARTICLE_SIZE.get(grade, math.nan), "sigma_paper": SANDPAPER[grade],
               "v_target": v_target, "models": {}, "decomposition": {}}
        if grade in PARTICLE_SIZE:
            row["ratio_paper"] = SANDPAPER[grade] / PARTICLE_SIZE[grade]
        for name, forces in models.items():
            row["models"][name] = _model_row(ap, forces, grade, v_target, psi)
        for name, (speed, phase) in decomposition.items():
            sigma = infer_sigma(speed, v_target, SANDPAPER[grade], bounds)
            row["decomposition"][name] = {"sigma": sigma, "phase": phase(sigma)}
        rows.append(row)
    cases = QUICK_TRAJECTORIES if quick else tuple((g, m) for g in GRADES for m in MODELS)
    by_grade = {r["grade"]: r for r in rows}
    trajectories = [{"grade": g, "model": m, **trajectory_run(ap, models[m], by_grade[g]["models"][m]["sigma"], psi)}
                    for g, m in cases]
    slopes = _slopes_rows(LOCKED_SLOPES_DEG[:1] if quick else (*LOCKED_SLOPES_DEG, SLIDING_SLOPE_DEG), psi)
    result = {"apparatus": {"slope_deg": SANDPAPER_SLOPE_DEG, "nu": ap.nu, "delta": ap.delta, "a": ap.a,
                            "delta_over_a": ap.delta_over_a, "length_over_a": ap.length / ap.a, "s": ap.s,
                            "v_star": ap.v_star, "tau": ap.tau, "psi": psi,
                            "tan_psi_hat": ap.delta_over_a * math.tan(psi), "bounds": list(bounds),
                            "finite_length_table_version": TABLE_VERSION},
              "rows": rows, "trajectories": trajectories, "slopes": slopes, "quick": quick}
    if not quick:
        result["scans"] = {name: _scan(ap, forces, psi) for name, forces in models.items()}
    return result


# -- records ------------------------------------------------------------------------

def _about_four(ratio: float) -> bool:
    return abs(ratio / PAPER_RATIO - 1.0) <= ABOUT


def records(result: dict) -> list:
    """Checks (the inverse solve, the fixed points, the slope independence) and findings (the numbers)."""
    out: list = []
    rows = result["rows"]
    for name in MODELS:
        cells = {r["grade"]: r["models"][name] for r in rows}
        out.append(at_most(f"Table 3 ({name}): speed at the sigma found vs V_(6.1)(sigma paper), relative error, "
                           "largest over the grades",
                           max(c["speed_error"] for c in cells.values()), SPEED_TOLERANCE,
                           f"brentq rtol {ROOT_RTOL:g} on sigma times d ln V/d ln sigma <= "
                           f"{max(c['elasticity'] for c in cells.values()):.2f}, plus Newton's 1e-12"))
        out.append(at_most(f"Table 3 ({name}): sigma recovered from the model's own speed at the paper's sigma, "
                           "relative error, largest over the grades",
                           max(c["recovery_error"] for c in cells.values()), RECOVERY_TOLERANCE,
                           "forward then inverse, started from half the true sigma"))
        for slope, models in result["slopes"].items():
            locked = [g for g in GRADES if models[name][g]["phase"] == LOCKED and cells[g]["phase"] == LOCKED]
            if slope in LOCKED_SLOPES_DEG:
                out.append(absolute(f"Table 3 ({name}): grades locked at {slope:g} degrees (of {len(GRADES)})",
                                    len(locked), len(GRADES), 0.0, "the premise of the slope-independence check"))
            if locked:
                spread = max(abs(models[name][g]["sigma"] / cells[g]["sigma"] - 1.0) for g in locked)
                note = ("locked: Omega_b and (6.1) both proportional to sin(alpha) (module docstring)"
                        if slope in LOCKED_SLOPES_DEG else "grades still locked there")
                out.append(at_most(f"Table 3 ({name}): sigma at {slope:g} vs {SANDPAPER_SLOPE_DEG:g} degrees, "
                                   f"{len(locked)} locked grades, relative", spread, SLOPE_TOLERANCE, note))
    for t in result["trajectories"]:
        label = f"Table 3 ({t['model']}, grade {t['grade']}): trajectory at the sigma found"
        out.append(absolute(f"{label}, settled (1 if completed)", float(t["status"] == "completed"), 1.0, 0.0,
                            f"{t['status']}, {t['steps']} steps over {t['t_end_tau']:.0f} tau"))
        out.append(absolute(f"{label}, final phase vs the fixed point's", PHASE_CODES[t["phase"]],
                            PHASE_CODES[t["fixed_phase"]], 0.0, f"codes {PHASE_CODES}"))
        row = next(r for r in rows if r["grade"] == t["grade"])
        out.append(relative(f"{label}, final speed b Omega_b vs V_(6.1)(sigma paper)", t["speed"], row["v_target"],
                            TRAJECTORY_TOLERANCE, f"slowest mode {t['settling_rate']:.3g}/tau, e^-{E_FOLDS:g} left; "
                            f"rtol {TRAJECTORY_RTOL:g}"))
    if "scans" in result:
        for name, scan in result["scans"].items():
            steps = np.diff(scan["speed"])
            out.append(at_most(f"Table 3 ({name}): V(sigma) non-increasing steps on a {SCAN_POINTS}-point grid",
                               int(np.sum(steps <= 0.0)), 0.0,
                               f"sigma from {1e3 * scan['sigma'][0]:.4g} to {1e3 * scan['sigma'][-1]:.4g} mm: "
                               "a monotone V makes the root unique"))

    for r in rows:
        for name in MODELS:
            c = r["models"][name]
            note = f"paper {1e3 * r['sigma_paper']:g} mm; {c['phase']}"
            out.append(Finding(f"Table 3 grade {r['grade']}: sigma re-inferred, {name} (mm)", 1e3 * c["sigma"], note))
            if "ratio" in c:
                out.append(Finding(f"Table 3 grade {r['grade']}: sigma / mean particle size, {name}", c["ratio"],
                                   f"paper {r['ratio_paper']:.3g}; 'about four' "
                                   f"{'holds' if _about_four(c['ratio']) else 'fails'} (within {ABOUT:.0%})"))
        for name, cell in r["decomposition"].items():
            out.append(Finding(f"Table 3 grade {r['grade']}: sigma re-inferred, {name} (mm)", 1e3 * cell["sigma"],
                               f"{cell['phase']}; separates the zeta* expansion of (6.1) from the finite gap"))
    for name in ("paper", *MODELS):
        sig = {r["grade"]: (r["sigma_paper"] if name == "paper" else r["models"][name]["sigma"])
               for r in rows if r["grade"] in PARTICLE_SIZE}
        out.append(Finding(f"Table 3: exponent p of sigma ~ (particle size)^p, {name}", _power_law(sig),
                           "least squares over the five grades in log-log; 1 if sigma is proportional"))
    for name in MODELS:
        cells = [r["models"][name] for r in rows]
        locked = [c["psi_to_lock"] for c in cells if c["phase"] == LOCKED]
        out.append(Finding(f"Table 3 ({name}): largest scaled friction angle needed to lock (rad)",
                           max(locked, default=math.nan), f"the paper's psi = {result['apparatus']['psi']:.4f}"))
        out.append(Finding(f"Table 3 ({name}): largest gap Reynolds number Re* at the steady states",
                           max(c["gap_reynolds"] for c in cells),
                           "force error about 0.068 Re* at delta/a = 0.41 (docs/inertia/inertia.md)"))
        if SLIDING_SLOPE_DEG in result["slopes"]:
            there = result["slopes"][SLIDING_SLOPE_DEG][name]
            out.append(Finding(f"Table 3 ({name}): sigma at {SLIDING_SLOPE_DEG:g} vs {SANDPAPER_SLOPE_DEG:g} "
                               "degrees, largest relative difference",
                               max(abs(there[r["grade"]]["sigma"] / r["models"][name]["sigma"] - 1.0) for r in rows),
                               "sliding there: " + (", ".join(g for g in GRADES if there[g]["phase"] == SLIDING)
                                                    or "none")))
    return out
