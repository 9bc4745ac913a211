"""Each exchange's area and mass flow on the engine, and what a flow carries from one side to the other.

The area is the exchange's base area (constant, a blocked leakage area as steps of time or of the dynamic body's
displacement, a leakage surface on a vertex trajectory), times the square of its mesh scale, through the activation
rule (:func:`exchange.network.activation.activated_area`). The flow is its law's kernel (``M.laws``, :mod:`exchange.laws.
registry`) from the side at the higher pressure, or its prescribed flow.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from blockage.moving_area import moving_leak_area

from exchange.network.activation import activated_area

from .layout import (AmbientColumn, AreaKind, CavityInt, Energy, ExchangeFloat, ExchangeInt, OpenState, StateColumn,
                     TableColumn, side)
from .tables import step_value, table_value

__all__ = ["base_area", "exchange_area", "exchange_flow", "add_transfer"]

EI, EF = ExchangeInt, ExchangeFloat


@njit(cache=True)
def base_area(M, j, t):
    """Leakage area of exchange j before activation [m^2] (:meth:`exchange.network.network.Network.base_area`): the
    constant, a step table of time, or the area of the dynamic body's interval ``M.interval[j]`` (of an FE rule's
    sampled flags: the interval in use, :mod:`exchange.engine.sampled`), times the square
    of its mesh scale; of a surface on a vertex trajectory the step table gives the interval of the active set and
    the next table holds the pack of :func:`blockage.moving_area.moving_leak_area`."""
    ei, tx, ty, ti = M.exchange_int, M.table_x, M.table_y, M.table_index
    kind, k = ei[j, EI.AREA], ei[j, EI.AREA_TABLE]
    if kind == AreaKind.MOVING_SURFACE:
        s, n = ti[k + 1, TableColumn.START], ti[k + 1, TableColumn.ROWS]
        return moving_leak_area(ty[s:s + n], int(step_value(tx, ty, ti, k, t)), t)
    if kind == AreaKind.STEPS_OF_BODY or kind == AreaKind.SAMPLED_OF_BODY:
        base = ty[ti[k, TableColumn.START] + M.interval[j]]
    elif k >= 0:
        base = step_value(tx, ty, ti, k, t)
    else:
        base = M.exchange_float[j, EF.AREA]
    if ei[j, EI.SCALE_TABLE] >= 0:  # the leakage surface scales with its cavity mesh: area × s²
        sc = table_value(tx, ty, ti, ei[j, EI.SCALE_TABLE], t)
        base *= sc * sc
    return base


@njit(cache=True)
def exchange_area(M, j, t):
    """Flow area [m^2] of exchange j at t: :func:`exchange.network.activation.activated_area` of its base area, with its
    time window, its open state (a pop vent not popped, or closed at its close pressure: shut), its amplitude and,
    with DELTA LEAKAGE AREA, its area at activation."""
    ei, ef = M.exchange_int, M.exchange_float
    window = ei[j, EI.WINDOW] == 1
    amp = ei[j, EI.AMPLITUDE]
    a = table_value(M.table_x, M.table_y, M.table_index, amp, t) if amp >= 0 else 1.0
    return activated_area(base_area(M, j, t), t, ef[j, EF.OPEN_TIME] if window else -np.inf,
                          ef[j, EF.CLOSE_TIME] if window else np.inf, M.open_state[j] != OpenState.OPEN, a,
                          ef[j, EF.AREA_AT_ACTIVATION] if ei[j, EI.DELTA_AREA] == 1 else 0.0)


@njit(cache=True)
def _law_flow(M, j, u, p_down, area, t):
    """Exchange j's law kernel from side u into p_down [Pa] [kg/s]."""
    return M.laws[M.exchange_int[j, EI.LAW]](M.law_float[j], M.law_int[j], M.table_x, M.table_y, M.table_index,
                                             M.state, M.ambient, u, p_down, area, t)


@njit(cache=True)
def exchange_flow(M, j, t):
    """Signed mass flow [kg/s] of exchange j, first side → second side, on the states in ``M.state``: 0 while shut
    or held closed (equalised); a prescribed flow as its law gives it; else the law from the side at the higher
    pressure (none back from ambient unless two-way)."""
    area = exchange_area(M, j, t)
    if area <= 0.0 or M.equalised[j] == 1:
        return 0.0
    ei, st, amb = M.exchange_int, M.state, M.ambient
    a, b = ei[j, EI.UP], ei[j, EI.DOWN]
    if ei[j, EI.PRESCRIBED] == 1:
        return _law_flow(M, j, a, side(st, amb, b, StateColumn.P), area, t)
    pa, pb = side(st, amb, a, StateColumn.P), side(st, amb, b, StateColumn.P)
    if pa >= pb:
        return _law_flow(M, j, a, pb, area, t)
    if b < 0 and ei[j, EI.TWO_WAY] == 0:
        return 0.0
    return -_law_flow(M, j, b, pa, area, t)


@njit(cache=True)
def add_transfer(M, dy, i, mdot, edot, src):
    """Add to cavity i's rates a mass flow ``mdot`` [kg/s] of the composition of side ``src`` (−1: ambient) and its
    enthalpy flow ``edot`` [W] (no energy unknown when isothermal)."""
    ci = M.cavity_int
    k, ns = ci[i, CavityInt.OFFSET], ci[i, CavityInt.SPECIES]
    for s in range(ns):
        dy[k + s] += mdot * (M.ambient[AmbientColumn.FRACTIONS + s] if src < 0 else
                             M.state[src, StateColumn.FRACTIONS + s])
    if ci[i, CavityInt.ENERGY] != Energy.ISOTHERMAL:
        dy[k + ns] += edot
