r"""Many points of a sweep in one compiled call: the reduced equations (2.11) without contact.

A regime map is thousands of short runs of the reduced model (2.11) that differ
in a few numbers. :func:`run_batch` builds each point's scene in Python, as
:func:`~dynamics.app.sweeps.point.run_point` does, sets its run up as
:func:`dynamics.simulation.simulate` would (:func:`problem`), and integrates all
the points it can in one call of a compiled loop
(:func:`dynamics.app.sweeps.compiled.integrate_points`: the engine's driver on
the reduced model's functions, no Python per step or per point). Each run's rows
then become the columns that ``simulate`` makes of them and are classified by
:func:`~dynamics.app.sweeps.point.classify_point`: the same steps, rows, regimes
and numbers as one point at a time.

The batch takes the points whose scene is the reduced equations without contact
or cavitation, with one output row per step (no ``run.output_interval``). The
other points, and the runs that failed (so that their reason is the per-point
path's message), go through :func:`~dynamics.app.sweeps.point.run_point`, each
alone. ``wall_time_s`` of a batched point is its own scene building and
classification plus its integration, timed inside the loop.

Building the scenes stays in Python: about 0.15 ms a point (its values applied
to the base scene as they are, not written out and read back as TOML), against a
median of about 0.65 ms of integration for a point of the regime map.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np

from dynamics.app.sweeps.compiled import integrate_points
from dynamics.app.sweeps.point import classify_point, run_point
from dynamics.app.sweeps.spec import point_key
from dynamics.equations import full, reduced
from dynamics.equations.limits import LIMIT_EVENTS
from dynamics.scenes import parse_scene
from numerics.engine import EVENT, REACHED_END, TERMINAL_EVENT

__all__ = ["DIRECTION", "Problem", "problem", "run_batch"]

#: The directions of the reduced model's events (:data:`dynamics.equations.reduced.EVENT_NAMES`) as
#: simulate() asks for them: the limits (terminal when the run stops at them), the runaway, the quarter
#: turns, the touch of rough walls (never, without contact).
DIRECTION = np.array([-1, -1, -1, 0, 1], dtype=np.int64)
_TURN = reduced.EVENT_NAMES.index("turn")


@dataclass(frozen=True)
class Problem:
    """A point's run as :func:`dynamics.simulation.simulate` sets it up for the reduced equations.

    Attributes
    ----------
    y0 : ndarray, shape (5,)
        :func:`dynamics.equations.reduced.initial_state`, rates in 1/tau.
    args : ndarray
        :func:`dynamics.equations.reduced.run_args` with the scene's limits.
    t_end_tau, rtol : float
        Duration in tau; relative tolerance, also the absolute one (the state is scaled).
    terminal : ndarray of int, shape (5,)
        Per event of :data:`dynamics.equations.reduced.EVENT_NAMES`: 1 where it ends the run.
    tau, phi0 : float
        The time scale (1 in a dimensionless scene), and the initial phi that sets phi's turn.
    """

    y0: np.ndarray
    args: np.ndarray
    t_end_tau: float
    rtol: float
    terminal: np.ndarray
    tau: float
    phi0: float


def problem(scene) -> Problem | None:
    """The run of ``scene`` as the batch integrates it, or None if the batch cannot run it.

    None for anything but the reduced equations without contact or cavitation
    and with every-step output, and for a start that ``simulate`` refuses: those
    points take :func:`~dynamics.app.sweeps.point.run_point`, which says why.
    """
    model, run, initial = scene.model, scene.run, scene.initial
    if (model.equations != "reduced" or model.forces == "auto" or model.ends != "infinite"
            or model.frame_terms != full.DEFAULT_FRAME_TERMS or model.fluid_spin != full.DEFAULT_FLUID_SPIN
            or scene.contact is not None or scene.cavitation is not None
            or run.output_interval is not None):
        return None
    limits = run.limits
    if initial.gap <= limits.gap_floor or initial.kappa_dot != 0.0 or initial.phi_dot != 0.0:
        return None
    tau = scene.tau
    if scene.apparatus is None:
        params, per_rate = scene.groups.reduced_params, (0.0, 0.0)
    else:
        ap = scene.apparatus
        params = ap.reduced_params
        per_rate = (ap.delta**2 / (ap.nu * tau), ap.b * ap.delta**2 / (ap.a * ap.nu * tau))
    args = reduced.run_args(params, gap_floor=limits.gap_floor, max_reynolds=limits.reynolds,
                            reynolds_per_rate=per_rate, x_b_limit=2.0 * math.pi * limits.max_turns)
    y0 = reduced.initial_state(initial.kappa, initial.phi, initial.omega_a * tau, initial.omega_b * tau,
                               one_minus_kappa0=initial.one_minus_kappa)
    stops = int(limits.stops)
    if stops and reduced.events(0.0, y0, args)[1] < 0.0:
        return None  # past the Reynolds limit at the start, which simulate() refuses
    return Problem(y0=y0, args=args, t_end_tau=float(run.t_end) / tau, rtol=float(run.rtol),
                   terminal=np.array([stops, stops, 1, 0, 0], dtype=np.int64), tau=tau, phi0=initial.phi)


def _classified(prepared: Problem, rows: tuple, code: int, stop: int) -> tuple[str, str, dict] | None:
    """(status, regime, numbers) of a run from its rows, as simulate() and classify_point make them.

    None when the run did not complete or stop at a limit: run_point then says why.
    """
    if code == REACHED_END:
        status, event = "completed", ""
    elif code == TERMINAL_EVENT and reduced.EVENT_NAMES[stop] in LIMIT_EVENTS:
        status, event = "stopped", reduced.EVENT_NAMES[stop]
    else:
        return None
    t, y, kind, events = rows
    # simulate() drops the rows that are only a quarter turn, which keep phi continuous
    keep = ~((kind == EVENT) & (events == _TURN))
    columns = reduced.position_columns(y, prepared.phi0)  # the rates are not classified
    tau = prepared.tau
    trajectory = SimpleNamespace(  # what classify_point reads of a Trajectory
        columns={"t_tau": np.asarray(t, dtype=float)[keep], "phi": columns["phi"][keep],
                 "kappa": columns["kappa"][keep], "one_minus_kappa": columns["one_minus_kappa"][keep],
                 "omega_b": y[3][keep] / tau},
        tau=tau, status=status, event=event)
    regime, numbers = classify_point(trajectory)
    return status, regime, numbers


def run_batch(base: Mapping[str, Any], source: str, points: Sequence[Mapping[str, Any]]) -> list[dict]:
    """The rows of ``points``, the reduced ones integrated together; the task a dask worker runs.

    Returns
    -------
    list of dict
        One row per point, in order, as :func:`~dynamics.app.sweeps.point.run_point` makes it.
    """
    rows: list[dict | None] = [None] * len(points)
    batched, seconds = [], []  # (index, Problem), time spent on each batched point outside the loop
    for i, point in enumerate(points):
        start = time.perf_counter()
        try:
            prepared = problem(parse_scene(base, source, point))
        except Exception:  # noqa: BLE001 - run_point records why
            prepared = None
        if prepared is None:
            rows[i] = run_point(base, point, source)
            continue
        batched.append((i, prepared))
        seconds.append(time.perf_counter() - start)
    if batched:
        problems = [p for _, p in batched]
        try:
            runs, status, stop_event, steps, clock = integrate_points(
                [p.y0 for p in problems], [p.args for p in problems], [p.t_end_tau for p in problems],
                [p.rtol for p in problems], [p.terminal for p in problems], DIRECTION)
        # A point fails alone: should the loop itself fail, every point runs on its own.
        except Exception:  # noqa: BLE001
            runs = None
        for k, (i, prepared) in enumerate(batched):
            point = points[i]
            start = time.perf_counter()
            try:
                result = None if runs is None else _classified(prepared, runs[k], status[k], stop_event[k])
            except Exception:  # noqa: BLE001 - run_point records why
                result = None
            if result is None:
                rows[i] = run_point(base, point, source)
                continue
            run_status, regime, numbers = result
            rows[i] = {**point, "point": point_key(point), **numbers, "status": run_status, "regime": regime,
                       "steps": int(steps[k]), "reason": "",
                       "wall_time_s": seconds[k] + (clock[k + 1] - clock[k]) + (time.perf_counter() - start)}
    return rows
