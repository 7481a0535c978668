r"""The roughness and the friction inferred from the unsteadiness of a measured descent.

The paper observes that "in principle, the unsteadiness offers insight into the
variations of kappa*". A run with rough surfaces that turn with the cylinders
(:mod:`dynamics.contact.roughness`) rocks irregularly at a steady mean speed; how
fast, how irregularly, and at which distances rolled the kicks recur depend on
the roughness (its rms, relative to the mean gap, and its correlation length)
and on the friction. From a measured X_b(t) (a camera's times and positions),
this module infers the parameters a scene marks as unknown, with intervals, by
approximate Bayesian computation (ABC):

1. **Summary statistics** of a record (:func:`summary_statistics`): the mean
   speed over the record after its first tenth (log), the spread of the speed
   about it (its coefficient of variation over the same part), the power of the speed's fluctuation at
   the distances rolled 2 pi a and 2 pi b, where the features of the inner and
   the outer surface recur, relative to its whole power, and the correlation of
   the speed's fluctuation with itself one inner and one outer turn later.
2. **A reference table** (:func:`reference_table`): parameters drawn from the
   priors (uniform, or log-uniform), each with its own surfaces (a seed), run
   through the scene's model on the compiled engine, the record sampled at the
   data's times, and its statistics.
3. **The posterior** (:func:`abc_posterior`): the draws whose statistics lie
   nearest the data's (scaled by the table's median absolute deviations), weighted
   with the Epanechnikov kernel, then moved by the local-linear regression of
   Beaumont, Zhang & Balding (Genetics 162, 2002) on the statistics' differences,
   in a transformed parameter space where the priors' bounds are at infinity (so
   that adjusted draws stay inside them). The estimate is the weighted median, the
   interval the weighted 5 and 95 % quantiles.

The statistics and the tolerance are choices: :func:`coverage` measures whether
the stated intervals hold, on data sets made by the model itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.special import expit, logit

__all__ = ["STATISTICS", "FitResult", "Prior", "abc_posterior", "coverage", "distance_spectrum", "fit",
           "read_fit_scene", "read_record", "reference_table", "simulate_record", "summary_statistics"]

#: The summary statistics, in the order of :func:`summary_statistics`.
STATISTICS = ("log_mean_speed", "speed_variation", "power_at_2pi_a", "power_at_2pi_b", "correlation_at_2pi_a",
              "correlation_at_2pi_b")
#: The share of the record left out at its start, where the release's transient lives.
TRANSIENT = 0.1


@dataclass(frozen=True)
class Prior:
    """A parameter to infer: a scene key (``"contact.roughness_amplitude"``) and its prior, uniform on
    [low, high], or uniform in the logarithm (``log``). Values are in SI (lengths in m, angles in rad)."""

    key: str
    low: float
    high: float
    log: bool = False

    def __post_init__(self):
        if not (math.isfinite(self.low) and math.isfinite(self.high) and self.low < self.high):
            msg = f"fit.{self.key}: low must be below high, both finite, got low = {self.low!r}, high = {self.high!r}"
            raise ValueError(msg)
        if self.log and not self.low > 0:
            msg = f"fit.{self.key}: a log prior needs low > 0, got {self.low!r}"
            raise ValueError(msg)

    def draw(self, rng: np.random.Generator, n: int) -> np.ndarray:
        if self.log:
            return np.exp(rng.uniform(math.log(self.low), math.log(self.high), n))
        return rng.uniform(self.low, self.high, n)

    def to_free(self, x: np.ndarray) -> np.ndarray:
        """The parameter mapped onto the real line (logit of its place in the prior's range)."""
        lo, hi, x = ((math.log(self.low), math.log(self.high), np.log(x)) if self.log else (self.low, self.high, x))
        u = np.clip((x - lo) / (hi - lo), 1e-12, 1.0 - 1e-12)
        return logit(u)

    def from_free(self, y: np.ndarray) -> np.ndarray:
        lo, hi = (math.log(self.low), math.log(self.high)) if self.log else (self.low, self.high)
        x = lo + (hi - lo) * expit(y)  # the logistic function without overflow at large |y|
        return np.exp(x) if self.log else x


def _speed(t: np.ndarray, x_b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distances and speeds at the record's samples after the transient (central differences)."""
    keep = t >= t[0] + TRANSIENT * (t[-1] - t[0])
    t, x = t[keep], x_b[keep]
    return x[1:-1], (x[2:] - x[:-2]) / (t[2:] - t[:-2])


def distance_spectrum(t, x_b) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """The speed's fluctuation against the distance rolled, and its periodogram.

    The record X_b(t) after its transient (the first ``TRANSIENT`` share) gives the speed at each sample
    (central differences), resampled at equal distances rolled: the surfaces' features recur
    in distance, not in time. Returns the fluctuation u about the mean speed on that grid,
    the wavelengths (inf for the mean) and the periodogram |FFT(u)|^2 of each, and the mean speed.

    Raises
    ------
    ValueError
        For fewer than 16 increasing times, or a record that does not roll forward.
    """
    t, x_b = np.asarray(t, dtype=float), np.asarray(x_b, dtype=float)
    if t.ndim != 1 or t.size < 16 or t.shape != x_b.shape or not np.all(np.diff(t) > 0):
        msg = "a record needs at least 16 increasing times and as many positions"
        raise ValueError(msg)
    x, v = _speed(t, x_b)
    mean = float(np.mean(v))
    if not mean > 0:
        msg = f"the record does not roll forward (mean speed {mean:g} m/s): nothing to infer a roughness from"
        raise ValueError(msg)
    grid = np.linspace(x[0], x[-1], x.size)
    u = np.interp(grid, x, v) - mean
    power = np.abs(np.fft.rfft(u)) ** 2
    wavelength = np.divide(x[-1] - x[0] + (grid[1] - grid[0]), np.arange(power.size),
                           out=np.full(power.size, np.inf), where=np.arange(power.size) > 0)
    return u, wavelength, power, mean


def summary_statistics(t, x_b, a: float, b: float) -> np.ndarray:
    """The :data:`STATISTICS` of a record X_b(t) (s, m) of a device of radii ``a``, ``b`` (m).

    The speed's fluctuation is taken against the distance rolled (:func:`distance_spectrum`):
    its power in the band of wavelengths within 10 % of 2 pi a and of 2 pi b over its whole
    power, and its correlation with itself shifted by one inner and one outer turn (0 where
    the record is shorter than the shift).
    """
    u, wavelength, power, mean = distance_spectrum(t, x_b)
    dx = wavelength[1] / u.size
    total = max(float(np.sum(power[1:])), 1e-300)
    v = _speed(np.asarray(t, dtype=float), np.asarray(x_b, dtype=float))[1]  # at the samples, as recorded

    def band(length: float) -> float:
        inside = np.abs(wavelength / length - 1.0) < 0.1
        return float(np.sum(power[inside])) / total

    def correlation(length: float) -> float:
        lag = int(round(length / dx))
        if lag <= 0 or lag >= u.size - 2:
            return 0.0
        return float(np.corrcoef(u[:-lag], u[lag:])[0, 1])

    turn_a, turn_b = 2.0 * math.pi * a, 2.0 * math.pi * b
    return np.array([math.log(mean), float(np.std(v)) / mean, band(turn_a), band(turn_b), correlation(turn_a),
                     correlation(turn_b)])


def _overrides(priors, theta, seed: int) -> list[str]:
    return [f"{p.key}={float(value)!r}" for p, value in zip(priors, theta)] + [f"contact.seed={int(seed)}"]


def simulate_record(scene_raw: dict, priors, theta, seed: int, times) -> np.ndarray:
    """X_b at ``times`` (m) of the scene with the parameters ``theta`` (in the order of ``priors``) and
    surfaces ``seed``, the run's rows interpolated (PCHIP) at the times."""
    from dynamics.app.run import run_scene
    from dynamics.scenes import parse_scene

    scene = parse_scene(scene_raw, "<fit>", _overrides(priors, theta, seed))
    run = run_scene(scene)
    if run.status != "completed":
        msg = f"a run of the reference table stopped early: {run.message}"
        raise RuntimeError(msg)
    return run.sol(np.asarray(times, dtype=float), "x_b")


def _table_rows(scene_raw: dict, priors, thetas, seeds, times, a: float, b: float) -> np.ndarray:
    """Statistics of each draw (NaN for a draw whose run failed: it is left out of the table)."""
    rows = np.full((len(thetas), len(STATISTICS)), np.nan)
    for i, (theta, seed) in enumerate(zip(thetas, seeds)):
        try:
            rows[i] = summary_statistics(times, simulate_record(scene_raw, priors, theta, seed, times), a, b)
        except (RuntimeError, ValueError):
            continue
    return rows


def reference_table(scene_raw: dict, priors, draws: int, times, *, seed: int = 0, client=None,
                    progress=None) -> tuple[np.ndarray, np.ndarray]:
    """``draws`` parameter sets from the priors and the statistics of their runs at ``times``.

    Each draw gets its own surfaces (a seed drawn with it). With a dask ``client`` the draws run in
    batches on its workers; ``progress(done, total)`` is called as batches end. Draws whose runs fail
    are left out. Returns (parameters (n, len(priors)), statistics (n, len(STATISTICS))).
    """
    from dynamics.scenes import parse_scene

    rng = np.random.default_rng(seed)
    thetas = np.column_stack([p.draw(rng, draws) for p in priors])
    seeds = rng.integers(0, 2**31 - 1, draws)
    scene = parse_scene(scene_raw, "<fit>", _overrides(priors, thetas[0], seeds[0]))
    a, b = scene.apparatus.a, scene.apparatus.b
    size = max(1, min(50, draws // 16 or 1))
    batches = [slice(i, min(i + size, draws)) for i in range(0, draws, size)]
    stats = np.full((draws, len(STATISTICS)), np.nan)
    if client is None:
        for k, part in enumerate(batches):
            stats[part] = _table_rows(scene_raw, priors, thetas[part], seeds[part], times, a, b)
            if progress is not None:
                progress(part.stop, draws)
    else:
        from dask.distributed import as_completed

        futures = {client.submit(_table_rows, scene_raw, priors, thetas[part], seeds[part], times, a, b,
                                 pure=False): part for part in batches}
        done = 0
        for future in as_completed(futures):
            part = futures[future]
            stats[part] = future.result()
            done += part.stop - part.start
            if progress is not None:
                progress(done, draws)
    ok = np.all(np.isfinite(stats), axis=1)
    return thetas[ok], stats[ok]


@dataclass(frozen=True)
class FitResult:
    """The posterior of the unknowns: estimates and 90 % intervals, and what they rest on."""

    keys: tuple[str, ...]
    estimate: dict  # key -> weighted posterior median
    interval: dict  # key -> (5 %, 95 %) weighted quantiles
    samples: np.ndarray  # (accepted, len(keys)), regression-adjusted
    weights: np.ndarray
    observed: np.ndarray  # the data's statistics
    accepted: int
    table_size: int
    info: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        return {"keys": list(self.keys), "estimate": self.estimate,
                "interval_90": {k: list(v) for k, v in self.interval.items()},
                "observed_statistics": dict(zip(STATISTICS, map(float, self.observed))),
                "accepted": self.accepted, "table_size": self.table_size, **self.info}


def _weighted_quantile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    order = np.argsort(values)
    cumulative = np.cumsum(weights[order])
    cumulative /= cumulative[-1]
    return float(np.interp(q, cumulative - 0.5 * weights[order] / weights.sum(), values[order]))


def abc_posterior(priors, observed: np.ndarray, thetas: np.ndarray, stats: np.ndarray, *,
                  accept: float = 0.1) -> FitResult:
    """Rejection ABC with local-linear regression adjustment (module docstring) on a reference table.

    ``accept`` is the share of the table kept: the draws whose scaled distance to ``observed`` is
    smallest, weighted 1 - (d/d_max)^2.
    """
    observed = np.asarray(observed, dtype=float)
    if not 0.0 < accept <= 1.0:
        msg = f"accept must be in (0, 1], got {accept!r}"
        raise ValueError(msg)
    scale = np.median(np.abs(stats - np.median(stats, axis=0)), axis=0)
    scale = np.where(scale > 0, scale, 1.0)
    distance = np.sqrt(np.sum(((stats - observed) / scale) ** 2, axis=1))
    n = max(int(math.ceil(accept * distance.size)), len(priors) + len(STATISTICS) + 2)
    keep = np.argsort(distance)[:n]
    d_max = distance[keep[-1]] * (1.0 + 1e-12) or 1.0
    weights = 1.0 - (distance[keep] / d_max) ** 2
    free = np.column_stack([p.to_free(thetas[keep, j]) for j, p in enumerate(priors)])
    design = np.column_stack([np.ones(n), (stats[keep] - observed) / scale])
    root = np.sqrt(weights)[:, None]
    beta, *_ = np.linalg.lstsq(design * root, free * root, rcond=None)
    adjusted = free - design[:, 1:] @ beta[1:]
    samples = np.column_stack([p.from_free(adjusted[:, j]) for j, p in enumerate(priors)])
    keys = tuple(p.key for p in priors)
    estimate = {k: _weighted_quantile(samples[:, j], weights, 0.5) for j, k in enumerate(keys)}
    interval = {k: (_weighted_quantile(samples[:, j], weights, 0.05), _weighted_quantile(samples[:, j], weights, 0.95))
                for j, k in enumerate(keys)}
    return FitResult(keys, estimate, interval, samples, weights, observed, n, int(distance.size))


def fit(times, x_b, scene_raw: dict, priors, *, draws: int = 2000, accept: float = 0.1, seed: int = 0,
        client=None, progress=None) -> FitResult:
    """The unknowns of ``priors`` from the record (``times`` in s, ``x_b`` in m) for the scene ``scene_raw``
    (a mapping of sections, as :func:`dynamics.scenes.parse_scene` takes): :func:`reference_table`, then
    :func:`abc_posterior`."""
    from dynamics.scenes import parse_scene

    times, x_b = np.asarray(times, dtype=float), np.asarray(x_b, dtype=float)
    ap = parse_scene(scene_raw, "<fit>").apparatus
    observed = summary_statistics(times, x_b, ap.a, ap.b)
    thetas, stats = reference_table(scene_raw, priors, draws, times, seed=seed, client=client, progress=progress)
    result = abc_posterior(priors, observed, thetas, stats, accept=accept)
    return FitResult(**{**result.__dict__, "info": {"draws": draws, "seed": seed, "accept": accept}})


def coverage(scene_raw: dict, priors, truths, times, *, draws: int, accept: float = 0.1, seed: int = 0,
             client=None) -> tuple[np.ndarray, list[FitResult | None]]:
    """Whether each stated 90 % interval contains the truth, on data sets made by the model itself.

    For each row of ``truths`` (parameters in the order of ``priors``) a record is simulated with its
    own surfaces (a seed no draw of the table uses), then fitted against one reference table shared
    by all. A record that does not roll forward has nothing to fit (as for :func:`fit`, and as the
    table leaves out such draws): it counts neither way. Returns (contained: (len(truths), len(priors)),
    1.0 where the interval contains the truth, 0.0 where not, NaN for a record that does not roll; the
    fits, None for such a record).
    """
    thetas, stats = reference_table(scene_raw, priors, draws, times, seed=seed, client=client)
    from dynamics.scenes import parse_scene

    ap = parse_scene(scene_raw, "<fit>").apparatus
    truths = np.atleast_2d(truths)
    contained, fits = np.full(truths.shape, np.nan), []
    for k, truth in enumerate(truths):
        record = simulate_record(scene_raw, priors, truth, 2**31 + k, times)
        try:
            observed = summary_statistics(times, record, ap.a, ap.b)
        except ValueError:  # the surfaces hold the device: no unsteadiness to read
            fits.append(None)
            continue
        result = abc_posterior(priors, observed, thetas, stats, accept=accept)
        fits.append(result)
        contained[k] = [result.interval[p.key][0] <= value <= result.interval[p.key][1]
                        for p, value in zip(priors, truth)]
    return contained, fits


def read_fit_scene(text: str, source: str = "<string>") -> tuple[dict, list[Prior]]:
    """A scene (TOML text) with a ``[fit]`` section of the unknowns, as (the scene without it, the priors).

    Each entry of ``[fit]`` is a dotted scene key and its prior, ``{low = ..., high = ..., log = false}``,
    the bounds numbers in SI or strings with units as the key takes them::

        [fit]
        "contact.roughness_amplitude" = {low = 0.05, high = 0.6}
        "contact.roughness_correlation" = {low = "1 mm", high = "20 mm", log = true}

    Raises :class:`dynamics.scenes.SceneError` naming the key for what cannot be fitted.
    """
    import tomllib

    from dynamics.scenes import SceneError
    from dynamics.scenes.load import read_value
    from dynamics.scenes.schema import SECTIONS

    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        msg = f"{source} is not valid TOML: {err}"
        raise SceneError(msg) from err
    table = raw.pop("fit", None)
    if not isinstance(table, dict) or not table:
        msg = (f"{source} has no [fit] section of the unknowns: give each as \"section.key\" = {{low = ..., "
               "high = ...}}")
        raise SceneError(msg)
    priors = []
    for name, spec in table.items():
        section, _, key_name = name.partition(".")
        rule = SECTIONS.get(section, {}).get(key_name)
        if rule is None or rule.choices or rule.integer:
            msg = f"fit.{name}: not a numeric scene key (one of a section's quantities, e.g. contact.sigma)"
            raise SceneError(msg)
        if not isinstance(spec, dict) or set(spec) - {"low", "high", "log"} or not {"low", "high"} <= set(spec):
            msg = f"fit.{name} must be a table {{low = ..., high = ..., log = false}}, got {spec!r}"
            raise SceneError(msg)
        low, high = (read_value(f"fit.{name}.{end}", spec[end], rule) for end in ("low", "high"))
        try:
            priors.append(Prior(name, low, high, bool(spec.get("log", False))))
        except ValueError as err:
            raise SceneError(str(err)) from err
    if "contact" not in raw:
        msg = f"{source}: the unknowns are the rough contact's, so the scene needs a [contact] section"
        raise SceneError(msg)
    return raw, priors


def read_record(text: str, source: str = "<string>") -> tuple[np.ndarray, np.ndarray]:
    """Times (s) and positions X_b (m) from CSV text with a header naming the columns ``t`` and ``x_b``."""
    import csv
    import io

    rows = list(csv.DictReader(io.StringIO(text)))
    if not rows or not {"t", "x_b"} <= set(rows[0]):
        msg = f"{source} must be CSV with a header naming the columns t and x_b (s, m)"
        raise ValueError(msg)
    try:
        t = np.array([float(r["t"]) for r in rows])
        x = np.array([float(r["x_b"]) for r in rows])
    except (TypeError, ValueError) as err:
        msg = f"{source}: t and x_b must be numbers: {err}"
        raise ValueError(msg) from err
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(x)) and np.all(np.diff(t) > 0)) or t.size < 16:
        msg = f"{source}: t must increase and t, x_b be finite, with at least 16 rows"
        raise ValueError(msg)
    return t, x
