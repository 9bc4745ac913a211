"""The network of a scene with bodies: geometric leakage areas, wrapped volumes and a dynamic impactor.

Extends :class:`exchange.network.network.Network` with two unknowns per dynamic body (displacement s [m] and speed v
[m/s] along its axis) and with exchanges whose area comes from a :class:`cases.model.area_track.AreaTrack`. For
prescribed motion the area's jumps are known times (breakpoints); for a dynamic body they are switch
functions s − s_k on the two crossings next to the body's current displacement.

The dynamic body obeys m·dv/dt = m·g + F_wrap + F_pressure + F_spring + F_contact along its axis
(:class:`BodyForces`). With hard contact (:class:`cases.model.seat_contact.SeatContact`) the body has two modes: *held*
on the seat (s and v frozen, the contact force F_c the reaction balancing the other forces) and *free*. One switch
function per contact, labelled ``<contact>:seat``, is F_c/F_scale while held (it fires when the reaction reaches
zero: lift-off, located exactly) and −g_min/L while free (it fires at impact, where v is set to 0: kinematic
contact is perfectly plastic). Penalty and softened contact add switches at the kinks of their force.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from exchange.network.discrete_state import DiscreteState
from exchange.network.network import Network

from cases.model import scene_seat
from cases.model.scene_lowering import lowered_geometry

__all__ = ["SceneNetwork", "BodyState", "GeometricArea", "BodyForces"]


@dataclass(frozen=True)
class BodyForces:
    """Forces on the dynamic body besides wrapping and contact: a spring −(preload + k·s) along the axis, and the
    gauge pressure of cavity ``cavity`` on ``area`` [m²] along it."""

    stiffness: float = 0.0
    preload: float = 0.0
    cavity: int | None = None
    area: float = 0.0


@dataclass
class BodyState:
    """The current displacement [m] and speed [m/s] of the dynamic body, shared with its wrapped volume."""

    s: float = 0.0
    v: float = 0.0


@dataclass(frozen=True)
class GeometricArea:
    """The leakage area of one exchange from an AreaTrack; ``by_time``: θ is time, else θ is s."""

    track: object
    by_time: bool


@dataclass
class SceneNetwork(Network):
    """A Network plus bodies. ``areas``: per exchange a GeometricArea or None; ``body``: the dynamic body or None;
    ``pushed``: index of the cavity whose gauge pressure pushes the dynamic body; ``volume_slope(s)``: dV/ds of it;
    ``forces``: its spring and pressure area; ``contact``: its SeatContact (``held``: hard contact holds it now;
    ``contact_log``: (t, kind, approach speed [m/s], pressure of the pressure cavity [Pa]) of every impact,
    lift-off, touch and separation).
    """

    areas: tuple = ()
    body: object = None
    pushed: int | None = None
    volume_slope: object = None
    body_state: BodyState = field(default_factory=BodyState)
    forces: BodyForces = field(default_factory=BodyForces)
    contact: object = None  # cases.model.seat_contact.SeatContact or None
    intervals: list = field(init=False, default_factory=list)
    held: bool = field(init=False, default=False)
    contact_log: list = field(init=False, default_factory=list)  # (t, kind, approach speed, pressure)

    def lowered_geometry(self):
        """Its geometry for the engine (:func:`cases.model.scene_lowering.lowered_geometry`)."""
        return lowered_geometry(self)

    def body_forces(self, t, y) -> tuple:
        """(gas force, acceleration, reaction of a hard seat holding it at rest, gas and spring force) of the
        dynamic body at (t, y) [N, m/s^2, N, N] (:func:`cases.model.scene_seat.body_forces`)."""
        return scene_seat.body_forces(self, t, y)

    def log_contact_events(self, events) -> None:
        """Its contact log from a run's events (:func:`cases.model.scene_seat.log_contact_events`)."""
        scene_seat.log_contact_events(self, events)

    def reset(self) -> None:
        super().reset()
        self.held, self.contact_log = False, []
        self.intervals = [None] * len(self.exchanges)
        if self.body is not None:
            self.body_state.s, self.body_state.v = 0.0, self.body.motion.initial_velocity
        for j, ga in enumerate(self.areas):
            if ga is not None and not ga.by_time:
                self.intervals[j] = int(ga.track.start_interval(0.0))

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
            c = self.contact
            if c is not None and c.hard and y[self.body_offset + 1] == 0.0 and c.held_sigma(0.0):
                self.held = self.body_forces(0.0, y)[2] > 0.0
            elif c is not None and not c.hard and y[self.body_offset + 1] == 0.0:
                y[self.body_offset] = scene_seat.rest_position(self, y)
        return y

    @property
    def breakpoints(self) -> tuple:
        pts = list(super().breakpoints)
        for ga in self.areas:
            if ga is not None and ga.by_time:  # area steps, and the kinks of a surface moving between frames
                pts += list(ga.track.crossings) + list(ga.track.frame_times)
        return tuple(pts)

    def base_area(self, index, t):
        ga = self.areas[index] if self.areas else None
        if ga is None:
            return super().base_area(index, t)
        if ga.by_time:
            return ga.track(t)
        return ga.track.area_in(self.intervals[index], self.body_state.s)

    def snapshot(self) -> DiscreteState:
        return replace(super().snapshot(), intervals=tuple(self.intervals), held=self.held)

    def restore(self, mode: DiscreteState | None) -> None:
        if mode is not None:
            super().restore(mode)
            self.intervals, self.held = list(mode.intervals), mode.held

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
