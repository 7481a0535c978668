r"""Flow snapshots of the unsteady solver: VTU files for ParaView, pictures and animations.

A snapshot is the mapping :meth:`lubrication.unsteady.solver.UnsteadySolver.fields` returns (``t`` added by
:func:`lubrication.unsteady.prescribed.run_prescribed`): ``x``, ``z`` (m), ``vorticity`` (1/s, clockwise positive),
``stream_function`` (m^2/s), ``u_x``, ``u_z`` (m/s), each of shape (n_r, n_theta), in the
frame translating with the outer centre B. Row 0 lies on the outer wall and the last row
on the inner one (Chebyshev-Lobatto points across the gap); the columns are the
computational angle theta_j = 2 pi j / n_theta, periodic.

VTU. One quadrilateral mesh per snapshot: the grid's points at (x, z, 0), cells joining
neighbouring rows and columns, the last column joined to the first (the periodic seam
closed without repeating a point); point data ``vorticity``, ``stream_function`` and
``velocity`` = (u_x, u_z, 0). A ``.pvd`` collection lists the files with their times, so
that ParaView opens the series as one time-dependent data set. meshio writes them; it is
in the ``fem`` extra and imported only here.

Pictures. The vorticity as filled contours, the streamlines as contours of the stream
function, and both walls. The grid's rows are circles (the images of |w| = const under
the map of :mod:`lubrication.unsteady.mapping`), so the picture is drawn on a finer grid:
Chebyshev interpolation across the gap (the solver's own representation there) and, along
each row, shape-preserving interpolation of the angle on the row's circle and of the
fields in theta. Coarse grids then show smooth walls and contours; the files keep the
solver's points.

Frames. ``"lab"``: as the solver gives them (translating with B, not turning).
``"outer"``: turning with the outer cylinder, whose clockwise angle theta_b(t) (the
integral of Omega_b) and spin Omega_b the caller gives per snapshot. Positions are turned
back by theta_b, so that the outer wall's material points stand still in the picture, and
the flow is the flow relative to the outer wall's rigid rotation -i Omega_b zeta: velocity
u + i Omega_b zeta (turned), stream function psi - Omega_b |zeta|^2 / 2, vorticity
omega - 2 Omega_b (all clockwise-positive as the project's rotations).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

__all__ = ["FIELD_NAMES", "FRAMES", "MAX_SNAPSHOTS", "animate", "draw_frame", "flow_mesh", "in_frame", "output_files",
           "pvd_text", "quad_cells", "refined", "require_meshio", "series_names", "write_vtu_series"]

#: The fields of a snapshot besides its positions ``x`` and ``z``.
FIELD_NAMES = ("vorticity", "stream_function", "u_x", "u_z")
#: The frames a snapshot can be drawn in (module docstring).
FRAMES = ("lab", "outer")
#: Most snapshots a run may ask for: each is a VTU file and a frame of the animation (0.1-0.3 s to draw).
MAX_SNAPSHOTS = 1000


def require_meshio():
    """The meshio module; an ImportError naming the extra that installs it when it is missing."""
    try:
        import meshio
    except ImportError as err:
        msg = ("flow snapshots are written as VTU files by meshio, which is in the fem extra: "
               "pip install 'snail-cylinder[fem]'")
        raise ImportError(msg) from err
    return meshio


def _grid(snapshot: Mapping) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """zeta = x + i z and the fields of a snapshot, checked to share one (n_r, n_theta) shape."""
    zeta = np.asarray(snapshot["x"], dtype=float) + 1j * np.asarray(snapshot["z"], dtype=float)
    if zeta.ndim != 2 or zeta.shape[0] < 2 or zeta.shape[1] < 3:
        msg = f"a snapshot's x and z must have shape (n_r >= 2, n_theta >= 3), got {zeta.shape}"
        raise ValueError(msg)
    fields = {name: np.asarray(snapshot[name], dtype=float) for name in FIELD_NAMES}
    for name, values in fields.items():
        if values.shape != zeta.shape:
            msg = f"the snapshot's {name} has shape {values.shape}, its grid {zeta.shape}"
            raise ValueError(msg)
    return zeta, fields


# ---------------------------------------------------------------------------- files

def quad_cells(n_r: int, n_theta: int) -> np.ndarray:
    """Quadrilaterals of the (n_r, n_theta) grid, shape ((n_r - 1) n_theta, 4), seam closed.

    Point (i, j) has the index i n_theta + j. Each cell runs along its outer row from j to j + 1
    (counterclockwise: the map keeps theta's sense), then back along the row inside it:
    counterclockwise round the cell, a positive area in the (x, z) plane.
    """
    i, j = np.meshgrid(np.arange(n_r - 1), np.arange(n_theta), indexing="ij")
    right = (j + 1) % n_theta
    cells = np.stack([i * n_theta + j, i * n_theta + right, (i + 1) * n_theta + right, (i + 1) * n_theta + j],
                     axis=-1)
    return cells.reshape(-1, 4)


def flow_mesh(snapshot: Mapping):
    """The snapshot as a :class:`meshio.Mesh`: quads of the grid, points (x, z, 0), the fields as point data.

    Point data: ``vorticity`` (1/s), ``stream_function`` (m^2/s), ``velocity`` (m/s, shape (n, 3)).

    Raises
    ------
    ImportError
        Without meshio (the ``fem`` extra).
    """
    meshio = require_meshio()
    zeta, fields = _grid(snapshot)
    n_r, n_theta = zeta.shape
    points = np.column_stack([zeta.real.ravel(), zeta.imag.ravel(), np.zeros(zeta.size)])
    velocity = np.column_stack([fields["u_x"].ravel(), fields["u_z"].ravel(), np.zeros(zeta.size)])
    return meshio.Mesh(points, [("quad", quad_cells(n_r, n_theta))],
                       point_data={"vorticity": fields["vorticity"].ravel(),
                                   "stream_function": fields["stream_function"].ravel(), "velocity": velocity})


def series_names(count: int, stem: str = "flow") -> list[str]:
    """The file names of a series of ``count`` snapshots: stem_0000.vtu, ... (wider past 10^4)."""
    width = max(4, len(str(max(count - 1, 0))))
    return [f"{stem}_{i:0{width}d}.vtu" for i in range(count)]


def output_files(stem: str = "flow") -> frozenset[str]:
    """Every file a series of up to :data:`MAX_SNAPSHOTS` snapshots may leave in a folder: the VTU files
    (:func:`series_names`), the collection ``stem.pvd`` and the animation ``stem.gif``."""
    return frozenset({f"{stem}.pvd", f"{stem}.gif", *series_names(MAX_SNAPSHOTS, stem)})


def pvd_text(files: Sequence[str], times: Sequence[float]) -> str:
    """A ParaView collection (.pvd) of ``files`` (relative to it) at ``times`` (s)."""
    from xml.sax.saxutils import quoteattr

    if len(files) != len(times):
        msg = f"a collection needs one time per file, got {len(files)} files and {len(times)} times"
        raise ValueError(msg)
    rows = "".join(f'    <DataSet timestep="{float(t)!r}" group="" part="0" file={quoteattr(str(name))}/>\n'
                   for name, t in zip(files, times))
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f"  <Collection>\n{rows}  </Collection>\n</VTKFile>\n")


def write_vtu_series(snapshots: Sequence[Mapping], folder: str | Path, stem: str = "flow") -> tuple[list[Path], Path]:
    """Write each snapshot as ``folder/stem_NNNN.vtu`` and the collection ``folder/stem.pvd``.

    Times are the snapshots' ``t`` (s). Returns the VTU paths and the collection's path.

    Raises
    ------
    ImportError
        Without meshio (the ``fem`` extra).
    """
    from numerics.files import write_text

    meshio = require_meshio()
    folder = Path(folder)
    names = series_names(len(snapshots), stem)
    paths = []
    for name, snapshot in zip(names, snapshots):
        path = folder / name
        meshio.write(path, flow_mesh(snapshot), file_format="vtu")
        paths.append(path)
    pvd = write_text(folder / f"{stem}.pvd", pvd_text(names, [float(s["t"]) for s in snapshots]))
    return paths, pvd


# ---------------------------------------------------------------------------- frames

def in_frame(snapshot: Mapping, frame: str = "lab", theta_b: float = 0.0, omega_b: float = 0.0) -> dict:
    """The snapshot's positions and fields in ``frame`` (module docstring); ``t`` kept.

    Parameters
    ----------
    snapshot : mapping
        As :meth:`lubrication.unsteady.solver.UnsteadySolver.fields` (any grid of points, such as :func:`refined`'s).
    frame : {"lab", "outer"}
    theta_b : float
        Angle the outer cylinder has turned since t = 0 (rad, clockwise); "outer" only.
    omega_b : float
        Its spin at the snapshot's time (rad/s, clockwise); "outer" only.
    """
    if frame not in FRAMES:
        msg = f"frame must be one of {', '.join(map(repr, FRAMES))}, got {frame!r}"
        raise ValueError(msg)
    zeta, fields = _grid(snapshot)
    out = {key: value for key, value in snapshot.items() if key not in ("x", "z", *FIELD_NAMES)}
    if frame == "outer":
        # a point of the outer wall moves as e^{-i theta_b} zeta_0: turning back by theta_b holds it still
        turn = complex(math.cos(theta_b), math.sin(theta_b))
        velocity = (fields["u_x"] + 1j * fields["u_z"] + 1j * omega_b * zeta) * turn
        fields = {"vorticity": fields["vorticity"] - 2.0 * omega_b,
                  "stream_function": fields["stream_function"] - 0.5 * omega_b * np.abs(zeta) ** 2,
                  "u_x": velocity.real, "u_z": velocity.imag}
        zeta = zeta * turn
    return {**out, "x": zeta.real, "z": zeta.imag, **fields}


# ---------------------------------------------------------------------------- a finer grid to draw on

def _circle(points: np.ndarray) -> tuple[complex, float]:
    """Centre and radius of the circle through ``points`` (complex), by least squares (exact on a circle)."""
    shift = points.mean()
    p = points - shift
    # |p - c|^2 = r^2  <=>  2 Re(conj(c) p) + (r^2 - |c|^2) = |p|^2: linear in (Re c, Im c, r^2 - |c|^2)
    matrix = np.column_stack([2.0 * p.real, 2.0 * p.imag, np.ones(p.size)])
    (cx, cz, k), *_ = np.linalg.lstsq(matrix, np.abs(p) ** 2, rcond=None)
    centre = complex(cx, cz)
    return centre + shift, math.sqrt(k + abs(centre) ** 2)


def _periodic_pchip(theta: np.ndarray, values: np.ndarray, fine: np.ndarray, jump: float = 0.0) -> np.ndarray:
    """Shape-preserving cubic interpolation of ``values`` (along axis 0) of a 2 pi-periodic variable.

    ``jump`` is what the quantity gains over a period (2 pi for an angle that goes round once).
    PCHIP is local (each slope from the two neighbouring intervals), so two points copied
    from each end make it periodic.
    """
    from scipy.interpolate import PchipInterpolator

    pad = 2
    nodes = np.concatenate([theta[-pad:] - 2.0 * math.pi, theta, theta[:pad] + 2.0 * math.pi])
    data = np.concatenate([values[-pad:] - jump, values, values[:pad] + jump])
    return PchipInterpolator(nodes, data, axis=0)(fine)


def refined(snapshot: Mapping, n_r: int = 24, n_theta: int = 192) -> dict:
    """The snapshot on a finer grid of at least ``n_r`` x ``n_theta`` points, for drawing (module docstring).

    Across the gap, barycentric interpolation on the solver's Chebyshev-Lobatto points; along
    each row, the row's circle is fitted and the angle on it and the fields are interpolated
    in theta by periodic PCHIP, which keeps the points in order round the circle however
    unevenly the map spreads them. Walls stay exact circles. A grid already as fine is kept.
    """
    from scipy.interpolate import BarycentricInterpolator

    zeta, fields = _grid(snapshot)
    rows, cols = zeta.shape
    data = np.stack([zeta.real, zeta.imag, *fields.values()], axis=-1)  # (rows, cols, 2 + fields)
    if n_r > rows:
        nodes = np.cos(math.pi * np.arange(rows) / (rows - 1))
        data = BarycentricInterpolator(nodes, data, axis=0)(np.cos(math.pi * np.arange(n_r) / (n_r - 1)))
        rows = n_r
    if n_theta > cols:
        theta = 2.0 * math.pi * np.arange(cols) / cols
        fine = 2.0 * math.pi * np.arange(n_theta) / n_theta
        out = np.empty((rows, n_theta, data.shape[2]))
        for i in range(rows):
            points = data[i, :, 0] + 1j * data[i, :, 1]
            centre, radius = _circle(points)
            offset = points - centre
            # each step round the row turns counterclockwise (the map keeps the sense), by less than 2 pi
            steps = np.mod(np.angle(np.roll(offset, -1) / offset), 2.0 * math.pi)
            angle = np.angle(offset[0]) + np.concatenate([[0.0], np.cumsum(steps[:-1])])
            on_circle = centre + radius * np.exp(1j * _periodic_pchip(theta, angle, fine, jump=2.0 * math.pi))
            out[i, :, 0], out[i, :, 1] = on_circle.real, on_circle.imag
            out[i, :, 2:] = _periodic_pchip(theta, data[i, :, 2:], fine)
        data = out
    result = {key: value for key, value in snapshot.items() if key not in ("x", "z", *FIELD_NAMES)}
    result.update(x=data[..., 0], z=data[..., 1])
    result.update({name: data[..., 2 + k] for k, name in enumerate(FIELD_NAMES)})
    return result


# ---------------------------------------------------------------------------- pictures

def _closed(values: np.ndarray) -> np.ndarray:
    """The grid's values with the first column repeated at the end: the contours close round the annulus."""
    return np.concatenate([values, values[:, :1]], axis=1)


def _vorticity_limit(snapshots: Sequence[Mapping]) -> float:
    """A symmetric colour range that holds every snapshot's vorticity (1 for a flow at rest)."""
    largest = max((float(np.max(np.abs(s["vorticity"]))) for s in snapshots), default=0.0)
    return largest if largest > 0.0 else 1.0


def _draw_flow(ax, view: Mapping, limit: float, streamlines: int) -> list:
    """Vorticity, streamlines and walls of a snapshot already in its frame; the artists added."""
    from matplotlib.patches import Circle

    x, z = _closed(view["x"]), _closed(view["z"])
    added = [ax.contourf(x, z, np.clip(_closed(view["vorticity"]), -limit, limit),
                         levels=np.linspace(-limit, limit, 25), cmap="RdBu_r")]
    psi = _closed(view["stream_function"])
    if float(psi.max() - psi.min()) > 1e-12 * float(np.abs(psi).max()):  # a fluid at rest has no streamlines
        added.append(ax.contour(x, z, psi, levels=np.linspace(psi.min(), psi.max(), streamlines + 2)[1:-1],
                                colors="k", linewidths=0.6, linestyles="solid"))
    for row, solid in ((0, False), (-1, True)):
        centre, radius = _circle(view["x"][row] + 1j * view["z"][row])
        added.append(ax.add_patch(Circle((centre.real, centre.imag), radius, fill=solid, facecolor="0.85",
                                         edgecolor="k", linewidth=1.4, zorder=3)))
    return added


def _title(snapshot: Mapping, frame: str) -> str:
    where = "turning with the outer cylinder" if frame == "outer" else "translating with B"
    time = f"t = {float(snapshot['t']):.4g} s, " if "t" in snapshot else ""
    return f"{time}frame {where}"


def _set_view(ax, b: float) -> None:
    ax.set(xlim=(-1.05 * b, 1.05 * b), ylim=(-1.05 * b, 1.05 * b), aspect="equal", xlabel="x (m)", ylabel="z (m)")


def draw_frame(snapshot: Mapping, ax=None, *, frame: str = "lab", theta_b: float = 0.0, omega_b: float = 0.0,
               vorticity_limit: float | None = None, streamlines: int = 16, colorbar: bool = True,
               fine_grid: tuple[int, int] = (24, 192)):
    """Draw one snapshot: vorticity filled, streamlines, both walls; return the matplotlib Axes.

    Parameters
    ----------
    snapshot : mapping
        As :meth:`lubrication.unsteady.solver.UnsteadySolver.fields`, with its time ``t`` (s) if it is to be shown.
    ax : matplotlib Axes or None
        Where to draw; default a new figure's (not shown: save it with ``ax.figure.savefig``).
    frame, theta_b, omega_b
        The frame and, for "outer", the outer cylinder's angle (rad) and spin (rad/s), clockwise
        (:func:`in_frame`).
    vorticity_limit : float or None
        Colour range [-limit, limit] (1/s); default the snapshot's largest |vorticity|.
    streamlines : int
        Contour levels of the stream function.
    colorbar : bool
    fine_grid : (int, int)
        Points (n_r, n_theta) of the grid the picture is drawn on (:func:`refined`).
    """
    from matplotlib.figure import Figure

    if ax is None:
        ax = Figure(figsize=(5.6, 4.6), layout="constrained").add_subplot()
    view = in_frame(refined(snapshot, *fine_grid), frame, theta_b, omega_b)
    filled = _draw_flow(ax, view, vorticity_limit or _vorticity_limit([view]), streamlines)[0]
    _set_view(ax, float(np.max(np.abs(view["x"][0] + 1j * view["z"][0]))))
    ax.set_title(_title(snapshot, frame), fontsize=9)
    if colorbar:
        ax.figure.colorbar(filled, ax=ax, label="vorticity (1/s, clockwise positive)", shrink=0.85)
    return ax


def animate(snapshots: Sequence[Mapping], path: str | Path, *, frame: str = "lab",
            theta_b: Sequence[float] | None = None, omega_b: Sequence[float] | None = None, fps: float = 10.0,
            dpi: float = 80.0, streamlines: int = 16, fine_grid: tuple[int, int] = (24, 192)) -> Path:
    """Draw each snapshot (as :func:`draw_frame`, one colour range for all) into a GIF at ``path``.

    ``theta_b`` and ``omega_b``: the outer cylinder's angle (rad) and spin (rad/s) at each snapshot,
    clockwise, for ``frame="outer"`` (zeros by default). Written by matplotlib's PillowWriter.
    """
    from matplotlib.animation import PillowWriter
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    count = len(snapshots)
    if count == 0:
        msg = "an animation needs at least one snapshot"
        raise ValueError(msg)
    theta_b = np.zeros(count) if theta_b is None else np.asarray(theta_b, dtype=float)
    omega_b = np.zeros(count) if omega_b is None else np.asarray(omega_b, dtype=float)
    if theta_b.shape != (count,) or omega_b.shape != (count,):
        msg = f"theta_b and omega_b need one value per snapshot ({count})"
        raise ValueError(msg)
    views = [in_frame(refined(s, *fine_grid), frame, tb, wb) for s, tb, wb in zip(snapshots, theta_b, omega_b)]
    limit = _vorticity_limit(views)
    # fixed axes, drawn once; each frame replaces only the flow's artists (a layout engine and
    # new axes would measure and draw every label again: three quarters of the time)
    fig = Figure(figsize=(5.6, 4.6))
    ax = fig.add_axes((0.17, 0.1, 0.62, 0.82))
    fig.colorbar(ScalarMappable(Normalize(-limit, limit), "RdBu_r"), cax=fig.add_axes((0.82, 0.14, 0.03, 0.72)),
                 label="vorticity (1/s, clockwise positive)")
    _set_view(ax, max(float(np.max(np.abs(v["x"][0] + 1j * v["z"][0]))) for v in views))
    path = Path(path)
    writer = PillowWriter(fps=fps)
    drawn: list = []
    with writer.saving(fig, path, dpi):
        for snapshot, view in zip(snapshots, views):
            for artist in drawn:
                artist.remove()
            drawn = _draw_flow(ax, view, limit, streamlines)
            ax.set_title(_title(snapshot, frame), fontsize=9)
            writer.grab_frame()
    return path
