"""The compiled Radau IIA engine on the project's models, against scipy's Radau; and the contract of simulate().

A catalogue of problems at module level, each a run of :func:`dynamics.simulation.simulate`:
the paper's figures 2 (rocking) and 3 (runaway) in the reduced model, figures 7 and 8
(rough contact, sliding and locked), the default scene (the steel apparatus, full model),
a level plane (alpha = 0: sedimentation (3.3), full model), a runaway of the full model
(aluminium at 12 degrees, s = 1.9, no Reynolds guard), a start at kappa0 = 0 exactly,
one at 1 - kappa0 = 1e-9 (below it only the gap floor 1e-12) and the full model's
stick-slip contact (psi = 0.13, just above the onset of sliding 0.1286).

Every problem is integrated by the compiled engine ("radau") and by scipy's Radau at
rtol = 1e-12 through the same driver (:func:`numerics.integrate.integrate`), the
reference. Errors are counted in tolerance units, as in scipy's own tests:

    e = |y - y_ref| / (atol + rtol |y_ref|),

in the scaled units in which the integrators' atol equals rtol (times and rates in
tau, X_b in b): phi, Omega_a tau, Omega_b tau and X_b / b with atol = rtol, and 1 - kappa,
which the stretched variables carry to full relative precision, with atol = 0. Samples
are compared at common output times (``t_eval``, 101 in each window): from the dense
output, whose error (degree-3 collocation polynomial) is first order in the tolerance
where the step ends' is of order 5/4 (tested below).

Reference windows are short enough that the default run stays within a minute
(scipy's Radau at rtol 1e-12 steps from Python, about 1,500 steps a second); the
slow tests repeat the comparison over the long windows.
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, field

import numpy as np
import pytest

from dynamics.apparatus import preset
from dynamics.contact.reduced import ContactParams
from dynamics.contact.steady import onset_of_sliding
from dynamics.equations.limits import MIN_GAP_FLOOR_FULL, Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.scenes import load_scene
from dynamics.simulation import Initial, simulate
from numerics.integrate import METHODS
from validation.contact_checks import KAPPA_STAR, RELEASE
from validation.dynamics_checks import FIG2, FIG3
from validation.full_contact_checks import STICK_SLIP_PSI, device

# The validation's releases: figures 2, 3, 7 and 8 from kappa0 = 0.5, phi0 = 0.3 at rest (kappa* = 0.98),
# and the full model's stick-slip (s = 1/4, Upsilon = 1, mu_ = 1.5, delta/a = 0.01, psi = 0.13).
STICK_SLIP_DEVICE = device(0.01)
SCENE = load_scene()
LEVEL = preset("steel", alpha=0.0)
REFERENCE_RTOL = 1e-12
#: Bound on the global error in tolerance units. Radau IIA's error estimate holds the
#: local error of each step below one unit; the global error of a tolerance-controlled
#: run is the local errors carried along and summed, which on a dissipative or
#: slowly rocking motion stays of the order of one unit and on a runaway grows with
#: the phase error. Measured at most 0.86 over the catalogue at rtol 1e-6 and 1e-8
#: (1.4 at rtol 1e-4, 1 - kappa of figure 3's runaway). 10 leaves room for an error
#: estimate that misses by a factor of a few, and fails for an engine off in its
#: coefficients (an error of the step's order, hundreds of units).
GLOBAL_ERROR_BOUND = 10.0
#: Bound on the error of event times in units of rtol (t + tau). An event time errs by the state's
#: error divided by the rate at which its guard crosses zero; the stick and slip guards near the onset
#: of sliding (the slip, and the friction's distance to its bound) cross slowly: measured up to 2.6
#: units in the stick-slip over 30 tau and 15.3 over 100 tau (its ninth switch), at most 0.012
#: for the touch and the stops.
EVENT_TIME_BOUND = 50.0


@dataclass(frozen=True)
class Problem:
    """A run of :func:`simulate`: its system, start, window (t_end, and the slow tests' long_t_end)."""

    system: object
    initial: Initial
    t_end: float
    long_t_end: float
    contact: object = None
    limits: Limits = field(default_factory=Limits)

    @property
    def b(self) -> float:
        """The unit of X_b in the columns (b, or 1 when dimensionless)."""
        return 1.0 if isinstance(self.system, ReducedParams) else self.system.b

    def run(self, method: str, rtol: float, t_end: float | None = None, **options):
        return simulate(self.system, self.initial, self.t_end if t_end is None else t_end, contact=self.contact,
                        limits=self.limits, method=method, rtol=rtol, **options)


def _tau(system) -> float:
    return 1.0 if isinstance(system, ReducedParams) else system.tau


CATALOGUE = {
    "figure 2": Problem(FIG2, RELEASE, 20.0, 50.0),
    "figure 3": Problem(FIG3, RELEASE, 100.0, 100.0, limits=Limits(max_turns=10)),
    "figure 7": Problem(FIG2, RELEASE, 20.0, 100.0, contact=ContactParams(KAPPA_STAR, 0.05)),
    "figure 8": Problem(FIG2, RELEASE, 20.0, 100.0, contact=ContactParams(KAPPA_STAR, 0.5)),
    "default scene": Problem(SCENE.apparatus, SCENE.initial, 1.0, 10.0),
    "level plane": Problem(LEVEL, Initial(0.3, math.pi), 20.0 * LEVEL.tau, 200.0 * LEVEL.tau),
    "runaway": Problem(preset("aluminium", alpha=math.radians(12.0)), Initial(0.5, 0.5), 2.0, 2.0,
                       limits=Limits(max_gap_reynolds=None, max_turns=3)),
    "kappa0 = 0": Problem(FIG2, Initial(0.0, 0.3), 20.0, 50.0),
    "1 - kappa0 = 1e-9": Problem(FIG2, Initial(one_minus_kappa=1e-9, phi=0.3), 5.0, 50.0,
                                 limits=Limits(gap_floor=1e-12)),
    "stick-slip": Problem(STICK_SLIP_DEVICE, RELEASE, 30.0 * STICK_SLIP_DEVICE.tau, 100.0 * STICK_SLIP_DEVICE.tau,
                          contact=ContactParams(KAPPA_STAR, STICK_SLIP_PSI)),
}
WITH_EVENTS = ("figure 3", "figure 7", "figure 8", "runaway", "stick-slip")


def samples(problem: Problem, t_end: float) -> np.ndarray:
    return np.linspace(0.0, t_end, 101)


@functools.cache
def reference(name: str, t_end: float):
    """scipy's Radau at rtol 1e-12 on the catalogue problem ``name``, sampled over [0, t_end]."""
    problem = CATALOGUE[name]
    return problem.run("Radau", REFERENCE_RTOL, t_end, t_eval=samples(problem, t_end))


def scaled(traj, problem: Problem) -> dict:
    """The sample rows in scaled units: 1 - kappa, phi, Omega_a tau, Omega_b tau, X_b / b."""
    keep = np.array(["sample" in row for row in traj.rows])
    c, tau = traj.columns, traj.tau
    return {"t": c["t"][keep], "one_minus_kappa": c["one_minus_kappa"][keep], "phi": c["phi"][keep],
            "omega_a": c["omega_a"][keep] * tau, "omega_b": c["omega_b"][keep] * tau,
            "x_b": c["x_b"][keep] / problem.b}


def tolerance_units(run, ref, problem: Problem, rtol: float) -> dict:
    """max e = |y - y_ref| / (atol + rtol |y_ref|) per column over the samples both runs have.

    phi is compared modulo 2 pi: its unwrapping between samples is tested on its own
    (:func:`test_phi_is_continuous_between_samples_far_apart`).
    """
    y, y_ref = scaled(run, problem), scaled(ref, problem)
    n = min(y["t"].size, y_ref["t"].size)  # a run ended by an event may hold one sample more or less
    np.testing.assert_allclose(y["t"][:n], y_ref["t"][:n], rtol=1e-15)
    out = {"one_minus_kappa": np.max(np.abs(y["one_minus_kappa"][:n] - y_ref["one_minus_kappa"][:n])
                                     / (rtol * y_ref["one_minus_kappa"][:n]))}
    phi_error = (y["phi"][:n] - y_ref["phi"][:n] + math.pi) % (2.0 * math.pi) - math.pi
    out["phi"] = np.max(np.abs(phi_error) / (rtol * (1.0 + np.abs(y_ref["phi"][:n]))))
    for name in ("omega_a", "omega_b", "x_b"):
        out[name] = np.max(np.abs(y[name][:n] - y_ref[name][:n]) / (rtol * (1.0 + np.abs(y_ref[name][:n]))))
    return out


def event_times(traj) -> tuple[list[str], np.ndarray]:
    """The names and times of what happened along the run, then of the event that ended it."""
    names = [e["name"] for e in traj.events] + ([traj.event] if traj.event else [])
    times = [e["t"] for e in traj.events] + ([traj.t[-1]] if traj.event else [])
    return names, np.array(times)


# -------------------------------------------------------------------- engine against scipy's Radau

def _check_against_reference(name: str, rtol: float, t_end: float):
    problem = CATALOGUE[name]
    ref = reference(name, t_end)
    run = problem.run("radau", rtol, t_end, t_eval=samples(problem, t_end))
    assert (run.status, run.event) == (ref.status, ref.event), run.message
    e = tolerance_units(run, ref, problem, rtol)
    for column, value in e.items():
        assert value < GLOBAL_ERROR_BOUND, f"{column}: {value:.3g} tolerance units"
    # Event times carry the state's error divided by the rate of the event function:
    # in units of rtol (t + tau), as a state component of size t.
    names, times = event_times(run)
    names_ref, times_ref = event_times(ref)
    assert names == names_ref
    tau = _tau(problem.system)
    if times.size:
        units = np.abs(times - times_ref) / (rtol * (times_ref + tau))
        assert units.max() < EVENT_TIME_BOUND, units
    return e


@pytest.mark.parametrize("rtol", [1e-6, 1e-8])
@pytest.mark.parametrize("name", list(CATALOGUE))
def test_engine_agrees_with_scipy_radau(name, rtol):
    """Every catalogue problem: the compiled run within GLOBAL_ERROR_BOUND tolerance units of the reference."""
    _check_against_reference(name, rtol, CATALOGUE[name].t_end)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(CATALOGUE))
def test_engine_agrees_with_scipy_radau_over_long_windows(name):
    """As above over the long windows (the default scene over 10 s, figure 7 over 100 tau, ...), rtol 1e-8."""
    _check_against_reference(name, 1e-8, CATALOGUE[name].long_t_end)


#: How well the reference's own event times are known: their change between rtol 1e-11 and
#: 1e-12 (measured) is at most 1.5e-13 relative, but 2.4e-11 in the stick-slip, whose stick and
#: slip guards (the slip, and the friction bound) cross zero slowly near the onset of sliding.
EVENT_TIME_RTOL = {"figure 3": 1e-12, "figure 7": 1e-12, "figure 8": 1e-12, "runaway": 1e-12,
                   "stick-slip": 1e-11}


@pytest.mark.parametrize("name", WITH_EVENTS)
def test_event_times_at_the_reference_tolerance(name):
    """Touch, switches and stops of the compiled run at rtol 1e-12 on the reference's (scipy's Radau at
    rtol 1e-12), to 1e-12 relative where the reference's event times are that good (EVENT_TIME_RTOL).

    Both are Radau IIA at the same tolerance on the same problem: they differ by rounding, which the
    step-size controller amplifies. Measured: 4e-16 (figure 3's stop), 2.3e-15 (touch of figures 7
    and 8), 1.8e-15 (runaway's stop), 8.2e-13 (stick-slip's switches).
    """
    problem = CATALOGUE[name]
    ref = reference(name, problem.t_end)
    run = problem.run("radau", REFERENCE_RTOL, problem.t_end, t_eval=samples(problem, problem.t_end))
    names, times = event_times(run)
    names_ref, times_ref = event_times(ref)
    assert names == names_ref and len(names) >= 1
    np.testing.assert_allclose(times, times_ref, rtol=EVENT_TIME_RTOL[name], atol=0.0)


@pytest.mark.parametrize("method", METHODS)
def test_gap_floor_is_reached_at_the_closed_form_time(method):
    """Sedimentation (3.3) on a level plane: r = r0 + t exactly, so 1 - kappa reaches the floor u at
    t = (1 - u)/sqrt(u (2 - u)) - r0. Every method integrates a linear solution exactly and the event
    is located to 4 eps on the dense output: the time to 1e-12 relative (measured <= 7e-16)."""
    kappa0, floor = 0.3, 1e-6
    traj = simulate(ReducedParams(0.0, 1.0, 1.0), Initial(kappa0, math.pi), 1e4, method=method,
                    limits=Limits(gap_floor=floor))
    r0 = kappa0 / math.sqrt(1.0 - kappa0**2)
    assert traj.event == "gap_floor" and traj.rows[-1] == "event:gap_floor+end"
    assert traj.t[-1] == pytest.approx((1.0 - floor) / math.sqrt(floor * (2.0 - floor)) - r0, rel=1e-12)
    assert traj.columns["one_minus_kappa"][-1] == pytest.approx(floor, rel=1e-12)


@pytest.mark.parametrize("name", list(CATALOGUE))
def test_steps_are_those_of_scipy_radau(name):
    """The engine is scipy's Radau step for step: at rtol 1e-8 it takes no more steps than scipy's
    (and no fewer), evaluations, Jacobians and LU decompositions alike, to 1% + 2 (rounding in the
    controller can part them; measured: equal counts in every problem)."""
    problem = CATALOGUE[name]
    mine, theirs = problem.run("radau", 1e-8), problem.run("Radau", 1e-8)
    for count in ("steps", "nfev", "njev", "nlu"):
        assert abs(getattr(mine, count) - getattr(theirs, count)) <= 0.01 * getattr(theirs, count) + 2, count


def test_error_falls_with_the_tolerance_at_the_orders_of_radau_iia():
    """Figure 2 over 20 tau, rtol = 1e-4 ... 1e-9 (atol = rtol), against the reference.

    The embedded error estimate is O(h^4), so the controller takes h ~ rtol^(1/4)
    and the number of steps grows as rtol^(-1/4). The step ends carry the method's
    global error, O(h^5) ~ rtol^(5/4); the dense output between them, the degree-3
    collocation polynomial, errs by O(h^4) ~ rtol. Fitted slopes: 0.972, 1.246 and
    -0.246 (measured); asserted within 0.1 of 1 and 5/4 (the fit spans five decades,
    and a bias of 0.1 would be a factor 3 at their ends) and 0.03 of -1/4.
    """
    problem = CATALOGUE["figure 2"]
    t_end = problem.t_end
    rtols = 10.0 ** -np.arange(4, 10)
    every_step = [problem.run("radau", rtol) for rtol in rtols]
    step_times = [traj.t[np.array(["step" in row for row in traj.rows])] for traj in every_step]
    t_eval = np.union1d(samples(problem, t_end), np.concatenate(step_times))
    ref = problem.run("Radau", REFERENCE_RTOL, t_eval=t_eval)
    names = ("one_minus_kappa", "phi", "omega_a", "omega_b", "x_b")
    ref_t, ref_y = ref.t, {k: ref.columns[k] for k in names}

    def max_error(t, columns):
        i = np.searchsorted(ref_t, t)
        np.testing.assert_array_equal(ref_t[i], t)
        return max(np.max(np.abs(columns[k] - ref_y[k][i])) for k in names)

    dense, ends = [], []
    for rtol, traj, t_steps in zip(rtols, every_step, step_times):
        sampled = problem.run("radau", rtol, t_eval=samples(problem, t_end))
        keep = np.array(["sample" in row for row in sampled.rows])
        dense.append(max_error(sampled.t[keep], {k: sampled.columns[k][keep] for k in names}))
        on_step = np.array(["step" in row for row in traj.rows])
        ends.append(max_error(t_steps, {k: traj.columns[k][on_step] for k in names}))
    steps = [traj.steps for traj in every_step]
    assert np.polyfit(np.log(rtols), np.log(dense), 1)[0] == pytest.approx(1.0, abs=0.1)
    assert np.polyfit(np.log(rtols), np.log(ends), 1)[0] == pytest.approx(1.25, abs=0.1)
    assert np.polyfit(np.log(rtols), np.log(steps), 1)[0] == pytest.approx(-0.25, abs=0.03)


# -------------------------------------------------------------------- near contact, every method

class _TooLong(Exception):
    """A run went past its wall-time budget."""


NEAR_CONTACT_BUDGET_S = 60.0


def _near_contact(one_minus_kappa0: float, method: str, t_end: float):
    """Figure 2's groups released at rest from 1 - kappa0 (gap floor 1e-12), within the wall-time budget."""
    start = time.perf_counter()

    def progress(t):
        if time.perf_counter() - start > NEAR_CONTACT_BUDGET_S:
            raise _TooLong(f"{method} at 1 - kappa0 = {one_minus_kappa0:g}: past {NEAR_CONTACT_BUDGET_S} s at t = {t}")

    traj = simulate(FIG2, Initial(one_minus_kappa=one_minus_kappa0, phi=0.3), t_end, method=method,
                    limits=Limits(gap_floor=1e-12), progress=progress)
    return traj, time.perf_counter() - start


@functools.cache
def _near_contact_radau(one_minus_kappa0: float, t_end: float):
    return _near_contact(one_minus_kappa0, "radau", t_end)[0]


def _check_near_contact(one_minus_kappa0: float, method: str, t_end: float):
    traj, seconds = _near_contact(one_minus_kappa0, method, t_end)
    assert traj.status == "completed", traj.message
    assert seconds < NEAR_CONTACT_BUDGET_S
    c, ref = traj.columns, _near_contact_radau(one_minus_kappa0, t_end).columns
    # The gap is carried to full relative precision (the start to a few ulp, through kappa/zeta and back).
    assert c["one_minus_kappa"][0] == pytest.approx(one_minus_kappa0, rel=4.0 * np.finfo(float).eps)
    assert np.all(c["one_minus_kappa"] > 0.5 * one_minus_kappa0)
    # The methods agree at the end to (steps) x rtol, the sum of the local errors of all the steps
    # with no damping (1 - kappa relative, as it is carried): 5e-6 to 7e-6 over 10 tau, 5e-5 over 50.
    # Measured over 10 tau 7e-7 in phi and the rates (BDF), 3.6e-7 in 1 - kappa (LSODA); over 50 tau
    # 2.6e-5 in 1 - kappa (BDF); 4e-15 between the two Radau.
    bound = traj.steps * 1e-8
    for name in ("phi", "omega_a", "omega_b"):
        assert c[name][-1] == pytest.approx(ref[name][-1], abs=bound), name
    assert c["one_minus_kappa"][-1] == pytest.approx(ref["one_minus_kappa"][-1], rel=bound)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("one_minus_kappa0", [1e-7, 1e-8, 1e-9, 1e-10])
def test_near_contact_starts_run_with_every_method(one_minus_kappa0, method):
    """Released 1e-7 ... 1e-10 from contact: every method starts (LSODA once failed at t = 0 with
    'Unexpected istate'), completes 10 tau within a minute (measured <= 0.4 s each) and agrees with the
    compiled Radau IIA."""
    _check_near_contact(one_minus_kappa0, method, 10.0)


@pytest.mark.slow
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("one_minus_kappa0", [1e-7, 1e-10])
def test_near_contact_starts_run_long_with_every_method(one_minus_kappa0, method):
    """As above over 50 tau (measured <= 4.1 s each, scipy's Radau the slowest)."""
    _check_near_contact(one_minus_kappa0, method, 50.0)


FULL_NEAR_CONTACT = preset("steel", alpha=math.radians(2.4))


def _full_near_contact(one_minus_kappa0: float, method: str):
    """The steel apparatus released at rest 1 - kappa0 from contact at the default scene's angle, 50 tau:
    the inner cylinder slides round the outer one in the film, within the wall-time budget."""
    start = time.perf_counter()

    def progress(t):
        if time.perf_counter() - start > NEAR_CONTACT_BUDGET_S:
            raise _TooLong(f"{method} at 1 - kappa0 = {one_minus_kappa0:g}: past {NEAR_CONTACT_BUDGET_S} s at t = {t}")

    ap = FULL_NEAR_CONTACT
    traj = simulate(ap, Initial(one_minus_kappa=one_minus_kappa0, phi=0.5), 50.0 * ap.tau, method=method,
                    limits=Limits(gap_floor=MIN_GAP_FLOOR_FULL, on_invalid="warn"), progress=progress)
    return traj, time.perf_counter() - start


@pytest.mark.parametrize(("one_minus_kappa0", "method"), [
    *((gap, method) for gap in (1e-6, 1e-8) for method in ("radau", "Radau", "BDF")
      if gap == 1e-6 or method == "radau"),
    # scipy's integrators step in Python: from 1e-8 they take the longest of the default run; 1e-6 checks
    # the same start with them, and the compiled engine runs from 1e-8 and 2e-10
    pytest.param(1e-8, "Radau", marks=pytest.mark.slow),
    pytest.param(1e-8, "BDF", marks=pytest.mark.slow),
    (2e-10, "radau"),
    pytest.param(2e-10, "Radau", marks=pytest.mark.slow),  # 17 s: scipy's Radau steps in Python
    pytest.param(2e-10, "BDF", marks=pytest.mark.slow),  # 43 s
])
def test_full_model_near_contact_starts_run_with_every_method(one_minus_kappa0, method):
    """The full equations released 1e-6 ... 2e-10 from contact (the gap floor they reach is 1e-10) slide the
    inner cylinder round the outer one
    at up to 50 rad/s. Carried in polar velocity near contact (dynamics.equations.full) the compiled Radau IIA
    takes 3,500-23,000 steps (0.2-1.8 s; the Cartesian velocity stalled from 1e-7), scipy's Radau the same
    steps, BDF 1,800-154,000; all within the budget and agreeing at the end to the accumulated tolerance."""
    traj, seconds = _full_near_contact(one_minus_kappa0, method)
    assert traj.status == "completed", traj.message
    assert seconds < NEAR_CONTACT_BUDGET_S
    c = traj.columns
    assert c["one_minus_kappa"][0] == pytest.approx(one_minus_kappa0, rel=4.0 * np.finfo(float).eps)
    if method != "radau":
        ref = _full_near_contact(one_minus_kappa0, "radau")[0].columns
        bound = traj.steps * 1e-8  # the local errors of all the steps, undamped
        assert c["omega_b"][-1] == pytest.approx(ref["omega_b"][-1], rel=bound)
        assert c["x_b"][-1] == pytest.approx(ref["x_b"][-1], rel=bound)


def test_full_model_near_contact_start_refuses_lsoda_and_says_what_runs():
    with pytest.raises(ValueError, match="method = 'LSODA' cannot follow the full equations released within 0.001 "
                                         "of contact .* use method = 'radau' .* or 'BDF'"):
        simulate(FULL_NEAR_CONTACT, Initial(one_minus_kappa=1e-6, phi=0.5), 1.0, method="LSODA")


# -------------------------------------------------------------------- the API's contract

@pytest.mark.parametrize(("call", "words"), [
    (lambda: simulate(FIG2, RELEASE, -1.0), "t_end must be in (0, inf) tau, got -1"),
    (lambda: simulate(SCENE.apparatus, RELEASE, -1.0), "t_end must be in (0, inf) s, got -1"),
    (lambda: Initial(kappa=1.5), "kappa must be in [0, 1), got 1.5"),
    (lambda: Initial(kappa=float("nan")), "kappa must be in [0, 1), got nan"),
    (lambda: simulate(FIG2, Initial(one_minus_kappa=1e-10), 1.0),
     "initial.kappa must leave 1 - kappa above the gap floor 1e-09"),
    (lambda: simulate(FIG2, Initial(one_minus_kappa=1e-10), 1.0, limits=Limits(gap_floor=1e-10)),
     "initial.kappa must leave 1 - kappa above the gap floor 1e-10"),
    (lambda: simulate(FIG2, Initial(0.99, 3.0), 1.0, contact=ContactParams(0.98, 0.1)),
     "initial.kappa must be in [0, kappa_star] = [0, 0.98]"),
    (lambda: simulate(FIG2, RELEASE, 1.0, rtol=1e-15), "rtol must be in [2.22045e-14, 0.1]"),
    (lambda: simulate(FIG2, RELEASE, 1.0, output_interval=2.0), "output_interval must be in (0, 1] tau"),
    (lambda: simulate(FIG2, RELEASE, 1.0, output_interval=0.1, t_eval=[0.0, 1.0]),
     "give output_interval or t_eval, not both"),
    (lambda: simulate(FIG2, RELEASE, 1.0, t_eval=[0.5, 0.2]), "t_eval must be a non-empty increasing array"),
    (lambda: simulate(FIG2, RELEASE, 1.0, equations="full"), "the full equations need a physical apparatus"),
], ids=["t_end<0 tau", "t_end<0 s", "kappa=1.5", "kappa=nan", "gap below floor", "gap at floor",
        "kappa beyond kappa*", "rtol", "output_interval", "interval and t_eval", "t_eval decreasing",
        "full without apparatus"])
def test_inputs_are_checked(call, words):
    """Each refusal is a ValueError naming the parameter and its allowed range (or what is wrong)."""
    with pytest.raises(ValueError) as info:
        call()
    assert words in str(info.value)


@pytest.mark.parametrize("equations", ["full", "reduced"])
def test_a_start_past_the_reynolds_limit_is_refused_unless_it_only_warns(equations):
    """Spinning the outer cylinder at 2000 rad/s at t = 0 puts the relative flow far past the limit: the run
    would only go on outside the model's validity, so the start is refused as the gap floor's is; with
    on_invalid = 'warn' it runs and records the passage."""
    apparatus = SCENE.apparatus
    spinning = Initial(0.5, 0.5, omega_b=2000.0)
    with pytest.raises(ValueError, match=r"give a gap Reynolds number Re\* = [0-9.]+ at t = 0, above "
                                         r"run.max_gap_reynolds"):
        simulate(apparatus, spinning, 0.01, equations=equations)
    warned = simulate(apparatus, spinning, 0.01, equations=equations, limits=Limits(on_invalid="warn"))
    assert warned.status == "completed"


def test_output_interval_rows_are_evenly_spaced_and_on_the_solution():
    """Figure 2 every 0.5 tau: rows exactly at k dt (0 to 20), each within the run's tolerance of the
    reference (rtol 1e-12) at the same times (measured 0.22 tolerance units at rtol 1e-8)."""
    problem, rtol, dt = CATALOGUE["figure 2"], 1e-8, 0.5
    traj = problem.run("radau", rtol, output_interval=dt)
    expected = dt * np.arange(41)
    np.testing.assert_array_equal(traj.t, expected)
    assert traj.rows[0] == "start+sample" and traj.rows[-1] == "sample+end" and set(traj.rows[1:-1]) == {"sample"}
    ref = problem.run("Radau", REFERENCE_RTOL, t_eval=expected)
    for column, value in tolerance_units(traj, ref, problem, rtol).items():
        assert value < GLOBAL_ERROR_BOUND, column


@pytest.mark.parametrize(("name", "rtol", "dt"), [
    ("default scene", 1e-8, 0.01),
    ("figure 7", 1e-4, 0.2),
    ("stick-slip", 1e-8, CATALOGUE["stick-slip"].t_end / 100),
])
def test_output_interval_rows_are_at_the_requested_times(name, rtol, dt):
    """The sample rows at exactly k dt, as for figure 2 above: in seconds for an apparatus, and after a
    contact switch."""
    traj = CATALOGUE[name].run("radau", rtol, output_interval=dt)
    keep = np.array(["sample" in row for row in traj.rows])
    np.testing.assert_array_equal(traj.t[keep], dt * np.arange(keep.sum()))


@pytest.mark.parametrize("dt", [0.5, 1.0])
def test_the_regime_and_the_inertia_report_are_judged_on_every_step(dt):
    """The default scene rocks with a period of about 0.46 s: rows every 0.5 s or 1 s alias the rocking, and
    its fastest swing falls between them. The regime and the inertia diagnostics are those of the
    every-step run all the same, number for number."""
    problem = CATALOGUE["default scene"]
    limits = Limits(on_invalid="warn")  # the release's first swing passes the Reynolds guard
    every_step = simulate(problem.system, problem.initial, 10.0, limits=limits)
    sampled = simulate(problem.system, problem.initial, 10.0, limits=limits, output_interval=dt)
    assert every_step.regime == "rocking"
    assert (sampled.regime, sampled.evidence) == (every_step.regime, every_step.evidence)
    assert sampled.info["inertia"] == every_step.info["inertia"]
    events = {row for row in sampled.rows if row.startswith("event:")}
    assert events == {"event:reynolds"} and set(sampled.rows) - events == {"start+sample", "sample", "sample+end"}


def test_phi_is_continuous_between_samples_far_apart():
    """Figure 3's runaway sampled every 5 tau, its line of centres turning several times between samples:
    phi grows monotonically by many turns and matches the every-step run's phi at the same times (the
    branch: within pi/2 of its linear interpolation between steps)."""
    every_step = simulate(FIG3, RELEASE, 1e4)
    sampled = simulate(FIG3, RELEASE, 1e4, output_interval=5.0)
    assert sampled.event == every_step.event == "runaway"
    keep = np.array(["sample" in row for row in sampled.rows])
    phi, t = sampled.columns["phi"][keep], sampled.t[keep]
    assert np.all(np.diff(phi) > 0.0)
    assert (phi[-1] - phi[0]) / (2.0 * math.pi) > 50.0
    np.testing.assert_allclose(phi, np.interp(t, every_step.t, every_step.columns["phi"]), atol=0.5 * math.pi)


def test_on_invalid_warn_goes_on_past_the_reynolds_limit():
    """The aluminium runaway with a tight Reynolds guard (Re* = 1): "stop" ends the run at the crossing;
    "warn" goes on to the runaway's turn limit and lists the crossing, at the same time, with its reason."""
    problem = CATALOGUE["runaway"]
    limits = Limits(max_gap_reynolds=1.0, max_turns=3)
    stopped = simulate(problem.system, problem.initial, 2.0, limits=limits)
    warned = simulate(problem.system, problem.initial, 2.0, limits=Limits(max_gap_reynolds=1.0, max_turns=3,
                                                                          on_invalid="warn"))
    assert stopped.status == "stopped" and stopped.event == "reynolds"
    assert warned.status == "stopped" and warned.event == "runaway" and warned.t[-1] > 5.0 * stopped.t[-1]
    crossings = [e for e in warned.events if e["name"] == "reynolds"]
    assert len(crossings) >= 1 and crossings[0]["t"] == stopped.t[-1]  # the same steps up to there
    passed = warned.info["limits_passed"]
    assert [p["name"] for p in passed] == ["reynolds"] * len(crossings)
    assert passed[0]["t"] == stopped.t[-1] and "max_gap_reynolds = 1" in passed[0]["reason"]
    assert "event:reynolds" in warned.rows
    assert "limits_passed" not in stopped.info


@pytest.mark.parametrize("name", ["figure 7", "default scene", "stick-slip"])
def test_runs_are_deterministic(name):
    """The same inputs give bit-identical columns, rows and counts."""
    problem = CATALOGUE[name]
    first, second = problem.run("radau", 1e-8), problem.run("radau", 1e-8)
    assert first.columns.keys() == second.columns.keys()
    for column in first.columns:
        np.testing.assert_array_equal(first.columns[column], second.columns[column], err_msg=column)
    np.testing.assert_array_equal(first.rows, second.rows)
    assert (first.steps, first.nfev, first.events) == (second.steps, second.nfev, second.events)


def test_the_stick_slip_problem_is_above_the_onset_and_switches():
    """The catalogue's stick-slip is what its name says: psi just above the onset of sliding, and the
    contact alternates locked and sliding in the window (6 switches in 30 tau)."""
    assert 1.0 < STICK_SLIP_PSI / onset_of_sliding(0.25, KAPPA_STAR) < 1.02
    switches = reference("stick-slip", CATALOGUE["stick-slip"].t_end).info["switches"]
    assert len(switches) >= 5
    assert [sw["to"] for sw in switches[1:]] == [("locked", "sliding")[i % 2] for i in range(len(switches) - 1)]
