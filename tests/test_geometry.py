"""Inputs are checked at the boundary; every message names the value and the allowed range."""

import math

import pytest

from lubrication import Annulus, Fluid, Motion

from apparatus import A, B


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"a": 0.01, "b": 0.008}, ["b must be greater than a"]),
        ({"a": 0.01, "b": 0.01}, ["b must be greater than a"]),
        ({"a": -0.01, "b": 0.02}, ["a must be in (0, inf)"]),
        ({"a": 0.0, "b": 0.02}, ["a must be in (0, inf)"]),
        ({"a": math.nan, "b": 0.02}, ["a must be a finite number"]),
        ({"a": 0.008, "b": math.inf}, ["b must be a finite number"]),
        ({"a": 0.008, "b": 0.01, "eps": 0.002}, ["eps must be in [0, 0.002)"]),
        ({"a": 0.008, "b": 0.01, "eps": -1e-4}, ["eps must be in"]),
        ({"a": 0.008, "b": 0.01, "length": 0.0}, ["length must be in (0, inf)"]),
        ({"a": "x", "b": 0.01}, ["a must be a finite number"]),
    ],
)
def test_annulus_rejects_bad_geometry(kwargs, words):
    with pytest.raises(ValueError) as err:
        Annulus(**kwargs)
    for word in words:
        assert word in str(err.value)


@pytest.mark.parametrize("kappa", [1.0, 1.5, -1e-12, math.nan, math.inf])
def test_kappa_outside_unit_interval_is_refused(kappa):
    with pytest.raises(ValueError, match=r"kappa must (be in \[0, 1\)|be a finite number)"):
        Annulus.from_kappa(0.008, 0.01, kappa)


@pytest.mark.parametrize(("nu", "rho"), [(0.0, 900.0), (-1e-4, 900.0), (1e-4, 0.0), (math.nan, 900.0)])
def test_fluid_rejects_non_positive_or_non_finite(nu, rho):
    with pytest.raises(ValueError, match=r"(nu|rho) must be"):
        Fluid(nu=nu, rho=rho)


def test_motion_rejects_non_finite():
    with pytest.raises(ValueError, match="omega_b must be a finite number"):
        Motion(omega_b=math.inf)


def test_near_contact_gap_keeps_its_precision():
    """1 - kappa given directly survives where eps/delta would round it away."""
    annulus = Annulus(a=A, b=B, one_minus_kappa=1e-17)
    assert annulus.one_minus_kappa == 1e-17
    assert annulus.kappa == 1.0 - 1e-17  # rounds to 1.0, which is why the field exists
    assert annulus.eps == pytest.approx(annulus.delta)


def test_relative_velocities():
    m = Motion(eps_dot=1.0, chi_dot=0.25, omega_a=2.0, omega_b=-1.0)
    assert (m.w_a, m.w_b) == (1.75, -1.25)
