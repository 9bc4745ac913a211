"""Cavity volume wrapped around moving bodies, along a parameter θ.

θ is time for prescribed motion and the driving body's displacement for a dynamic body. The cavity volume V(θ)
of a mesh whose nodes a convex body would penetrate are placed on the body's surface (the closest point, exact).
For one convex body in translation V is computed exactly as a piecewise cubic of the displacement
(:mod:`cases.model.wrap_exact`) and represented by an adaptive piecewise cubic with a proven error bound
(:mod:`cases.model.wrap_fit`); otherwise it is sampled on a grid and interpolated by a C² cubic spline, with
dV/dθ from the spline. Leakage areas along θ are :mod:`cases.model.area_track` (from the certified crossings of
:mod:`cases.model.crossings`).
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
    bound: float = float("nan")  # [m^3] largest distance to the exact wrapped volume (nan: sampled, unknown)

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
    """The wrapped volume on [lo, hi]; with ``knots_in_time`` (θ is the time: a prescribed motion) the spline's
    knots join the breakpoints.

    One convex body in translation (a dynamic body, or a prescribed displacement without rotation): the exact
    piecewise cubic V(s) in O(N log N) for N nodes reached (:mod:`cases.model.wrap_exact`) and its adaptive fit
    with a proven bound (:mod:`cases.model.wrap_fit`), composed with s(t) for a prescribed motion (a cubic of a
    piecewise-linear s(t) is a cubic between knots). Otherwise V is sampled on a grid and fitted by a C² spline:

    The spline is C² only: its third derivative jumps at every knot, which a high-order step straddling it would
    integrate at low order, leaving an error that no tolerance removes (about 3e-8 of the pressure of
    airbag_impactor at rtol 1e-8 … 1e-12). At the knots as stops, each piece is a cubic and the run converges.

    Only faces with a moved node change their divergence-theorem term, so each sample costs the projection of
    the nodes near the bodies plus the volume change of their faces.
    """
    fast = (_translating_convex(mesh, wrapper, lo, hi, theta_of, theta_rate, breakpoints, knots_in_time)
            if EXACT_TRANSLATION else None)
    if fast is not None:
        return fast
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


def _translating_convex(mesh, wrapper, lo, hi, theta_of, theta_rate, breakpoints, knots_in_time):
    """The exact-and-fitted WrappedVolume of one convex body in pure translation, else None."""
    from cases.model.fit_cache import load_fit, store_fit
    from cases.model.wrap_exact import exact_wrap
    from cases.model.wrap_fit import fit_wrap, in_time
    from cases.model.wrap_pieces import WalkError, convex_planes

    if len(wrapper.bodies) != 1:
        return None
    body = wrapper.bodies[0]
    motion = body.motion
    if body.deforming or getattr(motion, "rotation_table", None) is not None:
        return None
    x0, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    if knots_in_time:
        times = np.unique(np.r_[lo, hi, [t for t in breakpoints if lo < t < hi]])
        s = np.array([motion.displacement(t) for t in times])
        s_lo, s_hi = float(s.min()), float(s.max())
    else:
        s_lo, s_hi = lo, hi
    span = max(s_hi - s_lo, 1e-9 * max(float(np.linalg.norm(body.mesh.extents)), 1e-3))
    s_hi = s_lo + span
    key = _rigid_key(body, np.array([s_lo, s_hi]), np.asarray(body.axis, dtype=float), x0, faces)
    stored = f"{key}|{FIT_TOLERANCE!r}|{RING!r}|{JUMP_WIDTH!r}"  # on disk: the fit's settings too
    found = _FITS.get(key) or load_fit(stored)
    if found is None:
        planes = convex_planes(body.mesh.vertices, body.mesh.faces)
        if planes is None:
            return None
        try:
            exact = exact_wrap(planes, x0, faces, mesh.vertex_faces, body.axis, s_lo, s_hi)
        except WalkError:
            return None
        v0 = mesh_volume(x0, faces)
        width = JUMP_WIDTH * float(body.mesh.edges_unique_length.mean())
        found = (fit_wrap(exact, FIT_TOLERANCE * abs(v0), RING * _peak_slope(exact), width), v0)
        store_fit(stored, *found)
    if key not in _FITS:
        _FITS[key] = found
        while len(_FITS) > 8:
            del _FITS[next(iter(_FITS))]
    fit, v0 = found
    if knots_in_time:
        spline = in_time(fit, breakpoints, motion.displacement, lo, hi, v0)
        brk = tuple(sorted(set(map(float, breakpoints)) | set(map(float, spline.x[1:-1]))))
        return WrappedVolume(spline, theta_of, theta_rate, lo, hi, brk, fit.bound)
    return WrappedVolume(fit.ppoly(v0), theta_of, theta_rate, lo, hi, tuple(breakpoints), fit.bound)


def _peak_slope(exact) -> float:
    return float(np.max(np.abs(exact.value(exact.breaks)[1]), initial=0.0))


#: Fit of the exact volume: its tolerance relative to the cavity's volume, the slope overshoot allowed on a
#: piece relative to the peak |dV/ds|, and the width over which a jump of V is spread (a node switching to the
#: next facet of the body), relative to the body's mean edge length.
FIT_TOLERANCE, RING, JUMP_WIDTH = 1e-7, 1e-6, 1.0
#: Fits (and the cavity's V0) keyed by the digest of the meshes, the axis and the range of s: a sweep's variants
#: that leave the geometry alone reuse them; on disk too, for the next process (:mod:`cases.model.fit_cache`).
_FITS: dict = {}
#: The exact path for one convex body in translation (False: the sampled spline, for comparisons).
EXACT_TRANSLATION = True

#: Sampled volumes of one rigid body's placements, keyed by the digest of everything they depend on (the mesh,
#: the body's mesh, its transforms on the grid): the variants of a sweep that leave the geometry alone reuse them.
_RIGID_VOLUMES: dict = {}


def _rigid_key(body, T, grid, x0, faces) -> str:
    """Content digest of one rigid body's wrapping on ``grid``, its poses ``T`` (grid, 4, 4) (or of its range of
    s and its axis)."""
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
