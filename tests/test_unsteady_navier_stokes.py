"""The long-time limit of the unsteady solver is the steady Navier-Stokes flow of the finite-element solver.

The apparatus's annulus (a = 8 mm, b = 11.25 mm, delta/a = 0.41), the inner cylinder held at
kappa = 0.5, the inner wall turning at W_a and the outer one against it at W_b = -W_a a/(2 b),
from rest to three viscous times: the reduced gap Reynolds number
Re* = max(|W_a| a, |W_b| b) delta^2/(nu a) = W_a delta^2/nu is 1 and 5. The reference is
:func:`lubrication.navier_stokes.navier_stokes_forces` (Taylor-Hood, Newton) on its default mesh,
at rest in the frame of the line of centres (chi' = 0, so W = Omega and no frame forces). Its
accuracy, stated with :func:`lubrication.navier_stokes.inertial_mesh` as 1e-5 of the force at this
delta/a, measured here against the mesh refined twice each way: f_eps 4.6e-6 (all of it
inertial: Stokes flow has none), f_chi 3e-7, T_a 3e-8, T_b 1e-7, at both Reynolds numbers. The
spectral flow (16 x 12 points) agrees with the refined mesh to 3e-7 and with 32 x 24 points to 3e-7.
The steady state is the fixed point of the time step whatever its size (the extrapolated
convection is then exact), but steps left to grow to ~0.9 delta^2/nu (rtol 1e-4) took the
explicit convection near its stability limit and slowed the approach: f_eps still moved by 5e-6
from two to three viscous times. Capped at 0.1 delta^2/nu, it moves by 2e-10.
"""

import pytest

pytest.importorskip("skfem")

from lubrication.geometry import Annulus, Fluid, Motion  # noqa: E402
from lubrication.navier_stokes import navier_stokes_forces  # noqa: E402
from lubrication.unsteady import PrescribedMotion, Resolution, StepControl, run_prescribed  # noqa: E402

A, B, NU, RHO = 0.008, 0.01125, 2e-4, 1000.0
DELTA = B - A
T_VISC = DELTA**2 / NU
KAPPA = 0.5


@pytest.mark.parametrize("reynolds", [1.0, pytest.param(5.0, marks=pytest.mark.slow)])
def test_long_time_limit_is_the_steady_navier_stokes_flow(reynolds):
    w_a = reynolds * NU / DELTA**2
    w_b = -0.5 * w_a * A / B
    assert abs(max(abs(w_a) * A, abs(w_b) * B) * DELTA**2 / (NU * A) - reynolds) < 1e-12
    # Newton from the Stokes flow in one continuation step at Re* = 1 (2 iterations; the same loads to
    # 3e-12 as the default four steps); four at Re* = 5
    fe = navier_stokes_forces(Annulus(A, B, KAPPA * DELTA, length=1.0), Motion(omega_a=w_a, omega_b=w_b),
                              Fluid(NU, RHO), steps=1 if reynolds <= 1.0 else 4)
    # A above B: e_eps = +z, e_chi = +x
    run = run_prescribed(A, B, NU, RHO, PrescribedMotion(z_a=KAPPA * DELTA, omega_a=w_a, omega_b=w_b),
                         3.0 * T_VISC, resolution=Resolution(16, 12), control=StepControl(rtol=1e-4),
                         dt_max=0.1 * T_VISC)
    loads = {"f_eps": run.F_z, "f_chi": run.F_x, "T_a": run.T_a, "T_b": run.T_b}
    reference = {"f_eps": fe.total.f_eps, "f_chi": fe.total.f_chi, "T_a": fe.total.T_a, "T_b": fe.outer[2]}
    one_visc = run.t >= 2.0 * T_VISC
    for name, series in loads.items():
        # steady: the slowest viscous mode has decayed far below the comparison
        assert abs(series[one_visc][0] / series[-1] - 1.0) < 1e-6, name
        assert abs(series[-1] / reference[name] - 1.0) < 2e-5, name
    # the inertial radial force is a tenth (Re* = 1) to a half (Re* = 5) of the tangential one
    assert 0.05 < abs(fe.total.f_eps / fe.total.f_chi) < 0.6
