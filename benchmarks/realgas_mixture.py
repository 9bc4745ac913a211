"""Cost of a real-gas mixture cavity against the pure fluid: the N2 150 bar vessel discharge with other gases.

The scene is cases/validation/n2_150bar_discharge.toml (real gas, lumped wall with natural convection, real-gas
orifice, LSODA at rtol 1e-4) with its gas replaced: pure N2, CoolProp's pseudo-pure Air, and the mixtures air as
N2/O2/Ar (0.7812/0.2096/0.0092), N2/Ar 0.8/0.2, a hybrid inflator's Ar/He 0.9/0.1 and N2/CO2 0.9/0.1 (all by
mole). For each: CPU time of build + run (best of 5, after one warm-up run that loads CoolProp's fluids),
right-hand-side calls, that CPU time per right-hand side (build and history rows included), and the end pressure and lowest gas temperature.

Requires: numpy, CoolProp.

Usage::

    python benchmarks/realgas_mixture.py
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from cases.model.build import build_model  # noqa: E402
from cases.run.runner import run  # noqa: E402
from cases.scene.files import load_scene  # noqa: E402

SCENE = ROOT / "cases" / "validation" / "n2_150bar_discharge.toml"
GASES = {
    "N2 (pure)": "{N2 = 1.0}",
    "Air (pseudo-pure)": "{Air = 1.0}",
    "N2/O2/Ar air": "{N2 = 0.7812, O2 = 0.2096, Ar = 0.0092}",
    "N2/Ar 0.8/0.2": "{N2 = 0.8, Ar = 0.2}",
    "Ar/He 0.9/0.1": "{Ar = 0.9, He = 0.1}",
    "N2/CO2 0.9/0.1": "{N2 = 0.9, CO2 = 0.1}",
}


def measure(gas: str, folder: Path, repeats: int = 5) -> dict:
    """Best CPU time [s] of build + run of the scene with ``gas``, and what the run did."""
    text = SCENE.read_text().replace("gas = {N2 = 1.0}", f"gas = {gas}\ngas_by_mole = true")
    path = folder / "scene.toml"
    path.write_text(text)
    scene = load_scene(path)
    r = run(build_model(scene))
    best = float("inf")
    for _ in range(repeats):
        t = time.process_time()
        r = run(build_model(scene))
        best = min(best, time.process_time() - t)
    return {"cpu": best, "calls": r.summary["solver"]["rhs_calls"], "p_end": r.column("vessel.pressure")[-1],
            "T_min": r.column("vessel.temperature").min()}


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "data").mkdir()
        print(f"{'gas':20s} {'CPU [ms]':>9s} {'RHS':>5s} {'CPU/RHS [µs]':>12s} {'p end [bar]':>11s} {'T min [K]':>9s}")
        for label, gas in GASES.items():
            m = measure(gas, folder)
            per = 1e6 * m["cpu"] / m["calls"] if m["calls"] else float("nan")
            print(f"{label:20s} {1e3 * m['cpu']:9.1f} {m['calls']:5d} {per:12.1f} {m['p_end'] / 1e5:11.3f} "
                  f"{m['T_min']:9.2f}")


if __name__ == "__main__":
    main()
