"""One simulation API for every model: a system, an initial state and a duration in, a :class:`Trajectory` out.

:func:`simulate` runs the full equations (2.1)-(2.4) with any force model, or the
reduced equations (2.11), each with or without rough contact (section 5), with
the compiled Radau IIA integrator (:mod:`dynamics.engine`) or one of scipy's
solvers as a cross-check. The result is the same :class:`Trajectory` whatever
ran, after scipy's ``OdeResult``: the columns, ``status`` and ``message``,
``success``, the events along the way, and the counts.

Units. With an :class:`~dynamics.apparatus.Apparatus` everything is SI: the
initial rates in rad/s, ``t_end`` and ``output_interval`` in seconds, the columns
in s, m, rad, rad/s. With :class:`~dynamics.equations.reduced.ReducedParams`
alone (the reduced model without a device, as the paper's figures use), times
and rates are in tau, eps in delta and X_b in b (``dimensionless``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from dynamics.apparatus import Apparatus
from dynamics.contact import reduced as reduced_contact
from dynamics.contact.hybrid import Phase, run_phases
from dynamics.contact.reduced import FREE, LOCKED, SLIDING, ContactParams
from dynamics.engine import END, EVENT, INTERRUPTED, SAMPLE, START, STEP
from dynamics.equations import full, reduced
from dynamics.equations.forces import CAVITATING, ForceModel, force_model
from dynamics.equations.limits import (LIMIT_EVENTS, MIN_GAP_FLOOR_FULL, Limits, estimated_force_error,
                                       inertia_report, limit_message, reduced_reynolds)
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.integrate import METHODS, integrate
from dynamics.regime import classify
from lubrication.geometry import check_range

__all__ = ["MAX_ROWS", "MAX_STEPS", "PHASE_CODES", "Initial", "Trajectory", "simulate"]

#: Contact phases as numbers in the trajectory table.
PHASE_CODES = {FREE: 0, SLIDING: 1, LOCKED: 2}

_ROW_NAMES = ((START, "start"), (STEP, "step"), (SAMPLE, "sample"), (EVENT, "event"), (END, "end"))


@dataclass
class Trajectory:
    """A run of any model: its columns and how it ended.

    Attributes
    ----------
    columns : dict of ndarray
        t, t_tau, x_b, eps, chi, kappa, one_minus_kappa, phi, omega_a, omega_b,
        kappa_dot, phi_dot (SI, or scaled when :attr:`dimensionless`); with contact also the phase
        (:data:`PHASE_CODES`) and the scaled reaction c_eps and friction c_chi
        of (5.1)-(5.2). phi is continuous (unwrapped) in every output mode.
    rows : ndarray of str
        What each row is: "start", "step", "sample", "event:<name>", "end"
        (joined with "+" when a row is several).
    equations, forces, method : str
    status : str
        "completed" (reached t_end), "stopped" (a limit or a runaway stopped
        it: :attr:`event` names it), "failed" or "interrupted".
    message : str
        Why the run ended, with units.
    event : str
        The event that stopped the run ("" if none).
    events : list of dict
        What happened along the way: contact switches ("touch", "lift",
        "stick", "slip") and limits gone past with ``on_invalid = "warn"``,
        each ``{"name", "t"}`` (t in the run's time unit).
    steps, nfev, njev, nlu : int
        Accepted steps, right-hand side and Jacobian evaluations, LU decompositions.
    wall_time_s, tau : float
    dimensionless : bool
    groups : dict
        s, upsilon, mu (and delta_over_a with an apparatus).
    regime : str
        The motion the run settled into (:func:`dynamics.regime.classify`),
        judged on every integrator step whatever rows were output.
    evidence : dict
        The numbers that decided the regime.
    info : dict
        What a table cannot hold (contact switches, the chosen model, the
        estimated inertial error, ...).
    """

    columns: dict
    rows: np.ndarray
    equations: str
    forces: str
    method: str
    status: str
    message: str
    event: str
    events: list
    steps: int
    nfev: int
    njev: int
    nlu: int
    wall_time_s: float
    tau: float
    dimensionless: bool
    groups: dict = field(default_factory=dict)
    regime: str = ""
    evidence: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)

    @property
    def t(self) -> np.ndarray:
        return self.columns["t"]

    @property
    def success(self) -> bool:
        """True when the run reached t_end or stopped at an event it was told to stop at."""
        return self.status in ("completed", "stopped")


def simulate(system: Apparatus | ReducedParams, initial: Initial, t_end: float, *, equations: str | None = None,
             forces: ForceModel | str = "closed-form", contact=None, limits: Limits = Limits(),
             method: str = "radau", rtol: float = 1e-8, output_interval: float | None = None, t_eval=None,
             max_steps: int = 2_000_000, progress=None, frame_terms: str = "paper") -> Trajectory:
    """Integrate a model of the snail cylinder from ``initial`` over ``t_end``.

    Parameters
    ----------
    system : Apparatus or ReducedParams
        The device (SI), or the groups of the reduced model alone (dimensionless).
    initial : Initial
        Rates in 1/s with an apparatus, in 1/tau without. kappa' and phi' are
        not free in (2.11) and must be 0 for the reduced equations.
    t_end : float
        Duration: s with an apparatus, tau without.
    equations : {"full", "reduced"}, optional
        Default "full" for an apparatus, "reduced" for groups.
    forces : ForceModel or str
        The full equations' force model (:func:`dynamics.equations.forces.force_model`);
        the reduced equations have the closed forms built in.
    contact : ContactParams or RoughContact, optional
        Rough contact (section 5); a minimum gap that varies along the surfaces
        (:class:`dynamics.contact.roughness.RoughContact`) in the reduced equations only.
    limits : Limits
        Validity limits and what to do at them (:mod:`dynamics.equations.limits`).
    method : {"radau", "Radau", "BDF", "LSODA"}
        The compiled Radau IIA integrator, or one of scipy's (:mod:`dynamics.integrate`).
    rtol : float
        Relative tolerance, in [100 eps, 0.1].
    output_interval : float, optional
        Output rows at 0, dt, 2 dt, ... from the dense output (and at every
        event); by default one row per integrator step. The regime and the
        inertia diagnostics are judged on every step either way.
    t_eval : array_like, optional
        Output rows at these increasing times in [0, t_end] instead (and at every event).
    max_steps : int
        Accepted steps after which the run stops unfinished, in [1, :data:`MAX_STEPS`].
    progress : callable, optional
        ``progress(t)`` is called now and then with the time reached.
    frame_terms : {"paper", "quasi-steady"}
        The full equations' treatment of the fluid turning with the line of
        centres: (2.1)-(2.2) as printed, or with m'_a on the centripetal and
        Coriolis terms (:func:`dynamics.equations.full.frame_force`).

    Returns
    -------
    Trajectory

    Raises
    ------
    ValueError
        Naming the parameter and its allowed range, for inputs no model can run.
    """
    dimensionless = isinstance(system, ReducedParams)
    if not dimensionless and not isinstance(system, Apparatus):
        msg = f"system must be an Apparatus or ReducedParams, got {type(system).__name__}"
        raise TypeError(msg)
    if not isinstance(initial, Initial):
        msg = f"initial must be an Initial, got {type(initial).__name__}"
        raise TypeError(msg)
    unit = "tau" if dimensionless else "s"
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True, unit=unit)
    equations = equations or ("reduced" if dimensionless else "full")
    if equations not in ("full", "reduced"):
        msg = f"equations must be 'full' or 'reduced', got {equations!r}"
        raise ValueError(msg)
    if dimensionless and equations == "full":
        msg = "the full equations need a physical apparatus: pass an Apparatus (Apparatus.from_groups builds one)"
        raise ValueError(msg)
    if method not in METHODS:
        msg = f"method must be one of {', '.join(METHODS)}, got {method!r}"
        raise ValueError(msg)
    rtol = check_range("rtol", rtol, 100 * np.finfo(float).eps, 0.1, high_open=False)
    if isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer)) or not 1 <= max_steps <= MAX_STEPS:
        msg = f"max_steps must be an integer in [1, {MAX_STEPS:g}], got {max_steps!r}"
        raise ValueError(msg)
    if progress is not None and not callable(progress):
        msg = f"progress must be a function of the time reached, or None, got {progress!r}"
        raise TypeError(msg)
    if output_interval is not None:
        if t_eval is not None:
            msg = "give output_interval or t_eval, not both"
            raise ValueError(msg)
        output_interval = check_range("output_interval", output_interval, 0.0, t_end, low_open=True,
                                      high_open=False, unit=unit)
        count = math.floor(t_end / output_interval * (1.0 + 1e-12))
        if count >= MAX_ROWS:
            msg = (f"output_interval = {output_interval:g} {unit} asks for {count + 1:.3g} rows over t_end = "
                   f"{t_end:g} {unit}, more than {MAX_ROWS:g}: lengthen the interval")
            raise ValueError(msg)
        t_eval = output_interval * np.arange(count + 1)
    if t_eval is not None:
        try:
            t_eval = np.asarray(t_eval, dtype=float)
        except (TypeError, ValueError) as err:
            msg = f"t_eval must be an array of times in [0, t_end] = [0, {t_end:g}] {unit}, got {t_eval!r}"
            raise ValueError(msg) from err
        if t_eval.ndim != 1 or t_eval.size == 0 or not np.all(np.isfinite(t_eval)) or np.any(np.diff(t_eval) <= 0) \
                or t_eval[0] < 0 or t_eval[-1] > t_end or t_eval.size > MAX_ROWS:
            msg = (f"t_eval must be a non-empty increasing array of at most {MAX_ROWS:g} finite times in "
                   f"[0, t_end] = [0, {t_end:g}] {unit}")
            raise ValueError(msg)
    if not isinstance(limits, Limits):
        msg = f"limits must be a Limits, got {type(limits).__name__}"
        raise TypeError(msg)
    _check_start(initial, limits, contact, equations, method)
    if frame_terms not in full.FRAME_TERMS:
        msg = f"frame_terms must be one of {', '.join(full.FRAME_TERMS)}, got {frame_terms!r}"
        raise ValueError(msg)
    if frame_terms != "paper" and equations == "reduced":
        msg = "frame_terms applies to the full equations; the reduced equations (2.11) drop these O(delta/a) terms"
        raise ValueError(msg)
    run = _Run(system, dimensionless, t_end, limits, method, rtol, t_eval, max_steps, progress)
    run.frame_terms = frame_terms
    start = time.perf_counter()
    if equations == "reduced":
        if initial.kappa_dot != 0.0 or initial.phi_dot != 0.0:
            msg = ("initial.kappa_dot and initial.phi_dot must be 0 for the reduced equations, where (2.11a-b) "
                   f"fix kappa' and phi' from the state; got {initial.kappa_dot!r} and {initial.phi_dot!r}")
            raise ValueError(msg)
        trajectory = run.reduced(initial, contact)
    else:
        model = forces if isinstance(forces, ForceModel) else force_model(forces)
        trajectory = run.full(initial, model, contact)
        trajectory.info["frame_terms"] = frame_terms
    trajectory.wall_time_s = time.perf_counter() - start
    return trajectory


#: Most accepted steps a run may take: every step is kept in memory (about 300 bytes a step at the
#: peak, with its columns), so ten million steps need about 3 GB.
MAX_STEPS = 10_000_000
#: Most rows a run may be asked for at given times (output_interval, t_eval): about 1 GB at the peak.
MAX_ROWS = 2_000_000

#: 1 - kappa0 below which the full equations are not run with scipy's LSODA (measured: it stalls there).
LSODA_NEAR_CONTACT = 1e-3


def _check_start(initial: Initial, limits: Limits, contact, equations: str, method: str) -> None:
    """Refuse a start the run would reject at t = 0, or that its integrator cannot follow, naming the value
    and the reason.

    LSODA, a cross-check, stalls in the full equations released near contact: from the default scene's
    angle at 1 - kappa0 = 1e-4 and 1e-5 it took 200,000 steps for 3 s and 1.8 s (10 s from 1e-2 in 0.2 s),
    and from 1e-6 it failed outright, while the compiled Radau IIA and scipy's BDF and Radau ran.
    """
    if method == "LSODA" and equations == "full" and contact is None and initial.gap < LSODA_NEAR_CONTACT:
        msg = (f"method = 'LSODA' cannot follow the full equations released within {LSODA_NEAR_CONTACT:g} of "
               f"contact (initial 1 - kappa = {initial.gap:.3g}): it stalls or fails there; use method = "
               "'radau' (the compiled Radau IIA, the default) or 'BDF'")
        raise ValueError(msg)
    one_minus = initial.gap
    if contact is None and equations == "full" and limits.gap_floor < MIN_GAP_FLOOR_FULL:
        msg = (f"run.gap_floor must be in [{MIN_GAP_FLOOR_FULL:g}, 1) for the full equations, which cannot follow "
               f"the squeeze film closer to contact in double precision; got {limits.gap_floor:g}")
        raise ValueError(msg)
    if contact is None and one_minus <= limits.gap_floor:
        msg = (f"initial.kappa must leave 1 - kappa above the gap floor {limits.gap_floor:g} (the run would stop "
               f"at once), got 1 - kappa = {one_minus:.3g}; lower initial.kappa or the gap floor")
        raise ValueError(msg)
    if isinstance(contact, ContactParams) and initial.kappa > contact.kappa_star:
        msg = (f"initial.kappa must be in [0, kappa_star] = [0, {contact.kappa_star:.12g}]: the asperities touch at "
               f"kappa_star; got {initial.kappa!r}")
        raise ValueError(msg)
    if contact is not None and not isinstance(contact, ContactParams) and equations == "full":
        msg = ("a minimum gap that varies along the surfaces is modelled in the reduced equations only; use "
               "equations='reduced' or a uniform ContactParams")
        raise ValueError(msg)


class _FreeFull:
    """The free full model as a hybrid run: Cartesian velocity away from contact, polar near it.

    :mod:`dynamics.equations.full` explains why (the Newton iteration near
    contact) and where (|u| above POLAR_ABOVE, back below CARTESIAN_BELOW); a
    change of variables is a phase that continues the motion
    (:class:`dynamics.contact.hybrid.Phase`). A cavitating film stays in the
    Cartesian velocity (``polar=False``): its forces are only piecewise smooth,
    and at a kink of the Swift-Stieber film (steel, 1 degree, 1 atm below the
    bubble, 1 - kappa = 1.2e-4) the Newton iterations of Radau IIA and of BDF
    both failed in the polar velocity, where the Cartesian one runs through.
    """

    def __init__(self, apparatus, args, functions: full.ModelFunctions, stops: int, rtol: float, polar: bool = True):
        self.ap, self.args, self.f, self.polar = apparatus, args, functions, polar
        typical = args[2]
        self.atol = rtol * typical
        # q_r and q_t are rates of |u|: 1/tau for the size of their absolute tolerance
        self.polar_atol = rtol * np.array([*typical[:2], 1.0 / apparatus.tau, 1.0 / apparatus.tau, *typical[4:]])
        self.terminal = (stops, stops, 1, 0, 0, 1)

    def phase(self, y) -> Phase:
        """The first phase, from state ``y`` of :func:`dynamics.equations.full.rhs`, in the variables its |u| calls for."""
        if self.polar and math.hypot(y[0], y[1]) > full.POLAR_ABOVE:
            return self._polar(full.to_polar(self.ap, y))
        return self._cartesian(np.asarray(y, float))

    def _cartesian(self, y, continues: bool = False) -> Phase:
        if not self.polar:
            return Phase("free", self.f.rhs, self.f.jacobian, full.events, self.args, y, full.EVENT_NAMES,
                         self.terminal[:5], (-1, -1, -1, 0, 1), self.atol, extra={"polar": False})
        return Phase("free", self.f.rhs, self.f.jacobian, full.cartesian_events, self.args, y,
                     full.CARTESIAN_EVENT_NAMES, self.terminal, (-1, -1, -1, 0, 1, 1), self.atol, continues=continues,
                     extra={"polar": False})

    def _polar(self, y, continues: bool = False) -> Phase:
        return Phase("free", self.f.polar_rhs, self.f.polar_jacobian, full.polar_events, self.args, y,
                     full.POLAR_EVENT_NAMES, self.terminal, (-1, -1, -1, 0, 1, -1), self.polar_atol,
                     continues=continues, extra={"polar": True})

    def transition(self, phase: Phase, reason: str, t: float, end, phi: float) -> Phase:
        if reason == "to_polar":
            return self._polar(full.to_polar(self.ap, end), continues=True)
        return self._cartesian(full.to_cartesian(self.ap, end), continues=True)

    def columns(self, phase: Phase, t, y, kind) -> dict:
        """Scaled columns of one phase's rows (t in tau, rates in 1/tau, X_b in b)."""
        ap, tau = self.ap, self.ap.tau
        observe = full.polar_observables if phase.extra["polar"] else full.observables
        obs = observe(ap, y, phase.extra["phi0"])
        return {"kappa": obs["kappa"], "one_minus_kappa": obs["one_minus_kappa"], "phi": obs["phi"],
                "kappa_dot": obs["kappa_dot"] * tau, "phi_dot": obs["phi_dot"] * tau, "omega_a": obs["omega_a"] * tau,
                "omega_b": obs["omega_b"] * tau, "x_b": obs["x_b"] / ap.b}


def _check_reynolds_at_start(g: np.ndarray, limits: Limits) -> None:
    """Refuse initial rates that put the run past the Reynolds limit at t = 0 (event values ``g``:
    the Reynolds event is the second, max_gap_reynolds - Re*), unless the limits only warn."""
    if limits.stops and g[1] < 0.0:
        msg = (f"initial.omega_a, initial.omega_b and initial.phi_dot give a gap Reynolds number "
               f"Re* = {limits.reynolds - g[1]:.4g} at t = 0, above run.max_gap_reynolds = {limits.reynolds:g}: "
               "quasi-steady Stokes forces do not hold there; lower the initial rates, raise "
               "max_gap_reynolds, or set on_invalid = 'warn'")
        raise ValueError(msg)


class _Run:
    """The settings every model's run shares, and the conversion of its rows to a Trajectory."""

    def __init__(self, system, dimensionless, t_end, limits, method, rtol, t_eval, max_steps, progress):
        self.system, self.dimensionless, self.t_end = system, dimensionless, t_end
        self.limits, self.method, self.rtol = limits, method, rtol
        self.max_steps, self.progress = max_steps, progress
        self.tau = 1.0 if dimensionless else system.tau
        self.unit = "tau" if dimensionless else "s"
        self.t_eval = t_eval
        self.inertia_corrected = False  # forces with the first inertial correction (full equations)

    # -- the models -----------------------------------------------------------------------

    def reduced(self, initial: Initial, contact) -> Trajectory:
        params = self.system if self.dimensionless else self.system.reduced_params
        tau = self.tau
        t_end_tau = self.t_end / tau
        t_eval = None if self.t_eval is None else self.t_eval / tau
        progress = None if self.progress is None else (lambda t: self.progress(t * tau))
        rates = (initial.omega_a * tau, initial.omega_b * tau)
        if contact is not None:
            from dynamics.contact.roughness import RoughContact

            runner = reduced_contact.run_contact
            if isinstance(contact, RoughContact):
                from dynamics.contact.rough import run_rough_contact as runner
            fields = runner(params, contact, t_end_tau, initial.kappa, initial.phi, *rates, limits=self.limits,
                            method=self.method, rtol=self.rtol, t_eval=t_eval, steps=True,
                            max_steps=self.max_steps, progress=progress)
            return self._contact_trajectory(fields, "reduced", "closed-form", params)
        per_rate = (0.0, 0.0)
        if not self.dimensionless:
            ap = self.system
            per_rate = (ap.delta**2 / (ap.nu * tau), ap.b * ap.delta**2 / (ap.a * ap.nu * tau))
        limits = self.limits
        args = reduced.run_args(params, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                                reynolds_per_rate=per_rate, x_b_limit=2.0 * math.pi * limits.max_turns)
        y0 = reduced.initial_state(initial.kappa, initial.phi, *rates, one_minus_kappa0=initial.one_minus_kappa)
        _check_reynolds_at_start(reduced.events(0.0, y0, args), limits)
        stops = int(limits.stops)
        run = integrate(reduced.rhs, reduced.jacobian, (0.0, t_end_tau), y0, args=args, method=self.method,
                        rtol=self.rtol, atol=self.rtol, events=reduced.events, terminal=(stops, stops, 1, 0, 0),
                        direction=(-1, -1, -1, 0, 1), t_eval=t_eval, steps=True, max_steps=self.max_steps,
                        progress=progress)
        cols = reduced.columns(run.y, initial.phi, args)
        fields = {"t": run.t, "kind": run.kind, "event_names": _names(run.event, reduced.EVENT_NAMES), **cols,
                  "stop": reduced.EVENT_NAMES[run.stop_event] if run.stop_event >= 0 else "",
                  "code": run.code, "status_code": run.status, "message": run.message,
                  "steps": run.steps, "nfev": run.nfev, "njev": run.njev, "nlu": run.nlu}
        return self._trajectory(fields, "reduced", "closed-form", params)

    def full(self, initial: Initial, model: ForceModel, contact) -> Trajectory:
        ap = self.system
        self.inertia_corrected = model.inertia[0] > 0.0
        if contact is not None:
            from dynamics.contact import full as full_contact

            fields = full_contact.run_full_contact(ap, model, contact, initial, self.t_end, limits=self.limits,
                                                   method=self.method, rtol=self.rtol, t_eval=self.t_eval, steps=True,
                                                   max_steps=self.max_steps, progress=self.progress,
                                                   frame_terms=self.frame_terms)
            return self._contact_trajectory(fields, "full", model.name, ap.reduced_params)
        limits = self.limits
        args = full.run_args(ap, model, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                             max_turns=limits.max_turns, frame_terms=self.frame_terms)
        y0 = full.initial_state(ap, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                                initial.omega_a, initial.omega_b, one_minus_kappa=initial.gap)
        _check_reynolds_at_start(full.events(0.0, y0, args), limits)
        free = _FreeFull(ap, args, full.model_functions(model.kind), int(limits.stops), self.rtol,
                         polar=model.kind != CAVITATING)
        fields = run_phases(free.phase(y0), free.transition, free.columns, self.t_end, phi0=initial.phi,
                            method=self.method, rtol=self.rtol, t_eval=self.t_eval, steps=True,
                            max_steps=self.max_steps, progress=self.progress)
        del fields["phase"]  # one free phase in two sets of variables, no contact
        fields = dict(fields, t=fields["t"] / self.tau, stop=fields["stop_event"], status_code=fields["status"])
        return self._trajectory(fields, "full", model.name, ap.reduced_params)

    # -- rows to a Trajectory ---------------------------------------------------------------

    def _contact_trajectory(self, fields: dict, equations: str, forces: str, params) -> Trajectory:
        fields = dict(fields, stop=fields["stop_event"], status_code=fields["status"])
        trajectory = self._trajectory(fields, equations, forces, params)
        trajectory.info.update(phase_codes=PHASE_CODES, final_phase=str(fields["phase"][-1]),
                               switches=[{"t": sw.t * self.tau, "from": sw.old, "to": sw.new}
                                         for sw in fields["switches"]])
        return trajectory

    @staticmethod
    def _keep(fields: dict) -> np.ndarray:
        """Rows to keep: not the crossings of the vertical (they keep phi continuous) nor the changes of
        variables of the free full model, which are no rows a user asked for."""
        kind, names = fields["kind"], fields["event_names"]
        return ~(((kind & EVENT) != 0) & np.isin(names, _HIDDEN_EVENTS) & ((kind & ~EVENT) == 0))

    def _trajectory(self, fields: dict, equations: str, forces: str, params) -> Trajectory:
        """Columns in the output units from scaled rows (t in tau, rates in 1/tau, X_b in b).

        The regime and the inertia diagnostics are taken over every step; with
        requested output times, the rows that are only steps are then dropped.
        """
        tau = self.tau
        kind, names = fields["kind"], fields["event_names"]
        keep = self._keep(fields)
        if self.dimensionless:
            delta, b, alpha = 1.0, 1.0, 0.0
        else:
            ap = self.system
            delta, b, alpha = ap.delta, ap.b, ap.alpha
        t_tau = np.asarray(fields["t"], dtype=float)[keep]
        kappa = fields["kappa"][keep]
        phi = fields["phi"][keep]
        columns = {"t": t_tau * tau, "t_tau": t_tau, "x_b": fields["x_b"][keep] * b, "eps": kappa * delta,
                   "chi": phi - alpha, "kappa": kappa, "one_minus_kappa": fields["one_minus_kappa"][keep],
                   "phi": phi, "omega_a": fields["omega_a"][keep] / tau, "omega_b": fields["omega_b"][keep] / tau,
                   "kappa_dot": fields["kappa_dot"][keep] / tau, "phi_dot": fields["phi_dot"][keep] / tau}
        if "phase" in fields:
            columns["phase"] = np.array([PHASE_CODES[p] for p in fields["phase"][keep]], dtype=float)
            for name in ("c_eps", "c_chi", "theta_a", "theta_b"):
                if name in fields:
                    columns[name] = fields[name][keep]
        if self.t_eval is not None:
            # rows at requested times carry those times exactly, not their round trip through tau
            sampled = np.nonzero((kind[keep] & SAMPLE) != 0)[0]
            columns["t"][sampled] = self.t_eval[:sampled.size]
        rows = _row_labels(kind[keep], names[keep])
        # the estimated inertial error at each Reynolds event's row, quoted in its message: of the
        # quasi-steady Stokes forces, and of the forces the run used when they carry the correction
        at_reynolds = np.nonzero(names[keep] == "reynolds")[0]
        error_at, corrected_at = {}, {}
        if at_reynolds.size and not self.dimensionless:
            row_columns = {name: column[at_reynolds] for name, column in columns.items()}
            errors = estimated_force_error(self.system, row_columns)
            error_at = dict(zip(t_tau[at_reynolds], errors))
            if self.inertia_corrected:
                from lubrication.inertia import corrected_error_estimate

                left = corrected_error_estimate(errors, reduced_reynolds(self.system, row_columns))
                corrected_at = dict(zip(t_tau[at_reynolds], left))
        status, message, event = self._status(fields, columns, error_at, corrected_at)
        on_event = np.nonzero((kind & EVENT) != 0)[0]
        along = [{"name": names[i], "t": float(fields["t"][i]) * tau} for i in on_event]
        warned = [e for e in along if e["name"] in LIMIT_EVENTS and e["name"] != event]
        switches = [e for e in along if e["name"] in ("touch", "lift", "stick", "slip")]
        trajectory = Trajectory(columns=columns, rows=rows, equations=equations, forces=forces, method=self.method,
                                status=status, message=message, event=event, events=switches + warned,
                                steps=int(fields["steps"]), nfev=int(fields["nfev"]), njev=int(fields["njev"]),
                                nlu=int(fields["nlu"]), wall_time_s=0.0, tau=tau, dimensionless=self.dimensionless,
                                groups=_groups(self.system, params))
        kept = kind[keep]
        if self.t_eval is not None:  # judge on the steps, as in a run without requested times
            trajectory.columns, trajectory.rows = _rows(columns, rows, (kept & ~SAMPLE) != 0)
        if trajectory.t.size:
            trajectory.regime, trajectory.evidence = classify(trajectory)
            if not self.dimensionless:
                trajectory.info["inertia"] = inertia_report(self.system, trajectory.columns,
                                                            corrected=self.inertia_corrected)
        if warned:
            t_of = {id(e): float(fields["t"][i]) for e, i in zip(along, on_event)}  # in tau, as error_at's keys
            trajectory.info["limits_passed"] = [
                dict(w, reason=limit_message(w["name"], self.limits, self._when(t_of[id(w)]),
                                             error_at.get(t_of[id(w)]), corrected_at.get(t_of[id(w)])))
                for w in warned]
        if self.t_eval is not None:  # the rows asked for: the samples, events, start, and the end once
            shown = (kept & (START | SAMPLE | EVENT)) != 0
            last = kept.size - 1
            if not shown[last]:
                earlier = np.nonzero(shown)[0]
                if earlier.size and columns["t"][earlier[-1]] == columns["t"][last]:
                    rows[earlier[-1]] += "+end"  # the run ended on a requested time or an event
                else:
                    shown[last] = True
            trajectory.columns, trajectory.rows = _rows(columns, rows, shown)
        return trajectory

    def _when(self, t_tau: float) -> str:
        return f"t = {t_tau * self.tau:.6g} {self.unit}"

    def _status(self, fields: dict, columns: dict, error_at: dict, corrected_at: dict) -> tuple[str, str, str]:
        """(status, message with units, stop event).

        ``error_at``, ``corrected_at``: by event time, the estimated inertial error of the quasi-steady
        Stokes forces and, for forces with the first inertial correction, of those forces.
        """
        t_last = float(columns["t_tau"][-1]) if columns["t"].size else 0.0
        stop = fields["stop"]
        if fields["status_code"] == 0:
            return "completed", f"reached t_end = {self.t_end:.6g} {self.unit}", ""
        if fields["status_code"] == 1 and stop in LIMIT_EVENTS:
            message = limit_message(stop, self.limits, self._when(t_last), error_at.get(t_last),
                                    corrected_at.get(t_last))
            return "stopped", message, stop
        if fields.get("code") == INTERRUPTED:
            by = fields["message"].split(" at t = ")[0]  # "interrupted" or "interrupted by SIGTERM"
            return "interrupted", f"{by} at {self._when(t_last)}", ""
        if stop == "max_switches":
            return "stopped", fields["message"], stop
        message = fields["message"]
        for word in ("t = ",):
            if word in message:
                message = message.split(word)[0] + self._when(t_last)
        return "failed", message, ""


#: Events that are no rows a user asked for: quarter turns, and changes of variables.
_HIDDEN_EVENTS = ("turn", "to_polar", "to_cartesian")


def _rows(columns: dict, rows: np.ndarray, mask: np.ndarray) -> tuple[dict, np.ndarray]:
    """The columns and row labels of the rows in ``mask``."""
    return {name: column[mask] for name, column in columns.items()}, rows[mask]


def _names(events: np.ndarray, names: tuple) -> np.ndarray:
    """The event name of each row ("" where the row is no event)."""
    return np.array(("", *names), dtype=object)[events + 1]


def _row_labels(kind: np.ndarray, names: np.ndarray) -> np.ndarray:
    """What each row is ("step", "sample", "event:touch", "start+sample", ...), from its flags and event."""
    labels = np.empty(kind.size, dtype=object)
    plain = names == ""
    for value in np.unique(kind):
        for event in (np.unique(names[kind == value]) if value & EVENT else [""]):
            parts = [label if flag != EVENT else f"event:{event}" for flag, label in _ROW_NAMES if value & flag]
            labels[(kind == value) & ((names == event) | plain if not event else names == event)] = "+".join(parts)
    return labels


def _groups(system, params) -> dict:
    if isinstance(system, ReducedParams):
        return {"s": params.s, "upsilon": params.upsilon, "mu": params.mu_ratio}
    return {"s": system.s, "upsilon": system.upsilon, "mu": system.mu_ratio, "delta_over_a": system.delta_over_a}
