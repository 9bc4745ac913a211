"""The switch functions the engine watches, valued at (t, y): each is a smooth function of the state (or of time)
whose zero is a discontinuity or a kink of the right-hand side, found by root finding on the dense output and
stopped at (:mod:`exchange.engine.solver`).

Switch q has a kind (``M.switch_kind[q]``, :class:`~exchange.engine.layout.SwitchKind`) and a target
(``M.switch_target[q]``): its exchange, its row of the laws' kinks, the pushed cavity (a spline knot) or the seat's
kink. Which switches exist in the current discrete state, and what each does when it fires, is
:mod:`exchange.engine.modes`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from exchange.network.equalised import EQUALISED_BELOW, RELEASED_ABOVE
from cavity.isentropic import critical_pressure_ratio

from .body import seat_switch
from .gas import states
from .hosted import hosted_choke_ratio
from .sampled import sample_switch, tracked_interval
from .layout import (LAW_LOAD, AmbientColumn, SeatLaw, SeatState, BodyColumn, CavityInt, ExchangeFloat, ExchangeInt,
                     Fluid, KinkColumn,
                     KinkVariable, StateColumn, SwitchKind, TableColumn, is_body_switch, is_seat_switch, side)

__all__ = ["switches", "exchange_switch", "choke_ratio_of", "kink_value", "body_switch", "knot_switch"]

K, P = SwitchKind, StateColumn.P


@njit(cache=True)
def choke_ratio_of(M, i):
    """p*/p0 [-] of side i (−1: ambient): a real-gas cavity's from its equation of state (hosted), else the ideal
    gas's :func:`cavity.isentropic.critical_pressure_ratio` of its γ (:meth:`exchange.network.vent.GasPoint.
    choke_ratio`)."""
    if i < 0:
        return critical_pressure_ratio(M.ambient[AmbientColumn.GAMMA])
    if M.cavity_int[i, CavityInt.FLUID] == Fluid.REAL_GAS:
        return hosted_choke_ratio(M.cavity_int[i, CavityInt.HOST], i)
    return critical_pressure_ratio(M.state[i, StateColumn.GAMMA])


@njit(cache=True)
def exchange_switch(M, kind, j):
    """An exchange's switch on the states in ``M.state`` [-]: CHOKE (p_low − r*·p_high)/p_high, where the orifice
    law's second derivative jumps; REVERSAL Δp/p_max; JOIN the law's C¹ join, |Δp|/p_max/JOIN_BELOW − 1;
    EQUALISE and RELEASE |Δp|/p_max over their levels (:mod:`exchange.network.equalised`) − 1; POP and POP_DROP
    (Δp − p_pop)/max(p_pop, p_b); CLOSE (p_b − p_close)/p_close."""
    st, amb, ei, ef = M.state, M.ambient, M.exchange_int, M.exchange_float
    a, b = ei[j, ExchangeInt.UP], ei[j, ExchangeInt.DOWN]
    pa, pb = st[a, P], side(st, amb, b, P)
    if kind == K.CLOSE:
        close = ef[j, ExchangeFloat.CLOSE_PRESSURE]
        return (pb - close) / close
    if kind == K.REVERSAL:
        return (pa - pb) / max(pa, pb)
    if kind == K.JOIN:
        return abs(pa - pb) / max(pa, pb) / ef[j, ExchangeFloat.JOIN_BELOW] - 1.0
    if kind == K.EQUALISE or kind == K.RELEASE:
        return abs(pa - pb) / max(pa, pb) / (EQUALISED_BELOW if kind == K.EQUALISE else RELEASED_ABOVE) - 1.0
    if kind == K.POP or kind == K.POP_DROP:
        pop = ef[j, ExchangeFloat.POP_PRESSURE]
        return (pa - pb - pop) / max(pop, pb)
    if pa >= pb:  # CHOKE
        return (pb - choke_ratio_of(M, a) * pa) / pa
    return (pa - choke_ratio_of(M, b) * pb) / pb


@njit(cache=True)
def kink_value(M, r):
    """A law's kink r (a row of its table): (max(p_a, p_b) − x)/x on a Cd table of pressure, (|p_a − p_b| − Δp)/Δp
    on a leakage table, (s − x)/L on the dynamic body's displacement (L its seat's size, else 1 m)."""
    j, x = M.kink_int[r, KinkColumn.EXCHANGE], M.kink_x[r]
    if M.kink_int[r, KinkColumn.VARIABLE] == KinkVariable.BODY_DISPLACEMENT:
        size = M.seat_law[SeatLaw.SEAT_SIZE] if M.seat_state[SeatState.HAS] != 0.0 else 1.0
        return (M.law_float[j, LAW_LOAD] - x) / size
    ei = M.exchange_int
    pa, pb = M.state[ei[j, ExchangeInt.UP], P], side(M.state, M.ambient, ei[j, ExchangeInt.DOWN], P)
    if M.kink_int[r, KinkColumn.VARIABLE] == KinkVariable.UPSTREAM_PRESSURE:
        return (max(pa, pb) - x) / x
    return (abs(pa - pb) - x) / x


@njit(cache=True)
def knot_switch(M, kind, i, y):
    """(s − x_k)/span of the knot above (KNOT_UP) or below (KNOT_DOWN) the piece cavity i's volume spline holds (s
    leaves the piece through them)."""
    tx, ti, ci = M.table_x, M.table_index, M.cavity_int
    k = ci[i, CavityInt.VOLUME_TABLE]
    s, n = ti[k, TableColumn.START], ti[k, TableColumn.ROWS]
    p = ci[i, CavityInt.PIECE]
    knot = tx[s + p + 1] if kind == K.KNOT_UP else tx[s + p]
    return (y[ci[i, CavityInt.BODY_OFFSET]] - knot) / (tx[s + n - 1] - tx[s])


@njit(cache=True)
def body_switch(M, kind, j, y):
    """The dynamic body's switches: (s − s_k)/scale on the crossing above (CROSSING_UP) or below (CROSSING_DOWN)
    its area interval of exchange j, the knots of its volume spline, the seat's, and v/v_scale (TURN): between
    turning points s is monotone, so each crossing switch changes sign once."""
    if kind == K.KNOT_UP or kind == K.KNOT_DOWN:
        return knot_switch(M, kind, j, y)
    if is_seat_switch(kind):
        return seat_switch(M, kind, j, y)
    bd = M.body
    k = int(bd[BodyColumn.OFFSET])
    if kind == K.TURN:
        return y[k + 1] / bd[BodyColumn.SPEED_SCALE]
    start = M.table_index[M.exchange_int[j, ExchangeInt.AREA_TABLE], TableColumn.START]  # x = [−inf, crossings...]
    i = tracked_interval(M, j)
    c = M.table_x[start + 1 + i] if kind == K.CROSSING_UP else M.table_x[start + i]
    return (y[k] - c) / M.exchange_float[j, ExchangeFloat.SWITCH_SCALE]


@njit(cache=True)
def switches(M, qs, t, y, seg_end, vals):
    """Values of switches ``qs`` at (t, y) into ``vals``, inputs read as the right-hand side reads them; POP_HOLD is
    (t − due)/hold at the raw t, due = hold start + hold time (1: never watched, when not holding)."""
    states(M, np.nextafter(seg_end, -np.inf) if t >= seg_end else t, y)
    for n in range(qs.size):
        q = qs[n]
        kind, j = M.switch_kind[q], M.switch_target[q]
        if kind == K.LAW_KINK:
            vals[n] = kink_value(M, j)
        elif kind == K.POP_HOLD:
            h, start = M.exchange_float[j, ExchangeFloat.HOLD_TIME], M.hold_start[j]
            vals[n] = (t - (start + h)) / h if h > 0.0 and not math.isnan(start) else 1.0
        elif kind == K.SAMPLE:
            vals[n] = sample_switch(M, j, t)
        elif is_body_switch(kind):
            vals[n] = body_switch(M, kind, j, y)
        else:
            vals[n] = exchange_switch(M, kind, j)
