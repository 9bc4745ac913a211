"""Off-screen pictures and VTK series of a blocked vent (cases.results.render, cases.results.render_vtk).

Synthetic frames: a flat 10 x 10 vent of 1 cm cells in z = 0 and a sphere of radius 3 cm above it. Frame A:
the sphere 3 cm clear, nothing blocked. Frame B: the sphere touching the vent's centre, the faces around
the centre fully blocked, their neighbours partly, the nodes within 2 cm of the centre active.
"""
import xml.etree.ElementTree as ET

import numpy as np
import pytest

pv = pytest.importorskip("pyvista")
Image = pytest.importorskip("PIL.Image")
trimesh = pytest.importorskip("trimesh")

import cases.results.render as render
from cases.results.render import (
    BLOCKED_RGB,
    UNBLOCKED_RGB,
    Frame,
    blocked_colour_fraction,
    camera_for,
    render_animation,
    render_frame,
    write_vtk_series,
)
from cases.results.render_vtk import polygon_cells

N, H = 10, 0.01  # cells per side, cell size [m]


def vent(kind="quad"):
    """(vertices, faces) of the vent: quads, triangles, or a -1 padded mix of both."""
    xs = np.arange(N + 1) * H - N * H / 2
    x, y = np.meshgrid(xs, xs, indexing="ij")
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    i, j = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    a = (i * (N + 1) + j).ravel()
    quads = np.column_stack([a, a + N + 1, a + N + 2, a + 1])
    if kind == "quad":
        return vertices, quads
    triangles = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    if kind == "tri":
        return vertices, triangles
    half = len(quads) // 2
    padded = np.column_stack([triangles, np.full(len(triangles), -1)])
    return vertices, np.concatenate([quads[:half], padded[np.r_[half:len(quads), len(quads) + half:len(triangles)]]])


def sphere(z):
    body = trimesh.creation.icosphere(subdivisions=3, radius=0.03)
    return body.vertices + [0.0, 0.0, z], body.faces


def frames(kind="quad", bodies=True):
    """Frames A (nothing blocked) and B (a patch blocked) of the vent."""
    vertices, faces = vent(kind)
    radius = np.linalg.norm(vertices[:, :2], axis=1)
    active = radius < 0.015
    sizes = (faces >= 0).sum(axis=1)
    fraction = np.where(faces >= 0, active[faces], False).sum(axis=1) / sizes
    gaps = np.where(radius < 0.04, radius - 0.015, np.inf)
    n, m = len(vertices), len(faces)
    a = Frame(0.0, 101325.0, vertices, faces, np.zeros(m), np.zeros(n, bool), np.full(n, np.inf),
              (sphere(0.06),) if bodies else ())
    b = Frame(0.0125, 135.2e3, vertices, faces, fraction, active, gaps, (sphere(0.03),) if bodies else ())
    return a, b


def colours(path):
    """The distinct colours of a picture, each packed as 0xRRGGBB."""
    with Image.open(path) as picture:
        rgb = np.asarray(picture.convert("RGB")).reshape(-1, 3).astype(np.int64)
    return np.unique(rgb @ [65536, 256, 1])


@pytest.fixture(scope="module")
def pngs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("render")
    a, b = frames()
    camera = camera_for(a)
    return (render_frame(a, folder / "a.png", camera=camera), render_frame(b, folder / "b.png", camera=camera))


def test_colour_scale_endpoints():
    assert render.fraction_rgb(0.0).tolist() == list(UNBLOCKED_RGB)
    assert render.fraction_rgb(1.0).tolist() == list(BLOCKED_RGB)
    assert render.fraction_rgb([-1.0, 2.0]).tolist() == [list(UNBLOCKED_RGB), list(BLOCKED_RGB)]


def test_blocked_colour_absent_before_present_after(pngs):
    a, b = pngs
    assert blocked_colour_fraction(a) == 0.0
    assert blocked_colour_fraction(b) > 1e-3  # 4 fully blocked 1 cm faces, partly behind the sphere


def test_pictures_are_not_blank(pngs):
    for path in pngs:
        with Image.open(path) as picture:
            assert picture.size == (800, 600) and picture.format == "PNG"
        found = colours(path)
        assert len(found) > 10
        assert np.dot(UNBLOCKED_RGB, [65536, 256, 1]) in found  # open faces drawn flat, exactly in the blue


def test_blocked_colour_seen_through_translucent_body(tmp_path):
    _, bare = frames(bodies=False)
    _, covered = frames()
    camera = camera_for(covered)
    without = blocked_colour_fraction(render.frame_image(bare, camera=camera))
    behind = blocked_colour_fraction(render.frame_image(covered, camera=camera))
    assert without > 0.0 and behind > 0.8 * without


@pytest.mark.parametrize("kind", ["tri", "mixed"])
def test_triangles_and_mixed_faces(tmp_path, kind):
    a, b = frames(kind)
    camera = camera_for(a)
    assert blocked_colour_fraction(render_frame(a, tmp_path / "a.png", camera=camera, window_size=(400, 300))) == 0
    assert blocked_colour_fraction(render_frame(b, tmp_path / "b.png", camera=camera, window_size=(400, 300))) > 0


def test_scalar_bar_brings_the_blocked_colour(tmp_path):
    a, _ = frames()
    assert blocked_colour_fraction(render.frame_image(a, window_size=(400, 300), scalar_bar=True)) > 0.0


def test_animation_gif(tmp_path):
    a, b = frames()
    path = render_animation([a, b, b], tmp_path / "run.gif", fps=5)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.gif"]  # no temporary file left
    with Image.open(path) as gif:
        assert gif.format == "GIF" and gif.size == (800, 600)
        assert gif.n_frames >= 2  # identical consecutive pictures may be merged
        gif.seek(0)
        first = np.asarray(gif.convert("RGB"))
        gif.seek(gif.n_frames - 1)
        last = np.asarray(gif.convert("RGB"))
    assert blocked_colour_fraction(first) == 0.0
    assert blocked_colour_fraction(last) > 1e-3


def test_animation_rejects_other_formats(tmp_path):
    with pytest.raises(ValueError, match="gif"):
        render_animation(frames(), tmp_path / "run.mp4")
    with pytest.raises(ValueError, match="at least one frame"):
        render_animation([], tmp_path / "run.gif")


def test_camera_fixed_from_first_frame():
    a, b = frames()
    position, focal, up = camera_for(a)
    assert position[2] > 0.0 and abs(np.dot(up, np.subtract(focal, position))) < 1e-9
    assert camera_for(a) == camera_for(a)
    assert camera_for(b) != camera_for(a)  # the body moved: hence one camera for a whole animation


@pytest.mark.parametrize("kind", ["quad", "mixed"])
def test_vtk_series_round_trip(tmp_path, kind):
    series = frames(kind)
    pvd = write_vtk_series(series, tmp_path / "vtk")
    assert pvd == tmp_path / "vtk" / "leakage.pvd"
    assert sorted(p.name for p in pvd.parent.iterdir()) == ["leakage.pvd", "leakage_0000.vtu", "leakage_0001.vtu"]
    entries = ET.parse(pvd).getroot().findall("./Collection/DataSet")
    assert [float(e.get("timestep")) for e in entries] == [f.time for f in series]
    for entry, frame in zip(entries, series):
        mesh = pv.read(pvd.parent / entry.get("file"))
        assert (mesh.n_points, mesh.n_cells) == (len(frame.leak_vertices), len(frame.leak_faces))
        np.testing.assert_allclose(mesh.points, frame.leak_vertices)
        np.testing.assert_array_equal(mesh.cell_data["blocked_fraction"], frame.blocked_fraction)
        assert mesh.point_data["active"].dtype == np.uint8
        np.testing.assert_array_equal(mesh.point_data["active"], frame.active_nodes)
        expected = np.where(np.isfinite(frame.gaps), frame.gaps, np.nan)
        np.testing.assert_array_equal(mesh.point_data["gap"], expected)  # inf written as NaN
        np.testing.assert_array_equal(mesh.cells, polygon_cells(frame.leak_faces))  # a .vtu: cells as written
    assert list(pv.get_reader(pvd).time_values) == [f.time for f in series]


def test_frame_checks_shapes():
    a, _ = frames()
    with pytest.raises(ValueError, match="blocked_fraction"):
        Frame(0.0, 1e5, a.leak_vertices, a.leak_faces, np.zeros(3), a.active_nodes, a.gaps, ())
    with pytest.raises(ValueError, match="gaps"):
        Frame(0.0, 1e5, a.leak_vertices, a.leak_faces, a.blocked_fraction, a.active_nodes, a.gaps[:-1], ())
    with pytest.raises(ValueError, match="faces"):
        Frame(0.0, 1e5, a.leak_vertices, a.leak_faces[:, :2], a.blocked_fraction, a.active_nodes, a.gaps, ())
