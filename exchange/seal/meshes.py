"""Seal-surface meshes made here, for examples, tests and benchmarks: rings of quads or triangles.

>>> v, f = annulus_mesh(0.01, 0.02, 2, 8, triangles=True)
>>> v.shape, f.shape
((24, 3), (32, 3))
"""
from __future__ import annotations

import numpy as np

__all__ = ["annulus_mesh", "annulus_delaunay", "flat_flange_seat"]


def annulus_mesh(r_inner, r_outer, n_radial, n_angular, triangles=False, radii=None):
    """Structured ring in the plane z = 0: ``n_radial`` element rows between radii ``r_inner`` and ``r_outer``
    [m] (or the node ``radii`` given), ``n_angular`` elements around; quads (nodes counter-clockwise seen from +z),
    or each quad split into two triangles along alternating diagonals.

    Returns (vertices (n, 3), faces (m, 4) or (m, 3)); node (i, j) (radius i, angle j) has index i·n_angular + j.
    """
    r = np.linspace(r_inner, r_outer, n_radial + 1) if radii is None else np.asarray(radii, float)
    theta = np.linspace(0.0, 2.0 * np.pi, n_angular, endpoint=False)
    rr, tt = np.meshgrid(r, theta, indexing="ij")
    vertices = np.c_[(rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel(), np.zeros(rr.size)]
    i, j = np.meshgrid(np.arange(len(r) - 1), np.arange(n_angular), indexing="ij")
    a = (i * n_angular + j).ravel()
    b = (i * n_angular + (j + 1) % n_angular).ravel()
    c, d = b + n_angular, a + n_angular
    if not triangles:
        return vertices, np.c_[a, b, c, d]
    flip = ((i + j) % 2 == 0).ravel()
    first = np.where(flip[:, None], np.c_[a, b, c], np.c_[a, b, d])
    second = np.where(flip[:, None], np.c_[a, c, d], np.c_[b, c, d])
    return vertices, np.concatenate([first, second])


def annulus_delaunay(r_inner, r_outer, n_boundary, n_interior, seed=0):
    """Unstructured triangles of a ring: ``n_boundary`` nodes on each circle (jittered by 0.3 spacing), ``n_interior``
    random nodes between, Delaunay triangulation (scipy) without the triangles of the hole.

    The boundary segments are chords; the film's polar chart maps them to the exact circles.

    Returns (vertices (n, 3), faces (m, 3), inner node indices, outer node indices).
    """
    from scipy.spatial import Delaunay

    rng = np.random.default_rng(seed)
    even = np.linspace(0.0, 2.0 * np.pi, n_boundary, endpoint=False)
    step = 2.0 * np.pi / n_boundary
    t_in = even + rng.uniform(-0.3, 0.3, n_boundary) * step
    t_out = even + rng.uniform(-0.3, 0.3, n_boundary) * step + 0.5 * step
    inner_limit = r_inner + 0.3 * step * r_inner
    outer_limit = r_outer * np.cos(0.8 * step) - 0.3 * step * r_inner  # inside every chord of the outer circle
    r = np.sqrt(rng.uniform(inner_limit ** 2, outer_limit ** 2, n_interior))
    t = rng.uniform(0.0, 2.0 * np.pi, n_interior)
    xy = np.concatenate([np.c_[r_inner * np.cos(t_in), r_inner * np.sin(t_in)],
                         np.c_[r_outer * np.cos(t_out), r_outer * np.sin(t_out)], np.c_[r * np.cos(t), r * np.sin(t)]])
    tri = Delaunay(xy).simplices
    tri = tri[~np.all(tri < n_boundary, axis=1)]  # the hole: no point lies in it, so its triangles join 3 inner nodes
    vertices = np.c_[xy, np.zeros(len(xy))]
    return vertices, tri, np.arange(n_boundary), np.arange(n_boundary, 2 * n_boundary)


def flat_flange_seat(vertices, areas, clearance, slope=0.0):
    """Seat table (n, 4) of :mod:`exchange.contact.laws` for a rigid flat flange above a z = 0 seal face, moving
    down (−z) by s: g_i = clearance + slope·y_i − s (σ = −1), tributary ``areas`` (n,) [m²], every node reachable.

    >>> flat_flange_seat(np.array([[0.0, 0.01, 0.0]]), np.array([1e-6]), 2e-6, slope=1e-4).tolist()
    [[3e-06, -1.0, 1e-06, 1.0]]
    """
    v = np.asarray(vertices, float)
    return np.c_[clearance + slope * v[:, 1], -np.ones(len(v)), np.asarray(areas, float), np.ones(len(v))]
