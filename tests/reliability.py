"""Helpers of the reliability tests (issue 14): a small tank scene as data, written as TOML and run by the CLI."""
from __future__ import annotations

import copy

from cases.cli import main

from .toml_write import dumps

TANK = {"time": {"end": 0.05},
        "ambient": {"pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0}},
        "species": [{"name": "N2", "molar_mass": 0.0280134, "cp": [29.1]}],
        "cavity": [{"name": "tank", "pressure": 3.0e5, "temperature": 300.0, "gas": {"N2": 1.0}, "volume": 0.01}],
        "exchange": [{"name": "vent", "from": "tank", "area": 1e-4}]}


def tank(**top) -> dict:
    """A copy of the tank scene with top-level tables replaced or added."""
    data = copy.deepcopy(TANK)
    data.update(copy.deepcopy(top))
    return data


def write(folder, data: dict, name: str = "scene.toml"):
    path = folder / name
    path.write_text(dumps(data))
    return path


def run_cli(capsys, scene, out, *extra) -> tuple:
    """(exit code, stderr lines) of ``ventsim run scene --out out --quiet``."""
    code = main(["run", str(scene), "--out", str(out), "--quiet", *extra])
    return code, capsys.readouterr().err.strip().splitlines()


def error_line(capsys, folder, data: dict) -> str:
    """The one error line of running ``data`` (asserts: exit 2, one line, the file named, no traceback)."""
    scene = write(folder, data)
    code, err = run_cli(capsys, scene, folder / "out")
    assert code == 2, err
    assert len(err) == 1 and "Traceback" not in err[0], err
    assert err[0].startswith(f"ventsim: error: {scene}: "), err
    return err[0][len(f"ventsim: error: {scene}: "):]
