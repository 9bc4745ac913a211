"""Contact of a dynamic rigid body with the nodes of a fixed seat: gaps, nodal CPRESS, the force on the body.

The laws and their evaluation on the seat's nodes are the numba kernels of :mod:`exchange.contact.laws` (the
compiled path calls the same ones). The body translates along
its unit axis by s [m]; each seat node i has a tributary area A_i [m²] (every face gives A_e/N_e to each of its
N_e nodes, the same split as the blockage rule A_eb = A_e·N_c/N_e) and a gap measured along the axis,

.. math:: g_i(s) = g_{0,i} + \\sigma_i\\, s,

where g_{0,i} is the distance from the node to the body along +axis (σ = +1: moving the body along the axis opens
the gap) or along −axis (σ = −1), found once by casting a ray from the node (exact for any rigid shape). The
overclosure is h_i = −g_i, the approach speed v_rel,i = −σ_i·v, and the seat pushes the body along σ_i·axis with
A_i·p_i. Nodes whose rays miss the body never touch it.

Hard contact has no law: while the body is held on the seat its contact force F_c is the reaction that balances
the other forces, shared by the closed nodes in proportion to their areas (exact for a rigid flat face on a flat
seat: CPRESS = F_c / A_closed at every closed node).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from exchange.contact.definitions import ContactDamping, Hard, LinearPenalty, Softened, law_vector
from exchange.contact.laws import held_side, seat_force, seat_nodal

__all__ = ["SeatContact", "ray_gaps", "nodal_areas", "merged_seat_rows", "STATUS_CODES", "MERGE_ABOVE"]

#: Seats of more nodes than this are summed by the engine over merged rows (:func:`merged_seat_rows`): the same
#: force grouped, rounded once per row instead of compensated over every node, so a body at rest on a soft seat
#: is in equilibrium to one rounding of the force instead of exactly; below it the cost is small anyway.
MERGE_ABOVE = 1000

#: Codes of the per-node status in contact.npz and the VTK series.
STATUS_CODES = {"open": 0, "closed": 1, "VD": 2}


def nodal_areas(surface) -> np.ndarray:
    """Tributary area of every node [m²]: each face gives A_e/N_e to each of its N_e nodes.

    >>> import blockage
    >>> s = blockage.LeakageSurface([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    >>> nodal_areas(s).tolist()
    [0.25, 0.25, 0.25, 0.25]
    """
    out = np.zeros(len(surface.vertices))
    for f, n, a in zip(surface.faces, surface.face_sizes, surface.face_areas):
        out[f[:n]] += a / n
    return out


def ray_gaps(points, directions, triangles) -> np.ndarray:
    """Distance t >= 0 along each ray x + t·d to the first triangle it hits (inf if none), Möller–Trumbore.

    points, directions : (n, 3) float; triangles : (m, 3, 3) float, wound counter-clockwise seen from outside.
    Only front faces count (the ray enters the body there: d·n < 0), so a node lying on a face (t = 0) finds
    the body on one side only.

    >>> tri = np.array([[[-1, -1, 1], [0, 1, 1], [1, -1, 1]]], float)  # normal -z: faces the origin
    >>> ray_gaps(np.zeros((2, 3)), np.array([[0, 0, 1.0], [0, 0, -1.0]]), tri).tolist()
    [1.0, inf]
    """
    out = np.full(len(points), np.inf)
    e1, e2 = triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    size = float(np.max(np.abs(triangles))) if len(triangles) else 1.0
    for k in range(0, len(points), 256):
        x, d = points[k:k + 256, None, :], directions[k:k + 256, None, :]
        p = np.cross(d, e2[None])
        det = np.einsum("nmi,mi->nm", p, e1)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            s = x - triangles[None, :, 0]
            u = np.einsum("nmi,nmi->nm", s, p) * inv
            q = np.cross(s, e1[None])
            v = np.einsum("nmi,nmi->nm", np.broadcast_to(d, q.shape), q) * inv
            t = np.einsum("nmi,mi->nm", q, e2) * inv
            eps = 1e-12
            hit = (det > 1e-300) & (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (t >= -1e-12 * size)
        t = np.where(hit, np.maximum(t, 0.0), np.inf)
        out[k:k + 256] = t.min(axis=1)
    return out


@dataclass
class SeatContact:
    """A body in contact with seat nodes. Arrays are per node: ``g0``, ``sigma``, ``areas`` (see module doc).

    ``mass`` is the body's mass [kg], shared by the touching nodes in proportion to their areas for the critical
    damping fraction (nodal mass m_i = m·A_i/A_seat, A_seat the area of the nodes the body can reach).
    """

    name: str
    body: str
    law: object  # Hard, LinearPenalty or Softened
    damping: ContactDamping | None
    critical_fraction: float | None
    g0: np.ndarray
    sigma: np.ndarray
    areas: np.ndarray
    mass: float
    nodes: np.ndarray  # (n, 3) seat node coordinates [m]
    faces: np.ndarray
    exchange: int | None = None  # index of the exchange whose leakage surface is the seat

    def __post_init__(self):
        reach = np.isfinite(self.g0)
        self.reach = reach
        self.seat_area = float(self.areas[reach].sum())
        self.size = math.sqrt(max(float(self.areas.sum()), 1e-300))
        self.hard = isinstance(self.law, Hard)
        self.table = np.ascontiguousarray(np.column_stack([self.g0, self.sigma, self.areas, reach]), dtype=float)
        self.merged = merged_seat_rows(self.table) if len(self.table) > MERGE_ABOVE else self.table  # the engine's
        self.law_vector = self._law_vector()

    def _law_vector(self) -> np.ndarray:
        """The seat's parameters for :mod:`exchange.contact.laws` (:func:`exchange.contact.definitions.
        law_vector`)."""
        return law_vector(self.law, self.damping, self.critical_fraction, self.mass, self.seat_area, self.size)

    def gaps(self, s: float) -> np.ndarray:
        return self.g0 + self.sigma * s

    def force(self, s: float, v: float) -> float:
        """Force of the seat on the body along the axis [N] (law and damping; hard contact: damping only):
        :func:`exchange.contact.laws.seat_force`."""
        return seat_force(float(s), float(v), self.merged, self.law_vector)

    def held_sigma(self, s: float) -> float:
        """Side σ of the closed nodes of a hard contact (0 if none): :func:`exchange.contact.laws.held_side`."""
        return held_side(float(s), self.table, self.law_vector)

    def nodal(self, s: float, v: float, reaction: float = 0.0) -> tuple:
        """(CPRESS per node [Pa], status code per node) at (s, v); ``reaction`` is a held hard contact's F_c [N]
        (:func:`exchange.contact.laws.seat_nodal`, on the distinct rows of a large seat: :meth:`nodal_rows`)."""
        rows, node_row = self.nodal_rows()
        p, status = seat_nodal(float(s), float(v), float(reaction), rows, self.law_vector)
        return (p, status) if node_row is None else (p[node_row], status[node_row])

    def nodal_rows(self) -> tuple:
        """(one node of each distinct (clearance, side, reach), the row of each node): as for the engine's merged
        rows, a node's status depends on these only and its CPRESS too (the critical damping coefficient per unit
        area does not depend on the area: equal to round-off), so a seat of more than MERGE_ABOVE nodes is
        evaluated once per row. (table, None) for small seats and hard contact (its reaction is shared over the
        closed area, a sum over nodes)."""
        if getattr(self, "_nodal_rows", None) is None:
            if self.hard or len(self.table) <= MERGE_ABOVE:
                self._nodal_rows = (self.table, None)
            else:
                _, first, node_row = np.unique(self.table[:, [0, 1, 3]], axis=0, return_index=True,
                                               return_inverse=True)
                self._nodal_rows = (np.ascontiguousarray(self.table[first]), node_row.ravel())
        return self._nodal_rows

    def thresholds(self) -> np.ndarray:
        """Values of s where the force has a kink or a jump: each distinct g0 reaching touch, c0 (softened),
        the damping clearance and η·c0 (standard style). Hard contact's touch is its seat switch, not a kink."""
        gs = [] if self.hard else [0.0]
        if isinstance(self.law, Softened):
            gs.append(self.law.c0)
        if self.damping is not None and self.damping.style == "standard" and self.damping.c0 > 0:
            gs += [self.damping.c0, self.damping.eta * self.damping.c0]
        out = []
        for sig in (-1.0, 1.0):
            sel = self.reach & (self.sigma == sig)
            for g0 in np.unique(self.g0[sel]):
                out += [(g - g0) / sig for g in set(gs)]
        if not out:
            return np.zeros(0)
        out = np.sort(np.array(out, dtype=float))
        keep = np.diff(out, prepend=-np.inf) > 1e-12 * self.size
        return out[keep]


def merged_seat_rows(table) -> np.ndarray:
    """The seat's node table (n, 4) for the engine with the nodes of equal clearance, side and reach merged into one
    row carrying their summed area, in order of first appearance; unreachable nodes dropped (one kept if all are).

    Exact: a node's contact pressure depends on its clearance and speed only (the critical damping coefficient per
    unit area too: nodal mass and stiffness both scale with the area), so the seat's force Σ σ·A·p is the same sum
    grouped. A flat flange on a flat seat of any node count is then one row, and the right-hand side's cost does not
    grow with the seat's mesh.

    >>> merged_seat_rows(np.array([[0.0, 1.0, 0.5, 1.0], [1e-6, 1.0, 0.25, 1.0], [0.0, 1.0, 0.25, 1.0]])).tolist()
    [[0.0, 1.0, 0.75, 1.0], [1e-06, 1.0, 0.25, 1.0]]
    """
    t = np.asarray(table, dtype=float)
    keep = t[:, 3] != 0.0
    if keep.any():
        t = t[keep]
    else:
        t = t[:1]
    keys = np.ascontiguousarray(t[:, [0, 1, 3]])
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    out = t[first[order]].copy()
    out[:, 2] = np.bincount(rank[inverse], weights=t[:, 2], minlength=len(order))
    return np.ascontiguousarray(out)
