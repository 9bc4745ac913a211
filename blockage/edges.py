"""Edges: the edges of a leakage surface and the feature edges of a blocking surface.

Edge-to-edge contact (an option of :func:`blockage.evaluate`) makes both nodes of a
leakage-surface edge active when the edge lies within the contact tolerance of a
*feature edge* of a blocking surface: a boundary edge (one face), a non-manifold
edge (three or more faces) or a sharp edge (two faces whose normals differ by more
than ``TOL.feature_angle_deg``). This catches a thin bar lying across a vent between
its nodes, which node-to-face contact misses.

>>> import numpy as np
>>> surface_edges(np.array([[0, 1, 2, 3]]), np.array([4])).tolist()
[[0, 1], [0, 3], [1, 2], [2, 3]]
>>> square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
>>> feature_edges(square, np.array([[0, 1, 2], [0, 2, 3]])).tolist()
[[0, 1], [0, 3], [1, 2], [2, 3]]
"""

import numpy as np

from blockage.tolerance import TOL

__all__ = ["edge_active_nodes", "feature_edges", "surface_edges"]


def surface_edges(faces, face_sizes):
    """Unique undirected edges of polygons (triangles and quads).

    Parameters
    ----------
    faces : (m, k) int
        Vertex ids, padded with -1 past ``face_sizes`` (k = 3 or 4).
    face_sizes : (m,) int
        Number of vertices of each face (3 or 4).

    Returns
    -------
    edges : (e, 2) int
        Sorted vertex pairs ``i < j``, lexicographically sorted rows.
    """
    faces = np.asarray(faces, dtype=np.int64)
    sizes = np.asarray(face_sizes, dtype=np.int64)
    k = faces.shape[1]
    pairs = []
    for corner in range(k):
        nxt = (corner + 1) % k
        # the closing edge of a triangle stored in a quad row goes from vertex 2 to 0
        has = sizes > corner
        end = np.where(sizes == corner + 1, faces[:, 0], faces[:, nxt]) if k > 3 else faces[:, nxt]
        pairs.append(np.stack([faces[has, corner], end[has]], axis=1))
    edges = np.sort(np.concatenate(pairs), axis=1) if pairs else np.zeros((0, 2), np.int64)
    return np.unique(edges, axis=0).reshape(-1, 2)


def feature_edges(vertices, faces, angle_deg=None):
    """Boundary, non-manifold and sharp edges of a triangle mesh.

    Parameters
    ----------
    vertices : (n, 3) float
        Vertex positions [m].
    faces : (m, 3) int
        Triangles.
    angle_deg : float, optional
        Feature angle [deg] between adjacent face normals (default
        ``TOL.feature_angle_deg``).

    Returns
    -------
    edges : (e, 2) int
        Sorted vertex pairs, lexicographically sorted rows.
    """
    angle_deg = TOL.feature_angle_deg if angle_deg is None else angle_deg
    faces = np.asarray(faces, dtype=np.int64)
    if len(faces) == 0:
        return np.zeros((0, 2), np.int64)
    tri = np.asarray(vertices, dtype=np.float64)[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normals, axis=1)
    normals = np.divide(normals, length[:, None], out=np.zeros_like(normals), where=length[:, None] > 0)
    edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    owner = np.repeat(np.arange(len(faces)), 3)
    unique, inverse, counts = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    feature = counts != 2
    twice = np.flatnonzero(counts[inverse] == 2)
    by_edge = twice[np.argsort(inverse[twice], kind="stable")]
    first, second = owner[by_edge[0::2]], owner[by_edge[1::2]]
    cosine = np.einsum("ij,ij->i", normals[first], normals[second])
    sharp = cosine < np.cos(np.radians(angle_deg))
    feature[inverse[by_edge[0::2]][sharp]] = True
    return unique[feature]


def edge_active_nodes(edges, edge_distances, tolerance, n_vertices):
    """Nodes made active by edge-to-edge contact.

    Parameters
    ----------
    edges : (e, 2) int
        Leakage-surface edges.
    edge_distances : (e,) float
        Distance of each edge to the nearest blocking feature edge [m].
    tolerance : float
        Contact tolerance [m]; an edge is in contact when its distance is
        ``<= tolerance``.
    n_vertices : int
        Number of leakage-surface vertices.

    Returns
    -------
    active : (n_vertices,) bool
        Both nodes of every edge in contact.

    >>> edge_active_nodes(np.array([[0, 1], [1, 2]]), np.array([0.1, 0.3]), 0.2, 4).tolist()
    [True, True, False, False]
    """
    active = np.zeros(n_vertices, dtype=bool)
    active[np.asarray(edges)[np.asarray(edge_distances) <= tolerance].ravel()] = True
    return active
