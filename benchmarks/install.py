"""How long the README's first command takes on a fresh clone: ``python benchmarks/install.py``.

Clones the repository's committed HEAD into a temporary folder, runs ``bash .ci/setup`` there (a new virtual
environment ``.venv``, ``pip install -e ".[test]"`` into it, the numba warm-up), then the main job
(``.venv/bin/ventsim run cases/airbag_impactor_dynamic.toml --out ... --render``), and prints a table of the wall
time of each step (read from the lines ``.ci/setup`` prints as it goes) and the CPU time of the whole.

Options: ``--no-pip-cache`` downloads every wheel again (as a machine that never installed them would; the default
uses pip's cache of this machine, which makes the install step faster than on a new machine); ``--python PATH``
the interpreter the environment is made from (default ``python3``); ``--keep`` leaves the clone in place.
"""
from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed_setup(clone: Path, env: dict) -> list:
    """[(step, wall seconds)] of ``bash .ci/setup`` in ``clone``, one row per ``setup:`` step it announces."""
    rows, label, start = [], None, time.perf_counter()
    proc = subprocess.Popen(["bash", ".ci/setup"], cwd=clone, env=env, stderr=subprocess.PIPE, text=True)
    for line in proc.stderr:
        sys.stderr.write(line)
        text = line.strip()
        if text.startswith("setup: ") and not text.startswith("setup:   ") and not text.startswith("setup: ready"):
            now = time.perf_counter()
            if label is not None:
                rows.append((label, now - start))
            label, start = text[len("setup: "):].split(" (")[0], now
    if proc.wait() != 0:
        raise SystemExit(f"install.py: bash .ci/setup failed in {clone} (exit {proc.returncode})")
    if label is not None:
        rows.append((label, time.perf_counter() - start))
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-pip-cache", action="store_true")
    ap.add_argument("--python", default="python3")
    ap.add_argument("--keep", action="store_true")
    args = ap.parse_args(argv)
    tmp = Path(tempfile.mkdtemp(prefix="ventsim-install-"))
    clone = tmp / "ventsim"
    try:
        subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
        env["PYTHON"] = args.python
        if args.no_pip_cache:
            env["PIP_NO_CACHE_DIR"] = "1"
        cpu0, wall0 = _children_cpu(), time.perf_counter()
        rows = timed_setup(clone, env)
        setup_wall, setup_cpu = time.perf_counter() - wall0, _children_cpu() - cpu0
        cpu1, wall1 = _children_cpu(), time.perf_counter()
        subprocess.run([str(clone / ".venv/bin/ventsim"), "run", "cases/airbag_impactor_dynamic.toml", "--out",
                        str(tmp / "out"), "--render", "--quiet"], cwd=clone, env=env, check=True)
        job_wall, job_cpu = time.perf_counter() - wall1, _children_cpu() - cpu1
    finally:
        if not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)
    print(f"\nfresh clone of {ROOT.name} ({'no pip cache' if args.no_pip_cache else 'with pip cache'}, "
          f"{os.cpu_count()} cores)\n")
    print("| step | wall [s] |\n|---|---:|")
    for label, seconds in rows:
        print(f"| {label} | {seconds:.0f} |")
    print(f"| **bash .ci/setup in all** | **{setup_wall:.0f}** ({setup_cpu:.0f} s CPU) |")
    print(f"| main job after it (ventsim run ... --render) | {job_wall:.0f} ({job_cpu:.0f} s CPU) |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
