"""Issue 14: one sweep at a time per folder, results.csv current after every variant, a per-variant time limit."""
import csv

import pytest

from cases.sweep.parallel import run_variant, sweep
from cases.sweep.design import SweepError
from cases.sweep.folder import folder_lock
from cases.sweep.plot import ResultsTable
from tests.reliability import tank, write


def test_a_second_sweep_into_a_locked_folder_fails_at_once(tmp_path):
    scene, out = write(tmp_path, tank()), tmp_path / "sweep"
    with folder_lock(out.resolve()):
        with pytest.raises(SweepError, match=r"another sweep is writing this folder \(pid \d+\): wait for it or "
                                             r"choose another --out"):
            sweep(scene, {"exchange.vent.area": [1e-4, 2e-4]}, out=out, progress=False, plot=False)


def test_results_csv_is_current_after_every_variant(tmp_path):
    table = ResultsTable(tmp_path, ("a",), ["v1", "v2", "v3"], {}, every=1e9)
    for k, vid in enumerate(["v1", "v2", "v3"], start=1):
        table.add({"id": vid, "status": "ok", "inputs": {"a": k}, "figures": {"x [-]": 2.0 * k},
                   "wall_time [s]": 0.1, "error": ""})
        with (tmp_path / "results.csv").open() as fh:
            rows = list(csv.DictReader(fh))
        assert [r["id"] for r in rows] == ["v1", "v2", "v3"][:k]
        assert [float(r["x [-]"]) for r in rows] == [2.0 * i for i in range(1, k + 1)]


def test_a_variant_over_its_time_limit_is_a_failed_variant(tmp_path):
    record = run_variant(tank(), tmp_path / "scene.toml", tmp_path / "v1", {"k": 1}, timeout=1e-9)
    assert record["status"] == "failed"
    assert "the run stopped: " in record["error"] and "more than max_wall = 1e-09 s" in record["error"]
    assert (tmp_path / "v1" / "row.json").is_file()


def test_a_variant_cleans_the_temp_files_of_a_killed_writer(tmp_path):
    (tmp_path / "v1").mkdir()
    (tmp_path / "v1" / ".history.csv.a1b2.csv").write_text("partial")
    (tmp_path / "v1" / ".row.json.c3d4.json").write_text("{")
    assert run_variant(tank(), tmp_path / "scene.toml", tmp_path / "v1")["status"] == "ok"
    assert sorted(p.name for p in (tmp_path / "v1").iterdir()) == ["history.csv", "row.json", "summary.json"]
