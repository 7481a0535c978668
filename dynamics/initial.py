"""The initial state of a run, in the paper's variables."""

from __future__ import annotations

from dataclasses import dataclass

from lubrication.geometry import MAX_RATE
from numerics.keys import check_fields, key

__all__ = ["MAX_RATE", "Initial"]

_RATE = {"dimension": "1 / [time]", "unit": "rad/s", "example": "1 rad/s", "reduced_unit": "rad/tau",
         "low": -MAX_RATE, "high": MAX_RATE}


@dataclass(frozen=True)
class Initial:
    """The initial state; rates per second, or per tau in a dimensionless run.

    Angles and spins are clockwise, as in the paper's figure 1. Out-of-range
    values raise ValueError naming the field and its range.
    """

    kappa: float = key(0.0, help="eccentricity eps/delta", low=0.0, high=1.0, bounds="[)")
    phi: float = key(0.0, help="angle of the line of centres B->A from the upward vertical", unit="deg",
                     scale=0.017453292519943295, example="30 deg", low=-1e6, high=1e6)
    kappa_dot: float = key(0.0, help="d kappa/dt", dimension="1 / [time]", unit="1/s", example="0.1 / s",
                           reduced_unit="1/tau", low=-MAX_RATE, high=MAX_RATE)
    phi_dot: float = key(0.0, help="d phi/dt", **_RATE)
    omega_a: float = key(0.0, help="spin Omega_a of the inner cylinder", **_RATE)
    omega_b: float = key(0.0, help="spin Omega_b of the outer cylinder, X_b' = b Omega_b", **_RATE)
    one_minus_kappa: float | None = key(None, help="1 - kappa given directly, for starts so close to contact "
                                        "that kappa cannot carry the gap (then kappa is ignored)", low=0.0,
                                        high=1.0, bounds="(]", none="none")

    def __post_init__(self):
        check_fields(self)
        if self.one_minus_kappa is not None:
            object.__setattr__(self, "kappa", 1.0 - self.one_minus_kappa)

    @property
    def gap(self) -> float:
        """1 - kappa, exact when given as ``one_minus_kappa``."""
        return 1.0 - self.kappa if self.one_minus_kappa is None else self.one_minus_kappa
