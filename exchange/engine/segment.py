"""The start of a segment on the engine: the equalised exchanges, the dynamic body's area intervals and
volume-spline pieces, a DELTA LEAKAGE AREA opened by time on an area that follows the dynamic body, and which
switches are watched in which direction. Both integrators call these: the compiled DOP853
(:mod:`exchange.engine.solver`) and scipy's methods (:mod:`exchange.engine.system`)."""
from __future__ import annotations

import numpy as np
from numba import njit

from .body import has_body, lifting_side
from .flows import base_area
from .gas import states
from .layout import ExchangeFloat, ExchangeInt, SwitchKind, is_kink, one_way_direction
from .modes import lock_pieces, rederive_intervals, watched
from .rhs import rhs
from .sampled import rederive_sampled
from .switches import exchange_switch, switches

__all__ = ["begin_segment", "directions"]


@njit(cache=True)
def begin_segment(M, t, y, seg_end):
    """Segment start from (t, y): re-derive the dynamic body's area intervals and lock its volume-spline pieces, set
    a DELTA LEAKAGE AREA opened by time once past its open time, and equalise (hold closed) the two-way exchanges
    whose sides agree to :data:`exchange.network.equalised.EQUALISED_BELOW` (their release switch watches for the network
    driving them apart); returns the equalised bits (bit j: exchange j)."""
    ei, ef, eq = M.exchange_int, M.exchange_float, M.equalised
    if has_body(M):
        rederive_intervals(M, y)
        rederive_sampled(M, t, y)
        lock_pieces(M, y)
    for j in range(eq.size):  # a DELTA LEAKAGE AREA opened by time: its area at the open time, once past it
        base = ef[j, ExchangeFloat.AREA_AT_ACTIVATION]
        if ei[j, ExchangeInt.DELTA_AREA] == 1 and base != base and t >= ef[j, ExchangeFloat.OPEN_TIME]:
            ef[j, ExchangeFloat.AREA_AT_ACTIVATION] = base_area(M, j, ef[j, ExchangeFloat.OPEN_TIME])
    bits = 0
    ready = False
    for j in range(eq.size):
        if ei[j, ExchangeInt.EQUALISE] == 1 and eq[j] == 0:
            if not ready:  # the states at (t, y), inputs read as the right-hand side reads them
                states(M, np.nextafter(seg_end, -np.inf) if t >= seg_end else t, y)
                ready = True
            if exchange_switch(M, SwitchKind.EQUALISE, j) < 0.0:
                eq[j] = 1
        if eq[j] == 1:
            bits += 1 << j
    return bits


@njit(cache=True)
def directions(M, t, y, seg_end, last_q, last_t, last_dir, near):
    """(watched switches, their directions) at a segment start: away from each switch's current sign; the switch
    that has just fired for the opposite crossing; a switch within ``near`` of zero against its trend along the flow
    (not at all if it does not move). After a kink's switch fired (:func:`~exchange.engine.layout.is_kink`: the
    event leaves state and function as they are), ``near`` grows to 4 times its value at the restart (at most
    1e3·``near``): the state there is integrated afresh to the event time located on the step's dense output, and a
    low-order dense output (Radau's) leaves the fired switch up to ~1e3·rtol off zero; a twin that crossed at the
    same instant (two identical vents) has the same value and would otherwise fire again at once, in turn."""
    nsw, n = M.switch_kind.size, y.size
    every = np.arange(nsw)
    vals, pvals = np.empty(nsw), np.empty(nsw)
    wq, wd = np.empty(nsw, np.int64), np.empty(nsw)
    switches(M, every, t, y, seg_end, vals)
    if last_q >= 0 and t == last_t and is_kink(M.switch_kind[last_q]):
        near = max(near, min(4.0 * abs(vals[last_q]), 1e3 * near))
    probed, nw = False, 0
    for q in range(nsw):
        if not watched(M, q):
            continue  # the switch of another discrete state
        kind = M.switch_kind[q]
        if one_way_direction(kind) != 0.0:  # the body leaves its interval or piece through that end only
            d = one_way_direction(kind)
        elif kind == SwitchKind.TURN and lifting_side(M, y) != 0.0:  # freed at rest on its seat: it can only return
            d = -lifting_side(M, y)
        elif q == last_q and t == last_t:
            d = -last_dir
        elif abs(vals[q]) > near:
            d = 1.0 if vals[q] < 0 else -1.0
        else:
            if not probed:
                dt = 1e-9 * max(abs(t), 1e-6)
                fp = np.empty(n)
                rhs(M, t, y, fp, seg_end)
                switches(M, every, t + dt, y + dt * fp, seg_end, pvals)
                probed = True
            trend = pvals[q] - vals[q]
            d = -1.0 if trend > 0 else (1.0 if trend < 0 else 0.0)
        if d != 0.0:
            wq[nw], wd[nw] = q, d
            nw += 1
    return wq[:nw], wd[:nw]
