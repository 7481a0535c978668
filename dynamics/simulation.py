"""One simulation API for every model: a system, an initial state and a duration in, a :class:`~dynamics.trajectory.Trajectory` out.

:func:`simulate` runs the full equations (2.1)-(2.4) with any force model, or the
reduced equations (2.11), each with or without rough contact (section 5), with
the compiled Radau IIA integrator (:mod:`numerics.engine`) or one of scipy's
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
import warnings

import numpy as np

from dynamics.apparatus import Apparatus
from dynamics.contact import reduced as reduced_contact
from dynamics.contact.reduced import ContactParams
from dynamics.contact.roughness import RoughContact
from dynamics.equations import full, reduced
from dynamics.equations.limits import (
    MIN_GAP_FLOOR_FULL,
    VALIDITY_EVENTS,
    Limits,
    ValidityWarning,
    inertia_warning,
    stokes_message,
    unsteady_error,
)
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.trajectory import Recorder, Trajectory, event_names
from lubrication.film_transport import TransportedFilm
from lubrication.geometry import check_range
from lubrication.kernels import KernelModel, check_end_gap
from lubrication.registry import kernel_model
from lubrication.spin_table import DELTA_NODES as SPIN_DELTA_NODES
from numerics.hybrid import run_phases
from numerics.integrate import METHODS, integrate
from numerics.jit import compile_watch

__all__ = ["EQUATIONS", "MAX_ROWS", "MAX_STEPS", "NAVIER_STOKES_RTOL", "Initial", "Trajectory", "simulate"]


def simulate(system: Apparatus | ReducedParams, initial: Initial, t_end: float, *, equations: str | None = None,
             forces: KernelModel | str = "stokes-exact", contact=None, limits: Limits = Limits(),
             method: str = "radau", rtol: float | None = None, output_interval: float | None = None, t_eval=None,
             max_steps: int = 2_000_000, progress=None, frame_terms: str = full.DEFAULT_FRAME_TERMS,
             fluid_spin: str = full.DEFAULT_FLUID_SPIN, navier_stokes=None) -> Trajectory:
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
    equations : {"full", "reduced", "navier-stokes"}, optional
        Default "full" for an apparatus, "reduced" for groups; "navier-stokes": the
        unsteady flow of the gap coupled to both cylinders, the reference without a
        closure (:mod:`dynamics.equations.navier_stokes`; needs an apparatus, takes no
        force model or contact).
    forces : KernelModel, str or TransportedFilm
        The full equations' force model: a registered name (:func:`lubrication.registry.names`;
        "stokes-exact", the exact 2-D Stokes forces, by default; "closed-form" the paper's
        (2.5)-(2.7)), a model with options (:func:`lubrication.registry.kernel_model`), or a
        cavitating film whose content joins the state (:mod:`dynamics.equations.film`);
        the reduced equations have the closed forms built in.
    contact : ContactParams or RoughContact, optional
        Rough contact (section 5): a uniform minimum gap, or one that varies along the
        surfaces and turns with them (:class:`dynamics.contact.roughness.RoughContact`), in
        either equations; Stribeck friction and a compliant contact
        (:mod:`dynamics.contact.laws`) in the full equations only.
    limits : Limits
        Validity limits and what to do at them (:mod:`dynamics.equations.limits`).
    method : {"radau", "Radau", "BDF", "LSODA"}
        The compiled Radau IIA integrator, or one of scipy's (:mod:`numerics.integrate`).
    rtol : float, optional
        Relative tolerance, in [100 eps, 0.1]; default 1e-8 for the ODEs, :data:`NAVIER_STOKES_RTOL` for the
        flow solver's step control.
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
    frame_terms : {"quasi-steady", "paper"}
        The full equations' treatment of the fluid turning with the line of
        centres: m'_a on the centripetal and Coriolis terms
        (:func:`dynamics.equations.full.frame_force`; the closer to the coupled
        Navier-Stokes runs, docs/navier_stokes.md), or (2.1)-(2.2) as printed.
    fluid_spin : {"eccentric", "couette", "none"}
        The fluid's own angular momentum in (2.4): that of the Stokes flow at
        the state's eccentricity, the closest to the coupled Navier-Stokes
        runs (the default), that of the concentric Couette flow,
        m_f (a^2 Omega_a + b^2 Omega_b)/2, or none, as the paper writes (2.4)
        (:data:`dynamics.equations.full.FLUID_SPIN`, :func:`dynamics.equations.full.spin_state`).
        The other equations take the default only.
    navier_stokes : NavierStokesOptions, optional
        The flow solver's grid and the times of flow snapshots
        (:class:`dynamics.equations.navier_stokes.NavierStokesOptions`).

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
    if equations not in EQUATIONS:
        msg = f"equations must be one of {', '.join(map(repr, EQUATIONS))}, got {equations!r}"
        raise ValueError(msg)
    if dimensionless and equations != "reduced":
        msg = (f"the {equations} equations need a physical apparatus: pass an Apparatus (Apparatus.from_groups "
               "builds one)")
        raise ValueError(msg)
    navier_stokes = _check_navier_stokes(equations, navier_stokes, contact, frame_terms, method)
    if fluid_spin not in full.FLUID_SPIN:
        msg = f"fluid_spin must be one of {', '.join(full.FLUID_SPIN)}, got {fluid_spin!r}"
        raise ValueError(msg)
    if fluid_spin != full.DEFAULT_FLUID_SPIN and equations != "full":
        msg = (f"fluid_spin applies to the full equations (2.4); the {equations} equations "
               + ("drop the O(delta/a) fluid mass" if equations == "reduced" else "carry the fluid's spin themselves"))
        raise ValueError(msg)
    if method not in METHODS:
        msg = f"method must be one of {', '.join(METHODS)}, got {method!r}"
        raise ValueError(msg)
    if rtol is None:
        rtol = NAVIER_STOKES_RTOL if equations == "navier-stokes" else 1e-8
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
    full.check_frame_terms(frame_terms)
    if frame_terms != full.DEFAULT_FRAME_TERMS and equations == "reduced":
        msg = (f"frame_terms applies to the full equations; the reduced equations (2.11) drop these O(delta/a) terms: "
               f"leave it at its default {full.DEFAULT_FRAME_TERMS!r}")
        raise ValueError(msg)
    if equations == "reduced" and (initial.kappa_dot != 0.0 or initial.phi_dot != 0.0):
        msg = ("initial.kappa_dot and initial.phi_dot must be 0 for the reduced equations, where (2.11a-b) "
               f"fix kappa' and phi' from the state; got {initial.kappa_dot!r} and {initial.phi_dot!r}")
        raise ValueError(msg)
    film = isinstance(forces, TransportedFilm)
    if film and (equations == "reduced" or contact is not None):
        msg = "a transported film (forces=TransportedFilm) runs in the full equations without contact"
        raise ValueError(msg)
    model = (None if equations != "full" or film else forces if isinstance(forces, KernelModel)
             else kernel_model(forces))
    if model is not None:  # the full equations, whose system is an Apparatus
        check_end_gap(model.end_gap, system.a)
        _check_spin_table(system, fluid_spin)
    past_stokes = _check_stokes(system, limits, equations, frame_terms, fluid_spin)
    bar = _Bar(t_end, unit) if progress is True else None
    run = _Run(system, dimensionless, t_end, limits, method, rtol, t_eval, max_steps, bar or progress, frame_terms,
               fluid_spin)
    start = time.perf_counter()
    try:
        with compile_watch(on_first=bar.compiling if bar is not None else None) as watch:
            if equations == "navier-stokes":
                from dynamics.equations.navier_stokes import navier_stokes_run

                trajectory = navier_stokes_run(run, initial, navier_stokes)
            elif film:
                from dynamics.equations.film import film_run

                trajectory = film_run(run, initial, forces)
            else:
                trajectory = run.reduced(initial, contact) if model is None else run.full(initial, model, contact)
    finally:
        if bar is not None:
            bar.close()
    if equations == "full":
        trajectory.info["frame_terms"] = frame_terms
        trajectory.info["fluid_spin"] = fluid_spin
    if past_stokes is not None:
        trajectory.info["limits_passed"] = [past_stokes, *trajectory.info.get("limits_passed", [])]
    trajectory.compile_time_s = watch.compile_s
    trajectory.wall_time_s = time.perf_counter() - start - watch.compile_s
    _warn(trajectory)
    return trajectory


class _Bar:
    """``progress=True``: a bar of the simulated time (tqdm's, in a notebook its widget), saying when it compiles."""

    def __init__(self, total: float, unit: str):
        from tqdm.auto import tqdm

        self.bar = tqdm(total=total, unit=unit, desc="simulate", mininterval=0.5, leave=False)

    def compiling(self, _event) -> None:
        self.bar.set_description("simulate: compiling the kernels of this model (first run only, a minute or two)")

    def __call__(self, t: float) -> None:
        if self.bar.desc != "simulate":
            self.bar.set_description("simulate")
        self.bar.update(t - self.bar.n)

    def close(self) -> None:
        self.bar.close()


def _check_spin_table(apparatus, fluid_spin: str) -> None:
    """A ValidityWarning where the eccentric spin's table (:mod:`lubrication.spin_table`) is held at its widest
    gap: its shares change by about 0.25 per unit of delta/a there, and beyond it they are not measured."""
    widest = float(SPIN_DELTA_NODES[-1])
    if fluid_spin == "eccentric" and apparatus.delta_over_a > widest:
        warnings.warn(f"fluid_spin = 'eccentric': its table of Stokes solves reaches delta/a = {widest:g}, and this "
                      f"apparatus has {apparatus.delta_over_a:.3g}; the spin's shares are held at delta/a = "
                      f"{widest:g} (they change by about 0.25 per unit of delta/a there). fluid_spin = 'couette' "
                      "is exact where the annulus is concentric", ValidityWarning, stacklevel=3)


def _check_stokes(system, limits: Limits, equations: str, frame_terms: str, fluid_spin: str) -> dict | None:
    """A quasi-steady run of a device whose Stokes number exceeds ``max_stokes_number``: refused (ValueError)
    if the limits stop, else the record of its passage at t = 0. None within the limit, for the coupled
    Navier-Stokes run, and without an apparatus."""
    if not isinstance(system, Apparatus) or equations == "navier-stokes":
        return None
    stokes = system.delta**2 / (system.nu * system.tau)
    if stokes <= limits.stokes:
        return None
    unsteady = unsteady_error(stokes, frame_terms, fluid_spin=fluid_spin)
    if limits.stops:
        raise ValueError(stokes_message(limits, unsteady, stopping=True))
    return {"name": "stokes", "t": 0.0, "reason": stokes_message(limits, unsteady, stopping=False)}


def _warn(trajectory: Trajectory) -> None:
    """A :class:`~dynamics.equations.limits.ValidityWarning` for every limit the run passed or stopped at, and
    for forces that may err by more than the warning level."""
    for passed in trajectory.info.get("limits_passed", []):
        warnings.warn(passed["reason"], ValidityWarning, stacklevel=3)
    if trajectory.status == "stopped" and trajectory.event in VALIDITY_EVENTS:
        warnings.warn(trajectory.message, ValidityWarning, stacklevel=3)
    inertia = inertia_warning(trajectory.info.get("inertia", {}))
    if inertia:
        warnings.warn(f"fluid inertia: {inertia}", ValidityWarning, stacklevel=3)


#: The equations :func:`simulate` integrates.
EQUATIONS = ("full", "reduced", "navier-stokes")
#: The flow solver's default relative error per step (vorticity, wall velocities, A's position): its
#: trajectories' change when it is quartered (and on finer grids) is in docs/navier_stokes.md.
NAVIER_STOKES_RTOL = 1e-4


def _check_navier_stokes(equations, options, contact, frame_terms, method):
    """The Navier-Stokes options, refused where they do not apply, and what the flow does not take."""
    from dynamics.equations.navier_stokes import NavierStokesOptions

    if equations != "navier-stokes":
        if options is not None:
            raise ValueError("navier_stokes options apply to equations = 'navier-stokes' only")
        return None
    if contact is not None:
        raise ValueError("contact: the Navier-Stokes equations run without a contact model (smooth walls)")
    if frame_terms != full.DEFAULT_FRAME_TERMS:
        raise ValueError(f"frame_terms closes the ODE models' fluid inertia; the Navier-Stokes equations have none: "
                         f"leave it at its default {full.DEFAULT_FRAME_TERMS!r}")
    if method != "radau":
        raise ValueError(f"method picks the ODE models' integrator, got {method!r}; the Navier-Stokes equations "
                         "step with their own IMEX BDF2 (lubrication.unsteady.timestepping)")
    if options is None:
        return NavierStokesOptions()
    if not isinstance(options, NavierStokesOptions):
        msg = f"navier_stokes must be a NavierStokesOptions, got {type(options).__name__}"
        raise TypeError(msg)
    return options


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
    angle at 1 - kappa0 = 1e-4 and 1e-5 it took 200,000 steps to reach t = 3 s and 1.8 s (from 1e-2 it ran the
    10 s without trouble), and from 1e-6 it failed outright, while the compiled Radau IIA and scipy's BDF and
    Radau ran.
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
    if contact is not None and not isinstance(contact, (ContactParams, RoughContact)):
        msg = f"contact must be a ContactParams, a RoughContact or None, got {type(contact).__name__}"
        raise TypeError(msg)
    if isinstance(contact, RoughContact) and contact.laws and equations == "reduced":
        which = "contact.compliance (a compliant contact)" if contact.compliance is not None else \
            "contact.friction (Stribeck friction)"
        msg = (f"{which} is modelled in the full equations only; the reduced equations (2.11) keep section 5's "
               "hard contact and Coulomb friction: use equations='full' or leave it None")
        raise ValueError(msg)


def _check_reynolds_at_start(g: np.ndarray, limits: Limits) -> None:
    """Refuse initial rates that put the run past the Reynolds limit at t = 0 (event values ``g``:
    the Reynolds event is the second, max_gap_reynolds - Re*), unless the limits only warn."""
    if limits.stops and g[1] < 0.0:
        msg = (f"initial.omega_a, initial.omega_b and initial.phi_dot give a gap Reynolds number "
               f"Re* = {limits.reynolds - g[1]:.4g} at t = 0, above run.max_gap_reynolds = {limits.reynolds:g}: "
               "quasi-steady Stokes forces do not hold there; lower the initial rates, raise "
               "max_gap_reynolds, or set on_invalid = 'warn'")
        raise ValueError(msg)


class _Run(Recorder):
    """A run of the full or the reduced equations, with or without contact: the integration of each model."""

    def reduced(self, initial: Initial, contact) -> Trajectory:
        params = self.system if self.dimensionless else self.system.reduced_params
        tau = self.tau
        t_end_tau = self.t_end / tau
        t_eval = None if self.t_eval is None else self.t_eval / tau
        progress = None if self.progress is None else (lambda t: self.progress(t * tau))
        rates = (initial.omega_a * tau, initial.omega_b * tau)
        if contact is not None:
            runner = reduced_contact.run_contact
            if isinstance(contact, RoughContact):
                from dynamics.contact.rough import run_rough_contact as runner
            fields = runner(params, contact, t_end_tau, initial.kappa, initial.phi, *rates, limits=self.limits,
                            method=self.method, rtol=self.rtol, t_eval=t_eval, steps=True,
                            max_steps=self.max_steps, progress=progress)
            return self.contact_trajectory(fields, "reduced", "closed-form", params)
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
        fields = {"t": run.t, "kind": run.kind, "event_names": event_names(run.event, reduced.EVENT_NAMES), **cols,
                  "stop": reduced.EVENT_NAMES[run.stop_event] if run.stop_event >= 0 else "",
                  "code": run.code, "status_code": run.status, "message": run.message,
                  "steps": run.steps, "nfev": run.nfev, "njev": run.njev, "nlu": run.nlu}
        return self.trajectory(fields, "reduced", "closed-form", params)

    def full(self, initial: Initial, model: KernelModel, contact) -> Trajectory:
        ap = self.system
        self.inertia_corrected = model.inertia_corrected
        if contact is not None:
            from dynamics.contact import full as full_contact
            from dynamics.contact.rough_full import run_rough_full

            runner = run_rough_full if isinstance(contact, RoughContact) else full_contact.run_full_contact
            fields = runner(ap, model, contact, initial, self.t_end, limits=self.limits, method=self.method,
                            rtol=self.rtol, t_eval=self.t_eval, steps=True, max_steps=self.max_steps,
                            progress=self.progress, frame_terms=self.frame_terms, fluid_spin=self.fluid_spin)
            return self.contact_trajectory(fields, "full", model.name, ap.reduced_params)
        limits = self.limits
        args = full.run_args(ap, model, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                             max_turns=limits.max_turns, frame_terms=self.frame_terms, fluid_spin=self.fluid_spin)
        y0 = full.initial_state(ap, initial.kappa, initial.phi, initial.kappa_dot, initial.phi_dot,
                                initial.omega_a, initial.omega_b, one_minus_kappa=initial.gap)
        _check_reynolds_at_start(full.events(0.0, y0, args), limits)
        free = full.FreeFull(ap, args, full.model_functions(model), int(limits.stops), self.rtol, polar=model.smooth)
        fields = run_phases(free.phase(y0), free.transition, free.columns, self.t_end, phi0=initial.phi,
                            method=self.method, rtol=self.rtol, t_eval=self.t_eval, steps=True,
                            max_steps=self.max_steps, progress=self.progress)
        del fields["phase"]  # one free phase in two sets of variables, no contact
        fields = dict(fields, t=fields["t"] / self.tau, stop=fields["stop_event"], status_code=fields["status"])
        return self.trajectory(fields, "full", model.name, ap.reduced_params)
