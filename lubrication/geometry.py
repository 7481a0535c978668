"""The eccentric annulus, the fluid and the instantaneous motion.

Conventions (Balmforth, Bush, Vener & Young 2007, figure 1 and Appendix B).
The frame co-rotates with the line of centres. ``e_eps`` points from the
outer centre B to the inner centre A, ``e_chi`` is the direction of increasing
chi, and positive rotations turn ``e_eps`` towards ``e_chi`` (clockwise in the
paper's figure). The gap angle theta is measured from the narrowest point
(along ``e_eps``) in the positive sense. f_eps and f_chi are the fluid force on
the inner cylinder along ``e_eps`` and ``e_chi``; T_a is the fluid torque on it
about A, positive in the same sense as the rotations.
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass, field

__all__ = ["Annulus", "Fluid", "Motion", "FluidForces", "MAX_RATE", "MIN_ONE_MINUS_KAPPA", "NotANumberError", "RESISTANCE_NAMES",
           "Resistance", "check_finite", "check_range"]

#: The five resistance coefficients of a full film, in the order every table and array of
#: the project uses: f_eps per eps', then f_chi and T_a per W_a = Omega_a - chi', then
#: f_chi and T_a per W_b = Omega_b - chi' (see :class:`lubrication.geometry.Resistance`).
RESISTANCE_NAMES = ("f_eps_per_eps_dot", "f_chi_per_w_a", "t_a_per_w_a", "f_chi_per_w_b", "t_a_per_w_b")

# Forces grow as (1 - kappa)^(-3/2); below this gap they would overflow a double.
MIN_ONE_MINUS_KAPPA = 1e-150


class NotANumberError(TypeError, ValueError):
    """A value of the wrong type where a number belongs: a TypeError, and a ValueError for the callers
    that report every bad value alike (as numpy's ``AxisError`` is both a ValueError and an IndexError)."""


def check_finite(name: str, value: float) -> float:
    """Return ``value`` as a float, or raise naming ``name`` if it is not a finite number.

    Strings and booleans are refused although ``float`` takes them: "0.5" in a
    field is a mistake to report where it is made, not a number to guess.
    """
    if isinstance(value, (str, bytes, bool)):
        msg = f"{name} must be a finite number, got {value!r}"
        raise NotANumberError(msg)
    try:
        x = float(value)
    except (TypeError, ValueError) as err:
        msg = f"{name} must be a finite number, got {value!r}"
        raise ValueError(msg) from err
    if not math.isfinite(x):
        msg = f"{name} must be a finite number, got {value!r}"
        raise ValueError(msg)
    return x


def check_range(name: str, value: float, low: float, high: float, *,
                low_open: bool = False, high_open: bool = True, unit: str = "") -> float:
    """Check that ``value`` is finite and lies in the interval; the message names the range."""
    x = check_finite(name, value)
    too_low = x <= low if low_open else x < low
    too_high = x >= high if high_open else x > high
    if too_low or too_high:
        left = "(" if low_open else "["
        right = ")" if high_open else "]"
        hi = "inf" if math.isinf(high) else f"{high:g}"
        suffix = f" {unit}" if unit else ""
        msg = f"{name} must be in {left}{low:g}, {hi}{right}{suffix}, got {value!r}"
        raise ValueError(msg)
    return x


@dataclass(frozen=True)
class Annulus:
    """Two eccentric circles: inner radius ``a``, outer radius ``b``, centre distance ``eps``.

    Parameters
    ----------
    a, b : float
        Radii in m, ``0 < a < b``.
    eps : float
        Distance between the centres in m, ``0 <= eps < b - a``.
    length : float
        Axial length L in m; forces and torque are for the whole length.
    one_minus_kappa : float, optional
        ``1 - eps/(b - a)`` supplied directly, for states so close to contact
        that ``kappa`` itself has lost the relative precision of the gap. When
        given it takes precedence and ``eps`` is recomputed from it.
    """

    a: float
    b: float
    eps: float = 0.0
    length: float = 1.0
    one_minus_kappa: float = field(default=math.nan)

    def __post_init__(self):
        a = check_range("a", self.a, 0.0, math.inf, low_open=True, unit="m")
        b = check_finite("b", self.b)
        if not b > a:
            msg = f"b must be greater than a = {a:g} m (outer radius), got {self.b!r}"
            raise ValueError(msg)
        delta = b - a
        if not math.isfinite(delta / a):
            msg = f"b must be in (a, inf) with a finite ratio b/a, got a = {a!r} m, b = {self.b!r} m"
            raise ValueError(msg)
        check_range("length", self.length, 0.0, math.inf, low_open=True, unit="m")
        if math.isnan(self.one_minus_kappa):
            eps = check_range("eps", self.eps, 0.0, delta, unit="m (eps = kappa (b - a))")
            omk = (delta - eps) / delta
        else:
            omk = check_finite("one_minus_kappa", self.one_minus_kappa)
            eps = (1.0 - omk) * delta
        check_range("one_minus_kappa", omk, MIN_ONE_MINUS_KAPPA, 1.0, high_open=False,
                    unit="(the gap's narrowest point relative to its mean)")
        object.__setattr__(self, "eps", eps)
        object.__setattr__(self, "one_minus_kappa", omk)

    @classmethod
    def from_kappa(cls, a: float, b: float, kappa: float, length: float = 1.0) -> Annulus:
        """Annulus with eccentricity ratio ``kappa = eps/(b - a)`` in [0, 1)."""
        kappa = check_range("kappa", kappa, 0.0, 1.0)
        return cls(a=a, b=b, length=length, one_minus_kappa=1.0 - kappa)

    @property
    def delta(self) -> float:
        """Mean gap width b - a (m)."""
        return self.b - self.a

    @property
    def kappa(self) -> float:
        """Eccentricity ratio eps/delta in [0, 1)."""
        return 1.0 - self.one_minus_kappa

    @property
    def delta_over_a(self) -> float:
        return self.delta / self.a


@dataclass(frozen=True)
class Fluid:
    """A Newtonian fluid: kinematic viscosity ``nu`` (m^2/s) and density ``rho`` (kg/m^3)."""

    nu: float
    rho: float

    def __post_init__(self):
        check_range("nu", self.nu, 0.0, math.inf, low_open=True, unit="m^2/s")
        check_range("rho", self.rho, 0.0, math.inf, low_open=True, unit="kg/m^3")

    @property
    def mu(self) -> float:
        """Dynamic viscosity rho nu (Pa s)."""
        return self.rho * self.nu


# Rates beyond a million per second are no motion of a rolling device: bounded so that the forces and
# Reynolds numbers they give stay finite numbers.
MAX_RATE = 1e6


@dataclass(frozen=True)
class Motion:
    """Instantaneous velocities: eps' (m/s), chi', Omega_a, Omega_b (rad/s), each of size at most
    :data:`MAX_RATE`."""

    eps_dot: float = 0.0
    chi_dot: float = 0.0
    omega_a: float = 0.0
    omega_b: float = 0.0

    def __post_init__(self):
        for name in ("eps_dot", "chi_dot", "omega_a", "omega_b"):
            check_range(name, getattr(self, name), -MAX_RATE, MAX_RATE, high_open=False,
                        unit="m/s" if name == "eps_dot" else "rad/s")

    @property
    def w_a(self) -> float:
        """Inner rotation relative to the line of centres, Omega_a - chi'."""
        return self.omega_a - self.chi_dot

    @property
    def w_b(self) -> float:
        """Outer rotation relative to the line of centres, Omega_b - chi'."""
        return self.omega_b - self.chi_dot


@dataclass(frozen=True)
class FluidForces:
    """Fluid force (N) and torque (N m) on the inner cylinder, whole length."""

    f_eps: float
    f_chi: float
    T_a: float
    model: str = ""

    def as_tuple(self) -> tuple[float, float, float]:
        return (self.f_eps, self.f_chi, self.T_a)


@dataclass(frozen=True)
class Resistance:
    """The five resistance coefficients of the inner cylinder, whole length.

    By linearity and the reflection symmetry about the line of centres, a
    full-film force model is fixed by: f_eps per eps' (N s/m), and f_chi
    (N s) and T_a (N m s) per unit rotation W_a = Omega_a - chi' and
    W_b = Omega_b - chi'. Radial motion gives no f_chi or T_a, rotations no f_eps.
    """

    f_eps_per_eps_dot: float
    f_chi_per_w_a: float
    t_a_per_w_a: float
    f_chi_per_w_b: float
    t_a_per_w_b: float

    NAMES = RESISTANCE_NAMES

    def as_tuple(self) -> tuple[float, ...]:
        return astuple(self)
