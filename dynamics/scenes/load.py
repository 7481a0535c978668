"""Reading scenes: TOML text in, a validated :class:`~dynamics.scenes.schema.Scene` out.

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
Defaults, units, ranges and help live in :mod:`dynamics.scenes.schema`.

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
import re
import tomllib
from collections.abc import Iterable, Mapping
from importlib.resources import files
from pathlib import Path
from typing import Any

from dynamics.apparatus import PRESETS, Apparatus
from dynamics.equations import full
from dynamics.scenes.schema import (
    ALTERNATIVES,
    SECTIONS,
    Cavitation,
    Contact,
    Groups,
    Initial,
    Model,
    NavierStokes,
    Run,
    Scene,
    SceneError,
    field_of,
    spec,
)
from numerics.keys import Key, field_key
from numerics.units import UnitError, to_si

__all__ = ["load_scene", "parse_scene", "read_value", "resolved_toml"]

_OTHER = {(s, k1): k2 for s, a, b in ALTERNATIVES for k1, k2 in ((a, b), (b, a))}

# The section of each Apparatus field; the TOML key is the field's name.
_APPARATUS_SECTION = {f.name: field_key(f).section for f in dataclasses.fields(Apparatus)}
_PHYSICAL = ("apparatus", "fluid", "incline")
_GROUPS_KEY = {field_of("groups", k): f"groups.{k}" for k in SECTIONS["groups"]}


# -- reading values --------------------------------------------------------------

# pint reads a hertz as 1/s, and a radian as 1: "2 Hz" would pass as 2 rad/s, not 4 pi rad/s
_HERTZ = re.compile(r"hz\b|hertz", re.IGNORECASE)


def _si(name: str, text: str, key: Key) -> float:
    """A string quantity in SI base units, after checking its dimension; an angular rate in hertz is refused."""
    if key.unit == "rad/s" and _HERTZ.search(text):
        msg = (f"{name} = {text!r} is ambiguous: a hertz is a cycle per second, 2 pi rad/s, but reads as 1 rad/s; "
               f"give an angular velocity in rad/s (or rpm), {key.allowed()}")
        raise SceneError(msg)
    try:
        return to_si(text, key.dimension)
    except UnitError as err:
        msg = f"{name} = {text!r} {err}; expected {key.expected()}, {key.allowed()}"
        raise SceneError(msg) from err


def read_value(name: str, raw: Any, key: Key) -> Any:
    """The value of key ``name`` given as ``raw``: converted to SI and checked against its range."""
    if key.none and raw == key.none:
        return None
    if key.choices:
        if not isinstance(raw, str) or raw not in key.options():
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


def _unknown_section(name: str) -> SceneError:
    allowed = ", ".join(f"[{s}]" for s in SECTIONS)
    return SceneError(f"unknown section [{name}]; allowed sections: {allowed}")


def _not_a_table(section: str, table: Any) -> SceneError:
    keys = ", ".join(SECTIONS[section])
    return SceneError(f"[{section}] must be a table of keys ({keys}), got {table!r}")


def _check_key(section: str, key: str) -> None:
    if section not in SECTIONS:
        raise _unknown_section(section)
    if key not in SECTIONS[section]:
        keys = ", ".join(SECTIONS[section])
        msg = f"unknown key {section}.{key}; allowed keys in [{section}]: {keys}"
        raise SceneError(msg)


def _check_names(raw: Mapping[str, Any]) -> None:
    for section, table in raw.items():
        if section not in SECTIONS:
            raise _unknown_section(section)
        if not isinstance(table, Mapping):
            raise _not_a_table(section, table)
        for key in table:
            _check_key(section, key)


def _read(raw: Mapping[str, Any], section: str, dimensionless: bool = False) -> dict[str, Any]:
    """The keys given in ``[section]``, converted to SI and checked against their ranges."""
    values = {}
    for key, given in raw.get(section, {}).items():
        spec = SECTIONS[section][key]
        if dimensionless and spec.reduced_unit:
            spec = spec.in_tau()
        values[key] = read_value(f"{section}.{key}", given, spec)
    return values


def _missing(names: Iterable[str], why: str) -> SceneError:
    """An error for the missing keys ``names`` ("section.key"), with their ranges."""
    names = list(names)
    ranges = "; ".join(f"{n} {spec(n).allowed()}" for n in names)
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
               f"{spec(one).allowed()}, {second} {spec(other).allowed()})")
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
               f"{spec('apparatus.preset').allowed()}, or a, b, length, m_a, m_b), [fluid] and "
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
                   f"give contact.kappa_star = 1 - sigma/delta, {spec('contact.kappa_star').allowed()}")
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
                   f"{spec('contact.psi').allowed()}, or groups.delta_over_a > 0")
            raise SceneError(msg)
        values["psi"] = math.atan(math.tan(values.pop("friction_angle")) / groups.delta_over_a)
    if _either(values, "contact", "static_friction_angle", "psi_static") == "static_friction_angle":
        if groups.delta_over_a == 0.0:
            msg = ("contact.static_friction_angle is scaled by a/delta, but this scene has groups.delta_over_a = "
                   f"0: give contact.psi_static {spec('contact.psi_static').allowed()}, or groups.delta_over_a > 0")
            raise SceneError(msg)
        values["psi_static"] = math.atan(math.tan(values.pop("static_friction_angle")) / groups.delta_over_a)
    try:
        contact = Contact(**values)
    except ValueError as err:
        raise SceneError(f"contact.{err}") from err
    if contact.friction_law == "stribeck" and contact.psi_static is None:
        raise _missing(["contact.psi_static"], "Stribeck friction (contact.friction_law = 'stribeck') needs its "
                                               "static angle; give contact.psi_static or contact.static_friction_angle")
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
    if not cavitation.p_cav <= cavitation.p_ref:
        msg = (f"cavitation.p_cav must be in [0, p_ref] = [0, {cavitation.p_ref:g}] Pa: the film "
               f"cavitates at or below the ambient pressure; got {raw['cavitation']['p_cav']!r}")
        raise SceneError(msg)
    return cavitation


#: The [model] keys the coupled Navier-Stokes run has no use for, with the value it takes, and why.
_NOT_NAVIER_STOKES = (
    ("forces", "stokes-exact", "the flow of the gap gives the forces itself: leave model.forces at its default "
                               "'stokes-exact'"),
    ("frame_terms", full.DEFAULT_FRAME_TERMS, "frame_terms closes the ODE models' fluid inertia, which the "
                                             "Navier-Stokes flow carries itself: leave it "
                                             f"{full.DEFAULT_FRAME_TERMS!r}"),
    ("fluid_spin", full.DEFAULT_FLUID_SPIN, "the fluid's spin is the full equations'; the Navier-Stokes flow carries "
                                           f"it itself: leave it {full.DEFAULT_FLUID_SPIN!r}"),
    ("inertia", "none", "the first inertial correction is the ODE models'; the Navier-Stokes flow has all of the "
                        "fluid's inertia: leave it 'none'"),
    ("ends", "infinite", "the Navier-Stokes flow is plane, per unit length of an infinitely long annulus: leave it "
                         "'infinite'"),
    ("end_gap", None, "the Navier-Stokes flow is plane, without end faces: leave it 'none'"),
)


def _navier_stokes(raw: Mapping[str, Any], model: Model, run: Run) -> NavierStokes | None:
    """The flow solver's settings of a model.equations = 'navier-stokes' scene; refuse what it cannot take."""
    given = raw.get("navier_stokes")
    if model.equations != "navier-stokes":
        if given is not None:
            first = next(iter(given), None)
            name = f"navier_stokes.{first}" if first else "[navier_stokes]"
            msg = (f"{name}: the [navier_stokes] section sets the coupled flow solver, which runs with "
                   f"model.equations = 'navier-stokes' only (this scene has {model.equations!r})")
            raise SceneError(msg)
        return None
    for section in ("contact", "cavitation"):
        if section in raw:
            first = next(iter(raw[section]), None)
            name = f"{section}.{first}" if first else f"[{section}]"
            msg = (f"{name}: the Navier-Stokes equations run with smooth walls and a full film, without a "
                   f"[{section}] section; remove it or set model.equations = 'full'")
            raise SceneError(msg)
    for key_name, value, why in _NOT_NAVIER_STOKES:
        if getattr(model, key_name) != value:
            raise SceneError(f"model.{key_name} = {getattr(model, key_name)!r}: {why} with model.equations = "
                             "'navier-stokes'")
    settings = NavierStokes(**_read(raw, "navier_stokes"))
    from lubrication.unsteady.snapshots import MAX_SNAPSHOTS, require_meshio

    interval = settings.snapshot_interval
    if interval is not None:
        try:
            require_meshio()
        except ImportError as err:
            raise SceneError(f"navier_stokes.snapshot_interval: {err}") from err
        count = settings.snapshot_count(run.t_end)
        if interval > run.t_end or count > MAX_SNAPSHOTS:
            msg = (f"navier_stokes.snapshot_interval must be in (0, run.t_end] = (0, {run.t_end:g}] s and give at "
                   f"most {MAX_SNAPSHOTS} snapshots (t_end/interval + 1), got {given['snapshot_interval']!r}: "
                   f"{count} snapshots")
            raise SceneError(msg)
    elif settings.animation != "none":
        msg = (f"navier_stokes.animation = {settings.animation!r} draws the flow snapshots: give "
               f"navier_stokes.snapshot_interval (a time in (0, run.t_end] = (0, {run.t_end:g}] s), or set "
               "navier_stokes.animation = 'none'")
        raise SceneError(msg)
    return settings


def _run(raw: Mapping[str, Any], apparatus: Apparatus | None) -> Run:
    values = _read(raw, "run")
    _either(values, "run", "t_end", "t_end_tau", required="a scene says how long to run")
    _either(values, "run", "output_interval", "output_interval_tau")
    for name in ("t_end", "output_interval"):
        in_tau = f"{name}_tau"
        if apparatus is None:
            if name in values:
                msg = (f"run.{name} is in seconds, but this [groups] scene for the reduced model is "
                       f"dimensionless (no apparatus, times in tau): give run.{in_tau} "
                       f"{spec(f'run.{in_tau}').allowed()}; got run.{name} = {raw['run'][name]!r}")
                raise SceneError(msg)
            if in_tau in values:
                values[name] = values.pop(in_tau)
        elif in_tau in values:
            values[name] = values.pop(in_tau) * apparatus.tau
    if values.get("output_interval") is not None and values["output_interval"] > values["t_end"]:
        unit = "tau" if apparatus is None else "s"
        msg = (f"run.output_interval must be in (0, run.t_end] = (0, {values['t_end']:g}] {unit}, "
               f"got {values['output_interval']:g} {unit}")
        raise SceneError(msg)
    run = Run(**values)
    if run.output_interval is not None and run.t_end / run.output_interval + 1 > run.max_rows:
        unit = "tau" if apparatus is None else "s"
        msg = (f"run.output_interval = {run.output_interval:g} {unit} would write {run.t_end / run.output_interval + 1:.6g} "
               f"rows over run.t_end = {run.t_end:g} {unit}, more than run.max_rows = {run.max_rows}: "
               f"lengthen the interval or raise run.max_rows")
        raise SceneError(msg)
    return run


def _build(raw: dict[str, Any], source: str) -> Scene:
    _check_names(raw)
    model = Model(**_read(raw, "model"))
    if "groups" in raw:
        apparatus, groups, model = _groups(raw, model)
    else:
        apparatus = _physical_apparatus(raw)
        groups = Groups.from_apparatus(apparatus)
    initial = Initial(**_read(raw, "initial", dimensionless=apparatus is None))
    if model.equations == "reduced" and "forces" not in raw.get("model", {}):
        model = dataclasses.replace(model, forces="closed-form")  # the reduced equations' own, (2.11)
    _check_reduced(raw, model, initial)
    run = _run(raw, apparatus)
    navier_stokes = _navier_stokes(raw, model, run)
    return Scene(apparatus=apparatus, groups=groups, initial=initial, model=model,
                 contact=_contact(raw, apparatus, groups, initial), cavitation=_cavitation(raw),
                 run=run, navier_stokes=navier_stokes, source=source)


# -- overrides -----------------------------------------------------------------------

def _override_value(text: str) -> Any:
    """A TOML value ("0.3", "true", "\"steel\""), or else the text itself ("200 cSt", "steel")."""
    try:
        return tomllib.loads(f"value = {text}")["value"]
    except tomllib.TOMLDecodeError:
        return text


def _apply_overrides(raw: dict[str, Any], overrides: Iterable[str] | Mapping[str, Any]) -> None:
    if isinstance(overrides, Mapping):
        pairs = [(name, "", value) for name, value in overrides.items()]
    else:
        pairs = []
        for text in [overrides] if isinstance(overrides, str) else overrides:
            name, equals, value = str(text).partition("=")
            if any(c in str(text) for c in "\n\r"):  # a second line would set a key the override does not name
                msg = f"override {text!r} spans lines; give one section.key=value per override"
                raise SceneError(msg)
            if not equals:
                name = ""  # (a malformed override)
            pairs.append((name, text, _override_value(value.strip())))
    for name, text, value in pairs:
        section, dot, key = name.strip().partition(".")
        if not (dot and section and key):
            shown = text or f"{name}={value!r}"
            msg = f"override {shown!r} must have the form section.key=value, e.g. 'initial.kappa=0.3'"
            raise SceneError(msg)
        _check_key(section, key)
        table = raw.setdefault(section, {})
        if not isinstance(table, dict):
            raise _not_a_table(section, table)
        table.pop(_OTHER.get((section, key)), None)
        table[key] = value


# -- public functions ----------------------------------------------------------------

def parse_scene(scene: str | Mapping[str, Any], source: str = "<string>",
                overrides: Iterable[str] | Mapping[str, Any] = ()) -> Scene:
    """Read and validate a scene from TOML text or from a mapping of sections.

    Parameters
    ----------
    scene : str or Mapping
        TOML text, or a mapping ``{section: {key: value}}`` as ``tomllib`` returns it.
    source : str, optional
        Where the scene came from, kept in :attr:`Scene.source`.
    overrides : iterable of str, or mapping, optional
        ``"section.key=value"`` strings applied in order before validation. The
        value is read as a TOML value and, failing that, as a string, so
        ``"fluid.nu=200 cSt"`` and ``"model.equations=reduced"`` need no quotes.
        A mapping ``{"section.key": value}`` gives the values as ``tomllib``
        would return them, and is not parsed (a sweep's points).
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
        text = Path(path).read_text(encoding="utf-8-sig")  # a byte-order mark is not part of the TOML
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
    if scene.navier_stokes is not None:
        sections["navier_stokes"] = dataclasses.asdict(scene.navier_stokes)
    suffix = "_tau" if scene.dimensionless else ""
    run = scene.run
    sections["run"] = {f"t_end{suffix}": run.t_end, "rtol": run.rtol}
    if run.output_interval is not None:
        sections["run"][f"output_interval{suffix}"] = run.output_interval
    sections["run"].update(max_rows=run.max_rows, max_steps=run.max_steps, gap_floor=run.gap_floor,
                           max_gap_reynolds=run.max_gap_reynolds, max_stokes_number=run.max_stokes_number,
                           on_invalid=run.on_invalid)
    units = ("dimensionless: times in tau, rates in 1/tau, lengths in b" if scene.dimensionless
             else "SI units, angles in rad")
    lines = [f"# Scene {json.dumps(scene.source)}, fully resolved ({units})."]
    for name, table in sections.items():
        lines += ["", f"[{name}]"]
        for key_name, value in table.items():
            rule = SECTIONS[name][key_name]
            value = rule.none if value is None else value
            unit = rule.reduced_unit if scene.dimensionless and rule.reduced_unit else rule.unit
            unit = "rad" if rule.scale != 1.0 else unit  # angles are written in radians
            note = f"  # {rule.help}" + (f" ({unit})" if unit else "")
            lines.append(f"{key_name} = {_toml_value(value)}{note}")
    return "\n".join(lines) + "\n"
