"""Open ends beyond the (theta, z) solver: the force models of the equations of motion, scenes, ``snail forces``.

The closed forms and the exact Stokes forces with ``ends="open"`` are L times the
per-unit-length coefficients times the thin-gap finite-length factors of
``lubrication.finite_length.factor_table``. The stored 33 x 33 table takes about
10 s to build in the tests' private cache, so these tests put a 9 x 9 table in
its place and work at its nodes, where the kernel returns the solver's own
factors (interpolation, 1e-11: tests/test_finite_length.py). At a node with
zeta >= 0.2 the table was built with the discretisation that
``finite_length_factors`` uses by default ((128, 64) extrapolated), so the two
agree to rounding; their torque factors differ only by the thin-gap identity,
which the solver meets to 1e-10 (tests/test_finite_length.py), times
3 kappa^2/(2 zeta^2) for T_a per W_b.
"""

import functools
import json
import math

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.apparatus import preset
from dynamics.equations.limits import Limits
from dynamics.initial import Initial
from dynamics.scenes import load_scene
from dynamics.simulation import simulate
from lubrication import Annulus, Motion
from lubrication import finite_length as fl
from lubrication.registry import kernel_model
from lubrication.reynolds2d import reynolds2d_forces

from apparatus import A, B, L, CLI_GEOMETRY, PRESET_FLUID

NODES = 9


@pytest.fixture(scope="module")
def small_table():
    return fl._build_table(NODES, NODES, fl.ZETA_MIN, fl.X0)


@pytest.fixture
def table(monkeypatch, small_table):
    """The small table in place of the stored one, for every force model built during the test."""
    monkeypatch.setattr(fl, "factor_table", lambda: small_table)
    return small_table


def _node(i: int, j: int) -> tuple[float, float, float]:
    """(kappa, 1 - kappa, L/a) of the table node (i, j): zeta on log-Lobatto points, s = X0/(X0 + L/(a zeta))."""
    zeta = math.exp(0.5 * math.log(fl.ZETA_MIN) * (1.0 - math.cos(math.pi * i / (NODES - 1))))
    s = 0.5 * (1.0 + math.cos(math.pi * j / (NODES - 1)))
    kappa = math.sqrt((1.0 - zeta) * (1.0 + zeta))
    return kappa, zeta * zeta / (1.0 + kappa), fl.X0 * (1.0 - s) / s * zeta


UNIT_MOTIONS = (("f_eps_per_eps_dot", Motion(eps_dot=1.0), 0), ("f_chi_per_w_a", Motion(omega_a=1.0), 1),
                ("t_a_per_w_a", Motion(omega_a=1.0), 2), ("f_chi_per_w_b", Motion(omega_b=1.0), 1),
                ("t_a_per_w_b", Motion(omega_b=1.0), 2))


@pytest.mark.parametrize("model", ["closed-form", "stokes-exact"])
@pytest.mark.parametrize("node", [(2, 6), (3, 6)], ids=["zeta=0.51,L/a=11.9", "zeta=0.24,L/a=5.6"])
def test_open_ends_are_length_times_coefficient_times_factor(table, model, node):
    """Each of the five coefficients of the force model with open ends against L x (its infinite-length
    coefficient) x finite_length_factors, the (theta, z) solver called directly."""
    kappa, omk, length_over_a = _node(*node)
    annulus = Annulus(a=A, b=B, length=length_over_a * A, one_minus_kappa=omk)
    factors = fl.finite_length_factors(kappa, length_over_a)
    open_ends, infinite = kernel_model(model, ends="open", length_over_a=length_over_a), kernel_model(model)
    assert open_ends.name.endswith("/open-ends")
    for name, motion, index in UNIT_MOTIONS:
        got = open_ends.forces(annulus, motion, PRESET_FLUID).as_tuple()[index]
        want = infinite.forces(annulus, motion, PRESET_FLUID).as_tuple()[index] * factors[name]
        assert got == pytest.approx(want, rel=1e-9), name


def test_open_ends_are_linear_in_the_velocities(table):
    """A combined motion is the sum of the unit ones (the factors multiply coefficients, not forces)."""
    _, omk, length_over_a = _node(3, 6)
    annulus = Annulus(a=A, b=B, length=length_over_a * A, one_minus_kappa=omk)
    model = kernel_model("stokes-exact", ends="open", length_over_a=length_over_a)
    combined = np.array(model.forces(annulus, Motion(eps_dot=-2e-5, chi_dot=0.3, omega_a=1.2, omega_b=-0.4),
                                     PRESET_FLUID).as_tuple())
    parts = sum(np.array(model.forces(annulus, m, PRESET_FLUID).as_tuple()) for m in
                (Motion(eps_dot=-2e-5), Motion(omega_a=0.9), Motion(omega_b=-0.7)))
    assert np.allclose(combined, parts, rtol=1e-12, atol=1e-15 * np.abs(parts).max())


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


# ---------------------------------------------------------------- scenes: model.ends through `snail run`

NO_REYNOLDS_LIMIT = 'run.max_gap_reynolds="none"'  # the comparison is of the force models alone


def test_scene_with_open_ends_runs_the_finite_length_model(table, tmp_path, capsys):
    """`snail run --set model.ends="open"` on the default scene (steel, exact Stokes forces): the run is the
    simulation with kernel_model("stokes-exact", ends="open", L/a) to the integrator's determinism, and not the
    infinite one."""
    code, out, _ = run(capsys, "run", "-o", str(tmp_path / "open"), "--t-end", "0.3", "--no-plot", "--json",
                       "--set", 'model.ends="open"', "--set", NO_REYNOLDS_LIMIT)
    assert code == 0
    summary = json.loads(out)
    assert summary["forces"] == "stokes-exact/open-ends"
    # the scene's own apparatus: its slope in radians may differ from math.radians(2.4) in the last bit, which
    # the integrator's discrete choices (Newton iterations) can carry to 1e-9 of X_b
    ap = load_scene().apparatus
    assert ap.delta_over_a == preset("steel").delta_over_a and ap.alpha == pytest.approx(math.radians(2.4), rel=1e-15)
    limits = Limits(max_gap_reynolds=None)
    direct = {ends: simulate(ap, Initial(kappa=0.5, phi=0.5), 0.3, limits=limits, rtol=1e-8,
                             forces=kernel_model("stokes-exact", ends=ends, length_over_a=ap.length / ap.a))
              for ends in ("open", "infinite")}
    x_b = summary["final"]["x_b"]
    assert x_b == pytest.approx(float(direct["open"].columns["x_b"][-1]), rel=1e-12)
    assert abs(x_b / float(direct["infinite"].columns["x_b"][-1]) - 1.0) > 1e-3


def test_scene_refuses_open_ends_with_the_reynolds_solver(tmp_path, capsys):
    code, _, err = run(capsys, "run", "-o", str(tmp_path / "r"), "--t-end", "0.1", "--no-plot",
                       "--set", 'model.ends="open"', "--set", 'model.forces="reynolds"')
    assert code == 2 and "model.ends" in err


# ---------------------------------------------------------------- `snail forces --ends`

def _forces(capsys, *args):
    code, out, err = run(capsys, "forces", *CLI_GEOMETRY, "--kappa", "0.6", "--omega-a", "1.5", "--eps-dot", "-1e-5",
                         *args)
    return code, (json.loads(out) if code == 0 and "--json" in args else out), err


@pytest.mark.parametrize("model", ["closed-form", "stokes-exact"])
def test_forces_applies_open_ends_to_the_factor_models(table, capsys, model):
    make = functools.partial(kernel_model, model)
    code, data, _ = _forces(capsys, "--model", model, "--ends", "open", "--json")
    assert code == 0 and data["ends"] == "open"
    annulus = Annulus.from_kappa(A, B, 0.6, L)
    motion = Motion(eps_dot=-1e-5, omega_a=1.5)
    want = make(ends="open", length_over_a=L / A).forces(annulus, motion, PRESET_FLUID)
    infinite = make().forces(annulus, motion, PRESET_FLUID)
    assert (data["f_eps"], data["f_chi"], data["T_a"]) == pytest.approx(want.as_tuple(), rel=1e-14)
    assert data["f_chi"] < 0.95 * infinite.f_chi  # the ends take 13 % of the rotation force at kappa = 0.6


def test_forces_open_ends_with_half_sommerfeld(capsys):
    """The (theta, z) solver takes the end-region pressure p_end: --p-ref is it with open ends. The film's
    pressure swings by +-9 Pa about it here, so with p_ref = 5 Pa it ruptures: the result differs from the
    full film and equals the solver's."""
    args = ("--model", "reynolds", "--ends", "open", "--cavitation", "half-sommerfeld", "--p-ref", "5",
            "--p-cav", "0", "--json")
    code, data, _ = _forces(capsys, *args)
    assert code == 0 and data["p_ref"] == 5.0
    annulus = Annulus.from_kappa(A, B, 0.6, L)
    motion = Motion(eps_dot=-1e-5, omega_a=1.5)
    want = reynolds2d_forces(annulus, motion, PRESET_FLUID, cavitation="half-sommerfeld", p_end=5.0)  # its own grid
    full = reynolds2d_forces(annulus, motion, PRESET_FLUID)
    assert (data["f_eps"], data["f_chi"], data["T_a"]) == pytest.approx(want.as_tuple(), rel=1e-14)
    assert abs(data["f_eps"] / full.f_eps - 1.0) > 1.0  # f_eps even changes sign


def test_forces_n_axial_is_cells_along_the_whole_length(capsys):
    code, data, _ = _forces(capsys, "--model", "reynolds", "--ends", "open", "--n-axial", "16", "--json")
    assert code == 0 and data["n_axial"] == 16
    want = reynolds2d_forces(Annulus.from_kappa(A, B, 0.6, L), Motion(eps_dot=-1e-5, omega_a=1.5), PRESET_FLUID,
                             n_axial=16)
    assert data["f_chi"] == pytest.approx(want.f_chi, rel=1e-14)
    with pytest.raises(SystemExit):
        main(["forces", "--help"])
    assert "cells along the whole length" in " ".join(capsys.readouterr().out.split())


def test_forces_all_with_open_ends_compares_like_with_like(table, capsys):
    code, data, _ = _forces(capsys, "--model", "all", "--ends", "open", "--json")
    assert code == 0
    assert [m["model"] for m in data["models"]] == ["closed-form", "reynolds", "stokes-exact"]
    assert all(m["ends"] == "open" for m in data["models"]) and data["reference"] == "stokes-exact"
    closed, reynolds = data["models"][:2]
    # both are the thin-gap film with open ends: the 9 x 9 table between its nodes and the solver at N = 32
    # each err by about 1e-3, while the ends take 13 % of the rotation force at kappa = 0.6
    assert reynolds["f_chi"] == pytest.approx(closed["f_chi"], rel=1e-2)


@pytest.mark.parametrize(("args", "words"), [
    (["--model", "auto", "--ends", "open"], "--model auto chooses its model and options itself; drop --ends"),
    (["--model", "stokes", "--ends", "open"], "--ends: the stokes model is per unit length of an infinitely long "
                                              "annulus: ends must be 'infinite'"),
    (["--model", "all", "--ends", "sealed"], "ends = 'sealed' needs the Reynolds solver"),
    (["--model", "closed-form", "--ends", "sealed"], "ends = 'sealed' needs the Reynolds solver"),
    (["--model", "reynolds", "--ends", "open", "--grid", "uniform"], "--grid"),
    (["--model", "reynolds", "--n-axial", "32"], "--n-axial"),
    (["--model", "reynolds", "--ends", "open", "--cavitation", "jfo"], "only half-sommerfeld"),
    (["--model", "reynolds", "--ends", "sealed", "--cavitation", "half-sommerfeld"], "with sealed ends"),
    (["--model", "reynolds", "--ends", "open", "--n-axial", "31"], "--n-axial must be an even integer in [4, 4096]"),
])
def test_forces_refuses_what_a_model_cannot_do_with_the_ends(capsys, args, words):
    code, _, err = _forces(capsys, *args)
    assert code == 2
    assert words in err and "Traceback" not in err
