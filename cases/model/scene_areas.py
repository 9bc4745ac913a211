"""The blocked leakage areas, wrapped volumes and dynamic body of a scene network as the arrays the compiled engine
takes (its switches on the body's area intervals and volume-spline knots: :mod:`exchange.compiled_modes`; a mixin
of :class:`cases.model.scene_network.SceneNetwork`)."""
from __future__ import annotations

import numpy as np

__all__ = ["GeometricAreas", "REDERIVE_SLACK"]

#: A dynamic body's area interval is re-derived from its displacement at a restart when the displacement lies
#: outside the interval by more than this fraction of the track's range of θ.
REDERIVE_SLACK = 1e-7


class GeometricAreas:
    """Needs ``areas``, ``intervals``, ``exchanges``, ``cavities``, ``body``, ``contact``, ``body_offset``."""

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
