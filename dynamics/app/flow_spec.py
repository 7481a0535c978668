"""Motion files of ``snail flow``: TOML in, a checked :class:`FlowSpec` out.

A motion file prescribes how the two walls move; the fluid between them is at rest at
t = 0 and the walls move from t = 0 on (DESIGN.md, "snail flow"):

.. code-block:: toml

    [apparatus]
    preset = "steel"                 # or a, b, length (explicit keys override the preset)
    [fluid]
    nu = "200 cSt"                   # nu, rho; default the preset's
    [run]
    t_end = "0.5 s"
    rtol = 1e-4                      # the solver's step control
    n_theta = 16                     # optional: the grid (default: enough for the motion's
    n_r = 12                         #   most eccentric position, 16 points across)
    snapshot_interval = "0.05 s"     # or snapshot_times = [0.1, "0.2 s"]
    frame = "lab"                    # the animation's frame: "lab" or "outer"
    [motion]
    x_a = {mean = 0, amplitude = "1 mm", omega = "5 rad/s", phase = 0}
    z_a = "-1.5 mm"
    omega_a = 2.0
    omega_b = {mean = 1.0}

x_a, z_a: the position of A relative to B (m), x down the slope and z normal to it;
omega_a, omega_b: the spins (rad/s, clockwise positive). Each is a number (constant), a
string with units, or a table meaning mean + amplitude sin(omega t + phase), with missing
entries 0. Keys, units and ranges are stated once, as :class:`numerics.keys.Key` (those of
the apparatus and the fluid are the scenes' own), and read by the scenes' reader, so
that every message names the key, the value and the allowed range as a scene's does
(:class:`~dynamics.scenes.SceneError`). A motion that brings the inner wall closer to the
outer one than the unsteady solver resolves is refused before anything runs.
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path
from typing import Any

import numpy as np

from dynamics.apparatus import PRESETS
from dynamics.scenes import SceneError
from dynamics.scenes.load import read_value
from dynamics.scenes.schema import ALTERNATIVE_KEYS, SECTIONS
from lubrication.geometry import MAX_RATE
from lubrication.unsteady import (
    MIN_ONE_MINUS_KAPPA_UNSTEADY,
    AnnulusMap,
    Harmonic,
    PrescribedMotion,
    Resolution,
    default_resolution,
)
from lubrication.unsteady.snapshots import FRAMES, MAX_SNAPSHOTS
from numerics.keys import Key

__all__ = ["EXAMPLE", "FLOW_SECTIONS", "HARMONIC_ENTRIES", "MAX_LU_BYTES", "MAX_SNAPSHOTS", "FlowSpec",
           "load_motion", "parse_motion", "turned_angle"]

#: The example motion, shipped as package data: what ``snail flow`` runs without a file.
EXAMPLE = "flow_example.toml"
#: Largest banded LU factorisation of the solver a motion file may ask for (bytes): its band of
#: 9 (2 n_r) rows over n_theta 2 n_r columns of complex numbers, 576 n_r^2 n_theta bytes
#: (lubrication/unsteady/operator.py), and a step may hold two.
MAX_LU_BYTES = 2e9

_TIME = {"dimension": "[time]", "unit": "s", "example": "0.5 s"}
_POSITION = {"dimension": "[length]", "unit": "m", "low": -10.0, "high": 10.0, "example": "1.5 mm"}
_SPIN = {"dimension": "1 / [time]", "unit": "rad/s", "low": -MAX_RATE, "high": MAX_RATE, "example": "2 rad/s"}

#: section -> {key: Key}: every key a motion file may give.
FLOW_SECTIONS: dict[str, dict[str, Key]] = {
    "apparatus": {"preset": ALTERNATIVE_KEYS["apparatus", "preset"],
                  **{name: SECTIONS["apparatus"][name] for name in ("a", "b", "length")}},
    "fluid": {name: SECTIONS["fluid"][name] for name in ("nu", "rho")},
    "run": {
        "t_end": Key(help="duration of the motion, from the fluid at rest at t = 0", low=0.0, bounds="()", **_TIME),
        "rtol": Key(help="relative local error per step of the solver's step control (default 1e-4)", low=1e-10,
                    high=0.1, bounds="[]"),
        "n_theta": Key(help="grid points around the annulus (default: as many as the motion's most eccentric "
                            "position needs)", integer=True, low=8, high=1024, none="auto"),
        "n_r": Key(help="Chebyshev points across the gap, walls included (default 16)", integer=True, low=4,
                   high=64, none="auto"),
        "snapshot_times": Key(help="times of the flow snapshots, a list", low=0.0, bounds="[)", **_TIME),
        "snapshot_interval": Key(help="snapshots at t = 0, T, 2T, ... up to t_end, instead of snapshot_times",
                                 low=0.0, bounds="()", **_TIME),
        "animation": Key(help="an animation of the snapshots, flow.gif (the default), or none",
                         choices=("gif", "none")),
        "frame": Key(help="frame of the animation: 'lab' (the default) translates with B, 'outer' turns with the "
                          "outer cylinder", choices=FRAMES),
    },
    "motion": {
        "x_a": Key(help="position of the inner centre A relative to B, down the slope", **_POSITION),
        "z_a": Key(help="position of A relative to B, normal to the slope", **_POSITION),
        "omega_a": Key(help="spin of the inner cylinder, clockwise", **_SPIN),
        "omega_b": Key(help="spin of the outer cylinder, clockwise", **_SPIN),
    },
}

_FREQUENCY = Key(help="angular frequency", dimension="1 / [time]", unit="rad/s", low=0.0, high=MAX_RATE,
                 example="5 rad/s")
_PHASE = Key(help="phase at t = 0", unit="deg", scale=math.pi / 180.0, low=-1e6, high=1e6, example="90 deg")
#: The entries of a motion table (each 0 when missing), read with the key of their quantity (None) or their own.
HARMONIC_ENTRIES: dict[str, Key | None] = {"mean": None, "amplitude": None, "omega": _FREQUENCY, "phase": _PHASE}

_DEFAULTS = {"rtol": 1e-4, "n_theta": None, "n_r": None, "animation": "gif", "frame": "lab"}


@dataclass(frozen=True)
class FlowSpec:
    """A checked motion file, in SI units. Build it with :func:`load_motion` or :func:`parse_motion`.

    Attributes
    ----------
    a, b, length : float
        Radii and axial length (m).
    nu, rho : float
        Kinematic viscosity (m^2/s) and density (kg/m^3).
    preset : str or None
        The apparatus preset the file named.
    motion : PrescribedMotion
    t_end : float
        s.
    rtol : float
    resolution : Resolution
        The given grid, or the default for the most eccentric position.
    resolution_given : bool
    snapshot_times : tuple of float
        s, ascending, in [0, t_end].
    animation, frame : str
    eps_max, t_eps_max : float
        The largest distance |A - B| the motion reaches (m) and when (s).
    source : str
    """

    a: float
    b: float
    length: float
    nu: float
    rho: float
    preset: str | None
    motion: PrescribedMotion
    t_end: float
    rtol: float
    resolution: Resolution
    resolution_given: bool
    snapshot_times: tuple[float, ...]
    animation: str
    frame: str
    eps_max: float
    t_eps_max: float
    source: str = "<string>"

    @property
    def delta(self) -> float:
        """Mean gap b - a (m)."""
        return self.b - self.a

    @property
    def stokes_number(self) -> float:
        """delta^2 omega/nu, omega the motion's fastest angular frequency: 0 for a steady motion."""
        return self.delta**2 * self.motion.fastest() / self.nu

    @property
    def largest_wall_speed(self) -> float:
        """The largest speed of a wall in the frame translating with B (m/s): |U_A|, |Omega_a| a, |Omega_b| b."""
        t = np.linspace(0.0, self.t_end, _samples(self.motion, self.t_end))
        m = self.motion
        return float(np.max([np.abs(m.x_a.rate(t) + 1j * m.z_a.rate(t)), np.abs(m.omega_a.value(t)) * self.a,
                             np.abs(m.omega_b.value(t)) * self.b]))

    @property
    def reynolds_number(self) -> float:
        """V delta/nu, V the largest wall speed (:attr:`largest_wall_speed`)."""
        return self.largest_wall_speed * self.delta / self.nu

    def resolved(self) -> dict[str, dict[str, Any]]:
        """The inputs as the run used them, SI, by section (the motion's entries all explicit)."""
        motion = {name: {entry: getattr(getattr(self.motion, name), entry) for entry in HARMONIC_ENTRIES}
                  for name in FLOW_SECTIONS["motion"]}
        return {"apparatus": {"preset": self.preset, "a": self.a, "b": self.b, "length": self.length},
                "fluid": {"nu": self.nu, "rho": self.rho},
                "run": {"t_end": self.t_end, "rtol": self.rtol, "n_theta": self.resolution.n_theta,
                        "n_r": self.resolution.n_r, "snapshot_times": list(self.snapshot_times),
                        "animation": self.animation, "frame": self.frame},
                "motion": motion}


def turned_angle(harmonic: Harmonic, t):
    """The integral from 0 to ``t`` of mean + amplitude sin(omega s + phase) ds: a wall's angle (rad)."""
    h = harmonic
    if h.omega == 0.0:
        return h.value(0.0) * np.asarray(t, dtype=float)
    return h.mean * np.asarray(t, dtype=float) + h.amplitude / h.omega * (math.cos(h.phase) -
                                                                        np.cos(h.omega * np.asarray(t) + h.phase))


# -- reading ------------------------------------------------------------------------------

def _missing(names: list[str], why: str) -> SceneError:
    ranges = "; ".join(f"{n} {_key(n).allowed()}" for n in names)
    verb = "is" if len(names) == 1 else "are"
    return SceneError(f"{', '.join(names)} {verb} missing: {why} ({ranges})")


def _key(name: str) -> Key:
    section, key = name.split(".")
    return FLOW_SECTIONS[section][key]


def _check_names(raw: Mapping[str, Any]) -> None:
    for section, table in raw.items():
        if section not in FLOW_SECTIONS:
            allowed = ", ".join(f"[{s}]" for s in FLOW_SECTIONS)
            raise SceneError(f"unknown section [{section}]; allowed sections of a motion file: {allowed}")
        keys = ", ".join(FLOW_SECTIONS[section])
        if not isinstance(table, Mapping):
            raise SceneError(f"[{section}] must be a table of keys ({keys}), got {table!r}")
        for name in table:
            if name not in FLOW_SECTIONS[section]:
                why = " (a prescribed motion needs no masses)" if section == "apparatus" and name in (
                    "m_a", "m_b", "rho_a", "m_f_ends") else ""
                raise SceneError(f"unknown key {section}.{name}; allowed keys in [{section}]: {keys}{why}")


def _read(raw: Mapping[str, Any], section: str, skip: tuple[str, ...] = ()) -> dict[str, Any]:
    """The keys given in ``[section]`` (but ``skip``), converted to SI and checked against their ranges."""
    return {name: read_value(f"{section}.{name}", given, FLOW_SECTIONS[section][name])
            for name, given in raw.get(section, {}).items() if name not in skip}


def _apparatus(raw: Mapping[str, Any]) -> dict[str, Any]:
    """a, b, length, nu, rho and the preset's name: from the preset, overridden by the keys given."""
    given = _read(raw, "apparatus")
    fluid = _read(raw, "fluid")
    name = given.pop("preset", None)
    values = {}
    if name is not None:
        preset = PRESETS[name]
        values = {k: getattr(preset, k) for k in ("a", "b", "length", "nu", "rho")}
    values.update(given)
    values.update(fluid)
    missing = [f"{s}.{k}" for s, keys in (("apparatus", ("a", "b", "length")), ("fluid", ("nu", "rho")))
               for k in keys if k not in values]
    if missing:
        raise _missing(missing, "without apparatus.preset a motion file gives the radii and the length, "
                                "and the fluid")
    if not values["b"] > values["a"]:
        shown = f" = {raw['apparatus']['b']!r}" if "b" in raw.get("apparatus", {}) else ""
        msg = (f"apparatus.b{shown} must be in (a, inf) = ({values['a']:g}, inf) m (the outer radius), "
               f"got {values['b']:g} m")
        raise SceneError(msg)
    values["preset"] = name
    return values


def _harmonic(name: str, raw: Any) -> Harmonic:
    """A motion key: a number or a string with units (a constant), or a table of the entries."""
    key = FLOW_SECTIONS["motion"][name]
    if not isinstance(raw, Mapping):
        if isinstance(raw, list):
            msg = (f"motion.{name} must be a number, a string with units or a table "
                   f"{{mean, amplitude, omega, phase}}; got the list {raw!r}")
            raise SceneError(msg)
        return Harmonic(mean=read_value(f"motion.{name}", raw, key))
    entries = {}
    for entry, given in raw.items():
        if entry not in HARMONIC_ENTRIES:
            msg = (f"unknown entry motion.{name}.{entry}; a motion table has the entries "
                   f"{', '.join(HARMONIC_ENTRIES)} (mean + amplitude sin(omega t + phase))")
            raise SceneError(msg)
        entries[entry] = read_value(f"motion.{name}.{entry}", given, HARMONIC_ENTRIES[entry] or key)
    return Harmonic(**entries)


def _samples(motion: PrescribedMotion, t_end: float) -> int:
    """Samples of [0, t_end] that find a largest value of the motion: 64 a period of the fastest part."""
    periods = motion.fastest() * t_end / (2.0 * math.pi)
    return int(min(max(4001, 64 * periods), 2_000_000))


def _reach(motion: PrescribedMotion, a: float, b: float, t_end: float) -> tuple[float, float]:
    """The largest |A - B| over [0, t_end] and when; refused beyond the solver's narrowest gap."""
    # the solver's own search samples [0, t_end], then refines the largest sample
    eps_max, t_max = motion.largest_eccentricity(t_end, samples=_samples(motion, t_end))
    delta = b - a
    reach = (1.0 - MIN_ONE_MINUS_KAPPA_UNSTEADY) * delta
    if eps_max > reach:
        keys = [f"motion.{k}" for k in ("x_a", "z_a")
                if getattr(motion, k).mean != 0.0 or getattr(motion, k).amplitude != 0.0]
        what = ("through the outer wall" if eps_max >= delta else
                f"within 1 - kappa = {(delta - eps_max) / delta:.3g} of the outer wall")
        msg = (f"{' and '.join(keys)} bring the inner wall {what} (|A - B| = {eps_max:.6g} m at t = {t_max:.6g} s): "
               f"the unsteady solver resolves gaps down to 1 - kappa = {MIN_ONE_MINUS_KAPPA_UNSTEADY:g}, so "
               f"|A - B| = sqrt(x_a^2 + z_a^2) must stay in [0, {reach:.6g}] m (b - a = {delta:g} m)")
        raise SceneError(msg)
    return float(eps_max), float(t_max)


def _snapshots(raw: Mapping[str, Any], run: dict[str, Any], t_end: float) -> tuple[float, ...]:
    """The snapshot times: a list, or every interval from 0 to t_end; checked against t_end and the cap."""
    given = raw.get("run", {})
    if "snapshot_times" in given and "snapshot_interval" in given:
        raise SceneError("run.snapshot_times and run.snapshot_interval say the same thing: give one, not both")
    if "snapshot_interval" in given:
        interval = run["snapshot_interval"]
        count = math.floor(t_end / interval * (1.0 + 1e-12)) + 1
        if interval > t_end or count > MAX_SNAPSHOTS:
            msg = (f"run.snapshot_interval must be in (0, run.t_end] = (0, {t_end:g}] s and give at most "
                   f"{MAX_SNAPSHOTS} snapshots (t_end/interval + 1), got {given['snapshot_interval']!r} = "
                   f"{interval:g} s: {count} snapshots")
            raise SceneError(msg)
        return tuple(min(i * interval, t_end) for i in range(count))
    listed = given.get("snapshot_times", [])
    if not isinstance(listed, list):
        msg = f"run.snapshot_times must be a list of times, e.g. [0.1, \"0.2 s\"], got {listed!r}"
        raise SceneError(msg)
    key = FLOW_SECTIONS["run"]["snapshot_times"]
    times = set()
    for i, entry in enumerate(listed):
        t = read_value(f"run.snapshot_times[{i}]", entry, key)
        if t > t_end:
            msg = f"run.snapshot_times[{i}] must be in [0, run.t_end] = [0, {t_end:g}] s, got {entry!r}"
            raise SceneError(msg)
        times.add(t)
    if len(times) > MAX_SNAPSHOTS:
        raise SceneError(f"run.snapshot_times may list at most {MAX_SNAPSHOTS} times, got {len(times)}")
    return tuple(sorted(times))


def _build(raw: dict[str, Any], source: str) -> FlowSpec:
    _check_names(raw)
    device = _apparatus(raw)
    a, b = device["a"], device["b"]
    run = _read(raw, "run", skip=("snapshot_times",))  # a list: read entry by entry
    if "t_end" not in run:
        raise _missing(["run.t_end"], "a motion file says how long the walls move")
    t_end = run["t_end"]
    if "motion" not in raw:
        raise SceneError("[motion] is missing: a motion file says how the walls move (motion.x_a, motion.z_a "
                         "in m, motion.omega_a, motion.omega_b in rad/s; each a number or a table "
                         "{mean, amplitude, omega, phase})")
    motion = PrescribedMotion(**{name: _harmonic(name, given) for name, given in raw["motion"].items()})
    eps_max, t_max = _reach(motion, a, b, t_end)
    settings = {**_DEFAULTS, **run}
    n_theta, n_r = settings["n_theta"], settings["n_r"]
    given = n_theta is not None and n_r is not None
    if given and 576 * n_r**2 * n_theta > MAX_LU_BYTES:
        msg = (f"run.n_theta = {n_theta} and run.n_r = {n_r} need {576e-9 * n_r**2 * n_theta:.3g} GB for each "
               f"factorisation of the solver's banded matrix (576 n_r^2 n_theta bytes), more than "
               f"{MAX_LU_BYTES * 1e-9:g} GB: give fewer points")
        raise SceneError(msg)
    if not given:
        # the solver's default for the most eccentric position (run_prescribed's rule)
        position = motion.position(t_max)
        worst = default_resolution(AnnulusMap(a, b, position), n_r or 16)
        n_theta = n_theta or worst.n_theta
        n_r = n_r or worst.n_r
    return FlowSpec(a=a, b=b, length=device["length"], nu=device["nu"], rho=device["rho"], preset=device["preset"],
                    motion=motion, t_end=t_end, rtol=settings["rtol"], resolution=Resolution(n_theta, n_r),
                    resolution_given=given, snapshot_times=_snapshots(raw, run, t_end),
                    animation=settings["animation"], frame=settings["frame"], eps_max=eps_max, t_eps_max=t_max,
                    source=source)


def parse_motion(text: str | Mapping[str, Any], source: str = "<string>") -> FlowSpec:
    """Read and check a motion file from TOML text or a mapping of sections.

    Raises
    ------
    SceneError
        For invalid TOML, unknown sections, keys or entries, missing values, values out of
        range, or a motion beyond the solver's narrowest gap; the message names the key.
    """
    if isinstance(text, str):
        try:
            raw = tomllib.loads(text)
        except tomllib.TOMLDecodeError as err:
            raise SceneError(f"{source} is not valid TOML: {err}") from err
    else:
        raw = {name: dict(table) if isinstance(table, Mapping) else table for name, table in text.items()}
    return _build(raw, source)


def load_motion(path: str | os.PathLike | None = None) -> FlowSpec:
    """Load a motion file, or the shipped example (:data:`EXAMPLE`) when ``path`` is None.

    Raises
    ------
    SceneError
        If the file cannot be read, or for anything :func:`parse_motion` refuses.
    """
    if path is None:
        resource = files("dynamics.app") / EXAMPLE
        return parse_motion(resource.read_text(encoding="utf-8"), str(resource))
    try:
        text = Path(path).read_text(encoding="utf-8-sig")  # a byte-order mark is not part of the TOML
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError(f"cannot read the motion file {os.fspath(path)!r}: {err}") from err
    return parse_motion(text, os.fspath(path))
