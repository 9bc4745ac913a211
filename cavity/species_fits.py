"""A cache of the CoolProp cp0(T) fits of :func:`cavity.species.species_from_coolprop`, so that a run neither imports
CoolProp (~2.8 s) nor re-fits its species (~0.2 s each) when the fit is already known.

A fit is identified by the fluid, the temperature range, the piece width and the installed CoolProp version (read
from the package metadata, without importing CoolProp). Two places are looked up, in order:

1. ``cavity/data/coolprop_fits.json``, shipped with ventsim and written by ``python
   cavity/data/make_coolprop_fits.py`` (the built-in species of :data:`cavity.species.BUILTIN_COOLPROP_NAMES`); used only when it was
   made with the installed CoolProp version;
2. a file per CoolProp version in the user cache folder (``$VENTSIM_CACHE_DIR``, else
   ``$XDG_CACHE_HOME/ventsim``, else ``~/.cache/ventsim``), filled by every fresh fit. Set ``VENTSIM_CACHE_DIR``
   to an empty string to switch it off.

Floats are stored with ``repr`` (JSON round-trips float64 exactly), so a cached fit equals a fresh one bit for bit
on the machine that made it; the shipped fits, made on another, give this machine's cp(T) to round-off (measured
≤ 8.9e-16; their cubic coefficients differ by up to 1.3e-10 of their size, the least squares being
ill-conditioned in the coefficients, not in cp).
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

__all__ = ["SHIPPED", "coolprop_version", "fit_key", "lookup", "store", "user_cache_file", "write_json"]

SHIPPED = Path(__file__).resolve().parent / "data" / "coolprop_fits.json"


def coolprop_version() -> str:
    """The installed CoolProp version ("none" when it is not installed)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("CoolProp")
    except PackageNotFoundError:
        return "none"


def fit_key(fluid: str, t_range, width: float) -> str:
    """``"Nitrogen|default|100.0"``: what identifies a fit besides the CoolProp version.

    >>> fit_key("Nitrogen", None, 100.0), fit_key("Argon", (300.0, 900.0), 50)
    ('Nitrogen|default|100.0', 'Argon|300.0-900.0|50.0')
    """
    span = "default" if t_range is None else f"{float(t_range[0])!r}-{float(t_range[1])!r}"
    return f"{fluid}|{span}|{float(width)!r}"


def user_cache_file() -> Path | None:
    """This CoolProp version's cache file in the user cache folder, or None when switched off."""
    folder = os.environ.get("VENTSIM_CACHE_DIR")
    if folder == "":
        return None
    if folder is None:
        base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
        folder = str(Path(base) / "ventsim")
    return Path(folder) / f"coolprop_fits-{coolprop_version()}.json"


def _read(path: Path) -> dict:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return {}


_SHIPPED_PARSED: list = [None, {}]  # (path, mtime, size) and the parsed shipped table


def _shipped() -> dict:
    """The shipped table, parsed once per process (again if the file changes); not to be modified."""
    try:
        st = SHIPPED.stat()
    except OSError:
        return {}
    key = (str(SHIPPED), st.st_mtime_ns, st.st_size)
    if _SHIPPED_PARSED[0] != key:
        _SHIPPED_PARSED[:] = [key, _read(SHIPPED)]
    return _SHIPPED_PARSED[1]


def lookup(key: str) -> dict | None:
    """The stored fit (``molar_mass``, ``breaks``, ``pieces``, ``source``) of ``key`` for the installed CoolProp, or
    None."""
    shipped = _shipped()
    if shipped.get("coolprop") == coolprop_version() and key in shipped.get("fits", {}):
        return shipped["fits"][key]
    path = user_cache_file()
    return _read(path).get("fits", {}).get(key) if path is not None else None


def write_json(path: Path, data: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    with os.fdopen(fd, "w") as fh:
        json.dump(data, fh, sort_keys=True)
    os.replace(tmp, path)


def store(key: str, fit: dict, path: Path | None = None) -> None:
    """Add ``fit`` under ``key`` to the user cache (or to ``path``); a cache that cannot be written is skipped."""
    path = path if path is not None else user_cache_file()
    if path is None:
        return
    data = _read(path) or {"coolprop": coolprop_version(), "fits": {}}
    data.setdefault("fits", {})[key] = fit
    try:
        write_json(path, data)
    except OSError:
        pass
