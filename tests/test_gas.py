"""Gas model: CoolProp fits, temperature from internal energy, mixtures, heat loss, tank-test inflators."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import scene_from_dict
from cavity.gas import GasModel
from cavity.species import Species, builtin_species, species_from_coolprop
from cavity.tolerances import R_UNIVERSAL
from tests.scenes import tank

N2, CO2, AIR = (builtin_species(n) for n in ("N2", "CO2", "air"))
GAS = GasModel((N2, CO2, AIR))


@pytest.mark.parametrize("name,fluid", [("N2", "Nitrogen"), ("CO2", "CarbonDioxide"), ("H2O", "Water")])
def test_coolprop_fit_matches_propssi(name, fluid):
    import CoolProp.CoolProp as CP

    sp = species_from_coolprop(name)
    state = CP.AbstractState("HEOS", fluid)
    for T in np.linspace(320.0, 1950.0, 17):
        state.update(CP.DmolarT_INPUTS, 1e-6, T)
        assert sp.molar_cp(T) == pytest.approx(state.cp0molar(), rel=1e-4)  # cubic pieces: <= 3e-5 seen
    assert "max rel error" in sp.source


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 1.0), min_size=3, max_size=3).filter(lambda m: sum(m) > 1e-3),
       st.floats(150.0, 2900.0), st.floats(150.0, 2900.0))
def test_temperature_from_internal_energy_round_trip(masses, T, guess):
    mix = GAS.mixture(masses)
    assert mix.temperature(mix.internal_energy(T), guess) == pytest.approx(T, rel=1e-13)


def test_enthalpy_is_continuous_across_pieces_and_cp_is_its_derivative():
    mix = GAS.mixture([0.2, 0.5, 0.3])
    for b in GAS.breaks:
        assert mix.enthalpy(b * (1 - 1e-13)) == pytest.approx(mix.enthalpy(b), rel=1e-11)
    for T in (250.0, 555.5, 1234.0):
        h = 1e-3
        dHdT = (mix.enthalpy(T + h) - mix.enthalpy(T - h)) / (2 * h)
        assert dHdT == pytest.approx(mix.heat_capacity_p(T), rel=1e-7)


def test_dalton_pressure_and_mixture_gas_constant():
    masses = np.array([0.2, 0.5, 0.3])
    mix = GAS.mixture(masses)
    n = masses / np.array([N2.molar_mass, CO2.molar_mass, AIR.molar_mass])
    assert mix.moles == pytest.approx(n.sum(), rel=1e-15)
    assert mix.gas_constant == pytest.approx(R_UNIVERSAL * n.sum() / masses.sum(), rel=1e-15)


def test_mass_and_molar_fractions():
    y = GAS.mass_fractions({"N2": 1.0, "CO2": 1.0}, molar=True)
    assert y[1] / y[0] == pytest.approx(CO2.molar_mass / N2.molar_mass, rel=1e-15)
    assert y.sum() == pytest.approx(1.0, rel=1e-15)


def test_species_validation():
    with pytest.raises(ValueError, match="molar mass"):
        Species("x", -1.0, (29.0,))
    with pytest.raises(ValueError, match="cv > 0"):
        Species("x", 0.028, (5.0,))


def test_heat_loss_follows_exponential_cooling():
    h, A, Ta = 50.0, 0.5, 300.0
    sc = scene_from_dict(tank(temperature=400.0, energy="heat_loss", heat_transfer_coefficient=h,
                              heat_transfer_area=A), "mem.toml")
    r = run(build_model(sc))
    cav = r.model.network.cavities[0]
    m = sum(cav.initial_masses)
    cv = (29.100619163 - R_UNIVERSAL) / 0.0280134
    T_ref = Ta + 100.0 * np.exp(-h * A * r.column("time") / (m * cv))
    assert np.max(np.abs(r.column("tank.temperature") / T_ref - 1)) < 1e-9


def test_tank_test_inflator_reproduces_its_tank_curve(tmp_path):
    """A cavity identical to the test tank, fed by the tank-test inflator, must retrace the tank pressure."""
    (tmp_path / "tank.csv").write_text("time [s],p [Pa]\n0,1e5\n0.02,2.5e5\n0.05,3.1e5\n0.1,3.2e5\n")
    data = tank()
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "tank_test", "tank_pressure": "tank.csv",
                                      "tank_volume": 0.06, "temperature": 650.0, "gas": {"N2": 1.0}}]
    r = run(build_model(scene_from_dict(data, tmp_path / "scene.toml")))
    t = r.column("time")
    p_tank = np.interp(t, [0, 0.02, 0.05, 0.1], [1e5, 2.5e5, 3.1e5, 3.2e5])
    assert np.max(np.abs(r.column("tank.pressure") / p_tank - 1)) < 1e-9
    assert r.summary["solver"]["restarts"] >= 3  # stopped at each kink of the tank curve


def test_mixture_species_are_conserved(tmp_path):
    """CO2 injected into an air-filled tank: every species mass adds up, whatever the venting."""
    (tmp_path / "mdot.csv").write_text("t,mdot\n0,0\n0.01,2.0\n0.03,2.0\n0.04,0\n")
    data = tank(gas={"air": 1.0})
    data["species"] = []
    data["ambient"]["gas"] = {"air": 1.0}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": "mdot.csv",
                                      "temperature": 800.0, "gas": {"CO2": 0.7, "N2": 0.3}, "start": 0.005}]
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 2e-4}]
    r = run(build_model(scene_from_dict(data, tmp_path / "scene.toml")))
    net, traj = r.model.network, r.trajectory
    y1 = traj(0.1)
    names = net.gas.names
    injected = 0.5 * 0.01 * 2.0 * 2 + 0.02 * 2.0  # trapezoids of the table [kg]
    vented = y1[net.ledger_offset]
    masses = y1[:len(names)]
    total0 = sum(net.cavities[0].initial_masses)
    assert masses.sum() == pytest.approx(total0 + injected - vented, rel=1e-12)
    y_out = masses / masses.sum()
    assert y_out[names.index("CO2")] > 0.1 and r.summary["cavities"]["tank"]["final temperature [K]"] > 300
