"""Keep numba's on-disk cache of the compiled network path consistent with its sources.

numba's ``cache=True`` checks only the source file of each cached function, not the kernels it inlines from
other modules (``inline="always"`` helpers of :mod:`exchange.compiled_rhs` live in every caller's machine code):
after an edit or an update of one of those modules, a stale cached caller runs old code against new arrays (seen
as a ZeroDivisionError). :func:`purge_stale` keeps a digest of all the compiled modules' sources beside their cache
and drops every cached kernel of the path when the digest changes; numba then compiles afresh once.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["purge_stale", "kernel_sources"]

HERE = Path(__file__).resolve().parent
STAMP = "ventsim_kernels.sha256"
#: Kernels of other packages that the compiled path calls (the leakage area of a moving surface).
LINKED = ("blockage/areas.py", "blockage/moving_area.py")


def kernel_sources() -> list:
    """The modules whose numba kernels call each other (the compiled network path): every module of ``exchange``
    and ``cavity`` that compiles with ``@njit`` (the laws are inlined into the right-hand side), and the
    :data:`LINKED` ones."""
    found = [p for folder in (HERE, HERE.parent / "cavity") for p in sorted(folder.glob("*.py"))
             if p.name != "kernel_cache.py" and "@njit" in p.read_text(encoding="utf-8")]
    return sorted(found + [HERE.parent / name for name in LINKED if (HERE.parent / name).is_file()])


def purge_stale() -> bool:
    """Drop the cached kernels of the compiled path when their sources changed since they were cached; True when
    it purged. Nothing is done when numba caches elsewhere (``NUMBA_CACHE_DIR``) or the folder is read-only."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return False
    sources = kernel_sources()
    if not sources:
        return False
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sources if p.is_file())).hexdigest()
    folders = sorted({p.parent / "__pycache__" for p in sources})
    stamp = HERE / "__pycache__" / STAMP
    try:
        if stamp.is_file() and stamp.read_text().strip() == digest:
            return False
        for folder in folders:
            for cached in list(folder.glob("*.nbi")) + list(folder.glob("*.nbc")):
                if cached.name.split(".")[0] in {p.stem for p in sources}:
                    cached.unlink(missing_ok=True)
        stamp.parent.mkdir(exist_ok=True)
        stamp.write_text(digest + "\n")
    except OSError:
        return False
    return True
