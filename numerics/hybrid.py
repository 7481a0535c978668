"""Hybrid runs: phases with their own smooth equations, switched at events located on the dense output.

A contact run is a sequence of phases (free, sliding, locked). Each phase is a
smooth system, a :class:`Phase`: compiled ``fun``, ``jac`` and ``events``
(``f(t, y, args)``), its ``args`` and initial state, and what each event means.
:func:`run_phases` integrates a phase until ``t_end`` or a terminal event, in
one compiled call (:func:`numerics.integrate.integrate`); an event whose name is
in :data:`SWITCHES` ends the phase and ``transition`` gives the next one from the
state there; any other terminal event ends the run. So the run returns to Python
once per switch, never per step.

Why this is exact and does not chatter: each phase's right-hand side is smooth;
its guards are located to rounding on the dense output of the step that crosses
them; every reset is chosen so that the new phase moves off the switching
surface it starts on, and an event that starts at zero cannot fire in the first
step of its phase (:mod:`numerics.engine.driver`). A run that still switched more
than ``max_switches`` times stops with that reason rather than hang.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, NamedTuple

import numpy as np

from numerics.engine import END, INTERRUPTED, START, Interrupts, stop_message
from numerics.integrate import integrate

__all__ = ["MAX_SWITCHES", "SWITCHES", "Phase", "Switch", "run_phases"]

#: Events that end a phase, not the run: contact switches, and changes of the variables a free
#: full-model run is carried in (:mod:`dynamics.equations.full`).
SWITCHES = ("touch", "lift", "stick", "slip", "to_polar", "to_cartesian")

#: A run that switched this often is caught in a pathological cycle and stops with that reason. Figure 7's
#: run switches once, runs near the onset of sliding (stick-slip while rocking) some 20 times.
MAX_SWITCHES = 10_000


class Switch(NamedTuple):
    """A change of phase at time ``t`` (in the run's time unit)."""

    t: float
    old: str
    new: str


@dataclass(frozen=True)
class Phase:
    """One smooth phase of a hybrid run.

    Attributes
    ----------
    name : str
        "free", "sliding" or "locked".
    fun, jac, events : compiled functions of (t, y, args)
    args : tuple
    y0 : ndarray
        Initial state of the phase.
    event_names : tuple of str
        Name of each event function component: a name in :data:`SWITCHES` ends
        the phase; a terminal one of the others ends the run.
    terminal, direction : tuple of int
        Per event, as in :func:`numerics.engine.integrate`.
    atol : ndarray
        Absolute tolerance per component.
    sigma : float
        Sign of the sliding friction of the phase (0 when not sliding).
    record : bool
        Record the change into this phase as a :class:`Switch` (False restarts
        a phase without one).
    continues : bool
        The same motion as the phase before, in other variables: no switch is
        recorded and the phase's first row, a repeat of the switching state,
        is not output.
    """

    name: str
    fun: Callable
    jac: Callable
    events: Callable
    args: tuple
    y0: np.ndarray
    event_names: tuple
    terminal: tuple
    direction: tuple
    atol: np.ndarray
    sigma: float = 0.0
    record: bool = True
    continues: bool = False
    extra: dict = field(default_factory=dict)


def run_phases(start: Phase, transition, columns, t_end: float, *, phi0: float, method: str, rtol: float,
               t_eval=None, steps=None, max_steps: int, max_switches: int = MAX_SWITCHES, progress=None) -> dict:
    """Integrate a hybrid system phase by phase from t = 0 to ``t_end``.

    Parameters
    ----------
    start : Phase
    transition : callable
        ``transition(phase, event_name, t, y_end, phi_end) -> Phase``: the phase
        after a switching event at time ``t`` with state ``y_end`` and angle
        ``phi_end`` (continuous from the start of the run).
    columns : callable
        ``columns(phase, t, y, kind) -> dict`` of output columns of one phase's
        rows (state ``y`` of shape (n_state, k)), with a "phi" column that
        continues from ``phase.extra["phi0"]``, the angle at the phase's start
        (a free phase holds Cartesian states, so the turn must be carried).
    t_end : float
    phi0 : float
        The angle at the start of the run.
    method, rtol, max_steps, progress
        As for :func:`numerics.integrate.integrate` (``max_steps`` over all phases).
    t_eval : array_like, optional
        Output times; by default every step. Event rows (switches, the stop) are
        output either way.
    steps : bool, optional
        Output every step as well as ``t_eval`` (as :func:`numerics.integrate.integrate`).

    Returns
    -------
    dict
        ``t``, ``kind`` (row flags), ``phase`` (name per row), ``event_names``
        (the event of each event row, "" elsewhere), ``switches``, the
        concatenated columns, ``status`` (0 reached t_end, 1 stopped by an
        event, -1 failed or interrupted), ``stop_event`` (its name, or the
        engine's reason), ``message``, ``code`` and the totals ``steps``,
        ``nfev``, ``njev``, ``nlu``.
    """
    samples = None if t_eval is None else np.asarray(t_eval, dtype=float)
    phase, t0, phi = start, 0.0, phi0
    pieces, switches = [], []
    totals = {"steps": 0, "nfev": 0, "njev": 0, "nlu": 0}
    # one handler of Ctrl-C and SIGTERM for the whole run: each phase's run reads it, none sets its own
    with Interrupts() as interrupts:
        while True:
            phase_eval = None
            if samples is not None:
                phase_eval = samples[(samples > t0) & (samples <= t_end)] - t0 if pieces else samples - t0
                phase_eval = phase_eval[phase_eval <= t_end - t0]
            run = integrate(phase.fun, phase.jac, (0.0, t_end - t0), phase.y0, args=phase.args, method=method,
                            rtol=rtol, atol=phase.atol, events=phase.events, terminal=phase.terminal,
                            direction=phase.direction, t_eval=phase_eval, steps=steps,
                            max_steps=max(max_steps - totals["steps"], 1),
                            progress=None if progress is None else (lambda t, t0=t0: progress(t0 + t)))
            for key in totals:
                totals[key] += getattr(run, key)
            names = np.array([phase.event_names[i] if i >= 0 else "" for i in run.event], dtype=object)
            phase.extra["phi0"] = phi
            cols = columns(phase, run.t, run.y, run.kind)
            if run.t.size:
                phi = float(cols["phi"][-1])
            repeat = pieces and phase.continues and run.kind.size and run.kind[0] & START
            rows = slice(1 if repeat else 0, None)
            pieces.append((t0 + run.t[rows], run.kind[rows], np.full(run.t[rows].size, phase.name), names[rows],
                           {key: value[rows] for key, value in cols.items()}))
            name = phase.event_names[run.stop_event] if run.stop_event >= 0 else ""
            status, message, code = run.status, run.message, run.code
            if name not in SWITCHES:
                break
            t_switch = t0 + float(run.t[-1])
            if t_switch >= t_end:  # a switch exactly at t_end ends the run
                status, name = 0, ""
                break
            if len(switches) >= max_switches:
                status, name = -1, "max_switches"
                message = f"more than max_switches = {max_switches} phase switches by t = {t_switch:.17g}"
                break
            if interrupts.received:  # noted between two phases: the run stops at the switch
                status, name, code = -1, "", INTERRUPTED
                message = stop_message(INTERRUPTED, t_switch, by=interrupts.received)
                break
            old = phase.name
            phase = transition(phase, name, t_switch, run.y[:, -1], phi)
            if phase.record and not phase.continues:
                switches.append(Switch(t_switch, old, phase.name))
            t0 = t_switch
            # the state at the switch is the first row of the next phase: mark the last row as an event only
            pieces[-1][1][-1] &= ~END
    merged = {key: np.concatenate([p[4][key] for p in pieces]) for key in pieces[0][4]}
    return dict(t=np.concatenate([p[0] for p in pieces]), kind=np.concatenate([p[1] for p in pieces]),
                phase=np.concatenate([p[2] for p in pieces]), event_names=np.concatenate([p[3] for p in pieces]),
                switches=tuple(switches), status=status, stop_event=name, message=message, code=code, **totals,
                **merged)
