"""The engine's calls into the hosted parts of a network, in numba's object mode: a real-gas cavity's state, its
wall's heat and its choke ratio (a hosted law's flow is the law kernel of :mod:`exchange.laws.hosted`). Each calls
the Python function of :mod:`exchange.engine.host` of the same name through :data:`CALLS` (which that module fills
when it is imported, as lowering a network does): the compiled code holds no Python source, so editing the Python
side, or the flow laws it reads, does not invalidate the engine's cache."""
from __future__ import annotations

from numba import njit, objmode

__all__ = ["CALLS", "hosted_state", "hosted_wall", "hosted_choke_ratio", "hosted_law_flow"]

#: name -> the Python function of exchange.engine.host
CALLS = {}


@njit(cache=True)
def hosted_state(h, i, t, y, st, T_guess):
    """:func:`exchange.engine.host.cavity_state` in object mode: row i of ``st`` at (t, y); T [K] (NaN: failed)."""
    with objmode(T="float64"):
        T = CALLS["cavity_state"](h, i, t, y, st, T_guess)
    return T


@njit(cache=True)
def hosted_wall(h, i, inflow, dy):
    """:func:`exchange.engine.host.wall_heat` in object mode: the wall's rates into ``dy``; the heat leaving the gas [W]."""
    with objmode(q="float64"):
        q = CALLS["wall_heat"](h, i, inflow, dy)
    return q


@njit(cache=True)
def hosted_choke_ratio(h, i):
    """:func:`exchange.engine.host.choke_ratio` in object mode [-]."""
    with objmode(r="float64"):
        r = CALLS["choke_ratio"](h, i)
    return r


@njit(cache=True)
def hosted_law_flow(h, j, u, p_down, area, t, st):
    """:func:`exchange.engine.host.law_flow` in object mode [kg/s] (NaN: failed)."""
    with objmode(m="float64"):
        m = CALLS["law_flow"](h, j, u, p_down, area, t, st)
    return m
