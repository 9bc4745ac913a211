"""The dynamic body against its seat: rest position, reaction, the seat and kink switches, impacts and lift-offs
(a mixin of :class:`cases.model.scene_network.SceneNetwork`; the contact laws are :mod:`exchange.contact`)."""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from exchange.network_switches import _labelled

__all__ = ["SeatModes"]


class SeatModes:
    """Needs ``body``, ``contact``, ``held``, ``contact_log``, ``forces``, ``body_offset``, ``applied_force``,
    ``states``, ``input_time``."""

    def begin_segment(self, t0, t1, y0=None):
        super().begin_segment(t0, t1, y0)
        self.lifting = self.lifting_side(y0) if y0 is not None else 0.0

    def lifting_side(self, y) -> float:
        """σ when the free body rests on its hard seat (v = 0 exactly, a closed node), else 0.

        Freed at rest (a lift-off, or an impact whose reaction is not compressive), the body can leave the seat
        along σ only; its acceleration there is zero to round-off, so a probe of the turning-point switch v = 0
        would take its direction from a rounding error. The switch is watched for the return instead (−σ).
        """
        c, k = self.contact, self.body_offset
        if c is None or not c.hard or self.held or y[k + 1] != 0.0:
            return 0.0
        return c.held_sigma(y[k])

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

    def lowered_contact(self):
        """The seat contact as arrays for the compiled path (:mod:`exchange.compiled_body`): (1, held, force
        scale, law vector), the node table and the kink displacements; None without contact."""
        c = self.contact
        if c is None:
            return None
        head = np.concatenate([[1.0, float(self.held), self.force_scale()], c.law_vector])
        return head, c.table, np.asarray(c.thresholds(), dtype=float)

    def log_contact_events(self, events) -> None:
        """The contact log of a compiled run, from its events: (t, label, state before, state after, mode
        before) each, as :meth:`_seat_event` and :meth:`_log_touch` log them on the Python path."""
        k, c = self.body_offset, self.contact
        for t, label, before, after, mode in events:
            kind = label.rpartition(":")[2]
            if kind == "seat" and mode[2]:
                self.contact_log.append((t, "lift-off", 0.0, self._pressure(t, before)))
            elif kind == "seat":
                reach = np.flatnonzero(c.reach)
                i = reach[int(np.argmin(c.gaps(before[k])[reach]))]
                approach = -c.sigma[i] * before[k + 1]
                if approach > 0.0:
                    self.contact_log.append((t, "impact", float(approach), self._pressure(t, after)))
            elif kind.startswith("kink-"):
                self._log_touch(t, before)

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
