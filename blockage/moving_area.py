"""The leakage area of a surface whose nodes move linearly in time between frames (a vertex trajectory, a mesh
series), with a fixed set of active nodes: the one evaluation both integration paths use.

On frame interval k, [t_k, t_{k+1}], with w = (t − t_k)/(t_{k+1} − t_k) clipped to [0, 1] (the nodes are held
beyond the first and last frames), every node moves as x = x_k + w (x_{k+1} − x_k). A face's area is half the norm
of the cross product of two edge vectors (a triangle's AB × AC, a quad's diagonals AC × BD,
:func:`blockage.areas.face_areas`), each linear in w, so the cross product is a quadratic in w:

.. math::  A_e(w) = \\tfrac12 \\lVert \\mathbf a_e + \\mathbf b_e w + \\mathbf c_e w^2 \\rVert,\\qquad
           \\mathbf a = u_0 \\times v_0,\\ \\mathbf b = u_0 \\times \\delta v + \\delta u \\times v_0,\\
           \\mathbf c = \\delta u \\times \\delta v

(u, v the two edge vectors, δ their change over the interval). The face's blocked area is A_e·N_c/N_e with its
N_c active nodes (:func:`blockage.areas.blocked_face_areas`), and the leakage area follows
:func:`blockage.areas.leak_area_of` from the total and the obstruction at t: exact at every instant, not only at
frames.

Everything is packed in one float64 array (:func:`pack`) so that a numba right-hand side can hold it in a table:

``[frames K, faces m, intervals, effective area (NaN: none), permeability, cursor, crossings c, nodes n]``, then
the frame times (K,), the coefficients ((K − 1)·m·9: per interval and face a, b, c), the face sizes N_e (m,), the
active-node counts N_c of each face at the cursor's interval (m,, updated in place), per interval of the active
set the number of crossings applied (intervals,), per crossing its node and its change of state (+1, −1, 0)
(c, c), and the faces of each node (CSR: starts (n + 1,), faces). Moving the cursor from one interval to another
replays the crossings between them (O(crossings passed)), so the pack holds O(K·m + c) numbers, not a copy of the
active set per interval. The cursor makes a pack state: one pack per thread (each model has its own; the compiled
path copies it into its tables).
"""
from __future__ import annotations

import math

import numpy as np

from blockage._jit import njit
from blockage.areas import edge_vectors, leak_area_of

__all__ = ["area_coefficients", "pack", "moving_areas", "moving_leak_area", "moving_frame_times", "HEADER"]

#: Header length of a pack.
HEADER = 8


def area_coefficients(times, vertices, faces, face_sizes) -> np.ndarray:
    """(K − 1, m, 9) the cross-product coefficients a, b, c of every face on every frame interval.

    Parameters
    ----------
    times : (K,) float
        Frame times [s], increasing.
    vertices : (K, n, 3) float
        Node positions at the frames [m].
    faces : (m, 4) int
        Vertex ids, triangles padded with -1.
    face_sizes : (m,) int
        3 or 4.

    >>> v0 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    >>> c = area_coefficients([0.0, 1.0], np.stack([v0, 2 * v0]), np.array([[0, 1, 2, -1]]), np.array([3]))
    >>> c[0, 0].tolist()   # (1 + w)^2 e_z: a = e_z, b = 2 e_z, c = e_z
    [0.0, 0.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0]
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    out = np.empty((len(times) - 1, len(faces), 9))
    for k in range(len(times) - 1):
        u0, v0 = edge_vectors(vertices[k], faces, face_sizes)
        u1, v1 = edge_vectors(vertices[k + 1], faces, face_sizes)
        du, dv = u1 - u0, v1 - v0
        out[k, :, 0:3] = np.cross(u0, v0)
        out[k, :, 3:6] = np.cross(u0, dv) + np.cross(du, v0)
        out[k, :, 6:9] = np.cross(du, dv)
    return out


def pack(times, coefficients, faces, face_sizes, initial, applied, node, delta, effective_area=None,
         permeability=0.0) -> np.ndarray:
    """One float64 array holding a moving surface's area (layout in the module docstring).

    Parameters
    ----------
    times : (K,) float
        Frame times [s].
    coefficients : (K − 1, m, 9) float
        :func:`area_coefficients`.
    faces : (m, 4) int
        Vertex ids, triangles padded with -1.
    face_sizes : (m,) int
        3 or 4.
    initial : (n,) bool
        Active nodes in interval 0.
    applied : (intervals,) int
        Crossings applied in each interval of the active set (0 in the first, non-decreasing).
    node, delta : (c,) int
        Per crossing (in order) its node and its change of state (+1 becomes active, −1 released, 0 none).
    effective_area : float or None
        [m^2] (:func:`blockage.areas.leak_area`).
    permeability : float
        Fraction of a blocked area that still leaks [-].
    """
    faces = np.asarray(faces, dtype=np.int64)
    sizes = np.asarray(face_sizes, dtype=np.int64)
    n = len(initial)
    counts = np.zeros(len(faces))
    owners = [[] for _ in range(n)]
    for e in range(len(faces)):
        for corner in range(sizes[e]):
            counts[e] += bool(initial[faces[e, corner]])
            owners[faces[e, corner]].append(e)
    starts = np.concatenate([[0], np.cumsum([len(o) for o in owners])])
    flat = [e for o in owners for e in o]
    eff = math.nan if effective_area is None else float(effective_area)
    head = [len(times), len(faces), len(applied), eff, float(permeability), 0.0, len(node), n]
    return np.concatenate([np.asarray(head, dtype=float), np.asarray(times, dtype=float),
                           np.asarray(coefficients, dtype=float).ravel(), sizes.astype(float), counts,
                           np.asarray(applied, dtype=float), np.asarray(node, dtype=float),
                           np.asarray(delta, dtype=float), starts.astype(float), np.asarray(flat, dtype=float)])


def moving_frame_times(p) -> np.ndarray:
    """(K,) the frame times [s] of pack p (a copy)."""
    return np.array(p[HEADER:HEADER + int(p[0])])


@njit(inline="always")
def _offsets(p):
    """Start of each section of pack p: times, coefficients, sizes, counts, applied, node, delta, starts, faces."""
    K, m, ni, c, n = int(p[0]), int(p[1]), int(p[2]), int(p[6]), int(p[7])
    times = HEADER
    coef = times + K
    sizes = coef + (K - 1) * m * 9
    counts = sizes + m
    applied = counts + m
    node = applied + ni
    delta = node + c
    starts = delta + c
    return times, coef, sizes, counts, applied, node, delta, starts, starts + n + 1


@njit
def _move_to(p, i):
    """Set the active-node counts of pack p to interval i of the active set (crossings replayed)."""
    _, _, _, counts, applied, node, delta, starts, faces = _offsets(p)
    cur = int(p[5])
    if cur == i:
        return
    k_now, k = int(p[applied + cur]), int(p[applied + i])
    sign, lo, hi, step = (1.0, k_now, k, 1) if k > k_now else (-1.0, k_now - 1, k - 1, -1)
    for q in range(lo, hi, step):
        d = sign * p[delta + q]
        if d != 0.0:
            nd = int(p[node + q])
            for f in range(int(p[starts + nd]), int(p[starts + nd + 1])):
                p[counts + int(p[faces + f])] += d
    p[5] = float(i)


@njit
def moving_areas(p, i, t):
    """(total area, obstruction) [m^2] of pack p at time t [s] with the active set of interval i (i < 0: none
    active); the obstruction is Σ_e A_e(t)·N_c/N_e, at most the total.

    >>> v0 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    >>> frames = np.stack([v0, 2 * v0])
    >>> faces, sizes = np.array([[0, 1, 2, -1]]), np.array([3])
    >>> p = pack([0.0, 1.0], area_coefficients([0.0, 1.0], frames, faces, sizes), faces, sizes,
    ...          np.array([True, False, False]), np.array([0]), np.zeros(0), np.zeros(0))
    >>> moving_areas(p, 0, 0.5)   # (1.5)^2 / 2 and a third of it
    (1.125, 0.375)
    """
    times, coef, sizes, counts, _, _, _, _, _ = _offsets(p)
    if i >= 0:
        _move_to(p, i)
    K, m = int(p[0]), int(p[1])
    k = np.searchsorted(p[times:times + K], t, side="right") - 1
    k = min(max(k, 0), K - 2)
    t0, t1 = p[times + k], p[times + k + 1]
    w = min(max((t - t0) / (t1 - t0), 0.0), 1.0)
    total, obstruction = 0.0, 0.0
    for e in range(m):
        q = coef + (k * m + e) * 9
        x = p[q] + w * (p[q + 3] + w * p[q + 6])
        y = p[q + 1] + w * (p[q + 4] + w * p[q + 7])
        z = p[q + 2] + w * (p[q + 5] + w * p[q + 8])
        a = 0.5 * math.sqrt(x * x + y * y + z * z)
        total += a
        if i >= 0 and p[counts + e] > 0.0:
            obstruction += a * (p[counts + e] / p[sizes + e])  # the ratio first: a blocked face gives A_e exactly
    return total, min(obstruction, total)


@njit
def moving_leak_area(p, i, t):
    """Leakage area [m^2] of pack p at time t [s] with the active set of interval i (i < 0: none active),
    :func:`blockage.areas.leak_area_of` of :func:`moving_areas`, never below zero.

    >>> v0 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    >>> faces, sizes = np.array([[0, 1, 2, -1]]), np.array([3])
    >>> p = pack([0.0, 1.0], area_coefficients([0.0, 1.0], np.stack([v0, 2 * v0]), faces, sizes), faces, sizes,
    ...          np.array([True, False, False]), np.array([0, 1]), np.array([1]), np.array([1]), 1e-4)
    >>> round(moving_leak_area(p, 0, 0.5), 12), round(moving_leak_area(p, 1, 0.5), 12)   # 1 then 2 of 3 nodes
    (6.7e-05, 3.3e-05)
    """
    total, obstruction = moving_areas(p, i, t)
    return max(leak_area_of(total, obstruction, p[3], p[4]), 0.0)
