"""Each example deck in cases/decks gives the scene of its TOML twin, the same files and the same history."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import tests.closed_forms as cf
from cases.decks import deck_scene
from cases.run.library import DECK_TWINS, HERE, column_errors
from cases.run.runner import run_scene
from cases.scene.files import load_scene

DECKS = Path(HERE) / "decks"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """name -> (deck results, twin results, imported)."""
    out = {}
    for name, deck in DECK_TWINS.items():
        tmp = tmp_path_factory.mktemp(name)
        scene, imported = deck_scene(HERE / deck, tmp / "scene.toml")
        out[name] = (run_scene(scene), run_scene(load_scene(HERE / (deck.rsplit(".", 1)[0] + ".toml"))), imported)
    return out


@pytest.mark.parametrize("name", sorted(DECK_TWINS))
def test_deck_is_its_twin(name, runs):
    deck, twin, imported = runs[name]
    twin_path = HERE / (DECK_TWINS[name].rsplit(".", 1)[0] + ".toml")
    assert imported.data == tomllib.loads(twin_path.read_text())  # the same scene, key by key
    for file, text in imported.files.items():  # the same meshes and tables, byte for byte
        assert (twin_path.parent / file).read_text() == text, file
    assert deck.columns == twin.columns and deck.history.shape == twin.history.shape
    assert max(column_errors(deck.columns, deck.history, twin.columns, twin.history).values()) <= 1e-12


def test_box_blowdown_deck_matches_the_choked_closed_form(runs):
    deck, _, imported = runs["deck_box_blowdown"]
    gamma, R = 1.4, cf.R_U / 0.0280134
    tau = cf.blowdown_tau(0.06, 1.0, 1e-4, gamma, R, 300.0)
    t, p, T = deck.column("time"), deck.column("tank.pressure"), deck.column("tank.temperature")
    p_ref = np.array([cf.choked_adiabatic_pressure(x, 5e5, tau, gamma) for x in t])
    T_ref = np.array([cf.choked_adiabatic_temperature(x, 300.0, tau, gamma) for x in t])
    assert p_ref.min() >= 1e5 * ((gamma + 1) / 2) ** (gamma / (gamma - 1))  # choked all along
    assert np.max(np.abs(p / p_ref - 1)) <= 1e-6
    assert np.max(np.abs(T / T_ref - 1)) <= 1e-6
    assert math.isclose(deck.column("tank.volume")[0], 0.06, rel_tol=1e-14)  # *PARAMETER LZ = 0.06/(LX*LY)
    assert "ignored: *MATERIAL (line 13)" in imported.ignored  # listed once, with its line


def test_wang_nefske_gas_and_initial_state(runs):
    deck, _, imported = runs["deck_wang_nefske_bag"]
    species = imported.data["species"][0]
    assert math.isclose(cf.R_U / species["molar_mass"], 1005.0 - 718.0, rel_tol=1e-14)  # R = cp - cv
    assert math.isclose(species["cp"][0] / species["molar_mass"], 1005.0, rel_tol=1e-14)
    assert math.isclose(deck.column("bag1.temperature")[0], 101325.0 / (1.204 * 287.0), rel_tol=1e-14)
    assert math.isclose(deck.column("bag1.volume")[0], 0.4 * 0.4 * 0.375, rel_tol=1e-13)
    assert imported.data["cavity"][0]["inflator"][0]["gas"] == {"bag1_gas": 1.0}  # the bag's own gas
    fabric = next(e for e in imported.data["exchange"] if "fabric" in e["name"])
    assert math.isclose(fabric["area"], 0.002 * 0.4 * 0.4, rel_tol=1e-13)  # FAC x area of the porous part
    assert fabric["discharge_coefficient"] == 0.5  # FLC


def test_hydraulic_deck_conserves_liquid_mass(runs):
    deck, _, _ = runs["deck_hydraulic_two_cavity"]
    a, b = deck.column("a.pressure"), deck.column("b.pressure")
    assert a[0] == 1.1e6 and b[0] == 1e5 and a[-1] < a[0] and b[-1] > b[0]  # gauge + ambient, then A drains
    for name, bal in deck.summary["mass balance"].items():
        assert bal["relative imbalance [-]"] <= 1e-12, (name, bal)
