"""The network of a scene with bodies: geometric leakage areas, wrapped volumes and a dynamic impactor.

Extends :class:`exchange.network.Network` with two unknowns per dynamic body (displacement s [m] and speed v
[m/s] along its axis) and with exchanges whose area comes from a :class:`cases.geometry.BlockedArea`. For
prescribed motion the area's jumps are known times (breakpoints); for a dynamic body they are switch
functions s − s_k on the two crossings next to the body's current displacement.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from exchange.network import Network, _labelled

__all__ = ["SceneNetwork", "BodyState", "GeometricArea"]


@dataclass
class BodyState:
    """The current displacement [m] and speed [m/s] of the dynamic body, shared with its wrapped volume."""

    s: float = 0.0
    v: float = 0.0


@dataclass(frozen=True)
class GeometricArea:
    """The leakage area of one exchange from a BlockedArea track; ``by_time``: θ is time, else θ is s."""

    track: object
    by_time: bool


@dataclass
class SceneNetwork(Network):
    """A Network plus bodies. ``areas``: per exchange a GeometricArea or None; ``body``: the dynamic body or None;
    ``pushed``: index of the cavity whose gauge pressure pushes the dynamic body; ``volume_slope(s)``: dV/ds of it.
    """

    areas: tuple = ()
    body: object = None
    pushed: int | None = None
    volume_slope: object = None
    body_state: BodyState = field(default_factory=BodyState)
    intervals: list = field(init=False, default_factory=list)

    def reset(self) -> None:
        super().reset()
        self.intervals = [None] * len(self.exchanges)
        if self.body is not None:
            self.body_state.s, self.body_state.v = 0.0, self.body.motion.initial_velocity
        for j, ga in enumerate(self.areas):
            if ga is not None and not ga.by_time:
                self.intervals[j] = int(np.searchsorted(ga.track.crossings, 0.0, side="right"))

    @property
    def body_offset(self) -> int:
        return super().size

    @property
    def size(self) -> int:
        return super().size + (2 if self.body is not None else 0)

    def initial_state(self) -> np.ndarray:
        y = super().initial_state()
        if self.body is not None:
            y[self.body_offset:] = (0.0, self.body.motion.initial_velocity)
        return y

    @property
    def breakpoints(self) -> tuple:
        pts = list(super().breakpoints)
        for ga in self.areas:
            if ga is not None and ga.by_time:
                pts += list(ga.track.crossings)
        return tuple(pts)

    def states(self, t, y):
        if self.body is not None:
            self.body_state.s, self.body_state.v = y[self.body_offset], y[self.body_offset + 1]
        return super().states(t, y)

    def base_area(self, index, t):
        ga = self.areas[index] if self.areas else None
        if ga is None:
            return super().base_area(index, t)
        if ga.by_time:
            return ga.track(t)
        return float(ga.track.areas[self.intervals[index]])

    def rhs(self, t, y):
        dy = super().rhs(t, y)  # states() has set body_state from y
        if self.body is not None:
            k, m = self.body_offset, self.body.motion
            p = self.last_states[self.pushed].pressure
            force = (p - self.ambient.pressure) * self.volume_slope(y[k])  # dV/ds < 0 while intruding
            dy[k] = y[k + 1]
            dy[k + 1] = m.gravity + force / m.mass
        return dy

    def events(self):
        out = super().events()
        for j, ga in enumerate(self.areas):
            if ga is None or ga.by_time:
                continue
            i, crossings, name = self.intervals[j], ga.track.crossings, self.exchanges[j].name
            scale = max(ga.track.total_area ** 0.5, 1e-6)
            k = self.body_offset
            if i > 0:
                out.append(_labelled(lambda t, y, c=crossings[i - 1]: (y[k] - c) / scale, f"{name}:contact-{i}-down"))
            if i < len(crossings):
                out.append(_labelled(lambda t, y, c=crossings[i]: (y[k] - c) / scale, f"{name}:contact-{i}-up"))
        return out

    def on_event(self, t, y, label):
        name, _, kind = label.rpartition(":")
        if kind.startswith("contact-"):
            j = next(k for k, ex in enumerate(self.exchanges) if ex.name == name)
            self.intervals[j] += 1 if kind.endswith("-up") else -1
            return y
        return super().on_event(t, y, label)

    def snapshot(self):
        return super().snapshot() + (tuple(self.intervals),)

    def restore(self, mode):
        if mode is not None:
            super().restore(mode[:3])
            self.intervals = list(mode[3])

    def describe(self, t, y):
        text = super().describe(t, y)
        if self.body is not None:
            text += f"; {self.body.name}: s {y[self.body_offset]:.6g} m, v {y[self.body_offset + 1]:.6g} m/s"
        return text

    def impactor_energy(self, y) -> float:
        """Energy the dynamic body has given up since t = 0: ½m(v0² − v²) + m·g·s [J]."""
        m, k = self.body.motion, self.body_offset
        return 0.5 * m.mass * (m.initial_velocity ** 2 - y[k + 1] ** 2) + m.mass * m.gravity * y[k]


def first_contact(track):
    """θ of the first crossing after which some node is active (None if the track never blocks)."""
    for c, n in zip(track.crossings, track.actives[1:]):
        if n > 0:
            return float(c)
    return None
