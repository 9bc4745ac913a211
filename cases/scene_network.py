"""The network of a scene with bodies: geometric leakage areas, wrapped volumes and a dynamic impactor.

Extends :class:`exchange.network.Network` with two unknowns per dynamic body (displacement s [m] and speed v
[m/s] along its axis) and with exchanges whose area comes from a :class:`cases.area_track.AreaTrack`. For
prescribed motion the area's jumps are known times (breakpoints); for a dynamic body they are switch
functions s − s_k on the two crossings next to the body's current displacement.

The dynamic body obeys m·dv/dt = m·g + F_wrap + F_pressure + F_spring + F_contact along its axis
(:class:`BodyForces`). With hard contact (:class:`cases.seat_contact.SeatContact`) the body has two modes: *held*
on the seat (s and v frozen, the contact force F_c the reaction balancing the other forces) and *free*. One switch
function per contact, labelled ``<contact>:seat``, is F_c/F_scale while held (it fires when the reaction reaches
zero: lift-off, located exactly) and −g_min/L while free (it fires at impact, where v is set to 0: kinematic
contact is perfectly plastic). Penalty and softened contact add switches at the kinks of their force.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from exchange.network import Network, _labelled

__all__ = ["SceneNetwork", "BodyState", "GeometricArea", "BodyForces"]


#: A dynamic body's area interval is re-derived from its displacement at a restart when the displacement lies
#: outside the interval by more than this fraction of the track's range of θ.
REDERIVE_SLACK = 1e-7


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
    contact: object = None  # cases.seat_contact.SeatContact or None
    intervals: list = field(init=False, default_factory=list)
    held: bool = field(init=False, default=False)
    contact_log: list = field(init=False, default_factory=list)  # (t, kind, approach speed, pressure)

    def reset(self) -> None:
        super().reset()
        self.held, self.contact_log = False, []
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
            c = self.contact
            if c is not None and c.hard and y[self.body_offset + 1] == 0.0 and c.held_sigma(0.0):
                self.held = self.reaction(0.0, y) > 0.0
            elif c is not None and not c.hard and y[self.body_offset + 1] == 0.0:
                y[self.body_offset] = self.rest_position(y)
        return y

    def rest_position(self, y) -> float:
        """Displacement s [m] at which a body at rest on a penalty or softened seat is in static equilibrium.

        A body that starts at rest touching its seat while the other forces push it in (a preloaded poppet) starts
        at the overclosure that carries them, so it does not ring on the contact spring; otherwise 0. The root of
        the net force F(s) = F_applied(s) + m·g + F_seat(s, v=0) is bracketed by doubling steps into the seat and
        found by Brent's method to round-off.
        """
        k, m, c = self.body_offset, self.body.motion, self.contact
        sigma = c.held_sigma(0.0)  # the seat pushes the body along +sigma; 0: no closed node at s = 0
        y = np.array(y, dtype=float)

        def net(s):
            y[k] = s
            return self.applied_force(y, self.states(0.0, y)) + m.mass * m.gravity + c.force(s, 0.0)

        if sigma == 0.0 or net(0.0) * sigma >= 0.0:
            return 0.0
        inside, step = 0.0, 1e-12 * c.size
        while net(-sigma * step) * sigma < 0.0:
            inside, step = step, 2.0 * step
            if step > c.size:
                raise ValueError(f"contact {c.name!r}: the seat cannot carry the forces pressing {c.body!r} into it "
                                 f"within an overclosure of {c.size:.3g} m (stiffness too low?)")
        s0 = float(brentq(net, -sigma * inside, -sigma * step, xtol=1e-15 * c.size, rtol=4 * np.finfo(float).eps))
        net(s0)  # leaves the body state at s0
        return s0

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
        return ga.track.area_in(self.intervals[index], self.body_state.s)

    def rhs(self, t, y):
        dy = super().rhs(t, y)  # states() has set body_state from y
        if self.body is not None and not self.held:
            k, m = self.body_offset, self.body.motion
            force = self.applied_force(y, self.last_states)
            if self.contact is not None:
                force += self.contact.force(y[k], y[k + 1])
            dy[k] = y[k + 1]
            dy[k + 1] = m.gravity + force / m.mass
        return dy

    def applied_force(self, y, states) -> float:
        """Force on the dynamic body along its axis from wrapping, pressure area and spring [N] (not gravity)."""
        k, f, force = self.body_offset, self.forces, 0.0
        if self.pushed is not None:
            p = states[self.pushed].pressure
            force += (p - self.ambient.pressure) * self.volume_slope(y[k])  # dV/ds < 0 while intruding
        if f.cavity is not None:
            force += (states[f.cavity].pressure - self.ambient.pressure) * f.area
        return force - f.preload - f.stiffness * y[k]

    def reaction(self, t, y) -> float:
        """Hard contact held: the seat's reaction F_c [N] (> 0 compressive) balancing the other forces at rest."""
        k, m = self.body_offset, self.body.motion
        net = self.applied_force(y, self.states(self.input_time(t), y)) + m.mass * m.gravity
        return -self.contact.held_sigma(y[k]) * net

    def force_scale(self) -> float:
        m, f = self.body.motion, self.forces
        return max(f.preload + m.mass * abs(m.gravity), 1e-9)

    def _seat_switch(self, t, y):
        c, k = self.contact, self.body_offset
        if self.held:
            return self.reaction(t, y) / self.force_scale()
        return -float(np.min(c.gaps(y[k])[c.reach])) / c.size

    def _contact_events(self) -> list:
        c, k = self.contact, self.body_offset
        if c.hard:
            out = [_labelled(lambda t, y: self._seat_switch(t, y), f"{c.name}:seat")]
            if self.held:
                return out
        else:
            out = []
        for i, s_k in enumerate(c.thresholds()):
            out.append(_labelled(lambda t, y, s_k=s_k: (y[k] - s_k) / c.size, f"{c.name}:kink-{i}"))
        return out

    def begin_segment(self, t0, t1, y0=None):
        super().begin_segment(t0, t1, y0)
        if y0 is not None and self.body is not None:
            self._rederive_intervals(float(y0[self.body_offset]))

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
        return [_labelled(lambda t, y: y[k] / scale, f"{self.body.name}:turn")]

    def events(self):
        out = super().events()
        if self.body is not None and not self.held:
            out += self._turn_event()
        for j, ga in enumerate(self.areas):
            if ga is None or ga.by_time:
                continue
            i, crossings, name = self.intervals[j], ga.track.crossings, self.exchanges[j].name
            scale = max(ga.track.total_area ** 0.5, 1e-6)
            k = self.body_offset
            if i > 0:
                out.append(_directed(lambda t, y, c=crossings[i - 1]: (y[k] - c) / scale, f"{name}:contact-{i}-down",
                                     -1.0))
            if i < len(crossings):
                out.append(_directed(lambda t, y, c=crossings[i]: (y[k] - c) / scale, f"{name}:contact-{i}-up", 1.0))
        if self.contact is not None:
            out += self._contact_events()
        return out

    def on_event(self, t, y, label):
        name, _, kind = label.rpartition(":")
        if kind == "seat":
            return self._seat_event(t, y)
        if kind == "turn":
            return y
        if kind.startswith("kink-"):
            self._log_touch(t, y)
            return y
        if kind.startswith("contact-"):
            j = next(k for k, ex in enumerate(self.exchanges) if ex.name == name)
            self.intervals[j] += 1 if kind.endswith("-up") else -1
            return y
        return super().on_event(t, y, label)

    def _seat_event(self, t, y):
        """Hard contact: lift-off (held -> free) or impact (free -> on the seat with v = 0, held if the reaction is
        compressive; s is set to the exact touching position, as kinematic contact allows no penetration)."""
        k, c = self.body_offset, self.contact
        if self.held:
            self.held = False
            self.contact_log.append((t, "lift-off", 0.0, self._pressure(t, y)))
            return y
        reach = np.flatnonzero(c.reach)
        i = reach[int(np.argmin(c.gaps(y[k])[reach]))]
        approach = -c.sigma[i] * y[k + 1]
        if approach <= 0.0:  # not approaching: the gap has just opened
            return y
        y = np.array(y, dtype=float)
        y[k], y[k + 1] = -c.g0[i] / c.sigma[i], 0.0
        self.held = self.reaction(t, y) > 0.0
        self.contact_log.append((t, "impact", float(approach), self._pressure(t, y)))
        return y

    def _pressure(self, t, y) -> float:
        f = self.forces.cavity
        return float(self.states(self.input_time(t), y)[f].pressure) if f is not None else float("nan")

    def _log_touch(self, t, y):
        """Penalty/softened contact: record first touch and full separation (the kinks where g_min = 0)."""
        k, c = self.body_offset, self.contact
        reach = np.flatnonzero(c.reach)
        i = reach[int(np.argmin(c.gaps(y[k])[reach]))]
        if abs(c.gaps(y[k])[i]) <= 1e-9 * c.size:
            approach = float(-c.sigma[i] * y[k + 1])
            self.contact_log.append((t, "touch" if approach > 0 else "separate", approach, self._pressure(t, y)))

    def lowered_geometry(self):
        """The geometry as arrays for the compiled path (:func:`exchange.compiled.lower`): per blocked exchange its
        area steps (crossing times, area after each) and scale table, per wrapped cavity its volume spline of
        time; or why it cannot be lowered (a dynamic body, a moving surface, a pop vent on a blocked area)."""
        if self.body is not None or self.contact is not None:
            return "a dynamic body"
        areas, volumes = {}, {}
        for j, ga in enumerate(self.areas):
            if ga is None:
                continue
            track, act = ga.track, self.exchanges[j].activation
            if track.weights_at is not None:
                return f"exchange {self.exchanges[j].name}: a leakage surface on a vertex trajectory"
            if act is not None and act.pop_pressure is not None:
                return f"exchange {self.exchanges[j].name}: a pop vent on a blocked leakage area"
            scale = track.scale if track.effective_area is None else None
            areas[j] = (np.asarray(track.crossings, dtype=float), track.areas, scale)
        for cav in self.cavities:
            vol = cav.volume
            if hasattr(vol, "spline"):
                volumes[cav.name] = (vol.spline.x, vol.spline.c)
        return {"areas": areas, "volumes": volumes}

    def wrap_mode(self, mode):
        """A plain network's snapshot (from the compiled path) as this network's."""
        return mode, tuple(self.intervals), False

    def snapshot(self):
        return super().snapshot(), tuple(self.intervals), self.held

    def restore(self, mode):
        if mode is not None:
            super().restore(mode[0])
            self.intervals, self.held = list(mode[1]), mode[2]

    def describe(self, t, y):
        text = super().describe(t, y)
        if self.body is not None:
            text += f"; {self.body.name}: s {y[self.body_offset]:.6g} m, v {y[self.body_offset + 1]:.6g} m/s"
        return text

    def impactor_energy(self, y) -> float:
        """Energy the dynamic body has given up since t = 0: ½m(v0² − v²) + m·g·s [J]."""
        m, k = self.body.motion, self.body_offset
        return 0.5 * m.mass * (m.initial_velocity ** 2 - y[k + 1] ** 2) + m.mass * m.gravity * y[k]


def _directed(g, label, direction):
    """A switch function that can only cross one way (s leaves its interval through that end)."""
    g = _labelled(g, label)
    g.direction = direction
    return g


def first_contact(track):
    """θ of the first crossing after which some node is active (None if the track never blocks)."""
    for c, n in zip(track.crossings, track.actives[1:]):
        if n > 0:
            return float(c)
    return None
