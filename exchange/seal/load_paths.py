"""Load paths: how the channel heights of a seal's nodes follow one scalar load coordinate q.

* :class:`DisplacementPath` — q = s [m], the flange's displacement along its axis (penalty or softened contact,
  and hard contact while the flange is free): g_i = g0_i + σ_i·s, p_i from the contact law.
* :class:`ReactionPath` — q = F [N], the reaction of a hard contact while the flange is held on the seat at s:
  the nodes in contact share F in proportion to their areas, p = F/A_contact.

Both give the nodal channel heights h(q) (:mod:`exchange.seal.channel`) and, in closed form or by a root solve
to round-off, the load ``closing`` at which each node's channel closes (inf: never), and ``direction`` (+1 when
the seal tightens as q grows, −1 when it tightens as q falls).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from exchange.contact.laws import HARD, LINEAR, SOFTENED, TOUCH, SeatLaw, SeatNode, softened_pressure
from exchange.seal.channel import channel_height, seat_channel_heights, seat_state
from exchange.seal.gap_laws import NoGap

__all__ = ["DisplacementPath", "ReactionPath", "closing_clearance"]


def closing_clearance(law, gap_law):
    """The clearance g_c [m] at and below which a node's channel is closed under contact law ``law`` (the seat
    parameter vector of :mod:`exchange.contact.laws`) and ``gap_law`` (−inf: never).

    Closed means g <= 0 and p >= p_c (the gap law's closing pressure).

    >>> law = np.array([1.0, 1e12, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.01])  # linear, 1e12 Pa/m
    >>> from exchange.seal.gap_laws import TableGap
    >>> float(closing_clearance(law, TableGap((0.0, 2e6), (1e-6, 0.0))))
    -2e-06
    """
    p_c = gap_law.closing_pressure()
    if not math.isfinite(p_c):
        return -math.inf
    kind = int(law[SeatLaw.KIND])
    if kind == HARD:
        return TOUCH * law[SeatLaw.SEAT_SIZE] if p_c == 0.0 else -math.inf
    if kind == LINEAR:
        return -p_c / law[SeatLaw.STIFFNESS]
    if kind == SOFTENED:
        c0, p0 = law[SeatLaw.STIFFNESS], law[SeatLaw.P0]
        if p_c <= p0:
            return 0.0
        upper = c0
        while softened_pressure(upper, c0, p0) < p_c:
            upper *= 2.0
        return -brentq(lambda h: softened_pressure(h, c0, p0) - p_c, 0.0, upper, xtol=1e-300, rtol=1e-15)
    raise ValueError(f"unknown contact law code {kind}")


class DisplacementPath:
    """Channel heights against the flange's displacement s [m].

    ``nodes`` (n, 4) and ``law`` the seat arrays of :mod:`exchange.contact.laws` (one row per seal-film node),
    ``gap_law`` the roughness channel, ``loaded_to`` [m]: for a hysteretic gap law, the deepest displacement
    reached so far (every node then unloads from the pressure it carried there).
    """

    def __init__(self, nodes, law, gap_law=NoGap(), loaded_to=None):
        self.nodes = np.ascontiguousarray(nodes, dtype=float)
        self.law = np.asarray(law, dtype=float)
        self.gap_law = gap_law
        sides = np.unique(self.nodes[self.nodes[:, SeatNode.REACH] != 0.0, SeatNode.SIDE])
        if len(sides) != 1:
            raise ValueError("a seal's flange must lie on one side of every seal node (one sigma for all nodes)")
        self.sigma = float(sides[0])
        self.direction = -self.sigma
        self.p_max = None if loaded_to is None else seat_state(loaded_to, self.nodes, self.law)[1]
        self._closing = self.closing()

    def heights(self, s):
        """(n,) channel heights [m] at displacement ``s`` [m]; exactly 0 on the nodes closed at ``s`` by
        :meth:`closing` (the clearance computed as g0 + σ·s may miss the closing clearance by a rounding)."""
        h = seat_channel_heights(s, self.nodes, self.law, self.gap_law, 0.0, self.p_max)
        return np.where(self.direction * (s - self._closing) >= 0.0, 0.0, h)

    def in_contact(self, s):
        """(n,) bool: nodes in contact at ``s``."""
        return seat_state(s, self.nodes, self.law)[2]

    def state(self, s):
        """(heights (n,) [m], in contact (n,) bool) at ``s`` from one evaluation of the contact law: what
        :meth:`heights` and :meth:`in_contact` give."""
        clearance, pressure, closed = seat_state(s, self.nodes, self.law)
        h = channel_height(clearance, pressure, self.gap_law, self.p_max)
        return np.where(self.direction * (s - self._closing) >= 0.0, 0.0, h), closed

    def distinct(self):
        """(path over one node of each distinct (clearance, side, reach), the row of each node): a node's channel,
        contact state and closing displacement depend on these only (not on its area: no damping, no shared
        reaction), so the reduced path gives the same values, bit for bit. A flat ring: one row."""
        keys = self.nodes[:, [SeatNode.GAP, SeatNode.SIDE, SeatNode.REACH]]
        _, first, node_row = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        out = object.__new__(DisplacementPath)
        out.__dict__.update(self.__dict__)
        out.nodes = np.ascontiguousarray(self.nodes[first])
        out.p_max = None if self.p_max is None else self.p_max[first]
        out._closing = self._closing[first]
        return out, node_row.ravel()

    def closing(self):
        """(n,) displacement [m] at which each node's channel closes (inf never; the path's direction applies)."""
        g_c = -math.inf if self.p_max is not None else closing_clearance(self.law, self.gap_law)
        out = np.full(len(self.nodes), self.direction * np.inf)
        if math.isfinite(g_c):
            reach = self.nodes[:, SeatNode.REACH] != 0.0
            out[reach] = (g_c - self.nodes[reach, SeatNode.GAP]) / self.nodes[reach, SeatNode.SIDE]
        return out


class ReactionPath:
    """Channel heights against the reaction F [N] of a hard contact held at displacement ``s_seat`` [m]."""

    def __init__(self, nodes, law, gap_law=NoGap(), s_seat=0.0):
        self.nodes = np.ascontiguousarray(nodes, dtype=float)
        self.law = np.asarray(law, dtype=float)
        if int(self.law[SeatLaw.KIND]) != HARD:
            raise ValueError("a reaction path needs hard contact (law code 0)")
        self.gap_law = gap_law
        self.s_seat = float(s_seat)
        self.direction = 1.0
        self.contact = seat_state(self.s_seat, self.nodes, self.law)[2]
        self.contact_area = float(self.nodes[self.contact, SeatNode.AREA].sum())
        if self.contact_area <= 0.0:
            raise ValueError(f"no seal node touches the flange at s = {self.s_seat!r} m")
        self._closing = self.closing()

    def heights(self, force):
        """(n,) channel heights [m] at reaction ``force`` [N] >= 0 (exactly 0 on the nodes closed there)."""
        h = seat_channel_heights(self.s_seat, self.nodes, self.law, self.gap_law, max(float(force), 0.0))
        return np.where(force >= self._closing, 0.0, h)

    def in_contact(self, force):
        return self.contact.copy()

    def closing(self):
        """(n,) reaction [N] at which each node's channel closes: p_c·A_contact on the contact nodes, else inf."""
        p_c = self.gap_law.closing_pressure()
        return np.where(self.contact, p_c * self.contact_area, np.inf)
