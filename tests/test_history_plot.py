"""history.png (cases.results.history_plot): the panels an engineer expects, one line per series in its colour
where the data put it, an FE run dashed over the pressure, a long title wrapped instead of cut."""
from types import SimpleNamespace

import numpy as np

from cases.results.history_plot import COLOURS, PANEL_HEIGHT, WIDTH, draw_history, history_panels, nice_ticks

COLUMNS = ["time [s]", "bag.pressure [Pa]", "bag.gauge_pressure [Pa]", "bag.temperature [K]", "vent.mass_flow [kg/s]",
           "vent.area [m^2]", "vent.blocked_fraction [-]", "plate.displacement [m]"]


def history(blocked=True):
    t = np.linspace(0.0, 0.03, 61)
    return np.column_stack([t, 1e5 + 1e6 * t, 1e6 * t, 300 - 100 * t, 0.1 + t, 1e-3 * (1 - t), t if blocked else 0 * t,
                            np.zeros_like(t)])


def test_panels_follow_the_columns():
    panels = history_panels(COLUMNS, history())
    assert [label for label, _ in panels] == ["pressure [kPa]", "temperature [K]", "mass flow [kg/s]",
                                              "exchange area [mm^2]", "blocked fraction [-]"]  # displacement all 0
    (name, t, values, dashed), = panels[0][1]  # gauge pressure left out
    assert name == "bag.pressure" and not dashed
    np.testing.assert_allclose(values, (1e5 + 1e6 * t * 1e-3) * 1e-3)  # kPa against ms
    assert len(history_panels(COLUMNS, history(blocked=False))) == 4
    fe = SimpleNamespace(times=np.array([0.0, 0.03]), pressures=np.array([2e5, 1e5]))
    *_, (name, t, values, dashed) = history_panels(COLUMNS, history(), {"bag": fe})[0][1]
    assert name == "bag (FE run)" and dashed and values.tolist() == [200.0, 100.0] and t.tolist() == [0.0, 30.0]


def test_each_line_is_drawn_in_its_colour_where_its_data_are():
    image = np.asarray(draw_history(COLUMNS, history(), "a title"))
    assert image.shape == (PANEL_HEIGHT * 5, WIDTH, 3)
    first = np.linalg.norm(image.astype(float) - COLOURS[0], axis=2) < 40.0  # antialiased: near the colour
    for k in range(5):  # every panel has its first series' line
        band = first[k * PANEL_HEIGHT:(k + 1) * PANEL_HEIGHT]
        assert band.sum() > 200
    # the pressure rises linearly from the lower left to the upper right of the first panel: the line's pixels in
    # each column lie on one straight line (but for the legend's sample, a short horizontal stroke)
    ys, xs = np.nonzero(first[:PANEL_HEIGHT])
    columns = np.unique(xs)
    middle = np.array([np.median(ys[xs == x]) for x in columns])
    slope, intercept = np.polyfit(columns, middle, 1)
    near = np.abs(middle - (slope * columns + intercept)) < 10.0
    slope, intercept = np.polyfit(columns[near], middle[near], 1)  # again without the legend's stroke
    on_line = np.abs(middle - (slope * columns + intercept)) < 2.0
    assert slope < -0.1 and on_line.mean() > 0.9 and np.ptp(columns[on_line]) > 0.8 * (WIDTH - 100)


def test_the_fe_run_is_dashed_black_and_a_long_title_wraps():
    fe = SimpleNamespace(times=np.linspace(0.0, 0.03, 4), pressures=np.array([2e5, 2.1e5, 1.9e5, 1.8e5]))
    title = "a title much longer than the width of the picture " * 4
    image = np.asarray(draw_history(COLUMNS, history(), title, {"bag": fe}))
    assert image.shape[0] > PANEL_HEIGHT * 5  # room for the title's lines
    top = image[:40].max(axis=2) < 100
    rows = np.flatnonzero(top.any(axis=1))
    assert np.count_nonzero(np.diff(rows) > 1) >= 1  # two lines of text
    assert not top[:, :3].any() and not top[:, -3:].any()  # nothing cut at the edges
    dark = image[40:PANEL_HEIGHT].max(axis=2) < 60
    assert dark.sum() > 300  # frame, ticks and the dashed FE line


def test_ticks_are_round_and_inside():
    for low, high in [(0.0, 1.0), (112.8, 263.0), (-150.0, 80.0), (1e-6, 5e-5)]:
        ticks = nice_ticks(low, high)
        assert 2 <= len(ticks) <= 6 and ticks.min() >= low and ticks.max() <= high
        step = np.diff(ticks)[0]
        mantissa = step / 10 ** np.floor(np.log10(step))
        assert any(abs(mantissa - m) < 1e-9 for m in (1, 2, 2.5, 5))
