"""Which side of a blocking surface a point lies on: penetration counts as contact.

A leakage node inside a closed blocking body, or behind the interior of an open blocking sheet, is in contact
whatever its distance to the surface. The side is decided at the closest point with the *angle-weighted
pseudonormal* of the feature that holds it (Bærentzen & Aanæs, "Signed distance computation using the angle
weighted pseudonormal", IEEE TVCG 11(3), 2005): the face normal when the closest point is inside a face, the sum
of the two face normals on an edge, the angle-weighted sum of the incident face normals at a vertex. For a closed
manifold mesh, ``(p − c)·n < 0`` holds exactly when p is inside. For an open mesh, a closest point on a boundary
edge or boundary vertex is never "behind" (the point is beside the sheet, not behind it).

>>> import trimesh
>>> box = trimesh.creation.box(extents=(2.0, 2.0, 2.0))
>>> sides = Sides(box.vertices, box.faces)
>>> sides.closed
True
>>> import blockage
>>> pts = np.array([[0.0, 0.0, 0.5], [0.0, 0.0, 1.5], [0.99, 0.99, 0.99]])
>>> prox = blockage.Blocker(box).distances(pts)
>>> sides.behind(pts, prox.closest_points, prox.faces).tolist()
[True, False, True]
"""

import numpy as np

__all__ = ["Sides"]

#: Barycentric coordinate below which a closest point is taken to lie on an edge or a vertex [-].
ON_FEATURE = 1e-9


def _face_normals(vertices, faces):
    tri = vertices[faces]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(n, axis=1)
    return n / np.where(length > 0, length, 1.0)[:, None]


def _corner_angles(vertices, faces):
    """(m, 3) interior angle of each face at each of its corners [rad]."""
    tri = vertices[faces]
    out = np.zeros(faces.shape, dtype=float)
    for k in range(3):
        u = tri[:, (k + 1) % 3] - tri[:, k]
        v = tri[:, (k + 2) % 3] - tri[:, k]
        cos = np.einsum("ij,ij->i", u, v) / np.maximum(np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1), 1e-300)
        out[:, k] = np.arccos(np.clip(cos, -1.0, 1.0))
    return out


class Sides:
    """Pseudonormals of a triangle mesh, for the inside/behind test of points at their closest points.

    Parameters
    ----------
    vertices : (n, 3) float
        [m]
    faces : (m, 3) int

    Attributes
    ----------
    closed : bool
        Every edge has exactly two faces (then ``behind`` means inside).
    """

    def __init__(self, vertices, faces):
        vertices = np.asarray(vertices, dtype=float)
        faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
        self.faces = faces
        edges = np.sort(faces[:, [[0, 1], [1, 2], [2, 0]]].reshape(-1, 2), axis=1)  # edge k of face f: row 3f+k
        unique, inverse, counts = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
        self._edge_of = inverse.ravel()
        self._n_edges = len(unique)
        self.edge_boundary = (counts[self._edge_of] == 1).reshape(-1, 3)
        self.closed = bool(len(faces)) and bool(np.all(counts == 2))
        boundary_vertex = np.zeros(len(vertices), dtype=bool)
        boundary_vertex[unique[counts == 1].ravel()] = True
        self.vertex_boundary = boundary_vertex
        self._reference = vertices
        self._normals = self.normals(vertices)

    def normals(self, vertices) -> tuple:
        """(face (m, 3), edge (m, 3 edges, 3), vertex (n, 3)) pseudonormals of the mesh at ``vertices``."""
        vertices = np.asarray(vertices, dtype=float)
        face = _face_normals(vertices, self.faces)
        summed = np.zeros((self._n_edges, 3))
        np.add.at(summed, self._edge_of, np.repeat(face, 3, axis=0))
        edge = summed[self._edge_of].reshape(-1, 3, 3)
        vertex = np.zeros((len(vertices), 3))
        angles = _corner_angles(vertices, self.faces)
        for k in range(3):
            np.add.at(vertex, self.faces[:, k], angles[:, k, None] * face)
        return face, edge, vertex

    def behind(self, points, closest, faces, vertices=None) -> np.ndarray:
        """(k,) bool: the points lie behind the surface at their closest points (inside, for a closed mesh).

        Parameters
        ----------
        points, closest : (k, 3) float
            Query points and their closest points on the mesh [m], in the mesh's frame.
        faces : (k,) int
            Face holding each closest point (-1: none found, never behind).
        vertices : (n, 3) float, optional
            Current vertex positions when the mesh has deformed since construction (same frame as the points).
        """
        faces = np.asarray(faces, dtype=np.int64)
        out = np.zeros(len(faces), dtype=bool)
        ok = np.flatnonzero(faces >= 0)
        if not ok.size:
            return out
        face_n, edge_n, vertex_n = self._normals if vertices is None else self.normals(vertices)
        verts = self._vertices_or(vertices)
        f = faces[ok]
        near = np.asarray(closest, dtype=float)[ok]
        small = _barycentric(verts[self.faces[f]], near) < ON_FEATURE
        normal = face_n[f].copy()
        beside = np.zeros(len(f), dtype=bool)
        on_edge = np.flatnonzero(small.sum(axis=1) == 1)
        if on_edge.size:  # barycentric k ~ 0: the edge opposite corner k, which is edge (k + 1) % 3
            k = (np.argmax(small[on_edge], axis=1) + 1) % 3
            normal[on_edge] = edge_n[f[on_edge], k]
            beside[on_edge] = self.edge_boundary[f[on_edge], k]
        at_vertex = np.flatnonzero(small.sum(axis=1) >= 2)
        if at_vertex.size:
            v = self.faces[f[at_vertex], np.argmax(~small[at_vertex], axis=1)]
            normal[at_vertex] = vertex_n[v]
            beside[at_vertex] = self.vertex_boundary[v]
        offset = np.asarray(points, dtype=float)[ok] - near
        out[ok] = (np.einsum("ij,ij->i", offset, normal) < 0.0) & ~beside
        return out

    def _vertices_or(self, vertices):
        return self._reference if vertices is None else np.asarray(vertices, dtype=float)


def _barycentric(tri, p):
    """(k, 3) barycentric coordinates of points p on triangles tri (k, 3, 3)."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    v0, v1, v2 = b - a, c - a, p - a
    d00 = np.einsum("ij,ij->i", v0, v0)
    d01 = np.einsum("ij,ij->i", v0, v1)
    d11 = np.einsum("ij,ij->i", v1, v1)
    d20 = np.einsum("ij,ij->i", v2, v0)
    d21 = np.einsum("ij,ij->i", v2, v1)
    den = d00 * d11 - d01 * d01
    den = np.where(np.abs(den) > 0, den, 1.0)
    v = (d11 * d20 - d01 * d21) / den
    w = (d00 * d21 - d01 * d20) / den
    return np.stack([1.0 - v - w, v, w], axis=1)


def sides_of(blocker) -> Sides:
    """The :class:`Sides` of a :class:`blockage.Blocker` (topology built once; normals follow a refit)."""
    cached = getattr(blocker, "_sides", None)
    if cached is None or len(cached.faces) != len(blocker.faces):
        cached = Sides(blocker.vertices, blocker.faces)
        blocker._sides = cached
    if cached._reference is not blocker.vertices:
        cached._reference = blocker.vertices
        cached._normals = cached.normals(blocker.vertices)
    return cached


def penetrating(blocker, points, transform=None, open_depth=0.0) -> np.ndarray:
    """(n,) bool: points inside a closed blocker, or behind the interior of an open one within ``open_depth``.

    Only points inside the blocker's bounding box (grown by ``open_depth`` for an open blocker) are tested;
    their closest point is searched without a cutoff. An open sheet's back side counts only up to
    ``open_depth`` [m] (default 0: never), as its orientation is often arbitrary.

    Parameters
    ----------
    blocker : blockage.Blocker
    points : (n, 3) float
        [m], world frame.
    transform : (4, 4) float, optional
        Rigid placement of the blocker.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    local = points if transform is None else (points - transform[:3, 3]) @ transform[:3, :3]
    return signed_distances(blocker, local, 0.0, open_depth) < 0.0


def signed_distances(blocker, points, cutoff=np.inf, open_depth=0.0) -> np.ndarray:
    """(n,) signed distance [m] from points (the blocker's frame) to a blocker, capped at ``cutoff`` outside.

    Negative inside a closed blocker (minus the exact depth), or behind the interior of an open blocker within
    ``open_depth``; positive otherwise, exact up to ``cutoff`` and equal to it beyond. The signed distance is
    1-Lipschitz in the point for a closed blocker (so is its cap).

    >>> import trimesh, blockage
    >>> cube = blockage.Blocker(trimesh.creation.box(extents=(2.0, 2.0, 2.0)))
    >>> signed_distances(cube, [[0.0, 0.0, 0.5], [0.0, 0.0, 1.25], [0.0, 0.0, 9.0]], cutoff=1.0).tolist()
    [-0.5, 0.25, 1.0]
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    out = np.full(len(points), float(cutoff))
    if not len(blocker.faces) or not len(points):
        return out
    found = blocker.distances(points, cutoff=cutoff)
    near = np.flatnonzero(np.isfinite(found.distances))
    out[near] = found.distances[near]
    lo, hi = blocker.vertices.min(axis=0), blocker.vertices.max(axis=0)
    reach = 1e-9 * float(np.max(hi - lo)) + float(open_depth)
    if not near.size and not np.any(np.all((points >= lo - reach) & (points <= hi + reach), axis=1)):
        return out  # nothing near nor inside: the sides are not needed (their normals cost O(faces))
    sides = sides_of(blocker)
    depth = np.inf if sides.closed else float(open_depth)
    if not depth > 0.0:
        return out
    if near.size:  # the closest point is known: the side test needs nothing more
        behind = sides.behind(points[near], found.closest_points[near], found.faces[near])
        out[near[behind & (found.distances[near] <= depth)]] *= -1.0
    pad = 1e-9 * float(np.max(hi - lo)) + (0.0 if sides.closed else depth)
    far = np.flatnonzero(~np.isfinite(found.distances) & np.all((points >= lo - pad) & (points <= hi + pad), axis=1))
    if far.size and depth > cutoff:  # beyond the cutoff but inside the box: search without it
        full = blocker.distances(points[far], cutoff=depth)
        behind = sides.behind(points[far], full.closest_points, full.faces)
        out[far[behind]] = -full.distances[behind]
    return out
