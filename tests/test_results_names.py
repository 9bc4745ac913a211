"""Results[name] and Results.at(t, name) take the same names, with and without units; an unknown name is a
KeyError naming the closest columns; at(t) at an output time gives that history row (same dense output)."""
import numpy as np
import pytest

import ventsim
from ventsim.results import UnknownColumn


@pytest.fixture(scope="module")
def bag():
    return ventsim.run("cases/airbag_impactor_dynamic.toml")


def test_at_an_output_time_is_the_history_row_for_every_column(bag):
    history, columns = bag.raw.history, bag.raw.columns
    for k in (0, 37, len(history) // 2, len(history) - 1):
        t = history[k, 0]
        for j, name in enumerate(columns):
            # the same compiled read-back of the same dense output at the same t: equal to round-off
            tol = 1e-12 * (1 + abs(history[:, j]).max())
            assert bag.at(t, name) == pytest.approx(history[k, j], rel=1e-12, abs=tol), (name, t)


def test_names_with_and_without_units_agree(bag):
    t = 0.0123
    for name in ("cushion.pressure [Pa]", "vent.mass_flow [kg/s]", "vent.blocked_fraction [-]",
                 "headform.displacement [m]"):
        bare = name.split(" [")[0]
        assert bag.at(t, name) == bag.at(t, bare)
        assert np.array_equal(bag[name], bag[bare])
        assert np.array_equal(bag[name], bag.history[name].to_numpy())


def test_an_unknown_name_is_a_key_error_with_close_matches(bag):
    for call in (lambda n: bag[n], lambda n: bag.at(0.01, n)):
        with pytest.raises(KeyError) as info:
            call("cushion.presure")
        assert isinstance(info.value, UnknownColumn)
        assert str(info.value).startswith("no history column 'cushion.presure' (did you mean 'cushion.pressure [Pa]'")
    with pytest.raises(UnknownColumn, match=r"'cushion.pressure' is in \[Pa\], not in \[kPa\]"):
        bag["cushion.pressure [kPa]"]


def test_a_time_outside_the_run_is_named(bag):
    with pytest.raises(ValueError, match="t = 1.0 s is outside the run: give a time from 0 to 0.06 s"):
        bag.at(1.0, "cushion.pressure")


def test_tables_as_lists_of_lists_in_python_and_toml(tmp_path):
    rows = [[0.0, 0.1], [0.05, 0.2], [0.1, 0.0]]
    data = {"time": {"end": 0.1}, "cavity": [{"name": "tank", "pressure": 1e5, "temperature": 300.0,
                                              "volume": 0.01, "inflator": [{"name": "gen", "type": "mass_temperature",
                                                                            "mass_flow": rows, "temperature": 600.0}]}]}
    a = ventsim.run(ventsim.Scene(data))
    data["cavity"][0]["inflator"][0]["mass_flow"] = np.array(rows)
    b = ventsim.run(ventsim.Scene(data))
    assert np.array_equal(a["tank.pressure"], b["tank.pressure"])
    toml = tmp_path / "s.toml"
    toml.write_text('[time]\nend = 0.1\n[[cavity]]\nname = "tank"\npressure = 1e5\ntemperature = 300.0\n'
                    'volume = 0.01\n[[cavity.inflator]]\nname = "gen"\ntype = "mass_temperature"\n'
                    'mass_flow = [[0.0, 0.1], [0.05, 0.2], [0.1, 0.0]]\ntemperature = 600.0\n')
    c = ventsim.run(toml)
    assert np.array_equal(a["tank.pressure"], c["tank.pressure"])
