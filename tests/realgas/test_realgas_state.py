"""Real-gas cavity state against CoolProp HEOS, entropy of an isentropic expansion, and the tables' absence.

The state from (m, U, V) is found by Newton's method on HEOS at (ρ, T) (:mod:`cavity.realgas`); the reference
here is a different CoolProp route, the (ρ, u) flash ``DmassUmass_INPUTS`` of the same equation of state.
"""
import math

import CoolProp.CoolProp as CP
import numpy as np
import pytest

from cavity.realgas import IdealGasFluid, RealFluid, temperature_from_energy
from cavity.realgas_cavity import RealGasCavity
from cavity.volume import FixedVolume

CASES = [("Nitrogen", 300.0), ("Helium", 300.0), ("Hydrogen", 300.0), ("CarbonDioxide", 350.0)]  # CO2: T > Tc
PRESSURES = [1e5, 100e5, 300e5, 600e5]


@pytest.mark.parametrize("fluid,T0", CASES)
def test_closed_rigid_tank_pressure_equals_heos(fluid, T0):
    """p from (m, U, V) of a rigid tank, at its initial state and after adding 2 % of its energy, equals the
    HEOS (ρ, u) flash to <= 1e-6 (it is HEOS itself, so it agrees to ~1e-12)."""
    f = RealFluid(fluid)
    heos = CP.AbstractState("HEOS", fluid)
    worst = 0.0
    for p0 in PRESSURES:
        V = 0.05
        rho = f.density(p0, T0)
        cav = RealGasCavity("tank", FixedVolume(V), (rho * V,), T0, fluid=f)
        y = cav.initial_unknowns()
        for dU in (0.0, 0.02 * abs(y[1])):
            y1 = y.copy()
            y1[1] += dU
            s = cav.state(0.0, y1, T0)
            heos.update(CP.DmassUmass_INPUTS, y1[0] / V, y1[1] / y1[0])
            worst = max(worst, abs(s.pressure / heos.p() - 1.0), abs(s.temperature / heos.T() - 1.0))
        assert cav.state(0.0, y, 1.2 * T0).pressure == pytest.approx(p0, rel=1e-10)  # the initial state itself
    assert worst <= 1e-6
    assert worst <= 1e-9  # what it measures: HEOS to the Newton tolerance


def test_ideal_gas_fluid_state_is_the_closed_form():
    """The same Newton on an ideal gas of constant cv: T = u/cv exactly (to round-off)."""
    g = IdealGasFluid(296.8, 1.4)
    T, pt = temperature_from_energy(g, 2.0, g.cv * 412.5, 300.0)
    assert T == pytest.approx(412.5, rel=1e-13)
    assert pt.p == pytest.approx(2.0 * 296.8 * 412.5, rel=1e-13)


def test_isentropic_expansion_conserves_entropy(tmp_path):
    """N2 at 300 bar in a rigid-walled cylinder whose volume triples (dU = −p dV, adiabatic): the entropy at the
    end equals the initial one, |Δs|/cv <= 1e-8 (a relative temperature error of 1e-8)."""
    from cases.model.build import build_model
    from cases.run.runner import run
    from cases.scene.files import load_scene

    (tmp_path / "v.csv").write_text("time [s],volume [m^3]\n0,0.01\n0.01,0.03\n")
    (tmp_path / "s.toml").write_text("""
[time]
end = 0.01
[solver]
rtol = 1e-11
[ambient]
gas = {N2 = 1.0}
[[cavity]]
name = "cylinder"
fluid = "real_gas"
gas = {N2 = 1.0}
pressure = 300.0e5
temperature = 300.0
volume_table = "v.csv"
""")
    r = run(build_model(load_scene(tmp_path / "s.toml")))
    cav = r.model.network.cavities[0]
    f = cav.fluid
    s0 = f.at(cav.initial_masses[0] / 0.01, 300.0)
    T1, m1, V1 = r.column("cylinder.temperature")[-1], r.column("cylinder.mass")[-1], r.column("cylinder.volume")[-1]
    s1 = f.at(m1 / V1, T1)
    assert V1 == pytest.approx(0.03)
    assert T1 < 230.0  # it did expand and cool
    assert abs(s1.s - s0.s) / s0.cv <= 1e-8


def test_energy_offset_matches_the_ideal_gas_species():
    """At vanishing density the fluid's h equals the ideal-gas species' h (the offset's purpose) at 200–500 K,
    to the cp0 fit's accuracy."""
    from cavity.gas import GasModel
    from cavity.species import species_from_coolprop

    gas = GasModel((species_from_coolprop("N2"),))
    mix = gas.mixture([1.0])
    f = RealFluid("Nitrogen", mix.enthalpy, 300.0)
    for T in (200.0, 300.0, 500.0):
        assert f.at(1e-6, T).h == pytest.approx(mix.enthalpy(T), abs=1e-5 * mix.enthalpy(300.0))
    assert not math.isnan(f.offset)


def test_metastable_view_is_the_fluid_where_single_phase_and_refuses_the_dome():
    """The throat's frozen (metastable) view equals the fluid on single-phase states; the cavity's view names a
    two-phase state instead of returning it."""
    from cavity.realgas import RealGasSolveError

    f = RealFluid("CarbonDioxide")
    for rho, T in ((200.0, 320.0), (800.0, 350.0), (30.0, 250.0)):
        assert tuple(f.metastable.at(rho, T)) == tuple(f.at(rho, T))
    with pytest.raises(RealGasSolveError, match="two-phase"):
        f.at(360.0, 280.0)
    assert f.metastable.at(100.0, 270.0).c > 0.0  # supersaturated vapour: the gas branch continued


@pytest.mark.parametrize("fluid,rho,T", [("Nitrogen", 200.0, 250.0), ("Nitrogen", 5.0, 300.0),
                                         ("CarbonDioxide", 400.0, 320.0), ("Helium", 30.0, 80.0)])
def test_jet_derivatives_equal_central_differences(fluid, rho, T):
    """The jet's ∂/∂T|ρ and ∂/∂ρ|T of p, u, h, s and c (two of CoolProp's derivatives and the identities
    u_T = cv, h_T = cv + p_T/ρ, s_T = cv/T, u_ρ = (p − T p_T)/ρ², h_ρ = u_ρ + p_ρ/ρ − p/ρ², s_ρ = −p_T/ρ²)
    against central differences of HEOS evaluations (truncation and round-off below 1e-8 at these steps, CO2
    near its critical point included): <= 1e-7."""
    f = RealFluid(fluid)
    _, dT, dR = f.jet(rho, T, True)
    eT, eR = 1e-5 * T, 1e-6 * rho
    for k in range(5):
        fd_T = (f.at(rho, T + eT)[k] - f.at(rho, T - eT)[k]) / (2 * eT)
        fd_R = (f.at(rho + eR, T)[k] - f.at(rho - eR, T)[k]) / (2 * eR)
        assert dT[k] == pytest.approx(fd_T, rel=1e-7, abs=1e-9 * abs(f.at(rho, T)[k]) / T), k
        assert dR[k] == pytest.approx(fd_R, rel=1e-7, abs=1e-9 * abs(f.at(rho, T)[k]) / rho), k


def test_state_from_the_predictor_equals_a_cold_newton():
    """RealFluid.state (first-order prediction off the previous call, a Taylor last step) along a path with
    jumps of up to 30 % equals temperature_from_energy started far away, and HEOS's (ρ, u) flash, to 1e-12."""
    f, g = RealFluid("Nitrogen"), RealFluid("Nitrogen")
    heos = CP.AbstractState("HEOS", "Nitrogen")
    rng = np.random.default_rng(3)
    rho, T = 150.0, 280.0
    for _ in range(60):
        rho *= 1.0 + 0.3 * (rng.random() - 0.5) * (rng.random() < 0.2) + 1e-4 * rng.standard_normal()
        T *= 1.0 + 1e-3 * rng.standard_normal()
        u = g.at(rho, T).u
        T1, pt = f.state(rho, u, 300.0)
        T2, ref = temperature_from_energy(g, rho, u, 500.0)
        assert T1 == pytest.approx(T2, rel=1e-12) and pt.p == pytest.approx(ref.p, rel=1e-12)
        heos.update(CP.DmassUmass_INPUTS, rho, u - f.offset)
        assert pt.p == pytest.approx(heos.p(), rel=1e-10)


@pytest.mark.parametrize("fluid,rho,T", [("Nitrogen", 302.6, 293.0), ("Nitrogen", 40.0, 110.0),
                                         ("CarbonDioxide", 200.0, 305.0), ("CarbonDioxide", 700.0, 320.0)])
def test_a_guess_inside_the_dome_still_finds_the_single_phase_state(fluid, rho, T):
    """A first guess whose (ρ, T) is two-phase (after a failed step, the anchor and the guess sit at the dew line:
    N2 at its critical density guessed at 101 K) is not itself an error: the Newton restarts from above the
    critical temperature and finds the state, as HEOS's (ρ, u) flash; a state inside the dome still is one."""
    f = RealFluid(fluid)
    heos = CP.AbstractState("HEOS", fluid)
    u = f.at(rho, T).u
    cold = 0.6 * heos.T_critical()
    with pytest.raises(Exception):
        f.at(rho, cold)  # the guess is two-phase
    T1, pt = f.state(rho, u, cold)
    assert T1 == pytest.approx(T, rel=1e-12)
    heos.update(CP.DmassUmass_INPUTS, rho, u - f.offset)
    assert pt.p == pytest.approx(heos.p(), rel=1e-10)
    heos.update(CP.QT_INPUTS, 0.5, cold)
    inside = 0.5 * (heos.saturated_liquid_keyed_output(CP.iDmass) + heos.saturated_vapor_keyed_output(CP.iDmass))
    with pytest.raises(Exception, match="two-phase"):
        f.state(inside, heos.umass() + f.offset, T)
