"""The ``snail`` command: its JSON contract, negative numbers, and exit status 2 on bad input."""

import json
import subprocess
import sys

import pytest

from dynamics.app.cli import main

from apparatus import CLI_GEOMETRY



def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_forces_json_has_the_contract_keys(capsys):
    code, out, _ = run(capsys, "forces", "--model", "reynolds", *CLI_GEOMETRY, "--kappa", "0.9",
                       "--omega-a", "1", "--json")
    assert code == 0
    data = json.loads(out)
    for key in ("model", "f_eps", "f_chi", "T_a", "wall_time_s"):
        assert key in data
    assert data["model"] == "reynolds" and data["f_chi"] > 0 and data["T_a"] < 0


def test_all_models_with_relative_differences(capsys):
    code, out, _ = run(capsys, "forces", "--model=all", *CLI_GEOMETRY, "--kappa", "0.5", "--eps-dot", "-1e-6",
                       "--chi-dot", "-2.5E-1", "--omega-b", "-.5", "--json")
    assert code == 0
    data = json.loads(out)
    names = [m["model"] for m in data["models"]]
    assert names[:2] == ["closed-form", "reynolds"] and data["reference"] == names[-1]
    closed, numeric = data["models"][:2]
    assert closed["f_eps"] > 0  # the gap opens as eps' < 0: the fluid pulls the cylinder back
    # the Reynolds solver reproduces the closed forms; Stokes, if installed, differs at finite delta/a
    for name in ("f_eps", "f_chi", "T_a"):
        assert abs(closed[name] - numeric[name]) <= 1e-12 * max(abs(closed["f_eps"]), abs(closed["f_chi"]),
                                                               abs(closed["T_a"]))


def test_negative_numbers_in_scientific_notation_are_values(capsys):
    code, out, _ = run(capsys, "forces", *CLI_GEOMETRY, "--kappa", "0.5", "--eps-dot", "-1e-6", "--json")
    assert code == 0 and json.loads(out)["f_eps"] > 0


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--a", "0.02", "--b", "0.01", "--kappa", "0.5"], "b must be greater than a"),
        ([*CLI_GEOMETRY, "--kappa", "1"], "kappa must be in [0, 1)"),
        ([*CLI_GEOMETRY, "--kappa", "0.5", "--nu", "-1e-4"], "nu must be in (0, inf)"),
        ([*CLI_GEOMETRY, "--kappa", "0.5", "--rho", "0"], "rho must be in (0, inf)"),
        ([*CLI_GEOMETRY, "--kappa", "nan"], "not a finite number: 'nan'"),
        ([*CLI_GEOMETRY, "--kappa", "0.5", "--p-ref", "nan"], "not a finite number: 'nan'"),
        ([*CLI_GEOMETRY, "--kappa", "0.5", "--model", "reynolds", "--n", "3"], "n must be an integer in [8, 1048576], got 3"),
        ([*CLI_GEOMETRY, "--kappa", "abc"], "not a finite number"),
        ([*CLI_GEOMETRY, "--kappa", "0.5", "--model", "magic"], "invalid choice"),
        ([*CLI_GEOMETRY], "required: --kappa"),
    ],
)
def test_bad_input_exits_2_with_a_message_and_no_traceback(capsys, args, words):
    with pytest.raises(SystemExit) as exc:  # argparse's own errors exit from inside
        sys.exit(main(["forces", *args]))
    out, err = capsys.readouterr()
    assert exc.value.code == 2
    assert words in err
    assert "Traceback" not in err and out == ""


def test_console_script_entry_point_and_validate_registration():
    """The installed command reads the subcommands registered by `validation`."""
    proc = subprocess.run([sys.executable, "-m", "dynamics.app.cli", "--help"], capture_output=True, text=True,
                          check=False)
    assert proc.returncode == 0
    for command in ("forces", "run", "sweep", "validate", "corrections"):
        assert command in proc.stdout


@pytest.mark.slow
def test_validate_quick_writes_the_report(tmp_path, capsys):
    """Every quick group end to end (about three minutes when the kernels compile afresh)."""
    out_dir = tmp_path / "report"
    code, out, _ = run(capsys, "validate", "--quick", "-o", str(out_dir))
    assert code == 0, out
    checks = json.loads((out_dir / "validation.json").read_text())
    assert checks and all({"name", "measured", "reference", "tolerance", "passed"} <= set(c) for c in checks)
    assert all(c["passed"] for c in checks)
    assert "Validation report" in (out_dir / "report.md").read_text()
    assert not list(out_dir.glob(".*.tmp"))  # nothing half-written left behind


class _FailingGroup:
    """A group of one comparison that fails: 2 measured against at most 1."""

    @staticmethod
    def run(outdir, quick):
        from validation.checks import at_most

        return [at_most("a bound this group breaks", 2.0, 1.0)], [], "One failing comparison."


def test_validate_writes_the_report_and_fails_on_a_failed_comparison(tmp_path, capsys, monkeypatch):
    """The command's own path (report, exit status, nothing half-written) with two groups standing in for all."""
    from validation import suite
    from validation.reports import lubrication_checks

    monkeypatch.setattr(suite, "GROUPS", {"Reynolds solver against the lubrication closed forms": lubrication_checks})
    code, out, _ = run(capsys, "validate", "--quick", "-o", str(tmp_path / "passing"))
    assert code == 0, out
    checks = json.loads((tmp_path / "passing" / "validation.json").read_text())
    assert checks and all({"name", "measured", "reference", "tolerance", "passed"} <= set(c) for c in checks)
    assert all(c["passed"] for c in checks)
    assert "Validation report" in (tmp_path / "passing" / "report.md").read_text()
    assert not list((tmp_path / "passing").glob(".*.tmp"))

    monkeypatch.setitem(suite.GROUPS, "a failing group", _FailingGroup)
    code, out, _ = run(capsys, "validate", "--quick", "-o", str(tmp_path / "failing"))
    assert code == 1 and "FAILED: a bound this group breaks: measured 2" in out
    checks = json.loads((tmp_path / "failing" / "validation.json").read_text())
    assert [c["name"] for c in checks if not c["passed"]] == ["a bound this group breaks"]
    assert "**NO**" in (tmp_path / "failing" / "report.md").read_text()


def test_stokes_flow_field_is_written_for_paraview(tmp_path, capsys):
    meshio = pytest.importorskip("meshio")
    pytest.importorskip("skfem")
    code, out, _ = run(capsys, "forces", "--model", "stokes", *CLI_GEOMETRY, "--kappa", "0.5", "--omega-a", "1",
                       "--n-around", "64", "--n-across", "4", "--flow", str(tmp_path), "--json")
    assert code == 0 and json.loads(out)["model"] == "stokes"
    field = meshio.read(tmp_path / "flow.vtu")
    assert {"velocity", "pressure", "vorticity"} <= set(field.point_data)
    assert (tmp_path / "flow.png").stat().st_size > 10_000


def test_flow_without_stokes_is_refused(tmp_path, capsys):
    code, _, err = run(capsys, "forces", *CLI_GEOMETRY, "--kappa", "0.5", "--flow", str(tmp_path))
    assert code == 2 and "--flow draws the finite-element Stokes flow: it needs --model stokes" in err


def test_stokes_without_the_fem_extra_says_how_to_install_it(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "skfem", None)  # as if scikit-fem were not installed
    # a geometry no other test solved, so that no cached factorisation stands in for the import
    code, out, err = run(capsys, "forces", "--model", "stokes", *CLI_GEOMETRY, "--kappa", "0.3711")
    assert code == 2 and 'pip install "snail-cylinder[fem]"' in err and out == ""


def test_forces_with_cavitation(capsys):
    """Below the cavitation pressure the film ruptures: the JFO forces differ from the full film's."""
    args = ["forces", "--model", "reynolds", *CLI_GEOMETRY, "--kappa", "0.9", "--omega-a", "1", "--n", "256", "--json"]
    code, out, _ = run(capsys, *args, "--cavitation", "jfo", "--p-ref", "101325", "--p-cav", "101320")
    assert code == 0
    jfo = json.loads(out)
    code, out, _ = run(capsys, *args)
    full = json.loads(out)
    assert jfo["cavitation"] == "jfo" and abs(jfo["f_eps"] - full["f_eps"]) > 1e-3 * abs(full["f_chi"])


def test_all_models_report_each_component_against_its_own_size():
    """Near contact f_chi is a small component of the force: its difference is judged against itself."""
    from types import SimpleNamespace

    from dynamics.app.commands.forces import _relative_differences

    ref = SimpleNamespace(f_eps=1000.0, f_chi=1.0, T_a=2.0)
    other = SimpleNamespace(f_eps=1000.0, f_chi=1.33, T_a=2.0)
    assert _relative_differences(other, ref)["f_chi"] == pytest.approx(0.33)
    zero = SimpleNamespace(f_eps=5.0, f_chi=0.0, T_a=0.0)
    off = SimpleNamespace(f_eps=5.0, f_chi=1e-3, T_a=0.0)
    assert _relative_differences(off, zero)["f_chi"] == pytest.approx(2e-4)


@pytest.mark.parametrize(("args", "words"), [
    (["--model", "closed-form", "--cavitation", "jfo"], "--cavitation: cavitation is a rupture of the Reynolds "
                                                        "film: it needs the model 'reynolds', not 'closed-form'"),
    (["--model", "reynolds", "--cavitation", "jfo", "--p-ref", "-1"], "--p-ref must be in (0, inf) Pa"),
    (["--model", "reynolds", "--cavitation", "jfo", "--p-cav", "2e5"], "--p-cav must not exceed p_ref"),
    (["--model", "reynolds", "--p-ref", "2e5"], "--p-ref: p_ref goes with cavitation, which is 'none' here"),
])
def test_cavitation_options_are_checked(capsys, args, words):
    code, out, err = run(capsys, "forces", *CLI_GEOMETRY, "--kappa", "0.5", *args)
    assert code == 2 and words in err and out == ""


@pytest.mark.parametrize("cavitation", ["half-sommerfeld", "swift-stieber"])
def test_the_textbook_cut_at_the_reference_pressure_is_allowed(capsys, cavitation):
    """p_cav = p_ref, no margin: the classical half-Sommerfeld and Swift-Stieber films (lubrication.cavitation)."""
    code, out, err = run(capsys, "forces", *CLI_GEOMETRY, "--kappa", "0.5", "--omega-a", "1", "--model", "reynolds",
                         "--cavitation", cavitation, "--p-cav", "101325", "--p-ref", "101325", "--json")
    assert code == 0, err
    assert json.loads(out)["p_cav"] == json.loads(out)["p_ref"] == 101325


def test_a_gap_ratio_that_overflows_is_refused(capsys):
    code, _, err = run(capsys, "forces", "--a", "1e-300", "--b", "1e300", "--kappa", "0.5")
    assert code == 2 and "finite ratio b/a" in err


def test_version(capsys):
    from importlib.metadata import version

    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and version("snail-cylinder") in capsys.readouterr().out


@pytest.mark.parametrize("command", ["validate", "corrections"])
@pytest.mark.parametrize(("where", "words"), [
    ("", "must be a path"),
    ("/proc/snail-report", "cannot write outputs to /proc/snail-report"),
    ("file/inside", "is a file, not a folder"),
])
def test_report_folders_that_cannot_be_written_are_bad_input(tmp_path, capsys, command, where, words):
    """Refused before any check runs: exit 2, the path and the reason, nothing written."""
    (tmp_path / "file").write_text("not a folder")
    target = where if where.startswith("/") or not where else str(tmp_path / where)
    code, _, err = run(capsys, command, "--quick", "-o", target)
    assert code == 2 and words in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def _report(max_error, re_star, corrected=None):
    """An inertia report (dynamics.equations.limits.inertia_report) with the entries the warning reads."""
    report = {"max_estimated_force_error": max_error, "t_at_max_estimated_force_error": 0.03,
              "max_reduced_reynolds": re_star, "t_at_max_reduced_reynolds": 0.03,
              "estimated_force_error_at_max_reduced_reynolds": max_error}
    if corrected is not None:
        report["corrected_forces"] = {"max_estimated_force_error": corrected, "t_at_max_estimated_force_error": 0.02,
                                      "measured_to_reduced_reynolds": 30.0}
    return report


@pytest.mark.parametrize(("report", "expected"), [
    (_report(0.05, 0.8), ""),
    (_report(0.28, 4.9), "the quasi-steady Stokes forces may be in error by up to 28%"),
    (_report(0.28, 4.9, corrected=0.011), ""),
    (_report(2.2, 29.0, corrected=0.15), "the inertia-corrected forces may be in error by up to 15% (at t = 0.02 s)"),
    (_report(1.5, 31.0, corrected=0.09), "past Re* = 30, the largest at which the correction was compared"),
], ids=["plain, small", "plain, large", "corrected, small", "corrected, large", "corrected, past the comparisons"])
def test_inertia_warning_judges_the_forces_the_run_used(report, expected):
    """`snail run` warns of the inertial error of the forces it used: the plain forces' first-order
    error, or what the first inertial correction leaves and whether Re* went past its comparisons."""
    from dynamics.equations.limits import inertia_warning

    warning = inertia_warning(report)
    assert (expected in warning) if expected else warning == ""
    if "corrected_forces" in report and warning:
        assert "quasi-steady" not in warning
    if "quasi-steady" in warning:  # and it says what to do about it
        assert "model.inertia = 'first-order' adds their first inertial correction" in warning
