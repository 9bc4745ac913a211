"""PRESSURE AND MASS and DUAL PRESSURE inflators recover the mass flow and temperature they were made from."""
import math

import numpy as np

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import scene_from_dict
from exchange.laws.orifice import choked_flow_factor
from tests.scenes import tank

R_U, M, CP = 8.314462618, 0.0280134, 29.100619163
R, GAMMA = R_U / M, CP / (CP - R_U)
MDOT, T_IN, AREA, CD, V_TANK = 0.5, 600.0, 2e-5, 0.9, 0.06


def fill(tmp_path, inflator):
    data = tank()
    data["cavity"][0]["inflator"] = [dict({"name": "gen", "gas": {"N2": 1.0}}, **inflator)]
    return run(build_model(scene_from_dict(data, tmp_path / "s.toml")))


def test_orifice_inflators_match_the_mass_temperature_inflator(tmp_path):
    p_i = MDOT * math.sqrt(R * T_IN) / (CD * AREA * choked_flow_factor(GAMMA))  # choked orifice, from ṁ and T
    (tmp_path / "pi.csv").write_text(f"t,p\n0,{p_i!r}\n1,{p_i!r}\n")
    (tmp_path / "md.csv").write_text(f"t,m\n0,{MDOT!r}\n1,{MDOT!r}\n")
    rate = GAMMA * R * T_IN * MDOT / V_TANK  # tank test: ṁ = V ṗ / (γ R T)
    (tmp_path / "pt.csv").write_text(f"t,p\n0,1e5\n1,{1e5 + rate!r}\n")
    ref = fill(tmp_path, {"type": "mass_temperature", "mass_flow": MDOT, "temperature": T_IN})
    pm = fill(tmp_path, {"type": "pressure_mass", "inflator_pressure": "pi.csv", "mass_flow": "md.csv",
                         "orifice_area": AREA, "discharge_coefficient": CD})
    dp = fill(tmp_path, {"type": "dual_pressure", "inflator_pressure": "pi.csv", "tank_pressure": "pt.csv",
                         "tank_volume": V_TANK, "orifice_area": AREA, "discharge_coefficient": CD})
    p_ref = ref.column("tank.pressure")
    for r in (pm, dp):
        assert np.max(np.abs(r.column("tank.pressure") / p_ref - 1)) < 1e-10
        assert np.max(np.abs(r.column("tank.mass") / ref.column("tank.mass") - 1)) < 1e-10
