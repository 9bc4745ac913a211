"""An FE code's blockage rule in time: flags evaluated at the explicit time steps t_k = k·Δt only and used n cycles
later, turned into the step table of leakage area that the engine already runs for the exact rule.

The flags of cycle k (:mod:`blockage.fe_rules`) come from two contacts at t_k:

* the leakage nodes in contact, read from the exact crossings (:mod:`cases.model.crossings`): a node's state at
  t_k is the state after every crossing at θ <= t_k, so sampling costs O(crossings), not O(steps × nodes);
* the leakage faces that a blocker node touches (the main segments), evaluated at every t_k where a blocker's
  bounding box reaches the leakage surface's (:class:`MainSegments`).

The area used over [t_k, t_k+1) is the rule's area of the flags of cycle k − n (none before cycle n: an FE run
starts with no contact flags). It changes only where the flags of some cycle differ from the previous cycle's, so
the track holds one switch per such cycle. Each face's blocked share is carried by its *corners*: a face with N_e
corners, q of them flagged, is blocked over A_e·q/N_e, which covers the rules that count nodes (q = N_c) and those
that block whole elements (q = N_e); :class:`cases.model.area_track.AreaTrack` then builds the area steps from the
corner crossings exactly as from node crossings.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from blockage.areas import active_counts
from blockage.fe_rules import LeakTree, blocks_exchange, default_lag, default_side, face_counts, flagged_nodes

from cases.model.crossings import Crossings

__all__ = ["FeRule", "SampledFlags", "sampled_flags", "sample_index", "MainSegments", "corner_faces", "fe_rule",
           "sampled_permeability", "rule_faces"]


@dataclass(frozen=True)
class FeRule:
    """A rule as the sampling needs it: ``rule`` (:data:`blockage.fe_rules.RULES`), ``step`` Δt [s], ``lag`` n
    cycles, ``side`` (:data:`blockage.fe_rules.SIDES`) and ``sdfblk``."""

    rule: str
    step: float
    lag: int
    side: str
    sdfblk: float = 1.0


def fe_rule(spec, node_based: bool = False) -> FeRule:
    """The :class:`FeRule` of a scene's [blockage] table (``spec``: :class:`cases.scene.blockage_rule.BlockageSpec`)."""
    lag = default_lag(spec.rule) if spec.lag_cycles < 0 else int(spec.lag_cycles)
    side = default_side(spec.rule) if spec.contact_side == "rule" else spec.contact_side
    return FeRule(spec.rule, float(spec.step), lag, "secondary" if node_based else side,
                  float(spec.sdfblk) if spec.rule == "lsdyna_cpm" else 1.0)


def sampled_permeability(spec, exchange) -> float:
    """The fraction of blocked area that still leaks under the rule: the exchange's permeability, or [blockage]
    blocked_leak_fraction for a fabric law; SDFBLK s scales the obstruction, i.e. 1 − (1 − β)·s."""
    from cases.scene.blockage_rule import FABRIC_LAWS

    beta = exchange.permeability
    if spec.blocked_leak_fraction is not None and exchange.law in FABRIC_LAWS:
        beta = spec.blocked_leak_fraction
    s = spec.sdfblk if spec.rule == "lsdyna_cpm" else 1.0
    return 1.0 - (1.0 - beta) * s


def rule_blocks(spec, exchange) -> bool:
    """Whether the rule blocks this exchange at all (LS-DYNA BLOCK exempts vents, :func:`blocks_exchange`)."""
    return blocks_exchange(spec.rule, spec.block, exchange.law == "orifice", exchange.to == "ambient")


def corner_faces(face_sizes) -> np.ndarray:
    """(m, 4) the corner ids of each face (padded -1): corners are numbered face by face, N_e per face."""
    sizes = np.asarray(face_sizes, dtype=np.int64)
    start = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    cols = np.arange(4)[None, :]
    return np.where(cols < sizes[:, None], start[:, None] + cols, -1)


@dataclass(frozen=True)
class SampledFlags(Crossings):
    """The corner crossings of a sampled rule (what the area track is built from; ``node`` holds corner ids, θ the
    times t_(k+n) at which the flags of cycle k start to be used), plus ``nodes``: the flagged leakage nodes as
    crossings (for pictures), ``corners`` (m, 4) and ``face_sizes`` (m,), ``scale`` (SDFBLK), ``rule``."""

    nodes: Crossings | None = None
    corners: np.ndarray | None = None
    face_sizes: np.ndarray | None = None
    scale: float = 1.0
    rule: object = None

    def active_at(self, theta: float) -> np.ndarray:
        """(n,) bool: the leakage nodes whose flags are used at θ."""
        return self.nodes.active_at(theta)

    def face_fractions(self, theta: float) -> np.ndarray:
        """(m,) the blocked fraction of each face used at θ (SDFBLK included)."""
        corners = Crossings.active_at(self, theta)
        return self.scale * active_counts(corners, self.corners, self.face_sizes) / self.face_sizes


def sample_index(theta, step: float) -> np.ndarray:
    """(c,) int: the first k with k·step >= θ (the first cycle whose state includes a change at θ).

    >>> sample_index(np.array([0.0, 0.1, 0.1000001, 0.3]), 0.1).tolist()
    [0, 1, 2, 3]
    """
    theta = np.asarray(theta, dtype=float)
    k = np.ceil(theta / step).astype(np.int64)
    k = np.where((k - 1) * step >= theta, k - 1, k)
    return np.where(k * step < theta, k + 1, np.maximum(k, 0))


def _node_changes(exact: Crossings, step: float, last: int) -> tuple:
    """(initial (n,) bool at cycle 0, k (c',), node (c',), state (c',)): the exact crossings as changes of the
    sampled states, several crossings of a node within one cycle collapsed into the state after the last."""
    k = sample_index(exact.theta, step)
    keep = k <= last
    k, node, state = k[keep], exact.node[keep], exact.state[keep]
    order = np.lexsort((np.arange(len(k)), k, node))  # by node, cycle, then time order
    k, node, state = k[order], node[order], state[order]
    last_of = np.ones(len(k), dtype=bool)
    last_of[:-1] = (node[1:] != node[:-1]) | (k[1:] != k[:-1])
    k, node, state = k[last_of], node[last_of], state[last_of]
    prev = np.empty(len(k), dtype=bool)  # the node's state before the cycle
    first = np.ones(len(k), dtype=bool)
    first[1:] = node[1:] != node[:-1]
    prev[1:] = state[:-1]
    prev[first] = exact.initial[node[first]]
    change = state != prev
    k, node, state = k[change], node[change], state[change]
    initial = exact.initial.copy()
    at0 = k == 0
    initial[node[at0]] = state[at0]
    order = np.argsort(k[~at0], kind="stable")
    return initial, k[~at0][order], node[~at0][order], state[~at0][order]


class MainSegments:
    """The leakage faces touched by the blocker nodes at given times: ``bodies`` (:class:`cases.model.bodies.Body`)
    moving in time, the leakage surface's ``faces``/``face_sizes`` on nodes at ``positions(t)`` (n, 3) [m]."""

    def __init__(self, bodies, positions, faces, face_sizes, tolerance: float, open_depth: float = 0.0,
                 moving: bool = False):
        self.bodies, self.positions, self.moving = list(bodies), positions, moving
        self.tolerance, self.open_depth = float(tolerance), float(open_depth)
        self.tree = LeakTree(positions(0.0), faces, face_sizes)
        self.reach = 2.0 * max(self.tolerance, self.open_depth)
        self.queries = 0

    def _leak_box(self, times) -> tuple:
        """The leakage surface's bounding box over ``times`` grown by the reach (a bound when it moves)."""
        pts = np.concatenate([self.positions(t) for t in (np.unique(times[[0, -1]]) if not self.moving else times)])
        return pts.min(axis=0) - self.reach, pts.max(axis=0) + self.reach

    def _near(self, pts: np.ndarray) -> np.ndarray:
        """(k,) bool: blocker nodes that may be within the reach of a fixed leakage surface: within the reach plus
        the largest face's size of one of its nodes (a cheap bound, :class:`scipy.spatial.cKDTree`)."""
        if not hasattr(self, "_kd"):
            from scipy.spatial import cKDTree

            x = self.positions(0.0)
            tri = self.tree.blocker.faces
            size = float(np.max(np.linalg.norm(x[tri] - x[tri].mean(axis=1, keepdims=True), axis=2)))
            self._kd, self._bound = cKDTree(x), self.reach + size
        return np.isfinite(self._kd.query(pts, distance_upper_bound=self._bound)[0])

    def touched(self, times) -> dict:
        """{k: (faces touched,) int} for the k where some face is touched at ``times[k]``."""
        times = np.asarray(times, dtype=float)
        out = {}
        for start in range(0, len(times), 2048):
            chunk = times[start:start + 2048]
            lo, hi = self._leak_box(chunk)
            pts, owner = [], []
            for k, t in enumerate(chunk):
                x = np.concatenate([b.vertices_at(float(t)) for b in self.bodies]) if self.bodies else np.zeros((0, 3))
                x = x[np.all((x >= lo) & (x <= hi), axis=1)]
                if not len(x):
                    continue
                if self.moving:  # one query per step on the surface where it is
                    self.tree.refit(self.positions(float(t)))
                    self._record(out, start + k, x, np.zeros(len(x), np.int64))
                else:
                    pts.append(x)
                    owner.append(np.full(len(x), start + k))
            if pts:  # a fixed surface: one query for the whole chunk
                pts, owner = np.concatenate(pts), np.concatenate(owner)
                near = self._near(pts)
                self._record(out, None, pts[near], owner[near])
        return out

    def _record(self, out: dict, k, pts, owner) -> None:
        """Add to ``out`` the faces touched by ``pts`` (of steps ``owner``, or all of step ``k``)."""
        self.queries += len(pts)
        faces = self.tree.segments(pts, self.tolerance, self.open_depth)
        hit = faces >= 0
        steps = (np.full(len(pts), k) if k is not None else owner)[hit]
        pairs = np.unique(np.column_stack([steps, faces[hit]]), axis=0)  # sorted by step, then face
        cut = np.flatnonzero(np.diff(pairs[:, 0])) + 1
        for group in np.split(pairs, cut) if len(pairs) else ():
            out[int(group[0, 0])] = group[:, 1]


def _corner_changes(counts0, counts1, starts) -> tuple:
    """(corner ids, new states) turning the corner flags of faces with ``counts0`` flagged corners to ``counts1``."""
    changed = np.flatnonzero(counts0 != counts1)
    ids, states = [], []
    for e in changed:
        a, b = int(counts0[e]), int(counts1[e])
        ids.append(starts[e] + np.arange(min(a, b), max(a, b)))
        states.append(np.full(abs(b - a), b > a))
    if not ids:
        return np.zeros(0, np.int64), np.zeros(0, bool)
    return np.concatenate(ids), np.concatenate(states)


def sampled_flags(fe: FeRule, exact: Crossings, faces, face_sizes, t_end: float, main: MainSegments | None = None,
                  blocked: bool = True) -> SampledFlags:
    """The corner crossings of rule ``fe`` over [0, t_end] (module docstring).

    Parameters
    ----------
    exact : Crossings
        The leakage nodes' exact crossings (θ = time).
    faces, face_sizes : (m, 4) int, (m,) int
        The leakage faces; a node-based surface passes one single-node face per node.
    main : MainSegments, optional
        The blocker nodes, when the rule flags main segments.
    blocked : bool
        False: the rule does not block this exchange (LS-DYNA BLOCK): no flag is ever used.
    """
    faces, sizes = np.asarray(faces, dtype=np.int64), np.asarray(face_sizes, dtype=np.int64)
    corners = corner_faces(sizes)
    starts = corners[:, 0]
    last = int(np.floor(t_end / fe.step * (1.0 + 1e-12)))
    state, ks, nodes, states = _node_changes(exact, fe.step, last)
    touched = main.touched(np.arange(last + 1) * fe.step) if main is not None and fe.side != "secondary" else {}
    events = sorted((set(ks.tolist()) | set(touched) | {k + 1 for k in touched if k + 1 <= last}) - {0})
    empty = np.zeros(0, np.int64)

    def flags_at(k):
        hit = np.zeros(len(faces), dtype=bool)
        hit[touched.get(k, empty)] = True
        return flagged_nodes(state.copy(), hit, faces, sizes, fe.side)  # a copy: `state` moves on

    flags = flags_at(0) if blocked else np.zeros(len(state), dtype=bool)
    counts = face_counts(fe.rule, flags, faces, sizes)
    records, node_records = [(0, *_corner_changes(np.zeros_like(counts), counts, starts))], [(0, flags.copy())]
    cursor = 0
    for k in events if blocked else ():
        while cursor < len(ks) and ks[cursor] <= k:
            state[nodes[cursor]] = states[cursor]
            cursor += 1
        new = flags_at(k)
        new_counts = face_counts(fe.rule, new, faces, sizes)
        if np.any(new_counts != counts):
            records.append((k, *_corner_changes(counts, new_counts, starts)))
        if np.any(new != flags):
            node_records.append((k, new.copy()))
        flags, counts = new, new_counts
    return _assembled(fe, records, node_records, corners, sizes, last, t_end, exact, main)


def _assembled(fe, records, node_records, corners, sizes, last, t_end, exact, main) -> SampledFlags:
    """The records of changes (cycle k, ...) shifted by the lag to θ = (k + n)·Δt, as crossings."""
    n_corners, n_nodes = int(sizes.sum()), len(node_records[0][1])

    def shifted(k):
        return (k + fe.lag) * fe.step

    corner0 = np.zeros(n_corners, dtype=bool)
    theta, ids, states = [], [], []
    for k, c, s in records:
        if k == 0 and fe.lag == 0:
            corner0[c] = s
        elif k + fe.lag <= last and shifted(k) < t_end:
            theta.append(np.full(len(c), shifted(k)))
            ids.append(c)
            states.append(s)
    node0 = node_records[0][1] if fe.lag == 0 else np.zeros(n_nodes, dtype=bool)
    n_theta, n_ids, n_states, prev = [], [], [], np.zeros(n_nodes, dtype=bool)
    for k, f in node_records:
        if (k > 0 or fe.lag > 0) and k + fe.lag <= last and shifted(k) < t_end:
            diff = np.flatnonzero(f != prev)
            n_theta.append(np.full(len(diff), shifted(k)))
            n_ids.append(diff)
            n_states.append(f[diff])
        prev = f
    cat = (lambda parts, dtype: np.concatenate(parts).astype(dtype) if parts else np.zeros(0, dtype))
    nodes = Crossings(node0, cat(n_theta, float), cat(n_ids, np.int64), cat(n_states, bool), fe.step)
    evaluations = exact.evaluations + (main.queries if main is not None else 0)
    return SampledFlags(corner0, cat(theta, float), cat(ids, np.int64), cat(states, bool), fe.step, evaluations,
                        exact.unresolved, exact.uncertain, nodes=nodes, corners=corners, face_sizes=sizes.astype(float),
                        scale=fe.sdfblk, rule=fe)


def rule_faces(surface, weights, n: int) -> tuple:
    """(faces (m, 4) int padded with -1, face sizes (m,), corner weights A_e/N_e (corners,) [m^2], total area
    [m^2]) of a leakage surface; a node-based one (``surface`` None, n nodes of ``weights``): one single-node face
    per node, of its own weight."""
    if surface is None:
        faces, sizes = np.pad(np.arange(n)[:, None], ((0, 0), (0, 3)), constant_values=-1), np.ones(n, np.int64)
        return faces, sizes, np.asarray(weights, dtype=float), float(np.sum(weights))
    faces, sizes = np.asarray(surface.faces), np.asarray(surface.face_sizes)
    faces = np.pad(faces, ((0, 0), (0, 4 - faces.shape[1])), constant_values=-1)
    return faces, sizes, np.repeat(surface.face_areas / sizes, sizes), surface.total_area


def fe_leak_track(scene, j, exact: Crossings, surface, path, weights, driver, options: dict):
    """The :class:`cases.model.area_track.AreaTrack` of exchange j under the scene's FE rule: the sampled corner
    crossings of the exact ones, each corner weighing A_e/N_e of its face (a node-based surface: one corner per
    node, its own weight), the leak fraction of the blocked area and SDFBLK folded into the permeability."""
    from cases.model.area_track import AreaTrack

    spec, e = scene.blockage, scene.exchange[j]
    n = len(path.x0)
    faces, sizes, corner_w, total = rule_faces(surface, weights, n)
    fe = fe_rule(spec, node_based=surface is None)
    main = None
    if fe.side != "secondary" and e.blocked_by:
        bodies = [driver.bodies[name][0] for name in e.blocked_by]
        main = MainSegments(bodies, lambda t: path.positions(np.full(n, float(t)), np.arange(n)), faces, sizes,
                            e.contact_tolerance or 1e-300, e.penetration_depth, moving=path.trajectory is not None
                            or path.scale is not None)
    flags = sampled_flags(fe, exact, faces, sizes, scene.time.end, main, rule_blocks(spec, e))
    options = {**options, "permeability": sampled_permeability(spec, e)}
    track = AreaTrack.build(corner_w, total, flags, driver.lo, driver.hi, **options)
    if surface is not None and path.trajectory is not None:
        track = track.on_trajectory(*path.trajectory, faces, sizes, flag_faces=flags.corners)
    return track
