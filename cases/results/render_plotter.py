"""One off-screen plotter reused for every picture of a run, drawn by ventsim's own software renderer.

:mod:`cases.results.raster` draws the faces (NumPy and Pillow, no OpenGL): the leakage surface opaque with one flat
colour per face and its edges, the active nodes as dots, the context surfaces (the cavity) and the bodies translucent
(a closed one by its front faces only), lit by a head light, and the bodies' silhouettes opaque and antialiased where no
opaque face hides them. The camera's pixel rays (per plotter) and the meshes' edge tables (per process) are kept
between pictures, so a picture costs the drawing of its faces alone.
"""
from __future__ import annotations

import numpy as np

from cases.results.raster import (Camera, edge_topology, face_ids, face_normals, plane_depth, silhouette_edges,
                                  triangles_of)
from cases.results.render_annotate import annotate
from cases.results.render_style import (ACTIVE_NODE_RGB, BACKGROUND_RGB, BODY_OPACITY, BODY_RGB, CONTEXT_RGB,
                                        EDGE_RGB, LEGEND, SILHOUETTE_RGB, SILHOUETTE_WIDTH, VIEW_ANGLE, fraction_rgb,
                                        title)

__all__ = ["FramePlotter", "closed", "edge_pixels", "picture"]

AMBIENT = 0.45
"""Share of a lit surface's colour that does not depend on the light (the rest goes with the cosine between the
face's normal and the view: a head light)."""


def closed(faces) -> bool:
    """True when every edge of the faces is shared by exactly two faces (a closed body: cull its back)."""
    cells = np.asarray(faces, dtype=np.int64)
    if cells.ndim != 2 or not len(cells) or (cells < 0).any():
        return False
    _, inverse, _ = edge_topology(np.ascontiguousarray(cells).tobytes(), cells.shape[1])
    return bool((np.bincount(inverse) == 2).all())


def edge_pixels(frame, camera, window_size) -> float:
    """Median leakage-surface edge length projected at the focal distance [px]."""
    vertices = np.asarray(frame.leak_vertices, dtype=np.float64)
    faces = np.asarray(frame.leak_faces, dtype=np.int64)
    if not len(faces):
        return 0.0
    edge = np.median(np.linalg.norm(vertices[faces[:, 1]] - vertices[faces[:, 0]], axis=1))
    distance = np.linalg.norm(np.subtract(camera[0], camera[1]))
    return float(edge / (2.0 * distance * np.tan(np.radians(VIEW_ANGLE) / 2.0)) * window_size[1])


def _layer(cam, rays, parts):
    """Draw ``parts`` [(vertices, faces, rgb (3,) or (m, 3), lit, cull back faces)] far to near: (ids (h, w),
    colours (faces + 1, 3) float with the background first, depth (h, w) [m], normals, facing (m,) float)."""
    vertices, faces, colours, lit, cull, offset = [], [], [], [], [], 0
    for v, f, rgb, shaded, back in parts:
        v = np.asarray(v, dtype=np.float64).reshape(-1, 3)
        f, valid = triangles_of(f)
        faces.append(np.where(valid, f + offset, -1))
        vertices.append(v)
        colours.append(np.broadcast_to(np.asarray(rgb, dtype=np.float64), (len(f), 3)))
        lit.append(np.full(len(f), shaded))
        cull.append(np.full(len(f), back))
        offset += len(v)
    v, f = np.concatenate(vertices), np.concatenate(faces)
    valid = f >= 0
    corners = np.where(valid, f, f[:, :1])
    normals = face_normals(v, f)
    projected = cam.project(v)
    centroid = (v[corners] * valid[..., None]).sum(axis=1) / valid.sum(axis=1, keepdims=True)
    to_eye = cam.eye - centroid
    facing = np.einsum("ij,ij->i", normals, to_eye) / np.linalg.norm(to_eye, axis=1)
    shade = np.where(np.concatenate(lit), AMBIENT + (1.0 - AMBIENT) * np.abs(facing), 1.0)
    depth = (centroid - cam.eye) @ cam.forward
    keep = (projected[corners, 2] > 0.0).all(axis=1) & ~(np.concatenate(cull) & (facing <= 0.0))
    order = np.flatnonzero(keep)
    order = order[np.argsort(-depth[order], kind="stable")]
    ids = face_ids((cam.height, cam.width), projected[corners, :2], valid, order)
    table = np.vstack([np.asarray(BACKGROUND_RGB, dtype=np.float64), np.concatenate(colours) * shade[:, None]])
    return ids, table, plane_depth(ids, rays, cam.eye, v[f[:, 0]], normals, depth), normals, facing


def _edges(view, ids, n_leak) -> None:
    """Paint in :data:`EDGE_RGB` the pixels where the face changes, next to a leakage face (ids 1..n_leak)."""
    leak = (ids >= 1) & (ids <= n_leak)
    edge = np.zeros(ids.shape, dtype=bool)
    edge[:, 1:] |= (ids[:, 1:] != ids[:, :-1]) & (leak[:, 1:] | leak[:, :-1])
    edge[1:, :] |= (ids[1:, :] != ids[:-1, :]) & (leak[1:, :] | leak[:-1, :])
    view[edge] = EDGE_RGB


def _visible(cam, depth, points, tolerance):
    """(projected (n, 3), visible (n,) bool): points in the view and not behind the opaque surfaces."""
    p = cam.project(points)
    inside = (p[:, 0] >= 0) & (p[:, 0] < cam.width) & (p[:, 1] >= 0) & (p[:, 1] < cam.height) & (p[:, 2] > 0)
    x = np.clip(np.nan_to_num(p[:, 0]), 0, cam.width - 1).astype(np.int64)
    y = np.clip(np.nan_to_num(p[:, 1]), 0, cam.height - 1).astype(np.int64)
    return p, inside & (p[:, 2] <= depth[y, x] + tolerance)


def _dots(image, cam, depth, frame, diameter: float, tolerance: float) -> None:
    """The active nodes as discs of ``diameter`` [px] where the opaque surfaces do not hide them."""
    from PIL import ImageDraw

    active = np.asarray(frame.active_nodes, dtype=bool)
    if not active.any():
        return
    p, visible = _visible(cam, depth, np.asarray(frame.leak_vertices, dtype=np.float64)[active], tolerance)
    draw, r = ImageDraw.Draw(image), diameter / 2.0
    for x, y in p[visible, :2].tolist():
        draw.ellipse([x - 0.5 - r, y - 0.5 - r, x - 0.5 + r, y - 0.5 + r], fill=ACTIVE_NODE_RGB)


OUTLINE_SAMPLES = 3
"""The outline is drawn on a grid this many times finer per side and averaged down (antialiased)."""


def _outline(mask, cam, depth, vertices, faces, facing, width: float, tolerance: float, origin) -> None:
    """Draw the silhouette of one body (:func:`cases.results.raster.silhouette_edges`), ``width`` px wide, into
    ``mask`` (a Pillow "L" image of the picture's box from pixel ``origin`` (x, y), :data:`OUTLINE_SAMPLES` times
    finer) where the opaque surfaces do not hide the edge's middle."""
    from PIL import ImageDraw

    edges = silhouette_edges(faces, facing > 0.0)
    if not len(edges):
        return
    v = np.asarray(vertices, dtype=np.float64)
    _, visible = _visible(cam, depth, (v[edges[:, 0]] + v[edges[:, 1]]) / 2.0, tolerance)
    ends = (cam.project(v)[:, :2] - origin) * OUTLINE_SAMPLES - 0.5
    draw, w = ImageDraw.Draw(mask), max(int(round(width * OUTLINE_SAMPLES)), 1)
    r = w / 2.0
    for a, b in edges[visible].tolist():
        (x0, y0), (x1, y1) = ends[a], ends[b]
        draw.line([(x0, y0), (x1, y1)], fill=255, width=w)
        draw.ellipse([x1 - r, y1 - r, x1 + r, y1 + r], fill=255)  # round joints


def _outlines(view, cam, depth, bodies, facing, width: float, tolerance: float) -> None:
    """Blend the bodies' outlines (antialiased, ``width`` px) into ``view``, drawn on a finer grid over the box
    of the bodies' projections only."""
    from PIL import Image

    corners = cam.project(np.concatenate([np.asarray(v, dtype=np.float64).reshape(-1, 3) for v, *_ in bodies]))
    low = np.clip(np.floor(np.nanmin(corners[:, :2], axis=0) - width - 1), 0, [cam.width, cam.height]).astype(int)
    high = np.clip(np.ceil(np.nanmax(corners[:, :2], axis=0) + width + 1), 0, [cam.width, cam.height]).astype(int)
    if (high <= low).any():
        return
    mask = Image.new("L", tuple((high - low) * OUTLINE_SAMPLES), 0)
    start = 0
    for v, f, *_ in bodies:
        _outline(mask, cam, depth, v, f, facing[start:start + len(f)], width, tolerance, low)
        start += len(f)
    cover = np.asarray(mask.reduce(OUTLINE_SAMPLES), dtype=np.float64)[..., None] / 255.0
    box = view[low[1]:high[1], low[0]:high[0]]
    box[...] = box * (1.0 - cover) + np.asarray(SILHOUETTE_RGB, dtype=np.float64) * cover


def _blend(view, depth, layers, tolerance) -> None:
    """Blend translucent ``layers`` [((ids, colours, depth, ...), opacity)] over ``view`` where they are in front
    of the opaque surfaces; two layers: the farther first at each pixel (more: in their order)."""
    if not layers:
        return
    depths = [np.where(d < depth - tolerance, d, np.inf) for (_, _, d, *_), _ in layers]
    if len(layers) == 2:  # the farther of the two first where both are in front
        near = depths[1] <= depths[0]
        passes = [(0, near), (1, np.ones(depth.shape, bool)), (0, ~near)]
    else:
        passes = [(index, np.ones(depth.shape, bool)) for index in range(len(layers))]
    for index, where in passes:
        (ids, table, *_), alpha = layers[index]
        mask = where & np.isfinite(depths[index])
        view[mask] = view[mask] * (1.0 - alpha) + table[ids[mask]] * alpha


def picture(frame, camera, window_size, context_opacity=1.0, rays=None) -> np.ndarray:
    """The 3-D view of ``frame`` from ``camera`` (pyvista camera position) as (h, w, 3) uint8, without annotations.

    ``rays``: :meth:`cases.results.raster.Camera.rays` of this camera and size, when the caller keeps them.
    """
    from PIL import Image

    cam = Camera(camera, VIEW_ANGLE, window_size)
    rays = cam.rays() if rays is None else rays
    distance = float(np.linalg.norm(np.subtract(camera[0], camera[1])))
    tolerance, pixel = 1e-4 * distance, 2.0 * distance * cam.half / cam.height  # [m], [m] a pixel at the focus
    opaque = [(frame.leak_vertices, frame.leak_faces, fraction_rgb(frame.blocked_fraction), False, False)]
    context = [(v, f, CONTEXT_RGB, True, context_opacity < 1.0 and closed(f)) for v, f in frame.context]
    bodies = [(v, f, BODY_RGB, True, closed(f)) for v, f in frame.bodies]
    if context_opacity >= 1.0:
        opaque, context = opaque + context, []
    ids, table, depth, *_ = _layer(cam, rays, opaque)
    view = table[ids]
    pixels = edge_pixels(frame, camera, window_size)
    if pixels >= 8.0:
        _edges(view, ids, len(frame.leak_faces))
    image = Image.fromarray(view.astype(np.uint8))
    diameter = float(np.clip(pixels / 3.0, 3.0, 10.0))
    _dots(image, cam, depth, frame, diameter, 2.0 * diameter * pixel)
    view = np.asarray(image, dtype=np.float64)
    layers = [(_layer(cam, rays, parts), alpha) for parts, alpha in ((context, context_opacity), (bodies, BODY_OPACITY))
              if parts]
    _blend(view, depth, layers, tolerance)
    if bodies:
        _outlines(view, cam, depth, bodies, layers[-1][0][4], max(SILHOUETTE_WIDTH * cam.height / 600.0, 2.0),
                  3.0 * pixel)
    return np.rint(view).astype(np.uint8)


class FramePlotter:
    """Pictures of frames of one scene from one camera: ``image(frame) -> (h, w, 3) uint8``.

    Parameters
    ----------
    camera : pyvista camera position
        ``[position, focal point, view up]``, fixed for every picture.
    window_size : (int, int)
        (width, height) of the 3-D view [px].
    annotated : bool
        Add the title, legend, scale bar and the colour-bar strip (:mod:`cases.results.render_annotate`); the picture is
        then wider by :data:`cases.results.render_annotate.COLOUR_BAR_WIDTH`.
    context_opacity : float
        Opacity of the frames' context surfaces (1: opaque light grey; the whole-scene view makes the cavity
        translucent).
    """

    def __init__(self, camera, window_size=(800, 600), *, annotated=False, context_opacity=1.0):
        self.camera, self.window_size, self.annotated = camera, tuple(window_size), annotated
        self.context_opacity = context_opacity
        self._rays = (None, None)

    def image(self, frame, camera=None, context_opacity=None) -> np.ndarray:
        """The picture of ``frame`` as (h, w, 3) uint8 (``camera``, ``context_opacity``: change them from now on)."""
        if context_opacity is not None:
            self.context_opacity = context_opacity
        self.camera = camera if camera is not None else self.camera
        key = tuple(tuple(map(float, point)) for point in self.camera)
        if self._rays[0] != key:
            self._rays = (key, Camera(self.camera, VIEW_ANGLE, self.window_size).rays())
        view = picture(frame, self.camera, self.window_size, self.context_opacity, self._rays[1])
        if not self.annotated:
            return view
        return annotate(view, title(frame), LEGEND, self.camera, VIEW_ANGLE, fraction_rgb)

    def close(self) -> None:
        self._rays = (None, None)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
