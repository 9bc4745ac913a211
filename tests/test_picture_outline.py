"""A blocking body can be seen in a picture: its silhouette is drawn in its own colour exactly where the body
projects on screen; an annotated picture carries the scene's label and the orientation axes; a sweep plot's title
stays inside the figure.

The body's outline is found without trusting the renderer's camera: the body's vertices are projected with the
pinhole model of the camera position (VTK's, with the vertical view angle :data:`VIEW_ANGLE`), and the pixels of the
silhouette colour must appear only in the picture with the body, near the projected outline, and on all four sides
of its projected bounding box.
"""
import numpy as np
import pytest

pv = pytest.importorskip("pyvista")
trimesh = pytest.importorskip("trimesh")

from cases.results.render import Frame, camera_for, frame_image
from cases.results.render_annotate import COLOUR_BAR_WIDTH, screen_axes, view_part
from cases.results.render_style import AXIS_RGB, SILHOUETTE_RGB, VIEW_ANGLE

SIZE = (400, 300)


def project(points, camera, size):
    """(n, 2) pixel coordinates (x right, y down) of world ``points`` seen by ``camera`` in a ``size`` view."""
    position, focal, up = (np.asarray(v, dtype=float) for v in camera)
    forward = (focal - position) / np.linalg.norm(focal - position)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    v = np.asarray(points, dtype=float) - position
    depth = v @ forward
    half = np.tan(np.radians(VIEW_ANGLE) / 2.0)
    width, height = size
    x = (v @ right) / (depth * half * width / height)
    y = (v @ true_up) / (depth * half)
    return np.column_stack([(x + 1.0) / 2.0 * width, (1.0 - y) / 2.0 * height])


def near(image, rgb, tolerance=30.0):
    """(h, w) bool: the pixels within ``tolerance`` (Euclidean, 0-255) of ``rgb``."""
    return np.linalg.norm(image[..., :3].astype(float) - rgb, axis=-1) <= tolerance


def scene(with_body=True, offset=(0.0, 0.0, 0.04)):
    """A flat 10 cm vent in z = 0 and a 2 cm-radius sphere above it (the body), as a Frame."""
    xs = np.linspace(-0.05, 0.05, 11)
    x, y = np.meshgrid(xs, xs, indexing="ij")
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    i, j = np.meshgrid(np.arange(10), np.arange(10), indexing="ij")
    a = (i * 11 + j).ravel()
    faces = np.column_stack([a, a + 11, a + 12, a + 1])
    body = trimesh.creation.icosphere(subdivisions=3, radius=0.02)
    bodies = ((body.vertices + offset, body.faces),) if with_body else ()
    n = len(vertices)
    return Frame(0.01, 1.5e5, vertices, faces, np.zeros(len(faces)), np.zeros(n, bool), np.full(n, np.inf), bodies,
                 label="demo: exchange vent, p of cavity bag")


def test_the_projection_matches_vtk():
    """The oracle's projection and the renderer's (:class:`cases.results.raster.Camera`) agree with VTK's
    world-to-display transform (what ParaView and pyvista show from the same camera) to a pixel."""
    from cases.results.raster import Camera

    frame = scene()
    camera = camera_for(frame)
    plotter = pv.Plotter(off_screen=True, window_size=list(SIZE))
    plotter.camera_position = camera
    plotter.camera.view_angle = VIEW_ANGLE
    renderer = plotter.renderer
    points = np.asarray(frame.bodies[0][0])[:20]
    ours, renderers = project(points, camera, SIZE), Camera(camera, VIEW_ANGLE, SIZE).project(points)[:, :2]
    for point, (px, py), (rx, ry) in zip(points, ours, renderers):
        renderer.SetWorldPoint(*point, 1.0)
        renderer.WorldToDisplay()
        dx, dy, _ = renderer.GetDisplayPoint()
        assert abs(dx - px) < 1.0 and abs((SIZE[1] - dy) - py) < 1.0
        assert abs(dx - rx) < 1.0 and abs((SIZE[1] - dy) - ry) < 1.0
    plotter.close()


@pytest.mark.parametrize("offset", [(0.0, 0.0, 0.04), (0.02, -0.01, 0.025)])
def test_the_body_outline_is_drawn_where_the_body_projects(offset):
    with_body, without = scene(True, offset), scene(False)
    camera = camera_for(with_body)
    shown = view_part(frame_image(with_body, window_size=SIZE, camera=camera, scalar_bar=True))
    bare = view_part(frame_image(without, window_size=SIZE, camera=camera, scalar_bar=True))
    outline, before = near(shown, SILHOUETTE_RGB), near(bare, SILHOUETTE_RGB)
    assert not before.any()  # nothing else has the silhouette's colour
    ys, xs = np.nonzero(outline)
    assert len(xs) > 100
    corners = project(with_body.bodies[0][0], camera, SIZE)
    (x0, y0), (x1, y1) = corners.min(axis=0), corners.max(axis=0)
    margin = 4.0  # the outline is 3 px wide, centred on the projected edge
    assert np.all((xs >= x0 - margin) & (xs <= x1 + margin) & (ys >= y0 - margin) & (ys <= y1 + margin))
    # the outline goes round the body: outline pixels near each side of its projected box
    for on_side in (xs <= x0 + margin, xs >= x1 - margin, ys <= y0 + margin, ys >= y1 - margin):
        assert on_side.sum() >= 3
    # and not through it: the centre of the projected sphere is not outline
    cx, cy = project([np.mean(with_body.bodies[0][0], axis=0)], camera, SIZE)[0]
    assert not outline[int(cy) - 3:int(cy) + 4, int(cx) - 3:int(cx) + 4].any()


def test_an_annotated_picture_has_its_label_and_orientation_axes():
    frame = scene()
    camera = camera_for(frame)
    image = frame_image(frame, window_size=SIZE, camera=camera, scalar_bar=True)
    assert image.shape == (SIZE[1], SIZE[0] + COLOUR_BAR_WIDTH, 3)
    plain = frame_image(frame, window_size=SIZE, camera=camera, scalar_bar=False)
    corner = image[:SIZE[1] // 3, :SIZE[0] // 4]
    # x, y and z arrows, each in its own colour, in the top-left corner (the plain view has none of them there)
    for rgb, direction in zip(AXIS_RGB, screen_axes(camera)):
        if np.linalg.norm(direction) > 0.3:  # an axis pointing at the viewer is a dot
            assert near(corner, rgb, 10.0).sum() >= 10
            assert not near(plain[:SIZE[1] // 3, :SIZE[0] // 4], rgb, 10.0).any()
    # two title lines of dark text at the top centre: two bands of rows with dark pixels
    dark = (image[:60, SIZE[0] // 4:3 * SIZE[0] // 4].max(axis=2) < 100).any(axis=1)
    assert np.count_nonzero(np.diff(dark.astype(int)) == 1) + int(dark[0]) == 2


def test_screen_axes_are_orthonormal_in_3d():
    camera = camera_for(scene())
    d = screen_axes(camera)
    np.testing.assert_allclose(d.T @ d, np.eye(2), atol=1e-12)  # rows of a rotation: columns orthonormal


def test_the_sweep_title_stays_inside_the_figure():
    pytest.importorskip("matplotlib")
    from cases.sweep.plot import sweep_figure

    rows = [{"status": "ok", "exchange.vent.discharge_coefficient": cd, "cushion.peak_pressure [Pa]": 1e5 * cd,
             "vent.min_area [m^2]": 1e-3} for cd in (0.5, 0.65, 0.8)]
    title = "a sweep of the vent's discharge coefficient on the dynamic headform scene, with a long title " * 2
    fig = sweep_figure(rows, ["exchange.vent.discharge_coefficient"], title)
    assert fig is not None
    renderer = fig.canvas.get_renderer() if hasattr(fig.canvas, "get_renderer") else None
    if renderer is None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw_without_rendering()
    box = fig._suptitle.get_window_extent(renderer)
    assert box.x0 >= 0 and box.x1 <= fig.bbox.width and box.y1 <= fig.bbox.height
    assert len(fig._suptitle.get_text().splitlines()) > 2  # wrapped
