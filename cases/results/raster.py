"""A small software renderer for ventsim's pictures: NumPy and Pillow, no OpenGL.

The pictures hold a few thousand flat faces (a vent panel, a body, a cushion), so a painter's algorithm is enough:
faces are drawn far to near by the depth of their centroid into an *id buffer* (a 32-bit Pillow image whose pixel
is the index of the face that covers it), the colours are looked up from the ids, and each pixel's depth is the
exact depth of its face's plane along the pixel's ray. Translucent surfaces (bodies, the cavity in the whole-scene
view) have their own id buffer of front faces and are blended, one layer each, over the opaque picture where they
lie in front of it.

The camera is VTK's pinhole model (what pyvista and ParaView use): ``[position, focal point, view up]`` and a
vertical view angle [deg]; a world point ``p`` at depth ``d = (p - position) . forward`` lands at

.. math::

    x = \\frac{W}{2}\\left(1 + \\frac{(p - c) \\cdot r}{d \\tan(\\alpha/2) W/H}\\right), \\qquad
    y = \\frac{H}{2}\\left(1 - \\frac{(p - c) \\cdot u}{d \\tan(\\alpha/2)}\\right)

(pixels, x right, y down; ``r``, ``u`` the camera's right and true up). ``tests/test_picture_outline.py`` checks
this against VTK's own world-to-display transform.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

__all__ = ["Camera", "edge_topology", "face_ids", "face_normals", "plane_depth", "silhouette_edges", "triangles_of"]


class Camera:
    """A pinhole camera for a ``(width, height)`` picture [px]: projection of points and the rays of pixels.

    Parameters
    ----------
    position : camera position ``[position, focal point, view up]`` (pyvista's form) [m]
    view_angle : float
        Vertical view angle [deg].
    size : (int, int)
        (width, height) [px].
    """

    def __init__(self, position, view_angle: float, size):
        eye, focal, up = (np.asarray(v, dtype=np.float64) for v in position)
        forward = (focal - eye) / np.linalg.norm(focal - eye)
        right = np.cross(forward, up)
        right /= np.linalg.norm(right)
        self.eye, self.forward, self.right, self.up = eye, forward, right, np.cross(right, forward)
        self.width, self.height = int(size[0]), int(size[1])
        self.half = np.tan(np.radians(view_angle) / 2.0)

    def project(self, points) -> np.ndarray:
        """(n, 3) array: pixel x (right), pixel y (down) and depth [m] along the view of world ``points (n, 3)``."""
        v = np.asarray(points, dtype=np.float64).reshape(-1, 3) - self.eye
        depth = v @ self.forward
        safe = np.where(depth > 0.0, depth, np.nan)
        x = (v @ self.right) / (safe * self.half * self.width / self.height)
        y = (v @ self.up) / (safe * self.half)
        return np.column_stack([(x + 1.0) / 2.0 * self.width, (1.0 - y) / 2.0 * self.height, depth])

    def rays(self) -> np.ndarray:
        """(h, w, 3) direction of each pixel centre's ray, scaled so that its component along the view is 1."""
        xs = ((np.arange(self.width) + 0.5) / self.width * 2.0 - 1.0) * self.half * self.width / self.height
        ys = (1.0 - (np.arange(self.height) + 0.5) / self.height * 2.0) * self.half
        return (self.forward + xs[None, :, None] * self.right + ys[:, None, None] * self.up).astype(np.float64)


def triangles_of(faces) -> tuple[np.ndarray, np.ndarray]:
    """(m, 3|4) faces, -1 padded, as (corner indices (m, 4), valid (m, 4) bool): a triangle repeats no corner."""
    f = np.asarray(faces, dtype=np.int64)
    f = f if f.ndim == 2 else f.reshape(len(f), -1)
    if f.shape[1] == 3:
        f = np.column_stack([f, np.full(len(f), -1)])
    return f, f >= 0


def face_normals(vertices, faces) -> np.ndarray:
    """(m, 3) unit normals (right-hand rule on the corner order) of triangles and quads (-1 padded)."""
    v = np.asarray(vertices, dtype=np.float64)
    f, valid = triangles_of(faces)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    d = v[np.where(valid[:, 3], f[:, 3], f[:, 0])]
    n = np.where(valid[:, 3:], np.cross(c - a, d - b), np.cross(b - a, c - a))
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0.0, length, 1.0)


def face_ids(shape, corners, valid, order, first_id: int = 1) -> np.ndarray:
    """The id buffer (h, w) int32 of faces drawn in ``order`` (far to near): 0 where no face, else
    ``first_id + face index``.

    ``corners`` (m, 4, 2) are the projected corners [px] (a triangle's 4th is ignored where ``valid`` is False).
    """
    from PIL import Image, ImageDraw

    height, width = shape
    image = Image.new("I", (width, height), 0)
    draw = ImageDraw.Draw(image)
    flat = (np.asarray(corners, dtype=np.float64) - 0.5).reshape(len(corners), 8)  # Pillow centres pixels on integers
    quads = valid[:, 3].tolist()
    core = getattr(draw, "draw", None)  # Pillow's C drawing object: an "I" image's ink is the integer itself
    if core is not None and hasattr(core, "draw_polygon") and core.draw_ink(first_id + 7) == first_id + 7:
        polygon = core.draw_polygon  # takes the corners as a buffer of float32 (x, y) pairs
        for k, xy in zip(order.tolist(), flat[order].astype(np.float32)):
            polygon(xy if quads[k] else xy[:6], first_id + k, 1)
    else:
        for k, xy in zip(order.tolist(), flat[order].tolist()):
            draw.polygon(xy if quads[k] else xy[:6], fill=first_id + k)
    return np.asarray(image, dtype=np.int32)


def plane_depth(ids, rays, eye, points, normals, fallback) -> np.ndarray:
    """(h, w) depth [m] along the view of each pixel's face plane (``inf`` where ``ids`` is 0).

    Face ``k`` (id ``k + 1``) passes through ``points[k]`` with unit normal ``normals[k]``; a pixel's ray
    ``eye + t ray`` meets it at ``t = n . (p - eye) / (n . ray)``, and ``t`` is the depth because the ray's
    component along the view is 1. Faces seen edge-on take their ``fallback`` depth (centroid).
    """
    depth = np.full(ids.shape, np.inf)
    hit = ids > 0
    k = ids[hit] - 1
    n = normals[k]
    along = np.einsum("ij,ij->i", n, rays[hit])
    t = np.einsum("ij,ij->i", n, points[k] - eye) / np.where(np.abs(along) > 1e-9, along, 1.0)
    depth[hit] = np.where(np.abs(along) > 1e-9, t, fallback[k])
    return depth


def silhouette_edges(faces, front) -> np.ndarray:
    """(e, 2) vertex pairs of the edges between a front and a back face, and of edges with one face only.

    ``front`` (m,) bool: faces turned to the camera. (VTK's ``vtkPolyDataSilhouette`` without feature angles.)

    >>> silhouette_edges(np.array([[0, 1, 2], [0, 2, 3]]), np.array([True, False])).tolist()
    [[0, 1], [0, 2], [0, 3], [1, 2], [2, 3]]
    """
    f = np.ascontiguousarray(np.asarray(faces, dtype=np.int64).reshape(len(faces), -1))
    unique, inverse, owner = edge_topology(f.tobytes(), f.shape[1])
    counts = np.bincount(inverse, minlength=len(unique))
    fronts = np.bincount(inverse, weights=np.asarray(front)[owner].astype(np.float64), minlength=len(unique))
    return unique[(counts == 1) | ((fronts > 0) & (fronts < counts))]


@lru_cache(maxsize=16)
def edge_topology(data: bytes, corners: int):
    """(unique edges (e, 2), edge of each face side (s,), face of each side (s,)) of -1 padded faces."""
    f, valid = triangles_of(np.frombuffer(data, dtype=np.int64).reshape(-1, corners))
    quad = valid[:, 3]
    last = np.where(quad, f[:, 3], f[:, 0])  # a triangle's third edge closes on its first corner
    edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], np.column_stack([f[:, 2], last]),
                            np.column_stack([f[quad, 3], f[quad, 0]])])
    owner = np.concatenate([np.tile(np.arange(len(f)), 3), np.flatnonzero(quad)])
    low, high = edges.min(axis=1), edges.max(axis=1)
    span = int(high.max()) + 1 if len(edges) else 1
    keys, inverse = np.unique(low * span + high, return_inverse=True)  # one integer a vertex pair: a 1-D unique
    return np.column_stack([keys // span, keys % span]), inverse.ravel(), owner
