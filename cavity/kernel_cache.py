"""numba's on-disk cache, kept consistent with the sources a kernel is compiled from.

numba stamps a cached kernel with its own module's source; a kernel's machine code also holds every kernel it calls
from other modules, so an edit there must invalidate it too. :func:`install` gives numba a cache locator for
ventsim's packages whose stamp is the content hash of the kernel's module and of every ventsim module it imports,
directly or not (read from their ``import`` lines). An edit invalidates exactly the kernels that can see it: editing
one flow law recompiles that law's kernel only (the engine calls laws through their address, :mod:`exchange.laws.
registry`), editing the engine's layout recompiles the engine, editing a test recompiles nothing of the package.
The cache stays beside the sources (``__pycache__``) or under ``NUMBA_CACHE_DIR``, as numba's own locators put it.

It is installed when :mod:`cavity` is imported (every package that compiles kernels imports it, but
:mod:`blockage`, whose kernels are switched over when it is: :func:`install`).
"""
from __future__ import annotations

import hashlib
import re
import sys
from functools import lru_cache
from pathlib import Path

__all__ = ["install", "closure", "stamp"]

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("cavity", "blockage", "exchange", "cases")
_IMPORT = re.compile(r"^[ \t]*(?:from[ \t]+(\.*[\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#]*)|import[ \t]+([\w.]+))",
                     re.M)


def _module_file(name: str) -> Path | None:
    """The source file of a ventsim module or package ``name`` (dotted), or None."""
    if name.split(".")[0] not in PACKAGES:
        return None
    base = ROOT.joinpath(*name.split("."))
    for p in (base.with_suffix(".py"), base / "__init__.py"):
        if p.is_file():
            return p
    return None


def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


@lru_cache(maxsize=None)
def _imports(path: Path) -> tuple:
    """The ventsim modules a source file imports (each ``from a import b``: ``a``, and ``a.b`` when it is a
    module; relative imports resolved)."""
    package = _module_name(path) if path.name == "__init__.py" else _module_name(path).rpartition(".")[0]
    found = set()
    for source, names, plain in _IMPORT.findall(path.read_text(encoding="utf-8")):
        if plain:
            candidates = [plain]
        else:
            dots = len(source) - len(source.lstrip("."))
            base = package.split(".")[:len(package.split(".")) - dots + 1] if dots else []
            stem = ".".join(base + ([source.lstrip(".")] if source.lstrip(".") else []))
            listed = (n.split(" as ")[0].strip() for n in names.strip("()\\ \n").split(","))
            candidates = [stem] + [f"{stem}.{n}" for n in listed if n.isidentifier()]
        for name in candidates:
            f = _module_file(name)
            if f is not None and f != path:
                found.add(f)
    return tuple(sorted(found))


@lru_cache(maxsize=None)
def closure(path: Path) -> tuple:
    """``path`` and every ventsim source it imports, directly or not (sorted)."""
    seen, todo = {path}, [path]
    while todo:
        for f in _imports(todo.pop()):
            if f not in seen:
                seen.add(f)
                todo.append(f)
    return tuple(sorted(seen))


@lru_cache(maxsize=None)
def stamp(path: Path) -> str:
    """The content hash of ``path``'s closure."""
    h = hashlib.sha256()
    for f in closure(path):
        h.update(str(f.relative_to(ROOT)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def _ours(py_file) -> bool:
    try:
        rel = Path(py_file).resolve().relative_to(ROOT)
    except ValueError:
        return False
    return rel.parts[0] in PACKAGES and rel.suffix == ".py"


def _locators():
    from numba.core import caching

    class _ClosureStamp:
        """A numba cache locator whose source stamp covers the module's ventsim imports."""

        def get_source_stamp(self):
            return stamp(Path(self._py_file).resolve())

        @classmethod
        def from_function(cls, py_func, py_file):
            return super().from_function(py_func, py_file) if _ours(py_file) else None

    class ClosureUserLocator(_ClosureStamp, caching.UserProvidedCacheLocator):
        pass

    class ClosureInTreeLocator(_ClosureStamp, caching.InTreeCacheLocator):
        pass

    return ClosureUserLocator, ClosureInTreeLocator


_INSTALLED = []


def install() -> None:
    """Put the closure locators first in numba's list (once), and switch the cache of every ventsim kernel created
    before (and not compiled yet) to them."""
    if _INSTALLED:
        return
    from numba.core import caching
    from numba.core.registry import CPUDispatcher

    user, in_tree = _locators()
    caching.CacheImpl._locator_classes[:0] = [user, in_tree]
    _INSTALLED.append(True)
    for name, module in list(sys.modules.items()):
        if name.split(".")[0] not in PACKAGES or module is None:
            continue
        for value in list(vars(module).values()):
            if isinstance(value, CPUDispatcher) and isinstance(value._cache, caching.FunctionCache) \
                    and not value.overloads and _ours(value.py_func.__code__.co_filename):
                value.enable_caching()
