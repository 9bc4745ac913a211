"""Prescribed fluxes and the discharge-coefficient table."""
import dataclasses
import math

import numpy as np
import pytest

from exchange.laws.discharge import DischargeTable, discharge_coefficient
from exchange.laws.flux import mass_flux_mass_flow, volume_flux_mass_flow

# ---------------------------------------------------------------- flux

def test_mass_flux_is_flux_times_area_times_amplitude():
    assert mass_flux_mass_flow(0.5, 0.02) == pytest.approx(0.01, rel=1e-15)
    assert mass_flux_mass_flow(0.5, 0.02, amplitude=0.25) == pytest.approx(0.0025, rel=1e-15)
    assert mass_flux_mass_flow(-0.5, 0.02) == pytest.approx(-0.01, rel=1e-15)   # into the primary cavity
    assert mass_flux_mass_flow(0.5, 0.0) == 0.0


def test_volume_flux_uses_the_density():
    assert volume_flux_mass_flow(2.0, 0.01, 1.2) == pytest.approx(0.024, rel=1e-15)
    assert volume_flux_mass_flow(2.0, 0.01, 1.2, amplitude=-0.5) == pytest.approx(-0.012, rel=1e-15)


def test_flux_accepts_arrays():
    amp = np.array([0.0, 0.5, 1.0])
    np.testing.assert_allclose(mass_flux_mass_flow(0.5, 0.02, amp), [0.0, 0.005, 0.01], rtol=1e-15)
    np.testing.assert_allclose(volume_flux_mass_flow(2.0, np.array([0.01, 0.02]), 1.2), [0.024, 0.048], rtol=1e-15)


# ---------------------------------------------------------------- discharge coefficient

def test_discharge_table_interpolates_and_clamps():
    t = DischargeTable(x=(1.0e5, 2.0e5, 4.0e5), cd=(0.6, 0.8, 0.7))
    assert t(1.0e5) == 0.6 and t(2.0e5) == 0.8 and t(4.0e5) == 0.7
    assert t(1.5e5) == pytest.approx(0.7, rel=1e-14)
    assert t(3.0e5) == pytest.approx(0.75, rel=1e-14)
    assert t(0.0) == 0.6 and t(1.0e9) == 0.7          # clamped, not extrapolated


def test_discharge_array_path_matches_scalar_path():
    t = DischargeTable(x=(0.0, 0.01, 0.02), cd=(0.0, 0.7, 0.5), variable="time")
    x = np.array([-1.0, 0.0, 0.003, 0.01, 0.015, 0.02, 1.0])
    np.testing.assert_allclose(t(x), [t(float(v)) for v in x], rtol=1e-15, atol=0)


def test_single_row_table_is_a_constant():
    t = DischargeTable(x=(1.0e5,), cd=(0.62,))
    assert t(0.0) == t(1.0e5) == t(1.0e7) == 0.62


@pytest.mark.parametrize("x, cd, variable, message", [
    ((0.0, 1.0), (0.6, -0.1), "time", r"row 2: Cd must be >= 0, got -0.1"),
    ((2.0e5, 1.0e5), (0.6, 0.7), "pressure", r"row 2: pressure must be strictly greater than row 1's 200000.0 Pa"),
    ((0.0, 1.0, 1.0), (0.6, 0.7, 0.8), "time", r"row 3: time must be strictly greater than row 2's 1.0 s"),
    ((0.0, 1.0), (0.6, math.nan), "time", r"row 2: values must be finite"),
    ((0.0, 1.0), (0.6,), "time", r"2 time values but 1 Cd values"),
    ((), (), "time", r"at least one row"),
    ((0.0,), (0.6,), "temperature", r"variable must be one of"),
])
def test_invalid_discharge_tables(x, cd, variable, message):
    with pytest.raises(ValueError, match=message):
        DischargeTable(x=x, cd=cd, variable=variable)


def test_discharge_coefficient_dispatch():
    assert discharge_coefficient(0.62) == 0.62
    by_time = DischargeTable((0.0, 0.01), (0.0, 0.7), "time")
    by_pressure = DischargeTable((1.0e5, 2.0e5), (0.6, 0.8), "pressure")
    assert discharge_coefficient(by_time, pressure=1.5e5, time=0.005) == pytest.approx(0.35, rel=1e-14)
    assert discharge_coefficient(by_pressure, pressure=1.5e5, time=0.005) == pytest.approx(0.7, rel=1e-14)
    with pytest.raises(ValueError, match="function of time"):
        discharge_coefficient(by_time, pressure=1.5e5)
    with pytest.raises(dataclasses.FrozenInstanceError):
        by_time.cd = (1.0, 1.0)
