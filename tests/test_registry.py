"""The force-model registry: a model declared once is found everywhere, and the compositions' rules hold.

A toy model, constant forces, is declared and registered in this file alone; it
must then be a model of :func:`lubrication.registry.fluid_forces`, of ``snail forces
--model``, of a scene (``model.forces``), of :func:`dynamics.simulate`, and of the
generated scene reference and force-model reference of the docs.
"""

from __future__ import annotations

import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

from dynamics import Initial, preset, simulate
from dynamics.app.cli import main
from dynamics.app.run import run_scene
from dynamics.equations.limits import Limits
from dynamics.scenes import SceneError, load_scene
from lubrication import registry
from lubrication.geometry import Annulus, Fluid, FluidForces, Motion
from lubrication.spec import ForceModelSpec
from numerics.jit import jit
from numerics.keys import Key

from apparatus import A, B, L, CLI_GEOMETRY, PRESET_FLUID

ROOT = Path(__file__).resolve().parents[1]
#: The toy model's force along e_eps (N), along e_chi (N) and torque (N m), whatever the state.
F_EPS, F_CHI, T_A = -1e-3, 2e-4, -3e-6


def _constant_forces(annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
    return FluidForces(F_EPS, F_CHI, T_A, model="constant")


@jit
def _constant_kernel(data, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    return F_EPS, F_CHI, T_A


TOY = ForceModelSpec("constant", "constant forces, a test's model", _constant_forces,
                     kernel=lambda: (_constant_kernel, np.empty(0), True))


@pytest.fixture
def toy():
    registry.register(TOY)
    yield TOY
    registry.unregister(TOY.name)


def test_a_model_registered_in_a_test_is_a_model_of_fluid_forces(toy):
    annulus = Annulus.from_kappa(A, B, 0.4, length=0.1)
    f = registry.fluid_forces(annulus, Motion(omega_a=1.0), Fluid(2e-4, 1000.0), "constant")
    assert f.as_tuple() == (F_EPS, F_CHI, T_A)
    assert "constant" in registry.names(trajectories=True)


def test_a_registered_model_is_a_choice_of_snail_forces(toy, capsys):
    code = main(["forces", "--model", "constant", *CLI_GEOMETRY, "--kappa", "0.4", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and (out["model"], out["f_eps"], out["f_chi"], out["T_a"]) == ("constant", F_EPS, F_CHI, T_A)


def test_a_registered_model_drives_a_scene_and_simulate(toy):
    """The kernel enters the compiled equations: with constant forces (2.2) has the exact sedimentation
    eps'' = (f_eps - m'_a g cos(phi)) / m_eff from rest below the centre on a level plane (phi = pi, chi = pi),
    so eps(t) - eps(0) = (f_eps/m_eff + m'_a g / m_eff) t^2 / 2 while the inner cylinder stays on the
    vertical; checked at t = 2 ms, long before the gap closes, to the integrator's tolerance."""
    scene = load_scene(overrides=["model.forces=constant", "incline.alpha=0", "initial.kappa=0.2",
                                  "initial.phi=3.141592653589793", "run.t_end=0.002", "run.on_invalid=warn"])
    assert scene.model.forces == "constant"
    run = run_scene(scene)
    assert run.forces == "constant" and run.status == "completed"
    ap = scene.apparatus
    t = run.t[-1]
    f_chi_free = F_CHI  # f_chi turns the line of centres: eps chi'' = f_chi/m_eff, so chi moves as t^2 too
    accel = (F_EPS + ap.m_a_reduced * ap.g) / ap.m_eff  # (2.2) at phi = pi: A sinks along e_eps = -e_z
    assert run.columns["eps"][-1] - run.columns["eps"][0] == pytest.approx(0.5 * accel * t * t, rel=1e-4)
    assert f_chi_free != 0.0 and run.columns["chi"][-1] != run.columns["chi"][0]
    direct = simulate(preset("steel", alpha=0.0), Initial(0.2, math.pi), 0.002, forces="constant",
                      limits=Limits(on_invalid="warn"))
    assert direct.columns["eps"][-1] == pytest.approx(run.columns["eps"][-1], rel=1e-9)


def test_a_registered_model_is_in_the_generated_references(toy):
    pytest.importorskip("sphinx", reason="the docs extra: pip install '.[docs]'")
    spec = importlib.util.spec_from_file_location("snail_docs", ROOT / "docs" / "site" / "_ext" / "snail_docs.py")
    docs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(docs)
    scene = docs.scene_lines()
    allowed = scene[scene.index("   * - ``forces``") + 1]  # the row of model.forces: its allowed values
    assert "'stokes-exact'" in allowed and "'constant'" in allowed
    assert any("constant forces, a test's model" in line for line in docs.force_model_lines())


def test_an_unregistered_model_is_refused_by_name():
    with pytest.raises(SceneError, match="model.forces must be one of .*'stokes-exact'.*got 'constant'"):
        load_scene(overrides=["model.forces=constant"])
    with pytest.raises(ValueError, match="model must be one of closed-form, .*, got 'constant'"):
        registry.get("constant")


def test_a_name_is_registered_once(toy):
    with pytest.raises(ValueError, match="registered already"):
        registry.register(ForceModelSpec("constant", "another", _constant_forces))
    with pytest.raises(ValueError, match="are the compositions'"):
        registry.register(ForceModelSpec("other", "x", _constant_forces, options={"ends": Key("a clash")}))


# -- the compositions' rules, each stated once ---------------------------------------------------------

ANNULUS = Annulus.from_kappa(A, B, 0.6, length=L)
MOTION = Motion(eps_dot=-1e-5, chi_dot=0.2, omega_a=1.0, omega_b=0.5)


@pytest.mark.parametrize(("model", "options", "words"), [
    ("reynolds", {"inertia": "first-order"}, "inertia: the first inertial correction is tabulated"),
    ("stokes-exact", {"ends": "open", "inertia": "first-order"}, "ends = 'open'"),
    ("closed-form", {"cavitation": "jfo"}, "cavitation: cavitation is a rupture of the Reynolds film"),
    ("stokes-exact", {"ends": "sealed"}, "needs the Reynolds solver"),
    ("stokes", {"ends": "open"}, "per unit length of an infinitely long annulus"),
    ("reynolds", {"ends": "open", "cavitation": "jfo"}, "only half-sommerfeld carries over"),
    ("reynolds", {"p_cav": 1e5}, "p_cav: p_cav goes with cavitation, which is 'none' here"),
    ("reynolds", {"n_axial": 32}, "n_axial: n_axial goes with ends, which is 'infinite' here"),
    ("reynolds", {"n": 3}, "n must be an integer in [8, 1048576]"),
    ("closed-form", {"n": 32}, "takes no option 'n'"),
])
def test_a_composition_a_model_does_not_take_is_refused_naming_the_option(model, options, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace("[", r"\[")):
        registry.fluid_forces(ANNULUS, MOTION, PRESET_FLUID, model, **options)


def test_compositions_a_model_takes_give_its_forces():
    for model in ("closed-form", "stokes-exact"):
        plain = registry.fluid_forces(ANNULUS, MOTION, PRESET_FLUID, model)
        corrected = registry.fluid_forces(ANNULUS, MOTION, PRESET_FLUID, model, inertia="first-order")
        open_ends = registry.fluid_forces(ANNULUS, MOTION, PRESET_FLUID, model, ends="open")
        assert corrected.f_chi == plain.f_chi and corrected.f_eps != plain.f_eps
        assert abs(open_ends.f_chi) < abs(plain.f_chi)  # the ends take part of the rotation force
    film = registry.fluid_forces(ANNULUS, MOTION, PRESET_FLUID, "reynolds", cavitation="half-sommerfeld", p_cav=1e5)
    assert film.model == "reynolds/half-sommerfeld"


def test_a_motion_whose_forces_overflow_is_refused():
    """A rate whose forces would overflow never reaches a model; a model whose forces are not numbers is refused."""
    with pytest.raises(ValueError, match=r"chi_dot must be in \[-1e\+06, 1e\+06\]"):
        Motion(chi_dot=1e308, omega_a=-1e308)
    registry.register(ForceModelSpec("infinite", "forces that overflow, a test's model",
                                     lambda annulus, motion, fluid: FluidForces(math.inf, 0.0, 0.0, model="infinite")))
    try:
        with pytest.raises(ValueError, match="overflow a double"):
            registry.fluid_forces(ANNULUS, MOTION, PRESET_FLUID, "infinite")
    finally:
        registry.unregister("infinite")
