"""Exact contact intervals of points moving on straight segments relative to a fixed triangle mesh.

A rigid blocker that only translates, and a leakage node that is fixed, scaled by a piecewise-linear table or
moved linearly between frames, meet on a knot interval [a, b] of the motion as a point q(t) = P + t·D (t ∈ [0, 1],
θ = a + t·(b − a)) in the blocker's frame. Its distance to a triangle T is ≤ r exactly on

    {t : q(t) ∈ T ⊕ B(r)},

and T ⊕ B(r) is convex, so that set is one interval. T ⊕ B(r) is the union of the *prism* (points whose projection
on T's plane lies in T, within r of the plane) and the three edge *capsules* (segment ⊕ ball); the line meets the
prism on the interval cut by five half-spaces (linear in t) and each capsule on the union of a cylinder piece and
two ball pieces (quadratics in t). The interval is the hull of those pieces: closed forms, no sampling. Quadratics
are solved about the point of closest approach (t* first, then the small offset), so a root is accurate to a few
ulp of t even when |q − E| ≫ r.

With r = 0 the same pieces give the instants (or, sliding in the face plane, the intervals) where the point
touches the surface: contact at gap 0.

>>> tri = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
>>> lo, hi = triangle_intervals(np.array([[-1.0, 0.25, 0.5]]), np.array([[2.0, 0.0, 0.0]]), tri, 0.5)
>>> float(lo[0]), float(hi[0])
(0.5, 0.875)
"""
from __future__ import annotations

import numpy as np

__all__ = ["triangle_intervals", "candidate_rows", "EMPTY"]

#: lo > hi marks an empty interval.
EMPTY = (np.inf, -np.inf)


def _dot(u, v):
    return u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1] + u[:, 2] * v[:, 2]


def _cross(u, v):
    return np.stack([u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1], u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2],
                     u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]], axis=1)


def _clip(lo, hi, alpha, beta):
    """Intersect [lo, hi] with {t : alpha + beta·t ≥ 0} in place."""
    with np.errstate(divide="ignore", invalid="ignore"):
        root = -alpha / beta
    up, down, flat = beta > 0, beta < 0, beta == 0
    lo[up] = np.maximum(lo[up], root[up])
    hi[down] = np.minimum(hi[down], root[down])
    bad = (flat & (alpha < 0)) | (lo > hi)
    lo[bad], hi[bad] = EMPTY


def _within(w0, D, r, axis=None):
    """[lo, hi] of {t : |w0 + t·D|⊥ ≤ r}, distances taken perpendicular to the unit ``axis`` (None: full).

    The quadratic a·τ² + 2b·τ + c about t* (closest approach) has a small b and c, so the roots are accurate."""
    if axis is not None:
        w0 = w0 - _dot(w0, axis)[:, None] * axis
        D = D - _dot(D, axis)[:, None] * axis
    a = _dot(D, D)
    moving = a > 0
    t_star = np.where(moving, -_dot(w0, D) / np.where(moving, a, 1.0), 0.0)
    wc = w0 + t_star[:, None] * D
    if axis is not None:
        wc = wc - _dot(wc, axis)[:, None] * axis
    b, c = _dot(wc, D), _dot(wc, wc) - r * r
    disc = b * b - a * c
    lo, hi = np.full(len(a), EMPTY[0]), np.full(len(a), EMPTY[1])
    ok = moving & (disc >= 0)
    s = np.sqrt(np.where(ok, disc, 0.0))
    q = -(b + np.where(b >= 0, s, -s))  # stable roots: q/a and c/q
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.where(ok, q / np.where(moving, a, 1.0), 0.0)
        r2 = np.where(ok & (q != 0), c / np.where(q != 0, q, 1.0), r1)
    lo[ok] = t_star[ok] + np.minimum(r1, r2)[ok]
    hi[ok] = t_star[ok] + np.maximum(r1, r2)[ok]
    still = ~moving & (c <= 0)  # not moving (across the axis): in for all t, or never
    lo[still], hi[still] = -np.inf, np.inf
    return lo, hi


def _hull(lo, hi, lo2, hi2):
    """Hull of two intervals (either may be empty), in place into (lo, hi)."""
    full = lo2 <= hi2
    lo[full] = np.minimum(lo[full], lo2[full])
    hi[full] = np.maximum(hi[full], hi2[full])


def _prism(P, D, tri, r, lo, hi):
    """Clip [lo, hi] to the line's interval in T's prism of half-height r (degenerate faces: empty)."""
    A, B, C = tri[:, 0], tri[:, 1], tri[:, 2]
    n = _cross(B - A, C - A)
    length = np.sqrt(_dot(n, n))
    lo[length == 0], hi[length == 0] = EMPTY
    n = n / np.where(length > 0, length, 1.0)[:, None]
    h0, dh = _dot(n, P - A), _dot(n, D)
    _clip(lo, hi, r - h0, -dh)
    _clip(lo, hi, r + h0, dh)
    for v0, v1, v2 in ((A, B, C), (B, C, A), (C, A, B)):
        m = _cross(n, v1 - v0)
        m = np.where((_dot(m, v2 - v0) < 0)[:, None], -m, m)
        _clip(lo, hi, _dot(m, P - v0), _dot(m, D))


def triangle_intervals(P, D, tri, r, prism_only=False):
    """(lo, hi) (k,): the t ∈ [0, 1] where dist(P + t·D, T) ≤ r, exactly (lo > hi: never).

    Parameters
    ----------
    P, D : (k, 3) float
        Start [m] and displacement over the segment [m], in the triangle's frame.
    tri : (k, 3, 3) float
        Triangle corners [m].
    r : float
        Distance [m], ≥ 0 (0: touching).
    prism_only : bool
        Only the prism piece (the points whose projection lies on T): where a point passes an edge's side wall.
    """
    k = len(P)
    lo, hi = np.zeros(k), np.ones(k)
    _prism(P, D, tri, r, lo, hi)
    if not prism_only:
        for v0, v1 in ((tri[:, 0], tri[:, 1]), (tri[:, 1], tri[:, 2]), (tri[:, 2], tri[:, 0])):
            _capsule(P, D, v0, v1, r, lo, hi)
    lo, hi = np.maximum(lo, 0.0), np.minimum(hi, 1.0)
    empty = lo > hi
    lo[empty], hi[empty] = EMPTY
    return lo, hi


def _capsule(P, D, v0, v1, r, lo, hi):
    """Hull [lo, hi] with the line's interval in the capsule of edge v0 v1 of radius r."""
    e = v1 - v0
    ee = _dot(e, e)
    for v in (v0, v1):
        _hull(lo, hi, *_within(P - v, D, r))
    good = ee > 0
    if not good.any():
        return
    axis = e / np.sqrt(np.where(good, ee, 1.0))[:, None]
    clo, chi = _within(P - v0, D, r, axis)
    w0e, De = _dot(P - v0, e), _dot(D, e)
    _clip(clo, chi, w0e, De)
    _clip(clo, chi, ee - w0e, -De)
    clo[~good], chi[~good] = EMPTY
    _hull(lo, hi, clo, chi)


def candidate_rows(P, D, vertices, faces, reach, chunk=128):
    """(segment (m,), face (m,)) pairs whose bounding boxes, the segment's grown by ``reach`` [m], overlap.

    Segments go in chunks of ``chunk``; each chunk tests only the faces that meet the chunk's own box (node ids
    are spatially coherent, so a chunk's box is small), so the cost is about segments × faces near them."""
    tri = vertices[faces]
    flo, fhi = tri.min(axis=1), tri.max(axis=1)
    slo = np.minimum(P, P + D) - reach
    shi = np.maximum(P, P + D) + reach
    seg, face = [np.zeros(0, np.int64)], [np.zeros(0, np.int64)]
    for start in range(0, len(P), chunk):
        s = slice(start, start + chunk)
        near = np.flatnonzero(np.all((slo[s].min(axis=0) <= fhi) & (shi[s].max(axis=0) >= flo), axis=1))
        if not near.size:
            continue
        hit = np.all((slo[s, None] <= fhi[near][None]) & (shi[s, None] >= flo[near][None]), axis=2)
        i, f = np.nonzero(hit)
        seg.append(i + start)
        face.append(near[f])
    return np.concatenate(seg), np.concatenate(face)
