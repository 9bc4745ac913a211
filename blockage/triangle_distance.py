"""Exact closest point on a triangle (Ericson, Real-Time Collision Detection, 5.1.5).

The same law is written twice, operation for operation in the same order:

* :func:`closest_point_on_triangle` works on scalars and is compiled by numba; the
  broad phase (:mod:`blockage.traversal`) calls it for each candidate face.
* :func:`closest_points_on_triangles` works on arrays of pairs with numpy; the
  brute-force reference (:mod:`blockage.reference`) calls it for all pairs.

Because both evaluate the same IEEE-754 operations in the same order, and neither
fuses or reorders them, they return bit-identical results: a node classified by
the fast path is classified by the reference in exactly the same way, even when it
sits at ``tolerance * (1 +- 1e-12)``.

Triangles that are degenerate (:func:`degenerate_triangles`) are treated as their
three edges; so are the rare non-degenerate ones whose barycentric denominator
rounds to zero or below.

>>> import numpy as np
>>> tri = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
>>> q = closest_points_on_triangles(np.array([[0.25, 0.25, 2.0]]), tri)
>>> q.tolist()
[[0.25, 0.25, 0.0]]
>>> closest_point_on_triangle(2.0, 2.0, 0.0, *tri[0].ravel(), False)
(0.5, 0.5, 0.0)
"""

import numpy as np

from blockage._jit import njit
from blockage.tolerance import TOL

__all__ = [
    "closest_point_on_segment",
    "closest_point_on_triangle",
    "closest_points_on_segments",
    "closest_points_on_triangles",
    "degenerate_triangles",
    "is_degenerate",
    "squared_distances",
]


def degenerate_triangles(triangles):
    """Flag triangles too thin for the barycentric branch.

    Parameters
    ----------
    triangles : (m, 3, 3) float
        Vertices ``a, b, c`` of each triangle [m].

    Returns
    -------
    degenerate : (m,) bool
        True where ``|ab x ac|^2 <= TOL.degenerate_sin2 * |ab|^2 |ac|^2``, which
        includes every triangle with a repeated vertex or collinear vertices.
        Bit-identical to :func:`is_degenerate`.

    >>> degenerate_triangles(np.array([[[0.0, 0, 0], [1, 0, 0], [2, 0, 0]],
    ...                                [[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])).tolist()
    [True, False]
    """
    triangles = np.asarray(triangles, dtype=np.float64)
    a, b, c = (_components(triangles[:, k]) for k in range(3))
    ab, ac = _sub(b, a), _sub(c, a)
    n = (ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0])
    return _dot(n, n) <= TOL.degenerate_sin2 * (_dot(ab, ab) * _dot(ac, ac))


@njit
def is_degenerate(ax, ay, az, bx, by, bz, cx, cy, cz, sin2):
    """Scalar form of :func:`degenerate_triangles` (``sin2 = TOL.degenerate_sin2``)."""
    abx, aby, abz = bx - ax, by - ay, bz - az
    acx, acy, acz = cx - ax, cy - ay, cz - az
    nx, ny, nz = aby * acz - abz * acy, abz * acx - abx * acz, abx * acy - aby * acx
    nn = nx * nx + ny * ny + nz * nz
    return nn <= sin2 * ((abx * abx + aby * aby + abz * abz) * (acx * acx + acy * acy + acz * acz))


@njit
def closest_point_on_segment(px, py, pz, ax, ay, az, bx, by, bz):
    """Closest point on segment ``ab`` to ``p`` (scalars in, a tuple of 3 out).

    ``t = clamp((p - a).(b - a) / |b - a|^2, 0, 1)``; a zero-length segment
    returns ``a``.
    """
    ux = bx - ax
    uy = by - ay
    uz = bz - az
    uu = ux * ux + uy * uy + uz * uz
    t = 0.0
    if uu > 0.0:
        t = ((px - ax) * ux + (py - ay) * uy + (pz - az) * uz) / uu
        t = min(max(t, 0.0), 1.0)
    return ax + t * ux, ay + t * uy, az + t * uz


@njit
def _closest_point_on_edges(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz):
    """Closest point on the three edges ab, bc, ca (first wins a tie)."""
    qx, qy, qz = closest_point_on_segment(px, py, pz, ax, ay, az, bx, by, bz)
    best = (px - qx) * (px - qx) + (py - qy) * (py - qy) + (pz - qz) * (pz - qz)
    rx, ry, rz = closest_point_on_segment(px, py, pz, bx, by, bz, cx, cy, cz)
    sq = (px - rx) * (px - rx) + (py - ry) * (py - ry) + (pz - rz) * (pz - rz)
    if sq < best:
        qx, qy, qz, best = rx, ry, rz, sq
    rx, ry, rz = closest_point_on_segment(px, py, pz, cx, cy, cz, ax, ay, az)
    sq = (px - rx) * (px - rx) + (py - ry) * (py - ry) + (pz - rz) * (pz - rz)
    if sq < best:
        qx, qy, qz = rx, ry, rz
    return qx, qy, qz


@njit
def closest_point_on_triangle(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz, degenerate):
    """Closest point on triangle ``abc`` to ``p`` (Ericson 5.1.5, scalar form).

    Parameters are the 3 coordinates of ``p``, ``a``, ``b``, ``c`` [m] and the
    face's :func:`degenerate_triangles` flag. Returns ``(qx, qy, qz)`` [m].
    """
    if degenerate:
        return _closest_point_on_edges(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz)
    abx, aby, abz = bx - ax, by - ay, bz - az
    acx, acy, acz = cx - ax, cy - ay, cz - az
    apx, apy, apz = px - ax, py - ay, pz - az
    d1 = abx * apx + aby * apy + abz * apz
    d2 = acx * apx + acy * apy + acz * apz
    if d1 <= 0.0 and d2 <= 0.0:
        return ax, ay, az
    bpx, bpy, bpz = px - bx, py - by, pz - bz
    d3 = abx * bpx + aby * bpy + abz * bpz
    d4 = acx * bpx + acy * bpy + acz * bpz
    if d3 >= 0.0 and d4 <= d3:
        return bx, by, bz
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        den = d1 - d3
        v = d1 / den if den > 0.0 else 0.0
        return ax + v * abx, ay + v * aby, az + v * abz
    cpx, cpy, cpz = px - cx, py - cy, pz - cz
    d5 = abx * cpx + aby * cpy + abz * cpz
    d6 = acx * cpx + acy * cpy + acz * cpz
    if d6 >= 0.0 and d5 <= d6:
        return cx, cy, cz
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        den = d2 - d6
        w = d2 / den if den > 0.0 else 0.0
        return ax + w * acx, ay + w * acy, az + w * acz
    va = d3 * d6 - d5 * d4
    e43 = d4 - d3
    e56 = d5 - d6
    if va <= 0.0 and e43 >= 0.0 and e56 >= 0.0:
        den = e43 + e56
        w = e43 / den if den > 0.0 else 0.0
        return bx + w * (cx - bx), by + w * (cy - by), bz + w * (cz - bz)
    s = va + vb + vc
    if s > 0.0:
        inv = 1.0 / s
        v = vb * inv
        w = vc * inv
        return ax + abx * v + acx * w, ay + aby * v + acy * w, az + abz * v + acz * w
    return _closest_point_on_edges(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz)


def _components(array):
    """Split an (n, 3) array into a tuple of three (n,) arrays."""
    return array[:, 0], array[:, 1], array[:, 2]


def _sub(u, v):
    return u[0] - v[0], u[1] - v[1], u[2] - v[2]


def _dot(u, v):
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def _select(mask, u, v):
    return tuple(np.where(mask, ui, vi) for ui, vi in zip(u, v))


def _along(origin, t, direction):
    return tuple(o + t * d for o, d in zip(origin, direction))


def _segment_components(p, a, b):
    """Vector form of :func:`closest_point_on_segment` on component tuples."""
    u = _sub(b, a)
    uu = _dot(u, u)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = _dot(_sub(p, a), u) / uu
    t = np.where(uu > 0.0, np.minimum(np.maximum(t, 0.0), 1.0), 0.0)
    return _along(a, t, u)


def _edges_components(p, a, b, c):
    """Vector form of ``_closest_point_on_edges`` (first edge wins a tie)."""
    q = _segment_components(p, a, b)
    best = _dot(_sub(p, q), _sub(p, q))
    for s, e in ((b, c), (c, a)):
        r = _segment_components(p, s, e)
        sq = _dot(_sub(p, r), _sub(p, r))
        closer = sq < best
        q = _select(closer, r, q)
        best = np.where(closer, sq, best)
    return q


def _safe_ratio(num, den):
    """``num / den`` where ``den > 0``, else 0 (as the scalar kernel does)."""
    with np.errstate(all="ignore"):
        return np.where(den > 0.0, num / den, 0.0)


def _triangle_components(p, a, b, c, degenerate):
    """Vector form of :func:`closest_point_on_triangle` on component tuples."""
    ab, ac = _sub(b, a), _sub(c, a)
    ap, bp, cp = _sub(p, a), _sub(p, b), _sub(p, c)
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    vc = d1 * d4 - d3 * d2
    vb = d5 * d2 - d1 * d6
    va = d3 * d6 - d5 * d4
    e43, e56 = d4 - d3, d5 - d6
    s = va + vb + vc
    with np.errstate(all="ignore"):  # lanes of other regions may overflow
        inv = 1.0 / s
        v, w = vb * inv, vc * inv
        interior = tuple(a[k] + ab[k] * v + ac[k] * w for k in range(3))
    # Ericson's regions in his order of early returns: the first that holds wins.
    regions = (
        ((d1 <= 0.0) & (d2 <= 0.0), a),
        ((d3 >= 0.0) & (d4 <= d3), b),
        ((vc <= 0.0) & (d1 >= 0.0) & (d3 <= 0.0), _along(a, _safe_ratio(d1, d1 - d3), ab)),
        ((d6 >= 0.0) & (d5 <= d6), c),
        ((vb <= 0.0) & (d2 >= 0.0) & (d6 <= 0.0), _along(a, _safe_ratio(d2, d2 - d6), ac)),
        ((va <= 0.0) & (e43 >= 0.0) & (e56 >= 0.0), _along(b, _safe_ratio(e43, e43 + e56), _sub(c, b))),
        (s > 0.0, interior),
    )
    q = tuple(np.full_like(d1, np.nan) for _ in range(3))
    for mask, value in reversed(regions):
        q = _select(mask, value, q)
    # degenerate faces and the rare rounding fallback: closest point on the edges
    edge_rows = np.flatnonzero(degenerate | ~np.any([mask for mask, _ in regions], axis=0))
    if len(edge_rows):
        take = lambda u: tuple(x[edge_rows] for x in u)  # noqa: E731
        on_edges = _edges_components(take(p), take(a), take(b), take(c))
        for k in range(3):
            q[k][edge_rows] = on_edges[k]
    return q


def closest_points_on_triangles(points, triangles, degenerate=None):
    """Closest point on each triangle to each point, pairwise (numpy form).

    Parameters
    ----------
    points : (n, 3) float
        Query points [m].
    triangles : (n, 3, 3) float
        One triangle per point [m].
    degenerate : (n,) bool, optional
        :func:`degenerate_triangles` of ``triangles`` (computed when omitted).

    Returns
    -------
    closest : (n, 3) float
        Closest point on ``triangles[i]`` to ``points[i]`` [m], bit-identical to
        :func:`closest_point_on_triangle`.
    """
    points = np.asarray(points, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.float64)
    if degenerate is None:
        degenerate = degenerate_triangles(triangles)
    p = _components(points)
    a, b, c = (_components(triangles[:, k]) for k in range(3))
    return np.stack(_triangle_components(p, a, b, c, np.asarray(degenerate, bool)), axis=1)


def closest_points_on_segments(points, starts, ends):
    """Closest point on each segment to each point, pairwise (numpy form).

    Parameters
    ----------
    points, starts, ends : (n, 3) float
        Query points and segment end points [m].

    Returns
    -------
    closest : (n, 3) float
        Bit-identical to :func:`closest_point_on_segment` [m].

    >>> closest_points_on_segments(np.array([[0.5, 1.0, 0.0]]), np.zeros((1, 3)),
    ...                            np.array([[1.0, 0.0, 0.0]])).tolist()
    [[0.5, 0.0, 0.0]]
    """
    p, a, b = (_components(np.asarray(x, dtype=np.float64)) for x in (points, starts, ends))
    return np.stack(_segment_components(p, a, b), axis=1)


def squared_distances(points, closest):
    """Squared distances ``|p - q|^2`` summed x, y, z in that order.

    Parameters
    ----------
    points, closest : (n, 3) float
        Pairs of points [m].

    Returns
    -------
    sq : (n,) float
        Squared distances [m^2], computed as the compiled kernels compute them.

    >>> squared_distances(np.array([[3.0, 4.0, 0.0]]), np.zeros((1, 3))).tolist()
    [25.0]
    """
    d = _sub(_components(np.asarray(points, np.float64)), _components(np.asarray(closest, np.float64)))
    return _dot(d, d)
