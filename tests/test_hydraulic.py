"""Hydraulic cavities: closed compression follows p − p0 = K·ln(V0/V); liquid leaks through volume-rate tables."""
import numpy as np
import pytest

from cases.model.build import build_model
from cases.scene.errors import SceneError
from cases.run.runner import run
from cases.scene.files import scene_from_dict

K, RHO, P0 = 1.5e9, 870.0, 2.0e5  # oil: bulk modulus [Pa], density [kg/m^3], initial pressure [Pa]


def oil_scene(tmp_path, exchange=None):
    (tmp_path / "squeeze.csv").write_text("t,V\n0,1e-4\n0.01,0.995e-4\n0.02,0.99e-4\n0.03,0.999e-4\n")
    data = {"time": {"end": 0.03, "output_interval": 0.0005}, "solver": {"rtol": 1e-12},
            "cavity": [{"name": "seal", "fluid": "hydraulic", "pressure": P0, "temperature": 300.0,
                        "density": RHO, "bulk_modulus": K, "volume_table": "squeeze.csv"}]}
    if exchange:
        data["exchange"] = [exchange]
    return scene_from_dict(data, tmp_path / "s.toml")


def test_closed_hydraulic_cavity_follows_the_log_law(tmp_path):
    r = run(build_model(oil_scene(tmp_path)))
    V, p = r.column("seal.volume"), r.column("seal.pressure")
    ref = P0 + K * np.log(V[0] / V)
    assert np.max(np.abs(p - ref) / ref) <= 1e-10
    assert p.max() > 1.4e7  # 1 % squeeze of oil: about 15 MPa
    assert np.all(r.column("seal.mass") == r.column("seal.mass")[0])


def test_liquid_leaks_through_a_volume_rate_table(tmp_path):
    (tmp_path / "leak.csv").write_text("dp,q\n0,0\n1e6,1e-3\n1e8,5e-3\n")
    ex = {"name": "leak", "from": "seal", "area": 1e-5, "law": "volume_rate_leakage", "leakage_table": "leak.csv"}
    r = run(build_model(oil_scene(tmp_path, ex)))
    m = r.column("seal.mass")
    assert np.all(np.diff(m) <= 0) and m[-1] < m[0]
    assert r.summary["mass balance"]["seal"]["relative imbalance [-]"] <= 1e-12
    assert r.summary["modelled"]["cavities"]["seal"]["fluid"] == "hydraulic"


def test_orifice_law_is_refused_for_liquids(tmp_path):
    with pytest.raises(SceneError, match="is for gases"):
        oil_scene(tmp_path, {"name": "leak", "from": "seal", "area": 1e-5, "law": "orifice"})
