"""One validation check: a measured number, its reference and the tolerance it must meet."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

__all__ = ["Check", "relative", "absolute", "at_most"]


@dataclass(frozen=True)
class Check:
    """``passed`` when |measured - reference| <= tolerance (absolute), or <= tolerance |reference| (relative)."""

    name: str
    measured: float
    reference: float
    tolerance: float
    passed: bool
    kind: str = "relative"
    note: str = ""

    def __post_init__(self):
        # numpy scalars in, plain JSON-ready Python values out
        for name in ("measured", "reference", "tolerance"):
            object.__setattr__(self, name, float(getattr(self, name)))
        object.__setattr__(self, "passed", bool(self.passed))

    def as_dict(self) -> dict:
        """JSON-ready; non-finite numbers (a failed measurement) become strings."""
        return {k: (str(v) if isinstance(v, float) and not math.isfinite(v) else v)
                for k, v in asdict(self).items()}


def relative(name: str, measured: float, reference: float, tolerance: float, note: str = "") -> Check:
    ok = math.isfinite(measured) and abs(measured - reference) <= tolerance * abs(reference)
    return Check(name, measured, reference, tolerance, ok, "relative", note)


def absolute(name: str, measured: float, reference: float, tolerance: float, note: str = "") -> Check:
    ok = math.isfinite(measured) and abs(measured - reference) <= tolerance
    return Check(name, measured, reference, tolerance, ok, "absolute", note)


def at_most(name: str, measured: float, bound: float, note: str = "") -> Check:
    """A measured quantity (an error, a cost) that must not exceed ``bound``."""
    ok = math.isfinite(measured) and measured <= bound
    return Check(name, measured, bound, 0.0, ok, "upper-bound", note)
