"""Every data line of the example decks, broken in three ways, gives a scene or a one-line SceneError naming the
file and a line — never another exception (a traceback for the user)."""
from __future__ import annotations

import shutil

import pytest

from cases.decks import import_deck
from cases.scene.errors import SceneError
from cases.run.library import HERE

DECKS = ["box_blowdown.inp", "vented_box_blockage.inp", "hydraulic_two_cavity.inp", "wang_nefske_bag.k"]


def mutations(line):
    fields = line.split(",")
    yield ",".join(["x"] + fields[1:])  # a word where a number (or a name) was
    yield ",".join(fields[:-1]) if len(fields) > 1 else ""  # the last field dropped
    yield line[: max(1, len(line) // 2)]  # cut in the middle (fixed-width cards lose fields)


@pytest.mark.parametrize("deck", DECKS)
def test_broken_lines_give_one_line_errors(tmp_path, deck):
    src = HERE / "decks"
    for inc in src.glob("*_mesh.inp"):
        shutil.copy(inc, tmp_path / inc.name)
    lines = (src / deck).read_text().splitlines()
    data = [i for i, t in enumerate(lines) if t.strip() and t.lstrip()[0] not in "*$"]
    outcomes = {"ok": 0, "error": 0}
    for i in data:
        for broken in mutations(lines[i]):
            (tmp_path / deck).write_text("\n".join(lines[:i] + [broken] + lines[i + 1:]) + "\n")
            try:
                import_deck(tmp_path / deck)
                outcomes["ok"] += 1
            except SceneError as exc:
                message = str(exc)
                assert "\n" not in message and message.startswith(str(tmp_path)), message
                assert "please report" not in message, message  # the safety net in import_deck is not hit
                outcomes["error"] += 1
    assert outcomes["error"] > 0 and outcomes["ok"] + outcomes["error"] == 3 * len(data)


def _fuzz(tmp_path, name, text):
    lines = text.splitlines()
    data = [i for i, t in enumerate(lines) if t.strip() and t.lstrip()[0] not in "*$"]
    errors = 0
    for i in data:
        for broken in mutations(lines[i]):
            (tmp_path / name).write_text("\n".join(lines[:i] + [broken] + lines[i + 1:]) + "\n")
            try:
                import_deck(tmp_path / name)
            except SceneError as exc:
                assert "\n" not in str(exc) and "please report" not in str(exc), str(exc)
                errors += 1
    return errors


def test_broken_lines_of_the_parts_and_inflator_decks(tmp_path):
    from tests.decks.test_decks_inflator import DECK
    from tests.decks.test_decks_parts import FLAT, PARTS

    for inc in (HERE / "decks").glob("*_mesh.inp"):
        shutil.copy(inc, tmp_path / inc.name)
    parts = PARTS + FLAT[FLAT.index("*MATERIAL"):].replace(" BOX_NODES, ENCASTRE", " BOX-1.BOX_NODES, ENCASTRE")
    assert _fuzz(tmp_path, "parts.inp", parts) > 0
    assert _fuzz(tmp_path, "fill.inp", DECK) > 0
