"""`ventsim run` writes history.csv, summary.json and history.png, atomically."""
import json

import numpy as np

from cases.cli import main


def test_run_writes_three_outputs(tmp_path, verification_dir):
    out = tmp_path / "out"
    assert main(["run", str(verification_dir / "fill_constant.toml"), "--out", str(out), "--quiet"]) == 0
    header = (out / "history.csv").read_text().splitlines()[0].split(",")
    assert header == ["time [s]", "tank.pressure [Pa]", "tank.gauge_pressure [Pa]", "tank.temperature [K]",
                      "tank.mass [kg]", "tank.volume [m^3]", "tank.generator.mass_flow [kg/s]",
                      "tank.generator.temperature [K]"]
    data = np.loadtxt(out / "history.csv", delimiter=",", skiprows=1)
    assert data[0, 0] == 0.0 and abs(data[-1, 0] - 0.1) < 1e-15
    summary = json.loads((out / "summary.json").read_text())
    assert summary["cavities"]["tank"]["peak pressure [Pa]"] == data[:, 1].max()
    assert summary["solver"]["steps"] > 0 and summary["solver"]["rhs_calls"] > summary["solver"]["steps"]
    assert summary["modelled"]["cavities"]["tank"]["energy"] == "adiabatic"
    png = (out / "history.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    assert not list(out.glob(".*"))  # no temporary files left behind


def test_exchange_columns(tmp_path, verification_dir):
    out = tmp_path / "o"
    main(["run", str(verification_dir / "blowdown_choked.toml"), "--out", str(out), "--quiet"])
    header = (out / "history.csv").read_text().splitlines()[0].split(",")
    assert header[-3:] == ["vent.mass_flow [kg/s]", "vent.area [m^2]", "vent.blocked_fraction [-]"]
    data = np.loadtxt(out / "history.csv", delimiter=",", skiprows=1)
    assert np.all(data[:, -3] > 0) and np.all(data[:, -2] == 1e-4) and np.all(data[:, -1] == 0.0)


def test_failed_write_keeps_previous_file(tmp_path):
    from cases.results.output import atomic_path

    target = tmp_path / "summary.json"
    target.write_text("old")
    try:
        with atomic_path(target) as tmp:
            tmp.write_text("partial")
            raise RuntimeError("disk full")
    except RuntimeError:
        pass
    assert target.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["summary.json"]
