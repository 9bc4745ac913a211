"""`ventsim compare`: every rule in one command, its table, pictures and the sweep over the step."""
import csv
import subprocess
import sys

import pytest

from tests.conftest import ROOT
from tests.test_fe_sampling import plate_data
from tests.toml_write import dumps


def compare_cli(*args):
    return subprocess.run([sys.executable, "-m", "cases.cli", "compare", *map(str, args)], cwd=ROOT,
                          capture_output=True, text=True)


def test_compare_writes_the_table_the_pictures_and_a_sweep_that_converges_linearly(tmp_path):
    (tmp_path / "scene.toml").write_text(dumps(plate_data(tmp_path)))
    out = compare_cli(tmp_path / "scene.toml", "--rules", "radioss,lsdyna_cpg", "--step", "5e-4",
                      "--sweep", "2e-3,1e-3,5e-4,2.5e-4", "--out", tmp_path / "out", "--quiet")
    assert out.returncode == 0, out.stderr
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"compare.csv", "compare.png", "sweep.csv", "sweep.png", "faces_vent_radioss.png",
            "faces_vent_lsdyna_cpg.png"} <= names
    rows = list(csv.DictReader(open(tmp_path / "out" / "compare.csv")))
    assert [r["rule"] for r in rows] == ["exact", "radioss", "lsdyna_cpg"]
    assert float(rows[0]["|A - A_exact| area*time [m^2 s]"]) == 0.0
    assert float(rows[1]["lag [cycles]"]) == 1 and float(rows[1]["step [s]"]) == 5e-4
    assert float(rows[2]["blocked area*time [m^2 s]"]) > float(rows[1]["blocked area*time [m^2 s]"])  # elements
    assert "radioss" in out.stdout and "blocked area" in out.stdout  # printed too
    sweep = [r for r in csv.DictReader(open(tmp_path / "out" / "sweep.csv")) if r["rule"] == "radioss"]
    steps = [float(r["step [s]"]) for r in sweep]
    dist = [float(r["|A - A_exact| area*time [m^2 s]"]) for r in sweep]
    assert steps == sorted(steps, reverse=True)
    for (s0, d0), (s1, d1) in zip(zip(steps, dist), zip(steps[1:], dist[1:])):
        assert d1 <= d0 * (s1 / s0) * 1.5  # at least first order


def test_compare_errors_are_one_line(tmp_path):
    (tmp_path / "scene.toml").write_text(dumps(plate_data(tmp_path)))
    bad = compare_cli(tmp_path / "scene.toml", "--rules", "radioss", "--out", tmp_path / "o")
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "blockage.step" in bad.stderr
    bad = compare_cli(tmp_path / "scene.toml", "--rules", "radiosss", "--step", "1e-4", "--out", tmp_path / "o")
    assert bad.returncode == 2 and "did you mean 'radioss'" in bad.stderr
