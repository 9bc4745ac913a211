"""The dynamic body against its seat: its rest position, the seat's arrays for the compiled engine and the log of
impacts and lift-offs (a mixin of :class:`cases.model.scene_network.SceneNetwork`; the contact laws are
:mod:`exchange.contact.laws`, the seat's switches and what they do :mod:`exchange.compiled_body`)."""
from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from exchange.readback.values import body_values

__all__ = ["SeatModes"]


class SeatModes:
    """Needs ``body``, ``contact``, ``held``, ``contact_log``, ``forces``, ``body_offset``, ``states``,
    ``engine``."""

    def body_forces(self, t, y) -> tuple:
        """(gas force, acceleration, reaction of a hard seat holding it at rest, gas and spring force) of the
        dynamic body at (t, y) [N, m/s^2, N, N], from the compiled engine (:func:`exchange.readback.values.
        body_values`) in the network's current discrete state."""
        fast = self.engine()
        fast.load_discrete_state()
        return body_values(fast, t, y)

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
            return self.body_forces(0.0, y)[3] + m.mass * m.gravity + c.force(s, 0.0)

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

    def force_scale(self) -> float:
        m, f = self.body.motion, self.forces
        return max(f.preload + m.mass * abs(m.gravity), 1e-9)

    def lowered_contact(self):
        """The seat contact as arrays for the compiled path (:mod:`exchange.compiled_body`): (1, held, force
        scale, law vector), the node table and the kink displacements; None without contact."""
        c = self.contact
        if c is None:
            return None
        head = np.concatenate([[1.0, float(self.held), self.force_scale()], c.law_vector])
        return head, c.table, np.asarray(c.thresholds(), dtype=float)

    def log_contact_events(self, events) -> None:
        """The contact log of a run, from its events: (t, label, state before, state after, mode before) each
        (:func:`exchange.compiled_body.seat_event`: an impact sets s to the touching position and v to 0)."""
        k, c = self.body_offset, self.contact
        for t, label, before, after, mode in events:
            kind = label.rpartition(":")[2]
            if kind == "seat" and mode.held:
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
        return float(self.states(t, y)[f].pressure) if f is not None else float("nan")

    def _log_touch(self, t, y):
        """Penalty/softened contact: record first touch and full separation (the kinks where g_min = 0)."""
        k, c = self.body_offset, self.contact
        reach = np.flatnonzero(c.reach)
        i = reach[int(np.argmin(c.gaps(y[k])[reach]))]
        if abs(c.gaps(y[k])[i]) <= 1e-9 * c.size:
            approach = float(-c.sigma[i] * y[k + 1])
            self.contact_log.append((t, "touch" if approach > 0 else "separate", approach, self._pressure(t, y)))
