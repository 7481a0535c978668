"""One point of a sweep: its scene built, run and classified into one row of ``sweep.csv``.

:func:`classify_point` extends :func:`dynamics.regime.classify` (runaway,
rocking, sedimenting, locked and sliding rolling in contact, steady rolling,
transient) by "failed": the run raised or failed, and the row says why. The
row carries the numbers that decided the regime (:data:`dynamics.app.sweeps.store.NUMBERS`).
:func:`run_point` is the path every point can take, one scene at a time through
:func:`dynamics.app.run.run_scene`; :mod:`dynamics.app.sweeps.batch` runs the
common case, the reduced equations without contact, many points at once to the
same rows.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from typing import Any

from dynamics.app.sweeps.spec import point_key
from dynamics.ensemble import unsteadiness
from dynamics.regime import REGIMES as _CLASSIFIED
from dynamics.regime import classify, late_half
from dynamics.scenes import parse_scene

__all__ = ["REGIMES", "classify_point", "run_point"]

REGIMES = (*_CLASSIFIED, "failed")

# The evidence of dynamics.regime.classify that every row carries.
_EVIDENCE = ("final_kappa", "turns_of_phi_late", "phi_reversals_late", "omega_b_tau_growth_late", "stop_event")


def classify_point(trajectory) -> tuple[str, dict[str, Any]]:
    """The regime of a trajectory and the numbers that decided it.

    A failed or interrupted run is "failed"; otherwise the regime is that of
    :func:`dynamics.regime.classify` (steady rolling in contact is "locked
    rolling" or "sliding rolling" there).

    Returns
    -------
    regime : str
        One of :data:`REGIMES`.
    numbers : dict
        The keys of :data:`~dynamics.app.sweeps.store.NUMBERS` from ``t_end_tau`` to ``stop_event``.
    """
    c = trajectory.columns
    t = c["t_tau"]
    omega_b = c["omega_b"] * trajectory.tau
    regime, evidence = classify(trajectory)
    _, _, _, phi_spread, _, omega_b_spread = late_half(t, c["phi"], c["one_minus_kappa"], omega_b)
    final = float(omega_b[-1])
    numbers = {"t_end_tau": float(t[-1]), **{k: evidence[k] for k in _EVIDENCE},
               "omega_b_tau_final": final,
               # the spread, not the end-to-end change: a rocking Omega_b can end where it began
               "omega_b_change_late": omega_b_spread / abs(final) if final else math.inf,
               "phi_range_late": phi_spread}
    return ("failed" if trajectory.status in ("failed", "interrupted") else regime), numbers


def _radii(scene) -> tuple[float, float]:
    """a and b in the unit of the run's x_b: m, or b in a dimensionless scene (a unknown without delta/a)."""
    if scene.apparatus is not None:
        return scene.apparatus.a, scene.apparatus.b
    delta_over_a = scene.groups.delta_over_a
    return (1.0 / (1.0 + delta_over_a) if delta_over_a else math.nan), 1.0


def run_point(base: Mapping[str, Any], point: Mapping[str, Any], source: str = "[base]") -> dict[str, Any]:
    """Build, run and classify one point; a failure becomes a "failed" row with its reason. A point with
    rough contact also gets its unsteadiness (:func:`dynamics.ensemble.unsteadiness`).

    Returns
    -------
    dict
        The axis values, ``point`` (:func:`~dynamics.app.sweeps.spec.point_key`) and the keys of
        :data:`~dynamics.app.sweeps.store.NUMBERS`.
    """
    from dynamics.app.run import run_scene

    start = time.perf_counter()
    row = {**point, "point": point_key(point)}
    try:
        scene = parse_scene(base, source, point)
        trajectory = run_scene(scene)
        regime, numbers = classify_point(trajectory)
        if scene.contact is not None:
            numbers.update(unsteadiness(trajectory, *_radii(scene)))
        row.update(numbers, status=trajectory.status, regime=regime, steps=trajectory.steps,
                   reason=trajectory.message if regime == "failed" else "")
    # A point fails alone: any error is its reason, and the sweep goes on.
    except Exception as err:  # noqa: BLE001
        row.update(status="failed", regime="failed", reason=f"{type(err).__name__}: {err}")
    row["wall_time_s"] = time.perf_counter() - start
    return row
