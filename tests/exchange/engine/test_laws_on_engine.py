"""Tabulated, prescribed and bulk-viscosity laws, discharge-coefficient tables and tank-test inflators on the
engine.

Per law: the compiled right-hand side equals the reference assembled from the Python objects along a trajectory
(1e-12, tests.exchange.engine.pairs.assert_rhs_matches_reference), the compiled DOP853 and scipy's DOP853 on the same
network give the same events, discrete states and history column by column (1e-12 of each column's largest
magnitude), and the history read back compiled equals the pointwise one. Plus closed forms: the prescribed flux
moves exactly its mass, the tank-test inflator retraces its tank curve, and the laws are the numba kernels the
engine inlines.
"""
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.results.readback import history_columns, history_rows
from cases.run.runner import run
from cases.scene.files import load_scene, scene_from_dict
from cavity.integration import integrate
from tests.exchange.engine.pairs import (assert_rhs_matches_reference as assert_same_rhs, assert_same_history,
                                assert_same_on_both_integrators, both_integrators, scipy_dop853)
from tests.scenes import tank
from tests.exchange.engine.test_engine import law_scene
from tests.test_exchange_scenes import fill_with_pop
from tests.test_hydraulic import K, P0, oil_scene

TABLES = {"leak.csv": "dp,flow\n0,0\n1e4,150\n5e4,300\n1e5,400\n",
          "vleak.csv": "dp,flow\n0,0\n1e4,40\n1e5,120\n",
          "amp.csv": "t,a\n0,1\n0.05,0.6\n0.1,-0.5\n0.2,-0.5\n",
          "cd_p.csv": "p,cd\n1e5,0.6\n2e5,0.7\n3e5,0.9\n",
          "cd_t.csv": "t,cd\n0,0.5\n0.05,0.9\n0.1,0.7\n"}
LAWS = {"mass_rate_leakage": {"law": "mass_rate_leakage", "leakage_table": "leak.csv"},
        "volume_rate_leakage": {"law": "volume_rate_leakage", "leakage_table": "vleak.csv",
                                "leakage_table_extrapolation": "constant"},
        "mass_flux": {"law": "mass_flux", "flux": 20.0, "flux_amplitude": "amp.csv"},
        "volume_flux": {"law": "volume_flux", "flux": 5.0},
        "bulk_viscosity": {"law": "bulk_viscosity", "viscous_resistance": 50.0, "hydrodynamic_resistance": 0.5},
        "orifice Cd(p)": {"law": "orifice", "discharge_coefficient": "cd_p.csv"},
        "fabric Cd(t)": {"law": "fabric_leakage", "open_fraction": 0.4, "discharge_coefficient": "cd_t.csv",
                         "discharge_coefficient_of": "time"}}


def law_model(folder, name, two_way=False, to_cavity=False):
    for file, text in TABLES.items():
        (folder / file).write_text(text)
    return build_model(scene_from_dict(law_scene(folder, LAWS[name], two_way, to_cavity), folder / "scene.toml"))


def tank_test_model(folder):
    """test_gas's tank-test inflator feeding the tank, which vents through an orifice."""
    (folder / "tank.csv").write_text("time [s],p [Pa]\n0,1e5\n0.02,2.5e5\n0.05,3.1e5\n0.1,3.2e5\n0.12,3.0e5\n")
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "tank_test", "tank_pressure": "tank.csv",
                                      "tank_volume": 0.06, "temperature": 650.0, "gas": {"N2": 1.0},
                                      "start": 0.002, "scale": 0.8}]
    data["time"]["end"] = 0.15
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 2e-4}]
    return build_model(scene_from_dict(data, folder / "scene.toml"))


# a law's kinks in the state (rows of a leakage table, of a Cd table of pressure) are switches
# (exchange.law_kinks); the step that reaches one straddles it, and the kink is located on that step's dense
# output, which the kink spoils: the two integrators (equal right-hand sides, steps that part by round-off near
# the kink) locate it within ~3e-8 of its time (the state there is integrated afresh to it), and their histories
# agree to 1e-11 (both within 1.3e-10 of an rtol 1e-13 reference at rtol 1e-10; without the switches the compiled
# run stepped over the Cd kink with an error of 1.2e-7)
PARTING = {name: {"rtol": 1e-10, "steps": 4, "event_rtol": 1e-7}
           for name in ("mass_rate_leakage", "volume_rate_leakage", "orifice Cd(p)")}
CONFIGS = [(False, False), (True, False), (False, True)]


@pytest.mark.parametrize("name", list(LAWS))
@pytest.mark.parametrize("two_way, to_cavity", CONFIGS, ids=["to ambient", "two-way inflow", "to a cavity"])
def test_law_is_the_same_on_both_integrators(tmp_path, name, two_way, to_cavity):
    model = law_model(tmp_path, name, two_way, to_cavity)
    assert model.network.compiled_unsupported() is None
    assert_same_rhs(model)
    traj = assert_same_on_both_integrators(model, **PARTING.get(name, {}))
    assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))


def test_tank_test_inflator_is_the_same_on_both_integrators(tmp_path):
    model = tank_test_model(tmp_path)
    assert model.network.compiled_unsupported() is None
    assert_same_rhs(model)
    traj = assert_same_on_both_integrators(model)
    assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))


def test_delta_leakage_area_opened_by_time_is_the_same_on_both_integrators():
    """airbag_impactor's vent, which the headform covers and uncovers, with DELTA LEAKAGE AREA opened at 20 ms:
    it flows through the area uncovered since."""
    with open(HERE / CASES["airbag_impactor"], "rb") as f:
        data = tomllib.load(f)
    data["exchange"][0].update(open_time=0.02, delta_area=True)
    model = build_model(scene_from_dict(data, HERE / CASES["airbag_impactor"]))
    assert model.network.compiled_unsupported() is None
    assert_same_rhs(model, samples=13)
    fast_traj, slow_traj = both_integrators(model)
    assert [label for _, label in fast_traj.events] == [label for _, label in slow_traj.events]
    np.testing.assert_allclose([t for t, _ in fast_traj.events], [t for t, _ in slow_traj.events], rtol=1e-10)
    # while the headform covers more than at 20 ms the vent is shut and the inflow a table: the steps' error
    # estimates are round-off and the paths part by two steps, 1.5e-9 in pressure (the scene's rtol is 1e-8;
    # the unmodified scene agrees to 6e-13)
    times = np.asarray(model.output_times)
    fast, slow = history_rows(model, fast_traj, times), history_rows(model, slow_traj, times)
    for k, name in enumerate(history_columns(model)):
        scale = np.max(np.abs(slow[:, k]))
        np.testing.assert_allclose(fast[:, k], slow[:, k], rtol=1e-8, atol=1e-8 * scale, err_msg=name)
    area = fast[:, history_columns(model).index("vent.area [m^2]")]
    assert np.all(area[times < 0.02] == 0.0) and np.max(area) > 1e-5  # uncovered after it opened


def test_delta_leakage_area_of_a_pop_vent_is_the_same_on_both_integrators(tmp_path):
    """A pop vent of constant area with DELTA LEAKAGE AREA: after the pop it carries the area gained since, none;
    the pop, its hold and the area at activation are the same on both paths."""
    data = fill_with_pop(5.0e4, 0.004)
    data["exchange"][0]["delta_area"] = True
    model = build_model(scene_from_dict(data, tmp_path / "scene.toml"))
    assert model.network.compiled_unsupported() is None
    assert_same_rhs(model)
    traj = assert_same_on_both_integrators(model, ["vent:pop", "vent:pop-hold"])
    rows = assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))
    assert np.all(rows[:, history_columns(model).index("vent.area [m^2]")] == 0.0)
    assert traj.modes[-1].area_at_activation == (5e-4,) and model.network.area_at_activation == [5e-4]


def test_tank_test_inflator_retraces_its_tank_curve_compiled(tmp_path):
    """Closed form: a closed rigid cavity equal to the test tank, fed by the tank-test inflator, retraces the tank
    pressure (the inflator's definition, m·T = m0·T0 + γ·T_in·∫ṁ dt, with constant-cp N2)."""
    (tmp_path / "tank.csv").write_text("time [s],p [Pa]\n0,1e5\n0.02,2.5e5\n0.05,3.1e5\n0.1,3.2e5\n")
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "tank_test", "tank_pressure": "tank.csv",
                                      "tank_volume": 0.06, "temperature": 650.0, "gas": {"N2": 1.0}}]
    r = run(build_model(scene_from_dict(data, tmp_path / "scene.toml")))
    assert r.summary["solver"]["path"] == "compiled"
    t = r.column("time")
    p_tank = np.interp(t, [0, 0.02, 0.05, 0.1], [1e5, 2.5e5, 3.1e5, 3.2e5])
    assert np.max(np.abs(r.column("tank.pressure") / p_tank - 1)) < 1e-9


def test_prescribed_mass_flux_moves_exactly_its_mass_compiled(tmp_path):
    """Closed form: ∫ a(t)·q·A dt of the piecewise-linear amplitude crosses the exchange, on the compiled path."""
    model = law_model(tmp_path, "mass_flux", to_cavity=True)
    r = run(model)
    assert r.summary["solver"]["path"] == "compiled"
    t, m2 = r.column("time"), r.column("b.mass")
    ts, amp = np.array([0.0, 0.05, 0.1, 0.2]), np.array([1.0, 0.6, -0.5, -0.5])
    fine = np.union1d(t, ts)
    moved = np.concatenate([[0.0], np.cumsum(np.diff(fine) * 0.5 * (np.interp(fine[1:], ts, amp)
                                                                     + np.interp(fine[:-1], ts, amp)))])
    expected = 20.0 * 2e-4 * np.interp(t, fine, moved)
    np.testing.assert_allclose(m2 - m2[0], expected, rtol=0, atol=1e-10 * m2[0])


@pytest.mark.parametrize("name", ["mass_rate_leakage", "orifice Cd(p)"])
def test_kinked_laws_are_accurate_compiled(tmp_path, name):
    """Brute-force reference: across the kinks of a table law (switches there) the compiled run at rtol 1e-10
    stays within 10·rtol of scipy's DOP853 on the same network at rtol 1e-13."""
    model = law_model(tmp_path, name)
    net, times = model.network, np.asarray(model.output_times)
    fast = integrate(net, net.initial_state(), 0.0, model.scene.time.end, model.options)
    ref = scipy_dop853(model, replace(model.options, rtol=1e-13, atol=1e-20))
    assert fast.path == "compiled" and any(":kink" in label for _, label in fast.events)
    p_fast = np.array([net.states(t, y)[0].pressure for t, y in zip(times, fast.sample(times))])
    p_ref = np.array([net.states(t, y)[0].pressure for t, y in zip(times, ref.sample(times))])
    assert np.max(np.abs(p_fast / p_ref - 1.0)) <= 10 * model.options.rtol


def oil_model(folder, exchange):
    """tests.test_hydraulic's squeezed oil seal, with a temperature table and thermal expansion."""
    (folder / "oil_T.csv").write_text("t,T\n0,300\n0.015,330\n0.03,310\n")
    scene = oil_scene(folder, exchange)
    cav = replace(scene.cavity[0], temperature_table="oil_T.csv", thermal_expansion=7e-4)
    return build_model(replace(scene, cavity=(cav,)))


@pytest.mark.parametrize("leak", [None, {"name": "leak", "from": "seal", "area": 1e-5, "law": "volume_rate_leakage",
                                         "leakage_table": "leak.csv"}], ids=["closed", "leaking"])
def test_hydraulic_cavity_is_the_same_on_both_integrators(tmp_path, leak):
    (tmp_path / "leak.csv").write_text("dp,q\n0,0\n1e6,1e-3\n1e8,5e-3\n")
    model = oil_model(tmp_path, leak)
    assert model.network.compiled_unsupported() is None
    assert_same_rhs(model)
    traj = assert_same_on_both_integrators(model, **(PARTING["volume_rate_leakage"] if leak else {}))
    assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))


def test_hydraulic_deck_is_the_same_on_both_integrators():
    model = build_model(load_scene(HERE / CASES["deck_hydraulic_two_cavity"]))
    assert model.network.compiled_unsupported() is None
    assert_same_rhs(model)
    traj = assert_same_on_both_integrators(model, **PARTING["volume_rate_leakage"])
    assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))


def test_closed_hydraulic_cavity_follows_the_log_law_compiled(tmp_path):
    """Closed form: p − p0 = K·ln(V0/V) at constant temperature, on the compiled path."""
    r = run(build_model(oil_scene(tmp_path)))
    assert r.summary["solver"]["path"] == "compiled"
    V, p = r.column("seal.volume"), r.column("seal.pressure")
    ref = P0 + K * np.log(V[0] / V)
    assert np.max(np.abs(p - ref) / ref) <= 1e-10


@pytest.mark.parametrize("name, method", [("orifice Cd(p)", "LSODA"), ("mass_flux", "RK45"),
                                          ("bulk_viscosity", "BDF"), ("pop delta", "RK45")])
def test_other_methods_run_on_the_compiled_engine(tmp_path, name, method):
    """solve_ivp's other methods on the engine agree with its compiled DOP853, both at rtol 1e-10, to 100 times
    the scene's rtol."""
    if name == "pop delta":
        data = fill_with_pop(5.0e4, 0.004)
        data["exchange"][0]["delta_area"] = True
        model = build_model(scene_from_dict(data, tmp_path / "scene.toml"))
    else:
        model = law_model(tmp_path, name, to_cavity=True)
    fast, other = (run(replace(model, options=replace(model.options, method=m, rtol=1e-10))) for m in ("DOP853", method))
    assert other.summary["solver"]["path"] == "compiled, solve_ivp"
    scale = np.maximum(np.max(np.abs(fast.history), axis=0), 1e-300)
    assert np.max(np.abs(other.history - fast.history) / scale) < 100 * model.options.rtol
