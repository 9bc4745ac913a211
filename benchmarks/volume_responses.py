"""The scene-relative volume check on the library: each cavity's response, and the same scene's in litres.

Requires: the ventsim package. Run: python benchmarks/volume_responses.py
For every scene under cases/ (not cases/results) and every cavity of it given by its volume whose flows can be
bounded (:mod:`cases.scene.plausible_volume`), it prints the inflators' share of the gas (m_in/m), the vents' share
(t_ref/τ), the response r = max of the two, and r / 1000 (the same volume written in litres for m³), against the
thresholds; then the least response over its threshold, how many cavities a litres mistake would be caught in, and
the false alarms of the same scenes run for 1 % and 0.1 % of their time.end (previews).
"""
import math
from pathlib import Path

from cases.scene import plausible_volume as pv
from cases.scene.files import load_scene
from cases.scene.plausible import _integral

ROOT = Path(__file__).resolve().parents[1]


def rows(end_factor: float = 1.0):
    """(scene, cavity, inflated by tables, m_in/m, t_ref/τ) of every judged cavity, time.end times ``end_factor``."""
    for path in sorted(p for p in (ROOT / "cases").rglob("*.toml") if "results" not in p.parts):
        scene = load_scene(path)
        end = scene.time.end * end_factor
        for cav in scene.cavity:
            if cav.fluid not in ("gas", "real_gas") or not cav.volume:
                continue
            flow, area = pv.inflow(cav, end, _integral), pv.vent_area(scene, cav.name)
            if flow is None or area is None or not (flow[0] or area):
                continue
            added, t_ref, tables = flow
            held = cav.pressure * cav.volume / (pv.gas_constant(scene, cav.gas) * cav.temperature)
            tau = cav.volume / (pv.CD * area * math.sqrt(1.4 * pv.R_AIR * cav.temperature)) if area else math.inf
            yield path.relative_to(ROOT / "cases"), cav.name, cav.volume, tables, added / held, t_ref / tau


def judged(volume: float, tables: bool) -> bool:
    return tables or volume >= pv.MIN_VENTED_VOLUME


def least(tables: bool) -> float:
    return pv.MIN_RESPONSE if tables else pv.MIN_UNTIMED_RESPONSE


def main() -> None:
    table = list(rows())
    print("| scene | cavity | inflator tables | m_in/m | t_ref/τ | r | r in litres | judged | caught in litres |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, name, v, tables, f, g in table:
        r, ok = max(f, g), judged(v, tables)
        print(f"| {scene} | {name} | {tables} | {f:.3g} | {g:.3g} | {r:.3g} | {r / 1e3:.3g} | {ok} | "
              f"{judged(v * 1e3, tables) and r / 1e3 < least(tables)} |")
    worst = min(max(f, g) / least(t) for _, _, v, t, f, g in table if judged(v, t))
    caught = sum(judged(v * 1e3, t) and max(f, g) / 1e3 < least(t) for _, _, v, t, f, g in table)
    print(f"\nleast response over its threshold, as given: {worst:.3g}; a volume in litres caught in {caught} of "
          f"{len(table)} cavities")
    for factor in (0.01, 0.001):
        short = [(v, t, max(f, g)) for _, _, v, t, f, g in rows(factor)]
        alarms = sum(judged(v, t) and r < least(t) for v, t, r in short)
        print(f"time.end x {factor:g} (a preview): {alarms} false alarms of {len(short)}")


if __name__ == "__main__":
    main()
