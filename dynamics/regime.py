"""Which motion a trajectory settled into, and the numbers that decided it.

Regimes (section 3 of the paper): "runaway" (the line of centres winds round
with a rotation rate that keeps growing, (3.11)), "rocking" (the inner cylinder
sinks towards contact while the line of centres swings back and forth, (3.9)),
"sedimenting" (it sinks without swinging, as on a level plane, (3.3)), and
"transient" when the run ended before any of these showed.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["REGIMES", "classify"]

REGIMES = ("runaway", "rocking", "sedimenting", "transient")


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
    if trajectory.event in ("runaway", "reynolds") or (abs(turns) >= 1.0 and abs(omega_b[-1]) > abs(omega_b[late][0])):
        return "runaway", evidence
    if kappa[-1] >= 0.95 and abs(turns) < 1.0:
        return ("rocking" if swings >= 2 else "sedimenting"), evidence
    return "transient", evidence
