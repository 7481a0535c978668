"""The public kernel layer: one signature for the compiled forces of every model, and the data it reads.

Every force model that a trajectory can call has a compiled kernel::

    kernel(data, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b) -> (f_eps, f_chi, T_a)

with ``data`` the model's numbers packed in one float64 array (:class:`KernelModel`),
the radii ``a < b`` (m), the dynamic viscosity ``mu`` (Pa s), the axial ``length`` (m),
``kappa`` and ``omk`` = 1 - kappa (given apart, for precision near contact), the
radial speed ``eps_dot`` = eps' (m/s) and the wall rotations relative to the line of
centres ``w_a`` = Omega_a - chi', ``w_b`` = Omega_b - chi' (rad/s). It returns the
fluid's force on the inner cylinder along e_eps and e_chi (N) and its torque about
A (N m), for the whole length, in the conventions of :mod:`lubrication.geometry`.
One packed array, rather than a tuple of arrays, keeps one numba type for every
model, so that the equations of motion and the integrator are compiled once per
kernel and take any model's data.

The packed data. ``data[:HEADER]`` says where each block starts (0: absent):

* the model's own block (``data[MODEL]``, its size ``data[MODEL + 1]``), read by
  its kernel alone (a Reynolds grid's rule, a cavitation model and its pressures);
* the finite-length block of an annulus whose gap opens into end regions
  (:mod:`lubrication.finite_length`): L/a, the table's two coefficient arrays and
  its shape;
* the inertia block of the first inertial correction (:mod:`lubrication.inertia`):
  the fluid density, the kappa and delta/a nodes and the table;
* the end faces' films (:func:`end_face_forces`): the sum over the two ends of
  1/h, h the axial clearance between the inner cylinder's flat end face and the
  outer cylinder's end cap (0: no end faces).

A model whose forces are linear in (eps', W_a, W_b), its five resistance
coefficients a compiled function ``resistance(a, delta, mu, kappa, omk)``, gets its
kernel from :func:`lubrication.registry.linear_kernel`; the compositions of the registry, the
finite-length factors, the first inertial correction and the end faces, act on those coefficients
(:mod:`lubrication.registry`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from numerics.jit import jit, sources_hash

from .geometry import Annulus, Fluid, FluidForces, Motion

__all__ = ["HEADER", "MAX_END_GAP_OVER_A", "SOURCES_HASH", "KernelModel", "check_end_gap", "end_face_forces",
           "kernel_name", "linear", "model_block"]

# The header: where each block starts and the scalars of the compositions.
MODEL, MODEL_SIZE = 0, 1
ENDS, LENGTH_OVER_A, ZETA_MIN, X0, ROWS, COLS = range(2, 8)
INERTIA, RHO, N_KAPPA, N_DELTA, N_COLUMNS = range(8, 13)
END_FACES = 13
HEADER = 14
#: The largest end clearance over the inner radius taken: the faces' films are lubrication films, in error
#: by O(h/a) at the discs' rims.
MAX_END_GAP_OVER_A = 0.25


@dataclass(frozen=True)
class KernelModel:
    """A force model as the compiled equations of motion take it: its kernel and its packed data.

    Build it with :func:`lubrication.registry.kernel_model`.

    Attributes
    ----------
    name : str
        The model with its compositions: "stokes-exact/open-ends+inertia", ...
    kernel : numba dispatcher
        The compiled forces (the signature of the module docstring).
    kernel_name : str
        What the kernel is filed under: the model's name and a hash of the sources
        compiled into it, so that the equations compiled with it are filed apart.
    block : ndarray
        The model's own numbers (its kernel's block of :attr:`data`).
    length_table : tuple, optional
        (L/a, coefficients along e_eps, along e_chi, zeta_min, x0) of an annulus whose
        gap opens into end regions; None for an infinitely long one.
    inertia : tuple, optional
        (rho, kappa nodes, delta/a nodes, table) of the first inertial correction; None without it.
    end_gap : float, optional
        The axial clearance (m) between each flat end face of the inner cylinder and the outer
        cylinder's end cap, both ends alike (:func:`end_face_forces`); None: no end faces.
    smooth : bool
        Whether the forces are smooth in the state (a cavitating film's are only piecewise
        smooth, which the equations of motion take into account).
    options : dict
        The options the model was built with, for the record.
    """

    name: str
    kernel: object
    kernel_name: str
    block: np.ndarray = field(default_factory=lambda: np.empty(0))
    length_table: tuple | None = None
    inertia: tuple | None = None
    end_gap: float | None = None
    smooth: bool = True
    options: dict = field(default_factory=dict)

    @property
    def inertia_corrected(self) -> bool:
        return self.inertia is not None

    @cached_property
    def data(self) -> np.ndarray:
        """The packed array the kernel takes (module docstring)."""
        header = np.zeros(HEADER)
        parts = [header]
        size = HEADER

        def append(values: np.ndarray) -> int:
            nonlocal size
            start = size
            parts.append(np.asarray(values, dtype=float).ravel())
            size += parts[-1].size
            return start

        header[MODEL], header[MODEL_SIZE] = append(self.block), np.size(self.block)
        if self.length_table is not None:
            length_over_a, coef_eps, coef_chi, zeta_min, x0 = self.length_table
            header[ENDS] = append(coef_eps)
            append(coef_chi)
            header[LENGTH_OVER_A], header[ZETA_MIN], header[X0] = length_over_a, zeta_min, x0
            header[ROWS], header[COLS] = np.shape(coef_eps)
        if self.inertia is not None:
            rho, kappa_nodes, delta_nodes, table = self.inertia
            header[INERTIA] = append(kappa_nodes)
            append(delta_nodes)
            append(table)
            header[RHO], header[N_KAPPA], header[N_DELTA] = rho, np.size(kappa_nodes), np.size(delta_nodes)
            header[N_COLUMNS] = np.shape(table)[2]
        if self.end_gap is not None:
            header[END_FACES] = 2.0 / self.end_gap
        return np.concatenate(parts)

    def forces(self, annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
        """The kernel called from Python, for one instant (checks, single evaluations)."""
        f = self.kernel(self.data, annulus.a, annulus.b, fluid.mu, annulus.length, annulus.kappa,
                        annulus.one_minus_kappa, motion.eps_dot, motion.w_a, motion.w_b)
        return FluidForces(*f, model=self.name)


@jit(inline="always")
def model_block(data):
    """The model's own block of ``data`` (a view)."""
    start = int(data[MODEL])
    return data[start:start + int(data[MODEL_SIZE])]


def linear(data, a, b, mu, length, kappa, omk, eps_dot, w_a, w_b):
    """The kernel of a linear model, a template: its coefficients (RESISTANCE), the finite-length factors
    (END_FACTORS) and the first inertial correction (INERTIAL_F_EPS) of ``data``, the three bound and the copy
    compiled by :func:`lubrication.registry.linear_kernel`."""
    r = RESISTANCE(a, b - a, mu, kappa, omk)  # noqa: F821 - the globals are bound by linear_kernel
    ends = END_FACTORS(data, kappa, omk)  # noqa: F821
    f_eps = length * ends[0] * r[0] * eps_dot + INERTIAL_F_EPS(data, a, b, length, kappa, w_a, w_b)  # noqa: F821
    f_chi = length * (ends[1] * r[1] * w_a + ends[3] * r[3] * w_b)
    t_a = length * (ends[2] * r[2] * w_a + ends[4] * r[4] * w_b)
    faces = end_face_forces(data[END_FACES], a, mu, kappa * (b - a), eps_dot, w_a, w_b)
    return f_eps + faces[0], f_chi + faces[1], t_a + faces[2]


def check_end_gap(end_gap: float | None, a: float) -> None:
    """ValueError naming ``end_gap`` where it exceeds MAX_END_GAP_OVER_A times the inner radius ``a``."""
    if end_gap is not None and end_gap > MAX_END_GAP_OVER_A * a:
        msg = (f"end_gap: the end faces' films are lubrication films, in error by O(h/a): at most "
               f"{MAX_END_GAP_OVER_A:g} a = {MAX_END_GAP_OVER_A * a:g} m, got {end_gap!r} m")
        raise ValueError(msg)


@jit(inline="always")
def end_face_forces(inverse_gaps, a, mu, eps, eps_dot, w_a, w_b):
    """(f_eps, f_chi, T_a) of the films between the inner cylinder's flat end faces and the end caps.

    Each face, a disc of radius a centred at r = eps e_eps, shears a film of thickness h
    against the cap, which turns with the outer cylinder about its axis: plane Couette flow,
    stress -mu (v_A - v_cap)/h, where v_A - v_cap = r' + Omega_a J (x - r) - Omega_b J x and J
    turns a vector a quarter turn the way chi grows. Over the disc, with r' = eps' e_eps +
    eps chi' e_chi and J r = eps e_chi, the force is -(mu pi a^2/h)(eps' e_eps - eps W_b e_chi)
    and the torque about A -(mu pi a^4/(2 h))(W_a - W_b). ``inverse_gaps`` = the sum of 1/h over
    the ends (1/m); 0 gives zeros. Lubrication of the faces' films: h << a, and h fixed (the inner
    cylinder's axial position is not a state). They dissipate c (eps'^2 + eps^2 W_b^2 +
    (a^2/2)(W_a - W_b)^2) >= 0, c = mu pi a^2 sum(1/h).
    """
    c = mu * math.pi * a * a * inverse_gaps
    return -c * eps_dot, c * eps * w_b, -0.5 * c * a * a * (w_a - w_b)


#: The sources compiled into every kernel of this layer: the package's own.
SOURCES_HASH = sources_hash(*sorted(Path(__file__).parent.glob("*.py")))


def kernel_name(model: str, kernel) -> str:
    """What the equations compiled with ``kernel`` are filed under: the model, the kernel, and a hash of the
    kernel's file and of this package's sources (a kernel from outside the package, a test's say, carries its
    own file)."""
    function = getattr(kernel, "py_func", kernel)
    path = Path(function.__code__.co_filename)
    extra = (path,) if path.exists() and path.parent != Path(__file__).parent else ()
    digest = sources_hash(*extra, *sorted(Path(__file__).parent.glob("*.py")))
    # a model may have several kernels (a full and a cavitating film): each is filed apart
    return "".join(c if c.isalnum() else "_" for c in f"{model}_{function.__name__}") + f"_{digest}"
