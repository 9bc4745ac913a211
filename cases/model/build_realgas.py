"""Real-gas cavities of a scene: their fluid (CoolProp HEOS), initial state, wall, and real-gas orifice laws."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from cavity.gas import GasModel
from cavity.inflator_realgas import RealGasTankTestInflator, real_gas_tank_masses
from cavity.realgas import RealFluid
from cavity.tables import Table
from cavity.realgas_cavity import RealGasCavity
from cavity.wall import Wall
from exchange.laws import OrificeLaw
from exchange.realgas_orifice import RealGasOrificeLaw

from cases.scene.errors import SceneError
from cases.scene.realgas import coolprop_name

__all__ = ["real_gas_cavity", "real_gas_laws", "real_gas_tank_test"]

def real_gas_cavity(scene, gas: GasModel, i: int, volume, inflators: tuple) -> RealGasCavity:
    """The :class:`RealGasCavity` of ``scene.cavity[i]`` (initial mass from HEOS density at p, T)."""
    c = scene.cavity[i]
    name = next(k for k, v in c.gas.items() if v > 0)
    k = gas.index(name)
    unit = np.zeros(len(gas.species))
    unit[k] = 1.0
    ideal = gas.mixture(unit)  # 1 kg of the fluid as an ideal gas: the enthalpy reference
    try:
        fluid = RealFluid(coolprop_name(scene, name), ideal.enthalpy, scene.ambient.temperature)
        rho = fluid.density(c.pressure, c.temperature)
    except ValueError as exc:
        raise SceneError(scene.path, f"cavity[{i}].gas", f"CoolProp: {exc}") from None
    V0 = max(volume(0.0) + c.added_volume, c.minimum_volume)
    masses = unit * rho * V0
    wall = None
    if c.energy == "wall":
        wall = Wall(c.wall_mass, c.wall_heat_capacity, c.wall_inner_area, c.wall_outer_area or c.wall_inner_area,
                    c.wall_inner_h, c.wall_outer_h, c.wall_length, c.wall_temperature or c.temperature,
                    scene.ambient.temperature, c.wall_orientation, c.wall_jet_diameter, c.wall_layers,
                    c.wall_conductivity, c.wall_thickness)
    return RealGasCavity(c.name, volume, tuple(masses), c.temperature, c.energy, c.added_volume, c.minimum_volume,
                         c.heat_transfer_coefficient, c.heat_transfer_area, scene.ambient.temperature, inflators,
                         fluid=fluid, species_index=k, wall=wall)


def real_gas_laws(exchanges: tuple, cavities: tuple) -> tuple:
    """Orifice exchanges touching a real-gas cavity get the real-gas nozzle (:class:`RealGasOrificeLaw`)."""
    real = {i for i, c in enumerate(cavities) if getattr(c, "kind", "gas") == "realgas"}
    if not real:
        return exchanges
    return tuple(replace(ex, law=RealGasOrificeLaw(ex.law.discharge_coefficient))
                 if type(ex.law) is OrificeLaw and ({ex.upstream, ex.downstream} & real) else ex
                 for ex in exchanges)


def real_gas_tank_test(scene, inf, mass_fractions: tuple, mix) -> RealGasTankTestInflator:
    """A tank-test inflator whose tank holds the inflator's one species as a real gas (HEOS)."""
    name = next(k for k, v in inf.gas.items() if v > 0)
    table = inf.tank_pressure
    fluid = RealFluid(coolprop_name(scene, name))
    masses = real_gas_tank_masses(fluid, inf.tank_volume, table.x, table.y, inf.tank_temperature, inf.temperature)
    delivered = Table(table.x, tuple(m - masses[0] for m in masses), "delivered mass [kg]")
    return RealGasTankTestInflator(inf.name, table, inf.tank_volume, inf.temperature, mass_fractions, mix,
                                   inf.start, inf.scale, delivered=delivered)
