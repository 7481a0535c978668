"""The registry of force models: each declared once, and the rules by which they compose.

A model is a :class:`ForceModelSpec`: its name, a line of help, its options as
keys with units, ranges and help (:class:`numerics.keys.Key`), its Python face
(geometry + motion + fluid -> forces at one instant) and, if a trajectory can
call it, its compiled kernel (:mod:`lubrication.kernels`): a model whose forces
are linear in (eps', W_a, W_b) declares its five resistance coefficients, any
other model a function of its options that gives its kernel and packed block.
A module declares its model and registers it (:func:`register`), as a method
of scipy's ``solve_ivp`` or an element of scikit-fem is one class; everything
else derives from the registry: :func:`fluid_forces` and :func:`resistance`,
the kernels of the equations of motion (:func:`kernel_model`), the scene schema,
the command line's choices and help, the automatic choice and the docs.

The compositions are rules on the registry (:data:`COMPOSITIONS`), each stated
once: the annulus' ends (``ends = "open"``: the finite-length factors of
:mod:`lubrication.finite_length` on a linear model's coefficients, or the
Reynolds equation on (theta, z) for one instant), the first inertial correction
(``inertia = "first-order"``: :mod:`lubrication.inertia`, tabulated for plane
Stokes flow, so on linear models with infinite ends), cavitation (a film
that ruptures: the Reynolds solver's), and the end faces (``end_gap``: the films
between the inner cylinder's flat ends and the end caps,
:func:`lubrication.kernels.end_face_forces`, on linear models).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from importlib import import_module
from types import MappingProxyType

import numpy as np

from numerics.jit import specialise
from numerics.keys import Key

from .finite_length import end_factors, factor_table
from .geometry import Annulus, Fluid, FluidForces, Motion, Resistance, check_range
from .inertia import inertial_f_eps
from .inertia_table import DELTA_NODES, KAPPA_NODES, TABLE
from .kernels import SOURCES_HASH, KernelModel, check_end_gap, kernel_name, linear
from .spec import ForceModelSpec

__all__ = ["COMPOSITIONS", "Composition", "ForceModelSpec", "check_options", "fluid_forces", "linear_kernel", "get", "kernel_model", "names",
           "option_keys", "register", "resistance", "unregister"]


@dataclass(frozen=True)
class Composition:
    """An option that acts on a model from outside it, and the rule of which models it composes with.

    ``rule(spec, options, trajectory)`` returns "" where the option (at a value other than
    ``off``) composes with the model ``spec`` and its other ``options``, else the reason it
    does not, said once for every caller.
    """

    keys: Mapping[str, Key]
    off: object
    rule: Callable

    @property
    def name(self) -> str:
        return next(iter(self.keys))


def _ends_rule(spec: ForceModelSpec, options: Mapping, trajectory: bool) -> str:
    ends = options.get("ends", "infinite")
    if spec.linear:
        return "" if ends in ("infinite", "open") else (
            f"ends = {ends!r} needs the Reynolds solver (model 'reynolds'); the {spec.name} forces take 'infinite' "
            "or 'open' (times the thin-gap finite-length factors)")
    if spec.film and not trajectory:
        return ""
    if spec.film:
        return ("ends = 'open' is modelled in trajectories with the linear models times the finite-length factors "
                "(closed-form, stokes-exact); the Reynolds solver on (theta, z) is for single instants")
    return f"the {spec.name} model is per unit length of an infinitely long annulus: ends must be 'infinite'"


def _inertia_rule(spec: ForceModelSpec, options: Mapping, trajectory: bool) -> str:
    if spec.linear and options.get("ends", "infinite") == "infinite":
        return ""
    return ("the first inertial correction is tabulated for plane Stokes flow: it composes with the linear models "
            f"({', '.join(n for n in names() if get(n).linear)}) and ends = 'infinite', not with the "
            f"{spec.name} model" + (f" and ends = {options['ends']!r}" if spec.linear else ""))


def _cavitation_rule(spec: ForceModelSpec, options: Mapping, trajectory: bool) -> str:
    if not spec.film:
        return f"cavitation is a rupture of the Reynolds film: it needs the model 'reynolds', not {spec.name!r}"
    ends, cavitation = options.get("ends", "infinite"), options.get("cavitation", "none")
    if ends == "sealed":
        return "cavitation with sealed ends leaves the pressure level undetermined: use ends 'open' or 'infinite'"
    if ends == "open" and cavitation != "half-sommerfeld":
        return f"on (theta, z) only half-sommerfeld carries over, not {cavitation!r}: use ends 'infinite'"
    return ""


def _end_faces_rule(spec: ForceModelSpec, options: Mapping, trajectory: bool) -> str:
    if spec.linear:
        return ""
    return ("the end faces' films add to the linear models' coefficients "
            f"({', '.join(n for n in names() if get(n).linear)}), not to the {spec.name} model's")


_PRESSURE = {"dimension": "[pressure]", "unit": "Pa", "example": "1 atm"}

#: The compositions, each stated once (module docstring).
COMPOSITIONS = MappingProxyType({
    "ends": Composition(
        {"ends": Key("the annulus' ends: 'infinite' (per unit length, times the length), 'open' (the gap opens into "
                     "end regions at z = +-L/2) or 'sealed' (closed there; the Reynolds solver only)",
                     choices=("infinite", "open", "sealed")),
         "n_axial": Key("Reynolds solver on (theta, z): cells along the whole length, even (default 64)", low=4,
                        high=4096, integer=True)},
        "infinite", _ends_rule),
    "inertia": Composition(
        {"inertia": Key("'first-order' adds the first inertial correction of the flow relative to the line of "
                        "centres (the error left is second order in Re*)", choices=("none", "first-order"))},
        "none", _inertia_rule),
    "cavitation": Composition(
        {"cavitation": Key("cavitation model of the Reynolds film ('none': full film)",
                           choices=("none", "half-sommerfeld", "swift-stieber", "jfo")),
         "p_cav": Key("pressure below which the film ruptures (absolute; below 0 a liquid under tension)",
                      **_PRESSURE),
         "p_ref": Key("reference pressure: at the widest gap, or of the end regions with ends 'open' (absolute)",
                      low=0.0, bounds="()", **_PRESSURE)},
        "none", _cavitation_rule),
    "end_faces": Composition(
        {"end_gap": Key("axial clearance between each flat end face of the inner cylinder and the outer "
                        "cylinder's end cap: the faces' films add drag and torque ('none': no end faces)",
                        dimension="[length]", unit="m", low=0.0, bounds="()", example="0.5 mm", none="none")},
        None, _end_faces_rule),
})

_MODELS: dict[str, ForceModelSpec] = {}
#: The modules that declare the project's own models (their ``MODEL``), registered on first use of the registry.
_BUILT_IN = ("closed_form", "film", "stokes_exact", "stokes")


@cache
def _load_built_in() -> None:
    for module in _BUILT_IN:
        register(import_module(f"lubrication.{module}").MODEL)


def register(spec: ForceModelSpec) -> ForceModelSpec:
    """Add ``spec`` to the registry (ValueError for a name taken by another model)."""
    if not isinstance(spec, ForceModelSpec):
        msg = f"register takes a ForceModelSpec, got {type(spec).__name__}"
        raise TypeError(msg)
    clash = set(spec.options) & set(option_keys(compositions_only=True))
    if clash:
        msg = f"the options {sorted(clash)} of {spec.name!r} are the compositions'; name them otherwise"
        raise ValueError(msg)
    if _MODELS.get(spec.name, spec) is not spec:
        msg = f"a force model named {spec.name!r} is registered already"
        raise ValueError(msg)
    _MODELS[spec.name] = spec
    return spec


def unregister(name: str) -> None:
    """Remove the model ``name`` (a model a test or a notebook registered)."""
    _MODELS.pop(name, None)


def names(*, trajectories: bool = False) -> tuple[str, ...]:
    """The registered models, built-in first; with ``trajectories`` those an integrator step can call."""
    _load_built_in()
    return tuple(n for n, s in _MODELS.items() if s.for_trajectories or not trajectories)


def get(name: str) -> ForceModelSpec:
    """The model ``name``, or ValueError naming the registered ones."""
    _load_built_in()
    try:
        return _MODELS[name]
    except (KeyError, TypeError):
        msg = f"model must be one of {', '.join(names())}, got {name!r}"
        raise ValueError(msg) from None


def option_keys(*, compositions_only: bool = False) -> dict[str, Key]:
    """Every option a model or composition takes, by name: the command line's flags and the docs' table."""
    keys = {name: key for c in COMPOSITIONS.values() for name, key in c.keys.items()}
    if not compositions_only:
        for spec in _MODELS.values():
            for name, key in spec.options.items():
                keys.setdefault(name, key)
    return keys


def _checked(spec: ForceModelSpec, options: Mapping, trajectory: bool) -> dict:
    """``options`` checked against the model's keys and the compositions' rules; ValueError naming the option."""
    own, composed = {}, {}
    for name, value in options.items():
        if name in spec.options:
            own[name] = spec.options[name].check(name, value)
        elif any(name in c.keys for c in COMPOSITIONS.values()):
            composed[name] = next(c.keys[name] for c in COMPOSITIONS.values() if name in c.keys).check(name, value)
        else:
            allowed = sorted({*spec.options, *option_keys(compositions_only=True)})
            msg = f"the {spec.name} model takes no option {name!r}; its options: {', '.join(allowed)}"
            raise ValueError(msg)
    for composition in COMPOSITIONS.values():
        given = [k for k in composition.keys if k in composed]
        if not given:
            continue
        on = composed.get(composition.name, composition.off) != composition.off
        extra = [k for k in given if k != composition.name]
        if not on and extra and composition.name not in composed:  # said off explicitly: the rest is moot
            msg = (f"{extra[0]}: {', '.join(extra)} {'goes' if len(extra) == 1 else 'go'} with {composition.name}, "
                   f"which is {composition.off!r} here; set {composition.name} or leave {' and '.join(extra)} out")
            raise ValueError(msg)
        why = composition.rule(spec, composed, trajectory) if on else ""
        if why:
            msg = f"{composition.name}: {why}"
            raise ValueError(msg)
    return {**own, **composed}


def check_options(name: str, **options) -> dict:
    """``options`` of the model ``name`` for one instant, checked (their keys and the compositions' rules);
    ValueError names the option. What :func:`fluid_forces` checks before it computes anything."""
    return _checked(get(name), options, trajectory=False)


def fluid_forces(annulus: Annulus, motion: Motion, fluid: Fluid, model: str = "stokes-exact",
                 **options) -> FluidForces:
    """Force and torque on the inner cylinder at one instant, with the registered model ``model``.

    Parameters
    ----------
    annulus, motion, fluid
        Geometry (its ``length`` is L), velocities and fluid (:mod:`lubrication.geometry`).
    model : str
        A registered model (:func:`names`): "stokes-exact" (the exact 2-D Stokes forces, the
        default), "closed-form" (2.5)-(2.7), "reynolds", "stokes" (finite elements), ...
    **options
        The model's own options and the compositions' (:data:`COMPOSITIONS`: ``ends``,
        ``n_axial``, ``inertia``, ``cavitation``, ``p_cav``, ``p_ref``, ``end_gap``), each checked against
        its key and the rules; the same options as ``snail forces``.

    Returns
    -------
    FluidForces

    Raises
    ------
    ValueError
        Naming the option or argument: an unknown model or option, a value out of its range,
        a composition the model does not take, an annulus outside the range where the model's
        accuracy was measured, or a motion whose forces are not finite numbers.
    """
    spec = get(model)
    options = _checked(spec, options, trajectory=False)
    if spec.check is not None:
        spec.check(annulus)
    check_end_gap(options.get("end_gap"), annulus.a)
    if spec.linear:
        forces = kernel_model(spec.name, length_over_a=annulus.length / annulus.a, rho=fluid.rho,
                              **options).forces(annulus, motion, fluid)
    else:
        forces = spec.forces(annulus, motion, fluid, **options)
    if not all(math.isfinite(x) for x in forces.as_tuple()):
        msg = (f"the {spec.name} forces of eps_dot = {motion.eps_dot:g} m/s, chi_dot = {motion.chi_dot:g}, omega_a = "
               f"{motion.omega_a:g}, omega_b = {motion.omega_b:g} rad/s overflow a double: the motion is too fast "
               "for any force to be a number")
        raise ValueError(msg)
    return forces


def resistance(annulus: Annulus, fluid: Fluid, model: str = "stokes-exact", **options) -> Resistance:
    """The five coefficients of :class:`~lubrication.geometry.Resistance`, from three unit motions of ``model``."""
    radial = fluid_forces(annulus, Motion(eps_dot=1.0), fluid, model, **options)
    inner = fluid_forces(annulus, Motion(omega_a=1.0), fluid, model, **options)
    outer = fluid_forces(annulus, Motion(omega_b=1.0), fluid, model, **options)
    return Resistance(radial.f_eps, inner.f_chi, inner.T_a, outer.f_chi, outer.T_a)


def linear_kernel(resistance, name: str):
    """The kernel (:mod:`lubrication.kernels`) of a model whose five coefficients per unit length, in
    :data:`lubrication.geometry.RESISTANCE_NAMES` order (more may follow), are the compiled
    ``resistance(a, delta, mu, kappa, omk)``, with the two compositions that act on coefficients, the
    finite-length factors and the first inertial correction, read from its data; ``name`` names the copy
    (a Python identifier)."""
    return specialise(linear, f"{name}_{SOURCES_HASH}", RESISTANCE=resistance, END_FACTORS=end_factors,
                      INERTIAL_F_EPS=inertial_f_eps)


@cache
def _linear_kernel(name: str):
    spec = get(name)
    return linear_kernel(spec.resistance, "".join(c if c.isalnum() else "_" for c in name))


def kernel_model(name: str, *, length_over_a: float | None = None, rho: float | None = None, **options):
    """The model ``name`` with ``options`` as a trajectory calls it: its kernel and packed data.

    ``length_over_a`` (L/a) is needed with ``ends = "open"``, the fluid density ``rho``
    (kg/m^3) with ``inertia = "first-order"``. A model with ``in_trajectories`` is
    replaced by that one. Returns a :class:`lubrication.kernels.KernelModel`; ValueError
    names the option that cannot be modelled.
    """
    spec = get(name)
    if spec.in_trajectories and not (spec.linear or spec.kernel):
        spec = get(spec.in_trajectories)
    options = _checked(spec, options, trajectory=True)
    ends, inertia = options.get("ends", "infinite"), options.get("inertia", "none")
    label = spec.name + ("/open-ends" if ends == "open" else "") + ("+inertia" if inertia != "none" else "")
    if spec.linear:
        kernel, block, smooth = _linear_kernel(spec.name), None, True
    elif spec.kernel is not None:
        own = {k: v for k, v in options.items() if k in spec.options or k in COMPOSITIONS["cavitation"].keys}
        kernel, block, smooth = spec.kernel(**own)
        if options.get("cavitation", "none") != "none":
            label = f"{spec.name}/{options['cavitation']}"
    else:
        msg = f"the {spec.name} model has no compiled kernel: a trajectory cannot call it"
        raise ValueError(msg)
    length_table = None
    if ends == "open":
        if length_over_a is None:
            raise ValueError("ends = 'open' needs the annulus' length over its inner radius, length_over_a")
        length_over_a = check_range("length_over_a", length_over_a, 0.0, math.inf, low_open=True)
        length_table = (length_over_a, *factor_table().args)
    inertia_table = None
    if inertia != "none":
        if rho is None:
            raise ValueError("inertia = 'first-order' needs the fluid density rho (kg/m^3)")
        rho = check_range("rho", rho, 0.0, math.inf, low_open=True, unit="kg/m^3")
        inertia_table = (rho, KAPPA_NODES, DELTA_NODES, TABLE)
    end_gap = options.get("end_gap")
    if end_gap is not None:
        label += "+end-faces"
    return KernelModel(label, kernel, kernel_name(spec.name, kernel),
                       block=np.empty(0) if block is None else np.asarray(block, dtype=float),
                       length_table=length_table, inertia=inertia_table, end_gap=end_gap, smooth=smooth,
                       options=dict(options))
