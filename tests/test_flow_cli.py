"""``snail flow``: prescribed wall motions to forces.csv, summary.json and snapshots, against closed forms.

The references are independent of the solver: the steady circular Couette flow of the
inner wall spinning in the outer one at rest (torque 4 pi mu Omega a^2 b^2/(b^2 - a^2)
per unit length, uniform vorticity), reached after two viscous times delta^2/nu, where
the spin-up's slowest mode has decayed by exp(-2 pi^2) ~ 3e-9; and a rigid rotation of
both walls together, which leaves the fluid turning rigidly: no torque on either wall.
The runs are small (8 x 8 points: the concentric flows have the Fourier mode 0 only) and
short (two viscous times, 0.1 s).
"""

import dataclasses
import json
import math
import signal
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from dynamics.app.cli import main
from dynamics.app.flow_spec import load_motion, parse_motion

A, B, LENGTH, NU, RHO = 0.008, 0.01125, 0.1035, 2e-4, 1000.0  # the steel preset's
MU = RHO * NU
T_VISC = (B - A) ** 2 / NU  # 0.0528 s
SPIN = 1.0  # rad/s
COUETTE = 4.0 * math.pi * MU * SPIN * A * A * B * B / (B * B - A * A)  # N m per m
# the run's error: 8 Chebyshev points across give the steady torque to 4e-7, rtol 1e-4 of local
# error per step adds ~1e-7 (measured); the decay of the start, 3e-9
TORQUE_TOL = 1e-5


def motion_file(tmp_path: Path, motion: str, run: str = "", *, name: str = "motion.toml",
                t_end: float = 2.0 * T_VISC) -> Path:
    path = tmp_path / name
    path.write_text(f'[apparatus]\npreset = "steel"\n[run]\nt_end = {t_end!r}\nn_theta = 8\nn_r = 8\n{run}\n'
                    f"[motion]\n{motion}\n", encoding="utf-8")
    return path


def snail(capsys, *args):
    code = main(["flow", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


def read_csv(path: Path) -> tuple[list[str], np.ndarray]:
    lines = path.read_text().splitlines()
    return lines[0].split(","), np.loadtxt(lines[1:], delimiter=",", ndmin=2)


@pytest.fixture(scope="module")
def couette_run(tmp_path_factory):
    """The inner wall spun up from rest, with three snapshots; ``--json`` printed."""
    import contextlib
    import io

    tmp = tmp_path_factory.mktemp("couette")
    path = motion_file(tmp, f"omega_a = {SPIN}",
                       f"snapshot_times = [0.0, {T_VISC!r}, \"{2.0 * T_VISC!r} s\"]\nframe = \"outer\"")
    out = tmp / "out"
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        code = main(["flow", str(path), "-o", str(out), "--json"])
    return code, out, printed.getvalue()


def test_inner_spin_reaches_the_couette_torques_over_the_length(couette_run):
    code, out, _ = couette_run
    assert code == 0
    columns, data = read_csv(out / "forces.csv")
    assert columns == ["t", "x_a", "z_a", "F_x", "F_z", "T_a", "T_b"]
    last = dict(zip(columns, data[-1]))
    assert abs(last["t"] / (2.0 * T_VISC) - 1.0) < 1e-12
    # clockwise spin of the inner wall: the fluid holds it back (T_a < 0) and drags the outer one along
    assert abs(last["T_a"] / (-COUETTE * LENGTH) - 1.0) < TORQUE_TOL
    assert abs(last["T_b"] / (COUETTE * LENGTH) - 1.0) < TORQUE_TOL
    # concentric: no force at any time, whatever the spin-up (symmetry; rounding only)
    assert np.max(np.abs(data[:, 3:5])) < 1e-12 * COUETTE * LENGTH / A
    assert np.all(data[:, 1:3] == 0.0) and np.all(np.diff(data[:, 0]) > 0)


def test_summary_json_is_printed_and_says_what_ran(couette_run):
    code, out, printed = couette_run
    info = json.loads((out / "summary.json").read_text())
    assert json.loads(printed) == info
    assert info["status"] == "completed" and info["success"]
    assert info["t_end"] == info["t_end_requested"] == pytest.approx(2.0 * T_VISC, rel=1e-15)
    assert info["inputs"]["apparatus"] == {"preset": "steel", "a": A, "b": B, "length": LENGTH}
    assert info["inputs"]["fluid"] == {"nu": NU, "rho": RHO}
    assert info["inputs"]["motion"]["omega_a"] == {"mean": SPIN, "amplitude": 0.0, "omega": 0.0, "phase": 0.0}
    assert info["resolution"]["n_theta"] == 8 and info["resolution"]["n_r"] == 8
    assert info["steps"] > 10 and info["wall_time_s"] > 0.0
    # steady walls: Stokes number 0; the inner wall's speed a Omega is the largest: Re = a Omega delta/nu
    assert info["stokes_number"] == 0.0
    assert info["reynolds_number"] == pytest.approx(A * SPIN * (B - A) / NU, rel=1e-12)
    rows = len((out / "forces.csv").read_text().splitlines()) - 1
    assert rows == info["steps"] + 1  # the start and every accepted step


def test_snapshots_are_vtu_files_of_the_couette_flow_listed_by_the_collection(couette_run):
    meshio = pytest.importorskip("meshio")
    from PIL import Image

    _, out, _ = couette_run
    names = sorted(p.name for p in out.iterdir())
    assert names == ["flow.gif", "flow.pvd", "flow_0000.vtu", "flow_0001.vtu", "flow_0002.vtu", "forces.csv",
                     "summary.json"]
    rows = [(d.get("file"), float(d.get("timestep"))) for d in ET.parse(out / "flow.pvd").getroot().iter("DataSet")]
    assert [f for f, _ in rows] == ["flow_0000.vtu", "flow_0001.vtu", "flow_0002.vtu"]
    assert np.allclose([t for _, t in rows], [0.0, T_VISC, 2.0 * T_VISC], rtol=1e-12, atol=0)
    first, last = meshio.read(out / "flow_0000.vtu"), meshio.read(out / "flow_0002.vtu")
    assert last.points.shape == (64, 3) and last.cells_dict["quad"].shape == (7 * 8, 4)
    assert last.point_data["vorticity"].shape == (64,) and last.point_data["velocity"].shape == (64, 3)
    assert np.all(first.point_data["vorticity"] == 0.0)  # the fluid at rest at t = 0
    # steady Couette: uniform vorticity, clockwise -2 Omega a^2/(b^2 - a^2) (the flow turns counterclockwise
    # faster than rigidly near the inner wall); the inner wall moves at a Omega
    vorticity = -2.0 * SPIN * A * A / (B * B - A * A)
    assert np.allclose(last.point_data["vorticity"], vorticity, rtol=TORQUE_TOL)
    r = np.hypot(last.points[:, 0], last.points[:, 1])
    speed = np.linalg.norm(last.point_data["velocity"], axis=1)
    assert np.allclose(speed[np.isclose(r, A, rtol=1e-12)], A * SPIN, rtol=1e-12)
    with Image.open(out / "flow.gif") as gif:
        assert gif.n_frames == 3
    info = json.loads((out / "summary.json").read_text())
    assert info["snapshots"]["files"] == ["flow_0000.vtu", "flow_0001.vtu", "flow_0002.vtu"]
    assert info["snapshots"]["animation"] == "flow.gif" and info["snapshots"]["frame"] == "outer"


def test_a_rigid_rotation_of_both_walls_leaves_no_load(tmp_path, capsys):
    """omega_a = omega_b: once spun up, the fluid turns with the walls, and neither wall feels a torque."""
    path = motion_file(tmp_path, f"omega_a = {SPIN}\nomega_b = {{mean = {SPIN}}}")
    code, _, err = snail(capsys, path, "-o", tmp_path / "out")
    assert code == 0, err
    columns, data = read_csv(tmp_path / "out" / "forces.csv")
    last = dict(zip(columns, data[-1]))
    assert abs(last["T_a"]) < TORQUE_TOL * COUETTE * LENGTH and abs(last["T_b"]) < TORQUE_TOL * COUETTE * LENGTH
    assert np.max(np.abs(data[:, 3:5])) < 1e-12 * COUETTE * LENGTH / A


def test_the_loads_are_over_the_apparatus_length(tmp_path, capsys):
    """The same spin in a device of 1 m: the torque per unit length, the Couette value."""
    path = tmp_path / "long.toml"
    path.write_text(f'[apparatus]\na = {A}\nb = {B}\nlength = "1 m"\n[fluid]\nnu = "200 cSt"\nrho = 1000\n'
                    f"[run]\nt_end = {2.0 * T_VISC!r}\nn_theta = 8\nn_r = 8\n[motion]\nomega_a = {SPIN}\n")
    code, _, err = snail(capsys, path, "-o", tmp_path / "out")
    assert code == 0, err
    columns, data = read_csv(tmp_path / "out" / "forces.csv")
    assert abs(data[-1, columns.index("T_b")] / COUETTE - 1.0) < TORQUE_TOL
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["forces.csv", "summary.json"]


BAD = [
    ("unknown key", "omega_a = 1.0", "colour = 'red'",
     "unknown key run.colour; allowed keys in [run]: t_end, rtol, n_theta, n_r, snapshot_times, snapshot_interval"),
    ("negative viscosity", "omega_a = 1.0\n[fluid]\nnu = '-200 cSt'", "",
     "fluid.nu must be in [1e-09, 1000] m^2/s, got '-200 cSt' = -0.0002 m^2/s"),
    ("through the outer wall", "x_a = {amplitude = '4 mm', omega = '100 rad/s'}", "",
     "motion.x_a bring the inner wall through the outer wall (|A - B| = 0.004 m at t = 0.015708 s)"),
    ("narrower than the solver's reach", "z_a = '-3.24999 mm'", "",
     "motion.z_a bring the inner wall within 1 - kappa = 3.08e-06 of the outer wall"),
    ("unknown entry of a motion table", "omega_a = {mean = 1.0, frequency = 2.0}", "",
     "unknown entry motion.omega_a.frequency; a motion table has the entries mean, amplitude, omega, phase"),
    ("a frequency in hertz", "omega_b = {amplitude = 1.0, omega = '2 Hz'}", "",
     "motion.omega_b.omega = '2 Hz' is ambiguous"),
    ("a position with the wrong unit", "x_a = {amplitude = '1 s'}", "",
     "motion.x_a.amplitude = '1 s' has the unit second ([time]); expected the dimension [length]"),
    ("a motion given as a list", "x_a = [0.0, 0.001]", "", "motion.x_a must be a number, a string with units or a table"),
    ("a snapshot after t_end", "omega_a = 1.0", "snapshot_times = [0.05, 0.5]",
     "run.snapshot_times[1] must be in [0, run.t_end] = [0, 0.105625] s, got 0.5"),
    ("too many snapshots", "omega_a = 1.0", "snapshot_interval = '1 us'",
     "run.snapshot_interval must be in (0, run.t_end] = (0, 0.105625] s and give at most 1000 snapshots"),
    ("both snapshot keys", "omega_a = 1.0", "snapshot_interval = 0.01\nsnapshot_times = [0.01]",
     "run.snapshot_times and run.snapshot_interval say the same thing"),
    ("too coarse a grid", "omega_a = 1.0", "n_theta = 4",
     "run.n_theta must be in [8, 1024], or 'auto', got 4"),
    ("a grid whose factorisation fills the memory", "omega_a = 1.0", "n_theta = 1024\nn_r = 64",
     "run.n_theta = 1024 and run.n_r = 64 need 2.42 GB for each factorisation"),
    ("an unknown frame", "omega_a = 1.0", "frame = 'inner'", "run.frame must be one of 'lab', 'outer', got 'inner'"),
    ("an unknown section", "omega_a = 1.0\n[incline]\nalpha = 0.1", "",
     "unknown section [incline]; allowed sections of a motion file: [apparatus], [fluid], [run], [motion]"),
]


@pytest.mark.parametrize(("motion", "run", "words"), [case[1:] for case in BAD], ids=[case[0] for case in BAD])
def test_bad_motion_files_exit_2_naming_the_key_and_write_nothing(tmp_path, capsys, motion, run, words):
    # n_theta and n_r are given once by motion_file; a case that sets its own replaces them
    path = motion_file(tmp_path, motion, run)
    for name in ("n_theta", "n_r"):
        if name in run:
            path.write_text(path.read_text().replace(f"{name} = 8\n", "", 1))
    code, out, err = snail(capsys, path, "-o", tmp_path / "out")
    assert code == 2, err
    assert words in err and err.startswith("snail flow: error: ") and "Traceback" not in err and not out
    assert not (tmp_path / "out").exists() and not list(tmp_path.glob(".out*staging*"))


@pytest.mark.parametrize(("text", "words"), [
    ('[apparatus]\npreset = "steel"\n[motion]\nomega_a = 1.0\n', "run.t_end is missing: a motion file says how long "
                                                               "the walls move (run.t_end in (0, inf) s)"),
    ('[apparatus]\npreset = "steel"\n[run]\nt_end = 0.1\n', "[motion] is missing"),
    ('[apparatus]\na = 0.01\nb = "9 mm"\nlength = 0.1\n[fluid]\nnu = 1e-4\nrho = 900\n[run]\nt_end = 0.1\n'
     "[motion]\n", "apparatus.b = '9 mm' must be in (a, inf) = (0.01, inf) m"),
    ('[apparatus]\na = 0.01\nb = 0.02\n[run]\nt_end = 0.1\n[motion]\n',
     "apparatus.length, fluid.nu, fluid.rho are missing: without apparatus.preset"),
    ('[apparatus]\npreset = "steel"\nm_a = 0.158\n[run]\nt_end = 0.1\n[motion]\n',
     "unknown key apparatus.m_a; allowed keys in [apparatus]: preset, a, b, length (a prescribed motion needs no masses)"),
    ("[run\n", "is not valid TOML"),
], ids=["missing t_end", "missing motion", "b below a", "missing length and fluid", "a mass", "not TOML"])
def test_incomplete_motion_files_exit_2_naming_what_is_missing(tmp_path, capsys, text, words):
    path = tmp_path / "motion.toml"
    path.write_text(text, encoding="utf-8")
    code, _, err = snail(capsys, path, "-o", tmp_path / "out")
    assert code == 2 and words in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_a_missing_file_and_a_folder_of_other_files_are_bad_input(tmp_path, capsys):
    code, _, err = snail(capsys, tmp_path / "none.toml", "-o", tmp_path / "out")
    assert code == 2 and "cannot read the motion file" in err
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "notes.txt").write_text("precious")
    code, _, err = snail(capsys, motion_file(tmp_path, "omega_a = 1.0"), "-o", tmp_path / "full")
    assert code == 2 and "holds files that are not a run's outputs (notes.txt)" in err
    assert (tmp_path / "full" / "notes.txt").read_text() == "precious"


def test_a_second_run_replaces_the_set_whole(tmp_path, capsys):
    out = tmp_path / "out"
    with_snapshots = motion_file(tmp_path, "omega_a = 1.0", "snapshot_times = [0.0]\nanimation = 'none'",
                                 t_end=0.1 * T_VISC)
    assert snail(capsys, with_snapshots, "-o", out)[0] == 0
    assert sorted(p.name for p in out.iterdir()) == ["flow.pvd", "flow_0000.vtu", "forces.csv", "summary.json"]
    assert snail(capsys, motion_file(tmp_path, "omega_b = 1.0", name="other.toml", t_end=0.1 * T_VISC), "-o", out)[0] == 0
    assert sorted(p.name for p in out.iterdir()) == ["forces.csv", "summary.json"]
    assert json.loads((out / "summary.json").read_text())["inputs"]["motion"]["omega_b"]["mean"] == 1.0
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".out.") and not p.name.endswith(".lock")]


class _Signaller:
    """A progress bar that sends ``signum`` to this process once the run passes ``t_stop``."""

    def __init__(self, signum: int, t_stop: float):
        self.signum, self.t_stop, self.sent = signum, t_stop, False

    def __call__(self, t):
        if t > self.t_stop and not self.sent:
            self.sent = True
            signal.raise_signal(self.signum)

    def close(self):
        pass


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["ctrl-c", "sigterm"])
def test_an_interrupted_run_writes_what_it_computed_and_exits_1(tmp_path, capsys, monkeypatch, ctrl_c, signum):
    bar = _Signaller(signum, 0.3 * T_VISC)
    monkeypatch.setattr("dynamics.app.commands.flow.progress_bar", lambda *args: bar)
    path = motion_file(tmp_path, "omega_a = 1.0", "snapshot_interval = '0.01 s'\nanimation = 'none'")
    code, out, err = snail(capsys, path, "-o", tmp_path / "out")
    assert code == 1 and bar.sent and "Traceback" not in err
    info = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert info["status"] == "interrupted" and not info["success"]
    assert f"interrupted by {signal.Signals(signum).name} at t = " in info["reason"]
    assert 0.3 * T_VISC < info["t_end"] < 2.0 * T_VISC
    _, data = read_csv(tmp_path / "out" / "forces.csv")
    assert data[-1, 0] == info["t_end"] and len(data) == info["steps"] + 1
    # the snapshots up to the stop, and their files
    assert info["snapshots"]["times"] == pytest.approx([0.01 * i for i in range(info["snapshots"]["count"])])
    assert len(info["snapshots"]["files"]) == info["snapshots"]["count"] >= 2
    assert info["status"] in out


def test_ctrl_c_while_the_snapshots_are_written_leaves_them_out(tmp_path, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr("lubrication.unsteady.snapshots.animate", interrupted)
    path = motion_file(tmp_path, "omega_a = 1.0", "snapshot_times = [0.0]", t_end=0.1 * T_VISC)
    code, _, _ = snail(capsys, path, "-o", tmp_path / "out")
    assert code == 1
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["forces.csv", "summary.json"]
    info = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert info["status"] == "interrupted" and "while writing the snapshots" in info["reason"]
    assert info["t_end"] == pytest.approx(0.1 * T_VISC) and info["snapshots"]["files"] == []


def test_a_failed_step_keeps_the_steps_before_it_and_exits_1(tmp_path, capsys, monkeypatch):
    from lubrication.unsteady import UnsteadySolver

    step = UnsteadySolver.step

    def failing(self, *args, **kwargs):
        if self.counters.steps >= 5:
            raise FloatingPointError("overflow encountered")
        return step(self, *args, **kwargs)

    monkeypatch.setattr(UnsteadySolver, "step", failing)
    code, _, _ = snail(capsys, motion_file(tmp_path, "omega_a = 1.0"), "-o", tmp_path / "out")
    assert code == 1
    info = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert info["status"] == "failed" and info["reason"].startswith("FloatingPointError at t = ")
    assert info["steps"] == 5 and len(read_csv(tmp_path / "out" / "forces.csv")[1]) == 6


def test_the_example_is_documented_printed_and_valid(capsys):
    with pytest.raises(SystemExit):
        main(["flow", "--help"])
    help_text = capsys.readouterr().out
    assert "Without MOTION, runs the shipped example" in help_text and "--example" in help_text
    code, out, _ = snail(capsys, "--example")
    assert code == 0 and out.startswith("# The example motion of `snail flow`")
    shipped = load_motion()
    assert parse_motion(out) == dataclasses.replace(shipped, source="<string>")
    assert shipped.snapshot_times[0] == 0.0 and len(shipped.snapshot_times) == 51 and shipped.animation == "gif"


@pytest.mark.slow
def test_the_example_runs(tmp_path, capsys):
    code, out, err = snail(capsys, "-o", tmp_path / "out")
    assert code == 0, err
    info = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert info["status"] == "completed" and info["snapshots"]["count"] == 51
    assert (tmp_path / "out" / "flow.gif").stat().st_size > 0
