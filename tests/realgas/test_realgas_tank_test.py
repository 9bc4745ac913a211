"""Tank-test inflators read through a real-gas tank (cavity/inflator_realgas.py)."""
import CoolProp.CoolProp as CP
import numpy as np
import pytest

from cavity.inflator import tank_test_mass_flow
from cavity.inflator_realgas import real_gas_tank_masses
from cavity.realgas import IDEAL_LIMIT_DENSITY, IdealGasFluid, RealFluid

TIMES = (0.0, 0.005, 0.01, 0.02, 0.03, 0.05)


def test_ideal_gas_tank_is_the_abaqus_formula():
    """Constant-cp ideal gas, constant T_in: Δm per row = V·Δp/(γ·R·T_in) to 1e-12; a falling row delivers 0."""
    R, gamma, V, T_in = 296.8, 1.4, 0.06, 800.0
    p = (1.0e5, 1.6e5, 2.5e5, 3.1e5, 3.0e5, 3.4e5)
    m = real_gas_tank_masses(IdealGasFluid(R, gamma), V, TIMES, p, 300.0, lambda t: T_in)
    for i in range(1, len(p)):
        rate = (p[i] - p[i - 1]) / (TIMES[i] - TIMES[i - 1])
        expected = tank_test_mass_flow(V, rate, gamma, R, T_in) * (TIMES[i] - TIMES[i - 1]) if rate > 0 else 0.0
        assert m[i] - m[i - 1] == pytest.approx(expected, rel=1e-12, abs=1e-18)


def test_real_gas_tank_states_are_heos_at_every_row():
    """N2 tank from 100 to 300 bar fed at 600–800 K: the tank's (m_i, U_i) give the table's p_i through HEOS's own
    (ρ, u) flash to 1e-9 (U_i = U_0 + Σ Δm·h_in(T_mid), h_in the ideal-gas limit), and the real tank takes less
    mass than the ideal formula would (compressibility Z > 1 at these states)."""
    V, T0 = 0.01, 300.0
    p = (100e5, 140e5, 180e5, 220e5, 260e5, 300e5)
    T_in = lambda t: 600.0 + 4000.0 * t  # noqa: E731
    fluid = RealFluid("Nitrogen")
    m = real_gas_tank_masses(fluid, V, TIMES, p, T0, T_in)
    heos = CP.AbstractState("HEOS", "Nitrogen")
    heos.update(CP.PT_INPUTS, p[0], T0)
    U = m[0] * heos.umass()
    assert m[0] == pytest.approx(heos.rhomass() * V, rel=1e-12)
    for i in range(1, len(p)):
        heos.update(CP.DmassT_INPUTS, IDEAL_LIMIT_DENSITY, T_in(0.5 * (TIMES[i - 1] + TIMES[i])))
        U += (m[i] - m[i - 1]) * heos.hmass()
        heos.update(CP.DmassUmass_INPUTS, m[i] / V, U / m[i])
        assert heos.p() == pytest.approx(p[i], rel=1e-9)
    gamma, R = 1.4, 8.314462618 / fluid.molar_mass
    ideal = sum(V * (p[i] - p[i - 1]) / (gamma * R * T_in(0.5 * (TIMES[i - 1] + TIMES[i]))) for i in range(1, 6))
    assert m[-1] - m[0] < ideal


def _ar_he():
    from tests.realgas.test_realgas_mixture import _fluid

    return _fluid("Argon&Helium", (0.9, 0.1))


@pytest.mark.parametrize("gas,fluid", [("gas = {N2 = 1.0}", lambda: RealFluid("Nitrogen")),
                                       ("gas = {Ar = 0.9, He = 0.1}\ngas_by_mole = true", _ar_he)])
def test_scene_with_a_real_gas_tank_test_inflator(tmp_path, gas, fluid):
    """A rigid cavity filled by a real-gas tank-test inflator (N2, or a hybrid inflator's Ar/He mixture) receives
    exactly the tank's mass gain, the species in the tank's proportions; the compiled DOP853 and scipy's on the
    same engine give the same history."""
    from cases.model.build import build_model
    from cases.run.runner import run
    from cases.scene.files import load_scene

    (tmp_path / "p.csv").write_text("time [s],p [Pa]\n0,1.0e7\n0.01,1.5e7\n0.03,2.0e7\n")
    (tmp_path / "s.toml").write_text(f"""
[time]
end = 0.04
[ambient]
gas = {{N2 = 1.0}}
[[cavity]]
name = "bag"
gas = {{N2 = 1.0}}
pressure = 1.0e5
temperature = 300.0
volume = 0.06
[[cavity.inflator]]
name = "inf"
type = "tank_test"
{gas}
tank_pressure = "p.csv"
tank_volume = 0.001
temperature = 700.0
tank_gas = "real_gas"
tank_temperature = 300.0
""")
    r = run(build_model(load_scene(tmp_path / "s.toml")))
    inf = r.model.network.cavities[0].inflators[0]
    m = real_gas_tank_masses(fluid(), 0.001, (0.0, 0.01, 0.03), (1e7, 1.5e7, 2e7), 300.0, lambda t: 700.0)
    mass = r.column("bag.mass")
    assert mass[-1] - mass[0] == pytest.approx(m[-1] - m[0], rel=1e-10)
    assert inf.mass_between(0.0, 0.04) == pytest.approx(m[-1] - m[0], rel=1e-12)
    assert np.all(np.diff(mass) >= 0.0)
    net = r.model.network
    delivered = r.trajectory(0.04)[net.offsets[0]:net.offsets[0] + len(net.gas.names)] - \
        np.asarray(net.cavities[0].initial_masses)
    assert delivered / delivered.sum() == pytest.approx(np.asarray(inf.mass_fractions), rel=1e-10, abs=1e-14)
    assert r.summary["solver"]["path"] == "compiled"
    from dataclasses import replace

    slow = run(replace(r.model, options=replace(r.model.options, integrator="scipy")))
    assert slow.summary["solver"]["path"] == "compiled, solve_ivp"
    worst = np.max(np.abs(r.history - slow.history) / np.maximum(np.abs(slow.history).max(axis=0), 1e-300))
    assert worst <= 1e-12, worst  # the same steps, round-off apart
