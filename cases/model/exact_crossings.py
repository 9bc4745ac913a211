"""Crossings of leakage nodes solved in closed form where the motion makes each node's path a segment.

On a knot interval [a, b], a rigid blocker that only translates (a displacement table, a constant velocity, a
dynamic body's displacement θ = s, or held still) and a leakage node that is fixed, scaled by a piecewise-linear
table or moved linearly between frames meet as a point moving on a straight segment in the blocker's frame. The
node is in contact where

* it lies within the contact tolerance of a face: the union of one exact interval per nearby face
  (:func:`cases.model.segment_contact.triangle_intervals`), or
* it lies inside a closed blocker, or behind an open one within its penetration depth. Inside a closed blocker
  changes only where the segment crosses the surface, which lies within every tolerance ≥ 0 of it; behind an open
  sheet changes also where the point passes a face's side wall or the depth: those instants are breakpoints too.

Between consecutive breakpoints the state is constant: contact where the tolerance intervals cover the piece,
else the sign of the gap at its midpoint. So every crossing is an interval end computed in closed form (a root of
a linear or quadratic polynomial), with no resolution limit and no sampling; a contact of any length is found.
"""
from __future__ import annotations

import numpy as np

from blockage.sides import sides_of

from cases.model.gaps import RigidPlacement
from cases.model.segment_contact import candidate_rows, triangle_intervals

__all__ = ["exact_solver", "segment_exact", "behind_open_sheet", "flips", "events"]


def behind_open_sheet(field) -> bool:
    """Some blocker is an open sheet whose back counts within a penetration depth: the gap then jumps where a
    node passes its edge (not Lipschitz), so the bound cannot certify an interval."""
    return any(getattr(p, "open_depth", 0.0) > 0 and not sides_of(p.blocker).closed for p in field.placements)


def segment_exact(field) -> bool:
    """The field's nodes move on segments relative to every blocker within a knot interval (and no edge contact)."""
    if field.edges is not None and len(field.edges):
        return False
    return all(isinstance(p, RigidPlacement) and p.angle is None for p in field.placements)


def exact_solver(field, knots):
    """callable (j, nodes, in at knots[j], in at knots[j+1]) -> (θ, node, state after) on knot interval j, for
    :func:`cases.model.crossings.certified_crossings`; None when the motion is not one it solves."""
    if not segment_exact(field):
        return None
    knots = np.asarray(knots, dtype=float)

    def solve(j, nodes, start, end):
        a, b = float(knots[j]), float(knots[j + 1])
        nodes = np.asarray(nodes, dtype=np.int64)
        pair, t, inc = [np.arange(len(nodes))] * 2, [np.zeros(len(nodes)), np.ones(len(nodes))], \
            [np.zeros(len(nodes), np.int64)] * 2
        xa = field.path.positions(np.full(len(nodes), a), nodes)
        xb = field.path.positions(np.full(len(nodes), b), nodes)
        for placement in field.placements:
            P = placement.to_local(np.full(len(nodes), a), xa)
            D = placement.to_local(np.full(len(nodes), b), xb) - P
            for ev in events(placement, P, D, field.tolerance):
                for lst, x in zip((pair, t, inc), ev):
                    lst.append(x)
        pair, t, inc = (np.concatenate(x) for x in (pair, t, inc))
        return _crossings(field, nodes, a, b, pair, t, inc, start, end)

    return solve


def events(placement, P, D, tol):
    """(pair, t, +1/−1/0) events: tolerance intervals open (+1) and close (−1); 0: open-sheet breakpoints."""
    blocker = placement.blocker
    depth = float(placement.open_depth)
    sheet = depth > 0 and not sides_of(blocker).closed
    seg, face = candidate_rows(P, D, blocker.vertices, blocker.faces, max(tol, depth if sheet else 0.0))
    if not seg.size:
        return []
    tri = blocker.vertices[blocker.faces[face]]
    lo, hi = triangle_intervals(P[seg], D[seg], tri, tol)
    ok = lo <= hi
    out = [(seg[ok], lo[ok], np.ones(ok.sum(), np.int64)), (seg[ok], hi[ok], -np.ones(ok.sum(), np.int64))]
    if sheet:
        for prism_only in (False, True):
            lo, hi = triangle_intervals(P[seg], D[seg], tri, depth, prism_only)
            ok = lo <= hi
            zero = np.zeros(2 * ok.sum(), np.int64)
            out.append((np.concatenate([seg[ok], seg[ok]]), np.concatenate([lo[ok], hi[ok]]), zero))
    return out


def _crossings(field, nodes, a, b, pair, t, inc, start, end):
    """The state on each piece between breakpoints, and the crossings where it changes (see the module)."""
    order = np.lexsort((t, pair))
    pair, t, inc = pair[order], t[order], inc[order]
    cover = np.cumsum(inc)  # each pair's increments sum to 0: the count after each event is the pair's own
    piece = (pair[:-1] == pair[1:]) & (t[1:] > t[:-1])
    k = np.flatnonzero(piece)
    p, t0, t1 = pair[k], t[k], t[k + 1]
    state = cover[k] > 0
    free = np.flatnonzero(~state)
    if free.size:  # outside every tolerance interval: inside / behind a blocker or not
        mid = a + 0.5 * (t0[free] + t1[free]) * (b - a)
        state[free] = field.excess(mid, nodes[p[free]]) <= 0
    theta = np.where(t0 <= 0.0, a, a + t0 * (b - a))
    return flips(nodes, p, theta, state, start, end, b)


def flips(nodes, p, theta, state, start, end, b):
    """(θ, node, state after) where the state of consecutive pieces (pair ``p``, sorted, starting at ``theta``)
    changes; the first piece is compared with the state at the interval's start, and the last with the state at
    its end ``b`` (a knot: the next interval starts from it)."""
    first = np.ones(len(p), dtype=bool)
    first[1:] = p[1:] != p[:-1]
    last = np.append(first[1:], True)
    before = np.where(first, np.asarray(start, bool)[p], np.roll(state, 1))
    flip = state != before
    end = np.asarray(end, bool)
    tail = last & (state != end[p])
    who = np.concatenate([p[flip], p[tail]])
    return (np.concatenate([theta[flip], np.full(tail.sum(), b)]), nodes[who],
            np.concatenate([state[flip], end[p[tail]]]))
