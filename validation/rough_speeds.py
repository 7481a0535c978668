"""Rolling on a minimum gap that varies along both surfaces: its mean speed against the roughness amplitude.

The study behind the random-roughness numbers of the documentation: reduced-model
runs with :class:`dynamics.contact.roughness.RoughContact` over seeds and
amplitudes, each averaged once it has settled, against the uniform kappa*
steady rate (5.10)-(5.11) that the speed law (6.1) uses.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from dynamics.analysis import rolling_statistics
from dynamics.contact.reduced import ContactParams
from dynamics.contact.roughness import RoughContact
from dynamics.contact.steady import steady_state
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import simulate

__all__ = ["SpeedRow", "speed_table"]


class SpeedRow(NamedTuple):
    """Rolling statistics at one amplitude, over seeds (rates in 1/tau: speeds in b/tau)."""

    amplitude: float
    mean: float  # mean over seeds of each run's mean rolling rate <Omega_b>
    spread: float  # standard deviation of <Omega_b> over seeds
    ratio: float  # mean / the uniform kappa* steady Omega_b, (6.1) with exact=True
    fluctuation: float  # mean over seeds of the time standard deviation of Omega_b
    switch_rate: float  # mean over seeds of phase switches per tau
    seeds: int


def speed_table(params: ReducedParams, mean: ContactParams, correlation: float, amplitudes, seeds, *,
                t_end: float, t_settle: float, kappa0: float = 0.5, phi0: float = 0.3,
                rtol: float = 1e-8) -> tuple[float, tuple[SpeedRow, ...]]:
    """Mean rolling rate and its spread over ``seeds`` against the roughness amplitude.

    Every run starts from figure 2's release (``kappa0``, ``phi0``) at rest
    (:func:`dynamics.simulation.simulate`, the compiled integrator) and is
    averaged over [t_settle, t_end] (units of tau). The correlation length
    ``correlation`` is in rad on both surfaces (a = b in the reduced model).

    Returns
    -------
    uniform : float
        The steady Omega_b of the uniform kappa*_mean (5.10)-(5.11). (6.1) is
        V = V* sin(alpha) Omega_b / (3 s), so ratios of rates are ratios of speeds.
    rows : tuple of SpeedRow

    Raises
    ------
    RuntimeError
        If a run does not reach ``t_end``.
    """
    uniform = steady_state(params.s, mean.kappa_star, mean.psi).omega_b
    rows = []
    for amplitude in amplitudes:
        stats = []
        for seed in seeds:
            rough = RoughContact.from_seed(mean, amplitude, correlation, correlation, seed)
            traj = simulate(params, Initial(kappa0, phi0), t_end, contact=rough, limits=Limits(max_turns=1e6),
                            rtol=rtol)
            if traj.status != "completed":
                msg = f"amplitude {amplitude:g}, seed {seed}: the run stopped early: {traj.message}"
                raise RuntimeError(msg)
            stats.append(rolling_statistics(traj, t_settle))
        rates, fluctuations, switch_rates = np.array(stats).T
        rows.append(SpeedRow(float(amplitude), float(rates.mean()), float(rates.std(ddof=1)) if rates.size > 1
                             else 0.0, float(rates.mean()) / uniform, float(fluctuations.mean()),
                             float(switch_rates.mean()), len(stats)))
    return uniform, tuple(rows)
