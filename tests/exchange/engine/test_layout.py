"""The engine's layout: the model is read by name everywhere, each kind is named once, the switch legend and the
predicates agree with the kinds."""
from __future__ import annotations

import inspect
import re
from pathlib import Path

import pytest

from exchange.engine import layout
from exchange.engine.layout import FIELDS, SWITCH_LABELS, SwitchKind

ROOT = Path(__file__).resolve().parents[3]
#: Arrays of the model (their names and the short names kernels bind them to).
MODEL_ARRAYS = [name for name, _, _ in FIELDS] + ["ci", "cf", "ei", "ef", "ii", "fl", "ti", "st", "bd", "nodes"]
POSITIONAL = [
    re.compile(r"\bM\[\d"),  # the model as a positional tuple
    re.compile(r"\bmodel\[\d"),
    re.compile(r"\b(?:%s)\[[^\]\[]*,\s*-?\d+\s*\]" % "|".join(MODEL_ARRAYS)),  # a numbered column
    re.compile(r"\.(?:body|seat_state|seat_law|ambient)\[-?\d+\]"),  # a numbered entry of a vector field
]


def test_no_positional_access_to_the_model_outside_the_layout():
    offenders = []
    for package in ("cavity", "blockage", "exchange", "cases"):
        for path in (ROOT / package).rglob("*.py"):
            if path == Path(layout.__file__):
                continue
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
                code = line.split("#")[0]
                if any(p.search(code) for p in POSITIONAL) and ">>>" not in line:
                    offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not offenders, "\n".join(offenders)


def test_the_model_constructor_takes_the_fields_in_order():
    assert list(inspect.signature(layout._new.py_func).parameters) == [name for name, _, _ in FIELDS]
    assert list(layout.ModelArrays._fields) == [name for name, _, _ in FIELDS]


def test_every_switch_kind_has_one_label_and_its_predicates():
    assert set(SWITCH_LABELS) == set(SwitchKind)
    assert len(set(SWITCH_LABELS.values())) == len(SWITCH_LABELS)
    kinks = {k for k in SwitchKind if layout.is_kink(k)}
    assert kinks == {SwitchKind.CHOKE, SwitchKind.JOIN, SwitchKind.REVERSAL, SwitchKind.LAW_KINK}
    body = {k for k in SwitchKind if layout.is_body_switch(k)}
    assert body == {SwitchKind.TURN, SwitchKind.CROSSING_UP, SwitchKind.CROSSING_DOWN, SwitchKind.KNOT_UP,
                    SwitchKind.KNOT_DOWN, SwitchKind.SEAT, SwitchKind.SEAT_KINK}
    assert {k: layout.one_way_direction(k) for k in SwitchKind if layout.one_way_direction(k)} == {
        SwitchKind.CROSSING_UP: 1.0, SwitchKind.KNOT_UP: 1.0, SwitchKind.CROSSING_DOWN: -1.0,
        SwitchKind.KNOT_DOWN: -1.0, SwitchKind.SAMPLE: 1.0}  # time only grows


@pytest.mark.parametrize("pop_vent, popped, closed", [(True, False, False), (True, True, False), (True, True, True),
                                                     (False, False, False), (False, False, True)])
def test_the_open_state_encoding_round_trips(pop_vent, popped, closed):
    """Every discrete state an exchange can reach (a pop vent pops before it can close; only pop vents pop)."""
    assert layout.flags_of(layout.open_state_of(pop_vent, popped, closed), pop_vent) == (popped, closed)
