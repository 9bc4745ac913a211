"""Laws the engine runs in Python: any law object that is not one of the registry's lowered laws (a subclass, a
law of one's own with ``mass_flow(up, p_down, area, t)``, the real-gas nozzle of :mod:`exchange.laws.
realgas_orifice`), and the no-flow kernel of the engine's free law slots.

:func:`hosted_kernel` has the registry's kernel signature; it calls the object's own ``mass_flow`` through
:func:`exchange.engine.host.law_flow` in numba's object mode (~2 µs a call). Its ``law_int`` entries are the
network's host id and the exchange's index.
"""
from __future__ import annotations

from enum import IntEnum

from numba import njit

from exchange.engine.hosted import hosted_law_flow
from exchange.engine.layout import LAW_SIGNATURE

__all__ = ["hosted_kernel", "no_flow", "HostedInt"]


class HostedInt(IntEnum):
    HOST = 0  # the network's id in exchange.engine.hosted
    EXCHANGE = 1  # the exchange's index


@njit(LAW_SIGNATURE, cache=True)
def hosted_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The flow [kg/s] of exchange ``li[EXCHANGE]``'s law object from side u, computed in Python (NaN: it
    failed)."""
    return hosted_law_flow(li[HostedInt.HOST], li[HostedInt.EXCHANGE], u, p_down, area, t, st)


@njit(LAW_SIGNATURE, cache=True)
def no_flow(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """No flow (the engine's free law slots)."""
    return 0.0
