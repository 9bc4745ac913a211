"""Scene keys and checks of a real-gas cavity's vessel wall: lumped, one conducting material, or several materials
(``[[cavity.wall_materials]]``: a Type III or IV vessel's liner and composite shell; docs/realgas.md)."""
from __future__ import annotations

from dataclasses import dataclass

from cases.scene.errors import SceneError
from cases.scene.schema import key

__all__ = ["WallMaterialSpec", "check_wall", "wall_materials"]

_WALL_KEYS = ("wall_mass", "wall_heat_capacity", "wall_inner_area")
#: The keys of a wall of one material that wall_materials replaces.
_ONE_MATERIAL = ("wall_mass", "wall_heat_capacity", "wall_conductivity", "wall_thickness")


@dataclass(frozen=True, kw_only=True)
class WallMaterialSpec:
    """One material of a vessel wall, inner to outer."""

    name: str = key("what the material is ('liner', 'CFRP'); names the layer in messages")
    thickness: float = key("thickness of this material", "m", check="positive")
    conductivity: float = key("thermal conductivity", "W/(m K)", check="positive")
    density: float = key("density", "kg/m^3", check="positive")
    heat_capacity: float = key("specific heat", "J/(kg K)", check="positive")
    layers: int = key("cells across this material's thickness (1-D conduction, docs/realgas.md)", default=4,
                      bounds=(1, 200))


def check_wall(scene, c, where: str) -> None:
    """The keys a wall needs (SceneError naming the first missing or conflicting one)."""
    if c.wall_materials:
        given = [k for k in _ONE_MATERIAL if getattr(c, k)] + (["wall_layers"] if c.wall_layers != 1 else [])
        if given:
            raise SceneError(scene.path, f"{where}.{given[0]}", "give either wall_materials (each material's "
                             "thickness, conductivity, density, heat_capacity, layers) or the one-material keys "
                             f"{', '.join(_ONE_MATERIAL)}, wall_layers, not both")
        if sum(m.layers for m in c.wall_materials) > 400:
            raise SceneError(scene.path, f"{where}.wall_materials", "at most 400 layers in all")
    missing = [k for k in (_WALL_KEYS[2:] if c.wall_materials else _WALL_KEYS) if not getattr(c, k)]
    if missing or not (c.wall_inner_h or c.wall_length):
        raise SceneError(scene.path, f"{where}.{(missing or ['wall_length'])[0]}",
                         "required (> 0) for energy = 'wall' (wall_length unless wall_inner_h is given)")
    for k in ("wall_conductivity", "wall_thickness"):
        if c.wall_layers > 1 and not getattr(c, k):
            raise SceneError(scene.path, f"{where}.{k}", f"required (> 0) with wall_layers = {c.wall_layers} "
                             "(1-D conduction through the wall); or set wall_layers = 1 (lumped)")


def wall_materials(c) -> tuple:
    """The :class:`cavity.wall_materials.WallMaterial` of a cavity spec's ``wall_materials``, inner to outer."""
    from cavity.wall_materials import WallMaterial

    return tuple(WallMaterial(m.thickness, m.conductivity, m.density, m.heat_capacity, m.layers, m.name)
                 for m in c.wall_materials)
