"""Real-gas scenes: the energy books close with a wall, they run on the compiled path, bad keys are one line."""
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import load_scene
from exchange.network.network import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE

VALIDATION = Path(__file__).resolve().parents[2] / "cases" / "validation"


@pytest.fixture(scope="module")
def n2_run():
    return run(build_model(load_scene(VALIDATION / "n2_150bar_discharge.toml")))


@pytest.fixture(scope="module")
def filling_run():
    return run(build_model(load_scene(VALIDATION / "air_3_7kPa_filling.toml")))


@pytest.fixture(scope="module")
def layered_run(tmp_path_factory):
    """The N2 discharge with its 25 mm steel wall in 8 conducting layers (k = 45 W/(m K))."""
    text = (VALIDATION / "n2_150bar_discharge.toml").read_text().replace(
        "wall_length = 1.524", "wall_layers = 8\nwall_conductivity = 45.0\nwall_thickness = 0.025\nwall_length = 1.524")
    path = tmp_path_factory.mktemp("layered") / "n2_layered.toml"
    path.write_text(text.replace('"data/', f'"{(VALIDATION / "data").as_posix()}/'))
    return run(build_model(load_scene(path)))


@pytest.fixture(scope="module")
def composite_run():
    """The KIT helium discharge from a Type IV tank: an HDPE liner and a composite shell, 8 cells each."""
    return run(build_model(load_scene(VALIDATION / "he_700bar_typeIV_discharge.toml")))


def _books(r):
    """(gas imbalance, wall imbalance, scale) [J] of the one cavity of a run with a wall."""
    net = r.model.network
    y0, y1 = net.initial_state(), r.trajectory(r.model.scene.time.end)
    cav = net.cavities[0]
    k, ns = net.offsets[0], len(cav.initial_masses)
    e = net.ledger_offset + LEDGER_PER_EXCHANGE * len(net.exchanges)
    inflator_h, work, heat = y1[e + 1], y1[e + 2], y1[e + 3]
    exchanged = sum(y1[net.ledger_offset + LEDGER_PER_EXCHANGE * j + 1] for j in range(len(net.exchanges)))
    gas = (y1[k + ns] - y0[k + ns]) - (inflator_h - exchanged - work - heat)
    n = cav.wall.layers
    stored = sum(C * (y1[k + ns + 1 + j] - y0[k + ns + 1 + j]) for j, C in enumerate(cav.wall.capacities))
    wall = stored - (heat - y1[k + ns + 1 + n])
    scale = max(abs(y0[k + ns]), abs(exchanged), abs(heat))
    wall_scale = max(scale, cav.wall.thermal_mass * y0[k + ns + 1])  # T_w is stored absolute: its round-off
    assert LEDGER_PER_CAVITY == 4
    return gas, wall, scale, wall_scale, heat


@pytest.mark.parametrize("which", ["n2_run", "filling_run", "layered_run", "composite_run"])
def test_energy_books_close_with_a_wall(which, request):
    """Gas: ΔU = inflow − outflow − work − heat to the wall; wall: Σ C_j ΔT_j = heat in − heat to ambient;
    both to 1e-12 of the energies involved (lumped, one conducting material, two materials), the wall's own
    m_w·c_w·T_w included (its unknown is the absolute
    temperature, so that is the size of its round-off); the ledger integrals are advanced by the same steps."""
    r = request.getfixturevalue(which)
    gas, wall, scale, wall_scale, heat = _books(r)
    assert abs(heat) > 1e-3 * scale  # the wall did exchange heat
    assert abs(gas) <= 1e-12 * scale
    assert abs(wall) <= 1e-12 * wall_scale
    assert r.summary["mass balance"]["vessel"]["relative imbalance [-]"] <= 1e-12


def test_n2_blowdown_against_the_measurement(n2_run):
    """Haque et al. I1 (docs/validation.md): pressure RMS error <= 3.5 bar over the 21 measured points (measured
    2.96 bar; HydDown 2.44 bar on the same points), the computed gas temperature minimum within 5 K of the
    measured bottom-probe minimum, and the lumped wall within 2 K of the mean of the inner and outer wall probes
    at the end."""
    data = VALIDATION / "data"
    t, p = np.loadtxt(data / "n2_150bar_pressure.csv", delimiter=",", skiprows=1).T
    tc, pc = n2_run.column("time"), n2_run.column("vessel.pressure")
    err = np.interp(t, tc, pc) / 1e5 - p
    assert np.sqrt(np.mean(err ** 2)) <= 3.5
    _, T_low = np.loadtxt(data / "n2_150bar_gas_low.csv", delimiter=",", skiprows=1).T
    assert abs(n2_run.column("vessel.temperature").min() - T_low.min()) <= 5.0
    tw, Tw_in = np.loadtxt(data / "n2_150bar_wall_inner.csv", delimiter=",", skiprows=1).T
    _, Tw_out = np.loadtxt(data / "n2_150bar_wall_outer.csv", delimiter=",", skiprows=1).T
    wall = np.interp(tw[-1], tc, n2_run.column("vessel.wall_temperature"))
    assert abs(wall - 0.5 * (Tw_in[-1] + Tw_out[-1])) <= 2.0


@pytest.mark.parametrize("method, integrator, path", [("LSODA", "compiled", "compiled, solve_ivp"),
                                                      ("DOP853", "scipy", "compiled, solve_ivp"),
                                                      ("DOP853", "compiled", "compiled")])
def test_real_gas_runs_on_the_engine(n2_run, method, integrator, path):
    """The N2 discharge (real-gas cavity, wall, real-gas nozzle: hosted parts, exchange/engine/hosted.py) lowers and runs
    on every integrator; at rtol 1e-8 each history is within 1e-6 of the compiled DOP853's at rtol 1e-10,
    relative to each column's scale."""
    model = n2_run.model
    assert model.network.compiled_unsupported() is None

    def at(rtol, **options):
        o = model.options
        return run(replace(model, options=replace(o, rtol=rtol, atol=o.atol * rtol / o.rtol, **options)))

    ref, r = at(1e-10, method="DOP853"), at(1e-8, method=method, integrator=integrator)
    assert r.summary["solver"]["path"] == path
    a, b = r.history, ref.history
    assert np.max(np.abs(a - b) / np.abs(b).max(axis=0).clip(1e-300)) <= 1e-6


def test_a_failing_hosted_state_stops_with_its_reason(tmp_path):
    """A real-gas state CoolProp cannot give (the gas cooled far below the saturation line by a huge heat loss to a
    20 K ambient) stops the compiled run with the hosted part's own reason (here the nozzle finds no throat), not
    a traceback."""
    from cases.run.runner import RunError

    text = (VALIDATION / "n2_150bar_discharge.toml").read_text()
    head, cavity = text.split('energy = "wall"')
    head = head.replace('method = "LSODA"', 'method = "DOP853"').replace(
        "pressure = 101300.0\ntemperature = 288.0", "pressure = 101300.0\ntemperature = 20.0")
    path = tmp_path / "n2_cold.toml"
    head = head.replace("[time]", '[units]\nunchecked = ["ambient.temperature"]  # meant\n\n[time]', 1)
    path.write_text(head + 'energy = "heat_loss"\nheat_transfer_coefficient = 1.0e6\nheat_transfer_area = 10.0\n\n'
                    + cavity[cavity.index("[[exchange]]"):])
    scene = load_scene(path)
    with pytest.raises(RunError, match="right-hand side failed .*RealGasSolveError: Nitrogen"):
        run(build_model(scene))


@pytest.mark.parametrize("method", ["LSODA", "DOP853"])
def test_a_gas_that_condenses_mid_run_keeps_what_was_integrated(tmp_path, method):
    """CO2 from 100 bar, 330 K (above its critical point) through the N2 vessel's orifice: it reaches the
    two-phase region at ~12 s. The run stops with the reason in one line and keeps its history up to the last
    accepted step before the failure (solve_ivp itself returns nothing when the right-hand side raises; the
    compiled DOP853 keeps the steps of the piece it stopped in); the kept rows equal an uninterrupted run's to
    the solver's tolerance."""
    from cases.run.runner import RunError

    text = (VALIDATION / "n2_150bar_discharge.toml").read_text().replace("N2 = 1.0", "CO2 = 1.0").replace(
        "15.0e6", "10.0e6").replace("temperature = 288.0", "temperature = 330.0").replace(
        'method = "LSODA"', f'method = "{method}"')
    path = tmp_path / "co2.toml"
    path.write_text(text)
    with pytest.raises(RunError, match="two-phase") as exc:
        run(build_model(load_scene(path)))
    part = exc.value.partial
    assert part is not None and 5.0 < part.summary["stopped at [s]"] < 12.879
    t = part.column("time")
    assert t[-1] <= part.summary["stopped at [s]"] < t[-1] + 0.5 and len(t) > 10
    path.write_text(text.replace("end = 100.0", f"end = {float(t[-1])!r}"))
    whole = run(build_model(load_scene(path)))
    p, q = part.column("vessel.pressure"), whole.column("vessel.pressure")
    assert np.max(np.abs(p - q[:p.size])) <= 1e-3 * q[0]


SCENE = """
[time]
end = 1.0
[ambient]
gas = {N2 = 1.0}
[[cavity]]
name = "tank"
fluid = "real_gas"
gas = {N2 = 1.0}
pressure = 1.0e7
temperature = 300.0
volume = 0.01
"""


@pytest.mark.parametrize("old,new,where", [
    ('gas = {N2 = 1.0}\npressure', 'gas = {N2 = 0.5, Air = 0.5}\npressure', "cavity[0].gas.Air"),
    ('volume = 0.01', 'volume = 0.01\nenergy = "isothermal"', "cavity[0].energy"),
    ('volume = 0.01', 'volume = 0.01\nenergy = "wall"\nwall_mass = 1.0', "cavity[0].wall_heat_capacity"),
    ('fluid = "real_gas"', 'energy = "wall"', "cavity[0].energy"),
    ('volume = 0.01', 'volume = 0.01\nenergy = "wall"\nwall_mass = 1.0\nwall_heat_capacity = 500.0\n'
     'wall_inner_area = 0.3\nwall_outer_h = 5.0\nwall_length = 0.5\nwall_layers = 4\nwall_thickness = 0.01',
     "cavity[0].wall_conductivity"),
    ('volume = 0.01', 'volume = 0.01\nwall_layers = 0', "cavity[0].wall_layers"),
])
def test_bad_real_gas_keys_name_the_key(tmp_path, old, new, where):
    from cases.scene.errors import SceneError

    path = tmp_path / "s.toml"
    assert old in SCENE
    path.write_text(SCENE.replace(old, new, 1))
    with pytest.raises(SceneError) as exc:
        load_scene(path)
    assert where in str(exc.value) and "\n" not in str(exc.value)


def test_ledger_unknowns_do_not_enter_the_right_hand_side(filling_run):
    """The stiff Jacobian is differenced over ``coupled_unknowns`` only (cavity.jacobian): every other unknown
    (ledger integrals, heat to ambient), set 1000 times larger, must leave the compiled right-hand side
    unchanged. Not bit for bit: a real-gas state starts Newton from the previous state's prediction
    (cavity.realgas), so two evaluations at one (t, y) differ in the last digits (measured ≤ 4.1e-13 relative);
    1e-10 of each entry is far below what a real dependence on a 1000-fold change would show."""
    net = filling_run.model.network
    y = filling_run.trajectory(20.0)
    cols = set(net.coupled_unknowns)
    assert cols and len(cols) < y.size
    system = net.engine().solve_ivp_system(0.0)
    system.begin_segment(20.0, 30.0, y)
    f0 = system.rhs(20.0, y)
    for j in set(range(y.size)) - cols:
        y1 = y.copy()
        y1[j] = 1e3 * (abs(y1[j]) + 1.0)
        assert np.all(np.abs(system.rhs(20.0, y1) - f0) <= 1e-10 * np.abs(f0)), j


def test_layered_wall_is_colder_inside_than_outside(layered_run, n2_run):
    """While the gas cools the wall, heat flows outward through it: the inner layer is never warmer than the outer
    (1.8 K colder at most, at about 21 s), the lumped wall's temperature lies between them then, and the inner
    layer follows the inner probe closer than the lumped wall does (RMS over the measured points: 3.8 K against
    4.3 K)."""
    inner, outer = (layered_run.column(f"vessel.{c}") for c in ("wall_temperature", "outer_wall_temperature"))
    lumped = np.interp(layered_run.column("time"), n2_run.column("time"), n2_run.column("vessel.wall_temperature"))
    gap = outer - inner
    k = int(gap.argmax())
    assert gap.min() >= -1e-9 and 1.0 < gap[k] < 3.0 and inner[k] < lumped[k] < outer[k]
    data = np.loadtxt(VALIDATION / "data" / "n2_150bar_wall_inner.csv", delimiter=",", skiprows=1)
    rms = [np.sqrt(np.mean((np.interp(data[:, 0], r.column("time"), T) - data[:, 1]) ** 2))
           for r, T in ((layered_run, inner), (n2_run, n2_run.column("vessel.wall_temperature")))]
    assert rms[0] < rms[1] - 0.3, rms


def test_real_gas_on_the_compiled_dop853_converges_monotonically_in_rtol(n2_run):
    """The N2 discharge (real-gas state, wall and nozzle hosted) on the compiled DOP853: the error of pressure and
    temperatures against rtol 1e-12 falls at every rung of 1e-4 … 1e-10 (measured 7.7e-5, 2.2e-5, 8.6e-6, 3.3e-6,
    6.6e-8, 5.4e-9, 7.5e-10) and is below 1e-8 at the last."""
    model = n2_run.model

    def at(rtol):
        o = model.options
        r = run(replace(model, options=replace(o, method="DOP853", rtol=rtol, atol=o.atol * rtol / o.rtol)))
        assert r.summary["solver"]["path"] == "compiled"
        return r.history

    ref = at(1e-12)
    cols = [i for i, c in enumerate(n2_run.columns) if "pressure" in c or "temperature" in c]
    scale = np.abs(ref[:, cols]).max(axis=0)
    errors = [float((np.abs(at(r)[:, cols] - ref[:, cols]).max(axis=0) / scale).max())
              for r in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)]
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert errors[-1] < 1e-8


def test_a_stage_outside_the_gas_states_shortens_the_step(filling_run):
    """The filling on DOP853: a trial stage of a long step reaches a two-phase air state (39.7 K) that CoolProp
    refuses. scipy's DOP853 on the engine stops there with that reason; the compiled DOP853 rejects the step
    and retries it shorter, and finishes with LSODA's pressure history within 1 % of the final pressure
    (measured 0.38 %, LSODA's own error at rtol 1e-4) and its wall temperature to 1e-6."""
    from cases.run.runner import RunError

    model = filling_run.model
    options = replace(model.options, method="DOP853")
    with pytest.raises(RunError, match="two-phase"):
        run(replace(model, options=replace(options, integrator="scipy")))
    fast = run(replace(model, options=options))
    assert fast.summary["solver"]["path"] == "compiled"
    for name, tol in (("vessel.pressure", 1e-2), ("vessel.wall_temperature", 1e-6)):
        a, b = fast.column(name), filling_run.column(name)
        assert np.abs(a - b).max() <= tol * np.abs(b).max(), name


def test_a_copied_network_hosts_its_own_parts(n2_run):
    """The hosted parts are registered per network (exchange/engine/hosted.py): a copy of a lowered real-gas network
    (sharing its cached lowering) is lowered again for itself, and the registration goes with its network."""
    import copy
    import gc

    from exchange.engine.host import HOSTS

    net = n2_run.model.network
    fast = net.compiled_solver()
    assert HOSTS[fast.host].network is net and net.compiled_solver() is fast
    twin = copy.copy(net)
    other = twin.compiled_solver()
    assert other.host != fast.host and HOSTS[other.host].network is twin
    key = other.host
    del twin, other
    gc.collect()
    assert key not in HOSTS
