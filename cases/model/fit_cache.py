"""The exact wrapped-volume fits of :mod:`cases.model.wrapped_volume`, kept on disk between runs.

The fit of one convex body translating through a cavity's mesh (:func:`cases.model.wrap_fit.fit_wrap`, and the
cavity's volume V0) depends only on the two meshes, the axis and the range of displacement, which the caller's
``key`` digests, and on the code that computes it. Computing it is most of building a scene with a wrapping body
(0.4 s of CPU for the 5120-face headform on the 20,480-face cushion of ``cases/airbag_impactor_dynamic.toml``,
mostly the power diagram of the body's planes, :func:`cases.model.wrap_pieces.convex_planes`); reading it back
takes a millisecond. So a run of a scene whose geometry did not change reads the fit its previous run stored.

A file holds the fit's arrays (``.npz``, nothing pickled) under the digest of ``key`` and of the source of
:mod:`cases.model.wrapped_volume` with every ventsim module it imports (:func:`cavity.kernel_cache.stamp`, as for
numba's cache): an edit of that code gives new names. float64 arrays round-trip exactly, so a fit read back equals
a fresh one bit for bit. The folder is ``wrap_fits`` in the user cache folder (``$VENTSIM_CACHE_DIR``, else
``$XDG_CACHE_HOME/ventsim``, else ``~/.cache/ventsim``; an empty ``VENTSIM_CACHE_DIR`` switches it off, as for
the CoolProp fits of :mod:`cavity.species_fits`). A folder that cannot be written is skipped, a file that cannot be read is computed
again, and only the :data:`MAX_FILES` newest files are kept.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

import numpy as np

from cavity.species_fits import user_cache_file

__all__ = ["MAX_FILES", "fit_file", "load_fit", "store_fit"]

#: Fits kept in the folder (the oldest beyond are removed when one is stored); a few MB at most.
MAX_FILES = 64
_ARRAYS = ("knots", "values", "start", "end")


def fit_file(key: str) -> Path | None:
    """The file of the fit ``key`` (a digest of the geometry), or None when the cache is switched off."""
    from cavity.kernel_cache import stamp

    try:
        species = user_cache_file()  # the CoolProp fits' file: its folder is the user cache folder
    except (RuntimeError, KeyError):  # no home folder to put it in
        return None
    if species is None:
        return None
    folder = species.parent
    code = stamp(Path(__file__).resolve().with_name("wrapped_volume.py"))
    return folder / "wrap_fits" / f"{hashlib.sha256(f'{code}|{key}'.encode()).hexdigest()}.npz"


def load_fit(key: str):
    """(HermiteFit, V0 [m^3]) stored under ``key``, or None."""
    path = fit_file(key)
    if path is None or not path.is_file():
        return None
    from cases.model.wrap_fit import HermiteFit

    try:
        with np.load(path, allow_pickle=False) as data:
            arrays = [np.array(data[name], dtype=float) for name in _ARRAYS]
            bound, smoothing, v0 = (float(x) for x in data["scalars"])
    except (OSError, ValueError, KeyError):
        return None
    try:
        os.utime(path)  # recently used: kept by _prune
    except OSError:
        pass
    return HermiteFit(*arrays, np.float64(bound), smoothing), v0


def store_fit(key: str, fit, v0: float) -> None:
    """Keep ``fit`` and V0 under ``key`` (skipped when the folder cannot be written)."""
    path = fit_file(key)
    if path is None:
        return
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".tmp", dir=path.parent)
        with os.fdopen(fd, "wb") as fh:
            np.savez(fh, **{name: getattr(fit, name) for name in _ARRAYS},
                     scalars=np.array([fit.bound, fit.smoothing, v0], dtype=float))
        os.replace(tmp, path)
        _prune(path.parent)
    except OSError:
        pass


def _prune(folder: Path) -> None:
    """Remove all but the MAX_FILES newest fits."""
    files = sorted(folder.glob("*.npz"), key=lambda p: p.stat().st_mtime_ns, reverse=True)
    for p in files[MAX_FILES:]:
        p.unlink(missing_ok=True)
