"""Seat-contact scenes on the compiled DOP853 path against the Python (solve_ivp) path, same run, same rtol.

Requires: the ventsim package (numba). Run: python benchmarks/seat_compiled.py [--repeat N] [--rtol R]
Prints per relief valve the median solver wall time of each path (``summary.json`` solver "wall time [s]"), their
ratio (Python / compiled), the whole run (build excluded, outputs included), RHS calls, events, and the largest
history difference over each column's peak. One warm-up run per path first (imports, numba compilation).
"""
import argparse
import dataclasses
import statistics
import time

import numpy as np

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene

SCENES = ("relief_valve", "relief_valve_undamped")


def timed(scene, compiled: bool, rtol):
    model = build_model(scene)
    o = model.options
    if rtol is not None:
        o = dataclasses.replace(o, rtol=rtol, atol=o.atol * rtol / o.rtol)
    model.options = dataclasses.replace(o, compiled=compiled)
    t0 = time.perf_counter()
    results = run(model)
    return results.summary["solver"]["wall time [s]"], time.perf_counter() - t0, results


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rtol", type=float, default=None, help="default: the case's own")
    args = ap.parse_args()
    print(f"{'case':<24} {'path':<9} {'solve [s]':>10} {'run [s]':>9} {'RHS calls':>10} {'events':>7} "
          f"{'ratio':>7} {'max diff / peak':>16}")
    for name in SCENES:
        scene = load_scene(HERE / CASES[name])
        rows = {}
        for compiled in (True, False):
            timed(scene, compiled, args.rtol)  # warm-up
            runs = [timed(scene, compiled, args.rtol) for _ in range(args.repeat)]
            rows[compiled] = (statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs),
                              runs[-1][2])
        fast, slow = rows[True][2], rows[False][2]
        diff = np.abs(fast.history - slow.history).max(axis=0) / np.maximum(np.abs(slow.history).max(axis=0),
                                                                             1e-300)
        for compiled in (True, False):
            solve, whole, res = rows[compiled]
            st = res.summary["solver"]
            ratio = f"{rows[False][0] / rows[True][0]:>7.1f}" if compiled else f"{'':>7}"
            extra = f"{diff.max():>16.2e}" if compiled else ""
            print(f"{name:<24} {st['path']:<9} {solve:>10.4f} {whole:>9.3f} {st['rhs_calls']:>10} {st['events']:>7} "
                  f"{ratio} {extra}")


if __name__ == "__main__":
    main()
