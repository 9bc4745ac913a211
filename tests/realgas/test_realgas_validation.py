"""The measured vessel experiments added to cases/validation/ (docs/validation.md): each scene's figures against
its measurement, with margins around what the model gives (rtol 1e-4 moves them by < 0.1), so that a change of
the physics that moves a figure fails here. Each scene builds and runs in 0.02–0.3 s."""
from pathlib import Path

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import load_scene

VALIDATION = Path(__file__).resolve().parents[2] / "cases" / "validation"


def _csv(name):
    return np.loadtxt(VALIDATION / "data" / f"{name}.csv", delimiter=",", skiprows=1).T


def _probes(stem, names):
    """The mean of the named probes on the first one's times."""
    t, v = _csv(f"{stem}_{names[0]}")
    return t, np.mean([v] + [np.interp(t, *_csv(f"{stem}_{n}")) for n in names[1:]], axis=0)


def _rms(r, column, t, v, scale=1.0):
    e = np.interp(t, r.column("time"), r.column(column)) / scale - v
    return float(np.sqrt(np.mean(e ** 2)))


@pytest.fixture(scope="module")
def runs():
    cache = {}

    def get(scene):
        if scene not in cache:
            cache[scene] = run(build_model(load_scene(VALIDATION / f"{scene}.toml")))
        return cache[scene]
    return get


def test_h2_100bar_discharge(runs):
    """Woodfield et al., H2 from 100 bar through 0.5 mm: p RMS 1.08 bar; the gas minimum 249.3 K, 3.8 K above
    the probes' mean minimum (245.5 K; the low probe 237 K); after the minimum the computed gas warms faster than
    either probe (T RMS 13.3 K)."""
    r = runs("h2_100bar_discharge")
    assert _rms(r, "vessel.pressure", *_csv("h2_100bar_pressure"), 1e5) <= 1.3
    t, T = _probes("h2_100bar", ("gas_high", "gas_low"))
    assert abs(r.column("vessel.temperature").min() - T.min()) <= 5.0
    assert 10.0 <= _rms(r, "vessel.temperature", t, T) <= 16.0


@pytest.mark.parametrize("run_no, p_rms, T_rms, dT_min, wall_rms", [(7, 4.2, 4.1, 2.2, 2.7), (8, 1.6, 2.1, -2.45, 4.05)])
def test_h2_138bar_discharges(runs, run_no, p_rms, T_rms, dT_min, wall_rms):
    """Byrnes et al. runs 7 (30 s, insulated outside) and 8 (8 min, to 13.5 bar): p RMS 4.2 and 1.6 bar, gas T
    RMS 4.1 and 2.1 K, the gas minimum 2.2 K above and 2.45 K below the measured, the lumped wall against the
    mean wall probe 2.7 and 4.05 K RMS (each within 0.5 bar or 0.5 K)."""
    r = runs(f"h2_138bar_discharge_run{run_no}")
    stem = f"h2_138bar_run{run_no}"
    assert _rms(r, "vessel.pressure", *_csv(f"{stem}_pressure"), 1e5) == pytest.approx(p_rms, abs=0.5)
    t, T = _csv(f"{stem}_gas_mean")
    assert _rms(r, "vessel.temperature", t, T) == pytest.approx(T_rms, abs=0.5)
    assert r.column("vessel.temperature").min() - T.min() == pytest.approx(dT_min, abs=0.5)
    assert _rms(r, "vessel.wall_temperature", *_csv(f"{stem}_wall_mean")) == pytest.approx(wall_rms, abs=0.5)


def test_he_700bar_type_iv(runs):
    """KIT, He from 700 bar, HDPE liner and composite shell: the gas minimum 178.2 K (measured 177.5 K), but at
    74 s where the probe's is at 100 s, and the gas then warms faster (T RMS 18.7 K; the thermocouple lag Molkov
    et al. analysed); p RMS 8.4 bar, the model discharging faster than measured."""
    r = runs("he_700bar_typeIV_discharge")
    t, T = _csv("he_700bar_gas_mean")
    Tc = r.column("vessel.temperature")
    assert abs(Tc.min() - T.min()) <= 2.0
    assert 65.0 <= r.column("time")[np.argmin(Tc)] <= 85.0
    assert _rms(r, "vessel.pressure", *_csv("he_700bar_pressure"), 1e5) == pytest.approx(8.4, abs=1.0)
    assert _rms(r, "vessel.temperature", t, T) == pytest.approx(18.7, abs=1.0)
    inner, outer = r.column("vessel.wall_temperature"), r.column("vessel.outer_wall_temperature")
    assert inner.min() < 220.0 and outer.min() > 283.0  # the cold stays in the liner: 70 K across the wall


def test_h2_700bar_type_iv(runs):
    """GasTeF, H2 from 700 bar at 1.8 g/s: the gas minimum 215.9 K, below the probes' mean minimum (224 K) and
    2 K below the lowest probe's (218 K); the outer surface within 1.8 K RMS of its probe."""
    r = runs("h2_700bar_typeIV_discharge")
    _, low = _csv("h2_700bar_gas_low")
    assert low.min() - 5.0 <= r.column("vessel.temperature").min() <= low.min()
    assert _rms(r, "vessel.outer_wall_temperature", *_csv("h2_700bar_wall_outer")) <= 2.3


def test_ng_120bar_discharge(runs):
    """Haque et al., methane/ethane from 120 bar through a 59 mm conducting steel wall: p RMS 1.46 bar, the gas
    minimum 264.9 K (measured 262.8 K), the inner wall layer 2.2 K RMS from its probe."""
    r = runs("ng_120bar_discharge")
    assert _rms(r, "vessel.pressure", *_csv("ng_120bar_pressure"), 1e5) <= 1.8
    _, T = _csv("ng_120bar_gas_mean")
    assert abs(r.column("vessel.temperature").min() - T.min()) <= 3.0
    assert _rms(r, "vessel.wall_temperature", *_csv("ng_120bar_wall_inner")) <= 2.7


def test_h2_fillings(runs):
    """Woodfield et al.'s filling: the set-up's orifice from 100 bar gives a steady 0.36 g/s where the measured
    flow ramps from 0.2 to 0.75 g/s, so the computed peak (354.3 K) comes at the start and the pressure lags (RMS
    8.3 bar); the measured flow, which delivers 9 % more gas than the measured end state holds, overshoots to 120
    bar. The Type III filling (Dicken and Mérida) ends at 386 bar and 83.0 °C (HydDown's manual: measured 68.9 °C,
    HydDown 74.2 °C), its liner's gas side 25.5 K below the gas."""
    r = runs("h2_100bar_filling")
    assert r.column("vessel.temperature").max() == pytest.approx(354.3, abs=1.0)
    assert _rms(r, "vessel.pressure", *_csv("h2_100bar_filling_pressure"), 1e5) == pytest.approx(8.3, abs=1.0)
    assert r.column("vessel.pressure")[-1] == pytest.approx(100e5, rel=1e-3)
    m = runs("h2_100bar_filling_measured_flow")
    assert m.column("vessel.pressure").max() / 1e5 == pytest.approx(120.0, abs=1.5)
    d = runs("h2_typeIII_filling")
    assert d.column("vessel.pressure")[-1] / 1e5 == pytest.approx(386.5, abs=2.0)
    assert d.column("vessel.temperature")[-1] - 273.15 == pytest.approx(83.0, abs=1.0)
    assert d.column("vessel.temperature")[-1] - d.column("vessel.wall_temperature")[-1] == pytest.approx(25.5, abs=3)


@pytest.mark.parametrize("rate, t_close, dT_max, T_rms", [(5, 165.0, 1.1, 3.3), (10, 82.5, -0.1, 4.2),
                                                          (30, 29.0, -3.3, 5.6)])
def test_striednig_fillings(runs, rate, t_close, dT_max, T_rms):
    """Striednig et al., H2 from 50 to 240 bar at 5, 10, 30 MPa/min through the set-ups' orifices from 480 bar:
    the orifice closes for good at 240 bar (at 165, 82.5, 29 s: 8 % before HydDown's 180, 90, 31.5 s, the real-gas
    critical flux being 8.2 % above HydDown's formula at 480 bar), the vessel's mass stays and its pressure falls as
    the gas cools; the peak gas temperature 1.1 K above, 0.1 and 3.3 K below the measured (each within 1 K), T RMS
    3.3, 4.2, 5.6 K (within 0.7 K), and the last point within 1 K of the measured."""
    r = runs(f"h2_striednig_{rate}MPa_min_filling")
    closes = [t for t, label in r.trajectory.events if label == "orifice:close"]
    assert len(closes) == 1 and closes[0] == pytest.approx(t_close, rel=0.02)
    t, p, m = r.column("time"), r.column("vessel.pressure"), r.column("vessel.mass")
    assert p.max() == pytest.approx(240e5, rel=2e-3) and p[-1] < 235e5
    after = t > closes[0]
    assert np.ptp(m[after]) <= 1e-9 * m[-1]
    tm, Tm = _csv(f"h2_striednig_{rate}MPa_min_gas_mean")
    T = r.column("vessel.temperature")
    assert T.max() - Tm.max() == pytest.approx(dT_max, abs=1.0)
    assert abs(T.max() - Tm.max()) <= 5.0
    assert _rms(r, "vessel.temperature", tm, Tm) == pytest.approx(T_rms, abs=0.7)
    assert T[-1] == pytest.approx(Tm[-1], abs=1.0)


def test_air_filling_measured(runs):
    """The air filling from 3.7 kPa at 295 K: pressure within 0.022 bar RMS of the measured; the gas peaks at 326.3 K
    after 1 s, 12.2 K above the upper probe's 314.1 K at 7 s (HydDown: 320.7 K at 6 s, its inflow enthalpy blended
    from the reservoir's u to h over the first seconds), T RMS 8.8 K."""
    r = runs("air_3_7kPa_filling_271mm")
    assert _rms(r, "vessel.pressure", *_csv("air_3_7kPa_271mm_pressure"), 1e5) <= 0.03
    t, T = _csv("air_3_7kPa_271mm_gas_high")
    assert r.column("vessel.temperature").max() == pytest.approx(326.3, abs=1.0)
    assert _rms(r, "vessel.temperature", t, T) == pytest.approx(8.8, abs=1.0)
