"""Quantities with units in scenes, read by pint; the registry is built on first use.

Building pint's registry takes about a second, which a run given only plain SI
numbers should not pay, so it is created when the first string with units is read.
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

    # Decimal magnitudes: decimal unit factors (cSt, g/cm^3) convert exactly, where
    # binary floats would give 200 cSt = 2.0000000000000004e-4 m^2/s.
    return pint.UnitRegistry(non_int_type=Decimal)


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
