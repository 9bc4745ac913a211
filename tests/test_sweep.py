"""Parameter sweeps on Dask: designs, keys, a 12-variant sweep on a 2-worker LocalCluster checked variant by
variant against single runs, a failing variant that does not stop the others, resuming, interrupting."""
import csv
import hashlib
import json
import math
import os
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pyarrow.parquet as pq
import pytest

from cases.cli import main
from cases.scene.errors import SceneError
from cases.run.runner import run_scene
from cases.scene.files import scene_from_dict
from cases.sweep.parallel import _outcomes, figures, plan_sweep, sweep
from cases.sweep.design import (SweepError, apply_variant, lhs_design, make_design, parse_values, resolve_key,
                                variant_id)

ROOT = Path(__file__).resolve().parents[1]

SCENE = """title = "Tank filled by a generator, venting through one orifice"
[time]
end = 0.2
output_interval = 0.002
{solver}
[ambient]
pressure = 1.0e5
temperature = 300.0
gas = {{ N2 = 1.0 }}

[[species]]
name = "N2"
molar_mass = 0.0280134
cp = [29.100619163]

[[cavity]]
name = "tank"
pressure = 1.0e5
temperature = 300.0
gas = {{ N2 = 1.0 }}
volume = 0.06

[[cavity.inflator]]
name = "gen"
type = "mass_temperature"
mass_flow = "data/mdot.csv"   # relative to the scene: must resolve on the workers too
temperature = 600.0
gas = {{ N2 = 1.0 }}

[[exchange]]
name = "vent"
from = "tank"
to = "ambient"
area = 1.0e-4
discharge_coefficient = 0.8
"""

#: 12 variants (area, Cd, generator scale); the 8th has a negative area: it fails, the others must not
VARIANTS = [(a, cd, s) for a in (5e-5, 1e-4, 2e-4) for cd, s in ((0.6, 1.0), (0.8, 1.0), (0.8, 1.5), (1.0, 0.5))]
VARIANTS[7] = (-1e-4, 1.0, 0.5)
KEYS = ("exchange.vent.area", "exchange[0].discharge_coefficient", "cavity.tank.inflator.gen.scale")


def write_case(folder: Path, solver: str = "") -> Path:
    (folder / "data").mkdir(parents=True, exist_ok=True)
    (folder / "data" / "mdot.csv").write_text("time [s],mass flow [kg/s]\n0,0\n0.01,0.5\n0.05,0.5\n0.08,0\n")
    path = folder / "fill_vent.toml"
    path.write_text(SCENE.format(solver=solver))
    return path


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep")
    scene = write_case(folder)
    table = folder / "variants.csv"
    with table.open("w", newline="") as fh:
        csv.writer(fh).writerows([KEYS, *VARIANTS])
    return {"folder": folder, "scene": scene, "variants": table, "out": folder / "out"}


@pytest.fixture(scope="module")
def swept(case):
    """The 12-variant sweep, on a LocalCluster of 2 single-threaded worker processes."""
    rows = []
    res = sweep(case["scene"], out=case["out"], variants=case["variants"], workers=2, progress=False,
                on_row=rows.append)
    return res, rows


# ---------------------------------------------------------------------------------------------- designs, keys

def test_values_and_designs():
    assert parse_values("1e-4,2e-4") == [1e-4, 2e-4]
    assert parse_values("linspace(0.5,0.7,3)") == pytest.approx([0.5, 0.6, 0.7], rel=1e-15)
    *numbers, word = parse_values("geomspace(1,100,3),adiabatic")
    assert numbers == pytest.approx([1.0, 10.0, 100.0], rel=1e-15) and word == "adiabatic"
    full = make_design({"a": "1,2,3", "b": [4, 5]})
    assert len(full) == 6 and full[1] == {"a": 1, "b": 5}
    assert make_design({"a": "1,2,3", "b": "4"}, "list") == [{"a": 1, "b": 4}, {"a": 2, "b": 4}, {"a": 3, "b": 4}]
    with pytest.raises(SweepError, match="every key needs 3 values"):
        make_design({"a": "1,2,3", "b": "4,5"}, "list")
    assert make_design({"a": "1,1,2"}) == [{"a": 1}, {"a": 2}]  # repeated variants run once
    with pytest.raises(SweepError, match=r"linspace\(start,stop,count\)"):
        parse_values("linspace(1,2)")
    with pytest.raises(SweepError, match="either --vary"):
        make_design({}, "full")


def test_variants_file(tmp_path):
    table = tmp_path / "v.csv"
    table.write_text("time.end,exchange.vent.area,solver.method\n0.1,1e-4,RK45\n0.2,,DOP853\n")
    assert make_design(variants=table) == [{"time.end": 0.1, "exchange.vent.area": 1e-4, "solver.method": "RK45"},
                                           {"time.end": 0.2, "solver.method": "DOP853"}]  # empty: the scene's
    table.write_text("time.end,time.end\n0.1,0.2\n")
    with pytest.raises(SweepError, match="distinct"):
        make_design(variants=table)


def test_a_dead_worker_gives_lost_rows_that_run_again(tmp_path):
    from distributed import KilledWorker

    class Worker:
        address, name = "tcp://127.0.0.1:1", "w"

    finished = {"id": "def", "status": "ok", "inputs": {"time.end": 0.2}, "figures": {"tank.peak_pressure [Pa]": 1.0},
                "wall_time [s]": 0.1, "error": ""}
    (tmp_path / "variants" / "def").mkdir(parents=True)
    (tmp_path / "variants" / "def" / "row.json").write_text(json.dumps(finished))
    died = KilledWorker("ventsim-variants-abc", Worker(), 3)
    lost, done = _outcomes(died, [("abc", {"time.end": 0.1}), ("def", {"time.end": 0.2})], tmp_path)
    assert lost["status"] == "lost" and lost["error"].startswith("KilledWorker") and lost["figures"] == {}
    assert done == finished  # finished before its batch's worker died: kept


def test_latin_hypercube_is_seeded_and_stratified():
    a = lhs_design({"x": "0:1", "y": "10,20"}, samples=8, seed=3)
    assert a == lhs_design({"x": "0:1", "y": "10,20"}, samples=8, seed=3)
    assert a != lhs_design({"x": "0:1", "y": "10,20"}, samples=8, seed=4)
    assert sorted(int(r["x"] * 8) for r in a) == list(range(8))  # one sample in each of 8 strata
    assert all(10 <= r["y"] <= 20 for r in a)
    with pytest.raises(SweepError, match="needs numbers"):
        lhs_design({"x": "a,b"}, samples=4)


def test_variant_ids_are_stable_hashes_of_the_inputs():
    assert variant_id({"a": 1, "b": "x"}) == variant_id({"b": "x", "a": 1.0})
    assert variant_id({"a": 1}) != variant_id({"a": 2})
    # the same in every run and on every machine: a hash of the canonical JSON of the inputs
    assert variant_id({"time.end": 0.1}) == hashlib.sha256(b'{"time.end":0.1}').hexdigest()[:12]


def test_keys_address_the_toml_data(case):
    data = tomllib.loads(case["scene"].read_text())
    path = case["scene"]
    assert resolve_key(data, "exchange.vent.area", path) == ("exchange", 0, "area")
    assert resolve_key(data, "exchange[0].area", path) == ("exchange", 0, "area")
    assert resolve_key(data, "cavity.tank.inflator.gen.scale", path) == ("cavity", 0, "inflator", 0, "scale")
    assert resolve_key(data, "solver.rtol", path) == ("solver", "rtol")  # not in the file: the default
    steps = {k: resolve_key(data, k, path) for k in ("time.end", "solver.rtol", "species.N2.cp[0]")}
    new = apply_variant(data, steps, {"time.end": 0.1, "solver.rtol": 1e-6, "species.N2.cp[0]": 30.0})
    assert new["time"]["end"] == 0.1 and new["solver"] == {"rtol": 1e-6} and new["species"][0]["cp"] == [30.0]
    assert data["time"]["end"] == 0.2 and "solver" not in data  # the original is untouched


@pytest.mark.parametrize("key, message", [
    ("exchange.vnet.area", "no [[exchange]] table(s) named 'vnet' (did you mean 'vent'?); names: vent"),
    ("exchange.vent.aera", "unknown key 'aera' (did you mean 'area'?)"),
    ("exchange[3].area", "index 3 out of range: 1 [[exchange]] table(s)"),
    ("tiem.end", "unknown key 'tiem' (did you mean 'time' or 'title'?)"),
    ("time.end.x", "time.end is a value, not a table"),
    ("cavity.tank", "cavity[0] holds a table: address one of its values"),
])
def test_unknown_keys_fail_up_front_with_suggestions(case, key, message):
    with pytest.raises(SceneError) as exc:
        plan_sweep(case["scene"], {key: "1,2"})
    assert str(exc.value).startswith(f"{case['scene']}: {key}: {message}")


def test_cli_bad_key_is_one_line_and_starts_nothing(case, tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["sweep", str(case["scene"]), "--vary", "exchange.vent.aera=1e-4", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ventsim: error: ") and err.count("\n") == 1 and "did you mean 'area'" in err
    assert not out.exists()


# ---------------------------------------------------------------------------------------------- the sweep

def test_every_row_matches_the_variant_run_alone(case, swept):
    res, _ = swept
    assert res.counts == {"ok": 11, "failed": 1, "lost": 0} and (res.ran, res.skipped) == (12, 0)
    data = tomllib.loads(case["scene"].read_text())
    steps = {k: resolve_key(data, k, case["scene"]) for k in KEYS}
    for row, values in zip(res.rows, VARIANTS, strict=True):
        inputs = dict(zip(KEYS, values))
        assert row["id"] == variant_id(inputs) and {k: row[k] for k in KEYS} == inputs
        if row["status"] == "failed":
            continue
        alone = run_scene(scene_from_dict(apply_variant(data, steps, inputs), case["scene"]))
        expected = figures(alone)
        assert {k: row[k] for k in expected} == expected  # identical, not close
        assert expected["tank.peak_pressure [Pa]"] > 1.2e5 and expected["vent.min_area [m^2]"] == values[0]
    peaks = {r["tank.peak_pressure [Pa]"] for r in res.rows if r["status"] == "ok"}
    assert len(peaks) == 11  # every variant is a different run


def test_a_bad_value_fails_its_variant_only(case, swept):
    res, _ = swept
    (bad,) = res.failed
    assert bad["exchange.vent.area"] == -1e-4 and bad["status"] == "failed"
    assert bad["error"] == f"{case['scene'].resolve()}: exchange[0].area: expected a number >= 0 [m^2], got -0.0001"
    folder = case["out"] / "variants" / bad["id"]
    assert sorted(p.name for p in folder.iterdir()) == ["row.json"]
    ok = [r for r in res.rows if r["status"] == "ok"]
    assert len(ok) == 11
    for r in ok:
        folder = case["out"] / "variants" / r["id"]
        assert sorted(p.name for p in folder.iterdir()) == ["history.csv", "row.json", "summary.json"]
        summary = json.loads((folder / "summary.json").read_text())
        assert summary["cavities"]["tank"]["peak pressure [Pa]"] == r["tank.peak_pressure [Pa]"]
        assert summary["variant"]["id"] == r["id"]


def test_result_files_hold_every_row_exactly(case, swept):
    res, arrived = swept
    assert sorted(r["id"] for r in arrived) == sorted(r["id"] for r in res.rows)
    with (case["out"] / "results.csv").open(newline="") as fh:
        table = list(csv.DictReader(fh))
    parquet = pq.read_table(case["out"] / "results.parquet").to_pylist()
    assert [r["id"] for r in table] == [r["id"] for r in parquet] == [r["id"] for r in res.rows]
    for row, from_csv, from_pq in zip(res.rows, table, parquet, strict=True):
        for col, value in row.items():
            if isinstance(value, float):
                assert float(from_csv[col]) == from_pq[col] == value, col
            elif value is None:
                assert from_csv[col] == "" and from_pq[col] is None
            else:
                assert from_csv[col] == from_pq[col] == value, col
        assert row["wall_time [s]"] > 0
    png = (case["out"] / "sweep.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    assert not [p for p in case["out"].rglob(".*") if p.name != ".sweep.lock"]  # no temporary files left behind


def test_rerunning_the_command_skips_finished_variants(case, swept, capsys):
    marks = {p: p.stat().st_mtime_ns for p in (case["out"] / "variants").glob("*/row.json")}
    argv = ["sweep", str(case["scene"]), "--variants", str(case["variants"]), "--out", str(case["out"])]
    assert main(argv) == 1  # one variant failed (and stays failed: a bad value)
    assert "12 variants: 11 ok, 1 failed (0 run now, 12 finished before)" in capsys.readouterr().out
    assert {p: p.stat().st_mtime_ns for p in marks} == marks


def test_another_scene_in_the_same_folder_is_refused(case, swept, tmp_path):
    other = write_case(tmp_path, solver="[solver]\nrtol = 1e-6")
    with pytest.raises(SweepError, match="holds a sweep of another scene"):
        sweep(other, {"time.end": "0.1"}, out=case["out"], workers=1, progress=False)


# ---------------------------------------------------------------------------------------------- interrupt

CHILD = """import signal, sys
signal.signal(signal.SIGINT, signal.default_int_handler)  # even if started with SIGINT ignored
from cases.cli import main
sys.exit(main(sys.argv[1:]))
"""


def test_interrupted_sweep_resumes_with_the_remaining_variants_only(tmp_path):
    from dask.distributed import LocalCluster

    scene = write_case(tmp_path, solver="[solver]\nmethod = \"RK45\"   # scipy's RK45 on the engine\nmax_step = 1e-4")
    vary = ["--vary", "exchange.vent.area=5e-5,1e-4,2e-4,4e-4", "--vary", "cavity.tank.inflator.gen.scale=0.5,1,2"]
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-c", CHILD, "sweep", str(scene), *vary, "--out", str(out),
                             "--workers", "2", "--quiet"], cwd=ROOT, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 40
    while len(list(out.glob("variants/*/row.json"))) < 2 and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        raise
    assert proc.returncode == 130 and "ventsim: interrupted" in err, err
    finished = {p.parent.name: p.stat().st_mtime_ns for p in out.glob("variants/*/row.json")}
    assert 2 <= len(finished) < 12
    # resume on an existing scheduler (the --scheduler path), two variants per task
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        res = sweep(scene, {"exchange.vent.area": "5e-5,1e-4,2e-4,4e-4", "cavity.tank.inflator.gen.scale": "0.5,1,2"},
                    out=out, scheduler=cluster.scheduler_address, batch=2, progress=False, plot=False)
    assert (res.ran, res.skipped) == (12 - len(finished), len(finished))
    assert res.counts["ok"] == 12 and len({r["id"] for r in res.rows}) == 12
    assert {i: (out / "variants" / i / "row.json").stat().st_mtime_ns for i in finished} == finished
    assert all(math.isfinite(r["tank.peak_pressure [Pa]"]) for r in res.rows)
    assert os.path.getsize(out / "results.csv") > 0
