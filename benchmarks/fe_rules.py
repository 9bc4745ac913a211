"""The blockage rules of the FE codes on a scene (default airbag_impactor, the prescribed headform; --scene
cases/airbag_impactor_dynamic.toml for the dynamic one): `ventsim compare` at one step and a sweep over the step,
with the CPU and wall time of each run. Prints the tables; writes them with the pictures into the folder given
(default out/fe_rules).

    PYTHONPATH=$PWD python benchmarks/fe_rules.py [OUT] [--scene SCENE] [--step 1e-6] [--sweep 1e-4,1e-5,1e-6]
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from cases.run.compare import parse_rules, parse_steps
from cases.run.compare_command import compare

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out", nargs="?", type=Path, default=ROOT / "out" / "fe_rules")
    p.add_argument("--scene", type=Path, default=ROOT / "cases" / "airbag_impactor.toml")
    p.add_argument("--step", type=float, default=1e-6)
    p.add_argument("--sweep", default="1e-4,1e-5,1e-6")
    args = p.parse_args()
    start, wall = time.process_time(), time.perf_counter()
    compare(args.scene, parse_rules("exact,abaqus,radioss,lsdyna_cpm,lsdyna_cpg"), args.out, step=args.step,
            sweep=parse_steps(args.sweep) if args.sweep else (),
            say=lambda text: print(f"  [{time.process_time() - start:7.1f} s CPU, {time.perf_counter() - wall:7.1f} s "
                                   f"wall] {text}", flush=True))
    print(f"total {time.process_time() - start:.1f} s CPU, {time.perf_counter() - wall:.1f} s wall")


if __name__ == "__main__":
    main()
