"""Quantities with units in scenes, read by pint; the registry is built on first use.

Importing pint and building its registry takes about a second, which a run given
only plain SI numbers should not pay, so both happen when the first string with
units is read; pint keeps its parsed definitions in the project's cache folder
(:func:`lubrication.files.cache_folder`), which cuts the registry's build from
0.45 s to 0.1 s after the first time.
"""

from __future__ import annotations

from decimal import Decimal
from functools import cache

__all__ = ["UnitError", "to_si"]


class UnitError(ValueError):
    """A string that is not a quantity, or not of the expected dimension."""


@cache
def _registry():
    import pint

    from lubrication.files import cache_folder

    # Decimal magnitudes: decimal unit factors (cSt, g/cm^3) convert exactly, where
    # binary floats would give 200 cSt = 2.0000000000000004e-4 m^2/s.
    return pint.UnitRegistry(non_int_type=Decimal, cache_folder=cache_folder() / "pint")


def to_si(text: str, dimension: str) -> float:
    """The quantity ``text`` (such as "200 cSt") in SI base units, after checking its dimension.

    Raises
    ------
    UnitError
        If pint cannot read ``text`` (the message says why), or its dimension is
        not ``dimension`` (a pint dimensionality such as "[length] ** 2 / [time]").
    """
    try:
        quantity = _registry().Quantity(text)
    # pint's parser raises many types (PintError, TokenError, AssertionError, ValueError).
    except Exception as err:  # noqa: BLE001
        msg = f"not a quantity pint can read ({err})"
        raise UnitError(msg) from err
    if not quantity.check(dimension):
        msg = f"has the unit {quantity.units} ({quantity.dimensionality})"
        raise UnitError(msg)
    return float(quantity.to_base_units().magnitude)
