"""The hosted parts of a lowered network, Python's side: what the engine asks Python for (the object-mode calls that
ask are :mod:`exchange.engine.hosted`).

A network lowers (:mod:`exchange.engine.lower`) even when some of its parts are not numba kernels: a real-gas
cavity, whose state is CoolProp's HEOS (a C++ library reached through its Python wrapper, ~3 µs an update), its
wall's heat flows (film properties from CoolProp) and the real-gas nozzle, or a flow law a user wrote in Python.
Those parts stay the objects the scene built; the kernels call them in numba's object mode (:func:`hosted_state`,
:func:`hosted_wall`, :func:`hosted_choke_ratio` below, and the law kernel of :mod:`exchange.laws.hosted`; ~1.7 µs a
call measured here, less than the CoolProp update it wraps) and everything else (the other cavities, exchanges,
inflators, activation, ledger, switches, events, the integrator) runs compiled. Nothing is restated: each Python
function below calls the object's own method.

Each lowered network with hosted parts is registered here once (:func:`register`) under an integer id, which the
model carries (``CavityInt.HOST`` of a real-gas cavity, the law ints of a hosted law); the entry holds the network
weakly and goes with it. A hosted call that fails returns NaN (the engine then reports a failed right-hand side)
and keeps the exception in :attr:`Host.error` for the message.
"""
from __future__ import annotations

import itertools
import math
import weakref

import numpy as np

from .hosted import CALLS
from .layout import StateColumn
from exchange.laws.realgas_orifice import real_gas_point
from exchange.network.vent import GasPoint

__all__ = ["Host", "HOSTS", "register", "host_of", "cavity_state", "law_flow", "wall_heat", "choke_ratio"]

HOSTS: dict = {}
_IDS = itertools.count()
_FAILURES = (ArithmeticError, ValueError)


class Host:
    """A registered network's hosted parts, with the last state of each real-gas cavity and its flow-law view
    (set by :func:`cavity_state` at the start of every evaluation, read by the flows, walls and switches after
    it)."""

    def __init__(self, net):
        self._net = weakref.ref(net)
        self.states = [None] * len(net.cavities)
        self.points = [None] * len(net.cavities)
        self.error: BaseException | None = None

    @property
    def network(self):
        return self._net()

    def point(self, u: int, st) -> GasPoint:
        """The flow-law view (:class:`exchange.network.vent.GasPoint`) of side u (−1: ambient): a real-gas cavity's from its
        last state, an ideal gas's from its row of the state scratch."""
        net = self.network
        if u < 0:
            return net._ambient_point
        if getattr(net.cavities[u], "kind", "gas") == "realgas":
            return self.points[u]
        row, ns = st[u], len(net.cavities[u].initial_masses)
        c = StateColumn
        return GasPoint(row[c.P], row[c.T], row[c.RHO], row[c.R], row[c.GAMMA], row[c.H],
                        row[c.FRACTIONS:c.FRACTIONS + ns].copy())

    def fail(self, exc: BaseException) -> float:
        self.error = exc
        return math.nan


def register(net) -> int:
    """Register ``net``'s hosted parts; returns the id the arrays carry."""
    h = next(_IDS)
    HOSTS[h] = Host(net)
    weakref.finalize(net, HOSTS.pop, h, None)
    return h


def host_of(h: int) -> Host:
    return HOSTS[h]


def cavity_state(h: int, i: int, t: float, y, st, T_guess: float) -> float:
    """Fill row i of the state scratch ``st`` (:class:`exchange.engine.layout.StateColumn`) with real-gas cavity i's state at
    (t, y) (:meth:`cavity.realgas_cavity.RealGasCavity.state` and its gas point); returns T [K], NaN if it
    failed."""
    host = HOSTS[h]
    net = host.network
    cav, k = net.cavities[i], net.offsets[i]
    try:
        s = cav.state(t, y[k:k + cav.n_unknowns], T_guess)
    except _FAILURES as exc:
        return host.fail(exc)
    pt, row, ns = real_gas_point(s), st[i], len(cav.initial_masses)
    host.states[i], host.points[i] = s, pt
    c = StateColumn
    row[c.P], row[c.T], row[c.RHO], row[c.R], row[c.GAMMA], row[c.H] = pt.p, pt.T, pt.rho, pt.R, pt.gamma, pt.h
    row[c.V], row[c.DV], row[c.MASS] = s.volume, s.volume_rate, s.mixture.mass
    row[c.FRACTIONS:c.FRACTIONS + ns] = pt.mass_fractions
    return float(s.temperature)


def law_flow(h: int, j: int, u: int, p_down: float, area: float, t: float, st) -> float:
    """Mass flow [kg/s] of exchange j's hosted law from side u into p_down [Pa] through ``area`` [m^2] at t
    (``law.mass_flow(up, p_down, area, t)``); NaN if it failed."""
    host = HOSTS[h]
    try:
        return float(host.network.exchanges[j].law.mass_flow(host.point(u, st), p_down, area, t))
    except _FAILURES as exc:
        return host.fail(exc)


def wall_heat(h: int, i: int, inflow: float, dy) -> float:
    """Real-gas cavity i's wall (:meth:`cavity.realgas_cavity.RealGasCavity.wall_heat`, ``inflow`` [kg/s]
    entering it used when its inner convection depends on it): writes the wall's unknowns' rates into ``dy`` and
    returns the heat leaving the gas [W] (NaN if it failed)."""
    host = HOSTS[h]
    net = host.network
    cav, s = net.cavities[i], host.states[i]
    try:
        cav.wall_heat(s, inflow if cav.has_inflow_convection else 0.0)
    except _FAILURES as exc:
        return host.fail(exc)
    k = net.offsets[i] + len(cav.initial_masses) + 1
    dy[k:k + len(s.extra_rates)] = np.asarray(s.extra_rates, dtype=float)
    return float(s.heat_out)


def choke_ratio(h: int, i: int) -> float:
    """p*/p0 [-] of real-gas cavity i's last state (:meth:`exchange.realgas_orifice.RealGasPoint.choke_ratio`);
    NaN if it failed."""
    host = HOSTS[h]
    try:
        return float(host.points[i].choke_ratio())
    except _FAILURES as exc:
        return host.fail(exc)


CALLS.update(cavity_state=cavity_state, law_flow=law_flow, wall_heat=wall_heat, choke_ratio=choke_ratio)
