"""Viscous + hydrodynamic resistance: round trips, the linear limit, and a two-tank exponential oracle."""
import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from exchange.laws.bulk_viscosity import (
    bulk_viscosity_mass_flow,
    bulk_viscosity_pressure_drop,
    linear_resistance_conductance,
)
from exchange.laws.graefe import graefe_mass_flow
from exchange.laws.linear_resistance import linear_resistance_mass_flow

RHO = 1.2        # kg/m^3
AREA = 0.01      # m^2
COEFFS = [(100.0, 0.0), (0.0, 0.5), (100.0, 0.5), (1.0e-3, 50.0), (5.0e4, 1.0e-4)]
DPS = [s * 10.0 ** k for k in range(-6, 7) for s in (1.0, -1.0)]


@pytest.mark.parametrize("c_v, c_h", COEFFS)
def test_round_trip_solve_then_recompute_dp(c_v, c_h):
    for dp in DPS:
        mdot = bulk_viscosity_mass_flow(dp, RHO, AREA, c_v, c_h)
        assert math.copysign(1.0, mdot) == math.copysign(1.0, dp)
        assert bulk_viscosity_pressure_drop(mdot, RHO, AREA, c_v, c_h) == pytest.approx(dp, rel=1e-12)


@pytest.mark.parametrize("c_v, c_h", COEFFS)
def test_odd_and_increasing_in_dp(c_v, c_h):
    for dp in DPS:
        assert bulk_viscosity_mass_flow(-dp, RHO, AREA, c_v, c_h) == -bulk_viscosity_mass_flow(dp, RHO, AREA, c_v, c_h)
    grid = np.linspace(-2.0e4, 2.0e4, 401)
    m = [bulk_viscosity_mass_flow(float(x), RHO, AREA, c_v, c_h) for x in grid]
    assert all(b > a for a, b in itertools.pairwise(m))


def test_hand_values():
    assert bulk_viscosity_pressure_drop(0.12, RHO, AREA, 100.0, 0.5) == pytest.approx(1060.0, rel=1e-14)
    assert bulk_viscosity_mass_flow(1060.0, RHO, AREA, 100.0, 0.5) == pytest.approx(0.12, rel=1e-14)


def test_linear_case_is_exactly_proportional():
    base = bulk_viscosity_mass_flow(777.0, RHO, AREA, 100.0, 0.0)
    for k in range(-20, 21):                  # scaling by 2**k is exact in binary floating point
        assert bulk_viscosity_mass_flow(777.0 * 2.0 ** k, RHO, AREA, 100.0, 0.0) == base * 2.0 ** k
    g = linear_resistance_conductance(RHO, AREA, 100.0)
    assert base == pytest.approx(linear_resistance_mass_flow(777.0, g), rel=1e-15)
    assert g == pytest.approx(RHO * AREA / 100.0, rel=1e-15)


def test_quadratic_only_with_half_dynamic_head_is_bernoulli():
    for dp in [1.0, 1500.0, 2.0e5]:
        assert bulk_viscosity_mass_flow(dp, RHO, AREA, 0.0, 0.5) == \
            pytest.approx(graefe_mass_flow(1.0e5 + dp, 1.0e5, RHO, AREA), rel=1e-14)


def test_slope_at_zero_is_the_viscous_conductance():
    eps = 1e-9
    for c_h in [0.0, 0.5, 50.0]:
        slope = bulk_viscosity_mass_flow(eps, RHO, AREA, 100.0, c_h) / eps
        assert slope == pytest.approx(RHO * AREA / 100.0, rel=1e-9)
        assert bulk_viscosity_mass_flow(0.0, RHO, AREA, 100.0, c_h) == 0.0


def test_invalid_coefficients():
    with pytest.raises(ValueError, match="must be >= 0"):
        bulk_viscosity_mass_flow(10.0, RHO, AREA, -1.0, 0.5)
    with pytest.raises(ValueError, match="both zero"):
        bulk_viscosity_mass_flow(10.0, RHO, AREA, 0.0, 0.0)
    with pytest.raises(ValueError, match="c_v > 0"):
        linear_resistance_conductance(RHO, AREA, 0.0)
    assert bulk_viscosity_mass_flow(10.0, RHO, 0.0, 1.0, 1.0) == 0.0


def test_linear_resistance_accepts_arrays():
    np.testing.assert_array_equal(linear_resistance_mass_flow(np.array([-2.0, 0.0, 3.0]), 0.5), [-1.0, 0.0, 1.5])


def test_two_isothermal_tanks_exchange_mass_exponentially():
    # p_i = m_i R T / V_i, dm1/dt = -G (p1 - p2)  =>  Δp = Δp0 exp(-t/tau), 1/tau = G R T (1/V1 + 1/V2)
    R, T, V1, V2, G = 287.0, 300.0, 0.05, 0.02, 2.0e-7
    m0 = np.array([3.0e5 * V1 / (R * T), 1.0e5 * V2 / (R * T)])

    def rhs(t, m):
        mdot = linear_resistance_mass_flow(m[0] * R * T / V1 - m[1] * R * T / V2, G)
        return [-mdot, mdot]

    k = G * R * T * (1.0 / V1 + 1.0 / V2)
    t_end = 3.0 / k
    sol = solve_ivp(rhs, (0.0, t_end), m0, method="DOP853", rtol=1e-13, atol=1e-16, dense_output=True)
    t = np.linspace(0.0, t_end, 7)
    transferred = m0[0] - sol.sol(t)[0]
    exact = (2.0e5 / (R * T * (1.0 / V1 + 1.0 / V2))) * (1.0 - np.exp(-k * t))
    np.testing.assert_allclose(transferred[1:], exact[1:], rtol=1e-9)
    # the flows are equal and opposite, so the total changes by round-off only: about ε per step and a few ε in the
    # dense output (a bound that does not depend on how many steps a scipy version takes)
    steps = len(sol.t)
    np.testing.assert_allclose(sol.sol(t).sum(axis=0), m0.sum(), rtol=4 * (steps + 1) * np.finfo(float).eps)
