"""This engine against a previous one, on every library case, in the same run: solve time, RHS calls and the largest
difference between their histories.

The previous engine (``--baseline``, default 361c3af, the first engine before its layout was named and its kernels
stopped being inlined) is exported with ``git archive`` into a folder kept between runs
(``~/.cache/ventsim-bench/<rev>``, so its numba cache is compiled once) and run in a child process. The two are
measured in alternating rounds (``--rounds``): each round times every case ``--repeat`` times in both, after a
warm-up, and the best time of all rounds is kept, so a busy spell of the machine falls on both.

Timed is ``cases.run.runner.run`` (the integration and the read-back: history, peaks, summary; the model is built
once, outside). "difference": the largest |a − b| over each history column shared by both, divided by that
column's largest magnitude.

Since the wrapped volume of a convex body in translation became exact (a piecewise cubic on the contact set's
breakpoints), airbag_impactor and airbag_impactor_dynamic solve a different problem than the previous engine did;
the rows marked "(sampled wrap)" build them again with the previous representation (the 401-sample spline, which
rotating, deforming or several bodies still use) and compare the same problem.

``--ladder``: wall time against error on the rtol ladder 1e-4 … 1e-10 (absolute tolerances scaled with rtol), the
error against this engine's run at rtol 1e-12 with steps of at most t_end/4000; errors must not grow as rtol falls.

Run: python benchmarks/engine.py [--rounds 3] [--repeat 3] [--cases NAME ...] [--ladder] [--baseline REV]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from cases.model.build import build_model  # noqa: E402
from cases.run.library import CASES, HERE  # noqa: E402
from cases.run.runner import run  # noqa: E402
from cases.scene.files import load_scene  # noqa: E402

BASELINE = "361c3af"
LADDER = (1e-4, 1e-6, 1e-8, 1e-10)

#: run in the previous engine's tree: per case its best wall time, RHS calls and history (columns, rows), as JSON
CHILD = r"""
import json, sys, time
from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene
repeat, out = int(sys.argv[1]), {}
for name in [n for n in sys.argv[2:] if n in CASES]:  # a case newer than the tree: not there
    model = build_model(load_scene(HERE / CASES[name]))
    r, best = run(model), float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter(); r = run(model); best = min(best, time.perf_counter() - t0)
    out[name] = {"wall": best, "rhs": r.summary["solver"]["rhs_calls"], "columns": list(r.columns),
                 "history": r.history.tolist()}
print(json.dumps(out))
"""


def baseline_tree(rev: str) -> Path:
    """The previous engine's package at ``rev``, exported once and kept (its numba cache with it)."""
    folder = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "ventsim-bench" / rev
    if not (folder / "pyproject.toml").is_file():
        folder.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", "--format=tar", rev], capture_output=True,
                                 check=True).stdout
        with tempfile.TemporaryFile() as f:
            f.write(archive)
            f.seek(0)
            with tarfile.open(fileobj=f) as tar:
                tar.extractall(folder, filter="data")
    return folder


def previous(tree: Path, names, repeat: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree))
    out = subprocess.run([sys.executable, "-c", CHILD, str(repeat), *names], cwd=tree, env=env, capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def best(model, repeat: int, **options) -> tuple:
    m = replace(model, options=replace(model.options, **options)) if options else model
    results = run(m)  # warm-up
    wall = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        results = run(m)
        wall.append(time.perf_counter() - t0)
    return min(wall), results


def difference(columns, history, other_columns, other) -> float:
    """max over the shared columns of max|a − b| / max|b|."""
    a, b = np.asarray(history, float), np.asarray(other, float)
    if a.shape[0] != b.shape[0]:
        return float("inf")
    worst = 0.0
    for i, name in enumerate(columns):
        if name in other_columns:
            y = b[:, other_columns.index(name)]
            scale = np.max(np.abs(y))
            if scale > 0.0:
                worst = max(worst, float(np.max(np.abs(a[:, i] - y)) / scale))
    return worst


#: cases whose wrapped volume is exact now; also compared built with the sampled spline (the previous problem)
WRAPPED = ("airbag_impactor", "airbag_impactor_dynamic")
SAMPLED = " (sampled wrap)"


def sampled_wrap_model(name: str):
    """The case's model with the wrapped volume sampled on a grid and splined, as the previous engine had it."""
    from cases.model import wrapped_volume

    wrapped_volume.EXACT_TRANSLATION = False
    try:
        return build_model(load_scene(HERE / CASES[name]))
    finally:
        wrapped_volume.EXACT_TRANSLATION = True


def compare(names, rounds: int, repeat: int, rev: str) -> None:
    tree = baseline_tree(rev)
    models = {name: build_model(load_scene(HERE / CASES[name])) for name in names}
    models.update({name + SAMPLED: sampled_wrap_model(name) for name in names if name in WRAPPED})
    mine, theirs = {}, {}
    for _ in range(rounds):
        for name, record in previous(tree, names, repeat).items():
            if name not in theirs or record["wall"] < theirs[name]["wall"]:
                theirs[name] = record
        for name, model in models.items():
            wall, res = best(model, repeat)
            if name not in mine or wall < mine[name][0]:
                mine[name] = (wall, res)
    print(f"this engine against {rev} (best of {rounds} alternating rounds x {repeat})")
    print(f"{'case':<40} {'this [ms]':>10} {rev + ' [ms]':>13} {'ratio':>6} {'RHS this/prev':>16} {'difference':>10}")
    for name in models:
        wall, res = mine[name]
        prev = theirs.get(name.removesuffix(SAMPLED))
        if prev is None:
            print(f"{name:<40} {1e3 * wall:>10.2f} {'(not in ' + rev + ')':>13}")
            continue
        diff = difference(res.columns, res.history, prev["columns"], prev["history"])
        rhs = f"{res.summary['solver']['rhs_calls']}/{prev['rhs']}"
        print(f"{name:<40} {1e3 * wall:>10.2f} {1e3 * prev['wall']:>13.2f} {wall / prev['wall']:>6.2f} {rhs:>16} "
              f"{diff:>10.1e}")


def ladder(names, repeat: int) -> None:
    """Wall time [s] and error against an rtol-1e-12 reference, per case and rtol, on both integrators."""
    print(f"{'case':<26} {'rtol':>7} {'compiled [s]':>12} {'error':>9} {'scipy DOP853 [s]':>16} {'error':>9}")
    for name in names:
        model = build_model(load_scene(HERE / CASES[name]))
        o = model.options  # absolute tolerances scale with rtol, as a scene's defaults do (atol = rtol/100 × scale)
        at = lambda rtol: replace(model, options=replace(o, rtol=rtol, atol=o.atol * rtol / o.rtol))  # noqa: E731
        reference = run(replace(model, options=replace(at(1e-12).options, max_step=model.scene.time.end / 4000)))
        cols = list(reference.columns)
        for rtol in LADDER:
            fast, fres = best(at(rtol), repeat)
            slow, sres = best(at(rtol), repeat, integrator="scipy")
            ef = difference(fres.columns, fres.history, cols, reference.history)
            es = difference(sres.columns, sres.history, cols, reference.history)
            print(f"{name:<26} {rtol:>7.0e} {fast:>12.4f} {ef:>9.1e} {slow:>16.4f} {es:>9.1e}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cases", nargs="+", default=list(CASES))
    ap.add_argument("--ladder", action="store_true", help="wall time against error on the rtol ladder")
    ap.add_argument("--baseline", default=BASELINE, help="git revision of the previous engine")
    args = ap.parse_args()
    if args.ladder:
        ladder(args.cases, args.repeat)
    else:
        compare(args.cases, args.rounds, args.repeat, args.baseline)
    return 0


if __name__ == "__main__":
    sys.exit(main())
