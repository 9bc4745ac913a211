"""The leakage area of one exchange along θ, built incrementally from its crossings.

Between two crossings the active set is constant. The obstruction Σ_e A_e·N_c/N_e equals Σ_i a_i·w_i over the
nodes (a_i = 1 when active), with the node weight w_i = Σ_{e ∋ i} A_e/N_e (a node-based surface: its node's area,
or 1 with an effective area). A crossing flips one node, so it changes the obstruction by ±w_i: the obstruction on
every interval is one cumulative sum over the crossings in θ order, O(c) after an O(c log c) sort, instead of an
evaluation of the whole surface per interval.

The leakage area then follows :func:`blockage.areas.leak_area`. When the surface moves with its cavity mesh the
face areas change with θ: a uniformly scaled mesh scales every A_e by s(θ)² (so the area does, or not at all with an
effective area, which keeps only the blocked fraction); a surface on a vertex trajectory (θ is time) has face
areas that change within an interval: its area at θ is :func:`blockage.moving_area.moving_leak_area` of the pack
``moving`` (face-area coefficients per frame interval and the crossings replayed by a cursor), the one evaluation
the compiled path runs too.
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, field, replace

import numpy as np

from blockage.areas import leak_area
from blockage.moving_area import area_coefficients, moving_frame_times, moving_leak_area, pack

from cases.model.gaps import table_values

__all__ = ["AreaTrack", "node_weights", "MERGE_CROSSINGS"]

#: Crossings closer than this fraction of the θ range are one switch (nodes of a row that touch together).
MERGE_CROSSINGS = 1e-12


def node_weights(face_areas, faces, face_sizes, n: int) -> np.ndarray:
    """(n,) w_i = Σ over the faces holding node i of A_e / N_e [m^2]."""
    faces = np.asarray(faces)
    share = np.asarray(face_areas, dtype=float) / np.asarray(face_sizes, dtype=float)
    w = np.zeros(n)
    for k in range(faces.shape[1]):
        ok = faces[:, k] >= 0
        np.add.at(w, faces[ok, k], share[ok])
    return w


def _previous_states(crossings) -> np.ndarray:
    """State of each crossing's node just before it (the node's previous crossing, or its initial state)."""
    node, state = crossings.node, crossings.state
    order = np.lexsort((np.arange(len(node)), node))  # by node, then in θ order
    prev = np.empty(len(node), dtype=bool)
    first = np.ones(len(order), dtype=bool)
    first[1:] = node[order][1:] != node[order][:-1]
    shifted = np.empty(len(order), dtype=bool)
    shifted[1:] = state[order][:-1]
    shifted[first] = crossings.initial[node[order][first]]
    prev[order] = shifted
    return prev


@dataclass
class AreaTrack:
    """Leakage area of one exchange, piecewise in θ: ``crossings`` (distinct, sorted); interval i is
    [crossings[i−1], crossings[i]) with ``obstruction[i]`` and ``actives[i]`` (at the reference face areas).

    ``scale``: the surface's mesh scale table s(θ) (areas × s²); ``moving``: the pack of
    :mod:`blockage.moving_area` of a surface on a vertex trajectory (:meth:`on_trajectory`), else None;
    ``source``: the :class:`cases.model.crossings.Crossings` it was built from."""

    crossings: np.ndarray
    obstruction: np.ndarray
    actives: np.ndarray
    total_area: float
    effective_area: float | None = None
    permeability: float = 0.0
    scale: object = None
    moving: np.ndarray | None = None
    span: float = 1.0  # hi − lo of θ
    source: object = field(default=None, repr=False)
    applied: np.ndarray | None = field(default=None, repr=False)  # raw crossings replayed in interval i

    @classmethod
    def build(cls, weights, total, crossings, lo, hi, **options) -> "AreaTrack":
        delta = (crossings.state.astype(float) - _previous_states(crossings)) if len(crossings.theta) else \
            np.zeros(0)
        obstruction = float(np.dot(crossings.initial, weights)) + np.concatenate([[0.0], np.cumsum(
            delta * weights[crossings.node])]) if len(delta) else np.array([float(np.dot(crossings.initial, weights))])
        actives = int(crossings.initial.sum()) + np.concatenate([[0], np.cumsum(delta).astype(np.int64)])
        theta = crossings.theta
        applied = np.zeros(1, dtype=np.int64)
        if len(theta):  # one switch per group of crossings closer than the merge distance: the value after all
            start = np.diff(theta, prepend=-np.inf) > MERGE_CROSSINGS * (hi - lo)
            last = np.append(start[1:], True)
            theta = theta[start]
            obstruction = np.concatenate([obstruction[:1], obstruction[1:][last]])
            actives = np.concatenate([actives[:1], actives[1:][last]])
            applied = np.concatenate([[0], np.flatnonzero(last) + 1])
        obstruction = np.where(actives == 0, 0.0, np.where(actives == len(weights), float(total), obstruction))
        return cls(theta, np.clip(obstruction, 0.0, float(total)), actives, float(total), span=hi - lo, source=crossings, applied=applied,
                   **options)

    @property
    def areas(self) -> np.ndarray:
        """(intervals,) leakage area of each interval at the reference face areas [m^2]."""
        return np.array([max(leak_area(self.total_area, float(o), self.effective_area, self.permeability), 0.0)
                         for o in self.obstruction])

    def grouped(self, window: float) -> "AreaTrack":
        """The same track with each cluster of crossings spanning at most ``window`` replaced by one switch.

        Over a cluster [a, b] the obstruction goes from O₀ to O₁ through several steps. One step at
        t* = (I + O₀·a − O₁·b)/(O₀ − O₁), where I is the exact ∫_a^b O dt, keeps the blocked area·time exact (and
        every value is one the surface takes); the flow it changes is second order, ≈ |O₁ − O₀|·window²·|dφ/dt|/12
        for a flow law φ per unit area. Clusters whose net change is zero, or whose t* falls outside [a, b], are
        kept as they are."""
        theta, obs, act = self.crossings, self.obstruction, self.actives
        keep_t, keep_o, keep_a = [], [obs[0]], [act[0]]
        i, n = 0, len(theta)
        while i < n:
            j = i
            while j + 1 < n and theta[j + 1] - theta[i] <= window:
                j += 1
            a, b, o0, o1 = theta[i], theta[j], obs[i], obs[j + 1]
            area_time = float(np.dot(obs[i + 1:j + 1], np.diff(theta[i:j + 1]))) if j > i else 0.0
            t_star = (area_time + o0 * a - o1 * b) / (o0 - o1) if j > i and o0 != o1 else np.nan
            if j > i and a <= t_star <= b:
                keep_t.append(t_star)
                keep_o.append(o1)
                keep_a.append(act[j + 1])
            else:
                j = i
                keep_t.append(theta[i])
                keep_o.append(obs[i + 1])
                keep_a.append(act[i + 1])
            i = j + 1
        return AreaTrack(np.array(keep_t), np.array(keep_o), np.array(keep_a), self.total_area, self.effective_area,
                         self.permeability, self.scale, None, self.span, self.source, None)

    def active_at(self, theta: float) -> np.ndarray:
        """(n,) bool: the active nodes at θ (right limit at a crossing), from the crossings found."""
        return self.source.active_at(theta)

    def start_interval(self, theta: float = 0.0) -> int:
        """The interval a run starts in when θ is the dynamic body's displacement: the one holding θ."""
        return self.interval(theta)

    def interval(self, theta: float) -> int:
        return bisect.bisect_right(self.crossings, theta)

    def neighbours(self, theta: float) -> tuple:
        """The crossings just below and just above θ (±inf when none)."""
        i = self.interval(theta)
        return (self.crossings[i - 1] if i > 0 else -np.inf), (self.crossings[i] if i < len(self.crossings) else np.inf)

    def __call__(self, theta: float) -> float:
        return self.area_in(self.interval(theta), theta)

    def area_in(self, i: int, theta: float) -> float:
        """Leakage area [m^2] at θ with the active set of interval i."""
        if self.moving is not None:
            return float(moving_leak_area(self.moving, int(i), float(theta)))
        s2 = self._area_scale(theta)
        return max(leak_area(self.total_area * s2, float(self.obstruction[i]) * s2, self.effective_area,
                             self.permeability), 0.0)

    def _area_scale(self, theta: float) -> float:
        """s(θ)² of a surface scaled with its cavity mesh (face areas × s²), else 1."""
        return float(table_values(self.scale, np.array([theta]))[0]) ** 2 if self.scale is not None else 1.0

    def open_area(self, theta: float) -> float:
        """Leakage area [m^2] at θ with no node active."""
        if self.moving is not None:
            return float(moving_leak_area(self.moving, -1, float(theta)))
        s2 = self._area_scale(theta)
        return float(leak_area(self.total_area * s2, 0.0, self.effective_area, self.permeability))

    def smallest_area(self, lo: float, hi: float, extra=()) -> tuple:
        """(area [m^2], θ, interval) of the smallest leakage area over [lo, hi] (:func:`smallest_area`)."""
        return smallest_area(self, lo, hi, extra)

    @property
    def frame_times(self) -> np.ndarray:
        """Frame times [s] of a surface on a vertex trajectory (its face areas have kinks there), else empty."""
        return moving_frame_times(self.moving) if self.moving is not None else np.zeros(0)

    def on_trajectory(self, times, vertices, faces, face_sizes, flag_faces=None) -> "AreaTrack":
        """This track for a surface whose nodes move linearly between frames: ``times`` (K,) [s], ``vertices``
        (K, n, 3) [m] (θ is time), with its pack of :mod:`blockage.moving_area` (frame-interval coefficients of
        every face, the crossings of each interval, an effective area and permeability as this track's);
        ``flag_faces``: the ids the crossings' nodes are of, per face (default ``faces``: the crossings are the
        nodes'; the corners of :mod:`cases.model.fe_sampling` otherwise)."""
        src = self.source
        delta = src.state.astype(np.int64) - _previous_states(src).astype(np.int64)
        moving = pack(times, area_coefficients(times, vertices, faces, face_sizes),
                      faces if flag_faces is None else flag_faces, face_sizes, src.initial, self.applied, src.node,
                      delta, self.effective_area, self.permeability)
        return replace(self, moving=moving)


def smallest_area(track: AreaTrack, lo: float, hi: float, extra=()) -> tuple:
    """(area [m^2], θ, interval) of the smallest leakage area of ``track`` over [lo, hi].

    Constant on each interval at fixed face areas: the smallest interval value, at the interval's start. With a
    mesh scale s(θ) (piecewise linear) or a vertex trajectory the area also changes inside an interval: the
    candidates are both sides of every crossing, the scale's knots, the frames and ``extra`` (e.g. output
    times); a bounded Brent search (scipy's ``minimize_scalar``) then refines the best one between its
    neighbouring candidates (the area of moving faces is smooth between frames)."""
    inside = track.crossings[(track.crossings > lo) & (track.crossings <= hi)]
    if track.moving is None and track.scale is None:
        first = track.interval(lo)
        areas = track.areas[first:first + len(inside) + 1]
        k = int(np.argmin(areas))
        return float(areas[k]), float(lo if k == 0 else inside[k - 1]), first + k
    knots = np.asarray(track.scale.x, dtype=float) if track.scale is not None else np.zeros(0)
    pts = np.unique(np.concatenate([[lo, hi], inside, knots, track.frame_times, np.asarray(extra, dtype=float)]))
    pts = pts[(pts >= lo) & (pts <= hi)]
    best, crossing = (np.inf, lo, 0, 0), set(inside.tolist())
    for q, theta in enumerate(pts):  # the right limit at θ and, at a crossing, the left limit
        i = track.interval(theta)
        for side in ((i, i - 1) if theta in crossing and i > 0 else (i,)):
            a = track.area_in(side, theta)
            if a < best[0]:
                best = (a, float(theta), side, q)
    return _refined(track, best, pts)


def _refined(track: AreaTrack, best: tuple, pts: np.ndarray) -> tuple:
    from scipy.optimize import minimize_scalar

    area, theta, i, q = best
    for a, b in ((pts[q - 1] if q else None, theta), (theta, pts[q + 1] if q + 1 < len(pts) else None)):
        if a is None or b is None or not b > a:
            continue
        mid = track.interval(0.5 * (a + b))
        res = minimize_scalar(lambda x: track.area_in(mid, x), bounds=(a, b), method="bounded",
                              options={"xatol": 1e-12 * max(track.span, abs(b)), "maxiter": 200})
        if res.fun < area:
            area, theta, i = float(res.fun), float(res.x), mid
    return area, theta, i
