"""Every pressure-driven law at Δp -> 0: finite, no NaN, monotone to 0, exactly 0 at Δp = 0 and below."""
import math

import pytest

from exchange.laws.bulk_viscosity import bulk_viscosity_mass_flow
from exchange.laws.linear_resistance import linear_resistance_mass_flow
from exchange.laws.fabric import (
    anagonye_wang_mass_flow,
    fabric_leakage_mass_flow,
    wang_nefske_mass_flow,
)
from exchange.laws.graefe import graefe_mass_flow
from exchange.laws.leakage_table import LeakageTable, leakage_table_mass_flow

P = 1.0e5
T0, R_AIR, GAMMA_AIR, RHO = 300.0, 287.0, 1.4, 1.16
TABLE = LeakageTable.from_rows([(0.0, 0.0), (500.0, 0.8), (5000.0, 3.0)], kind="volume")

# law(dp) for dp = p_up - p_down, with p_down = P
ONE_WAY = {
    "fabric": lambda dp: fabric_leakage_mass_flow(P + dp, T0, P, R_AIR, GAMMA_AIR, 0.1, 0.6, 0.05),
    "wang_nefske": lambda dp: wang_nefske_mass_flow(P + dp, T0, P, R_AIR, GAMMA_AIR, 0.7, 1e-3, 0.5, 1e-2),
    "graefe": lambda dp: graefe_mass_flow(P + dp, P, RHO, 0.1, 0.05, 0.5),
    "anagonye_wang": lambda dp: anagonye_wang_mass_flow(P + dp, T0, P, R_AIR, GAMMA_AIR, 0.11, 0.1,
                                                        0.01, 0.002, 0.005, 0.001),
    "leakage_table": lambda dp: leakage_table_mass_flow(TABLE, dp, 0.1, rho_up=RHO),
}
TWO_WAY = {
    "bulk_viscosity": lambda dp: bulk_viscosity_mass_flow(dp, RHO, 0.1, 100.0, 0.5),
    "bulk_viscosity_quadratic": lambda dp: bulk_viscosity_mass_flow(dp, RHO, 0.1, 0.0, 0.5),
    "linear": lambda dp: linear_resistance_mass_flow(dp, 1e-6),
}
# 1 Pa down to 1e-9 Pa: about 70 ulps of 1e5 Pa, so P + dp still differs from P (1e-12 Pa would not)
SMALL = [10.0 ** -k for k in range(10)]


@pytest.mark.parametrize("name", sorted(ONE_WAY) + sorted(TWO_WAY))
def test_tends_to_zero_monotonically(name):
    law = {**ONE_WAY, **TWO_WAY}[name]
    values = [law(dp) for dp in SMALL]
    assert all(math.isfinite(v) and v > 0.0 for v in values), values
    assert values == sorted(values, reverse=True)
    assert values[-1] < 1e-4 * values[0]          # sqrt-like laws: sqrt(1e-9) ~ 3e-5 of the 1 Pa value
    assert law(0.0) == 0.0


@pytest.mark.parametrize("name", sorted(ONE_WAY))
def test_one_way_laws_give_zero_for_negative_dp(name):
    for dp in [-1e-12, -1.0, -1e4]:
        assert ONE_WAY[name](dp) == 0.0


@pytest.mark.parametrize("name", sorted(TWO_WAY))
def test_two_way_laws_are_odd(name):
    for dp in [1e-12, 1.0, 1e4]:
        assert TWO_WAY[name](-dp) == -TWO_WAY[name](dp)
