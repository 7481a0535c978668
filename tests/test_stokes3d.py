"""The 3-D Stokes solver of the finite annulus: the 2-D flow it must contain, its mesh, and the thin-gap limit.

With a mirror plane at the gap end the flow is the 2-D one, which the Q2 elements
represent exactly along z: the 3-D coefficients must be L times the 2-D solver's
on the same cross-section, to rounding. With open ends, as delta/a -> 0 the 3-D
factors must tend to the thin-gap Reynolds factors, the difference falling like
delta/a (slow).
"""

import numpy as np
import pytest

pytest.importorskip("skfem")

from lubrication.finite_length import finite_length_factors
from lubrication.stokes import stokes_resistance
from lubrication.stokes3d import extruded_mesh, stokes3d_resistance

from apparatus import A, B, L

NAMES = ("f_eps_per_eps_dot", "f_chi_per_w_a", "t_a_per_w_a", "f_chi_per_w_b", "t_a_per_w_b")


def test_mesh_nodes_lie_on_the_circles():
    eps = 0.5 * (B - A)
    z = np.array([0.0, 0.3, 1.0])
    mesh, s_nodes = extruded_mesh(A, B, eps, 16, 2, z)
    x, y, zz = mesh.doflocs
    inner, outer = s_nodes == 0.0, s_nodes == 1.0
    assert np.allclose(np.hypot(x[inner] - eps, y[inner]), A, rtol=1e-14, atol=0)
    assert np.allclose(np.hypot(x[outer], y[outer]), B, rtol=1e-14, atol=0)
    assert set(np.round(zz, 12)) == {0.0, 0.15, 0.3, 0.65, 1.0}  # vertices and mid-edge planes


@pytest.mark.parametrize("kappa", [0.0, 0.6])
def test_sealed_ends_give_the_two_dimensional_flow(kappa):
    r3 = stokes3d_resistance(A, B, kappa, L, n_around=16, n_across=1, n_axial=2, ends="sealed")
    r2 = stokes_resistance(A, B, kappa, n_around=16, n_across=1)
    for name in NAMES:
        two_d = L * getattr(r2, name)
        if two_d == 0.0 or abs(two_d) < 1e-12 * abs(L * r2.t_a_per_w_a):  # f_chi vanishes at kappa = 0
            continue
        assert getattr(r3, name) == pytest.approx(two_d, rel=1e-11), name


def test_open_ends_reduce_the_forces():
    """The ends relieve the pressure: every force coefficient falls below L times the 2-D one."""
    r3 = stokes3d_resistance(A, B, 0.6, L, n_around=16, n_across=1, n_axial=4)
    r2 = stokes_resistance(A, B, 0.6, n_around=16, n_across=1)
    for name in ("f_eps_per_eps_dot", "f_chi_per_w_a", "f_chi_per_w_b"):
        assert 0.8 < getattr(r3, name) / (L * getattr(r2, name)) < 0.95, name


@pytest.mark.slow
def test_thin_gap_limit_of_the_open_annulus():
    """3-D factor - thin Reynolds factor ~ c delta/a: the difference halves with delta/a (within 15 per cent).

    L/a = 4, kappa = 0.6; the 3-D factor is taken against the 2-D solve on the
    same cross-section, so the cross-section's error cancels.
    """
    kappa, length_over_a = 0.6, 4.0
    thin = finite_length_factors(kappa, length_over_a)
    diffs = []
    for delta_over_a in (0.1, 0.05):
        a, b = 1.0, 1.0 + delta_over_a
        r3 = stokes3d_resistance(a, b, kappa, length_over_a, n_around=48, n_across=2, n_axial=12)
        r2 = stokes_resistance(a, b, kappa, n_around=48, n_across=2)
        diffs.append(np.array([getattr(r3, n) / (length_over_a * getattr(r2, n)) - thin[n] for n in NAMES[:2]]))
    ratio = np.abs(diffs[0]) / np.abs(diffs[1])
    assert np.all(np.abs(ratio - 2.0) < 0.3), ratio


def test_bad_input():
    with pytest.raises(ValueError, match="ends must be"):
        stokes3d_resistance(A, B, 0.5, L, ends="closed")
    with pytest.raises(ValueError, match="n_axial must be"):
        stokes3d_resistance(A, B, 0.5, L, n_axial=0)
