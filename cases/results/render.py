"""Off-screen pictures of a leakage surface being blocked: PNG frames, an animated GIF, a VTK series.

What is drawn (see ``docs/rendering.md``)
-----------------------------------------
- the leakage surface, each face filled with one flat, unlit colour for its blocked fraction
  ``A_eb / A_e`` on a fixed scale [0, 1] (:func:`fraction_rgb`): unblocked :data:`UNBLOCKED_RGB` (blue),
  half blocked :data:`HALF_BLOCKED_RGB` (pale yellow), fully blocked :data:`BLOCKED_RGB` (red); face
  edges in dark grey;
- active blockage nodes as black dots;
- blocking bodies translucent green (:data:`BODY_OPACITY`, front faces only, so one layer is blended) with their
  silhouette as seen from the camera drawn opaque in dark green (:data:`SILHOUETTE_RGB`), antialiased;
- optional context surfaces (e.g. the cavity) light grey, opaque or translucent;
- annotated (``scalar_bar=True``, as the pictures of a run are): the title (the frame's ``label``: scene,
  exchange and cavity; then ``t = 12.50 ms, p = 135.2 kPa``), orientation axes, a one-line legend, a scale bar
  and, in a strip to the right of the view, the colour bar of ``A_eb / A_e [-]``
  (:mod:`cases.results.render_annotate`).

Nothing but the faces is red in the 3-D view (:func:`cases.results.render_annotate.view_part` of an annotated picture), so
:func:`blocked_colour_fraction` of it is > 0 exactly when some face is (nearly) fully blocked. A face seen through
a body is blended with the body's grey and still counts.

The camera is fixed: :func:`camera_for` frames the union of the bounds of the leakage surface and the bodies
in one frame (the first one for an animation; context surfaces only on request), looking at the leakage
surface from the side of the bodies, 35 degrees off its mean normal, so that an animation does not jump.

The pictures are drawn off screen by ventsim's own renderer (:mod:`cases.results.raster`, NumPy and Pillow, no
OpenGL and no pyvista; see :mod:`cases.results.render_plotter`). GIFs are assembled with Pillow.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cases.results.output import atomic_path
from cases.results.render_plotter import FramePlotter
from cases.results.render_style import (BLOCKED_RGB, BLOCKED_TOLERANCE, HALF_BLOCKED_RGB, SILHOUETTE_RGB, UNBLOCKED_RGB,
                                       VIEW_ANGLE, fraction_rgb, title)
from cases.results.render_vtk import polygon_cells, write_vtk_series

__all__ = ["BLOCKED_RGB", "HALF_BLOCKED_RGB", "UNBLOCKED_RGB", "SILHOUETTE_RGB", "Frame", "blocked_colour_fraction", "camera_for",
           "fraction_rgb", "frame_image", "render_animation", "render_frame", "save_png", "title", "write_vtk_series"]

@dataclass(frozen=True)
class Frame:
    """One picture's worth of state (SI units), produced by the scene runner.

    Attributes
    ----------
    time : float
        [s]
    pressure : float
        Cavity pressure shown in the title [Pa].
    leak_vertices : (n, 3) float
        Leakage-surface nodes at this time [m].
    leak_faces : (m, 3) or (m, 4) int
        Faces; triangles in a 4-column array have ``-1`` in the last column.
    blocked_fraction : (m,) float
        ``A_eb / A_e`` per face, in [0, 1].
    active_nodes : (n,) bool
    gaps : (n,) float
        Gap per node [m], ``inf`` beyond the detection cutoff.
    bodies : tuple of ((k, 3) float, (l, 3) int)
        Blocking bodies at this time (drawn translucent).
    context : tuple of ((k, 3) float, (l, 3|4) int)
        Other surfaces drawn opaque light grey (e.g. the rest of the cushion).
    cpress : (n,) float or None
        Contact pressure per node [Pa] when the surface is a contact seat (written to the VTK series).
    contact_status : (n,) uint8 or None
        0 open, 1 closed, 2 VD (viscous damping within the damping clearance), with ``cpress``.
    label : str
        First line of an annotated picture's title (e.g. ``"airbag_impactor: exchange vent, cavity cushion"``).
    """

    time: float
    pressure: float
    leak_vertices: np.ndarray
    leak_faces: np.ndarray
    blocked_fraction: np.ndarray
    active_nodes: np.ndarray
    gaps: np.ndarray
    bodies: tuple
    context: tuple = ()
    cpress: object = None
    contact_status: object = None
    label: str = ""

    def __post_init__(self):
        n_faces, n_nodes = len(self.leak_faces), len(self.leak_vertices)
        shapes = {"leak_vertices": (np.asarray(self.leak_vertices).shape, (n_nodes, 3)),
                  "blocked_fraction": (np.shape(self.blocked_fraction), (n_faces,)),
                  "active_nodes": (np.shape(self.active_nodes), (n_nodes,)),
                  "gaps": (np.shape(self.gaps), (n_nodes,))}
        if self.cpress is not None:
            shapes.update(cpress=(np.shape(self.cpress), (n_nodes,)),
                          contact_status=(np.shape(self.contact_status), (n_nodes,)))
        for name, (got, want) in shapes.items():
            if got != want:
                raise ValueError(f"Frame.{name} must have shape {want}, got {got}")
        polygon_cells(self.leak_faces)  # validates the face array


def _face_normals(vertices, faces):
    """(m, 3) area vectors (twice the area along the normal) of triangles and quads (-1 padded)."""
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64).reshape(len(faces), -1)
    if not len(f):
        return np.zeros((0, 3))
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    tri = np.cross(b - a, c - a)
    if f.shape[1] == 3:
        return tri
    quad = f[:, 3] >= 0
    d = v[np.where(quad, f[:, 3], f[:, 0])]
    return np.where(quad[:, None], np.cross(c - a, d - b), tri)


def _view_normal(leak, faces, bodies):
    """Unit mean normal of the leakage surface turned towards the bodies' centroid; for a closed or
    degenerate surface the direction to the bodies, else +z."""
    normals = _face_normals(leak, faces)
    mean = normals.sum(axis=0)
    towards = np.concatenate(bodies).mean(axis=0) - leak.mean(axis=0) if bodies else np.zeros(3)
    if np.linalg.norm(mean) <= 1e-6 * np.linalg.norm(normals, axis=1).sum():
        mean = towards
    norm = np.linalg.norm(mean)
    if not norm > 0.0:
        return np.array([0.0, 0.0, 1.0])
    return -mean / norm if mean @ towards < 0.0 else mean / norm


def camera_for(frame, *, include_context=False, off_normal=35.0, around=30.0):
    """A pyvista camera position ``[position, focal point, view up]`` framing ``frame``.

    The focal point is the centre of the union of the bounds of the leakage surface and the bodies (and the
    context surfaces if ``include_context``: off by default, since a whole cushion would leave the vent a few
    pixels wide; context outside the view is clipped). The camera looks from ``off_normal`` degrees off the
    leakage surface's mean normal, turned to the side of the bodies and ``around`` degrees about the normal,
    from far enough that the bounding sphere fits the vertical view angle (:data:`VIEW_ANGLE`).

    >>> frame = Frame(0.0, 1e5, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.array([[0, 1, 2]]), np.zeros(1),
    ...               np.zeros(3, bool), np.zeros(3), ())
    >>> position, focal, up = camera_for(frame)
    >>> focal, bool(position[2] > 0), bool(up[2] > 0)
    ((0.5, 0.5, 0.0), True, True)
    """
    leak = np.asarray(frame.leak_vertices, dtype=np.float64)
    bodies = [np.asarray(v, dtype=np.float64).reshape(-1, 3) for v, _ in frame.bodies]
    context = [np.asarray(v, dtype=np.float64).reshape(-1, 3) for v, _ in frame.context] if include_context else []
    points = np.concatenate([leak.reshape(-1, 3)] + bodies + context)
    low, high = points.min(axis=0), points.max(axis=0)
    centre, radius = (low + high) / 2.0, max(np.linalg.norm(high - low) / 2.0, 1e-6)
    normal = _view_normal(leak, frame.leak_faces, bodies)
    e1 = np.cross(normal, np.eye(3)[np.argmin(np.abs(normal))])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(normal, e1)
    a, b = np.radians(off_normal), np.radians(around)
    direction = normal * np.cos(a) + (e1 * np.cos(b) + e2 * np.sin(b)) * np.sin(a)
    distance = 1.05 * radius / np.sin(np.radians(VIEW_ANGLE) / 2.0)
    up = np.array([0.0, 0.0, 1.0]) if abs(direction[2]) < 0.95 else np.array([0.0, 1.0, 0.0])
    up -= (up @ direction) * direction
    return [tuple(map(float, point)) for point in (centre + distance * direction, centre, up / np.linalg.norm(up))]


def frame_image(frame, *, window_size=(800, 600), camera=None, scalar_bar=False):
    """The picture of ``frame`` as an (height, width, 3) uint8 array (off screen).

    ``camera`` is a pyvista camera position (default :func:`camera_for` of this frame). ``scalar_bar`` adds the
    annotations (title, legend, scale bar) and the colour-bar strip (:mod:`cases.results.render_annotate`).
    """
    camera = camera if camera is not None else camera_for(frame)
    with FramePlotter(camera, window_size, annotated=scalar_bar) as plotter:
        return plotter.image(frame)


def save_png(image, path):
    """Write an (h, w, 3) uint8 picture to the PNG ``path`` atomically (fast zlib level: pictures compress well)."""
    from PIL import Image

    path = Path(path)
    with atomic_path(path) as tmp:
        Image.fromarray(image).save(tmp, format="PNG", compress_level=3)
    return path


def render_frame(frame, path, *, window_size=(800, 600), camera=None, scalar_bar=False):
    """Render ``frame`` off screen to the PNG ``path`` (written atomically) and return the path.

    Parameters
    ----------
    frame : Frame
    path : path-like
        PNG file; its folder is created if missing.
    window_size : (int, int)
        (width, height) in pixels.
    camera : pyvista camera position, optional
        ``[position, focal point, view up]``; default :func:`camera_for` of ``frame``. Pass the same camera
        for every time of a run so that the pictures line up.
    scalar_bar : bool
        Add the annotations and the colour-bar strip (it contains the blocked colour, so
        :func:`blocked_colour_fraction` sees it; :func:`cases.results.render_annotate.view_part` cuts it off).
    """
    return save_png(frame_image(frame, window_size=window_size, camera=camera, scalar_bar=scalar_bar), path)


def render_animation(frames, path, *, fps=10, window_size=(800, 600), camera=None, annotated=False):
    """Render ``frames`` off screen into the animated GIF ``path`` (Pillow, looping, written atomically).

    The camera is fixed for the whole animation: ``camera`` or :func:`camera_for` of the first frame.
    Consecutive identical pictures are merged by the GIF writer into one longer-lasting frame. One plotter draws
    every frame (:class:`cases.results.render_plotter.FramePlotter`); ``annotated`` adds the title, scale bar and colour
    bar to each.
    """
    from PIL import Image

    frames = list(frames)
    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise ValueError(f"{path}: only .gif animations are supported (Pillow); MP4 would need imageio-ffmpeg")
    if not frames:
        raise ValueError("render_animation needs at least one frame")
    camera = camera if camera is not None else camera_for(frames[0])
    with FramePlotter(camera, window_size, annotated=annotated) as plotter:
        # quantized at once to a 256-colour palette (1 byte a pixel) to keep a long run's frames small
        pictures = [Image.fromarray(plotter.image(frame)).quantize(256, method=Image.Quantize.FASTOCTREE,
                                                                   dither=Image.Dither.NONE) for frame in frames]
    with atomic_path(path) as tmp:
        pictures[0].save(tmp, format="GIF", save_all=True, append_images=pictures[1:],
                         duration=max(round(1000.0 / fps), 20), loop=0)
    return path


def blocked_colour_fraction(image, *, rgb=BLOCKED_RGB, tolerance=BLOCKED_TOLERANCE):
    """Fraction of the pixels within ``tolerance`` (Euclidean, 0-255 scale) of the fully-blocked colour.

    Parameters
    ----------
    image : path-like or (h, w, 3|4) uint8 array
        A PNG written by :func:`render_frame` (for a GIF file, its first frame).
    rgb : (3,) int
        Reference colour, default :data:`BLOCKED_RGB`.
    tolerance : float
        Default :data:`BLOCKED_TOLERANCE`.

    >>> blocked_colour_fraction(np.array([[BLOCKED_RGB, UNBLOCKED_RGB]], dtype=np.uint8))
    0.5
    """
    if not isinstance(image, np.ndarray):
        from PIL import Image

        with Image.open(image) as picture:
            image = np.asarray(picture.convert("RGB"))
    pixels = np.asarray(image)[..., :3].reshape(-1, 3).astype(np.float64)
    if not len(pixels):
        return 0.0
    distance = np.linalg.norm(pixels - np.asarray(rgb, dtype=np.float64), axis=1)
    return float(np.mean(distance <= tolerance))
