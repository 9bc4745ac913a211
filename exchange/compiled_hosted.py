"""The compiled path's calls into the hosted parts of a network (:mod:`exchange.hosted`), in numba's object
mode: a real-gas cavity's state, a hosted law's flow, a real-gas wall's heat and a real-gas upstream's choke
ratio. Each is one object-mode block around the Python function of the same name (~1.7 µs with its arrays
boxed, measured); the arrays are passed by reference (boxing does not copy), so the Python side writes the state
scratch and the rates in place.
"""
from __future__ import annotations

import numpy as np
from numba import njit, objmode

from . import hosted
from .compiled_tables import GAM
from .orifice import critical_pressure_ratio

__all__ = ["hosted_state", "hosted_flow", "hosted_wall", "choke_ratio_of", "inflow_scratch", "add_wall_heat"]


@njit(cache=True)
def hosted_state(h, i, t, y, st, T_guess):
    """:func:`exchange.hosted.cavity_state`: row i of ``st`` at (t, y); T [K] (NaN: failed)."""
    with objmode(T="float64"):
        T = hosted.cavity_state(h, i, t, y, st, T_guess)
    return T


@njit(cache=True)
def hosted_flow(h, j, u, p_down, area, t, st):
    """:func:`exchange.hosted.law_flow` [kg/s] (NaN: failed)."""
    with objmode(m="float64"):
        m = hosted.law_flow(h, j, u, p_down, area, t, st)
    return m


@njit(cache=True)
def hosted_wall(h, i, inflow, dy):
    """:func:`exchange.hosted.wall_heat`: the wall's rates into ``dy``; the heat leaving the gas [W]."""
    with objmode(q="float64"):
        q = hosted.wall_heat(h, i, inflow, dy)
    return q


@njit(cache=True)
def _hosted_choke_ratio(h, i):
    with objmode(r="float64"):
        r = hosted.choke_ratio(h, i)
    return r


@njit(cache=True, inline="always")
def choke_ratio_of(ci, st, amb, i):
    """p*/p0 [-] of side i (−1: ambient): a real-gas cavity's from its equation of state (hosted), else the ideal
    gas's :func:`exchange.orifice.critical_pressure_ratio` of its γ (:meth:`exchange.vent.GasPoint.choke_ratio`)."""
    if i < 0:
        return critical_pressure_ratio(amb[GAM])
    if ci[i, 7] == 2:
        return _hosted_choke_ratio(ci[i, 8], i)
    return critical_pressure_ratio(st[i, GAM])


@njit(cache=True, inline="always")
def inflow_scratch(ci):
    """Zeros per cavity when a real-gas cavity has a wall (energy code 3, ``ci[i, 1]``), for the mass flowing into
    each [kg/s] that its inner convection may depend on; else an empty array."""
    walls = False
    for i in range(ci.shape[0]):
        walls = walls or ci[i, 1] == 3
    return np.zeros(ci.shape[0] if walls else 0)


@njit(cache=True, inline="always")
def add_wall_heat(ci, inflow, dy):
    """Each real-gas wall's rates into ``dy`` and its heat out of the gas's energy, into the cavity's ledger of
    heat lost (layout: :mod:`exchange.network`); False if a wall failed."""
    ok = True
    for i in range(ci.shape[0]):
        if ci[i, 1] == 3:
            heat = hosted_wall(ci[i, 8], i, inflow[i], dy)
            ok = ok and heat == heat
            dy[ci[i, 0] + ci[i, 5]] -= heat
            dy[ci[i, 4] + 3] += heat
    return ok
