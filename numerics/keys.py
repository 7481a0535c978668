"""What a parameter means: its unit, its allowed range and a line of help, stated once.

A :class:`Key` is attached to a dataclass field with :func:`key`. The same
statement then serves every reader: the dataclass checks its own values when it
is built from Python (:func:`check_fields`), the scene reader converts and checks
TOML values with it, the resolved scene and the documentation print its help,
and every message names the parameter and its range in the same words.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Any, Callable

__all__ = ["Key", "check_fields", "field_key", "key"]


@dataclass(frozen=True)
class Key:
    """How one parameter is read and checked.

    A quantity (the default) is a float in SI units, or in ``unit`` when
    ``scale`` says how many SI units one ``unit`` is (angles shown in degrees
    have scale pi/180); a choice is one of ``choices``; an integer has
    ``integer`` set. ``bounds`` says which ends of [low, high] are included.
    """

    help: str = ""  # one line: what the parameter is
    dimension: str = "[]"  # pint dimensionality of a quantity given as a string with units
    unit: str = ""  # unit of the range in messages and docs; SI except angles (deg)
    low: float = -math.inf
    high: float = math.inf
    bounds: str = "[]"  # "[]", "[)", "(]" or "()"
    scale: float = 1.0  # SI value of one `unit`: pi/180 for angles shown in deg
    example: str = ""  # a string value the key accepts, for messages
    reduced_unit: str = ""  # unit in a dimensionless scene, where the value is a plain number
    choices: tuple[str, ...] | Callable[[], tuple[str, ...]] = ()  # the allowed strings (or what lists them now)
    integer: bool = False  # an integer rather than a quantity
    none: str = ""  # a string that stands for "no value" (None), such as "none"
    section: str = ""  # the scene section of a field whose dataclass spans several
    toml: str = ""  # the scene's name for the field, when it differs from the field's

    def options(self) -> tuple[str, ...]:
        """The allowed strings of a choice, as they are now (a registry's may grow); () for a number."""
        return tuple(self.choices()) if callable(self.choices) else self.choices

    def allowed(self) -> str:
        """The allowed values: "in [0, 1)", "in (0, inf) m" or "one of 'full', 'reduced'"."""
        if self.choices:
            text = "one of " + ", ".join(repr(c) for c in self.options())
        else:
            number = str if self.integer else "{:g}".format
            low = "-inf" if self.low == -math.inf else number(self.low)
            high = "inf" if self.high == math.inf else number(self.high)
            left = "(" if self.low == -math.inf else self.bounds[0]
            right = ")" if self.high == math.inf else self.bounds[1]
            unit = f" {self.unit}" if self.unit else ""
            text = f"in {left}{low}, {high}{right}{unit}"
        return text + (f", or {self.none!r}" if self.none else "")

    def contains(self, x: float) -> bool:
        """Whether ``x`` (in ``unit``) lies in the range; NaN and infinities never do."""
        above = x > self.low if self.bounds[0] == "(" else x >= self.low
        below = x < self.high if self.bounds[1] == ")" else x <= self.high
        return math.isfinite(x) and above and below

    def expected(self) -> str:
        """What kind of value is expected, for messages."""
        if self.dimension != "[]":
            return f"the dimension {self.dimension} (e.g. {self.example!r})"
        if self.scale != 1.0:
            return f"an angle: a number in rad or a string such as {self.example!r}"
        return "a plain number" + (f" in {self.unit}" if self.unit else "")

    def in_tau(self) -> Key:
        """This key in a dimensionless scene: a plain number in units of tau and b."""
        return _in_tau(self)

    def check(self, name: str, value: Any) -> Any:
        """``value`` (already in SI) if it is allowed, else ValueError naming ``name`` and the range."""
        if value is None and self.none:
            return None
        if self.choices:
            if not isinstance(value, str) or value not in self.options():
                msg = f"{name} must be {self.allowed()}, got {value!r}"
                raise ValueError(msg)
            return value
        if self.integer:
            if isinstance(value, bool) or not isinstance(value, int) or not self.contains(value):
                msg = f"{name} must be an integer {self.allowed()}, got {value!r}"
                raise ValueError(msg)
            return value
        try:
            x = math.nan if isinstance(value, (str, bytes)) else float(value)  # "0.5" is no number
        except (TypeError, ValueError):
            x = math.nan
        if isinstance(value, bool) or not self.contains(x / self.scale):
            angle = self.scale != 1.0 and math.isfinite(x)
            shown = f"{value!r} rad = {x / self.scale:g} {self.unit}" if angle else repr(value)
            msg = f"{name} must be {self.allowed()}, got {shown}"
            raise ValueError(msg)
        return x


@functools.cache
def _in_tau(spec: Key) -> Key:
    """:meth:`Key.in_tau`, made once per key: a sweep reads each point's scene anew, and a copy of a
    dataclass costs more than its hash."""
    return dataclasses.replace(spec, dimension="[]", unit=spec.reduced_unit, example="", reduced_unit="")


def key(default: Any = dataclasses.MISSING, **rule: Any) -> Any:
    """A dataclass field carrying a :class:`Key`: ``kappa: float = key(0.0, low=0.0, high=1.0, ...)``."""
    return dataclasses.field(default=default, metadata={"key": Key(**rule)})


def field_key(field: dataclasses.Field) -> Key | None:
    """The :class:`Key` of a dataclass field, or None if it has none."""
    return field.metadata.get("key")


@functools.cache
def _keyed_fields(cls: type) -> tuple[tuple[str, Key], ...]:
    """(name, Key) of every keyed field of the dataclass ``cls``: looked up once per class."""
    return tuple((f.name, spec) for f in dataclasses.fields(cls) if (spec := field_key(f)) is not None)


def check_fields(obj: Any) -> None:
    """Check every keyed field of the dataclass instance ``obj`` and store the checked value.

    Raises ValueError naming the field and its allowed range, as the scene reader does.
    """
    for name, spec in _keyed_fields(type(obj)):
        object.__setattr__(obj, name, spec.check(name, getattr(obj, name)))
