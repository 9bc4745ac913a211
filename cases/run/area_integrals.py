"""Time integrals of leakage-area tracks, exact where the areas are steps: the blocked area·time of a run and the
L1 distance between two tracks, the measures `ventsim compare` reports.

A track (:class:`cases.model.area_track.AreaTrack`, θ = time) is constant between its crossings when its faces do
not move; then every integral here is a sum over the pieces between the union of the breakpoints, exact. When the
surface scales with its cavity mesh or follows a trajectory, each piece is integrated with 5-point Gauss–Legendre
(the face areas are smooth between frames: the error is far below the sampling differences being measured).
"""
from __future__ import annotations

import numpy as np

__all__ = ["breakpoints", "leak_area_time", "blocked_area_time", "area_distance", "TimeSteps", "time_steps"]

_X, _W = np.polynomial.legendre.leggauss(5)


def breakpoints(tracks, t0: float, t1: float) -> np.ndarray:
    """Sorted times in [t0, t1] where any of ``tracks`` may change its rule of area: crossings, frames, knots."""
    pts = [np.array([t0, t1])]
    for tr in tracks:
        pts += [np.asarray(tr.crossings, dtype=float), tr.frame_times]
        if tr.scale is not None:
            pts.append(np.asarray(tr.scale.x, dtype=float))
    pts = np.unique(np.concatenate(pts))
    return pts[(pts >= t0) & (pts <= t1)]


def _smooth(track) -> bool:
    return track.moving is not None or track.scale is not None


def _integral(tracks, t0: float, t1: float, integrand) -> float:
    """∫ integrand(areas of ``tracks`` at t) dt over [t0, t1], piece by piece between the breakpoints."""
    edges = breakpoints(tracks, t0, t1)
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        if not b > a:
            continue
        mid = 0.5 * (a + b)
        idx = [tr.interval(mid) for tr in tracks]
        if not any(_smooth(tr) for tr in tracks):
            total += float(integrand([tr.area_in(i, mid) for tr, i in zip(tracks, idx)])) * (b - a)
            continue
        xs = mid + 0.5 * (b - a) * _X
        vals = [integrand([tr.area_in(i, x) for tr, i in zip(tracks, idx)]) for x in xs]
        total += 0.5 * (b - a) * float(np.dot(_W, vals))
    return float(total)


def leak_area_time(track, t0: float, t1: float) -> float:
    """∫ A_leak dt over [t0, t1] [m^2·s]."""
    return _integral([track], t0, t1, lambda a: a[0])


def blocked_area_time(track, t0: float, t1: float) -> float:
    """∫ (A_open − A_leak) dt over [t0, t1] [m^2·s]: the area the blockage took away, times how long.

    >>> from types import SimpleNamespace as NS
    >>> tr = NS(crossings=np.array([1.0, 2.0]), frame_times=np.zeros(0), scale=None, moving=None,
    ...         interval=lambda t: int(np.searchsorted([1.0, 2.0], t, side="right")),
    ...         area_in=lambda i, t: [4.0, 1.0, 4.0][i], open_area=lambda t: 4.0)
    >>> blocked_area_time(tr, 0.0, 3.0)
    3.0
    """
    return _open_time(track, t0, t1) - leak_area_time(track, t0, t1)


def _open_time(track, t0: float, t1: float) -> float:
    """∫ A_open dt [m^2·s] (the unblocked leakage area)."""
    if not _smooth(track):
        return float(track.open_area(t0)) * (t1 - t0)
    edges = breakpoints([track], t0, t1)
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        xs = 0.5 * (a + b) + 0.5 * (b - a) * _X
        total += 0.5 * (b - a) * float(np.dot(_W, [track.open_area(x) for x in xs]))
    return float(total)


def area_distance(a, b, t0: float, t1: float) -> float:
    """∫ |A_a − A_b| dt over [t0, t1] [m^2·s]: how far apart two tracks of the same exchange are."""
    return _integral([a, b], t0, t1, lambda v: abs(v[0] - v[1]))


class TimeSteps:
    """A leakage area that is a step function of time: ``times`` (k,) [s] where it changes, ``areas`` (k + 1,)
    [m^2] before, between and after them, ``open`` [m^2] the area with nothing blocked. It reads as an area track of
    time (crossings, interval, area_in, open_area), for the integrals above."""

    frame_times, scale, moving = np.zeros(0), None, None

    def __init__(self, times, areas, open_area: float):
        self.crossings, self.areas = np.asarray(times, dtype=float), np.asarray(areas, dtype=float)
        self._open = float(open_area)

    def interval(self, t: float) -> int:
        return int(np.searchsorted(self.crossings, t, side="right"))

    def area_in(self, i: int, t: float) -> float:
        return float(self.areas[i])

    def __call__(self, t: float) -> float:
        return self.area_in(self.interval(t), t)

    def open_area(self, t: float) -> float:
        return self._open


def time_steps(track, trajectory, j: int) -> TimeSteps:
    """The area of exchange j in time from a run's ``trajectory`` when its ``track`` is one of the dynamic body's
    displacement (the area interval of each segment's discrete state; an FE rule's the interval in use)."""
    times, idx = [], []
    for seg, mode in zip(trajectory.segments, trajectory.modes):
        if mode is not None and (not idx or mode.intervals[j] != idx[-1]):
            times.append(float(seg.t_min))
            idx.append(mode.intervals[j])
    areas = track.areas[idx] if idx else np.array([track.open_area(0.0)])
    return TimeSteps(times[1:], areas, track.open_area(0.0))
