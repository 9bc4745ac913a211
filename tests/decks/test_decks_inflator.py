"""An Abaqus inflator deck against the rigid adiabatic fill closed form, with the inflation delay of a step
INFLATION TIME AMPLITUDE, a constant MASS FLOW AMPLITUDE and an inflator mixture of one species."""
from __future__ import annotations

import numpy as np
import pytest

import tests.closed_forms as cf
from cases.decks import deck_scene, import_deck
from cases.scene.errors import SceneError
from cases.run.runner import run_scene

from .box_decks import head
from .box_decks import write as write_deck

DECK = head("rigid box filled by an inflator", "-273.15") + """*INITIAL CONDITIONS, TYPE=TEMPERATURE
 REF, 26.85
*FLUID INFLATOR PROPERTY, NAME=GEN, TYPE=TEMPERATURE AND MASS
 0.0, 326.85, 0.05
 1.0, 326.85, 0.05
*FLUID INFLATOR MIXTURE, NUMBER SPECIES=1, TYPE=MASS FRACTION
 N2
 0.0, 1.0
*FLUID INFLATOR, NAME=INF, PROPERTY=GEN
 REF
*AMPLITUDE, NAME=DEPLOY
 0.0, 0.0, 0.01, 0.0, 0.01, 1.0, 1.0, 1.0
*AMPLITUDE, NAME=HALF
 0.0, 0.5, 1.0, 0.5
*STEP
*DYNAMIC, EXPLICIT
 , 0.1
*FLUID INFLATOR ACTIVATION, INFLATION TIME AMPLITUDE=DEPLOY, MASS FLOW AMPLITUDE=HALF
 INF
*OUTPUT, HISTORY, NUMBER INTERVAL=100
*END STEP
"""


def write(tmp_path, text):
    return write_deck(tmp_path, text, name="fill.inp")


def test_delayed_fill_matches_the_closed_form(tmp_path):
    scene, imported = deck_scene(write(tmp_path, DECK), tmp_path / "out" / "fill.toml")
    inflator = imported.data["cavity"][0]["inflator"][0]
    assert inflator["start"] == 0.01 and inflator["scale"] == 0.5 and inflator["temperature"] == 600.0
    assert imported.data["cavity"][0]["temperature"] == 300.0  # θ − ABSOLUTE ZERO
    r = run_scene(scene)
    t, p = r.column("time"), r.column("tank.pressure")
    R = cf.R_U / 0.0280134
    ref = [cf.fill_pressure(max(0.0, x - 0.01), 1e5, 1.4, R, 0.025, 600.0, 0.06) for x in t]
    assert np.max(np.abs(p / ref - 1)) <= 1e-9
    assert abs(p[5] / 1e5 - 1) <= 1e-15  # nothing before the deployment time


def test_a_ramp_that_is_not_a_step_is_refused(tmp_path):
    deck = write(tmp_path, DECK.replace(" 0.0, 0.0, 0.01, 0.0, 0.01, 1.0, 1.0, 1.0", " 0.0, 0.0, 1.0, 1.0"))
    with pytest.raises(SceneError) as info:
        import_deck(deck)
    assert str(info.value) == (f"{deck}: line 36: *FLUID INFLATOR ACTIVATION: INFLATION TIME AMPLITUDE=DEPLOY: "
                               "ventsim reads a step from 0 to 1 (0 up to t_a, 1 from t_b = the next point on, "
                               "t_b - t_a <= 0.001 x the step time)")


def test_an_inflator_never_activated_is_a_note(tmp_path):
    imported = import_deck(write(tmp_path, DECK.replace("*FLUID INFLATOR ACTIVATION, INFLATION TIME AMPLITUDE="
                                                        "DEPLOY, MASS FLOW AMPLITUDE=HALF\n INF\n", "")))
    assert "inflator" not in imported.data["cavity"][0]
    assert imported.notes == ["inflator INF is never activated (*FLUID INFLATOR ACTIVATION): no inflow, as in Abaqus"]


def test_smooth_step_deployment_and_equally_spaced_flow_amplitude(tmp_path):
    """A SMOOTH STEP from 0 at 0.01 to 1 at 0.01 (no ramp) is the same delay; an EQUALLY SPACED constant 0.5 the
    same multiplier: the history is the tabular deck's."""
    text = DECK.replace("*AMPLITUDE, NAME=DEPLOY\n 0.0, 0.0, 0.01, 0.0, 0.01, 1.0, 1.0, 1.0",
                        "*AMPLITUDE, NAME=DEPLOY, DEFINITION=SMOOTH STEP\n 0.01, 0.0, 0.01, 1.0")
    text = text.replace("*AMPLITUDE, NAME=HALF\n 0.0, 0.5, 1.0, 0.5",
                        "*AMPLITUDE, NAME=HALF, DEFINITION=EQUALLY SPACED, FIXED INTERVAL=0.5\n 0.5, 0.5, 0.5")
    assert text != DECK
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a = import_deck(write(tmp_path / "a", text)).data["cavity"][0]["inflator"][0]
    b = import_deck(write(tmp_path / "b", DECK)).data["cavity"][0]["inflator"][0]
    assert a == b and a["start"] == 0.01 and a["scale"] == 0.5


def test_smooth_step_is_refused_as_a_table(tmp_path):
    text = DECK.replace("*AMPLITUDE, NAME=HALF\n 0.0, 0.5, 1.0, 0.5",
                        "*AMPLITUDE, NAME=HALF, DEFINITION=SMOOTH STEP\n 0.0, 0.5, 1.0, 0.5")
    with pytest.raises(SceneError) as info:
        import_deck(write(tmp_path, text))
    assert "AMPLITUDE=HALF is a SMOOTH STEP" in str(info.value) and "line 36" in str(info.value)
