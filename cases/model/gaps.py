"""Gaps of leakage nodes to moving blockers, for many (θ, node) pairs at once, with bounds on how fast they change.

Each blocker is placed at θ (time for prescribed motion, the dynamic body's displacement otherwise):

* :class:`RigidPlacement`: a rigid body translated along its axis by s(θ) (a table, a constant velocity or θ
  itself) after a rotation by φ(θ) about an axis through a centre. The query points are moved into the body's
  frame, so one tree serves every pair. A body point moves at most at |ṡ| + |φ̇|·(|x − c| + |s|).
* :class:`DeformingPlacement`: a body whose vertices follow a trajectory (linear between frames); its tree is
  refitted once per distinct θ. Its surface moves at most at the fastest vertex speed of the frame interval.

Leakage nodes move with :class:`NodePath` (fixed, scaled with the cavity mesh, or a trajectory). The gap is the
signed distance (:func:`blockage.sides.signed_distances`): negative inside a closed blocker, so penetration counts
as contact; it is 1-Lipschitz in the relative position, which is what :mod:`cases.model.crossings` needs.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from blockage.sides import signed_distances

__all__ = ["table_values", "table_slopes", "NodePath", "RigidPlacement", "DeformingPlacement", "SelfPlacement",
           "GapField"]


def table_values(table, x) -> np.ndarray:
    """:meth:`cavity.tables.Table.__call__` at many x (piecewise linear; constant or linear ends)."""
    xs, ys = np.asarray(table.x, dtype=float), np.asarray(table.y, dtype=float)
    x = np.asarray(x, dtype=float)
    if len(xs) == 1:
        return np.full(x.shape, ys[0])
    out = np.interp(x, xs, ys)
    if table.extrapolation == "linear":
        lo, hi = x < xs[0], x > xs[-1]
        out[lo] = ys[0] + (x[lo] - xs[0]) * (ys[1] - ys[0]) / (xs[1] - xs[0])
        out[hi] = ys[-1] + (x[hi] - xs[-1]) * (ys[-1] - ys[-2]) / (xs[-1] - xs[-2])
    return out


def table_slopes(table, a: float, b: float) -> float:
    """Largest |slope| of a piecewise-linear table on [a, b] (exact: the table is linear between its rows)."""
    xs, ys = np.asarray(table.x, dtype=float), np.asarray(table.y, dtype=float)
    if len(xs) == 1:
        return 0.0
    slopes = np.abs(np.diff(ys) / np.diff(xs))
    first = max(int(np.searchsorted(xs, a, side="right")) - 1, 0)
    last = min(int(np.searchsorted(xs, b, side="left")), len(slopes))
    inner = slopes[first:max(last, first + 1)]
    out = float(inner.max()) if inner.size else 0.0
    if table.extrapolation == "linear" and (a < xs[0] or b > xs[-1]):
        out = max(out, slopes[0], slopes[-1])
    elif a < xs[0] or b > xs[-1]:
        out = max(out, 0.0)
    return out


@dataclass(frozen=True)
class NodePath:
    """Positions of the leakage nodes at θ: ``x0`` (n, 3) [m] fixed, scaled by ``scale(θ)`` about the origin
    (a cavity mesh with a scale table), or following ``trajectory`` (times (k,), vertices (k, n, 3))."""

    x0: np.ndarray
    scale: object = None  # cavity.tables.Table or None
    trajectory: object = None  # (times, vertices) or None

    def positions(self, thetas, nodes) -> np.ndarray:
        thetas = np.asarray(thetas, dtype=float)
        if self.trajectory is not None:
            times, verts = self.trajectory
            i = np.clip(np.searchsorted(times, thetas, side="right") - 1, 0, len(times) - 2)
            w = np.clip((thetas - times[i]) / (times[i + 1] - times[i]), 0.0, 1.0)[:, None]
            return (1.0 - w) * verts[i, nodes] + w * verts[i + 1, nodes]
        x = self.x0[nodes]
        if self.scale is not None:
            return x * table_values(self.scale, thetas)[:, None]
        return x

    def speeds(self, a: float, b: float, nodes) -> np.ndarray:
        """(k,) bound on each node's speed on [a, b] [m per unit θ] (a, b within one knot interval)."""
        if self.trajectory is not None:
            times, verts = self.trajectory
            i = min(max(int(np.searchsorted(times, 0.5 * (a + b), side="right")) - 1, 0), len(times) - 2)
            inside = times[0] <= 0.5 * (a + b) <= times[-1]
            v = np.linalg.norm(verts[i + 1, nodes] - verts[i, nodes], axis=1) / (times[i + 1] - times[i])
            return v if inside else np.zeros(len(nodes))
        if self.scale is not None:
            return table_slopes(self.scale, a, b) * np.linalg.norm(self.x0[nodes], axis=1)
        return np.zeros(len(nodes))

    def extent(self, a: float, b: float, nodes, centre) -> np.ndarray:
        """(k,) largest distance of each node from ``centre`` on [a, b] [m] (convex in θ: its ends, or bound)."""
        ends = [np.linalg.norm(self.positions(np.full(len(nodes), t), nodes) - centre, axis=1) for t in (a, b)]
        return np.maximum(ends[0], ends[1]) + (b - a) * self.speeds(a, b, nodes)


def _rotations(axis, radians) -> np.ndarray:
    """(k, 3, 3) rotation matrices by ``radians`` (k,) about the unit vector ``axis`` (Rodrigues)."""
    u = np.asarray(axis, dtype=float)
    K = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    s, c = np.sin(radians)[:, None, None], np.cos(radians)[:, None, None]
    return np.eye(3)[None] + s * K[None] + (1.0 - c) * (K @ K)[None]


@dataclass
class RigidPlacement:
    """A rigid blocker: ``blocker`` (blockage.Blocker) in its initial pose, translated by s(θ) along ``axis``
    (``displacement`` a Table, else ``velocity``·θ) after a rotation by ``angle`` (Table [deg]) about
    ``rotation_axis`` through ``centre``; ``open_depth`` as for :func:`blockage.sides.signed_distances`."""

    blocker: object
    axis: tuple
    displacement: object = None
    velocity: float = 0.0
    angle: object = None
    rotation_axis: tuple = (0.0, 0.0, 1.0)
    centre: tuple = (0.0, 0.0, 0.0)
    open_depth: float = 0.0

    def shift(self, thetas) -> np.ndarray:
        return table_values(self.displacement, thetas) if self.displacement is not None else self.velocity * thetas

    def to_local(self, thetas, points) -> np.ndarray:
        """Points [m] at θ moved into the blocker's initial frame."""
        x = points - self.shift(thetas)[:, None] * np.asarray(self.axis)
        if self.angle is None:
            return x
        c = np.asarray(self.centre, dtype=float)
        R = _rotations(self.rotation_axis, np.radians(table_values(self.angle, thetas)))
        return np.einsum("kji,kj->ki", R, x - c) + c

    def signed(self, thetas, points, cutoff, nodes=None) -> np.ndarray:
        return signed_distances(self.blocker, self.to_local(thetas, points), cutoff, self.open_depth)

    def edge_gaps(self, thetas, starts, ends, cutoff) -> np.ndarray:
        """(k,) distance of each segment (at θ) to the blocker's feature edges [m], ``inf`` beyond the cutoff."""
        return self.blocker.edge_distances(self.to_local(thetas, starts), self.to_local(thetas, ends), cutoff)

    def speeds(self, a, b, path: NodePath, nodes) -> np.ndarray:
        ds = table_slopes(self.displacement, a, b) if self.displacement is not None else abs(self.velocity)
        out = np.full(len(nodes), ds) + path.speeds(a, b, nodes)
        if self.angle is not None:
            w = math.radians(table_slopes(self.angle, a, b))
            s_max = float(np.max(np.abs(self.shift(np.array([a, b])))))
            if self.displacement is not None:
                s_max = max(s_max, float(np.max(np.abs(self.displacement.y))))
            out += w * (path.extent(a, b, nodes, np.asarray(self.centre, dtype=float)) + s_max)
        return out


@dataclass
class DeformingPlacement:
    """A blocker whose vertices follow ``trajectory`` (times (k,), vertices (k, m, 3)), linear between frames."""

    blocker: object
    trajectory: tuple
    open_depth: float = 0.0

    def vertices(self, theta: float) -> np.ndarray:
        times, verts = self.trajectory
        i = min(max(int(np.searchsorted(times, theta, side="right")) - 1, 0), len(times) - 2)
        w = min(max((theta - times[i]) / (times[i + 1] - times[i]), 0.0), 1.0)
        return (1.0 - w) * verts[i] + w * verts[i + 1]

    def _per_theta(self, thetas, query) -> np.ndarray:
        """``query(rows)`` with the blocker refitted to its vertices at each distinct θ."""
        out = np.empty(len(thetas))
        unique, which = np.unique(thetas, return_inverse=True)
        for k, theta in enumerate(unique):
            sel = np.flatnonzero(which.ravel() == k)
            self.blocker.refit(self.vertices(theta))
            out[sel] = query(sel)
        return out

    def signed(self, thetas, points, cutoff, nodes=None) -> np.ndarray:
        return self._per_theta(thetas, lambda sel: signed_distances(self.blocker, points[sel], cutoff,
                                                                    self.open_depth))

    def edge_gaps(self, thetas, starts, ends, cutoff) -> np.ndarray:
        return self._per_theta(thetas, lambda sel: self.blocker.edge_distances(starts[sel], ends[sel], cutoff))

    def speeds(self, a, b, path: NodePath, nodes) -> np.ndarray:
        times, verts = self.trajectory
        mid = 0.5 * (a + b)
        if not times[0] <= mid <= times[-1]:
            v = 0.0
        else:
            i = min(max(int(np.searchsorted(times, mid, side="right")) - 1, 0), len(times) - 2)
            v = float(np.max(np.linalg.norm(verts[i + 1] - verts[i], axis=1))) / (times[i + 1] - times[i])
        return v + path.speeds(a, b, nodes)


@dataclass
class SelfPlacement:
    """The cavity's own surface as a blocker of a leakage surface cut from it: ``blocker`` built on the cavity
    mesh, ``ids`` (n,) the mesh vertex of each leakage node (faces holding it are ignored); the mesh scales by
    ``scale`` (a Table) about the origin, or follows ``trajectory`` (times, vertices) of a mesh series."""

    blocker: object
    ids: np.ndarray
    scale: object = None
    trajectory: tuple | None = None

    def signed(self, thetas, points, cutoff, nodes=None) -> np.ndarray:
        if self.trajectory is not None:
            moving = DeformingPlacement(self.blocker, self.trajectory)
            return moving._per_theta(thetas, lambda sel: np.minimum(self.blocker.distances(
                points[sel], cutoff, None, self.ids[nodes[sel]]).distances, cutoff))
        s = table_values(self.scale, thetas) if self.scale is not None else np.ones(len(thetas))
        d = np.empty(len(points))
        for value in np.unique(s):  # one query per scale (mostly one)
            sel = np.flatnonzero(s == value)
            found = self.blocker.distances(points[sel] / value, cutoff / value, None, self.ids[nodes[sel]])
            d[sel] = np.minimum(found.distances * value, cutoff)
        return d

    def edge_gaps(self, thetas, starts, ends, cutoff) -> np.ndarray:
        return np.full(len(starts), np.inf)  # edges of the own surface touch it everywhere: not a contact

    def speeds(self, a, b, path: NodePath, nodes) -> np.ndarray:
        """Both the node and the surface move with the mesh: twice its fastest point."""
        if self.trajectory is not None:
            return 2.0 * DeformingPlacement(self.blocker, self.trajectory).speeds(a, b, NodePath(path.x0), nodes)
        if self.scale is None:
            return np.zeros(len(nodes))
        size = float(np.max(np.linalg.norm(self.blocker.vertices, axis=1)))
        return 2.0 * table_slopes(self.scale, a, b) * size + np.zeros(len(nodes))


@dataclass
class GapField:
    """f_i(θ) = min over blockers of the signed gap − tolerance, for :func:`cases.model.crossings.certified_crossings`.

    ``cutoff`` [m]: gaps are exact up to it and capped there (a capped gap is still 1-Lipschitz). With ``edges``
    ((e, 2) node pairs) a node's gap is also the distance of each of its edges to the blockers' feature edges
    (edge-to-edge contact)."""

    path: NodePath
    placements: list
    tolerance: float
    cutoff: float
    edges: np.ndarray | None = None

    def excess(self, thetas, nodes) -> np.ndarray:
        thetas, nodes = np.asarray(thetas, dtype=float), np.asarray(nodes, dtype=np.int64)
        x = self.path.positions(thetas, nodes)
        g = np.full(len(nodes), self.cutoff)
        for placement in self.placements:
            g = np.minimum(g, placement.signed(thetas, x, self.cutoff, nodes))
        if self.edges is not None and len(self.edges):
            g = np.minimum(g, self._edge_gaps(thetas, nodes))
        return g - self.tolerance

    def _edge_gaps(self, thetas, nodes) -> np.ndarray:
        """(k,) smallest distance of the edges at each (θ, node) pair to the blockers' feature edges [m]."""
        if not hasattr(self, "_incident"):
            e = np.asarray(self.edges)
            ends = np.concatenate([e, e[:, ::-1]])
            order = np.argsort(ends[:, 0], kind="stable")
            self._incident = (np.searchsorted(ends[order, 0], np.arange(len(self.path.x0) + 1)), ends[order, 1])
        start, other = self._incident
        count = start[nodes + 1] - start[nodes]
        pair = np.repeat(np.arange(len(nodes)), count)
        if not pair.size:
            return np.full(len(nodes), self.cutoff)
        offsets = np.arange(pair.size) - np.repeat(np.cumsum(count) - count, count)
        far = other[start[nodes[pair]] + offsets]
        th = thetas[pair]
        a, b = self.path.positions(th, nodes[pair]), self.path.positions(th, far)
        d = np.full(pair.size, self.cutoff)
        for placement in self.placements:
            d = np.minimum(d, placement.edge_gaps(th, a, b, self.cutoff))
        out = np.full(len(nodes), self.cutoff)
        np.minimum.at(out, pair, d)
        return out

    def speed(self, knots):
        def bound(j, nodes):
            a, b = knots[j], knots[j + 1]
            out = np.max([p.speeds(a, b, self.path, nodes) for p in self.placements], axis=0) \
                if self.placements else np.zeros(len(nodes))
            if self.edges is not None and len(self.edges):  # an edge's far end may move faster than the node
                out = out + float(np.max(self.path.speeds(a, b, np.arange(len(self.path.x0))), initial=0.0))
            return out
        return bound
