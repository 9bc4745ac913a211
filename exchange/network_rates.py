"""The rates of a cavity network: the flow through each exchange and d(unknowns)/dt, with the ledger's running
integrals (a mixin of :class:`exchange.network.Network`, which supplies the layout, the states and the areas)."""
from __future__ import annotations

import numpy as np

from .network_switches import gas_point
from .wall_heat import wall_heat_flows

__all__ = ["NetworkRates", "LEDGER_PER_EXCHANGE", "LEDGER_PER_CAVITY"]

LEDGER_PER_EXCHANGE = 2  # mass, energy
LEDGER_PER_CAVITY = 4  # inflator mass, inflator enthalpy, boundary work, heat lost


class NetworkRates:
    """Needs ``cavities``, ``exchanges``, ``offsets``, ``ledger_offset``, ``_ledger``, ``_inflow_fractions``,
    ``_walls``, ``_ambient_point``, ``equalised``, ``states()``, ``exchange_area()`` and ``input_time()``."""

    def exchange_flows(self, t: float, states: list) -> list:
        """Signed mass flow [kg/s] and the GasPoint it carries, per exchange."""
        points = [gas_point(s) for s in states]
        flows = []
        for j, ex in enumerate(self.exchanges):
            a = points[ex.upstream]
            b = self._ambient_point if ex.downstream is None else points[ex.downstream]
            mdot = 0.0 if self.equalised[j] else ex.mass_flow(a, b, self.exchange_area(j, t), t)
            flows.append((mdot, a if mdot >= 0.0 else b))
        return flows

    def rhs(self, t: float, y) -> np.ndarray:
        """d(unknowns)/dt at (t, y)."""
        t = self.input_time(t)
        states = self.last_states = self.states(t, y)
        flows = self.exchange_flows(t, states)
        if self._walls:  # real-gas cavities' walls
            wall_heat_flows(self, t, states, flows)
        dy = np.zeros_like(y)
        for cav, k, s, c, fractions in zip(self.cavities, self.offsets, states, self._ledger,
                                           self._inflow_fractions):
            ns = len(cav.initial_masses)
            for inf, y_in in zip(cav.inflators, fractions):
                mdot = inf.mass_flow(t)
                if mdot:
                    hdot = mdot * inf.gas.enthalpy(inf.temperature(t)) / inf.gas.mass
                    dy[k:k + ns] += mdot * y_in
                    dy[c] += mdot
                    dy[c + 1] += hdot
                    if not cav.isothermal:
                        dy[k + ns] += hdot
            if not cav.isothermal:
                extra = getattr(s, "extra_rates", None)
                work = s.pressure * s.volume_rate
                heat = cav.heat_loss(s.temperature) if extra is None else s.heat_out
                dy[k + ns] -= work + heat
                dy[c + 2] += work
                dy[c + 3] += heat
                if extra:  # a real-gas cavity's wall: temperature, heat to ambient
                    dy[k + ns + 1:k + ns + 1 + len(extra)] = extra
        for j, (ex, (mdot, carrier)) in enumerate(zip(self.exchanges, flows)):
            if mdot == 0.0:
                continue
            edot = mdot * carrier.h
            self._transfer(dy, ex.upstream, -mdot, -edot, carrier)
            if ex.downstream is not None:
                self._transfer(dy, ex.downstream, mdot, edot, carrier)
            e = self.ledger_offset + LEDGER_PER_EXCHANGE * j
            dy[e] += mdot
            dy[e + 1] += edot
        return dy

    def _transfer(self, dy, i, mdot, edot, carrier):
        k, cav = self.offsets[i], self.cavities[i]
        ns = len(cav.initial_masses)
        dy[k:k + ns] += mdot * carrier.mass_fractions
        if not cav.isothermal:
            dy[k + ns] += edot
