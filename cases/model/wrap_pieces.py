"""Where each node of a wrapped mesh lies while a convex body translates through it: exact pieces along s.

A convex body bounded by planes n_f·p = c_f (outward unit normals) is translated by s along the unit vector a.
In the body's frame a node x0 moves on the line p(s) = x0 − s·a, and its signed plane values are affine in s:

.. math:: l_f(s) = \\alpha_f - \\beta_f s,\\qquad \\alpha_f = \\mathbf n_f\\cdot\\mathbf x_0 - c_f,\\quad
          \\beta_f = \\mathbf n_f\\cdot\\mathbf a .

The node is inside while g(s) = max_f l_f(s) < 0 (g is convex and piecewise affine, so that is one interval),
and there its closest point on the surface is its projection on the plane of the largest l_f (an interior point's
nearest boundary point lies on its nearest face plane): in the world, x(s) = x0 − l_f(s)·n_f, affine in s on each
piece where one plane is the largest. The pieces are found by walking the line through the cells of g (the cells
of the power diagram of the sites n_f with weights −2c_f, since argmax_f l_f = argmin_f |p − n_f|² + 2c_f): from a
cell, the next one is the neighbour whose line overtakes first. A neighbour list that holds more than the cells'
true neighbours changes nothing (a plane can only overtake where it becomes the largest), so the lists are the
regular triangulation's edges (the lower hull of the lifted sites) joined with the planes of faces sharing a vertex.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from exchange.engine.arrays import copy_into

__all__ = ["ConvexPlanes", "convex_planes", "node_pieces", "WalkError"]

#: A body with at most this many distinct planes lists every plane as every plane's neighbour.
ALL_NEIGHBOURS = 64
#: Cells one node's walk may cross before it is given up (:class:`WalkError`).
MAX_STEPS = 100000


class WalkError(RuntimeError):
    """A node's walk did not reach the end of the range (the caller falls back to sampling)."""


class ConvexPlanes:
    """The distinct face planes of a convex mesh, about an origin ``o`` [m]: ``normals`` (P, 3), ``offsets``
    (P,) [m] (n·(p − o) = c), ``face_plane`` (F,) the plane of each face, neighbour lists in CSR (``ptr``,
    ``idx``)."""

    def __init__(self, normals, offsets, face_plane, origin, ptr, idx, bounding_radius):
        self.normals, self.offsets, self.face_plane = normals, offsets, face_plane
        self.origin, self.ptr, self.idx, self.bounding_radius = origin, ptr, idx, bounding_radius

    def argmax(self, points) -> np.ndarray:
        """The plane with the largest n·(p − o) − c for each point (p in the body's frame), (n, 3) → (n,)."""
        return _argmax(np.ascontiguousarray(np.asarray(points, dtype=float) - self.origin), self.normals, self.offsets)


def convex_planes(vertices, faces, rel: float = 1e-9):
    """The :class:`ConvexPlanes` of a closed outward mesh, or None if the mesh is not convex (a vertex more than
    ``rel`` of its size in front of a face plane) or has degenerate faces."""
    v, f = np.asarray(vertices, dtype=float), np.asarray(faces)
    origin = v.mean(axis=0)
    x = v - origin
    tri = x[f]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(cross, axis=1)
    size = float(np.max(np.linalg.norm(x, axis=1)))
    if not np.all(norm > 1e-14 * size * size):
        return None
    n = cross / norm[:, None]
    c = np.einsum("ij,ij->i", n, tri.mean(axis=1))
    if np.any(c <= 0.0) or not _locally_convex(x, f, n, c, rel * size):
        return None
    key = np.round(np.column_stack([n, c / size]) / 1e-9).astype(np.int64)
    _, first, face_plane = np.unique(key, axis=0, return_index=True, return_inverse=True)
    face_plane = face_plane.ravel()
    normals, offsets = n[first], c[first]
    ptr, idx = _neighbours(normals, offsets, f, face_plane)
    return ConvexPlanes(normals, offsets, face_plane, origin, ptr, idx, size * (1.0 + 1e-9))


def _locally_convex(x, faces, n, c, tol) -> bool:
    """Every edge convex (the far node of each face's neighbour across an edge behind its plane): with the mesh
    closed and consistently oriented, the body is convex and every vertex is behind every face plane."""
    import trimesh

    mesh = trimesh.Trimesh(x, faces, process=False)
    if not (mesh.is_watertight and mesh.is_winding_consistent):
        return False
    pairs, far = mesh.face_adjacency, mesh.face_adjacency_unshared
    ahead = np.maximum(np.einsum("ij,ij->i", n[pairs[:, 0]], x[far[:, 1]]) - c[pairs[:, 0]],
                       np.einsum("ij,ij->i", n[pairs[:, 1]], x[far[:, 0]]) - c[pairs[:, 1]])
    return bool(np.all(ahead <= tol))


def _neighbours(normals, offsets, faces, face_plane):
    """CSR lists holding each plane's power-diagram neighbours (plus the planes of faces sharing a vertex)."""
    P = len(normals)
    if P <= ALL_NEIGHBOURS:
        pairs = np.array([(i, j) for i in range(P) for j in range(P) if i != j], dtype=np.int64).reshape(-1, 2)
    else:
        from scipy.spatial import ConvexHull

        hull = ConvexHull(np.column_stack([normals, 1.0 + 2.0 * offsets]))
        simplices = hull.simplices[hull.equations[:, 3] < 0.0]  # the lower hull: the regular triangulation
        pairs = [np.column_stack([simplices[:, i], simplices[:, j]]) for i in range(4) for j in range(4) if i != j]
        pairs.append(_vertex_pairs(faces, face_plane))
        pairs = np.concatenate(pairs).astype(np.int64)
        key = np.unique(pairs[:, 0] * P + pairs[:, 1])  # sorted as the pairs (i, j) are, each once
        pairs = np.column_stack([key // P, key % P])
        pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    ptr = np.searchsorted(pairs[:, 0], np.arange(P + 1)).astype(np.int64)
    return ptr, np.ascontiguousarray(pairs[:, 1], dtype=np.int64)


def _vertex_pairs(faces, face_plane) -> np.ndarray:
    """(plane, plane) of every ordered pair of faces that share a vertex (with repeats), (m, 2)."""
    vertex, plane = np.ravel(faces), np.repeat(face_plane, 3)
    order = np.argsort(vertex, kind="stable")
    vertex, plane = vertex[order], plane[order]
    starts = np.flatnonzero(np.r_[True, vertex[1:] != vertex[:-1]])
    counts = np.diff(np.r_[starts, len(vertex)])
    group = np.repeat(np.arange(len(starts)), counts)  # each entry's vertex group
    partners = counts[group]
    left = np.repeat(np.arange(len(vertex)), partners)  # each entry once per entry of its group
    within = np.arange(len(left)) - np.repeat(np.cumsum(partners) - partners, partners)
    right = starts[group[left]] + within
    return np.column_stack([plane[left], plane[right]])


def node_pieces(planes: ConvexPlanes, points, axis, lo: float, hi: float):
    """Exact pieces of the nodes ``points`` (n, 3) [m] inside the body translated by s ∈ [lo, hi] along the unit
    ``axis``: (node, s0, s1, plane) arrays sorted by node then s0; on a piece the node lies at
    x0 − (α − β·s)·n of its plane."""
    a = np.asarray(axis, dtype=float)
    x = np.asarray(points, dtype=float) - planes.origin
    # nodes whose line passes the body's bounding sphere (centre o, radius R: every vertex is within R)
    t = x @ a
    lateral = np.linalg.norm(x - t[:, None] * a, axis=1)
    R = planes.bounding_radius
    cand = np.flatnonzero((lateral <= R) & (t - np.sqrt(np.maximum(R * R - lateral ** 2, 0.0)) <= hi)
                          & (t + np.sqrt(np.maximum(R * R - lateral ** 2, 0.0)) >= lo))
    if not cand.size:
        empty = np.zeros(0)
        return np.zeros(0, dtype=np.int64), empty, empty, np.zeros(0, dtype=np.int64)
    half = np.sqrt(np.maximum(R * R - lateral[cand] ** 2, 0.0))
    start = np.clip(t[cand] - half, lo, hi)  # where the line enters the sphere (nothing touches before)
    first = planes.argmax(x[cand] - start[:, None] * a + planes.origin)
    beta = planes.normals @ a
    node, s0, s1, plane, stuck = _walk(x[cand], start, first, planes.normals, planes.offsets, beta, planes.ptr,
                                       planes.idx, hi)
    if stuck:
        raise WalkError(f"{stuck} nodes crossed more than {MAX_STEPS} cells of the body: not walked to the end")
    return cand[node], s0, s1, plane


@njit(cache=True)
def _walk(x, start, first, normals, offsets, beta, ptr, idx, hi):
    """Walk every node's line from ``start`` to ``hi`` through the cells of max_f l_f; the pieces inside."""
    cap = 8 * len(x) + 16
    node = np.empty(cap, np.int64)
    s0 = np.empty(cap)
    s1 = np.empty(cap)
    plane = np.empty(cap, np.int64)
    m, stuck = 0, 0
    for i in range(len(x)):
        s, f = start[i], first[i]
        af = normals[f, 0] * x[i, 0] + normals[f, 1] * x[i, 1] + normals[f, 2] * x[i, 2] - offsets[f]
        inside = af - beta[f] * s < 0.0
        done = False
        for _ in range(MAX_STEPS):
            sn, g, bg = hi, -1, 0.0
            for q in range(ptr[f], ptr[f + 1]):
                k = idx[q]
                if beta[k] < beta[f]:
                    ak = normals[k, 0] * x[i, 0] + normals[k, 1] * x[i, 1] + normals[k, 2] * x[i, 2] - offsets[k]
                    sc = max((ak - af) / (beta[k] - beta[f]), s)
                    if sc < sn or (sc == sn and g >= 0 and beta[k] < bg):
                        sn, g, bg = sc, k, beta[k]
            sz = np.inf
            if beta[f] != 0.0 and ((inside and beta[f] < 0.0) or (not inside and beta[f] > 0.0)):
                sz = max(af / beta[f], s)
            end = min(sn, sz, hi)
            if inside and end > s:
                if m == cap:
                    cap *= 2
                    node, s0, s1, plane = _grow(node, cap), _growf(s0, cap), _growf(s1, cap), _grow(plane, cap)
                node[m], s0[m], s1[m], plane[m] = i, s, end, f
                m += 1
            if end >= hi:
                done = True
                break
            s = end
            if sz <= sn:
                if inside:  # g is convex: once out, the node stays out
                    done = True
                    break
                inside = True
            else:
                f = g
                af = normals[f, 0] * x[i, 0] + normals[f, 1] * x[i, 1] + normals[f, 2] * x[i, 2] - offsets[f]
        stuck += not done
    return node[:m], s0[:m], s1[:m], plane[:m], stuck


@njit(cache=True)
def _argmax(x, normals, offsets):
    """Index of the largest normals·x − offsets for each row of x (brute force over the planes)."""
    out = np.empty(len(x), np.int64)
    for i in range(len(x)):
        best, k = -np.inf, 0
        for f in range(len(normals)):
            v = normals[f, 0] * x[i, 0] + normals[f, 1] * x[i, 1] + normals[f, 2] * x[i, 2] - offsets[f]
            if v > best:
                best, k = v, f
        out[i] = k
    return out


@njit(cache=True)
def _grow(a, cap):
    out = np.empty(cap, a.dtype)
    copy_into(out, a)
    return out


@njit(cache=True)
def _growf(a, cap):
    out = np.empty(cap)
    copy_into(out, a)
    return out
