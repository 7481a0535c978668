r"""The tilt of the inner cylinder's axis: the strip theory of a tilted film, and whether a tilt grows.

A tilted inner cylinder. Its cross-section at height z (from the mid-plane,
|z| <= L/2) is displaced from the outer cylinder's axis by r + z gamma: r is the
mid-plane's displacement eps e_eps of (2.1)-(2.4), gamma the tilt, a small vector
in the plane of the cross-section (rad). In strip theory each section is a
slice of the plane problem, with its own eccentricity and its own velocity
r' + z gamma' (gamma' the tilt's rate in the frame of the plane), both cylinders
turning at Omega_a, Omega_b. Its force per unit length f(r + z gamma, r' + z gamma')
is any registered force model's (:mod:`lubrication.registry`, per unit length of
an infinitely long annulus), and the film's total force and its moment about
the mid-plane are

    F = int f dz,    M = int z f dz    over [-L/2, L/2]   (Gauss-Legendre).

What it leaves out is the axial flow, whose pressure gradient is of order
(a/L)^2 against the azimuthal one, and the end regions into which the device's
gap opens: against the Reynolds equation on (theta, z)
(:func:`lubrication.reynolds2d.reynolds2d_pressure` with
:func:`~lubrication.reynolds2d.tilted_gap`) with sealed ends the moment's error
falls as (a/L)^2, and with open ends the moment is a fraction of the strips'
that tends to 1 near contact (both measured in tests/test_tilt.py and stated
on the force models' page of the docs).

Linear tilt. For a small tilt, M = (L^3/12)(K gamma + C gamma'), with K and C the
derivatives of the force per unit length with respect to a section's
displacement and velocity (:func:`tilt_coefficients`, central differences of
the model's kernel). The tilt obeys the moment equation of the inner cylinder
about its mid-point (its outer cylinder, rolling on the plane, does not tilt):

    I_t gamma'' = (L^3/12)(K gamma + C gamma') + I_a J (Omega_a gamma)',

with I_t = m_eff L^2/12 + m_a a^2/4 its transverse moment of inertia, each
section carrying the effective mass m_eff of (2.1)-(2.2) per unit length; I_a =
m_a a^2/2 its axial one, whose spin, tilted with the axis, gives the gyroscopic
term; J the quarter turn e_eps -> e_chi. Gravity, uniform along the axis, has
no moment about the mid-point, so a tilt is neither started nor restored by it:
it grows or decays by the film alone. K holds the film's cross-coupled
stiffness, the source of the half-frequency whirl of journal bearings: without
inertia an aligned journal whose walls turn whirls undamped (near the centre of
a thin film at (Omega_a + Omega_b)/2), and any inertia makes that whirl grow.

:func:`tilt_history` integrates this equation along a computed trajectory (the
matrix at its rows, linear between them), from unit tilts in both directions:
the tilt's largest amplification over the run, and the largest growth rate of
the equation frozen at each instant, say whether the trajectory's aligned motion
is stable to a tilt. Quasi-steady forces, as in (2.1)-(2.4); and the section's frame
is singular where the mid-plane is centred, so the trajectory must keep
kappa >= :data:`KAPPA_MIN`.

Contact. The hard contact of section 5 (uniform or rough surfaces) touches along
the whole generator where the line of centres meets the surfaces, with every
section at the constraint |r + z gamma| = eps*. A tilt would carry one end
through it (first order in a radial tilt, second order in a tangential one), so
while in contact the axis stays parallel, and a tilt lives only in the free
flights between a lift-off and the next touch, which starts each of them
aligned. :func:`tilt_in_flights` integrates the tilt equation over each flight of
a run with contact phases, from unit tilts at its start: how far a tilt seeded
at a lift-off (by an imperfection of the device) can grow before the next touch
realigns the axis. The compliant contact holds a tilt by the asperities'
elasticity, which this module does not model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.linalg import expm

from dynamics.contact.laws import COMPLIANT
from dynamics.contact.reduced import FREE
from dynamics.trajectory import PHASE_CODES
from lubrication.geometry import Annulus, Fluid, FluidForces, Motion
from lubrication.kernels import KernelModel
from lubrication.registry import kernel_model

__all__ = ["KAPPA_MIN", "FlightTilts", "TiltHistory", "flights", "strip_forces", "tilt_coefficients",
           "tilt_history", "tilt_in_flights"]

#: The smallest eccentricity ratio taken: a section's frame (e_eps, e_chi) turns as 1/eps under a displacement.
KAPPA_MIN = 1e-3
#: Gauss-Legendre points along the axis in :func:`strip_forces`.
STRIP_POINTS = 32
#: Exponentials per interval between a run's rows in :func:`tilt_history`.
SUBSTEPS = 8
#: The quarter turn e_eps -> e_chi, in the components (along e_eps, along e_chi) of any frame turned with them.
J = np.array([[0.0, -1.0], [1.0, 0.0]])
# displacement steps of the central differences, a fraction of the smaller of eps and the gap: their error is
# O(step^2) ~ 1e-12 of the force, their rounding ~ 1e-16/step
_STEP = 1e-6


def _per_length(model: KernelModel) -> KernelModel:
    if model.length_table is not None or model.end_gap is not None:
        msg = (f"strip theory takes the force per unit length of an infinitely long annulus: the {model.name} model "
               "has ends or end faces; build it with ends = 'infinite' and no end_gap")
        raise ValueError(msg)
    return model


def _section(model, a, b, mu, eps, omk, d, v, omega_a, omega_b) -> np.ndarray:
    """Force per unit length (along e_eps, e_chi of the mid-plane) and torque per unit length of a section
    displaced by ``d`` from the mid-plane's centre and moving at ``v`` (both in those components)."""
    delta = b - a
    eps_s = math.hypot(eps + d[0], d[1])
    omk_s = omk - (2.0 * eps * d[0] + d[0] * d[0] + d[1] * d[1]) / ((eps_s + eps) * delta)  # without cancellation
    c, s = (eps + d[0]) / eps_s, d[1] / eps_s  # the section's e_eps in the mid-plane's frame
    eps_dot = v[0] * c + v[1] * s
    chi_dot = (v[1] * c - v[0] * s) / eps_s
    f_eps, f_chi, t_a = model.kernel(model.data, a, b, mu, 1.0, eps_s / delta, omk_s, eps_dot,
                                     omega_a - chi_dot, omega_b - chi_dot)
    return np.array([f_eps * c - f_chi * s, f_eps * s + f_chi * c, t_a])


def _check_kappa(kappa) -> None:
    low = float(np.min(kappa))
    if not low >= KAPPA_MIN:
        msg = (f"kappa: the tilt's sections need kappa >= {KAPPA_MIN:g} (their frame is singular at the centre), "
               f"got {low!r}")
        raise ValueError(msg)


def strip_forces(model: KernelModel, annulus: Annulus, motion: Motion, fluid: Fluid, tilt, tilt_rate=(0.0, 0.0),
                 *, points: int = STRIP_POINTS) -> tuple[FluidForces, np.ndarray]:
    """The film's force, torque and moment on a tilted inner cylinder of length ``annulus.length`` (strip theory).

    Parameters
    ----------
    model : KernelModel
        A force model per unit length (:func:`lubrication.registry.kernel_model`, ends 'infinite').
    annulus, motion, fluid
        The mid-plane's section and its motion.
    tilt : (float, float)
        gamma along e_eps and e_chi (rad): the section at z is displaced by z gamma from the mid-plane's.
    tilt_rate : (float, float)
        gamma' in the frame of the plane, in the same components (rad/s). A tilt fixed in the frame of
        the line of centres (as :func:`lubrication.reynolds2d.tilted_gap` with ``tilt_rate = 0``) has
        gamma' = chi' J gamma.

    Returns
    -------
    (FluidForces, ndarray)
        The totals (f_eps, f_chi, T_a) and the moment int z f dz along (e_eps, e_chi) (N m).
    """
    _per_length(model)
    _check_kappa(annulus.kappa)
    a, b, length, mu = annulus.a, annulus.b, annulus.length, fluid.mu
    eps = annulus.kappa * (b - a)
    tilt, tilt_rate = np.asarray(tilt, dtype=float), np.asarray(tilt_rate, dtype=float)
    base = np.array([motion.eps_dot, eps * motion.chi_dot])
    x, w = np.polynomial.legendre.leggauss(points)
    total, moment = np.zeros(3), np.zeros(2)
    for z, weight in zip(0.5 * length * x, 0.5 * length * w, strict=True):
        f = _section(model, a, b, mu, eps, annulus.one_minus_kappa, z * tilt, base + z * tilt_rate,
                     motion.omega_a, motion.omega_b)
        total += weight * f
        moment += weight * z * f[:2]
    return FluidForces(*total, model=f"{model.name}, strips"), moment


def tilt_coefficients(model: KernelModel, annulus: Annulus, motion: Motion, fluid: Fluid) -> tuple[np.ndarray,
                                                                                                      np.ndarray]:
    """(K, C): the derivatives of the force per unit length with respect to a section's displacement and
    velocity (N/m^2 and N s/m^2), 2x2 in the components along (e_eps, e_chi) of the mid-plane.

    Central differences of the model's kernel at fixed Omega_a, Omega_b; ``annulus.length`` is not used.
    """
    _per_length(model)
    _check_kappa(annulus.kappa)
    a, b, mu = annulus.a, annulus.b, fluid.mu
    eps, omk = annulus.kappa * (b - a), annulus.one_minus_kappa
    v = np.array([motion.eps_dot, eps * motion.chi_dot])
    zero = np.zeros(2)
    h = _STEP * min(eps, omk * (b - a))
    # forces are linear in the velocity for most models, and smooth in it for all: any step of its scale will do
    h_v = _STEP * (abs(v[0]) + abs(v[1]) + (b - a) * (abs(motion.omega_a) + abs(motion.omega_b))) or _STEP
    k, c = np.empty((2, 2)), np.empty((2, 2))
    for j in range(2):
        step = np.zeros(2)
        step[j] = h
        k[:, j] = (_section(model, a, b, mu, eps, omk, step, v, motion.omega_a, motion.omega_b)[:2]
                   - _section(model, a, b, mu, eps, omk, -step, v, motion.omega_a, motion.omega_b)[:2]) / (2.0 * h)
        step[j] = h_v
        c[:, j] = (_section(model, a, b, mu, eps, omk, zero, v + step, motion.omega_a, motion.omega_b)[:2]
                   - _section(model, a, b, mu, eps, omk, zero, v - step, motion.omega_a, motion.omega_b)[:2]
                   ) / (2.0 * h_v)
    return k, c


@dataclass(frozen=True)
class TiltHistory:
    """A tilt along a trajectory (:func:`tilt_history`).

    Attributes
    ----------
    t : ndarray
        Times (s).
    gain : ndarray
        |gamma(t)| / |gamma(t0)| for the worst unit tilt at t0 (released without a rate): the largest
        singular value of the map from the initial tilt to the tilt at t.
    frozen_growth : ndarray
        The largest real part of the tilt equation's eigenvalues with its coefficients frozen at t (1/s):
        positive where the aligned motion of that instant, held, would tilt.
    frozen_frequency : ndarray
        The imaginary part of that eigenvalue (rad/s): the whirl's rate.
    """

    t: np.ndarray
    gain: np.ndarray
    frozen_growth: np.ndarray
    frozen_frequency: np.ndarray

    @property
    def largest_gain(self) -> float:
        return float(np.max(self.gain))


def _columns(trajectory) -> dict:
    """The run's columns the tilt equation reads, one row per time (at a switch, the phase before it)."""
    if trajectory.dimensionless or trajectory.equations != "full":
        msg = "tilt_history takes a run of the full equations (2.1)-(2.4) in SI units"
        raise ValueError(msg)
    phase = trajectory.columns.get("phase")
    if phase is not None and np.any(phase == PHASE_CODES[COMPLIANT]):
        msg = ("a run with the compliant contact holds a tilt by the asperities' elasticity, which the tilt "
               "equation leaves out: take a run with the hard contact")
        raise ValueError(msg)
    t, unique = np.unique(trajectory.t, return_index=True)
    names = ("one_minus_kappa", "kappa_dot", "phi", "phi_dot", "omega_a", "omega_b") + (() if phase is None
                                                                                         else ("phase",))
    return {name: trajectory.columns[name][unique] for name in names} | {"t": t}


def _matrix(model, ap, fluid, row, spin_rate) -> np.ndarray:
    """The tilt equation's matrix, d(gamma, gamma')/dt = A (gamma, gamma'), at one row of a run, in the plane's
    components (x, z)."""
    omk = float(row["one_minus_kappa"])
    chi = float(row["phi"]) - ap.alpha
    annulus = Annulus(a=ap.a, b=ap.b, length=ap.length, one_minus_kappa=omk)
    motion = Motion(eps_dot=ap.delta * float(row["kappa_dot"]), chi_dot=float(row["phi_dot"]),
                    omega_a=float(row["omega_a"]), omega_b=float(row["omega_b"]))
    k, c = tilt_coefficients(model, annulus, motion, fluid)
    q = np.array([[math.sin(chi), math.cos(chi)], [math.cos(chi), -math.sin(chi)]])  # columns e_eps, e_chi
    j_plane = q @ J @ q.T  # the quarter turn in (x, z): the same matrix at every chi
    film = ap.length**3 / 12.0
    inertia_t = ap.m_eff * ap.length**2 / 12.0 + ap.m_a * ap.a**2 / 4.0
    inertia_a = ap.m_a * ap.a**2 / 2.0
    out = np.zeros((4, 4))
    out[:2, 2:] = np.eye(2)
    out[2:, :2] = (film * q @ k @ q.T + inertia_a * spin_rate * j_plane) / inertia_t
    out[2:, 2:] = (film * q @ c @ q.T + inertia_a * motion.omega_a * j_plane) / inertia_t
    return out


def tilt_history(trajectory, apparatus, forces: str | KernelModel = "stokes-exact", *,
                 t_span=None, substeps: int = SUBSTEPS) -> TiltHistory:
    """Integrate the linear tilt equation (module docstring) along ``trajectory`` of ``apparatus``.

    Parameters
    ----------
    trajectory : Trajectory
        A free run of the full equations in SI (:func:`dynamics.simulate`), with rows dense enough to
        interpolate (every step, as runs give by default).
    apparatus : Apparatus
        Its device.
    forces : str or KernelModel
        The force model per unit length of the sections (ends 'infinite'): a registered name or a built model.
    t_span : (float, float), optional
        The part of the run; default all of it.
    substeps : int
        Exponentials per row interval (their error falls as substeps^-2; with 8, 1e-3 of the gain over 12 s of
        the default release, against scipy's Radau at rtol 1e-8 on the same matrix).
    """
    model = _per_length(kernel_model(forces) if isinstance(forces, str) else forces)
    cols = _columns(trajectory)
    t_rows = cols["t"]
    t0, t1 = (t_rows[0], t_rows[-1]) if t_span is None else map(float, t_span)
    inside = (t_rows >= t0) & (t_rows <= t1)
    rows = np.flatnonzero(inside)
    if rows.size < 2:
        raise ValueError(f"t_span: the run has {rows.size} row(s) in {t0!r}..{t1!r} s, at least 2 are needed")
    if "phase" in cols and np.any(cols["phase"][rows[1:-1]] != PHASE_CODES[FREE]):
        msg = (f"t_span: {t0!r}..{t1!r} s holds contact phases, where the line contact keeps the axis parallel: "
               "the span must lie within one free flight (tilt_in_flights takes each)")
        raise ValueError(msg)
    _check_kappa(1.0 - cols["one_minus_kappa"][rows])
    ap = apparatus
    fluid = Fluid(nu=ap.nu, rho=ap.rho)
    t = t_rows[rows]
    spin_rate = PchipInterpolator(t_rows, cols["omega_a"]).derivative()(t)
    matrices = np.array([_matrix(model, ap, fluid, {name: values[i] for name, values in cols.items()}, rate)
                         for i, rate in zip(rows, spin_rate, strict=True)])
    # from row to row (the run's steps), a product of exponentials of the matrix at the midpoints of ``substeps``
    # equal parts, the matrix linear between rows: exact for the stiff squeeze modes (rates above 1e9/s near
    # contact), second order in the part's length through the commutators of the stiff and slow modes
    h = np.diff(t)[:, None, None] / substeps
    steps = np.broadcast_to(np.eye(4), matrices[1:].shape)
    for k in range(substeps):
        w = (k + 0.5) / substeps
        steps = expm(((1.0 - w) * matrices[:-1] + w * matrices[1:]) * h) @ steps
    y = np.zeros((4, 2))
    y[0, 0] = y[1, 1] = 1.0  # unit tilts along x and z, released without a rate
    gain = np.empty(t.size)
    gain[0] = 1.0
    for i, step in enumerate(steps, start=1):
        y = step @ y
        gain[i] = np.linalg.norm(y[:2], 2)
    eigen = np.linalg.eigvals(matrices)
    worst = eigen[np.arange(t.size), np.argmax(eigen.real, axis=1)]
    return TiltHistory(t=t, gain=gain, frozen_growth=worst.real, frozen_frequency=np.abs(worst.imag))


@dataclass(frozen=True)
class FlightTilts:
    """A tilt over each free flight of a run with contact phases (:func:`tilt_in_flights`).

    Attributes
    ----------
    start, end : ndarray
        Each flight's start (a lift-off, or the release) and end (the next touch, or the run's end) (s).
    gain : ndarray
        The largest gain over the flight of the worst unit tilt at its start (:attr:`TiltHistory.gain`).
    frozen_growth : ndarray
        The largest growth rate of the frozen tilt equation over the flight (1/s).
    """

    start: np.ndarray
    end: np.ndarray
    gain: np.ndarray
    frozen_growth: np.ndarray

    @property
    def largest_gain(self) -> float:
        """The largest gain over every flight; 1 for a run with none (a tilt never starts)."""
        return float(np.max(self.gain, initial=1.0))


def flights(trajectory) -> list[tuple[float, float]]:
    """The free flights of a run, (start, end) in s: from the release if it starts free and from each lift-off,
    to the next touch or the run's end."""
    free = PHASE_CODES[FREE]
    t = trajectory.columns["t"]
    start = float(t[0]) if trajectory.columns["phase"][0] == free else None
    out = []
    for event in sorted(trajectory.events, key=lambda event: event["t"]):
        if event["name"] == "lift":
            start = float(event["t"])
        elif event["name"] == "touch" and start is not None:
            out.append((start, float(event["t"])))
            start = None
    if start is not None:
        out.append((start, float(t[-1])))
    return out


def tilt_in_flights(trajectory, apparatus, forces: str | KernelModel = "stokes-exact", *,
                    substeps: int = SUBSTEPS) -> FlightTilts:
    """:func:`tilt_history` over each free flight of ``trajectory``, a run of the full equations with the hard
    contact (module docstring: contact), with rows dense enough to interpolate (every step).

    ``forces`` and ``substeps`` as for :func:`tilt_history`.
    """
    if "phase" not in trajectory.columns:
        msg = "tilt_in_flights takes a run with contact phases; a free run is one flight: take tilt_history"
        raise ValueError(msg)
    model = _per_length(kernel_model(forces) if isinstance(forces, str) else forces)
    spans = [span for span in flights(trajectory) if span[1] > span[0]]
    histories = [tilt_history(trajectory, apparatus, model, t_span=span, substeps=substeps) for span in spans]
    return FlightTilts(start=np.array([span[0] for span in spans]), end=np.array([span[1] for span in spans]),
                       gain=np.array([history.largest_gain for history in histories]),
                       frozen_growth=np.array([float(np.max(history.frozen_growth)) for history in histories]))
