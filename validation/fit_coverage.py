r"""How well ``snail fit`` recovers the roughness from a descent: its intervals on records the model makes.

The paper suggests that "the unsteadiness offers insight into the variations of
kappa*". :mod:`dynamics.fit` infers the roughness's amplitude and correlation
length, and the friction, from a record X_b(t) by approximate Bayesian computation. This study asks
whether its stated 90 % intervals hold, and how narrow they are, for the device of
Table 3 (steel, 500 cSt) with the full equations (2.1)-(2.4), the exact Stokes
forces and surfaces that turn with both cylinders, on 4 degrees, where every
realisation rolls:

* :data:`RECORDS` synthetic records of 60 s, sampled as a camera at
  :data:`RATE` Hz, each with parameters drawn from the priors of :data:`SCENE`'s
  ``[fit]`` section and surfaces of its own (seeds no draw of the table uses);
* each fitted against one reference table of :data:`DRAWS` runs (the default of
  ``snail fit``) with the default acceptance, :func:`dynamics.fit.coverage`;
* per parameter, the share of the intervals that contain the truth (90 % if they
  are right; the binomial spread of that share over the records is stated), the
  intervals' width against the prior's, and the estimates' error.

``python -m validation.fit_coverage`` runs it on 2 worker processes (minutes) and
stores the numbers in ``docs/fit_coverage/fit_coverage.json``; ``python -m
validation.reports.fit_coverage`` writes ``docs/fit_coverage.md`` and its figure
from them.
"""

from __future__ import annotations

import math
import time
import warnings
from pathlib import Path

import numpy as np

from dynamics.equations.limits import ValidityWarning
from dynamics.fit import coverage, read_fit_scene

from . import rough_experiments
from .checks import Check, at_least

__all__ = ["ACCEPT", "DRAWS", "RATE", "RECORDS", "RESULTS", "SCENE", "checks_of", "compute", "findings",
           "fitted_records"]

#: The rough-surface study's scene on 4 degrees, where every realisation rolls, with the unknowns and their priors.
SCENE = rough_experiments.SCENE.replace('alpha = "2.4 deg"', 'alpha = "4 deg"') + """[fit]
"contact.roughness_amplitude" = {low = 0.1, high = 0.6}
"contact.roughness_correlation" = {low = "0.5 mm", high = "5 mm", log = true}
"contact.friction_angle" = {low = "2 deg", high = "10 deg"}
"""
RECORDS = 40
RATE = 25.0  # Hz: a camera's frames
DRAWS = 2000  # snail fit's default
ACCEPT = 0.1  # snail fit's default
WORKERS = 2
RESULTS = Path(__file__).resolve().parents[1] / "docs" / "fit_coverage" / "fit_coverage.json"


def compute(log=print) -> dict:
    import logging

    from dask.distributed import Client, LocalCluster

    start = time.perf_counter()
    raw, priors = read_fit_scene(SCENE)
    times = np.arange(0.0, 60.0, 1.0 / RATE)
    rng = np.random.default_rng(7)
    truths = np.column_stack([p.draw(rng, RECORDS) for p in priors])
    log(f"a reference table of {DRAWS} runs on {WORKERS} workers, then {RECORDS} records fitted")
    with warnings.catch_warnings(), LocalCluster(n_workers=WORKERS, threads_per_worker=1, processes=True,
                                                 dashboard_address=":0", silence_logs=logging.CRITICAL) as cluster, \
            Client(cluster) as client:
        warnings.simplefilter("ignore", ValidityWarning)  # Re* passed in the release's first swing
        contained, fits = coverage(raw, priors, truths, times, draws=DRAWS, accept=ACCEPT, client=client)
    parameters = []
    for j, p in enumerate(priors):
        parameters.append({"key": p.key, "low": p.low, "high": p.high, "log": p.log,
                           "truth": truths[:, j].tolist(),
                           "estimate": [None if fit is None else fit.estimate[p.key] for fit in fits],
                           "interval": [None if fit is None else list(fit.interval[p.key]) for fit in fits],
                           "contained": [None if math.isnan(c) else bool(c) for c in contained[:, j]]})
    fitted = next(fit for fit in fits if fit is not None)
    return {"scene": SCENE, "records": RECORDS, "rate_hz": RATE, "draws": DRAWS, "accept": ACCEPT,
            "table_size": fitted.table_size, "accepted": fitted.accepted, "parameters": parameters,
            "wall_time_s": time.perf_counter() - start}


def fitted_records(parameter: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(truth, estimate, interval, contained) of the records that roll (one that does not has no fit)."""
    rows = [i for i, c in enumerate(parameter["contained"]) if c is not None]
    return (np.array([parameter["truth"][i] for i in rows]), np.array([parameter["estimate"][i] for i in rows]),
            np.array([parameter["interval"][i] for i in rows]).reshape(-1, 2),
            np.array([parameter["contained"][i] for i in rows], dtype=bool))


def _summary(parameter: dict) -> dict:
    """Over the records that roll: coverage, its binomial standard error at the nominal 90 %, the median width
    over the prior's, and the median relative error of the estimates (in the logarithm for a log prior)."""
    truth, estimate, interval, contained = fitted_records(parameter)
    n = truth.size
    if parameter["log"]:
        width = np.log(interval[:, 1] / interval[:, 0]) / math.log(parameter["high"] / parameter["low"])
    else:
        width = (interval[:, 1] - interval[:, 0]) / (parameter["high"] - parameter["low"])
    return {"fitted": n, "coverage": float(np.mean(contained)), "se": math.sqrt(0.9 * 0.1 / n),
            "width": float(np.median(width)), "error": float(np.median(np.abs(estimate / truth - 1.0)))}


def checks_of(result: dict) -> list[Check]:
    """The stated 90 % intervals contain the truth in at least 80 % of the records, for each parameter."""
    return [at_least(f"{p['key']}: share of the 90 % intervals that contain the truth", _summary(p)["coverage"],
                     0.8, note=f"{_summary(p)['fitted']} records that roll") for p in result["parameters"]]


def findings(result: dict) -> list[dict]:
    """How narrow the intervals are and how near the estimates, per parameter."""
    out = []
    for p in result["parameters"]:
        s = _summary(p)
        prior = "in the logarithm, " if p["log"] else ""
        records = ("the records" if s["fitted"] == len(p["truth"]) else
                   f"the {s['fitted']} records that roll (of {len(p['truth'])})")
        out.append({"name": p["key"],
                    "text": f"intervals contain the truth in {s['coverage']:.0%} of {records} (90 % if right, "
                            f"binomial standard error {s['se']:.0%}); their median width is {s['width']:.2f} of the "
                            f"prior's ({prior}{p['low']:.3g} to {p['high']:.3g}, SI); the estimates' median relative "
                            f"error is {s['error']:.0%}"})
    return out


if __name__ == "__main__":
    from numerics.files import write_json

    result = compute(log=lambda text: print(text, flush=True))
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    write_json(RESULTS, result)
    print(RESULTS)
