"""Moved to :mod:`dynamics.regime`."""

from dynamics.regime import REGIMES, STEADY_SPREAD, classify  # noqa: F401
