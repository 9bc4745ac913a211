"""The one engine: its compiled DOP853 against scipy's DOP853 stepping the same lowered network, its right-hand
side against a reference assembled from the Python objects, and its history read back in one compiled call
against rows built point by point (tests.exchange.engine.pairs).

Whole runs of every library case (same steps, same events, the same pressures to round-off), the equalised mode
of a two-way vent, pop vents, fabric, Graefe and linear-resistance laws; which integrator ran, laws of one's own
(hosted), a network that does not lower, and the step budget.
"""
import copy
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.results.readback import history_columns, history_rows
from cases.run.runner import run
from cases.scene.files import load_scene, scene_from_dict
from cavity.integration import SolverError, integrate
from exchange.laws import orifice
from tests.exchange.engine.pairs import (assert_rhs_matches_reference, assert_same_history, assert_same_on_both_integrators,
                                both_integrators, compiled_dop853, pressures)
from tests.scenes import pop_hold_reset, tank
from tests.test_exchange_scenes import fill_with_pop

LOWERABLE = ["blowdown_choked", "blowdown_isothermal", "blowdown_subsonic", "fill_constant", "compression_mesh",
             "airbag_vented", "airbag_impactor", "airbag_impactor_dynamic", "seal_vent", "seal_vent_nodes",
             "vent_bar_edge",  # bodies: area steps and volume splines, the dynamic body's areas and switches
             "bag_unfold",  # a vent cut from a cavity mesh series: face areas that change between frames
             "deck_box_blowdown", "deck_vented_box_blockage", "deck_wang_nefske_bag",
             "deck_hydraulic_two_cavity"]  # hydraulic cavities, bulk viscosity and a volume-rate leakage table
SEATED = ["relief_valve", "relief_valve_undamped",  # seat contact: compared in tests/exchange/engine/test_seat.py
          "seal_flange"]  # and a seal loaded by the seated flange


def model_of(name):
    return build_model(load_scene(HERE / CASES[name]))


@pytest.mark.parametrize("name", ["blowdown_subsonic", "compression_mesh", "airbag_vented", "airbag_impactor",
                                  "seal_vent", "bag_unfold", "deck_hydraulic_two_cavity"])
def test_right_hand_side_equals_the_reference_assembly(name):
    assert_rhs_matches_reference(model_of(name))


@pytest.mark.parametrize("name", LOWERABLE)
def test_compiled_dop853_matches_scipys_on_the_library(name):
    model = model_of(name)
    fast_traj, slow_traj = both_integrators(model)
    # twin vents (airbag_vented) reach a switch at one instant: which twin's switch fires first is decided by
    # round-off, so compare the kinds of switch in time order
    assert [label.split(":")[1] for _, label in fast_traj.events] == \
        [label.split(":")[1] for _, label in slow_traj.events]
    np.testing.assert_allclose([t for t, _ in fast_traj.events], [t for t, _ in slow_traj.events], rtol=1e-9)
    assert abs(fast_traj.stats["steps"] - slow_traj.stats["steps"]) <= 2
    times = np.asarray(model.output_times)
    p_fast, p_slow = pressures(model, fast_traj, times), pressures(model, slow_traj, times)
    assert np.max(np.abs(p_fast / p_slow - 1.0)) <= 10 * model.options.rtol


def test_the_default_path_is_compiled_and_says_so():
    model = model_of("blowdown_choked")
    net = model.network
    assert model.options.method == "DOP853"
    traj = integrate(net, net.initial_state(), 0.0, 0.5, model.options)
    assert traj.path == "compiled"
    assert traj.stats["steps"] == 3 and traj.stats["rhs_calls"] == 47  # as solve_ivp's DOP853 (docs/benchmarks.md)
    other = integrate(net, net.initial_state(), 0.0, 0.5, replace(model.options, method="RK45"))
    assert other.path == "compiled, solve_ivp"


def two_way_scene(folder: Path, p0: float, end: float):
    data = tank(pressure=p0)
    data["time"] = {"end": end, "output_interval": 0.01}
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-3 if p0 < 1e5 else 1e-4, "two_way": True}]
    data["units"] = {"unchecked": ["cavity[0].pressure"]}  # a vacuum start is meant
    return build_model(scene_from_dict(data, folder / "scene.toml"))


@pytest.mark.parametrize("p0, end", [(3e5, 20.0), (100.0, 1.0)])
def test_equalised_mode_is_the_same_on_both_integrators(tmp_path, p0, end):
    model = two_way_scene(tmp_path, p0, end)
    fast_traj, slow_traj = both_integrators(model)
    labels = [label for _, label in slow_traj.events]
    assert labels == [label for _, label in fast_traj.events] and labels[-1] == "vent:equalise"
    np.testing.assert_allclose([t for t, _ in fast_traj.events], [t for t, _ in slow_traj.events], rtol=1e-6)
    assert fast_traj.modes[-1].equalised == (True,) and slow_traj.modes[-1].equalised == (True,)
    times = np.linspace(0.0, end, 201)
    assert np.max(np.abs(pressures(model, fast_traj, times) / pressures(model, slow_traj, times) - 1)) < 1e-8


def late_inflation(folder: Path):
    """The model of a tank at ambient (its two-way vent equalised from the start) that an inflator pressurises from
    10 ms (late.csv written into ``folder``)."""
    (folder / "late.csv").write_text("t,mdot\n0,0\n0.01,0\n0.011,0.1\n0.05,0.1\n")
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": "late.csv",
                                      "temperature": 300.0, "gas": {"N2": 1.0}}]
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4, "two_way": True}]
    return build_model(scene_from_dict(data, folder / "scene.toml"))


def test_release_reopens_an_equalised_exchange(tmp_path):
    """A tank at ambient (equalised from the start) is pressurised by an inflator from 10 ms: the vent opens."""
    model = late_inflation(tmp_path)
    fast_traj, slow_traj = both_integrators(model)
    for traj in (fast_traj, slow_traj):
        assert [label for _, label in traj.events][:1] == ["vent:release"]
        assert 0.01 < traj.events[0][0] < 0.011
        assert traj.modes[0].equalised == (True,)
    times = np.linspace(0.0, 0.1, 101)
    assert np.max(np.abs(pressures(model, fast_traj, times) / pressures(model, slow_traj, times) - 1)) < 1e-8


def test_laws_of_ones_own_run_hosted_on_the_compiled_path(tmp_path):
    """A law the compiled path does not carry (a subclass of one it does, a prescribed law written in Python) is
    called in Python from the compiled kernels (exchange/engine/hosted.py): the run is compiled and gives the history of
    the same law lowered to 1e-12; a law without mass_flow is refused with the reason."""
    from exchange.laws import FluxLaw, OrificeLaw

    class OwnOrifice(OrificeLaw):
        """A law the compiled path does not know (a subclass of one it does)."""

    class OwnFlux(FluxLaw):
        """A prescribed law of one's own."""

    data = tank(pressure=2e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4}]
    model = build_model(scene_from_dict(copy.deepcopy(data), tmp_path / "scene.toml"))
    net = model.network
    times = np.linspace(0.0, 0.1, 41)
    for own, lowered in ((OwnOrifice(), OrificeLaw()), (OwnFlux("mass", -2.0), FluxLaw("mass", -2.0))):
        out = []
        for law in (own, lowered):
            net.exchanges = (replace(net.exchanges[0], law=law),)
            traj = integrate(net, net.initial_state(), 0.0, 0.1, model.options)
            assert traj.path == "compiled" and (net.compiled_solver().host >= 0) == (law is own)
            out.append(pressures(model, traj, times))
        assert np.max(np.abs(out[0] / out[1] - 1.0)) < 1e-12

    class NoLaw:
        pneumatic, prescribed = True, False

    net.exchanges = (replace(net.exchanges[0], law=NoLaw()),)
    assert net.compiled_solver() is None and "NoLaw has no mass_flow" in net.compiled_unsupported()
    with pytest.raises(SolverError, match="the engine cannot run Network: exchange vent: law NoLaw has no mass_flow"):
        integrate(net, net.initial_state(), 0.0, 0.1, model.options)


def test_step_budget_inside_one_segment_on_the_compiled_path(tmp_path):
    data = tank(pressure=5e5)
    data["time"]["end"] = 2.0
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4}]
    model = build_model(scene_from_dict(data, tmp_path / "scene.toml"))
    net = model.network
    with pytest.raises(SolverError, match=r"more than 3 steps before t = [0-9.e+-]+ s; tank: mass"):
        integrate(net, net.initial_state(), 0.0, 2.0, replace(model.options, max_steps=3))


# ---- the history read back in one compiled call against the rows built point by point


def default_run(model):
    return compiled_dop853(model)


@pytest.mark.parametrize("name", LOWERABLE)
def test_compiled_history_equals_the_pointwise_history_on_the_library(name):
    model = model_of(name)
    traj = default_run(model)
    assert_same_history(model, traj)
    results = run(model)
    assert results.trajectory.path == "compiled"
    base = [results.columns.index(c) for c in history_columns(model)]  # the state columns (and what they derive)
    np.testing.assert_allclose(results.history[:, base], history_rows(model, results.trajectory, model.output_times),
                               rtol=1e-12, atol=1e-300)


@pytest.mark.parametrize("name", SEATED)
def test_compiled_history_of_the_seated_cases(name):
    model = model_of(name)
    assert_same_history(model, default_run(model))


def test_every_library_case_on_the_compiled_path_is_compared():
    compiled = [name for name in CASES if model_of(name).network.compiled_solver() is not None]
    assert sorted(compiled) == sorted(LOWERABLE + SEATED)


@pytest.mark.parametrize("p0, end", [(3e5, 20.0), (100.0, 1.0)])
def test_compiled_history_of_a_two_way_vent_that_equalises(tmp_path, p0, end):
    model = two_way_scene(tmp_path, p0, end)
    traj = default_run(model)
    assert [label for _, label in traj.events][-1] == "vent:equalise"
    times = np.linspace(0.0, end, 201)
    rows = assert_same_history(model, traj, np.union1d(times, [t for t, _ in traj.events]))
    t_eq = traj.events[-1][0]
    flow = rows[:, history_columns(model).index("vent.mass_flow [kg/s]")]
    assert np.all(flow[rows[:, 0] >= t_eq] == 0.0) and np.all(flow[rows[:, 0] < t_eq] != 0.0)


def test_compiled_history_of_a_vent_released_from_equalised(tmp_path):
    model = late_inflation(tmp_path)
    traj = default_run(model)
    assert traj.modes[0].equalised == (True,) and traj.events[0][1] == "vent:release"
    assert_same_history(model, traj, np.union1d(np.linspace(0.0, 0.1, 101), [t for t, _ in traj.events]))


def test_compiled_history_with_a_time_window_an_amplitude_and_two_cavities(tmp_path):
    """Tank a vents to ambient through a window (10–60 ms) with an amplitude table and feeds tank b through
    an orifice; a and b equalise (held closed) once the window has shut."""
    (tmp_path / "amp.csv").write_text("t,a\n0,0.2\n0.02,1.0\n0.04,0.5\n0.08,0.7\n")
    data = tank(pressure=3e5)
    data["cavity"][0]["name"] = "a"
    data["cavity"].append({"name": "b", "pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0},
                           "volume": 0.01})
    data["time"] = {"end": 2.0, "output_interval": 0.002}
    data["exchange"] = [{"name": "vent", "from": "a", "area": 2e-4, "open_time": 0.01, "close_time": 0.06,
                         "amplitude": "amp.csv"},
                        {"name": "link", "from": "a", "to": "b", "area": 5e-5}]
    model = build_model(scene_from_dict(data, tmp_path / "scene.toml"))
    traj = default_run(model)
    assert "link:equalise" in [label for _, label in traj.events]
    times = np.union1d(np.asarray(model.output_times), [0.01, 0.02, 0.04, 0.06] + [t for t, _ in traj.events])
    rows = assert_same_history(model, traj, times)
    area = rows[:, history_columns(model).index("vent.area [m^2]")]
    assert np.all(area[(rows[:, 0] < 0.01) | (rows[:, 0] >= 0.06)] == 0.0)
    assert area[rows[:, 0] == 0.02][0] == pytest.approx(2e-4)


# ---- pop vents (pop, pop-drop, pop-hold) and the fabric / Graefe / linear-resistance laws on the compiled path

def fabric_pop_between_cavities(folder: Path) -> dict:
    """An inflated tank pops (after a hold) into a second tank through fabric; the second leaks to ambient through
    Graefe porosity; the first has a window-limited orifice with an amplitude."""
    (folder / "amp.csv").write_text("t,a\n0,0.5\n0.03,1.0\n")
    data = tank(energy="adiabatic")
    data["time"] = {"end": 0.08, "output_interval": 0.001}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": 0.5,
                                      "temperature": 600.0, "gas": {"N2": 1.0}}]
    data["cavity"].append({"name": "b", "pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0},
                           "volume": 0.02})
    data["exchange"] = [{"name": "seam", "from": "tank", "to": "b", "area": 4e-4, "law": "fabric_leakage",
                         "open_fraction": 0.4, "discharge_coefficient": 0.8, "pop_pressure": 3e4,
                         "pop_hold_time": 0.002},
                        {"name": "skin", "from": "b", "area": 2e-3, "law": "graefe", "flc": 0.3, "fac": 0.5},
                        {"name": "vent", "from": "tank", "area": 1e-4, "open_time": 0.01, "close_time": 0.06,
                         "amplitude": "amp.csv"}]
    return data


def law_scene(folder: Path, law: dict, two_way: bool, to_cavity: bool) -> dict:
    """A tank venting to ambient (one-way), filling from it (two-way, below ambient) or feeding a second tank."""
    data = tank(pressure=0.9e5 if two_way else 3e5)  # subsonic inflow (a constant choked inflow makes steps
    data["time"] = {"end": 0.2, "output_interval": 0.002}  # whose error estimate is round-off: paths may differ)
    area = 1e-4 if law["law"] == "linear_resistance" else 2e-4 if to_cavity or two_way else 2e-3
    vent = dict({"name": "vent", "from": "tank", "area": area, "two_way": two_way}, **law)
    if to_cavity:
        data["cavity"].append({"name": "b", "pressure": 1.5e5, "temperature": 280.0, "gas": {"N2": 1.0},
                               "volume": 0.03})
        vent["to"] = "b"
    data["exchange"] = [vent]
    return data


POP_SCENES = {"pop": lambda folder: fill_with_pop(5.0e4),
              "pop-hold": lambda folder: fill_with_pop(5.0e4, 0.004),
              "pop-hold reset": pop_hold_reset,
              "fabric pop between cavities": fabric_pop_between_cavities}
LAWS = [{"law": "fabric_leakage", "open_fraction": 0.3, "discharge_coefficient": 0.9},
        {"law": "graefe", "flc": 0.8, "fac": 0.7},
        {"law": "linear_resistance", "conductance": 0.05}]


@pytest.mark.parametrize("name, pops", [("pop", ["vent:pop"]), ("pop-hold", ["vent:pop", "vent:pop-hold"]),
                                        ("pop-hold reset", ["vent:pop", "vent:pop-drop"]),
                                        ("fabric pop between cavities", ["seam:pop", "seam:pop-hold"])])
def test_pop_vents_are_the_same_on_both_integrators(tmp_path, name, pops):
    model = build_model(scene_from_dict(POP_SCENES[name](tmp_path), tmp_path / "scene.toml"))
    assert_rhs_matches_reference(model)
    traj = assert_same_on_both_integrators(model, pops)
    assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))


@pytest.mark.parametrize("name", list(POP_SCENES))
def test_pop_vents_run_compiled(tmp_path, name):
    model = build_model(scene_from_dict(POP_SCENES[name](tmp_path), tmp_path / "scene.toml"))
    assert model.network.compiled_unsupported() is None
    results = run(model)
    assert results.summary["solver"]["path"] == "compiled"
    shut = [t for t, label in results.trajectory.events if label.endswith(("vent:pop", "vent:pop-hold"))]
    if name == "pop-hold reset":  # never opens: no flow at all
        assert np.all(results.column("vent.mass_flow") == 0.0) and np.all(results.column("vent.area") == 0.0)
    elif name.startswith("pop"):
        t, flow = results.column("time"), results.column("vent.mass_flow")
        assert np.all(flow[t < shut[-1]] == 0.0) and np.all(flow[t > shut[-1]] > 0.0)


def test_the_pop_vent_mode_is_left_on_the_network(tmp_path):
    """After a run the network holds the final discrete state."""
    model = build_model(scene_from_dict(fill_with_pop(5.0e4, 0.004), tmp_path / "scene.toml"))
    traj = default_run(model)
    net = model.network
    pops = [t for t, label in traj.events if ":pop" in label]  # (the orifice's join switch fires too)
    assert net.popped == [True] and net.holding_since == [pops[0]] and net.area_at_activation == [5e-4]
    t_pop, t_open = pops[0], pops[1]
    def first_three(mode):
        return mode.popped, mode.holding_since, mode.area_at_activation

    assert first_three(traj.mode_at(0.5 * t_pop))[:2] == ((False,), (None,))
    assert first_three(traj.mode_at(0.5 * (t_pop + t_open))) == ((False,), (t_pop,), (None,))
    assert first_three(traj.mode_at(t_open)) == ((True,), (t_pop,), (5e-4,))


@pytest.mark.parametrize("law", LAWS, ids=[law["law"] for law in LAWS])
@pytest.mark.parametrize("two_way, to_cavity", [(False, False), (True, False), (False, True)])
def test_fabric_and_resistance_laws_are_the_same_on_both_integrators(tmp_path, law, two_way, to_cavity):
    model = build_model(scene_from_dict(law_scene(tmp_path, law, two_way, to_cavity), tmp_path / "scene.toml"))
    assert_rhs_matches_reference(model)
    traj = assert_same_on_both_integrators(model)
    assert_same_history(model, traj, np.union1d(model.output_times, [t for t, _ in traj.events]))
    assert run(model).summary["solver"]["path"] == "compiled"


@pytest.mark.parametrize("name, method", [("airbag_vented", "LSODA"), ("airbag_impactor", "Radau"),
                                          ("airbag_impactor_dynamic", "RK45"), ("seal_vent", "BDF"),
                                          ("bag_unfold", "LSODA")])
def test_other_methods_run_on_the_compiled_engine(name, method):
    """solve_ivp's other methods step the same compiled right-hand side, switches and switch actions as DOP853
    ("compiled, solve_ivp"): at rtol 1e-10 they land within 100·rtol of the scene of the compiled DOP853's history
    at rtol 1e-10 (at the scene's rtol the DOP853 itself is only that close: airbag_impactor_dynamic 3.6e-7 in
    pressure at 1e-8, docs/benchmarks.md), with the same contact and pop events."""
    model = model_of(name)
    fast, other = (run(replace(model, options=replace(model.options, method=m, rtol=1e-10))) for m in ("DOP853", method))
    assert other.summary["solver"]["path"] == "compiled, solve_ivp"
    assert [label for _, label in other.trajectory.events if ":contact" in label or ":pop" in label] == \
        [label for _, label in fast.trajectory.events if ":contact" in label or ":pop" in label]
    scale = np.maximum(np.max(np.abs(fast.history), axis=0), 1e-300)
    assert np.max(np.abs(other.history - fast.history) / scale) < 100 * model.options.rtol


def test_twin_switches_after_a_low_order_dense_output_do_not_fire_in_turn():
    """airbag_vented's two identical vents cross their orifice join at one instant. Radau locates the event on its
    low-order dense output and the state there, integrated afresh, leaves the switch 7e-10 off zero (700·rtol at
    rtol 1e-12): the twin, whose value is the same, was watched away from that sign and fired at once, then the
    first again, until the run stopped ("switches keep firing"). Near an event the zero band now grows with the
    fired switch's value at the restart, so the run finishes."""
    model = model_of("airbag_vented")
    o = model.options
    r = run(replace(model, options=replace(o, method="Radau", rtol=1e-12, atol=o.atol * 1e-12 / o.rtol)))
    assert r.summary["solver"]["path"] == "compiled, solve_ivp"
    times = [t for t, _ in r.trajectory.events]
    assert len(times) - len(set(times)) <= 2  # no instant fires more than a switch and its twin's turn


# ---- an exchange that closes for good once its downstream cavity reaches a pressure (a filling to a target)

def filling_to_target(folder: Path, target: float, p_b: float = 1.0e5):
    """A 1 m³ reservoir at 20 bar fills a 10 L vessel through an orifice that closes once the vessel reaches
    ``target``; the vessel leaks slowly to ambient through a linear resistance afterwards."""
    data = tank(pressure=20e5, volume=1.0)
    data["cavity"][0]["name"] = "reservoir"
    data["cavity"].append({"name": "vessel", "pressure": p_b, "temperature": 300.0, "gas": {"N2": 1.0},
                           "volume": 0.01})
    data["time"] = {"end": 0.5, "output_interval": 0.002}
    data["exchange"] = [{"name": "fill", "from": "reservoir", "to": "vessel", "area": 2e-5,
                         "close_pressure": target},
                        {"name": "leak", "from": "vessel", "area": 1e-6, "law": "linear_resistance",
                         "conductance": 1e-3}]
    return build_model(scene_from_dict(data, folder / "scene.toml"))


def test_a_filling_closes_at_its_target_pressure_on_both_integrators(tmp_path):
    """The vessel's pressure reaches the 6 bar target at the close event (to 1e-9), the fill flow is zero from
    then on (the leak lowers the vessel slowly), the same on both integrators, the right-hand side as the
    reference assembly's in both states, and the network left closed."""
    model = filling_to_target(tmp_path, 6e5)
    assert_rhs_matches_reference(model)
    traj = assert_same_on_both_integrators(model)
    closes = [t for t, label in traj.events if label == "fill:close"]
    assert len(closes) == 1 and 0.0 < closes[0] < 0.5
    assert model.network.states(closes[0], traj(closes[0]))[1].pressure == pytest.approx(6e5, rel=1e-9)
    rows = assert_same_history(model, traj, np.union1d(model.output_times, closes))
    cols, t = history_columns(model), rows[:, 0]
    flow, p = rows[:, cols.index("fill.mass_flow [kg/s]")], rows[:, cols.index("vessel.pressure [Pa]")]
    assert np.all(flow[t >= closes[0]] == 0.0) and np.all(flow[t < closes[0]] > 0.0)
    assert p.max() <= 6e5 * (1 + 1e-9) and p[-1] < 6e5
    assert model.network.closed == [True, False] and traj.mode_at(0.0).closed == (False, False)


def test_a_vessel_already_at_its_target_is_closed_from_the_start(tmp_path):
    model = filling_to_target(tmp_path, 6e5, p_b=7e5)
    r = run(model)
    assert r.trajectory.events[0] == (0.0, "fill:close")
    assert np.all(r.column("fill.mass_flow") == 0.0)


def test_a_close_pressure_on_a_vent_to_ambient_is_one_line(tmp_path):
    from cases.scene.errors import SceneError

    data = tank(pressure=3e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4, "close_pressure": 2e5}]
    with pytest.raises(SceneError, match=r"exchange\[0\]\.close_pressure: needs a `to` cavity") as exc:
        build_model(scene_from_dict(data, tmp_path / "scene.toml"))
    assert "\n" not in str(exc.value)


def test_the_integrator_is_a_scene_key(tmp_path):
    """``[solver] integrator = "scipy"`` runs DOP853 through solve_ivp on the engine (the same history to 1e-12
    here); another value is one line naming the key and the choices."""
    from cases.scene.errors import SceneError

    data = tank(pressure=3e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4}]
    fast = run(build_model(scene_from_dict(data, tmp_path / "a.toml")))
    data["solver"]["integrator"] = "scipy"
    slow = run(build_model(scene_from_dict(data, tmp_path / "b.toml")))
    assert (fast.summary["solver"]["path"], slow.summary["solver"]["path"]) == ("compiled", "compiled, solve_ivp")
    np.testing.assert_allclose(slow.column("tank.pressure"), fast.column("tank.pressure"), rtol=1e-12)
    data["solver"]["integrator"] = "python"
    with pytest.raises(SceneError, match=r"solver\.integrator") as exc:
        build_model(scene_from_dict(data, tmp_path / "c.toml"))
    assert "\n" not in str(exc.value) and "scipy" in str(exc.value)
