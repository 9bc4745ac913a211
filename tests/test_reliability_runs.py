"""Issue 14: runs are bounded, fail in one line with what they had, write their outputs as one set, warn instead of
clamping silently; pop vents armed above their pressure open at t = 0; the orifice join is a switch."""
import json
from dataclasses import replace

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.runner import RunError, run
from cases.scene.files import scene_from_dict
from tests.reliability import run_cli, tank, write


def model(tmp_path, data):
    return build_model(scene_from_dict(data, tmp_path / "scene.toml"))


# ---------------------------------------------------------------------------------------------- bounded runs

def stiff_scene() -> dict:
    """A 1e-9 m^3 cavity fed 1 g/s with a 100 m^2 pop vent: stiff for an explicit method."""
    data = tank(limits={"steps": 3000})
    data["cavity"][0].update(volume=1e-9, pressure=1e5)
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": 1e-3,
                                      "temperature": 300.0, "gas": {"N2": 1.0}}]
    data["exchange"][0].update(area=100.0, pop_pressure=1e4)
    data["units"] = {"unchecked": ["exchange[0].area"]}  # 100 m^2 on 1 mm^3 is meant: what makes it stiff
    return data


def test_a_stiff_scene_stops_with_the_method_to_use(capsys, tmp_path):
    code, err = run_cli(capsys, write(tmp_path, stiff_scene()), tmp_path / "out")
    assert code == 2 and len(err) == 1
    assert "the run stopped: more than 3000 steps before t = " in err[0]
    assert "the scene is stiff here (its fastest time scale, " in err[0]
    assert "for the explicit method 'DOP853': set [solver] method = 'Radau' (or 'LSODA')" in err[0]


def test_a_step_budget_on_a_scene_that_is_not_stiff_does_not_advise_radau(capsys, tmp_path):
    code, err = run_cli(capsys, write(tmp_path, tank(limits={"steps": 3}, solver={"method": "RK45"})),
                        tmp_path / "out")
    assert code == 2 and "more than 3 steps before t = " in err[0]
    assert "Radau" not in err[0] and "the scene is not stiff here (fastest time scale " in err[0]


def test_a_failed_run_writes_what_it_had(capsys, tmp_path):
    code, err = run_cli(capsys, write(tmp_path, stiff_scene()), tmp_path / "out")
    assert code == 2 and err[0].endswith(f"(wrote what it had into {tmp_path / 'out'})")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["error"].startswith("more than 3000 steps before t = ")
    h = np.loadtxt(tmp_path / "out" / "history.csv", delimiter=",", skiprows=1, ndmin=2)
    assert h[0, 0] == 0.0 and h[-1, 0] <= summary["stopped at [s]"] < 0.05 and np.all(np.isfinite(h))


def test_max_wall_stops_a_run(capsys, tmp_path):
    code, err = run_cli(capsys, write(tmp_path, tank()), tmp_path / "out", "--max-wall", "1e-9")
    assert code == 2 and "the run stopped: " in err[0] and "more than max_wall = 1e-09 s" in err[0]


def test_max_wall_on_scipys_methods_stops_between_steps(tmp_path):
    m = model(tmp_path, tank(solver={"method": "RK45"}))
    with pytest.raises(RunError, match=r"more than max_wall = 1e-09 s of wall time before t = "):
        run(m, max_wall=1e-9)


def test_an_extreme_discharge_coefficient_is_one_line(capsys, tmp_path):
    data = tank()
    data["exchange"][0]["discharge_coefficient"] = 1e300
    code, err = run_cli(capsys, write(tmp_path, data), tmp_path / "out")
    assert code == 2 and err == [f"ventsim: error: {tmp_path / 'scene.toml'}: exchange[0].discharge_coefficient: "
                                 "1e+300 is above 10: a discharge coefficient is at most about 1 (the ideal flow); "
                                 "if it is meant, add 'exchange[0].discharge_coefficient' to [units] unchecked (or "
                                 "set [units] check = false)"]
    data["units"] = {"unchecked": ["exchange[0].discharge_coefficient"]}  # let through, the run stops on one line
    code, err = run_cli(capsys, write(tmp_path, data), tmp_path / "out")
    assert code == 2 and len(err) == 1 and "the run stopped: " in err[0] and "tank: mass" in err[0]


# ---------------------------------------------------------------------------------------------- outputs

def test_out_pointing_at_a_file_is_refused_before_the_run(capsys, tmp_path):
    (tmp_path / "out").write_text("x")
    code, err = run_cli(capsys, write(tmp_path, stiff_scene()), tmp_path / "out")
    assert code == 2 and err == [f"ventsim: error: {tmp_path / 'out'}: --out: is a file; expected an output folder "
                                 "(new, or one of an earlier run)"]


def test_out_holding_other_files_is_refused(capsys, tmp_path):
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "notes.txt").write_text("mine")
    code, err = run_cli(capsys, write(tmp_path, tank()), tmp_path / "out")
    assert code == 2 and err[0].endswith("--out: holds files a run did not write (notes.txt); the folder is "
                                         "replaced as a whole: choose a new or empty folder")


def test_an_interrupted_write_keeps_the_earlier_set(capsys, tmp_path, monkeypatch):
    scene, out = write(tmp_path, tank()), tmp_path / "out"
    assert run_cli(capsys, scene, out)[0] == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}

    def killed(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr("cases.results.output.plot_history", killed)  # history and summary written, the picture not
    data = tank()
    data["cavity"][0]["pressure"] = 4e5
    assert run_cli(capsys, write(tmp_path, data), out)[0] == 130
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "scene.toml"]


def test_leftovers_of_a_killed_run_are_cleaned(capsys, tmp_path):
    scene, out = write(tmp_path, tank()), tmp_path / "out"
    assert run_cli(capsys, scene, out)[0] == 0
    (tmp_path / ".out.new-dead").mkdir()
    (tmp_path / ".out.new-dead" / "history.csv").write_text("partial")
    (out / ".history.csv.k2j3.csv").write_text("partial temp file")
    assert run_cli(capsys, scene, out)[0] == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "scene.toml"]
    assert sorted(p.name for p in out.iterdir()) == ["history.csv", "history.png", "summary.json"]


def test_a_run_killed_between_the_two_renames_gets_its_set_back(capsys, tmp_path):
    scene, out = write(tmp_path, tank()), tmp_path / "out"
    assert run_cli(capsys, scene, out)[0] == 0
    old = tmp_path / ".out.old-x"
    old.mkdir()
    out.rename(old / "set")  # the state after the first rename of a swap
    from cases.results.output import _clean

    _clean(out)
    assert sorted(p.name for p in out.iterdir()) == ["history.csv", "history.png", "summary.json"]
    assert not old.exists()


# ---------------------------------------------------------------------------------------------- warnings

def test_a_clamped_inflator_temperature_is_warned(capsys, tmp_path):
    (tmp_path / "p.csv").write_text("t,p\n0,1e7\n1,1e7\n")
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "pressure_mass", "inflator_pressure": "p.csv",
                                      "mass_flow": 0.01, "orifice_area": 1e-4, "gas": {"N2": 1.0}}]
    code, err = run_cli(capsys, write(tmp_path, data), tmp_path / "out")
    message = ("inflator 'gen': the gas temperature from the orifice relation left [50, 10000] K and was held at "
               "the bound: check its pressure and mass flow tables")
    assert code == 0 and err == [f"ventsim: warning: {message}"]
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["warnings"] == [message]


def test_a_species_outside_its_data_range_is_warned(tmp_path):
    data = tank()
    data["species"] = []
    data["ambient"]["gas"] = {"N2": 1.0}
    data["cavity"][0]["gas"] = {"CO2": 1.0}
    data["cavity"][0]["inflator"] = [{"name": "hot", "type": "mass_temperature", "mass_flow": 0.01,
                                      "temperature": 3500.0, "gas": {"CO2": 1.0}}]
    warnings = run(model(tmp_path, data)).summary["warnings"]
    assert any(w.startswith("inflator 'hot' reached 3500 to 3500 K, outside the data range of species 'CO2' (100 to "
                            "3000 K): its cp is held at the end value there; for data over that range give "
                            "[[species]] with coolprop") for w in warnings), warnings


@pytest.mark.parametrize("fluid, T", [("CO2", 200.0), ("H2O", 200.0), ("N2", 100.0), ("CO2", 2900.0)])
def test_coolprop_species_hold_from_100_to_3000_K(fluid, T):
    import CoolProp.CoolProp as CP

    from cavity.species import BUILTIN_COOLPROP_NAMES, builtin_species

    s = builtin_species(fluid)
    state = CP.AbstractState("HEOS", BUILTIN_COOLPROP_NAMES[fluid])
    state.update(CP.DmolarT_INPUTS, 1e-6, T)
    assert s.valid_range == (100.0, 3000.0)
    assert abs(s.molar_cp(T) / state.cp0molar() - 1.0) < 1e-6
    assert float(s.source.split("max rel error ")[1]) < 1e-6


# ---------------------------------------------------------------------------------------------- pop at t = 0

@pytest.mark.parametrize("integrator", ["compiled", "scipy"])
@pytest.mark.parametrize("hold", [0.0, 0.01])
def test_a_pop_vent_armed_above_its_pressure_opens_at_t0(tmp_path, integrator, hold):
    data = tank()
    data["exchange"][0].update(pop_pressure=5e4, pop_hold_time=hold)  # 3 bar in the tank: 2 bar above
    m = model(tmp_path, data)
    m.options = replace(m.options, integrator=integrator)
    r = run(m)
    assert r.trajectory.path == ("compiled" if integrator == "compiled" else "compiled, solve_ivp")
    pops = [(t, label) for t, label in r.trajectory.events if ":pop" in label]
    assert pops == ([(0.0, "vent:pop")] if not hold else [(0.0, "vent:pop"), (pytest.approx(0.01, abs=1e-15),
                                                                                 "vent:pop-hold")])
    t, area, p = r.history[:, 0], r.column("vent.area"), r.column("tank.pressure")
    assert np.all(area[t >= hold] == 1e-4) and np.all(area[t < hold] == 0.0)
    assert p[-1] < 0.9 * 3e5


# ---------------------------------------------------------------------------------------------- orifice join

@pytest.mark.parametrize("integrator", ["compiled", "scipy"])
def test_history_rows_across_the_orifice_join_at_rtol_1e12(tmp_path, integrator):
    """Reference without interpolation: scipy's DOP853 on the engine with every output time a stop."""
    from cavity.integration import SWITCH_NEAR_ZERO_PER_RTOL, integrate

    data = tank(time={"end": 2.0, "output_interval": 0.002}, solver={"rtol": 1e-12})
    data["cavity"][0].update(pressure=5e5, volume=0.06)
    data["exchange"][0].update(area=1e-3)
    m = model(tmp_path, data)
    net = m.network
    traj = integrate(net, net.initial_state(), 0.0, 2.0, replace(m.options, integrator=integrator))
    assert [label for _, label in traj.events] == ["vent:choke", "vent:join", "vent:reversal"]
    y0 = net.initial_state()
    stepped = net.engine().solve_ivp_system(SWITCH_NEAR_ZERO_PER_RTOL * m.options.rtol)
    stepped.breakpoints = tuple(stepped.breakpoints) + tuple(m.output_times[1:-1])
    ref = integrate(stepped, y0, 0.0, 2.0, m.options)
    rows, exact = traj.sample(m.output_times), np.array([ref(t) for t in m.output_times])
    err = np.abs(rows - exact)[:, :2] / np.abs(exact[:, :2]).max(axis=0)
    assert err.max() <= 1e-11  # 2.5e-11 when the join was not a switch; 7.6e-13 with it (compiled path)


def test_a_table_that_ends_before_the_run_is_warned(capsys, tmp_path):
    (tmp_path / "m.csv").write_text("t,m\n0,0.5\n0.02,0.5\n")
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": "m.csv",
                                      "temperature": 600.0, "gas": {"N2": 1.0}, "start": 0.01}]
    code, err = run_cli(capsys, write(tmp_path, data), tmp_path / "out")
    assert code == 0 and err == ["ventsim: warning: cavity[0].inflator[0].mass_flow: the table ends at 0.03 s, before "
                                 "time.end = 0.05 s: its last value 0.5 is held from there; extend the table to "
                                 "time.end (or end it with 0) if that is not meant"]


def test_max_wall_stops_the_compiled_path_inside_its_run(tmp_path):
    m = model(tmp_path, tank(solver={"max_step": 1e-8}, limits={"steps": 10 ** 7}))  # 5e6 steps asked for
    assert m.network.compiled_solver() is not None
    with pytest.raises(RunError, match=r"more than max_wall = 0\.2 s of wall time before t = ([0-9.e-]+) s") as info:
        run(m, max_wall=0.2)
    t_stop = float(info.value.args[0].split("before t = ")[1].split(" s")[0])
    assert 0.0 < t_stop < 0.05  # stopped inside the run, not after it


def test_species_range_reads_the_temperature_column_by_name(tmp_path):
    data = tank()
    data["species"] = []
    data["cavity"][0]["gas"] = {"N2": 1.0}
    r = run(model(tmp_path, data))  # 300 K to a few K below: inside 100-3000 K
    assert "warnings" not in r.summary
