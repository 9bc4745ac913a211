"""Scene checks of real-gas cavities and vessel walls (docs/realgas.md)."""
from __future__ import annotations

from cavity.realgas_cavity import REAL_GAS_ENERGY_MODELS
from cavity.species import BUILTIN_COOLPROP_NAMES

from cases.scene.errors import SceneError

__all__ = ["check_real_gas", "coolprop_name"]

_WALL_KEYS = ("wall_mass", "wall_heat_capacity", "wall_inner_area", "wall_outer_h")


def coolprop_name(scene, species: str) -> str:
    """The CoolProp fluid of a species of the scene ('' if it has none: user polynomial, Abaqus air)."""
    for sp in scene.species:
        if sp.name == species:
            return sp.coolprop
    if species.lower() == "air" and species != "Air":
        return ""  # the Abaqus-deck air polynomial: no equation of state
    return BUILTIN_COOLPROP_NAMES.get(species, species)


def _species(gas: dict) -> set:
    return {k for k, v in gas.items() if v > 0}


def check_real_gas(scene) -> None:
    """Every real-gas cavity: one species with a CoolProp name, an energy model it supports, the wall keys its
    wall needs, and only its own fluid flowing in (SceneError naming the key otherwise)."""
    real = {c.name: c for c in scene.cavity if c.fluid == "real_gas"}
    for i, c in enumerate(scene.cavity):
        where = f"cavity[{i}]"
        for j, inf in enumerate(c.inflator):
            if inf.tank_gas == "real_gas":
                _check_real_tank(scene, inf, f"{where}.inflator[{j}]")
        if c.fluid != "real_gas":
            if c.energy == "wall":
                raise SceneError(scene.path, f"{where}.energy", "energy = 'wall' needs fluid = 'real_gas'")
            continue
        species = [k for k, v in c.gas.items() if v > 0]
        if len(species) != 1 or not coolprop_name(scene, species[0]):
            raise SceneError(scene.path, f"{where}.gas", "a real_gas cavity holds one species with a CoolProp "
                             "name (N2, He, H2, CO2, Air, or a [[species]] with coolprop = ...)")
        if c.energy not in REAL_GAS_ENERGY_MODELS:
            raise SceneError(scene.path, f"{where}.energy", f"a real_gas cavity is one of "
                             f"{', '.join(map(repr, REAL_GAS_ENERGY_MODELS))}, got {c.energy!r}")
        if c.energy == "wall":
            missing = [k for k in _WALL_KEYS if not getattr(c, k)]
            if missing or not (c.wall_inner_h or c.wall_length):
                raise SceneError(scene.path, f"{where}.{(missing or ['wall_length'])[0]}",
                                 "required (> 0) for energy = 'wall' (wall_length unless wall_inner_h is given)")
            for k in ("wall_conductivity", "wall_thickness"):
                if c.wall_layers > 1 and not getattr(c, k):
                    raise SceneError(scene.path, f"{where}.{k}", f"required (> 0) with wall_layers = {c.wall_layers} "
                                     "(1-D conduction through the wall); or set wall_layers = 1 (lumped)")
        for j, inf in enumerate(c.inflator):
            if _species(inf.gas) != {species[0]}:
                raise SceneError(scene.path, f"{where}.inflator[{j}].gas", f"a real_gas cavity takes only its own "
                                 f"fluid {species[0]!r}")
    for j, e in enumerate(scene.exchange):
        for into, other in ((e.to, e.from_), (e.from_, e.to)):
            if into not in real or (other == "ambient" and not e.two_way):
                continue
            gas = scene.ambient.gas if other == "ambient" else next(c.gas for c in scene.cavity if c.name == other)
            if _species(gas) != _species(real[into].gas):
                raise SceneError(scene.path, f"exchange[{j}]", f"gas flowing into the real_gas cavity {into!r} "
                                 f"must be its own fluid (the {other} gas differs)")


def _check_real_tank(scene, inf, where: str) -> None:
    gas = sorted(_species(inf.gas))
    if inf.type != "tank_test":
        raise SceneError(scene.path, f"{where}.tank_gas", "only a tank_test inflator has a real-gas tank")
    if len(gas) != 1 or not coolprop_name(scene, gas[0]):
        raise SceneError(scene.path, f"{where}.gas", "a real-gas tank holds one species with a CoolProp name")
    if not inf.tank_temperature:
        raise SceneError(scene.path, f"{where}.tank_temperature", "required (> 0) for tank_gas = 'real_gas'")
