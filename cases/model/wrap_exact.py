"""The exact volume of a closed mesh wrapped around a translating convex body: a piecewise cubic in s.

Each node moves affinely in s on each of its pieces (:func:`cases.model.wrap_pieces.node_pieces`), so each face's
divergence-theorem term x_a·(x_b × x_c)/6 is a cubic in s between the breakpoints of its three nodes. Every face
whose nodes move contributes the change of its cubic at each of its breakpoints (an event); one sort of all events
and a running sum give V(s) − V(0) exactly as a piecewise cubic, its knots the displacements where the contact set
or a node's nearest body plane changes: O(E log E) for E events, E proportional to the nodes the body reaches.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from cases.model.wrap_pieces import ConvexPlanes, node_pieces
from exchange.engine.arrays import copy_into

__all__ = ["ExactWrap", "exact_wrap"]


class ExactWrap:
    """V(s) − V0 [m^3] as a piecewise cubic: ``breaks`` (M + 1,) [m] increasing, ``coef`` (M, 4) in the variable
    σ = (s − ``mid``)/``half`` (lowest power first), zero outside; ``rounding`` bounds the running sum's error
    [m^3]."""

    def __init__(self, breaks, coef, mid, half, rounding):
        self.breaks, self.coef, self.mid, self.half, self.rounding = breaks, coef, mid, half, rounding

    def piece(self, s, side="right") -> np.ndarray:
        """Index of the piece holding s (the right limit at a break with side "right", else the left); −1 or M
        outside."""
        return np.searchsorted(self.breaks, s, side=side) - 1

    def value(self, s, side="right"):
        """(V − V0, dV/ds) at s [m^3, m^2]: the right or left limit at a break."""
        s = np.asarray(s, dtype=float)
        j = np.where(s == self.breaks[-1], len(self.coef) - 1, np.where(s == self.breaks[0], 0, self.piece(s, side)))
        ok = (j >= 0) & (j < len(self.coef))
        c = self.coef[np.clip(j, 0, max(len(self.coef) - 1, 0))] if len(self.coef) else np.zeros(s.shape + (4,))
        x = (s - self.mid) / self.half
        v = ((c[..., 3] * x + c[..., 2]) * x + c[..., 1]) * x + c[..., 0]
        d = ((3.0 * c[..., 3] * x + 2.0 * c[..., 2]) * x + c[..., 1]) / self.half
        return np.where(ok, v, 0.0), np.where(ok, d, 0.0)


def exact_wrap(planes: ConvexPlanes, vertices, faces, vertex_faces, axis, lo: float, hi: float) -> ExactWrap:
    """The exact wrapped volume change of the closed mesh (``vertices`` (n, 3) [m], ``faces`` (m, 3),
    ``vertex_faces`` (n, k) padded with −1) around the convex body of ``planes`` translated by s ∈ [lo, hi]
    along the unit ``axis`` (the body as its planes were given at s = 0)."""
    a = np.asarray(axis, dtype=float)
    x0 = np.asarray(vertices, dtype=float)
    node, s0, s1, plane = node_pieces(planes, x0, a, lo, hi)
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    if not node.size:
        return ExactWrap(np.array([lo, hi]), np.zeros((1, 4)), mid, half, 0.0)
    o = planes.origin
    n = planes.normals[plane]
    alpha = np.einsum("ij,ij->i", n, x0[node] - o) - planes.offsets[plane]
    beta = n @ a
    # x(s) = x0 − (α − β s) n = u + σ w in σ = (s − mid)/half
    u = x0[node] - o - (alpha - beta * mid)[:, None] * n
    w = (beta * half)[:, None] * n
    ptr = np.searchsorted(node, np.arange(len(x0) + 1)).astype(np.int64)
    touched = np.unique(np.asarray(vertex_faces)[np.unique(node)])
    touched = touched[touched >= 0].astype(np.int64)
    pos, delta = _events(np.asarray(faces, dtype=np.int64), touched, x0 - o, ptr, s0, s1, u, w)
    order = np.argsort(pos, kind="stable")
    pos, delta = pos[order], delta[order]
    total = np.cumsum(delta.astype(np.longdouble), axis=0)
    last = np.r_[np.flatnonzero(pos[1:] != pos[:-1]), len(pos) - 1]
    breaks = np.r_[lo, pos[last], hi] if pos[0] > lo else np.r_[pos[last], hi]
    coef = total[last].astype(float)
    if pos[0] > lo:
        coef = np.vstack([np.zeros((1, 4)), coef])
    return _merged(breaks, coef, mid, half, 4.0 * np.finfo(float).eps * float(np.sum(np.abs(delta)))
                   + float(np.max(np.abs(total[-1]))))


def _merged(breaks, coef, mid, half, rounding) -> ExactWrap:
    """The pieces narrower than 1e-12 of the range dropped (nodes of a symmetric ring reach the body at the same
    s up to rounding), each absorbed by the piece before it; ``rounding`` grows by what that can change."""
    tiny = np.flatnonzero(np.diff(breaks) <= 1e-12 * (breaks[-1] - breaks[0]))
    if not tiny.size:
        return ExactWrap(breaks, coef, mid, half, rounding)
    x = (breaks[:-1] - mid) / half
    slope = np.abs((3.0 * coef[:, 3] * x + 2.0 * coef[:, 2]) * x + coef[:, 1]) / half
    widths = np.diff(breaks)
    rounding += float(np.sum(widths[tiny])) * 2.0 * float(np.max(slope)) * 2.0
    keep = np.ones(len(coef), dtype=bool)
    keep[tiny] = False
    keep[0] |= not keep.any()
    starts = breaks[:-1][keep]
    starts[0] = breaks[0]  # each kept piece runs to the next kept one's start
    return ExactWrap(np.r_[starts, breaks[-1]], coef[keep], mid, half, rounding)


@njit(cache=True)
def _cubic(ua, wa, ub, wb, uc, wc, out):
    """Coefficients (lowest first) of (ua + σ wa)·((ub + σ wb) × (uc + σ wc))/6 into out."""
    out[0] = _triple(ua, ub, uc) / 6.0
    out[1] = (_triple(wa, ub, uc) + _triple(ua, wb, uc) + _triple(ua, ub, wc)) / 6.0
    out[2] = (_triple(ua, wb, wc) + _triple(wa, ub, wc) + _triple(wa, wb, uc)) / 6.0
    out[3] = _triple(wa, wb, wc) / 6.0


@njit(cache=True)
def _triple(a, b, c):
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


@njit(cache=True)
def _state(n, s, x0, ptr, s0, s1, u, w):
    """(u, w) of node n at s (its piece holding s, else its rest position and no motion)."""
    for q in range(ptr[n], ptr[n + 1]):
        if s0[q] <= s < s1[q]:
            return u[q], w[q]
    return x0[n], np.zeros(3)


@njit(cache=True)
def _events(faces, touched, x0, ptr, s0, s1, u, w):
    """For each touched face, at each of its breakpoints, the change of its term's cubic (minus its rest term)."""
    cap = 16 * len(touched) + 16
    pos = np.empty(cap)
    delta = np.empty((cap, 4))
    m = 0
    cur, prev = np.zeros(4), np.zeros(4)
    for t in touched:
        a, b, c = faces[t, 0], faces[t, 1], faces[t, 2]
        rest = _triple(x0[a], x0[b], x0[c]) / 6.0
        nb = 0
        for n in (a, b, c):
            nb += 2 * (ptr[n + 1] - ptr[n])
        bp = np.empty(nb)
        k = 0
        for n in (a, b, c):
            for q in range(ptr[n], ptr[n + 1]):
                bp[k], bp[k + 1] = s0[q], s1[q]
                k += 2
        bp = np.unique(bp)
        prev[:] = 0.0
        for j in range(len(bp)):
            cur[:] = 0.0
            if j + 1 < len(bp):
                sm = 0.5 * (bp[j] + bp[j + 1])
                ua, wa = _state(a, sm, x0, ptr, s0, s1, u, w)
                ub, wb = _state(b, sm, x0, ptr, s0, s1, u, w)
                uc, wc = _state(c, sm, x0, ptr, s0, s1, u, w)
                _cubic(ua, wa, ub, wb, uc, wc, cur)
                cur[0] -= rest
            if m == cap:
                cap *= 2
                pos2, delta2 = np.empty(cap), np.empty((cap, 4))
                copy_into(pos2, pos[:m])
                for i in range(m):
                    copy_into(delta2[i], delta[i])
                pos, delta = pos2, delta2
            pos[m] = bp[j]
            for r in range(4):
                delta[m, r] = cur[r] - prev[r]
                prev[r] = cur[r]
            m += 1
    return pos[:m], delta[:m]
