r"""Unsteady plane Navier-Stokes flow between two rigid circular walls, stepped with the walls' velocities.

Equations
---------
In the frame translating with the outer centre B, per unit length, with the map
variables of :mod:`lubrication.unsteady.mapping` (x Chebyshev across, theta Fourier
around) and the vorticity omega = -Lap psi (counterclockwise-positive, walls.py):

    d omega/dt|_(x,theta) + (u - x_t) . grad omega = nu Lap omega,    Lap psi + omega = 0,

the arbitrary Lagrangian-Eulerian form at fixed computational coordinates, x_t the
velocity of a grid point (:meth:`AnnulusMap.mesh_velocity`). In the map variables
u . grad omega = g (psi_theta omega_s - psi_s omega_theta) and
x_t . grad omega = Re(mu) omega_s + Im(mu) omega_theta; the solver's unknown is
Psi = H psi (mapping.py), and g psi_theta = (H Psi_theta - H_theta Psi)/k,
g psi_s = (H Psi_s - H_s Psi)/k are formed without dividing by H. In this non-conservative
collocation form the geometric conservation law holds trivially (a uniform field
has no gradient, whatever the grid does); the tests check it on a moving grid.

Time step (timestepping.py): variable-step BDF2 (implicit Euler on the first two
steps: the initial level, where the walls may start impulsively, enters no BDF
formula or predictor after the first step; in the first step the fluid's
acceleration at the inner wall, which the wall pressure and the circulation
condition need, starts from the fluid's velocity there, not the wall's:
:attr:`FlowLevel.fluid_q`) on the
viscous term, the metric and the boundary conditions; the convective term
N = -(u - x_t) . grad omega explicit, extrapolated linearly from the last two
levels. One step solves, in one linear system (system.py), the new flow, the
inner wall's stream-function constant (fixed by the circulation condition) and
the new wall velocities q = (U_x, U_z, Omega_a, Omega_b) from four linear wall
equations given by the caller,

    M q_new - C loads_new = r,    loads = (F_x, F_z, T_a, T_b) per unit length:

prescribed motion is M = I, C = 0, r = q(t_new); a free body puts its Newton laws
there, with the BDF derivative of its velocities (:meth:`UnsteadySolver.bdf`).

Geometry of the new level. z_A(t_new) follows from the new velocity by the same
BDF2 formula, alpha_0 z_new + alpha_1 z_n + alpha_2 z_{n-1} = dt U_new. Unless the
caller prescribes it, the step predicts z_new from the extrapolated velocity,
solves, corrects z_new from the computed U_new and solves again, until two
successive positions differ by less than ``geometry_tol`` times the narrowest
gap; a step whose corrections do not converge in ``max_corrections`` is rejected
and retried with half the step. The flow is stored with the geometry it was
solved on.

Error control. The local error of the step is estimated from the difference
between the BDF2 solution and the explicit quadratic predictor through the last
three levels (timestepping.py; linear through two, conservatively, when only two
BDF2 levels exist; the first steps, implicit Euler and the first two BDF2 ones,
keep the initial step uncontrolled), on omega (root-mean-square over the interior
nodes: the wall values are algebraic, the multipliers that keep the no-slip
conditions, and follow the BDF derivative of the interior field, so they jump
between the implicit Euler start and BDF2 however short the step) and,
when the caller asks (free motion), on the wall velocities and on z_A; the step
is accepted when the larger of these, scaled by atol + rtol |value|, is at most 1.

Loads (walls.py): the force on the inner wall from the wall pressure (integrated
from the tangential momentum balance, whose material acceleration at the wall is
the wall's) and the viscous traction; the torques on the inner wall about A and
on the outer wall about B. The uniform body force g_eff of the frame (gravity
less B's acceleration) adds -rho pi a^2 g_eff to the inner wall's force only.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from ..geometry import check_finite, check_range
from .mapping import MIN_ONE_MINUS_KAPPA_UNSTEADY, AnnulusMap
from .operator import pack, unpack
from .resolution import Resolution, default_resolution
from .spectral import Grid
from .system import StepSystem, flow_rhs, one_blas_thread
from .timestepping import (
    Bdf,
    bdf,
    error_constant,
    extrapolation,
    next_step,
    predictor_weights,
)

__all__ = ["FlowLevel", "LOAD_NAMES", "StepControl", "StepResult", "UnsteadySolver", "VELOCITY_NAMES",
           "prescribed_wall"]

logger = logging.getLogger(__name__)

#: Order of the loads per unit length: force on the inner wall (N/m), torque on it about A
#: and torque on the outer wall about B (N m/m), clockwise positive.
LOAD_NAMES = ("F_x", "F_z", "T_a", "T_b")
#: Order of the wall velocities q: inner centre velocity (m/s), spins (rad/s, clockwise).
VELOCITY_NAMES = ("U_x", "U_z", "Omega_a", "Omega_b")


@dataclass(frozen=True)
class StepControl:
    """Time-step control.

    Parameters
    ----------
    rtol : float
        Relative local error per step.
    atol : float or None
        Absolute error of the vorticity (1/s); default rtol times the vorticity
        scale V/delta of the largest wall speed V met so far.
    adaptive : bool
        False: every step has the size asked for (convergence studies).
    safety, fac_min, fac_max : float
        Step-size law (timestepping.py).
    geometry_tol : float
        Corrections of z_new stop when they change it by less than this times the narrowest gap.
    max_corrections : int
    refactor_ratio : float
        A factorisation is reused (defect correction) only if alpha_0/dt has changed by less than
        this factor; otherwise the step factorises anew.
    reuse : bool
        Reuse factorisations across steps and corrections (False: factorise every solve).
    hold : float
        An accepted step whose proposed successor is within this factor of it is kept
        unchanged, so that its factorisation can be reused.
    """

    rtol: float = 1e-4
    atol: float | None = None
    adaptive: bool = True
    safety: float = 0.8
    fac_min: float = 0.2
    fac_max: float = 2.0
    geometry_tol: float = 1e-6
    max_corrections: int = 8
    refactor_ratio: float = 1.25
    reuse: bool = True
    hold: float = 1.25

    def __post_init__(self):
        check_range("rtol", self.rtol, 0.0, 1.0, low_open=True)
        if self.atol is not None:
            check_range("atol", self.atol, 0.0, math.inf, low_open=True, unit="1/s")
        check_range("geometry_tol", self.geometry_tol, 0.0, 1.0, low_open=True)


@dataclass
class FlowLevel:
    """The state at one time level.

    Attributes
    ----------
    t : float
    z_a : complex
        Inner centre (m).
    q : ndarray, shape (4,)
        Wall velocities :data:`VELOCITY_NAMES`.
    h_psi, omega : ndarray, shape (n_modes, n_r)
        Fourier-Chebyshev coefficients of Psi = H psi (the stream function times the
        weight H of :mod:`lubrication.unsteady.mapping`) and of omega
        (counterclockwise-positive, walls.py), in the solver's length unit b:
        H psi / b^2 and omega, both in 1/s. :meth:`UnsteadySolver.fields` gives psi.
    c_in : float
        psi / b^2 on the inner wall minus Im(conj(U) zeta)/b^2 there.
    loads : ndarray, shape (4,)
        :data:`LOAD_NAMES`, per unit length.
    convection : ndarray, shape (n_modes, n_r)
        -(u - x_t) . grad omega at this level.
    dt : float or None
        The step that led to this level.
    order : int
        1 if it came from an implicit Euler step, 2 from BDF2, 0 for the initial level.
    fluid_q : ndarray, shape (4,), or None
        The wall velocities as the fluid along the inner wall has them (None: ``q``, as at
        every stepped level, where no-slip holds). The initial level may break no-slip
        (walls set moving in a fluid at rest): the fluid's acceleration at the inner wall
        in the first step, which the wall pressure and the circulation condition need, is
        then measured from the fluid's velocity there, not from the wall's
        (:meth:`UnsteadySolver.fluid_wall_velocity`).
    """

    t: float
    z_a: complex
    q: np.ndarray
    h_psi: np.ndarray
    omega: np.ndarray
    c_in: float
    loads: np.ndarray
    convection: np.ndarray
    dt: float | None = None
    order: int = 0
    fluid_q: np.ndarray | None = None

    @property
    def q_seen_by_fluid(self) -> np.ndarray:
        """``fluid_q`` where given, else ``q``."""
        return self.q if self.fluid_q is None else self.fluid_q


@dataclass
class StepResult:
    """Outcome of one attempted step."""

    accepted: bool
    dt: float
    dt_next: float
    error: float
    corrections: int
    factorisations: int
    sweeps: int
    reason: str = ""


@dataclass
class _Counters:
    steps: int = 0
    rejected: int = 0
    factorisations: int = 0
    solves: int = 0
    sweeps: int = 0
    corrections: int = 0


class UnsteadySolver:
    """Unsteady Navier-Stokes flow in the annulus, one monolithic step at a time.

    Parameters
    ----------
    a, b : float
        Inner and outer radius (m).
    nu, rho : float
        Kinematic viscosity (m^2/s) and density (kg/m^3).
    resolution : Resolution or None
        Grid; default :func:`default_resolution` at the starting position.
    g_eff : complex or (float, float)
        Uniform body force per unit mass of the frame, x + i z (m/s^2): gravity
        less the acceleration of B. Enters only the inner wall's force.
    control : StepControl or None
    """

    def __init__(self, a: float, b: float, nu: float, rho: float, resolution: Resolution | None = None, *,
                 g_eff=0j, control: StepControl | None = None):
        self.a = check_range("a", a, 0.0, math.inf, low_open=True, unit="m")
        self.b = check_finite("b", b)
        if not self.b > self.a:
            msg = f"b must be greater than a = {self.a:g} m (outer radius), got {b!r}"
            raise ValueError(msg)
        self.nu = check_range("nu", nu, 0.0, math.inf, low_open=True, unit="m^2/s")
        self.rho = check_range("rho", rho, 0.0, math.inf, low_open=True, unit="kg/m^3")
        self.mu = self.rho * self.nu
        if not isinstance(g_eff, complex):
            g_eff = complex(*g_eff) if np.ndim(g_eff) == 1 else complex(g_eff)
        check_finite("g_eff (x)", g_eff.real)
        check_finite("g_eff (z)", g_eff.imag)
        self.g_eff = g_eff
        # Internally lengths are in units of b (time in s): the stream function then has the
        # size of the vorticity, and the LU's equilibration works on a matrix whose ranges
        # come from the geometry alone (in SI units it failed at 1 - kappa = 1e-4).
        self._unit = self.b
        self._q_scale = np.array([1.0 / self.b, 1.0 / self.b, 1.0, 1.0])   # q internal = q * scale
        self._load_scale = np.array([1.0, 1.0, self.b, self.b])            # loads SI = internal * scale
        self._nu = self.nu / self.b**2
        self._rho = self.rho * self.b**3
        self.resolution = resolution
        self.control = control or StepControl()
        self.grid: Grid | None = None
        self.levels: list[FlowLevel] = []
        self.counters = _Counters()
        self._factors: StepSystem | None = None
        self._fresh = True
        self._speed = 0.0

    # ------------------------------------------------------------------ set-up

    def geometry(self, z_a: complex) -> AnnulusMap:
        """The map at inner centre ``z_a`` (m), in the solver's length unit b; refuses gaps it does not resolve."""
        geo = AnnulusMap(self.a / self.b, 1.0, complex(z_a) / self.b)
        if geo.one_minus_kappa < MIN_ONE_MINUS_KAPPA_UNSTEADY * (1.0 - 1e-9):  # slack for rounding
            msg = (f"one_minus_kappa = 1 - kappa must be at least {MIN_ONE_MINUS_KAPPA_UNSTEADY:g} for the unsteady "
                   f"solver (the narrowest gap it resolves), reached {geo.one_minus_kappa:.3g} at z_a = {z_a}")
            raise ValueError(msg)
        return geo

    def _ensure_grid(self, geo: AnnulusMap):
        if self.grid is None:
            if self.resolution is None:
                self.resolution = default_resolution(geo)
            res = self.resolution
            self.grid = Grid(res.n_theta, res.n_r, res.dealias)

    def start(self, z_a: complex = 0j, q=(0.0, 0.0, 0.0, 0.0), *, t: float = 0.0,
              h_psi: np.ndarray | None = None, omega: np.ndarray | None = None, c_in: float = 0.0):
        """Set the initial level: fluid at rest unless ``h_psi`` and ``omega`` coefficients are given.

        ``h_psi`` and ``omega`` are the coefficients of :class:`FlowLevel` (H psi and the
        vorticity, in units of b), as :meth:`fields_from_stream_function` makes them."""
        geo = self.geometry(complex(z_a))
        self._ensure_grid(geo)
        q = np.array(q, dtype=float)
        if q.shape != (4,) or not np.all(np.isfinite(q)):
            msg = f"q must be 4 finite numbers (U_x, U_z, Omega_a, Omega_b), got {q!r}"
            raise ValueError(msg)
        shape = (self.grid.n_modes, self.grid.n_r)
        psi = np.zeros(shape, dtype=complex) if h_psi is None else np.array(h_psi, dtype=complex)
        omega = np.zeros(shape, dtype=complex) if omega is None else np.array(omega, dtype=complex)
        if psi.shape != shape or omega.shape != shape:
            msg = f"h_psi and omega must have shape {shape}"
            raise ValueError(msg)
        qu = q * self._q_scale
        conv = self.convection(geo, psi, omega, complex(qu[0], qu[1]))
        loads = self._loads_of_level(geo, psi, omega, qu)
        fluid_q = np.array([*self.fluid_wall_velocity(geo, psi), q[3]])
        self.levels = [FlowLevel(float(t), complex(z_a), q, psi, omega, float(c_in), loads, conv, fluid_q=fluid_q)]
        self._fresh = True
        self._factors = None
        self._note_speed(q)

    def start_from_rest(self, z_a: complex = 0j, q=(0.0, 0.0, 0.0, 0.0), t: float = 0.0):
        """Fluid at rest at time ``t``, inner centre at ``z_a``, walls with velocities ``q`` from then on."""
        self.start(z_a, q, t=t)

    def fields_from_stream_function(self, z_a: complex, stream) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients (Psi = H psi, omega = -Lap psi) of a stream function given as ``stream(zeta)`` (m^2/s).

        The pair that :meth:`start` takes (:class:`FlowLevel`)."""
        geo = self.geometry(complex(z_a))
        self._ensure_grid(geo)
        grid = self.grid
        zeta = geo.zeta(geo.w(grid.x, grid.theta))
        weight = geo.stream_weight_fields(grid.x, grid.theta)[0]
        big_psi = grid.to_spectral(weight * np.asarray(stream(zeta * self.b), dtype=float)) / self.b**2
        from .operator import ImplicitOperator
        omega = -ImplicitOperator(grid, geo, self._nu, 0.0).stream_laplacian(big_psi)
        return big_psi, omega

    # ------------------------------------------------------------------ physics

    def fluid_wall_velocity(self, geo: AnnulusMap, psi: np.ndarray) -> tuple[float, float, float]:
        """(U_x, U_z, Omega_a) of the rigid motion that the fluid's velocity along the inner wall stands for.

        With the tangential velocity u . t = -d psi/dn (t counterclockwise, n into the
        fluid; u . t ds = -psi_s d theta), a rigid motion U + Omega_a has
        oint (zeta - z_A)(u . t) ds = -i pi a^2 U and oint u . t ds = -2 pi a^2 Omega_a
        (clockwise Omega_a), so for any field

            U = -(i/(pi a^2)) int (zeta - z_A) psi_s d theta,   Omega_a = (1/(2 pi a^2)) int psi_s d theta:

        exactly the two moments of the wall velocity that the wall pressure's force
        (walls.py) and the circulation condition involve. Zero for a fluid at rest;
        the walls' own (U, Omega_a) where the fluid meets no-slip. ``psi`` holds the
        coefficients of Psi = H psi in the solver's units; the result is in SI.
        """
        grid = self.grid
        x = grid.x[-1:]
        h, h_s, _ = geo.stream_weight_fields(x, grid.theta_pad)
        scale = 2.0 / geo.tau
        big = grid.to_physical(psi[:, -1:])
        big_s = grid.to_physical(scale * (psi @ grid.d1[-1])[:, None])
        psi_s = ((big_s - h_s * big / h) / h)[0]
        zeta = geo.zeta(geo.w(x, grid.theta_pad))[0] - geo.z_a
        mean = 2.0 * math.pi / grid.n_pad
        a = geo.a
        u = -1j / (math.pi * a * a) * np.sum(zeta * psi_s) * mean
        omega_a = np.sum(psi_s) * mean / (2.0 * math.pi * a * a)
        return u.real * self.b, u.imag * self.b, float(omega_a)

    def convection(self, geo: AnnulusMap, psi: np.ndarray, omega: np.ndarray, u: complex) -> np.ndarray:
        """Coefficients of N = -(u - x_t) . grad omega (padded products, truncated)."""
        grid = self.grid
        scale = 2.0 / geo.tau
        # g psi_theta = (H Psi_theta - H_theta Psi)/k, g psi_s = (H Psi_s - H_s Psi)/k (mapping.py)
        big = grid.to_physical(psi)
        ps_t = grid.to_physical(grid.d_theta(psi))
        ps_s = grid.to_physical(scale * grid.d_x(psi))
        om_t = grid.to_physical(grid.d_theta(omega))
        om_s = grid.to_physical(scale * grid.d_x(omega))
        h, h_s, h_t = geo.stream_weight_fields(grid.x, grid.theta_pad)
        k_metric = (geo.b * geo.one_minus_p2) ** 2
        g_psi_t = (h * ps_t - h_t * big) / k_metric
        g_psi_s = (h * ps_s - h_s * big) / k_metric
        mesh = geo.mesh_velocity(u, grid.x, grid.theta_pad)
        n = -(g_psi_t * om_s - g_psi_s * om_t) + mesh.real * om_s + mesh.imag * om_t
        return grid.to_spectral(n)

    def _loads_of_level(self, geo, psi, omega, q) -> np.ndarray:
        """Loads of a stored level without acceleration (used for the initial level)."""
        sys_ = StepSystem(self.grid, geo, self._nu, self._rho, 0.0)
        x = np.concatenate([psi, omega], axis=1).reshape(-1)
        s = np.array([0.0, *q])
        g = self.g_eff / self.b
        lam0 = np.array([-sys_.added_mass * g.real, -sys_.added_mass * g.imag, 0.0, 0.0])
        return sys_.loads(x, s, lam0) * self._load_scale

    def _note_speed(self, q):
        # the largest wall speed met, in units of b per second
        self._speed = max(self._speed, max(abs(complex(q[0], q[1])), abs(q[2]) * self.a, abs(q[3]) * self.b) / self.b)

    # ------------------------------------------------------------------ stepping

    @property
    def state(self) -> FlowLevel:
        """The newest level."""
        return self.levels[0]

    def bdf(self, dt: float) -> Bdf:
        """BDF coefficients of a step ``dt`` from the newest level (for the caller's wall equations)."""
        prev = self.levels[0].dt if len(self.levels) >= 2 else None
        return bdf(dt, prev)

    def _system(self, geo: AnnulusMap, c0: float) -> tuple[StepSystem, StepSystem | None]:
        """The step's system and the factors to solve it with (None: factorise it)."""
        system = StepSystem(self.grid, geo, self._nu, self._rho, c0)
        f = self._factors
        if self.control.reuse and f is not None and \
                max(c0 / f.c0, f.c0 / c0) <= self.control.refactor_ratio:
            return system, f
        return system, None

    def _solve(self, geo, b_: Bdf, rhs, wall, q_hist, guess=None):
        system, factors = self._system(geo, b_.c0)
        e, g, h, lam0 = system.borders(b_, wall, q_hist, self.g_eff / self.b)
        sweeps = 0
        out = None
        if factors is not None:
            out = system.solve(rhs, e, g, h, factors, guess=guess)
            if out is not None:
                sweeps = out[2]
        factorised = 0
        if out is None:
            system.factorise()
            factorised = 1
            self._factors = system
            out = system.solve(rhs, e, g, h)
        x, s, _ = out
        self.counters.solves += 1
        self.counters.sweeps += sweeps
        self.counters.factorisations += factorised
        loads = system.loads(x, s, lam0)
        return x, s, loads, factorised, sweeps

    def step(self, dt: float, wall, z_new: complex | None = None, *, control_motion: bool | None = None) -> StepResult:
        """Attempt one step of size ``dt``; on success append the new level (see ``_step``)."""
        with one_blas_thread():
            return self._step(dt, wall, z_new, control_motion)

    def _step(self, dt, wall, z_new, control_motion) -> StepResult:
        """Attempt one step of size ``dt``; on success append the new level.

        Parameters
        ----------
        dt : float
        wall : (M, C, r) or callable
            The wall equations M q_new - C loads_new = r (4 x 4, 4 x 4, 4); a
            callable is called as ``wall(t_new, bdf)`` and returns them.
        z_new : complex or None
            The inner centre at the new level, if prescribed; otherwise from BDF2 of U.
        control_motion : bool or None
            Include q and z_A in the error estimate (default: when z_new is not prescribed).
        """
        ctl = self.control
        dt = check_range("dt", dt, 0.0, math.inf, low_open=True, unit="s")
        lv = self.levels
        now = lv[0]
        before = lv[1] if len(lv) >= 2 else None
        b_ = self.bdf(dt)
        t_new = now.t + dt
        mats = wall(t_new, b_) if callable(wall) else wall
        m_, c_, r_ = (np.asarray(v, dtype=float) for v in mats)
        if m_.shape != (4, 4) or c_.shape != (4, 4) or r_.shape != (4,):
            msg = "wall equations must be M (4 x 4), C (4 x 4) and r (4,)"
            raise ValueError(msg)
        # in internal units: q = q_int / scale, loads = loads_int * load_scale
        wall_ = (m_ / self._q_scale[None, :], c_ * self._load_scale[None, :], r_)
        w_n, w_b = extrapolation(dt, now.dt if before is not None else None)
        conv = w_n * now.convection + (w_b * before.convection if before is not None else 0.0)
        om_hist = b_.history(now.omega, before.omega if before is not None else 0.0)
        # the fluid's acceleration at the inner wall (wall pressure, circulation condition)
        q_hist = b_.history(now.q_seen_by_fluid, before.q_seen_by_fluid if before is not None else 0.0) \
            * self._q_scale
        z_hist = b_.history(now.z_a, before.z_a if before is not None else 0.0) / self.b
        rhs = flow_rhs(self.grid, conv - om_hist)
        # the predictor uses the leading BDF2 levels only: the wall vorticity (and through it
        # the vorticity next to the wall) follows the derivative formula, and jumps where
        # implicit Euler gives way to BDF2
        smooth = 0
        for level in lv:
            if level.order != 2:
                break
            smooth += 1
        steps = tuple(level.dt for level in lv[:smooth - 1])[:2]  # (h', h'') of the usable levels
        pw = predictor_weights(dt, steps) if smooth else (1.0,)
        controlled = smooth >= 2
        q_pred = sum(w * level.q for w, level in zip(pw, lv)) * self._q_scale
        # the extrapolated solution starts a defect correction
        guess = (pack(sum(w * level.h_psi for w, level in zip(pw, lv)),
                      sum(w * level.omega for w, level in zip(pw, lv))),
                 np.array([sum(w * level.c_in for w, level in zip(pw, lv)), *q_pred]))
        corrections = 0
        factorisations = 0
        sweeps_total = 0
        if z_new is not None:
            z = complex(z_new) / self.b
            geo = self.geometry(z * self.b)
            x, s, loads, nf, sw = self._solve(geo, b_, rhs, wall_, q_hist, guess)
            factorisations += nf
            sweeps_total += sw
        else:
            # BDF2 position of the predicted velocity
            z = (complex(q_pred[0], q_pred[1]) - z_hist) / b_.c0
            converged = False
            for corrections in range(1, ctl.max_corrections + 1):
                geo = self.geometry(z * self.b)
                x, s, loads, nf, sw = self._solve(geo, b_, rhs, wall_, q_hist, guess)
                guess = (x, s)
                factorisations += nf
                sweeps_total += sw
                z_next = (complex(s[1], s[2]) - z_hist) / b_.c0
                if abs(z_next - z) <= ctl.geometry_tol * geo.gap:
                    converged = True
                    break
                z = z_next
                if abs(z) >= 1.0 - self.a / self.b:
                    break
            self.counters.corrections += corrections
            if not converged:
                self.counters.rejected += 1
                return StepResult(False, dt, 0.5 * dt, math.inf, corrections, factorisations, sweeps_total,
                                  "the corrections of the new position did not converge")
        psi, om = unpack(x, self.grid.n_r)
        psi = self.grid.symmetrise(psi)
        om = self.grid.symmetrise(om)
        q_new = s[1:].copy()
        # local error estimate
        e_const = error_constant(dt, steps)
        om_pred = sum(w * level.omega for w, level in zip(pw, lv))
        self._note_speed(q_new / self._q_scale)
        atol = ctl.atol
        if atol is None:
            atol = ctl.rtol * max(self._speed, 1e-300) / (1.0 - self.a / self.b)
        # the wall values of omega are algebraic (the multipliers of no-slip, set by the
        # derivative of the interior field): the estimate is on the interior, as for a DAE
        inner = slice(1, self.grid.n_r - 1)
        err_om = e_const * _rms((om - om_pred)[:, inner]) / (atol + ctl.rtol * _rms(om[:, inner]))
        err = err_om
        if control_motion is None:
            control_motion = z_new is None
        if control_motion:
            z_pred = sum(w * level.z_a for w, level in zip(pw, lv)) / self.b
            scale_u = ctl.rtol * self._speed + 1e-300
            err_q = np.abs(q_new - q_pred) / (ctl.rtol * np.abs(q_new) +
                                              scale_u * np.array([1.0, 1.0, self.b / self.a, 1.0]))
            err_z = abs(z - z_pred) / (ctl.rtol * geo.gap + 1e-300)
            err = max(err, e_const * float(err_q.max()), e_const * err_z)
        if ctl.adaptive and controlled:
            dt_next = next_step(dt, err, safety=ctl.safety, fac_min=ctl.fac_min, fac_max=ctl.fac_max)
            if err <= 1.0 and 1.0 / ctl.hold <= dt_next / dt <= ctl.hold:
                dt_next = dt  # hold the step (and the factorisation) within the tolerance
        else:
            dt_next = dt
        if ctl.adaptive and controlled and err > 1.0:
            self.counters.rejected += 1
            return StepResult(False, dt, dt_next, err, corrections, factorisations, sweeps_total,
                              "local error above tolerance")
        u_new = complex(q_new[0], q_new[1])  # internal units
        new = FlowLevel(t_new, z * self.b, q_new / self._q_scale, psi, om, float(s[0]), loads * self._load_scale,
                        self.convection(geo, psi, om, u_new), dt, 2 if before is not None else 1)
        # the initial level is kept out of every later BDF formula and predictor: the
        # walls may have started impulsively, and no polynomial through it is smooth
        self.levels = [new] if self._fresh else [new, *lv[:2]]
        self._fresh = False
        self.counters.steps += 1
        return StepResult(True, dt, dt_next, err, corrections, factorisations, sweeps_total)

    def regrid(self, resolution: Resolution) -> None:
        """Carry the stored levels over to another grid (a coupled run whose gap narrows or widens).

        Fourier modes are kept or truncated and new ones start at zero; across the gap the
        values are the Chebyshev interpolant's at the new points. Both are exact for what the
        new grid can hold, at the stored geometries; the factorisation is made anew.
        """
        if not self.levels:
            raise ValueError("regrid needs a started solver")
        old = self.grid
        new = Grid(resolution.n_theta, resolution.n_r, resolution.dealias)
        across = _chebyshev_transfer(old.n_r, new.n_r)
        keep = min(old.K, new.K)

        def carry(f: np.ndarray) -> np.ndarray:
            out = np.zeros((new.n_modes, old.n_r), dtype=complex)
            out[new.K - keep:new.K + keep + 1] = f[old.K - keep:old.K + keep + 1]
            return out @ across.T

        for level in self.levels:
            level.h_psi, level.omega, level.convection = carry(level.h_psi), carry(level.omega), carry(level.convection)
        self.grid, self.resolution, self._factors = new, resolution, None

    # ------------------------------------------------------------------ output

    def fields(self, level: FlowLevel | None = None) -> dict[str, np.ndarray]:
        """Vorticity, stream function and velocity on the physical grid points of a level.

        Returns
        -------
        dict
            ``x``, ``z`` (m), shape (n_r, n_theta): positions of the grid points
            (row 0 on the outer wall, the last row on the inner one);
            ``vorticity`` (1/s, clockwise positive, as the project's rotations);
            ``stream_function`` (m^2/s, u_x = d psi/dz, u_z = -d psi/dx);
            ``u_x``, ``u_z`` (m/s), in the frame translating with B.
        """
        lv = level or self.levels[0]
        grid = self.grid
        geo = self.geometry(lv.z_a)
        n = grid.n_theta
        w = geo.w(grid.x, grid.theta)
        zeta = geo.zeta(w) * self.b
        scale = 2.0 / geo.tau
        h, h_s, h_t = geo.stream_weight_fields(grid.x, grid.theta)
        psi = grid.to_physical(lv.h_psi, n) / h
        ps_s = (grid.to_physical(scale * grid.d_x(lv.h_psi), n) - h_s * psi) / h
        ps_t = (grid.to_physical(grid.d_theta(lv.h_psi), n) - h_t * psi) / h
        # u_x + i u_z = -i grad psi, grad psi = (psi_s + i psi_theta)/conj(zeta_sigma)
        vel = -1j * (ps_s + 1j * ps_t) / np.conj(geo.dzeta_dsigma(w)) * self.b
        return {"x": zeta.real, "z": zeta.imag, "vorticity": -grid.to_physical(lv.omega, n),
                "stream_function": psi * self.b**2, "u_x": vel.real, "u_z": vel.imag}


def _chebyshev_transfer(n_from: int, n_to: int) -> np.ndarray:
    """The matrix taking values at n_from Chebyshev-Lobatto points to the interpolant's values at n_to points."""
    if n_from == n_to:
        return np.eye(n_from)
    x_from = np.cos(np.pi * np.arange(n_from) / (n_from - 1))
    x_to = np.cos(np.pi * np.arange(n_to) / (n_to - 1))
    # columns: the interpolant of each unit vector, through its Chebyshev coefficients
    coefficients = np.polynomial.chebyshev.chebfit(x_from, np.eye(n_from), n_from - 1)
    return np.polynomial.chebyshev.chebval(x_to, coefficients).T


def _rms(f: np.ndarray) -> float:
    """Root mean square over theta (Parseval) and the Chebyshev nodes."""
    return float(np.sqrt(np.sum(np.abs(f) ** 2) / f.shape[1]))


def prescribed_wall(q) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wall equations of a prescribed motion: M = I, C = 0, r = q."""
    return np.eye(4), np.zeros((4, 4)), np.asarray(q, dtype=float)

