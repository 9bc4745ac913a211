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


def pop_hold_reset(folder) -> dict:
    """A tank with a pressure spike (10 kg/s for 3 ms, spike.csv written into ``folder``) shorter than its vent's
    0.02 s pop hold time: the vent pops (the hold starts), drops back (re-armed) and never opens; a linear
    resistance leaks the tank meanwhile."""
    (folder / "spike.csv").write_text("t,mdot\n0,0\n0.001,10.0\n0.004,10.0\n0.005,0\n")
    data = tank()
    data["time"] = {"end": 0.05, "output_interval": 0.001}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": "spike.csv",
                                      "temperature": 300.0, "gas": {"N2": 1.0}}]
    data["exchange"] = [{"name": "leak", "from": "tank", "area": 1e-4, "law": "linear_resistance",
                         "conductance": 1.0},
                        {"name": "vent", "from": "tank", "area": 5e-4, "pop_pressure": 3e4, "pop_hold_time": 0.02}]
    return data
