"""The blocked leakage areas of a scene network: intervals of the dynamic body's displacement, their switches,
and the arrays the compiled path takes for prescribed motion (a mixin of :class:`cases.model.scene_network.SceneNetwork`)."""
from __future__ import annotations

import numpy as np

from exchange.network_switches import _labelled

__all__ = ["GeometricAreas", "REDERIVE_SLACK"]

#: A dynamic body's area interval is re-derived from its displacement at a restart when the displacement lies
#: outside the interval by more than this fraction of the track's range of θ.
REDERIVE_SLACK = 1e-7


class GeometricAreas:
    """Needs ``areas``, ``intervals``, ``exchanges``, ``cavities``, ``body``, ``contact``, ``body_offset``."""

    def begin_segment(self, t0, t1, y0=None):
        super().begin_segment(t0, t1, y0)
        if y0 is not None and self.body is not None:
            self._rederive_intervals(float(y0[self.body_offset]))
            vol = self._pushed_spline()
            if vol is not None:
                vol.lock(float(y0[self.body_offset]), float(y0[self.body_offset + 1]))

    def _pushed_spline(self):
        """The volume spline of the dynamic body's displacement of the cavity it intrudes into, or None."""
        if self.body is None or self.pushed is None:
            return None
        vol = self.cavities[self.pushed].volume
        return vol if hasattr(vol, "lock") else None

    def _unlock_spline(self) -> None:
        vol = self._pushed_spline()
        if vol is not None:
            vol.unlock()

    def _knot_events(self) -> list:
        """Switches (s − x_k)/span on the knots bounding the piece of the pushed cavity's volume spline held
        this segment (:meth:`cases.model.wrapped_volume.WrappedVolume.lock`): s leaves the piece through them."""
        vol = self._pushed_spline()
        if vol is None or vol.piece is None:
            return []
        below, above, span = vol.knots_around()
        k, name, out = self.body_offset, self.cavities[self.pushed].name, []
        if below is not None:
            out.append(_directed(lambda t, y, c=below: (y[k] - c) / span, f"{name}:knot-down", -1.0))
        if above is not None:
            out.append(_directed(lambda t, y, c=above: (y[k] - c) / span, f"{name}:knot-up", 1.0))
        return out

    def _rederive_intervals(self, s: float) -> None:
        """Make each area interval hold the body's displacement s (a crossing passed inside the step of a
        turning point is caught here, at the restart, so a release is never missed)."""
        for j, ga in enumerate(self.areas):
            if ga is None or ga.by_time:
                continue
            below, above = ga.track.crossings[:self.intervals[j]], ga.track.crossings[self.intervals[j]:]
            slack = REDERIVE_SLACK * ga.track.span  # a restart at a crossing event lies within the solver's error
            if (len(below) and s < below[-1] - slack) or (len(above) and s > above[0] + slack):
                self.intervals[j] = ga.track.interval(s)

    def _turn_event(self) -> list:
        """Turning points of the dynamic body (v = 0) end a segment: between them s is monotone, so each
        crossing switch s − s_k can change sign only once."""
        k, scale = self.body_offset + 1, max(abs(self.body.motion.initial_velocity), 1e-3)
        lifting = self.lifting  # freed at rest on its seat: it can only return (SeatModes)
        g = lambda t, y: y[k] / scale  # noqa: E731
        return [_directed(g, f"{self.body.name}:turn", -lifting) if lifting else _labelled(g, f"{self.body.name}:turn")]

    def _area_events(self) -> list:
        """Switches s − s_k on the crossings next to the dynamic body's displacement, per blocked exchange."""
        out = []
        for j, ga in enumerate(self.areas):
            if ga is None or ga.by_time:
                continue
            i, crossings, name = self.intervals[j], ga.track.crossings, self.exchanges[j].name
            scale = max(ga.track.total_area ** 0.5, 1e-6)
            k = self.body_offset
            if i > 0:
                out.append(_directed(lambda t, y, c=crossings[i - 1]: (y[k] - c) / scale, f"{name}:contact-down",
                                     -1.0))
            if i < len(crossings):
                out.append(_directed(lambda t, y, c=crossings[i]: (y[k] - c) / scale, f"{name}:contact-up", 1.0))
        return out

    def lowered_geometry(self):
        """The geometry as arrays for the compiled path (:func:`exchange.compiled.lower`): per blocked exchange its
        area steps (crossing times, area after each), scale table, whether it follows the dynamic body, its switch
        scale and the pack of a surface on a vertex trajectory (:mod:`blockage.moving_area`) or None; per wrapped
        cavity its volume spline of time (of the dynamic body's displacement for the cavity it intrudes into), the
        dynamic body and its seat contact; or why it cannot be lowered (a moving surface blocked by the dynamic
        body: scenes refuse it at load, :func:`cases.model.build_leak.build_leak_area`)."""
        areas, volumes = {}, {}
        for j, ga in enumerate(self.areas):
            if ga is None:
                continue
            track = ga.track
            if track.moving is not None and not ga.by_time:
                return f"exchange {self.exchanges[j].name}: a leakage surface on a vertex trajectory, blocked by " \
                       "the dynamic body"
            scale = track.scale if track.effective_area is None else None
            areas[j] = (np.asarray(track.crossings, dtype=float), track.areas, scale, not ga.by_time,
                        max(track.total_area ** 0.5, 1e-6), track.moving)
        for i, cav in enumerate(self.cavities):
            vol = cav.volume
            if hasattr(vol, "spline"):
                volumes[cav.name] = (vol.spline.x, vol.spline.c, self.body is not None and i == self.pushed)
        return {"areas": areas, "volumes": volumes, "body": self._lowered_body(), "contact": self.lowered_contact()}

    def _lowered_body(self):
        """The dynamic body's parameters for :func:`exchange.compiled_body.body_rhs`, or None."""
        if self.body is None:
            return None
        m, f = self.body.motion, self.forces
        span = max([ga.track.span for ga in self.areas if ga is not None] + [1.0])
        return (float(self.body_offset), m.mass, m.gravity, -1 if self.pushed is None else self.pushed,
                -1 if f.cavity is None else f.cavity, f.area, f.stiffness, f.preload,
                max(abs(m.initial_velocity), 1e-3), REDERIVE_SLACK * span)

    def wrap_mode(self, mode, intervals=None, held=False):
        """A plain network's snapshot (from the compiled path) as this network's."""
        if intervals is None:
            return mode, tuple(self.intervals), held
        by_s = [ga is not None and not ga.by_time for ga in self.areas] if self.areas else [False] * len(intervals)
        return mode, tuple(int(i) if s else None for i, s in zip(intervals, by_s)), held


def _directed(g, label, direction):
    """A switch function that can only cross one way (s leaves its interval through that end)."""
    g = _labelled(g, label)
    g.direction = direction
    return g
