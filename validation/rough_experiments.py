r"""Surfaces that turn with the cylinders against the experiments of section 4 and figures 10-11.

The paper's experiments disagree with its smooth-wall theory in four ways: on
shallow slopes the cylinders (a) roll at a mean speed that stays steady, (b)
rock irregularly, the inner cylinder near its lowest point but dragged slightly
up the rear side; (c) the speeds grow with the slope and steepen; (d) the data
suggest a gradual transition from locked to sliding contact near 3 degrees, where
a uniform minimum gap kappa* switches abruptly. This study runs the full
equations (2.1)-(2.4) with the exact Stokes forces and rough surfaces that turn
with both bodies (:mod:`dynamics.contact.rough_full`) on the apparatus of
Table 3 (steel, 500 cSt), each 60 s from the release kappa = 0.5, phi = 0.5 rad:

* :data:`SCENE` at 2.4 deg with smooth walls, with a uniform kappa* (the paper's
  sigma = 50 um) and with rough surfaces of the same mean minimum gap;
* an ensemble of :data:`SEEDS` surface realisations there: the statistics of
  :func:`dynamics.ensemble.unsteadiness`, the speed over the third and the
  fourth quarter of each run, and the spectrum of the speed against the distance
  rolled (:func:`dynamics.fit.distance_spectrum`), where each surface's
  features recur with its own circumference: 2 pi a and 2 pi b;
* the slopes :data:`SLOPES`, uniform and rough (:data:`SLOPE_SEEDS` realisations):
  mean speed and share of the time locked;
* the uniform sigma that rolls at the rough ensemble's mean speed: the paper's
  kappa* read as an effective value;
* a tilt of the inner cylinder's axis over the free flights between contacts of
  the ensemble's realisations (:func:`dynamics.tilt.tilt_in_flights`): how far a
  tilt seeded at a lift-off grows before the next touch realigns the axis.

``python -m validation.rough_experiments`` runs it (minutes) and stores the numbers
in ``docs/rough_experiments/rough_experiments.json``; ``python -m
validation.reports.rough_experiments`` writes ``docs/rough_experiments.md`` and
its figures from them.
"""

from __future__ import annotations

import math
import time
import warnings
from pathlib import Path

import numpy as np

from dynamics.ensemble import ensemble_statistics, unsteadiness
from dynamics.equations.limits import ValidityWarning
from dynamics.fit import distance_spectrum

from .checks import Check, absolute, at_least, at_most

__all__ = ["RESULTS", "SCENE", "SEEDS", "SLOPES", "checks_of", "compute", "findings", "relative_density",
           "turn_contrast"]

SCENE = """[apparatus]
preset = "steel"
[fluid]
nu = "500 cSt"
[incline]
alpha = "2.4 deg"
[initial]
kappa = 0.5
phi = 0.5
[contact]
sigma = "50 um"
friction_angle = "5 deg"
roughness_amplitude = 0.5
roughness_correlation = "1 mm"
[run]
t_end = "60 s"
output_interval = "0.01 s"
max_gap_reynolds = "none"
on_invalid = "warn"
"""
SEEDS = 16
#: The spectrum needs many turns of each surface: the runs of SEEDS realisations for it are this long, on a slope
#: where every realisation rolls (at 2.4 deg a 60 s run covers about four turns of the inner cylinder).
SPECTRUM_SLOPE = 4.0
SPECTRUM_T_END = 300.0
SLOPES = (1.5, 2.0, 2.4, 3.0, 4.0, 5.0)
SLOPE_SEEDS = 4
#: Uniform minimum gaps (m) among which the one matching the rough ensemble's mean speed is interpolated.
SIGMAS = (10e-6, 20e-6, 35e-6, 50e-6, 70e-6, 100e-6)
#: A realisation has halted when its late mean speed is below this share of the uniform kappa*'s.
HALTED = 0.1
#: Wavelengths (m) at which the spectrum's density is read, log-spaced across the record's range.
WAVELENGTHS = tuple(float(x) for x in np.geomspace(0.01, 0.3, 91))
#: A band of wavelengths within this fraction of its centre (as :func:`dynamics.fit.summary_statistics`).
BAND = 0.1
RESULTS = Path(__file__).resolve().parents[1] / "docs" / "rough_experiments" / "rough_experiments.json"
SERIES_STEP = 0.05  # s between the stored rows of the showcase runs


#: The scene with smooth walls: no [contact] section.
SMOOTH = SCENE[:SCENE.index("[contact]")] + SCENE[SCENE.index("[run]"):]


def _run(overrides: list[str], text: str = SCENE):
    from dynamics.app.run import run_scene
    from dynamics.scenes import parse_scene

    scene = parse_scene(text, "<rough experiments>", overrides)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)  # Re* passed in the release's first swing: recorded
        run = run_scene(scene)
    if run.status != "completed":
        raise RuntimeError(f"{overrides}: {run.message}")
    return run, scene.apparatus


def relative_density(t, x_b, wavelengths=WAVELENGTHS) -> list[float]:
    """The share of the speed's fluctuation power within BAND of each wavelength, over the share a flat
    spectrum would put there (1 everywhere for white noise); NaN for a run that does not roll forward."""
    t, x_b = np.asarray(t, dtype=float), np.asarray(x_b, dtype=float)
    rising = np.concatenate(([True], np.diff(t) > 0))  # an event row repeats its time
    try:
        _, wavelength, power, _ = distance_spectrum(t[rising], x_b[rising])
    except ValueError:  # it stopped: rough surfaces can hold the device on a slope
        return [math.nan] * len(wavelengths)
    power, wavelength = power[1:], wavelength[1:]
    total = float(np.sum(power))
    out = []
    for length in wavelengths:
        inside = np.abs(wavelength / length - 1.0) < BAND
        out.append(float(np.sum(power[inside]) / total / (np.count_nonzero(inside) / power.size))
                   if np.any(inside) else math.nan)
    return out


def _quarters(run) -> tuple[float, float]:
    """Mean speeds over the third and the fourth quarter of the run (m/s)."""
    t, x = run.columns["t"], run.columns["x_b"]
    end = t[-1]
    x_at = np.interp([0.5 * end, 0.75 * end, end], t, x)
    return float((x_at[1] - x_at[0]) / (0.25 * end)), float((x_at[2] - x_at[1]) / (0.25 * end))


def _numbers(run, ap) -> dict:
    q3, q4 = _quarters(run)
    return {**unsteadiness(run, ap.a, ap.b), "speed_q3": q3, "speed_q4": q4, "quarter_ratio": q4 / q3}


def _series(run) -> dict:
    c = run.columns
    grid = np.arange(0.0, c["t"][-1], SERIES_STEP)
    t, index = np.unique(c["t"], return_index=True)
    return {"t": grid.tolist(), **{k: [float(f"{v:.6g}") for v in np.interp(grid, t, np.asarray(c[k])[index])]
                                   for k in ("x_b", "phi", "one_minus_kappa")}}


def _tilt(ap) -> dict:
    """Per realisation of the ensemble, run again with a row at every step: its free flights' durations and the
    largest gain of a unit tilt over each (:func:`dynamics.tilt.tilt_in_flights`, the exact Stokes forces)."""
    from dynamics.tilt import tilt_in_flights

    per_seed = []
    for seed in range(SEEDS):
        run, _ = _run([f"contact.seed={seed}", "run.output_interval=none"])
        flights = tilt_in_flights(run, ap)
        per_seed.append({"seed": seed, "duration": (flights.end - flights.start).tolist(),
                         "gain": flights.gain.tolist(), "frozen_growth": flights.frozen_growth.tolist()})
    return {"forces": "stokes-exact", "realisations": per_seed}


def compute(log=print) -> dict:
    start = time.perf_counter()
    showcase = {}
    for label, text, overrides in (("smooth", SMOOTH, []), ("uniform", SCENE, ["contact.roughness_amplitude=0"]),
                                   ("rough", SCENE, ["contact.seed=0"])):
        log(f"showcase: {label}")
        run, ap = _run(overrides, text)
        showcase[label] = {**_numbers(run, ap), "series": _series(run)}
    a, b = ap.a, ap.b
    log(f"ensemble: {SEEDS} realisations")
    realisations = [{"seed": seed, **_numbers(_run([f"contact.seed={seed}"])[0], ap)} for seed in range(SEEDS)]
    halt_speed = HALTED * showcase["uniform"]["mean_speed_late"]
    rolling = [r for r in realisations if r["mean_speed_late"] > halt_speed]
    numbers = [k for k in realisations[0] if k != "seed"]
    stats = {"all": ensemble_statistics(realisations, by=(), numbers=numbers)[0],
             "rolling": ensemble_statistics(rolling, by=(), numbers=numbers)[0],
             "halted": len(realisations) - len(rolling), "halt_speed": halt_speed}
    log(f"spectrum: {SEEDS} realisations of {SPECTRUM_T_END:g} s at {SPECTRUM_SLOPE:g} deg")
    turns = (2.0 * math.pi * a, 2.0 * math.pi * b)
    records = {"outer": [], "inner": []}
    for seed in range(SEEDS):
        run, _ = _run([f"contact.seed={seed}", f"incline.alpha={SPECTRUM_SLOPE} deg",
                       f"run.t_end={SPECTRUM_T_END} s"])
        t = run.columns["t"]
        # the distance rolled, and the inner surface's arc past the contact (theta_a = phi - Theta_a)
        for name, x in (("outer", run.columns["x_b"]), ("inner", -a * np.unwrap(run.columns["theta_a"]))):
            records[name].append((relative_density(t, x), relative_density(t, x, turns)))
    spectrum = {"slope_deg": SPECTRUM_SLOPE, "t_end_s": SPECTRUM_T_END, "wavelengths": list(WAVELENGTHS),
                "turn_a": turns[0], "turn_b": turns[1]}
    for name, rows in records.items():
        density = np.array([row[0] for row in rows])
        spectrum[name] = {"mean": np.mean(density, axis=0).tolist(),
                          "se": (np.std(density, axis=0, ddof=1) / math.sqrt(SEEDS)).tolist(),
                          "at_turns": [row[1] for row in rows]}
    slopes = []
    for slope in SLOPES:
        log(f"slope {slope:g} deg")
        uniform, _ = _run([f"incline.alpha={slope} deg", "contact.roughness_amplitude=0"])
        rough = [_numbers(_run([f"incline.alpha={slope} deg", f"contact.seed={seed}"])[0], ap)
                 for seed in range(SLOPE_SEEDS)]
        slopes.append({"slope_deg": slope, "uniform": _numbers(uniform, ap),
                       "rough": ensemble_statistics(rough, by=(), numbers=("mean_speed_late", "locked_fraction_late",
                                                                             "phi_rms_late"))[0]})
    log(f"tilt over the free flights: {SEEDS} realisations")
    tilt = _tilt(ap)
    log("uniform sigmas")
    uniform_speeds = []
    for sigma in SIGMAS:
        run, _ = _run([f"contact.sigma={sigma}", "contact.roughness_amplitude=0"])
        uniform_speeds.append(_numbers(run, ap)["mean_speed_late"])
    target = stats["rolling"]["mean_speed_late_mean"]
    inside = uniform_speeds[0] <= target <= uniform_speeds[-1]  # the speeds grow with sigma: no extrapolation
    sigma_eff = float(np.exp(np.interp(math.log(target), np.log(uniform_speeds), np.log(SIGMAS)))) if inside \
        else None
    return {"scene": SCENE, "a": a, "b": b, "seeds": SEEDS, "showcase": showcase, "realisations": realisations,
            "ensemble": stats, "spectrum": spectrum, "slopes": slopes, "slope_seeds": SLOPE_SEEDS,
            "sigmas": list(SIGMAS), "uniform_speeds": uniform_speeds, "sigma_effective": sigma_eff, "tilt": tilt,
            "wall_time_s": time.perf_counter() - start}


def turn_contrast(spectrum: dict, record: str, turn: float) -> tuple[float, float]:
    """Of the spectrum of ``record`` ("outer": the speed against the distance rolled; "inner": the inner
    surface's speed past the contact against its arc), the ensemble's mean density within BAND of ``turn``
    (the mean of the realisations' own), and the local
    background: the median of the mean spectrum over wavelengths within a factor 2 of ``turn`` that lie more
    than 2 BAND from either surface's turn (harmonics left in: they can only raise the background)."""
    w = np.array(spectrum["wavelengths"])
    turns = (spectrum["turn_a"], spectrum["turn_b"])
    near = (w > turn / 2.0) & (w < turn * 2.0)
    clear = np.array([all(abs(x / line - 1.0) > 2.0 * BAND for line in turns) for x in w])
    column = 0 if turn == turns[0] else 1
    at = float(np.mean([row[column] for row in spectrum[record]["at_turns"]]))
    return at, float(np.nanmedian(np.array(spectrum[record]["mean"], dtype=float)[near & clear]))


def checks_of(result: dict) -> list[Check]:
    """What the study claims, each judged from the stored numbers.

    (a) The rolling realisations' speed over the fourth quarter equals that over the third, within three
    standard errors of their mean ratio or 5 %, whichever is larger; the smooth run's ratio is below that band.
    (b) They switch contact phases (a rate above zero by three standard errors) and sit up the rear side
    (phi - pi > 0, three standard errors). The spectra (:func:`turn_contrast`): the outer cylinder's speed
    against the distance rolled has at least twice the local background's density at 2 pi b (the outer rolls
    on the plane without slipping, so its features recur exactly there); the inner surface's speed past the
    contact, against its own arc, at 2 pi a. Against the distance rolled the inner features recur at 2 pi a
    only while the surfaces are locked (a Omega_a = b Omega_b): sliding stretches that period, which the page
    states as a finding. (c) The rough speeds grow with the slope, faster than sin(alpha) from 3 degrees up.
    (d) The rough runs' locked share falls with the slope (by at most 0.05 up at any step).
    """
    rolling = result["ensemble"]["rolling"]
    band = max(0.05, 3.0 * rolling["quarter_ratio_se"])
    checks = [absolute("(a) rolling realisations: speed over the 4th quarter over the 3rd", rolling["quarter_ratio_mean"],
                       1.0, band, note="three standard errors or 5 %"),
              at_most("(a) smooth walls: speed over the 4th quarter over the 3rd",
                      result["showcase"]["smooth"]["quarter_ratio"], 1.0 - band, note="they slow down"),
              at_least("(b) contact switches per s, standard errors above zero",
                       rolling["switch_rate_late_mean"] / rolling["switch_rate_late_se"], 3.0),
              at_least("(b) phi - pi, standard errors above zero (up the rear side)",
                       (rolling["phi_mean_late_mean"] - math.pi) / rolling["phi_mean_late_se"], 3.0)]
    spectrum = result["spectrum"]
    for record, name, turn, against in (("outer", "2 pi b", spectrum["turn_b"], "the distance rolled"),
                                        ("inner", "2 pi a", spectrum["turn_a"], "the inner surface's arc")):
        at, background = turn_contrast(spectrum, record, turn)
        checks.append(at_least(f"spectrum against {against}: density at {name} over the local background",
                               at / background, 2.0))
    slopes = result["slopes"]
    speeds = [s["rough"]["mean_speed_late_mean"] for s in slopes]
    checks.append(at_least("(c) rough: smallest ratio of the speeds on consecutive slopes",
                           min(b / a for a, b in zip(speeds, speeds[1:])), 1.0))
    per_sin = {s["slope_deg"]: s["rough"]["mean_speed_late_mean"] / math.sin(math.radians(s["slope_deg"]))
               for s in slopes}
    checks.append(at_least("(c) rough: speed over sin(alpha) at the steepest slope over at 3 degrees",
                           per_sin[max(per_sin)] / per_sin[3.0], 1.0, note="the speeds steepen"))
    locked = [s["rough"]["locked_fraction_late_mean"] for s in slopes]
    checks.append(at_most("(d) rough: largest rise of the locked share from one slope to the next",
                          max(b - a for a, b in zip(locked, locked[1:])), 0.05))
    return checks


def findings(result: dict) -> list[dict]:
    """Numbers the page states without a verdict: the spectrum's contrast at each turn."""
    out = []
    spectrum = result["spectrum"]
    for record, against in (("outer", "against the distance rolled"), ("inner", "against the inner surface's arc")):
        for name, turn in (("2 pi a", spectrum["turn_a"]), ("2 pi b", spectrum["turn_b"])):
            at, background = turn_contrast(spectrum, record, turn)
            out.append({"name": f"{against}, density at {name}",
                        "text": f"{at:.3g} times a flat spectrum's, against {background:.3g} around it "
                                f"({at / background:.2g} times the local background)"})
    return out


if __name__ == "__main__":
    import json

    from numerics.files import write_json

    result = compute(log=lambda text: print(text, flush=True))
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    # numpy scalars as plain numbers, and NaN (a number a run cannot give) as null
    plain = json.loads(json.dumps(result, default=lambda x: x.item()).replace("NaN", "null"))
    write_json(RESULTS, plain)
