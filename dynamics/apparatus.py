"""The snail-cylinder apparatus and its derived groups.

An :class:`Apparatus` holds the dimensional parameters (SI units) of the device
of Balmforth, Bush, Vener & Young (2007): a solid inner cylinder (radius ``a``,
mass ``m_a``) in a thin hollow outer cylinder (radius ``b``, mass ``m_b``) that
rolls without slipping down a plane inclined at ``alpha``, the gap filled with
fluid (kinematic viscosity ``nu``, density ``rho``) over the axial length
``length``. Every group of section 2 is a property: the masses m''_a, m'_a,
m_f, M, the effective mass of (2.1)-(2.2), the time scale tau (2.9), the
groups Upsilon, s, mu_ of (2.12), the decay exponent q (3.10) and the speed
scale V* (6.2).

Table 2 reconciled
------------------
The printed tables are not mutually consistent; the presets :data:`STEEL` and
:data:`ALUMINIUM` take

* a = 0.8 cm, b = 1.125 cm, L = 10.35 cm, m_b = 47 g (Table 2);
* m_a = 158 g (steel) / 55 g (aluminium) (Tables 1 and 2);
* rho = 1000 kg/m^3. The printed m''_a = 21 g needs rho L = 21 g / (pi a^2);
  with L = 10.35 cm that is rho = 1.01 g/cm^3, while Table 1's 0.92-0.96 gives
  19.2-20.0 g. A round 1 g/cm^3 gives m''_a = 20.8 g, which prints as 21 g,
  and is evidently what the authors used;
* 24 g of oil in all (Table 1), of which pi (b^2 - a^2) L rho = 20.3 g fills
  the gap and the rest, 3.7 g, sits at the ends beyond the inner cylinder
  ("about 4 g of the total 24 g resides at the ends", Table 2 caption). The
  end fluid is carried by the outer cylinder: it counts in the total mass M
  but not in the gap fluid m_f (field ``m_f_ends``).

This reproduces the printed M = 229 g (steel), m''_a = 21 g, m'_a = 34 g
(aluminium), mu_ = 1.75 (steel) and q = 0.98 / 1.14 within their rounding.
It does not reproduce three printed numbers, each inconsistent with the
tables themselves: M = 127 g for aluminium (Table 1 sums to 55 + 47 + 24 =
126 g), m'_a = 134 g for steel (m_a - m''_a = 158 - 21 = 137 g in the same
table), and mu_ = 3.11 for aluminium (erratum 4: (127 + 47)/55 = 3.16 with the
printed M, 3.15 with Table 1's; the printed q = 1.14 follows from either).

The groups do not depend on the nominal ``nu`` and ``alpha`` of the presets
except through tau, Upsilon, s and V*: the presets carry the steel run of
figure 5(a) (nu = 2e-4 m^2/s, 2.4 degrees) and the aluminium run of figure 6
(nu = 2e-4 m^2/s, 5 degrees); override them with :func:`preset`.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from types import MappingProxyType

from dynamics.equations.reduced import ReducedParams
from dynamics.equations.special import decay_exponent
from lubrication.geometry import check_finite, check_range
from numerics.keys import check_fields, key

__all__ = ["ALUMINIUM", "DENSITY", "PRESETS", "STANDARD_GRAVITY", "STEEL", "Apparatus", "preset"]

STANDARD_GRAVITY = 9.80665  # m/s^2


def _positive(name: str, value: float, unit: str) -> float:
    return check_range(name, value, 0.0, math.inf, low_open=True, unit=unit)


# The ranges are those of devices from a micrometre to ten metres, of gases to mercury, and of
# viscosities from light gases to bitumen: wide, and finite, so that every derived group of a device
# inside them is a finite number (a viscosity of 1e-300 m^2/s or a mass of 1e200 kg is no device).
_LENGTH = {"dimension": "[length]", "unit": "m", "low": 1e-6, "high": 10.0, "bounds": "[]", "example": "0.8 cm"}
_MASS = {"dimension": "[mass]", "unit": "kg", "low": 1e-12, "high": 1e6, "bounds": "[]", "example": "158 g"}
#: Densities of fluids and of solid inner cylinders (kg/m^3).
DENSITY = {"dimension": "[mass] / [length] ** 3", "unit": "kg/m^3", "low": 1e-2, "high": 1e5,
           "bounds": "[]", "example": "0.95 g/cm^3"}


@dataclass(frozen=True)
class Apparatus:
    """Dimensional parameters of the snail cylinder (SI units).

    Parameters
    ----------
    a, b : float
        Inner and outer radii (m), ``0 < a < b``.
    length : float
        Axial length L of the inner cylinder and of the fluid-filled gap (m).
    m_a, m_b : float
        Masses of the inner (solid) and outer (thin shell) cylinders (kg). The
        inner cylinder must be heavier than the fluid it displaces.
    nu : float
        Kinematic viscosity of the fluid (m^2/s).
    rho : float
        Density of the fluid (kg/m^3).
    alpha : float
        Inclination of the plane (rad), in (-pi/2, pi/2); positive rolls the
        device in the direction of positive X_b.
    g : float, optional
        Gravitational acceleration (m/s^2); standard gravity by default.
    m_f_ends : float, optional
        Fluid outside the gap, e.g. at the ends beyond the inner cylinder (kg).
        It moves with the outer cylinder: it adds to the total mass M, not to
        the gap fluid m_f. Zero by default.

    Raises
    ------
    ValueError
        Naming the field and its allowed range, for non-finite numbers,
        lengths, masses, viscosity, density or gravity outside their ranges
        (those of the keys), ``a >= b``, ``alpha`` outside (-pi/2, pi/2), an
        inner cylinder lighter than the fluid it displaces, or a combination
        whose derived groups (tau, Upsilon, s, mu_, V*) are not finite.
    """

    a: float = key(help="inner radius", section="apparatus", **_LENGTH)
    b: float = key(help="outer radius, > a", section="apparatus", **_LENGTH)
    length: float = key(help="axial length of the inner cylinder and of the gap", section="apparatus",
                        **_LENGTH)
    m_a: float = key(help="mass of the inner (solid) cylinder", section="apparatus", **_MASS)
    m_b: float = key(help="mass of the outer (thin shell) cylinder", section="apparatus", **_MASS)
    nu: float = key(help="kinematic viscosity of the fluid", section="fluid", dimension="[length] ** 2 / [time]",
                    unit="m^2/s", low=1e-9, high=1e3, bounds="[]", example="200 cSt")
    rho: float = key(help="density of the fluid", section="fluid", **DENSITY)
    alpha: float = key(help="inclination of the plane, positive down the slope", section="incline",
                       unit="deg", low=-90.0, high=90.0, bounds="()", scale=math.pi / 180.0, example="2.4 deg")
    g: float = key(STANDARD_GRAVITY, help="gravitational acceleration", section="incline",
                   dimension="[length] / [time] ** 2", unit="m/s^2", low=1e-3, high=1e4, bounds="[]",
                   example="9.81 m/s^2")
    m_f_ends: float = key(0.0, help="fluid outside the gap, carried by the outer cylinder", section="apparatus",
                          **dict(_MASS, low=0.0))

    def __post_init__(self):
        check_fields(self)
        if not self.b > self.a:
            msg = f"b must be in (a, inf) = ({self.a:g}, inf) m (outer radius), got {self.b!r}"
            raise ValueError(msg)
        # tau and Upsilon carry m'_a = m_a - m''_a: a buoyant inner cylinder
        # has no sedimentation time scale.
        if not self.m_a_reduced > 0.0:
            msg = (f"m_a must be in (m''_a, inf) = ({self.m_a_displaced:g}, inf) kg: the inner "
                   f"cylinder must be heavier than the fluid it displaces, got {self.m_a!r}")
            raise ValueError(msg)
        derived = {"tau": self.tau, "upsilon": self.upsilon, "s": self.s, "mu_ratio": self.mu_ratio,
                   "v_star": self.v_star}
        bad = [f"{name} = {value:g}" for name, value in derived.items() if not 0.0 < abs(value) < math.inf
               and not (name == "s" and value == 0.0)]
        if bad:
            msg = (f"the apparatus gives {', '.join(bad)}, which no run can use: its keys a, b, length, m_a, m_b, "
                   "nu, rho and g lie in their ranges but combine to an extreme device; bring m_a further above "
                   f"the displaced fluid m''_a = {self.m_a_displaced:g} kg, or the other keys closer together")
            raise ValueError(msg)

    @classmethod
    def from_groups(cls, s: float, upsilon: float, mu_ratio: float, delta_over_a: float, *,
                    a: float = 0.008, length: float = 0.1035, rho: float = 1000.0,
                    density_ratio: float = 7.85, g: float = STANDARD_GRAVITY) -> Apparatus:
        """A dimensional apparatus with the given groups (2.12) in the distinguished limit.

        The slope follows from ``sin(alpha) = s (delta/a) m'_a / M``, so that
        sin(alpha) ~ delta/a as the reduced model assumes.

        Parameters
        ----------
        s, upsilon, mu_ratio : float
            The groups s, Upsilon and mu_ = (M + m_b)/m_a of (2.12).
        delta_over_a : float
            Gap-to-radius ratio (b - a)/a, positive.
        a : float, optional
            Inner radius (m); default 0.8 cm as in Table 2.
        length : float, optional
            Axial length (m); default 10.35 cm as in Table 2.
        rho : float, optional
            Fluid density (kg/m^3); default 1000, as the Table 2 presets.
        density_ratio : float, optional
            m_a/m''_a, the inner cylinder's density over the fluid's, > 1;
            default 7.85 (steel in a fluid of density 1000 kg/m^3).
        g : float, optional
            Gravitational acceleration (m/s^2).

        Returns
        -------
        Apparatus
            With no end fluid. The viscosity follows from Upsilon, the outer
            mass m_b from mu_ and the slope from s.

        Raises
        ------
        ValueError
            If ``mu_ratio <= 1 + m_f/m_a``: mu_ = 1 + (2 m_b + m_f)/m_a exceeds
            1 + m_f/m_a for every outer cylinder with positive mass, so the
            paper's mu_ = 1 would need a massless outer shell and no fluid. A
            larger ``density_ratio`` or a smaller ``delta_over_a`` lowers the
            bound. Also if |s| is too large for any slope, or if an argument
            is out of its range.
        """
        s = check_finite("s", s)
        upsilon = _positive("upsilon", upsilon, "")
        mu_ratio = check_finite("mu_ratio", mu_ratio)
        delta_over_a = _positive("delta_over_a", delta_over_a, "")
        a = _positive("a", a, "m")
        length = _positive("length", length, "m")
        rho = _positive("rho", rho, "kg/m^3")
        g = _positive("g", g, "m/s^2")
        density_ratio = check_range("density_ratio", density_ratio, 1.0, math.inf, low_open=True)

        delta = delta_over_a * a
        b = a + delta
        m_displaced = math.pi * a * a * length * rho
        m_f = math.pi * (b * b - a * a) * length * rho
        m_a = density_ratio * m_displaced
        mu_min = 1.0 + m_f / m_a
        if not mu_ratio > mu_min:
            msg = (f"mu_ratio must be in (1 + m_f/m_a, inf) = ({mu_min:.6g}, inf) for "
                   f"delta_over_a = {delta_over_a:g} and density_ratio = {density_ratio:g}, "
                   f"got {mu_ratio!r}: mu_ = (M + m_b)/m_a = 1 + (2 m_b + m_f)/m_a needs a "
                   f"positive outer mass m_b; the bound falls with a thinner gap delta_over_a, or "
                   f"with an inner cylinder denser than {density_ratio:g} times the fluid")
            raise ValueError(msg)
        m_b = 0.5 * (mu_ratio * m_a - m_a - m_f)
        m_reduced = m_a - m_displaced
        # Upsilon = g delta^3 m_a m'_a / (144 nu^2 m''_a^2)  (2.12)
        nu = math.sqrt(g * delta**3 * m_a * m_reduced / (144.0 * upsilon * m_displaced**2))
        total = m_a + m_b + m_f
        sin_alpha = s * delta_over_a * m_reduced / total
        if not abs(sin_alpha) < 1.0:
            bound = total / (delta_over_a * m_reduced)
            msg = (f"s must be in (-{bound:.6g}, {bound:.6g}) for these groups "
                   f"(|sin alpha| < 1), got {s!r}")
            raise ValueError(msg)
        return cls(a=a, b=b, length=length, m_a=m_a, m_b=m_b, nu=nu, rho=rho,
                   alpha=math.asin(sin_alpha), g=g)

    # -- geometry and fluid --------------------------------------------------
    @property
    def delta(self) -> float:
        """Mean gap b - a (m)."""
        return self.b - self.a

    @property
    def delta_over_a(self) -> float:
        """Gap-to-radius ratio delta/a, the small parameter of the reduced model."""
        return self.delta / self.a

    @property
    def mu(self) -> float:
        """Dynamic viscosity rho nu (Pa s); not the paper's mass ratio (see :attr:`mu_ratio`)."""
        return self.rho * self.nu

    # -- masses ----------------------------------------------------------------
    @property
    def m_a_displaced(self) -> float:
        """m''_a = pi a^2 L rho, the fluid displaced by the inner cylinder (kg)."""
        return math.pi * self.a**2 * self.length * self.rho

    @property
    def m_a_reduced(self) -> float:
        """m'_a = m_a - m''_a, the inner cylinder's mass less its buoyancy (kg)."""
        return self.m_a - self.m_a_displaced

    @property
    def m_f(self) -> float:
        """m_f = pi (b^2 - a^2) L rho, the fluid in the gap (kg)."""
        return math.pi * (self.b**2 - self.a**2) * self.length * self.rho

    @property
    def M(self) -> float:  # noqa: N802  (the paper's symbol)
        """Total mass m_a + m_b + m_f, plus any end fluid (kg)."""
        return self.m_a + self.m_b + self.m_f + self.m_f_ends

    @property
    def m_eff(self) -> float:
        """Effective inertial mass m_a + m''_a^2 / m_f of (2.1)-(2.2) (kg).

        The fluid's centre of mass moves by -(m''_a/m_f) eps when the inner
        cylinder moves by eps (A5); working in the fluid's frame adds
        m''_a times that acceleration (A23), hence m''_a^2/m_f (A28). The
        text's m_a + m''_a/m_f adds a pure number to a mass (erratum 1).
        """
        return self.m_a + self.m_a_displaced**2 / self.m_f

    # -- groups ----------------------------------------------------------------
    @property
    def tau(self) -> float:
        """Time scale tau = 12 m''_a nu a / (m'_a delta^2 g) (2.9), in s."""
        return 12.0 * self.m_a_displaced * self.nu * self.a / (
            self.m_a_reduced * self.delta**2 * self.g)

    @property
    def upsilon(self) -> float:
        """Upsilon = g delta^3 m_a m'_a / (144 nu^2 m''_a^2) (2.12): inertia over lubrication."""
        return self.g * self.delta**3 * self.m_a * self.m_a_reduced / (
            144.0 * self.nu**2 * self.m_a_displaced**2)

    @property
    def s(self) -> float:
        """Slope group s = (a sin(alpha)/delta) (M/m'_a) (2.12)."""
        return self.a * math.sin(self.alpha) / self.delta * self.M / self.m_a_reduced

    @property
    def mu_ratio(self) -> float:
        """The paper's mu = (M + m_b)/m_a (2.12), a mass ratio (not the viscosity)."""
        return (self.M + self.m_b) / self.m_a

    @property
    def q(self) -> float:
        """Decay exponent q = 3 (1 + 4 mu_^2) / (2 (1 + 2 mu_)^2) of the rocking (3.10)."""
        return decay_exponent(self.mu_ratio)

    @property
    def v_star(self) -> float:
        """Speed scale V* = b M delta g / (4 nu m''_a) (6.2), in m/s."""
        return self.b * self.M * self.delta * self.g / (4.0 * self.nu * self.m_a_displaced)

    @property
    def runaway_acceleration(self) -> float:
        """Dimensional runaway acceleration M g sin(alpha) / (M + m_b + m_a/2) (3.11), in m/s^2."""
        return self.M * self.g * math.sin(self.alpha) / (self.M + self.m_b + 0.5 * self.m_a)

    @property
    def reduced_params(self) -> ReducedParams:
        """The groups (s, Upsilon, mu_) of the reduced model (2.11)."""
        return ReducedParams(s=self.s, upsilon=self.upsilon, mu_ratio=self.mu_ratio)


def _table2(m_a: float, alpha_deg: float) -> Apparatus:
    """The apparatus of Table 2 with 24 g of oil in all (see the module docstring)."""
    gap_only = Apparatus(a=0.008, b=0.01125, length=0.1035, m_a=m_a, m_b=0.047,
                         nu=2e-4, rho=1000.0, alpha=math.radians(alpha_deg))
    return dataclasses.replace(gap_only, m_f_ends=0.024 - gap_only.m_f)


STEEL = _table2(m_a=0.158, alpha_deg=2.4)  # figure 5(a)
ALUMINIUM = _table2(m_a=0.055, alpha_deg=5.0)  # figure 6
PRESETS = MappingProxyType({"steel": STEEL, "aluminium": ALUMINIUM})


def preset(name: str, **overrides: float) -> Apparatus:
    """The preset ``name`` ("steel" or "aluminium") with fields replaced by ``overrides``.

    Raises
    ------
    ValueError
        For an unknown preset name or field, or an out-of-range value.
    """
    try:
        base = PRESETS[name]
    except KeyError as err:
        msg = f"preset must be one of {sorted(PRESETS)}, got {name!r}"
        raise ValueError(msg) from err
    fields = {f.name for f in dataclasses.fields(Apparatus)}
    unknown = sorted(set(overrides) - fields)
    if unknown:
        msg = f"unknown apparatus field(s) {unknown}; allowed: {sorted(fields)}"
        raise ValueError(msg)
    return dataclasses.replace(base, **overrides)
