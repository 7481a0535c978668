"""At small Reynolds and Stokes numbers the unsteady solver's loads are the exact Stokes loads.

Each wall motion is held (velocities of 1e-13 m/s or rad/s times the radius: Re ~ 1e-12)
and stepped with fixed steps of 100 viscous times (BDF2 is L-stable: four steps reach the
steady state); the inner centre moves with the translations, and the exact loads
(:mod:`lubrication.stokes_exact`) are taken at its final position. Radial translation
gives f_eps, the rotations f_chi, T_a and T_b, the translation along e_chi (chi' = V/eps,
W_a = W_b = -V/eps) f_chi; T_b = -(T_a + eps f_chi) holds for quasi-steady Stokes flow.
T_a per W_b is about 1% of T_a per W_a at kappa = 0.99: it is compared against its row,
max |T_a per W|, as the finite-element benchmarks do.

The solver's unknowns are H psi and omega (H = |1 + conj(p) w|^2/|w|, mapping.py): for these
flows trigonometric polynomials of degree 1 and 2 in the map's angle at every eccentricity, so
that a fixed grid of 16 x 12 points holds them from kappa = 0.3 to 1 - kappa = 1e-5.
"""

import math

import numpy as np
import pytest

from lubrication.stokes_exact import stokes_exact_resistance
from lubrication.unsteady import (
    PrescribedMotion,
    Resolution,
    StepControl,
    UnsteadySolver,
    prescribed_wall,
    run_prescribed,
)

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


@pytest.mark.parametrize("one_minus_kappa", [0.7, 0.1, 0.01, 1e-3, 1e-4, 1e-5])
def test_steady_loads_are_the_exact_stokes_loads(one_minus_kappa):
    """16 x 12 points at every gap, each load within 1e-6 of the exact one. Measured: 1e-9 or less up to
    1 - kappa = 1e-4; at 1e-5, 2e-8 for T_b per W_a (a torque ~ tau^2 smaller than T_a per W_a, the
    difference of larger terms) and 2e-9 or less for the others; 1e-5 of T_b per W_a at 1e-7."""
    kappa = 1.0 - one_minus_kappa
    resolution = Resolution(16, 12)
    tol = 1e-6
    z, f_eps, _, _, _ = _loads(kappa, resolution, "radial")
    r, _ = _exact(z)
    assert abs(f_eps / (-V * r[0]) - 1.0) < tol
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


@pytest.mark.parametrize("motion", ["w_a", "w_b", "radial"])
def test_exact_stokes_flow_has_two_modes_near_contact(motion):
    """At 1 - kappa = 1e-4 (beta = 0.012) the steady H psi has modes |k| <= 1 and omega |k| <= 2 only:
    the rest is rounding (below 1e-10 of the largest coefficient; measured 1e-13). psi itself still
    has 8% of its largest coefficient at |k| = 15 (its coefficients fall like exp(-beta |k|))."""
    kappa = 1.0 - 1e-4
    z0 = kappa * DELTA * 1j
    u, omega_a, omega_b = {"radial": (-V * 1j, 0.0, 0.0), "w_a": (0j, V / A, 0.0), "w_b": (0j, 0.0, V / B)}[motion]
    solver = UnsteadySolver(A, B, NU, RHO, Resolution(32, 12), control=StepControl(adaptive=False))
    q = (u.real, u.imag, omega_a, omega_b)
    solver.start(z0, q)
    for n in range(1, 5):
        assert solver.step(100.0 * T_VISC, prescribed_wall(q), z0 + u * 100.0 * T_VISC * n).accepted
    st = solver.state
    kk = solver.grid.K
    k = np.abs(solver.grid.k)
    big_psi = np.max(np.abs(st.h_psi), axis=1)
    omega = np.max(np.abs(st.omega), axis=1)
    assert np.max(big_psi[k >= 2]) < 1e-10 * np.max(big_psi)
    assert np.max(omega[k >= 3]) < 1e-10 * np.max(omega)
    assert omega[kk + 2] > 1e-3 * np.max(omega)  # degree 2, not less
    # psi = (H psi)/H on the grid: slowly decaying coefficients
    psi = solver.grid.to_spectral(solver.fields()["stream_function"])
    psi_k = np.max(np.abs(psi), axis=1)
    assert psi_k[kk + 15] > 1e-2 * np.max(psi_k)
