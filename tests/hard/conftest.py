"""Warm the compiled integrator once per session (numba compiles it on first use, ~20–40 s on a fresh checkout,
then loads it from its cache in ~0.5 s), so that no hard case's step or wall-time bound pays for compilation."""
import pytest


@pytest.fixture(scope="session", autouse=True)
def compiled_integrator_warm(tmp_path_factory):
    from hard_scenes import run_scene, tank

    data = tank(pressure=2e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4}]
    r = run_scene(data, tmp_path_factory.mktemp("warm"))
    assert r.trajectory.path == "compiled"
