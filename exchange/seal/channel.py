r"""The leak-channel height of every seal node from its contact state.

A seal node faces the flange across the clearance g [m] (the distance between the nominal surfaces, negative
when they overlap) and carries the contact pressure p [Pa] that the contact law gives. Its channel is the open
clearance plus the roughness channel that the gap law leaves at that pressure:

.. math:: h = \max(g, 0) + h_{gap}(p)

* open (p = 0): the clearance plus the gap at first touch h_gap(0);
* softened contact (Abaqus exponential pressure–overclosure, p > 0 at a clearance 0 < g < c0): the clearance
  itself is a leak gap (the law stands for the roughness), plus h_gap(p) if a gap law is given too (:class:`NoGap`
  otherwise: the channel closes at zero clearance);
* penalty (linear) contact: g < 0, p = k·(−g), h = h_gap(p);
* hard contact: a node held on the seat has g = 0 and carries its share of the reaction, h = h_gap(p).

h is continuous through every change of state, and exactly 0 only where the clearance is closed and the gap law
is closed at that pressure. The contact laws are those of :mod:`exchange.contact.laws` (evaluated by its
``seat_nodal`` kernel, without damping: the leak gap follows the elastic contact, not the viscous pressure).
"""
from __future__ import annotations

import numpy as np

from exchange.contact.laws import HARD, SeatNode, seat_nodal
from exchange.seal.gap_laws import NoGap

__all__ = ["channel_height", "seat_state", "seat_channel_heights", "contact_fraction"]


def channel_height(clearance, pressure, gap_law, p_max=None):
    """Channel height [m] of nodes with clearance ``clearance`` [m] and contact pressure ``pressure`` [Pa] under
    ``gap_law`` (``p_max`` [Pa]: the largest pressure carried, for a hysteretic law).

    >>> from exchange.seal.gap_laws import ExponentialGap
    >>> law = ExponentialGap(h0=5e-6, p0=1e6)
    >>> channel_height(np.array([3e-6, 0.0, -1e-7]), np.array([0.0, 0.0, 1e6]), law).round(12).tolist()
    [8e-06, 5e-06, 1.839397e-06]
    """
    gap = gap_law.gap(pressure) if p_max is None else gap_law.gap(pressure, p_max)
    return np.maximum(np.asarray(clearance, float), 0.0) + gap


def seat_state(s, nodes, law, reaction=0.0):
    """(clearance (n,) [m], pressure (n,) [Pa], in contact (n,) bool) of a seat's nodes at body displacement
    ``s`` [m], without damping; ``nodes`` (n, 4) and ``law`` the seat arrays of :mod:`exchange.contact.laws`,
    ``reaction`` [N] the held hard contact's force (shared by the closed nodes). Held hard-contact nodes get g = 0.

    >>> nodes = np.array([[0.0, -1.0, 0.5, 1.0], [2e-6, -1.0, 0.5, 1.0]])
    >>> law = np.array([1.0, 1e12, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.01])  # linear, k = 1e12 Pa/m
    >>> g, p, closed = seat_state(1e-6, nodes, law)
    >>> g.tolist(), p.tolist(), closed.tolist()
    ([-1e-06, 1e-06], [1000000.0, 0.0], [True, False])
    """
    nodes = np.ascontiguousarray(nodes, dtype=float)
    elastic = np.array(law, dtype=float)
    elastic[3] = 0.0  # NO_DAMPING
    pressure, status = seat_nodal(float(s), 0.0, float(reaction), nodes, elastic)
    closed = status == 1
    clearance = nodes[:, SeatNode.GAP] + nodes[:, SeatNode.SIDE] * s
    if int(elastic[0]) == HARD:
        clearance = np.where(closed, 0.0, clearance)
    if not np.isfinite(clearance).all():
        raise ValueError("every seal node must face the flange (a node's ray missed it: infinite clearance)")
    return clearance, pressure, closed


def seat_channel_heights(s, nodes, law, gap_law=NoGap(), reaction=0.0, p_max=None):
    """Channel height (n,) [m] of a seat's nodes at displacement ``s`` [m] (:func:`seat_state`,
    :func:`channel_height`)."""
    clearance, pressure, _ = seat_state(s, nodes, law, reaction)
    return channel_height(clearance, pressure, gap_law, p_max)


def contact_fraction(closed, areas):
    """Contact-area fraction [-]: the tributary area of the nodes in contact over the seal's area.

    >>> contact_fraction(np.array([True, False, True]), np.array([1.0, 2.0, 1.0]))
    0.5
    """
    return float(np.sum(np.where(closed, areas, 0.0)) / np.sum(areas))
