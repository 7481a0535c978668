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

import math
from dataclasses import dataclass

import numpy as np

from dynamics.keys import check_fields, key

__all__ = ["GAP_FLOOR", "LIMIT_EVENTS", "MAX_REYNOLDS", "MAX_TURNS", "ON_INVALID", "WARN_FORCE_ERROR", "Limits",
           "inertia_report", "limit_message"]

#: The continuum film loses its meaning near 1 - kappa ~ 1e-7 (a molecule across the paper's
#: 3.25 mm gap); the mathematical model is followed two decades further, so that its own approach
#: to contact can be studied.
GAP_FLOOR = 1e-9
#: The gap Reynolds number is the reduced Reynolds number of the flow relative to the line of
#: centres, Re* = max(|W_a| a, |W_b| b) delta^2 / (nu a), W = Omega - chi': in the frame of the
#: line of centres the fictitious forces of a plane flow only shift the pressure, so it is the
#: relative flow whose inertia makes the quasi-steady Stokes forces wrong. Measured with steady
#: Navier-Stokes solves (docs/inertia/inertia.md): the force error is G Re* with G <= 0.099
#: (0.068 at the apparatus' delta/a = 0.41), so Re* = 0.1 bounds it by 1% and Re* = 1 by 10%.
#: The default stops a run at Re* = 10, where the first correction is of the size of the force
#: itself and the Stokes forces are not even a first approximation; below it, every run
#: reports its largest estimated error (:func:`inertia_report`), and max_gap_reynolds = 1 keeps
#: it under 10%. (The paper's default release passes Re* = 8 for a few milliseconds as the
#: inner centre swings past the outer one.)
MAX_REYNOLDS = 10.0
#: Estimated relative force error above which a run warns (summary and standard error).
WARN_FORCE_ERROR = 0.1
#: Rocking turns the outer cylinder only slowly; a runaway is stopped after this many turns.
MAX_TURNS = 100.0
ON_INVALID = ("stop", "warn")
#: The names of the limit events, in the order every model's event function lists them.
LIMIT_EVENTS = ("gap_floor", "reynolds", "runaway")


@dataclass(frozen=True)
class Limits:
    """The validity limits of a run and what to do at them."""

    gap_floor: float = key(GAP_FLOOR, help="smallest 1 - kappa a smooth-wall run goes to", low=0.0, high=1.0,
                           bounds="()")
    max_gap_reynolds: float | None = key(MAX_REYNOLDS, help="largest reduced gap Reynolds number "
                                         "Re* = max(|W_a| a, |W_b| b) delta^2/(nu a), W = Omega - phi' (the "
                                         "relative force error is below Re*/10); 'none' for no limit", low=0.0,
                                         bounds="()", none="none")
    on_invalid: str = key("stop", help="at a validity limit: 'stop' the run, or 'warn' and go on",
                          choices=ON_INVALID)
    max_turns: float = key(MAX_TURNS, help="turns of the outer cylinder after which a runaway is stopped",
                           low=0.0, bounds="()")

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


def limit_message(name: str, limits: Limits, when: str) -> str:
    """Why a run stopped (or what it went past) at the limit event ``name``, at ``when`` (a time with units)."""
    if name == "gap_floor":
        return (f"1 - kappa fell to gap_floor = {limits.gap_floor:g} at {when}: the smooth-wall continuum model "
                "has no meaning at such gaps (contact needs a contact model)")
    if name == "reynolds":
        return (f"the gap Reynolds number Re* reached max_gap_reynolds = {limits.reynolds:g} at {when}: the "
                f"quasi-steady Stokes forces, the model's assumption, may be in error by up to "
                f"{0.099 * limits.reynolds:.0%} there (docs/inertia/inertia.md)")
    if name == "runaway":
        return f"runaway: the outer cylinder turned max_turns = {limits.max_turns:g} times by {when}"
    msg = f"not a limit event: {name!r}"
    raise ValueError(msg)


def inertia_report(apparatus, columns: dict) -> dict:
    """How far a run's quasi-steady Stokes forces can be trusted, from its SI columns.

    Returns the largest, along the run, of: the reduced Reynolds number Re* (and
    when it occurred); the estimated relative error of the fluid force from the
    inertia of the relative flow (:func:`lubrication.inertia.inertial_error_estimate`,
    first order in Re*); the force the rotating frame exerts and (2.1)-(2.2) leave out,
    (m_eff - m'_a) eps phi'^2, over m'_a g (the equations carry m_eff where the
    centripetal term of a fluid turning with the line of centres needs m'_a:
    docs/inertia/inertia.md); the squeeze Reynolds number |eps'| delta / nu, which the
    estimate does not cover; and the Stokes number delta^2/(nu tau) of the unsteady
    inertia no steady solve sees.
    """
    from lubrication.inertia import inertial_error_estimate

    ap = apparatus
    kappa, phi_dot = columns["kappa"], columns["phi_dot"]
    w_a, w_b = columns["omega_a"] - phi_dot, columns["omega_b"] - phi_dot
    fade = kappa * kappa / (kappa * kappa + 1e-6)
    re_star = fade * np.maximum(np.abs(w_a) * ap.a, np.abs(w_b) * ap.b) * ap.delta**2 / (ap.nu * ap.a)
    per = ap.delta / ap.nu
    errors = np.array([inertial_error_estimate(min(k, 1.0 - 1e-12), ap.delta_over_a, wa * ap.a * per,
                                               wb * ap.b * per) * f
                       for k, wa, wb, f in zip(kappa, w_a, w_b, fade)])
    errors = np.where(np.isfinite(errors), errors, 0.0)
    frame = (ap.m_eff - ap.m_a_reduced) * columns["eps"] * phi_dot**2 / (ap.m_a_reduced * ap.g)
    worst = int(np.argmax(re_star)) if re_star.size else 0
    return {"max_reduced_reynolds": float(re_star.max(initial=0.0)),
            "t_at_max_reduced_reynolds": float(columns["t"][worst]) if re_star.size else 0.0,
            "max_estimated_force_error": float(errors.max(initial=0.0)),
            "max_frame_force_over_weight": float(np.abs(frame).max(initial=0.0)),
            "max_squeeze_reynolds": float(np.abs(columns["kappa_dot"]).max(initial=0.0) * ap.delta * per),
            "stokes_number": ap.delta**2 / (ap.nu * ap.tau)}
