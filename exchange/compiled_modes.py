"""The discrete state of a lowered network on the engine: which switches are watched, what a switch does, and the
state recorded per segment (the network's ``snapshot``, :meth:`exchange.compiled.CompiledNetwork.current_mode`).
The state lives in the
model tuple of :class:`exchange.compiled.CompiledNetwork`: ``M[20]`` equalised flags, ``M[21]`` 0 while a pop vent
has not popped (2 once an exchange closed at its close pressure, else 1), ``M[22]`` the start of its hold [s]
(NaN: not holding); ``M[12]`` and ``M[13]`` are the exchanges'
``ei`` and ``ef`` (:mod:`exchange.compiled_rhs`); a pop sets the vent's area at activation ``ef[j, 9]``. Switch
kinds: 0 choke, 1 one-way reversal, 2 equalise, 3 release, 4 pop, 5 pop-drop, 6 pop-hold, 7 orifice join, 8/9 the
dynamic body reaching the crossing above/below its area interval ``M[23][j]``, 10 its turning point, 11/12 a
row of a law's Cd table of pressure / leakage table (:mod:`exchange.law_kinks`), 13 the body's seat (hard
contact: lift-off and impact), 14 a kink of its seat's force (:mod:`exchange.compiled_body`), 15/16 the knot
above/below the piece of the pushed cavity's volume spline the segment holds (``M[7][i, 9]``), 17 the downstream
cavity reaching an exchange's close pressure ``ef[j, 10]``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .compiled_body import seat_event, seat_switch, seat_watched
from .compiled_rhs import base_area
from .lowered_columns import KNOT_SLACK

__all__ = ["watched", "on_event", "record_segment", "body_switch", "rederive_intervals", "lock_pieces"]


@njit(cache=True)
def watched(M, kind, j):
    """Switch (kind, exchange j) is watched in the current discrete state: equalise while
    open, release while equalised, pop while armed, pop-drop and pop-hold while holding, none once popped; the
    close pressure while open."""
    eq, op, hold = M[20], M[21], M[22]
    if kind == 17:  # the close pressure: while open
        return op[j] == 1
    if kind == 11 or kind == 12:  # a law's kinks (exchange.law_kinks): always watched
        return True
    if kind == 8:  # a crossing above the body's area interval exists
        return M[23][j] < M[6][M[12][j, 8], 1] - 1
    if kind == 9:
        return M[23][j] > 0
    if kind == 15 or kind == 16:  # a knot above / below the held piece of cavity j's volume spline exists
        p = M[7][j, 9]
        return p < M[6][M[7][j, 3], 1] - 1 if kind == 15 else p >= 0
    if kind >= 10:  # the body's turning point, seat and kinks
        return seat_watched(M, kind)
    if kind == 2 or kind == 3:
        return eq[j] == (1 if kind == 3 else 0)
    if kind == 7:
        return True
    if kind >= 4:
        return op[j] == 0 and (math.isnan(hold[j]) if kind == 4 else not math.isnan(hold[j]))
    return True


@njit(cache=True)
def on_event(M, kind, j, t, y, seg_end):
    """What switch (kind, j) does when it fires at t: equalise holds the exchange closed, release opens it; a pop crossing starts the
    hold (or pops at once without a hold time), a drop re-arms, the hold's end pops; a seat switch may change the
    body's state ``y`` in place (:func:`exchange.compiled_body.seat_event`)."""
    if kind == 17:  # the downstream cavity reached the close pressure: shut for good
        M[21][j] = 2
    elif kind == 15 or kind == 16:
        pass  # a knot only ends the segment: the next one holds the piece beyond (lock_pieces)
    elif kind >= 13:
        seat_event(M, kind, t, y, seg_end)
    elif kind == 8 or kind == 9:  # the body's displacement passed the crossing: the next area interval
        M[23][j] += 1 if kind == 8 else -1
    elif kind == 10:
        pass  # a turning point only ends the segment
    elif kind == 2 or kind == 3:
        M[20][j] = 1 if kind == 2 else 0
    elif kind == 4 and M[13][j, 5] > 0.0:
        M[22][j] = t
    elif kind == 5:
        M[22][j] = math.nan
    elif kind == 4 or kind == 6:  # (kind 7, the orifice join, changes nothing); its area at activation
        M[21][j] = 1
        M[13][j, 9] = base_area(M[12], M[13], M[23], M[4], M[5], M[6], j, t)


@njit(cache=True)
def record_segment(M, segs, nseg, first, end, t_min, t_max, mode):
    """Row nseg of the segment table: first record, end record, t_min, t_max, mode code (bits: equalised), then
    per exchange its open flag (0 a pop vent not popped, 1 open, 2 closed at its close pressure), then per exchange
    the hold start [s] (NaN: none), then per exchange the dynamic body's area interval, then 1 while the body is
    held on its seat."""
    ei, op, hold = M[12], M[21], M[22]
    ne = op.size
    segs[nseg, 0], segs[nseg, 1], segs[nseg, 2], segs[nseg, 3], segs[nseg, 4] = first, end, t_min, t_max, mode
    for j in range(ne):
        segs[nseg, 5 + j] = op[j]
        segs[nseg, 5 + ne + j] = hold[j]
        segs[nseg, 5 + 2 * ne + j] = M[23][j]
    segs[nseg, 5 + 3 * ne] = M[25][1]


@njit(cache=True)
def body_switch(M, kind, j, y):
    """The dynamic body's switches: (s − s_k)/scale on the crossing above (kind 8) or below (9) its area interval
    of exchange j, on the knot above (15) or below (16) the held piece of cavity j's volume spline, and
    v/v_scale (10): between turning points s is monotone, so each crossing switch changes sign once."""
    if kind == 15 or kind == 16:
        return knot_switch(M, kind, j, y)
    if kind >= 13:
        return seat_switch(M, kind, j, y)
    bd = M[24]
    k = int(bd[0])
    if kind == 10:
        return y[k + 1] / bd[8]
    start = M[6][M[12][j, 8], 0]  # step table: x = [−inf, crossings...]
    i = M[23][j]
    c = M[4][start + 1 + i] if kind == 8 else M[4][start + i]
    return (y[k] - c) / M[13][j, 8]


@njit(cache=True)
def rederive_intervals(M, y):
    """The area interval of each exchange re-derived from the body's displacement when it lies outside by more
    than the slack (a crossing passed inside the step of a turning point is caught here, at the restart, so a
    release is never missed; the slack, :data:`cases.model.scene_areas.REDERIVE_SLACK` of the track's span, is the
    solver's error at a restart on a crossing event)."""
    bd, ei, tx, ti, iv = M[24], M[12], M[4], M[6], M[23]
    s = y[int(bd[0])]
    for j in range(iv.size):
        if ei[j, 10] != 2:
            continue
        start, n = ti[ei[j, 8], 0], ti[ei[j, 8], 1] - 1  # n crossings at tx[start + 1 ...]
        i = iv[j]
        if (i > 0 and s < tx[start + i] - bd[9]) or (i < n and s > tx[start + 1 + i] + bd[9]):
            iv[j] = np.searchsorted(tx[start + 1:start + 1 + n], s, side="right")


@njit(cache=True)
def knot_switch(M, kind, j, y):
    """(s − x_k)/span of the knot above (kind 15) or below (16) the piece cavity j's volume spline holds (s leaves
    the piece through them)."""
    tx, ti, ci = M[4], M[6], M[7]
    s, n = ti[ci[j, 3], 0], ti[ci[j, 3], 1]
    p = ci[j, 9]
    knot = tx[s + p + 1] if kind == 15 else tx[s + p]
    return (y[ci[j, 6]] - knot) / (tx[s + n - 1] - tx[s])


@njit(cache=True)
def lock_pieces(M, y):
    """At a segment start, hold for each volume spline of the dynamic body's displacement the piece holding s,
    nudged by KNOT_SLACK of its span along the body's velocity
    (a θ that is a state sees one cubic, extended past its knots, whose switches end the segment: no step
    straddles the jump of d³V/dθ³ at a knot; piece −1: below the first knot, n − 1: above the last)."""
    tx, ti, ci = M[4], M[6], M[7]
    for i in range(ci.shape[0]):
        if ci[i, 2] != 4:
            continue
        s, n = ti[ci[i, 3], 0], ti[ci[i, 3], 1]
        v = y[ci[i, 6] + 1]
        nudge = KNOT_SLACK * (tx[s + n - 1] - tx[s]) * np.sign(v)
        ci[i, 9] = np.searchsorted(tx[s:s + n], y[ci[i, 6]] + nudge, side="right") - 1
