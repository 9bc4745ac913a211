"""A network of cavities joined by exchanges: the unknowns of a whole scene's gas, their layout and the discrete
state, which the compiled engine lowers and integrates (:mod:`exchange.engine`: its right-hand side, switches and
events; :mod:`exchange.readback.values`: its values at an instant).

Unknown vector layout::

    [cavity 0 unknowns | cavity 1 unknowns | ... | ledger]

where each cavity holds its species masses [kg] (and its internal energy U [J] unless isothermal), and the
ledger holds running integrals that take no part in the dynamics but close the books exactly: per exchange the
mass [kg] and energy [J] that crossed it (positive upstream → downstream), per cavity the inflator mass [kg],
inflator enthalpy [J], boundary work ∫p dV [J] and heat lost [J]. Because every explicit or implicit Runge–Kutta
step is linear in the rates, initial + inflow − outflow − final vanishes to round-off.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .discrete_state import DiscreteState
from .lowering import NetworkLowering
from .vent import GasPoint

__all__ = ["Network", "LEDGER_PER_EXCHANGE", "LEDGER_PER_CAVITY"]

LEDGER_PER_EXCHANGE = 2  # mass, energy
LEDGER_PER_CAVITY = 4  # inflator mass, inflator enthalpy, boundary work, heat lost


@dataclass
class Network(NetworkLowering):
    """Cavities, exchanges and the environment of one scene, with its discrete state: per exchange whether a pop
    vent has popped, when its hold started, its area when it opened (DELTA LEAKAGE AREA), whether a two-way
    exchange is held closed (equalised) and whether it has closed for good at its close pressure. The compiled engine keeps that state in its arrays during a run and the
    network receives it per segment (``snapshot``/``restore``).

    Attributes
    ----------
    gas : cavity.gas.GasModel
    cavities : tuple of cavity.cavity.Cavity
    exchanges : tuple of exchange.network.vent.Exchange
    ambient : exchange.network.vent.Ambient
    """

    gas: object
    cavities: tuple
    exchanges: tuple
    ambient: object
    offsets: list = field(init=False)
    ledger_offset: int = field(init=False)
    _ambient_point: GasPoint = field(init=False)
    ledger_offsets: list = field(init=False)  # per cavity: its first ledger unknown
    popped: list = field(init=False)  # per exchange: the pop condition has been met (it stays open)
    holding_since: list = field(init=False)  # per exchange: when Δp last rose above the pop pressure, or None
    area_at_activation: list = field(init=False)

    def __post_init__(self):
        self.offsets, k = [], 0
        for cav in self.cavities:
            self.offsets.append(k)
            k += cav.n_unknowns
        self.ledger_offset = k
        self._ambient_point = self.ambient.point()
        self.ledger_offsets = [self.ledger_offset + LEDGER_PER_EXCHANGE * len(self.exchanges) + LEDGER_PER_CAVITY * i
                        for i in range(len(self.cavities))]
        real = any(getattr(c, "kind", "gas") == "realgas" for c in self.cavities)
        #: the unknowns the right-hand side depends on (cavity states; not the ledger), for a Jacobian by
        #: differences that skips the rest (cavity.jacobian); real-gas networks only, ideal ones unchanged
        self.coupled_unknowns = [k + i for cav, k in zip(self.cavities, self.offsets)
                                 for i in range(getattr(cav, "n_coupled", cav.n_unknowns))] \
            if real and type(self) is Network else None
        self.reset()

    def reset(self) -> None:
        """Back to the discrete state of t = 0 (vents armed, nothing popped)."""
        self.popped = [False] * len(self.exchanges)
        self.holding_since = [None] * len(self.exchanges)
        self.area_at_activation = [None] * len(self.exchanges)  # set when each exchange opens
        self.equalised = [False] * len(self.exchanges)  # two-way exchanges held closed at Δp ≈ 0
        self.closed = [False] * len(self.exchanges)  # closed for good at their close pressure

    @property
    def size(self) -> int:
        return self.ledger_offset + LEDGER_PER_EXCHANGE * len(self.exchanges) + LEDGER_PER_CAVITY * len(self.cavities)

    def initial_state(self) -> np.ndarray:
        """Unknowns at t = 0; also resets the discrete state."""
        self.reset()
        y = np.zeros(self.size)
        for cav, k in zip(self.cavities, self.offsets):
            y[k:k + cav.n_unknowns] = cav.initial_unknowns(self.gas)
        return y

    @property
    def breakpoints(self) -> tuple:
        pts = [b for cav in self.cavities for b in cav.breakpoints]
        pts += [b for ex in self.exchanges if ex.activation is not None for b in ex.activation.breakpoints]
        pts += [b for ex in self.exchanges for b in getattr(ex.law, "breakpoints", ())]  # tables of time
        return tuple(pts)

    def states(self, t: float, y) -> list:
        """The :class:`exchange.readback.values.GasState` of every cavity at (t, y), from the compiled engine."""
        from exchange.readback.values import cavity_states

        return cavity_states(self.engine(), t, y)

    def base_area(self, index: int, t: float) -> float:
        """Leakage area of exchange ``index`` before activation rules [m^2] (lowered as it is: a constant here)."""
        return self.exchanges[index].area

    def can_equalise(self, index: int) -> bool:
        """Exchange ``index`` has an equalised mode: a pneumatic law between two gas cavities, or two-way to
        ambient (:data:`exchange.network.equalised.EQUALISED_BELOW`)."""
        ex = self.exchanges[index]
        if ex.law.prescribed or not ex.law.pneumatic or not (ex.two_way or ex.downstream is not None):
            return False
        return all(getattr(self.cavities[i], "kind", "gas") == "gas" for i in (ex.upstream, ex.downstream)
                   if i is not None)

    def snapshot(self) -> DiscreteState:
        """The discrete state (for reading results back on a segment)."""
        return DiscreteState(tuple(self.popped), tuple(self.holding_since), tuple(self.area_at_activation),
                             tuple(self.equalised), tuple(self.closed), (None,) * len(self.exchanges))

    def restore(self, mode: DiscreteState | None) -> None:
        if mode is not None:
            self.popped, self.holding_since = list(mode.popped), list(mode.holding_since)
            self.area_at_activation = list(mode.area_at_activation)
            self.equalised, self.closed = list(mode.equalised), list(mode.closed)

    def is_plain(self) -> bool:
        """True for a plain :class:`Network` (a subclass lowers itself only through ``lowered_geometry``)."""
        return type(self) is Network

    def describe(self, t: float, y) -> str:
        """A one-line account of the cavities' state, for error messages."""
        parts = []
        for cav, k in zip(self.cavities, self.offsets):
            ns = len(cav.initial_masses)
            m = y[k:k + ns]
            parts.append(f"{cav.name}: mass {m.sum():.6g} kg" + ("" if cav.isothermal else f", U {y[k + ns]:.6g} J"))
        return "; ".join(parts)
