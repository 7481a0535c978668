"""The automatic model choice: the cheapest model whose measured error meets a tolerance.

Every choice is read from the stored speed-versus-accuracy study
``dynamics/data/model_choice.json``, written by ``benchmarks/accuracy.py``;
nothing is guessed. The study holds, on a grid of delta/a and kappa:

* for each force model (closed forms (2.5)-(2.7), the Reynolds solver with
  its grid, profile and N, the exact Stokes resistance, finite-element Stokes
  meshes), the largest relative error of the five resistance coefficients
  against the exact Stokes solution (T_a per W_b against |T_a per W_a|) and
  the cost of one evaluation;
* for the reduced equations (2.11) and the full equations (2.1)-(2.4), the
  relative error of (X_b, 1 - kappa) at the end of a trajectory against the full
  equations with the exact Stokes forces.

Between two measured delta/a the worse of the two is used; below the
smallest the smallest's (the errors of the lubrication forms and of the
reduced equations are O(delta/a), so they only fall); beyond the largest the
study says nothing, and the most accurate model is chosen. Over kappa the
largest error of every measured kappa up to ``kappa_max`` is used, the first
measured kappa at or above it included.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import asdict, dataclass, field
from functools import lru_cache
from importlib.resources import files

from lubrication.geometry import check_range

__all__ = ["Choice", "choose_equations", "choose_forces", "near_contact_kappa", "resolve_model", "study"]

#: Force models of the study that the equations of motion can call, and the name its trajectories
#: were run under (the study's "stokes" runs use the exact Stokes forces).
_TRAJECTORY_KEY = {"closed-form": "closed-form", "reynolds": "reynolds", "stokes-exact": "stokes"}


@dataclass(frozen=True)
class Choice:
    """A chosen model and why.

    Attributes
    ----------
    model : str
        Force model ("closed-form", "reynolds", "stokes-exact") or equations
        ("reduced", "full").
    options : dict
        Options of the registered force model (:mod:`lubrication.registry`).
    error : float or None
        The measured error the choice rests on (relative; see the module
        docstring); None when the choice follows from another one.
    cost_s : float or None
        Measured wall seconds: of one force evaluation from jitted code, or of
        the study's trajectory.
    reason : str
        One sentence saying why.
    """

    model: str
    options: dict = field(default_factory=dict)
    error: float | None = None
    cost_s: float | None = None
    reason: str = ""

    def as_dict(self) -> dict:
        return asdict(self)


@lru_cache(maxsize=1)
def study() -> dict:
    """The stored speed-versus-accuracy study (package data written by ``benchmarks/accuracy.py``)."""
    return json.loads(files("dynamics").joinpath("data", "model_choice.json").read_text())


def near_contact_kappa() -> float:
    """The largest kappa of the study: the band a trajectory that nears contact needs."""
    return max(study()["kappas"])


def _bracket(value: float, grid: list[float]) -> tuple[list[int], str]:
    """Indices of the measured delta/a to take the worst of, and a phrase saying which."""
    for i, g in enumerate(grid):
        if math.isclose(value, g, rel_tol=1e-6):
            return [i], f"delta/a = {g:g}"
    if value < grid[0]:
        return [0], f"delta/a = {grid[0]:g} (the study's smallest; errors there are O(delta/a))"
    if value > grid[-1]:
        return [], ""
    j = next(i for i, g in enumerate(grid) if g > value)
    return [j - 1, j], f"delta/a = {grid[j - 1]:g} and {grid[j]:g} (the worse of the two)"


def _kappa_band(kappa_max: float, kappas: list[float]) -> tuple[list[int], str]:
    inside = [i for i, k in enumerate(kappas) if k <= kappa_max]
    above = [i for i, k in enumerate(kappas) if k >= kappa_max]
    band = sorted(set(inside + above[:1]))
    top = kappas[band[-1]]
    phrase = f"kappa <= {top:g}"
    if kappa_max > top:
        phrase += f" (the study's largest kappa; kappa_max = {kappa_max:g} is beyond it)"
    return band, phrase


def _adapter_options(entry: dict) -> dict:
    """The options of a study entry that its force-model adapter takes (the Reynolds grid's)."""
    return dict(entry["options"]) if entry["model"] == "reynolds" else {}


def _label(model: str, options: dict) -> str:
    return model + ("" if not options else " (" + ", ".join(f"{k} = {v}" for k, v in options.items()) + ")")


def _check(tolerance: float, delta_over_a: float) -> tuple[float, float]:
    tolerance = check_range("tolerance", tolerance, 0.0, 1.0, low_open=True)
    delta_over_a = check_range("delta_over_a", delta_over_a, 0.0, math.inf)
    return tolerance, delta_over_a


def choose_forces(tolerance: float, delta_over_a: float, kappa_max: float, *,
                  reynolds_profiles: tuple[str, ...] = ("thin", "eccentric"), trajectory: bool = False) -> Choice:
    """The cheapest force model for the equations of motion whose measured error meets ``tolerance``.

    Parameters
    ----------
    tolerance : float
        Largest acceptable relative error of the resistance coefficients, in (0, 1).
    delta_over_a : float
        Mean gap over inner radius of the scene, >= 0.
    kappa_max : float
        Largest eccentricity the forces are needed at, in [0, 1).
    reynolds_profiles : tuple of str
        Gap profiles of the Reynolds solver that may be chosen (a scene's
        Reynolds model has the thin gap (B1) only).
    trajectory : bool
        The forces drive the full equations: a model's error is then the
        larger of its force error and the measured trajectory error of the
        full equations with that kind of forces, where the study has one
        (the gap 1 - kappa near contact responds to a force error somewhat
        more than one to one).

    Returns
    -------
    Choice
        ``model`` is a :mod:`lubrication.registry` name. Cost is the measured
        time of one evaluation from jitted code, the largest over the band.
        Candidates are the models a right-hand side can call: closed forms,
        Reynolds and the exact Stokes solution; the finite-element solve is
        far too slow for that.
    """
    tolerance, delta_over_a = _check(tolerance, delta_over_a)
    kappa_max = check_range("kappa_max", kappa_max, 0.0, 1.0)
    data = study()
    rows, where = _bracket(delta_over_a, data["deltas"])
    band, kappa_phrase = _kappa_band(kappa_max, data["kappas"])
    candidates = [e for e in data["forces"] if e["equations_of_motion"]
                  and (e["model"] != "reynolds" or e["options"]["profile"] in reynolds_profiles)]
    if not rows:  # beyond the study: the most accurate at its largest delta/a, whatever the cost
        last = len(data["deltas"]) - 1
        best = min(candidates, key=lambda e: max(e["error"][last][k] for k in band))
        error = max(best["error"][last][k] for k in band)
        return Choice(best["model"], _adapter_options(best), error,
                      max(best["jit_s"][last][k] for k in band),
                      f"delta/a = {delta_over_a:g} is beyond the study (largest {data['deltas'][-1]:g}), so "
                      f"the most accurate measured model there, {_label(best['model'], best['options'])} "
                      f"(error {error:.1e} at delta/a = {data['deltas'][-1]:g}), is taken without a "
                      f"measured guarantee of the tolerance {tolerance:g}")
    along = data["equations"]["full"]
    eq_rows = _bracket(delta_over_a, data["equations"]["deltas"])[0] if trajectory else []
    measured = []
    for e in candidates:
        error = max(e["error"][r][k] for r in rows for k in band)
        runs = [along.get(_TRAJECTORY_KEY[e["model"]], [None] * (max(eq_rows, default=0) + 1))[r] for r in eq_rows]
        error = max([error] + [x for x in runs if x is not None])
        cost = max(e["jit_s"][r][k] for r in rows for k in band)
        measured.append((e, error, cost))
    meeting = [m for m in measured if m[1] <= tolerance]
    if meeting:
        e, error, cost = min(meeting, key=lambda m: m[2])
        kind = "force and trajectory error" if trajectory else "error"
        reason = (f"{_label(e['model'], e['options'])} is the cheapest force model ({cost * 1e6:.3g} us per "
                  f"evaluation) whose measured {kind} {error:.1e} at {where}, {kappa_phrase}, meets the "
                  f"tolerance {tolerance:g}")
    else:
        e, error, cost = min(measured, key=lambda m: m[1])
        reason = (f"no force model meets the tolerance {tolerance:g} at {where}, {kappa_phrase}; "
                  f"{_label(e['model'], e['options'])} is the most accurate measured, error {error:.1e}")
    return Choice(e["model"], _adapter_options(e), error, cost, reason)


def choose_equations(tolerance: float, delta_over_a: float, forces: str = "auto") -> Choice:
    """The reduced equations (2.11) when their measured O(delta/a) trajectory error meets
    ``tolerance``, else the full equations (2.1)-(2.4).

    Parameters
    ----------
    tolerance : float
        Largest acceptable relative trajectory error, in (0, 1).
    delta_over_a : float
        Mean gap over inner radius, >= 0.
    forces : {"auto", "closed-form"}
        The forces the full equations would have. "auto": the best measured
        (exact Stokes) forces, whose recorded error is that of the integration
        only. "closed-form": the reduced equations' own forces; then the full
        equations are chosen only when they are measured more accurate, since
        at finite delta/a the full equations with closed forms need not be
        closer to the truth than the reduced ones.
    """
    tolerance, delta_over_a = _check(tolerance, delta_over_a)
    if forces not in ("auto", "closed-form"):
        msg = f"forces must be 'auto' or 'closed-form' (the reduced equations' own), got {forces!r}"
        raise ValueError(msg)
    eq = study()["equations"]
    # the study's rows for the full equations are keyed by the force model they were run with
    full_forces = _TRAJECTORY_KEY["stokes-exact" if forces == "auto" else "closed-form"]
    rows, where = _bracket(delta_over_a, eq["deltas"])
    if not rows:
        last = len(eq["deltas"]) - 1
        return Choice("full", {}, eq["full"][full_forces][last], eq["full_s"][full_forces][last],
                      f"delta/a = {delta_over_a:g} is beyond the study (largest {eq['deltas'][-1]:g}), "
                      "where the reduced equations' error is unmeasured, so the full equations are used")
    error = max(eq["reduced"][r] for r in rows)
    cost = max(eq["reduced_s"][r] for r in rows)
    full_error = max(eq["full"][full_forces][r] for r in rows)
    full_cost = max(eq["full_s"][full_forces][r] for r in rows)
    with_forces = f" with {full_forces} forces" if forces != "auto" else ""
    if error <= tolerance:
        return Choice("reduced", {}, error, cost,
                      f"the reduced equations' measured trajectory error {error:.1e} at {where} meets the "
                      f"tolerance {tolerance:g}")
    if full_error <= tolerance:
        return Choice("full", {}, full_error, full_cost,
                      f"the reduced equations' measured trajectory error {error:.1e} at {where} exceeds the "
                      f"tolerance {tolerance:g}, so the full equations{with_forces} are used (error "
                      f"{full_error:.1e})")
    if full_error < error:
        return Choice("full", {}, full_error, full_cost,
                      f"neither the reduced equations (error {error:.1e}) nor the full equations{with_forces} "
                      f"(error {full_error:.1e}) meet the tolerance {tolerance:g} at {where}; the full are "
                      "the more accurate measured")
    return Choice("reduced", {}, error, cost,
                  f"neither the reduced equations (error {error:.1e}) nor the full equations{with_forces} "
                  f"(error {full_error:.1e}) meet the tolerance {tolerance:g} at {where}; the reduced are "
                  "the more accurate measured")


def _unsteady_note(scene, tolerance: float) -> str:
    """The ODE models' error in x_b measured against Navier-Stokes runs at the scene's Stokes number, and what
    to do where that alone exceeds ``tolerance``."""
    from dynamics.equations.limits import unsteady_error

    ap = scene.apparatus
    unsteady = unsteady_error(ap.delta**2 / (ap.nu * ap.tau))
    by_start = unsteady["by_start"]
    note = (f"; against Navier-Stokes runs the full equations with exact forces misplace a rocking release's x_b "
            f"by {by_start['release']:.1e} ({by_start['runaway']:.1e} a runaway's) at this fluid's Stokes number "
            f"{unsteady['stokes_number']:.3g} (docs/stokes_limit.md)")
    if by_start["release"] > tolerance:
        note += ", more than the tolerance: no ODE model meets it, equations = 'navier-stokes' has no such error"
    return note


def resolve_model(scene) -> tuple:
    """The scene's model with every "auto" replaced by a choice, and the choices as a dict.

    The tolerance is ``scene.model.tolerance``, the gap ``scene.groups.delta_over_a``.
    Forces are chosen for every kappa up to the larger of the initial kappa and
    :func:`near_contact_kappa`: a trajectory may close the gap whatever its start.
    The reduced equations are considered only with closed-form (or "auto") forces
    and no cavitation, since (2.11) has the full-film closed forms built in; when
    they are chosen, the forces are the closed forms.

    Returns
    -------
    model : dynamics.scenes.load.Model
        With concrete ``equations`` and ``forces`` (and Reynolds ``n``, ``grid``).
    choices : dict
        ``tolerance``, ``delta_over_a``, and for each automatic key
        (``equations``, ``forces``) the :class:`Choice` as a dict.
    """
    model = scene.model
    delta = scene.groups.delta_over_a
    record: dict = {"tolerance": model.tolerance, "delta_over_a": delta}
    equations = model.equations
    if equations == "auto":
        if scene.cavitation is not None or model.forces not in ("closed-form", "auto"):
            chosen = Choice("full", reason=f"the reduced equations (2.11) have the full-film closed forms "
                                           f"built in, and the scene asks for {model.forces} forces"
                                           f"{' with cavitation' if scene.cavitation is not None else ''}")
        else:
            chosen = choose_equations(model.tolerance, delta, model.forces)
        if scene.apparatus is not None:
            chosen = dataclasses.replace(chosen, reason=chosen.reason + _unsteady_note(scene, model.tolerance))
        equations = chosen.model
        record["equations"] = chosen.as_dict()
    forces, reynolds = model.forces, {}
    if forces == "auto":
        if equations == "reduced":
            chosen = Choice("closed-form", reason="the reduced equations (2.11) have the closed forms "
                                                  "(2.5)-(2.7) built in")
        else:
            kappa_max = max(scene.initial.kappa, near_contact_kappa())
            chosen = choose_forces(model.tolerance, delta, kappa_max, reynolds_profiles=("thin",), trajectory=True)
            record["kappa_max"] = kappa_max
        forces = chosen.model
        reynolds = {k: chosen.options[k] for k in ("n", "grid") if k in chosen.options}
        record["forces"] = chosen.as_dict()
    return dataclasses.replace(model, equations=equations, forces=forces, **reynolds), record
