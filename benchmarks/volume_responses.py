"""The scene-relative volume check on the library: each cavity's response, and the same scene's in litres.

Requires: the ventsim package. Run: python benchmarks/volume_responses.py
For every scene under cases/ (not cases/results) and every cavity of it that the check judges
(:mod:`cases.scene.plausible_volume`), it prints the inflators' share of the gas (m_in/m), the vents' share
(time.end/τ), the response r = max of the two, and r / 1000 (the same volume written in litres for m³), against the
threshold MIN_RESPONSE; then the least response, and how many cavities a litres mistake would be caught in.
"""
import math
from pathlib import Path

from cases.scene import plausible_volume as pv
from cases.scene.files import load_scene
from cases.scene.plausible import _integral

ROOT = Path(__file__).resolve().parents[1]


def rows():
    for path in sorted(p for p in (ROOT / "cases").rglob("*.toml") if "results" not in p.parts):
        scene = load_scene(path)
        for cav in scene.cavity:
            if cav.fluid not in ("gas", "real_gas") or not cav.volume:
                continue
            added, area = pv._added(cav, scene.time.end, _integral), pv._vent_area(scene, cav.name)
            if added is None or area is None or not (added or area):
                continue
            held = cav.pressure * cav.volume / (pv._gas_constant(scene, cav.gas) * cav.temperature)
            vented = scene.time.end / (cav.volume / (pv.CD * area * math.sqrt(1.4 * pv.R_AIR * cav.temperature))) \
                if area else 0.0
            yield path.relative_to(ROOT / "cases"), cav.name, added / held, vented


def main() -> None:
    table = list(rows())
    print(f"| scene | cavity | m_in/m | time.end/τ | r | r in litres | caught (r/1000 < {pv.MIN_RESPONSE:g}) |")
    print("|---|---|---|---|---|---|---|")
    for scene, name, f, g in table:
        r = max(f, g)
        print(f"| {scene} | {name} | {f:.3g} | {g:.3g} | {r:.3g} | {r / 1e3:.3g} | {r / 1e3 < pv.MIN_RESPONSE} |")
    least = min(max(f, g) for *_, f, g in table)
    caught = sum(max(f, g) / 1e3 < pv.MIN_RESPONSE for *_, f, g in table)
    print(f"\nleast response {least:.3g} ({least / pv.MIN_RESPONSE:.0f} times the threshold {pv.MIN_RESPONSE:g}); "
          f"a volume in litres caught in {caught} of {len(table)} judged cavities")


if __name__ == "__main__":
    main()
