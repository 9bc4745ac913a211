"""Compile ventsim's numba kernels ahead of the first run: ``python3 -m cases.warmup`` (``bash .ci/setup`` runs it
after installing). It runs a small scene on the compiled network path, one with a blocked leakage surface, one
whose vent moves with its cavity's mesh series (the moving-area law Python calls too) and the README's main job (a
cushion wrapped around a dynamic headform: the kernels that build its exact wrapped volume), quietly; numba caches the
machine code beside the sources (``__pycache__``), so the first ``ventsim run`` starts at once instead of compiling.
Every scene runs on the same compiled engine, so the first three compile all of it. It also writes the bytecode of
ventsim's packages (``.pyc``, as ``pip install`` does for a regular install; an editable install writes it at the first
import, unless ``PYTHONDONTWRITEBYTECODE`` is set): without it every run compiles its ~170 modules from source again,
about 0.2 s of CPU (measured with ``compile()`` over the modules the main job imports). It prints each scene's
measured wall and CPU time as it goes (``benchmarks/compile.py`` and ``benchmarks/install.py`` measure it in a
fresh copy); with the cache filled, a few seconds."""
from __future__ import annotations

import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
PACKAGES = ("cases", "cavity", "exchange", "blockage", "ventsim")
SCENES = ("verification/blowdown_choked.toml", "seal_vent.toml", "bag_unfold.toml", "airbag_impactor_dynamic.toml")


def compile_bytecode(root: Path = HERE.parent) -> None:
    """Write the ``.pyc`` files of ventsim's packages under ``root`` (those missing or out of date)."""
    import compileall

    for package in PACKAGES:
        if (root / package).is_dir():
            compileall.compile_dir(root / package, quiet=1)


def main() -> int:
    from cases.model.build import build_model
    from cases.run.runner import run
    from cases.scene.files import load_scene

    print("ventsim: compiling the numba kernels ahead of the first run (from an empty cache minutes of CPU, "
          "depending on the machine; seconds when cached)", file=sys.stderr, flush=True)
    cpu, wall = time.process_time(), time.perf_counter()
    compile_bytecode()
    for k, name in enumerate(SCENES, start=1):
        c, w = time.process_time(), time.perf_counter()
        print(f"ventsim:   {k}/{len(SCENES)} {name} ...", end="", file=sys.stderr, flush=True)
        run(build_model(load_scene(HERE / name)))
        print(f" {time.perf_counter() - w:.0f} s ({time.process_time() - c:.0f} s CPU)", file=sys.stderr, flush=True)
    print(f"ventsim: numba kernels compiled and cached in {time.perf_counter() - wall:.0f} s "
          f"({time.process_time() - cpu:.0f} s CPU)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
