"""A scene network's geometry as the engine takes it (:class:`exchange.engine.geometry.Geometry`): its blocked
leakage areas, wrapped volumes, dynamic body and seat."""
from __future__ import annotations

import numpy as np

from exchange.engine.geometry import AreaSteps, BodyParameters, Geometry, Seat, VolumeSpline

__all__ = ["lowered_geometry", "force_scale", "REDERIVE_SLACK"]

#: A dynamic body's area interval is re-derived from its displacement at a restart when the displacement lies
#: outside the interval by more than this fraction of the track's range of θ.
REDERIVE_SLACK = 1e-7


def lowered_geometry(net) -> Geometry | str:
    """The geometry of a :class:`cases.model.scene_network.SceneNetwork`: per blocked exchange its area steps (of
    time, or of the dynamic body's displacement), per wrapped cavity its volume spline, the dynamic body and its
    seat; or why it cannot be lowered (a moving surface blocked by the dynamic body: scenes refuse it at load,
    :func:`cases.model.build_leak.build_leak_area`)."""
    areas, volumes = {}, {}
    for j, ga in enumerate(net.areas):
        if ga is None:
            continue
        track = ga.track
        if track.moving is not None and not ga.by_time:
            return f"exchange {net.exchanges[j].name}: a leakage surface on a vertex trajectory, blocked by the " \
                   "dynamic body"
        areas[j] = AreaSteps(np.asarray(track.crossings, dtype=float), track.areas,
                             track.scale if track.effective_area is None else None, not ga.by_time,
                             max(track.total_area ** 0.5, 1e-6), track.moving, getattr(track, "sampling", None))
    for i, cav in enumerate(net.cavities):
        if hasattr(cav.volume, "spline"):
            spline = cav.volume.spline
            volumes[cav.name] = VolumeSpline(spline.x, spline.c, net.body is not None and i == net.pushed)
    return Geometry(areas, volumes, _body(net), _seat(net))


def _body(net) -> BodyParameters | None:
    if net.body is None:
        return None
    m, f = net.body.motion, net.forces
    span = max([ga.track.span for ga in net.areas if ga is not None] + [1.0])
    return BodyParameters(net.body_offset, m.mass, m.gravity, -1 if net.pushed is None else net.pushed,
                          -1 if f.cavity is None else f.cavity, f.area, f.stiffness, f.preload,
                          max(abs(m.initial_velocity), 1e-3), REDERIVE_SLACK * span)


def force_scale(net) -> float:
    """The force scale of the seat's lift-off switch [N]: preload plus weight (at least 1e-9 N)."""
    m, f = net.body.motion, net.forces
    return max(f.preload + m.mass * abs(m.gravity), 1e-9)


def _seat(net) -> Seat | None:
    c = net.contact
    if c is None:
        return None
    return Seat(c.law_vector, c.merged, np.asarray(c.thresholds(), dtype=float), bool(net.held), force_scale(net),
                c.hard)

