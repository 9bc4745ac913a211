"""The right-hand side: d(unknowns)/dt of a lowered network at (t, y) in its current discrete state.

Layout of the unknowns: :mod:`exchange.network`. Per cavity its species masses change by its inflators and exchanges
and its internal energy by their enthalpy flows, minus p·dV/dt and the heat it loses; the ledger integrates what
crossed each exchange and each cavity's inflator mass and enthalpy, boundary work and heat lost, so the books
close to round-off. The dynamic body adds its equation of motion (:mod:`exchange.engine.body`). The tests pair this
with a naive assembly from the Python objects (``tests/exchange/engine/pairs.py``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from cavity.cavity import heat_loss

from .body import body_rhs, has_body, is_held
from .flows import add_transfer, exchange_flow
from .gas import states
from .hosted import hosted_wall
from .inflators import inflator_enthalpy_flow, inflator_flow
from .layout import CavityFloat, CavityInt, Energy, ExchangeInt, InflatorFloat, InflatorInt, StateColumn, side

__all__ = ["rhs"]

CI, P, T, DV = CavityInt, StateColumn.P, StateColumn.T, StateColumn.DV


@njit(cache=True)
def _walls(M):
    """A real-gas cavity has a wall (its inner convection may depend on the mass flowing in)."""
    for i in range(M.cavity_int.shape[0]):
        if M.cavity_int[i, CI.ENERGY] == Energy.WALL:
            return True
    return False


@njit(cache=True)
def _inflators(M, t, dy, inflow):
    """Each started inflator's mass, species and enthalpy into its cavity and the cavity's ledger."""
    ci = M.cavity_int
    for q in range(M.inflator_int.shape[0]):
        if t < M.inflator_float[q, InflatorFloat.START]:
            continue
        mdot, T_in = inflator_flow(M, q, t)
        if mdot != 0.0:
            i = M.inflator_int[q, InflatorInt.CAVITY]
            hdot = inflator_enthalpy_flow(M, q, mdot, T_in)
            k, ns, c = ci[i, CI.OFFSET], ci[i, CI.SPECIES], ci[i, CI.LEDGER]
            for s in range(ns):
                dy[k + s] += mdot * M.inflator_float[q, InflatorFloat.FRACTIONS + s]
            dy[c] += mdot
            dy[c + 1] += hdot
            if ci[i, CI.ENERGY] != Energy.ISOTHERMAL:
                dy[k + ns] += hdot
            if inflow.size:
                inflow[i] += mdot


@njit(cache=True)
def _work_and_heat(M, dy):
    """Each gas cavity's boundary work p·dV/dt and heat lost, out of its energy and into its ledger."""
    ci, cf, st = M.cavity_int, M.cavity_float, M.state
    for i in range(ci.shape[0]):
        energy = ci[i, CI.ENERGY]
        if energy != Energy.ISOTHERMAL:
            work = st[i, P] * st[i, DV]
            heat = heat_loss(cf[i, CavityFloat.HEAT_TRANSFER], st[i, T], cf[i, CavityFloat.AMBIENT_TEMPERATURE]) \
                if energy == Energy.HEAT_LOSS else 0.0
            k, ns, c = ci[i, CI.OFFSET], ci[i, CI.SPECIES], ci[i, CI.LEDGER]
            dy[k + ns] -= work + heat
            dy[c + 2] += work
            dy[c + 3] += heat


@njit(cache=True)
def _exchanges(M, t, dy, inflow):
    """Each exchange's flow between its sides and into the ledger; False when a hosted law failed."""
    ei, ok = M.exchange_int, True
    for j in range(ei.shape[0]):
        mdot = exchange_flow(M, j, t)
        if mdot == 0.0:
            continue
        if not mdot == mdot:  # a hosted law failed
            ok = False
            continue
        up, down = ei[j, ExchangeInt.UP], ei[j, ExchangeInt.DOWN]
        if inflow.size:
            into = down if mdot > 0.0 else up
            if into >= 0:
                inflow[into] += abs(mdot)
        src = up if mdot >= 0.0 else down
        edot = mdot * side(M.state, M.ambient, src, StateColumn.H)
        add_transfer(M, dy, up, -mdot, -edot, src)
        if down >= 0:
            add_transfer(M, dy, down, mdot, edot, src)
        e = M.ledger + 2 * j
        dy[e] += mdot
        dy[e + 1] += edot
    return ok


@njit(cache=True)
def _wall_heat(M, inflow, dy):
    """Each real-gas wall's rates into ``dy`` and its heat out of the gas's energy, into the cavity's ledger of heat
    lost; False if a wall failed."""
    ok, ci = True, M.cavity_int
    for i in range(ci.shape[0]):
        if ci[i, CI.ENERGY] == Energy.WALL:
            heat = hosted_wall(ci[i, CI.HOST], i, inflow[i], dy)
            ok = ok and heat == heat
            dy[ci[i, CI.OFFSET] + ci[i, CI.SPECIES]] -= heat
            dy[ci[i, CI.LEDGER] + 3] += heat
    return ok


@njit(cache=True)
def rhs(M, t, y, dy, seg_end):
    """d(unknowns)/dt into dy; False if a cavity's state or a hosted part failed.

    ``seg_end``: inputs are read at its left limit when t reaches it (a step ending on a table break sees the piece
    it integrated over)."""
    if t >= seg_end:
        t = np.nextafter(seg_end, -np.inf)
    ok = states(M, t, y)
    dy[:] = 0.0
    inflow = np.zeros(M.cavity_int.shape[0] if _walls(M) else 0)  # mass flowing into each cavity [kg/s]
    _inflators(M, t, dy, inflow)
    _work_and_heat(M, dy)
    ok = _exchanges(M, t, dy, inflow) and ok
    if inflow.size:
        ok = _wall_heat(M, inflow, dy) and ok
    if has_body(M) and not is_held(M):
        body_rhs(M, y, dy)
    return ok
