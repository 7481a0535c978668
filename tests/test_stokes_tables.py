"""Tabulated Stokes resistance ratios: accuracy between nodes, limits, cache, jitted lookup.

The accuracy bounds are measured (see lubrication/stokes_tables.py and the
report): with the default 16 Chebyshev-Lobatto nodes in zeta the interpolation
error is below 1e-7 of each coefficient for delta/a <= 0.406, under the
finite-element error (~1e-6) of the nodes themselves.
"""

import math
import time

import numpy as np
import pytest

pytest.importorskip("skfem")

from lubrication.closed_form import lubrication_forces  # noqa: E402
from lubrication.forces import Resistance  # noqa: E402
from lubrication.geometry import Annulus, Fluid, Motion  # noqa: E402
from lubrication.stokes import _INSTALL_HINT, stokes_resistance  # noqa: E402
from lubrication.stokes_tables import (  # noqa: E402
    KAPPA_MAX,
    N_NODES,
    RATIO_NAMES,
    TABLE_VERSION,
    StokesTable,
    cache_folder,
    contact_limits,
    table_forces,
    table_ratios,
)

THIN = 0.03  # cheap default-mesh solves (0.2 s): a full default table in about 3 s


@pytest.fixture(scope="module")
def thin_table(tmp_path_factory):
    return StokesTable.load(THIN, folder=tmp_path_factory.mktemp("tables"))


def between_nodes(table, count=3):
    """kappa halfway (in zeta) between neighbouring nodes, where interpolation is weakest."""
    z = table.zeta_nodes
    mid = 0.5 * (z[1:] + z[:-1])
    pick = mid[np.linspace(0, mid.size - 1, count).astype(int)]
    return np.sqrt((1.0 - pick) * (1.0 + pick))


def test_names_match_resistance():
    assert RATIO_NAMES == Resistance.NAMES


def test_cache_folder_follows_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("SNAIL_CACHE", str(tmp_path))
    assert cache_folder() == tmp_path
    monkeypatch.delenv("SNAIL_CACHE")
    assert cache_folder().name == "snail-cylinder"


def test_table_reproduces_fresh_solves_between_nodes(thin_table):
    """Measured 3e-8 at delta/a = 0.01, 1e-7 at 0.406, 2.5e-7 at 1 (T_a per W_a, the least smooth)."""
    err = thin_table.interpolation_error(between_nodes(thin_table))
    assert err.max() < 1e-6


def test_ratios_tend_to_one_in_the_thin_gap(thin_table):
    """ratio = 1 + c delta/a with c between 0.5 and 2.5 (validation/corrections.py)."""
    r = thin_table.ratios(np.linspace(0.0, 0.999, 11))
    assert np.all(np.abs(r - 1.0) < 3.0 * THIN)
    assert np.all(r > 1.0)


def test_jitted_lookup_agrees_with_numpy_twin(thin_table):
    kappas = np.concatenate([np.linspace(0.0, 0.99, 23), [0.995, 0.9999, 1.0 - 1e-9]])
    twin = thin_table.ratios(kappas)
    for i, kappa in enumerate(kappas):
        zeta = math.sqrt((1.0 - kappa) * (1.0 + kappa))
        jitted = table_ratios(*thin_table.arrays, zeta)
        np.testing.assert_allclose(jitted, twin[:, i], rtol=1e-13)


def test_forces_are_ratios_times_closed_forms(thin_table):
    a, mu, length = 0.008, 0.19, 0.1035
    annulus = Annulus.from_kappa(a, a * (1.0 + THIN), 0.7, length)
    fluid = Fluid(nu=mu / 960.0, rho=960.0)
    r = dict(zip(RATIO_NAMES, thin_table.ratios(0.7)))
    args = (a, annulus.delta, fluid.mu, length, annulus.kappa, annulus.one_minus_kappa)
    f_eps = lubrication_forces(*args, 1.0, 0.0, 0.0)[0]
    _, f_chi_a, t_a_a = lubrication_forces(*args, 0.0, 1.0, 0.0)
    _, f_chi_b, t_a_b = lubrication_forces(*args, 0.0, 0.0, 1.0)
    motion = Motion(eps_dot=2e-4, chi_dot=0.3, omega_a=-1.1, omega_b=2.0)
    got = thin_table.forces(annulus, motion, fluid)
    expect = (r["f_eps_per_eps_dot"] * f_eps * motion.eps_dot,
              r["f_chi_per_w_a"] * f_chi_a * motion.w_a + r["f_chi_per_w_b"] * f_chi_b * motion.w_b,
              r["t_a_per_w_a"] * t_a_a * motion.w_a + r["t_a_per_w_b"] * t_a_b * motion.w_b)
    np.testing.assert_allclose(got.as_tuple(), expect, rtol=1e-12)
    assert got.model == "stokes-table"
    with pytest.raises(ValueError, match="delta/a"):
        thin_table.forces(Annulus.from_kappa(a, 2.0 * a, 0.5, length), motion, fluid)


def test_beyond_kappa_max_blends_to_the_contact_limits(thin_table):
    """Below zeta_min: linear in zeta^2 from the last node to (b/a)^p (T_a per W_b held)."""
    b_over_a = 1.0 + THIN
    expect = [b_over_a**1.5, b_over_a**0.5, b_over_a**0.5, b_over_a**2.5, thin_table.node_ratios[4, 0]]
    np.testing.assert_allclose(thin_table.contact, expect, rtol=1e-15)
    at_contact = table_ratios(*thin_table.arrays, 0.0)
    np.testing.assert_allclose(at_contact, expect, rtol=1e-15)
    edge = thin_table.ratios(KAPPA_MAX)
    np.testing.assert_allclose(edge, thin_table.node_ratios[:, 0], rtol=1e-13)
    # halfway in zeta^2 between the last node and contact
    zeta_half = thin_table.zeta_nodes[0] / math.sqrt(2.0)
    half = thin_table.ratios(math.sqrt(1.0 - zeta_half**2))
    np.testing.assert_allclose(half, 0.5 * (edge + np.array(expect)), rtol=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("delta_over_a", [0.1, 0.40625])
def test_beyond_kappa_max_against_finer_solves(delta_over_a, tmp_path):
    """kappa = 0.999 with a twice finer mesh: the blended ratios agree to 1e-4 of the row.

    Measured at delta/a = 0.406: at most 3e-6 (T_a per W_a) for the four blended
    ratios; the held T_a per W_b is 4e-4 off itself, 3e-7 of R_t_a, its scale here.
    """
    table = StokesTable.load(delta_over_a, folder=tmp_path)
    kappa = 0.999
    n_around, n_across = table.settings["n_around"], table.settings["n_across"]
    fine = stokes_resistance(1.0, 1.0 + delta_over_a, kappa, n_around=2 * n_around, n_across=2 * n_across)
    found = fine.lubrication_ratios()
    got = table.ratios(kappa)
    lub = fine.lubrication()
    for k, name in enumerate(RATIO_NAMES):
        scale = abs(lub["t_a_per_w_a"] / lub[name]) if name == "t_a_per_w_b" else 1.0
        assert abs(got[k] - found[name]) / found[name] / scale < 1e-4, name


@pytest.mark.slow
@pytest.mark.parametrize("delta_over_a", [0.40625, 1.0])
def test_default_table_accuracy_on_thick_gaps(delta_over_a, tmp_path):
    table = StokesTable.load(delta_over_a, folder=tmp_path)
    assert table.interpolation_error(between_nodes(table, 5)).max() < 1e-6


def test_stale_or_foreign_cache_files_are_rebuilt(tmp_path):
    settings = {"n_nodes": 3, "n_around": 64, "n_across": 2}  # coarse and quick: the cache, not accuracy
    table = StokesTable.load(THIN, folder=tmp_path, **settings)
    path = StokesTable.path(THIN, tmp_path)
    assert path.is_file() and table.build_time_s > 0.0
    again = StokesTable.load(THIN, folder=tmp_path, **settings)
    assert again.build_time_s == 0.0  # read back, not rebuilt
    np.testing.assert_array_equal(again.node_ratios, table.node_ratios)
    assert again.settings == table.settings

    # another format version: rebuilt
    with np.load(path) as data:
        stored = dict(data)
    stored["version"] = np.array(TABLE_VERSION - 1)
    np.savez(path, **stored)
    assert StokesTable.load(THIN, folder=tmp_path, **settings).build_time_s > 0.0
    # other settings asked for: rebuilt and overwritten
    rebuilt = StokesTable.load(THIN, folder=tmp_path, **{**settings, "n_nodes": 4})
    assert rebuilt.zeta_nodes.size == 4
    assert StokesTable.read(path).zeta_nodes.size == 4
    # a file that needs pickle to read is never unpickled: rebuilt
    np.savez(path, **{**stored, "node_ratios": np.array([{"evil": 1}], dtype=object)})
    assert StokesTable.read(path) is None
    assert StokesTable.load(THIN, folder=tmp_path, **settings).build_time_s > 0.0
    # not an npz at all
    path.write_bytes(b"not a table")
    assert StokesTable.load(THIN, folder=tmp_path, **settings).build_time_s > 0.0


def test_loading_never_allows_pickle(tmp_path, monkeypatch):
    table = StokesTable.build(THIN, n_nodes=3, n_around=64, n_across=2)
    path = table.save(tmp_path / "t.npz")
    seen = []
    original = np.load

    def spy(*args, **kwargs):
        seen.append(kwargs.get("allow_pickle"))
        return original(*args, **kwargs)

    monkeypatch.setattr(np, "load", spy)
    assert StokesTable.read(path) is not None
    assert seen == [False]


def test_input_checks():
    with pytest.raises(ValueError, match="delta_over_a"):
        StokesTable.build(-0.1)
    with pytest.raises(ValueError, match="n_nodes"):
        StokesTable.build(0.1, n_nodes=1)
    with pytest.raises(ValueError, match="kappa_max"):
        StokesTable.build(0.1, kappa_max=1.0)


def test_missing_fem_message_names_the_extra(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "skfem", None)  # import skfem now raises ImportError
    with pytest.raises(ImportError, match=r'pip install "snail-cylinder\[fem\]"'):
        StokesTable.build(0.0123, n_nodes=2, n_around=64, n_across=2)
    assert 'pip install "snail-cylinder[fem]"' == _INSTALL_HINT


def test_jitted_lookup_cost(thin_table):
    """Interpolation plus closed forms in jitted code: well under a microsecond per lookup."""
    from numba import njit

    @njit(cache=False)
    def many(zeta_nodes, node_ratios, contact, kappas):
        total = 0.0
        for kappa in kappas:
            f = table_forces(zeta_nodes, node_ratios, contact, 0.008, 0.003, 0.19, 0.1,
                             kappa, 1.0 - kappa, 1e-4, 0.5, 1.0)
            total += f[0] + f[1] + f[2]
        return total

    kappas = np.linspace(0.0, 0.995, 200_000)
    many(*thin_table.arrays, kappas[:10])
    start = time.perf_counter()
    many(*thin_table.arrays, kappas)
    per_call = (time.perf_counter() - start) / kappas.size
    assert per_call < 1e-6


def test_contact_limits_shape():
    limits = contact_limits(0.5, np.full(5, 7.0))
    np.testing.assert_allclose(limits, [1.5**1.5, 1.5**0.5, 1.5**0.5, 1.5**2.5, 7.0])
    assert N_NODES >= 2



def test_gaps_equal_to_rounding_share_one_table():
    """The apparatus' (b - a)/a = 0.40624999999999994 is keyed, and so cached, as 0.40625; 0.41 is not."""
    from lubrication.stokes_tables import _settings

    def key(delta_over_a):
        return _settings(delta_over_a, 0.99, 16, None, None, 0.5)["delta_over_a"]

    assert key((0.01125 - 0.008) / 0.008) == key(0.40625) == 0.40625
    assert key(0.41) != key(0.40625)
