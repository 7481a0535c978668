"""Trajectories of the full model (2.1)-(2.4) and the reduced model (2.11), in one output form.

Both models go through :func:`dynamics.integrate.integrate`; the result is a
:class:`Trajectory` with SI columns (or, for a dimensionless reduced run without
an apparatus, lengths in delta and b, times and rates in tau) and the reason the
run ended.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from dynamics.contact import full as full_contact
from dynamics.contact import reduced as contact
from dynamics.contact import rough as rough_contact
from dynamics.contact.roughness import RoughContact
from dynamics.equations import full, reduced
from dynamics.equations.forces import ForceModel
from dynamics.equations.limits import (
    GAP_FLOOR,
    MAX_REYNOLDS,
    MAX_TURNS,
    gap_floor_event,
    reynolds_event,
)
from dynamics.initial import Initial
from dynamics.integrate import Integration, integrate

__all__ = ["Initial", "Trajectory", "simulate_contact", "simulate_full", "simulate_full_contact", "simulate_reduced"]

# contact phases as numbers in the trajectory table
PHASE_CODES = {contact.FREE: 0, contact.SLIDING: 1, contact.LOCKED: 2}


@dataclass
class Trajectory:
    """Columns of a run and how it ended.

    ``columns`` has t, t_tau, x_b, eps, chi, kappa, one_minus_kappa, phi,
    omega_a, omega_b (SI, or scaled when ``dimensionless``), and for a run with
    contact the phase (codes in :data:`PHASE_CODES`) and the scaled reaction
    c_eps and friction c_chi of (5.1)-(5.2). ``info`` carries what a table
    cannot, such as the list of contact switches.
    """

    columns: dict[str, np.ndarray]
    equations: str
    forces: str
    status: str
    reason: str
    event: str
    steps: int
    nfev: int
    njev: int
    wall_time_s: float
    tau: float
    dimensionless: bool
    method: str
    groups: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)

    @property
    def t(self) -> np.ndarray:
        return self.columns["t"]


def _result(run: Integration, columns, **info) -> Trajectory:
    return Trajectory(columns=columns, status=run.status, reason=run.reason, event=run.event,
                      steps=run.steps, nfev=run.nfev, njev=run.njev, wall_time_s=run.wall_time_s, **info)


def simulate_full(apparatus, force_model: ForceModel, initial: Initial, t_end: float, *,
                  rtol: float = 1e-8, method: str = "LSODA", gap_floor: float = GAP_FLOOR,
                  max_reynolds: float = MAX_REYNOLDS, progress: str | None = None) -> Trajectory:
    """The full dimensional model from ``initial`` (SI) over ``t_end`` seconds.

    Stops early, with the reason, when 1 - kappa falls to ``gap_floor`` or the
    gap Reynolds number max(|Omega_a| a, |Omega_b| b) delta / nu reaches
    ``max_reynolds``.
    """
    p = full.params_array(apparatus)
    model = full.model_arguments(force_model)
    typical = full.typical_scales(apparatus)
    y0 = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot,
                            initial.phi_dot, initial.omega_a, initial.omega_b)
    re_scale = apparatus.delta / apparatus.nu

    def one_minus_kappa(y):
        one_plus = 1.0 + y[0] ** 2 + y[1] ** 2
        return 1.0 / (one_plus * (1.0 + math.sqrt(1.0 - 1.0 / one_plus)))

    def reynolds_number(y):
        return re_scale * max(abs(y[4]) * apparatus.a, abs(y[5]) * apparatus.b)

    events = (gap_floor_event(one_minus_kappa, gap_floor), reynolds_event(reynolds_number, max_reynolds))
    run = integrate(lambda t, y: full.rhs(t, y, p, *model), y0, t_end,
                    jac=lambda t, y: full.jacobian(t, y, p, *model, typical),
                    rtol=rtol, atol=rtol * typical, method=method, events=events, progress=progress)
    obs = full.observables(apparatus, run.y)
    columns = {"t": run.t, "t_tau": run.t / apparatus.tau, **obs}
    return _result(run, columns, equations="full", forces=force_model.name, tau=apparatus.tau,
                   dimensionless=False, method=method, groups=_groups(apparatus))


def simulate_full_contact(apparatus, force_model: ForceModel, rough: contact.ContactParams, initial: Initial,
                          t_end: float, *, rtol: float = 1e-8, method: str = "LSODA",
                          max_reynolds: float = MAX_REYNOLDS, progress: str | None = None) -> Trajectory:
    """The full model with rough contact (:mod:`dynamics.contact.full`) over ``t_end`` seconds.

    ``rough`` carries kappa* and the paper's scaled friction angle psi; the
    physical friction coefficient is tan(psi_hat) = (delta/a) tan(psi) (C2).
    Columns as :func:`simulate_full` and, as :func:`simulate_contact`, the
    phase, C_e = N/(m'_a g) and C_x = -(a/delta) F/(m'_a g) of (5.1)-(5.2).
    """
    y0 = full.initial_state(apparatus, initial.kappa, initial.phi, initial.kappa_dot,
                            initial.phi_dot, initial.omega_a, initial.omega_b)
    scale = apparatus.delta / apparatus.nu / apparatus.tau  # gap Reynolds number per scaled rate
    rates = {contact.FREE: (4, 5)}

    def events(phase):
        i, j = rates.get(phase, (2, 3))
        reynolds = reynolds_event(lambda y: scale * max(abs(y[i]) * apparatus.a, abs(y[j]) * apparatus.b),
                                  max_reynolds, apparatus.tau)
        return (reynolds,)

    run = full_contact.simulate_full_contact(apparatus, force_model, rough, y0, t_end, rtol=rtol,
                                             method=method, extra_events=events, progress=progress)
    t = run["t"]
    columns = {"t": t, "t_tau": run["t_tau"], **{k: run[k] for k in ("x_b", "eps", "chi", "kappa",
                                                                     "one_minus_kappa", "phi", "omega_a",
                                                                     "omega_b")},
               "phase": np.array([PHASE_CODES[p] for p in run["phase"]], dtype=float),
               "c_eps": run["c_eps"], "c_chi": run["c_chi"]}
    status = {0: "completed", 1: "stopped"}.get(run["status"], run["stop_reason"])
    info = {"phase_codes": PHASE_CODES, "final_phase": str(run["phase"][-1]) if t.size else "",
            "switches": [{"t": sw.t, "from": sw.old, "to": sw.new} for sw in run["switches"]],
            "tan_friction": full_contact.friction_coefficient(apparatus, rough)}
    return Trajectory(columns=columns, equations="full", forces=force_model.name, status=status,
                      reason=run["message"] if run["status"] else f"reached t_end = {t_end:.6g} s",
                      event=run["stop_reason"] if run["status"] == 1 else "",
                      steps=run["steps"], nfev=run["nfev"], njev=run["njev"], wall_time_s=run["wall_time_s"],
                      tau=apparatus.tau, dimensionless=False, method=method, groups=_groups(apparatus), info=info)


def simulate_reduced(params: reduced.ReducedParams, initial: Initial, t_end_tau: float, *,
                     apparatus=None, rtol: float = 1e-8, method: str = "LSODA",
                     gap_floor: float = GAP_FLOOR, max_turns: float = MAX_TURNS,
                     progress: str | None = None) -> Trajectory:
    """The reduced model (2.11) from ``initial`` over ``t_end_tau`` units of tau.

    With an ``apparatus`` the initial rates are in 1/s and the output is SI;
    without, everything is scaled (times and rates in tau, eps in delta, X_b in b).
    kappa' and phi' are not free in (2.11): ``initial.kappa_dot`` and ``phi_dot``
    are not used. Stops as :func:`dynamics.equations.reduced.simulate_reduced` does.
    """
    tau = apparatus.tau if apparatus is not None else 1.0
    run = reduced.simulate_reduced(params, t_end_tau, initial.kappa, initial.phi, initial.omega_a * tau,
                                   initial.omega_b * tau, rtol=rtol, atol=rtol, method=method,
                                   gap_floor=gap_floor, max_turns=max_turns, progress=progress)
    return _from_reduced(run, params, apparatus, method, {})


def simulate_contact(params: reduced.ReducedParams, rough: contact.ContactParams | RoughContact,
                     initial: Initial, t_end_tau: float, *, apparatus=None, rtol: float = 1e-8,
                     method: str = "LSODA", max_turns: float = MAX_TURNS,
                     progress: str | None = None) -> Trajectory:
    """The reduced model with rough contact (section 5); output as :func:`simulate_reduced`.

    ``rough`` is a uniform minimum gap kappa* (:class:`dynamics.contact.reduced.ContactParams`)
    or one that varies with the orientation of both surfaces
    (:class:`dynamics.contact.roughness.RoughContact`), whose material angles are added as columns.
    """
    tau = apparatus.tau if apparatus is not None else 1.0
    simulate = (rough_contact.simulate_rough_contact if isinstance(rough, RoughContact)
                else contact.simulate_contact)
    run = simulate(params, rough, t_end_tau, initial.kappa, initial.phi, initial.omega_a * tau,
                   initial.omega_b * tau, rtol=rtol, atol=rtol, method=method, max_turns=max_turns,
                   progress=progress)
    extra = {"phase": np.array([PHASE_CODES[p] for p in run.phase], dtype=float),
             "c_eps": run.c_eps, "c_chi": run.c_chi}
    if isinstance(run, rough_contact.RoughTrajectory):
        extra.update(theta_a=run.theta_a, theta_b=run.theta_b)
    info = {"phase_codes": PHASE_CODES, "final_phase": str(run.phase[-1]) if run.phase.size else "",
            "switches": [{"t": sw.t * tau, "from": sw.old, "to": sw.new} for sw in run.switches]}
    trajectory = _from_reduced(run, params, apparatus, method, extra)
    trajectory.info.update(info)
    return trajectory


def _from_reduced(run, params, apparatus, method: str, extra: dict) -> Trajectory:
    """A :class:`Trajectory` from a reduced-model run (times in tau), in SI when there is an apparatus."""
    if apparatus is not None:
        tau, delta, b, alpha = apparatus.tau, apparatus.delta, apparatus.b, apparatus.alpha
        groups = _groups(apparatus)
    else:
        tau, delta, b, alpha = 1.0, 1.0, 1.0, 0.0
        groups = {"s": params.s, "upsilon": params.upsilon, "mu": params.mu_ratio}
    columns = {"t": run.t * tau, "t_tau": run.t, "kappa": run.kappa, "one_minus_kappa": run.one_minus_kappa,
               "eps": run.kappa * delta, "chi": run.phi - alpha, "phi": run.phi, "omega_a": run.omega_a / tau,
               "omega_b": run.omega_b / tau, "x_b": run.x_b * b, **extra}
    status = {0: "completed", 1: "stopped"}.get(run.status, run.stop_reason)
    return Trajectory(columns=columns, equations="reduced", forces="closed-form", status=status,
                      reason=run.message, event=run.stop_reason if run.status == 1 else "",
                      steps=run.steps, nfev=run.nfev, njev=run.njev, wall_time_s=run.wall_time_s,
                      tau=tau, dimensionless=apparatus is None, method=method, groups=groups)


def _groups(apparatus) -> dict:
    return {"s": apparatus.s, "upsilon": apparatus.upsilon, "mu": apparatus.mu_ratio,
            "delta_over_a": apparatus.delta_over_a}
