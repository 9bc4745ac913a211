"""Hard cases driven by the inflator: a step change in its tables, and choked ↔ unchoked transitions.

Steps are tables with two rows 1 ns apart (a table must increase strictly): the integrator stops at every row, so
the jump lies between two segments and the fill of a closed rigid tank still follows its closed form
p = p0 + γ·R·∫ṁ·T_in dt / V (same constant-cp gas) to the solver's tolerance.
"""
import numpy as np
import pytest

from cavity.tables import Table
from hard_scenes import GAMMA, MONOTONE_RTOL, P_AMB, R_N2, check_sane, run_scene, series, tank

MDOT = ((0.0, 0.0), (0.01, 0.0), (0.010000001, 2.0), (0.03, 2.0), (0.030000001, 0.0))  # [s], [kg/s]
T_IN = ((0.0, 500.0), (0.02, 500.0), (0.020000001, 900.0))  # [s], [K]


def write(path, rows):
    path.write_text("time [s],value\n" + "".join(f"{a!r},{b!r}\n" for a, b in rows))
    return path.name


def stepped(tmp_path, vented):
    data = tank()
    data["time"] = {"end": 0.05, "output_interval": 0.0005}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "gas": {"N2": 1.0},
                                      "mass_flow": write(tmp_path / "mdot.csv", MDOT),
                                      "temperature": write(tmp_path / "t_in.csv", T_IN)}]
    if vented:
        data["exchange"] = [{"name": "vent", "from": "tank", "area": 2e-4}]
    return data


def closed_tank_pressure(times):
    """p0 + γR/V ∫ ṁ T_in dt: the product of two piecewise-linear tables is quadratic per piece (Simpson exact)."""
    mdot, T = Table(*zip(*MDOT)), Table(*zip(*T_IN))
    knots = sorted({0.0, *mdot.x, *T.x, *times})
    energy, acc = {0.0: 0.0}, 0.0
    for a, b in zip(knots[:-1], knots[1:]):
        f = lambda t: mdot(t) * T(t)  # noqa: E731
        acc += (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b))
        energy[b] = acc
    return np.array([1e5 + GAMMA * R_N2 * energy[t] / 0.06 for t in times])


def test_step_in_inflator_tables_closed_tank_follows_closed_form(tmp_path):
    r = run_scene(stepped(tmp_path, vented=False), tmp_path)
    check_sane(r, max_steps=100)
    t, p, T, m = series(r)
    assert np.max(np.abs(p / closed_tank_pressure(list(t)) - 1.0)) < 1e-9
    assert np.all(np.diff(p) >= -MONOTONE_RTOL * p[1:])
    assert r.summary["solver"]["restarts"] >= len(MDOT) + len(T_IN) - 2  # stopped at every row


def test_step_in_inflator_tables_vented_tank_stays_below_closed_tank(tmp_path):
    r = run_scene(stepped(tmp_path, vented=True), tmp_path)
    check_sane(r, max_steps=200)
    t, p, T, m = series(r)
    assert np.all(p <= closed_tank_pressure(list(t)) * (1 + 1e-9))
    assert np.all(p >= P_AMB * (1 - 1e-9))
    after = t >= 0.030000001
    assert np.all(np.diff(p[after]) <= MONOTONE_RTOL * p[after][:-1]), "after the inflator stops p must fall"
    assert np.ptp(p[t <= 0.01]) <= 1e-12 * P_AMB, "nothing happens before the inflator starts"


def test_inflate_then_blow_down_crosses_choking_both_ways(tmp_path):
    """A 3 kg/s pulse of 50 ms into a vented 60 L tank: 1 → 7 bar (vent unchoked, then choked), then the blowdown
    back through choking and subsonic flow to near ambient."""
    data = tank()
    data["time"] = {"end": 1.5, "output_interval": 0.001}
    data["cavity"][0]["inflator"] = [{"name": "gen", "type": "mass_temperature", "gas": {"N2": 1.0},
                                      "temperature": 600.0,
                                      "mass_flow": write(tmp_path / "pulse.csv",
                                                         [(0.0, 3.0), (0.05, 3.0), (0.0500001, 0.0)])}]
    data["exchange"] = [{"name": "vent", "from": "tank", "area": 2e-4}]
    r = run_scene(data, tmp_path)
    check_sane(r, max_steps=300)
    t, p, T, m = series(r)
    bound = 1e5 + GAMMA * R_N2 * 3.0 * 600.0 * np.minimum(t, 0.05) / 0.06  # the same pulse into a closed tank
    assert np.all(p <= bound * (1 + 1e-9))
    pulse = t <= 0.05
    assert np.all(np.diff(p[pulse]) >= -MONOTONE_RTOL * p[pulse][1:])
    after = t >= 0.0500001
    assert np.all(np.diff(p[after]) <= MONOTONE_RTOL * p[after][:-1])
    assert p.max() > 2.0 * P_AMB > 1.2 * P_AMB > p[-1] > P_AMB
    chokes = [tt for tt, label in r.summary["solver"]["event log"] if label == "vent:choke"]
    assert len(chokes) == 2 and chokes[0] < 0.05 < chokes[1]  # chokes on the way up, unchokes on the way down
    crit = ((GAMMA + 1) / 2) ** (GAMMA / (GAMMA - 1))
    for tc in chokes:  # the switch sits where p/p_amb crosses the critical ratio
        assert r.model.network.states(tc, r.trajectory(tc))[0].pressure == pytest.approx(crit * P_AMB, rel=1e-8)
