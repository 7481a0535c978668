"""Where the models stop being meaningful, and what a run does there.

The equations assume smooth walls, a continuum film and quasi-steady Stokes flow
in the gap. Each assumption has a measurable limit, watched by an event of the
run: the gap 1 - kappa falling to ``gap_floor``, the gap Reynolds number reaching
``max_gap_reynolds``. At a
limit the run stops and says why (``on_invalid = "stop"``), or goes on past it
and records where it crossed (``"warn"``). A runaway, whose rotation grows
without bound (3.11), is stopped after ``max_turns`` turns of the outer cylinder
whatever ``on_invalid`` says: that bounds the cost of a run, not its validity.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from functools import cache
from importlib import resources

import numpy as np

from dynamics.equations import full
from dynamics.equations.full import frame_force
from numerics.jit import jit
from numerics.keys import check_fields, key

__all__ = ["GAP_FLOOR", "LIMIT_EVENTS", "MAX_REYNOLDS", "MAX_TURNS", "MEASURED_STOKES", "MIN_GAP_FLOOR_FULL",
           "ON_INVALID", "VALIDITY_EVENTS", "WARN_FORCE_ERROR", "Limits", "ValidityWarning", "estimated_force_error",
           "first_order_force_over_weight", "frame_force_over_weight", "inertia_report", "inertia_warning",
           "limit_message", "reduced_reynolds", "stokes_message", "unsteady_error"]

#: The continuum film loses its meaning near 1 - kappa ~ 1e-7 (a molecule across the paper's
#: 3.25 mm gap); the mathematical model is followed two decades further, so that its own approach
#: to contact can be studied.
GAP_FLOOR = 1e-9
#: The smallest gap floor a run of the full equations can reach. The squeeze film relaxes at a rate that grows as
#: (1 - kappa)^(-3/2) / tau: at 1 - kappa = 1e-10 that is 3.5e14 times 1/tau, within the 4.5e15 that
#: double precision can tell from 1; at 1e-11 it is past it. Measured with the steel apparatus on
#: 2.4 degrees released from 1 - kappa = 1e-10: 2 s in 41,188 steps; from 1e-11 (and 3e-12, 1e-12) the
#: Newton iteration of the implicit integrator fails, at t = 0.44-0.51 s, with the gap still at its start.
#: The reduced equations (2.11) carry no radial inertia and follow the gap further.
MIN_GAP_FLOOR_FULL = 1e-10
#: The gap Reynolds number is the reduced Reynolds number of the flow relative to the line of
#: centres, Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a), W = Omega - chi': in the frame of the
#: line of centres the fictitious forces of a plane flow only shift the pressure, so it is the
#: relative flow whose inertia makes the quasi-steady Stokes forces wrong. Measured with steady
#: Navier-Stokes solves (docs/inertia/inertia.md): the first inertial correction of the force is
#: G Re* of the Stokes force of the wall rotations, measured against |R_chi_a W_a| + |R_chi_b W_b|,
#: a scale that does not cancel when the walls counter-rotate. Over every direction of (W_a, W_b)
#: and every kappa, G <= 0.0995 for delta/a >= 0.01 (1/10 in the thin-gap limit; 0.081 at the
#: apparatus' delta/a = 0.41), and full Newton solutions agree with the first-order error to 1% of
#: itself up to Re* = 1. The estimated error therefore reaches 10% at Re* = 1.0 for the thinnest
#: gaps and at Re* = 1.23 for the apparatus, and 1% at Re* = 0.10 and 0.12. The default is the
#: first of these, Re* = 1: below it the estimated force error is under 10% for every apparatus
#: and wall motion. Below the limit every run reports its estimated error (:func:`inertia_report`);
#: the squeeze eps' and the unsteady inertia (Stokes number delta^2/(nu tau)) are not in it.
#: The steel apparatus in 200 cSt oil released from rest at kappa = 0.5, phi = 0.5 rad passes
#: Re* = 8.2 (estimated error 49%) as the inner centre swings round the outer one with
#: chi' ~ 110 rad/s and the walls nearly at rest; Re* > 1 from 7 ms to 52 ms, after which the
#: rocking stays below 1. At the default such a run stops at 7 ms, or goes on with a record
#: of the crossing under ``on_invalid = "warn"``.
MAX_REYNOLDS = 1.0
#: Estimated relative force error above which a run warns (summary and standard error).
WARN_FORCE_ERROR = 0.1


@cache
def _stokes_study() -> dict:
    return json.loads(resources.files("dynamics").joinpath("data", "stokes_error.json").read_text(encoding="utf-8"))


def _two_digits_down(x: float) -> float:
    scale = 10.0 ** (math.floor(math.log10(x)) - 1)
    return math.floor(x / scale) * scale


#: The Stokes number St = delta^2 / (nu tau) measures the unsteady inertia of the flow in the gap, which every
#: ODE model leaves out (it takes the flow as quasi-steady). Measured against the coupled Navier-Stokes run
#: (docs/stokes_limit.md, validation/stokes_limit.py): with the default frame terms and fluid spin the error of
#: x_b along a rocking release grows from 0.16% at St = 0.075 to 3.3% at 7.5, and a runaway's is 0.6-0.7% over
#: St = 0.019-0.96. Without the fluid's spin ((2.4) as printed) it does not vanish with St: 1.8% to 4.4% and
#: 6.6-8.2%, the runaway's the spin's share of the device's moment of inertia (7.6%). MEASURED_STOKES is the
#: largest St measured (rounded down to two digits): beyond it the stated error is held at the last measured
#: value, and a run says so. A device's St is fixed by its fluid (St goes as 1/nu^2): a limit set in
#: ``max_stokes_number`` is judged before a run. None by default: the models' own comparisons (the reduced model's limit, the paper's figures at its oils) run at any St.
MEASURED_STOKES = _two_digits_down(max(st for st, _ in _stokes_study()["families"]["release"]["paper"]["none"]))
#: Rocking turns the outer cylinder only slowly; a runaway is stopped after this many turns.
MAX_TURNS = 100.0
ON_INVALID = ("stop", "warn")
#: The names of the limit events, in the order every model's event function lists them.
LIMIT_EVENTS = ("gap_floor", "reynolds", "runaway")


@dataclass(frozen=True)
class Limits:
    """The validity limits of a run and what to do at them."""

    gap_floor: float = key(GAP_FLOOR, help="smallest 1 - kappa a smooth-wall run goes to (the full equations "
                                           "reach 1e-10)", low=0.0, high=1.0, bounds="()")
    max_gap_reynolds: float | None = key(MAX_REYNOLDS, help="largest reduced gap Reynolds number "
                                         "Re* = max(|W_a| a, |W_b| b) delta^2/(nu a), W = Omega - phi' (at first "
                                         "order the force error is below Re*/10 of |f_chi,a| + |f_chi,b|, the "
                                         "Stokes force of the two walls' rotations); 'none' for no limit",
                                         low=0.0, bounds="()", none="none")
    on_invalid: str = key("stop", help="at a validity limit: 'stop' the run, or 'warn' and go on",
                          choices=ON_INVALID)
    max_turns: float = key(MAX_TURNS, help="turns of the outer cylinder after which a runaway is stopped",
                           low=0.0, bounds="()")
    max_stokes_number: float | None = key(None, help="largest Stokes number delta^2/(nu tau) of the fluid's "
                                          "unsteady inertia, which the quasi-steady ODE models leave out, judged "
                                          "before the run; 'none' (the default): no limit, and a run past the "
                                          "largest St at which their x_b error was measured against Navier-Stokes "
                                          "runs (7.5, docs/stokes_limit.md) says so",
                                          low=0.0, bounds="()", none="none")

    def __post_init__(self):
        check_fields(self)

    @property
    def stops(self) -> bool:
        """Whether crossing the gap floor or the Reynolds limit ends the run."""
        return self.on_invalid == "stop"

    @property
    def reynolds(self) -> float:
        """The Reynolds limit as a number (inf for none)."""
        return math.inf if self.max_gap_reynolds is None else self.max_gap_reynolds

    @property
    def stokes(self) -> float:
        """The Stokes-number limit as a number (inf for none)."""
        return math.inf if self.max_stokes_number is None else self.max_stokes_number


def unsteady_error(stokes_number: float, frame_terms: str = full.DEFAULT_FRAME_TERMS,
                   regime: str | None = None, fluid_spin: str = full.DEFAULT_FLUID_SPIN) -> dict:
    """The measured relative error of x_b of the quasi-steady models at ``stokes_number``, and what it rests on.

    Measured for two starts, a rocking release and a runaway, with the full equations, the exact Stokes
    forces, ``frame_terms`` and ``fluid_spin`` (an error below the reference's own is stated as that), at
    several St (``dynamics/data/stokes_error.json``, from ``validation.stokes_limit``): interpolated linearly
    in log St between them, the nearest measured value outside them (the error tends to a floor at small St). With the run's ``regime`` the estimate is that of
    the start of the same kind (a runaway's, else the release's); without it (before a run), the larger.
    ``measured_to_stokes_number``: the largest St measured for that start; beyond it the value is held.
    """
    study = _stokes_study()
    by_start, reach = {}, {}
    for label, family in study["families"].items():
        st, error = np.array(family[frame_terms][fluid_spin]).T
        by_start[label] = float(np.interp(math.log(stokes_number), np.log(st), error))
        reach[label] = float(st[-1])
    start = max(by_start, key=by_start.get) if regime is None else "runaway" if regime == "runaway" else "release"
    return {"stokes_number": stokes_number, "estimated_x_b_error": by_start[start], "from_start": start,
            "by_start": by_start, "horizon": study["horizon"][start],
            "measured_to_stokes_number": reach[start], "basis": study["basis"]}


def stokes_message(limits: Limits, unsteady: dict, stopping: bool) -> str:
    """Why a run is refused (``stopping``) or went on past ``max_stokes_number``, from :func:`unsteady_error`."""
    head = (f"the Stokes number delta^2/(nu tau) = {unsteady['stokes_number']:.3g} exceeds max_stokes_number = "
            f"{limits.stokes:g}: the ODE models were measured against Navier-Stokes runs up to St = "
            f"{unsteady['measured_to_stokes_number']:.3g}, where they misplace x_b by "
            f"{_percent(unsteady['estimated_x_b_error'])} within {unsteady['horizon']} (docs/stokes_limit.md)")
    if stopping:
        return head + "; on_invalid = 'warn' runs it anyway, equations = 'navier-stokes' without that error"
    return head


def limit_message(name: str, limits: Limits, when: str, error: float | None = None,
                  corrected: float | None = None) -> str:
    """Why a run stopped (or what it went past) at the limit event ``name``, at ``when`` (a time with units).

    ``error``: the estimated relative force error of the quasi-steady Stokes
    forces at the event's state (:func:`estimated_force_error`); without it the
    Reynolds message quotes the bound Re*/10 that holds for every apparatus and
    wall motion at first order. ``corrected``: for forces that carry the first
    inertial correction, the estimated error they leave there
    (:func:`lubrication.inertia.corrected_error_estimate`), which the message
    then quotes as the run's.
    """
    if name == "gap_floor":
        return (f"1 - kappa fell to gap_floor = {limits.gap_floor:g} at {when}: the smooth-wall continuum model "
                "has no meaning at such gaps (contact needs a contact model)")
    if name == "reynolds":
        reached = f"the gap Reynolds number Re* reached max_gap_reynolds = {limits.reynolds:g} at {when}: "
        if corrected is not None:
            plain = "" if error is None else f"; the quasi-steady Stokes forces by {_percent(error)}"
            return (reached + "the forces carry the first inertial correction, which leaves at most an estimated "
                    f"{_percent(corrected)} there (the table's interpolation, and second order in Re*{plain}; "
                    "docs/inertia/inertia.md)")
        if error is None:
            size = f"up to about {_percent(0.1 * limits.reynolds)} (Re*/10, the bound for any apparatus)"
        else:
            size = f"by an estimated {_percent(error)} there"
        return (reached + f"the quasi-steady Stokes forces, the model's assumption, are in error {size} "
                "(first order in Re*, docs/inertia/inertia.md)")
    if name == "runaway":
        return f"runaway: the outer cylinder turned max_turns = {limits.max_turns:g} times by {when}"
    msg = f"not a limit event: {name!r}"
    raise ValueError(msg)


def _percent(x: float) -> str:
    return f"{100.0 * x:.3g}%"


def _relative_rates(columns: dict):
    """kappa, W_a, W_b (rad/s) of each row and the fade of the relative rates near kappa = 0.

    The fade kappa^2 / (kappa^2 + 1e-6) is the run's Reynolds event's
    (:func:`dynamics.equations.full.reduced_reynolds`): where the centres nearly
    coincide chi' is not a frame rate.
    """
    kappa, phi_dot = columns["kappa"], columns["phi_dot"]
    fade = kappa * kappa / (kappa * kappa + 1e-6)
    return np.minimum(kappa, 1.0 - 1e-12), columns["omega_a"] - phi_dot, columns["omega_b"] - phi_dot, fade


def reduced_reynolds(apparatus, columns: dict) -> np.ndarray:
    """Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a), W = Omega - phi', at each row of a run's SI columns."""
    ap = apparatus
    _, w_a, w_b, fade = _relative_rates(columns)
    return fade * np.maximum(np.abs(w_a) * ap.a, np.abs(w_b) * ap.b) * ap.delta**2 / (ap.nu * ap.a)


def estimated_force_error(apparatus, columns: dict) -> np.ndarray:
    """Estimated relative force error of the quasi-steady Stokes forces at each row of a run's SI columns.

    :func:`lubrication.inertia.inertial_error_estimate` with the apparatus'
    delta/a: the first inertial correction of the flow relative to the line of
    centres against the Stokes force scale |R_chi_a W_a| + |R_chi_b W_b| of
    the wall rotations (a scale that cannot cancel). First order in Re*; the
    squeeze and the unsteady inertia are not in it.
    """
    from lubrication.inertia import inertial_error_estimate

    ap = apparatus
    kappa, w_a, w_b, fade = _relative_rates(columns)
    per = ap.delta / ap.nu
    return fade * inertial_error_estimate(kappa, ap.delta_over_a, w_a * ap.a * per, w_b * ap.b * per)


def first_order_force_over_weight(apparatus, columns: dict) -> np.ndarray:
    """|f_eps^(1)| / (m'_a g): the first inertial correction of the force at each row, against the buoyant weight.

    :func:`lubrication.inertia.first_order_f_eps`; what ``inertia = "first-order"`` adds to the
    forces of a trajectory (:func:`lubrication.registry.kernel_model`).
    """
    from lubrication.inertia import first_order_f_eps

    ap = apparatus
    kappa, w_a, w_b, fade = _relative_rates(columns)
    force = first_order_f_eps(kappa, ap.delta_over_a, ap.a, ap.rho, ap.length, w_a, w_b)
    return fade * np.abs(force) / (ap.m_a_reduced * ap.g)


def frame_force_over_weight(apparatus, columns: dict) -> np.ndarray:
    """|frame force| / (m'_a g) at each row: what ``frame_terms = "quasi-steady"`` adds to (2.1)-(2.2) as printed.

    :func:`dynamics.equations.full.frame_force` at the row's state.
    """
    from dynamics.equations.full import params_array

    ap = apparatus
    states = [np.ascontiguousarray(v, dtype=float) for v in (columns["eps"], columns["kappa_dot"] * ap.delta,
                                                             columns["phi_dot"], columns["omega_a"],
                                                             columns["omega_b"])]
    return _frame_force_magnitudes(params_array(ap, "quasi-steady"), *states) / (ap.m_a_reduced * ap.g)


@jit
def _frame_force_magnitudes(p, eps, eps_dot, chi_dot, omega_a, omega_b):
    """|frame force| (N) of :func:`dynamics.equations.full.frame_force` along arrays of states."""
    out = np.empty(eps.size)
    for i in range(eps.size):
        f_eps, f_chi = frame_force(p, eps[i], eps_dot[i], chi_dot[i], omega_a[i], omega_b[i])
        out[i] = math.hypot(f_eps, f_chi)
    return out


def inertia_report(apparatus, columns: dict, corrected: bool = False, frame_terms: str = full.DEFAULT_FRAME_TERMS,
                   regime: str | None = None, fluid_spin: str = full.DEFAULT_FLUID_SPIN) -> dict:
    """How far a run's quasi-steady Stokes forces can be trusted, from its SI columns.

    Returns, each with the time at which it occurred: the largest reduced Reynolds
    number Re* (:func:`reduced_reynolds`) and the estimated relative force error at
    that point; the largest estimated relative force error
    (:func:`estimated_force_error`: the two maxima need not coincide, since the
    error per unit Re* depends on kappa and on the direction of (W_a, W_b)); the
    largest first inertial correction of the force over the buoyant weight m'_a g
    (:func:`first_order_force_over_weight`); the largest force of the rotating
    frame that (2.1)-(2.2) as printed leave out, over m'_a g
    (:func:`frame_force_over_weight`); the squeeze Reynolds number
    |eps'| delta / nu, which the estimate does not cover; and the Stokes number
    delta^2/(nu tau) of the unsteady inertia no steady solve sees, with the
    error of x_b it implies for ``frame_terms``, ``fluid_spin`` and the run's ``regime`` (``unsteady``:
    :func:`unsteady_error`). With
    ``corrected`` (forces that carry the first inertial correction), also
    ``corrected_forces``: the largest estimated error those forces leave
    (:func:`lubrication.inertia.corrected_error_estimate`), its time, and the
    Re* up to which that estimate was measured.
    """
    ap = apparatus
    t = columns["t"]
    re_star = reduced_reynolds(ap, columns)
    errors = estimated_force_error(ap, columns)

    def worst(values):
        if values.size == 0:
            return 0, 0.0, 0.0
        i = int(np.argmax(values))
        return i, float(values[i]), float(t[i])

    i_re, max_re, t_re = worst(re_star)
    _, max_err, t_err = worst(errors)
    _, max_first, t_first = worst(first_order_force_over_weight(ap, columns))
    _, max_frame, t_frame = worst(frame_force_over_weight(ap, columns))
    report = {"max_reduced_reynolds": max_re, "t_at_max_reduced_reynolds": t_re,
              "estimated_force_error_at_max_reduced_reynolds": float(errors[i_re]) if errors.size else 0.0,
              "max_estimated_force_error": max_err, "t_at_max_estimated_force_error": t_err,
              "force_error_scale": "|R_chi_a W_a| + |R_chi_b W_b|: the Stokes force of the wall rotations",
              "max_first_order_force_over_weight": max_first, "t_at_max_first_order_force": t_first,
              "max_frame_force_over_weight": max_frame, "t_at_max_frame_force": t_frame,
              "max_squeeze_reynolds": float(np.abs(columns["kappa_dot"]).max(initial=0.0) * ap.delta**2 / ap.nu),
              "stokes_number": ap.delta**2 / (ap.nu * ap.tau),
              "unsteady": unsteady_error(ap.delta**2 / (ap.nu * ap.tau), frame_terms, regime, fluid_spin)}
    if corrected:
        from lubrication.inertia import CORRECTED_MEASURED_TO, corrected_error_estimate

        _, max_left, t_left = worst(corrected_error_estimate(errors, re_star))
        report["corrected_forces"] = {
            "max_estimated_force_error": max_left, "t_at_max_estimated_force_error": t_left,
            "measured_to_reduced_reynolds": CORRECTED_MEASURED_TO,
            "basis": "the table's interpolation and the second-order remainder, against Newton solutions of "
                     "steady Navier-Stokes flow (docs/inertia/inertia.md)"}
    return report


class ValidityWarning(UserWarning):
    """A run went past, or stopped at, a limit of its model's validity (:class:`Limits`), or its forces may
    err by more than :data:`WARN_FORCE_ERROR` (:func:`inertia_warning`). Filter it as any warning:
    ``warnings.simplefilter("ignore", ValidityWarning)``."""


#: The limits whose stop is no success: the model left its validity there (a runaway's stop bounds a cost).
VALIDITY_EVENTS = ("gap_floor", "reynolds")


def inertia_warning(inertia: dict) -> str:
    """What a run's inertia report (:func:`inertia_report`) warns of, and what to do about it, or "".

    The forces the run used are judged: the quasi-steady Stokes forces by their
    first-order error, forces with the first inertial correction by what that
    leaves, and by whether the run went past the Reynolds numbers at which it was measured;
    and the quasi-steady flow by the error its Stokes number implies (:func:`unsteady_error`).
    """
    unsteady = inertia.get("unsteady")
    beyond = unsteady is not None and unsteady["stokes_number"] > unsteady["measured_to_stokes_number"]
    if unsteady is None or (unsteady["estimated_x_b_error"] <= WARN_FORCE_ERROR and not beyond):
        return _force_warning(inertia)
    kind = "runaway" if unsteady["from_start"] == "runaway" else "rocking release"
    past = (f", past St = {unsteady['measured_to_stokes_number']:.3g}, the largest measured, where it was that much"
            if beyond else "")
    flow = (f"the quasi-steady flow (Stokes number {unsteady['stokes_number']:.3g}) may misplace x_b by "
            f"{_percent(unsteady['estimated_x_b_error'])} within {unsteady['horizon']} (measured on a {kind}{past}: "
            "docs/stokes_limit.md); equations = 'navier-stokes' solves the unsteady flow instead")
    forces = _force_warning(inertia)
    return f"{forces}; {flow}" if forces else flow


def _force_warning(inertia: dict) -> str:
    corrected = inertia.get("corrected_forces")
    if corrected is not None:
        beyond = inertia["max_reduced_reynolds"] > corrected["measured_to_reduced_reynolds"]
        if corrected["max_estimated_force_error"] <= WARN_FORCE_ERROR and not beyond:
            return ""
        past = (f"; Re* reached {inertia['max_reduced_reynolds']:.3g} (t = {inertia['t_at_max_reduced_reynolds']:.3g}"
                f" s), past Re* = {corrected['measured_to_reduced_reynolds']:g}, the largest at which the "
                "correction was compared with Navier-Stokes solutions") if beyond else ""
        return (f"the inertia-corrected forces may be in error by up to {corrected['max_estimated_force_error']:.0%} "
                f"(at t = {corrected['t_at_max_estimated_force_error']:.3g} s){past}")
    if inertia.get("max_estimated_force_error", 0.0) <= WARN_FORCE_ERROR:
        return ""
    return (f"the quasi-steady Stokes forces may be in error by up to {inertia['max_estimated_force_error']:.0%} "
            f"(at t = {inertia['t_at_max_estimated_force_error']:.3g} s; at the largest gap Reynolds number, "
            f"Re* = {inertia['max_reduced_reynolds']:.2g} at t = {inertia['t_at_max_reduced_reynolds']:.3g} s, by "
            f"{inertia['estimated_force_error_at_max_reduced_reynolds']:.0%}); model.inertia = 'first-order' adds "
            "their first inertial correction, which leaves an error second order in Re* (estimated in the run's "
            "'inertia' record)")
