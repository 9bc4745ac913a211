"""Fabric leakage laws: hand values, independent re-derivations from the sources, limits."""
import math

import pytest

from exchange.laws.fabric import (
    anagonye_wang_area_factor,
    anagonye_wang_mass_flow,
    fabric_leakage_mass_flow,
    wang_nefske_mass_flow,
)
from exchange.laws.graefe import graefe_mass_flow, graefe_velocity
from exchange.laws.orifice import (
    choked_flow_factor,
    critical_pressure_ratio,
    orifice_mass_flow,
)

R_AIR = 287.0      # J/(kg K)
GAMMA_AIR = 1.4
T0 = 300.0         # K
P_ATM = 1.0e5      # Pa
REL = 1e-12        # float rounding of a handful of operations


def radioss_isenthalpic_mass_flow(p, T, p_ext, R, gamma, a_eff):
    """OpenRadioss airbagb1.F, IFVENT = 1, written as in the source: density at the throat times velocity."""
    rho = p / (R * T)
    p_ext = max(p_ext, p * critical_pressure_ratio(gamma))
    rho_ex = rho * (p_ext / p) ** (1.0 / gamma)
    u2 = 2.0 * gamma / (gamma - 1.0) * p / rho * (1.0 - (p_ext / p) ** ((gamma - 1.0) / gamma))
    return a_eff * rho_ex * math.sqrt(max(u2, 0.0))


@pytest.mark.parametrize("p_up", [1.05e5, 1.5e5, 1.9e5, 3.0e5, 1.0e6])
def test_wang_nefske_equals_radioss_isenthalpic_form(p_up):
    got = wang_nefske_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 0.7, 1.0e-4, 0.5, 2.0e-4)
    ref = radioss_isenthalpic_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 0.7e-4 + 1.0e-4)
    assert got == pytest.approx(ref, rel=REL)


def test_wang_nefske_choked_closed_form():
    # choked: mdot = (C A) p / sqrt(R T) * C*, C* = sqrt(g) (2/(g+1))^((g+1)/(2(g-1)))
    p_up = 4.0e5
    ref = 1.7e-4 * p_up / math.sqrt(R_AIR * T0) * choked_flow_factor(GAMMA_AIR)
    assert wang_nefske_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 0.7, 1.0e-4, 0.5, 2.0e-4) == \
        pytest.approx(ref, rel=REL)


def test_wang_nefske_vent_and_porosity_add():
    args = (1.3e5, T0, P_ATM, R_AIR, GAMMA_AIR)
    both = wang_nefske_mass_flow(*args, 0.7, 1.0e-4, 0.5, 2.0e-4)
    vent = wang_nefske_mass_flow(*args, 0.7, 1.0e-4)
    fabric = wang_nefske_mass_flow(*args, 0.0, 0.0, 0.5, 2.0e-4)
    assert both == pytest.approx(vent + fabric, rel=REL)
    assert vent / fabric == pytest.approx(0.7, rel=REL)


def test_fabric_leakage_is_orifice_on_open_area():
    args = (1.4e5, 320.0, P_ATM, R_AIR, GAMMA_AIR)
    assert fabric_leakage_mass_flow(*args, 0.02, Cd=0.6, open_fraction=0.25) == \
        orifice_mass_flow(*args, 0.02 * 0.25, 0.6)
    assert fabric_leakage_mass_flow(*args, 0.02, Cd=0.6, open_fraction=0.0) == 0.0


def test_graefe_hand_values_and_bernoulli():
    u = graefe_velocity(1.015e5, 1.0e5, 1.2)
    assert u == pytest.approx(50.0, rel=REL)
    assert 0.5 * 1.2 * u * u == pytest.approx(1500.0, rel=REL)   # dynamic pressure = Δp
    assert graefe_mass_flow(1.015e5, 1.0e5, 1.2, 0.01, FLC=0.5, FAC=0.2) == pytest.approx(0.06, rel=REL)
    # mdot = rho * u * A_eff
    assert graefe_mass_flow(1.015e5, 1.0e5, 1.2, 0.01, 0.5, 0.2) == pytest.approx(1.2 * u * 0.001, rel=REL)


@pytest.mark.parametrize("eps", [1e-3, 1e-4])
def test_graefe_is_incompressible_limit_of_wang_nefske(eps):
    # With q = 1 - eps the orifice law is A sqrt(2 rho dp) (1 - 3 eps / (4 gamma) + O(eps^2)).
    p_up = P_ATM / (1.0 - eps)
    rho = p_up / (R_AIR * T0)
    ratio = wang_nefske_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 1.0, 1.0) / \
        graefe_mass_flow(p_up, P_ATM, rho, 1.0)
    first_order = -3.0 * eps / (4.0 * GAMMA_AIR)
    assert ratio - 1.0 == pytest.approx(first_order, rel=10 * eps)   # O(eps^2) remainder


def test_anagonye_wang_factor_hand_value_and_clamps():
    coeffs = (0.01, 0.002, 0.005, 0.001)
    assert anagonye_wang_area_factor(1.25, 2.0e5, 1.0e5, *coeffs) == pytest.approx(0.0125, rel=REL)
    # r_s = max(A/A0, 1): a shrunk fabric counts as unstretched
    assert anagonye_wang_area_factor(0.8, 2.0e5, 1.0e5, *coeffs) == anagonye_wang_area_factor(1.0, 2.0e5, 1.0e5,
                                                                                                *coeffs)
    # r_p = min(p_ext/p, 1); p <= 0 gives r_p = 1
    at_one = anagonye_wang_area_factor(1.0, 1.0e5, 1.0e5, *coeffs)
    assert at_one == pytest.approx(0.01 + 0.005 + 0.002 + 0.001, rel=REL)
    assert anagonye_wang_area_factor(1.0, 0.5e5, 1.0e5, *coeffs) == at_one
    assert anagonye_wang_area_factor(1.0, 0.0, 1.0e5, *coeffs) == at_one


def test_anagonye_wang_mass_flow_is_orifice_on_factor_area():
    coeffs = (0.01, 0.002, 0.005, 0.001)
    p_up = 1.6e5
    f = anagonye_wang_area_factor(1.1, p_up, P_ATM, *coeffs)
    got = anagonye_wang_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 1.1e-2, 1.0e-2, *coeffs)
    assert got == pytest.approx(orifice_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, f * 1.1e-2), rel=REL)
    # a negative factor never reverses the flow
    assert anagonye_wang_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 1.0, 1.0, -1.0, 0.0, 0.0, 0.0) == 0.0


@pytest.mark.parametrize("p_up", [P_ATM, 0.9e5, 0.0])
def test_laws_are_one_directional(p_up):
    rho = 1.2
    assert fabric_leakage_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 1.0) == 0.0
    assert wang_nefske_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 1.0, 1.0, 1.0, 1.0) == 0.0
    assert graefe_velocity(p_up, P_ATM, rho) == 0.0
    assert graefe_mass_flow(p_up, P_ATM, rho, 1.0) == 0.0
    assert anagonye_wang_mass_flow(p_up, T0, P_ATM, R_AIR, GAMMA_AIR, 1.0, 1.0, 0.01, 0.0, 0.0, 0.0) == 0.0
