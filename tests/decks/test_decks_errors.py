"""Bad decks stop with one line naming the file, the line and the keyword; harmless unknown keywords are listed
once as ignored; an M3D4R membrane deck runs (meshio would end the process on it)."""
from __future__ import annotations

import re

import pytest

from cases.cli import main
from cases.decks import deck_scene, import_deck
from cases.scene.errors import SceneError
from cases.run.library import column_errors
from cases.run.runner import run_scene

from .box_decks import BOX, head, write

STEM = head("test deck") + """*INITIAL CONDITIONS, TYPE=FLUID PRESSURE
 REF, 4.0e5
*INITIAL CONDITIONS, TYPE=TEMPERATURE
 REF, 300.
*FLUID EXCHANGE PROPERTY, NAME=ORI, TYPE=ORIFICE
 1.0
*FLUID EXCHANGE, NAME=VENT, PROPERTY=ORI, EFFECTIVE AREA=1.0e-4
 REF
*STEP
*DYNAMIC, EXPLICIT
 , 0.05
*FLUID EXCHANGE ACTIVATION
 VENT
*END STEP
"""


def error_of(path, units="SI"):
    with pytest.raises(SceneError) as info:
        import_deck(path, units)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_unknown_keyword_is_listed_once_and_does_not_stop_the_run(tmp_path):
    deck = write(tmp_path, STEM.replace("*STEP", "*FOO BAR, X=1\n 1, 2\n*FOO BAR\n*STEP"))
    imported = import_deck(deck)
    assert [i for i in imported.ignored if "FOO" in i] == ["ignored: *FOO BAR (line 27)"]


def test_broken_data_line(tmp_path):
    deck = write(tmp_path, STEM.replace(" 100, 0.25, 0.2, 0.15", " 100, 0.25, 0.2O, 0.15"))
    assert error_of(deck) == f"{deck}: line 9: *NODE: expected a number, got '0.2O'"


def test_missing_include(tmp_path):
    deck = write(tmp_path, STEM.replace("INPUT=box_mesh.inp", "INPUT=box_mesh2.inp"))
    assert error_of(deck) == f"{deck}: line 7: *INCLUDE: the file 'box_mesh2.inp' does not exist"


def test_error_in_an_included_file_names_that_file(tmp_path):
    deck = write(tmp_path, STEM, mesh=BOX.replace(" 6, 4, 8, 5, 1", " 6, 4, 8, 5"))
    assert error_of(deck) == f"{tmp_path / 'box_mesh.inp'}: line 18: *ELEMENT: element 6 of type SFM3D4R needs 4 " \
                             "nodes, got 3"


def test_undefined_parameter(tmp_path):
    deck = write(tmp_path, STEM.replace("LZ = 0.3", "LZ = LQ * 2"))
    assert error_of(deck) == f"{deck}: line 6: *PARAMETER: unknown parameter 'LQ'"


def test_unknown_reference_suggests_the_name(tmp_path):
    deck = write(tmp_path, STEM.replace("PROPERTY=ORI,", "PROPERTY=ORIF,"))
    assert error_of(deck) == (f"{deck}: line 25: *FLUID EXCHANGE: PROPERTY=ORIF: no *FLUID EXCHANGE PROPERTY of that "
                              "name (did you mean 'ORI'?)")


def test_inward_normals_are_an_error_at_the_cavity(tmp_path):
    deck = write(tmp_path, STEM.replace(" BOX, SPOS", " BOX, SNEG"))
    message = error_of(deck)
    assert message.startswith(f"{deck}: line 18: *FLUID CAVITY: ") and "volume" in message


def test_solid_element_faces_are_refused(tmp_path):
    solid = "*ELEMENT, TYPE=C3D8R, ELSET=BRICK\n 9, 1, 2, 3, 4, 5, 6, 7, 8\n"
    deck = write(tmp_path, STEM.replace("*SURFACE, NAME=WALL\n BOX, SPOS", solid + "*SURFACE, NAME=WALL\n BRICK, S1"))
    assert error_of(deck) == (f"{deck}: line 13: *SURFACE: WALL: face S1 of element 9: ventsim reads shell, "
                              "membrane and surface-element faces (SPOS, SNEG) only")


def test_a_solid_surface_ventsim_does_not_need_is_no_error(tmp_path):
    solid = "*ELEMENT, TYPE=C3D8R, ELSET=BRICK\n 9, 1, 2, 3, 4, 5, 6, 7, 8\n*SURFACE, NAME=IMPACTOR\n BRICK, S1\n"
    imported = import_deck(write(tmp_path, STEM.replace("*SURFACE, NAME=WALL", solid + "*SURFACE, NAME=WALL")))
    assert imported.data["cavity"][0]["mesh"] == "deck/cavity_tank.obj"
    assert "ignored: *ELEMENT, TYPE=C3D8R (line 10): not a surface element (no cavity, vent or blocker)" in \
        imported.ignored


def test_second_step_is_refused(tmp_path):
    deck = write(tmp_path, STEM + "*STEP\n*DYNAMIC, EXPLICIT\n , 0.1\n*END STEP\n")
    assert error_of(deck) == f"{deck}: line 33: *STEP: a second step (the first is at line 27): ventsim reads one step"


def test_unknown_units(tmp_path):
    deck = write(tmp_path, STEM)
    assert error_of(deck, "furlong") == f"{deck}: unknown --units 'furlong'; known: SI, mm-t-s, mm-kg-ms"


def test_m3d4r_membrane_deck_runs(tmp_path):
    membrane = BOX.replace("SFM3D4R", "M3D4R")
    deck = write(tmp_path, STEM.replace("*PHYSICAL", "*MEMBRANE SECTION, ELSET=BOX, MATERIAL=FABRIC\n 0.0003\n"
                                                  "*PHYSICAL"), mesh=membrane)
    scene, imported = deck_scene(deck, tmp_path / "out" / "scene.toml")
    assert imported.ignored == ["ignored: *MEMBRANE SECTION (line 12)"]
    r = run_scene(scene)
    assert abs(r.column("tank.volume")[0] - 0.06) <= 1e-15


def test_cli_prints_one_line_and_returns_2(tmp_path, capsys):
    deck = write(tmp_path, STEM.replace(" , 0.05", " , soon"))
    assert main(["run", str(deck), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"ventsim: error: {deck}: line 29: *DYNAMIC: expected a number for the time period, got 'soon'"]


def test_cli_import_writes_the_scene(tmp_path, capsys):
    deck = write(tmp_path, STEM)
    assert main(["import", str(deck), "--out", str(tmp_path / "scene.toml"), "--quiet"]) == 0
    assert (tmp_path / "scene.toml").is_file() and (tmp_path / "deck" / "cavity_tank.obj").is_file()


def _mm_t_s(text):
    """The same deck in mm, tonne, s: lengths ×1e3, pressures ×1e-6 (MPa), areas ×1e6, molar masses and
    energies per mol: kg -> t (×1e-3), J -> mJ (×1e3)."""
    text = text.replace("LX = 0.5", "LX = 500.").replace("LY = 0.4", "LY = 400.").replace("LZ = 0.3", "LZ = 300.")
    text = text.replace(" 100, 0.25, 0.2, 0.15", " 100, 250., 200., 150.")
    text = text.replace("8.314462618", "8314.462618").replace("0.0280134", "2.80134e-5")
    text = text.replace("29.100619163", "29100.619163").replace("AMBIENT PRESSURE=1.0e5", "AMBIENT PRESSURE=0.1")
    return text.replace(" REF, 4.0e5", " REF, 0.4").replace("EFFECTIVE AREA=1.0e-4", "EFFECTIVE AREA=100.")


def test_units_mm_t_s_give_the_si_history(tmp_path):
    si = run_scene(deck_scene(write(tmp_path, STEM), tmp_path / "si" / "s.toml")[0])
    mm_deck = write(tmp_path, _mm_t_s(STEM), name="mm.inp")
    mm = run_scene(deck_scene(mm_deck, tmp_path / "mm" / "s.toml", "mm-t-s")[0])
    assert max(column_errors(mm.columns, mm.history, si.columns, si.history).values()) <= 1e-9
    assert re.search("LX = 500", mm_deck.read_text())


def test_parameter_expressions_with_functions(tmp_path):
    deck = write(tmp_path, STEM.replace("LZ = 0.3", "LZ = sqrt(0.09) * cos(0.0)"))
    r = run_scene(deck_scene(deck, tmp_path / "o" / "s.toml")[0])
    assert abs(r.column("tank.volume")[0] / 0.06 - 1) <= 1e-14


def test_cli_run_reports_the_ignored_keywords_in_summary(tmp_path, capsys):
    import json

    deck = write(tmp_path, STEM.replace("*STEP", "*MATERIAL, NAME=X\n*STEP"))
    assert main(["run", str(deck), "--out", str(tmp_path / "out")]) == 0
    assert "ventsim: deck.inp: ignored: *MATERIAL (line 27)" in capsys.readouterr().err.splitlines()
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["modelled"]["deck"]["ignored"] == ["ignored: *MATERIAL (line 27)"]
    assert (tmp_path / "out" / "scene" / "deck.toml").is_file()


def test_blanks_case_and_abbreviations_on_keyword_lines(tmp_path):
    """'Blanks on a keyword line are ignored', keywords and parameters are not case sensitive and keywords may be
    abbreviated (Analysis User's Guide, "Input syntax rules"): the deck below is the STEM deck."""
    text = STEM.replace("*FLUID CAVITY, NAME=TANK, BEHAVIOR=N2, REF NODE=REF, SURFACE=WALL, ADIABATIC, AMBIENT "
                        "PRESSURE=1.0e5", "*fluidcavity, name = tank, behavior=n2, refnode=ref, surface=wall, "
                        "adiabatic, ambientpressure=1.0e5")
    text = text.replace("*INITIAL CONDITIONS, TYPE=FLUID PRESSURE", "*Initial Cond, type=FluidPressure")
    text = text.replace("*FLUID EXCHANGE ACTIVATION", "*Fluid Exchange Activ")
    assert text != STEM
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    assert import_deck(write(tmp_path / "a", text)).data == import_deck(write(tmp_path / "b", STEM)).data


def test_cli_import_with_units(tmp_path):
    deck = write(tmp_path, _mm_t_s(STEM), name="mm.inp")
    assert main(["import", str(deck), "--out", str(tmp_path / "mm.toml"), "--units", "mm-t-s", "--quiet"]) == 0
    import tomllib

    data = tomllib.loads((tmp_path / "mm.toml").read_text())
    assert data["cavity"][0]["pressure"] == pytest.approx(5e5, rel=1e-15)
    assert data["exchange"][0]["area"] == pytest.approx(1e-4, rel=1e-15)
