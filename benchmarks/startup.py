"""First experience: how long a new user waits, measured in fresh processes.

Prints four figures (CPU time is user + system of the child process, so other engineers' load on the machine
inflates the wall time but hardly the CPU time):

1. import time of ``import ventsim`` (CPU and wall, median of ``--runs`` runs, 3 by default);
2. the main job of the README, ``ventsim run cases/airbag_impactor_dynamic.toml``, without and with ``--render``
   (CPU, median of ``--runs`` runs each after one run that warms the caches, and with the package's bytecode written
   as ``python -m cases.warmup`` writes it at install; the rendering cost is the difference,
   and the rendering phase alone as
   ``ventsim run --verbose`` reports it: the difference also holds the noise of two whole runs);
3. the first run of a scene on the compiled path with an empty numba cache (``NUMBA_CACHE_DIR`` pointed at an
   empty temporary folder): numba's compilation, what the first run after installing costs; and the same scene
   again with that cache filled.

4. with ``--library``: the first run of every library scene after installing (``bash .ci/setup`` compiles the
   kernels with ``python3 -m cases.warmup``), each in a fresh process with the installed cache: its whole CPU
   time bounds the compilation it still pays (goal: <= 10 s).

Goals: first compilation <= 10 s; warm main job <= 2 s CPU without ``--render``, <= 3 s with it; import <= 0.5 s.

Requires: the package installed (``bash .ci/setup``). Usage::

    python benchmarks/startup.py            # everything (the compilation alone takes about 1-2 min of CPU)
    python benchmarks/startup.py --no-compile
    python benchmarks/startup.py --no-compile --library   # + the first run of every library scene
    python benchmarks/startup.py --no-compile --runs 5     # median of 5 instead of 3
"""
from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MAIN = ROOT / "cases" / "airbag_impactor_dynamic.toml"
COMPILED = ROOT / "cases" / "verification" / "blowdown_choked.toml"


def child(args, env=None, phase=None) -> tuple[float, float]:
    """(CPU [s], wall [s]) of one child process running ``args``; raises if it fails. With ``phase`` (a
    ``ventsim run --verbose`` phase, e.g. "rendered"), the CPU time that phase reports instead (wall: nan)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run(args, cwd=ROOT, env={**os.environ, **(env or {})}, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode:
        raise RuntimeError(f"{' '.join(map(str, args))} failed:\n{out.stderr}")
    if phase is not None:
        line = next(l for l in out.stderr.splitlines() if l.startswith(f"ventsim: {phase} in "))
        return float(line.split(" in ")[1].split()[0]), float("nan")
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime, wall


def median(n, args, env=None, phase=None) -> tuple[float, float]:
    """(CPU, wall) medians of ``n`` runs of :func:`child`."""
    runs = [child(args, env, phase) for _ in range(n)]
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)


def ventsim(*args) -> list:
    return [sys.executable, "-m", "cases.cli", *map(str, args)]


def library_rows() -> list:
    """(name, CPU, wall) of the first run of each library scene in a fresh process, numba's cache as installed."""
    from cases.run.library import CASES, HERE

    rows = []
    with tempfile.TemporaryDirectory() as out:
        for name, path in CASES.items():
            rows.append((f"first run: {name}", *child(ventsim("run", HERE / path, "--out", out, "--quiet"))))
    return rows


def main(argv) -> None:
    n = int(argv[argv.index("--runs") + 1]) if "--runs" in argv else 3
    from cases.warmup import compile_bytecode

    compile_bytecode()  # as installing does: the runs below read .pyc files even under PYTHONDONTWRITEBYTECODE
    rows = [("import ventsim", *median(n, [sys.executable, "-c", "import ventsim"]))]
    with tempfile.TemporaryDirectory() as out:
        child(ventsim("run", MAIN, "--out", out, "--quiet"))  # warm the numba and CoolProp caches
        plain = median(n, ventsim("run", MAIN, "--out", out, "--quiet"))
        rendered = median(n, ventsim("run", MAIN, "--out", out, "--quiet", "--render"))
        phase = median(n, ventsim("run", MAIN, "--out", out, "--verbose", "--render"), phase="rendered")
    rows.append(("main job, no render", *plain))
    rows.append(("main job, --render", *rendered))
    rows.append(("  rendering (difference)", rendered[0] - plain[0], rendered[1] - plain[1]))
    rows.append(("  rendering phase alone (--verbose)", *phase))
    if "--no-compile" not in argv:
        with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
            env = {"NUMBA_CACHE_DIR": cache}
            rows.append(("first compiled run, empty numba cache", *child(ventsim("run", COMPILED, "--out", out,
                                                                                 "--quiet"), env)))
            rows.append(("same scene, cache filled", *child(ventsim("run", COMPILED, "--out", out, "--quiet"), env)))
    if "--library" in argv:
        rows += library_rows()
    print(f"{'what':<40} {'CPU [s]':>9} {'wall [s]':>9}")
    for name, cpu, wall in rows:
        print(f"{name:<40} {cpu:>9.2f} {wall:>9.2f}")
    print(f"medians of {n} runs; goals: first compilation <= 10 s, main job <= 2 s CPU (<= 3 s with --render), "
          "import <= 0.5 s")


if __name__ == "__main__":
    main(sys.argv[1:])
