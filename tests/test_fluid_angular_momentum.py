"""The angular momentum of the Stokes flow in the gap (lubrication.stokes.fluid_angular_momentum).

Three references independent of the finite elements: circular Couette flow in the concentric annulus,
V = A r + B/r, whose angular momentum 2 pi rho L int (A r^3 + B r) dr is m_f a^2 Omega_a / 2 for the inner
wall turning alone and m_f b^2 Omega_b / 2 for the outer; rigid turning of everything, whose only angular
momentum is that of the annulus' area; lubrication theory in a thin gap, where the flux around the annulus
is Q = (U_a + U_b) delta (1 - kappa^2)/(2 + kappa^2) (U the walls' speeds relative to the line of centres) and
the angular momentum rho L R^2 2 pi Q, R the mean radius, up to O(delta/a).
"""

import math

import numpy as np
import pytest

pytest.importorskip("skfem")

from lubrication.geometry import Annulus, Fluid, Motion  # noqa: E402
from lubrication.stokes import fluid_angular_momentum  # noqa: E402

FLUID = Fluid(rho=950.0, nu=5e-4)


@pytest.mark.parametrize(("omega_a", "omega_b"), [(3.0, 0.0), (0.0, -2.0)])
def test_the_concentric_annulus_carries_the_couette_flows_angular_momentum(omega_a, omega_b):
    """Q2 elements on the isoparametric mesh resolve A r + B/r to rounding here (measured 1e-9)."""
    annulus = Annulus(a=0.008, b=0.01125, eps=0.0, length=0.1)
    m_f = FLUID.rho * math.pi * (annulus.b**2 - annulus.a**2) * annulus.length
    couette = 0.5 * m_f * (annulus.a**2 * omega_a + annulus.b**2 * omega_b)
    assert fluid_angular_momentum(annulus, Motion(0.0, 0.0, omega_a, omega_b), FLUID) == pytest.approx(couette,
                                                                                                      rel=1e-6)


def test_a_fluid_turning_with_both_walls_carries_the_polar_moment_of_its_area():
    """Omega_a = Omega_b = chi': no flow relative to the line of centres; the annulus' polar moment about B by
    quadrature on a polar grid (the disc of radius b less the disc of radius a at distance eps)."""
    a, b, eps, rate = 0.008, 0.01125, 0.6 * 0.00325, 4.0
    r = np.linspace(0.0, b, 4001)
    theta = np.linspace(0.0, 2 * math.pi, 2001)
    rr, tt = np.meshgrid(r, theta, indexing="ij")
    outside_a = (rr * np.cos(tt) - eps) ** 2 + (rr * np.sin(tt)) ** 2 > a * a
    polar = np.trapezoid(np.trapezoid(np.where(outside_a, rr**3, 0.0), theta, axis=1), r)
    annulus = Annulus(a=a, b=b, eps=eps, length=0.1)
    got = fluid_angular_momentum(annulus, Motion(0.0, rate, rate, rate), FLUID)
    # the polar grid's staircase along the circle of radius a: about 1e-4 of the area's moment here
    assert got == pytest.approx(FLUID.rho * annulus.length * rate * polar, rel=3e-4)


@pytest.mark.parametrize("kappa", [0.5, 0.9])
@pytest.mark.parametrize(("omega_a", "omega_b"), [(1.0, 0.0), (0.0, 1.0)])
def test_in_a_thin_gap_the_flux_of_lubrication_theory_sets_it(kappa, omega_a, omega_b):
    """Each wall turning alone, against rho L R^2 2 pi Q: the difference is first order in delta/a (from
    delta/a = 0.01 to 0.003 it shrinks by their ratio, to 20%), and below (delta/a)/(1 - kappa), the thin-gap
    parameter of the pinch (measured 0.35 of it)."""
    a = 0.008
    errors = []
    for delta_over_a in (0.01, 0.003):
        delta = delta_over_a * a
        annulus = Annulus(a=a, b=a + delta, eps=kappa * delta, length=0.1)
        motion = Motion(0.0, 0.0, omega_a, omega_b)
        flux = (a * motion.w_a + annulus.b * motion.w_b) * delta * (1 - kappa**2) / (2 + kappa**2)
        thin = FLUID.rho * annulus.length * (a + 0.5 * delta) ** 2 * 2 * math.pi * flux
        errors.append(fluid_angular_momentum(annulus, motion, FLUID) / thin - 1.0)
        assert abs(errors[-1]) < delta_over_a / (1.0 - kappa)
    assert errors[0] / errors[1] == pytest.approx(0.01 / 0.003, rel=0.2)
