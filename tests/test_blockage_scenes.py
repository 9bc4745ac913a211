"""Blockage in scenes: exact onset times, area steps A_e·N_c/N_e, output-interval independence."""
import math

import numpy as np
import pytest
import trimesh

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import scene_from_dict
from tests.scenes import tank

TOL, V, Z0, SLOPE = 1e-3, 0.5, 0.011, 0.04  # tolerance [m], plate speed [m/s], plate height at x=0 [m], tilt
S_STOP = Z0 - 1e-4  # the plate stops 0.1 mm short of the vent: it never passes through it


def write_vent(path):
    """A hand-built vent: 3 x 3 nodes 10 mm apart in z = 0, four quads of 1 cm^2 (OBJ keeps quads)."""
    lines = [f"v {x} {y} 0.0" for y in (0.0, 0.01, 0.02) for x in (0.0, 0.01, 0.02)]
    lines += ["f 1 2 5 4", "f 2 3 6 5", "f 4 5 8 7", "f 5 6 9 8"]
    path.write_text("\n".join(lines) + "\n")


def write_plate(path):
    """A plate whose lower face is the plane z = Z0 + SLOPE·x, tilted so the node columns touch one by one."""
    plate = trimesh.creation.box(extents=(0.2, 0.2, 0.004))
    plate.apply_transform(trimesh.transformations.rotation_matrix(-math.atan(SLOPE), (0, 1, 0)))
    plate.apply_translation((0.0, 0.0, Z0 + 0.002 * math.sqrt(1 + SLOPE**2)))
    plate.export(path)


def plate_scene(tmp_path, output_interval=0.001):
    write_vent(tmp_path / "vent.obj")
    write_plate(tmp_path / "plate.ply")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 0.04, "output_interval": output_interval}
    (tmp_path / "motion.csv").write_text(f"t,s\n0,0\n{S_STOP / V!r},{S_STOP!r}\n1,{S_STOP!r}\n")
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [0, 0, -1], "displacement_table": "motion.csv"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    return scene_from_dict(data, tmp_path / "scene.toml")


def onset_times():
    """While the plate moves at V: node column at x touches when its distance to the plane, (Z0 + SLOPE·x − V t)/√(1+SLOPE²), equals TOL."""
    c = math.sqrt(1 + SLOPE**2)
    return [(Z0 + SLOPE * x - TOL * c) / V for x in (0.0, 0.01, 0.02)]


def test_flat_plate_onset_times_and_area_steps(tmp_path):
    r = run(build_model(plate_scene(tmp_path)))
    track = r.model.network.areas[0].track
    expected = onset_times()
    assert len(track.crossings) == 3
    assert np.max(np.abs(track.crossings - expected)) <= 1e-9
    # A_e·N_c/N_e with A_e = 1 cm^2, N_e = 4: columns x=0, 0.01, 0.02 in turn
    assert np.allclose(track.areas, [4e-4, 3e-4, 1e-4, 0.0], rtol=1e-12, atol=1e-18)
    t, area = r.column("time"), r.column("vent.area")
    for lo, hi, a in zip([0.0] + expected, expected + [1.0], [4e-4, 3e-4, 1e-4, 0.0]):
        sel = (t > lo) & (t < hi)
        assert np.allclose(area[sel], a, rtol=1e-12, atol=1e-18)
    assert r.summary["blockage"]["vent"]["first blockage time [s]"] == pytest.approx(expected[0], abs=1e-9)
    p = r.column("tank.pressure")
    assert np.ptp(p[t > expected[-1]]) == 0.0  # fully blocked: the tank holds its pressure


def test_peak_and_results_do_not_depend_on_output_interval(tmp_path):
    a = run(build_model(plate_scene(tmp_path, 0.001)))
    b = run(build_model(plate_scene(tmp_path, 0.0001)))
    pa, pb = (x.summary["cavities"]["tank"]["final pressure [Pa]"] for x in (a, b))
    assert abs(pa / pb - 1) <= 1e-12
    assert a.summary["solver"]["steps"] == b.summary["solver"]["steps"]


def test_hinged_flap_rotation_table_closes_columns_at_the_closed_form_times(tmp_path):
    """A flap hinged at x = −5 mm rotates from 20° down to 0°: column x touches when (x + 5 mm)·sin φ = tol."""
    write_vent(tmp_path / "vent.obj")
    flap = trimesh.creation.box(extents=(0.04, 0.06, 0.002))
    flap.apply_translation((0.015, 0.01, 0.001))  # lower face in z = 0, hinge edge at x = −0.005
    flap.apply_transform(trimesh.transformations.rotation_matrix(math.radians(-20.0), (0, 1, 0), (-0.005, 0, 0)))
    flap.export(tmp_path / "flap.ply")
    (tmp_path / "angle.csv").write_text("t,deg\n0,0\n0.03,20\n0.04,20\n")  # rotates back by +20° about y
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 0.04, "output_interval": 0.001}
    data["body"] = [{"name": "flap", "mesh": "flap.ply", "rotation_table": "angle.csv",
                     "rotation_axis": [0, 1, 0], "rotation_centre": [-0.005, 0, 0]}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["flap"],
                         "contact_tolerance": TOL}]
    r = run(build_model(scene_from_dict(data, tmp_path / "s.toml")))
    track = r.model.network.areas[0].track
    phi = [math.degrees(math.asin(TOL / (x + 0.005))) for x in (0.0, 0.01, 0.02)]  # angle at touch [deg]
    expected = [0.03 * (1 - p / 20.0) for p in phi]  # 20° − 20°·t/0.03 = φ
    # the hinge column (x = 0) is within 1 mm of the hinge: it is blocked when sin φ <= 0.2 (φ ≈ 11.5°)
    assert np.max(np.abs(track.crossings - expected)) <= 1e-9
    assert np.allclose(track.areas, [4e-4, 3e-4, 1e-4, 0.0], rtol=1e-12, atol=1e-18)


def test_vertex_trajectory_reproduces_the_rigid_plate(tmp_path):
    """The plate's motion given as vertex frames (an FE-like export) gives the same onset times."""
    rigid = run(build_model(plate_scene(tmp_path)))
    plate = trimesh.load(tmp_path / "plate.ply")
    times = np.array([0.0, S_STOP / V, 1.0])
    frames = np.array([plate.vertices - [0, 0, s] for s in (0.0, S_STOP, S_STOP)])
    np.savez(tmp_path / "plate_traj.npz", times=times, vertices=frames)
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 0.04, "output_interval": 0.001}
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "vertex_trajectory": "plate_traj.npz"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    r = run(build_model(scene_from_dict(data, tmp_path / "s.toml")))
    a, b = rigid.model.network.areas[0].track, r.model.network.areas[0].track
    assert np.max(np.abs(a.crossings - b.crossings)) <= 1e-9 and np.array_equal(a.areas, b.areas)
    assert abs(r.summary["cavities"]["tank"]["final pressure [Pa]"]
               / rigid.summary["cavities"]["tank"]["final pressure [Pa]"] - 1) < 1e-9


def test_delta_leakage_area_counts_only_area_gained_after_activation(tmp_path):
    """Abaqus DELTA LEAKAGE AREA: opened while one node column is blocked (3 cm² of 4 open), the vent's flow
    area is the leakage area minus those 3 cm²: zero while the plate covers more, 1 cm² once it has gone."""
    scene = plate_scene(tmp_path)
    (tmp_path / "motion.csv").write_text(f"t,s\n0,0\n{S_STOP / V!r},{S_STOP!r}\n0.03,{S_STOP!r}\n0.035,0\n")
    t_open = 0.5 * (onset_times()[0] + onset_times()[1])
    from dataclasses import replace

    ex = replace(scene.exchange[0], open_time=t_open, delta_area=True)
    r = run(build_model(replace(scene, exchange=(ex,))))
    t, area = r.column("time"), r.column("vent.area")
    assert np.all(area[t < t_open] == 0.0) and np.all(area[(t > t_open) & (t < 0.03)] == 0.0)
    assert np.allclose(area[t > 0.0351], 1e-4, rtol=1e-12)
    assert r.summary["cavities"]["tank"]["final pressure [Pa]"] < 2.0e5
