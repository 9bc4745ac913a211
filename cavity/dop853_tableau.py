"""The DOP853 tableau (Hairer, Nørsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., Springer
1993, section II.10; Dormand & Prince, J. Comp. Appl. Math. 6 (1980) 19–26), read from scipy's
``scipy/integrate/_ivp/dop853_coefficients.py`` so that the compiled integrator steps exactly as ``solve_ivp``.

The file holds numpy arrays only; importing it as ``scipy.integrate._ivp.dop853_coefficients`` would first run
``scipy.integrate``'s ``__init__`` (quadrature, special functions, optimisation: about half a second of CPU) that
the compiled path never uses, so it is executed on its own, and imported the ordinary way only when scipy's layout
differs.

>>> tableau().N_STAGES
12
"""
from __future__ import annotations

import importlib.util
from functools import lru_cache
from pathlib import Path
from types import ModuleType

__all__ = ["tableau"]


@lru_cache(maxsize=1)
def tableau() -> ModuleType:
    """scipy's ``dop853_coefficients`` module (``N_STAGES``, ``A``, ``B``, ``C``, ``E3``, ``E5``, ``D``)."""
    scipy = importlib.util.find_spec("scipy")
    path = Path(scipy.origin).parent / "integrate" / "_ivp" / "dop853_coefficients.py" if scipy and scipy.origin \
        else None
    if path is None or not path.is_file():
        from scipy.integrate._ivp import dop853_coefficients

        return dop853_coefficients
    spec = importlib.util.spec_from_file_location("_ventsim_dop853_coefficients", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
