r"""Tabulated Stokes resistance functions, for use inside an integrator step.

A finite-element Stokes solve (:mod:`lubrication.stokes`) takes about a second,
far too long for a right-hand side. Its five resistance functions depend only
on (kappa, delta/a), so for one delta/a they are solved once on a grid of
kappa, stored, and interpolated. What is tabulated is each coefficient
divided by its lubrication form (2.5)-(2.7),

    r_eps   = R_eps / R_eps^lub,      r_chi_a = R_chi_a / R_chi_a^lub,
    r_t_a   = R_t_a / R_t_a^lub,      r_chi_b = R_chi_b / R_chi_b^lub,
    r_t_b   = R_t_b / R_t_b^lub,

which carry no singularity at contact: they are 1 + O(delta/a), vary by a few
per cent to tens of per cent across 0 <= kappa < 1, and the closed forms
restore the (1 - kappa^2)^(-3/2) and (1 - kappa^2)^(-1/2) growth exactly.

The variable. Every ratio is even in kappa (kappa -> -kappa is the mirror
image of the annulus), hence a smooth function of kappa^2 = 1 - zeta^2 near
kappa = 0, with zeta = sqrt(1 - kappa^2). Near contact the narrow-gap flow is
a local lubrication flow whose corrections come in powers of zeta (the width
of the pressure peak is ~ zeta); f_chi, for one, approaches its limit like
zeta^3, which is not smooth in kappa. The ratios are therefore tabulated
against zeta on Chebyshev-Lobatto points of [zeta_min, 1] and interpolated by
the barycentric formula. The two f_chi ratios have a finite limit at kappa = 0,
where both the force and (2.6) vanish; the node at zeta = 1 is solved at
kappa = KAPPA_AXIS (1e-4), which gives that limit to about 1e-8.

Beyond the table (kappa > kappa_max, zeta < zeta_min): there the pressure
peak narrows without bound and a fixed table cannot resolve it. The narrow
gap is then a local lubrication flow whose only geometric scale is the
relative curvature 1/a - 1/b = delta/(a b); the thin-gap forms (2.5)-(2.7)
use delta/a^2, i.e. a b/delta replaced by a^2/delta, and drive the outer wall
at a W_b instead of b W_b. The four ratios dominated by the narrow gap
therefore tend to powers of b/a,

    r_eps -> (b/a)^(3/2),   r_chi_a, r_t_a -> (b/a)^(1/2),   r_chi_b -> (b/a)^(5/2),

(the finite-element solves at kappa = 0.9999 agree to 5e-6 for delta/a = 0.1
and 0.406), and approach them like zeta^2 or faster. Below zeta_min each of
these ratios is blended to its limit linearly in zeta^2. R_t_b is the small
O(zeta) remainder of cancelling Couette and Poiseuille torques, whose limit
the local analysis does not fix; its ratio is held at its value at zeta_min.
That costs little where it matters: R_t_b / R_t_a ~ zeta^2 / 3 there, so an
error of a per cent in r_t_b is 1e-4 of the torque's larger entry at kappa_max
= 0.99 and less beyond.

Storage: one ``.npz`` file per delta/a in a cache folder (``$SNAIL_CACHE``, else
``~/.cache/snail-cylinder``), holding the ratios and the settings that made
them (format version, mesh, kappa_max, number of nodes). A file whose settings
differ from those asked for, or that cannot be read without pickle, is rebuilt.
"""

from __future__ import annotations

import io
import logging
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._jit import jit
from .closed_form import lubrication_forces
from .files import write_bytes
from .geometry import RESISTANCE_NAMES, Annulus, Fluid, FluidForces, Motion, check_range

__all__ = ["RATIO_NAMES", "KAPPA_MAX", "N_NODES", "TABLE_VERSION", "StokesTable", "cache_folder",
           "contact_limits", "table_forces", "table_ratios"]

logger = logging.getLogger(__name__)

#: Row order of the tabulated ratios.
RATIO_NAMES = RESISTANCE_NAMES

#: Exponents p of the contact limits (b/a)^p of the ratios, in RATIO_NAMES order;
#: NaN for r_t_b, whose limit is not fixed by the local analysis (module docstring).
_CONTACT_POWERS = (1.5, 0.5, 0.5, 2.5, math.nan)

#: Default largest tabulated kappa. The default mesh of the Stokes solver holds
#: its 1e-6 accuracy up to here (R_t_b to 3e-5 of itself, 3e-7 of R_t_a).
KAPPA_MAX = 0.99

#: Default number of Chebyshev-Lobatto nodes in zeta. Measured interpolation error against
#: fresh solves between nodes (:meth:`StokesTable.interpolation_error`): 3e-8 (delta/a = 0.01),
#: 1e-7 (0.406), 2.5e-7 (1), largest for T_a per W_a, whose ratio has a pole at
#: 1 + 2 kappa^2 = 0 (zeta^2 = 3/2), near the interval; 14 nodes give 8.5e-7 at 0.406.
N_NODES = 16

#: kappa of the node at zeta = 1, where the f_chi ratios take their finite limit.
KAPPA_AXIS = 1e-4

#: Bumped whenever the meaning or layout of a stored table changes; older files are rebuilt.
TABLE_VERSION = 1


def cache_folder() -> Path:
    """Folder of the stored tables: ``$SNAIL_CACHE`` if set, else ``~/.cache/snail-cylinder``."""
    env = os.environ.get("SNAIL_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "snail-cylinder"


def contact_limits(delta_over_a: float, ratio_at_kappa_max: np.ndarray) -> np.ndarray:
    """Values the ratios are blended to at contact, shape (5,), RATIO_NAMES order.

    (b/a)^p for the four coefficients dominated by the narrow gap; r_t_b keeps
    ``ratio_at_kappa_max`` (module docstring).
    """
    powers = np.array(_CONTACT_POWERS)
    return np.where(np.isnan(powers), ratio_at_kappa_max, (1.0 + delta_over_a) ** np.nan_to_num(powers))


def lobatto_zeta(zeta_min: float, n: int) -> np.ndarray:
    """Chebyshev-Lobatto points of [zeta_min, 1], increasing, ends included."""
    return zeta_min + 0.5 * (1.0 - zeta_min) * (1.0 - np.cos(np.pi * np.arange(n) / (n - 1)))


@jit
def table_ratios(zeta_nodes, node_ratios, contact, zeta):
    """The five ratios at ``zeta`` = sqrt(1 - kappa^2), RATIO_NAMES order.

    Parameters
    ----------
    zeta_nodes : ndarray, shape (n,), float64
        Chebyshev-Lobatto points of [zeta_min, 1], increasing (the barycentric
        weights (-1)^j, halved at the ends, hold for these points only).
    node_ratios : ndarray, shape (5, n), float64
        The ratios at the nodes.
    contact : ndarray, shape (5,), float64
        Values at zeta = 0 (:func:`contact_limits`); below zeta_min each ratio
        is blended to it linearly in zeta^2.
    zeta : float
        In [0, 1].
    """
    n = zeta_nodes.size
    z0 = zeta_nodes[0]
    if zeta < z0:
        s = (zeta / z0) ** 2
        return (contact[0] + (node_ratios[0, 0] - contact[0]) * s,
                contact[1] + (node_ratios[1, 0] - contact[1]) * s,
                contact[2] + (node_ratios[2, 0] - contact[2]) * s,
                contact[3] + (node_ratios[3, 0] - contact[3]) * s,
                contact[4] + (node_ratios[4, 0] - contact[4]) * s)
    den = 0.0
    r0 = r1 = r2 = r3 = r4 = 0.0
    for j in range(n):
        diff = zeta - zeta_nodes[j]
        if diff == 0.0:
            return (node_ratios[0, j], node_ratios[1, j], node_ratios[2, j],
                    node_ratios[3, j], node_ratios[4, j])
        w = 1.0 if j % 2 == 0 else -1.0
        if j == 0 or j == n - 1:
            w *= 0.5
        c = w / diff
        den += c
        r0 += c * node_ratios[0, j]
        r1 += c * node_ratios[1, j]
        r2 += c * node_ratios[2, j]
        r3 += c * node_ratios[3, j]
        r4 += c * node_ratios[4, j]
    return r0 / den, r1 / den, r2 / den, r3 / den, r4 / den


@jit
def table_forces(zeta_nodes, node_ratios, contact, a, delta, mu, length, kappa, omk,
                 eps_dot, w_a, w_b):
    """Stokes force and torque from a table: interpolated ratios times (2.5)-(2.7).

    Parameters
    ----------
    zeta_nodes, node_ratios, contact : ndarray, float64
        The arrays of a :class:`StokesTable` (see :func:`table_ratios`), built
        for delta/a = ``delta / a``.
    a, delta, mu, length, kappa, omk, eps_dot, w_a, w_b : float
        As for :func:`lubrication.closed_form.lubrication_forces`: radius a (m),
        mean gap (m), viscosity (Pa s), length (m), kappa and 1 - kappa,
        eps' (m/s), W_a and W_b (rad/s).

    Returns
    -------
    f_eps, f_chi, T_a : float
        N, N, N m, whole length.
    """
    zeta = math.sqrt(omk * (1.0 + kappa))
    r_eps, r_chi_a, r_t_a, r_chi_b, r_t_b = table_ratios(zeta_nodes, node_ratios, contact, zeta)
    f_eps = lubrication_forces(a, delta, mu, length, kappa, omk, eps_dot, 0.0, 0.0)[0]
    _, f_chi_a, t_a_a = lubrication_forces(a, delta, mu, length, kappa, omk, 0.0, w_a, 0.0)
    _, f_chi_b, t_a_b = lubrication_forces(a, delta, mu, length, kappa, omk, 0.0, 0.0, w_b)
    return (r_eps * f_eps, r_chi_a * f_chi_a + r_chi_b * f_chi_b,
            r_t_a * t_a_a + r_t_b * t_a_b)


def _settings(delta_over_a, kappa_max, n_nodes, n_around, n_across, clustering) -> dict:
    from .stokes import default_mesh

    d = check_range("delta_over_a", delta_over_a, 0.0, math.inf, low_open=True)
    # gaps equal to 12 digits (0.40625 and the apparatus' (b - a)/a = 0.40624999999999994) share one
    # table: their ratios differ by O(1e-12), far below the table's own error
    d = float(f"{d:.12g}")
    kappa_max = check_range("kappa_max", kappa_max, 0.0, 1.0, low_open=True)
    if isinstance(n_nodes, bool) or not isinstance(n_nodes, (int, np.integer)) or n_nodes < 2:
        msg = f"n_nodes must be an integer >= 2, got {n_nodes!r}"
        raise ValueError(msg)
    auto_around, auto_across = default_mesh(d)
    return {"version": TABLE_VERSION, "delta_over_a": d, "kappa_max": kappa_max,
            "n_nodes": int(n_nodes),
            "n_around": int(auto_around if n_around is None else n_around),
            "n_across": int(auto_across if n_across is None else n_across),
            "clustering": float(clustering)}


@dataclass(frozen=True, eq=False)
class StokesTable:
    """Stokes resistance ratios of one delta/a, tabulated against zeta = sqrt(1 - kappa^2).

    Build or load one with :meth:`load` (cached) or :meth:`build` (no files).

    Attributes
    ----------
    settings : dict
        ``version``, ``delta_over_a``, ``kappa_max``, ``n_nodes``, ``n_around``,
        ``n_across``, ``clustering``: what made the table.
    zeta_nodes : ndarray, shape (n,)
        Chebyshev-Lobatto points of [sqrt(1 - kappa_max^2), 1], increasing.
    node_ratios : ndarray, shape (5, n)
        Stokes coefficient / lubrication form (2.5)-(2.7) at the nodes, rows in
        :data:`RATIO_NAMES` order.
    contact : ndarray, shape (5,)
        Values at contact (:func:`contact_limits`).
    build_time_s : float
        Wall time of the Stokes solves (0 for a table loaded from a file).
    """

    settings: dict
    zeta_nodes: np.ndarray
    node_ratios: np.ndarray
    contact: np.ndarray
    build_time_s: float = 0.0

    @property
    def delta_over_a(self) -> float:
        return self.settings["delta_over_a"]

    @property
    def kappa_max(self) -> float:
        return self.settings["kappa_max"]

    @property
    def kappa_nodes(self) -> np.ndarray:
        """kappa at the nodes (the node at zeta = 1 was solved at KAPPA_AXIS)."""
        z = self.zeta_nodes
        return np.sqrt((1.0 - z) * (1.0 + z))

    @property
    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(zeta_nodes, node_ratios, contact): the arguments of :func:`table_forces`."""
        return self.zeta_nodes, self.node_ratios, self.contact

    @classmethod
    def build(cls, delta_over_a: float, *, kappa_max: float = KAPPA_MAX, n_nodes: int = N_NODES,
              n_around: int | None = None, n_across: int | None = None,
              clustering: float = 0.5) -> StokesTable:
        """Solve the Stokes problem at every node (about n_nodes seconds); writes nothing.

        Parameters
        ----------
        delta_over_a : float
            Mean gap over inner radius.
        kappa_max : float
            Largest tabulated kappa; beyond it the ratios are blended to their
            contact values (module docstring).
        n_nodes : int
            Chebyshev-Lobatto nodes in zeta.
        n_around, n_across, clustering
            Mesh of :func:`lubrication.stokes.stokes_resistance` (default
            :func:`lubrication.stokes.default_mesh`).
        """
        from .stokes import stokes_resistance

        s = _settings(delta_over_a, kappa_max, n_nodes, n_around, n_across, clustering)
        zeta_min = math.sqrt((1.0 - s["kappa_max"]) * (1.0 + s["kappa_max"]))
        zeta = lobatto_zeta(zeta_min, s["n_nodes"])
        start = time.perf_counter()
        ratios = np.empty((len(RATIO_NAMES), zeta.size))
        for j, z in enumerate(zeta):
            kappa = max(math.sqrt((1.0 - z) * (1.0 + z)), KAPPA_AXIS)
            r = stokes_resistance(1.0, 1.0 + s["delta_over_a"], kappa, n_around=s["n_around"],
                                  n_across=s["n_across"], clustering=s["clustering"])
            found = r.lubrication_ratios()
            ratios[:, j] = [found[name] for name in RATIO_NAMES]
        wall = time.perf_counter() - start
        logger.info("Stokes table for delta/a %g: %d nodes in %.1f s.", s["delta_over_a"], zeta.size, wall)
        return cls(s, zeta, ratios, contact_limits(s["delta_over_a"], ratios[:, 0]), wall)

    @classmethod
    def load(cls, delta_over_a: float, *, folder: str | os.PathLike | None = None,
             kappa_max: float = KAPPA_MAX, n_nodes: int = N_NODES, n_around: int | None = None,
             n_across: int | None = None, clustering: float = 0.5) -> StokesTable:
        """The table of ``delta_over_a`` from the cache, built and stored if absent or stale.

        Parameters
        ----------
        folder : path, optional
            Where tables are kept; :func:`cache_folder` by default.
        kappa_max, n_nodes, n_around, n_across, clustering
            As for :meth:`build`. A stored table made with other settings, or by
            another TABLE_VERSION, is rebuilt and overwritten.
        """
        wanted = _settings(delta_over_a, kappa_max, n_nodes, n_around, n_across, clustering)
        path = cls.path(wanted["delta_over_a"], folder)
        stored = cls.read(path)
        if stored is not None and stored.settings == wanted:
            return stored
        if stored is not None:
            logger.info("Stokes table %s was made with other settings; rebuilding.", path)
        table = cls.build(wanted["delta_over_a"], kappa_max=wanted["kappa_max"],
                          n_nodes=wanted["n_nodes"], n_around=wanted["n_around"],
                          n_across=wanted["n_across"], clustering=wanted["clustering"])
        table.save(path)
        return table

    @staticmethod
    def path(delta_over_a: float, folder: str | os.PathLike | None = None) -> Path:
        """File of the table of ``delta_over_a`` in ``folder`` (default :func:`cache_folder`)."""
        folder = cache_folder() if folder is None else Path(folder)
        return folder / f"stokes-ratios-delta_over_a-{float(delta_over_a)!r}.npz"

    @classmethod
    def read(cls, path: str | os.PathLike) -> StokesTable | None:
        """The table stored at ``path``, or None if absent or unreadable without pickle."""
        path = Path(path)
        if not path.is_file():
            return None
        try:
            with np.load(path, allow_pickle=False) as data:
                settings = {"version": int(data["version"]),
                            "delta_over_a": float(data["delta_over_a"]),
                            "kappa_max": float(data["kappa_max"]),
                            "n_nodes": int(data["n_nodes"]), "n_around": int(data["n_around"]),
                            "n_across": int(data["n_across"]), "clustering": float(data["clustering"])}
                arrays = [np.ascontiguousarray(data[k], dtype=np.float64)
                          for k in ("zeta_nodes", "node_ratios", "contact")]
        except (OSError, ValueError, KeyError) as err:
            logger.warning("Ignoring unreadable Stokes table %s: %s", path, err)
            return None
        zeta, ratios, contact = arrays
        if ratios.shape != (len(RATIO_NAMES), zeta.size) or contact.shape != (len(RATIO_NAMES),):
            logger.warning("Ignoring Stokes table %s with inconsistent shapes.", path)
            return None
        return cls(settings, zeta, ratios, contact)

    def save(self, path: str | os.PathLike) -> Path:
        """Write the table as ``.npz`` (no pickled objects), whole or not at all."""
        buf = io.BytesIO()
        np.savez(buf, zeta_nodes=self.zeta_nodes, node_ratios=self.node_ratios, contact=self.contact,
                 **self.settings)
        return write_bytes(path, buf.getvalue())

    def ratios(self, kappa) -> np.ndarray:
        """Interpolated ratios at ``kappa`` (scalar or array in [0, 1)), shape (5,) + kappa's shape.

        NumPy twin of the jitted :func:`table_ratios`: scipy's barycentric
        interpolator inside the table, the zeta^2 blend beyond.
        """
        from scipy.interpolate import BarycentricInterpolator

        kappa = np.asarray(kappa, dtype=float)
        if not np.all((kappa >= 0.0) & (kappa < 1.0)):
            msg = f"kappa must be in [0, 1), got {kappa!r}"
            raise ValueError(msg)
        zeta = np.sqrt((1.0 - kappa) * (1.0 + kappa))
        inside = BarycentricInterpolator(self.zeta_nodes, self.node_ratios, axis=1)(
            np.maximum(zeta, self.zeta_nodes[0]))
        blend = (zeta / self.zeta_nodes[0]) ** 2
        beyond = self.contact.reshape((-1,) + (1,) * zeta.ndim) + np.multiply.outer(
            self.node_ratios[:, 0] - self.contact, blend)
        return np.where(zeta < self.zeta_nodes[0], beyond, inside)

    def forces(self, annulus: Annulus, motion: Motion, fluid: Fluid) -> FluidForces:
        """Stokes force and torque on the inner cylinder from the table, whole length."""
        if not math.isclose(annulus.delta_over_a, self.delta_over_a, rel_tol=1e-9):
            msg = (f"this Stokes table is for delta/a = {self.delta_over_a:g}, "
                   f"the annulus has delta/a = {annulus.delta_over_a:g}")
            raise ValueError(msg)
        f = table_forces(*self.arrays, annulus.a, annulus.delta, fluid.mu, annulus.length,
                         annulus.kappa, annulus.one_minus_kappa, motion.eps_dot, motion.w_a, motion.w_b)
        return FluidForces(*f, model="stokes-table")

    def interpolation_error(self, kappas) -> np.ndarray:
        """|table / fresh Stokes solve - 1| at ``kappas``, shape (5, len(kappas)), same mesh.

        For R_t_b near contact the relative error of a small O(zeta) remainder
        is large by construction; compare it with R_t_a, which is (2.7) larger
        by (1 + 2 kappa^2)/(1 - kappa^2).
        """
        from .stokes import stokes_resistance

        s = self.settings
        kappas = np.atleast_1d(np.asarray(kappas, dtype=float))
        table = self.ratios(kappas)
        err = np.empty_like(table)
        for i, kappa in enumerate(kappas):
            r = stokes_resistance(1.0, 1.0 + s["delta_over_a"], float(kappa), n_around=s["n_around"],
                                  n_across=s["n_across"], clustering=s["clustering"])
            found = r.lubrication_ratios()
            err[:, i] = [abs(table[k, i] / found[name] - 1.0) for k, name in enumerate(RATIO_NAMES)]
        return err
