"""Certified search of the instants at which leakage nodes enter and leave contact.

A node's *excess* f(θ) = gap(θ) − tolerance (≤ 0: active) is a distance, so it changes no faster than the
node's speed relative to the blocker: |f(θ₁) − f(θ₂)| ≤ L·|θ₁ − θ₂| on a knot interval of the motion, where the
bound L comes from the motion (:mod:`cases.model.gaps`). From the values at the ends of an interval [a, b] of length h,

    min f ≥ (f(a) + f(b) − L·h) / 2,        max f ≤ (f(a) + f(b) + L·h) / 2,

so an interval is *settled* (the node is out of contact all along, or in contact all along) when the first bound
is > 0 or the second ≤ 0. Every unsettled interval is bisected, all nodes together (one batched gap query per
level), until it is settled or shorter than the resolution h_min; the leaves whose ends differ in state hold a
crossing, located to a few ulp by regula falsi (Illinois). Guarantee: every contact, and every release, that
lasts at least h_min is found and timed to machine precision; a contact shorter than h_min can be missed, and
then it removes at most A_node·h_min of blocked area·time (A_node: the node's share of its faces' areas). A node
whose gap hovers within the bound of the tolerance over more than :data:`MAX_LEAVES` sub-intervals of a knot
interval (a blade sliding over a vent inside the tolerance) is handed to a solver when the motion has one
(:mod:`cases.model.exact_crossings` for translations: every crossing exact, no resolution limit;
:mod:`cases.model.chord_crossings` for rotations: chords of certified deviation); otherwise it is bisected up
to :data:`MAX_LEAVES_UNSOLVED` sub-intervals, and what stays unsettled is reported in ``uncertain``.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

__all__ = ["Crossings", "certified_crossings", "RESOLUTION", "batched_roots", "SearchBudget", "MAX_PENDING"]

#: h_min as a fraction of the searched range of θ.
RESOLUTION = 1e-10
#: Unsettled (node, interval) pairs at one bisection level beyond which the search stops (memory).
MAX_PENDING = 20_000_000
#: Unsettled sub-intervals of one (node, knot interval) beyond which that pair goes to the closed-form solver: its
#: gap hovers within the bound of the tolerance (a plate sliding along a seat just outside it).
MAX_LEAVES = 64
#: The same when no solver can take over (a deforming blocker, edge contact): bisected further, so that what
#: stays uncertain (and is reported) is only where the gap really hovers.
MAX_LEAVES_UNSOLVED = 1024


class SearchBudget(RuntimeError):
    """The crossing search ran past its wall-time deadline or its pending-pair budget."""


@dataclass(frozen=True)
class Crossings:
    """Contact changes of n nodes on [lo, hi]: ``initial`` (n,) bool active at lo; ``theta`` (c,) sorted, the
    node (c,) and its state after (c,) bool; ``resolution`` h_min; ``evaluations`` gap queries made;
    ``unresolved`` sub-intervals of (node, knot interval) pairs left unbisected under :data:`MAX_LEAVES` that no
    closed form could solve either, ``uncertain`` (n,) their total length per node [θ] (the node's state is not
    certified there: at most its weight times that much blocked area·θ is at stake; a contact shorter than h_min
    elsewhere is within the guarantee and not counted)."""

    initial: np.ndarray
    theta: np.ndarray
    node: np.ndarray
    state: np.ndarray
    resolution: float
    evaluations: int = 0
    unresolved: int = 0
    uncertain: np.ndarray | None = None

    def active_at(self, theta: float) -> np.ndarray:
        """(n,) bool: active nodes at θ (right limit at a crossing)."""
        active = self.initial.copy()
        k = int(np.searchsorted(self.theta, theta, side="right"))
        active[self.node[:k]] = self.state[:k]  # later crossings of a node overwrite earlier ones
        return active


def certified_crossings(excess, n: int, knots, speed, resolution: float = RESOLUTION,
                        deadline: float = np.inf, exact=None, exact_first: bool = False) -> Crossings:
    """All crossings of f_i(θ) = 0 for nodes i < n on [knots[0], knots[-1]].

    Parameters
    ----------
    excess : callable (thetas (k,), nodes (k,) int) -> (k,) float
        f_i(θ) [m] for many (θ, node) pairs in one call; ≤ 0 means in contact.
    n : int
        Number of nodes.
    knots : (K + 1,) float
        Increasing θ values, the motion's breakpoints and the ends of the range.
    speed : callable (j, nodes (k,) int) -> (k,) float
        Bound on |df_i/dθ| on [knots[j], knots[j+1]] [m per unit of θ].
    resolution, deadline : float
        h_min as a fraction of the range; ``time.perf_counter()`` after which :class:`SearchBudget` is raised.
    exact : callable (j, nodes (k,), in at knots[j] (k,), in at knots[j+1] (k,)) -> (θ, node, state) or None
        Every crossing of those nodes on knot interval j in closed form (:mod:`cases.model.exact_crossings`), for
        the pairs the bound cannot settle; without it (or when it returns None) they go to ``uncertain``.
    exact_first : bool
        Solve every pair with ``exact`` first (the gap is not Lipschitz: behind an open sheet around its edge).
    """
    knots = np.asarray(knots, dtype=float)
    h_min = resolution * (knots[-1] - knots[0])
    F, (a, b, fa, fb, node, origin, L) = _knot_pairs(excess, n, knots, speed)
    evaluations = F.size
    brackets, solved, uncertain, unresolved = [], [], np.zeros(n), 0
    if exact_first and exact is not None and a.size:
        left = _settle_stuck(np.ones(a.size, bool), (a, b, fa, fb, node, origin), F <= 0, n, exact, [], solved,
                             uncertain)
        a, b, fa, fb, node, L, origin = (v[left] for v in (a, b, fa, fb, node, L, origin))
    while a.size:
        if time.perf_counter() > deadline or a.size > MAX_PENDING:
            raise SearchBudget(f"{a.size} node intervals still unsettled after {evaluations} gap evaluations")
        h = b - a
        settled = (((fa > 0) & (fb > 0) & (fa + fb - L * h > 0))
                   | ((fa <= 0) & (fb <= 0) & (fa + fb + L * h <= 0)))
        leaf = ~settled & (h <= h_min)
        change = leaf & ((fa <= 0) != (fb <= 0))
        if change.any():
            brackets.append((a[change], b[change], fa[change], fb[change], node[change], origin[change]))
        split = ~settled & ~leaf
        stuck = _crowded(split, origin, MAX_LEAVES if exact is not None else MAX_LEAVES_UNSOLVED)
        if stuck.any():
            left = _settle_stuck(stuck, (a, b, fa, fb, node, origin), F <= 0, n, exact, brackets, solved,
                                 uncertain)
            unresolved += int(np.count_nonzero(left))
            np.add.at(uncertain, node[left], h[left])
        split &= ~stuck
        a, b, fa, fb, node, L, origin = (v[split] for v in (a, b, fa, fb, node, L, origin))
        m = 0.5 * (a + b)
        fm = excess(m, node) if m.size else m
        evaluations += m.size
        a, b = np.concatenate([a, m]), np.concatenate([m, b])
        fa, fb = np.concatenate([fa, fm]), np.concatenate([fm, fb])
        node, L, origin = np.concatenate([node, node]), np.concatenate([L, L]), np.concatenate([origin, origin])
    found = _located(F[0] <= 0, brackets, solved, excess, h_min, evaluations, n)
    banded = int(sum(np.count_nonzero(x[5] > 0) for x in solved if len(x) > 5))  # nodes a solver left uncertain
    return replace(found, unresolved=unresolved + banded, uncertain=uncertain)


def _knot_pairs(excess, n, knots, speed):
    """f at every knot (K + 1, n), and the (node, knot interval) pairs: a, b, f(a), f(b), node, origin, bound L."""
    nodes = np.arange(n)
    F = excess(np.repeat(knots, n), np.tile(nodes, len(knots))).reshape(len(knots), n)
    node = np.tile(nodes, len(knots) - 1)
    L = np.concatenate([np.asarray(speed(j, nodes), dtype=float) for j in range(len(knots) - 1)]) \
        if len(knots) > 1 else np.zeros(0)
    return F, (np.repeat(knots[:-1], n), np.repeat(knots[1:], n), F[:-1].ravel(), F[1:].ravel(), node,
               np.arange(node.size), L)


def _crowded(split, origin, most) -> np.ndarray:
    """(k,) bool: the intervals of (node, knot interval) pairs holding more than ``most`` unsettled ones (their
    gap hovers at the tolerance): not bisected further."""
    count = np.bincount(origin[split], minlength=int(origin.max()) + 1 if origin.size else 0)
    return split & (count > most)[origin]


def _settle_stuck(stuck, arrays, inside, n, exact, brackets, solved, uncertain=None) -> np.ndarray:
    """Hand the stuck (node, knot interval) pairs to ``exact``; (k,) bool: the stuck intervals it could not solve
    (their brackets are kept, their length counted as uncertain). A solver may return a fourth array, the length
    of θ on which each node's state stays uncertain (added to ``uncertain``)."""
    a, b, fa, fb, node, origin = arrays
    left = stuck.copy()
    if exact is not None:
        pairs = np.unique(origin[stuck])
        for j in np.unique(pairs // n):
            ids = pairs[pairs // n == j] % n
            got = exact(int(j), ids, inside[j, ids], inside[j + 1, ids])
            if got is None:
                continue
            theta, who, state = got[:3]
            solved.append((theta, who, state, np.full(len(theta), int(j)), j * n + ids) + tuple(got[3:]))
            left &= ~np.isin(origin, j * n + ids)
            if len(got) > 3 and uncertain is not None:
                uncertain[ids] += got[3]
    change = left & ((fa <= 0) != (fb <= 0))
    if change.any():
        brackets.append((a[change], b[change], fa[change], fb[change], node[change], origin[change]))
    return left


def _located(initial, brackets, solved, excess, h_min, evaluations, n) -> Crossings:
    empty = np.zeros(0)
    theta, node, state, key = empty, empty.astype(np.int64), empty.astype(bool), empty.astype(np.int64)
    calls = 0
    if brackets:
        a, b, fa, fb, node, origin = (np.concatenate(parts) for parts in zip(*brackets))
        if solved:  # brackets found before a pair was solved exactly: the exact answer replaces them
            keep = ~np.isin(origin, np.concatenate([s[4] for s in solved]))
            a, b, fa, fb, node, origin = (v[keep] for v in (a, b, fa, fb, node, origin))
        theta, calls = batched_roots(excess, node, a, b, fa, fb)
        state, key = fb <= 0, origin // max(n, 1)
    if solved:
        theta, node, state, key = (np.concatenate([x] + [s[i] for s in solved])
                                   for i, x in enumerate((theta, node, state, key)))
    order = np.lexsort((node, key, theta))  # same θ: a knot's end before the next interval's start
    return Crossings(initial, theta[order], node[order].astype(np.int64), state[order].astype(bool), h_min,
                     evaluations + calls)

def batched_roots(excess, nodes, a, b, fa, fb, iterations=200):
    """Roots of f_i(θ) = 0 in brackets [a, b] with f(a), f(b) of opposite states, many pairs at once (Illinois
    regula falsi on the state-preserving sign: ≤ 0 is "in"). Returns (θ where the state changes, gap calls)."""
    a, b, fa, fb = (np.asarray(v, dtype=float).copy() for v in (a, b, fa, fb))
    side = np.zeros(len(a))
    calls = 0
    for _ in range(iterations):
        open_ = np.abs(b - a) > 4.0 * np.finfo(float).eps * np.maximum(np.abs(a), np.abs(b)) + 1e-300
        if not open_.any():
            break
        idx = np.flatnonzero(open_)
        with np.errstate(divide="ignore", invalid="ignore"):
            c = (a[idx] * fb[idx] - b[idx] * fa[idx]) / (fb[idx] - fa[idx])
        bad = ~np.isfinite(c) | (c <= np.minimum(a[idx], b[idx])) | (c >= np.maximum(a[idx], b[idx]))
        c[bad] = 0.5 * (a[idx][bad] + b[idx][bad])
        fc = excess(c, nodes[idx])
        calls += c.size
        left = (fc <= 0) == (fa[idx] <= 0)  # same state as a: the change is in [c, b]
        i_l, i_r = idx[left], idx[~left]
        a[i_l], fa[i_l] = c[left], fc[left]
        fb[i_l] = np.where(side[i_l] == 1, fb[i_l] / 2, fb[i_l])  # Illinois: halve the stale end
        side[i_l] = 1
        b[i_r], fb[i_r] = c[~left], fc[~left]
        fa[i_r] = np.where(side[i_r] == -1, fa[i_r] / 2, fa[i_r])
        side[i_r] = -1
    return b, calls
