"""Wall time of every case of the library: load, build (geometry precomputation), integrate; rendering excluded.

Requires: the ventsim package. Run: python benchmarks/scenes.py [--repeat N]
Prints the median over N runs (after one warm-up run that pays for imports, numba compilation and CoolProp).
"""
import argparse
import statistics
import time

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene


def timed(name):
    t0 = time.perf_counter()
    scene = load_scene(HERE / CASES[name])
    t1 = time.perf_counter()
    model = build_model(scene)
    t2 = time.perf_counter()
    results = run(model)
    t3 = time.perf_counter()
    return t1 - t0, t2 - t1, t3 - t2, results.summary["solver"]


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"{'case':<26} {'load [s]':>9} {'build [s]':>10} {'run [s]':>9} {'total [s]':>10} {'steps':>7} "
          f"{'RHS calls':>10} {'events':>7}")
    for name in CASES:
        timed(name)  # warm-up
        runs = [timed(name) for _ in range(args.repeat)]
        load, build, integ = (statistics.median(r[i] for r in runs) for i in range(3))
        st = runs[-1][3]
        print(f"{name:<26} {load:>9.3f} {build:>10.3f} {integ:>9.3f} {load + build + integ:>10.3f} "
              f"{st['steps']:>7} {st['rhs_calls']:>10} {st['events']:>7}")


if __name__ == "__main__":
    main()
