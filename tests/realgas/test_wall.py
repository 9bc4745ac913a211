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


def _slab_mean_temperature(Bi: float, Fo: float, terms: int = 60) -> float:
    """Mean of θ/θ_i across a slab, adiabatic on one face, convective (Biot Bi) on the other, at Fourier number Fo:
    Σ C_n sin(ζ_n)/ζ_n exp(−ζ_n² Fo), ζ_n tan ζ_n = Bi, C_n = 4 sin ζ_n/(2ζ_n + sin 2ζ_n) (Incropera & DeWitt,
    *Fundamentals of Heat and Mass Transfer*, eq. 5.39; the one-face problem is half of the symmetric one)."""
    from scipy.optimize import brentq

    total = 0.0
    for n in range(terms):
        lo, hi = n * np.pi + 1e-12, n * np.pi + np.pi / 2 - 1e-12
        z = brentq(lambda z: z * np.tan(z) - Bi, lo, hi, xtol=1e-15)
        total += 4 * np.sin(z) / (2 * z + np.sin(2 * z)) * np.sin(z) / z * np.exp(-z * z * Fo)
    return total


def test_layered_wall_converges_to_the_slab_solution():
    """A 25 mm steel slab (k 45 W/(m K), ρc 3.9e6 J/(m³ K)) at 300 K, one face to 200 K fluid through h = 2000
    W/(m² K) (Bi = 1.11), the other adiabatic, for 20 s (Fo = 0.37): the stored heat of N = 2 … 32 layers
    approaches the exact series monotonically, at second order (error ratio 3.9–4.0 a halving: 1.0e-2 at N = 2,
    1.6e-4 at 16, below 1e-4 at 32)."""
    from scipy.integrate import solve_ivp

    L, k, rho_c, h, A, T0, Tf, t_end = 0.025, 45.0, 3.9e6, 2000.0, 1.0, 300.0, 200.0, 20.0
    exact = _slab_mean_temperature(h * L / k, k / rho_c * t_end / L ** 2)
    errors = []
    for n in (2, 4, 8, 16, 32):
        wall = Wall(rho_c * L * A, 1.0, A, A, h, 0.0, 1.0, T0, 250.0, layers=n, conductivity=k, thickness=L)

        def rates(t, T, wall=wall):
            q_in, q_out = wall.heat_flows(None, 0.0, Tf, T[0], 0.0, T[-1])
            return wall.layer_rates(T, q_in, q_out)

        T = solve_ivp(rates, (0.0, t_end), [T0] * n, method="Radau", rtol=1e-11, atol=1e-9).y[:, -1]
        mean = sum(C * Tj for C, Tj in zip(wall.capacities, T)) / wall.thermal_mass
        errors.append(abs((mean - Tf) / (T0 - Tf) - exact))
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert all(3.0 < a / b < 5.0 for a, b in zip(errors, errors[1:])), errors
    assert errors[-1] < 1e-4, errors


def test_one_layer_is_the_lumped_wall():
    """layers = 1 is the lumped wall: Q_in = h_i A_i (T_gas − T_w) with no conduction resistance, whatever k."""
    lumped = Wall(300.0, 500.0, 1.4, 1.7, 50.0, 5.0, 1.5, 288.0, 293.0)
    assert lumped.heat_flows(None, 1e5, 250.0, 280.0) == (50.0 * 1.4 * -30.0, 5.0 * 1.7 * (280.0 - 293.0))
    assert lumped.capacities == (300.0 * 500.0,)
    with pytest.raises(ValueError, match="conductivity > 0"):
        Wall(300.0, 500.0, 1.4, 1.7, 50.0, 5.0, 1.5, 288.0, 293.0, layers=4)
