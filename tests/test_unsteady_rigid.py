"""Exact rigid states of the unsteady solver, kept to rounding on a fixed and on a moving grid.

* Concentric rigid rotation: psi = Omega (|zeta|^2 - b^2)/2, omega = -2 Omega (counterclockwise
  vorticity of a clockwise rotation), pressure rho Omega^2 r^2 / 2: no torque on either wall,
  no force on the centred inner cylinder.
* The same rotation with the inner cylinder off centre and orbiting B with the fluid
  (z_A(t) = z_A(0) e^{-i Omega t}): the grid slides with p(t), the state is still exact; the
  pressure's force on the inner wall is -rho pi a^2 Omega^2 z_A (the centripetal force of the
  displaced fluid), the torques vanish. This is the geometric conservation test of the moving
  grid: a uniform vorticity must stay uniform whatever the grid does.
* Fluid at rest in the uniform body force g_eff: only the buoyancy-like -rho pi a^2 g_eff.
"""

import cmath
import math

import numpy as np
import pytest

from lubrication.unsteady import Resolution, StepControl, UnsteadySolver, prescribed_wall

A, B, NU, RHO = 0.008, 0.01125, 2e-4, 1000.0
DELTA = B - A
OMEGA = 3.0


def _rigid_solver(z0, resolution):
    solver = UnsteadySolver(A, B, NU, RHO, resolution, control=StepControl(adaptive=False))
    psi, omega = solver.fields_from_stream_function(z0, lambda z: OMEGA * (np.abs(z) ** 2 - B * B) / 2.0)
    u0 = -1j * OMEGA * z0
    c_in = 0.0
    solver.start(z0, (u0.real, u0.imag, OMEGA, OMEGA), h_psi=psi, omega=omega, c_in=c_in)
    return solver


def test_concentric_rigid_rotation_is_kept_to_rounding():
    solver = _rigid_solver(0j, Resolution(16, 16))
    q = (0.0, 0.0, OMEGA, OMEGA)
    dt = 0.01 * DELTA**2 / NU
    for _ in range(20):
        assert solver.step(dt, prescribed_wall(q), 0j).accepted
    st = solver.state
    kk = solver.grid.K
    # omega_0 = -2 Omega everywhere, every other mode zero
    assert np.max(np.abs(st.omega[kk] + 2.0 * OMEGA)) < 1e-12 * OMEGA
    st.omega[kk] = 0.0
    assert np.max(np.abs(st.omega)) < 1e-12 * OMEGA
    torque_scale = 4.0 * math.pi * RHO * NU * A * A * OMEGA
    assert abs(st.loads[2]) < 1e-11 * torque_scale and abs(st.loads[3]) < 1e-11 * torque_scale
    assert abs(st.loads[0]) < 1e-11 * torque_scale / A and abs(st.loads[1]) < 1e-11 * torque_scale / A


@pytest.mark.parametrize("kappa", [0.3, 0.7])
def test_orbiting_rigid_rotation_on_the_moving_grid(kappa):
    z0 = kappa * DELTA * cmath.exp(0.5j)
    # the rigid stream function is truncated at exp(-beta K): below 1e-14 at these points
    solver = _rigid_solver(z0, Resolution(96, 16))
    omega0 = solver.state.omega.copy()
    dt = 2e-3 / OMEGA
    worst_f = worst_t = 0.0
    for n in range(1, 21):
        t = n * dt
        z = z0 * cmath.exp(-1j * OMEGA * t)
        u = -1j * OMEGA * z
        assert solver.step(dt, prescribed_wall((u.real, u.imag, OMEGA, OMEGA)), z).accepted
        st = solver.state
        f_exact = -RHO * math.pi * A * A * OMEGA**2 * z
        if n > 4:  # the acceleration rho pi a^2 U' is the BDF derivative: first order on the Euler steps
            worst_f = max(worst_f, abs(complex(st.loads[0], st.loads[1]) - f_exact) / abs(f_exact))
        worst_t = max(worst_t, abs(st.loads[2]) + abs(st.loads[3]))
    # the grid has moved through 0.04 rad of the orbit; the vorticity is still uniform
    assert np.max(np.abs(solver.state.omega - omega0)) < 1e-9 * OMEGA
    # BDF2's error on U' of the circular motion, (Omega dt)^2 / 3 at most, decaying from the start
    assert worst_f < (OMEGA * dt) ** 2
    assert worst_t < 1e-9 * 4.0 * math.pi * RHO * NU * A * A * OMEGA


def test_fluid_at_rest_feels_only_the_body_force():
    g_eff = complex(0.7, -9.8)
    solver = UnsteadySolver(A, B, NU, RHO, Resolution(32, 12), g_eff=g_eff)
    z0 = 0.4 * DELTA * cmath.exp(1j)
    solver.start(z0)
    for _ in range(5):
        assert solver.step(1e-3, prescribed_wall((0.0, 0.0, 0.0, 0.0)), z0).accepted
    st = solver.state
    expected = -RHO * math.pi * A * A * g_eff
    assert abs(complex(st.loads[0], st.loads[1]) - expected) < 1e-14 * abs(expected)
    assert np.max(np.abs(st.omega)) == 0.0 and st.loads[2] == 0.0 and st.loads[3] == 0.0


@pytest.mark.parametrize("kappa", [0.0, 0.6])
def test_fluid_wall_velocity_of_a_rigid_field_is_the_walls(kappa):
    """The fluid moving rigidly with the inner wall, psi = Im(conj(U) zeta) + Omega_a |zeta - z_A|^2/2,
    stands for the wall velocities (U, Omega_a) at its inner wall; a fluid at rest for none."""
    z0 = kappa * DELTA * cmath.exp(-0.8j)
    u, omega_a = complex(0.02, -0.03), 1.7
    solver = UnsteadySolver(A, B, NU, RHO, Resolution(64, 16))
    psi, _ = solver.fields_from_stream_function(
        z0, lambda z: (np.conj(u) * z).imag + omega_a * np.abs(z - z0) ** 2 / 2.0)
    geo = solver.geometry(z0)
    got = solver.fluid_wall_velocity(geo, psi)
    assert abs(complex(got[0], got[1]) - u) < 1e-12 * abs(u)
    assert abs(got[2] - omega_a) < 1e-12 * omega_a
    assert solver.fluid_wall_velocity(geo, np.zeros_like(psi)) == (0.0, 0.0, 0.0)
