"""Bad scenes fail with one line naming the file and the key, never a traceback."""
import shutil
import subprocess
import sys

import pytest
import trimesh

from cases.cli import main

FILL = "fill_constant.toml"
MESH = "compression_mesh.toml"


@pytest.fixture
def case(tmp_path, verification_dir):
    """Copy the verification folder and return a function that writes an edited scene into it."""
    for f in verification_dir.iterdir():
        shutil.copy(f, tmp_path / f.name)

    def edit(name, old, new):
        text = (tmp_path / name).read_text()
        assert old in text, old
        path = tmp_path / f"edited_{name}"
        path.write_text(text.replace(old, new))
        return path

    return edit


def error_of(capsys, scene, tmp_path):
    code = main(["run", str(scene), "--out", str(tmp_path / "out"), "--quiet"])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert "Traceback" not in err
    assert len(err.splitlines()) == 1, err
    assert str(scene) in err  # names the file
    return err


def test_typo_in_key_suggests_the_right_one(case, capsys, tmp_path):
    err = error_of(capsys, case(FILL, "temperature = 300.0     # [K]\ngas = { N2 = 1.0 }\nvolume",
                                "temprature = 300.0\ngas = { N2 = 1.0 }\nvolume"), tmp_path)
    assert "cavity[0].temprature" in err and "did you mean 'temperature'" in err


def test_missing_csv_names_the_key(case, capsys, tmp_path):
    err = error_of(capsys, case(FILL, '"inflator_constant.csv"', '"no_such_table.csv"'), tmp_path)
    assert "cavity[0].inflator[0].mass_flow" in err and "no_such_table.csv" in err and "does not exist" in err


def test_nan_in_table_names_the_row(case, capsys, tmp_path):
    (tmp_path / "nan.csv").write_text("time [s],mass flow [kg/s]\n0.0,0.5\n0.5,nan\n1.0,0.5\n")
    err = error_of(capsys, case(FILL, '"inflator_constant.csv"', '"nan.csv"'), tmp_path)
    assert "mass_flow" in err and "nan.csv line 3" in err and "NaN" in err


def test_unsorted_times_are_rejected(case, capsys, tmp_path):
    (tmp_path / "unsorted.csv").write_text("time [s],mass flow [kg/s]\n0.0,0.5\n0.5,0.4\n0.2,0.5\n")
    err = error_of(capsys, case(FILL, '"inflator_constant.csv"', '"unsorted.csv"'), tmp_path)
    assert "mass_flow" in err and "strictly increasing" in err and "rows 2 and 3" in err


def test_inside_out_mesh_says_normals_point_inwards(case, capsys, tmp_path):
    mesh = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
    mesh.invert()
    mesh.export(tmp_path / "inside_out.ply")
    err = error_of(capsys, case(MESH, '"sphere_r200mm.ply"', '"inside_out.ply"'), tmp_path)
    assert "cavity[0].mesh" in err and "inwards" in err


def test_open_mesh_is_rejected(case, capsys, tmp_path):
    mesh = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
    mesh.update_faces(mesh.faces[:, 0] != 0)
    mesh.export(tmp_path / "open.ply")
    err = error_of(capsys, case(MESH, '"sphere_r200mm.ply"', '"open.ply"'), tmp_path)
    assert "cavity[0].mesh" in err and "not closed" in err


def test_unknown_section_and_bad_choice(case, capsys, tmp_path):
    err = error_of(capsys, case(FILL, "[solver]", "[solvr]"), tmp_path)
    assert "solvr" in err and "did you mean 'solver'" in err
    err = error_of(capsys, case(FILL, 'type = "mass_temperature"', 'type = "mass_temprature"'), tmp_path)
    assert "inflator[0].type" in err and "did you mean 'mass_temperature'" in err


def test_negative_and_wrongly_typed_values(case, capsys, tmp_path):
    err = error_of(capsys, case(FILL, "volume = 0.06", "volume = -0.06"), tmp_path)
    assert "cavity[0].volume" in err and ">= 0" in err
    err = error_of(capsys, case(FILL, "pressure = 1.0e5        # [Pa]\ntemperature = 300.0     # [K]\n"
                                      "gas = { N2 = 1.0 }\nvolume", 'pressure = "high"\ntemperature = 300.0\n'
                                                                   "gas = { N2 = 1.0 }\nvolume"), tmp_path)
    assert "cavity[0].pressure" in err and "expected a number" in err


def test_a_relative_tolerance_below_the_machine_precision_names_its_key(case, capsys, tmp_path):
    """rtol 1e-300 made the compiled DOP853 divide by zero (a fuzz find): it is refused at load."""
    err = error_of(capsys, case(FILL, "rtol = 1e-8", "rtol = 1e-300"), tmp_path)
    assert "solver.rtol" in err and "2.22e-14 <= rtol < 1" in err


def test_exchange_to_unknown_cavity(case, capsys, tmp_path, verification_dir):
    err = error_of(capsys, case("blowdown_choked.toml", 'to = "ambient"', 'to = "ambiant"'), tmp_path)
    assert "exchange[0].to" in err and "did you mean 'ambient'" in err


def test_console_script_prints_one_line(case, tmp_path):
    scene = case(FILL, "[solver]", "[solvr]")
    proc = subprocess.run([sys.executable, "-m", "cases.cli", "run", str(scene), "--out", str(tmp_path / "o")],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
