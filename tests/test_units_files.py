"""Series and node files in a scene written in mm-t-s or mm-kg-ms: a cavity or body given as a mesh series (.npz,
.pvd with point ids, .xdmf), a vertex trajectory and a node CSV are converted like the inline values, so the scene
gives its SI twin's history.

Each twin is made from the millimetre scene by the conversion the loader must do (every number times its unit's SI
factor, :meth:`UnitSystem.scale`): the two runs see the same SI inputs bit for bit, so their histories agree to
round-off; a value or file left unconverted, or converted by the wrong power of a unit, is off by 1e3 or more."""
import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest
import trimesh

from cases.model.build import build_model
from cases.model.mesh_series import read_mesh_series, write_pvd, write_xdmf
from cases.run.library import column_errors
from cases.run.runner import run
from cases.scene.errors import SceneError
from cases.scene.files import scene_from_dict
from cases.scene.ply import write_ply
from cases.scene.unit_systems import unit_system
from tests.scenes import tank
from tests.toml_write import dumps

CASES = Path(__file__).resolve().parents[1] / "cases"
#: Each history column within this share of its peak (the brief's figure; the same SI inputs give 0).
RTOL = 1e-12
LENGTH, AREA, TIME, PRESSURE, MASS_FLOW = (1, 0, 0), (2, 0, 0), (0, 0, 1), (-1, 1, -2), (0, 1, -1)


def same_history(si, other) -> None:
    a, b = run(build_model(si)), run(build_model(other))
    errors = column_errors(b.columns, b.history, a.columns, a.history)
    assert max(errors.values()) <= RTOL, {k: v for k, v in errors.items() if v > RTOL}


def csv_pair(rows, mm: Path, si: Path, system: str, ex: tuple, ey: tuple) -> str:
    """Write a 2-column table ``rows`` given in ``system`` to ``mm`` and its SI twin to ``si``; the mm name."""
    s = unit_system(system)
    np.savetxt(mm, rows, delimiter=",", fmt="%.17g", header="x,y", comments="")
    np.savetxt(si, rows * [s.scale(ex), s.scale(ey)], delimiter=",", fmt="%.17g", header="x,y", comments="")
    return mm.name


def library_copy(tmp_path, name: str) -> dict:
    """Library scene ``name`` as a dict, its files copied into tmp_path (same relative names)."""
    for sub in ("meshes", "data"):
        shutil.copytree(CASES / sub, tmp_path / sub, dirs_exist_ok=True)
    return tomllib.loads((CASES / name).read_text())


def load_csv(path: Path) -> np.ndarray:
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def test_a_cavity_mesh_series_in_mm_kg_ms(tmp_path):
    """bag_unfold (a cavity given as an .npz series, self-contact) in mm, kg, ms."""
    s = unit_system("mm-kg-ms")
    si = library_copy(tmp_path, "bag_unfold.toml")
    d = tmp_path / "data"
    with np.load(tmp_path / "meshes" / "bag_unfold.npz") as z:
        times, verts, faces = z["times"] * 1e3, z["vertices"] * 1e3, z["faces"]
    np.savez(tmp_path / "bag_mm.npz", times=times, vertices=verts, faces=faces)
    np.savez(tmp_path / "bag_si.npz", times=times * s.time, vertices=verts * s.length, faces=faces)
    mdot = csv_pair(load_csv(d / "inflator_driver.csv") * [1e3, 1e-3], d / "mdot_mm.csv", d / "mdot_si.csv",
                    "mm-kg-ms", TIME, MASS_FLOW)
    temp = csv_pair(load_csv(d / "inflator_driver_temperature.csv") * [1e3, 1.0], d / "T_mm.csv", d / "T_si.csv",
                    "mm-kg-ms", TIME, (0, 0, 0))
    mm = tomllib.loads(dumps(si))
    mm["units"] = {"system": "mm-kg-ms"}
    mm["time"] = {"end": 25.0, "output_interval": 0.5}  # through the unfolding and the vent's release
    mm["ambient"]["pressure"] = mm["cavity"][0]["pressure"] = 101325.0e-9  # GPa
    mm["cavity"][0]["mesh_series"] = "bag_mm.npz"
    mm["cavity"][0]["inflator"][0].update(mass_flow=f"data/{mdot}", temperature=f"data/{temp}")
    box = [x * 1e3 for x in si["exchange"][0]["leakage_box"]]
    mm["exchange"][0].update(leakage_box=box, effective_area=200.0, contact_tolerance=2.0)
    si["time"] = {"end": 25.0 * s.time, "output_interval": 0.5 * s.time}
    si["ambient"]["pressure"] = si["cavity"][0]["pressure"] = 101325.0e-9 * s.scale(PRESSURE)
    si["cavity"][0]["mesh_series"] = "bag_si.npz"
    si["cavity"][0]["inflator"][0].update(mass_flow="data/mdot_si.csv", temperature="data/T_si.csv")
    si["exchange"][0].update(leakage_box=[x * s.length for x in box], effective_area=200.0 * s.scale(AREA),
                             contact_tolerance=2.0 * s.length)
    a, b = scene_from_dict(si, tmp_path / "si.toml"), scene_from_dict(mm, tmp_path / "mm.toml")
    assert b.units.given == "mm-kg-ms" and b.cavity[0].mesh_series.endswith("_bag_mm.npz")
    same_history(a, b)


def test_node_csv_in_mm_t_s(tmp_path):
    """seal_vent_nodes (a node-based leak path: x, y, z and area per node) in mm, tonne, s."""
    s = unit_system("mm-t-s")
    si = library_copy(tmp_path, "seal_vent_nodes.toml")
    si["time"] = {"end": 0.03, "output_interval": 0.0005}  # closing, then opening again
    d = tmp_path / "data"
    nodes = load_csv(d / "seal_leak_nodes.csv") * [1e3, 1e3, 1e3, 1e6]
    rows = "".join(",".join(repr(float(v)) for v in row) + "\n" for row in nodes)
    (d / "nodes_mm.csv").write_text("# x [mm], y [mm], z [mm], area [mm^2]\nx,y,z,area\n" + rows)
    np.savetxt(d / "nodes_si.csv", nodes * ([s.length] * 3 + [s.scale(AREA)]), delimiter=",", fmt="%.17g")
    flange = trimesh.load(tmp_path / "meshes" / "seal_flange.ply", process=False)
    v, f = np.asarray(flange.vertices) * 1e3, np.asarray(flange.faces)
    write_ply(tmp_path / "flange_mm.ply", v, f)
    write_ply(tmp_path / "flange_si.ply", v * s.length, f)
    csv_pair(load_csv(d / "flange_motion.csv") * [1.0, 1e3], d / "motion_mm.csv", d / "motion_si.csv", "mm-t-s",
             TIME, LENGTH)
    csv_pair(load_csv(d / "seal_supply.csv") * [1.0, 1e-3], d / "supply_mm.csv", d / "supply_si.csv", "mm-t-s",
             TIME, MASS_FLOW)
    twins = {}
    for name, k in (("mm", 1.0), ("si", None)):
        x = tomllib.loads(dumps(si))
        f = (lambda v, e: v) if k else (lambda v, e: v * s.scale(e))
        if k:
            x["units"] = {"system": "mm-t-s"}
        x["ambient"]["pressure"] = f(0.101325, PRESSURE)  # MPa
        x["body"][0].update(mesh=f"flange_{name}.ply", displacement_table=f"data/motion_{name}.csv")
        x["cavity"][0].update(pressure=f(0.3, PRESSURE), volume=f(1.508e5, (3, 0, 0)))
        x["cavity"][0]["inflator"][0]["mass_flow"] = f"data/supply_{name}.csv"
        x["exchange"][0].update(leakage_nodes=f"data/nodes_{name}.csv", effective_area=f(3.0, AREA),
                                contact_tolerance=f(0.1, LENGTH))
        twins[name] = scene_from_dict(x, tmp_path / f"{name}.toml")
    converted = Path(twins["mm"].exchange[0].leakage_nodes)  # the mm file, converted to SI at load
    assert twins["mm"].units.given == "mm-t-s" and converted.name != "nodes_mm.csv"
    np.testing.assert_allclose(load_csv(converted), load_csv(d / "nodes_si.csv"), rtol=1e-15, atol=0.0)
    same_history(twins["si"], twins["mm"])


def tank_mm() -> dict:
    """tests.scenes.tank (60 L, 1 bar, 300 K) written in mm-t-s, with the library's N2."""
    data = tank(pressure=0.1, volume=6e7)
    del data["species"]
    data["units"] = {"system": "mm-t-s"}
    data["ambient"]["pressure"] = 0.1
    return data


def plate_files(folder: Path, factor: float, time_factor: float) -> None:
    """The plates' and vents' files in millimetres and seconds times ``factor`` and ``time_factor``."""
    folder.mkdir()
    times = np.linspace(0.0, 0.03, 7) * time_factor
    down = np.interp(times, np.array([0.0, 0.01, 0.02, 0.03]) * time_factor, [0.0, 1.2, 1.2, 0.0])
    plates = []
    for x0 in (0.0, 100.0):  # tilted: the node columns come within the tolerance one after another
        plate = trimesh.creation.box(extents=(20.0, 20.0, 4.0))
        plate.apply_transform(trimesh.transformations.rotation_matrix(-0.02, (0, 1, 0)))
        plate.apply_translation((x0 + 10.0, 10.0, 3.0))
        plates.append(plate)
    faces = np.asarray(plates[0].faces)
    frames = [(np.asarray(p.vertices)[None] - down[:, None, None] * [0.0, 0.0, 1.0]) * factor for p in plates]
    ids = np.tile(np.arange(len(plates[0].vertices)) + 100, (len(times), 1))
    write_pvd(folder / "plate.pvd", times, frames[0], faces, point_data={"GlobalNodeId": ids})
    write_ply(folder / "plate2.ply", np.asarray(plates[1].vertices) * factor, faces)
    np.savez(folder / "plate2.npz", times=times, vertices=frames[1])
    grid = np.array([[x, y, 0.0] for y in np.linspace(0, 20.0, 5) for x in np.linspace(0, 20.0, 5)])
    quads = np.array([[j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1, (j + 1) * 5 + i] for j in range(4)
                      for i in range(4)])
    write_xdmf(folder / "vent.xdmf", times[[0, -1]], np.stack([grid, grid]) * factor, quads)
    write_ply(folder / "vent2.ply", (grid + [100.0, 0.0, 0.0]) * factor, np.vstack([quads[:, :3], quads[:, [0, 2, 3]]]))


def plate_scene(folder: Path, f) -> dict:
    """A tank vented through a grid vent that a plate closes and opens again (a .pvd body series with point ids,
    the vent a fixed .xdmf series), and a second vent closed by a plate following an .npz vertex trajectory; the
    numbers are the mm-t-s ones passed through ``f(value, exponents)``."""
    data = tank(pressure=f(0.2, PRESSURE), volume=f(6e7, (3, 0, 0)))
    del data["species"]
    data["ambient"]["pressure"] = f(0.1, PRESSURE)
    data["time"] = {"end": f(0.03, TIME), "output_interval": f(0.0005, TIME)}
    data["body"] = [{"name": "plate", "mesh_series": "plate.pvd"},
                    {"name": "plate2", "mesh": "plate2.ply", "vertex_trajectory": "plate2.npz"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.xdmf", "blocked_by": ["plate"],
                         "contact_tolerance": f(0.1, LENGTH)},
                        {"name": "vent2", "from": "tank", "leakage_surface": "vent2.ply", "blocked_by": ["plate2"],
                         "contact_tolerance": f(0.1, LENGTH)}]
    return data


def test_body_series_trajectory_and_surface_series_in_mm_t_s(tmp_path):
    s = unit_system("mm-t-s")
    plate_files(tmp_path / "mm", 1.0, 1.0)
    plate_files(tmp_path / "si", s.length, s.time)
    mm = plate_scene(tmp_path / "mm", lambda v, e: v)
    mm["units"] = {"system": "mm-t-s"}
    si = plate_scene(tmp_path / "si", lambda v, e: v * s.scale(e))
    a, b = scene_from_dict(si, tmp_path / "si" / "s.toml"), scene_from_dict(mm, tmp_path / "mm" / "s.toml")
    series = read_mesh_series(b.base / b.body[0].mesh_series)
    assert np.array_equal(series.vertices, read_mesh_series(tmp_path / "si" / "plate.pvd").vertices)
    same_history(a, b)


def test_a_converted_pvd_keeps_its_point_ids(tmp_path):
    """Ids vouch for the node order where the geometric checks alone would refuse a large motion: the copy
    keeps them (a copy without them would be refused)."""
    box = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    v = np.asarray(box.vertices)
    frames = np.stack([v, v * [1.0, 1.0, 9.0]]) * 1e3  # an edge grows 9x: refused without ids
    ids = np.tile(np.arange(len(v)), (2, 1))
    write_pvd(tmp_path / "b.pvd", [0.0, 1.0], frames, np.asarray(box.faces), point_data={"node_id": ids})
    data = tank_mm()
    data["time"] = {"end": 1.0}
    data["body"] = [{"name": "b", "mesh_series": "b.pvd"}]
    scene = scene_from_dict(data, tmp_path / "s.toml")
    s = read_mesh_series(scene.base / scene.body[0].mesh_series)
    assert np.allclose(s.vertices, frames * 1e-3, rtol=1e-15, atol=0)


@pytest.mark.parametrize("key, value, expected", [
    ("mesh_series", "none.pvd", r"s\.toml: body\[0\]\.mesh_series: file '.*none\.pvd' does not exist"),
    ("mesh_series", "bad.xdmf", r"s\.toml: body\[0\]\.mesh_series: .*bad\.xdmf: cannot read the XDMF"),
    ("vertex_trajectory", "bad.npz", r"s\.toml: body\[0\]\.vertex_trajectory: .*bad\.npz: cannot read the \.npz"),
])
def test_a_bad_series_in_mm_is_one_line_naming_file_and_key(tmp_path, key, value, expected):
    (tmp_path / "bad.xdmf").write_text("<Xdmf>")
    (tmp_path / "bad.npz").write_bytes(b"not an npz")
    box = trimesh.creation.box(extents=(10.0, 10.0, 10.0))
    write_ply(tmp_path / "b.ply", np.asarray(box.vertices), np.asarray(box.faces))
    data = tank_mm()
    data["body"] = [{"name": "b", key: value, **({"mesh": "b.ply"} if key == "vertex_trajectory" else {})}]
    with pytest.raises(SceneError, match=expected) as info:
        scene_from_dict(data, tmp_path / "s.toml")
    assert "\n" not in str(info.value)


def test_a_bad_node_csv_in_mm_is_one_line_naming_file_and_key(tmp_path):
    (tmp_path / "n.csv").write_text("x,y\n1,2\n")
    data = tank_mm()
    data["exchange"] = [{"name": "leak", "from": "tank", "leakage_nodes": "n.csv", "effective_area": 1.0}]
    with pytest.raises(SceneError, match=r"s\.toml: exchange\[0\]\.leakage_nodes: 'n\.csv': expected rows of x, y, z"):
        scene_from_dict(data, tmp_path / "s.toml")
