"""Scene checks of real-gas cavities and vessel walls (docs/realgas.md)."""
from __future__ import annotations

from cavity.realgas_cavity import REAL_GAS_ENERGY_MODELS
from cavity.species import coolprop_fluid_name, coolprop_fluid_names

from cases.scene.errors import SceneError
from cases.scene.schema import suggest
from cases.scene.walls import check_wall

__all__ = ["check_real_gas", "coolprop_name"]


def coolprop_name(scene, species: str) -> str:
    """The CoolProp fluid of a species of the scene ('' if it has none: user polynomial, Abaqus air)."""
    for sp in scene.species:
        if sp.name == species:
            return sp.coolprop
    if species.lower() == "air" and species != "Air":
        return ""  # the Abaqus-deck air polynomial: no equation of state
    return coolprop_fluid_name(species)


def _species(gas: dict) -> set:
    return {k for k, v in gas.items() if v > 0}


def _check_gas(scene, gas: dict, where: str, what: str) -> list:
    """The CoolProp names of a real gas's species (one, or a mixture of fixed composition); SceneError at
    ``where`` for a species without one, a name CoolProp does not know (with suggestions) or pseudo-pure Air in
    a mixture."""
    species = sorted(_species(gas))
    names = [coolprop_name(scene, sp) for sp in species]
    for sp, name in zip(species, names):
        if not name:
            raise SceneError(scene.path, f"{where}.{sp}", f"{what} holds species with a CoolProp name (N2, He, H2, "
                             "CO2, Ar, O2, Air, or a [[species]] with coolprop = ...)")
    if len(names) > 1:
        known = coolprop_fluid_names()
        for sp, name in zip(species, names):
            if name not in known:
                raise SceneError(scene.path, f"{where}.{sp}", f"CoolProp has no fluid {name!r}{suggest(name, known)}")
            if name.lower() == "air":
                raise SceneError(scene.path, f"{where}.{sp}", "CoolProp's Air is pseudo-pure and cannot be part of "
                                 "a mixture: give air as its components (N2, O2, Ar)")
    return names


def _mass_basis(scene, gas: dict, by_mole: bool) -> dict:
    """{species: mass fraction} of a real gas (CoolProp molar masses for a molar composition)."""
    import CoolProp.CoolProp as CP

    w = {k: v * (CP.PropsSI("M", coolprop_name(scene, k)) if by_mole else 1.0) for k, v in gas.items() if v > 0}
    total = sum(w.values())
    return {k: v / total for k, v in w.items()}


def _same_gas(scene, a: tuple, b: tuple) -> bool:
    """Two (gas, gas_by_mole) compositions of real-gas species are the same (mass fractions within 1e-9)."""
    if _species(a[0]) != _species(b[0]):
        return False
    if len(_species(a[0])) == 1:
        return True
    ya, yb = _mass_basis(scene, *a), _mass_basis(scene, *b)
    return all(abs(ya[k] - yb[k]) <= 1e-9 for k in ya)


def check_real_gas(scene) -> None:
    """Every real-gas cavity: one species or a mixture of species with CoolProp names, an energy model it
    supports, the wall keys its wall needs, and only its own gas (the same composition) flowing in (SceneError
    naming the key otherwise)."""
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
        _check_gas(scene, c.gas, f"{where}.gas", "a real_gas cavity")
        if c.energy not in REAL_GAS_ENERGY_MODELS:
            raise SceneError(scene.path, f"{where}.energy", f"a real_gas cavity is one of "
                             f"{', '.join(map(repr, REAL_GAS_ENERGY_MODELS))}, got {c.energy!r}")
        if c.energy == "wall":
            check_wall(scene, c, where)
        for j, inf in enumerate(c.inflator):
            if not _same_gas(scene, (inf.gas, inf.gas_by_mole), (c.gas, c.gas_by_mole)):
                raise SceneError(scene.path, f"{where}.inflator[{j}].gas", f"a real_gas cavity takes only its own "
                                 f"gas {c.gas!r} (the same composition)")
    for j, e in enumerate(scene.exchange):
        for into, other in ((e.to, e.from_), (e.from_, e.to)):
            if into not in real or (other == "ambient" and not e.two_way):
                continue
            src = scene.ambient if other == "ambient" else next(c for c in scene.cavity if c.name == other)
            dst = real[into]
            if not _same_gas(scene, (src.gas, src.gas_by_mole), (dst.gas, dst.gas_by_mole)):
                raise SceneError(scene.path, f"exchange[{j}]", f"gas flowing into the real_gas cavity {into!r} "
                                 f"must be its own gas, the same composition (the {other} gas differs)")


def _check_real_tank(scene, inf, where: str) -> None:
    if inf.type != "tank_test":
        raise SceneError(scene.path, f"{where}.tank_gas", "only a tank_test inflator has a real-gas tank")
    _check_gas(scene, inf.gas, f"{where}.gas", "a real-gas tank")
    if not inf.tank_temperature:
        raise SceneError(scene.path, f"{where}.tank_temperature", "required (> 0) for tank_gas = 'real_gas'")
