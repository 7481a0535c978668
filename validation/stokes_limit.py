r"""The quasi-steady models' error against the Stokes number: the measured basis of ``max_stokes_number``.

Every ODE model of the project takes the flow in the gap as quasi-steady. What
that leaves out, the fluid's unsteady inertia, is measured by the Stokes number
St = delta^2 / (nu tau), the time for vorticity to diffuse across the gap over
the time scale (2.9) of the motion. For one device tau is proportional to nu,
so St goes as 1/nu^2, and so does the gap Reynolds number Re*: running one
start at several viscosities measures the error against St.

Two families, each the same start and slope at several viscosities
(:data:`FAMILIES`): the default release (steel, 2.4 deg, kappa = 0.5,
phi = 0.5 rad, which rocks), and the aluminium runaway of the paper's figure 6
at 5 deg from the same start. For each point: the coupled Navier-Stokes run
(:mod:`dynamics.equations.navier_stokes`) as the reference, again at a quarter
of its tolerance (its own error), and the full equations with the exact 2-D
Stokes forces for each ``frame_terms`` and ``fluid_spin``. The measure is the relative error of
X_b at the horizon (as :func:`validation.navier_stokes_verdict.errors`).

The error does not vanish as St goes to 0. Equation (2.4), as the paper writes
it, drops the fluid's own angular momentum about its centre of mass: a fluid
turning with the cylinders carries m_f (a^2 + b^2)/2 of moment of inertia that
the ODE models leave out, a share :func:`spin_share` of the rolling device's,
whatever the viscosity; the Navier-Stokes run has it. The checks, without the
spin: the runaway's error at the smallest St is that share (it rolls, as the
share assumes); the release's error grows with St by more than the references'
own error; every point's error is resolved. With it (``fluid_spin``), most of
the runaway's error is gone. The measured errors are what
:mod:`dynamics.equations.limits` states in every run's summary
(``dynamics/data/stokes_error.json``, written by ``generators/stokes_error.py``
from this study's stored numbers), and the largest St measured is the default
limit.

``python -m validation.stokes_limit`` runs the study and stores its numbers in
``docs/stokes_limit/stokes_limit.json`` (``--models``: the references' checks kept, after a change to the ODE
models); ``python -m validation.reports.stokes_limit``
writes ``docs/stokes_limit.md`` from them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from dynamics.apparatus import preset
from dynamics.equations.full import FLUID_SPIN
from dynamics.equations.limits import Limits, reduced_reynolds
from dynamics.initial import Initial
from dynamics.simulation import NAVIER_STOKES_RTOL, simulate

from .checks import Check, at_least, at_most, relative

__all__ = ["FAMILIES", "FRAME_TERMS", "RESOLVED", "RESULTS", "SPIN_TOLERANCE", "Family", "checks_of", "compute",
           "run_point", "spin_share"]


@dataclass(frozen=True)
class Family:
    """A start on a slope, run at several viscosities (m^2/s) for ``horizon_tau`` times tau, or for
    ``horizon_s`` seconds where tau is not the run's time scale."""

    label: str
    title: str
    preset: str
    slope_deg: float
    kappa: float
    phi: float
    viscosities: tuple
    horizon_tau: float | None = None
    horizon_s: float | None = None
    n_theta: int | None = None  # the reference's points around; None: the solver's choice from the gap

    def apparatus(self, nu: float):
        return preset(self.preset, nu=nu, alpha=math.radians(self.slope_deg))

    def horizon(self, nu: float) -> float:
        """The run's length (s)."""
        return self.horizon_s if self.horizon_s is not None else self.horizon_tau * self.apparatus(nu).tau


#: The verdict's cases (a) and (b) (docs/navier_stokes.md). The rocking release runs for 35 tau (1 s at 200 cSt):
#: its motion scales with tau. A runaway's does not: gravity spins it up at a rate the viscosity hardly changes
#: (at 1000 cSt it turns as fast in its first 0.5 s as at 200 cSt), so it runs for 1 s at every viscosity, and
#: its references have 48 points around, fixed, as in the verdict (their fast flow needs more than the gap asks for).
FAMILIES = (
    Family("release", "default release (steel, 2.4 deg)", "steel", 2.4, 0.5, 0.5,
           (1e-3, 5e-4, 3e-4, 2e-4, 1.4e-4, 1e-4), horizon_tau=35.0),
    Family("runaway", "aluminium runaway, 5 deg", "aluminium", 5.0, 0.5, 0.5,
           (1e-3, 5e-4, 3e-4, 2e-4, 1.4e-4), horizon_s=1.0, n_theta=48),
)
FRAME_TERMS = ("paper", "quasi-steady")
LIMITS = Limits(on_invalid="warn", max_turns=1000.0, max_stokes_number=None)
ODE_RTOL = 1e-9
TIGHT_RTOL = 0.25 * NAVIER_STOKES_RTOL
#: Every point's error must exceed this many times the reference's own.
RESOLVED = 5.0
#: The runaway's error at the smallest St against the fluid's spin share (:func:`spin_share`), relative: the share
#: counts the fluid as turning rigidly with the outer cylinder and the device as rolling at a uniform acceleration.
SPIN_TOLERANCE = 0.2
#: With the fluid's spin added to (2.4) (``fluid_spin = "couette"`` or ``"eccentric"``), what is left of the
#: runaway's error: at most a quarter of the spin share.
SPIN_LEFT = 0.02
#: With the eccentric flow's spin (the default), the release's error at the smallest St is at most this share of
#: that without: the floor goes with the spin.
SPIN_FLOOR = 0.25
RESULTS = Path(__file__).resolve().parents[1] / "docs" / "stokes_limit" / "stokes_limit.json"


def _x_b_error(reference: dict, t: np.ndarray, other: dict) -> float:
    x_ref = reference["x_b"][-1]
    return float((np.interp(t[-1], other["t"], other["x_b"]) - x_ref) / x_ref)


def run_point(family: Family, nu: float, log=print, kept: dict | None = None) -> dict:
    """The reference, its check at a quarter of the tolerance, and each closure's error, at one viscosity.

    ``kept``: the point as stored; its check at a quarter of the tolerance is kept instead of run again (the
    models-only rerun, ``--models``), and the reference, run again, must reproduce its stored X_b.
    """
    from dynamics.equations.navier_stokes import NavierStokesOptions

    ap = family.apparatus(nu)
    initial = Initial(family.kappa, family.phi)
    horizon = family.horizon(nu)
    stokes = ap.delta**2 / (ap.nu * ap.tau)
    log(f"{family.label}: nu = {nu:g} m^2/s, St = {stokes:.3g}, {horizon:.3g} s")
    runs = {}
    tolerances = (("reference", NAVIER_STOKES_RTOL),) if kept else (("reference", NAVIER_STOKES_RTOL),
                                                                    ("tight", TIGHT_RTOL))
    for name, rtol in tolerances:
        start = time.perf_counter()
        run = simulate(ap, initial, horizon, equations="navier-stokes", limits=LIMITS, rtol=rtol,
                       navier_stokes=NavierStokesOptions(n_theta=family.n_theta))
        if run.status != "completed":
            raise RuntimeError(f"{family.label}, nu = {nu:g}: the Navier-Stokes run stopped at "
                               f"{run.columns['t'][-1]:.4g} s: {run.message}")
        runs[name] = (run.columns, time.perf_counter() - start)
    reference, wall = runs["reference"]
    t = reference["t"]
    if kept and float(reference["x_b"][-1]) != kept["x_b_reference"]:
        raise RuntimeError(f"{family.label}, nu = {nu:g}: the Navier-Stokes reference no longer reproduces its "
                           "stored X_b; run the whole study again")
    models = {frame: {} for frame in FRAME_TERMS}
    for frame in FRAME_TERMS:
        for spin in FLUID_SPIN:
            run = simulate(ap, initial, horizon, forces="stokes-exact", frame_terms=frame, fluid_spin=spin,
                           limits=LIMITS, rtol=ODE_RTOL, t_eval=t)
            models[frame][spin] = {"x_b_relative": _x_b_error(reference, t, run.columns), "status": run.status}
    return {"nu": nu, "stokes_number": stokes, "tau_s": ap.tau, "horizon_s": horizon,
            "x_b_reference": float(reference["x_b"][-1]),
            "max_reduced_reynolds": float(np.max(reduced_reynolds(ap, reference))),
            "reference_error": kept["reference_error"] if kept else abs(_x_b_error(reference, t, runs["tight"][0])),
            "navier_stokes_wall_s": wall, "steps": int(t.size), "models": models}


def spin_share(apparatus) -> float:
    """The fluid's own moment of inertia, m_f (a^2 + b^2)/2, over the device's about the contact with the plane
    with it: what (2.4) leaves out of a device rolling with its fluid turning as a rigid body."""
    ap = apparatus
    spin = ap.m_f * (ap.a**2 + ap.b**2) / 2.0
    return spin / (spin + 0.5 * ap.m_a * ap.a**2 + (ap.M + ap.m_b) * ap.b**2)


def checks_of(result: dict) -> list[Check]:
    """Without the fluid's spin in (2.4) ("none"): every point resolved; the runaway's error at the smallest St is
    the fluid's spin share; the release's error grows with St by more than the references' own errors. With the
    spin ("couette", "eccentric", quasi-steady frame terms) the runaway's error is at most SPIN_LEFT at every St,
    and with the eccentric one the release's at the smallest St at most SPIN_FLOOR of its error without."""
    checks = []
    for family in result["families"]:
        points = family["points"]
        for frame in FRAME_TERMS:
            tag = f"{family['title']}, frame terms {frame}, no fluid spin"
            errors = [abs(p["models"][frame]["none"]["x_b_relative"]) for p in points]
            checks.append(at_least(f"{tag}: smallest |x_b error| over the reference's own error",
                                   min(e / p["reference_error"] for e, p in zip(errors, points)), RESOLVED))
            if family["label"] == "runaway":
                checks.append(relative(f"{tag}: |x_b error| at the smallest St against the fluid's spin share",
                                       errors[0], family["spin_share"], SPIN_TOLERANCE))
            else:
                checks.append(at_least(f"{tag}: growth of |x_b error| from the smallest to the largest St over the "
                                       "references' own error",
                                       (errors[-1] - errors[0]) / max(p["reference_error"] for p in points), 10.0))
    release = next(f for f in result["families"] if f["label"] == "release")
    low = release["points"][0]["models"]["quasi-steady"]
    checks.append(at_most("default release, frame terms quasi-steady: |x_b error| at the smallest St with the "
                          "eccentric fluid spin over that without", abs(low["eccentric"]["x_b_relative"])
                          / abs(low["none"]["x_b_relative"]), SPIN_FLOOR,
                          note="the floor is the spin: what is left vanishes with St, as unsteady inertia does"))
    runaway = next(f for f in result["families"] if f["label"] == "runaway")
    for spin in ("couette", "eccentric"):
        checks.append(at_most(f"aluminium runaway, frame terms quasi-steady, {spin} fluid spin in (2.4): largest "
                              "|x_b error| over the St measured",
                              max(abs(p["models"]["quasi-steady"][spin]["x_b_relative"]) for p in runaway["points"]),
                              SPIN_LEFT, note="the floor is the spin: adding it removes most of the error"))
    return checks


def compute(families=FAMILIES, log=print, stored: dict | None = None) -> dict:
    """Run every point of every family, and fit each family and closure.

    ``stored``: a previous result whose checks of the references' own error are kept (:func:`run_point`).
    """
    start = time.perf_counter()
    out = []
    for family in families:
        before = {} if stored is None else {p["nu"]: p for f in stored["families"] if f["label"] == family.label
                                            for p in f["points"]}
        points = [run_point(family, nu, log, before.get(nu)) for nu in family.viscosities]
        out.append({"label": family.label, "title": family.title, "preset": family.preset,
                    "slope_deg": family.slope_deg, "kappa0": family.kappa, "phi0": family.phi,
                    "horizon_tau": family.horizon_tau, "horizon_s": family.horizon_s, "n_theta": family.n_theta,
                    "spin_share": spin_share(family.apparatus(family.viscosities[0])), "points": points})
    return {"families": out, "navier_stokes_rtol": NAVIER_STOKES_RTOL, "tight_rtol": TIGHT_RTOL,
            "ode_rtol": ODE_RTOL, "resolved": RESOLVED,
            # a models-only rerun keeps the cost of the whole study as measured when it last ran in full
            "wall_time_s": stored["wall_time_s"] if stored else time.perf_counter() - start}


if __name__ == "__main__":
    import json
    import sys

    from numerics.files import write_json

    # "python -m validation.stokes_limit runaway" runs that family again and keeps the other's stored numbers;
    # "--models" keeps the references' checks at a quarter of the tolerance and reruns the rest
    models_only = "--models" in sys.argv
    labels = [arg for arg in sys.argv[1:] if arg != "--models"]
    chosen = [f for f in FAMILIES if not labels or f.label in labels]
    stored = json.loads(RESULTS.read_text()) if models_only else None
    result = json.loads(json.dumps(compute(chosen, log=lambda text: print(text, flush=True), stored=stored),
                                   default=lambda x: x.item()))
    if len(chosen) < len(FAMILIES):
        kept = {f["label"]: f for f in json.loads(RESULTS.read_text())["families"]}
        kept.update({f["label"]: f for f in result["families"]})
        result["families"] = [kept[f.label] for f in FAMILIES]
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    write_json(RESULTS, result)
