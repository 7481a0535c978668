r"""The equations of motion against the paper: figures 2 and 3, section 3, the distinguished limit, the runaway.

Every check runs the integrators of :mod:`dynamics` and compares a measured
number with a closed form of section 3 or with a derivation below.

Figures 2 and 3
---------------
The reduced model (2.11) with Upsilon = mu_ = 1, s = 1/4 (figure 2, rocking) and
s = 0.9 (figure 3, runaway), released from rest. The text does not give the
initial position it shows; both start here at kappa0 = 0.5, phi0 = 0.3 rad. The
rocking is measured against the multiple scales (3.9)-(3.10): the centre
phi* = pi + asin(s) (the text's "phi = -asin(s)" names it by its sine), the
frequency, the rate sqrt(1 - s^2) at which 1/zeta grows, the decay exponent q of
the envelope (also for mu_ = 3), and the distance rolled, which grows as
(3 s / sqrt(1 - s^2)) ln t (:func:`dynamics.equations.special.slow_approach`), not as the
text's t^(1 - q) = t^(1/6). The runaway is measured against (3.11).

The runaway of the full model
-----------------------------
Rigid co-rotation: the gap closed (eps = delta), Omega_a = Omega_b = chi' = Omega.
Then (2.4) reads, with I_a = m_a a^2/2,

    I(chi) Omega' - m'_a b delta sin(chi) Omega^2 = M g b sin(alpha) + m'_a g delta sin(phi),
    I(chi) = I_0 + 2 m'_a b delta cos(chi),   I_0 = I_a + (M + m_b) b^2 + m_eff delta^2,

and Omega times it is the derivative of the energy (1/2) I(chi) Omega^2 +
m'_a g delta cos(phi) - M g sin(alpha) X_b: the model is a rigid body rolling
about its contact point whose fluid is a point mass at its centre of mass (no
intrinsic angular momentum, as (2.4) assumes). After theta = X_b/b radians,
Omega^2 = 2 K theta / I(chi) (1 + O(1/theta)) with K = M g b sin(alpha), and
t = int dtheta/Omega = <sqrt(I)> sqrt(2 theta / K): the mean acceleration is

    a_0 = M g sin(alpha) b^2 / <sqrt(I)>^2,
    <sqrt(I)> = (1/2 pi) oint sqrt(I) dchi = (2/pi) sqrt(I_0 + B) E(2 B/(I_0 + B)),  B = 2 m'_a b delta,

E the complete elliptic integral of the second kind. The paper's estimate (3.11),
M g sin(alpha)/(M + m_b + m_a/2), is a_0 with a = b and delta = 0; the
rigid-body value M g sin(alpha) b^2/(I_a + (M + m_b) b^2) drops m_eff delta^2.

The co-rotation is not free of loss. Within each turn Omega speeds up and slows
down, Omega' = Omega^2 m'_a b delta sin(chi)/I(chi) (from the energy), and the
film must supply the torque and the tangential force that carry the inner
cylinder along: T_a = I_a Omega' and, from (2.1), f_chi = Omega' (m_eff delta +
m'_a b cos chi). Near contact (2.6)-(2.7) give, with c = 4 pi mu a^3 L,
f_chi = c (W_a + W_b)/(delta^2 zeta) and T_a = -c W_a/(delta zeta), so the
dissipation, minus the power of the fluid forces on both cylinders,

    D = -f_eps eps' + delta f_chi W_b - T_a (W_a - W_b) = (delta zeta / c) [(delta f_chi + T_a)^2 + T_a^2],

is O(zeta Omega^4). The same centrifugal load closes the gap: (2.2) and (2.5)
give d(1/zeta)/dt = (delta^3/3c) Omega^2 [m_eff - (m'_a b sin chi)^2 / I] (the
second term is the d'Alembert force of (2.2)), so zeta ~ t^-3 while Omega ~ t:
D / (K Omega) tends to a constant, the fraction f of the work of gravity lost
in the film,

    f = (9 (m'_a b)^2 / m_eff) <sin^2(chi) (J^2 + I_a^2) I^(-7/2)>
        / <I^(-1/2) (1 - (m'_a b sin chi)^2 / (m_eff I))>,   J = I_a + m_eff delta^2 + m'_a b delta cos(chi),

(time averages over a turn are chi-averages weighted by 1/Omega ~ sqrt(I)),
independent of the slope and the viscosity. The model's asymptotic acceleration
is (1 - f) a_0 (:func:`runaway_estimates`).

Whether the full model can rock at all
--------------------------------------
At contact, at rest, (2.4) balances M g b sin(alpha) + m'_a g delta sin(phi) = 0:
a rest point exists only if s b/a = M b sin(alpha)/(m'_a delta) < 1, where the
reduced model, leading order in delta/a, has s < 1. For the aluminium
apparatus (delta/a = 0.41) the critical slope is 4.5 degrees
(:func:`critical_slope`): at the paper's 5 degrees (s = 0.79, s b/a = 1.11) every
start runs away, while (2.11) with the same groups can still rock.

Sedimentation of the full model
-------------------------------
On a level plane the inner cylinder falls straight down, m_eff eps'' = f_eps -
m'_a g, (2.5) giving f_eps = -R(kappa) eps' with R = R_0/zeta^3. Writing eps =
eps_r + eps_r' s(t) about the solution eps_r of (3.3) (R eps_r' = m'_a g), the
first-order terms give s' = -m_eff d(1/R)/dt, and the start from rest fixes
s(0+) = -m_eff/R(kappa0) (the distance lost while the speed builds up): the full
model lags (3.3) by the local inertial time, s = -t_i zeta^3 with t_i =
m_eff/R_0 (:func:`inertial_time`), so kappa falls short by t_i zeta^6 / tau, at
most t_i zeta0^6 / tau just after the start.
"""

from __future__ import annotations

import math
import time

import numpy as np

from dynamics.analysis import mechanical_energy, rocking_envelope
from dynamics.apparatus import Apparatus, preset
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import (
    ReducedParams,
    initial_state,
    reduced_jacobian,
    reduced_rhs,
)
from dynamics.equations.special import (
    contact_equilibrium,
    critical_slope,
    decay_exponent,
    inertial_time,
    rocking_frequency,
    runaway_estimates,
    runaway_spin_rate,
    sedimentation,
    slow_approach,
    steady_rolling,
)
from dynamics.initial import Initial
from dynamics.regime import classify
from dynamics.simulation import simulate
from dynamics.trajectory import Trajectory
from lubrication.registry import kernel_model

from .checks import Check, Finding, absolute, at_least, at_most, relative

__all__ = [
    "FIG2",
    "FIG3",
    "run",
]

FIG2 = ReducedParams(s=0.25, upsilon=1.0, mu_ratio=1.0)  # figure 2: rocking
FIG3 = ReducedParams(s=0.9, upsilon=1.0, mu_ratio=1.0)  # figure 3: runaway
START = (0.5, 0.3)  # kappa0, phi0 (rad) of both figures, from rest: the text does not give them
ROCKING_FLOOR = 1e-6  # 1 - kappa at which the figure-2 runs stop: about 730 tau, 90 periods
RATIOS = (0.1, 0.03, 0.01, 0.003)  # delta/a of the distinguished limit
LIMIT_GROUPS = (0.5, 1.0, 2.0)  # (s, Upsilon, mu_) held fixed as delta/a -> 0
LIMIT_START = Initial(0.3, 0.5)
LIMIT_WINDOW = 10.0  # tau
LIMIT_RTOL = 1e-10  # far below the smallest difference measured (3e-4)
STEEP = 30.0  # degrees: s = 4.6 for the aluminium apparatus, far from any rest state
RUNAWAY_REYNOLDS = 1e3  # raised from 10: the check measures what the model implies, not its validity
RUNAWAY_TURNS = 1e4  # raised from 100: 30 degrees turns the outer cylinder some 500 times in 5 s
# The co-rotating runaway's stiffest mode (-7e8/s at 1 s on 30 degrees, the closing gap) turns with the line of
# centres at Omega ~ 280 rad/s. With the Cartesian velocity Radau IIA's simplified Newton iteration then converged
# only on steps of ~1e-5 s (2e6 steps by 2.8 s of the 5 s); near contact the full model now carries the velocity
# in the frame of the line of centres (dynamics.equations.full), in which the compiled Radau IIA runs it.
RUNAWAY_METHOD = "radau"
SPIN_PLANE = ("kappa", "phi", "omega_a", "omega_b")


# ------------------------------------------------------------------ closed forms derived here

def _zeta(kappa, one_minus_kappa):
    return np.sqrt(one_minus_kappa * (1.0 + kappa))


# ------------------------------------------------------------------ figures 2 and 3, section 3

def rocking_run(mu_ratio: float = 1.0) -> Trajectory:
    """Figure 2's groups with ``mu_ratio``, sampled 40 times a rocking period down to the gap floor.

    rtol 1e-9 (atol the same) keeps phi within 1e-9 rad of a run at rtol 1e-11 (measured), against
    rocking amplitudes above 7e-4 rad to the end.
    """
    params = ReducedParams(FIG2.s, FIG2.upsilon, mu_ratio)
    period = 2.0 * math.pi / rocking_frequency(params.s, params.upsilon, mu_ratio)
    t_end = 1000.0  # the floor stops it first (about 730 tau)
    return simulate(params, Initial(*START), t_end, t_eval=np.arange(0.0, t_end, period / 40.0), rtol=1e-9,
                    limits=Limits(gap_floor=ROCKING_FLOOR))


def rocking_checks(traj: Trajectory, mu_ratio: float, full_set: bool) -> list[Check]:
    """Centre, frequency, closing rate, decay exponent and distance rolled of a rocking run.

    Fitted after t = 100 tau, where zeta < 0.01: the multiple scales' O(zeta)
    corrections are then below 1%.
    """
    s, ups = FIG2.s, FIG2.upsilon
    tag = f"figure 2 (mu_={mu_ratio:g})"
    phi_star = contact_equilibrium(s)
    c = traj.columns
    zeta = _zeta(c["kappa"], c["one_minus_kappa"])
    t_peak, amplitude = rocking_envelope(traj.t, c["phi"] - phi_star)
    late = t_peak > 100.0
    exponent = np.polyfit(np.log(np.interp(t_peak[late], traj.t, zeta)), np.log(amplitude[late]), 1)[0]
    checks = [
        absolute(f"{tag}: stopped by the gap-floor event (1 if so)", float(traj.event == "gap_floor"), 1.0,
                 0.0, f"{traj.message}: the inner cylinder reaches contact"),
        relative(f"{tag}: 1 - kappa where it stopped", c["one_minus_kappa"][-1], ROCKING_FLOOR, 1e-6,
                 "the event is located on the dense output"),
        relative(f"{tag}: decay exponent of the rocking envelope against zeta", exponent,
                 decay_exponent(mu_ratio), 0.05, "q of (3.10); 5% allows the O(zeta) corrections"),
    ]
    if not full_set:
        return checks
    periods = traj.t > traj.t[-1] - 10.0 * 2.0 * math.pi / rocking_frequency(s, ups, mu_ratio)
    i = np.searchsorted(traj.t, 100.0)
    closing = (1.0 / zeta[-1] - 1.0 / zeta[i]) / (traj.t[-1] - traj.t[i])
    j, k = np.searchsorted(traj.t, 300.0), np.searchsorted(traj.t, 700.0)
    per_log_t = (c["x_b"][k] - c["x_b"][j]) / math.log(traj.t[k] / traj.t[j])
    checks += [
        absolute(f"{tag}: mean of phi - phi* over the last 10 periods (rad)",
                 np.mean(c["phi"][periods] - phi_star), 0.0, 1e-3,
                 f"phi* = pi + asin(s) = {phi_star:.6f}; the remaining amplitude is {amplitude[-1]:.1e} rad"),
        relative(f"{tag}: rocking frequency after t = 100 tau", math.pi / np.mean(np.diff(t_peak[late])),
                 rocking_frequency(s, ups, mu_ratio), 0.01, "omega of (3.10); O(zeta) shift, zeta < 0.01"),
        relative(f"{tag}: growth rate of 1/zeta after t = 100 tau", closing, math.sqrt(1.0 - s * s), 0.01,
                 "(3.9): d(1/zeta)/dt = sqrt(1 - s^2); O(amplitude^2) corrections"),
        relative(f"{tag}: distance rolled per e-fold of t over [300, 700] tau", per_log_t,
                 3.0 * s / math.sqrt(1.0 - s * s), 0.03,
                 "slow_approach: X_b = (3 s / sqrt(1 - s^2)) ln t + const; the text's X_b ~ t^(1/6) "
                 "would grow this by 15% across the window"),
    ]
    return checks


def runaway_run() -> Trajectory:
    """Figure 3: (2.11) with s = 0.9 from rest, until the outer cylinder has turned 100 times."""
    return simulate(FIG3, Initial(*START), 1e4, limits=Limits(max_turns=100.0))


def runaway_checks(traj: Trajectory) -> list[Check]:
    """Omega_a and Omega_b grow at the rate s/((mu_ + 1/2) Upsilon) of (3.11).

    Over the non-uniform winding the mean of kappa sin(phi) in (2.11d) is
    O(1/Omega) ~ 1/t, which adds a ln(t) to Omega: fitted as r t + c ln t + d over
    the second half of the run, r carries only the O(1/Omega^2) remainder
    (measured 0.3% after 100 turns, where the plain slope is 3.5% low).
    """
    rate = runaway_spin_rate(FIG3.s, FIG3.upsilon, FIG3.mu_ratio)
    c = traj.columns
    late = traj.t >= 0.5 * traj.t[-1]
    t = traj.t[late]
    design = np.column_stack([t, np.log(t), np.ones_like(t)])
    checks = []
    for name in ("omega_a", "omega_b"):
        slope = np.linalg.lstsq(design, c[name][late], rcond=None)[0][0]
        checks.append(relative(f"figure 3: d{name}/dt in the runaway (fit r t + c ln t + d)", slope, rate, 0.01,
                               f"(3.11) s/((mu_ + 1/2) Upsilon); run stopped: {traj.message}"))
    # phi' = r t + c ln t + d integrates to the basis below
    design = np.column_stack([0.5 * t * t, t * np.log(t) - t, t, np.ones_like(t)])
    slope = np.linalg.lstsq(design, c["phi"][late], rcond=None)[0][0]
    checks.append(relative("figure 3: d(phi')/dt in the runaway (fit of phi, same form)", slope, rate, 0.01,
                           "(3.11): phi' ~ Omega_b, the inner cylinder is carried round"))
    return checks


def steady_rolling_checks(s_values=(0.1, 0.25, 0.5, 0.9, 0.99)) -> list[Check]:
    """(3.2) is a fixed point of (2.11) to rounding, and linearly unstable (section 3.1)."""
    checks = []
    for s in s_values:
        params = ReducedParams(s, FIG2.upsilon, FIG2.mu_ratio)
        eq = steady_rolling(s)
        y = initial_state(eq.kappa, eq.phi, eq.omega_a, eq.omega_b)
        # the terms of xi', eta' are O(1), those of the rates O(1/Upsilon)
        checks.append(at_most(f"steady rolling (3.2), s={s:g}: largest rate of change", np.max(np.abs(
            reduced_rhs(0.0, y, params)[:4])), 1e-14 * (1.0 + 1.0 / params.upsilon), "rounding"))
        growth = np.max(np.linalg.eigvals(reduced_jacobian(0.0, y, params)[:4, :4]).real)
        checks.append(at_least(f"steady rolling (3.2), s={s:g}: largest real part of the Jacobian's eigenvalues",
                               growth, 1e-6, "must be positive: the equilibrium is unstable (section 3.1)"))
    return checks


def sedimentation_check(kappa0: float = 0.3, t_end: float = 1e3) -> Check:
    """(3.3) on a level plane: the stretched radius grows linearly, so the integrator is exact up to rounding."""
    t = np.linspace(0.0, t_end, 101)
    traj = simulate(ReducedParams(0.0, 1.0, 1.0), Initial(kappa0, math.pi), t_end, t_eval=t,
                    limits=Limits(gap_floor=1e-12))
    error = np.max(np.abs(traj.columns["kappa"] - sedimentation(traj.t, kappa0)[0]))
    return at_most(f"sedimentation (3.3) from kappa0={kappa0:g}: max |kappa - exact| over {t_end:g} tau",
                   error, 1e-8, "linear in the stretched variable r: rounding only")


# ------------------------------------------------------------------ the full model

def _scaled(trajectory, t_tau) -> dict[str, np.ndarray]:
    """kappa, phi and the rotation rates times tau on the grid ``t_tau``."""
    c = trajectory.columns
    return {k: np.interp(t_tau, c["t_tau"], c[k] * (trajectory.tau if k.startswith("omega") else 1.0))
            for k in SPIN_PLANE}


def distinguished_limit(ratios=RATIOS) -> dict:
    """Max difference full - reduced over [0, 10] tau for each delta/a, per variable."""
    s, ups, mu = LIMIT_GROUPS
    t_tau = np.linspace(0.0, LIMIT_WINDOW, 401)
    ref = _scaled(simulate(ReducedParams(s, ups, mu), LIMIT_START, LIMIT_WINDOW, rtol=LIMIT_RTOL / 100), t_tau)
    diffs = {k: [] for k in SPIN_PLANE}
    for ratio in ratios:
        apparatus = Apparatus.from_groups(s, ups, mu, ratio)
        # a limit of the equations: the inertial guard, a statement about the fluid, is lifted
        run = simulate(apparatus, LIMIT_START, LIMIT_WINDOW * apparatus.tau, forces=kernel_model("closed-form"), rtol=LIMIT_RTOL,
                       limits=Limits(max_gap_reynolds=None))
        got = _scaled(run, t_tau)
        for k in SPIN_PLANE:
            diffs[k].append(float(np.max(np.abs(got[k] - ref[k]))))
    return {"ratios": list(ratios), "diffs": diffs,
            "max": [max(d[i] for d in diffs.values()) for i in range(len(ratios))]}


def limit_checks(limit: dict) -> list[Check]:
    ratios = np.log(limit["ratios"])
    slope = np.polyfit(ratios, np.log(limit["max"]), 1)[0]
    per_variable = ", ".join(f"{k} {np.polyfit(ratios, np.log(v), 1)[0]:.3f}" for k, v in limit["diffs"].items())
    return [absolute("full against reduced: log-log slope of the max difference against delta/a", slope, 1.0,
                     0.1, f"(s, Upsilon, mu_) = {LIMIT_GROUPS} over {LIMIT_WINDOW:g} tau; "
                     f"per variable: {per_variable}"),
            at_most(f"full against reduced: max difference / (delta/a) at delta/a = {limit['ratios'][-1]:g}",
                    limit["max"][-1] / limit["ratios"][-1], 3.0,
                    "kappa, phi (rad), Omega_a tau, Omega_b tau; an O(1) coefficient of the first-order term")]


def level_plane(ratios=(0.03, 0.01, 0.003), kappa0: float = 0.3) -> list[dict]:
    """The full model on a level plane from rest against (3.3): deviation over the inertial time."""
    out = []
    apparatuses = [(f"delta/a={r:g}", Apparatus.from_groups(0.0, 1.0, 2.0, r)) for r in ratios]
    for name, apparatus in [*apparatuses, ("steel preset", preset("steel", alpha=0.0))]:
        run = simulate(apparatus, Initial(kappa0, math.pi), 8 * apparatus.tau, forces=kernel_model("closed-form"), rtol=1e-10)
        t_i = inertial_time(apparatus)
        c = run.columns
        kappa_ref, omk_ref = sedimentation(c["t_tau"], kappa0)
        out.append({"name": name, "t_i": t_i, "t_tau": c["t_tau"], "deviation": kappa_ref - c["kappa"],
                    "lag": t_i * _zeta(kappa_ref, omk_ref) ** 6,
                    "swing": float(np.max(np.abs(c["phi"] - math.pi)))})
    return out


def level_plane_checks(runs: list[dict], kappa0: float = 0.3) -> list[Check]:
    zeta0 = math.sqrt(1.0 - kappa0**2)
    checks = []
    for r in runs[:-1]:
        checks.append(relative(f"level plane, {r['name']}: max |kappa - (3.3)| / (t_i/tau)",
                               np.max(np.abs(r["deviation"])) / r["t_i"], zeta0**6, 0.03,
                               f"lag t_i zeta^6, largest at the start: zeta0^6; t_i/tau = {r['t_i']:.2e}; "
                               "next order O(t_i/tau) with a logarithm"))
    steel = runs[-1]
    late = steel["t_tau"] >= 3.0 * steel["t_i"]
    checks.append(relative("level plane, steel preset: max |kappa - (3.3)| after 3 t_i",
                           np.max(np.abs(steel["deviation"][late])), np.max(steel["lag"][late]), steel["t_i"],
                           f"against the lag t_i zeta^6; first order in t_i/tau = {steel['t_i']:.2f} (the tolerance)"))
    checks.append(at_most("level plane: largest |phi - pi| of all runs (straight down, no swing)",
                          max(r["swing"] for r in runs), 0.0, "exact by symmetry"))
    return checks


def full_runaway(alpha_deg: float, t_end: float, start=Initial(0.5, 0.5)) -> dict:
    """The aluminium apparatus rolling away on a slope: fitted acceleration and film losses, late half."""
    apparatus = preset("aluminium", alpha=math.radians(alpha_deg))
    run = simulate(apparatus, start, t_end, forces=kernel_model("closed-form"), method=RUNAWAY_METHOD,
                   limits=Limits(max_gap_reynolds=RUNAWAY_REYNOLDS, max_turns=RUNAWAY_TURNS))
    c = run.columns
    t, x_b = c["t"], c["x_b"]
    late = t >= 0.5 * t_end
    acceleration = 2.0 * np.polyfit(t[late], x_b[late], 2)[0]
    energy = mechanical_energy(apparatus, c)
    i = np.argmax(late)
    work = apparatus.M * apparatus.g * math.sin(apparatus.alpha) * (x_b[-1] - x_b[i])
    reynolds = np.max(np.abs(c["omega_b"])) * apparatus.b * apparatus.delta / apparatus.nu
    return {"apparatus": apparatus, "run": run, "acceleration": float(acceleration),
            "lost_fraction": float((energy[i] - energy[-1]) / work), "reynolds": float(reynolds),
            "estimates": runaway_estimates(apparatus), "alpha_deg": alpha_deg}


def full_runaway_checks(steep: dict, paper_slope: dict) -> list[Check]:
    est = steep["estimates"]
    tag = f"aluminium at {steep['alpha_deg']:g} deg (s = {steep['apparatus'].s:.2f})"
    checks = [
        relative(f"{tag}: runaway acceleration against the co-rotating (1 - f) a_0", steep["acceleration"],
                 est.model, 1e-3, "quadratic fit to X_b over the second half; corrections O(g/(delta Omega^2)) "
                 "to f, a fraction of f = 0.6%"),
        relative(f"{tag}: share of the work of gravity lost in the film, second half", steep["lost_fraction"],
                 est.dissipated_fraction, 0.02, "f of the module docstring, approached from below as "
                 "g/(delta Omega^2) -> 0: 1.3% short over 2.5-5 s at 30 deg (10% short at 12 deg)"),
        at_most(f"{tag}: stopped only by t_end", 0.0 if steep["run"].status == "completed" else 1.0, 0.0,
                f"max_reynolds raised to {RUNAWAY_REYNOLDS:g} (reached {steep['reynolds']:.0f}): the check "
                "measures what the model implies beyond its Stokes-flow validity"),
    ]
    est = paper_slope["estimates"]
    a = paper_slope["acceleration"]
    tag = f"aluminium at {paper_slope['alpha_deg']:g} deg"
    # the other estimates differ from each other by a few per cent: reported, not judged
    for name, value, why in (("paper's (3.11) M g sin(alpha)/(M + m_b + m_a/2)", est.paper, "a = b, delta = 0"),
                             ("rigid body M g sin(alpha) b^2/(m_a a^2/2 + (M + m_b) b^2)", est.rigid,
                              "no m_eff delta^2, no film loss"),
                             ("observed 2 g sin(alpha)/3 (figure 6)", est.observed, "experiment")):
        checks.append(Finding(f"{tag}: runaway acceleration estimate, {name} (m/s^2)", value,
                              f"{why}; the model's is {a:.4g} m/s^2, {a / value - 1:+.1%}"))
    checks.append(relative(f"{tag}: runaway acceleration against the co-rotating (1 - f) a_0", a, est.model, 0.005,
                           "still approaching: g/(delta Omega^2) ~ 0.1 over the fit"))
    return checks


def regime_map(alpha_deg: float, kappas, phis, equations: str = "full", t_end: float = 6.0) -> np.ndarray:
    """Regime (1 runaway, 0 rocking or sedimenting, -1 transient) from rest on a (kappa0, phi0) grid.

    6 s is some seven rocking periods at contact; a runaway stops earlier, after
    20 turns of the outer cylinder. The Reynolds limit is lifted: the relative
    flow's Re* can pass 10 in the swing just after the release, which decides
    nothing about the regime.
    """
    apparatus = preset("aluminium", alpha=math.radians(alpha_deg))
    code = {"runaway": 1, "rocking": 0, "sedimenting": 0, "transient": -1}
    out = np.empty((len(kappas), len(phis)), dtype=int)
    for i, kappa0 in enumerate(kappas):
        for j, phi0 in enumerate(phis):
            run = simulate(apparatus, Initial(kappa0, phi0), t_end, equations=equations, forces=kernel_model("closed-form"),
                           limits=Limits(max_gap_reynolds=None, max_turns=20.0))
            out[i, j] = code[classify(run)[0]]
    return out


def regime_checks(maps: dict) -> list[Check]:
    checks = []
    for (alpha_deg, equations), grid in maps.items():
        apparatus = preset("aluminium", alpha=math.radians(alpha_deg))
        share = float(np.mean(grid == 1))
        rest = apparatus.s * (1.0 if equations == "reduced" else apparatus.b / apparatus.a) < 1.0
        tag = (f"aluminium at {alpha_deg:g} deg, {equations} model: share of {grid.size} starts from rest "
               "that run away")
        if rest:
            # a rest point exists, so the start selects: both outcomes must occur
            one = 1.0 / grid.size
            checks.append(at_most(f"{tag}, below 1: some rock", share, 1.0 - one,
                                  f"s = {apparatus.s:.3f}: a rest point exists"))
            checks.append(at_least(f"{tag}, above 0: some run away", share, one,
                                   f"s = {apparatus.s:.3f}: a rest point exists"))
        else:
            checks.append(absolute(tag, share, 1.0, 0.0,
                                   f"s b/a = {apparatus.s * apparatus.b / apparatus.a:.3f} > 1: no rest point at "
                                   f"contact above {math.degrees(critical_slope(apparatus)):.2f} deg, every start "
                                   "runs away"))
        checks.append(at_most(f"aluminium at {alpha_deg:g} deg, {equations} model: unclassified starts",
                              float(np.sum(grid == -1)), 0.0, "transient after 6 s"))
    return checks


def extremes(quick: bool) -> list[Check]:
    """The full model from kappa = 0 exactly at extreme groups (delta/a = 0.1, mu_ = 2): finite, with a reason.

    A runaway at small Upsilon turns thousands of times before the Reynolds
    limit, so each run is cut at 50 tau or after about 100 turns by (3.11),
    where the runaway limit (max_turns = 100) may stop it first.
    """
    cases = [("steel preset, 10 s", preset("steel"), 10.0)]
    for ups in ((1e-3, 1e3) if not quick else (1e-3,)):
        for s in (0.0, 0.999, 2.0):
            apparatus = Apparatus.from_groups(s, ups, 2.0, 0.1)
            t_tau = 50.0 if s == 0.0 else min(50.0, math.sqrt(4.0 * math.pi * 100.0 / runaway_spin_rate(s, ups, 2.0)))
            cases.append((f"s={s:g}, Upsilon={ups:g}, {t_tau:.3g} tau", apparatus, t_tau * apparatus.tau))
    checks = []
    for name, apparatus, t_end in cases:
        run = simulate(apparatus, Initial(0.0, 0.0), t_end, forces=kernel_model("closed-form"))
        bad = sum(int(np.count_nonzero(~np.isfinite(v))) for v in run.columns.values())
        clear = run.status == "completed" or (run.status == "stopped" and run.event in ("gap_floor", "reynolds", "runaway"))
        checks.append(absolute(f"full model from kappa0 = 0, {name}: non-finite values", bad, 0.0, 0.0,
                               f"{run.status}: {run.message}; regime {classify(run)[0]}"))
        checks.append(absolute(f"full model from kappa0 = 0, {name}: completed or stopped at a stated limit "
                               "(1 if so)", float(clear), 1.0, 0.0, run.message))
    return checks


# ------------------------------------------------------------------ figures

def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _path_panel(ax, kappa, phi, star=None):
    circle = np.linspace(0.0, 2.0 * math.pi, 200)
    ax.plot(np.sin(circle), np.cos(circle), "k", lw=0.5)
    ax.plot(kappa * np.sin(phi), kappa * np.cos(phi), lw=0.6)
    ax.plot(kappa[0] * math.sin(phi[0]), kappa[0] * math.cos(phi[0]), "o", ms=4, label="start")
    if star is not None:
        ax.plot(math.sin(star), math.cos(star), "*", ms=10, color="C3", label="phi* = pi + asin(s)")
    ax.set_aspect("equal")
    ax.set_xlabel("kappa sin(phi)")
    ax.set_ylabel("kappa cos(phi)  (up)")
    ax.legend(fontsize=7, loc="upper right")


def figure2(path, traj: Trajectory) -> None:
    """Panels of figure 2 with the multiple-scale laws (3.9) dashed."""
    plt = _plt()
    from numerics.files import save_figure

    c = traj.columns
    s = FIG2.s
    phi_star = contact_equilibrium(s)
    shown = traj.t <= 150.0
    t = traj.t[shown]
    zeta = _zeta(c["kappa"], c["one_minus_kappa"])
    i100 = np.searchsorted(traj.t, 100.0)
    law = slow_approach(traj.t[i100:] - traj.t[i100], zeta[i100], s, FIG2.mu_ratio)
    fig, axes = plt.subplots(2, 3, figsize=(12, 7))
    _path_panel(axes[0, 0], c["kappa"][shown], c["phi"][shown], phi_star)
    axes[0, 0].set_title("(a) path of the inner centre, t <= 150")
    axes[0, 1].plot(t, c["kappa"][shown], lw=0.8)
    axes[0, 1].set_ylabel("(b) kappa")
    axes[0, 2].plot(t, c["phi"][shown], lw=0.6)
    axes[0, 2].axhline(phi_star, ls="--", color="C3", lw=0.8)
    axes[0, 2].set_ylabel("(c) phi (rad)")
    axes[1, 0].plot(t, c["omega_a"][shown], lw=0.6, label="Omega_a")
    axes[1, 0].plot(t, c["omega_b"][shown], lw=0.6, label="Omega_b")
    axes[1, 0].set_ylabel("(d) rates x tau")
    axes[1, 0].legend(fontsize=7)
    axes[1, 1].plot(t, c["x_b"][shown], lw=0.8)
    axes[1, 1].set_ylabel("(e) X_b / b")
    ax = axes[1, 2]
    t_peak, amplitude = rocking_envelope(traj.t, c["phi"] - phi_star)
    ax.loglog(traj.t[1:], zeta[1:], lw=0.8, label="zeta")
    ax.loglog(traj.t[i100:], law.zeta, "k--", lw=0.8, label="(3.9)")
    ax.loglog(t_peak, amplitude, ".", ms=2, label="|phi - phi*| peaks")
    ax.loglog(traj.t[i100:], np.interp(traj.t[i100], t_peak, amplitude) * law.amplitude, "k:", lw=0.8,
              label="(zeta/zeta_100)^q")
    ax.set_xlabel("t / tau")
    ax.set_title("(f) approach to contact, to the gap floor", fontsize=9)
    ax.legend(fontsize=7)
    for a in (axes[0, 1], axes[0, 2], axes[1, 0], axes[1, 1]):
        a.set_xlabel("t / tau")
    fig.suptitle(f"Figure 2: reduced model, Upsilon = mu_ = 1, s = 1/4, from kappa0 = {START[0]}, "
                 f"phi0 = {START[1]} at rest", fontsize=10)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def figure3(path, traj: Trajectory) -> None:
    """Panels of figure 3 with the runaway (3.11) dashed."""
    plt = _plt()
    from numerics.files import save_figure

    c = traj.columns
    rate = runaway_spin_rate(FIG3.s, FIG3.upsilon, FIG3.mu_ratio)
    t = traj.t
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    _path_panel(axes[0, 0], c["kappa"], c["phi"])
    axes[0, 0].set_title("(a) path of the inner centre")
    axes[0, 1].plot(t, c["kappa"], lw=0.6)
    axes[0, 1].set_ylabel("(b) kappa")
    ax = axes[1, 0]
    ax.plot(t, c["phi"], lw=0.8, label="phi (rad)")
    ax.plot(t, c["x_b"], lw=0.8, label="X_b / b")
    ax.plot(t, 0.5 * rate * t**2, "k--", lw=0.8, label="(3.11): s t^2/(2 (mu_+1/2) Upsilon)")
    ax.set_ylabel("(c) phi and X_b")
    ax.legend(fontsize=7)
    ax = axes[1, 1]
    ax.plot(t, c["omega_a"], lw=0.6, label="Omega_a")
    ax.plot(t, c["omega_b"], lw=0.6, label="Omega_b")
    ax.plot(t, rate * t, "k--", lw=0.8, label="(3.11)")
    ax.set_ylabel("(d) rates x tau")
    ax.legend(fontsize=7)
    for a in (axes[0, 1], axes[1, 0], axes[1, 1]):
        a.set_xlabel("t / tau")
    fig.suptitle(f"Figure 3: reduced model, Upsilon = mu_ = 1, s = 0.9, from kappa0 = {START[0]}, "
                 f"phi0 = {START[1]} at rest", fontsize=10)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def limit_figure(path, limit: dict, level: list[dict]) -> None:
    plt = _plt()
    from numerics.files import save_figure

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.3))
    r = np.array(limit["ratios"])
    for k, v in limit["diffs"].items():
        ax.loglog(r, v, "o-", ms=4, label=k + (" x tau" if k.startswith("omega") else ""))
    ax.loglog(r, limit["max"][0] * r / r[0], "k--", lw=0.8, label="slope 1")
    ax.set_xlabel("delta / a")
    ax.set_ylabel(f"max |full - reduced| over {LIMIT_WINDOW:g} tau")
    ax.set_title(f"distinguished limit, (s, Upsilon, mu_) = {LIMIT_GROUPS}", fontsize=9)
    ax.legend(fontsize=7)
    for i, run in enumerate(level):
        t = run["t_tau"]
        bx.semilogx(t[1:] / run["t_i"], run["deviation"][1:] / run["t_i"], color=f"C{i}", lw=0.8, label=run["name"])
        bx.semilogx(t[1:] / run["t_i"], run["lag"][1:] / run["t_i"], color=f"C{i}", ls="--", lw=0.8)
    bx.set_xlabel("t / t_i")
    bx.set_ylabel("((3.3) - kappa) / (t_i / tau)")
    bx.set_title("level plane from rest: lag behind (3.3); dashed t_i zeta^6", fontsize=9)
    bx.legend(fontsize=7)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def runaway_figure(path, runs: list[dict]) -> None:
    """Acceleration per turn of the line of centres (same phase: the periodic parts cancel)."""
    plt = _plt()
    from numerics.files import save_figure

    fig, axes = plt.subplots(1, len(runs), figsize=(5.5 * len(runs), 4.2), squeeze=False)
    for ax, r in zip(axes[0], runs):
        c = r["run"].columns
        chi = c["chi"] - c["chi"][0]
        turns = np.arange(1, int(chi[-1] / (2.0 * math.pi)) + 1) * 2.0 * math.pi
        t_k = np.interp(turns, chi, c["t"])
        speed = np.diff(np.interp(t_k, c["t"], c["x_b"])) / np.diff(t_k)
        middle = 0.5 * (t_k[1:] + t_k[:-1])
        ax.plot(0.5 * (middle[1:] + middle[:-1]), np.diff(speed) / np.diff(middle), ".", ms=3, label="per turn")
        est = r["estimates"]
        for name, value, colour, style in (("paper (3.11)", est.paper, "C1", "--"),
                                           ("rigid body", est.rigid, "C2", "--"),
                                           ("observed 2 g sin(alpha)/3", est.observed, "C3", ":"),
                                           ("co-rotating a_0", est.lossless, "k", "--"),
                                           ("(1 - f) a_0", est.model, "k", "-")):
            ax.axhline(value, color=colour, ls=style, lw=0.8, label=f"{name}: {value:.4f}")
        ax.axhline(r["acceleration"], color="C0", lw=0.6, label=f"fit, second half: {r['acceleration']:.4f}")
        low = min(est.paper, r["acceleration"])
        ax.set_ylim(0.97 * low, 1.03 * max(est.rigid, est.observed))
        ax.set_xlabel("t (s)")
        ax.set_ylabel("d^2 X_b/dt^2 (m/s^2)")
        ax.set_title(f"aluminium, {r['alpha_deg']:g} deg: runaway of the full model", fontsize=9)
        ax.legend(fontsize=6)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


def regime_figure(path, maps: dict, kappas, phis) -> None:
    plt = _plt()
    from matplotlib.colors import ListedColormap

    from numerics.files import save_figure

    fig, axes = plt.subplots(1, len(maps), figsize=(4.2 * len(maps), 3.8), squeeze=False)
    cmap = ListedColormap(["0.6", "C0", "C3"])  # transient, rocking, runaway
    for ax, ((alpha_deg, equations), grid) in zip(axes[0], maps.items()):
        ax.pcolormesh(np.arange(len(phis) + 1), np.arange(len(kappas) + 1), grid, cmap=cmap, vmin=-1, vmax=1,
                      edgecolors="w", linewidth=0.5)
        ax.set_xticks(np.arange(len(phis)) + 0.5, [f"{p:.2f}" for p in phis], fontsize=6, rotation=90)
        ax.set_yticks(np.arange(len(kappas)) + 0.5, [f"{k:g}" for k in kappas], fontsize=7)
        ax.set_xlabel("phi0 (rad)")
        ax.set_ylabel("kappa0")
        apparatus = preset("aluminium", alpha=math.radians(alpha_deg))
        ax.set_title(f"{equations}, {alpha_deg:g} deg: s = {apparatus.s:.2f}, s b/a = "
                     f"{apparatus.s * apparatus.b / apparatus.a:.2f}", fontsize=8)
    fig.suptitle("aluminium apparatus from rest: runaway (red), rocking (blue), undecided (grey)", fontsize=9)
    fig.tight_layout()
    save_figure(path, fig, dpi=110)
    plt.close(fig)


# ------------------------------------------------------------------ the group

def run(outdir, quick: bool = False):
    """All equations-of-motion checks; returns (checks, figure file names, a markdown paragraph)."""
    started = time.perf_counter()
    rocking = rocking_run(1.0)
    checks = rocking_checks(rocking, 1.0, full_set=True)
    checks += rocking_checks(rocking_run(3.0), 3.0, full_set=not quick)
    runaway = runaway_run()
    checks += runaway_checks(runaway)
    checks += steady_rolling_checks((0.25, 0.9) if quick else (0.1, 0.25, 0.5, 0.9, 0.99))
    checks.append(sedimentation_check())
    limit = distinguished_limit(RATIOS[:3] if quick else RATIOS)
    checks += limit_checks(limit)
    level = level_plane((0.03, 0.01) if quick else (0.03, 0.01, 0.003))
    checks += level_plane_checks(level)
    steep = full_runaway(STEEP, 5.0)
    paper_slope = full_runaway(5.0, 4.0)
    checks += full_runaway_checks(steep, paper_slope)
    kappas = (0.5, 0.99) if quick else (0.0, 0.5, 0.9, 0.99, 0.999)
    phis = np.linspace(0.0, 2.0 * math.pi, 4 if quick else 12, endpoint=False)
    maps = {(5.0, "reduced"): regime_map(5.0, kappas, phis, "reduced"),
            (5.0, "full"): regime_map(5.0, kappas, phis),
            (4.0, "full"): regime_map(4.0, kappas, phis)}
    checks += regime_checks(maps)
    checks += extremes(quick)
    figures = []
    if not quick:
        figure2(outdir / "dynamics_figure2.png", rocking)
        figure3(outdir / "dynamics_figure3.png", runaway)
        limit_figure(outdir / "dynamics_limit.png", limit, level)
        runaway_figure(outdir / "dynamics_runaway.png", [steep, paper_slope])
        regime_figure(outdir / "dynamics_regimes.png", maps, kappas, phis)
        figures = ["dynamics_figure2.png", "dynamics_figure3.png", "dynamics_limit.png", "dynamics_runaway.png",
                   "dynamics_regimes.png"]
    return checks, figures, _paragraph(steep, paper_slope, maps, time.perf_counter() - started)


def _paragraph(steep: dict, paper_slope: dict, maps: dict, seconds: float) -> str:
    ap, est, a = paper_slope["apparatus"], paper_slope["estimates"], paper_slope["acceleration"]
    i_a = 0.5 * ap.m_a * ap.a**2
    big = (ap.M + ap.m_b) * ap.b**2
    uniform = ap.M * ap.g * math.sin(ap.alpha) * ap.b**2 / (i_a + big + ap.m_eff * ap.delta**2)  # with <I>
    full5 = maps[(5.0, "full")]
    return (
        f"Figures 2 and 3 are regenerated with the reduced model (2.11) from kappa0 = {START[0]}, "
        f"phi0 = {START[1]} rad at rest (the text does not give the initial position). Figure 2 rocks down to "
        f"contact about phi* = pi + asin(s) with the frequency, closing rate and envelope exponent of "
        "(3.9)-(3.10); the distance rolled grows as (3 s/sqrt(1 - s^2)) ln t, not as the text's t^(1/6). In "
        "figure 3 both rates grow at the slope of (3.11) once the O(1/Omega) mean of kappa sin(phi) is "
        "fitted out. The full model approaches (2.11) at first order in delta/a, and on a level plane it "
        "lags (3.3) by the local inertial time t_i zeta^3 (derived in `validation/dynamics_checks.py`).\n\n"
        f"Runaway of the full model, aluminium apparatus: at {paper_slope['alpha_deg']:g} degrees the "
        f"quadratic fit to X_b over the second half of a {paper_slope['run'].t[-1]:.0f} s run gives "
        f"{a:.4f} m/s^2, against the paper's (3.11) {est.paper:.4f}, the rigid body {est.rigid:.4f} and the "
        f"observed 2 g sin(alpha)/3 = {est.observed:.4f}. The estimates differ in the moment of inertia about "
        f"the contact point, over b^2: the paper takes m_a b^2/2 for the inner cylinder where it has "
        f"m_a a^2/2 ({0.5 * ap.m_a * (ap.b**2 - ap.a**2) / big:.1%} of (M + m_b) b^2 with a/b = "
        f"{ap.a / ap.b:.2f}); the rigid body leaves out the eccentric inner cylinder's m_eff delta^2 "
        f"({ap.m_eff * ap.delta**2 / (i_a + big):.1%}; m_eff = m_a + m''_a^2/m_f carries the added mass of the "
        f"fluid pushed round it), whose buoyancy-reduced weight m'_a also makes the turn non-uniform, "
        f"which raises the mean acceleration by {est.lossless / uniform - 1:.2%} (<sqrt(I)>^2 < <I>); "
        "and the co-rotation is not loss-free: the film shears as it carries the inner cylinder through "
        f"the speed changes within each turn, a fixed share f = {est.dissipated_fraction:.2%} of the work of "
        f"gravity, independent of slope and viscosity, because the gap closes as t^-3 while Omega grows as t. "
        f"The model's own asymptote (1 - f) a_0 is {est.model:.4f} at {paper_slope['alpha_deg']:g} degrees "
        f"and is met to {abs(steep['acceleration'] / steep['estimates'].model - 1):.1e} at {STEEP:g} degrees "
        f"(s = {steep['apparatus'].s:.2f}), where {steep['lost_fraction']:.2%} of the work was lost over the fit. "
        f"Both runs go past the Stokes-flow limit (max_reynolds raised to {RUNAWAY_REYNOLDS:g}, reached "
        f"{steep['reynolds']:.0f}): they measure what the model implies. The observed law is "
        f"{est.observed / a - 1:.1%} faster than the model, {est.observed / est.paper - 1:.1%} faster than "
        "(3.11).\n\n"
        f"Runaway or rocking at {paper_slope['alpha_deg']:g} degrees: in the full model the rest point at "
        f"contact needs M b sin(alpha) < m'_a delta, i.e. s b/a < 1, not s < 1; for the aluminium apparatus "
        f"that is alpha < {math.degrees(critical_slope(ap)):.2f} degrees. At 5 degrees (s = {ap.s:.2f}, "
        f"s b/a = {ap.s * ap.b / ap.a:.2f}) {np.mean(full5 == 1):.0%} of the starts from rest ran away, "
        f"where the reduced model with the same groups rocks from {np.mean(maps[(5.0, 'reduced')] == 0):.0%} "
        f"of them; at 4 degrees the full model rocks from {np.mean(maps[(4.0, 'full')] == 0):.0%}. The "
        "regime is dynamics.regime.classify over 6 s; a runaway is stopped after 20 turns of the outer "
        f"cylinder. The group ran in {seconds:.0f} s."
    )
