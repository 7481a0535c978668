"""The scene schema: every section, every key, its unit, range and help, stated once.

The sections are dataclasses whose fields carry a :class:`numerics.keys.Key`
(:func:`numerics.keys.key`): the scene reader (:mod:`dynamics.scenes.load`)
converts and checks TOML values with it, the dataclasses check themselves with
it when built from Python, the resolved scene writes its help as comments, and
the documentation's scene reference is generated from :data:`SECTIONS`. Keys a
scene may give instead of a field (``apparatus.preset``, ``apparatus.rho_a``,
``contact.sigma``, ``contact.friction_angle``, ``contact.static_friction_angle``,
``run.t_end_tau``) are listed in
:data:`ALTERNATIVE_KEYS` next to the field they stand for.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from dataclasses import dataclass, field

from dynamics.apparatus import DENSITY, PRESETS, Apparatus
from dynamics.contact.laws import CONTACT_LAWS, FRICTION_LAWS, HEIGHTS
from dynamics.contact.roughness import SPECTRA
from dynamics.equations.full import DEFAULT_FLUID_SPIN, DEFAULT_FRAME_TERMS, FLUID_SPIN, FRAME_TERMS
from dynamics.equations.limits import Limits
from dynamics.equations.reduced import ReducedParams
from dynamics.initial import Initial
from dynamics.simulation import NAVIER_STOKES_RTOL
from lubrication import registry
from lubrication.reynolds import TRAJECTORY_CELLS
from numerics.keys import Key, check_fields, field_key, key

__all__ = [
    "ALTERNATIVES",
    "ALTERNATIVE_KEYS",
    "ANIMATIONS",
    "CAVITATION_MODELS",
    "EQUATIONS",
    "SECTIONS",
    "Cavitation",
    "Contact",
    "Groups",
    "Initial",
    "Model",
    "NavierStokes",
    "Run",
    "Scene",
    "SceneError",
    "field_of",
    "spec",
]

EQUATIONS = ("full", "reduced", "navier-stokes", "auto")
CAVITATION_MODELS = ("half-sommerfeld", "swift-stieber", "jfo")

_DEG = math.pi / 180.0
_FRICTION = {"unit": "deg", "low": 0.0, "high": 90.0, "bounds": "[)", "scale": _DEG, "example": "5 deg"}


def _limit(name: str):
    """A field of Limits, with its default and its key, repeated in the run section."""
    f = Limits.__dataclass_fields__[name]
    return dataclasses.field(default=f.default, metadata=f.metadata)


def _registered(default, rule: Key, **changes):
    """A field carrying a key of the force-model registry (:mod:`lubrication.registry`), as scenes take it."""
    return dataclasses.field(default=default, metadata={"key": dataclasses.replace(rule, **changes)})


class SceneError(ValueError):
    """A scene that cannot run; the message names the key, the value and the allowed range."""


@dataclass(frozen=True)
class Groups:
    """The groups (2.12) of the reduced model and the gap ratio, all dimensionless."""

    s: float = key(help="slope group (a sin(alpha)/delta)(M/m'_a)")
    upsilon: float = key(help="Upsilon = g delta^3 m_a m'_a / (144 nu^2 m''_a^2), inertia over lubrication",
                         low=0.0, bounds="()")
    mu_ratio: float = key(help="the paper's mass ratio mu = (M + m_b)/m_a", low=0.0, bounds="()", toml="mu")
    delta_over_a: float = key(0.0, help="gap ratio (b - a)/a; 0 is the reduced model's limit", low=0.0,
                              bounds="[)")

    def __post_init__(self):
        check_fields(self)

    @classmethod
    def from_apparatus(cls, apparatus: Apparatus) -> Groups:
        """The groups of a physical apparatus."""
        return cls(s=apparatus.s, upsilon=apparatus.upsilon, mu_ratio=apparatus.mu_ratio,
                   delta_over_a=apparatus.delta_over_a)

    @property
    def reduced_params(self) -> ReducedParams:
        """(s, Upsilon, mu_) as the reduced model (2.11) takes them."""
        return ReducedParams(s=self.s, upsilon=self.upsilon, mu_ratio=self.mu_ratio)


@dataclass(frozen=True)
class Model:
    """What to model: the equations of motion and the fluid forces in them."""

    equations: str = key("full", help="'full' (2.1)-(2.4), 'reduced' (2.11), 'navier-stokes' (the unsteady flow "
                                      "of the gap coupled to both cylinders, no closure; see [navier_stokes]), or "
                                      "'auto' (the cheaper of 'full' and 'reduced' that meets model.tolerance)",
                         choices=EQUATIONS)
    forces: str = key("stokes-exact", help="the full equations' force model: 'stokes-exact' (the exact 2-D Stokes "
                                           "forces), 'closed-form' (the paper's (2.5)-(2.7)), 'reynolds' (the "
                                           "Reynolds solver), any other registered model, or 'auto'",
                      choices=lambda: (*registry.names(trajectories=True), "auto"))
    tolerance: float = key(0.01, help="relative error 'auto' may accept (measured)", low=0.0, high=1.0,
                           bounds="()")
    n: int = _registered(TRAJECTORY_CELLS, registry.get("reynolds").options["n"],
                         help="Reynolds solver: cells around the gap (exact thin-gap forces from 8)")
    grid: str = _registered("sommerfeld", registry.get("reynolds").options["grid"])
    ends: str = _registered("infinite", registry.option_keys(compositions_only=True)["ends"],
                            help="'infinite': per unit length of an infinitely long annulus; 'open': the gap opens "
                                 "into end regions at z = +-L/2 (finite-length factors on the linear models)",
                            choices=("infinite", "open"))
    inertia: str = _registered("none", registry.option_keys(compositions_only=True)["inertia"])
    end_gap: float | None = _registered(None, registry.option_keys(compositions_only=True)["end_gap"],
                                        help="full equations: axial clearance between each flat end face of the "
                                             "inner cylinder and the end cap; the faces' films add drag and torque "
                                             "(linear force models; 'none': no end faces)")
    frame_terms: str = key(DEFAULT_FRAME_TERMS, help="full equations: 'quasi-steady' carries m'_a, not m_eff, on "
                                                     "the centripetal and Coriolis terms, as a fluid turning with the "
                                                     "line of centres requires (the closer to the Navier-Stokes runs); "
                                                     "'paper' is (2.1)-(2.2) as printed", choices=FRAME_TERMS)
    fluid_spin: str = key(DEFAULT_FLUID_SPIN, help="full equations: 'eccentric' adds to (2.4) the fluid's own "
                                                   "angular momentum, that of the Stokes flow at the eccentricity, "
                                                   "the closest to the Navier-Stokes runs "
                                                   "(docs/site/equations_of_motion.md); 'couette' that of the "
                                                   "concentric Couette flow, m_f (a^2 Omega_a + b^2 Omega_b)/2; "
                                                   "'none' is (2.4) as printed, without it", choices=FLUID_SPIN)

    def __post_init__(self):
        check_fields(self)


@dataclass(frozen=True)
class Contact:
    """Rough contact (section 5): asperities stop the approach at kappa = kappa_star.

    A scene gives the minimum gap as ``sigma`` (a length) or ``kappa_star``,
    and friction as the physical ``friction_angle`` psi_hat or the scaled
    ``psi``, tan psi = (a/delta) tan psi_hat; both are resolved to the fields,
    as the static angle of Stribeck friction is (``static_friction_angle`` or
    ``psi_static``). The minimum gap varies along the surfaces when
    ``roughness_amplitude`` > 0 (:mod:`dynamics.contact.roughness`), in either
    equations; the compliant contact and Stribeck friction
    (:mod:`dynamics.contact.laws`) are the full equations' only.
    """

    kappa_star: float = key(help="eccentricity at which the asperities touch, 1 - sigma/delta", low=0.0,
                            high=1.0, bounds="()")
    psi: float = key(0.0, help="scaled friction angle, tan(psi) = (a/delta) tan(friction_angle)", **_FRICTION)
    roughness_amplitude: float = key(0.0, help="standard deviation of sigma along the surfaces over its mean",
                                     low=0.0, high=1.0, bounds="[)")
    roughness_correlation: float | None = key(None, help="correlation length of the roughness, as a distance "
                                                         "rolled", dimension="[length]", unit="m", low=0.0,
                                              bounds="()", example="1 mm", reduced_unit="b", none="none")
    seed: int = key(0, help="seed of the random roughness: the same seed gives the same surfaces", low=0,
                    integer=True)
    roughness_spectrum: str = key("gaussian", help="spectrum of the heights along each surface: 'gaussian', or "
                                                   "'self-affine' (flat below 1/correlation, k^-(1 + 2 H) above)",
                                  choices=SPECTRA)
    roughness_hurst: float = key(0.8, help="Hurst exponent H of a self-affine spectrum", low=0.0, high=1.0,
                                 bounds="()")
    roughness_bandwidth: float = key(10.0, help="a self-affine spectrum's cutoff wavenumber over its roll-off "
                                                "1/correlation: the shortest wavelength is correlation/bandwidth",
                                     low=1.0, high=1e4, bounds="[]")
    law: str = key("hard", help="the normal contact: 'hard' (section 5's wall of asperities, impacts and "
                                "phases) or 'compliant' (a Greenwood-Williamson load and damping; full "
                                "equations)", choices=CONTACT_LAWS)
    heights: str = key("exponential", help="compliant contact: distribution of the asperity summit heights",
                       choices=HEIGHTS)
    stiffness: float | None = key(None, help="compliant contact: stiffness -dP/dd where the summits touch; "
                                             "'none': 1000 m'_a g / sigma", dimension="[mass] / [time] ** 2",
                                  unit="N/m", low=0.0, bounds="()", example="1e6 N/m", none="none")
    damping_ratio: float = key(1.0, help="compliant contact: damping of its radial oscillation, 1 critical",
                               low=0.0, high=100.0, bounds="[]")
    slip_velocity: float = key(1e-5, help="compliant contact: slip speed below which the friction fades "
                                          "(its regularisation)", dimension="[length] / [time]", unit="m/s",
                               low=0.0, bounds="()", example="10 um/s")
    friction_law: str = key("coulomb", help="'coulomb' (psi) or 'stribeck' (falling from psi_static to psi "
                                            "over stribeck_velocity; full equations)", choices=FRICTION_LAWS)
    psi_static: float | None = key(None, help="Stribeck friction: scaled static friction angle, at least psi",
                                   **_FRICTION, none="none")
    stribeck_velocity: float = key(1e-3, help="Stribeck friction: slip speed over which friction falls to "
                                              "its kinetic value", dimension="[length] / [time]", unit="m/s",
                                   low=0.0, bounds="()", example="1 mm/s")

    def __post_init__(self):
        check_fields(self)
        if self.psi_static is not None and not self.psi_static >= self.psi:
            msg = (f"psi_static must be in [psi, 90) deg = [{math.degrees(self.psi):g}, 90) deg: static friction "
                   f"is at least the kinetic, got {math.degrees(self.psi_static):g} deg")
            raise ValueError(msg)


@dataclass(frozen=True)
class Cavitation:
    """A cavitation model for the film pressure; without this section the film is full."""

    model: str = key(help="the cavitation model ('jfo': mass-conserving Jakobsson-Floberg-Olsson)",
                     choices=CAVITATION_MODELS)
    p_cav: float = key(0.0, help="pressure below which the film ruptures (absolute)", dimension="[pressure]",
                       unit="Pa", low=0.0, example="0.1 atm")
    p_ref: float = key(101325.0, help="ambient pressure, which fixes the film's free constant (absolute)",
                       dimension="[pressure]", unit="Pa", low=0.0, bounds="()", example="1 atm")

    def __post_init__(self):
        check_fields(self)


#: The animation choices of [navier_stokes]: as ``snail flow``'s ``run.animation``.
ANIMATIONS = ("none", "gif")


@dataclass(frozen=True)
class NavierStokes:
    """The coupled Navier-Stokes solver of model.equations = 'navier-stokes': its grid, its step control, and
    flow snapshots written with the trajectory.

    The grid and the tolerance are :class:`dynamics.equations.navier_stokes.NavierStokesOptions`' and
    :data:`dynamics.simulation.NAVIER_STOKES_RTOL`'s; the snapshots are VTU files with a ParaView
    collection, and on request a GIF of the vorticity and streamlines in the frame of the outer cylinder
    (:mod:`lubrication.unsteady.snapshots`).
    """

    n_r: int = key(16, help="Chebyshev points across the gap, walls included", integer=True, low=4, high=64)
    n_theta: int | None = key(None, help="points around the annulus; 'auto': the solver's default for the current "
                                         "gap, the grid following the gap as it narrows or widens", integer=True,
                              low=8, high=1024, none="auto")
    rtol: float = key(NAVIER_STOKES_RTOL, help="relative local error per step of the flow solver (run.rtol is the "
                                               "ODE integrators')", low=1e-10, high=0.1, bounds="[]")
    snapshot_interval: float | None = key(None, help="flow snapshots at t = 0, T, 2T, ... up to t_end, written as "
                                                     "flow_*.vtu and flow.pvd; 'none': no snapshots",
                                          dimension="[time]", unit="s", low=0.0, bounds="()", example="0.05 s",
                                          none="none")
    animation: str = key("none", help="'gif': flow.gif, the snapshots' vorticity and streamlines in the frame of "
                                      "the outer cylinder (needs snapshot_interval); 'none'", choices=ANIMATIONS)

    def __post_init__(self):
        check_fields(self)

    def snapshot_count(self, t_end: float) -> int:
        """How many snapshots a run of ``t_end`` (s) takes: at 0, T, 2T, ... up to t_end (within rounding)."""
        if self.snapshot_interval is None:
            return 0
        return math.floor(t_end / self.snapshot_interval * (1.0 + 1e-12)) + 1

    def snapshot_times(self, t_end: float) -> tuple[float, ...]:
        """The times of the :meth:`snapshot_count` snapshots (s), none past ``t_end``; () without snapshots."""
        return tuple(min(float(k * self.snapshot_interval), t_end) for k in range(self.snapshot_count(t_end)))


@dataclass(frozen=True)
class Run:
    """How long to integrate, how accurately, what to output, and what to do at the validity limits."""

    t_end: float = key(help="duration (in units of tau in a dimensionless scene)", dimension="[time]", unit="s",
                       low=0.0, bounds="()", example="30 s")
    # below 100 eps the error control asks for more than rounding allows: simulate() refuses it too
    rtol: float = key(1e-8, help="relative tolerance of the ODE integrator (the Navier-Stokes solver's is "
                                 "navier_stokes.rtol)", low=100 * sys.float_info.epsilon, high=0.1,
                      bounds="[]")
    output_interval: float | None = key(None, help="rows of trajectory.csv at this interval (and at every event); "
                                        "'none': one row per integrator step", dimension="[time]", unit="s",
                                        low=0.0, bounds="()", example="0.1 s", reduced_unit="tau", none="none")
    max_rows: int = key(200_000, help="most rows trajectory.csv may hold: a longer every-step output is thinned "
                                      "to every k-th step (event rows kept); an output_interval giving more rows "
                                      "is refused before the run", low=1, high=2_000_000, integer=True)
    max_steps: int = key(2_000_000, help="accepted integrator steps after which a run stops unfinished "
                                         "(every step is held in memory, about 300 bytes each)", low=1,
                         high=10_000_000, integer=True)
    gap_floor: float = _limit("gap_floor")
    max_gap_reynolds: float | None = _limit("max_gap_reynolds")
    max_stokes_number: float | None = _limit("max_stokes_number")
    on_invalid: str = _limit("on_invalid")

    def __post_init__(self):
        check_fields(self)

    @property
    def limits(self) -> Limits:
        """The validity limits of :mod:`dynamics.equations.limits` this run asks for."""
        return Limits(gap_floor=self.gap_floor, max_gap_reynolds=self.max_gap_reynolds,
                      max_stokes_number=self.max_stokes_number, on_invalid=self.on_invalid)


@dataclass(frozen=True)
class Scene:
    """A validated scene. Build it with :func:`dynamics.scenes.load.load_scene` or ``parse_scene``.

    Attributes
    ----------
    apparatus : Apparatus or None
        The device (SI). None for a dimensionless ``[groups]`` scene of the
        reduced model.
    groups : Groups
        s, Upsilon, mu_ and delta/a. They are derived from the apparatus when
        there is one.
    initial : Initial
        SI, or in units of tau when :attr:`dimensionless`.
    model : Model
    contact : Contact or None
        None when the scene has no ``[contact]`` section, and then there is no
        contact machinery.
    cavitation : Cavitation or None
        None when the scene has no ``[cavitation]`` section, and then the film
        is full.
    run : Run
        ``t_end`` in s, or in tau when :attr:`dimensionless`.
    navier_stokes : NavierStokes or None
        The flow solver's settings when ``model.equations`` is "navier-stokes"
        (the defaults when the scene has no ``[navier_stokes]`` section), None
        otherwise.
    source : str
        Where the scene was read from. It is not compared, so that a scene
        equals its resolved copy.
    """

    apparatus: Apparatus | None
    groups: Groups
    initial: Initial
    model: Model
    contact: Contact | None
    cavitation: Cavitation | None
    run: Run
    navier_stokes: NavierStokes | None = None
    source: str = field(default="<string>", compare=False)

    @property
    def dimensionless(self) -> bool:
        """True for a ``[groups]`` scene without an apparatus: times in tau, rates in 1/tau."""
        return self.apparatus is None

    @property
    def tau(self) -> float:
        """The time scale (2.9) in s, or 1 in a dimensionless scene."""
        return 1.0 if self.apparatus is None else self.apparatus.tau

    @property
    def t_end_tau(self) -> float:
        """The run length in units of tau."""
        return self.run.t_end / self.tau


# -- the table every reader uses ------------------------------------------------------

#: Keys a scene may give in place of a field: (section, key) -> its rule.
ALTERNATIVE_KEYS: dict[tuple[str, str], Key] = {
    ("apparatus", "preset"): Key(help="a device of the paper's Table 2; explicit keys override it",
                                 choices=tuple(PRESETS)),
    ("apparatus", "rho_a"): Key(help="density of a solid inner cylinder, instead of m_a",
                                **dict(DENSITY, example="7.85 g/cm^3")),
    ("contact", "sigma"): Key(help="the asperities' gap, instead of kappa_star = 1 - sigma/delta",
                              dimension="[length]", unit="m", low=0.0, bounds="()", example="50 um"),
    ("contact", "friction_angle"): Key(help="physical friction angle psi_hat, instead of psi", **_FRICTION),
    ("contact", "static_friction_angle"): Key(help="physical static friction angle, instead of psi_static",
                                              **_FRICTION),
    ("run", "t_end_tau"): Key(help="duration in units of tau, instead of t_end", unit="tau", low=0.0,
                              bounds="()"),
    ("run", "output_interval_tau"): Key(help="output interval in units of tau, instead of output_interval",
                                        unit="tau", low=0.0, bounds="()"),
}

#: Pairs of keys that say the same thing: a scene gives one, and an override of one replaces the other.
ALTERNATIVES = (("apparatus", "m_a", "rho_a"), ("contact", "sigma", "kappa_star"),
                ("contact", "friction_angle", "psi"), ("contact", "static_friction_angle", "psi_static"),
                ("run", "t_end", "t_end_tau"),
                ("run", "output_interval", "output_interval_tau"))

_SECTION_CLASSES = {"groups": Groups, "initial": Initial, "model": Model, "contact": Contact,
                    "cavitation": Cavitation, "navier_stokes": NavierStokes, "run": Run}


def _sections() -> dict[str, dict[str, Key]]:
    """Every section's keys in the order of its dataclass, alternatives after the field they replace."""
    table: dict[str, dict[str, Key]] = {"apparatus": {}, "fluid": {}, "incline": {}}
    for f in dataclasses.fields(Apparatus):
        table[field_key(f).section][f.name] = field_key(f)
    table["apparatus"] = {"preset": ALTERNATIVE_KEYS["apparatus", "preset"], **table["apparatus"]}
    for name, cls in _SECTION_CLASSES.items():
        table[name] = {(field_key(f).toml or f.name): field_key(f) for f in dataclasses.fields(cls)}
    for (section, name), rule in ALTERNATIVE_KEYS.items():
        table[section].setdefault(name, rule)
    return {name: table[name] for name in ("apparatus", "fluid", "incline", "groups", "initial", "model",
                                           "contact", "cavitation", "navier_stokes", "run")}


#: section -> {key: Key}, in the order scenes and the documentation list them.
SECTIONS: dict[str, dict[str, Key]] = _sections()


def spec(name: str) -> Key:
    """The rule of the key ``name``, given as "section.key"."""
    section, key_name = name.split(".")
    return SECTIONS[section][key_name]


def field_of(section: str, key_name: str) -> str:
    """The dataclass field a scene key fills (``groups.mu`` fills ``mu_ratio``)."""
    for f in dataclasses.fields(_SECTION_CLASSES.get(section, Apparatus)):
        if (field_key(f).toml or f.name) == key_name:
            return f.name
    return key_name
