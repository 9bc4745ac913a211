"""Brute-force reference: every query against every primitive, pure numpy, chunked.

This is the truth the fast path is tested against (the habit of trimesh's
``closest_point_naive``). It shares only the exact kernels with the fast path, in
their numpy form (:func:`blockage.triangle_distance.closest_points_on_triangles`,
:func:`blockage.segment_distance.closest_points_between_segments`), which are
bit-identical to the compiled ones; it has no tree, no bound, no margin, no
cutoff and no query reordering. A blocker placed by a transform is moved here by
transforming its vertices (the fast path transforms the query points instead).

Cost: ``O(n m)`` kernel evaluations; fine for tests and for subsamples.

>>> import trimesh
>>> box = trimesh.creation.box(extents=(2.0, 2.0, 2.0))
>>> nearest_faces([[0.0, 0.0, 1.5]], box.vertices, box.faces).distances.tolist()
[0.5]
"""

import numpy as np

from blockage.api import (blockage_result, leakage_surface, placed_blockers, _check_options)
from blockage.blocker import Proximity
from blockage.edges import edge_active_nodes
from blockage.sides import Sides
from blockage.segment_distance import closest_points_between_segments
from blockage.triangle_distance import closest_points_on_triangles, degenerate_triangles, squared_distances
from blockage.validation import as_points, as_tolerance

__all__ = ["evaluate_nodes_reference", "evaluate_reference", "nearest_faces", "nearest_segments", "winding_numbers"]

_PAIRS_PER_CHUNK = 1 << 13


def _chunks(n_queries, n_primitives):
    step = max(1, _PAIRS_PER_CHUNK // max(n_primitives, 1))
    return (slice(start, min(start + step, n_queries)) for start in range(0, n_queries, step))


def nearest_faces(points, vertices, faces, exclude_vertices=None):
    """Exact nearest face of every point, by brute force.

    Parameters
    ----------
    points : (n, 3) float
        Query points [m].
    vertices : (v, 3) float
        Blocker vertices [m].
    faces : (m, 3) int
        Blocker triangles.
    exclude_vertices : (n,) int, optional
        Per point, a vertex id whose incident faces are ignored (-1: none).

    Returns
    -------
    proximity : Proximity
        Distances [m] (no cutoff), closest points [m], face indices (first
        minimum in face order; -1 and ``inf`` when there is no face).
    """
    points = as_points(points)
    triangles = np.asarray(vertices, dtype=np.float64)[np.asarray(faces, dtype=np.int64)].reshape(-1, 3, 3)
    faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    degenerate = degenerate_triangles(triangles)
    n, m = len(points), len(triangles)
    sq, face, closest = np.full(n, np.inf), np.full(n, -1, np.int64), np.full((n, 3), np.nan)
    if m == 0:
        return Proximity(sq, closest, face)
    for rows in _chunks(n, m):
        k = rows.stop - rows.start
        p = np.repeat(points[rows], m, axis=0)
        q = closest_points_on_triangles(p, np.tile(triangles, (k, 1, 1)), np.tile(degenerate, k))
        d = squared_distances(p, q).reshape(k, m)
        if exclude_vertices is not None:
            ids = np.asarray(exclude_vertices, dtype=np.int64)[rows]
            d[(faces[None, :, :] == ids[:, None, None]).any(axis=2) & (ids[:, None] >= 0)] = np.inf
        best = np.argmin(d, axis=1)
        hit = np.isfinite(d[np.arange(k), best])
        sq[rows] = d[np.arange(k), best]
        face[rows] = np.where(hit, best, -1)
        closest[rows] = np.where(hit[:, None], q.reshape(k, m, 3)[np.arange(k), best], np.nan)
    return Proximity(np.sqrt(sq), closest, face)


def nearest_segments(starts, ends, seg_starts, seg_ends, seg_vertices=None, exclude_vertices=None):
    """Exact distance from each query segment to the nearest indexed segment.

    Parameters
    ----------
    starts, ends : (n, 3) float
        Query segments [m].
    seg_starts, seg_ends : (m, 3) float
        Indexed segments [m].
    seg_vertices : (m, 2) int, optional
        Vertex ids of the indexed segments (for exclusion).
    exclude_vertices : (n, 2) int, optional
        Per query, vertex ids whose segments are ignored (-1: none).

    Returns
    -------
    distances : (n,) float
        [m] (``inf`` when there is no segment).
    """
    starts, ends = as_points(starts, "starts"), as_points(ends, "ends")
    seg_starts, seg_ends = np.asarray(seg_starts, np.float64), np.asarray(seg_ends, np.float64)
    n, m = len(starts), len(seg_starts)
    out = np.full(n, np.inf)
    if m == 0:
        return out
    for rows in _chunks(n, m):
        k = rows.stop - rows.start
        c = closest_points_between_segments(np.repeat(starts[rows], m, axis=0), np.repeat(ends[rows], m, axis=0),
                                            np.tile(seg_starts, (k, 1)), np.tile(seg_ends, (k, 1)))
        d = squared_distances(c[:, :3], c[:, 3:]).reshape(k, m)
        if exclude_vertices is not None:
            ids = np.asarray(exclude_vertices, dtype=np.int64)[rows]
            touch = (seg_vertices[None, :, :, None] == ids[:, None, None, :]) & (ids[:, None, None, :] >= 0)
            d[touch.any(axis=(2, 3))] = np.inf
        out[rows] = np.sqrt(d.min(axis=1))
    return out


def _world_vertices(blocker, transform):
    if transform is None:
        return blocker.vertices
    return blocker.vertices @ transform[:3, :3].T + transform[:3, 3]


def _self_ids(surface, blocker, ids):
    if surface is not None and surface.source is not None and blocker.source is surface.source:
        return surface.source_vertices[ids]
    return None


def _nearest_all(points, placed, surface=None):
    n = len(points)
    best = Proximity(np.full(n, np.inf), np.full((n, 3), np.nan), np.full(n, -1, np.int64))
    for blocker, transform in placed:
        found = nearest_faces(points, _world_vertices(blocker, transform), blocker.faces,
                              _self_ids(surface, blocker, np.arange(n)))
        closer = found.distances < best.distances
        best = Proximity(np.where(closer, found.distances, best.distances),
                         np.where(closer[:, None], found.closest_points, best.closest_points),
                         np.where(closer, found.faces, best.faces))
    return best


def _edge_distances(surface, placed):
    ends = surface.vertices[surface.edges]
    distances = np.full(len(ends), np.inf)
    for blocker, transform in placed:
        world = _world_vertices(blocker, transform)
        feature = blocker.feature_edges
        found = nearest_segments(ends[:, 0], ends[:, 1], world[feature[:, 0]], world[feature[:, 1]], feature,
                                 _self_ids(surface, blocker, surface.edges))
        distances = np.minimum(distances, found)
    return distances


def winding_numbers(points, vertices, faces):
    """(n,) generalized winding number of a triangle mesh at each point (1 inside a closed mesh, 0 outside).

    Van Oosterom & Strackee's solid angle of each triangle, summed over all of them and divided by 4π
    (Jacobson et al., "Robust inside-outside segmentation using generalized winding numbers", SIGGRAPH 2013).
    Independent of distances and normals: the reference for the penetration rule of closed blockers.
    """
    points = as_points(points)
    tri = np.asarray(vertices, dtype=float)[np.asarray(faces)]
    out = np.zeros(len(points))
    for rows in _chunks(len(points), len(tri)):
        a, b, c = (tri[None, :, k] - points[rows, None] for k in range(3))
        la, lb, lc = (np.linalg.norm(v, axis=2) for v in (a, b, c))
        det = np.einsum("pfi,pfi->pf", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("pfi,pfi->pf", a, b) * lc + np.einsum("pfi,pfi->pf", b, c) * la
               + np.einsum("pfi,pfi->pf", c, a) * lb)
        out[rows] = np.sum(2.0 * np.arctan2(det, den), axis=1) / (4.0 * np.pi)
    return out


def _penetrated(points, placed, surface=None, open_depth=0.0):
    """Points inside a closed blocker (winding number > 1/2), or behind an open one's interior (brute-force
    closest point and :class:`blockage.sides.Sides`)."""
    inside = np.zeros(len(points), dtype=bool)
    for blocker, transform in placed:
        if surface is not None and surface.source is not None and blocker.source is surface.source:
            continue
        world = _world_vertices(blocker, transform)
        sides = Sides(world, blocker.faces)
        if sides.closed:
            inside |= winding_numbers(points, world, blocker.faces) > 0.5
            continue
        if open_depth > 0.0:
            found = nearest_faces(points, world, blocker.faces)
            inside |= sides.behind(points, found.closest_points, found.faces) & (found.distances <= open_depth)
    return inside


def evaluate_reference(leak, blockers, tolerance, *, effective_area=None, edge_contact=False, permeability=0.0,
                       penetration=True):
    """:func:`blockage.evaluate` by brute force (distances are exact for every node)."""
    surface = leakage_surface(leak)
    tolerance = as_tolerance(tolerance)
    effective_area, permeability = _check_options(effective_area, permeability)
    placed = placed_blockers(blockers)
    proximity = _nearest_all(surface.vertices, placed, surface)
    active = proximity.distances <= tolerance
    if penetration is not False:
        active |= _penetrated(surface.vertices, placed, surface, 0.0 if penetration is True else penetration)
    if edge_contact and len(surface.edges):
        active |= edge_active_nodes(surface.edges, _edge_distances(surface, placed), tolerance,
                                    len(surface.vertices))
    return blockage_result(surface, active, proximity, tolerance, effective_area, permeability)


def evaluate_nodes_reference(points, blockers, tolerance, penetration=True):
    """Active nodes of a node-based surface by brute force: ``(active, distances)``."""
    points = as_points(points)
    tolerance = as_tolerance(tolerance)
    placed = placed_blockers(blockers)
    proximity = _nearest_all(points, placed)
    active = proximity.distances <= tolerance
    if penetration is not False:
        active |= _penetrated(points, placed, None, 0.0 if penetration is True else penetration)
    return active, proximity.distances
