"""Activations on blocked leakage areas on the engine, the compiled DOP853 against scipy's: pop vents on the library's airbag
(area steps of time), its dynamic-body twin (areas of the body's displacement) and the seal (blocked by a flange),
with and without a hold time; DELTA LEAKAGE AREA on the dynamic-body airbag's vent, opened by time or by a pop (the
area it subtracts is the body's at that moment, known only during the run)."""
from dataclasses import replace

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.results.readback import history_columns, history_rows
from cases.scene.files import load_scene
from tests.exchange.engine.pairs import assert_same_history as assert_same_readback, both_integrators

#: (case, pop pressure above ambient [Pa]): each pops mid-run (airbags peak near 1.6e5 Pa gauge, the seal near
#: 2.1e5 Pa gauge after starting at 2.0e5 Pa)
CASES_WITH_POP = [("airbag_impactor", 8.0e4), ("airbag_impactor_dynamic", 8.0e4), ("seal_vent", 2.05e5)]


def popped_model(name: str, pop: float, hold: float, **activation):
    scene = load_scene(HERE / CASES[name])
    ex = replace(scene.exchange[0], pop_pressure=pop, pop_hold_time=hold, **activation)
    return build_model(replace(scene, exchange=(ex,) + tuple(scene.exchange[1:])))


def assert_same_history(model, fast, slow):
    """Every history column (areas, flows, pressures) of the compiled DOP853 within 10·rtol of scipy's at the
    output times (of each column's largest magnitude), each read back compiled and pointwise alike; returns
    scipy's history and its columns."""
    times = np.asarray(model.output_times)
    a, b = assert_same_readback(model, fast), history_rows(model, slow, times)
    columns = history_columns(model)
    for k, column in enumerate(columns):
        scale = np.max(np.abs(b[:, k]))
        np.testing.assert_allclose(a[:, k], b[:, k], rtol=10 * model.options.rtol,
                                   atol=10 * model.options.rtol * scale, err_msg=column)
    return b, columns


@pytest.mark.parametrize("hold", [0.0, 0.002], ids=["pop", "pop-hold"])
@pytest.mark.parametrize("name, pop", CASES_WITH_POP, ids=[c for c, _ in CASES_WITH_POP])
def test_a_pop_vent_on_a_blocked_area_is_the_same_on_both_integrators(name, pop, hold):
    """Same events (the pop among them) at the same times (1e-9), steps within 2, and every history column
    (areas, flows, pressures) within 10·rtol of each other at the output times."""
    model = popped_model(name, pop, hold)
    net = model.network
    assert net.compiled_unsupported() is None
    fast, slow = both_integrators(model)
    labels = [label for _, label in slow.events]
    assert [label for _, label in fast.events] == labels
    pops = [t for t, label in slow.events if label.endswith(":pop-hold" if hold else ":pop")]
    assert len(pops) == 1 and 0.0 < pops[0] < model.scene.time.end
    np.testing.assert_allclose([t for t, _ in fast.events], [t for t, _ in slow.events], rtol=1e-9)
    assert abs(fast.stats["steps"] - slow.stats["steps"]) <= 2
    times = np.asarray(model.output_times)
    b, columns = assert_same_history(model, fast, slow)
    area = b[:, columns.index(f"{net.exchanges[0].name}.area [m^2]")]
    assert np.all(area[times < pops[0]] == 0.0) and area[times > pops[0]].max() > 0.0
    assert len(np.unique(area[times > pops[0]])) > 5  # the body keeps blocking the popped vent


@pytest.mark.parametrize("how", ["by time", "by pop"])
def test_delta_area_on_an_area_that_follows_the_dynamic_body(how):
    """Opened at 22 ms (the headform near its deepest, the vent 0.89 of 1.4 cm² open) or by a pop at 8e4 Pa gauge
    (~10 ms): the flow area is the body's area less its area at that moment, zero at first and growing as the
    headform rebounds; taking the area at the start instead (1.4 cm²) would leave the vent shut."""
    pop, opened = (0.0, 0.022) if how == "by time" else (8.0e4, 0.0)  # pop_pressure 0: none
    model = popped_model("airbag_impactor_dynamic", pop, 0.0, open_time=opened, delta_area=True)
    assert model.network.compiled_unsupported() is None
    fast, slow = both_integrators(model)
    assert [label for _, label in fast.events] == [label for _, label in slow.events]
    np.testing.assert_allclose([t for t, _ in fast.events], [t for t, _ in slow.events], rtol=1e-9)
    b, columns = assert_same_history(model, fast, slow)
    times, area = np.asarray(model.output_times), b[:, columns.index("vent.area [m^2]")]
    t_open = opened if not pop else [t for t, label in slow.events if label == "vent:pop"][0]
    assert np.all(area[times < t_open] == 0.0)
    assert 0.0 < area.max() < 0.6 * 1.4e-3 and area[-1] == area.max()  # 1.4 cm² less the area at the opening
