"""Small scenes built in code for tests (dicts in the TOML's shape)."""
from __future__ import annotations

import copy

N2_CONSTANT_CP = {"name": "N2", "molar_mass": 0.0280134, "cp": [29.100619163]}


def tank(**cavity) -> dict:
    """A rigid 60 L tank of constant-cp N2 at 1 bar, 300 K; keyword arguments override cavity keys."""
    cav = {"name": "tank", "pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0}, "volume": 0.06}
    cav.update(cavity)
    return {"time": {"end": 0.1, "output_interval": 0.001}, "solver": {"rtol": 1e-10},
            "ambient": {"pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0}},
            "species": [copy.deepcopy(N2_CONSTANT_CP)], "cavity": [cav]}
