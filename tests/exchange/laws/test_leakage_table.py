"""MASS / VOLUME RATE LEAKAGE tables: validation, interpolation, extrapolation, and the orifice-law oracle."""
import dataclasses
import math

import numpy as np
import pytest

from exchange.laws.leakage_table import LeakageTable, leakage_table_mass_flow
from exchange.laws.orifice import orifice_mass_flow

P_DOWN = 1.0e5   # Pa
T0 = 300.0       # K
R_AIR = 287.0
GAMMA_AIR = 1.4


def orifice_flux(dp):
    """Orifice-law mass flux [kg/(s m^2)] for cavity pressure P_DOWN + dp venting to P_DOWN."""
    return orifice_mass_flow(P_DOWN + dp, T0, P_DOWN, R_AIR, GAMMA_AIR, 1.0)


# ---------------------------------------------------------------- validation

@pytest.mark.parametrize("dp, flow, message", [
    ((1.0, 2.0), (0.0, 1.0), r"row 1 must be \(0, 0\)"),
    ((0.0, 2.0), (0.5, 1.0), r"row 1 must be \(0, 0\)"),
    ((0.0, 2.0, 1.0), (0.0, 1.0, 2.0), r"row 3: \|dp\| must be strictly greater than row 2's 2.0 Pa, got 1.0"),
    ((0.0, 2.0, 2.0), (0.0, 1.0, 2.0), r"row 3: \|dp\| must be strictly greater"),
    ((0.0, -1.0), (0.0, 1.0), r"row 2: \|dp\| must be strictly greater than row 1's 0.0 Pa"),
    ((0.0, 1.0, 2.0), (0.0, 1.0, -0.5), r"row 3: flow per area must be >= 0, got -0.5"),
    ((0.0, 1.0), (0.0, math.nan), r"row 2: values must be finite"),
    ((0.0, math.inf), (0.0, 1.0), r"row 2: values must be finite"),
    ((0.0, 1.0), (0.0,), r"2 \|dp\| values but 1 flow values"),
    ((0.0,), (0.0,), r"at least 2 rows"),
])
def test_invalid_tables_are_rejected_with_row_and_expectation(dp, flow, message):
    with pytest.raises(ValueError, match=message):
        LeakageTable(dp=dp, flow=flow)


def test_invalid_options_and_row_shapes():
    with pytest.raises(ValueError, match="kind must be one of"):
        LeakageTable((0.0, 1.0), (0.0, 1.0), kind="heat")
    with pytest.raises(ValueError, match="extrapolation must be one of"):
        LeakageTable((0.0, 1.0), (0.0, 1.0), extrapolation="cubic")
    with pytest.raises(ValueError, match=r"row 2: expected 2 values, got 3"):
        LeakageTable.from_rows([(0.0, 0.0), (1.0, 2.0, 3.0)])


def test_table_is_frozen_and_normalised_to_float_tuples():
    t = LeakageTable(dp=[0, 10], flow=[0, 1])
    assert t.dp == (0.0, 10.0) and isinstance(t.flow, tuple)
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.dp = (0.0, 5.0)


def test_abaqus_row_order_is_flow_then_dp():
    a = LeakageTable.from_abaqus_rows([(0.0, 0.0), (2.0, 100.0), (3.0, 300.0)])
    b = LeakageTable.from_rows([(0.0, 0.0), (100.0, 2.0), (300.0, 3.0)])
    assert a == b


# ---------------------------------------------------------------- evaluation

def test_interpolation_nodes_midpoints_and_extrapolation_rules():
    rows = [(0.0, 0.0), (1000.0, 2.0), (3000.0, 3.0)]
    lin = LeakageTable.from_rows(rows)
    const = LeakageTable.from_rows(rows, extrapolation="constant")
    for dp, q in rows:
        assert lin.flow_per_area(dp) == q
    assert lin.flow_per_area(500.0) == 1.0
    assert lin.flow_per_area(2000.0) == 2.5
    assert lin.flow_per_area(5000.0) == 4.0        # last slope 0.5e-3 continued
    assert const.flow_per_area(5000.0) == 3.0
    assert lin.flow_per_area(-10.0) == 0.0 and lin.flow_per_area(math.nan) == 0.0


def test_falling_last_segment_is_clamped_at_zero_flow():
    t = LeakageTable.from_rows([(0.0, 0.0), (1.0, 2.0), (2.0, 1.0)])
    assert t.flow_per_area(2.5) == pytest.approx(0.5)
    assert t.flow_per_area(10.0) == 0.0


@pytest.mark.parametrize("extrapolation", ["linear", "constant"])
def test_array_path_matches_scalar_path(extrapolation):
    t = LeakageTable.from_rows([(0.0, 0.0), (1.0, 2.0), (2.0, 1.0), (4.0, 1.5)], extrapolation=extrapolation)
    x = np.array([-1.0, 0.0, 0.3, 1.0, 1.7, 2.0, 3.9, 4.0, 6.0, 20.0])
    np.testing.assert_allclose(t.flow_per_area(x), [t.flow_per_area(float(v)) for v in x], rtol=1e-15, atol=0)


def test_mass_and_volume_tables_give_mass_flow():
    rows = [(0.0, 0.0), (1.0e4, 0.5)]
    mass = LeakageTable.from_rows(rows)
    vol = LeakageTable.from_rows(rows, kind="volume")
    assert leakage_table_mass_flow(mass, 5.0e3, 0.02) == pytest.approx(0.005)
    assert leakage_table_mass_flow(vol, 5.0e3, 0.02, rho_up=1.2) == pytest.approx(0.006)
    assert leakage_table_mass_flow(vol, -5.0e3, 0.02, rho_up=1.2) == 0.0
    with pytest.raises(ValueError, match="needs the upstream density"):
        leakage_table_mass_flow(vol, 5.0e3, 0.02)


def test_continuous_at_zero_dp():
    t = LeakageTable.from_rows([(0.0, 0.0), (100.0, 1.0), (400.0, 2.0)])
    values = [t.flow_per_area(10.0 ** -k) for k in range(13)]
    assert all(math.isfinite(v) and v >= 0.0 for v in values)
    assert values == sorted(values, reverse=True)
    assert values[-1] == pytest.approx(1e-14, rel=1e-9)   # slope 0.01 times 1e-12
    assert t.flow_per_area(0.0) == 0.0


# ---------------------------------------------------------------- oracle: a sampled orifice law

STEP = 2000.0          # Pa, table spacing h
N_SEGMENTS = 100       # up to Δp = 2e5 Pa: through the choke point at Δp ≈ 89.3 kPa
FD_STEP = 20.0         # Pa, finite-difference step for f''
SAFETY = 1.1           # margin on the sampled max |f''|
ABS_TOL = 1e-12        # kg/(s m^2): rounding of f ≈ 500 in the choked (linear, f'' = 0) segments


def test_sampled_orifice_law_is_reproduced_within_linear_interpolation_error():
    nodes = [k * STEP for k in range(N_SEGMENTS + 1)]
    table = LeakageTable(dp=nodes, flow=[orifice_flux(x) for x in nodes])
    worst_ratio = 0.0
    for k in range(1, N_SEGMENTS):          # segment [kh, (k+1)h]; the first one is checked below
        a, b = nodes[k], nodes[k + 1]
        grid = np.linspace(a, b, 41)
        f2 = [(orifice_flux(x + FD_STEP) - 2 * orifice_flux(x) + orifice_flux(x - FD_STEP)) / FD_STEP ** 2
              for x in grid]
        bound = SAFETY * max(abs(v) for v in f2) * STEP ** 2 / 8.0
        errors = [orifice_flux(x) - table.flow_per_area(x) for x in grid]
        assert max(abs(e) for e in errors) <= bound + ABS_TOL, (k, max(errors), bound)
        assert min(errors) >= -ABS_TOL          # concave law: the chord lies below it
        if bound > ABS_TOL:
            worst_ratio = max(worst_ratio, max(abs(e) for e in errors) / bound)
    # the bound is tight where f'' is nearly constant (chord error = |f''| h^2 / 8 exactly for a parabola)
    assert worst_ratio > 0.5


def test_first_segment_sqrt_like_error():
    # Near Δp = 0 the orifice flux is ~ c sqrt(Δp) (|f''| unbounded); a chord of c sqrt(x) on [0, h] errs by at
    # most f(h) / 4 (at x = h/4). Allow 0.3 f(h) for the O(Δp/p) deviation from a pure square root.
    table = LeakageTable(dp=[0.0, STEP, 2 * STEP], flow=[0.0, orifice_flux(STEP), orifice_flux(2 * STEP)])
    grid = np.linspace(0.0, STEP, 201)
    errors = [orifice_flux(x) - table.flow_per_area(x) for x in grid]
    assert min(errors) >= 0.0
    assert max(errors) <= 0.3 * orifice_flux(STEP)
    assert max(errors) >= 0.2 * orifice_flux(STEP)     # and it is sqrt-like, not accidentally small
