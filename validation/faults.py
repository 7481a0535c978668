"""Bad input and faults: what was tried, and what each gets.

Every case is run for real: the command line through :func:`dynamics.app.cli.main`
(its exit status and the message on standard error), the Python API through the
call (the exception and its message). A case passes when the status (or the
exception type) is the expected one, the message carries the expected words, no
traceback is printed and, for the command line, nothing is left in the output
folder. :func:`validation.reports.faults.table` renders the catalogue as the markdown table stored in
``docs/faults.md`` (``python -m validation.reports.faults``), with the temporary folders
written as ``<tmp>``; ``tests/test_faults.py`` runs every case and checks that the
stored table is the one the cases give now.

Faults that need a second process (two runs into one folder, Ctrl-C, a second
Ctrl-C, SIGTERM, Ctrl-C in a sweep) are exercised by ``tests/test_run_outputs.py``
and ``tests/test_sweep.py`` and listed in
:data:`PROCESS_FAULTS` with what each gets.
"""

from __future__ import annotations

import contextlib
import io
import math
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

__all__ = ["CASES", "PROCESS_FAULTS", "Case", "Outcome", "run_case"]

GEOMETRY = ("--a", "0.008", "--b", "0.01125")


@dataclass(frozen=True)
class Case:
    """One thing a user might do wrong: ``argv`` for the command line, or ``call`` for the API."""

    what: str
    expected: str  # "exit 2", "exit 0", or an exception type name
    words: tuple[str, ...]
    argv: tuple[str, ...] = ()
    call: object = None
    scene: str = ""  # TOML written to a file named by "{scene}" in argv
    sweep: str = ""  # TOML written to a file named by "{sweep}" in argv


def _api(name):
    def call():
        from dynamics import Initial, Limits, preset, simulate
        from lubrication import Annulus, Fluid, Motion

        steel = preset("steel")
        if name == "a length as a string":
            Annulus(a="0.008", b=0.01125)
        elif name == "a rate as a string":
            Motion(chi_dot="1")
        elif name == "rate 1e308":
            Motion(chi_dot=1e308)
        elif name == "finite elements near contact":
            from lubrication import fluid_forces
            fluid_forces(Annulus.from_kappa(0.008, 0.01125, 1.0 - 1e-9), Motion(-1e-5, 0.2, 1.0, 0.0),
                         Fluid(nu=2e-4, rho=960.0), "stokes")
        elif name == "exact forces":
            from lubrication import stokes_exact_forces
            stokes_exact_forces(Annulus.from_kappa(0.008, 0.01125, 0.5), Motion(-1e-5, 0.2, 1.0, 0.0),
                                Fluid(nu=2e-4, rho=960.0))
        elif name == "a density as a string":
            Fluid(nu=2e-4, rho="960")
        elif name == "max_steps 0":
            simulate(steel, Initial(0.5), 1.0, max_steps=0)
        elif name == "t_eval with nan":
            simulate(steel, Initial(0.5), 1.0, t_eval=[0.0, math.nan, 1.0])
        elif name == "progress 3":
            simulate(steel, Initial(0.5), 1.0, progress=3)
        elif name == "output interval 1e-9":
            simulate(steel, Initial(0.5), 10.0, output_interval=1e-9)
        elif name == "gravity 1e300":
            preset("steel", nu=2e-4, g=1e300)
        elif name == "negative t_end":
            simulate(steel, Initial(0.5), -1.0)
        elif name == "kappa 1.5":
            Initial(kappa=1.5)
        elif name == "kappa nan":
            Initial(kappa=math.nan)
        elif name == "start beyond the gap floor":
            simulate(steel, Initial(one_minus_kappa=1e-10), 1.0)
        elif name == "bad method":
            simulate(steel, Initial(0.5), 1.0, method="RK45")
        elif name == "gap floor 2":
            Limits(gap_floor=2.0)
        elif name == "on_invalid ignore":
            Limits(on_invalid="ignore")
    return call


#: A sweep of two points, for the cases that must be refused before it runs.
_SWEEP = """[base]
apparatus = {preset = "steel"}
run = {t_end = 0.01}
[axes]
"initial.kappa" = {start = 0.1, stop = 0.5, num = 2}
"initial.phi" = {start = 0.1, stop = 0.5, num = 2}
"initial.omega_a" = {start = 0.0, stop = 1.0, num = 2}
"""

CASES: tuple[Case, ...] = (
    Case("scene: unknown key", "exit 2", ("initial.colour", "allowed keys"), ("run", "--set", "initial.colour=red")),
    Case("scene: kappa0 = 1", "exit 2", ("initial.kappa", "[0, 1)"), ("run", "--set", "initial.kappa=1.0")),
    Case("scene: start within 1e-10 of contact (beyond the gap floor)", "exit 2",
         ("initial.kappa", "gap floor"), ("run", "--set", "initial.kappa=0.9999999999")),
    Case("scene: negative viscosity", "exit 2", ("fluid.nu", "[1e-09, 1000] m^2/s"), ("run", "--set", "fluid.nu=-200 cSt")),
    Case("scene: wrong unit", "exit 2", ("incline.alpha", "unit"), ("run", "--set", "incline.alpha=2 kg")),
    Case("scene: gap floor out of range", "exit 2", ("run.gap_floor", "(0, 1)"), ("run", "--set", "run.gap_floor=2")),
    Case("scene: negative Reynolds limit", "exit 2", ("run.max_gap_reynolds", "(0, inf)", "'none'"),
         ("run", "--set", "run.max_gap_reynolds=-1")),
    Case("scene: unknown on_invalid", "exit 2", ("run.on_invalid", "'stop', 'warn'"),
         ("run", "--set", "run.on_invalid=ignore")),
    Case("scene: output interval longer than the run", "exit 2", ("run.output_interval",),
         ("run", "--t-end", "1", "--output-interval", "5 s")),
    Case("scene: output interval giving more rows than run.max_rows", "exit 2", ("would write", "run.max_rows"),
         ("run", "--t-end", "1000", "--output-interval", "1 ms")),
    Case("scene: initial spin past the Reynolds limit", "exit 2", ("Re* =", "run.max_gap_reynolds", "'warn'"),
         ("run", "--set", "initial.omega_b=2000", "--set", "run.on_invalid=stop")),
    Case("scene: Reynolds grid of 8 cells uniform in theta (forces wrong near contact)", "exit 1",
         ("resolve the film", "only to kappa = 0.557", "'sommerfeld'"),
         ("run", "--t-end", "2", "--set", "model.forces=reynolds", "--set", "model.grid=uniform", "--set",
          "model.n=8", "--set", "run.max_gap_reynolds=none", "--set", "run.on_invalid=stop")),
    Case("scene: open ends in the reduced equations", "exit 2", ("model.ends", "full"),
         ("run", "--model", "reduced", "--set", "model.ends=open")),
    Case("scene: Reynolds forces in the reduced equations", "exit 2", ("model.forces", "'closed-form' or 'auto'"),
         ("run", "--model", "reduced", "--forces", "reynolds")),
    Case("scene file with a UTF-8 byte-order mark", "exit 0", ("reached t_end",), ("run", "{scene}", "--t-end", "0.1"),
         scene="\ufeff[apparatus]\npreset = \"steel\"\n[run]\nt_end = 1.0\n"),
    Case("scene file that is not TOML", "exit 2", ("not valid TOML",), ("run", "{scene}"), scene="[apparatus\n"),
    Case("output folder: empty path", "exit 2", ("must be a path",), ("run", "-o", "")),
    Case("output folder: in /proc", "exit 2", ("cannot write outputs to /proc/snail",), ("run", "-o", "/proc/snail")),
    Case("output folder: through a file", "exit 2", ("is a file, not a folder",), ("run", "-o", "{file}/out")),
    Case("output folder: holds other files", "exit 2", ("not a run's outputs",), ("run", "-o", "{full}")),
    Case("report folder of snail validate: in /proc", "exit 2", ("cannot write outputs to /proc/snail",),
         ("validate", "--quick", "-o", "/proc/snail")),
    Case("report folder of snail corrections: through a file", "exit 2", ("is a file, not a folder",),
         ("corrections", "--quick", "-o", "{file}/out")),
    Case("scene: gravity 1e300 (crashed the process: its groups overflow)", "exit 2", ("incline.g", "[0.001, 10000]"),
         ("run", "--set", "incline.g=1e300")),
    Case("scene: viscosity 1e-300", "exit 2", ("fluid.nu", "[1e-09, 1000] m^2/s"), ("run", "--set", "fluid.nu=1e-300")),
    Case("scene: viscosity 1e300", "exit 2", ("fluid.nu", "[1e-09, 1000] m^2/s"), ("run", "--set", "fluid.nu=1e300")),
    Case("scene: length 1e-300 m", "exit 2", ("apparatus.length", "[1e-06, 10] m"),
         ("run", "--set", "apparatus.length=1e-300")),
    Case("scene: inner density 1e30 kg/m^3", "exit 2", ("apparatus.rho_a", "[0.01, 100000] kg/m^3"),
         ("run", "--set", "apparatus.rho_a=1e30")),
    Case("scene: inner mass 1e200 kg", "exit 2", ("apparatus.m_a", "[1e-12, 1e+06] kg"),
         ("run", "--set", "apparatus.m_a=1e200")),
    Case("scene: initial spin 1e200 rad/s", "exit 2", ("initial.omega_a", "[-1e+06, 1e+06] rad/s"),
         ("run", "--set", "initial.omega_a=1e200")),
    Case("scene: an override that spans two lines", "exit 2", ("spans lines",),
         ("run", "--set", "initial.kappa=0.3\nphi = 9")),
    Case("scene: more integrator steps than memory holds", "exit 2", ("run.max_steps", "[1, 10000000]"),
         ("run", "--set", "run.max_steps=1000000000000")),
    Case("scene: start 1e-12 from contact, gap floor 1e-13 (the Newton iteration failed there)", "exit 2",
         ("run.gap_floor", "[1e-10, 1)", "full equations"),
         ("run", "--set", "initial.one_minus_kappa=1e-12", "--set", "run.gap_floor=1e-13")),
    Case("sweep: output path is a file", "exit 2", ("is a file, not a folder",),
         ("sweep", "{sweep}", "-o", "{file}"), sweep=_SWEEP),
    Case("sweep: scheduler address malformed (wrote a table first)", "exit 2", ("--scheduler", "cannot reach"),
         ("sweep", "{sweep}", "-o", "{tmp}/out", "--scheduler", "not-an-address"), sweep=_SWEEP),
    Case("sweep: 1e15 points (hung, eating memory)", "exit 2", ("10,000,000", "points"),
         ("sweep", "{sweep}", "-o", "{tmp}/out"), sweep=_SWEEP.replace("num = 2", "num = 100000")),
    Case("sweep: num = 1e12 (MemoryError)", "exit 2", ("num must be an integer in [1, 10,000,000]",),
         ("sweep", "{sweep}", "-o", "{tmp}/out"), sweep=_SWEEP.replace("num = 2", "num = 1000000000000")),
    Case("sweep: 100,000 workers", "exit 2", ("workers", "cores"),
         ("sweep", "{sweep}", "-o", "{tmp}/out", "--workers", "100000"), sweep=_SWEEP),
    Case("forces: reference pressure not a number", "exit 2", ("not a finite number: 'nan'",),
         ("forces", *GEOMETRY, "--kappa", "0.5", "--p-ref", "nan")),
    Case("forces: kappa = 1", "exit 2", ("kappa must be in [0, 1)",), ("forces", *GEOMETRY, "--kappa", "1")),
    Case("forces: b < a", "exit 2", ("b must be greater than a",), ("forces", "--a", "0.02", "--b", "0.01",
                                                                  "--kappa", "0.5")),
    Case("forces: b/a overflows", "exit 2", ("finite ratio b/a",), ("forces", "--a", "1e-300", "--b", "1e300",
                                                                  "--kappa", "0.5")),
    Case("forces: cavitation with the default (exact Stokes) forces", "exit 2", ("needs the model 'reynolds'",),
         ("forces", *GEOMETRY, "--kappa", "0.5", "--cavitation", "jfo")),
    Case("forces: finite elements at 1 - kappa = 1e-12 (f_chi 100 times too large)", "exit 2",
         ("kappa", "stokes-exact"),
         ("forces", "--model", "stokes", *GEOMETRY, "--kappa", "0.999999999999", "--eps-dot", "-1e-5", "--chi-dot",
          "0.2", "--omega-a", "1")),
    Case("forces: every model at delta/a = 9999 (8 GB, never finished)", "exit 2", ("delta_over_a", "[0.0001, 10]"),
         ("forces", "--model", "all", "--a", "0.001", "--b", "10", "--kappa", "0.5")),
    Case("forces: flow folder in /proc (failed after the solve)", "exit 2", ("--flow /proc/x",),
         ("forces", "--model", "stokes", *GEOMETRY, "--kappa", "0.5", "--flow", "/proc/x")),
    Case("forces: negative reference pressure", "exit 2", ("--p-ref must be in (0, inf) Pa",),
         ("forces", *GEOMETRY, "--kappa", "0.5", "--model", "reynolds", "--cavitation", "jfo", "--p-ref", "-1")),
    Case("forces: not a number", "exit 2", ("not a finite number",), ("forces", *GEOMETRY, "--kappa", "abc")),
    Case("API: Annulus(a='0.008')", "NotANumberError", ("a must be a finite number",),
         call=_api("a length as a string")),
    Case("API: Motion(chi_dot='1')", "NotANumberError", ("chi_dot must be a finite number",),
         call=_api("a rate as a string")),
    Case("API: Motion(chi_dot=1e308) (infinite forces)", "ValueError", ("chi_dot",), call=_api("rate 1e308")),
    Case("API: finite-element forces at 1 - kappa = 1e-9 (f_chi 71 % low)", "ValueError", ("kappa",),
         call=_api("finite elements near contact")),
    Case("API: lubrication.stokes_exact_forces on an annulus (a numba typing error)", "no error", (),
         call=_api("exact forces")),
    Case("API: Fluid(rho='960')", "NotANumberError", ("rho must be a finite number",),
         call=_api("a density as a string")),
    Case("API: simulate with max_steps=0", "ValueError", ("max_steps must be an integer in [1, 1e+07]",),
         call=_api("max_steps 0")),
    Case("API: simulate with NaN in t_eval", "ValueError", ("t_eval", "finite times"), call=_api("t_eval with nan")),
    Case("API: simulate with progress=3", "TypeError", ("progress must be a function",), call=_api("progress 3")),
    Case("API: output_interval=1e-9 s over 10 s (7.45 GiB of rows)", "ValueError", ("output_interval", "rows"),
         call=_api("output interval 1e-9")),
    Case("API: preset('steel', g=1e300) (killed the interpreter)", "ValueError", ("g must be in [0.001, 10000]",),
         call=_api("gravity 1e300")),
    Case("API: simulate with a negative t_end", "ValueError", ("t_end must be in (0, inf) s",),
         call=_api("negative t_end")),
    Case("API: Initial(kappa=1.5)", "ValueError", ("kappa must be in [0, 1)", "1.5"), call=_api("kappa 1.5")),
    Case("API: Initial(kappa=nan)", "ValueError", ("kappa must be in [0, 1)", "nan"), call=_api("kappa nan")),
    Case("API: start beyond the gap floor", "ValueError", ("gap floor",), call=_api("start beyond the gap floor")),
    Case("API: unknown integrator", "ValueError", ("method must be one of",), call=_api("bad method")),
    Case("API: Limits(gap_floor=2)", "ValueError", ("gap_floor must be in (0, 1)",), call=_api("gap floor 2")),
    Case("API: Limits(on_invalid='ignore')", "ValueError", ("on_invalid must be one of",),
         call=_api("on_invalid ignore")),
)


#: Faults exercised in subprocesses by tests/test_run_outputs.py and tests/test_sweep.py: (what was tried,
#: what it gets).
PROCESS_FAULTS = (
    ("a second snail run into a folder another run is writing", "exit 2 at once: 'another run is writing to "
     "DIR'; the first run's set is untouched"),
    ("Ctrl-C during a run", "exit 1; the folder holds the new set, summary.json status 'interrupted' with the time "
     "reached"),
    ("Ctrl-C twice", "exit 1 or 130; the folder holds either the previous complete set or the new one, never a "
     "mixture, and no staging folder is left"),
    ("SIGTERM during a run", "as Ctrl-C, the reason naming SIGTERM"),
    ("Ctrl-C while a sweep starts its cluster (one time in ten a traceback)", "exit 130, 'interrupted', no "
     "traceback: the signal waits until the cluster is up, then closes it"),
    ("Ctrl-C while a sweep compiles its batch runner (no answer until the compile ended)", "exit 130 within "
     "seconds: the compile runs on a worker, closed with the cluster"),
)


@dataclass(frozen=True)
class Outcome:
    case: Case
    got: str
    message: str
    clean: bool  # no traceback, nothing half-written

    @property
    def passed(self) -> bool:
        return self.got == self.case.expected and self.clean and all(w in self.message for w in self.case.words)


def run_case(case: Case) -> Outcome:
    """Run one case in a fresh temporary folder."""
    from dynamics.app.cli import main
    from dynamics.app.sweeps.run import max_workers

    if case.call is not None:
        try:
            case.call()
        except Exception as err:  # noqa: BLE001 - the type is what is checked
            return Outcome(case, type(err).__name__, str(err), True)
        return Outcome(case, "no error", "", True)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "file").write_text("a file")
        (tmp / "full").mkdir()
        (tmp / "full" / "notes.txt").write_text("keep me")
        (tmp / "scene.toml").write_text(case.scene, encoding="utf-8")
        (tmp / "sweep.toml").write_text(case.sweep, encoding="utf-8")
        argv = [a.replace("{scene}", str(tmp / "scene.toml")).replace("{sweep}", str(tmp / "sweep.toml"))
                .replace("{file}", str(tmp / "file")).replace("{full}", str(tmp / "full"))
                .replace("{tmp}", str(tmp)) for a in case.argv]
        if argv and argv[0] == "run" and "-o" not in argv:
            argv += ["-o", str(tmp / "out")]
        if argv and argv[0] == "run":
            argv.append("--no-plot")
        err, out = io.StringIO(), io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            try:
                code = main(argv)
            except SystemExit as exit_:
                code = exit_.code
        text = (err.getvalue() + out.getvalue()).replace(str(tmp), "<tmp>")
        text = re.sub(r"steps in [0-9.]+ s", "steps in <time> s", text)  # wall times vary from run to run
        text = re.sub(r"snail \w+: compiling [^\n]*\n", "", text)  # only when numba's cache is cold
        text = re.sub(r" \(and [0-9.]+ s compiling\)", "", text)  # likewise
        text = text.replace(f"[1, {max_workers()}] (this machine's cores)", "[1, <cores>] (this machine's cores)")
        left = code == 2 and (tmp / "out").exists()  # refused input leaves nothing; a stopped run keeps its data
        intact = (tmp / "full" / "notes.txt").read_text() == "keep me" and (tmp / "file").read_text() == "a file"
        return Outcome(case, f"exit {code}", text, "Traceback" not in text and not left and intact)
