"""The unsteady solver against exact concentric solutions (tests/unsteady_exact.py).

* Couette spin-up (Bessel J1, Y1 series): the torques on both walls, with fixed steps
  (BDF2's second order, fitted) and with the adaptive steps (the stated tolerance), the outer
  or the inner wall started.
* The inner cylinder oscillating along x about the centre, small amplitude: the
  periodic force against the unsteady Stokes solution (I1, K1); the reference's own
  limits, the steady drag and the inviscid added mass, are checked first.
"""

import math

import numpy as np
import pytest
from unsteady_exact import (
    couette_spinup_torques,
    inviscid_added_mass,
    oscillating_cylinder_force,
    steady_drag,
)

from lubrication.stokes_exact import stokes_exact_resistance
from lubrication.unsteady import PrescribedMotion, Resolution, StepControl, run_prescribed

A, B, NU, RHO = 0.008, 0.01125, 2e-4, 1000.0
MU = RHO * NU
DELTA = B - A
T_VISC = DELTA**2 / NU  # viscous time of the gap
OMEGA_B = 1.0
T_LIMIT = 4.0 * math.pi * MU * OMEGA_B * A * A * B * B / (B * B - A * A)


def test_couette_limit_and_signs_agree_with_the_exact_stokes_model():
    """The spin-up's limit 4 pi mu Omega_b a^2 b^2/(b^2 - a^2) > 0 (clockwise: the fluid drags the held
    inner wall the way the outer one turns) is lubrication.stokes_exact's T_a per W_b at kappa = 0,
    and T_b its T_b per W_b."""
    r = stokes_exact_resistance(A, DELTA, MU, 0.0, 1.0)
    assert T_LIMIT > 0
    assert abs(r[4] * OMEGA_B / T_LIMIT - 1.0) < 1e-14
    assert abs(r[6] * OMEGA_B / T_LIMIT + 1.0) < 1e-14
    t_a, t_b = couette_spinup_torques(A, B, NU, RHO, OMEGA_B, [50.0 * T_VISC])
    assert abs(t_a[0] / T_LIMIT - 1.0) < 1e-14 and abs(t_b[0] / T_LIMIT + 1.0) < 1e-14


def test_couette_spin_up_is_second_order_in_time():
    """Fixed steps T/20 .. T/160 to T = 0.2 delta^2/nu: the torque's error falls as dt^2 (slope fitted)."""
    t_end = 0.2 * T_VISC
    t_a, _ = couette_spinup_torques(A, B, NU, RHO, OMEGA_B, [t_end])
    steps = np.array([20, 40, 80, 160])
    errors = []
    for n in steps:
        run = run_prescribed(A, B, NU, RHO, PrescribedMotion(omega_b=OMEGA_B), t_end, resolution=Resolution(8, 24),
                             dt_fixed=t_end / n)
        errors.append(abs(run.T_a[-1] / t_a[0] - 1.0))
    order = -np.polyfit(np.log(steps), np.log(errors), 1)[0]
    # measured 2.06 (ratios 4.18, 4.06, 4.02); the space error (n_r = 24) is below 1e-9 of it
    assert abs(order - 2.0) < 0.1
    assert errors[-1] < 5e-5


@pytest.mark.parametrize(("omega_a", "omega_b"), [(0.0, OMEGA_B), (OMEGA_B, 0.0)])
def test_adaptive_couette_spin_up_meets_its_tolerance(omega_a, omega_b):
    """rtol = 1e-5 of local error per step (on the interior vorticity): the torques from 0.1 to 2 viscous
    times within 30 rtol of the limit torque of the series. Measured: T_a 15 rtol, T_b 26 rtol (the global
    error of the walls' vorticity, which the estimate leaves out as algebraic, and of the uncontrolled start).

    The inner wall started impulsively checks the first step's circulation condition: the fluid's
    acceleration at the wall is measured from the fluid's velocity there (at rest), not from the
    wall's (measured 9e-5 and 1.5e-4 of the limit; with the wall's: 0.8 and 1.35)."""
    rtol = 1e-5
    run = run_prescribed(A, B, NU, RHO, PrescribedMotion(omega_a=omega_a, omega_b=omega_b), 2.0 * T_VISC,
                         resolution=Resolution(8, 24), control=StepControl(rtol=rtol))
    keep = run.t >= 0.1 * T_VISC
    t_a, t_b = couette_spinup_torques(A, B, NU, RHO, omega_b, run.t[keep], omega_a=omega_a)
    err_a = np.abs(run.T_a[keep] - t_a) / T_LIMIT
    err_b = np.abs(run.T_b[keep] - t_b) / T_LIMIT
    assert err_a.max() < 30 * rtol and err_b.max() < 30 * rtol
    assert run.steps < 400


def test_oscillation_reference_has_its_limits():
    """The I1, K1 solution tends to the steady drag at small frequency and to the added mass at large."""
    slow = oscillating_cylinder_force(A, B, NU, RHO, 1e-6 / T_VISC)
    assert abs(slow.real / steady_drag(A, B, MU) - 1.0) < 1e-8
    # the Stokes layers of thickness (nu/w)^(1/2) add a relative O((nu/w)^(1/2)/delta) to the
    # inviscid added mass: fitted slope -1/2 in w, 0.021 at w delta^2/nu = 1e4
    ws = np.array([1e2, 1e3, 1e4]) / T_VISC  # beyond, I1 and K1 leave the double range
    rel = [abs(-oscillating_cylinder_force(A, B, NU, RHO, w).imag / (w * inviscid_added_mass(A, B, RHO)) - 1.0)
           for w in ws]
    assert abs(np.polyfit(np.log(ws), np.log(rel), 1)[0] + 0.5) < 0.05
    assert rel[2] < 0.03
    assert abs(inviscid_added_mass(A, B, RHO) / (RHO * math.pi * A * A) - 3.05) < 0.01  # NUMERICS.md


@pytest.mark.parametrize("stokes_number", [pytest.param(0.3, marks=pytest.mark.slow), 3.0])
def test_oscillating_cylinder_force_in_the_periodic_state(stokes_number):
    """x_A = X sin(w t), X = 1e-3 delta: the force's complex amplitude over the last period within 1e-4.

    Neglected: the geometry's change O((X/delta)^2), convection O(X w delta/nu) at 2 w, and the start's
    transient, which decays like exp(-pi^2 nu t/delta^2), below 1e-6 after 1.5 viscous times. The
    concentric flow has the Fourier modes k = +-1 only: 8 points around hold it (measured 3.6e-5, as
    with 16; the time step's error at rtol = 1e-5)."""
    w = stokes_number / T_VISC
    x_amp = 1e-3 * DELTA
    period = 2.0 * math.pi / w
    t_end = period * math.ceil((1.5 * T_VISC + period) / period)
    run = run_prescribed(A, B, NU, RHO, PrescribedMotion(x_a=(0.0, x_amp, w, 0.0)), t_end,
                         resolution=Resolution(8, 20), control=StepControl(rtol=1e-5))
    last = run.t >= t_end - period
    t = run.t[last]
    basis = np.column_stack([np.cos(w * t), np.sin(w * t), np.ones_like(t)])
    c = np.linalg.lstsq(basis, run.F_x[last], rcond=None)[0]
    z = (c[0] - 1j * c[1]) / (x_amp * w)  # F_x = Re(z U e^{i w t}), U = X w
    exact = oscillating_cylinder_force(A, B, NU, RHO, w)
    assert abs(z / exact - 1.0) < 1e-4
    assert np.max(np.abs(run.F_z)) < 1e-12 * abs(exact) * x_amp * w


def test_oscillating_spin_torque_in_the_periodic_state():
    """Omega_a = sin(w t), concentric, outer wall held: the torque's amplitude within 3e-4 of the Bessel
    solution. The inner wall's angular acceleration enters the circulation condition at every step
    (the inner spin-up only in its first) and the rigid-rotation part of the wall traction. The
    start's transient is below 1e-6 after 1.5 viscous times (measured 1.59e-4 as after 2.5)."""
    from unsteady_exact import oscillating_spin_torque

    w = 3.0 / T_VISC
    period = 2.0 * math.pi / w
    t_end = period * math.ceil((1.5 * T_VISC + period) / period)
    run = run_prescribed(A, B, NU, RHO, PrescribedMotion(omega_a=(0.0, 1.0, w, 0.0)), t_end,
                         resolution=Resolution(8, 20), control=StepControl(rtol=1e-5))
    last = run.t >= t_end - period
    t = run.t[last]
    basis = np.column_stack([np.cos(w * t), np.sin(w * t), np.ones_like(t)])
    c = np.linalg.lstsq(basis, run.T_a[last], rcond=None)[0]
    z = c[0] - 1j * c[1]  # T_a = Re(z e^{i w t}); Omega_a = sin(w t) = Re(-i e^{i w t}), so z = -i Z
    exact = -1j * oscillating_spin_torque(A, B, NU, RHO, w)
    # rtol = 1e-5 per step: measured 1.6e-4, the global error of the wall vorticity as in the Couette test
    assert abs(z / exact - 1.0) < 3e-4
