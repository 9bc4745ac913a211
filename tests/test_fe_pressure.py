"""The FE run's control-volume pressure (ASCII abstat) read in SI and drawn over ventsim's."""
import numpy as np
import pytest

from cases.results.fe_pressure import read_abstat
from cases.scene.errors import SceneError
from tests.test_fe_sampling import plate_data
from tests.toml_write import dumps


def write_abstat(path, times, pressures):
    """An ASCII abstat as LS-DYNA's binout translator writes it: a title, then per state a header line and one row
    per airbag (time, airbag number, volume, pressure, internal energy, ...)."""
    lines = [" airbag test", "                         ls-dyna (version R13)     date 01/01/2026"]
    for t, ps in zip(times, pressures):
        lines += ["", "", "      time   airbag/cv #  volume        pressure    internal energy      dm/dt in      "
                  "density dm/dt out  total mass gas temp. surface area   reaction"]
        for n, p in enumerate(ps, start=1):
            lines.append(f"{t:12.5E}{n:8d}{5.7e4:15.4E}{p:15.4E}{1.0:15.4E}{0.0:15.4E}{1.2e-9:15.4E}"
                         f"{0.0:11.3E}{1e-5:11.3E}{300.0:11.3E}{1e4:11.3E}{0.0:11.3E}")
    path.write_text("\n".join(lines) + "\n")


def test_an_ascii_abstat_is_read_per_airbag_in_si(tmp_path):
    times = np.array([0.0, 1.0, 2.0, 3.0])  # ms
    pressures = np.array([[1.0e-4, 2.0e-4], [1.5e-4, 2.5e-4], [1.2e-4, 2.2e-4], [1.1e-4, 2.1e-4]])  # GPa
    write_abstat(tmp_path / "abstat", times, pressures)
    found = read_abstat(tmp_path / "abstat", "mm-kg-ms")
    assert sorted(found) == [1, 2]
    np.testing.assert_allclose(found[1].times, times * 1e-3, rtol=1e-12)
    np.testing.assert_allclose(found[2].pressures, pressures[:, 1] * 1e9, rtol=1e-4)  # 5 digits in the file
    assert found[1].peak() == pytest.approx((1.5e5, 1e-3), rel=1e-4)
    (tmp_path / "empty").write_text("nothing here\n")
    with pytest.raises(SceneError, match=r"no airbag pressure rows"):
        read_abstat(tmp_path / "empty")


def test_compare_and_history_png_show_the_fe_runs_pressure(tmp_path):
    from cases.cli import main
    from cases.run.compare_command import compare

    write_abstat(tmp_path / "abstat", [0.0, 0.01, 0.02, 0.03], [[2.0e5], [2.1e5], [1.9e5], [1.8e5]])
    data = plate_data(tmp_path)
    data["fe_run"] = {"abstat": "abstat", "airbags": {"tank": 1}}
    (tmp_path / "scene.toml").write_text(dumps(data))
    done = compare(tmp_path / "scene.toml", ["exact", "abaqus"], tmp_path / "cmp", step=1e-3)
    fe = done["rows"][-1]
    assert fe["rule"] == "FE run (abstat)" and fe["tank peak pressure [Pa]"] == pytest.approx(2.1e5)
    assert fe["tank peak pressure time [s]"] == pytest.approx(0.01)
    assert main(["run", str(tmp_path / "scene.toml"), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    assert (tmp_path / "run" / "history.png").stat().st_size > 0
    data["fe_run"]["abstat"] = "missing"
    (tmp_path / "scene.toml").write_text(dumps(data))
    assert main(["run", str(tmp_path / "scene.toml"), "--out", str(tmp_path / "run2"), "--quiet"]) == 2
