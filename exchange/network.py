"""A network of cavities joined by exchanges: the ODE right-hand side of a whole scene's gas.

Unknown vector layout::

    [cavity 0 unknowns | cavity 1 unknowns | ... | ledger]

where each cavity holds its species masses [kg] (and its internal energy U [J] unless isothermal), and the
ledger holds running integrals that take no part in the dynamics but close the books exactly: per exchange the
mass [kg] and energy [J] that crossed it (positive upstream → downstream), per cavity the inflator mass [kg],
inflator enthalpy [J], boundary work ∫p dV [J] and heat lost [J]. Because every explicit or implicit Runge–Kutta
step is linear in the rates, initial + inflow − outflow − final vanishes to round-off.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from cavity.cavity import CavityState
from .activation import activated_area
from .equalised import EQUALISED_BELOW
from .network_lowering import NetworkLowering
from .network_rates import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE, NetworkRates
from .network_switches import NetworkSwitches
from .vent import GasPoint

__all__ = ["Network", "LEDGER_PER_EXCHANGE", "LEDGER_PER_CAVITY"]


@dataclass
class Network(NetworkRates, NetworkLowering, NetworkSwitches):
    """Cavities, exchanges and the environment of one scene.

    Attributes
    ----------
    gas : cavity.gas.GasModel
    cavities : tuple of cavity.cavity.Cavity
    exchanges : tuple of exchange.vent.Exchange
    ambient : exchange.vent.Ambient
    """

    gas: object
    cavities: tuple
    exchanges: tuple
    ambient: object
    offsets: list = field(init=False)
    ledger_offset: int = field(init=False)
    _T_guess: list = field(init=False)
    _ambient_point: GasPoint = field(init=False)
    _segment_end: float = field(init=False, default=math.inf)
    _ledger: list = field(init=False)
    last_states: list = field(init=False, default=None)  # the cavity states of the latest rhs call
    _inflow_fractions: list = field(init=False)
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
        self._ledger = [self.ledger_offset + LEDGER_PER_EXCHANGE * len(self.exchanges) + LEDGER_PER_CAVITY * i
                        for i in range(len(self.cavities))]
        self._inflow_fractions = [[np.asarray(inf.mass_fractions, dtype=float) for inf in c.inflators]
                                  for c in self.cavities]
        self._layout = [(cav, k, getattr(cav, "kind", "gas"), cav.n_unknowns)
                        for cav, k in zip(self.cavities, self.offsets)]
        self._walls = [i for i, c in enumerate(self.cavities) if getattr(c, "wall", None) is not None]
        self._keep_states = any(getattr(c, "kind", "gas") == "realgas" for c in self.cavities)
        self._kept = (None, None)
        #: the unknowns the right-hand side depends on (cavity states; not the ledger), for a Jacobian by
        #: differences that skips the rest (cavity.integration); real-gas networks only, ideal ones unchanged
        self.coupled_unknowns = [k + i for cav, k in zip(self.cavities, self.offsets)
                                 for i in range(getattr(cav, "n_coupled", cav.n_unknowns))] \
            if self._keep_states and type(self) is Network else None
        self.reset()

    def reset(self) -> None:
        """Back to the discrete state of t = 0 (vents armed, nothing popped)."""
        self._T_guess = [c.initial_temperature for c in self.cavities]
        self._segment_end = math.inf
        self.popped = [False] * len(self.exchanges)
        self.holding_since = [None] * len(self.exchanges)
        self.area_at_activation = [None] * len(self.exchanges)  # set when each exchange opens
        self.equalised = [False] * len(self.exchanges)  # two-way exchanges held closed at Δp ≈ 0

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
        """The gas state of every cavity at (t, y). With a real-gas cavity the last (t, y) and its states are
        kept: the switch functions, evaluated one after the other at each step's end, solve the equation of state
        once."""
        if self._keep_states:
            key = (t, np.asarray(y, dtype=float).tobytes())
            if key == self._kept[0]:
                return self._kept[1]
            out = self._states(t, y)
            self._kept = (key, out)
            return out
        return self._states(t, y)

    def _states(self, t: float, y) -> list:
        out = []
        for i, (cav, k, kind, n) in enumerate(self._layout):
            if kind == "hydraulic":
                out.append(cav.state(t, y[k:k + 1]))
                continue
            s = (cav.state(t, y[k:k + n], self._T_guess[i]) if kind == "realgas" else
                 CavityState.of(cav, self.gas, t, y[k:k + n], self._T_guess[i]))
            self._T_guess[i] = s.temperature
            out.append(s)
        return out

    def base_area(self, index: int, t: float) -> float:
        """Leakage area of exchange ``index`` before activation rules [m^2]."""
        return self.exchanges[index].area

    def exchange_area(self, index: int, t: float) -> float:
        """Flow area of exchange ``index`` at t [m^2]: the leakage area after activation (window, pop, amplitude)."""
        ex, act = self.exchanges[index], self.exchanges[index].activation
        if act is not None and act.delta_area and act.pop_pressure is None and t >= act.open_time \
                and self.area_at_activation[index] is None:  # opened by time: the area at the opening time
            self.area_at_activation[index] = self.base_area(index, act.open_time)
        return activated_area(self.base_area(index, t), t, ex.activation, self.popped[index],
                              self.area_at_activation[index] or 0.0)

    def begin_segment(self, t0: float, t1: float, y0=None) -> None:
        """The integrator is about to integrate over [t0, t1] from y0; no breakpoint lies inside.

        A two-way pneumatic exchange whose sides agree to :data:`EQUALISED_BELOW` at t0 starts the segment
        equalised (held closed); its release switch watches for the network driving them apart.
        """
        self._segment_end = t1
        if y0 is None:
            return
        for j in range(len(self.exchanges)):
            if not self.equalised[j] and self.can_equalise(j) and self._dp_relative(t0, y0, j) < EQUALISED_BELOW:
                self.equalised[j] = True

    def input_time(self, t: float) -> float:
        """The time at which to read tabulated inputs: at the end of a segment, its left limit.

        Tables are right-continuous at their breakpoints; a step ending on a breakpoint must see the slope of the
        piece it integrated over, not the next one.
        """
        end = self._segment_end
        return math.nextafter(end, -math.inf) if t >= end else t

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
