"""Hard cases: a vent that a vibrating plate blocks and uncovers 30 times, and a vent that pops open onto a huge area.

Toggling: a rigid 0.15 L tank of constant-cp N2 at 3 bar blows down (choked throughout) through a flat annular seat
(cases/meshes/seal_leak.obj, z = 0) that a flat plate covers whenever it comes within the contact tolerance. The plate
moves on a triangle wave, so the seat is blocked on exactly known intervals. A rigid adiabatic cavity with no inflow
is frozen while blocked, so the state depends only on the accumulated open time t_o, and the choked adiabatic closed
form p/p0 = [1 + (γ−1)/2 · t_o/τ]^(−2γ/(γ−1)) holds at every output time: every toggle must be located exactly.

Pop: a 60 L tank filled at 0.5 kg/s pops a 50 cm² vent at 0.5 bar gauge; the pressure then falls without
overshoot towards the level where the vent passes the inflow (a fast transient right after a discontinuity).
"""
import math
from pathlib import Path

import numpy as np
import pytest

from hard_scenes import GAMMA, MONOTONE_RTOL, P_AMB, R_N2, check_sane, run_scene, series, tank

SEAT = Path(__file__).resolve().parents[2] / "cases" / "meshes" / "seal_leak.obj"
PERIOD, CYCLES = 1e-3, 30          # [s], [-] triangle wave of the plate
LIFT0, STROKE, TOL = 3e-4, 2.8e-4, 1e-4  # [m] initial gap, stroke towards the seat, contact tolerance
P0, V, CD, AREA, T0 = 3.0e5, 1.5e-4, 0.6, 3.0e-6, 300.0


def plate_displacement(t):
    """Triangle wave 0 → STROKE → 0 over each PERIOD [m]."""
    phase = np.mod(t, PERIOD) / PERIOD
    return STROKE * (1.0 - np.abs(2.0 * phase - 1.0))


def open_time(t):
    """Accumulated time the seat was uncovered up to t [s] (blocked while LIFT0 − d(t) ≤ TOL)."""
    frac_blocked = 1.0 - (LIFT0 - TOL) / STROKE  # part of each period with d ≥ LIFT0 − TOL
    whole = np.floor(t / PERIOD)
    rest = np.clip(t - whole * PERIOD, 0.0, PERIOD)
    half = PERIOD / 2.0
    t_in = half * (1.0 - frac_blocked)  # time in the period when the seat is covered
    blocked_in_rest = np.clip(np.minimum(rest, PERIOD - t_in) - t_in, 0.0, None)
    return t - whole * frac_blocked * PERIOD - blocked_in_rest


def toggling_scene(folder: Path) -> dict:
    times = np.arange(0.0, CYCLES * PERIOD + 1e-12, PERIOD / 2.0)
    (folder / "plate.csv").write_text("t,d\n" + "".join(f"{float(t)!r},{float(plate_displacement(t))!r}\n" for t in times))
    data = tank(volume=V, pressure=P0)
    data["time"] = {"end": CYCLES * PERIOD, "output_interval": PERIOD / 40.0}
    data["body"] = [{"name": "plate", "box": [0.0, 0.0, LIFT0 + 1e-3, 0.05, 0.05, 2e-3], "axis": [0.0, 0.0, -1.0],
                     "displacement_table": "plate.csv"}]
    data["exchange"] = [{"name": "seat", "from": "tank", "discharge_coefficient": CD, "effective_area": AREA,
                         "leakage_surface": str(SEAT), "blocked_by": ["plate"], "contact_tolerance": TOL}]
    return data


def test_vent_blocked_thirty_times_follows_the_closed_form_in_open_time(tmp_path):
    r = run_scene(toggling_scene(tmp_path), tmp_path)
    check_sane(r, max_steps=3000)
    t, p, T, m = series(r)
    area = r.column("seat.area")
    blocked = area == 0.0
    starts = np.flatnonzero(blocked[1:] & ~blocked[:-1])
    assert len(starts) == CYCLES and np.all((area == 0.0) | np.isclose(area, AREA, rtol=1e-12, atol=0.0))
    assert np.all(np.diff(p) <= MONOTONE_RTOL * p[:-1])  # outflow only
    c_star = CD * (2.0 / (GAMMA + 1.0)) ** ((GAMMA + 1.0) / (2.0 * (GAMMA - 1.0)))
    tau = V / (c_star * AREA * math.sqrt(GAMMA * R_N2 * T0))
    closed = P0 * (1.0 + 0.5 * (GAMMA - 1.0) * open_time(t) / tau) ** (-2.0 * GAMMA / (GAMMA - 1.0))
    assert p.min() > 1.9 * P_AMB  # choked throughout, so the closed form applies
    assert np.max(np.abs(p / closed - 1.0)) < 1e-8


def pop_scene() -> dict:
    data = tank()
    data["time"] = {"end": 0.2, "output_interval": 1e-4}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "mass_flow": 0.5,
                                      "temperature": 600.0, "gas": {"N2": 1.0}}]
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 5e-3, "pop_pressure": 5e4}]
    return data


def test_pop_open_onto_a_huge_vent_falls_without_overshoot(tmp_path):
    r = run_scene(pop_scene(), tmp_path)
    check_sane(r, max_steps=2000)
    t, p, T, m = series(r)
    t_pop = 5e4 * 0.06 / (GAMMA * R_N2 * 0.5 * 600.0)  # p = p0 + γRṁT_in t/V reaches the pop pressure
    opened = [te for te, label in r.summary["solver"]["event log"] if label == "vent:pop"]
    assert opened == [pytest.approx(t_pop, abs=1e-9)]
    assert p.max() <= (P_AMB + 5e4) * (1.0 + 1e-9)  # bounded by the pop pressure
    after = t > t_pop
    assert np.all(np.diff(p[after]) <= MONOTONE_RTOL * p[after][:-1])  # monotone fall, no overshoot
    assert P_AMB < p[-1] < P_AMB + 5e4
    # the gas warms towards the inflator's 600 K, so the vent flow falls towards the 0.5 kg/s inflow from above
    flow = r.column("vent.mass_flow")[t > t_pop + 0.01]
    assert np.all(flow > 0.5) and np.all(np.diff(flow) <= 0.0) and flow[-1] < 1.1 * 0.5
