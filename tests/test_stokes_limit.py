"""The Stokes-number limit: the study's stored numbers, its page and package table, and the guard of every run.

The study (validation/stokes_limit.py) measures the x_b error of the quasi-steady models against coupled
Navier-Stokes runs at several viscosities; its conclusions are checks judged from the stored numbers, and the
slow test reruns its cheapest point. The guard (dynamics.equations.limits) is tested on runs: a device over
the limit is refused or flagged, the coupled run is not, and every run states the error its St implies.
"""

import json
import math
import warnings

import pytest

from dynamics import Initial, Limits, ValidityWarning, preset, simulate
from dynamics.equations import full, limits
from dynamics.scenes import SceneError, load_scene
from generators.stokes_error import DATA_FILE, stokes_error
from validation import stokes_limit as study
from validation.checks import verdict
from validation.reports import stokes_limit as report


@pytest.fixture(scope="module")
def stored():
    return json.loads(study.RESULTS.read_text())


def test_the_stored_numbers_carry_the_conclusions(stored):
    assert [f["label"] for f in stored["families"]] == [f.label for f in study.FAMILIES]
    for family, spec in zip(stored["families"], study.FAMILIES):
        assert [p["nu"] for p in family["points"]] == list(spec.viscosities)
        for p in family["points"]:
            assert p["horizon_s"] == pytest.approx(spec.horizon(p["nu"]), rel=1e-12)
    failed = [c.name for c in study.checks_of(stored) if not verdict(c.kind, c.measured, c.reference, c.tolerance)]
    assert not failed


def test_the_page_and_the_package_table_are_the_stored_numbers(stored):
    assert report.PAGE.read_text() == report.markdown(stored)
    assert json.loads(DATA_FILE.read_text()) == json.loads(json.dumps(stokes_error(stored)))


def test_the_spin_share_is_the_fluid_annulus_moment_of_inertia():
    """m_f (a^2 + b^2)/2 over itself plus (1/2) m_a a^2 + (M + m_b) b^2, from the device's numbers by hand."""
    ap = preset("aluminium")
    annulus = math.pi * (ap.b**2 - ap.a**2) * ap.length * ap.rho  # the fluid's mass, from its volume
    spin = annulus * (ap.a**2 + ap.b**2) / 2.0
    rolling = 0.5 * ap.m_a * ap.a**2 + (ap.m_a + ap.m_b + annulus + ap.m_f_ends + ap.m_b) * ap.b**2  # (M + m_b) b^2
    assert study.spin_share(ap) == pytest.approx(spin / (spin + rolling), rel=1e-12)


@pytest.mark.parametrize("spin", full.FLUID_SPIN)
def test_the_estimate_is_the_measured_error_between_and_beyond_the_points(stored, spin):
    """Each fluid spin's own errors, an error below the reference's own stated as that."""
    family = stored["families"][0]

    def error(point):
        return max(abs(point["models"]["paper"][spin]["x_b_relative"]), point["reference_error"])

    for p in family["points"]:
        got = limits.unsteady_error(p["stokes_number"], "paper", "rocking", spin)["estimated_x_b_error"]
        assert got == pytest.approx(error(p), rel=1e-12)
    first = family["points"][0]
    below = limits.unsteady_error(0.1 * first["stokes_number"], "paper", "rocking", spin)
    assert below["estimated_x_b_error"] == pytest.approx(error(first), rel=1e-12)
    a, b = family["points"][1:3]
    middle = math.sqrt(a["stokes_number"] * b["stokes_number"])  # halfway in log St
    assert limits.unsteady_error(middle, "paper", "rocking", spin)["estimated_x_b_error"] == pytest.approx(
        0.5 * (error(a) + error(b)), rel=1e-12)


def test_the_estimate_follows_the_regime_and_before_a_run_takes_the_larger():
    one = limits.unsteady_error(0.5)
    assert one["estimated_x_b_error"] == max(one["by_start"].values())
    rocking, runaway = (limits.unsteady_error(0.5, regime=r) for r in ("rocking", "runaway"))
    assert rocking["from_start"] == "release" and runaway["from_start"] == "runaway"
    assert rocking["estimated_x_b_error"] == rocking["by_start"]["release"]
    measured = json.loads(DATA_FILE.read_text())["families"]["release"]["paper"]["none"]
    assert limits.MEASURED_STOKES <= max(st for st, _ in measured)


def _fluid_with_stokes(stokes: float) -> float:
    """The viscosity (m^2/s) that gives the steel device on 2.4 degrees this Stokes number (St ~ 1/nu^2)."""
    ap = preset("steel")
    return ap.nu * math.sqrt(ap.delta**2 / (ap.nu * ap.tau) / stokes)


def test_a_device_past_the_limit_is_refused_or_flagged_and_past_the_measured_range_warned():
    stokes = 2.0 * limits.MEASURED_STOKES
    ap = preset("steel", nu=_fluid_with_stokes(stokes))
    assert ap.delta**2 / (ap.nu * ap.tau) == pytest.approx(stokes, rel=1e-12)
    start = Initial(kappa=0.5, phi=0.5)
    bound = limits.MEASURED_STOKES
    with pytest.raises(ValueError, match="exceeds max_stokes_number"):
        simulate(ap, start, 1e-3, limits=Limits(max_stokes_number=bound, max_gap_reynolds=None))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ValidityWarning)
        run = simulate(ap, start, 1e-3, limits=Limits(max_stokes_number=bound, on_invalid="warn"))
    passed = run.info["limits_passed"][0]
    assert (passed["name"], passed["t"]) == ("stokes", 0.0)
    assert any("max_stokes_number" in str(w.message) for w in caught)
    # no limit by default: the run goes on, and says that its St is past the measured range
    assert Limits().max_stokes_number is None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ValidityWarning)
        free = simulate(ap, start, 1e-3, limits=Limits(max_gap_reynolds=None))
    assert all(p["name"] != "stokes" for p in free.info.get("limits_passed", []))
    assert any("the largest measured" in str(w.message) for w in caught)
    unsteady = free.info["inertia"]["unsteady"]
    assert unsteady["stokes_number"] == pytest.approx(stokes, rel=1e-12)
    assert unsteady == limits.unsteady_error(unsteady["stokes_number"], full.DEFAULT_FRAME_TERMS, free.regime,
                                             full.DEFAULT_FLUID_SPIN)
    # a run states the error of its own model
    paper = simulate(ap, start, 1e-3, limits=Limits(max_gap_reynolds=None, on_invalid="warn"), frame_terms="paper",
                     fluid_spin="none")
    stated = paper.info["inertia"]["unsteady"]
    assert stated == limits.unsteady_error(stated["stokes_number"], "paper", paper.regime, "none")
    assert stated["estimated_x_b_error"] != unsteady["estimated_x_b_error"]


def test_scenes_take_the_limit_and_name_it_when_refused():
    scene = load_scene(None, ["run.max_stokes_number=3"])
    assert scene.run.limits.max_stokes_number == 3.0
    assert load_scene(None, ["run.max_stokes_number=none"]).run.limits.stokes == math.inf
    with pytest.raises(SceneError, match="run.max_stokes_number"):
        load_scene(None, ["run.max_stokes_number=-1"])


@pytest.mark.slow
def test_a_rerun_gives_the_stored_numbers(stored):
    """The release family's most viscous point, the cheapest: its errors again, within the reference's own."""
    family = study.FAMILIES[0]
    again = study.run_point(family, family.viscosities[0], log=lambda _: None)
    kept = stored["families"][0]["points"][0]
    for frame in study.FRAME_TERMS:
        for spin in full.FLUID_SPIN:
            assert again["models"][frame][spin]["x_b_relative"] == pytest.approx(
                kept["models"][frame][spin]["x_b_relative"], abs=kept["reference_error"] + 1e-9)
