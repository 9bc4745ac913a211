"""What numba compilation costs a user: each figure in CPU seconds, measured in a temporary copy of the package with
an empty cache (numba caches beside the sources, so a copy starts cold) and an empty user cache
(``VENTSIM_CACHE_DIR`` inside the copy: no wrapped-volume fit from an earlier run), as on a new machine.

- cold warm-up: ``python -m cases.warmup`` on an empty cache, with the CPU each kernel's first compile took
  (numba's compile events; a caller's time includes the callees it compiled);
- the README's main job (``ventsim run cases/airbag_impactor_dynamic.toml --render``) on an empty cache, without
  the warm-up;
- the first run of each library scene on an empty cache (one fresh copy per scene; ``--scenes`` picks some);
- after the warm-up, the next run of the main job once one flow law module was edited, and once the engine's
  right-hand side was edited (numba's cache is stamped with each module's import closure,
  :mod:`cavity.kernel_cache`).

``--baseline REV`` measures a git revision the same way (``git archive``), for a before/after table.

Run: python benchmarks/compile.py [--scenes all|none|NAME ...] [--baseline REV] [--top 25]
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("cavity", "blockage", "exchange", "cases", "ventsim")
MAIN_JOB = ["-m", "cases.cli", "run", "cases/airbag_impactor_dynamic.toml", "--out", "out_main", "--render",
            "--quiet"]

#: run in the copy: the warm-up with numba's compile events recorded, as JSON on the last line of stdout
WARMUP = r"""
import json, sys, time
from numba.core import event
stack, rows = [], []
class Listener(event.Listener):
    def on_start(self, ev):
        if ev.kind == "numba:compile":
            stack.append(time.process_time())
    def on_end(self, ev):
        if ev.kind == "numba:compile":
            f = ev.data["dispatcher"].py_func
            rows.append((f"{f.__module__}.{f.__qualname__}", time.process_time() - stack.pop()))
event.register("numba:compile", Listener())
import runpy
try:
    runpy.run_module("cases.warmup", run_name="__main__")
except SystemExit:
    pass
print(json.dumps(rows))
"""

#: run in the copy: one library scene, built and run
SCENE = r"""
import sys
from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene
run(build_model(load_scene(HERE / CASES[sys.argv[1]])))
"""


def _skipped(folder, names) -> set:
    """numba's and Python's caches, and run outputs (``out/``, ``out_*/``), left out of a copy."""
    return {n for n in names if n == "__pycache__" or ((n == "out" or n.startswith("out_"))
                                                        and os.path.isdir(os.path.join(folder, n)))}


def copy_tree(dest: Path, rev, source: Path = ROOT) -> Path:
    """The package as it is (``rev`` None: the tree at ``source``, else a git revision) in ``dest``, without
    caches."""
    if rev is None:
        for name in PACKAGES:
            shutil.copytree(source / name, dest / name, ignore=_skipped)
        shutil.copy2(source / "pyproject.toml", dest / "pyproject.toml")
    else:
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev], check=True, capture_output=True).stdout
        with tempfile.TemporaryFile() as f:
            f.write(archive)
            f.seek(0)
            with tarfile.open(fileobj=f) as tar:
                tar.extractall(dest, filter="data")
    return dest


def cpu_of(tree: Path, args: list) -> tuple[float, str]:
    """(CPU seconds of a child python with ``args`` run in ``tree``, its stdout)."""
    env = dict(os.environ, PYTHONPATH=str(tree), PYTHONDONTWRITEBYTECODE="1",
               VENTSIM_CACHE_DIR=str(tree / ".user-cache"))  # no wrapped-volume fits kept from other runs
    env.pop("NUMBA_CACHE_DIR", None)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([sys.executable] + args, cwd=tree, env=env, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode:
        raise RuntimeError(f"{' '.join(args)} failed in {tree}:\n{out.stderr[-3000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out.stdout


def touch(path: Path) -> None:
    """Edit a module: append a comment (its content, hence its stamp, changes)."""
    path.write_text(path.read_text(encoding="utf-8") + "\n# edited by benchmarks/compile.py\n", encoding="utf-8")


def measure(rev: str | None, scenes: list, top: int) -> dict:
    label = rev or "working tree"
    out = {"label": label}
    with tempfile.TemporaryDirectory() as tmp:
        pristine = copy_tree(Path(tmp) / "pristine", rev)  # the sources as they are now, for every copy below
        tree = copy_tree(Path(tmp) / "warm", None, pristine)
        cpu, stdout = cpu_of(tree, ["-c", WARMUP])
        rows = json.loads(stdout.strip().splitlines()[-1])
        out["warmup"] = cpu
        totals = {}
        for name, seconds in rows:
            totals[name] = totals.get(name, 0.0) + seconds
        out["kernels"] = sorted(totals.items(), key=lambda kv: -kv[1])[:top]
        out["main job, warm"] = cpu_of(tree, MAIN_JOB)[0]
        law = tree / "exchange" / "laws" / "orifice.py"
        if law.is_file():
            touch(law)
            out["main job after editing exchange/laws/orifice.py"] = cpu_of(tree, MAIN_JOB)[0]
        engine = tree / "exchange" / "engine" / "rhs.py"
        if engine.is_file():
            touch(engine)
            out["main job after editing exchange/engine/rhs.py"] = cpu_of(tree, MAIN_JOB)[0]
        cold = copy_tree(Path(tmp) / "cold", None, pristine)
        out["main job, cold (no warm-up)"] = cpu_of(cold, MAIN_JOB)[0]
        out["scenes"] = {}
        for name in scenes:
            first = copy_tree(Path(tmp) / f"scene_{name}", None, pristine)
            out["scenes"][name] = cpu_of(first, ["-c", SCENE, name])[0]
            shutil.rmtree(first)
    print(f"\n== {label}")
    for key, value in out.items():
        if isinstance(value, float):
            print(f"{key:55s} {value:8.1f} s CPU")
    print(f"first run of each library scene, cold cache [s CPU]:")
    for name, cpu in out["scenes"].items():
        print(f"  {name:30s} {cpu:8.1f}")
    print(f"the {top} costliest kernels' first compile [s CPU, inclusive of the callees they compiled]:")
    for name, cpu in out["kernels"]:
        print(f"  {cpu:8.1f}  {name}")
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", nargs="+", default=["all"], help="library scenes to run cold (all, none or names)")
    ap.add_argument("--baseline", default=None, help="a git revision measured the same way, first")
    ap.add_argument("--top", type=int, default=25)
    ap.add_argument("--json", default=None, help="write the figures to this file")
    args = ap.parse_args()
    sys.path.insert(0, str(ROOT))
    from cases.run.library import CASES

    scenes = list(CASES) if args.scenes == ["all"] else [] if args.scenes == ["none"] else args.scenes
    results = [measure(args.baseline, scenes, args.top)] if args.baseline else []
    results.append(measure(None, scenes, args.top))
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
