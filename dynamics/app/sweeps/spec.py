"""Sweep files: a base scene and the axes along which it varies, and the points they make.

A sweep file is TOML. It names a base scene and the axes along which it varies:

.. code-block:: toml

    base = "scene.toml"          # relative to this file; or an inline [base] table of scene sections
    seed = 1                     # seed of the random axes (default 0)

    [axes]
    "groups.s" = [0.1, 0.5, 0.9]                                  # a list of values
    "initial.kappa" = {start = 0.1, stop = 0.9, num = 5}          # evenly spaced, both ends included
    "groups.upsilon" = {start = 0.1, stop = 10, num = 3, spacing = "log"}
    "initial.phi" = {random = "uniform", low = 0, high = 6.28, num = 100}
    "contact.seed" = {start = 0, stop = 99, num = 100}            # integers from integer ends: 0, 1, ..., 99

An axis key is a dotted scene key, ``section.key``, applied to the base scene as
an override (:func:`dynamics.scenes.load.parse_scene`). The grid axes (lists and
``start/stop/num``) are crossed: the sweep is their Cartesian product. The
random axes are drawn together, ``num`` joint samples from one generator seeded
by ``seed`` (so they must agree on ``num``), and these samples are crossed with
the grid. ``random`` is ``"uniform"`` or ``"log-uniform"``. A ``contact.seed`` axis makes
an ensemble of surface realisations (``ensemble.csv``, :func:`dynamics.app.sweeps.store.write_ensemble`).

The file is validated before anything runs: unknown keys, malformed axes and
axis values that the base scene refuses are :class:`SweepError`, whose message
names the key. A combination of values that only fails together is a failed
point, recorded with its reason.

Each point is named by :func:`point_key`, a hash of its overrides (the key of
its row in ``sweep.csv``); :meth:`Sweep.fingerprint` names the whole sweep.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from dynamics.scenes import SceneError, parse_scene

__all__ = ["MAX_POINTS", "Axis", "Sweep", "SweepError", "load_sweep", "overrides", "parse_sweep", "point_key"]

#: Most points a sweep may have: its table and its list of points are held in memory (about a
#: kilobyte a point), and ten million points of the regime map take hours on a few cores.
MAX_POINTS = 10_000_000
_TOP_KEYS = ("base", "seed", "axes")
_GRID_KEYS = ("start", "stop", "num", "spacing")
_RANDOM_KEYS = ("random", "low", "high", "num")
_SPACINGS = ("linear", "log")
_DISTRIBUTIONS = ("uniform", "log-uniform")


class SweepError(ValueError):
    """A sweep that cannot run; the message names the key of the sweep file."""


@dataclass(frozen=True)
class Axis:
    """One axis: a scene key and its values (a grid axis), or its samples (a random axis)."""

    key: str  # dotted scene key, "section.key"
    values: tuple  # numbers or strings, as TOML gives them
    random: bool = False  # True: drawn jointly with the other random axes, not crossed with them
    log: bool = False  # spaced or drawn evenly in the logarithm: plot it on a log scale


@dataclass(frozen=True)
class Sweep:
    """A validated sweep: the base scene as a mapping of sections, and the axes.

    Build it with :func:`load_sweep` or :func:`parse_sweep`.
    """

    base: dict  # {section: {key: value}}, the base scene before overrides
    axes: tuple[Axis, ...]
    source: str = "<string>"
    seed: int = 0

    @property
    def keys(self) -> tuple[str, ...]:
        """The axis keys, the first columns of ``sweep.csv``."""
        return tuple(axis.key for axis in self.axes)

    def points(self) -> list[dict[str, Any]]:
        """Every point as ``{axis key: value}``: the grid's product, crossed with the random samples."""
        grid = [a for a in self.axes if not a.random]
        random = [a for a in self.axes if a.random]
        samples = list(zip(*(a.values for a in random))) if random else [()]
        out = []
        for values in itertools.product(*(a.values for a in grid)):
            for sample in samples:
                point = dict(zip((a.key for a in grid), values))
                point.update(zip((a.key for a in random), sample))
                out.append({key: point[key] for key in self.keys})
        return out

    def fingerprint(self) -> str:
        """A hash of the base scene and the axes: a results folder belongs to one sweep."""
        text = json.dumps({"base": self.base, "axes": [[a.key, list(a.values)] for a in self.axes]},
                          sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _value_text(value: Any) -> str:
    """An override's value as TOML: repr keeps every bit of a float, json quotes a string."""
    if isinstance(value, float):
        return repr(value)
    return json.dumps(value)


def overrides(point: Mapping[str, Any]) -> list[str]:
    """The point as ``section.key=value`` overrides of the base scene."""
    return [f"{key}={_value_text(value)}" for key, value in point.items()]


def point_key(point: Mapping[str, Any]) -> str:
    """A stable name of the point: the first 16 hex digits of the SHA-256 of its overrides."""
    return hashlib.sha256("\n".join(overrides(point)).encode()).hexdigest()[:16]


def _grid_axis(key: str, spec: Mapping[str, Any]) -> Axis:
    unknown = [k for k in spec if k not in _GRID_KEYS]
    if unknown:
        msg = f"axes.{key}: unknown key {unknown[0]!r}; a grid axis has {', '.join(_GRID_KEYS)}"
        raise SweepError(msg)
    missing = [k for k in ("start", "stop", "num") if k not in spec]
    if missing:
        msg = f"axes.{key}: {', '.join(missing)} missing; a grid axis is {{start = ..., stop = ..., num = ...}}"
        raise SweepError(msg)
    start, stop = (_number(key, name, spec[name]) for name in ("start", "stop"))
    num = _count(key, spec["num"])
    spacing = spec.get("spacing", "linear")
    if spacing not in _SPACINGS:
        msg = f"axes.{key}.spacing must be one of {', '.join(map(repr, _SPACINGS))}, got {spacing!r}"
        raise SweepError(msg)
    if spacing == "log":
        if not (start > 0 and stop > 0):
            msg = f"axes.{key}: spacing = 'log' needs start > 0 and stop > 0, got {start:g} and {stop:g}"
            raise SweepError(msg)
        return Axis(key, _rounded(np.geomspace(start, stop, num)), log=True)
    values = np.linspace(start, stop, num)
    if all(isinstance(spec[name], int) for name in ("start", "stop")) and np.all(values == np.round(values)):
        return Axis(key, tuple(int(v) for v in np.round(values)))  # integers stay integers: seeds, counts
    return Axis(key, _rounded(values))


def _rounded(values: np.ndarray) -> tuple[float, ...]:
    """Grid values to 12 digits: 0.75 rather than 0.7499999999999999, in overrides and the table."""
    return tuple(float(f"{v:.12g}") for v in values)


def _random_axis(key: str, spec: Mapping[str, Any], rng: np.random.Generator) -> Axis:
    unknown = [k for k in spec if k not in _RANDOM_KEYS]
    missing = [k for k in _RANDOM_KEYS if k not in spec]
    if unknown or missing:
        what = f"unknown key {unknown[0]!r}" if unknown else f"{', '.join(missing)} missing"
        msg = (f"axes.{key}: {what}; a random axis is {{random = 'uniform', low = ..., high = ..., "
               f"num = ...}}")
        raise SweepError(msg)
    if spec["random"] not in _DISTRIBUTIONS:
        msg = f"axes.{key}.random must be one of {', '.join(map(repr, _DISTRIBUTIONS))}, got {spec['random']!r}"
        raise SweepError(msg)
    low, high = (_number(key, name, spec[name]) for name in ("low", "high"))
    num = _count(key, spec["num"])
    if not low < high:
        msg = f"axes.{key}: low must be below high, got low = {low:g}, high = {high:g}"
        raise SweepError(msg)
    if spec["random"] == "log-uniform":
        if not low > 0:
            msg = f"axes.{key}: random = 'log-uniform' needs low > 0, got {low:g}"
            raise SweepError(msg)
        samples = np.exp(rng.uniform(math.log(low), math.log(high), num))
        return Axis(key, tuple(float(v) for v in samples), random=True, log=True)
    return Axis(key, tuple(float(v) for v in rng.uniform(low, high, num)), random=True)


def _number(key: str, name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        msg = f"axes.{key}.{name} must be a finite number, got {value!r}"
        raise SweepError(msg)
    return float(value)


def _count(key: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= MAX_POINTS:
        msg = f"axes.{key}.num must be an integer in [1, {MAX_POINTS:,}], got {value!r}"
        raise SweepError(msg)
    return value


def _axis(key: str, spec: Any, rng: np.random.Generator) -> Axis:
    if isinstance(spec, list):
        if not spec:
            raise SweepError(f"axes.{key} is an empty list; give at least one value")
        bad = [v for v in spec if isinstance(v, (list, dict))]
        if bad:
            msg = f"axes.{key}: values must be numbers or strings, got {bad[0]!r}"
            raise SweepError(msg)
        return Axis(key, tuple(spec))
    if isinstance(spec, Mapping):
        return _random_axis(key, spec, rng) if "random" in spec else _grid_axis(key, spec)
    msg = (f"axes.{key} must be a list of values, {{start, stop, num}} or {{random, low, high, num}}, "
           f"got {spec!r}")
    raise SweepError(msg)


def _check_values(base: dict, axis: Axis, source: str) -> None:
    """Each value of ``axis`` must make a valid scene with the base; random axes are checked at their extremes."""
    values = (min(axis.values), max(axis.values)) if axis.random else axis.values
    for value in dict.fromkeys(values):
        try:
            parse_scene(base, source, overrides({axis.key: value}))
        except SceneError as err:
            msg = f"axes.{axis.key} = {value!r}: {err}"
            raise SweepError(msg) from err


def _base(raw: Mapping[str, Any], base_dir: Path) -> tuple[dict, str]:
    """The base scene as a mapping of sections, and where it came from."""
    if "base" not in raw:
        raise SweepError("base is missing: a sweep names its base scene, base = \"scene.toml\" or a [base] table")
    given = raw["base"]
    if isinstance(given, Mapping):
        return {name: dict(table) if isinstance(table, Mapping) else table for name, table in given.items()}, "[base]"
    if not isinstance(given, str):
        msg = f"base must be a scene file name or a [base] table, got {given!r}"
        raise SweepError(msg)
    path = base_dir / given
    try:
        return tomllib.loads(path.read_text(encoding="utf-8")), os.fspath(path)
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as err:
        msg = f"base = {given!r}: cannot read the scene file {os.fspath(path)!r}: {err}"
        raise SweepError(msg) from err


def parse_sweep(sweep: str | Mapping[str, Any], source: str = "<string>",
                base_dir: str | os.PathLike = ".") -> Sweep:
    """Read and validate a sweep from TOML text or a mapping.

    Parameters
    ----------
    sweep : str or Mapping
        TOML text, or the mapping ``tomllib`` returns for it.
    source : str, optional
        Where the sweep came from, for messages.
    base_dir : path-like, optional
        The folder a ``base = "scene.toml"`` name is relative to.

    Returns
    -------
    Sweep

    Raises
    ------
    SweepError
        For invalid TOML, an unknown key, a malformed axis, or an axis value the
        base scene refuses; the message names the key.
    """
    if isinstance(sweep, str):
        try:
            raw = tomllib.loads(sweep)
        except tomllib.TOMLDecodeError as err:
            msg = f"{source} is not valid TOML: {err}"
            raise SweepError(msg) from err
    else:
        raw = dict(sweep)
    unknown = [k for k in raw if k not in _TOP_KEYS]
    if unknown:
        msg = f"unknown key {unknown[0]!r} in {source}; a sweep file has {', '.join(_TOP_KEYS)}"
        raise SweepError(msg)
    base, base_source = _base(raw, Path(base_dir))
    seed = raw.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        msg = f"seed must be an integer >= 0, got {seed!r}"
        raise SweepError(msg)
    given = raw.get("axes")
    if not isinstance(given, Mapping) or not given:
        msg = f"axes must be a table of at least one axis, e.g. \"groups.s\" = [0.1, 0.5]; got {given!r}"
        raise SweepError(msg)
    try:
        parse_scene(base, base_source)
    except SceneError as err:
        msg = f"base ({base_source}): {err}"
        raise SweepError(msg) from err
    rng = np.random.default_rng(seed)
    axes = tuple(_axis(key, spec, rng) for key, spec in given.items())
    sizes = {a.key: len(a.values) for a in axes if a.random}
    if len(set(sizes.values())) > 1:
        msg = ("random axes are drawn together and need the same num, got "
               + ", ".join(f"axes.{k}.num = {n}" for k, n in sizes.items()))
        raise SweepError(msg)
    points = math.prod(len(a.values) for a in axes if not a.random) * max(sizes.values(), default=1)
    if points > MAX_POINTS:
        msg = (f"the axes make {points:,} points, more than {MAX_POINTS:,}: "
               + " x ".join(f"{len(a.values)} ({a.key})" for a in axes if not a.random)
               + (f" x {max(sizes.values())} random samples" if sizes else ""))
        raise SweepError(msg)
    for axis in axes:
        _check_values(base, axis, base_source)
    return Sweep(base=base, axes=axes, source=source, seed=seed)


def load_sweep(path: str | os.PathLike) -> Sweep:
    """Load a sweep file; a ``base`` file name is relative to the sweep file's folder.

    Raises
    ------
    SweepError
        If the file cannot be read, or for any error :func:`parse_sweep` reports.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        msg = f"cannot read the sweep file {os.fspath(path)!r}: {err}"
        raise SweepError(msg) from err
    return parse_sweep(text, os.fspath(path), path.parent)
