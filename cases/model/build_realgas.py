"""Real-gas cavities of a scene: their fluid (CoolProp HEOS), initial state, wall, and real-gas orifice laws."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from cavity.gas import GasModel
from cavity.inflator_realgas import RealGasTankTestInflator, real_gas_tank_masses
from cavity.realgas import RealFluid
from cavity.realgas_mixture import check_single_phase
from cavity.tables import Table
from cavity.realgas_cavity import RealGasCavity
from cavity.wall import Wall
from exchange.laws.orifice import OrificeLaw
from exchange.laws.realgas_orifice import RealGasOrificeLaw

from cases.scene.errors import SceneError
from cases.scene.realgas import coolprop_name
from cases.scene.walls import wall_materials

__all__ = ["real_gas_cavity", "real_gas_laws", "real_gas_tank_test"]

def _fluid(scene, gas: GasModel, y, where: str, ideal_enthalpy=None) -> RealFluid:
    """The HEOS fluid of the species with mass fractions ``y`` (ns,) > 0: pure, or a mixture of fixed composition
    (``"Nitrogen&Argon"`` with those mass fractions); CoolProp's refusals as a SceneError at ``where``."""
    present = [k for k in range(len(y)) if y[k] > 0.0]
    names = [coolprop_name(scene, gas.names[k]) for k in present]
    fractions = [float(y[k]) for k in present] if len(present) > 1 else None
    try:
        return RealFluid("&".join(names), ideal_enthalpy, scene.ambient.temperature, fractions)
    except ValueError as exc:
        raise SceneError(scene.path, where, f"CoolProp: {exc}") from None


def real_gas_cavity(scene, gas: GasModel, i: int, volume, inflators: tuple) -> RealGasCavity:
    """The :class:`RealGasCavity` of ``scene.cavity[i]`` (initial mass from HEOS density at p, T); its gas one
    species or a mixture of fixed composition (docs/realgas.md)."""
    c = scene.cavity[i]
    unit = gas.mass_fractions(c.gas, molar=c.gas_by_mole)
    k = int(np.argmax(unit))
    ideal = gas.mixture(unit)  # 1 kg of the gas as an ideal gas: the enthalpy reference
    fluid = _fluid(scene, gas, unit, f"cavity[{i}].gas", ideal.enthalpy)
    try:
        rho = fluid.density(c.pressure, c.temperature)
        if c.temperature < fluid.caution_below:  # a mixture below a component's critical temperature
            check_single_phase(fluid.name, fluid.mass_fractions, rho, c.temperature)
    except ValueError as exc:
        raise SceneError(scene.path, f"cavity[{i}].gas", f"CoolProp: {exc}") from None
    try:
        if c.energy == "wall" and not c.wall_inner_h:
            fluid.film_properties(c.pressure, c.temperature)
    except ValueError as exc:
        raise SceneError(scene.path, f"cavity[{i}].wall_inner_h", f"natural convection needs the gas's viscosity "
                         f"and conductivity; CoolProp: {exc}; give wall_inner_h instead") from None
    V0 = max(volume(0.0) + c.added_volume, c.minimum_volume)
    masses = unit * rho * V0
    wall = None
    if c.energy == "wall":
        wall = Wall(c.wall_mass, c.wall_heat_capacity, c.wall_inner_area, c.wall_outer_area or c.wall_inner_area,
                    c.wall_inner_h, c.wall_outer_h, c.wall_length, c.wall_temperature or c.temperature,
                    scene.ambient.temperature, c.wall_orientation, c.wall_jet_diameter, c.wall_layers,
                    c.wall_conductivity, c.wall_thickness, wall_materials(c))
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


def real_gas_tank_test(scene, gas: GasModel, inf, mass_fractions: tuple, mix) -> RealGasTankTestInflator:
    """A tank-test inflator whose tank holds the inflator's gas (one species or a mixture of fixed composition,
    ``mass_fractions`` over the scene's species) as a real gas (HEOS)."""
    table = inf.tank_pressure
    where = f"inflator {inf.name!r}.gas"
    fluid = _fluid(scene, gas, mass_fractions, where)
    try:
        masses = real_gas_tank_masses(fluid, inf.tank_volume, table.x, table.y, inf.tank_temperature,
                                      inf.temperature)
    except (ValueError, ArithmeticError) as exc:
        raise SceneError(scene.path, where, f"the real-gas tank: {exc}") from None
    delivered = Table(table.x, tuple(m - masses[0] for m in masses), "delivered mass [kg]")
    return RealGasTankTestInflator(inf.name, table, inf.tank_volume, inf.temperature, mass_fractions, mix,
                                   inf.start, inf.scale, delivered=delivered)
