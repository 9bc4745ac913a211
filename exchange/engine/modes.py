"""The discrete state of a lowered network on the engine: which switches exist in it, what a switch does when it
fires, and the state recorded per segment.

The state lives in the model: ``M.equalised`` (1 while an exchange is held closed), ``M.open_state``
(:class:`~exchange.engine.layout.OpenState`), ``M.hold_start`` (a pop vent's hold, NaN: not holding),
``M.interval`` (the dynamic body's area interval per exchange; an FE rule's sampled flags also keep the interval
holding s now and their queue of samples in ``M.sampling``, :mod:`exchange.engine.sampled`), ``seat_state[HELD]``
and each volume spline's held piece (``CavityInt.PIECE``); a pop sets the vent's area at activation.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .body import seat_event, seat_watched
from .flows import base_area
from .sampled import apply_head, crossing_count, move_tracked, tracked_interval
from .layout import (KNOT_SLACK, BodyColumn, CavityInt, ExchangeFloat, ExchangeInt, OpenState, SamplingColumn,
                     SeatState, SegmentColumn, SwitchKind, TableColumn, VolumeKind, AreaKind, is_seat_switch,
                     segment_blocks)

__all__ = ["watched", "on_event", "record_segment", "rederive_intervals", "lock_pieces"]

K = SwitchKind


@njit(cache=True)
def watched(M, q):
    """Switch q exists in the current discrete state: equalise while open, release while equalised, pop while
    armed, pop-drop and pop-hold while holding, none once popped; the close pressure while open; a crossing or knot
    only where there is one beyond; the body's turning point and seat kinks as :func:`exchange.engine.body.
    seat_watched` says."""
    kind, j = M.switch_kind[q], M.switch_target[q]
    if kind == K.CLOSE:
        return M.open_state[j] == OpenState.OPEN
    if kind == K.CROSSING_UP:
        return tracked_interval(M, j) < crossing_count(M, j)
    if kind == K.CROSSING_DOWN:
        return tracked_interval(M, j) > 0
    if kind == K.SAMPLE:
        return M.sampling[j, SamplingColumn.COUNT] > 0
    if kind == K.KNOT_UP or kind == K.KNOT_DOWN:  # a knot above / below the held piece of cavity j's spline
        p = M.cavity_int[j, CavityInt.PIECE]
        rows = M.table_index[M.cavity_int[j, CavityInt.VOLUME_TABLE], TableColumn.ROWS]
        return p < rows - 1 if kind == K.KNOT_UP else p >= 0
    if kind == K.TURN or is_seat_switch(kind):
        return seat_watched(M, kind)
    if kind == K.EQUALISE or kind == K.RELEASE:
        return M.equalised[j] == (1 if kind == K.RELEASE else 0)
    if kind == K.POP:
        return M.open_state[j] == OpenState.SHUT and math.isnan(M.hold_start[j])
    if kind == K.POP_DROP or kind == K.POP_HOLD:
        return M.open_state[j] == OpenState.SHUT and not math.isnan(M.hold_start[j])
    return True  # choke, join, reversal, a law's kinks


@njit(cache=True)
def on_event(M, q, t, y, seg_end):
    """What switch q does when it fires at t: equalise holds the exchange closed, release opens it; a pop crossing
    starts the hold (or pops at once without a hold time), a drop re-arms, the hold's end pops and sets the vent's
    area at activation; the close pressure shuts the exchange for good; a crossing moves the body's area interval
    (an FE rule's current one, whose sample comes into use at its SAMPLE switch: :mod:`exchange.engine.sampled`);
    the seat switch may change the body's state ``y`` in place (:func:`exchange.engine.body.seat_event`). Kinks,
    knots and the turning point only end the segment."""
    kind, j = M.switch_kind[q], M.switch_target[q]
    if kind == K.CLOSE:
        M.open_state[j] = OpenState.CLOSED
    elif kind == K.SEAT:
        seat_event(M, t, y, seg_end)
    elif kind == K.CROSSING_UP or kind == K.CROSSING_DOWN:
        move_tracked(M, j, tracked_interval(M, j) + (1 if kind == K.CROSSING_UP else -1), t)
    elif kind == K.SAMPLE:
        apply_head(M, j)
    elif kind == K.EQUALISE or kind == K.RELEASE:
        M.equalised[j] = 1 if kind == K.EQUALISE else 0
    elif kind == K.POP and M.exchange_float[j, ExchangeFloat.HOLD_TIME] > 0.0:
        M.hold_start[j] = t
    elif kind == K.POP_DROP:
        M.hold_start[j] = math.nan
    elif kind == K.POP or kind == K.POP_HOLD:
        M.open_state[j] = OpenState.OPEN
        M.exchange_float[j, ExchangeFloat.AREA_AT_ACTIVATION] = base_area(M, j, t)


@njit(cache=True)
def record_segment(M, segs, nseg, first, end, t_min, t_max, mode):
    """Row nseg of the segment table (:class:`~exchange.engine.layout.SegmentColumn`): its records, span and
    equalised bits, then per exchange its open state, hold start and area interval, then whether the body is held."""
    ne = M.open_state.size
    opened, hold, interval, held, _ = segment_blocks(ne)
    segs[nseg, SegmentColumn.FIRST], segs[nseg, SegmentColumn.END] = first, end
    segs[nseg, SegmentColumn.T_MIN], segs[nseg, SegmentColumn.T_MAX] = t_min, t_max
    segs[nseg, SegmentColumn.EQUALISED] = mode
    for j in range(ne):
        segs[nseg, opened + j] = M.open_state[j]
        segs[nseg, hold + j] = M.hold_start[j]
        segs[nseg, interval + j] = M.interval[j]
    segs[nseg, held] = M.seat_state[SeatState.HELD]


@njit(cache=True)
def rederive_intervals(M, y):
    """The area interval of each exchange re-derived from the body's displacement when it lies outside by more than
    the slack (a crossing passed inside the step of a turning point is caught here, at the restart, so a release is
    never missed; the slack, :data:`cases.model.scene_lowering.REDERIVE_SLACK` of the track's span, is the solver's
    error at a restart on a crossing event)."""
    bd, ei, tx, ti = M.body, M.exchange_int, M.table_x, M.table_index
    s, slack = y[int(bd[BodyColumn.OFFSET])], bd[BodyColumn.SLACK]
    for j in range(M.interval.size):
        if ei[j, ExchangeInt.AREA] != AreaKind.STEPS_OF_BODY:
            continue
        k = ei[j, ExchangeInt.AREA_TABLE]
        start, n = ti[k, TableColumn.START], ti[k, TableColumn.ROWS] - 1  # n crossings at tx[start + 1 ...]
        i = M.interval[j]
        if (i > 0 and s < tx[start + i] - slack) or (i < n and s > tx[start + 1 + i] + slack):
            M.interval[j] = np.searchsorted(tx[start + 1:start + 1 + n], s, side="right")


@njit(cache=True)
def lock_pieces(M, y):
    """At a segment start, hold for each volume spline of the dynamic body's displacement the piece holding s,
    nudged by KNOT_SLACK of its span along the body's velocity (a step then sees one cubic, extended past its knots,
    whose switches end the segment: no step straddles the jump of d³V/ds³ at a knot; piece −1: below the first knot,
    n − 1: above the last)."""
    tx, ti, ci = M.table_x, M.table_index, M.cavity_int
    for i in range(ci.shape[0]):
        if ci[i, CavityInt.VOLUME] != VolumeKind.SPLINE_OF_BODY:
            continue
        k = ci[i, CavityInt.VOLUME_TABLE]
        s, n = ti[k, TableColumn.START], ti[k, TableColumn.ROWS]
        b = ci[i, CavityInt.BODY_OFFSET]
        nudge = KNOT_SLACK * (tx[s + n - 1] - tx[s]) * np.sign(y[b + 1])
        ci[i, CavityInt.PIECE] = np.searchsorted(tx[s:s + n], y[b] + nudge, side="right") - 1
