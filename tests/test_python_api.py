"""ventsim as a library: a scene built in Python (no file) runs and matches a closed form; it is validated by the
TOML loader (same errors, same hash); the DataFrame history carries units in its column names."""
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import trimesh

import ventsim
from cavity.tolerances import R_UNIVERSAL
from cases.scene.files import read_scene_data

ROOT = Path(__file__).resolve().parents[1]
M, V, MDOT, T_IN, P0, T0 = 0.0280134, 0.06, 0.5, 600.0, 1.0e5, 300.0


def fill_scene(mass_flow=np.array([[0.0, MDOT], [1.0, MDOT]])):
    return {"time": {"end": 0.1, "output_interval": 0.005},
            "ambient": {"pressure": P0, "temperature": T0, "gas": {"N2": 1.0}},
            "species": [{"name": "N2", "molar_mass": M, "cp": [3.5 * R_UNIVERSAL]}],
            "cavity": [{"name": "tank", "pressure": P0, "temperature": T0, "gas": {"N2": 1.0}, "volume": V,
                        "inflator": [{"name": "gen", "type": "mass_temperature", "temperature": T_IN,
                                      "mass_flow": mass_flow}]}]}


def test_a_python_scene_matches_the_rigid_fill_closed_form_and_names_units():
    r = ventsim.run(ventsim.Scene(fill_scene()))
    h = r.history
    assert list(h.columns) == ["time [s]", "tank.pressure [Pa]", "tank.gauge_pressure [Pa]", "tank.temperature [K]",
                               "tank.mass [kg]", "tank.volume [m^3]", "tank.gen.mass_flow [kg/s]",
                               "tank.gen.temperature [K]"]
    t = h["time [s]"].to_numpy()
    p_exact = P0 + 1.4 * R_UNIVERSAL / M * MDOT * T_IN * t / V
    assert np.max(np.abs(h["tank.pressure [Pa]"] / p_exact - 1.0)) < 1e-6
    assert np.max(np.abs(h["tank.mass [kg]"] - (P0 * V * M / (R_UNIVERSAL * T0) + MDOT * t))) < 1e-9
    assert np.array_equal(h["tank.gauge_pressure [Pa]"], h["tank.pressure [Pa]"] - P0)
    assert np.all(h["tank.gen.mass_flow [kg/s]"] == MDOT) and np.all(h["tank.gen.temperature [K]"] == T_IN)
    assert r.at(0.0333, "tank.pressure") == pytest.approx(P0 + 1.4 * R_UNIVERSAL / M * MDOT * T_IN * 0.0333 / V,
                                                          rel=1e-6)


def test_python_and_toml_give_the_same_validated_scene_and_hash():
    toml = ROOT / "cases/verification/fill_constant.toml"
    data = read_scene_data(toml)
    data["cavity"][0]["inflator"][0]["mass_flow"] = np.loadtxt(toml.parent / "inflator_constant.csv", delimiter=",",
                                                               skiprows=1)
    from_python, from_file = ventsim.Scene(data), ventsim.load(toml)
    assert from_python.sha256 == from_file.sha256
    a, b = from_python.spec.cavity[0].inflator[0].mass_flow, from_file.spec.cavity[0].inflator[0].mass_flow
    assert (a.x, a.y) == (b.x, b.y)
    changed = ventsim.Scene({**data, "time": {**data["time"], "end": 0.2}})
    assert changed.sha256 != from_file.sha256


def test_a_python_scene_fails_like_a_toml_file():
    with pytest.raises(ventsim.SceneError, match=r"^<python scene>: cavity\[0\]\.temprature: unknown key "
                                                 r"\(did you mean 'temperature'"):
        ventsim.Scene(time={"end": 0.1}, cavity=[{"name": "tank", "pressure": P0, "temprature": T0}])
    with pytest.raises(ventsim.SceneError, match=r"cavity\[0\]\.inflator\[0\]\.mass_flow: expected a table of "
                                                 r"shape \(n, 2\)"):
        ventsim.Scene(fill_scene(mass_flow=np.zeros((3, 3))))
    with pytest.raises(ventsim.SceneError, match=r"cavity\[0\]\.inflator\[0\]\.mass_flow: .*rows 1 and 2 repeat the "
                                                 r"abscissa \(0\.0 then 0\.0\)"):
        ventsim.Scene(fill_scene(mass_flow=np.array([[0.0, 1.0], [0.0, 2.0]])))


def test_a_trimesh_object_is_read_back_in_double_precision():
    sphere = trimesh.creation.icosphere(subdivisions=2, radius=0.15)
    sphere.apply_translation((0.1, -0.2, 0.3))
    r = ventsim.run(ventsim.Scene(time={"end": 1e-3}, cavity=[{"name": "ball", "pressure": 2e5,
                                                               "temperature": 300.0, "mesh": sphere}]))
    # float32 coordinates would be 1e-7 off; two sums of the faces' signed volumes in different orders differ by
    # at most n·ε·Σ|v_f| (the sphere is off the origin, so the terms cancel): a bound independent of numpy's sums
    tri = sphere.vertices[sphere.faces]
    terms = np.abs(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2]))) / 6.0
    bound = len(terms) * np.finfo(float).eps * terms.sum() / sphere.volume
    assert r["ball.volume"][0] == pytest.approx(sphere.volume, rel=bound)
    assert bound < 1e-10


def test_results_save_and_summary_carry_version_and_hash(tmp_path):
    import pandas as pd

    scene = ventsim.Scene(fill_scene())
    r = ventsim.run(scene)
    paths = r.save(tmp_path)
    back = pd.read_csv(paths["history"])
    assert np.array_equal(back.to_numpy(), r.history.to_numpy())
    import json

    summary = json.loads(Path(paths["summary"]).read_text())
    assert summary["ventsim"] == {"version": ventsim.__version__, "scene sha256": scene.sha256}
    with open(ROOT / "pyproject.toml", "rb") as fh:
        assert ventsim.__version__ == tomllib.load(fh)["project"]["version"]
    fig = r.plot()
    assert [ax.get_ylabel() for ax in fig.axes] == ["pressure [kPa]", "temperature [K]", "mass flow [kg/s]"]
    assert math.isclose(r["tank.pressure"][-1], r.summary["cavities"]["tank"]["final pressure [Pa]"], rel_tol=1e-12)


def test_a_scene_rebuilt_from_the_spec_objects_of_a_loaded_one_is_the_same_scene():
    toml = ROOT / "cases/airbag_vented.toml"
    spec = ventsim.load(toml).spec
    rebuilt = ventsim.Scene(title=spec.title, time=spec.time, solver=spec.solver, ambient=spec.ambient,
                            species=list(spec.species), cavity=list(spec.cavity), exchange=list(spec.exchange),
                            base=toml.parent)
    assert rebuilt.sha256 == ventsim.load(toml).sha256
    assert rebuilt.spec.cavity[0].inflator[0].mass_flow.y == spec.cavity[0].inflator[0].mass_flow.y
