"""Same-run speed of the compiled path against the Python path on the scene kinds moved to it: leakage tables,
prescribed fluxes, bulk viscosity, Cd tables, DELTA LEAKAGE AREA (also on an area that follows the dynamic body),
tank-test, pressure-and-mass and dual-pressure inflators, hydraulic cavities, pop vents on blocked areas.

Requires: the ventsim package and its tests/ folder (the scenes are tests.test_compiled_laws's,
tests.test_compiled_inflators's and tests.test_compiled_blocked_activation's). Run:
python benchmarks/compiled_laws.py [--repeat N]. Prints, per scene, the best of N warm solves (``integrate``
alone, numba compiled beforehand) on each path, their ratio, steps and the largest relative pressure difference
between the two runs. About 60 s.
"""
import argparse
import math
import tempfile
import time
import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.scene.files import load_scene, scene_from_dict
from cavity.integration import integrate
from tests.test_compiled_blocked_activation import popped_model
from tests.test_compiled_inflators import orifice_model
from tests.test_compiled_laws import law_model, oil_model, tank_test_model
from tests.test_exchange_scenes import fill_with_pop


def airbag_delta(folder):
    with open(HERE / CASES["airbag_impactor"], "rb") as f:
        data = tomllib.load(f)
    data["exchange"][0].update(open_time=0.02, delta_area=True)
    return build_model(scene_from_dict(data, HERE / CASES["airbag_impactor"]))


def pop_delta(folder):
    data = fill_with_pop(5.0e4, 0.004)
    data["exchange"][0]["delta_area"] = True
    return build_model(scene_from_dict(data, folder / "scene.toml"))


def leaking_oil(folder):
    (folder / "leak.csv").write_text("dp,q\n0,0\n1e6,1e-3\n1e8,5e-3\n")
    return oil_model(folder, {"name": "leak", "from": "seal", "area": 1e-5, "law": "volume_rate_leakage",
                              "leakage_table": "leak.csv"})


SCENES = {"mass-rate leakage table": lambda d: law_model(d, "mass_rate_leakage"),
          "volume-rate leakage, two tanks": lambda d: law_model(d, "volume_rate_leakage", to_cavity=True),
          "mass flux with amplitude": lambda d: law_model(d, "mass_flux", to_cavity=True),
          "volume flux": lambda d: law_model(d, "volume_flux"),
          "bulk viscosity": lambda d: law_model(d, "bulk_viscosity"),
          "orifice, Cd(p) table": lambda d: law_model(d, "orifice Cd(p)"),
          "fabric, Cd(t) table, two-way": lambda d: law_model(d, "fabric Cd(t)", two_way=True),
          "delta area by time (airbag_impactor)": airbag_delta,
          "delta area at a pop": pop_delta,
          "tank-test inflator": tank_test_model,
          "pressure-and-mass inflator": lambda d: orifice_model(d, "pressure_mass"),
          "dual-pressure inflator": lambda d: orifice_model(d, "dual_pressure"),
          "pop on blocked vent (airbag_impactor)": lambda d: popped_model("airbag_impactor", 8.0e4, 0.0),
          "delta area, dynamic body (22 ms)": lambda d: popped_model("airbag_impactor_dynamic", 0.0, 0.0,
                                                                      open_time=0.022, delta_area=True),
          "hydraulic, leaking": leaking_oil,
          "deck_hydraulic_two_cavity": lambda d: build_model(load_scene(HERE / CASES["deck_hydraulic_two_cavity"]))}


def best(model, compiled, repeat):
    net, out = model.network, []
    for _ in range(repeat + 1):  # the first run warms up
        t0 = time.perf_counter()
        traj = integrate(net, net.initial_state(), 0.0, model.scene.time.end, replace(model.options, compiled=compiled))
        out.append(time.perf_counter() - t0)
    return min(out[1:]), traj


def pressures(model, traj, times):
    net, rows = model.network, []
    for t, y in zip(times, traj.sample(times)):
        net.restore(traj.mode_at(t))
        rows.append([s.pressure for s in net.states(t, y)])
    return np.array(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    print(f"{'scene':<38} {'python [ms]':>11} {'compiled [ms]':>13} {'ratio':>6} {'steps':>9} {'max dp/p':>9}")
    for name, make in SCENES.items():
        with tempfile.TemporaryDirectory() as tmp:
            model = make(Path(tmp))
            slow, slow_traj = best(model, False, args.repeat)
            fast, fast_traj = best(model, True, args.repeat)
            times = np.asarray(model.output_times)
            dp = np.max(np.abs(pressures(model, fast_traj, times) / pressures(model, slow_traj, times) - 1.0))
        steps = f"{slow_traj.stats['steps']}/{fast_traj.stats['steps']}"
        print(f"{name:<38} {1e3 * slow:>11.2f} {1e3 * fast:>13.3f} {slow / fast:>6.0f} {steps:>9} "
              f"{dp if math.isfinite(dp) else float('nan'):>9.1e}")


if __name__ == "__main__":
    main()
