"""ventsim from Python: load or build a scene, run it, get a DataFrame history, a summary, plots and files.

>>> import ventsim
>>> scene = ventsim.load("cases/verification/blowdown_choked.toml")
>>> results = ventsim.run(scene)
>>> round(results.summary["cavities"]["tank"]["peak pressure [Pa]"])
500000

The four packages underneath stay usable on their own: ``cavity`` (gas, cavities, integrator), ``blockage``
(node-to-face proximity, blocked areas), ``exchange`` (flow laws, the network) and ``cases`` (scene files,
runner, outputs, pictures). See ``docs/python.md``.
"""
from __future__ import annotations

from cases.scene.errors import SceneError

__all__ = ["Scene", "Results", "SceneError", "load", "run", "__version__"]

#: Where each public name lives: imported on first use, so that ``import ventsim`` stays cheap (numba, scipy,
#: trimesh and matplotlib load only when a scene is loaded, run or drawn).
_LAZY = {"Scene": ".scene", "load": ".scene", "Results": ".results", "run": ".results"}


def __getattr__(name: str):
    if name == "__version__":
        from cases.run.provenance import version

        value = version()
    elif name in _LAZY:
        from importlib import import_module

        value = getattr(import_module(_LAZY[name], __name__), name)
    else:
        raise AttributeError(f"module 'ventsim' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
