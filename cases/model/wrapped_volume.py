"""Cavity volume wrapped around moving bodies, along a parameter θ.

θ is time for prescribed motion and the driving body's displacement for a dynamic body. The cavity volume V(θ)
of a mesh whose nodes a convex body would penetrate are placed on the body's surface (the closest point, exact) is
sampled on a grid and interpolated by a C² cubic spline, with dV/dθ from the spline. Leakage areas along θ are
:mod:`cases.model.area_track` (from the certified crossings of :mod:`cases.model.crossings`).
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np

from cavity.volume import mesh_volume, mesh_volumes

__all__ = ["Wrapper", "WrappedVolume", "wrapped_volume", "GRID_POINTS"]

#: Samples of θ used to fit the volume spline.
GRID_POINTS = 401


def _spline(grid, vols):
    """scipy's not-a-knot ``CubicSpline`` of the volumes (imported here: scipy.interpolate is slow to import)."""
    from scipy.interpolate import CubicSpline

    return CubicSpline(grid, vols)


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
    """Volume of a closed mesh wrapped around bodies, as a C² spline of θ [m^3]; ``theta_of()`` gives θ now.

    The compiled engine evaluates the spline itself (:func:`exchange.engine.tables.spline_piece_value`), for a
    θ that is a state on the piece a segment holds (its knots are switches)."""

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


def wrapped_volume(mesh, wrapper: Wrapper, lo: float, hi: float, theta_of, theta_rate, breakpoints=(),
                   knots_in_time: bool = False):
    """Sample the wrapped volume on [lo, hi] and fit the spline; with ``knots_in_time`` (θ is the time: a
    prescribed motion) the spline's knots join the breakpoints.

    The spline is C² only: its third derivative jumps at every knot, which a high-order step straddling it would
    integrate at low order, leaving an error that no tolerance removes (about 3e-8 of the pressure of
    airbag_impactor at rtol 1e-8 … 1e-12). At the knots as stops, each piece is a cubic and the run converges.

    Only faces with a moved node change their divergence-theorem term, so each sample costs the projection of
    the nodes near the bodies plus the volume change of their faces.
    """
    grid = np.linspace(lo, hi, GRID_POINTS)
    if knots_in_time:
        breakpoints = tuple(sorted(set(map(float, breakpoints)) | set(map(float, grid[1:-1]))))
    x0, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    v0 = mesh_volume(x0, faces)
    node_faces = mesh.vertex_faces  # (n, k) padded with -1
    if len(wrapper.bodies) == 1 and not wrapper.bodies[0].deforming:
        T = np.array([wrapper.bodies[0].transform(th) for th in grid])  # the body's pose at every θ
        key = _rigid_key(wrapper.bodies[0], T, grid, x0, faces)
        vols = _RIGID_VOLUMES.get(key)
        if vols is None:
            vols = _volumes_of_placements(_rigid_placements(wrapper, grid, x0, T), x0, faces, node_faces, v0)
            _RIGID_VOLUMES[key] = vols
            while len(_RIGID_VOLUMES) > 8:
                del _RIGID_VOLUMES[next(iter(_RIGID_VOLUMES))]
        return WrappedVolume(_spline(grid, vols), theta_of, theta_rate, lo, hi, tuple(breakpoints))
    vols = []
    for th, x in zip(grid, (wrapper.place(x0, th) for th in grid)):
        moved = np.flatnonzero(np.any(x != x0, axis=1))
        if not moved.size:
            vols.append(v0)
            continue
        touched = np.unique(node_faces[moved])
        touched = touched[touched >= 0]
        vols.append(v0 + mesh_volume(x, faces[touched]) - mesh_volume(x0, faces[touched]))
    return WrappedVolume(_spline(grid, vols), theta_of, theta_rate, lo, hi, tuple(breakpoints))


#: Sampled volumes of one rigid body's placements, keyed by the digest of everything they depend on (the mesh,
#: the body's mesh, its transforms on the grid): the variants of a sweep that leave the geometry alone reuse them.
_RIGID_VOLUMES: dict = {}


def _rigid_key(body, T, grid, x0, faces) -> str:
    """Content digest of one rigid body's wrapping on ``grid``, its poses ``T`` (grid, 4, 4)."""
    digest = hashlib.sha1()
    for a in (x0, faces, grid, T, body.mesh.vertices, body.mesh.faces):
        digest.update(np.ascontiguousarray(a).tobytes())
    return digest.hexdigest()


def _volumes_of_placements(placed, x0, faces, node_faces, v0) -> np.ndarray:
    """V at every θ of ``placed`` = (nodes, (grid, nodes, 3) positions) [m^3]: v0 plus the volume change of the
    faces holding a node that moves anywhere on the grid (a face whose nodes stay put adds exactly 0), all θ in
    one contraction over those faces' vertices only."""
    nodes, positions = placed
    moving = np.any(positions != x0[nodes], axis=(0, 2))
    if not moving.any():
        return np.full(len(positions), v0)
    touched = np.unique(node_faces[nodes[moving]])
    touched = faces[touched[touched >= 0]]
    used, local = np.unique(touched, return_inverse=True)
    local = local.reshape(touched.shape)
    x = np.broadcast_to(x0[used], (len(positions),) + (len(used), 3)).copy()
    x[:, np.searchsorted(used, nodes[moving])] = positions[:, moving]
    return v0 + mesh_volumes(x, local) - mesh_volume(x0, touched)


def _rigid_placements(wrapper: Wrapper, grid, x0, T):
    """Positions of the wrapped mesh's nodes the body can reach, at every θ of ``grid``, in one tree query (one
    rigid body): (node ids, (grid, nodes, 3) positions [m]); every other node stays at x0.

    In the body's own frame the body is fixed and the nodes move: all (θ, node) pairs near the body are
    projected together, instead of one query per θ.
    """
    body = wrapper.bodies[0]
    blocker = wrapper.placed(grid[0])[0][0]
    sphere = body.mesh.bounding_sphere.primitive
    centres = np.einsum("gij,j->gi", T[:, :3, :3], sphere.center) + T[:, :3, 3]  # world, per θ
    lo, hi = centres.min(axis=0) - sphere.radius, centres.max(axis=0) + sphere.radius
    cand = np.flatnonzero(np.all((x0 >= lo) & (x0 <= hi), axis=1))  # nodes the swept body can reach
    local = np.einsum("gji,gnj->gni", T[:, :3, :3], x0[cand][None] - T[:, None, :3, 3])  # (grid, cand, 3)
    g_idx, c_idx = np.nonzero(np.sum((local - sphere.center) ** 2, axis=2) <= sphere.radius ** 2)
    out = np.broadcast_to(x0[cand], (len(grid),) + (len(cand), 3)).copy()
    if g_idx.size:
        pts = local[g_idx, c_idx]
        prox = blocker.distances(pts, cutoff=2.0 * sphere.radius)
        inside = behind_closest_face(pts, prox.closest_points, body.mesh.face_normals[prox.faces])
        g_in, c_in, cp = g_idx[inside], c_idx[inside], prox.closest_points[inside]
        R, t = T[g_in, :3, :3], T[g_in, :3, 3]
        out[g_in, c_in] = np.einsum("kij,kj->ki", R, cp) + t
    return cand, out
