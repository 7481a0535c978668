"""Scenes: TOML files that say what to simulate, read into typed and validated dataclasses.

A scene names the apparatus (or a preset), the fluid, the incline, the initial
state, the model and the run length (DESIGN.md, "Scenes"). A minimal one:

.. code-block:: toml

    [apparatus]
    preset = "steel"
    [fluid]
    nu = "200 cSt"
    [incline]
    alpha = "2.4 deg"
    [initial]
    kappa = 0.5
    [run]
    t_end = "10 s"

Every quantity is a number in SI units (angles in radians) or a string with
units, such as ``"0.8 cm"`` or ``"2.4 deg"``. The string is parsed by pint, its
dimension is checked and it is converted to SI base units. Unknown sections
or keys, missing values, values of the wrong type or dimension and unphysical
values all raise :class:`SceneError`. The message names the key as
``section.key`` and gives the value and the allowed range. Validation is
complete when :func:`load_scene` returns, so nothing runs on a bad scene.
Defaults live in the dataclasses below, one commented field each.

Physical and dimensionless scenes
---------------------------------
A scene with ``[apparatus]``, ``[fluid]`` and ``[incline]`` is physical.
Everything is in SI, and the groups (2.12) are derived from the apparatus.
A ``[groups]`` scene gives s, Upsilon, mu_ and delta/a instead. What it
becomes depends on ``model.equations``:

* ``"reduced"``: the scene is dimensionless. There is no apparatus,
  tau = 1, the initial rates are in units of 1/tau and the run length is
  ``run.t_end_tau``. This is how to run the paper's figures, which use
  mu_ = 1. No physical device has that value, since M + m_b > m_a.
* ``"full"`` (the default): :meth:`Apparatus.from_groups` builds a physical
  apparatus in the distinguished limit, or the scene is refused with the
  reason. From then on it is a physical scene, and its groups are derived
  from that apparatus (they equal the given ones to rounding).
* ``"auto"``: ``"reduced"`` when ``groups.delta_over_a = 0`` (its default:
  the distinguished limit delta/a -> 0 itself, which only (2.11) describes).
  For a finite gap the apparatus is built as for ``"full"``, and the run
  chooses between the equations from the speed-accuracy study
  (:mod:`dynamics.app.auto`); either way the output is then in SI units.

:func:`resolved_toml` writes the resolved scene back as TOML with SI numbers.
A physical scene is written as its apparatus, whether it came from a preset
or from groups, so that ``parse_scene(resolved_toml(s)) == s``.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import tomllib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from decimal import Decimal
from importlib.resources import files
from pathlib import Path
from typing import Any

import pint

from dynamics.apparatus import PRESETS, Apparatus
from dynamics.equations.reduced import ReducedParams
from lubrication.reynolds import GRIDS, MAX_CELLS, MIN_CELLS

__all__ = [
    "CAVITATION_MODELS",
    "EQUATIONS",
    "FORCES",
    "SECTIONS",
    "Cavitation",
    "Contact",
    "Groups",
    "Initial",
    "Model",
    "Run",
    "Scene",
    "SceneError",
    "load_scene",
    "parse_scene",
    "resolved_toml",
]

EQUATIONS = ("full", "reduced", "auto")
FORCES = ("closed-form", "reynolds", "stokes", "auto")
CAVITATION_MODELS = ("half-sommerfeld", "swift-stieber", "jfo")

# Decimal magnitudes: decimal unit factors (cSt, g/cm^3) convert exactly, where
# binary floats would give 200 cSt = 2.0000000000000004e-4 m^2/s.
_UREG = pint.UnitRegistry(non_int_type=Decimal)


class SceneError(ValueError):
    """A scene that cannot run; the message names the key, the value and the allowed range."""


# -- the resolved scene ------------------------------------------------------

@dataclass(frozen=True)
class Groups:
    """The groups (2.12) of the reduced model and the gap ratio, all dimensionless."""

    s: float  # slope group (a sin(alpha)/delta)(M/m'_a), finite
    upsilon: float  # Upsilon = g delta^3 m_a m'_a / (144 nu^2 m''_a^2), > 0
    mu_ratio: float  # the paper's mass ratio mu = (M + m_b)/m_a (TOML key groups.mu), > 0
    delta_over_a: float = 0.0  # gap ratio (b - a)/a, >= 0; 0 is the reduced model's limit

    @classmethod
    def from_apparatus(cls, apparatus: Apparatus) -> Groups:
        """The groups of a physical apparatus."""
        return cls(s=apparatus.s, upsilon=apparatus.upsilon, mu_ratio=apparatus.mu_ratio,
                   delta_over_a=apparatus.delta_over_a)

    @property
    def reduced_params(self) -> ReducedParams:
        """(s, Upsilon, mu_) as the reduced model (2.11) takes them."""
        return ReducedParams(s=self.s, upsilon=self.upsilon, mu_ratio=self.mu_ratio)


@dataclass(frozen=True)
class Initial:
    """The initial state; rates per second, or per tau in a dimensionless scene.

    Angles and spins are clockwise, as in the paper's figure 1.
    """

    kappa: float = 0.0  # eccentricity eps/delta, in [0, 1) (dimensionless)
    phi: float = 0.0  # angle of the line of centres B->A from the upward vertical (rad)
    kappa_dot: float = 0.0  # d kappa/dt (1/s, or 1/tau)
    phi_dot: float = 0.0  # d phi/dt (rad/s, or rad/tau)
    omega_a: float = 0.0  # spin Omega_a of the inner cylinder (rad/s, or rad/tau)
    omega_b: float = 0.0  # spin Omega_b of the outer cylinder, X_b' = b Omega_b (rad/s, or rad/tau)


@dataclass(frozen=True)
class Model:
    """What to model: the equations of motion and the fluid forces in them.

    ``n`` and ``grid`` configure the Reynolds solver; on the Sommerfeld grid
    its thin-gap forces are exact from n = 8.
    """

    equations: str = "full"  # "full" (2.1)-(2.4), "reduced" (2.11) or "auto"
    forces: str = "closed-form"  # "closed-form" (2.5)-(2.7), "reynolds", "stokes" or "auto"
    tolerance: float = 0.01  # relative error "auto" equations and forces may accept (measured), in (0, 1)
    n: int = 16  # Reynolds: cells around the gap, >= 8
    grid: str = "sommerfeld"  # Reynolds: uniform in the Sommerfeld angle or in theta ("uniform")


@dataclass(frozen=True)
class Contact:
    """Rough contact (section 5): asperities stop the approach at kappa = kappa_star.

    A scene gives the minimum gap as ``sigma`` (a length) or ``kappa_star``,
    and friction as the physical ``friction_angle`` psi_hat or the scaled
    ``psi``, tan psi = (a/delta) tan psi_hat; both are resolved here. A rough
    surface lets the minimum gap vary along the surface at random.
    """

    kappa_star: float  # eccentricity at which the asperities touch, 1 - sigma/delta, in (0, 1)
    psi: float = 0.0  # scaled friction angle, in [0, pi/2) (rad)
    roughness_amplitude: float = 0.0  # std of sigma along the surface over its mean, in [0, 1)
    roughness_correlation: float | None = None  # correlation length as a distance rolled (m, or b)
    seed: int = 0  # seed of the random roughness: the same seed gives the same surface


@dataclass(frozen=True)
class Cavitation:
    """A cavitation model for the film pressure; without this section the film is full.

    ``model`` is "half-sommerfeld", "swift-stieber" or "jfo" (the mass-conserving
    Jakobsson-Floberg-Olsson model).
    """

    model: str  # the cavitation model, one of CAVITATION_MODELS
    p_cav: float = 0.0  # the film pressure may not fall below it (Pa, absolute)
    p_ref: float = 101325.0  # ambient pressure, which fixes the film's free constant (Pa, absolute)


@dataclass(frozen=True)
class Run:
    """How long to integrate and how accurately."""

    t_end: float  # duration (s; in units of tau in a dimensionless scene), > 0
    rtol: float = 1e-8  # relative tolerance of the integrator, in (0, 0.1]


@dataclass(frozen=True)
class Scene:
    """A validated scene. Build it with :func:`load_scene` or :func:`parse_scene`.

    Attributes
    ----------
    apparatus : Apparatus or None
        The device (SI). None for a dimensionless ``[groups]`` scene of the
        reduced model.
    groups : Groups
        s, Upsilon, mu_ and delta/a. They are derived from the apparatus when
        there is one.
    initial : Initial
        SI, or in units of tau when :attr:`dimensionless`.
    model : Model
    contact : Contact or None
        None when the scene has no ``[contact]`` section, and then there is no
        contact machinery.
    cavitation : Cavitation or None
        None when the scene has no ``[cavitation]`` section, and then the film
        is full.
    run : Run
        ``t_end`` in s, or in tau when :attr:`dimensionless`.
    source : str
        Where the scene was read from. It is not compared, so that a scene
        equals its resolved copy.
    """

    apparatus: Apparatus | None
    groups: Groups
    initial: Initial
    model: Model
    contact: Contact | None
    cavitation: Cavitation | None
    run: Run
    source: str = field(default="<string>", compare=False)

    @property
    def dimensionless(self) -> bool:
        """True for a ``[groups]`` scene without an apparatus: times in tau, rates in 1/tau."""
        return self.apparatus is None

    @property
    def tau(self) -> float:
        """The time scale (2.9) in s, or 1 in a dimensionless scene."""
        return 1.0 if self.apparatus is None else self.apparatus.tau

    @property
    def t_end_tau(self) -> float:
        """The run length in units of tau."""
        return self.run.t_end / self.tau


# -- what each key accepts -----------------------------------------------------

@dataclass(frozen=True)
class _Key:
    """How one scene key is read: a quantity (the default), an integer or a choice."""

    dimension: str = "[]"  # pint dimensionality of a quantity
    unit: str = ""  # unit of the range in messages; SI except angles (deg)
    low: float = -math.inf
    high: float = math.inf
    bounds: str = "[]"  # which ends of the range are included: "[]", "[)", "(]" or "()"
    scale: float = 1.0  # SI value of one `unit`: pi/180 for angles shown in deg
    example: str = ""  # a string value the key accepts, for messages
    reduced_unit: str = ""  # unit in a dimensionless scene, where the value is a plain number
    choices: tuple[str, ...] = ()  # the allowed strings of a choice
    integer: bool = False  # an integer rather than a quantity

    def allowed(self) -> str:
        """The allowed values: "in [0, 1)", "in (0, inf) m" or "one of 'full', 'reduced'"."""
        if self.choices:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        number = str if self.integer else "{:g}".format
        low = "-inf" if self.low == -math.inf else number(self.low)
        high = "inf" if self.high == math.inf else number(self.high)
        left = "(" if self.low == -math.inf else self.bounds[0]
        right = ")" if self.high == math.inf else self.bounds[1]
        unit = f" {self.unit}" if self.unit else ""
        return f"in {left}{low}, {high}{right}{unit}"

    def contains(self, x: float) -> bool:
        above = x > self.low if self.bounds[0] == "(" else x >= self.low
        below = x < self.high if self.bounds[1] == ")" else x <= self.high
        return math.isfinite(x) and above and below

    def expected(self) -> str:
        if self.dimension != "[]":
            return f"the dimension {self.dimension} (e.g. {self.example!r})"
        if self.scale != 1.0:
            return f"an angle: a number in rad or a string such as {self.example!r}"
        return "a plain number" + (f" in {self.unit}" if self.unit else "")

    def in_tau(self) -> _Key:
        """This key in a dimensionless scene: a plain number in units of tau and b."""
        return dataclasses.replace(self, dimension="[]", unit=self.reduced_unit, example="",
                                   reduced_unit="")


_DEG = math.pi / 180.0
_LENGTH = _Key("[length]", "m", 0.0, bounds="()", example="0.8 cm")
_MASS = _Key("[mass]", "kg", 0.0, bounds="()", example="158 g")
_DENSITY = _Key("[mass] / [length] ** 3", "kg/m^3", 0.0, bounds="()", example="0.95 g/cm^3")
_SPIN = _Key("1 / [time]", "rad/s", example="1 rad/s", reduced_unit="rad/tau")
_FRICTION = _Key(unit="deg", low=0.0, high=90.0, bounds="[)", scale=_DEG, example="5 deg")
_POSITIVE = _Key(low=0.0, bounds="()")

_KEYS: dict[str, dict[str, _Key]] = {
    "apparatus": {
        "preset": _Key(choices=tuple(PRESETS)),
        "a": _LENGTH,
        "b": _LENGTH,
        "length": _LENGTH,
        "m_a": _MASS,
        "rho_a": _DENSITY,
        "m_b": _MASS,
        "m_f_ends": dataclasses.replace(_MASS, bounds="[)"),
    },
    "fluid": {
        "nu": _Key("[length] ** 2 / [time]", "m^2/s", 0.0, bounds="()", example="200 cSt"),
        "rho": _DENSITY,
    },
    "incline": {
        "alpha": _Key(unit="deg", low=-90.0, high=90.0, bounds="()", scale=_DEG, example="2.4 deg"),
        "g": _Key("[length] / [time] ** 2", "m/s^2", 0.0, bounds="()", example="9.81 m/s^2"),
    },
    "groups": {
        "s": _Key(),
        "upsilon": _POSITIVE,
        "mu": _POSITIVE,
        "delta_over_a": _Key(low=0.0, bounds="[)"),
    },
    "initial": {
        "kappa": _Key(low=0.0, high=1.0, bounds="[)"),
        "phi": _Key(unit="deg", scale=_DEG, example="30 deg"),
        "kappa_dot": _Key("1 / [time]", "1/s", example="0.1 / s", reduced_unit="1/tau"),
        "phi_dot": _SPIN,
        "omega_a": _SPIN,
        "omega_b": _SPIN,
    },
    "model": {
        "equations": _Key(choices=EQUATIONS),
        "forces": _Key(choices=FORCES),
        "tolerance": _Key(low=0.0, high=1.0, bounds="()"),
        "n": _Key(low=MIN_CELLS, high=MAX_CELLS, integer=True),
        "grid": _Key(choices=GRIDS),
    },
    "contact": {
        "sigma": dataclasses.replace(_LENGTH, example="50 um"),
        "kappa_star": _Key(low=0.0, high=1.0, bounds="()"),
        "friction_angle": _FRICTION,
        "psi": _FRICTION,
        "roughness_amplitude": _Key(low=0.0, high=1.0, bounds="[)"),
        "roughness_correlation": dataclasses.replace(_LENGTH, example="1 mm", reduced_unit="b"),
        "seed": _Key(low=0, integer=True),
    },
    "cavitation": {
        "model": _Key(choices=CAVITATION_MODELS),
        "p_cav": _Key("[pressure]", "Pa", 0.0, example="0.1 atm"),
        "p_ref": _Key("[pressure]", "Pa", 0.0, bounds="()", example="1 atm"),
    },
    "run": {
        "t_end": _Key("[time]", "s", 0.0, bounds="()", example="30 s"),
        "t_end_tau": _Key(unit="tau", low=0.0, bounds="()"),
        "rtol": _Key(low=0.0, high=0.1, bounds="(]"),
    },
}
SECTIONS = tuple(_KEYS)

# Keys that say the same thing two ways: a scene gives one of each pair, and an
# override of one replaces the other.
_ALTERNATIVES = (("apparatus", "m_a", "rho_a"), ("contact", "sigma", "kappa_star"),
                 ("contact", "friction_angle", "psi"), ("run", "t_end", "t_end_tau"))
_OTHER = {(s, k1): k2 for s, a, b in _ALTERNATIVES for k1, k2 in ((a, b), (b, a))}

# The section of each Apparatus field; the TOML key is the field's name.
_APPARATUS_SECTION = {"a": "apparatus", "b": "apparatus", "length": "apparatus",
                      "m_a": "apparatus", "m_b": "apparatus", "m_f_ends": "apparatus",
                      "nu": "fluid", "rho": "fluid", "alpha": "incline", "g": "incline"}
_PHYSICAL = ("apparatus", "fluid", "incline")
_GROUPS_KEY = {"s": "groups.s", "upsilon": "groups.upsilon", "mu_ratio": "groups.mu",
               "delta_over_a": "groups.delta_over_a"}


# -- reading values --------------------------------------------------------------

def _si(name: str, text: str, key: _Key) -> float:
    """A string quantity in SI base units, after checking its dimension."""
    try:
        quantity = _UREG.Quantity(text)
    # pint's parser raises many types (PintError, TokenError, AssertionError, ValueError).
    except Exception as err:  # noqa: BLE001
        msg = (f"{name} = {text!r} is not a quantity pint can read ({err}); "
               f"expected {key.expected()}, {key.allowed()}")
        raise SceneError(msg) from err
    if not quantity.check(key.dimension):
        msg = (f"{name} = {text!r} has the unit {quantity.units} ({quantity.dimensionality}); "
               f"expected {key.expected()}, {key.allowed()}")
        raise SceneError(msg)
    return float(quantity.to_base_units().magnitude)


def _value(name: str, raw: Any, key: _Key) -> Any:
    """The value of key ``name`` given as ``raw``: converted to SI and checked against its range."""
    if key.choices:
        if not isinstance(raw, str) or raw not in key.choices:
            msg = f"{name} must be {key.allowed()}, got {raw!r}"
            raise SceneError(msg)
        return raw
    if key.integer:
        if isinstance(raw, bool) or not isinstance(raw, int):
            msg = f"{name} must be an integer {key.allowed()}, got {raw!r}"
            raise SceneError(msg)
        value = raw
    elif isinstance(raw, str):
        value = _si(name, raw, key)
    elif isinstance(raw, (int, float)) and not isinstance(raw, bool):
        value = float(raw)
    else:
        msg = (f"{name} must be a number or a string with units, {key.expected()}, "
               f"{key.allowed()}; got {raw!r}")
        raise SceneError(msg)
    if not key.contains(value / key.scale):
        shown = repr(raw)
        if isinstance(raw, str) or key.scale != 1.0:
            shown += f" = {value / key.scale:g} {key.unit}".rstrip()
        msg = f"{name} must be {key.allowed()}, got {shown}"
        raise SceneError(msg)
    return value


def _spec(name: str) -> _Key:
    """The rules of key ``name``, "section.key"."""
    section, key = name.split(".")
    return _KEYS[section][key]


def _unknown_section(name: str) -> SceneError:
    allowed = ", ".join(f"[{s}]" for s in SECTIONS)
    return SceneError(f"unknown section [{name}]; allowed sections: {allowed}")


def _not_a_table(section: str, table: Any) -> SceneError:
    keys = ", ".join(_KEYS[section])
    return SceneError(f"[{section}] must be a table of keys ({keys}), got {table!r}")


def _check_key(section: str, key: str) -> None:
    if section not in _KEYS:
        raise _unknown_section(section)
    if key not in _KEYS[section]:
        keys = ", ".join(_KEYS[section])
        msg = f"unknown key {section}.{key}; allowed keys in [{section}]: {keys}"
        raise SceneError(msg)


def _check_names(raw: Mapping[str, Any]) -> None:
    for section, table in raw.items():
        if section not in _KEYS:
            raise _unknown_section(section)
        if not isinstance(table, Mapping):
            raise _not_a_table(section, table)
        for key in table:
            _check_key(section, key)


def _read(raw: Mapping[str, Any], section: str, dimensionless: bool = False) -> dict[str, Any]:
    """The keys given in ``[section]``, converted to SI and checked against their ranges."""
    values = {}
    for key, given in raw.get(section, {}).items():
        spec = _KEYS[section][key]
        if dimensionless and spec.reduced_unit:
            spec = spec.in_tau()
        values[key] = _value(f"{section}.{key}", given, spec)
    return values


def _missing(names: Iterable[str], why: str) -> SceneError:
    """An error for the missing keys ``names`` ("section.key"), with their ranges."""
    names = list(names)
    ranges = "; ".join(f"{n} {_spec(n).allowed()}" for n in names)
    verb = "is" if len(names) == 1 else "are"
    return SceneError(f"{', '.join(names)} {verb} missing: {why} ({ranges})")


def _either(values: Mapping[str, Any], section: str, first: str, second: str,
            required: str = "") -> str | None:
    """Which of two alternative keys is given, or None.

    Both is an error; so is neither when ``required`` says why one is needed.
    """
    given = [k for k in (first, second) if k in values]
    one, other = f"{section}.{first}", f"{section}.{second}"
    if len(given) == 2:
        msg = (f"{one} and {other} say the same thing: give one, not both ({first} "
               f"{_spec(one).allowed()}, {second} {_spec(other).allowed()})")
        raise SceneError(msg)
    if not given and required:
        raise _missing([one], f"{required}; give {one} or {other}")
    return given[0] if given else None


def _translated(err: ValueError, keys: Mapping[str, str], raw: Mapping[str, Any],
                context: str = "") -> SceneError:
    """A constructor's error, which starts with a field name, restated for that field's key.

    ``keys`` maps field names to scene keys, ``raw`` the scene keys to the values given.
    """
    name = str(err).split(" ", 1)[0]
    key = keys.get(name, "scene")
    given = f" = {raw[key]!r}" if key in raw else ""
    return SceneError(f"{key}{given}: {err}{context}")


# -- building the scene ----------------------------------------------------------

def _flat(raw: Mapping[str, Any]) -> dict[str, Any]:
    """The given values by "section.key", as written, for messages."""
    return {f"{s}.{k}": v for s, table in raw.items() for k, v in table.items()}


def _physical_apparatus(raw: Mapping[str, Any]) -> Apparatus:
    if not any(s in raw for s in _PHYSICAL):
        msg = ("apparatus.preset is missing: a scene needs [apparatus] (a preset, "
               f"{_spec('apparatus.preset').allowed()}, or a, b, length, m_a, m_b), [fluid] and "
               "[incline]; or else [groups] (s, upsilon, mu)")
        raise SceneError(msg)
    given = {s: _read(raw, s) for s in _PHYSICAL}
    name = given["apparatus"].pop("preset", None)
    mass = _either(given["apparatus"], "apparatus", "m_a", "rho_a")
    rho_a = given["apparatus"].pop("rho_a", None)
    fields = dataclasses.asdict(PRESETS[name]) if name else {}
    for values in given.values():
        fields.update(values)
    missing = [f.name for f in dataclasses.fields(Apparatus)
               if f.default is dataclasses.MISSING and f.name not in fields
               and not (f.name == "m_a" and mass)]
    if missing:
        names = [f"{_APPARATUS_SECTION[f]}.{f}" for f in missing]
        raise _missing(names, "without apparatus.preset a scene gives the whole apparatus, fluid "
                              "and incline (apparatus.rho_a may replace apparatus.m_a)")
    if rho_a is not None:
        # A solid inner cylinder: m_a = rho_a pi a^2 L.
        fields["m_a"] = rho_a * math.pi * fields["a"] ** 2 * fields["length"]
    keys = {f: f"{s}.{f}" for f, s in _APPARATUS_SECTION.items()}
    if mass == "rho_a":
        keys["m_a"] = "apparatus.rho_a"
    try:
        return Apparatus(**fields)
    except ValueError as err:
        raise _translated(err, keys, _flat(raw)) from err


def _groups(raw: Mapping[str, Any], model: Model) -> tuple[Apparatus | None, Groups, Model]:
    """The apparatus (None if dimensionless), the groups and the model of a ``[groups]`` scene."""
    clash = [f"{s}.{k}" for s in _PHYSICAL for k in raw.get(s, {})]
    clash = clash or [f"[{s}]" for s in _PHYSICAL if s in raw]  # empty sections clash too
    if clash:
        given = ", ".join(f"groups.{k}" for k in raw["groups"]) or "[groups]"
        msg = (f"{', '.join(clash)} clash with {given}: a scene gives either [groups] or "
               "[apparatus]/[fluid]/[incline], not both")
        raise SceneError(msg)
    values = _read(raw, "groups")
    missing = [f"groups.{k}" for k in ("s", "upsilon", "mu") if k not in values]
    if missing:
        raise _missing(missing, "a [groups] scene gives s, upsilon and mu")
    values["mu_ratio"] = values.pop("mu")
    groups = Groups(**values)
    if model.equations == "auto" and groups.delta_over_a == 0:
        model = dataclasses.replace(model, equations="reduced")
    if model.equations == "reduced":
        return None, groups, model
    try:
        apparatus = Apparatus.from_groups(groups.s, groups.upsilon, groups.mu_ratio,
                                          groups.delta_over_a)
    except ValueError as err:
        context = ("; the full equations need a physical apparatus, which a [groups] scene builds "
                   "with Apparatus.from_groups; model.equations = 'reduced' runs these groups "
                   "dimensionless")
        raise _translated(err, _GROUPS_KEY, _flat(raw), context) from err
    return apparatus, Groups.from_apparatus(apparatus), model


def _check_reduced(raw: Mapping[str, Any], model: Model, initial: Initial) -> None:
    """Refuse what the reduced model (2.11) cannot take.

    It has the full-film closed forms built in, and it is first order in kappa and phi.
    """
    if model.equations != "reduced":
        return
    if model.forces not in ("closed-form", "auto"):
        msg = (f"model.forces must be 'closed-form' or 'auto' for model.equations = 'reduced', whose "
               f"equations (2.11) have the lubrication closed forms built in; got {model.forces!r}")
        raise SceneError(msg)
    if "cavitation" in raw:
        msg = ("cavitation.model: model.equations = 'reduced' has full-film lubrication built in "
               "(2.11); cavitation needs model.equations = 'full' and a physical apparatus")
        raise SceneError(msg)
    for key in ("kappa_dot", "phi_dot"):
        if getattr(initial, key) != 0.0:
            msg = (f"initial.{key} must be 0 for model.equations = 'reduced', where (2.11a-b) fix "
                   f"kappa' and phi' from the state; got {raw['initial'][key]!r}")
            raise SceneError(msg)


def _contact(raw: Mapping[str, Any], apparatus: Apparatus | None, groups: Groups,
             initial: Initial) -> Contact | None:
    if "contact" not in raw:
        return None
    values = _read(raw, "contact", dimensionless=apparatus is None)
    gap = _either(values, "contact", "sigma", "kappa_star", required="contact needs the asperities' gap")
    if gap == "sigma":
        if apparatus is None:
            msg = ("contact.sigma is a length, but this [groups] scene is dimensionless (no apparatus): "
                   f"give contact.kappa_star = 1 - sigma/delta, {_spec('contact.kappa_star').allowed()}")
            raise SceneError(msg)
        sigma = values.pop("sigma")
        if not sigma < apparatus.delta:
            msg = (f"contact.sigma must be in (0, delta) = (0, {apparatus.delta:g}) m, a gap narrower "
                   f"than the mean gap; got {raw['contact']['sigma']!r}")
            raise SceneError(msg)
        values["kappa_star"] = 1.0 - sigma / apparatus.delta
    if _either(values, "contact", "friction_angle", "psi") == "friction_angle":
        if groups.delta_over_a == 0.0:
            msg = ("contact.friction_angle is scaled by a/delta (tan psi = (a/delta) tan "
                   "friction_angle), but this scene has groups.delta_over_a = 0: give contact.psi "
                   f"{_spec('contact.psi').allowed()}, or groups.delta_over_a > 0")
            raise SceneError(msg)
        values["psi"] = math.atan(math.tan(values.pop("friction_angle")) / groups.delta_over_a)
    contact = Contact(**values)
    if contact.roughness_amplitude > 0.0 and contact.roughness_correlation is None:
        raise _missing(["contact.roughness_correlation"],
                       "a rough surface (contact.roughness_amplitude > 0) needs its correlation length")
    if initial.kappa > contact.kappa_star:
        msg = (f"initial.kappa must be in [0, contact.kappa_star] = [0, {contact.kappa_star:g}]: the "
               f"asperities touch at kappa_star; got {initial.kappa:g}")
        raise SceneError(msg)
    return contact


def _cavitation(raw: Mapping[str, Any]) -> Cavitation | None:
    if "cavitation" not in raw:
        return None
    values = _read(raw, "cavitation")
    if "model" not in values:
        raise _missing(["cavitation.model"], "a [cavitation] section names its model")
    cavitation = Cavitation(**values)
    if not cavitation.p_cav < cavitation.p_ref:
        msg = (f"cavitation.p_cav must be in [0, p_ref) = [0, {cavitation.p_ref:g}) Pa: the film "
               f"cavitates below the ambient pressure; got {raw['cavitation']['p_cav']!r}")
        raise SceneError(msg)
    return cavitation


def _run(raw: Mapping[str, Any], apparatus: Apparatus | None) -> Run:
    values = _read(raw, "run")
    given = _either(values, "run", "t_end", "t_end_tau", required="a scene says how long to run")
    if apparatus is None:
        if given == "t_end":
            msg = (f"run.t_end is in seconds, but this [groups] scene for the reduced model is "
                   f"dimensionless (no apparatus, times in tau): give run.t_end_tau "
                   f"{_spec('run.t_end_tau').allowed()}; got run.t_end = {raw['run']['t_end']!r}")
            raise SceneError(msg)
        values["t_end"] = values.pop("t_end_tau")
    elif given == "t_end_tau":
        values["t_end"] = values.pop("t_end_tau") * apparatus.tau
    return Run(**values)


def _build(raw: dict[str, Any], source: str) -> Scene:
    _check_names(raw)
    model = Model(**_read(raw, "model"))
    if "groups" in raw:
        apparatus, groups, model = _groups(raw, model)
    else:
        apparatus = _physical_apparatus(raw)
        groups = Groups.from_apparatus(apparatus)
    initial = Initial(**_read(raw, "initial", dimensionless=apparatus is None))
    _check_reduced(raw, model, initial)
    return Scene(apparatus=apparatus, groups=groups, initial=initial, model=model,
                 contact=_contact(raw, apparatus, groups, initial), cavitation=_cavitation(raw),
                 run=_run(raw, apparatus), source=source)


# -- overrides -----------------------------------------------------------------------

def _override_value(text: str) -> Any:
    """A TOML value ("0.3", "true", "\"steel\""), or else the text itself ("200 cSt", "steel")."""
    try:
        return tomllib.loads(f"value = {text}")["value"]
    except tomllib.TOMLDecodeError:
        return text


def _apply_overrides(raw: dict[str, Any], overrides: Iterable[str]) -> None:
    for text in [overrides] if isinstance(overrides, str) else overrides:
        name, equals, value = str(text).partition("=")
        section, dot, key = name.strip().partition(".")
        if not (equals and dot and section and key):
            msg = f"override {text!r} must have the form section.key=value, e.g. 'initial.kappa=0.3'"
            raise SceneError(msg)
        _check_key(section, key)
        table = raw.setdefault(section, {})
        if not isinstance(table, dict):
            raise _not_a_table(section, table)
        table.pop(_OTHER.get((section, key)), None)
        table[key] = _override_value(value.strip())


# -- public functions ----------------------------------------------------------------

def parse_scene(scene: str | Mapping[str, Any], source: str = "<string>",
                overrides: Iterable[str] = ()) -> Scene:
    """Read and validate a scene from TOML text or from a mapping of sections.

    Parameters
    ----------
    scene : str or Mapping
        TOML text, or a mapping ``{section: {key: value}}`` as ``tomllib`` returns it.
    source : str, optional
        Where the scene came from, kept in :attr:`Scene.source`.
    overrides : iterable of str, optional
        ``"section.key=value"`` strings applied in order before validation. The
        value is read as a TOML value and, failing that, as a string, so
        ``"fluid.nu=200 cSt"`` and ``"model.equations=reduced"`` need no quotes.
        An override of one of two alternative keys (``m_a``/``rho_a``,
        ``sigma``/``kappa_star``, ``friction_angle``/``psi``,
        ``t_end``/``t_end_tau``) replaces the other.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        For invalid TOML, a malformed override, or a scene that cannot run. The
        message names the key, the value given and the allowed range.
    """
    if isinstance(scene, str):
        try:
            raw = tomllib.loads(scene)
        except tomllib.TOMLDecodeError as err:
            msg = f"{source} is not valid TOML: {err}"
            raise SceneError(msg) from err
    elif isinstance(scene, Mapping):
        raw = {name: dict(table) if isinstance(table, Mapping) else table
               for name, table in scene.items()}
    else:
        msg = f"a scene is TOML text or a mapping of sections, got {type(scene).__name__}"
        raise SceneError(msg)
    _apply_overrides(raw, overrides)
    return _build(raw, source)


def load_scene(path: str | os.PathLike | None = None, overrides: Iterable[str] = ()) -> Scene:
    """Load a scene file, or the embedded default scene when ``path`` is None.

    Parameters
    ----------
    path : str or path-like, optional
        A TOML scene file. The default is ``dynamics/scenes/default.toml``: the
        paper's steel apparatus in 200 cSt oil at 2.4 degrees.
    overrides : iterable of str, optional
        ``"section.key=value"`` strings, see :func:`parse_scene`.

    Raises
    ------
    SceneError
        If the file cannot be read, or for any error :func:`parse_scene` reports.
    """
    if path is None:
        resource = files("dynamics.scenes") / "default.toml"
        return parse_scene(resource.read_text(encoding="utf-8"), str(resource), overrides)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        msg = f"cannot read the scene file {os.fspath(path)!r}: {err}"
        raise SceneError(msg) from err
    return parse_scene(text, os.fspath(path), overrides)


def _toml_value(value: bool | int | float | str) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        # repr is the shortest string that reads back to the same float, and valid TOML.
        return repr(value)
    # A JSON string is a TOML basic string, except that TOML also escapes DEL.
    return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")


def resolved_toml(scene: Scene) -> str:
    """The scene written back as TOML, fully resolved: every value explicit, in SI numbers.

    A physical scene is written as its apparatus, fluid and incline, whether it
    came from a preset or from groups. A dimensionless scene is written as its
    groups, with times in tau. ``parse_scene(resolved_toml(scene)) == scene``.
    """
    sections: dict[str, dict[str, Any]] = {}
    if scene.apparatus is None:
        g = scene.groups
        sections["groups"] = {"s": g.s, "upsilon": g.upsilon, "mu": g.mu_ratio,
                              "delta_over_a": g.delta_over_a}
    else:
        for name, section in _APPARATUS_SECTION.items():
            sections.setdefault(section, {})[name] = getattr(scene.apparatus, name)
    sections["initial"] = dataclasses.asdict(scene.initial)
    sections["model"] = dataclasses.asdict(scene.model)
    if scene.contact is not None:
        contact = dataclasses.asdict(scene.contact)
        sections["contact"] = {k: v for k, v in contact.items() if v is not None}  # TOML has no null
    if scene.cavitation is not None:
        sections["cavitation"] = dataclasses.asdict(scene.cavitation)
    t_end = "t_end_tau" if scene.dimensionless else "t_end"
    sections["run"] = {t_end: scene.run.t_end, "rtol": scene.run.rtol}
    units = ("dimensionless: times in tau, rates in 1/tau, lengths in b" if scene.dimensionless
             else "SI units, angles in rad")
    lines = [f"# Scene {json.dumps(scene.source)}, fully resolved ({units})."]
    for name, table in sections.items():
        lines += ["", f"[{name}]"] + [f"{key} = {_toml_value(value)}" for key, value in table.items()]
    return "\n".join(lines) + "\n"
