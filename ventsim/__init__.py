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
from cases.run.provenance import version as _version

from .results import Results, run
from .scene import Scene, load

__version__ = _version()

__all__ = ["Scene", "Results", "SceneError", "load", "run", "__version__"]
