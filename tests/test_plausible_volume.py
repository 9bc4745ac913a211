"""The scene-relative volume check (cases/scene/plausible_volume.py): a volume in litres taken for m³ is caught at
any size against the cavity's own inflators and vents, in one line naming the file, the key, the value, the likely
mistake and the override; no library scene and no shipped deck sets it off."""
import glob
import math
import tomllib
from pathlib import Path

import pytest

import ventsim
from cases.decks import deck_scene, import_deck
from cases.scene import plausible_volume
from cases.scene.errors import SceneError
from cases.scene.files import scene_from_dict
from cases.scene.plausible_volume import MIN_RESPONSE, response

ROOT = Path(__file__).resolve().parents[1]
VENT_40MM = math.pi * 0.02 ** 2  # [m^2]


def bag(volume: float, inflator_kg: float = 0.07, vent: float = VENT_40MM) -> dict:
    """An airbag of ``volume`` at 1 bar, 300 K, filled by ``inflator_kg`` of N2 in 30 ms, vented through ``vent``."""
    cavity = {"name": "bag", "pressure": 1.0e5, "temperature": 300.0, "gas": {"N2": 1.0}, "volume": volume}
    if inflator_kg:
        rate = inflator_kg / 0.03
        cavity["inflator"] = [{"name": "gen", "type": "mass_temperature", "temperature": 600.0, "gas": {"N2": 1.0},
                               "mass_flow": [[0.0, rate], [0.03, rate], [0.0301, 0.0]]}]
    data = {"time": {"end": 0.1}, "ambient": {"gas": {"N2": 1.0}}, "cavity": [cavity]}
    if vent:
        data["exchange"] = [{"name": "vent", "from": "bag", "area": vent, "discharge_coefficient": 0.6}]
    return data


def message(data) -> str:
    with pytest.raises(SceneError) as info:
        ventsim.Scene(data)
    text = str(info.value)
    assert "\n" not in text and text.startswith("<python scene>: cavity[0].volume: ")
    assert "add 'cavity[0].volume' to [units] unchecked" in text  # the override
    return text


@pytest.mark.parametrize("litres, vent_mm", [(60.0, 40.0), (2.0, 10.0), (0.5, 6.0)])
def test_an_airbag_volume_in_litres_is_caught_against_its_vent_and_inflator(litres, vent_mm):
    """A 60 L, 2 L and 0.5 L bag written in litres: 1000 times too large; the same bag in m^3 loads."""
    kg = 0.07 * litres / 60.0  # an inflator for the bag's size: about its own gas again
    vent = math.pi * (vent_mm * 5e-4) ** 2
    assert ventsim.Scene(bag(litres * 1e-3, kg, vent)).spec.cavity[0].volume == litres * 1e-3
    text = message(bag(litres, kg, vent))
    assert f"a volume in litres ({litres:g} L = {litres * 1e-3:.6g} m^3)" in text
    assert "orders of magnitude too large for its scene" in text and f"its vents ({vent:.3g} m^2)" in text


def test_a_vessel_that_only_vents_and_one_that_is_only_filled():
    assert "it has no vent" in message(bag(60.0, vent=0.0))
    ventsim.Scene(bag(0.06, vent=0.0))
    text = message(bag(50.0, inflator_kg=0.0, vent=1e-4))  # a 50 L blowdown through 1 cm^2 for 0.1 s
    assert "its inflators add 0 kg" in text and "would take 2.4e+03 s to relieve it" in text
    ventsim.Scene(bag(0.05, inflator_kg=0.0, vent=1e-4))


def test_the_response_is_the_larger_share_and_scales_as_one_over_the_volume():
    """Closed forms: added/held, and end/τ with τ = V/(0.6·A·√(1.4·287.05·T))."""
    c0 = math.sqrt(1.4 * 287.05 * 300.0)
    assert response(held=2.0, added=0.5, area=0.0, volume=1.0, temperature=300.0, end=1.0) == 0.25
    r = response(held=2.0, added=0.0, area=1e-4, volume=0.05, temperature=300.0, end=0.1)
    assert r == pytest.approx(0.1 * 0.6 * 1e-4 * c0 / 0.05, rel=1e-15)
    assert response(held=2e3, added=0.0, area=1e-4, volume=50.0, temperature=300.0, end=0.1) == pytest.approx(
        r * 1e-3, rel=1e-15)


def test_the_override_and_what_is_not_judged():
    data = bag(60.0)
    data["units"] = {"unchecked": ["cavity[0].volume"]}
    assert ventsim.Scene(data).spec.cavity[0].volume == 60.0
    data = bag(60.0)
    data["cavity"][0]["inflator"][0].update(type="tank_test", tank_pressure=[[0.0, 2e5], [0.03, 1e5]],
                                            tank_volume=1e-3, mass_flow=None)
    del data["cavity"][0]["inflator"][0]["mass_flow"]
    data["exchange"] = [{"name": "vent", "from": "bag", "area": VENT_40MM, "law": "linear_resistance",
                         "conductance": 1.0}]
    ventsim.Scene(data)  # neither the inflator's mass nor the vent's flow is known before the run: not judged


def library_scenes():
    names = set(glob.glob(str(ROOT / "cases" / "**" / "*.toml"), recursive=True))
    return sorted(n for n in names if "/results/" not in n)


@pytest.mark.parametrize("end_factor", [1.0, 0.01, 0.001])
def test_no_library_scene_sets_it_off_not_even_in_a_short_preview(monkeypatch, end_factor):
    """Every library scene loads, also run for 1 % or 0.1 % of its time.end (as the fuzz campaign's warm-up and
    users' previews do); the responses judged as given are at least 20 times their threshold."""
    seen = []
    real = plausible_volume.response

    def spy(**kw):
        seen.append(real(**kw))
        return seen[-1]

    monkeypatch.setattr(plausible_volume, "response", spy)
    scenes = library_scenes()
    assert len(scenes) >= 30
    for name in scenes:
        data = tomllib.loads(Path(name).read_text())
        data["time"]["end"] *= end_factor
        data["time"].pop("output_interval", None)
        scene_from_dict(data, name)  # raises on a false alarm
    if end_factor == 1.0:
        assert len(seen) >= 6 and min(seen) > 20 * MIN_RESPONSE  # 0.205 (seal_vent) against 3e-3


@pytest.mark.parametrize("deck", ["cases/decks/box_blowdown.inp", "cases/decks/vented_box_blockage.inp",
                                  "cases/decks/hydraulic_two_cavity.inp", "cases/decks/wang_nefske_bag.k",
                                  "tests/decks/hard_contact_rest.inp"])
def test_the_shipped_decks_import_without_it(deck, tmp_path):
    """The decks of the library and tests/decks (the generated ones are imported by tests/decks in every unit
    system)."""
    scene, _ = deck_scene(ROOT / deck, tmp_path / "scene.toml", "SI", imported=import_deck(ROOT / deck, "SI"))
    assert scene.units.check and scene.cavity
