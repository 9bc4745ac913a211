"""LS-DYNA deck errors are one line with the file, line and keyword; fixed and free format read alike."""
from __future__ import annotations

import pytest


from cases.decks import deck_scene, import_deck
from cases.decks.conversions import R_U
from cases.run.runner import run_scene
from cases.scene.errors import SceneError
from cases.run.library import HERE, column_errors

BAG = (HERE / "decks" / "wang_nefske_bag.k").read_text()


def write(tmp_path, text):
    (tmp_path / "wang_nefske_bag.k").write_text(text)
    return tmp_path / "wang_nefske_bag.k"


def error_of(path):
    with pytest.raises(SceneError) as info:
        import_deck(path)
    assert "\n" not in str(info.value)
    return str(info.value)


def line_of(text, needle):
    return text.splitlines().index(needle) + 1


def test_free_format_card_reads_like_fixed_width(tmp_path):
    fixed = BAG.replace("718.0, 1005.0, 600.0, 0, 10, 0.0, 0, 0.0",
                        "".join(f"{v:>10}" for v in ("718.0", "1005.0", "600.0", 0, 10, "0.0", 0, "0.0")))
    assert import_deck(write(tmp_path, fixed)).data == import_deck(HERE / "decks" / "wang_nefske_bag.k").data


def test_particle_airbag_is_refused_by_name(tmp_path):
    text = BAG.replace("*AIRBAG_WANG_NEFSKE_ID", "*AIRBAG_PARTICLE_ID")
    deck = write(tmp_path, text)
    assert error_of(deck) == (f"{deck}: line {line_of(text, '*AIRBAG_PARTICLE_ID')}: *AIRBAG_PARTICLE_ID: not "
                              "supported: ventsim reads *AIRBAG_SIMPLE_AIRBAG_MODEL, *AIRBAG_WANG_NEFSKE, "
                              "*AIRBAG_HYBRID and *AIRBAG_INTERACTION")


def _hybrid_of_the_wang_nefske_bag():
    """The Wang–Nefske bag written as *AIRBAG_HYBRID with one gas: MW = R_u/(cp − cv), A = cp·MW, the same
    ambient state (ATMOST = PE/(RO·R)), a constant 600 K temperature curve and PVENT = PPOP."""
    f10 = lambda *v: "".join(f"{x:>10}" for x in v)
    mw, t0 = R_U / 287.0, 101325.0 / (1.204 * 287.0)
    start = BAG.index("*AIRBAG_WANG_NEFSKE_ID")
    cards = ["*AIRBAG_HYBRID_ID", f10(1) + "driver bag", f10(1, 1, 0, "1.0", "1.0", "0.0", "0.0", "0.0"),
             f"{t0!r}, 101325.0, 1.204, 1.0, 1.0, 0.0",
             f10("0.7", 0, "5.0e-4", 0, "0.0", 0, "0.0", 0),
             f10(0, "1.0e4", 1, 0, 0, 0),
             f"10, 20, 0, {mw!r}, 1.0, {1005.0 * mw!r}, 0.0, 0.0", f10("1.0"),
             "*DEFINE_CURVE", f10(20), f"{0.0!r:>20}{600.0!r:>20}", f"{1.0!r:>20}{600.0!r:>20}", "*END"]
    return BAG[:start] + "\n".join(cards) + "\n"


def test_hybrid_with_one_gas_is_the_wang_nefske_bag(tmp_path):
    hybrid = deck_scene(write(tmp_path, _hybrid_of_the_wang_nefske_bag()), tmp_path / "h" / "s.toml")[0]
    wang = deck_scene(HERE / "decks" / "wang_nefske_bag.k", tmp_path / "w" / "s.toml")[0]
    h, w = run_scene(hybrid), run_scene(wang)
    assert h.columns == w.columns
    assert max(column_errors(h.columns, h.history, w.columns, w.history).values()) <= 1e-12


def test_missing_curve(tmp_path):
    text = BAG.replace("718.0, 1005.0, 600.0, 0, 10,", "718.0, 1005.0, 600.0, 0, 11,")
    deck = write(tmp_path, text)
    assert error_of(deck) == f"{deck}: line {line_of(text, '*AIRBAG_WANG_NEFSKE_ID')}: *AIRBAG_WANG_NEFSKE_ID: " \
                             "LCMT: no *DEFINE_CURVE 11"


def test_broken_field(tmp_path):
    card = "".join(f"{v:>10}" for v in ("0.7", 0, "5.0e-4", 0, "0.0", 0, "0.0", 0))
    broken = card.replace("    5.0e-4", "    5.0e4x")
    text = BAG.replace(card, broken)
    deck = write(tmp_path, text)
    n = line_of(text, broken)
    assert error_of(deck) == f"{deck}: line {n}: *AIRBAG_WANG_NEFSKE_ID: field 3: expected a number, got '5.0e4x'"


def test_missing_include(tmp_path):
    text = BAG.replace("*TITLE", "*INCLUDE\nnodes.k\n*TITLE")
    deck = write(tmp_path, text)
    assert error_of(deck) == f"{deck}: line 2: *INCLUDE: the file 'nodes.k' does not exist"


def test_unknown_keyword_is_ignored_once(tmp_path):
    text = BAG.replace("*END", "*CONTROL_TIMESTEP\n0.0\n*CONTROL_TIMESTEP\n0.0\n*END")
    imported = import_deck(write(tmp_path, text))
    assert [i for i in imported.ignored if "TIMESTEP" in i] == \
        [f"ignored: *CONTROL_TIMESTEP (line {line_of(text, '*CONTROL_TIMESTEP')})"]


def test_shell_thickness_option_reads_the_same_bag(tmp_path):
    start, end = BAG.index("*ELEMENT_SHELL"), BAG.index("*PART")
    cards = [c for c in BAG[start:end].splitlines()[1:] if not c.startswith("$")]
    thick = "*ELEMENT_SHELL_THICKNESS\n" + "".join(f"{c}\n{'0.0004':>16}\n" for c in cards)
    imported = import_deck(write(tmp_path, BAG[:start] + thick + BAG[end:]))
    assert imported.data == import_deck(HERE / "decks" / "wang_nefske_bag.k").data


def test_empty_part_set(tmp_path):
    text = BAG.replace("*SET_PART_LIST\n         1\n         1         2", "*SET_PART_LIST\n         1\n         7")
    deck = write(tmp_path, text)
    assert error_of(deck) == (f"{deck}: line {line_of(text, '*AIRBAG_WANG_NEFSKE_ID')}: *AIRBAG_WANG_NEFSKE_ID: "
                              "SID 1 (SIDTYP 1): the set has no shell elements or segments")


def test_parameters_replace_ampersand_fields(tmp_path):
    text = BAG.replace("*CONTROL_TERMINATION", "*PARAMETER\nR endt          0.06I lcmass          10\n"
                                                "*CONTROL_TERMINATION")
    text = text.replace("$#  endtim\n      0.06", "$#  endtim\n     &endt").replace(
        "718.0, 1005.0, 600.0, 0, 10,", "718.0, 1005.0, 600.0, 0, &lcmass,")
    assert "&endt" in text and "&lcmass" in text
    assert import_deck(write(tmp_path, text)).data == import_deck(HERE / "decks" / "wang_nefske_bag.k").data


def test_unknown_parameter_and_text_after_end(tmp_path):
    text = BAG.replace("$#  endtim\n      0.06", "$#  endtim\n     &endt")
    deck = write(tmp_path, text)
    assert error_of(deck).endswith("*CONTROL_TERMINATION: field 1: '&endt' names no *PARAMETER defined before")
    assert import_deck(write(tmp_path, BAG + "this is not a card\n")).data == \
        import_deck(HERE / "decks" / "wang_nefske_bag.k").data


def _wang_nefske_card4(ppop):
    return "".join(f"{v:>10}" for v in ("101325.0", "1.204", "1.0", 0, "0.0", ppop, 0, 0))


def test_simple_airbag_model_is_the_wang_nefske_bag_without_pop(tmp_path):
    """*AIRBAG_SIMPLE_AIRBAG_MODEL (CV CP T LCID MU A PE RO) with the Wang–Nefske bag's data gives its history
    when the Wang–Nefske vent has no pop pressure (both vents are the isentropic orifice)."""
    no_pop = BAG.replace(_wang_nefske_card4("1.0e4"), _wang_nefske_card4("0.0"))
    start = BAG.index("*AIRBAG_WANG_NEFSKE_ID")
    simple = BAG[:start] + "\n".join([
        "*AIRBAG_SIMPLE_AIRBAG_MODEL_ID", f"{1:>10}driver bag",
        "".join(f"{v:>10}" for v in (1, 1, 0, "1.0", "1.0", "0.0", "0.0", "0.0")),
        "".join(f"{v:>10}" for v in ("718.0", "1005.0", "600.0", 10, "0.7", "5.0e-4", "101325.0", "1.204")),
        "*END"]) + "\n"
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a = run_scene(deck_scene(write(tmp_path / "a", simple), tmp_path / "a" / "s.toml")[0])
    b = run_scene(deck_scene(write(tmp_path / "b", no_pop), tmp_path / "b" / "s.toml")[0])
    assert a.columns == b.columns
    assert max(column_errors(a.columns, a.history, b.columns, b.history).values()) <= 1e-12


def test_airbag_interaction_joins_two_bags(tmp_path):
    """A second bag (the same box shifted 1 m, no inflator, no vent) fed through *AIRBAG_INTERACTION: an orifice
    of AREA and Cd = SF between them; the second bag's pressure rises and mass is conserved."""
    nodes = BAG[BAG.index("*NODE\n"):BAG.index("*ELEMENT_SHELL")].splitlines()[2:]
    shells = BAG[BAG.index("*ELEMENT_SHELL"):BAG.index("*PART")].splitlines()[2:]
    moved = [f"{int(n[:8]) + 1000:>8}{float(n[8:24]) + 1.0!r:>16}{n[24:]}" for n in nodes]
    second = [f"{int(e[:8]) + 1000:>8}{3:>8}" + "".join(f"{int(e[k:k + 8]) + 1000:>8}" for k in range(16, 48, 8))
              for e in shells]
    text = BAG.replace("*ELEMENT_SHELL", "*NODE\n" + "\n".join(moved) + "\n*ELEMENT_SHELL\n" + "\n".join(second) +
                       "\n*ELEMENT_SHELL").replace("*END\n", "\n".join([
        "*SET_PART_LIST", f"{2:>10}", f"{3:>10}", "*AIRBAG_WANG_NEFSKE_ID", f"{2:>10}passenger side",
        "".join(f"{v:>10}" for v in (2, 1, 0, "1.0", "1.0", "0.0", "0.0", "0.0")),
        "718.0, 1005.0, 600.0, 0, 0, 0.0, 0, 0.0", "0.0, 0, 0.0, 0, 0.0, 0, 0.0, 0",
        "101325.0, 1.204, 1.0, 0, 0.0, 0.0, 0, 0", "*AIRBAG_INTERACTION", "1, 2, 1.0e-3, 0.8", "*END"]) + "\n")
    scene, imported = deck_scene(write(tmp_path, text), tmp_path / "o" / "s.toml")
    link = next(e for e in imported.data["exchange"] if e["name"] == "bag1_to_bag2")
    assert link == {"name": "bag1_to_bag2", "from": "bag1", "to": "bag2", "law": "orifice", "area": 1e-3,
                    "discharge_coefficient": 0.8}
    assert "bag2: no mass flow curve (LCMT/LCID = 0): no inflator" in imported.notes
    r = run_scene(scene)
    assert r.column("bag2.pressure")[-1] > 1.5e5 and r.column("bag2.mass")[-1] > r.column("bag2.mass")[0]
    for name, bal in r.summary["mass balance"].items():
        assert bal["relative imbalance [-]"] <= 1e-12, name
