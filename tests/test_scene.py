"""Scenes: the embedded default, units, every class of bad input, overrides and the resolved TOML."""

import dataclasses
import json
import math
import sys

import pytest

from dynamics.apparatus import STEEL, Apparatus
from dynamics.scenes import (
    Cavitation,
    Contact,
    Groups,
    SceneError,
    load_scene,
    parse_scene,
    resolved_toml,
)

from apparatus import A, L

# A physical scene and a dimensionless [groups] scene, as mappings to edit.
PHYSICAL = {
    "apparatus": {"preset": "steel"},
    "fluid": {"nu": "200 cSt"},
    "incline": {"alpha": "2.4 deg"},
    "initial": {"kappa": 0.5, "phi": 0.5},
    "run": {"t_end": "10 s"},
}
# The paper's figures: mu = 1, which no physical apparatus has.
GROUPS = {
    "groups": {"s": 0.5, "upsilon": 1.0, "mu": 1.0},
    "model": {"equations": "reduced"},
    "initial": {"kappa": 0.5},
    "run": {"t_end_tau": 50.0},
}
WITHOUT = object()  # marks a key or section to delete


def edited(base, **changes):
    """``base`` with sections (or single keys) replaced; ``WITHOUT`` deletes."""
    scene = {name: dict(table) for name, table in base.items()}
    for section, table in changes.items():
        if table is WITHOUT:
            del scene[section]
            continue
        scene.setdefault(section, {})
        for key, value in table.items():
            if value is WITHOUT:
                scene[section].pop(key, None)
            else:
                scene[section][key] = value
    return scene


def test_default_scene_is_the_steel_apparatus_and_its_groups_match():
    scene = load_scene()
    app = scene.apparatus
    assert app == dataclasses.replace(STEEL, nu=2e-4, alpha=app.alpha)
    assert app.alpha == pytest.approx(math.radians(2.4), rel=1e-15)
    assert scene.groups == Groups.from_apparatus(app)
    assert scene.groups.upsilon == app.upsilon and scene.groups.delta_over_a == app.delta_over_a
    assert scene.groups.reduced_params == app.reduced_params
    assert not scene.dimensionless and scene.tau == app.tau
    assert (scene.initial.kappa, scene.initial.phi, scene.initial.omega_b) == (0.5, 0.5, 0.0)
    assert (scene.model.equations, scene.model.forces) == ("full", "stokes-exact")  # the accurate forces
    assert (scene.run.t_end, scene.run.rtol) == (10.0, 1e-8)
    assert scene.t_end_tau == pytest.approx(10.0 / app.tau)
    assert scene.contact is None and scene.cavitation is None
    assert scene.source.endswith("default.toml")


@pytest.mark.parametrize(("override", "read", "expected"), [
    ("fluid.nu=200 cSt", lambda s: s.apparatus.nu, 2e-4),
    ("apparatus.a=0.8 cm", lambda s: s.apparatus.a, 0.008),
    ("incline.alpha=2.4 deg", lambda s: s.apparatus.alpha, math.radians(2.4)),
    ("apparatus.m_a=158 g", lambda s: s.apparatus.m_a, 0.158),
    ("fluid.rho=0.95 g/cm^3", lambda s: s.apparatus.rho, 950.0),
    ("run.t_end=30 s", lambda s: s.run.t_end, 30.0),
    ("run.t_end=2 min", lambda s: s.run.t_end, 120.0),
    ("initial.omega_b=60 rpm", lambda s: s.initial.omega_b, 2.0 * math.pi),
    ("initial.phi=90 deg", lambda s: s.initial.phi, math.pi / 2),
    ("incline.g=9.81 m/s^2", lambda s: s.apparatus.g, 9.81),
    ("incline.alpha=0.05", lambda s: s.apparatus.alpha, 0.05),  # a number is in rad
])
def test_unit_strings_convert_to_si(override, read, expected):
    assert read(load_scene(overrides=[override])) == pytest.approx(expected, rel=1e-14)


def test_rho_a_gives_the_mass_of_a_solid_inner_cylinder():
    scene = parse_scene(edited(PHYSICAL, apparatus={"rho_a": "7.85 g/cm^3"}))
    assert scene.apparatus.m_a == pytest.approx(7850.0 * math.pi * A**2 * L)


def bad(case, scene, *words):
    return pytest.param(scene, words, id=case)


BAD = [
    # unknown names
    bad("unknown section", edited(PHYSICAL, colour={"red": 1}),
        "[colour]", "allowed sections", "[apparatus]"),
    bad("unknown key", edited(PHYSICAL, fluid={"viscosity": 1.0}),
        "fluid.viscosity", "allowed keys in [fluid]: nu, rho"),
    bad("section not a table", {**PHYSICAL, "apparatus": "steel"}, "[apparatus]", "table"),
    # missing values
    bad("missing group", edited(GROUPS, groups={"upsilon": WITHOUT}),
        "groups.upsilon", "missing", "(0, inf)"),
    bad("missing without preset", edited(PHYSICAL, apparatus={"preset": WITHOUT, "a": 0.008}),
        "apparatus.b", "missing", "[1e-06, 10] m"),
    bad("missing run length", edited(PHYSICAL, run=WITHOUT), "run.t_end", "missing", "(0, inf) s"),
    bad("no apparatus or groups", {"run": {"t_end": 1.0}}, "apparatus.preset", "missing", "[groups]"),
    bad("missing contact gap", edited(PHYSICAL, contact={"psi": 0.1}),
        "contact.sigma", "missing", "contact.kappa_star"),
    bad("rough without correlation",
        edited(PHYSICAL, contact={"kappa_star": 0.9, "roughness_amplitude": 0.1}),
        "contact.roughness_correlation", "missing", "(0, inf) m"),
    bad("missing cavitation model", edited(PHYSICAL, cavitation={"p_cav": 0.0}),
        "cavitation.model", "missing", "'jfo'"),
    # wrong type, unit or dimension
    bad("wrong dimension", edited(PHYSICAL, incline={"alpha": "2.4 kg"}),
        "incline.alpha", "kilogram", "[mass]", "angle", "(-90, 90) deg"),
    bad("wrong dimension of a unit", edited(PHYSICAL, fluid={"nu": "200 furlongs"}),
        "fluid.nu", "([length])", "[length] ** 2 / [time]", "[1e-09, 1000] m^2/s"),
    bad("unreadable quantity", edited(PHYSICAL, fluid={"nu": "200 cSt)"}),
        "fluid.nu", "not a quantity", "[1e-09, 1000] m^2/s"),
    bad("wrong type", edited(PHYSICAL, fluid={"nu": True}), "fluid.nu", "[1e-09, 1000] m^2/s", "True"),
    bad("unknown choice", edited(PHYSICAL, model={"equations": "partial"}),
        "model.equations", "'full', 'reduced', 'navier-stokes', 'auto'"),
    bad("float for an integer", edited(PHYSICAL, model={"n": 16.0}),
        "model.n", "integer", "[8, 1048576]"),
    bad("not finite", edited(PHYSICAL, initial={"phi": math.nan}), "initial.phi", "[-1e+06, 1e+06] deg"),
    bad("units in a dimensionless scene", edited(GROUPS, initial={"omega_b": "1 rad/s"}),
        "initial.omega_b", "rad/tau"),
    # unphysical values
    bad("a >= b", edited(PHYSICAL, apparatus={"b": "0.7 cm"}),
        "apparatus.b", "'0.7 cm'", "(a, inf) = (0.008, inf) m"),
    bad("kappa0 >= 1", edited(PHYSICAL, initial={"kappa": 1.0}), "initial.kappa", "[0, 1)", "got 1.0"),
    bad("kappa0 < 0", edited(PHYSICAL, initial={"kappa": -0.1}), "initial.kappa", "[0, 1)"),
    bad("negative viscosity", edited(PHYSICAL, fluid={"nu": "-200 cSt"}),
        "fluid.nu", "[1e-09, 1000] m^2/s", "'-200 cSt' = -0.0002 m^2/s"),
    bad("negative mass", edited(PHYSICAL, apparatus={"m_b": "-47 g"}),
        "apparatus.m_b", "[1e-12, 1e+06] kg", "-47 g"),
    bad("buoyant inner cylinder", edited(PHYSICAL, apparatus={"m_a": "10 g"}),
        "apparatus.m_a", "'10 g'", "heavier than the fluid", ", inf) kg"),
    bad("buoyant inner density", edited(PHYSICAL, apparatus={"rho_a": "0.9 g/cm^3"}),
        "apparatus.rho_a", "heavier than the fluid"),
    bad("slope too steep", edited(PHYSICAL, incline={"alpha": "95 deg"}),
        "incline.alpha", "(-90, 90) deg", "95 deg"),
    bad("slope in rad too steep", edited(PHYSICAL, incline={"alpha": 1.6}),
        "incline.alpha", "(-90, 90) deg", "91.6732 deg"),
    bad("rtol too loose", edited(PHYSICAL, run={"rtol": 0.5}), "run.rtol", "[2.22045e-14, 0.1]"),
    bad("rtol below rounding", edited(PHYSICAL, run={"rtol": 1e-20}), "run.rtol", "[2.22045e-14, 0.1]", "1e-20"),
    bad("negative run length", edited(PHYSICAL, run={"t_end": "-1 s"}), "run.t_end", "(0, inf) s"),
    bad("asperities wider than the gap", edited(PHYSICAL, contact={"sigma": "4 mm"}),
        "contact.sigma", "(0, delta) = (0, 0.00325) m"),
    bad("start beyond contact", edited(PHYSICAL, contact={"kappa_star": 0.4}),
        "initial.kappa", "[0, contact.kappa_star] = [0, 0.4]"),
    bad("cavitation above ambient", edited(PHYSICAL, cavitation={"model": "jfo", "p_cav": "2 atm"}),
        "cavitation.p_cav", "[0, 101325] Pa"),
    bad("unknown cavitation model", edited(PHYSICAL, cavitation={"model": "elrod"}),
        "cavitation.model", "'half-sommerfeld', 'swift-stieber', 'jfo'"),
    # alternatives and clashes
    bad("m_a and rho_a", edited(PHYSICAL, apparatus={"m_a": "158 g", "rho_a": 7850.0}),
        "apparatus.m_a", "apparatus.rho_a", "not both"),
    bad("t_end and t_end_tau", edited(PHYSICAL, run={"t_end_tau": 100.0}),
        "run.t_end", "run.t_end_tau", "not both", "(0, inf) tau"),
    bad("groups and apparatus", edited(GROUPS, apparatus={"preset": "steel"}),
        "apparatus.preset", "groups.s", "either [groups] or [apparatus]/[fluid]/[incline]"),
    bad("groups and an empty section", edited(GROUPS, fluid={}), "[fluid]", "either [groups]"),
    # what a dimensionless [groups] scene or the reduced model cannot have
    bad("seconds in a dimensionless scene", edited(GROUPS, run={"t_end_tau": WITHOUT, "t_end": "30 s"}),
        "run.t_end", "dimensionless", "run.t_end_tau in (0, inf) tau"),
    bad("length in a dimensionless scene", edited(GROUPS, contact={"sigma": "50 um"}),
        "contact.sigma", "contact.kappa_star", "(0, 1)"),
    bad("friction angle without delta/a",
        edited(GROUPS, contact={"kappa_star": 0.9, "friction_angle": "5 deg"}),
        "contact.friction_angle", "groups.delta_over_a", "[0, 90) deg"),
    bad("mu = 1 for the full model",
        edited(GROUPS, model={"equations": "full"}, groups={"delta_over_a": 0.1}),
        "groups.mu", "mu_ratio must be in (1 + m_f/m_a, inf)", "equations = 'reduced'"),
    bad("full model without delta/a", edited(GROUPS, model={"equations": "full"}),
        "groups.delta_over_a", "(0, inf)", "physical apparatus"),
    bad("reduced model with Reynolds forces", edited(GROUPS, model={"forces": "reynolds"}),
        "model.forces", "'closed-form' or 'auto'"),
    bad("reduced model with kappa_dot", edited(GROUPS, initial={"kappa_dot": 0.1}),
        "initial.kappa_dot", "must be 0", "got 0.1"),
    bad("reduced model with cavitation",
        edited(PHYSICAL, model={"equations": "reduced"}, cavitation={"model": "jfo"}),
        "cavitation.model", "'full'"),
    bad("an angular rate in hertz (pint reads 1 Hz as 1 rad/s)", edited(PHYSICAL, initial={"omega_b": "1 Hz"}),
        "initial.omega_b", "ambiguous", "rad/s (or rpm)"),
]


@pytest.mark.parametrize(("scene", "words"), BAD)
def test_bad_scenes_name_the_key_and_the_allowed_range(scene, words):
    with pytest.raises(SceneError) as info:
        parse_scene(scene)
    for word in words:
        assert word in str(info.value)


def test_the_smallest_rtol_a_scene_takes_is_the_one_a_run_takes():
    from dynamics.app.run import run_scene

    smallest = 100 * sys.float_info.epsilon
    tiny_run = {"rtol": smallest, "t_end_tau": 1e-6}
    trajectory = run_scene(parse_scene(edited(GROUPS, run=tiny_run)))
    assert trajectory.status == "completed"
    with pytest.raises(SceneError, match=r"run\.rtol must be in \[2\.22045e-14, 0\.1\]"):
        parse_scene(edited(GROUPS, run={**tiny_run, "rtol": math.nextafter(smallest, 0.0)}))


def test_errors_come_from_toml_text_too():
    text = '[apparatus]\npreset = "steel"\n[incline]\nalpha = "2.4 kg"\n[run]\nt_end = 1.0\n'
    with pytest.raises(SceneError, match=r"incline\.alpha = '2\.4 kg' has the unit kilogram"):
        parse_scene(text)
    with pytest.raises(SceneError, match="not valid TOML"):
        parse_scene("[apparatus\n")


def test_groups_for_the_reduced_model_are_dimensionless():
    scene = parse_scene(GROUPS)
    assert scene.dimensionless and scene.apparatus is None and scene.tau == 1.0
    assert scene.groups == Groups(s=0.5, upsilon=1.0, mu_ratio=1.0)
    assert scene.run.t_end == scene.t_end_tau == 50.0


@pytest.mark.parametrize("equations", ["full", "auto"])
def test_groups_for_the_full_model_build_an_apparatus(equations):
    groups = {"s": 0.3, "upsilon": 2.0, "mu": 2.0, "delta_over_a": 0.05}
    scene = parse_scene(edited(GROUPS, groups=groups, model={"equations": equations}))
    assert scene.model.equations == equations and not scene.dimensionless  # auto: chosen by the run
    assert isinstance(scene.apparatus, Apparatus)
    given = Groups(s=0.3, upsilon=2.0, mu_ratio=2.0, delta_over_a=0.05)
    for name in ("s", "upsilon", "mu_ratio", "delta_over_a"):
        assert getattr(scene.groups, name) == pytest.approx(getattr(given, name), rel=1e-12)
    assert scene.run.t_end == pytest.approx(50.0 * scene.apparatus.tau)


def test_auto_equations_without_a_gap_ratio_are_the_reduced_model():
    scene = parse_scene(edited(GROUPS, model={"equations": "auto"}))
    assert scene.model.equations == "reduced" and scene.dimensionless


def test_contact_converts_the_physical_gap_and_friction_angle():
    contact = {"sigma": "50 um", "friction_angle": "5 deg", "roughness_amplitude": 0.2,
               "roughness_correlation": "1 mm", "seed": 7}
    scene = parse_scene(edited(PHYSICAL, contact=contact))
    app, contact = scene.apparatus, scene.contact
    assert contact.kappa_star == pytest.approx(1.0 - 50e-6 / app.delta)  # kappa* = 1 - sigma/delta
    # tan psi = (a/delta) tan psi_hat (section 5)
    assert math.tan(contact.psi) == pytest.approx(math.tan(math.radians(5.0)) * app.a / app.delta)
    assert (contact.roughness_amplitude, contact.roughness_correlation, contact.seed) == (0.2, 1e-3, 7)


def test_cavitation_section_is_parsed_with_defaults():
    scene = parse_scene(edited(PHYSICAL, cavitation={"model": "swift-stieber", "p_cav": "0.1 bar"}))
    assert scene.cavitation == Cavitation(model="swift-stieber", p_cav=1e4)


def test_cavitation_at_the_reference_pressure_is_a_scene():
    """p_cav = p_ref: the textbook half-Sommerfeld and Swift-Stieber films, cut at the ambient pressure."""
    scene = parse_scene(edited(PHYSICAL, cavitation={"model": "half-sommerfeld", "p_cav": "1 atm", "p_ref": "1 atm"}))
    assert scene.cavitation.p_cav == scene.cavitation.p_ref == 101325.0


def test_overrides_replace_values_and_their_alternatives():
    scene = load_scene(overrides=["initial.kappa=0.3", "fluid.nu=500 cSt", "model.forces=reynolds",
                                  "model.n=32", "run.t_end_tau=100", "contact.kappa_star=0.99"])
    assert scene.initial.kappa == 0.3 and scene.apparatus.nu == pytest.approx(5e-4)
    assert (scene.model.forces, scene.model.n) == ("reynolds", 32)
    assert scene.t_end_tau == pytest.approx(100.0)
    assert scene.contact == Contact(kappa_star=0.99)
    assert parse_scene(GROUPS, overrides=["groups.s=0.2"]).groups.s == 0.2


@pytest.mark.parametrize(("override", "words"), [
    ("initial.kappa", ["'initial.kappa'", "section.key=value"]),
    ("kappa=0.3", ["'kappa=0.3'", "section.key=value"]),
    ("initial.kappa=1.5", ["initial.kappa", "[0, 1)"]),
    ("initial.colour=red", ["initial.colour", "allowed keys in [initial]"]),
    ("colour.red=1", ["[colour]", "allowed sections"]),
    ("groups.s=0.2", ["groups.s", "either [groups]"]),
    ("fluid.nu=fast", ["fluid.nu", "'fast'", "[1e-09, 1000] m^2/s"]),
    ("initial.kappa=0.3\nphi = 9", ["spans lines", "one section.key=value"]),
])
def test_bad_overrides_are_refused(override, words):
    with pytest.raises(SceneError) as info:
        load_scene(overrides=[override])
    for word in words:
        assert word in str(info.value)


def test_overrides_as_a_mapping_are_the_parsed_values_of_the_strings():
    texts = ["initial.kappa=0.3", "fluid.nu=500 cSt", "model.forces=reynolds", "model.n=32",
             "run.t_end_tau=100", "contact.kappa_star=0.99"]
    values = {"initial.kappa": 0.3, "fluid.nu": "500 cSt", "model.forces": "reynolds", "model.n": 32,
              "run.t_end_tau": 100, "contact.kappa_star": 0.99}
    assert load_scene(overrides=values) == load_scene(overrides=texts)
    with pytest.raises(SceneError, match="'kappa=0.3' must have the form section.key=value"):
        load_scene(overrides={"kappa": 0.3})
    with pytest.raises(SceneError, match="initial.kappa must be in"):
        load_scene(overrides={"initial.kappa": 1.5})
    with pytest.raises(SceneError, match="model.n must be an integer"):
        load_scene(overrides={"model.n": "32"})  # a value is not parsed again


def test_load_scene_reads_a_file_and_records_its_path(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(resolved_toml(load_scene()), encoding="utf-8")
    scene = load_scene(path, overrides=["initial.phi=1.0"])
    assert scene.source == str(path) and scene.initial.phi == 1.0
    with pytest.raises(SceneError, match="cannot read the scene file"):
        load_scene(tmp_path / "missing.toml")


ROUND_TRIP = {
    "default": None,
    "groups, reduced": GROUPS,
    "groups, full": edited(GROUPS, groups={"mu": 2.0, "delta_over_a": 0.1}, model={"equations": "full"}),
    "aluminium, everything": {
        "apparatus": {"preset": "aluminium", "rho_a": "2.7 g/cm^3", "m_f_ends": "4 g"},
        "fluid": {"nu": "500 cSt", "rho": "0.96 g/cm^3"},
        "incline": {"alpha": "5 deg", "g": 9.81},
        "initial": {"kappa": 0.2, "phi": "-30 deg", "kappa_dot": "0.1 / s", "omega_a": "10 rpm"},
        "model": {"forces": "reynolds", "n": 64, "grid": "uniform", "tolerance": 1e-3},
        "contact": {"sigma": "0.3 mm", "friction_angle": "3 deg", "roughness_amplitude": 0.1,
                    "roughness_correlation": "2 mm", "seed": 11},
        "cavitation": {"model": "jfo", "p_cav": "0.2 atm", "p_ref": "1 atm"},
        "run": {"t_end_tau": 300.0, "rtol": 1e-6},
    },
}


@pytest.mark.parametrize("name", ROUND_TRIP)
def test_resolved_toml_round_trips(name):
    scene = load_scene() if ROUND_TRIP[name] is None else parse_scene(ROUND_TRIP[name])
    text = resolved_toml(scene)
    again = parse_scene(text)
    assert again == scene and again.dimensionless == scene.dimensionless
    assert resolved_toml(again).splitlines()[1:] == text.splitlines()[1:]


def test_a_byte_order_mark_is_not_part_of_the_scene(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_bytes("\ufeff".encode() + resolved_toml(load_scene()).encode())
    assert load_scene(path) == load_scene()


def test_quantities_read_before_convert_without_pint_and_equal_what_pint_gives(tmp_path, monkeypatch):
    from numerics import units

    monkeypatch.setenv("SNAIL_CACHE", str(tmp_path))
    units._memo.cache_clear()
    first = units.to_si("200 cSt", "[length] ** 2 / [time]")
    stored = json.loads((tmp_path / "units.json").read_text())
    assert stored["si"] == {"200 cSt|[length] ** 2 / [time]": first}
    # a later process reads the memo; a wrong value planted there shows it is used without pint
    stored["si"]["200 cSt|[length] ** 2 / [time]"] = 1.0
    (tmp_path / "units.json").write_text(json.dumps(stored))
    units._memo.cache_clear()
    assert units.to_si("200 cSt", "[length] ** 2 / [time]") == 1.0
    # ... but only under the pint version that wrote it
    stored["pint"] = "0.0"
    (tmp_path / "units.json").write_text(json.dumps(stored))
    units._memo.cache_clear()
    assert units.to_si("200 cSt", "[length] ** 2 / [time]") == first == pytest.approx(2e-4, rel=1e-15)
    units._memo.cache_clear()
