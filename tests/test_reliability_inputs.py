"""Issue 14: every bad input found by the fuzz campaign is one clear line naming the file and the key."""
import numpy as np
import pytest
import trimesh

from tests.reliability import error_line, run_cli, tank, write

FILL_CSV = "time [s],mass flow [kg/s]\n0.0,0.5\n0.05,0.5\n"


def with_inflator(mass_flow, temperature=600.0):
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": mass_flow,
                                      "temperature": temperature, "gas": {"N2": 1.0}}]
    return data


# ---------------------------------------------------------------------------------------------- encodings

@pytest.mark.parametrize("encoding, expected", [("utf-16", "it looks like UTF-16"),
                                                ("latin-1", "byte 0xe8 at offset 4; Latin-1 or Windows-1252?")])
def test_a_scene_not_in_utf8_is_named(capsys, tmp_path, encoding, expected):
    scene = write(tmp_path, tank())
    scene.write_bytes(("# sc\u00e8ne\n" + scene.read_text()).encode(encoding))
    code, err = run_cli(capsys, scene, tmp_path / "out")
    assert code == 2 and err == [f"ventsim: error: {scene}: scene file {str(scene)!r} is not UTF-8 text "
                                 f"({expected}): save it as UTF-8"]


def test_a_binary_scene_is_named(capsys, tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_bytes(bytes(range(256)))
    code, err = run_cli(capsys, scene, tmp_path / "out")
    assert code == 2 and "is not UTF-8 text (it looks like a binary file)" in err[0]


def test_a_latin1_table_is_named(capsys, tmp_path):
    (tmp_path / "m.csv").write_bytes("# d\u00e9bit\n0,0.5\n1,0.5\n".encode("latin-1"))
    assert error_line(capsys, tmp_path, with_inflator("m.csv")) == (
        f"cavity[0].inflator[0].mass_flow: table file {str(tmp_path / 'm.csv')!r} is not UTF-8 text (byte 0xe9 at "
        "offset 3; Latin-1 or Windows-1252?): save it as UTF-8")


# ---------------------------------------------------------------------------------------------- types

@pytest.mark.parametrize("where, value, expected", [
    (("solver", "rtol"), 1e30, "solver.rtol: expected a relative tolerance 2.22e-14 <= rtol < 1"),
    (("exchange", "law"), 4, "exchange[0].law: expected one of 'orifice', 'fabric_leakage', 'graefe', "
                             "'mass_rate_leakage', 'volume_rate_leakage', 'mass_flux', 'volume_flux', "
                             "'bulk_viscosity', 'linear_resistance', 'seal', got 4"),
    (("exchange", "law"), True, "exchange[0].law: expected one of"),
    (("exchange", "law"), "orifce", "exchange[0].law: expected one of"),
    (("exchange", "name"), 7, "exchange[0].name: expected a text string, got 7"),
    (("exchange", "two_way"), "false", "exchange[0].two_way: expected true or false (a TOML boolean, no "
                                       "quotes), got 'false'"),
    (("exchange", "effective_area"), 0.0, "exchange[0].effective_area: expected a number > 0 [m^2], got 0.0"),
    (("exchange", "amplitude"), -1.0, "exchange[0].amplitude: row 1 has -1.0; expected >= 0"),
    (("exchange", "discharge_coefficient"), "x.csv", "exchange[0].discharge_coefficient: table file"),
    (("cavity", "name"), "ambient", "cavity[0].name: 'ambient' is reserved for the surroundings (exchange.to)"),
    (("cavity", "temperature"), 0.1, "cavity[0].temperature: 0.1 K is below 10 K, where no gas here is an "
                                     "ideal gas; temperatures are absolute [K]"),
    (("cavity", "gas"), {"N2": 1.1}, "cavity[0].gas: fractions sum to 1.1; expected 1 (within 1e-09)"),
    (("cavity", "gas"), {"N2": [1.0]}, "cavity[0].gas.N2: expected a fraction >= 0 (a number), got [1.0]"),
    (("cavity", "gas"), ["N2"], "cavity[0].gas: expected a table {species = fraction}, got ['N2']"),
    (("cavity", "mesh"), ["a.ply"], "cavity[0].mesh: expected a text string, got ['a.ply']"),
    (("species", "cp"), 29.1, "species[0].cp: expected a list of 1 to 6 numbers (a, b, c, d, e, f), got 29.1"),
    (("species", "cp"), "29", "species[0].cp: expected a list of 1 to 6 numbers (a, b, c, d, e, f), got '29'"),
    (("time", "output_interval"), 1e300, "time.output_interval: 1e+300 s is longer than time.end (0.05 s): no "
                                         "rows between t = 0 and the end"),
])
def test_wrong_types_and_ranges(capsys, tmp_path, where, value, expected):
    data = tank(solver={})
    table = data[where[0]]
    (table[0] if isinstance(table, list) else table)[where[1]] = value
    if where[1] == "effective_area":
        data["cavity"][0].pop("volume")
        data["cavity"][0]["mesh"] = str(tmp_path / "s.ply")
        trimesh.creation.icosphere(subdivisions=1, radius=0.1).export(tmp_path / "s.ply")
        data["exchange"][0].pop("area")
        data["exchange"][0]["leakage_box"] = [-1, -1, 0.05, 1, 1, 1]
    if where[1] == "mesh":
        data["cavity"][0].pop("volume")
    assert error_line(capsys, tmp_path, data).startswith(expected)


def test_a_typo_in_a_choice_suggests(capsys, tmp_path):
    data = tank()
    data["exchange"][0]["law"] = "orifce"
    assert error_line(capsys, tmp_path, data).endswith("got 'orifce' (did you mean 'orifice'?)")


@pytest.mark.parametrize("value, expected", [
    (20, "body[0].sphere_subdivisions: expected a whole number from 0 to 9, got 20"),
    ("four", "body[0].sphere_subdivisions: expected a whole number, got 'four'"),
])
def test_subdivisions_are_bounded(capsys, tmp_path, value, expected):
    assert error_line(capsys, tmp_path, body_scene(tmp_path, sphere_subdivisions=value)) == expected


def body_scene(folder, **body) -> dict:
    """A cushion mesh cavity with a leakage box blocked by a sphere."""
    trimesh.creation.icosphere(subdivisions=2, radius=0.2).export(folder / "cushion.ply")
    data = tank()
    data["cavity"][0].pop("volume")
    data["cavity"][0]["mesh"] = "cushion.ply"
    data["exchange"][0].pop("area")
    data["exchange"][0].update(leakage_box=[-1, -1, 0.15, 1, 1, 1], blocked_by=["ball"], contact_tolerance=1e-3)
    data["body"] = [dict({"name": "ball", "sphere": [0, 0, 0.3, 0.05], "velocity": 1.0}, **body)]
    return data


@pytest.mark.parametrize("key", ["axis", "rotation_axis"])
def test_a_zero_axis_is_caught_in_validation(capsys, tmp_path, key):
    err = error_line(capsys, tmp_path, body_scene(tmp_path, **{key: [0.0, 0.0, 0.0]}))
    assert err == f"body[0].{key}: a direction cannot be the zero vector (0, 0, 0)"


# ---------------------------------------------------------------------------------------------- tables

@pytest.mark.parametrize("text, expected", [
    ("t,m\n0,0_5\n1,0.5\n", "m.csv line 2: expected 2 numbers, got ['0', '0_5']"),
    ("t,m\n0,0.5\n0.04,0.5\n0.04,0.6\n", "m.csv (mass flow [kg/s]): rows 2 and 3 repeat the abscissa (0.04 then "
                                         "0.04)"),
])
def test_table_cells(capsys, tmp_path, text, expected):
    (tmp_path / "m.csv").write_text(text)
    assert error_line(capsys, tmp_path, with_inflator("m.csv")) == f"cavity[0].inflator[0].mass_flow: {expected}"


def test_a_comment_then_a_header_is_read(capsys, tmp_path):
    (tmp_path / "m.csv").write_text("# measured 2026\n" + FILL_CSV)
    code, err = run_cli(capsys, write(tmp_path, with_inflator("m.csv")), tmp_path / "out")
    assert code == 0 and err == []


def test_a_directory_given_as_a_table(capsys, tmp_path):
    (tmp_path / "m.csv").mkdir()
    assert error_line(capsys, tmp_path, with_inflator("m.csv")) == (
        f"cavity[0].inflator[0].mass_flow: table file {str(tmp_path / 'm.csv')!r} is a directory, not a file")


def test_too_many_table_rows(capsys, tmp_path):
    x = np.linspace(0.0, 0.05, 100_001)
    (tmp_path / "m.csv").write_text("t,m\n" + "".join(f"{float(v)!r},0.5\n" for v in x))
    assert error_line(capsys, tmp_path, with_inflator("m.csv")) == (
        "cavity[0].inflator[0].mass_flow: 100001 rows exceed limits.table_rows = 100000: resample the table or "
        "raise the limit")


# ---------------------------------------------------------------------------------------------- budgets

@pytest.mark.parametrize("time, solver, expected", [
    ({"end": 0.05, "output_interval": 1e-9}, {}, "time.output_interval: 5e+07 rows of history.csv (time.end / "
                                                 "output_interval) exceed limits.output_rows = 1000000: raise the "
                                                 "interval or the limit"),
    ({"end": 5e4, "output_interval": 1e-3}, {}, "time.output_interval: 5e+07 rows of history.csv"),
    ({"end": 0.05}, {"max_step": 1e-12}, "solver.max_step: time.end / max_step = 5e+10 steps exceed limits.steps "
                                         "= 2000000: raise max_step or the limit"),
])
def test_budgets_are_checked_before_the_run(capsys, tmp_path, time, solver, expected):
    assert error_line(capsys, tmp_path, tank(time=time, solver=solver)).startswith(expected)


# ---------------------------------------------------------------------------------------------- meshes

def mesh_scene(folder, mesh) -> dict:
    mesh.export(folder / "m.ply")
    data = tank()
    data["cavity"][0].pop("volume")
    data["cavity"][0]["mesh"] = "m.ply"
    return data


@pytest.mark.parametrize("bad", [7, -2])
def test_a_face_that_indexes_a_missing_vertex(capsys, tmp_path, bad):
    from cases.scene.ply import write_ply

    s = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
    faces = np.array(s.faces)
    faces[5, 2] = len(s.vertices) + bad if bad > 0 else bad
    write_ply(tmp_path / "m.ply", s.vertices, faces)
    data = tank()
    data["cavity"][0].pop("volume")
    data["cavity"][0]["mesh"] = "m.ply"
    err = error_line(capsys, tmp_path, data)
    assert err.startswith(f"cavity[0].mesh: 'm.ply': face 5 indexes vertices {faces[5].tolist()} but the mesh has "
                          f"{len(s.vertices)} vertices"), err


def test_a_mesh_without_faces(capsys, tmp_path):
    (tmp_path / "m.ply").write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nelement face 0\nproperty list uchar int vertex_indices\n"
                                    "end_header\n0 0 0\n1 0 0\n0 1 0\n")
    data = tank()
    data["cavity"][0].pop("volume")
    data["cavity"][0]["mesh"] = "m.ply"
    assert error_line(capsys, tmp_path, data) == "cavity[0].mesh: 'm.ply' has no faces"


def test_a_bowtie_vertex(capsys, tmp_path):
    a = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
    b = a.copy()
    b.apply_translation(2.0 * a.vertices[0])  # b's antipode of vertex 0 lands on a's vertex 0
    both = trimesh.Trimesh(np.vstack([a.vertices, b.vertices]), np.vstack([a.faces, b.faces + len(a.vertices)]))
    err = error_line(capsys, tmp_path, mesh_scene(tmp_path, both))
    assert err.startswith("cavity[0].mesh: 'm.ply': vertex ") and err.endswith(
        "joins two shells at a single point (a bowtie): separate them or merge them along an edge")


def test_an_inside_out_second_shell(capsys, tmp_path):
    inner = trimesh.creation.icosphere(subdivisions=1, radius=0.05)
    inner.invert()
    both = trimesh.util.concatenate([trimesh.creation.icosphere(subdivisions=2, radius=0.2), inner])
    err = error_line(capsys, tmp_path, mesh_scene(tmp_path, both))
    assert err.startswith("cavity[0].mesh: 'm.ply': shell 2 of 2 encloses -0.000") and err.endswith(
        "m^3: its normals point inwards (inside out); flip it")


def test_a_nan_vertex(capsys, tmp_path):
    s = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
    v = s.vertices.copy()
    v[3] = np.nan
    err = error_line(capsys, tmp_path, mesh_scene(tmp_path, trimesh.Trimesh(v, s.faces, process=False)))
    assert err == "cavity[0].mesh: 'm.ply': vertex 3 has a non-finite coordinate"


def test_a_mesh_in_millimetres_is_an_error_unless_meant(capsys, tmp_path):
    s = trimesh.creation.icosphere(subdivisions=2, radius=200.0)  # meant as 200 mm
    data = mesh_scene(tmp_path, s)
    err = error_line(capsys, tmp_path, data)
    assert err.startswith("cavity[0].mesh: 'm.ply' encloses 3.23764e+07 m^3 and spans 692.82 m: coordinates in "
                          "millimetres (then it encloses 0.0324 m^3)?"), err
    data["units"] = {"unchecked": ["cavity[0].mesh"]}  # meant: a warning remains
    code, err = run_cli(capsys, write(tmp_path, data), tmp_path / "out")
    assert code == 0
    assert len(err) == 1 and err[0].startswith("ventsim: warning: cavity[0].mesh: 'm.ply' encloses 3.23764e+07 m^3, "
                                               "spans 692.82 ")
    assert err[0].endswith("m: coordinates look like millimetres (x 1e-3: 0.693 m); a mesh must be in the scene's "
                           "units: set [units] system = 'mm-t-s' or 'mm-kg-ms', or scale the mesh by 1e-3")
    import json

    assert json.loads((tmp_path / "out" / "summary.json").read_text())["warnings"] == [err[0][18:]]


def test_a_directory_given_as_a_mesh(capsys, tmp_path):
    (tmp_path / "m.ply").mkdir()
    data = tank()
    data["cavity"][0].pop("volume")
    data["cavity"][0]["mesh"] = "m.ply"
    assert error_line(capsys, tmp_path, data) == "cavity[0].mesh: 'm.ply' is a directory, not a file"


# ---------------------------------------------------------------------------------------------- Python API

def test_scene_dataclasses_built_in_python_are_validated():
    from dataclasses import replace

    from cases.model.build import build_model
    from cases.scene.errors import SceneError
    from cases.scene.files import scene_from_dict

    good = scene_from_dict(tank(), "/nowhere/scene.toml")
    bad = replace(good, cavity=(replace(good.cavity[0], pressure=-1.0),))
    with pytest.raises(SceneError, match=r"cavity\[0\]\.pressure: expected a number > 0 \[Pa\], got -1\.0"):
        build_model(bad)
    typo = replace(good, exchange=(replace(good.exchange[0], law="orifce"),))
    with pytest.raises(SceneError, match=r"exchange\[0\]\.law: .*got 'orifce' \(did you mean 'orifice'\?\)"):
        build_model(typo)
    built = replace(good, _path="")
    with pytest.raises(SceneError, match=r"^<scene built in Python>: ambient\.gas: fractions sum to 0\.5"):
        build_model(replace(built, ambient=replace(built.ambient, gas={"N2": 0.5})))


def test_the_sweep_uses_the_same_validation(tmp_path):
    from cases.sweep.parallel import run_variant

    data = tank()
    data["exchange"][0]["two_way"] = "false"
    record = run_variant(data, tmp_path / "scene.toml", tmp_path / "v1")
    assert record["status"] == "failed"
    assert record["error"].endswith("exchange[0].two_way: expected true or false (a TOML boolean, no quotes), "
                                    "got 'false'")


def test_a_wrapping_body_that_encloses_the_cavity(capsys, tmp_path):
    data = body_scene(tmp_path)
    data["body"][0]["sphere"] = [0.0, 0.0, 0.0, 0.5]
    data["cavity"][0]["wrapped_by"] = ["ball"]
    assert error_line(capsys, tmp_path, data) == (
        "cavity[0].mesh: body 'ball', which the cavity wraps, encloses its whole mesh at t = 0: no volume would be "
        "left (check the body's size and position)")
