"""Pop vents on blocked leakage areas run compiled and match the Python path: the library's airbag (area steps
of time), its dynamic-body twin (areas of the body's displacement) and the seal (blocked by a flange), each with a
pop pressure on its blocked exchange, with and without a hold time."""
from dataclasses import replace

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import compiled_readback, history_columns, history_rows
from cases.scene.files import load_scene
from tests.test_compiled import both_paths

#: (case, pop pressure above ambient [Pa]): each pops mid-run (airbags peak near 1.6e5 Pa gauge, the seal near
#: 2.1e5 Pa gauge after starting at 2.0e5 Pa)
CASES_WITH_POP = [("airbag_impactor", 8.0e4), ("airbag_impactor_dynamic", 8.0e4), ("seal_vent", 2.05e5)]


def popped_model(name: str, pop: float, hold: float):
    scene = load_scene(HERE / CASES[name])
    ex = replace(scene.exchange[0], pop_pressure=pop, pop_hold_time=hold)
    return build_model(replace(scene, exchange=(ex,) + tuple(scene.exchange[1:])))


@pytest.mark.parametrize("hold", [0.0, 0.002], ids=["pop", "pop-hold"])
@pytest.mark.parametrize("name, pop", CASES_WITH_POP, ids=[c for c, _ in CASES_WITH_POP])
def test_a_pop_vent_on_a_blocked_area_is_the_same_on_both_paths(name, pop, hold):
    """Same events (the pop among them) at the same times (1e-9), steps within 2, and every history column
    (areas, flows, pressures) read back compiled within 10·rtol of the Python path's at the output times."""
    model = popped_model(name, pop, hold)
    net = model.network
    assert net.compiled_unsupported() is None
    fast, slow = both_paths(model)
    assert (fast.path, slow.path) == ("compiled", "python")
    labels = [label for _, label in slow.events]
    assert [label for _, label in fast.events] == labels
    pops = [t for t, label in slow.events if label.endswith(":pop-hold" if hold else ":pop")]
    assert len(pops) == 1 and 0.0 < pops[0] < model.scene.time.end
    np.testing.assert_allclose([t for t, _ in fast.events], [t for t, _ in slow.events], rtol=1e-9)
    assert abs(fast.stats["steps"] - slow.stats["steps"]) <= 2
    times = np.asarray(model.output_times)
    a, b = compiled_readback(model, fast)(times), history_rows(model, slow, times)
    columns = history_columns(model)
    for k, column in enumerate(columns):
        scale = np.max(np.abs(b[:, k]))
        np.testing.assert_allclose(a[:, k], b[:, k], rtol=10 * model.options.rtol,
                                   atol=10 * model.options.rtol * scale, err_msg=column)
    area = b[:, columns.index(f"{net.exchanges[0].name}.area [m^2]")]
    assert np.all(area[times < pops[0]] == 0.0) and area[times > pops[0]].max() > 0.0
    assert len(np.unique(area[times > pops[0]])) > 5  # the body keeps blocking the popped vent
