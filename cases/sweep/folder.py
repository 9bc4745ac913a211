"""A sweep folder: its manifest (one scene per folder) and the lock that lets one sweep at a time write it."""
from __future__ import annotations

import contextlib
import hashlib
import json
import os
from pathlib import Path

from cases.scene.errors import SweepError

__all__ = ["check_manifest", "folder_lock", "write_json", "MANIFEST", "LOCK", "RESULTS_CSV", "RESULTS_PARQUET", "PLOT", "ROW", "DESIGNS"]

MANIFEST, LOCK = "sweep.json", ".sweep.lock"
RESULTS_CSV, RESULTS_PARQUET, PLOT = "results.csv", "results.parquet", "sweep.png"
ROW = "row.json"  # in each variant's folder, written last: the variant is finished
DESIGNS = ("full", "list", "lhs")


def write_json(path: Path, obj) -> None:
    from cases.results.output import atomic_path

    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(obj, indent=1) + "\n")


def check_manifest(out: Path, plan: Plan) -> None:
    """A sweep folder belongs to one scene (its parsed data): refuse to mix results of another."""
    digest = hashlib.sha256(json.dumps(plan.data, sort_keys=True, default=str).encode()).hexdigest()[:16]
    path = out / MANIFEST
    if path.is_file():
        old = json.loads(path.read_text())
        if old.get("scene hash") != digest:
            raise SweepError(f"{out}: holds a sweep of another scene ({old.get('scene')}, or it changed since): "
                             "choose another --out, or delete the folder")
    write_json(path, {"scene": str(plan.scene), "scene hash": digest, "keys": list(plan.keys),
                       "variants": len(plan.variants)})



@contextlib.contextmanager
def folder_lock(out: Path):
    """Hold ``out/.sweep.lock`` (an advisory lock the system releases if the process dies) while a sweep writes
    ``out``; raise SweepError if another sweep holds it."""
    import fcntl

    out.mkdir(parents=True, exist_ok=True)
    with open(out / LOCK, "a+") as fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.seek(0)
            raise SweepError(f"{out}: another sweep is writing this folder ({fh.read().strip() or 'pid unknown'}): "
                             "wait for it or choose another --out") from None
        fh.seek(0)
        fh.truncate()
        fh.write(f"pid {os.getpid()}")
        fh.flush()
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)
