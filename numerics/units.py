"""Quantities with units in scenes, read by pint; the registry is built on first use.

Importing pint and building its registry is a cost that a run given only plain
SI numbers should not pay, so both happen when the first string with units is
read; pint keeps its parsed definitions in the project's cache folder
(:func:`numerics.files.cache_folder`), which shortens the registry's build after
the first time.

Even then pint's import is a large part of a warm ``snail run``. So
every quantity read is remembered in that folder (``units.json``), under
pint's version: a scene whose strings were all read before (the default
scene, after its first run) converts them without importing pint.
"""

from __future__ import annotations

import json
import math
from decimal import Decimal
from functools import cache
from importlib.metadata import version

__all__ = ["UnitError", "to_si"]


class UnitError(ValueError):
    """A string that is not a quantity, or not of the expected dimension."""


@cache
def _registry():
    import pint

    from numerics.files import cache_folder

    # Decimal magnitudes: decimal unit factors (cSt, g/cm^3) convert exactly, where
    # binary floats would give 200 cSt = 2.0000000000000004e-4 m^2/s.
    return pint.UnitRegistry(non_int_type=Decimal, cache_folder=cache_folder() / "pint")


def _memo_path():
    from numerics.files import cache_folder

    return cache_folder() / "units.json"


@cache
def _memo() -> dict:
    """The quantities read before with this version of pint, {"text|dimension": SI value}."""
    try:
        stored = json.loads(_memo_path().read_text())
    except (OSError, ValueError):  # none yet, or unreadable: start afresh
        return {}
    ok = isinstance(stored, dict) and stored.get("pint") == version("pint") and isinstance(stored.get("si"), dict)
    return stored["si"] if ok else {}


def _remember(key: str, value: float) -> None:
    from numerics.files import write_json

    if not math.isfinite(value):  # JSON has no inf; such a quantity is read by pint each time
        return
    memo = _memo()
    memo[key] = value
    try:
        write_json(_memo_path(), {"pint": version("pint"), "si": memo})
    except OSError:  # a read-only folder: the next run imports pint
        pass


def to_si(text: str, dimension: str) -> float:
    """The quantity ``text`` (such as "200 cSt") in SI base units, after checking its dimension.

    Raises
    ------
    UnitError
        If pint cannot read ``text`` (the message says why), or its dimension is
        not ``dimension`` (a pint dimensionality such as "[length] ** 2 / [time]").
    """
    key = f"{text}|{dimension}"
    if key in _memo():
        return _memo()[key]
    try:
        quantity = _registry().Quantity(text)
    # pint's parser raises many types (PintError, TokenError, AssertionError, ValueError).
    except Exception as err:  # noqa: BLE001
        msg = f"not a quantity pint can read ({err})"
        raise UnitError(msg) from err
    if not quantity.check(dimension):
        msg = f"has the unit {quantity.units} ({quantity.dimensionality})"
        raise UnitError(msg)
    value = float(quantity.to_base_units().magnitude)
    _remember(key, value)
    return value
