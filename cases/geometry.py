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


@dataclass
class Wrapper:
    """Places the nodes of a surface that penetrate convex bodies on the bodies' surfaces.

    ``bodies`` is a sequence of (Body, Blocker); ``transforms(θ)`` gives each body's 4x4 placement.
    """

    bodies: list
    transforms: object  # callable θ -> list of 4x4

    def place(self, points: np.ndarray, theta: float) -> np.ndarray:
        """The points after projection of those inside a body onto its surface [m]."""
        out = points.copy()
        for (body, blocker), T in zip(self.bodies, self.transforms(theta)):
            centre = body.mesh.bounding_sphere.primitive.center + T[:3, 3]
            radius = body.mesh.bounding_sphere.primitive.radius
            near = np.flatnonzero(np.linalg.norm(out - centre, axis=1) <= radius)
            if not near.size:
                continue
            prox = blocker.distances(out[near], cutoff=2.0 * radius, transform=T)
            normals = body.mesh.face_normals[prox.faces]  # translation only: normals unchanged
            inside = np.einsum("ij,ij->i", out[near] - prox.closest_points, normals) < 0.0
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
    vols = []
    for th in grid:
        x = wrapper.place(x0, th)
        moved = np.flatnonzero(np.any(x != x0, axis=1))
        if not moved.size:
            vols.append(v0)
            continue
        touched = np.unique(node_faces[moved])
        touched = touched[touched >= 0]
        vols.append(v0 + mesh_volume(x, faces[touched]) - mesh_volume(x0, faces[touched]))
    return WrappedVolume(CubicSpline(grid, vols), theta_of, theta_rate, lo, hi, tuple(breakpoints))


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


def blocked_area_track(surface, node_positions, blockers, tolerance, lo, hi, *, effective_area=None,
                       permeability=0.0) -> BlockedArea:
    """Find the gap crossings of every leakage node on θ ∈ [lo, hi] and the leakage area between them.

    Parameters
    ----------
    surface : blockage.LeakageSurface
        The leakage surface at θ = lo (its faces; vertices are given by ``node_positions``).
    node_positions : callable (θ, nodes or None) -> (n, 3)
        Coordinates [m] of the leakage nodes ``nodes`` (all when None) at θ (moved, e.g. wrapped around a body).
    blockers : callable θ -> list of (Blocker, 4x4)
        The blocking bodies placed at θ.
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
    inside = np.array([gaps(th) <= tolerance for th in grid])  # (grid, nodes)
    roots = []
    for i, node in zip(*np.nonzero(inside[1:] != inside[:-1])):
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
