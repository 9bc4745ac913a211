"""The lumped wall: the correlations as written, and a closed tank relaxing to its wall (a closed form)."""
import math

import numpy as np
import pytest

from cavity.wall import (Wall, forced_inflow_nusselt, horizontal_cylinder_nusselt, natural_convection_coefficient,
                         natural_convection_nusselt, rayleigh_number)

AIR = (1.16, 1007.0, 1.85e-5, 0.0263, 1.0 / 300.0)  # ρ, cp, μ, k, β near 1 bar, 300 K


def test_correlations_as_tabulated():
    """Geankoplis (vertical) and Morgan (horizontal) branches at one point each, and the forced term added."""
    assert natural_convection_nusselt(1e3) == pytest.approx(1.36 * 1e3 ** 0.2)
    assert natural_convection_nusselt(1e6) == pytest.approx(0.59 * 1e6 ** 0.25)
    assert natural_convection_nusselt(1e11) == pytest.approx(0.13 * 1e11 ** 0.333)
    assert horizontal_cylinder_nusselt(1e3) == pytest.approx(0.850 * 1e3 ** 0.188)
    assert horizontal_cylinder_nusselt(1e9) == pytest.approx(0.125 * 1e9 ** 0.333)
    L, Tg, Tw = 0.2, 290.0, 300.0
    Ra = rayleigh_number(L, Tw - Tg, *AIR)
    assert Ra == pytest.approx(9.81 * AIR[4] * 10.0 * L ** 3 * AIR[0] ** 2 * AIR[1] / (AIR[2] * AIR[3]))
    h0 = natural_convection_coefficient(L, Tg, Tw, AIR)
    assert h0 == pytest.approx(natural_convection_nusselt(Ra) * AIR[3] / L)
    h1 = natural_convection_coefficient(L, Tg, Tw, AIR, inflow=0.01, jet_diameter=0.2)
    Re = 4.0 * 0.01 / (math.pi * 0.2 * AIR[2])
    assert h1 - h0 == pytest.approx(forced_inflow_nusselt(Re) * AIR[3] / L)


def test_closed_tank_relaxes_to_its_wall(tmp_path):
    """N2 at 1 bar, 350 K in a rigid 10 L tank with a 0.5 kg wall at 300 K, h_i given, no outer loss: the
    temperature difference decays as exp(−t/τ), 1/τ = h_i A (1/(m c_v) + 1/(m_w c_w)), to the accuracy of a
    constant c_v (measured 2.3e-4; bound 5e-3); the common final temperature conserves energy."""
    from cases.model.build import build_model
    from cases.run.runner import run
    from cases.scene.files import load_scene

    (tmp_path / "s.toml").write_text("""
[time]
end = 30.0
[ambient]
temperature = 300.0
gas = {N2 = 1.0}
[[cavity]]
name = "tank"
fluid = "real_gas"
gas = {N2 = 1.0}
pressure = 1.0e5
temperature = 350.0
volume = 0.01
energy = "wall"
wall_mass = 0.05
wall_heat_capacity = 50.0
wall_inner_area = 0.1
wall_inner_h = 10.0
wall_outer_h = 1e-300
wall_temperature = 300.0
""")
    r = run(build_model(load_scene(tmp_path / "s.toml")))
    cav = r.model.network.cavities[0]
    m = cav.initial_masses[0]
    cv = cav.fluid.at(m / 0.01, 325.0).cv
    tau = 1.0 / (10.0 * 0.1 * (1.0 / (m * cv) + 1.0 / (0.05 * 50.0)))
    t, T, Tw = r.column("time"), r.column("tank.temperature"), r.column("tank.wall_temperature")
    k = np.searchsorted(t, tau)
    assert (T[k] - Tw[k]) / 50.0 == pytest.approx(math.exp(-t[k] / tau), rel=5e-3)
    final = (m * cv * T[-1] + 0.05 * 50.0 * Tw[-1]) / (m * cv + 0.05 * 50.0)
    assert final == pytest.approx((m * cv * 350.0 + 0.05 * 50.0 * 300.0) / (m * cv + 0.05 * 50.0), rel=1e-3)
    assert T[-1] - Tw[-1] < 1e-3 * 50.0  # relaxed (30 s is 16 τ)
