"""The run record: a :class:`Trajectory`, and the conversion of a run's rows into one (:class:`Recorder`).

Whatever ran (the full or the reduced equations, any force model, rough contact,
a transported film), the result is one :class:`Trajectory`, after scipy's
``OdeResult``: the columns, ``status`` and ``message``, ``success``, the events
along the way (``t_events``, ``y_events``), an interpolant (``sol``), the counts.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from dynamics.contact.laws import COMPLIANT
from dynamics.contact.reduced import FREE, LOCKED, SLIDING
from dynamics.equations import full
from dynamics.equations.limits import (
    LIMIT_EVENTS,
    VALIDITY_EVENTS,
    estimated_force_error,
    inertia_report,
    limit_message,
    reduced_reynolds,
)
from dynamics.equations.reduced import ReducedParams
from dynamics.regime import classify
from numerics.engine import END, EVENT, INTERRUPTED, SAMPLE, START, STEP

__all__ = ["PHASE_CODES", "Recorder", "Trajectory", "event_names"]

#: Contact phases as numbers in the trajectory table (a compliant contact is one smooth phase).
PHASE_CODES = {FREE: 0, SLIDING: 1, LOCKED: 2, COMPLIANT: 3}

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
    wall_time_s : float
        Seconds the run took, compiling left out (:attr:`compile_time_s`).
    tau : float
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
    compile_time_s : float
        Seconds numba spent compiling kernels for the run (0 when they came from its cache).
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
    compile_time_s: float = 0.0

    @property
    def t(self) -> np.ndarray:
        return self.columns["t"]

    def __repr__(self) -> str:
        unit = "tau" if self.dimensionless else "s"
        span = f"{self.t[0]:.4g}..{self.t[-1]:.4g} {unit}" if self.t.size else "no rows"
        return (f"Trajectory({self.equations} equations, {self.forces} forces, {self.status}: {self.message}; "
                f"regime {self.regime!r}, {self.t.size} rows over {span}, {self.steps} steps)")

    @property
    def mean_speed(self) -> float:
        """X_b(t_end)/t_end, from the release: the transient included (m/s, or b/tau dimensionless); see
        :attr:`late_mean_speed` for the motion the run settled into."""
        t = self.t
        return float(self.columns["x_b"][-1] / t[-1]) if t.size and t[-1] > 0 else 0.0

    @property
    def late_mean_speed(self) -> float:
        """The mean speed over the second half of the run, where the regime is judged (:mod:`dynamics.regime`)."""
        t, x_b = self.t, self.columns["x_b"]
        if not t.size or t[-1] <= 0:
            return 0.0
        late = min(int(np.searchsorted(t, 0.5 * t[-1])), t.size - 1)
        return float((x_b[-1] - x_b[late]) / (t[-1] - t[late])) if t[-1] > t[late] else 0.0

    @property
    def t_events(self) -> dict[str, np.ndarray]:
        """The times of each event, by name (as scipy's ``t_events``, keyed by name rather than index)."""
        return {name: self.t[rows] for name, rows in self._event_rows().items()}

    @property
    def y_events(self) -> dict[str, dict[str, np.ndarray]]:
        """The columns at each event, by name: ``y_events["touch"]["kappa"]``."""
        return {name: {k: v[rows] for k, v in self.columns.items()} for name, rows in self._event_rows().items()}

    def _event_rows(self) -> dict[str, np.ndarray]:
        names: dict[str, list[int]] = {}
        for i, label in enumerate(self.rows):
            for part in str(label).split("+"):
                if part.startswith("event:"):
                    names.setdefault(part[len("event:"):], []).append(i)
        return {name: np.array(rows, dtype=int) for name, rows in names.items()}

    def sol(self, t, column: str | None = None):
        """The columns at times ``t`` interpolated between the output rows, as scipy's ``sol`` is called.

        A piecewise-cubic interpolant (scipy's PCHIP: no overshoot between rows) of each column, or of
        ``column`` alone; exact at the rows, and between them as accurate as the rows are dense (ask the run
        for rows at the times wanted, ``output_interval`` or ``t_eval``, for values from the integrator's own
        dense output). Returns a dict of arrays, or an array for one column.
        """
        from scipy.interpolate import PchipInterpolator

        t_rows, unique = np.unique(self.t, return_index=True)  # an event row may repeat a step's time
        names = [column] if column is not None else list(self.columns)
        out = {name: PchipInterpolator(t_rows, self.columns[name][unique])(t) for name in names}
        return out[column] if column is not None else out

    def to_pandas(self):
        """The columns as a pandas DataFrame indexed by t, with the row labels as a column ``row``."""
        try:
            import pandas as pd
        except ImportError as err:
            msg = "to_pandas needs pandas: pip install pandas"
            raise ImportError(msg) from err
        frame = pd.DataFrame({k: v for k, v in self.columns.items() if k != "t"}, index=pd.Index(self.t, name="t"))
        frame["row"] = self.rows
        return frame

    def plot(self, path=None):
        """The figure of ``snail run`` (:mod:`dynamics.app.figures`): a matplotlib Figure, also written to
        ``path`` as PNG if given."""
        from dynamics.app.figures import trajectory_figure

        fig = trajectory_figure(self)
        if path is not None:
            fig.savefig(path, dpi=110)
        return fig

    @property
    def success(self) -> bool:
        """True when the run reached t_end, or stopped at an event that bounds its cost (a runaway's turns);
        False when it failed, was interrupted, or stopped where its model leaves its validity (a gap floor,
        the Reynolds limit: :data:`~dynamics.equations.limits.VALIDITY_EVENTS`)."""
        return self.status == "completed" or (self.status == "stopped" and self.event not in VALIDITY_EVENTS)


class Recorder:
    """The settings every model's run shares, and the conversion of its scaled rows (t in tau, rates in 1/tau,
    X_b in b) into a :class:`Trajectory`: a model's run (:mod:`dynamics.simulation`, :mod:`dynamics.equations.film`)
    integrates, and hands its rows to :meth:`trajectory` or :meth:`Recorder.contact_trajectory`."""

    def __init__(self, system, dimensionless, t_end, limits, method, rtol, t_eval, max_steps, progress,
                 frame_terms=full.DEFAULT_FRAME_TERMS, fluid_spin=full.DEFAULT_FLUID_SPIN):
        self.system, self.dimensionless, self.t_end = system, dimensionless, t_end
        self.limits, self.method, self.rtol = limits, method, rtol
        self.max_steps, self.progress, self.frame_terms = max_steps, progress, frame_terms
        self.fluid_spin = fluid_spin
        self.tau = 1.0 if dimensionless else system.tau
        self.unit = "tau" if dimensionless else "s"
        self.t_eval = t_eval
        self.inertia_corrected = False  # forces with the first inertial correction (full equations)

    def contact_trajectory(self, fields: dict, equations: str, forces: str, params) -> Trajectory:
        """As :meth:`trajectory`, from the fields of a contact run (its stop event and status code)."""
        fields = dict(fields, stop=fields["stop_event"], status_code=fields["status"])
        trajectory = self.trajectory(fields, equations, forces, params)
        trajectory.info.update(phase_codes=PHASE_CODES, final_phase=str(fields["phase"][-1]),
                               switches=[{"t": sw.t * self.tau, "from": sw.old, "to": sw.new}
                                         for sw in fields["switches"]])
        return trajectory

    @staticmethod
    def keep(fields: dict) -> np.ndarray:
        """Rows to keep: not the crossings of the vertical (they keep phi continuous) nor the changes of
        variables of the free full model, which are no rows a user asked for."""
        kind, names = fields["kind"], fields["event_names"]
        return ~(((kind & EVENT) != 0) & np.isin(names, _HIDDEN_EVENTS) & ((kind & ~EVENT) == 0))

    def trajectory(self, fields: dict, equations: str, forces: str, params) -> Trajectory:
        """Columns in the output units from scaled rows (t in tau, rates in 1/tau, X_b in b).

        The regime and the inertia diagnostics are taken over every step; with
        requested output times, the rows that are only steps are then dropped.
        """
        tau = self.tau
        kind, names = fields["kind"], fields["event_names"]
        keep = self.keep(fields)
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
                                                            corrected=self.inertia_corrected,
                                                            frame_terms=self.frame_terms,
                                                            regime=trajectory.regime, fluid_spin=self.fluid_spin)
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


def event_names(events: np.ndarray, names: tuple) -> np.ndarray:
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
