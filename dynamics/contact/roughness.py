r"""Rough surfaces: a minimum gap that varies with the orientation of both cylinders.

Section 5 stops the approach of the cylinders at a uniform kappa*; its
discussion adds that the minimum gap "more probably would be a complicated
function of the orientations of both" cylinders, and suggests "slight
stochastic variations in kappa*" (section 6.2: "the minimum gap is not likely to
be the same all the way around the cylinder surfaces"). This module builds
that function, kappa*(theta_a, theta_b); :mod:`dynamics.contact.rough` moves
the contact of :mod:`dynamics.contact.reduced` onto it.

Kinematics
----------
phi is the angle of the line of centres B -> A from the upward vertical and
Omega_a, Omega_b the rotation rates, all clockwise. Let Theta_a, Theta_b be
the angles the cylinders have turned, Theta' = Omega; Theta_b is X_b, the
distance rolled in units of b. The asperities touch where the gap is narrowest,
on the line of centres (theta = 0 of Appendix B). The material point of each
surface there has the body angle

    theta_a = phi - Theta_a,    theta_b = phi - Theta_b = phi - X_b,

measured clockwise from the body-fixed mark that pointed up at Theta = 0. So
theta_a' = phi' - Omega_a and theta_b' = phi' - Omega_b. In steady rolling
(phi' = 0) the contact runs over the outer surface at speed b Omega_b, which
is the speed down the plane, and over the inner one at a Omega_a. A distance
ell rolled therefore spans the angle ell/a on the inner surface and ell/b on
the outer.

Random surfaces
---------------
Each surface carries a stationary, 2 pi-periodic random function of its body
angle, a random Fourier series with a Gaussian spectrum:

    f(theta) = sum_{k=1}^{K} c_k (A_k cos k theta + B_k sin k theta),
    c_k^2 = w_k ~ exp(-k^2 lambda^2 / 2),   A_k, B_k ~ N(0, 1),

where the coefficients A_k, B_k are drawn from a numpy Generator seeded by
``seed``. The correlation of the series is

    C(Delta) = sum_k w_k cos(k Delta) / sum_k w_k ~ exp(-Delta^2 / (2 lambda^2)).

Poisson summation gives this Gaussian to within its periodisation and the
missing k = 0 term, a relative O(lambda / sqrt(2 pi)). The correlation length
lambda (an angle) is the standard deviation of that Gaussian. K stops where
c_k / c_1 falls below the double-precision epsilon. Each series is then scaled
so that its mean square around the circle is exactly 1. The scene's amplitude
is therefore the standard deviation of sigma along the surfaces, not just its
ensemble mean. The scaling is invariant under rotations, so the field stays
stationary; it is Gaussian in the limit of many modes.

Spectra. The Gaussian spectrum above is the default. A self-affine surface
(:class:`Spectrum` with ``kind = "self-affine"``) has instead

    w_k = 1                          for k lambda <= 1,
    w_k = (k lambda)^-(1 + 2 H)      for k lambda > 1,   k <= K = bandwidth/lambda,

the power spectrum of a profile along a circle that is flat below the
roll-off wavenumber 1/lambda and falls as k^-(1 + 2H) above it, H in (0, 1)
the Hurst exponent. Such a profile has no slope without a short-wavelength
cutoff (sum_k k^2 w_k diverges for H < 1), so the series stops at the
wavenumber ``bandwidth``/lambda, where the asperities of a real surface stop.
Both are drawn from the same seeded normal coefficients and scaled to unit
mean square the same way, so they differ only in the weights w_k; the
correlation function below holds for either with its own weights.

The heights of the two surfaces add in the gap, so the minimum gap is

    sigma(theta_a, theta_b) = sigma_mean (1 + amplitude g),
    g = (f_a(theta_a) + f_b(theta_b)) / sqrt(2),

where the surfaces are independent and equally rough. The mean of g over the
torus is 0 and its mean square is 1. kappa* = 1 - sigma/delta then varies around
kappa*_mean = 1 - sigma_mean/delta.

Clipping rule
-------------
For amplitude 0.9 a Gaussian g goes below -1/0.9 about one time in eight, and
there sigma would be negative. The rule is: neither the gap sigma nor the
eccentricity kappa* may fall below a tenth of its mean. Each is left exactly
unchanged above a fifth of its mean (the knee), and below the knee it is
blended C^2 towards the floor:

    x -> x                                     for x >= knee,
    x -> floor + (knee - floor)/(1 + v + v^2), v = (knee - x)/(knee - floor),

first for x = sigma/sigma_mean and then for kappa*/kappa*_mean. The blend is
monotone and matches value, slope and curvature at the knee, so the contact
equations stay smooth. The result is kappa* in (kappa*_mean/10,
1 - sigma_mean/(10 delta)), strictly inside (0, 1). Where the clip acts, the
mean and spread of sigma differ slightly from the unclipped ones. At
amplitude 0 nothing is clipped, and kappa* is kappa*_mean exactly.

The compiled field
------------------
The integrator asks for f, f' and f'' of both surfaces at every evaluation of
a rough phase's right-hand side, so the series is not summed there. Each
surface keeps instead a table (:attr:`SurfaceHeights.jets`): at N equally
spaced nodes theta_j = j h, h = 2 pi/N, the Taylor coefficients
f^(m)(theta_j) h^m/m! for m = 0 .. M = :data:`JET_ORDER`, all computed at once
by inverse FFTs of the coefficients. At theta the compiled field takes the
nearest node, u = (theta - theta_j)/h in [-1/2, 1/2], and evaluates the
polynomial and its first two derivatives: about 3M multiply-adds, whatever
the number of modes K. N is the power of two with pi K/N <= 1/2, so that
k |theta - theta_j| <= 1/2 for every mode. The remainder of the Taylor
polynomial then bounds the error of f'' (the largest) by

    sum_k k^(M+1) c_k (|A_k| + |B_k|) |theta - theta_j|^(M-1)/(M-1)!  <=  S_2 (1/2)^(M-1)/(M-1)!,

with S_2 = sum_k k^2 (|A_k| + |B_k|) c_k the size of the terms of f'': 2e-17 S_2
for M = 16, below the rounding, which is that of the FFTs (tests/test_roughness.py
measures both). The polynomials of neighbouring nodes meet at mid-interval to that
rounding, so the field is smooth at the integrator's tolerances.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np

from dynamics.contact.laws import Compliance, Stribeck
from dynamics.contact.reduced import ContactParams
from lubrication.geometry import check_range
from numerics.jit import jit

__all__ = ["CLIP_FLOOR", "CLIP_KNEE", "GAUSSIAN", "JET_ORDER", "MAX_MODES", "SPECTRA", "LocalCurvature", "LocalGap",
           "RoughContact", "Spectrum", "SurfaceHeights", "soft_floor"]

CLIP_FLOOR = 0.1  # sigma and kappa* never fall below this fraction of their means
CLIP_KNEE = 0.2  # ... and are left unchanged above this fraction
# The series needs about 12/lambda modes; a shorter correlation than 12/MAX_MODES
# (6e-4 rad) would need a compiled field of more than 17 MB a surface, which every phase's args carry.
MAX_MODES = 20_000
_TAIL = 4.0 * math.log(1.0 / np.finfo(float).eps)  # c_k/c_1 < eps beyond k^2 = 1 + _TAIL/lambda^2
_CHUNK = 4096  # samples per block when evaluating at many angles (memory ~ chunk x K)
#: The degree of the compiled field's Taylor polynomials at its nodes (module docstring: the compiled field).
JET_ORDER = 16
_JET_REACH = 0.5  # the nodes are close enough that k |theta - theta_j| <= this for every mode k <= K

#: The spectra a surface may have (:class:`Spectrum`).
SPECTRA = ("gaussian", "self-affine")


@dataclass(frozen=True)
class Spectrum:
    """The power spectrum of one surface's heights along its circle (module docstring).

    Attributes
    ----------
    kind : {"gaussian", "self-affine"}
    hurst : float
        Hurst exponent H of a self-affine surface, in (0, 1): the spectrum falls
        as k^-(1 + 2H) beyond the roll-off. Unused for "gaussian".
    bandwidth : float
        Short-wavelength cutoff of a self-affine surface, as the ratio of the
        cutoff wavenumber to the roll-off wavenumber 1/lambda, in [1, 1e4].
        Unused for "gaussian", whose series ends where its weights reach rounding.
    """

    kind: str = "gaussian"
    hurst: float = 0.8
    bandwidth: float = 10.0

    def __post_init__(self):
        if self.kind not in SPECTRA:
            msg = f"spectrum must be one of {', '.join(map(repr, SPECTRA))}, got {self.kind!r}"
            raise ValueError(msg)
        object.__setattr__(self, "hurst", check_range("hurst", self.hurst, 0.0, 1.0, low_open=True,
                                                      high_open=True))
        object.__setattr__(self, "bandwidth", check_range("bandwidth", self.bandwidth, 1.0, 1e4,
                                                          high_open=False))

    def modes(self, correlation: float) -> int:
        """K, the number of Fourier modes of a surface with correlation length ``correlation`` (rad)."""
        if self.kind == "gaussian":
            n = max(1, int(math.sqrt(1.0 + _TAIL / correlation**2)))
            least = math.sqrt(_TAIL / MAX_MODES**2)
        else:
            n = max(1, int(self.bandwidth / correlation))
            least = self.bandwidth / (MAX_MODES + 1)
        if n > MAX_MODES:
            msg = (f"correlation must be at least {least:.3g} rad (a series of at most {MAX_MODES} modes), "
                   f"got {correlation!r}")
            raise ValueError(msg)
        return n

    def amplitudes(self, correlation: float, n: int) -> np.ndarray:
        """c_k = sqrt(w_k), k = 1 .. n, before the random draw (module docstring)."""
        k = np.arange(1, n + 1)
        if self.kind == "gaussian":
            return np.exp(-0.25 * (k * correlation) ** 2)
        x = k * correlation  # wavenumber over the roll-off 1/lambda
        return np.where(x <= 1.0, 1.0, np.maximum(x, 1.0) ** -(0.5 + self.hurst))


#: The default spectrum, that of the paper's suggestion as the reduced model first took it.
GAUSSIAN = Spectrum()


def soft_floor(x, floor: float, knee: float):
    """The clipping rule: x above ``knee``, blended C^2 towards ``floor`` below it.

    Parameters
    ----------
    x : float or array_like
    floor, knee : float
        0 <= floor < knee.

    Returns
    -------
    value, slope : ndarray
        The clipped x, in (floor, inf), and its derivative d value / dx in (0, 1].
    """
    x = np.asarray(x, dtype=float)
    v = np.maximum((knee - x) / (knee - floor), 0.0)
    blend = 1.0 / (1.0 + v * (1.0 + v))
    below = x < knee
    return (np.where(below, floor + (knee - floor) * blend, x),
            np.where(below, (1.0 + 2.0 * v) * blend * blend, 1.0))


@jit
def _soft_floor_kernel(x, floor, knee):
    """Scalar twin of :func:`soft_floor`."""
    if x >= knee:
        return x, 1.0
    v = (knee - x) / (knee - floor)
    blend = 1.0 / (1.0 + v * (1.0 + v))
    return floor + (knee - floor) * blend, (1.0 + 2.0 * v) * blend * blend


@jit
def _soft_floor2_kernel(x, floor, knee):
    """:func:`_soft_floor_kernel` and the curvature d^2 value/dx^2 (module docstring: curvatures)."""
    if x >= knee:
        return x, 1.0, 0.0
    v = (knee - x) / (knee - floor)
    blend = 1.0 / (1.0 + v * (1.0 + v))
    return (floor + (knee - floor) * blend, (1.0 + 2.0 * v) * blend * blend,
            6.0 * v * (1.0 + v) * blend * blend * blend / (knee - floor))


def soft_floor_curvature(x, floor: float, knee: float):
    """d^2/dx^2 of :func:`soft_floor` (0 above ``knee``, continuous at it)."""
    x = np.asarray(x, dtype=float)
    v = np.maximum((knee - x) / (knee - floor), 0.0)
    blend = 1.0 / (1.0 + v * (1.0 + v))
    return np.where(x < knee, 6.0 * v * (1.0 + v) * blend**3 / (knee - floor), 0.0)


def _jets(cos_coefficients: np.ndarray, sin_coefficients: np.ndarray) -> np.ndarray:
    """The compiled field's table of a series (module docstring: the compiled field), flat, node after node.

    Row j holds T_m = f^(m)(theta_j) h^m / m!, m = 0 .. JET_ORDER, at the node theta_j = j h,
    h = 2 pi / N: each derivative of the series at all N nodes at once, by an inverse real FFT of
    its coefficients times (i k h)^m / m! (a product that stays below 1, whatever K and m).
    """
    modes = cos_coefficients.size
    nodes = max(16, 1 << math.ceil(math.log2(math.pi * modes / _JET_REACH)))
    h = 2.0 * math.pi / nodes
    k = np.arange(1, modes + 1)
    # irfft gives (2/N) Re(X_k e^{i k theta_j}) for 0 < k < N/2: X_k = (N/2)(A_k - i B_k) gives A_k cos + B_k sin
    coefficients = 0.5 * nodes * (cos_coefficients - 1j * sin_coefficients)
    spectrum = np.zeros(nodes // 2 + 1, dtype=complex)
    table = np.empty((nodes, JET_ORDER + 1))
    for m in range(JET_ORDER + 1):
        spectrum[1:modes + 1] = coefficients
        table[:, m] = np.fft.irfft(spectrum, n=nodes)
        coefficients = coefficients * (1j * h / (m + 1)) * k
    return table.ravel()


@jit
def _heights_kernel(theta, jets):
    """Scalar twin of :meth:`SurfaceHeights.__call__`, with the curvature: f, f' and f'' at ``theta``.

    From the table ``jets`` (:attr:`SurfaceHeights.jets`): the Taylor polynomial of degree
    JET_ORDER at the nearest node, in u = (theta - theta_j)/h, |u| <= 1/2, and its first two
    derivatives by Horner's scheme, whatever the number of modes.
    """
    width = JET_ORDER + 1
    nodes = jets.size // width
    h = 2.0 * math.pi / nodes
    x = theta % (2.0 * math.pi)
    j = int(math.floor(x / h + 0.5))
    u = (x - j * h) / h
    row = (j % nodes) * width
    value, slope, curvature = jets[row + JET_ORDER], 0.0, 0.0
    for m in range(JET_ORDER - 1, -1, -1):
        curvature = curvature * u + 2.0 * slope
        slope = slope * u + value
        value = value * u + jets[row + m]
    return value, slope / h, curvature / (h * h)


@jit
def _local2_kernel(theta_a, theta_b, jets_a, jets_b, amplitude, kappa_mean, gap_mean):
    """:func:`_local_kernel` and the curvatures (k_aa, k_ab, k_bb) of kappa* (module docstring).

    The first four values are those of :func:`_local_kernel` operation for operation.
    """
    f_a, df_a, ddf_a = _heights_kernel(theta_a, jets_a)
    f_b, df_b, ddf_b = _heights_kernel(theta_b, jets_b)
    scale = amplitude / math.sqrt(2.0)
    gap, gap_slope, gap_curvature = _soft_floor2_kernel(1.0 + scale * (f_a + f_b), CLIP_FLOOR, CLIP_KNEE)
    ratio = 1.0 - gap_mean * (gap - 1.0) / kappa_mean
    clipped, ratio_slope, ratio_curvature = _soft_floor2_kernel(ratio, CLIP_FLOOR, CLIP_KNEE)
    chain = -gap_mean * ratio_slope * gap_slope
    bend = -gap_mean * (ratio_slope * gap_curvature - gap_mean * ratio_curvature * gap_slope * gap_slope / kappa_mean)
    slope_a, slope_b = scale * df_a, scale * df_b
    return (kappa_mean * clipped, gap_mean * gap + kappa_mean * (ratio - clipped),
            chain * scale * df_a, chain * scale * df_b,
            bend * slope_a * slope_a + chain * scale * ddf_a, bend * slope_a * slope_b,
            bend * slope_b * slope_b + chain * scale * ddf_b)


@jit
def _local_kernel(theta_a, theta_b, jets_a, jets_b, amplitude, kappa_mean, gap_mean):
    """Scalar twin of :meth:`RoughContact.local`: (kappa*, 1 - kappa*, d kappa*/d theta_a, .../d theta_b)."""
    f_a, df_a, _ = _heights_kernel(theta_a, jets_a)
    f_b, df_b, _ = _heights_kernel(theta_b, jets_b)
    scale = amplitude / math.sqrt(2.0)
    gap, gap_slope = _soft_floor_kernel(1.0 + scale * (f_a + f_b), CLIP_FLOOR, CLIP_KNEE)
    ratio = 1.0 - gap_mean * (gap - 1.0) / kappa_mean
    clipped, ratio_slope = _soft_floor_kernel(ratio, CLIP_FLOOR, CLIP_KNEE)
    chain = -gap_mean * ratio_slope * gap_slope
    return (kappa_mean * clipped, gap_mean * gap + kappa_mean * (ratio - clipped),
            chain * scale * df_a, chain * scale * df_b)


@dataclass(frozen=True, eq=False)
class SurfaceHeights:
    """One surface's random height, f(theta), with unit mean square around the circle.

    Build it with :meth:`from_rng`. ``cos_coefficients[k-1]`` and
    ``sin_coefficients[k-1]`` multiply cos(k theta) and sin(k theta).
    """

    correlation: float  # correlation length lambda, an angle (rad)
    cos_coefficients: np.ndarray
    sin_coefficients: np.ndarray
    spectrum: Spectrum = GAUSSIAN

    @classmethod
    def from_rng(cls, correlation: float, rng: np.random.Generator, spectrum: Spectrum = GAUSSIAN) -> SurfaceHeights:
        """Draw a surface with correlation length ``correlation`` (rad, > 0) and ``spectrum`` from ``rng``."""
        lam = check_range("correlation", correlation, 0.0, math.inf, low_open=True, unit="rad")
        if not isinstance(spectrum, Spectrum):
            msg = f"spectrum must be a Spectrum, got {type(spectrum).__name__}"
            raise TypeError(msg)
        n = spectrum.modes(lam)
        amplitude = spectrum.amplitudes(lam, n)
        a, b = amplitude * rng.standard_normal((2, n))
        rms = math.sqrt(0.5 * float(np.sum(a * a + b * b)))  # mean square over the circle (Parseval)
        return cls(lam, a / rms, b / rms, spectrum)

    @property
    def modes(self) -> int:
        """K, the number of Fourier modes."""
        return self.cos_coefficients.size

    @cached_property
    def jets(self) -> np.ndarray:
        """The table the compiled field evaluates (module docstring: the compiled field), built once."""
        return _jets(self.cos_coefficients, self.sin_coefficients)

    def __call__(self, theta):
        """f(theta) and f'(theta) at body angles ``theta`` (rad, any shape)."""
        theta = np.asarray(theta, dtype=float)
        flat = np.mod(theta.ravel(), 2.0 * math.pi)  # keeps k theta small, f is 2 pi-periodic
        k = np.arange(1, self.modes + 1)
        value, slope = np.empty(flat.size), np.empty(flat.size)
        for start in range(0, flat.size, _CHUNK):
            phase = np.multiply.outer(flat[start:start + _CHUNK], k)
            cos, sin = np.cos(phase), np.sin(phase)
            value[start:start + _CHUNK] = cos @ self.cos_coefficients + sin @ self.sin_coefficients
            slope[start:start + _CHUNK] = (cos @ (k * self.sin_coefficients)
                                           - sin @ (k * self.cos_coefficients))
        return value.reshape(theta.shape), slope.reshape(theta.shape)

    def curvature(self, theta):
        """f''(theta) at body angles ``theta`` (rad, any shape)."""
        theta = np.asarray(theta, dtype=float)
        flat = np.mod(theta.ravel(), 2.0 * math.pi)
        k = np.arange(1, self.modes + 1)
        out = np.empty(flat.size)
        for start in range(0, flat.size, _CHUNK):
            phase = np.multiply.outer(flat[start:start + _CHUNK], k)
            out[start:start + _CHUNK] = -(np.cos(phase) @ (k * k * self.cos_coefficients)
                                          + np.sin(phase) @ (k * k * self.sin_coefficients))
        return out.reshape(theta.shape)

    def correlation_function(self, delta):
        """C(Delta) = sum_k w_k cos(k Delta) / sum_k w_k, the correlation of the series of this spectrum.

        It is what the sample correlation of many surfaces averages to, up to
        the O(1/K) bias of scaling each one to unit mean square.
        """
        k = np.arange(1, self.modes + 1)
        weight = (np.exp(-0.5 * (k * self.correlation) ** 2) if self.spectrum.kind == "gaussian"
                  else self.spectrum.amplitudes(self.correlation, self.modes) ** 2)
        return np.cos(np.multiply.outer(np.asarray(delta, dtype=float), k)) @ weight / weight.sum()


class LocalGap(NamedTuple):
    """kappa* where the line of centres meets the surfaces, and its slopes along them.

    All fields are floats, or arrays of the shape of the angles.
    """

    kappa: object  # kappa*(theta_a, theta_b), in (0, 1)
    one_minus_kappa: object  # 1 - kappa* = sigma/delta, without cancellation
    dkappa_a: object  # d kappa* / d theta_a
    dkappa_b: object  # d kappa* / d theta_b

    @property
    def zeta(self):
        """zeta* = sqrt(1 - kappa*^2)."""
        return np.sqrt(self.one_minus_kappa * (1.0 + self.kappa))

    @property
    def r_star(self):
        """The stretched radius r* = kappa*/zeta* of the constraint (see :mod:`dynamics.equations.reduced`)."""
        return self.kappa / self.zeta


class LocalCurvature(NamedTuple):
    """Second derivatives of kappa*(theta_a, theta_b) (module docstring: curvatures)."""

    kappa_aa: object
    kappa_ab: object
    kappa_bb: object


@dataclass(frozen=True, eq=False)
class RoughContact:
    """Rough contact whose minimum gap varies along both surfaces (module docstring).

    Attributes
    ----------
    mean : ContactParams
        kappa*_mean = 1 - sigma_mean/delta and the (kinetic) friction angle psi of section 5.
    amplitude : float
        Standard deviation of sigma along the surfaces over its mean, in [0, 1).
    inner, outer : SurfaceHeights
        The unit height functions f_a(theta_a) and f_b(theta_b).
    friction : Stribeck or None
        Velocity-weakening friction (:mod:`dynamics.contact.laws`); None: Coulomb with ``mean.psi``.
        The full equations only.
    compliance : Compliance or None
        A compliant asperity contact (:mod:`dynamics.contact.laws`); None: the hard contact
        of section 5. The full equations only.
    """

    mean: ContactParams
    amplitude: float
    inner: SurfaceHeights
    outer: SurfaceHeights
    friction: Stribeck | None = None
    compliance: Compliance | None = None

    def __post_init__(self):
        object.__setattr__(self, "amplitude", check_range("amplitude", self.amplitude, 0.0, 1.0))
        if self.friction is not None and not isinstance(self.friction, Stribeck):
            msg = f"friction must be a Stribeck law or None (Coulomb), got {type(self.friction).__name__}"
            raise TypeError(msg)
        if self.compliance is not None and not isinstance(self.compliance, Compliance):
            msg = f"compliance must be a Compliance or None (the hard contact), got {type(self.compliance).__name__}"
            raise TypeError(msg)
        if self.friction is not None and not self.friction.psi_static >= self.mean.psi:
            msg = (f"psi_static must be in [psi, pi/2) = [{self.mean.psi:.6g}, {0.5 * math.pi:.6g}) rad: static "
                   f"friction is at least the kinetic friction; got {self.friction.psi_static!r}")
            raise ValueError(msg)

    @property
    def laws(self) -> bool:
        """Whether the contact asks for a law beyond section 5's (Stribeck friction or compliance)."""
        return self.friction is not None or self.compliance is not None

    @classmethod
    def from_seed(cls, mean: ContactParams, amplitude: float, correlation_a: float, correlation_b: float,
                  seed: int, *, spectrum: Spectrum = GAUSSIAN, friction: Stribeck | None = None,
                  compliance: Compliance | None = None) -> RoughContact:
        """Both surfaces from one seed, with correlation lengths in rad on each surface.

        ``seed`` (an int >= 0) seeds a :class:`numpy.random.SeedSequence` with one
        independent child stream per surface, so that a seed always gives the same pair.
        Both surfaces have ``spectrum``.
        """
        if isinstance(seed, bool) or not (isinstance(seed, (int, np.integer)) and seed >= 0):
            msg = f"seed must be an integer >= 0, got {seed!r}"
            raise ValueError(msg)
        inner, outer = (np.random.default_rng(child) for child in np.random.SeedSequence(int(seed)).spawn(2))
        return cls(mean, amplitude, SurfaceHeights.from_rng(correlation_a, inner, spectrum),
                   SurfaceHeights.from_rng(correlation_b, outer, spectrum), friction, compliance)

    @classmethod
    def from_rolled_length(cls, mean: ContactParams, amplitude: float, length: float, a: float, b: float,
                           seed: int, **kwargs) -> RoughContact:
        """Correlation given as a distance rolled, ``length``: the angles length/a and length/b.

        ``length``, ``a`` and ``b`` are in one unit: metres, or b in a
        dimensionless scene (then b = 1 and a = 1/(1 + delta/a)). ``kwargs`` as
        for :meth:`from_seed` (spectrum, friction, compliance).
        """
        length = check_range("length", length, 0.0, math.inf, low_open=True)
        a = check_range("a", a, 0.0, math.inf, low_open=True)
        b = check_range("b", b, a, math.inf, low_open=False)
        return cls.from_seed(mean, amplitude, length / a, length / b, seed, **kwargs)

    @classmethod
    def uniform(cls, mean: ContactParams, *, friction: Stribeck | None = None,
                compliance: Compliance | None = None) -> RoughContact:
        """Surfaces of uniform minimum gap (amplitude 0), to give a uniform contact the laws of
        :mod:`dynamics.contact.laws`. The one mode drawn (seed 0) multiplies the amplitude 0."""
        return cls.from_seed(mean, 0.0, 2.0 * math.pi, 2.0 * math.pi, 0, friction=friction, compliance=compliance)

    def gap_ratio(self, theta_a, theta_b):
        """x = sigma/sigma_mean = 1 + amplitude g before clipping, and dx/dtheta_a, dx/dtheta_b."""
        f_a, df_a = self.inner(theta_a)
        f_b, df_b = self.outer(theta_b)
        scale = self.amplitude / math.sqrt(2.0)
        return 1.0 + scale * (f_a + f_b), scale * df_a, scale * df_b

    def local(self, theta_a, theta_b) -> LocalGap:
        """kappa*(theta_a, theta_b), clipped as the module docstring states, and its slopes."""
        x, dx_a, dx_b = self.gap_ratio(theta_a, theta_b)
        gap, gap_slope = soft_floor(x, CLIP_FLOOR, CLIP_KNEE)
        kappa_mean, gap_mean = self.mean.kappa_star, self.mean.one_minus_kappa_star
        ratio = 1.0 - gap_mean * (gap - 1.0) / kappa_mean  # kappa*/kappa*_mean before its floor
        clipped, ratio_slope = soft_floor(ratio, CLIP_FLOOR, CLIP_KNEE)
        chain = -gap_mean * ratio_slope * gap_slope  # d kappa*/dx
        return LocalGap(kappa_mean * clipped, gap_mean * gap + kappa_mean * (ratio - clipped),
                        chain * dx_a, chain * dx_b)

    def curvature(self, theta_a, theta_b) -> LocalCurvature:
        """The second derivatives of kappa*(theta_a, theta_b) (module docstring), NumPy twin of the compiled field."""
        x, dx_a, dx_b = self.gap_ratio(theta_a, theta_b)
        scale = self.amplitude / math.sqrt(2.0)
        ddx_a = scale * self.inner.curvature(theta_a)
        ddx_b = scale * self.outer.curvature(theta_b)
        gap, gap_slope = soft_floor(x, CLIP_FLOOR, CLIP_KNEE)
        gap_curvature = soft_floor_curvature(x, CLIP_FLOOR, CLIP_KNEE)
        kappa_mean, gap_mean = self.mean.kappa_star, self.mean.one_minus_kappa_star
        ratio = 1.0 - gap_mean * (gap - 1.0) / kappa_mean
        _, ratio_slope = soft_floor(ratio, CLIP_FLOOR, CLIP_KNEE)
        ratio_curvature = soft_floor_curvature(ratio, CLIP_FLOOR, CLIP_KNEE)
        chain = -gap_mean * ratio_slope * gap_slope
        bend = -gap_mean * (ratio_slope * gap_curvature - gap_mean * ratio_curvature * gap_slope**2 / kappa_mean)
        return LocalCurvature(bend * dx_a * dx_a + chain * ddx_a, bend * dx_a * dx_b, bend * dx_b * dx_b + chain * ddx_b)

    def local_at(self, theta_a: float, theta_b: float) -> LocalGap:
        """:meth:`local` at one pair of angles, as floats: the compiled twin the integrator calls."""
        return LocalGap(*_local_kernel(float(theta_a), float(theta_b), self.inner.jets, self.outer.jets,
                                       self.amplitude, self.mean.kappa_star, self.mean.one_minus_kappa_star))
