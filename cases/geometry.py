"""Geometry that moves with the bodies: wrapped cavity volume and blocked leakage area along a parameter θ.

θ is time for prescribed motion and the driving body's displacement for a dynamic body. Everything geometric is
computed before integration:

* the cavity volume V(θ) of a mesh whose nodes a convex body would penetrate are placed on the body's surface
  (the closest point, exact), sampled on a grid and interpolated by a C² cubic spline, with dV/dθ from the
  spline;
* for each blocked exchange, the values of θ at which a leakage node's exact gap crosses the contact tolerance
  (found on a grid, then to machine precision by Brent's method on that node's gap), and the leakage area on
  each interval between them (``blockage.evaluate`` at the interval's midpoint). The area is piecewise constant
  in θ, and its jumps are integration breakpoints (prescribed) or switch events (dynamic).
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

import blockage
from cavity.volume import mesh_volume

__all__ = ["Wrapper", "BlockedArea", "WrappedVolume", "blocked_area_track", "GRID_POINTS"]

#: Samples of θ used to find gap crossings and to fit the volume spline.
GRID_POINTS = 401
#: Crossings closer than this fraction of the θ range are one switch.
MERGE_CROSSINGS = 1e-12


def behind_closest_face(points, closest, normals) -> np.ndarray:
    """Which points lie inside a convex body: behind the outward normal of the face holding their closest point.

    points, closest, normals : (n, 3) float
    """
    return np.einsum("ij,ij->i", points - closest, normals) < 0.0


@dataclass
class Wrapper:
    """Places the nodes of a surface that penetrate convex bodies on the bodies' surfaces.

    ``bodies`` is a sequence of Body; ``placed(θ)`` gives each body's (Blocker, 4x4 transform); a deforming
    body's Blocker has been refitted to its vertices at θ (identity transform).
    """

    bodies: list
    placed: object  # callable θ -> list of (Blocker, 4x4 or None)

    def place(self, points: np.ndarray, theta: float) -> np.ndarray:
        """The points after projection of those inside a body onto its surface [m]."""
        out = points.copy()
        for body, (blocker, T) in zip(self.bodies, self.placed(theta)):
            verts = body.vertices_at(theta)
            centre = verts.mean(axis=0)
            radius = float(np.sqrt(np.max(np.sum((verts - centre) ** 2, axis=1))))
            near = np.flatnonzero(np.linalg.norm(out - centre, axis=1) <= radius)
            if not near.size:
                continue
            prox = blocker.distances(out[near], cutoff=2.0 * radius, transform=T)
            if body.deforming:
                tri = verts[body.mesh.faces[prox.faces]]
                normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
            else:
                normals = body.mesh.face_normals[prox.faces] @ T[:3, :3].T
            inside = behind_closest_face(out[near], prox.closest_points, normals)
            out[near[inside]] = prox.closest_points[inside]
        return out


@dataclass
class WrappedVolume:
    """Volume of a closed mesh wrapped around bodies, as a C² spline of θ [m^3]; ``theta_of()`` gives θ now."""

    spline: object
    theta_of: object  # callable t -> θ
    theta_rate: object  # callable t -> dθ/dt
    lo: float
    hi: float
    breakpoints: tuple = ()

    def at(self, theta: float) -> float:
        return float(self.spline(min(max(theta, self.lo), self.hi)))

    def slope(self, theta: float) -> float:
        """dV/dθ (0 outside the sampled range, where nothing touches)."""
        return float(self.spline(theta, 1)) if self.lo <= theta <= self.hi else 0.0

    def __call__(self, t: float) -> float:
        return self.at(self.theta_of(t))

    def rate(self, t: float) -> float:
        return self.slope(self.theta_of(t)) * self.theta_rate(t)


def wrapped_volume(mesh, wrapper: Wrapper, lo: float, hi: float, theta_of, theta_rate, breakpoints=()):
    """Sample the wrapped volume on [lo, hi] and fit the spline.

    Only faces with a moved node change their divergence-theorem term, so each sample costs the projection of
    the nodes near the bodies plus the volume change of their faces.
    """
    grid = np.linspace(lo, hi, GRID_POINTS)
    x0, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    v0 = mesh_volume(x0, faces)
    node_faces = mesh.vertex_faces  # (n, k) padded with -1
    placed = _rigid_placements(wrapper, grid, x0)
    vols = []
    for th, x in zip(grid, placed if placed is not None else (wrapper.place(x0, th) for th in grid)):
        moved = np.flatnonzero(np.any(x != x0, axis=1))
        if not moved.size:
            vols.append(v0)
            continue
        touched = np.unique(node_faces[moved])
        touched = touched[touched >= 0]
        vols.append(v0 + mesh_volume(x, faces[touched]) - mesh_volume(x0, faces[touched]))
    return WrappedVolume(CubicSpline(grid, vols), theta_of, theta_rate, lo, hi, tuple(breakpoints))


def _rigid_placements(wrapper: Wrapper, grid, x0):
    """Node positions of the wrapped mesh at every θ of ``grid`` in one tree query (one rigid body), or None.

    In the body's own frame the body is fixed and the nodes move: all (θ, node) pairs near the body are
    projected together, instead of one query per θ.
    """
    if len(wrapper.bodies) != 1 or wrapper.bodies[0].deforming:
        return None
    body = wrapper.bodies[0]
    blocker = wrapper.placed(grid[0])[0][0]
    T = np.array([body.transform(th) for th in grid])
    sphere = body.mesh.bounding_sphere.primitive
    centres = np.einsum("gij,j->gi", T[:, :3, :3], sphere.center) + T[:, :3, 3]  # world, per θ
    lo, hi = centres.min(axis=0) - sphere.radius, centres.max(axis=0) + sphere.radius
    cand = np.flatnonzero(np.all((x0 >= lo) & (x0 <= hi), axis=1))  # nodes the swept body can reach
    local = np.einsum("gji,gnj->gni", T[:, :3, :3], x0[cand][None] - T[:, None, :3, 3])  # (grid, cand, 3)
    g_idx, c_idx = np.nonzero(np.sum((local - sphere.center) ** 2, axis=2) <= sphere.radius ** 2)
    n_idx = cand[c_idx]
    out = np.broadcast_to(x0, (len(grid),) + x0.shape).copy()
    if g_idx.size:
        pts = local[g_idx, c_idx]
        prox = blocker.distances(pts, cutoff=2.0 * sphere.radius)
        inside = behind_closest_face(pts, prox.closest_points, body.mesh.face_normals[prox.faces])
        g_in, n_in, cp = g_idx[inside], n_idx[inside], prox.closest_points[inside]
        R, t = T[g_in, :3, :3], T[g_in, :3, 3]
        out[g_in, n_in] = np.einsum("kij,kj->ki", R, cp) + t
    return out


@dataclass
class BlockedArea:
    """Leakage area of one exchange, piecewise constant in θ.

    ``crossings`` are sorted θ values where the active set changes; ``areas[i]`` holds on
    [crossings[i-1], crossings[i]) (areas[0] before the first); ``first_active`` is θ of the first contact.
    """

    crossings: np.ndarray
    areas: np.ndarray
    total_area: float
    actives: list = field(default_factory=list)  # active-node count per interval

    def __call__(self, theta: float) -> float:
        return float(self.areas[bisect.bisect_right(self.crossings, theta)])

    def neighbours(self, theta: float) -> tuple:
        """The crossings just below and just above θ (±inf when none)."""
        i = bisect.bisect_right(self.crossings, theta)
        below = self.crossings[i - 1] if i > 0 else -np.inf
        above = self.crossings[i] if i < len(self.crossings) else np.inf
        return below, above


def batched_roots(batched, nodes, a, b, tolerance, cutoff, iterations=200):
    """Roots of gap_i(θ) = tolerance for many (node, bracket) pairs at once (Illinois regula falsi).

    Each iteration evaluates every unresolved pair in one batched query; a pair stops when its bracket is
    within a few ulp. Returns the θ of each pair where the node's status changes.
    """
    a, b = a.astype(float).copy(), b.astype(float).copy()
    fa = np.minimum(batched(a, nodes), cutoff) - tolerance
    fb = np.minimum(batched(b, nodes), cutoff) - tolerance
    side = np.zeros(len(a))
    for _ in range(iterations):
        open_ = np.abs(b - a) > 4.0 * np.finfo(float).eps * np.maximum(np.abs(a), np.abs(b)) + 1e-300
        if not open_.any():
            break
        idx = np.flatnonzero(open_)
        with np.errstate(divide="ignore", invalid="ignore"):
            c = (a[idx] * fb[idx] - b[idx] * fa[idx]) / (fb[idx] - fa[idx])
        bad = ~np.isfinite(c) | (c <= np.minimum(a[idx], b[idx])) | (c >= np.maximum(a[idx], b[idx]))
        c[bad] = 0.5 * (a[idx][bad] + b[idx][bad])
        fc = np.minimum(batched(c, nodes[idx]), cutoff) - tolerance
        left = np.sign(fc) == np.sign(fa[idx])  # root in [c, b]
        i_l, i_r = idx[left], idx[~left]
        a[i_l], fa[i_l] = c[left], fc[left]
        fb[i_l] = np.where(side[i_l] == 1, fb[i_l] / 2, fb[i_l])  # Illinois: halve the stale end
        side[i_l] = 1
        b[i_r], fb[i_r] = c[~left], fc[~left]
        fa[i_r] = np.where(side[i_r] == -1, fa[i_r] / 2, fa[i_r])
        side[i_r] = -1
    return 0.5 * (a + b)


def rigid_batched_gaps(points, bodies, placements, wrapping, cutoff):
    """gap(θ_i) of node i for many (θ_i, node_i) pairs at once, for rigid bodies [m].

    Each query point is moved into the body's own frame (T(θ_i)⁻¹ applied per point), so one tree query
    serves all pairs. With ``wrapping`` the surface wraps the body: a node inside it lies on its surface (gap 0).
    """
    def inside(body, blocker, local):
        """Which local points lie inside the (convex) body: sign of the offset along the closest face normal."""
        sphere = body.mesh.bounding_sphere.primitive
        cand = np.flatnonzero(np.linalg.norm(local - sphere.center, axis=1) <= sphere.radius)
        out = np.zeros(len(local), dtype=bool)
        if cand.size:
            prox = blocker.distances(local[cand], cutoff=2.0 * sphere.radius)
            normals = body.mesh.face_normals[prox.faces]
            out[cand] = behind_closest_face(local[cand], prox.closest_points, normals)
        return out

    def gaps(thetas, nodes):
        x = points[nodes]
        g = np.full(len(x), np.inf)
        unique, which = np.unique(thetas, return_inverse=True)
        for body, blocker in bodies:
            T = np.array([placements(body, th) for th in unique])[which.ravel()]
            local = np.einsum("nji,nj->ni", T[:, :3, :3], x - T[:, :3, 3])
            d = blocker.distances(local, cutoff=cutoff).distances
            if wrapping:
                far = np.flatnonzero(~np.isfinite(d))
                d[far[inside(body, blocker, local[far])]] = 0.0
                near = np.flatnonzero(np.isfinite(d) & (d > 0))
                d[near[inside(body, blocker, local[near])]] = 0.0
            g = np.minimum(g, d)
        return g
    return gaps


def blocked_area_track(surface, node_positions, blockers, tolerance, lo, hi, *, effective_area=None,
                       permeability=0.0, batched=None) -> BlockedArea:
    """Find the gap crossings of every leakage node on θ ∈ [lo, hi] and the leakage area between them.

    Parameters
    ----------
    surface : blockage.LeakageSurface
        The leakage surface at θ = lo (its faces; vertices are given by ``node_positions``).
    node_positions : callable (θ, nodes or None) -> (n, 3)
        Coordinates [m] of the leakage nodes ``nodes`` (all when None) at θ (moved, e.g. wrapped around a body).
    blockers : callable θ -> list of (Blocker, 4x4)
        The blocking bodies placed at θ.
    batched : callable (θ (k,), nodes (k,)) -> gaps (k,), optional
        The same gaps evaluated for many pairs in one query (rigid bodies): used for the grid and the roots.
    tolerance : float
        Contact tolerance [m].
    """
    cutoff = 4.0 * tolerance

    def gaps(theta, nodes=None):
        x = node_positions(theta, nodes)
        g = np.full(len(x), np.inf)
        for blocker, T in blockers(theta):
            g = np.minimum(g, blocker.distances(x, cutoff=cutoff, transform=T).distances)
        return g

    grid = np.linspace(lo, hi, GRID_POINTS)
    if batched is not None:
        n = len(surface.vertices)
        inside = batched(np.repeat(grid, n), np.tile(np.arange(n), len(grid))).reshape(len(grid), n) <= tolerance
    else:
        inside = np.array([gaps(th) <= tolerance for th in grid])  # (grid, nodes)
    pairs = np.argwhere(inside[1:] != inside[:-1])
    if batched is not None and len(pairs):
        roots = list(batched_roots(batched, pairs[:, 1], grid[pairs[:, 0]], grid[pairs[:, 0] + 1], tolerance,
                                   cutoff))
    else:
        roots = []
        for i, node in pairs:
            def excess(th, node=node):  # gap − tolerance, finite beyond the cutoff so Brent's method can use it
                return min(gaps(th, [node])[0], cutoff) - tolerance

            roots.append(brentq(excess, grid[i], grid[i + 1], xtol=1e-15, rtol=8.9e-16))
    crossings = np.sort(roots)
    if len(crossings):  # nodes that cross together (a column of a grid) give roots a few ulp apart: one event
        keep = np.diff(crossings, prepend=-np.inf) > MERGE_CROSSINGS * (hi - lo)
        crossings = crossings[keep]
    edges = np.concatenate([[lo], crossings, [hi]])
    areas, actives = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        mid = 0.5 * (a + b)
        leak = surface.with_vertices(node_positions(mid, None))
        res = blockage.evaluate(leak, blockers(mid), tolerance, effective_area=effective_area,
                                permeability=permeability)
        areas.append(res.leak_area)
        actives.append(int(res.active_nodes.sum()))
    return BlockedArea(crossings, np.array(areas), surface.total_area, actives)
