"""Crossings of leakage nodes under a rotating rigid blocker: chords with a certified deviation.

In a rotating blocker's frame a node does not move on a segment but on an arc: q(θ) = Rᵀ(φ(θ))·y(θ) + c with
y(θ) = x(θ) − s(θ)·axis − c linear and φ linear on a knot interval. Its second derivative is bounded,

    |q''| ≤ M = φ̇²·max|y| + 2·|φ̇|·|ẏ|,

so on a sub-interval of length h the arc stays within δ = M·h²/8 of its chord (linear interpolation error). The
distance is 1-Lipschitz, so with the exact chord intervals of :mod:`cases.model.segment_contact` at radii
tolerance − δ and tolerance + δ, the node is certainly in contact where the first covers it, certainly not within
the tolerance where the second does not (then the gap's sign at the midpoint decides, as for a translation), and
uncertain only in between: a band of width ~δ/v around each entry and exit. The bands are solved again with
shorter chords (δ smaller by :data:`SHRINK` per pass, :data:`LEVELS` passes) until they are narrower than the
search's resolution h_min; then the crossing is bracketed by the true gap at the band's ends and located by regula
falsi, which is the bisection's own guarantee. A band still wider (a node whose gap hovers within δ of the
tolerance) is reported as uncertain, with its length. The first chords are made short enough that
δ ≤ :data:`DEVIATION`·tolerance, at most :data:`MAX_CHORDS` per node interval.
"""
from __future__ import annotations

import math

import numpy as np

from cases.model.crossings import RESOLUTION, batched_roots
from cases.model.exact_crossings import flips
from cases.model.gaps import RigidPlacement, table_slopes
from cases.model.segment_contact import candidate_rows, triangle_intervals

__all__ = ["chord_solver", "DEVIATION", "MAX_CHORDS"]

#: Largest deviation of an arc from its chord, as a fraction of the contact tolerance [-].
DEVIATION = 1e-3
#: Most chords per (node, knot interval) pair.
MAX_CHORDS = 512
#: Passes over the bands left wider than the search's resolution, each with chords of SHRINK times the deviation.
LEVELS = 4
SHRINK = 1e-4


def chord_solver(field, knots):
    """callable (j, nodes, in at knots[j], in at knots[j+1]) -> (θ, node, state after, uncertain length per node)
    for rigid blockers some of which rotate; None for other fields (deforming, edge contact, self-contact, an
    open sheet with a penetration depth)."""
    if field.edges is not None and len(field.edges):
        return None
    if not all(isinstance(p, RigidPlacement) and not p.open_depth for p in field.placements):
        return None
    knots = np.asarray(knots, dtype=float)
    h_min = RESOLUTION * (knots[-1] - knots[0])

    def solve(j, nodes, start, end):
        a, b = float(knots[j]), float(knots[j + 1])
        nodes = np.asarray(nodes, dtype=np.int64)
        bend = np.max([_curvature(p, field.path, a, b, nodes) for p in field.placements], axis=0)
        ones = np.ones(len(nodes))
        p, lo, hi, state, band = _chord_pieces(field, nodes, a * ones, b * ones, bend, DEVIATION)
        for level in range(1, LEVELS):  # the wide bands again, with chords of a smaller deviation
            again = band & (hi - lo > h_min)
            if not again.any():
                break
            q, lo2, hi2, state2, band2 = _chord_pieces(field, nodes[p[again]], lo[again], hi[again],
                                                       bend[p[again]], DEVIATION * SHRINK ** level)
            owner = np.flatnonzero(again)[q]
            keep = ~again
            p, lo, hi, state, band = (np.concatenate([x[keep], y]) for x, y in
                                      ((p, p[owner]), (lo, lo2), (hi, hi2), (state, state2), (band, band2)))
        uncertain = np.zeros(len(nodes))
        wide = band & (hi - lo > h_min)  # narrower bands hold the crossing to the search's resolution
        np.add.at(uncertain, p[wide], hi[wide] - lo[wide])
        p, lo, state = _bracketed(field, nodes, p, lo, hi, state, band)
        theta, who, after = flips(nodes, p, lo, state, start, end, b)
        return theta, who, after, uncertain

    return solve


def _chord_pieces(field, nodes, a, b, bend, deviation):
    """Pieces (pair, lo, hi, state, band) of each pair's interval [a_i, b_i] (node ``nodes[i]``), sorted; chords
    deviate from the arc by at most ``deviation``·tolerance."""
    tol = float(field.tolerance)
    h = np.sqrt(8.0 * deviation * max(tol, 1e-300) / np.maximum(bend, 1e-300))
    m = np.clip(np.ceil((b - a) / h), 1, MAX_CHORDS).astype(np.int64)
    pair = np.repeat(np.arange(len(nodes)), m)
    k = np.arange(pair.size) - np.repeat(np.cumsum(m) - m, m)
    t0 = a[pair] + (b - a)[pair] * k / m[pair]
    t1 = np.where(k + 1 == m[pair], b[pair], a[pair] + (b - a)[pair] * (k + 1) / m[pair])
    delta = bend[pair] * (t1 - t0) ** 2 / 8.0
    x0, x1 = field.path.positions(t0, nodes[pair]), field.path.positions(t1, nodes[pair])
    every = np.arange(len(nodes))
    zero = np.zeros(len(nodes), np.int64)
    ev = [(every, a, zero, zero), (every, b, zero, zero)]
    for placement in field.placements:
        P = placement.to_local(t0, x0)
        ev += _chord_events(placement, P, placement.to_local(t1, x1) - P, tol, delta, pair, t0, t1)
    return _pieces(field, nodes, ev)


def _curvature(placement, path, a, b, nodes) -> np.ndarray:
    """(k,) M = φ̇²·max|y| + 2|φ̇|·|ẏ| [m per θ²] on [a, b] (0 without rotation)."""
    if placement.angle is None:
        return np.zeros(len(nodes))
    w = math.radians(table_slopes(placement.angle, a, b))
    c = np.asarray(placement.centre, dtype=float)
    axis = np.asarray(placement.axis, dtype=float)
    ends = [path.positions(np.full(len(nodes), t), nodes) - placement.shift(np.array([t]))[0] * axis - c
            for t in (a, b)]
    size = np.maximum(np.linalg.norm(ends[0], axis=1), np.linalg.norm(ends[1], axis=1))
    ds = table_slopes(placement.displacement, a, b) if placement.displacement is not None else \
        abs(placement.velocity)
    return w * w * size + 2.0 * w * (ds + path.speeds(a, b, nodes))


def _chord_events(placement, P, D, tol, delta, pair, t0, t1):
    """(pair, θ, +1/−1 of the outer radius, +1/−1 of the inner radius) events of the chords."""
    blocker = placement.blocker
    seg, face = candidate_rows(P, D, blocker.vertices, blocker.faces, tol + float(delta.max(initial=0.0)))
    if not seg.size:
        return []
    tri = blocker.vertices[blocker.faces[face]]
    out = []
    for radius, outer in ((tol + delta[seg], True), (tol - delta[seg], False)):
        rows = np.flatnonzero(radius >= 0)
        lo, hi = triangle_intervals(P[seg[rows]], D[seg[rows]], tri[rows], radius[rows])
        ok = lo <= hi
        s = seg[rows[ok]]
        span = t1[s] - t0[s]
        one = np.ones(ok.sum(), np.int64)
        for t, sign in ((lo[ok], 1), (hi[ok], -1)):
            theta = np.where(t >= 1.0, t1[s], t0[s] + t * span)
            out.append((pair[s], theta, sign * one if outer else 0 * one, 0 * one if outer else sign * one))
    return out


def _pieces(field, nodes, ev):
    """States of the pieces between events: certain inside the inner radius, by the sign outside the outer one;
    in between (``band``) the state at the piece's start, to be bracketed."""
    pair, theta, outer, inner = (np.concatenate([e[i] for e in ev]) for i in range(4))
    order = np.lexsort((theta, pair))
    pair, theta = pair[order], theta[order]
    near, sure = np.cumsum(outer[order]), np.cumsum(inner[order])
    k = np.flatnonzero((pair[:-1] == pair[1:]) & (theta[1:] > theta[:-1]))
    p, lo, hi = pair[k], theta[k], theta[k + 1]
    state = sure[k] > 0
    free = np.flatnonzero(near[k] <= 0)
    if free.size:
        state[free] = field.excess(0.5 * (lo[free] + hi[free]), nodes[p[free]]) <= 0
    return p, lo, hi, state, (near[k] > 0) & (sure[k] <= 0)


def _bracketed(field, nodes, p, lo, hi, state, band):
    """The bands' states from the true gap at their ends, split at the crossing (regula falsi) where they differ;
    returns (pair, start, state) of all pieces sorted."""
    i = np.flatnonzero(band)
    if i.size:
        f_lo, f_hi = field.excess(lo[i], nodes[p[i]]), field.excess(hi[i], nodes[p[i]])
        state = state.copy()
        state[i] = f_lo <= 0
        split = (f_lo <= 0) != (f_hi <= 0)
        if split.any():
            s = i[split]
            roots, _ = batched_roots(field.excess, nodes[p[s]], lo[s], hi[s], f_lo[split], f_hi[split])
            p, lo, state = (np.concatenate([x, y]) for x, y in ((p, p[s]), (lo, roots), (state, f_hi[split] <= 0)))
    order = np.lexsort((lo, p))
    return p[order], lo[order], state[order]
