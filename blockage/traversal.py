"""Compiled tree queries: nearest face within a cutoff, nearest feature edge within a cutoff.

Each query point descends the :mod:`blockage.broadphase` tree depth first, nearer
child first, and prunes every node whose (inflated) box is farther than the best
squared distance found so far or than ``limit_sq``. Leaves call the exact kernels
of :mod:`blockage.triangle_distance` and :mod:`blockage.segment_distance`, so the
minimum found is bit-identical to the brute-force minimum whenever it is within
the limit. The kernels release the GIL (:mod:`blockage.parallel` runs chunks in
threads).

The functions return the raw minimum (``inf`` and ``-1`` when nothing is within the
limit); :class:`blockage.blocker.Blocker` turns it into distances.
"""

import numpy as np

from blockage._jit import njit
from blockage.segment_distance import closest_points_of_segments
from blockage.triangle_distance import closest_point_on_triangle

__all__ = ["nearest_segments", "nearest_triangles"]

_STACK = 128


@njit
def _box_sq(p, box):
    """Squared distance from a point to an axis-aligned box ``lo, hi``."""
    sq = 0.0
    for k in range(3):
        if p[k] < box[k]:
            sq += (box[k] - p[k]) * (box[k] - p[k])
        elif p[k] > box[k + 3]:
            sq += (p[k] - box[k + 3]) * (p[k] - box[k + 3])
    return sq


@njit
def _segment_box_sq(seg, box):
    """Squared distance between the bounding box of a segment and a box ``lo, hi`` row."""
    sq = 0.0
    for k in range(3):
        lo, hi = min(seg[k], seg[k + 3]), max(seg[k], seg[k + 3])
        if hi < box[k]:
            sq += (box[k] - hi) * (box[k] - hi)
        elif box[k + 3] < lo:
            sq += (lo - box[k + 3]) * (lo - box[k + 3])
    return sq


@njit
def _push_children(node, lb_left, lb_right, threshold, stack, bound, top):
    """Push the children that pass, farther first so the nearer is popped first."""
    left, right = 2 * node, 2 * node + 1
    if lb_left <= lb_right:
        first, lb_first, second, lb_second = right, lb_right, left, lb_left
    else:
        first, lb_first, second, lb_second = left, lb_left, right, lb_right
    if lb_first <= threshold:
        stack[top] = first
        bound[top] = lb_first
        top += 1
    if lb_second <= threshold:
        stack[top] = second
        bound[top] = lb_second
        top += 1
    return top


@njit
def _face_bound_sq(px, py, pz, g, margin):
    """Lower bound of the squared distance to a face from its plane and radius."""
    dx, dy, dz = px - g[0], py - g[1], pz - g[2]
    h = dx * g[3] + dy * g[4] + dz * g[5]
    wx, wy, wz = dx - h * g[3], dy - h * g[4], dz - h * g[5]
    off_plane = max(abs(h) - margin, 0.0)
    in_plane = max(np.sqrt(wx * wx + wy * wy + wz * wz) - g[6] - margin, 0.0)
    return off_plane * off_plane + in_plane * in_plane


@njit
def _excluded(vertices, exclude):
    """True when a face (or edge) touches the excluded vertex id."""
    if exclude < 0:
        return False
    for v in vertices:
        if v == exclude:
            return True
    return False


@njit
def _nearest_in_leaf(p, start, stop, exclude, threshold, tri, degenerate, bounds, face_vertices, margin, best):
    """Scan one leaf; ``best`` is ``[sq, face, qx, qy, qz]``, updated in place."""
    px, py, pz = p[0], p[1], p[2]
    for f in range(start, stop):
        if _face_bound_sq(px, py, pz, bounds[f], margin) > min(best[0], threshold):
            continue
        if _excluded(face_vertices[f], exclude):
            continue
        t = tri[f]
        cx, cy, cz = closest_point_on_triangle(px, py, pz, t[0], t[1], t[2], t[3], t[4], t[5],
                                               t[6], t[7], t[8], degenerate[f])
        sq = (px - cx) * (px - cx) + (py - cy) * (py - cy) + (pz - cz) * (pz - cz)
        if sq < best[0]:
            best[0], best[1], best[2], best[3], best[4] = sq, f, cx, cy, cz


@njit
def _nearest_triangle(p, exclude, limit_sq, boxes, slots, leaf_size, tri, degenerate, bounds,
                      face_vertices, margin, stack, bound, best):
    """Nearest face to one point; writes ``(sq, face, qx, qy, qz)`` into ``best``."""
    best[0], best[1], best[2], best[3], best[4] = np.inf, -1.0, np.nan, np.nan, np.nan
    top = 0
    lb = _box_sq(p, boxes[1])
    if lb <= limit_sq:
        stack[0], bound[0], top = 1, lb, 1
    while top > 0:
        top -= 1
        node = stack[top]
        threshold = min(best[0], limit_sq)
        if bound[top] > threshold:
            continue
        if node < slots:
            lb_left = _box_sq(p, boxes[2 * node])
            lb_right = _box_sq(p, boxes[2 * node + 1])
            top = _push_children(node, lb_left, lb_right, threshold, stack, bound, top)
        else:
            start = (node - slots) * leaf_size
            stop = min(start + leaf_size, tri.shape[0])
            _nearest_in_leaf(p, start, stop, exclude, limit_sq, tri, degenerate, bounds, face_vertices,
                             margin, best)


@njit(nogil=True)
def nearest_triangles(points, exclude, limit_sq, boxes, slots, leaf_size, tri, degenerate, bounds,
                      face_vertices, margin):
    """Nearest face of each point among faces within ``sqrt(limit_sq)``.

    Parameters
    ----------
    points : (n, 3) float
        Query points in the blocker's frame [m], ideally in Morton order.
    exclude : (n,) int
        Blocker vertex id whose incident faces each point ignores (-1: none).
    limit_sq : float
        Squared search radius [m^2] (the cutoff plus the box margin, squared).
    boxes, slots, leaf_size :
        The tree (:class:`blockage.broadphase.Tree`).
    tri : (m, 9) float
        Triangles in tree order, ``a, b, c`` flattened [m].
    degenerate : (m,) bool
        :func:`blockage.triangle_distance.degenerate_triangles` in tree order.
    bounds : (m, 8) float
        :func:`blockage.broadphase.face_bounds` in tree order.
    face_vertices : (m, 3) int
        Vertex ids of each face in tree order.
    margin : float
        Round-off allowance of the bounds [m].

    Returns
    -------
    result : (n, 5) float
        Squared distance [m^2] (``inf`` if no face within the limit), sorted face
        position (-1 if none) and closest point [m] of each point.
    """
    n = points.shape[0]
    result = np.empty((n, 5))
    stack = np.empty(_STACK, np.int64)
    bound = np.empty(_STACK)
    for i in range(n):
        _nearest_triangle(points[i], exclude[i], limit_sq, boxes, slots, leaf_size, tri, degenerate,
                          bounds, face_vertices, margin, stack, bound, result[i])
    return result


@njit
def _nearest_segment(seg, exclude, limit_sq, boxes, slots, leaf_size, segs, seg_vertices, stack, bound, out):
    """Nearest indexed segment to one query segment; writes ``(sq, position)``."""
    best, best_seg, top = np.inf, -1, 0
    lb = _segment_box_sq(seg, boxes[1])
    if lb <= limit_sq:
        stack[0], bound[0], top = 1, lb, 1
    while top > 0:
        top -= 1
        node = stack[top]
        threshold = min(best, limit_sq)
        if bound[top] > threshold:
            continue
        if node < slots:
            lb_left = _segment_box_sq(seg, boxes[2 * node])
            lb_right = _segment_box_sq(seg, boxes[2 * node + 1])
            top = _push_children(node, lb_left, lb_right, threshold, stack, bound, top)
            continue
        start = (node - slots) * leaf_size
        for e in range(start, min(start + leaf_size, segs.shape[0])):
            if _excluded(seg_vertices[e], exclude[0]) or _excluded(seg_vertices[e], exclude[1]):
                continue
            s = segs[e]
            c = closest_points_of_segments(seg[0], seg[1], seg[2], seg[3], seg[4], seg[5],
                                           s[0], s[1], s[2], s[3], s[4], s[5])
            sq = (c[0] - c[3]) * (c[0] - c[3]) + (c[1] - c[4]) * (c[1] - c[4]) + (c[2] - c[5]) * (c[2] - c[5])
            if sq < best:
                best, best_seg = sq, e
    out[0], out[1] = best, best_seg


@njit(nogil=True)
def nearest_segments(queries, exclude, limit_sq, boxes, slots, leaf_size, segs, seg_vertices):
    """Nearest indexed segment of each query segment within ``sqrt(limit_sq)``.

    Parameters
    ----------
    queries : (n, 6) float
        Query segments, start and end flattened [m].
    exclude : (n, 2) int
        Vertex ids (in the indexed segments' numbering, -1: none); indexed
        segments touching either are ignored (self-contact).
    limit_sq : float
        Squared search radius [m^2].
    boxes, slots, leaf_size :
        The tree over ``segs`` (:class:`blockage.broadphase.Tree`).
    segs : (m, 6) float
        Indexed segments in tree order [m].
    seg_vertices : (m, 2) int
        Vertex ids of the indexed segments in tree order.

    Returns
    -------
    result : (n, 2) float
        Squared distance [m^2] (``inf`` if none within the limit) and sorted
        position of the nearest segment (-1 if none).
    """
    n = queries.shape[0]
    result = np.empty((n, 2))
    stack = np.empty(_STACK, np.int64)
    bound = np.empty(_STACK)
    for i in range(n):
        _nearest_segment(queries[i], exclude[i], limit_sq, boxes, slots, leaf_size, segs, seg_vertices,
                         stack, bound, result[i])
    return result
