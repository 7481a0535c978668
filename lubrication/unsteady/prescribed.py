r"""Prescribed wall motions from a fluid at rest: the driver and its time series.

Each of x_a, z_a (the inner centre relative to B, m) and Omega_a, Omega_b
(clockwise spins, rad/s) is a constant or ``mean + amplitude sin(omega t + phase)``.
The position and the velocities are exact at every step (the solver is given
z_new, and the wall equations M = I, C = 0, r = q(t_new)); the fluid is at rest at
t = 0 while the walls already move with q(0) (an impulsive start when q(0) != 0).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..geometry import check_finite, check_range
from .mapping import MIN_ONE_MINUS_KAPPA_UNSTEADY
from .resolution import Resolution, default_resolution
from .solver import StepControl, UnsteadySolver, prescribed_wall

__all__ = ["Harmonic", "PrescribedMotion", "PrescribedRun", "first_steps", "march", "run_prescribed"]


@dataclass(frozen=True)
class Harmonic:
    """mean + amplitude sin(omega t + phase)."""

    mean: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0

    def __post_init__(self):
        for name in ("mean", "amplitude", "omega", "phase"):
            check_finite(name, getattr(self, name))

    def value(self, t):
        return self.mean + self.amplitude * np.sin(self.omega * t + self.phase)

    def rate(self, t):
        return self.amplitude * self.omega * np.cos(self.omega * t + self.phase)


def _harmonic(name, spec) -> Harmonic:
    if isinstance(spec, Harmonic):
        return spec
    if np.ndim(spec) == 0:
        return Harmonic(mean=check_finite(name, spec))
    values = tuple(spec)
    if not 1 <= len(values) <= 4:
        msg = f"{name} must be a number or (mean, amplitude, omega, phase), got {spec!r}"
        raise ValueError(msg)
    return Harmonic(*values)


@dataclass(frozen=True)
class PrescribedMotion:
    """The walls' motion: each entry a constant or (mean, amplitude, omega, phase).

    x_a, z_a in m; omega_a, omega_b in rad/s (clockwise); omega (the frequencies) in rad/s.
    """

    x_a: Harmonic | float | tuple = 0.0
    z_a: Harmonic | float | tuple = 0.0
    omega_a: Harmonic | float | tuple = 0.0
    omega_b: Harmonic | float | tuple = 0.0

    def __post_init__(self):
        for name in ("x_a", "z_a", "omega_a", "omega_b"):
            object.__setattr__(self, name, _harmonic(name, getattr(self, name)))

    def position(self, t: float) -> complex:
        return complex(self.x_a.value(t), self.z_a.value(t))

    def velocities(self, t: float) -> np.ndarray:
        """q = (U_x, U_z, Omega_a, Omega_b) at ``t``."""
        return np.array([self.x_a.rate(t), self.z_a.rate(t), self.omega_a.value(t), self.omega_b.value(t)])

    def fastest(self) -> float:
        """Largest angular frequency of the motion (rad/s), 0 if steady."""
        return max(abs(h.omega) for h in (self.x_a, self.z_a, self.omega_a, self.omega_b))

    def largest_eccentricity(self, t_end: float, samples: int = 4001) -> tuple[float, float]:
        """max |z_a(t)| over [0, t_end] (sampled, then refined) and the time it is reached."""
        t = np.linspace(0.0, t_end, samples)
        eps = np.abs(self.x_a.value(t) + 1j * self.z_a.value(t))
        i = int(np.argmax(eps))
        # refine by golden section on the bracketing interval
        lo, hi = t[max(i - 1, 0)], t[min(i + 1, samples - 1)]
        f = lambda s: -abs(self.position(s))  # noqa: E731
        for _ in range(60):
            m1, m2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
            if f(m1) < f(m2):
                hi = m2
            else:
                lo = m1
        tm = 0.5 * (lo + hi)
        return max(abs(self.position(tm)), float(eps[i])), tm


@dataclass
class PrescribedRun:
    """Time series of a prescribed-motion run (per unit length).

    Attributes
    ----------
    t, x_a, z_a : ndarray
        s, m, m.
    F_x, F_z : ndarray
        Force of the fluid on the inner wall (N/m), the buoyancy-like -rho pi a^2 g_eff included.
    T_a, T_b : ndarray
        Torque of the fluid on the inner wall about A and on the outer wall about B (N m/m), clockwise.
    snapshots : list of dict
        Fields at the requested times (:meth:`UnsteadySolver.fields`), each with its ``t``.
    resolution : Resolution
    steps, rejected, factorisations, sweeps : int
        Accepted and rejected steps, LU factorisations, defect-correction sweeps.
    wall_time_s : float
    """

    t: np.ndarray
    x_a: np.ndarray
    z_a: np.ndarray
    F_x: np.ndarray
    F_z: np.ndarray
    T_a: np.ndarray
    T_b: np.ndarray
    resolution: Resolution
    snapshots: list = field(default_factory=list)
    steps: int = 0
    rejected: int = 0
    factorisations: int = 0
    sweeps: int = 0
    wall_time_s: float = 0.0


def first_steps(delta: float, nu: float, motion: PrescribedMotion) -> tuple[float, float]:
    """The first step and the largest step of a prescribed motion (s): 1e-3 of the shorter of the viscous
    time delta^2/nu and 1/(fastest frequency), and at least 60 steps a period of the fastest harmonic."""
    fastest = motion.fastest()
    viscous = delta * delta / nu
    return 1e-3 * (viscous if fastest == 0.0 else min(viscous, 1.0 / fastest)), (
        0.1 / fastest if fastest > 0.0 else math.inf)


def march(solver: UnsteadySolver, motion: PrescribedMotion, t_end: float, *, dt: float, dt_max: float,
          targets: list, on_step, stop=None, dt_fixed: float | None = None) -> str | None:
    """Step ``solver`` with the walls on ``motion`` to ``t_end``, landing on the times of ``targets``.

    ``on_step(level)`` is called after every accepted step; it pops the targets it has handled (a
    step shortened to land on the first target does not shrink the next one). ``stop()``, if given,
    is asked before every attempt (rejected steps too): a string it returns stops the march and is
    returned. Returns None at ``t_end``.

    Raises
    ------
    RuntimeError
        When the step size underflows.
    """
    eps_t = 1e-12 * t_end
    while solver.state.t < t_end - eps_t:
        if stop is not None and (why := stop()):
            return why
        t_now = solver.state.t
        target = min([t_end, *targets[:1]])
        h = min(dt, dt_max, target - t_now)
        if target - t_now - h < 0.05 * h:  # do not leave a sliver before the target
            h = target - t_now
        t_new = t_now + h
        res = solver.step(h, prescribed_wall(motion.velocities(t_new)), motion.position(t_new))
        if not res.accepted:
            dt = res.dt_next
            if dt < 1e-14 * max(t_end, 1.0):
                msg = f"step size underflow at t = {t_now:.6g} s ({res.reason})"
                raise RuntimeError(msg)
            continue
        on_step(solver.state)
        if dt_fixed is None:
            dt = max(res.dt_next, dt) if h < dt else res.dt_next
        else:
            dt = dt_fixed
    return None


def run_prescribed(a: float, b: float, nu: float, rho: float, motion: PrescribedMotion, t_end: float, *,
                   resolution: Resolution | None = None, control: StepControl | None = None, g_eff=0j,
                   dt_initial: float | None = None, dt_max: float | None = None,
                   snapshot_times=(), dt_fixed: float | None = None) -> PrescribedRun:
    """Run a prescribed wall motion from a fluid at rest at t = 0 to ``t_end``.

    Parameters
    ----------
    a, b, nu, rho : float
        Radii (m), kinematic viscosity (m^2/s), density (kg/m^3).
    motion : PrescribedMotion
    t_end : float
        s.
    resolution : Resolution or None
        Default: :func:`default_resolution` for the largest eccentricity of the motion.
    control : StepControl or None
    g_eff : complex
        Uniform body force per unit mass of the frame (m/s^2), x + i z.
    dt_initial : float or None
        First step; default 1e-3 of the smaller of the viscous time delta^2/nu and 1/(fastest frequency).
    dt_max : float or None
        Largest step.
    snapshot_times : sequence of float
        Times at which to keep the fields (steps are shortened to land on them).
    dt_fixed : float or None
        Constant steps (the step control is then off).

    Returns
    -------
    PrescribedRun

    Raises
    ------
    ValueError
        Non-finite or non-positive inputs, or a motion whose narrowest gap is
        below what the solver resolves (naming 1 - kappa and the time it is reached).
    """
    start = time.perf_counter()
    t_end = check_range("t_end", t_end, 0.0, math.inf, low_open=True, unit="s")
    if not b > a:
        msg = f"b must be greater than a = {a:g} m (outer radius), got {b!r}"
        raise ValueError(msg)
    delta = b - a
    eps_max, t_max = motion.largest_eccentricity(t_end)
    omk = (delta - eps_max) / delta
    if omk < MIN_ONE_MINUS_KAPPA_UNSTEADY * (1.0 - 1e-9):  # slack for rounding
        msg = (f"one_minus_kappa = 1 - kappa must stay at least {MIN_ONE_MINUS_KAPPA_UNSTEADY:g} for the unsteady "
               f"solver; the motion reaches {omk:.3g} (kappa = {eps_max / delta:.6g}) at t = {t_max:.6g} s")
        raise ValueError(msg)
    if dt_fixed is not None:
        dt_fixed = check_range("dt_fixed", dt_fixed, 0.0, math.inf, low_open=True, unit="s")
        base = control or StepControl()
        control = StepControl(**{**base.__dict__, "adaptive": False})
    solver = UnsteadySolver(a, b, nu, rho, resolution, g_eff=g_eff, control=control)
    if solver.resolution is None:
        from .mapping import AnnulusMap
        worst = AnnulusMap(a, b, (motion.position(t_max) / max(abs(motion.position(t_max)), 1e-300)) * eps_max)
        solver.resolution = default_resolution(worst)
    solver.start(motion.position(0.0), motion.velocities(0.0))
    dt, dt_max_rule = first_steps(delta, nu, motion)
    dt = dt_fixed or (dt_initial if dt_initial is not None else dt)
    dt_max = math.inf if dt_max is None else check_range("dt_max", dt_max, 0.0, math.inf, low_open=True, unit="s")
    snaps = sorted(float(s) for s in snapshot_times if 0.0 <= float(s) <= t_end)
    out = {k: [] for k in ("t", "x_a", "z_a", "F_x", "F_z", "T_a", "T_b")}
    snapshots = []

    def record(level):
        out["t"].append(level.t)
        out["x_a"].append(level.z_a.real)
        out["z_a"].append(level.z_a.imag)
        for i, k in enumerate(("F_x", "F_z", "T_a", "T_b")):
            out[k].append(level.loads[i])
        while snaps and snaps[0] <= level.t + 1e-12 * t_end:  # the steps land on them
            snapshots.append({"t": level.t, **solver.fields()})
            snaps.pop(0)

    record(solver.state)
    march(solver, motion, t_end, dt=dt, dt_max=min(dt_max, dt_max_rule), targets=snaps, on_step=record,
          dt_fixed=dt_fixed)
    c = solver.counters
    arrays = {k: np.array(v) for k, v in out.items()}
    return PrescribedRun(**arrays, resolution=solver.resolution, snapshots=snapshots, steps=c.steps,
                         rejected=c.rejected, factorisations=c.factorisations, sweeps=c.sweeps,
                         wall_time_s=time.perf_counter() - start)
