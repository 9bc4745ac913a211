"""The real-gas nozzle: the ideal law for an ideal gas, and an independent integration of the isentrope for N2."""
import math

import numpy as np

import CoolProp.CoolProp as CP
import pytest
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from cavity.realgas import IdealGasFluid, RealFluid
from exchange.laws.orifice import LINEAR_BELOW, orifice_mass_flow
from exchange.laws.realgas_orifice import RealGasOrificeLaw, real_gas_critical_state, real_gas_mass_flux
from exchange.network.vent import GasPoint


@pytest.mark.parametrize("gamma", [1.1, 1.3, 1.4, 5.0 / 3.0])
def test_equals_the_ideal_law_for_an_ideal_gas(gamma):
    """Choked and subsonic, p_down/p0 from 0.05 to 0.999 (400 ratios): <= 1e-12. Nearer to p0 both laws carry
    the rounding of the pressure difference itself (1e-16·p0 of a Δp of s·p0: 1e-12 at s = 1e-4) and, in the C¹
    band below s = 1e-4, the ideal law's slope (q^(2/γ) − q^((γ+1)/γ) at q = 1 − 1e-4) loses four more digits:
    there the two agree to <= 3e-11."""
    R, T0 = 296.8, 300.0
    g = IdealGasFluid(R, gamma)
    rho0 = 2.0e5 / (R * T0)
    p0 = g.at(rho0, T0).p  # the same p0 on both sides (ρ0·R·T0 rounds)
    for q in np.linspace(0.05, 0.999, 400):
        ideal = orifice_mass_flow(p0, T0, q * p0, R, gamma, 1.0)
        assert real_gas_mass_flux(g, rho0, T0, q * p0) == pytest.approx(ideal, rel=1e-12, abs=0.0), q
    for s in (5e-4, 1.1e-4, LINEAR_BELOW, 0.5 * LINEAR_BELOW, 1e-6, 1e-8):
        ideal = orifice_mass_flow(p0, T0, (1.0 - s) * p0, R, gamma, 1.0)
        assert real_gas_mass_flux(g, rho0, T0, (1.0 - s) * p0) == pytest.approx(ideal, rel=3e-11, abs=0.0), s
    assert real_gas_mass_flux(g, rho0, T0, p0) == 0.0
    p_star = real_gas_critical_state(g, rho0, T0)[0]
    assert p_star / p0 == pytest.approx((2.0 / (gamma + 1.0)) ** (gamma / (gamma - 1.0)), rel=1e-12)


def _independent_flux(fluid, p0, T0, p_down):
    """G(p_t) = ρ(p_t, s0)·√(2∫ dp/ρ) along the isentrope by adaptive quadrature of CoolProp (p, s) flashes,
    maximised over p_t >= p_down by a bounded scalar search (the choked flux is the largest)."""
    st = CP.AbstractState("HEOS", fluid)
    st.update(CP.PT_INPUTS, p0, T0)
    s0 = st.smass()

    def rho(p):
        st.update(CP.PSmass_INPUTS, p, s0)
        return st.rhomass()

    def flux(p):
        drop, _ = quad(lambda x: 1.0 / rho(x), p, p0, epsabs=0.0, epsrel=1e-13, limit=200)
        return rho(p) * math.sqrt(2.0 * drop)

    best = minimize_scalar(lambda p: -flux(p), bounds=(0.2 * p0, 0.8 * p0), method="bounded",
                           options={"xatol": 1e-6 * p0})
    p_star = best.x
    return (flux(p_down) if p_down > p_star else -best.fun), p_star


@pytest.mark.parametrize("p_down", [1.0e5, 200.0e5, 270.0e5])
def test_nitrogen_300_bar_equals_an_independent_isentrope_integration(p_down):
    """N2 at 300 bar, 300 K: choked (1 bar) and subsonic (200, 270 bar) flux to <= 1e-8."""
    p0, T0 = 300.0e5, 300.0
    f = RealFluid("Nitrogen")
    rho0 = f.density(p0, T0)
    ref, p_star_ref = _independent_flux("Nitrogen", p0, T0, p_down)
    assert real_gas_mass_flux(f, rho0, T0, p_down) == pytest.approx(ref, rel=1e-8)
    if p_down < p_star_ref:
        p_star = real_gas_critical_state(f, rho0, T0)[0]
        assert p_star == pytest.approx(p_star_ref, rel=1e-6)  # a flat maximum: its place is less sharp than G
        assert abs(p_star / p0 - 0.528) > 0.05  # far from the ideal-gas ratio: the real gas matters here


def test_law_falls_back_to_the_ideal_law_for_ideal_gas_points():
    """Gas flowing back from an ideal-gas side (ambient) uses the ideal law, Cd and area applied alike."""
    law = RealGasOrificeLaw(0.7)
    up = GasPoint(2.0e5, 300.0, 2.0e5 / (287.0 * 300.0), 287.0, 1.4, 3.0e5, (1.0,))
    assert law.mass_flow(up, 1.0e5, 1e-4, 0.0) == orifice_mass_flow(2.0e5, 300.0, 1.0e5, 287.0, 1.4, 1e-4, 0.7)
