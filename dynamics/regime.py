"""Which motion a trajectory settled into, and the numbers that decided it.

Regimes (section 3 of the paper): "runaway" (the line of centres winds round
with a rotation rate that keeps growing, (3.11)), "rocking" (the inner cylinder
sinks towards contact while the line of centres swings back and forth, (3.9)),
"sedimenting" (it sinks without swinging, as on a level plane, (3.3)),
"locked rolling" and "sliding rolling" (steady rolling in contact with rough
walls, section 5: the phase held over the second half and Omega_b steady to
1%), "steady rolling" (without contact: the gap, the angle and the rolling
speed all constant over the second half, as a cavitating film allows, section
7), and "transient" when the run ended before any of these showed.

Steady means: over the second half of the run, 1 - kappa and Omega_b vary by
less than STEADY_SPREAD of their final values, and phi by less than
STEADY_SPREAD rad. A full film approaching contact is never steady (its 1 - kappa
keeps falling as t^-2), and rocking is not (phi swings).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["REGIMES", "classify"]

REGIMES = ("runaway", "rocking", "sedimenting", "locked rolling", "sliding rolling", "steady rolling", "transient")

#: Largest relative spread of 1 - kappa and Omega_b (and spread of phi, rad) over the second half
#: of a run that counts as steady.
STEADY_SPREAD = 0.01
_ROLLING = {1.0: "sliding rolling", 2.0: "locked rolling"}  # by contact phase code


def classify(trajectory) -> tuple[str, dict]:
    """Regime of ``trajectory`` from its second half; returns (regime, evidence)."""
    c = trajectory.columns
    t, phi, kappa = c["t_tau"], c["phi"], c["kappa"]
    omega_b = c["omega_b"] * trajectory.tau
    half = np.searchsorted(t, 0.5 * t[-1])
    late = slice(min(half, len(t) - 1), None)
    turns = float((phi[-1] - phi[late][0]) / (2 * math.pi))
    swings = int(np.count_nonzero(np.diff(np.sign(np.diff(phi[late]))) != 0)) if phi[late].size > 2 else 0
    growth = float(omega_b[-1] - omega_b[late][0])
    evidence = {"turns_of_phi_late": turns, "phi_reversals_late": swings, "final_kappa": float(kappa[-1]),
                "omega_b_tau_growth_late": growth, "stop_event": trajectory.event}
    if trajectory.event == "runaway" or (abs(turns) >= 1.0 and abs(omega_b[-1]) > abs(omega_b[late][0])):
        return "runaway", evidence
    phase = c.get("phase")
    if phase is not None and phase[late].size and np.all(phase[late] == phase[-1]) and phase[-1] in _ROLLING:
        spread = float(np.ptp(omega_b[late]) / max(abs(omega_b[-1]), 1e-300))
        evidence["omega_b_relative_spread_late"] = spread
        if spread < STEADY_SPREAD:
            return _ROLLING[float(phase[-1])], evidence
    gap = c["one_minus_kappa"][late]
    spreads = {"one_minus_kappa_relative_spread_late": float(np.ptp(gap) / max(gap[-1], 1e-300)),
               "phi_spread_late": float(np.ptp(phi[late])),
               "omega_b_relative_spread_late": float(np.ptp(omega_b[late]) / max(abs(omega_b[-1]), 1e-300))}
    evidence.update(spreads)
    if phase is None and omega_b[-1] != 0.0 and max(spreads.values()) < STEADY_SPREAD:
        return "steady rolling", evidence
    if kappa[-1] >= 0.95 and abs(turns) < 1.0:
        return ("rocking" if swings >= 2 else "sedimenting"), evidence
    return "transient", evidence
