"""Validation records that anyone can re-check from their own numbers.

A :class:`Check` is a comparison: a measured number, a reference, a tolerance
and a kind that says how they are compared. Whether it passed is never given:
:func:`verdict` computes it from those four fields, so a written
``validation.json`` can be verified again from its contents alone. A
:class:`Finding` is a number the report states without judging it (a share, a
fitted coefficient); findings are listed apart and never counted as passes.

Kinds
-----
relative   |measured - reference| <= tolerance |reference|
absolute   |measured - reference| <= tolerance
at-most    measured <= reference + tolerance   (reference is an upper bound)
at-least   measured >= reference - tolerance   (reference is a lower bound)

A measurement that is not a finite number fails every kind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["KINDS", "Check", "Finding", "absolute", "at_least", "at_most", "comparisons", "relative", "verdict"]

KINDS = ("relative", "absolute", "at-most", "at-least")


def verdict(kind: str, measured: float, reference: float, tolerance: float) -> bool:
    """Whether a comparison of ``kind`` passes; the one rule every record is judged by."""
    if not math.isfinite(measured):
        return False
    if kind == "relative":
        return abs(measured - reference) <= tolerance * abs(reference)
    if kind == "absolute":
        return abs(measured - reference) <= tolerance
    if kind == "at-most":
        return measured <= reference + tolerance
    if kind == "at-least":
        return measured >= reference - tolerance
    msg = f"kind must be one of {', '.join(KINDS)}, got {kind!r}"
    raise ValueError(msg)


@dataclass(frozen=True)
class Check:
    """A comparison; :attr:`passed` follows from the numbers by :func:`verdict`."""

    name: str
    measured: float
    reference: float
    tolerance: float
    kind: str = "relative"
    note: str = ""

    def __post_init__(self):
        # numpy scalars in, plain JSON-ready Python values out
        for field in ("measured", "reference", "tolerance"):
            object.__setattr__(self, field, float(getattr(self, field)))
        if self.kind not in KINDS:
            msg = f"kind must be one of {', '.join(KINDS)}, got {self.kind!r}"
            raise ValueError(msg)
        if not (math.isfinite(self.reference) and math.isfinite(self.tolerance) and self.tolerance >= 0.0):
            msg = (f"check {self.name!r}: the reference and tolerance must be finite and the tolerance "
                   f">= 0, got {self.reference!r} and {self.tolerance!r}")
            raise ValueError(msg)

    @property
    def passed(self) -> bool:
        return verdict(self.kind, self.measured, self.reference, self.tolerance)

    def as_dict(self) -> dict:
        """JSON-ready, with ``passed``; a non-finite measurement (a failed run) becomes a string."""
        measured = self.measured if math.isfinite(self.measured) else str(self.measured)
        return {"name": self.name, "kind": self.kind, "measured": measured, "reference": self.reference,
                "tolerance": self.tolerance, "passed": self.passed, "note": self.note}


@dataclass(frozen=True)
class Finding:
    """A number the report states without a pass or fail: never counted as a check."""

    name: str
    value: float
    note: str = ""

    def __post_init__(self):
        object.__setattr__(self, "value", float(self.value))

    def as_dict(self) -> dict:
        value = self.value if math.isfinite(self.value) else str(self.value)
        return {"name": self.name, "value": value, "note": self.note}


def relative(name: str, measured: float, reference: float, tolerance: float, note: str = "") -> Check:
    return Check(name, measured, reference, tolerance, "relative", note)


def absolute(name: str, measured: float, reference: float, tolerance: float, note: str = "") -> Check:
    return Check(name, measured, reference, tolerance, "absolute", note)


def at_most(name: str, measured: float, bound: float, note: str = "", slack: float = 0.0) -> Check:
    """A measured quantity (an error, a cost) that must not exceed ``bound``."""
    return Check(name, measured, bound, slack, "at-most", note)


def at_least(name: str, measured: float, bound: float, note: str = "", slack: float = 0.0) -> Check:
    """A measured quantity that must reach ``bound``."""
    return Check(name, measured, bound, slack, "at-least", note)


def comparisons(records) -> list[Check]:
    """The checks among ``records``, findings left out."""
    return [r for r in records if isinstance(r, Check)]
