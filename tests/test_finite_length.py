"""Finite-length factors: the torque identity, the closed-form limits, the table and its kernel.

The solver itself is tested in tests/test_reynolds2d.py; here the factors
built on it. The full table (33 x 33 nodes, about 10 s to build) is checked
against direct solves in a slow test; the default tests use a small table,
whose kernel must reproduce its own nodes exactly (interpolation) and the
closed forms on its edges.
"""

import math

import numpy as np
import pytest

from lubrication import Annulus, Motion, closed_form_forces
from lubrication import finite_length as fl

from apparatus import A, B, OIL



@pytest.mark.parametrize("kappa", [0.3, 0.9, 0.99])
def test_torque_factors_follow_from_the_force_factors(kappa):
    """Thin gap: T_a = Couette - (eps/2) f_chi at any length, so the torque factors follow from F_chi."""
    got = fl.finite_length_factors(kappa, fl.APPARATUS_LENGTH_OVER_A, n=64, n_axial=32, extrapolate=False)
    want = fl.thin_gap_factors(kappa, got["f_eps_per_eps_dot"], got["f_chi_per_w_a"])
    for name in fl.FACTOR_NAMES:
        assert got[name] == pytest.approx(want[name], rel=1e-10), name


def test_factors_do_not_depend_on_the_gap_width_for_the_thin_gap():
    thin = fl.finite_length_factors(0.7, 6.0, n=32, n_axial=16, delta_over_a=0.01, extrapolate=False)
    wide = fl.finite_length_factors(0.7, 6.0, n=32, n_axial=16, delta_over_a=1.0, extrapolate=False)
    for name in fl.FACTOR_NAMES:
        assert thin[name] == pytest.approx(wide[name], rel=1e-12), name


def test_eccentric_gap_tends_to_the_thin_gap():
    """The exact gap differs from the thin one by O(delta/a): halving delta/a halves the difference."""
    diffs = []
    for delta_over_a in (0.02, 0.01):
        thin = fl.finite_length_factors(0.6, 6.0, n=64, n_axial=32, delta_over_a=delta_over_a)
        exact = fl.finite_length_factors(0.6, 6.0, n=64, n_axial=32, delta_over_a=delta_over_a,
                                         profile="eccentric")
        diffs.append(abs(exact["f_chi_per_w_a"] - thin["f_chi_per_w_a"]))
    assert diffs[0] / diffs[1] == pytest.approx(2.0, rel=0.05)


@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.9])
def test_short_bearing_factors_are_the_closed_forms_ratio(kappa):
    """The factor formulas against the short-bearing forces divided by (2.5)-(2.7)."""
    length_over_a = 0.3
    annulus = Annulus.from_kappa(A, B, kappa, length_over_a * A)
    factors = fl.short_bearing_factors(kappa, length_over_a)
    for name, motion, index in (("f_eps_per_eps_dot", Motion(eps_dot=1.0), 0),
                                ("f_chi_per_w_a", Motion(omega_a=1.0), 1), ("t_a_per_w_a", Motion(omega_a=1.0), 2),
                                ("f_chi_per_w_b", Motion(omega_b=1.0), 1), ("t_a_per_w_b", Motion(omega_b=1.0), 2)):
        short = fl.short_bearing_forces(annulus, motion, OIL).as_tuple()[index]
        long_ = closed_form_forces(annulus, motion, OIL).as_tuple()[index]
        if long_ == 0.0:
            continue
        assert factors[name] == pytest.approx(short / long_, rel=1e-12), name


@pytest.mark.parametrize("kappa", [0.3, 0.9])
def test_short_bearing_torque_obeys_the_thin_gap_identity(kappa):
    """Ocvirk's torque: its Poiseuille part is -(eps/2) f_chi, its Couette part mu a^3 L (W_b - W_a) oint 1/h."""
    annulus = Annulus.from_kappa(A, B, kappa, 0.3 * A)
    motion = Motion(omega_a=1.3, omega_b=0.4)
    f = fl.short_bearing_forces(annulus, motion, OIL)
    zeta = math.sqrt(1 - kappa**2)
    couette = OIL.mu * A**3 * annulus.length * (motion.w_b - motion.w_a) * 2 * math.pi / (annulus.delta * zeta)
    assert f.T_a - couette == pytest.approx(-0.5 * annulus.eps * f.f_chi, rel=1e-13)


def test_small_eccentricity_factor_series_and_limits():
    for length_over_a in (1e-5, 0.0199, 0.0201):  # both sides of the series branch at l/2 = 1e-2
        x = 0.5 * length_over_a
        series = x * x / 3 - 2 * x**4 / 15 + 17 * x**6 / 315
        assert fl.small_eccentricity_factor(length_over_a) == pytest.approx(series, rel=1e-13)
    assert fl.small_eccentricity_factor(1e4) == pytest.approx(1 - 2e-4, rel=1e-14)


@pytest.fixture(scope="module")
def small_table():
    nodes = 9
    return fl._build_table(nodes, nodes, fl.ZETA_MIN, fl.X0), nodes


def _node_values(nodes):
    zeta = np.exp(0.5 * math.log(fl.ZETA_MIN) * (1 - np.cos(np.pi * np.arange(nodes) / (nodes - 1))))
    s = 0.5 * (1 + np.cos(np.pi * np.arange(nodes) / (nodes - 1)))
    return zeta, s


def _kernel_at_node(table, zeta, s):
    length_over_a = fl.X0 * (1 - s) / s * zeta
    kappa = math.sqrt((1 - zeta) * (1 + zeta))
    return fl.finite_length_factor_kernel(kappa, zeta**2 / (1 + kappa), length_over_a, *table.args), length_over_a


def test_kernel_interpolates_the_table_nodes(small_table):
    """At a node the kernel must return the solver's factors there (the table's interpolation property)."""
    table, nodes = small_table
    zeta, s = _node_values(nodes)
    for i, j in ((1, 2), (4, 4), (7, 6), (nodes - 1, 3)):
        got, length_over_a = _kernel_at_node(table, zeta[i], s[j])
        want = fl._thin_factor_pair(zeta[i], length_over_a)
        assert got[0] == pytest.approx(want[0], rel=1e-11)
        assert got[1] == pytest.approx(want[1], rel=1e-11)
        kappa = math.sqrt((1 - zeta[i]) * (1 + zeta[i]))
        assert got[2:] == pytest.approx(tuple(fl.thin_gap_factors(kappa, *want).values())[2:], rel=1e-9)


def test_kernel_at_zero_eccentricity_is_the_closed_form(small_table):
    """The zeta = 1 edge holds 1 - tanh(l/2)/(l/2) at every node, and no Poiseuille torque."""
    table, nodes = small_table
    _, s = _node_values(nodes)
    for j in range(1, nodes - 1):
        got, length_over_a = _kernel_at_node(table, 1.0, s[j])
        exact = fl.small_eccentricity_factor(length_over_a)
        assert got[0] == pytest.approx(exact, rel=1e-12)
        assert got[1] == pytest.approx(exact, rel=1e-12)
        assert got[2] == 1.0 and got[4] == 1.0


@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.999])
def test_kernel_limits_in_length(small_table, kappa):
    table, _ = small_table
    omk = 1.0 - kappa
    assert fl.finite_length_factor_kernel(kappa, omk, math.inf, *table.args) == pytest.approx((1.0,) * 5, rel=1e-14)
    short = fl.finite_length_factor_kernel(kappa, omk, 0.0, *table.args)
    limit = fl.short_bearing_factors(kappa, 1e-300)  # the Couette part alone
    assert short == pytest.approx(tuple(limit.values()), abs=1e-14, rel=1e-12)


def test_kernel_at_the_smallest_gap_is_finite(small_table):
    """1 - kappa = 1e-150: F rounds to 1, the W_b torque factor is large and finite."""
    table, _ = small_table
    got = fl.finite_length_factor_kernel(1.0, 1e-150, fl.APPARATUS_LENGTH_OVER_A, *table.args)
    assert got[:4] == pytest.approx((1.0,) * 4, rel=1e-12)
    assert 1e70 < got[4] < 1e80  # 1 + O(1/zeta), zeta = 1.4e-75


@pytest.mark.slow
def test_stored_table_against_direct_solves(rng):
    """The 33 x 33 table: measured largest error 2.9e-5 over 150 random (zeta, L/a), at zeta = 0.012 and
    L/a = 0.94, and 9.3e-6 for zeta > 0.02, which is checked here against 2e-5."""
    table = fl.factor_table()
    for coef in (table.coef_eps, table.coef_chi):
        assert np.abs(coef[-1]).max() < 1e-6  # the log(zeta) direction
    worst = 0.0
    for _ in range(20):
        zeta = math.exp(rng.uniform(math.log(0.02), 0.0))
        length_over_a = math.exp(rng.uniform(math.log(0.3), math.log(200.0)))
        kappa = math.sqrt((1 - zeta) * (1 + zeta))
        got = fl.finite_length_factor_kernel(kappa, zeta**2 / (1 + kappa), length_over_a, *table.args)
        want = fl._thin_factor_pair(zeta, length_over_a)
        worst = max(worst, abs(got[0] - want[0]), abs(got[1] - want[1]))
    assert worst < 2e-5


@pytest.mark.slow
@pytest.mark.parametrize("zeta", [5e-3, 2e-3])
def test_stored_table_below_its_range(zeta):
    """Continued linearly in log(zeta): measured within 2e-6 of direct solves at the apparatus' length."""
    table = fl.factor_table()
    kappa = math.sqrt((1 - zeta) * (1 + zeta))
    got = fl.finite_length_factor_kernel(kappa, zeta**2 / (1 + kappa), fl.APPARATUS_LENGTH_OVER_A, *table.args)
    want = fl._thin_factor_pair(zeta, fl.APPARATUS_LENGTH_OVER_A)
    assert abs(got[0] - want[0]) < 1e-5 and abs(got[1] - want[1]) < 1e-5


@pytest.mark.parametrize(("args", "match"), [
    ((1.0, 5.0), "kappa must be"),
    ((-0.1, 5.0), "kappa must be"),
    ((0.5, 0.0), "length_over_a must be"),
    ((0.5, math.nan), "length_over_a must be"),
])
def test_bad_input(args, match):
    with pytest.raises(ValueError, match=match):
        fl.finite_length_factors(*args)
