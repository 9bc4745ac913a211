"""Scene keys that replay a run the way a finite-element code would: the [blockage] table (which code's blockage
rule, its explicit time step and lag) and the [fe_run] table (the units of an FE run's files and its control-volume
pressure to compare with). ``docs/fe_rules.md`` describes the rules; :mod:`blockage.fe_rules` holds them.
"""
from __future__ import annotations

from dataclasses import dataclass

from blockage.fe_rules import RULES, SIDES

from cases.scene.errors import SceneError
from cases.scene.schema import key, unknown_name

__all__ = ["BlockageSpec", "FeRunSpec", "check_blockage", "part_ids", "FABRIC_LAWS", "MAX_SAMPLES", "UNIT_SYSTEMS"]

#: Flow laws through a porous fabric: their blocked part leaks `blocked_leak_fraction` (ELA, AC') when it is given.
FABRIC_LAWS = ("fabric_leakage", "graefe", "mass_rate_leakage", "volume_rate_leakage")
#: Most explicit time steps t_k a run may sample its flags at (time.end / step).
MAX_SAMPLES = 10 ** 8
#: The unit systems of FE result files (as `ventsim run --units` for decks).
UNIT_SYSTEMS = ("SI", "mm-t-s", "mm-kg-ms")


@dataclass(frozen=True, kw_only=True)
class BlockageSpec:
    """Which blockage rule the scene's blocked exchanges follow (docs/fe_rules.md)."""

    rule: str = key("'exact' (ventsim: every contact and release at its own instant), or an FE code's rule: "
                    "'abaqus', 'radioss', 'lsdyna_cpm' (*AIRBAG_PARTICLE BLOCK), 'lsdyna_cpg' (*AIRBAG_CPG, whole "
                    "elements)", default="exact", choices=RULES)
    step: float = key("FE rules: the explicit time step Δt; the flags are evaluated at t_k = k·Δt only", "s",
                      default=0.0, check="nonnegative")
    lag_cycles: int = key("FE rules: the flags of cycle k − n are used at cycle k; −1: the rule's own (radioss 1, "
                          "the others 0)", default=-1, bounds=(-1, 10 ** 6))
    contact_side: str = key("FE rules: what is flagged: the leakage nodes in contact ('secondary'), the nodes of "
                            "the leakage faces a blocker node touches ('main'), or 'both'; 'rule': the rule's own "
                            "(radioss and lsdyna_cpg both, the others secondary)", default="rule",
                            choices=("rule",) + SIDES)
    block: int = key("lsdyna_cpm, lsdyna_cpg: LS-DYNA BLOCK = 10·M + N; N = 0 none, 1 all, 2 not external vents, 3 "
                     "not internal vents, 4 no vents (orifice exchanges are vents)", default=1, bounds=(0, 19))
    sdfblk: float = key("lsdyna_cpm: SDFBLK, the scale-down factor of the blockage, (0, 1]", default=1.0,
                        check="fraction")
    blocked_leak_fraction: float = key("fraction of blocked fabric that still leaks (LS-DYNA ELA, Radioss AC') "
                                       "for the fabric-law exchanges; omitted: each exchange's permeability",
                                       default=None, check="fraction")
    strict: bool = key("true: a run whose contact intervals are not all certified (a rotating or deforming "
                        "blocker hovering near the tolerance) stops with an error instead of a warning; also "
                        "`ventsim run --strict`", default=False)


@dataclass(frozen=True, kw_only=True)
class FeRunSpec:
    """The finite-element run a scene replays: the units of its files and its control-volume pressure."""

    units: str = key("unit system of the FE run's result files (d3plot, abstat): SI, mm-t-s or mm-kg-ms",
                     default="SI", choices=UNIT_SYSTEMS)
    abstat: str = key("the FE run's control-volume history: a binout file or an ASCII abstat file; its pressure "
                      "is drawn over ventsim's in history.png and `ventsim compare`", default="")
    airbags: dict = key("{cavity = airbag number} of the abstat file (1-based); omitted: the cavities in order",
                        default={})


def check_blockage(scene, path) -> None:
    """Cross-key checks of [blockage] and [fe_run]."""
    b, where = scene.blockage, "blockage"
    if b.rule == "exact":
        if b.step:
            raise SceneError(path, f"{where}.step", "the exact rule has no time step (it times every contact and "
                                                    "release exactly); choose an FE rule or drop the step")
    else:
        if not b.step > 0:
            raise SceneError(path, f"{where}.step", f"rule {b.rule!r} samples its flags at t_k = k·step: give the "
                                                    "explicit time step [s] (e.g. 1e-6)")
        if scene.time.end / b.step > MAX_SAMPLES:
            raise SceneError(path, f"{where}.step", f"time.end / step = {scene.time.end / b.step:.3g} samples, more "
                                                    f"than {MAX_SAMPLES:g}: give a larger step")
    if not b.sdfblk > 0:
        raise SceneError(path, f"{where}.sdfblk", f"expected a factor in (0, 1], got {b.sdfblk!r}")
    _check_parts(scene, path)
    if scene.fe_run.abstat and not (scene.base / scene.fe_run.abstat).is_file():
        raise SceneError(path, "fe_run.abstat", f"{scene.fe_run.abstat!r}: file not found")
    names = [c.name for c in scene.cavity]
    for name, number in scene.fe_run.airbags.items():
        if name not in names:
            raise unknown_name(path, f"fe_run.airbags.{name}", "cavity", name, names)
        if isinstance(number, bool) or not isinstance(number, int) or number < 1:
            raise SceneError(path, f"fe_run.airbags.{name}", f"expected an airbag number >= 1, got {number!r}")


def part_ids(path):
    """The converter of a `parts` key: a list of part ids (whole numbers >= 1) as a tuple."""
    def convert(value, where) -> tuple:
        if not isinstance(value, (list, tuple)) or not value or not all(
                isinstance(x, int) and not isinstance(x, bool) and x >= 1 for x in value):
            raise SceneError(path, where, f"expected a list of part ids (whole numbers >= 1), got {value!r}")
        return tuple(int(x) for x in value)
    return convert


def _check_parts(scene, path) -> None:
    """`parts` names the parts of an LS-DYNA d3plot series: it needs one."""
    from cases.model.mesh_series_d3plot import is_d3plot

    for kind, keys in (("cavity", ("mesh_series",)), ("body", ("mesh_series", "vertex_trajectory")),
                       ("exchange", ("leakage_surface",))):
        for i, item in enumerate(getattr(scene, kind)):
            if item.parts and not any(is_d3plot(getattr(item, k)) for k in keys if getattr(item, k)):
                raise SceneError(path, f"{kind}[{i}].parts", f"parts apply to an LS-DYNA d3plot given as "
                                                             f"{' or '.join(keys)} (a file named d3plot or *.d3plot)")
