"""Run HydDown on one set-up file and print its history as JSON (run with HydDown's own interpreter).

Requires: hyddown (a separate venv: ``python3 -m venv /work/venv-hyddown && /work/venv-hyddown/bin/pip install
hyddown``). Usage: ``python _hyddown_run.py SETUP.yml [REPEATS]`` -> {"wall time [s]", "cpu time [s]" (best of the repeats), "time", "p",
"T", "T_wall" (the vessel's mean wall), "T_wall_inner", "T_wall_outer" (its surfaces)}.
"""
import json
import sys
import time

import yaml
from hyddown import HydDown

setup = yaml.safe_load(open(sys.argv[1]))
setup.pop("validation", None)
# `calculation.eta` (the Woodfield filling's set-up) is a key of older HydDown versions that 0.50's input check
# refuses and its model does not read: dropped, so that 0.50 runs the set-up as it models it
setup.get("calculation", {}).pop("eta", None)
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 3
wall = cpu = float("inf")
for _ in range(repeats):  # the first run also loads CoolProp's fluid: the best of the repeats is reported
    start, start_cpu = time.perf_counter(), time.process_time()
    hd = HydDown(setup)
    hd.run()
    wall, cpu = min(wall, time.perf_counter() - start), min(cpu, time.process_time() - start_cpu)
print(json.dumps({"wall time [s]": wall, "cpu time [s]": cpu, "time": list(map(float, hd.time_array)), "p": list(map(float, hd.P)),
                  "T": list(map(float, hd.T_fluid)), "T_wall": list(map(float, hd.T_vessel)),
                  "T_wall_inner": list(map(float, hd.T_inner_wall)),
                  "T_wall_outer": list(map(float, hd.T_outer_wall))}))
