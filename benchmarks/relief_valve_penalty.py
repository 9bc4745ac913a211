"""The relief valve (cases/relief_valve.toml) on a 1e12 Pa/m penalty seat instead of hard contact, without damping
and with critical damping fractions 0.03 and 0.3: reseats, peak CPRESS, largest body speed, first opening against
the preload's prediction and wall time (the table in docs/contact.md). About 50 s.

    python benchmarks/relief_valve_penalty.py
"""
import copy
import time
import tomllib
from pathlib import Path

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import scene_from_dict

SCENE = Path(__file__).resolve().parents[1] / "cases" / "relief_valve.toml"
VARIANTS = [("no damping", {"damping": "none"}), ("critical fraction 0.03", {"damping": "critical_fraction"}),
            ("critical fraction 0.3", {"damping": "critical_fraction", "critical_fraction": 0.3})]


def main() -> None:
    base = tomllib.loads(SCENE.read_text())
    print("| penalty 1e12 Pa/m | reseats | peak CPRESS | largest body speed | first opening vs p_open | wall |")
    print("|---|---|---|---|---|---|")
    for label, damping in VARIANTS:
        data = copy.deepcopy(base)
        data["contact"] = [{"name": "seat", "body": "poppet", "seat": "seat_leak", "pressure_overclosure": "linear",
                            "stiffness": 1e12, **damping}]
        t0 = time.perf_counter()
        s = run(build_model(scene_from_dict(data, SCENE))).summary["contact"]["seat"]
        wall = time.perf_counter() - t0
        first = s["opening pressures [Pa]"][0] / s["opening pressure predicted [Pa]"] - 1.0
        print(f"| {label} | {s['reseats']} | {s['peak CPRESS [Pa]'] / 1e6:.2f} MPa | "
              f"{s['peak body speed [m/s]']:.3f} m/s | {first:+.1e} | {wall:.1f} s |", flush=True)


if __name__ == "__main__":
    main()
