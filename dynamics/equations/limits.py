"""Where the models stop being meaningful, as terminal events with a stated reason.

Both models assume smooth walls, a continuum film and quasi-steady Stokes flow
in the gap. A run that leaves those assumptions is stopped and says why.
"""

from __future__ import annotations

import math

from dynamics.integrate import Event

__all__ = ["GAP_FLOOR", "MAX_REYNOLDS", "MAX_TURNS", "gap_floor_event", "reynolds_event", "runaway_event"]

# The continuum film loses its meaning near 1 - kappa ~ 1e-7 (a molecule across the
# paper's 3.25 mm gap); the mathematical model is followed two decades further, so
# that its own approach to contact can be studied, then the run stops.
GAP_FLOOR = 1e-9
# Quasi-steady Stokes flow needs a small gap Reynolds number (wall speed) delta / nu.
MAX_REYNOLDS = 10.0
# A runaway's rotation rate grows without bound (3.11), and with it the cost of each
# turn; a dimensionless run has no Reynolds number to stop it, so it stops after this
# many turns of the outer cylinder. Rocking turns the cylinder only slowly.
MAX_TURNS = 100.0


def gap_floor_event(one_minus_kappa, floor: float = GAP_FLOOR) -> Event:
    """Stop where 1 - kappa, given by ``one_minus_kappa(y)``, falls to ``floor``."""
    log_floor = math.log(floor)
    return Event("gap_floor", lambda t, y: math.log(one_minus_kappa(y)) - log_floor, -1.0,
                 lambda t: f"1 - kappa fell to {floor:g} at t = {t:.6g}: the smooth-wall continuum "
                           "model has no meaning at such gaps (contact needs a contact model)")


def runaway_event(turns_of_outer, max_turns: float = MAX_TURNS) -> Event:
    """Stop when ``turns_of_outer(y)`` (angle turned by the outer cylinder, rad) reaches max_turns turns."""
    limit = 2.0 * math.pi * max_turns
    return Event("runaway", lambda t, y: limit - abs(turns_of_outer(y)), -1.0,
                 lambda t: f"runaway: the outer cylinder turned {max_turns:g} times by t = {t:.6g}")


def reynolds_event(reynolds_number, max_reynolds: float = MAX_REYNOLDS, seconds_per_unit: float = 1.0) -> Event:
    """Stop when the gap Reynolds number ``reynolds_number(y)`` reaches ``max_reynolds``.

    ``seconds_per_unit`` converts the integrator's time to seconds for the message.
    """
    return Event("reynolds", lambda t, y: max_reynolds - reynolds_number(y), -1.0,
                 lambda t: f"the gap Reynolds number reached {max_reynolds:g} at t = {t * seconds_per_unit:.6g} s: "
                           "quasi-steady Stokes flow, the model's assumption, no longer holds")
