"""Hard case: a solver failure must surface as cavity.integration.SolverError naming the time and the state."""
import re

import pytest

from cavity.integration import SolverError
from hard_scenes import run_scene, tank


def pulsed_blowdown(tmp_path):
    """A blowdown with a 41-row inflator table: the integrator stops at every row (41 segments)."""
    rows = "".join(f"{0.0025 * i!r},{0.01 * (i % 2)!r}\n" for i in range(41))
    (tmp_path / "pulses.csv").write_text("t,mdot\n" + rows)
    data = tank(pressure=5e5)
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": "pulses.csv",
                                      "temperature": 300.0, "gas": {"N2": 1.0}}]
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4}]
    return data


def test_step_budget_exceeded_is_a_solver_error_with_time_and_state(tmp_path):
    with pytest.raises(SolverError) as info:
        run_scene(pulsed_blowdown(tmp_path), tmp_path, max_steps=20)
    msg = str(info.value)
    assert "more than 20 steps" in msg
    t = float(re.search(r"t = ([0-9.eE+-]+) s", msg).group(1))
    assert 0.0 < t < 0.1
    assert re.search(r"tank: mass [0-9.eE+-]+ kg, U [0-9.eE+-]+ J", msg), msg


def test_the_same_scene_runs_with_its_default_budget(tmp_path):
    r = run_scene(pulsed_blowdown(tmp_path), tmp_path)
    assert r.summary["solver"]["steps"] < 400


def test_step_budget_is_enforced_inside_one_segment(tmp_path):
    data = tank(pressure=5e5)
    data["time"]["end"] = 2.0
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4}]
    with pytest.raises(SolverError, match="more than 3 steps"):
        run_scene(data, tmp_path, max_steps=3)
