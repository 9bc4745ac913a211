"""An FE code's blockage rule with a dynamic body: the rule's area as a step function of the body's displacement s,
which the engine samples at the explicit code's cycles (:mod:`exchange.engine.sampled`).

With the body along its axis at s, the rule's flags are a function of s alone (:mod:`blockage.fe_rules`): the
secondary nodes are the exact rule's active nodes at s (they change at the exact crossings, found and certified
along s), and the main segments are the leakage faces nearest to the body's nodes in contact (each node's segment
changes where it enters or leaves contact, or its nearest face changes). So the rule's area is constant between
the union of those displacements: its crossings along s. The main segments' changes are found node by node on a
grid of s (a quarter of the contact tolerance, at most MAX_GRID points over the travel: a node stays in contact over
at least twice the tolerance of travel unless it grazes an edge of the surface) and located by bisection to the
last bit of s.

The track's last crossing is +inf and its last area the flagless one: the engine uses it before cycle n of a rule
with a lag of n cycles.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from blockage.fe_rules import LeakTree, face_counts, flagged_nodes

from cases.model.area_track import AreaTrack
from cases.model.crossings import Crossings

__all__ = ["SampledTrack", "main_segments_along", "rule_flags_along", "dynamic_fe_track", "GRID_TOLERANCES"]

#: Grid spacing of the main-segment search along s, in contact tolerances.
GRID_TOLERANCES = 0.25
#: Most grid points of that search over the body's travel (a zero tolerance: contact only behind the surface).
MAX_GRID = 20000
#: Bisection steps locating a main segment's change (the bracket shrinks below the last bit of s).
BISECTIONS = 64


@dataclass
class SampledTrack(AreaTrack):
    """An FE rule's area along s (:class:`cases.model.area_track.AreaTrack`, its last interval the flagless area),
    with ``sampling`` (step [s], lag [cycles]) for the engine."""

    sampling: tuple = (0.0, 0)

    def start_interval(self, theta: float = 0.0) -> int:
        """The interval in use at the run's start: the one holding s, or the flagless one with a lag."""
        return len(self.crossings) if self.sampling[1] > 0 else super().start_interval(theta)


def _range_in_box(x, axis, lo, hi, box_lo, box_hi) -> tuple:
    """(a, b) (k,): the s in [lo, hi] where x + s·axis lies in the box (a > b: never)."""
    a, b = np.full(len(x), lo), np.full(len(x), hi)
    for d in range(3):
        if axis[d] == 0.0:
            out = (x[:, d] < box_lo[d]) | (x[:, d] > box_hi[d])
            a[out], b[out] = np.inf, -np.inf
            continue
        t0, t1 = (box_lo[d] - x[:, d]) / axis[d], (box_hi[d] - x[:, d]) / axis[d]
        a, b = np.maximum(a, np.minimum(t0, t1)), np.minimum(b, np.maximum(t0, t1))
    return a, b


def main_segments_along(tree: LeakTree, x, axis, lo: float, hi: float, tolerance: float,
                        open_depth: float = 0.0) -> tuple:
    """(initial (k,) int, s (e,), node (e,), segment (e,)): the main segment of each blocker node x + s·axis
    ((k, 3) [m] at s = 0, ``axis`` unit) at s = lo (−1: out of contact) and its changes along [lo, hi], sorted by s
    (the segment from s on; :meth:`blockage.fe_rules.LeakTree.segments`)."""
    x, axis = np.asarray(x, dtype=float).reshape(-1, 3), np.asarray(axis, dtype=float)
    pts = tree.blocker.vertices
    reach = 2.0 * max(tolerance, open_depth) + 1e-12 * float(np.ptp(pts, axis=0).max() + hi - lo)
    a, b = _range_in_box(x, axis, lo, hi, pts.min(axis=0) - reach, pts.max(axis=0) + reach)
    h = max(GRID_TOLERANCES * max(tolerance, open_depth), (hi - lo) / MAX_GRID)
    grid = np.linspace(lo, hi, max(int(np.ceil((hi - lo) / h)), 1) + 1)
    initial = np.full(len(x), -1, dtype=np.int64)
    near = np.flatnonzero(a <= b)
    if not near.size:
        return initial, np.zeros(0), np.zeros(0, np.int64), np.zeros(0, np.int64)
    first = np.clip(np.searchsorted(grid, a[near], side="right") - 1, 0, len(grid) - 1)
    last = np.clip(np.searchsorted(grid, b[near], side="left"), 0, len(grid) - 1)
    count = last - first + 1
    node = np.repeat(near, count)
    gi = np.repeat(first - np.cumsum(count) + count, count) + np.arange(count.sum())
    seg = tree.segments(x[node] + grid[gi][:, None] * axis, tolerance, open_depth)
    at_lo = gi == 0
    initial[node[at_lo]] = seg[at_lo]
    # a node is out of contact outside its box range: pad each run with -1 before and after
    prev = np.where(np.r_[True, node[1:] != node[:-1]], -1, np.r_[-1, seg[:-1]])
    prev[at_lo] = seg[at_lo]  # the state at lo is the initial one
    s_prev = np.where(gi > 0, grid[np.maximum(gi - 1, 0)], lo)
    change = np.flatnonzero(seg != prev)
    tail = np.flatnonzero((np.r_[node[1:] != node[:-1], True]) & (seg != -1) & (gi < len(grid) - 1))
    brackets = [(s_prev[change], grid[gi[change]], node[change], prev[change]),
                (grid[gi[tail]], grid[gi[tail] + 1], node[tail], seg[tail])]
    s_a, s_b, nodes, seg_a = (np.concatenate(p) for p in zip(*brackets))
    return (initial,) + _located(tree, x, axis, s_a, s_b, nodes, seg_a, tolerance, open_depth)


def _located(tree, x, axis, s_a, s_b, nodes, seg_a, tolerance, open_depth) -> tuple:
    """The changes of segment inside brackets [s_a, s_b] (segment seg_a at s_a, another at s_b) by bisection, one
    per bracket and again on what is left of it when the segment at its end is not the one found."""
    out_s, out_n, out_g = [], [], []
    seg_b = tree.segments(x[nodes] + s_b[:, None] * axis, tolerance, open_depth)
    while len(nodes):
        a, b = s_a.copy(), s_b.copy()
        for _ in range(BISECTIONS):
            mid = 0.5 * (a + b)
            same = tree.segments(x[nodes] + mid[:, None] * axis, tolerance, open_depth) == seg_a
            a, b = np.where(same, mid, a), np.where(same, b, mid)
        found = tree.segments(x[nodes] + b[:, None] * axis, tolerance, open_depth)
        out_s.append(b)
        out_n.append(nodes)
        out_g.append(found)
        more = (found != seg_b) & (b < s_b)
        s_a, s_b, nodes, seg_a, seg_b = b[more], s_b[more], nodes[more], found[more], seg_b[more]
    s, n, g = np.concatenate(out_s), np.concatenate(out_n), np.concatenate(out_g)
    order = np.lexsort((n, s))
    return s[order], n[order], g[order]


def rule_flags_along(fe, exact: Crossings, faces, face_sizes, main=None, fixed=None, blocked: bool = True):
    """The corner crossings along s of rule ``fe`` (:class:`cases.model.fe_sampling.FeRule`; no sampling, no lag):
    the rule's flags at every s from the exact crossings ``exact`` (θ = s) and the main segments ``main`` (the
    tuple of :func:`main_segments_along`, None: none) plus the faces ``fixed`` (m,) bool touched by bodies that do
    not move; as :class:`cases.model.fe_sampling.SampledFlags` (θ = s), its corners weighing A_e/N_e each."""
    from cases.model.fe_sampling import SampledFlags, _corner_changes, corner_faces

    faces, sizes = np.asarray(faces, dtype=np.int64), np.asarray(face_sizes, dtype=np.int64)
    corners = corner_faces(sizes)
    starts, m = corners[:, 0], len(faces)
    fixed = np.zeros(m, dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool)
    init, ms, mn, mg = main if main is not None else (np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64),
                                                      np.zeros(0, np.int64))
    state, seg = exact.initial.copy(), np.asarray(init, dtype=np.int64).copy()

    def counts():
        if not blocked:
            return np.zeros(m, dtype=np.int64)
        hit = fixed.copy()
        hit[seg[seg >= 0]] = True
        return face_counts(fe.rule, flagged_nodes(state, hit, faces, sizes, fe.side), faces, sizes)

    theta = np.concatenate([exact.theta, ms])
    which = np.concatenate([np.zeros(len(exact.theta), bool), np.ones(len(ms), bool)])
    idx = np.concatenate([np.arange(len(exact.theta)), np.arange(len(ms))])
    order = np.argsort(theta, kind="stable")
    now = counts()
    corner0 = np.zeros(int(sizes.sum()), dtype=bool)
    corner0[_corner_changes(np.zeros(m, np.int64), now, starts)[0]] = True
    th, ids, sts = [], [], []
    i = 0
    while i < len(order):
        here = theta[order[i]]
        while i < len(order) and theta[order[i]] == here:
            k = idx[order[i]]
            if which[order[i]]:
                seg[mn[k]] = mg[k]
            else:
                state[exact.node[k]] = exact.state[k]
            i += 1
        new = counts()
        if np.any(new != now):
            c, s = _corner_changes(now, new, starts)
            th.append(np.full(len(c), here))
            ids.append(c)
            sts.append(s)
            now = new
    cat = (lambda parts, dtype: np.concatenate(parts).astype(dtype) if parts else np.zeros(0, dtype))
    return SampledFlags(corner0, cat(th, float), cat(ids, np.int64), cat(sts, bool), exact.resolution,
                        exact.evaluations, exact.unresolved, exact.uncertain, nodes=exact, corners=corners,
                        face_sizes=sizes.astype(float), scale=fe.sdfblk, rule=fe)


def dynamic_fe_track(scene, j, exact: Crossings, surface, x_leak, weights, driver, options) -> SampledTrack:
    """The :class:`SampledTrack` of exchange j under the scene's FE rule with the dynamic body (θ = s): the rule's
    corner crossings along s (:func:`rule_flags_along`, main segments of the leakage ``surface`` on its nodes
    ``x_leak`` by :func:`main_segments_along`; None: node-based, of node ``weights``), each corner weighing A_e/N_e,
    then the flagless interval after a last crossing at +inf."""
    from cases.model.fe_sampling import fe_rule, rule_blocks, rule_faces, sampled_permeability

    spec, e = scene.blockage, scene.exchange[j]
    faces, sizes, corner_w, total = rule_faces(surface, weights, len(x_leak))
    fe = fe_rule(spec, node_based=surface is None)
    main, fixed = None, None
    if fe.side != "secondary" and e.blocked_by:
        tree = LeakTree(x_leak, faces, sizes)
        tol, depth = e.contact_tolerance or 1e-300, float(e.penetration_depth or 0.0)
        fixed = np.zeros(len(faces), dtype=bool)
        for name in e.blocked_by:
            body = driver.bodies[name][0]
            if body is driver.dynamic:
                main = main_segments_along(tree, body.mesh.vertices, body.axis, driver.lo, driver.hi, tol, depth)
            else:  # held where it starts
                fixed |= tree.touched(body.vertices_at(0.0), tol, depth)
    flags = rule_flags_along(fe, exact, faces, sizes, main, fixed, rule_blocks(spec, e))
    options = {**options, "permeability": sampled_permeability(spec, e)}
    track = AreaTrack.build(corner_w, total, flags, driver.lo, driver.hi, **options)
    return SampledTrack(np.r_[track.crossings, np.inf], np.r_[track.obstruction, 0.0], np.r_[track.actives, 0],
                        track.total_area, track.effective_area, track.permeability, track.scale, None, track.span,
                        flags, None, sampling=(fe.step, fe.lag))
