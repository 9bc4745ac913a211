"""Exchanges in whole scenes: cavity-to-cavity transfer, conservation, pop-open vents, tables, laws."""

import numpy as np
import pytest

from cases.model.build import build_model
from cases.scene.errors import SceneError
from cases.run.runner import run
from cases.scene.files import scene_from_dict
from tests.scenes import pop_hold_reset, tank

R_U = 8.314462618
M_N2, CP_N2 = 0.0280134, 29.100619163
R_N2, GAMMA = R_U / M_N2, CP_N2 / (CP_N2 - R_U)


def two_tanks(energy="isothermal", law=None, end=0.2, area=1e-4):
    data = tank(pressure=3.0e5, energy=energy)
    data["time"]["end"] = end
    data["cavity"].append({"name": "tank2", "pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0},
                           "volume": 0.02, "energy": energy})
    data["exchange"] = [dict({"name": "pipe", "from": "tank", "to": "tank2", "area": area}, **(law or {}))]
    return data


def run_dict(data, tmp_path=None, name="scene.toml"):
    return run(build_model(scene_from_dict(data, (tmp_path or __import__("pathlib").Path(".")) / name)))


def test_linear_resistance_between_isothermal_tanks_is_exponential():
    G, A = 0.04, 1e-4  # conductance per area [kg/(s Pa m^2)], area [m^2]
    r = run_dict(two_tanks(law={"law": "linear_resistance", "conductance": G}))
    t = r.column("time")
    tau = 1.0 / (G * A * R_N2 * 300.0 * (1 / 0.06 + 1 / 0.02))
    dp = r.column("tank.pressure") - r.column("tank2.pressure")
    assert t[-1] > 2 * tau  # the transfer is well under way
    assert np.max(np.abs(dp - 2.0e5 * np.exp(-t / tau))) / 2.0e5 <= 1e-9
    m1, m2 = r.column("tank.mass"), r.column("tank2.mass")
    m_total0 = m1[0] + m2[0]
    m1_eq = m_total0 * 0.06 / 0.08  # equal pressures: m1/V1 = m2/V2
    m1_ref = m1_eq + (m1[0] - m1_eq) * np.exp(-t / tau)
    assert np.max(np.abs(m1 / m1_ref - 1.0)) <= 1e-9
    assert np.max(np.abs((m1 + m2) / m_total0 - 1.0)) <= 1e-12


def total_internal_energy(r, t):
    net = r.model.network
    states = net.states(t, r.trajectory(t))
    return sum(net.gas.mixture(s.mass * s.mass_fractions).internal_energy(s.temperature) for s in states)


def test_orifice_between_adiabatic_tanks_conserves_mass_and_energy():
    r = run_dict(two_tanks(energy="adiabatic", law={"law": "orifice", "discharge_coefficient": 0.7}, end=0.5,
                           area=1e-3))
    m = r.column("tank.mass") + r.column("tank2.mass")
    assert np.max(np.abs(m / m[0] - 1.0)) <= 1e-12
    U = [total_internal_energy(r, t) for t in r.column("time")]
    assert np.max(np.abs(np.array(U) / U[0] - 1.0)) <= 1e-10
    T2 = r.column("tank2.temperature")
    assert T2.max() > 320.0  # the receiving tank heats up: enthalpy, not internal energy, is carried
    assert abs(r.column("tank.pressure")[-1] / r.column("tank2.pressure")[-1] - 1) < 1e-3  # equalised


def test_vent_to_ambient_conserves_internal_energy_plus_enthalpy_carried_out():
    data = tank(pressure=4.0e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 2e-4, "discharge_coefficient": 0.6}]
    r = run_dict(data)
    net = r.model.network
    E_out_index = net.ledger_offset + 1
    U0 = total_internal_energy(r, 0.0)
    for t in r.column("time")[::50]:
        balance = total_internal_energy(r, t) + r.trajectory(t)[E_out_index]
        assert abs(balance / U0 - 1.0) <= 1e-10


def fill_with_pop(pop, hold=0.0):
    data = tank()  # 60 L at ambient 1 bar, 300 K
    data["time"] = {"end": 0.1, "output_interval": 0.01}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": 0.5,
                                      "temperature": 600.0, "gas": {"N2": 1.0}}]
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 5e-4, "pop_pressure": pop,
                         "pop_hold_time": hold}]
    return data


@pytest.mark.parametrize("hold", [0.0, 0.004])
def test_pop_vent_opens_at_the_closed_form_time(hold):
    pop = 5.0e4  # gauge [Pa]
    r = run_dict(fill_with_pop(pop, hold))
    t_pop = pop * 0.06 / (GAMMA * R_N2 * 0.5 * 600.0)  # p = p0 + γRṁT_in t/V reaches p_amb + pop
    log = r.summary["solver"]["event log"]
    opened = [t for t, label in log if label in ("vent:pop", "vent:pop-hold")]
    assert abs(opened[-1] - (t_pop + hold)) <= 1e-9, (opened, t_pop + hold)
    if hold:
        assert [label for _, label in log if label.startswith("vent:pop")] == ["vent:pop", "vent:pop-hold"]
    flow = r.column("vent.mass_flow")
    t = r.column("time")
    assert np.all(flow[t < t_pop + hold - 1e-12] == 0.0) and np.all(flow[t > t_pop + hold + 1e-12] > 0.0)


def test_pop_hold_resets_when_pressure_drops_back(tmp_path):
    """A pressure spike shorter than the hold time does not open the vent."""
    r = run_dict(pop_hold_reset(tmp_path), tmp_path)
    labels = [label for _, label in r.summary["solver"]["event log"] if label.startswith("vent:pop")]
    assert labels[:2] == ["vent:pop", "vent:pop-drop"] and "vent:pop-hold" not in labels
    assert np.all(r.column("vent.mass_flow") == 0.0)


def test_time_window_and_amplitude(tmp_path):
    (tmp_path / "amp.csv").write_text("t,a\n0,0\n0.05,1\n")
    data = tank(pressure=3e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4, "open_time": 0.01, "close_time": 0.08,
                         "amplitude": "amp.csv"}]
    r = run_dict(data, tmp_path)
    t, area = r.column("time"), r.column("vent.area")
    assert np.all(area[t < 0.01] == 0) and np.all(area[t >= 0.08] == 0)
    inside = (t > 0.01) & (t < 0.05)
    assert np.allclose(area[inside], 1e-4 * t[inside] / 0.05, rtol=1e-12)
    p = r.column("tank.pressure")
    assert np.ptp(p[t >= 0.08]) == 0.0 and p[-1] < 3e5


def test_table_law_reproduces_the_orifice_law_within_interpolation_error(tmp_path):
    """Isothermal blowdown: a mass-rate table sampled from the orifice law at 300 K follows the orifice run."""
    from exchange.laws.orifice import orifice_mass_flow

    dp = np.concatenate([[0.0], np.geomspace(1.0, 4e5, 400)])
    flux = [orifice_mass_flow(1e5 + d, 300.0, 1e5, R_N2, GAMMA, 1.0) for d in dp]
    (tmp_path / "leak.csv").write_text("dp,flux\n" + "\n".join(f"{a:.17g},{b:.17g}" for a, b in zip(dp, flux)))
    runs = {}
    for law in ({"law": "orifice"}, {"law": "mass_rate_leakage", "leakage_table": "leak.csv"}):
        data = tank(pressure=4e5, energy="isothermal")
        data["exchange"] = [dict({"name": "vent", "from": "tank", "area": 1e-4}, **law)]
        runs[law["law"]] = run_dict(data, tmp_path).column("tank.pressure")
    rel = np.max(np.abs(runs["mass_rate_leakage"] / runs["orifice"] - 1.0))
    assert 0 < rel < 2e-5  # geometric rows 2.2 % apart: interpolation error of order (h/x)²/8·|x f''/f'| ~ 1e-5


@pytest.mark.parametrize("rows,message", [
    ("dp,flux\n10,0\n100,1\n", "row 1"),
    ("dp,flux\n0,0\n100,-1\n", "row 2"),
    ("dp,flux\n0,0\n100,1\n50,2\n", "strictly increasing"),
])
def test_bad_leakage_tables_are_rejected(tmp_path, rows, message):
    (tmp_path / "bad.csv").write_text(rows)
    data = tank(pressure=3e5)
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 1e-4, "law": "mass_rate_leakage",
                         "leakage_table": "bad.csv"}]
    with pytest.raises(SceneError, match=message) as err:
        run_dict(data, tmp_path)
    assert "exchange[0]" in str(err.value) and "\n" not in str(err.value)


def test_prescribed_mass_flux_moves_exact_mass():
    data = two_tanks(law={"law": "mass_flux", "flux": 10.0})  # 10 kg/(s m^2) x 1e-4 m^2 = 1 g/s
    r = run_dict(data)
    m2 = r.column("tank2.mass")
    assert np.allclose(m2 - m2[0], 1e-3 * r.column("time"), rtol=1e-10, atol=1e-16)


@pytest.mark.parametrize("law", [{"law": "fabric_leakage", "open_fraction": 0.3, "discharge_coefficient": 0.9},
                                 {"law": "graefe", "flc": 0.8, "fac": 1.0},
                                 {"law": "bulk_viscosity", "viscous_resistance": 50.0,
                                  "hydrodynamic_resistance": 0.5}])
def test_every_law_vents_monotonically_and_conserves_mass(law):
    data = tank(pressure=3e5)
    data["exchange"] = [dict({"name": "vent", "from": "tank", "area": 2e-3}, **law)]
    r = run_dict(data)
    p = r.column("tank.pressure")
    assert np.all(np.diff(p) <= 0) and p[-1] < 0.8 * p[0] and p[-1] >= 1e5
    assert r.summary["mass balance"]["tank"]["relative imbalance [-]"] <= 1e-12
