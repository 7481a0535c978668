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
keeps falling as t^-2), and rocking is not (phi swings). The steady regimes and
sedimentation are claims about what did not happen, so they need a run of at
least SHORTEST_SETTLED tau: over less, nothing has had time to change, and a run
of a microsecond would look steady. Such a run is "transient" unless it shows
swings or a runaway.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["REGIMES", "classify", "late_half"]

REGIMES = ("runaway", "rocking", "sedimenting", "locked rolling", "sliding rolling", "steady rolling", "transient")

#: Largest relative spread of 1 - kappa and Omega_b (and spread of phi, rad) over the second half
#: of a run that counts as steady.
STEADY_SPREAD = 0.01
#: Shortest run (in tau, the time scale of the sinking) that can show a steady state or sedimentation.
SHORTEST_SETTLED = 2.0
_ROLLING = {1.0: "sliding rolling", 2.0: "locked rolling"}  # by contact phase code


def late_half(t, phi, gap, omega_b) -> tuple[int, float, int, float, float, float]:
    """The second half of a run and the numbers read of it.

    Parameters
    ----------
    t, phi, gap, omega_b : array_like, shape (k,), k >= 1
        Time (increasing), the angle of the line of centres (unwrapped), 1 - kappa
        and Omega_b, row by row.

    Returns
    -------
    late : int
        The first row at or after half the final time (the last row if none is).
    turns : float
        (phi at the end - phi at ``late``) / 2 pi.
    reversals : int
        Sign changes of phi's increments from ``late`` on.
    phi_spread, gap_spread, omega_b_spread : float
        Largest minus smallest value from ``late`` on.

    Raises
    ------
    ValueError
        If the columns are empty or of different lengths.
    """
    columns = [np.asarray(x, dtype=float) for x in (t, phi, gap, omega_b)]
    if not 1 <= columns[0].size == columns[1].size == columns[2].size == columns[3].size:
        msg = f"late_half needs t, phi, gap and omega_b of one length, at least 1; got {[c.size for c in columns]}"
        raise ValueError(msg)
    t, phi, gap, omega_b = columns
    late = min(int(np.searchsorted(t, 0.5 * t[-1])), t.size - 1)
    phi_late = phi[late:]
    # reversals of phi: sign changes of its increments (a zero increment counts as a sign of its own)
    swings = int(np.count_nonzero(np.diff(np.sign(np.diff(phi_late))))) if phi_late.size > 2 else 0
    return (late, float((phi[-1] - phi[late]) / (2.0 * math.pi)), swings, float(np.ptp(phi_late)),
            float(np.ptp(gap[late:])), float(np.ptp(omega_b[late:])))


def classify(trajectory) -> tuple[str, dict]:
    """Regime of ``trajectory`` from its second half; returns (regime, evidence)."""
    c = trajectory.columns
    phi, kappa = c["phi"], c["kappa"]
    omega_b = c["omega_b"] * trajectory.tau
    late, turns, swings, phi_spread, gap_spread, omega_b_spread = late_half(c["t_tau"], phi, c["one_minus_kappa"],
                                                                            omega_b)
    growth = float(omega_b[-1] - omega_b[late])
    evidence = {"turns_of_phi_late": turns, "phi_reversals_late": swings, "final_kappa": float(kappa[-1]),
                "omega_b_tau_growth_late": growth, "stop_event": trajectory.event}
    if trajectory.event == "runaway" or (abs(turns) >= 1.0 and abs(omega_b[-1]) > abs(omega_b[late])):
        return "runaway", evidence
    settled = c["t_tau"][-1] - c["t_tau"][0] >= SHORTEST_SETTLED
    phase = c.get("phase")
    if (settled and phase is not None and phase[late:].size and np.all(phase[late:] == phase[-1])
            and phase[-1] in _ROLLING):
        spread = omega_b_spread / max(abs(float(omega_b[-1])), 1e-300)
        evidence["omega_b_relative_spread_late"] = spread
        if spread < STEADY_SPREAD:
            return _ROLLING[float(phase[-1])], evidence
    gap = c["one_minus_kappa"]
    spreads = {"one_minus_kappa_relative_spread_late": gap_spread / max(float(gap[-1]), 1e-300),
               "phi_spread_late": phi_spread,
               "omega_b_relative_spread_late": omega_b_spread / max(abs(float(omega_b[-1])), 1e-300)}
    evidence.update(spreads)
    if settled and phase is None and omega_b[-1] != 0.0 and max(spreads.values()) < STEADY_SPREAD:
        return "steady rolling", evidence
    if kappa[-1] >= 0.95 and abs(turns) < 1.0:
        if swings >= 2:
            return "rocking", evidence
        if settled:
            return "sedimenting", evidence
    return "transient", evidence
