"""Flow snapshots (lubrication.unsteady.snapshots): VTU files and their collection, frames, pictures, animations.

The snapshots here are made from closed forms on the solver's kind of grid (Chebyshev
points across, row 0 on the outer wall; uniform theta), not by the solver: circular
Couette flow, whose vorticity is uniform, and a rigid rotation, which is at rest in the
frame turning with the outer wall.
"""

import math
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from lubrication.unsteady import AnnulusMap
from lubrication.unsteady.snapshots import (
    FIELD_NAMES,
    animate,
    draw_frame,
    flow_mesh,
    in_frame,
    quad_cells,
    refined,
    require_meshio,
    write_vtu_series,
)

A, B = 0.008, 0.01125


def _concentric_grid(n_r: int, n_theta: int) -> np.ndarray:
    """zeta on the solver's grid of the concentric annulus: r = b exp(-ln(b/a)(1 - x)/2), x Chebyshev-Lobatto."""
    x = np.cos(math.pi * np.arange(n_r) / (n_r - 1))
    r = B * np.exp(-math.log(B / A) * (1.0 - x) / 2.0)
    return r[:, None] * np.exp(2j * math.pi * np.arange(n_theta) / n_theta)[None, :]


def couette(spin: float, n_r: int = 6, n_theta: int = 12, t: float = 0.0) -> dict:
    """Steady flow of the inner wall spinning clockwise at ``spin`` (rad/s) inside the outer one at rest.

    Counterclockwise u_theta = C r + D/r with u_theta(a) = -spin a, u_theta(b) = 0; psi' = -u_theta;
    counterclockwise vorticity 2 C, so the clockwise field the project uses is -2 C.
    """
    zeta = _concentric_grid(n_r, n_theta)
    r = np.abs(zeta)
    c = spin * A * A / (B * B - A * A)
    d = -c * B * B
    velocity = (c * r + d / r) * 1j * zeta / r
    return {"t": t, "x": zeta.real, "z": zeta.imag, "vorticity": np.full(zeta.shape, -2.0 * c),
            "stream_function": -(0.5 * c * r**2 + d * np.log(r / B)), "u_x": velocity.real, "u_z": velocity.imag}


def rigid_rotation(spin: float, n_r: int = 6, n_theta: int = 12) -> dict:
    """Everything turning clockwise at ``spin`` about B: u = -i spin zeta, psi = spin |zeta|^2/2, vorticity 2 spin."""
    zeta = _concentric_grid(n_r, n_theta)
    velocity = -1j * spin * zeta
    return {"t": 1.0, "x": zeta.real, "z": zeta.imag, "vorticity": np.full(zeta.shape, 2.0 * spin),
            "stream_function": 0.5 * spin * np.abs(zeta) ** 2, "u_x": velocity.real, "u_z": velocity.imag}


def test_the_quad_mesh_closes_the_seam_with_counterclockwise_cells():
    n_r, n_theta = 5, 8
    cells = quad_cells(n_r, n_theta)
    assert cells.shape == ((n_r - 1) * n_theta, 4)
    uses = np.bincount(cells.ravel(), minlength=n_r * n_theta).reshape(n_r, n_theta)
    assert np.all(uses[1:-1] == 4) and np.all(uses[[0, -1]] == 2)  # no seam: every point in all its cells
    p = _concentric_grid(n_r, n_theta).ravel()[cells]
    area = 0.5 * np.sum(p.real * np.roll(p.imag, -1, axis=1) - np.roll(p.real, -1, axis=1) * p.imag, axis=1)
    assert np.all(area > 0.0)
    # the cells tile the polygonal annulus: its area between the inner and outer polygons
    polygon = 0.5 * n_theta * math.sin(2.0 * math.pi / n_theta)
    assert abs(area.sum() / (polygon * (B * B - A * A)) - 1.0) < 1e-12


def test_vtu_series_reads_back_with_its_fields_and_the_collection_lists_it(tmp_path):
    meshio = pytest.importorskip("meshio")
    snaps = [couette(spin, t=t) for spin, t in ((0.5, 0.0), (1.0, 0.25), (2.0, 0.5))]
    paths, pvd = write_vtu_series(snaps, tmp_path)
    assert [p.name for p in paths] == ["flow_0000.vtu", "flow_0001.vtu", "flow_0002.vtu"]
    for path, snap in zip(paths, snaps):
        mesh = meshio.read(path)
        n = snap["x"].size
        assert mesh.points.shape == (n, 3) and np.all(mesh.points[:, 2] == 0.0)
        assert np.array_equal(mesh.points[:, 0], snap["x"].ravel()) and np.array_equal(mesh.points[:, 1], snap["z"].ravel())
        assert mesh.cells_dict["quad"].shape == ((6 - 1) * 12, 4)
        assert mesh.point_data["vorticity"].shape == (n,) and mesh.point_data["stream_function"].shape == (n,)
        assert mesh.point_data["velocity"].shape == (n, 3)
        # Couette's uniform vorticity -2 spin a^2/(b^2 - a^2), and the inner wall's speed spin a
        spin = -snap["vorticity"][0, 0] * (B * B - A * A) / (2.0 * A * A)
        assert np.allclose(mesh.point_data["vorticity"], -2.0 * spin * A * A / (B * B - A * A), rtol=1e-15)
        inner = np.linalg.norm(mesh.point_data["velocity"], axis=1).reshape(6, 12)[-1]
        assert np.allclose(inner, spin * A, rtol=1e-12)
    root = ET.parse(pvd).getroot()
    rows = [(d.get("file"), float(d.get("timestep"))) for d in root.iter("DataSet")]
    assert root.get("type") == "Collection"
    assert rows == [("flow_0000.vtu", 0.0), ("flow_0001.vtu", 0.25), ("flow_0002.vtu", 0.5)]


def test_the_mesh_without_meshio_names_the_extra_that_installs_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "meshio", None)  # import meshio then raises ImportError
    with pytest.raises(ImportError, match=r"fem extra: pip install 'snail-cylinder\[fem\]'"):
        require_meshio()
    with pytest.raises(ImportError, match="meshio"):
        flow_mesh(couette(1.0))


def test_a_rigid_rotation_is_at_rest_in_the_frame_of_the_outer_wall():
    spin, turned = 3.0, 0.7
    snap = rigid_rotation(spin)
    view = in_frame(snap, "outer", theta_b=turned, omega_b=spin)
    scale = spin * B
    assert np.max(np.hypot(view["u_x"], view["u_z"])) < 1e-15 * scale
    assert np.max(np.abs(view["vorticity"])) < 1e-15 * spin
    assert np.max(np.abs(view["stream_function"])) < 1e-15 * scale * B
    # a point of the outer wall turned clockwise by theta_b since t = 0 is back where it started
    lab = snap["x"] + 1j * snap["z"]
    assert np.allclose(view["x"] + 1j * view["z"], lab * np.exp(1j * turned), rtol=0, atol=1e-15 * B)
    same = in_frame(snap, "lab", theta_b=turned, omega_b=spin)
    assert all(np.array_equal(same[k], snap[k]) for k in ("x", "z", *FIELD_NAMES)) and same["t"] == snap["t"]
    with pytest.raises(ValueError, match="frame must be one of 'lab', 'outer'"):
        in_frame(snap, "inner")


@pytest.mark.parametrize("kappa", [0.0, 0.5, 0.99])
def test_the_finer_grid_to_draw_on_keeps_the_walls_exact_and_the_rows_in_order(kappa):
    """On the eccentric grid of the map, coarse (6 x 12): the finer grid's wall rows lie on the walls, every row
    goes once round counterclockwise, and a uniform field stays uniform."""
    z_a = kappa * (B - A) * np.exp(-2.0j)
    geo = AnnulusMap(A, B, z_a)
    x = np.cos(math.pi * np.arange(6) / 5)
    zeta = geo.zeta(geo.w(x, 2.0 * math.pi * np.arange(12) / 12))
    snap = {"x": zeta.real, "z": zeta.imag, "vorticity": np.full(zeta.shape, 4.0),
            "stream_function": np.zeros(zeta.shape), "u_x": zeta.real, "u_z": zeta.imag}
    fine = refined(snap, n_r=20, n_theta=96)
    points = fine["x"] + 1j * fine["z"]
    assert points.shape == (20, 96)
    assert np.allclose(np.abs(points[0]), B, rtol=1e-12)
    assert np.allclose(np.abs(points[-1] - z_a), A, rtol=1e-12)
    for row in points[[0, 10, -1]]:
        centre = row.mean()
        turns = np.sum(np.angle(np.roll(row - centre, -1) / (row - centre))) / (2.0 * math.pi)
        assert abs(turns - 1.0) < 1e-12 and np.all(np.angle(np.roll(row - centre, -1) / (row - centre)) > 0)
    assert np.allclose(fine["vorticity"], 4.0, rtol=1e-14)


def test_a_frame_shows_the_flow_between_the_two_walls():
    ax = draw_frame(couette(1.0, t=0.125))
    circles = sorted((p.get_radius(), p.center) for p in ax.patches)
    assert np.allclose([r for r, _ in circles], [A, B], rtol=1e-12)
    assert np.allclose([c for _, c in circles], 0.0, atol=1e-15)
    assert len(ax.collections) >= 2  # the filled vorticity and the streamlines
    assert ax.get_title().startswith("t = 0.125 s") and len(ax.figure.axes) == 2  # with its colour bar


def test_an_animation_is_a_gif_of_one_frame_per_snapshot(tmp_path):
    from PIL import Image

    snaps = [couette(spin, t=0.1 * i) for i, spin in enumerate((0.0, 1.0, 2.0))]  # the first at rest
    path = animate(snaps, tmp_path / "flow.gif", frame="outer", theta_b=[0.0, 0.1, 0.2], omega_b=[0.0, 1.0, 1.0])
    with Image.open(path) as gif:
        assert gif.format == "GIF" and gif.n_frames == 3
    with pytest.raises(ValueError, match="one value per snapshot"):
        animate(snaps, tmp_path / "other.gif", theta_b=[0.0])
