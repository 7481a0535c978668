"""The apparatus, its derived groups, the Table 2 presets and the from_groups constructor."""

import dataclasses
import math

import pint
import pytest

from dynamics.apparatus import ALUMINIUM, PRESETS, STEEL, Apparatus, preset
from dynamics.equations.reduced import ReducedParams
from dynamics.equations.special import decay_exponent, runaway_spin_rate

from apparatus import A, B, L

GRAM = 1e-3

# Table 2 as printed (grams, and the dimensionless mu_ and q).
TABLE2 = {
    "steel": {"M": 229, "m_a": 158, "m_a_reduced": 134, "m_a_displaced": 21, "mu_ratio": 1.75,
              "q": 0.98},
    "aluminium": {"M": 127, "m_a": 55, "m_a_reduced": 34, "m_a_displaced": 21,
                  "mu_ratio": 3.11, "q": 1.14},
}


@pytest.fixture(scope="module")
def ureg():
    return pint.UnitRegistry()


def _kwargs(**overrides):
    base = dict(a=A, b=B, length=L, m_a=0.158, m_b=0.047, nu=2e-4, rho=960.0,
                alpha=0.04)
    base.update(overrides)
    return base


# -- validation ---------------------------------------------------------------

@pytest.mark.parametrize(("field", "value", "words"), [
    ("a", 0.0, "a must be in [1e-06, 10] m"),
    ("a", -1.0, "a must be in [1e-06, 10] m"),
    ("b", 0.008, "b must be in (a, inf)"),
    ("b", 0.005, "b must be in (a, inf)"),
    ("length", 0.0, "length must be in [1e-06, 10] m"),
    ("m_a", 0.0, "m_a must be in [1e-12, 1e+06] kg"),
    ("m_b", -0.047, "m_b must be in [1e-12, 1e+06] kg"),
    ("nu", 0.0, "nu must be in [1e-09, 1000] m^2/s"),
    ("rho", -1.0, "rho must be in [0.01, 100000] kg/m^3"),
    ("alpha", math.pi / 2, "alpha must be in (-90, 90) deg, got 1.5707963267948966 rad = 90 deg"),
    ("alpha", -2.0, "alpha must be in (-90, 90) deg"),
    ("g", 0.0, "g must be in [0.001, 10000]"),
    ("m_f_ends", -1e-3, "m_f_ends must be in [0, 1e+06] kg"),
    ("a", math.nan, "a must be in [1e-06, 10] m, got nan"),
    ("nu", math.inf, "nu must be in [1e-09, 1000] m^2/s, got inf"),
    ("alpha", "steep", "alpha must be in (-90, 90) deg, got 'steep'"),
])
def test_invalid_field_is_named_with_its_range(field, value, words):
    with pytest.raises(ValueError) as info:
        Apparatus(**_kwargs(**{field: value}))
    assert words in str(info.value)


def test_buoyant_inner_cylinder_is_refused():
    # rho above the steel's density: m'_a < 0, tau and Upsilon meaningless.
    with pytest.raises(ValueError, match=r"m_a must be in \(m''_a, inf\)"):
        Apparatus(**_kwargs(rho=8000.0))


def test_fields_are_stored_as_floats_and_frozen():
    app = Apparatus(**_kwargs(m_a=1, m_b=1))
    assert isinstance(app.m_a, float) and isinstance(app.m_b, float)
    with pytest.raises(dataclasses.FrozenInstanceError):
        app.a = 0.01


# -- derived groups -----------------------------------------------------------

def test_derived_groups_from_their_definitions():
    app = Apparatus(**_kwargs())
    a, b, L, rho, nu, g = app.a, app.b, app.length, app.rho, app.nu, app.g
    delta = b - a
    m2 = math.pi * a * a * L * rho
    m1 = app.m_a - m2
    m_f = math.pi * (b * b - a * a) * L * rho
    big_m = app.m_a + app.m_b + m_f
    assert app.delta == pytest.approx(delta, rel=1e-15)
    assert app.delta_over_a == pytest.approx(delta / a, rel=1e-15)
    assert app.mu == pytest.approx(rho * nu, rel=1e-15)
    assert app.m_a_displaced == pytest.approx(m2, rel=1e-15)
    assert app.m_a_reduced == pytest.approx(m1, rel=1e-15)
    assert app.m_f == pytest.approx(m_f, rel=1e-15)
    assert app.M == pytest.approx(big_m, rel=1e-15)
    assert app.tau == pytest.approx(12 * m2 * nu * a / (m1 * delta**2 * g), rel=1e-14)
    assert app.upsilon == pytest.approx(g * delta**3 * app.m_a * m1 / (144 * nu**2 * m2**2),
                                        rel=1e-14)
    assert app.s == pytest.approx(a * math.sin(app.alpha) / delta * big_m / m1, rel=1e-14)
    assert app.mu_ratio == pytest.approx((big_m + app.m_b) / app.m_a, rel=1e-15)
    mu_ = app.mu_ratio
    assert app.q == pytest.approx(3 * (1 + 4 * mu_**2) / (2 * (1 + 2 * mu_) ** 2), rel=1e-15)
    assert app.v_star == pytest.approx(b * big_m * delta * g / (4 * nu * m2), rel=1e-14)
    assert app.reduced_params == ReducedParams(app.s, app.upsilon, app.mu_ratio)


def test_tau_and_v_star_are_a_time_and_a_speed(ureg):
    m, kg, s = ureg.meter, ureg.kilogram, ureg.second
    a, delta, nu, g = 0.008 * m, 0.00325 * m, 2e-4 * m**2 / s, 9.8 * m / s**2
    m2, m1, big_m = 0.021 * kg, 0.137 * kg, 0.229 * kg
    assert (12 * m2 * nu * a / (m1 * delta**2 * g)).dimensionality == s.dimensionality
    v_star = (a + delta) * big_m * delta * g / (4 * nu * m2)
    assert v_star.dimensionality == (m / s).dimensionality
    assert (g * delta**3 * m2 * m1 / (144 * nu**2 * m2**2)).dimensionless


def test_effective_mass_erratum_1(ureg):
    """m_eff = m_a + m''_a^2/m_f (A28), not the text's m_a + m''_a/m_f below (2.1).

    m''_a/m_f is a ratio of masses, a pure number: adding it to the mass m_a is
    dimensionally meaningless, and its numerical value would change with the
    unit of mass. m''_a^2/m_f is a mass: the fluid's centre of mass moves by
    -(m''_a/m_f) eps (A5), and the fluid frame adds m''_a times that
    acceleration to the inner cylinder's equation (A23), hence (m''_a)^2/m_f.
    """
    m_a, m2, m_f = (x * ureg.gram for x in (158.0, 21.0, 20.0))
    with pytest.raises(pint.DimensionalityError):
        m_a + m2 / m_f  # noqa: B018  (the printed formula)
    assert (m_a + m2**2 / m_f).dimensionality == ureg.kilogram.dimensionality
    # The printed formula's number depends on the unit of mass; the right one does not.
    grams = 158.0 + 21.0 / 20.0
    kilograms = 0.158 + 0.021 / 0.020
    assert kilograms * 1e3 != pytest.approx(grams, rel=1e-3)
    assert STEEL.m_eff == pytest.approx(STEEL.m_a + STEEL.m_a_displaced**2 / STEEL.m_f, rel=1e-15)
    assert STEEL.m_eff != pytest.approx(STEEL.m_a + STEEL.m_a_displaced / STEEL.m_f, rel=1e-3)


def test_runaway_acceleration_matches_the_reduced_runaway():
    """(3.11) dimensionally: b d(Omega_b)/dt = (b/a) M g sin(alpha)/(M + m_b + m_a/2).

    The reduced slope s/((mu_ + 1/2) Upsilon) in units of 1/tau^2, times b/tau^2,
    is the printed dimensional acceleration up to the factor b/a = 1 + delta/a:
    the two agree at leading order in delta/a, as the distinguished limit says.
    """
    for app in (STEEL, ALUMINIUM):
        reduced = runaway_spin_rate(app.s, app.upsilon, app.mu_ratio) * app.b / app.tau**2
        assert reduced / app.runaway_acceleration == pytest.approx(app.b / app.a, rel=1e-13)


# -- Table 2 --------------------------------------------------------------------

@pytest.mark.parametrize("name", ["steel", "aluminium"])
@pytest.mark.parametrize("group", ["m_a", "m_a_displaced", "M", "m_a_reduced"])
def test_masses_against_table2(name, group):
    """Printed to the gram: agreement within half a gram, except the two misprints below."""
    app = PRESETS[name]
    derived = getattr(app, group) / GRAM
    printed = TABLE2[name][group]
    misprints = {("steel", "m_a_reduced"), ("aluminium", "M")}
    if (name, group) in misprints:
        assert abs(derived - printed) > 0.5
    else:
        assert abs(derived - printed) <= 0.5


@pytest.mark.parametrize(("name", "group"), [("steel", "mu_ratio"), ("steel", "q"),
                                             ("aluminium", "q")])
def test_groups_against_table2(name, group):
    """Printed to two decimals: agreement within 0.005."""
    assert abs(getattr(PRESETS[name], group) - TABLE2[name][group]) <= 0.005


def test_table2_misprints_steel_reduced_mass_and_aluminium_total_mass():
    """Two printed masses contradict the tables' own definitions.

    m'_a = m_a - m''_a: 158 - 21 = 137 g, printed 134 g for steel (the aluminium
    entry 55 - 21 = 34 g is consistent). M = m_a + m_b + oil: 55 + 47 + 24 = 126 g,
    printed 127 g for aluminium (the steel entry 158 + 47 + 24 = 229 g is consistent).
    """
    assert STEEL.m_a_reduced / GRAM == pytest.approx(158 - 20.81, abs=0.01)
    assert ALUMINIUM.M / GRAM == pytest.approx(126.0, abs=1e-9)
    assert STEEL.M / GRAM == pytest.approx(229.0, abs=1e-9)


def test_aluminium_mu_erratum_4():
    """Printed mu_ = 3.11 for aluminium follows from neither M.

    With the printed M = 127 g, (127 + 47)/55 = 3.16; with Table 1's masses
    (M = 126 g) the preset gives 3.145. The printed q = 1.14 is consistent with
    3.11 and, to its two decimals, with 3.145 too (q is flat there), but not
    with 3.16 (q = 1.146 -> 1.15).
    """
    printed_mu, printed_q = TABLE2["aluminium"]["mu_ratio"], TABLE2["aluminium"]["q"]
    from_printed_m = (127 + 47) / 55
    assert round(from_printed_m, 2) == 3.16
    assert ALUMINIUM.mu_ratio == pytest.approx(173 / 55, rel=1e-12)
    for mu_ in (from_printed_m, ALUMINIUM.mu_ratio):
        assert abs(mu_ - printed_mu) > 0.005
    assert round(decay_exponent(printed_mu), 2) == printed_q
    assert round(decay_exponent(ALUMINIUM.mu_ratio), 2) == printed_q
    assert round(decay_exponent(from_printed_m), 2) != printed_q


def test_presets_hold_24_g_of_oil_with_about_4_g_at_the_ends():
    for app in (STEEL, ALUMINIUM):
        assert (app.m_f + app.m_f_ends) / GRAM == pytest.approx(24.0, rel=1e-12)
        assert 3.0 < app.m_f_ends / GRAM < 5.0  # "about 4 g", Table 2 caption


def test_preset_overrides_and_errors():
    app = preset("steel", nu=5e-4, alpha=math.radians(1.0))
    assert app.nu == 5e-4 and app.m_a == STEEL.m_a
    assert app.upsilon == pytest.approx(STEEL.upsilon * (2e-4 / 5e-4) ** 2, rel=1e-12)
    with pytest.raises(ValueError, match="preset must be one of"):
        preset("brass")
    with pytest.raises(ValueError, match="unknown apparatus field"):
        preset("steel", viscosity=1.0)
    with pytest.raises(ValueError, match="nu must be in"):
        preset("aluminium", nu=-1.0)


# -- distinguished-limit constructor -----------------------------------------------

@pytest.mark.parametrize(("s", "upsilon", "mu_ratio", "delta_over_a"), [
    (0.25, 1.0, 1.75, 0.05),
    (0.9, 0.01, 3.0, 0.4),
    (2.0, 5.0, 1.5, 0.01),
    (0.0, 1e3, 10.0, 0.2),
    (-0.5, 1e-3, 2.0, 0.1),
])
def test_from_groups_round_trip(s, upsilon, mu_ratio, delta_over_a):
    # 1e-12: a handful of roundings in the forward and inverse formulas
    # (delta = b - a cancels by a factor (1 + delta/a)/(delta/a) <= 101 here).
    app = Apparatus.from_groups(s, upsilon, mu_ratio, delta_over_a)
    assert app.s == pytest.approx(s, rel=1e-12, abs=1e-15)
    assert app.upsilon == pytest.approx(upsilon, rel=1e-12)
    assert app.mu_ratio == pytest.approx(mu_ratio, rel=1e-12)
    assert app.delta_over_a == pytest.approx(delta_over_a, rel=1e-12)
    # Distinguished limit: sin(alpha) ~ delta/a.
    assert abs(math.sin(app.alpha)) <= abs(s) * delta_over_a


def test_from_groups_free_ratios():
    app = Apparatus.from_groups(0.5, 1.0, 2.0, 0.1, a=0.02, length=0.3, rho=900.0,
                                density_ratio=3.0, g=9.81)
    assert (app.a, app.length, app.rho, app.g) == (0.02, 0.3, 900.0, 9.81)
    assert app.m_a / app.m_a_displaced == pytest.approx(3.0, rel=1e-14)
    assert app.m_f_ends == 0.0


def test_from_groups_refuses_mu_ratio_one():
    """mu_ = (M + m_b)/m_a = 1 + (2 m_b + m_f)/m_a > 1 for any real device."""
    with pytest.raises(ValueError, match=r"mu_ratio must be in \(1 \+ m_f/m_a, inf\)"):
        Apparatus.from_groups(0.25, 1.0, 1.0, 0.1)
    bound = 1.0 + ((1.1**2 - 1.0) / 7.85)
    with pytest.raises(ValueError, match="mu_ratio"):
        Apparatus.from_groups(0.25, 1.0, bound, 0.1)
    # Just above the bound a (light) outer cylinder exists.
    app = Apparatus.from_groups(0.25, 1.0, bound * (1 + 1e-9), 0.1)
    assert app.m_b > 0.0


@pytest.mark.parametrize(("kwargs", "words"), [
    (dict(s=0.25, upsilon=0.0, mu_ratio=2.0, delta_over_a=0.1), "upsilon must be in (0, inf)"),
    (dict(s=0.25, upsilon=1.0, mu_ratio=2.0, delta_over_a=-0.1),
     "delta_over_a must be in (0, inf)"),
    (dict(s=math.nan, upsilon=1.0, mu_ratio=2.0, delta_over_a=0.1), "s must be a finite number"),
    (dict(s=50.0, upsilon=1.0, mu_ratio=2.0, delta_over_a=0.4), "s must be in"),
    (dict(s=0.5, upsilon=1.0, mu_ratio=2.0, delta_over_a=0.1, density_ratio=1.0),
     "density_ratio must be in (1, inf)"),
])
def test_from_groups_invalid(kwargs, words):
    with pytest.raises(ValueError) as info:
        Apparatus.from_groups(**kwargs)
    assert words in str(info.value)
