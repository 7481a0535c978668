"""The unsteadiness of a rolling run, and its statistics over an ensemble of surface realisations.

On shallow slopes the cylinders of the experiments roll erratically, rocking back
and forth about a mean speed that stays steady (section 4, figure 5). A model with
surfaces that turn with the cylinders (:mod:`dynamics.contact.roughness`) makes
each run one realisation of the surfaces; what it predicts is read off the second
half of a run (after the release's transient) by :func:`unsteadiness`, and over
realisations (runs that differ only in ``contact.seed``) by
:func:`ensemble_statistics`: the count, mean, standard deviation and standard
error of the mean of each number, so that a user sees how far the ensemble has
converged.

The numbers of one run (:data:`UNSTEADINESS`), over its second half, each
average time-weighted (trapezoidal over the rows, or over row intervals for the
speed, so that the output rows' spacing does not weigh them):

* ``mean_speed_late``: distance rolled over time (m/s, or b/tau in a
  dimensionless scene);
* ``speed_spread_late``: standard deviation of the speed about that mean (the
  speed of each row interval);
* ``phi_mean_late``, ``phi_rms_late``: the mean angle of the line of centres
  (from the upward vertical, unwrapped: pi at the lowest point) and its
  standard deviation, the rocking amplitude (a mean away from pi is the inner
  cylinder dragged up one side);
* ``locked_fraction_late``: share of the time in the locked phase (NaN
  without a hard contact);
* ``switch_rate_late``: contact switches (touch, lift, stick, slip) per unit
  time;
* ``power_at_2pi_a``, ``power_at_2pi_b``: the share of the speed's fluctuation,
  against the distance rolled, within 10 % of the wavelengths 2 pi a and 2 pi b
  at which each surface's features recur (:func:`dynamics.fit.summary_statistics`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from dynamics.regime import late_half
from dynamics.trajectory import PHASE_CODES

__all__ = ["ENSEMBLE_FIELDS", "UNSTEADINESS", "ensemble_statistics", "unsteadiness"]

#: The numbers :func:`unsteadiness` reads off a run, in order.
UNSTEADINESS = ("mean_speed_late", "speed_spread_late", "phi_mean_late", "phi_rms_late", "locked_fraction_late",
                "switch_rate_late", "power_at_2pi_a", "power_at_2pi_b")
#: What :func:`ensemble_statistics` gives of each number: count, mean, standard deviation, standard error.
ENSEMBLE_FIELDS = ("n", "mean", "sd", "se")
_SWITCHES = ("touch", "lift", "stick", "slip")


def unsteadiness(trajectory, a: float, b: float) -> dict[str, float]:
    """The :data:`UNSTEADINESS` of ``trajectory`` over its second half.

    Parameters
    ----------
    trajectory : dynamics.trajectory.Trajectory
        Any run; the numbers a run cannot give (a locked share without contact, the turn
        spectrum of a run that does not roll forward or has too few rows) are NaN.
    a, b : float
        The radii in the unit of the run's x_b (m, or b in a dimensionless scene).
    """
    c = trajectory.columns
    t, phi, x_b = (np.asarray(c[k], dtype=float) for k in ("t", "phi", "x_b"))
    out = dict.fromkeys(UNSTEADINESS, math.nan)
    late = late_half(t, phi, c["one_minus_kappa"], c["omega_b"])[0]
    t, phi, x_b = t[late:], phi[late:], x_b[late:]
    if t.size < 3 or not t[-1] > t[0]:
        return out
    dt = np.diff(t)
    span = t[-1] - t[0]
    speed = np.diff(x_b) / np.where(dt > 0, dt, np.inf)  # an event row repeats a time: its interval weighs 0
    mean = (x_b[-1] - x_b[0]) / span
    phi_mean = float(np.trapezoid(phi, t) / span)
    out.update(mean_speed_late=float(mean),
               speed_spread_late=math.sqrt(float(np.sum(dt * (speed - mean) ** 2)) / span),
               phi_mean_late=phi_mean, phi_rms_late=math.sqrt(float(np.trapezoid((phi - phi_mean) ** 2, t)) / span),
               switch_rate_late=sum(e["name"] in _SWITCHES and e["t"] >= t[0] for e in trajectory.events) / span)
    if "phase" in c:
        phase = np.asarray(c["phase"], dtype=float)[late:]
        out["locked_fraction_late"] = float(np.sum(dt[phase[:-1] == PHASE_CODES["locked"]]) / span)
    if mean > 0 and t.size >= 16 and math.isfinite(a):
        from dynamics.fit import STATISTICS, summary_statistics

        rising = np.concatenate(([True], dt > 0))  # an event row repeats its time
        try:
            stats = dict(zip(STATISTICS, summary_statistics(t[rising], x_b[rising], a, b)))
        except ValueError:  # its own window (the half less a tenth) does not roll forward: no spectrum
            return out
        out.update(power_at_2pi_a=stats["power_at_2pi_a"], power_at_2pi_b=stats["power_at_2pi_b"])
    return out


def ensemble_statistics(rows: Iterable[Mapping], by: Sequence[str], numbers: Sequence[str] = UNSTEADINESS
                        ) -> list[dict]:
    """Each number's :data:`ENSEMBLE_FIELDS` over the rows that share the values of ``by``.

    Parameters
    ----------
    rows : iterable of mapping
        One row per realisation (a sweep's rows: strings or numbers); an empty or NaN
        value is left out of that number's statistics (a failed run, a number the run
        cannot give).
    by : sequence of str
        The keys that define a group (every axis but the realisation's seed).
    numbers : sequence of str
        The keys whose statistics are wanted.

    Returns
    -------
    list of dict
        One per group, in the order the groups first appear: the values of ``by``,
        ``realisations`` (rows in the group), and ``<number>_<field>`` for each number and
        field; sd is the sample standard deviation (n - 1), se = sd / sqrt(n), both NaN
        for fewer than two values.
    """
    groups: dict[tuple, list[Mapping]] = {}
    for row in rows:
        groups.setdefault(tuple(row[k] for k in by), []).append(row)
    out = []
    for values, members in groups.items():
        entry = {**dict(zip(by, values)), "realisations": len(members)}
        for name in numbers:
            x = np.array([float(v) for m in members if (v := m.get(name, "")) not in ("", None)], dtype=float)
            x = x[np.isfinite(x)]
            sd = float(np.std(x, ddof=1)) if x.size > 1 else math.nan
            entry.update({f"{name}_n": int(x.size), f"{name}_mean": float(np.mean(x)) if x.size else math.nan,
                          f"{name}_sd": sd, f"{name}_se": sd / math.sqrt(x.size) if x.size > 1 else math.nan})
        out.append(entry)
    return out
