"""The films between the inner cylinder's flat end faces and the end caps (``end_gap``).

Each face is a disc of radius a at the inner centre r, sliding over a cap that turns with the
outer cylinder about its axis across a film of thickness h: plane Couette flow. The reference
here integrates that film's shear stress over the disc by quadrature, in Cartesian components,
from the velocities of the two surfaces alone; the kernel's closed form is checked against it.
"""

import math
import warnings

import numpy as np
import pytest

from dynamics import Initial, Limits, ValidityWarning, preset, simulate
from dynamics.app.run import run_scene
from dynamics.scenes import SceneError, load_scene
from lubrication import Annulus, Motion, fluid_forces
from lubrication.registry import kernel_model

from apparatus import A, B, L as LENGTH, OIL as FLUID


def quarter_turn(v):
    """J v: a quarter turn the way chi grows (J e_eps = e_chi, e_eps = (sin chi, cos chi))."""
    return np.stack([v[1], -v[0]])


def faces_by_quadrature(kappa, chi, motion, h):
    """(f_eps, f_chi, T_a) of two faces: the stress -mu (v_A - v_cap)/h summed over a polar rule on each
    disc (Gauss-Legendre in the radius, equal steps in the angle: exact for the quadratic integrands)."""
    eps = kappa * (B - A)
    e_eps, e_chi = np.array([math.sin(chi), math.cos(chi)]), np.array([math.cos(chi), -math.sin(chi)])
    r = eps * e_eps
    r_dot = motion.eps_dot * e_eps + eps * motion.chi_dot * e_chi
    nodes, weights = np.polynomial.legendre.leggauss(6)
    rho, w_rho = 0.5 * A * (nodes + 1.0), 0.5 * A * weights
    angle = np.linspace(0.0, 2.0 * math.pi, 12, endpoint=False)
    rr, aa = np.meshgrid(rho, angle, indexing="ij")
    area = (w_rho[:, None] * rr * (2.0 * math.pi / angle.size)).ravel()  # rho d rho d angle
    offset = np.stack([(rr * np.sin(aa)).ravel(), (rr * np.cos(aa)).ravel()])  # x - r
    x = offset + r[:, None]
    relative = r_dot[:, None] + motion.omega_a * quarter_turn(offset) - motion.omega_b * quarter_turn(x)
    stress = -2.0 * FLUID.mu / h * relative  # two faces, each with clearance h
    force = stress @ area
    torque = np.sum(quarter_turn(offset) * stress, axis=0) @ area  # power T_a Omega_a of the spin part
    return force @ e_eps, force @ e_chi, torque


@pytest.mark.parametrize("model", ["closed-form", "stokes-exact"])
@pytest.mark.parametrize("kappa", [0.0, 0.4, 0.95])
def test_the_faces_forces_are_the_integrated_shear_of_their_films(model, kappa):
    rng = np.random.default_rng(7)
    annulus = Annulus(A, B, kappa * (B - A), LENGTH)
    h = 4e-4
    for _ in range(4):
        motion = Motion(eps_dot=rng.uniform(-1, 1) * 1e-3, chi_dot=rng.uniform(-3, 3), omega_a=rng.uniform(-3, 3),
                        omega_b=rng.uniform(-3, 3))
        with_faces = fluid_forces(annulus, motion, FLUID, model, end_gap=h).as_tuple()
        without = fluid_forces(annulus, motion, FLUID, model).as_tuple()
        added = np.subtract(with_faces[:3], without[:3])
        expected = faces_by_quadrature(kappa, 0.7, motion, h)
        scale = 2.0 * FLUID.mu * math.pi * A**2 / h * max(abs(motion.eps_dot), A * 3.0)
        np.testing.assert_allclose(added[:2], expected[:2], rtol=0, atol=1e-12 * scale)
        assert added[2] == pytest.approx(expected[2], abs=1e-12 * scale * A)


def test_the_faces_dissipate_and_their_drag_falls_as_the_clearance_grows():
    """The power the faces' films take from the motion, their forces on A less their reaction on B's caps,
    is the sum of the squares of the films' three shears, and falls as 1/h."""
    annulus = Annulus(A, B, 0.6 * (B - A), LENGTH)
    motion = Motion(eps_dot=2e-4, chi_dot=0.5, omega_a=2.0, omega_b=-1.0)
    base = fluid_forces(annulus, motion, FLUID, "stokes-exact").as_tuple()[:3]
    eps = 0.6 * (B - A)
    powers = []
    for h in (1e-4, 4e-4):
        f_eps, f_chi, t_a = np.subtract(fluid_forces(annulus, motion, FLUID, "stokes-exact", end_gap=h).as_tuple()[:3],
                                        base)
        # the power of the faces' forces on A, less that of their reaction on B's caps (T_b = -(T_a + eps f_chi))
        powers.append(f_eps * motion.eps_dot + f_chi * eps * motion.chi_dot + t_a * motion.omega_a
                      - (t_a + eps * f_chi) * motion.omega_b)
    assert powers[0] < 0.0 and powers[1] < 0.0
    assert powers[0] / powers[1] == pytest.approx(4.0, rel=1e-12)  # c ~ 1/h
    # each term its own square: c (eps'^2 + eps^2 W_b^2 + (a^2/2)(W_a - W_b)^2), c = mu pi a^2 (2/h)
    w_a, w_b = motion.omega_a - motion.chi_dot, motion.omega_b - motion.chi_dot
    c = FLUID.mu * math.pi * A**2 * 2.0 / 1e-4
    dissipated = c * (motion.eps_dot**2 + eps**2 * w_b**2 + 0.5 * A**2 * (w_a - w_b) ** 2)
    assert -powers[0] == pytest.approx(dissipated, rel=1e-12)


def test_only_the_linear_models_take_end_faces_and_scenes_name_the_key():
    with pytest.raises(ValueError, match="end_gap"):
        fluid_forces(Annulus(A, B, 0.5 * (B - A), LENGTH), Motion(omega_a=1.0), FLUID, "reynolds", end_gap=1e-3)
    with pytest.raises(ValueError, match="end_gap"):
        kernel_model("closed-form", end_gap=-1e-3)
    # lubrication films: refused beyond a quarter of the inner radius, at one instant and along a run
    with pytest.raises(ValueError, match="end_gap: .* at most"):
        fluid_forces(Annulus(A, B, 0.5 * (B - A), LENGTH), Motion(omega_a=1.0), FLUID, "closed-form", end_gap=0.3 * A)
    with pytest.raises(ValueError, match="end_gap: .* at most"):
        simulate(preset("steel"), Initial(0.5, 0.5), 0.01, forces=kernel_model("closed-form", end_gap=0.3 * A))
    with pytest.raises(SceneError, match="model.end_gap"):
        run_scene(load_scene(None, ['model.end_gap="3 mm"', "run.t_end=0.01 s"]))
    with pytest.raises(SceneError, match="model.end_gap"):
        run_scene(load_scene(None, ["model.equations=reduced", 'model.end_gap="0.5 mm"']))
    with pytest.raises(SceneError, match="end_gap"):
        load_scene(None, ["model.equations=navier-stokes", 'model.end_gap="0.5 mm"'])
    scene = load_scene(None, ['model.end_gap="0.5 mm"', "run.t_end=0.01 s"])
    assert scene.model.end_gap == pytest.approx(5e-4, rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        assert run_scene(scene).forces.endswith("+end-faces")


def test_the_faces_leave_a_smooth_release_rocking_regularly():
    """A linear, dissipative drag on smooth walls: the default release still rocks with a regular period
    (successive half periods over the last seconds within 5% of their mean) and rolls as far within 1%."""
    ap = preset("steel")
    runs = {}
    for gap in (None, 5e-4):
        forces = kernel_model("stokes-exact", **({} if gap is None else {"end_gap": gap}))
        runs[gap] = simulate(ap, Initial(0.5, 0.5), 20.0, forces=forces, limits=Limits(max_gap_reynolds=None))
    c = runs[5e-4].columns
    rocking = np.diff(c["phi"])
    reversals = c["t"][1:-1][rocking[:-1] * rocking[1:] < 0.0]
    late = np.diff(reversals[reversals > 10.0])
    assert runs[5e-4].regime == "rocking" and late.size > 20
    assert np.max(np.abs(late / np.mean(late) - 1.0)) < 0.05
    assert c["x_b"][-1] == pytest.approx(runs[None].columns["x_b"][-1], rel=0.01)
    assert c["x_b"][-1] != runs[None].columns["x_b"][-1]
