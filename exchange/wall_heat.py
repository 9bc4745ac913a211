"""The heat flows of real-gas cavities' walls in one right-hand side (:class:`exchange.network.Network`)."""
from __future__ import annotations

__all__ = ["wall_heat_flows"]


def wall_heat_flows(net, t: float, states: list, flows: list) -> None:
    """Give the walls of ``net._walls`` their heat flows (:meth:`cavity.realgas_cavity.RealGasCavity.wall_heat`),
    with the mass flow entering each cavity (inflators and exchanges, [kg/s]) when its inner convection depends on
    it. Only the right-hand side needs them: states read by switches and outputs skip the film properties."""
    for i in net._walls:
        cav, inflow = net.cavities[i], 0.0
        if cav.has_inflow_convection:
            inflow = sum(inf.mass_flow(t) for inf in cav.inflators)
            for ex, (mdot, _) in zip(net.exchanges, flows):
                if (ex.downstream == i and mdot > 0.0) or (ex.upstream == i and mdot < 0.0):
                    inflow += abs(mdot)
        cav.wall_heat(states[i], inflow)
