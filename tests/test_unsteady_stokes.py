"""At small Reynolds and Stokes numbers the unsteady solver's loads are the exact Stokes loads.

Each wall motion is held (velocities of 1e-13 m/s or rad/s times the radius: Re ~ 1e-12)
and stepped with fixed steps of 100 viscous times (BDF2 is L-stable: four steps reach the
steady state); the inner centre moves with the translations, and the exact loads
(:mod:`lubrication.stokes_exact`) are taken at its final position. Radial translation
gives f_eps, the rotations f_chi, T_a and T_b, the translation along e_chi (chi' = V/eps,
W_a = W_b = -V/eps) f_chi; T_b = -(T_a + eps f_chi) holds for quasi-steady Stokes flow.
T_a per W_b is about 1% of T_a per W_a at kappa = 0.99: it is compared against its row,
max |T_a per W|, as the finite-element benchmarks do.
"""

import cmath
import math

import numpy as np
import pytest

from lubrication.stokes_exact import stokes_exact_resistance
from lubrication.unsteady import AnnulusMap, PrescribedMotion, Resolution, default_resolution, run_prescribed

A, B, NU, RHO = 0.008, 0.01125, 2e-4, 1000.0
MU = RHO * NU
DELTA = B - A
T_VISC = DELTA**2 / NU
CHI = 0.4
V = 1e-13


def _loads(kappa, resolution, motion):
    e_eps = complex(math.sin(CHI), math.cos(CHI))
    e_chi = -1j * e_eps
    z0 = kappa * DELTA * e_eps
    u, omega_a, omega_b = {"radial": (-V * e_eps, 0.0, 0.0), "w_a": (0j, V / A, 0.0), "w_b": (0j, 0.0, V / B),
                           "chi": (V * e_chi, 0.0, 0.0)}[motion]
    # z_A(t) = z0 + u t, written as mean + amplitude sin(w t) with w t << 1 (1e-5 of it at the end)
    w = 1e-6
    spec = {"x_a": (z0.real, u.real / w, w, 0.0) if u else z0.real,
            "z_a": (z0.imag, u.imag / w, w, 0.0) if u else z0.imag, "omega_a": omega_a, "omega_b": omega_b}
    run = run_prescribed(A, B, NU, RHO, PrescribedMotion(**spec), 400.0 * T_VISC, resolution=resolution,
                         dt_fixed=100.0 * T_VISC)
    z = complex(run.x_a[-1], run.z_a[-1])
    f = complex(run.F_x[-1], run.F_z[-1])
    return z, (f * np.conj(e_eps)).real, (f * np.conj(e_chi)).real, run.T_a[-1], run.T_b[-1]


def _exact(z):
    eps = abs(z)
    omk = (DELTA - eps) / DELTA
    return stokes_exact_resistance(A, DELTA, MU, 1.0 - omk, omk), eps


@pytest.mark.parametrize("kappa", [0.3, 0.9, 0.99, pytest.param(0.999, marks=pytest.mark.slow),
                                   pytest.param(0.9999, marks=pytest.mark.slow)])
def test_steady_loads_are_the_exact_stokes_loads(kappa):
    geo = AnnulusMap(A, B, kappa * DELTA * 1j)
    resolution = default_resolution(geo)
    tol = 1e-4
    z, f_eps, _, _, _ = _loads(kappa, resolution, "radial")
    r, _ = _exact(z)
    assert abs(f_eps / (-V * r[0]) - 1.0) < tol  # moving inwards: the gap stays above the reach
    z, f_eps_a, f_chi_a, t_a_a, t_b_a = _loads(kappa, resolution, "w_a")
    r, eps = _exact(z)
    w_a = V / A
    assert abs(f_chi_a / (r[1] * w_a) - 1.0) < tol
    assert abs(t_a_a / (r[2] * w_a) - 1.0) < tol
    assert abs(t_b_a / (r[5] * w_a) - 1.0) < tol
    assert abs(f_eps_a) < tol * abs(f_chi_a)  # rotations give no radial force at Re -> 0
    z, _, f_chi_b, t_a_b, t_b_b = _loads(kappa, resolution, "w_b")
    r, eps = _exact(z)
    w_b = V / B
    assert abs(f_chi_b / (r[3] * w_b) - 1.0) < tol
    assert abs(t_a_b - r[4] * w_b) < tol * max(abs(r[2]), abs(r[4])) * w_b
    assert abs(t_b_b / (r[6] * w_b) - 1.0) < tol
    # quasi-steady Stokes: the fluid carries no torque
    assert abs(t_b_b + t_a_b + eps * f_chi_b) < tol * abs(t_b_b)
    z, _, f_chi_c, _, _ = _loads(kappa, resolution, "chi")
    r, eps = _exact(z)
    assert abs(f_chi_c / ((r[1] + r[3]) * (-V / eps)) - 1.0) < tol


def test_stokes_loads_converge_spectrally_in_theta():
    """At kappa = 0.9 the error of f_chi falls like exp(-beta K): each 16 more modes gain a factor
    exp(-16 beta) ~ 1e-3 or more until rounding."""
    errors = []
    for n_theta in (16, 32, 48):
        z, _, f_chi, _, _ = _loads(0.9, Resolution(n_theta, 16), "w_a")
        r, _ = _exact(z)
        errors.append(abs(f_chi / (r[1] * V / A) - 1.0))
    assert errors[1] < 1e-3 * errors[0] or errors[1] < 1e-8
    assert errors[2] < 1e-8  # the solve's rounding floor, 1e-9 to 1e-8 here
