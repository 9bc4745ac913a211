"""Seal-surface topology: elements, boundary loops, the pressurised and outer edges, nodal areas.

A seal surface is a mesh of triangles and quads (``faces`` (m, 3) or (m, 4), triangles padded with −1 in a
4-column array, the layout of :class:`blockage.LeakageSurface`). Its leak path runs from the *pressurised edge*
(the nodes where the film sees the upstream pressure p1) to the *outer edge* (pressure p2). Either edge is a node
set given by the caller, or a boundary loop found from the mesh: a boundary edge belongs to exactly one element,
and each connected set of boundary edges is a loop. With exactly two loops (a ring) "inner" is the loop with the
smaller bounding box and "outer" the other; with more (a gasket with bolt holes) the caller names node sets.
"""
from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

__all__ = ["split_faces", "boundary_loops", "edge_nodes", "nodal_areas", "element_pairs"]


def split_faces(faces):
    """(triangles (mt, 3) int, quads (mq, 4) int) of a face array whose triangles may be padded with −1.

    >>> t, q = split_faces([[0, 1, 2, -1], [1, 3, 4, 2]])
    >>> t.tolist(), q.tolist()
    ([[0, 1, 2]], [[1, 3, 4, 2]])
    """
    f = np.asarray(faces, dtype=np.int64)
    if f.ndim != 2 or f.shape[1] not in (3, 4):
        raise ValueError(f"faces must be an (m, 3) or (m, 4) array of node indices, got shape {f.shape}")
    if f.shape[1] == 3:
        return f.copy(), np.zeros((0, 4), np.int64)
    tri = f[:, 3] < 0
    if np.any(f[:, :3] < 0):
        raise ValueError("faces: only the 4th column may be −1 (a triangle in a quad array)")
    return f[tri, :3].copy(), f[~tri].copy()


def element_pairs(triangles, quads):
    """Node pairs that share an element (rows (k, 2)): the 3 sides of each triangle, all 6 pairs of each quad.

    >>> element_pairs(np.array([[0, 1, 2]]), np.zeros((0, 4), int)).tolist()
    [[0, 1], [1, 2], [2, 0]]
    """
    tri_pairs = triangles[:, [[0, 1], [1, 2], [2, 0]]].reshape(-1, 2)
    quad_pairs = quads[:, [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2], [1, 3]]].reshape(-1, 2)
    return np.concatenate([tri_pairs, quad_pairs])


def _sides(triangles, quads):
    tri = triangles[:, [[0, 1], [1, 2], [2, 0]]].reshape(-1, 2)
    quad = quads[:, [[0, 1], [1, 2], [2, 3], [3, 0]]].reshape(-1, 2)
    return np.sort(np.concatenate([tri, quad]), axis=1)


def boundary_loops(n_nodes, triangles, quads):
    """Node sets of the boundary loops, largest bounding box last is up to the caller: a list of sorted int arrays.

    >>> t = np.array([[0, 1, 2], [0, 2, 3]])  # a square: one loop
    >>> [loop.tolist() for loop in boundary_loops(4, t, np.zeros((0, 4), int))]
    [[0, 1, 2, 3]]
    """
    sides = _sides(triangles, quads)
    unique, counts = np.unique(sides, axis=0, return_counts=True)
    edges = unique[counts == 1]
    if len(edges) == 0:
        return []
    graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n_nodes, n_nodes))
    _, labels = connected_components(graph, directed=False)
    on_boundary = np.unique(edges)
    return [np.sort(on_boundary[labels[on_boundary] == k]) for k in np.unique(labels[on_boundary])]


def _box_size(vertices, nodes):
    span = vertices[nodes].max(axis=0) - vertices[nodes].min(axis=0)
    return float(np.linalg.norm(span))


def edge_nodes(vertices, triangles, quads, which, other=None):
    """Boolean mask (n,) of an edge: ``which`` is "inner", "outer" or an array of node indices.

    ``other`` (a mask) is removed from a loop edge so the two edges never share a node.
    """
    n = len(vertices)
    mask = np.zeros(n, bool)
    if isinstance(which, str):
        loops = boundary_loops(n, triangles, quads)
        if which not in ("inner", "outer"):
            raise ValueError(f"an edge is 'inner', 'outer' or an array of node indices, got {which!r}")
        if len(loops) != 2:
            sizes = ", ".join(f"{len(loop)} nodes ({_box_size(vertices, loop):.4g} m)" for loop in loops)
            raise ValueError(f"'{which}' needs a ring with exactly 2 boundary loops; this surface has {len(loops)}"
                             f"{': ' + sizes if loops else ''}. Give the edge as an array of node indices instead")
        loops.sort(key=lambda loop: _box_size(vertices, loop))
        mask[loops[0] if which == "inner" else loops[1]] = True
    else:
        index = np.asarray(which, dtype=np.int64).ravel()
        if index.size == 0 or index.min() < 0 or index.max() >= n:
            raise ValueError(f"edge node indices must be a non-empty set within 0..{n - 1}")
        mask[index] = True
    if other is not None:
        mask &= ~other
    return mask


def nodal_areas(vertices, triangles, quads):
    """Tributary area of every node [m²]: each element gives A_e/N_e to each of its N_e nodes (quads split along
    their 0–2 diagonal for the area).

    >>> v = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    >>> nodal_areas(v, np.zeros((0, 3), int), np.array([[0, 1, 2, 3]])).tolist()
    [0.25, 0.25, 0.25, 0.25]
    """
    out = np.zeros(len(vertices))
    for elements, size in ((triangles, 3), (quads, 4)):
        if len(elements) == 0:
            continue
        x = vertices[elements]
        area = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
        if size == 4:
            area += 0.5 * np.linalg.norm(np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]), axis=1)
        np.add.at(out, elements.ravel(), np.repeat(area / size, size))
    return out
