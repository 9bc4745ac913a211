"""Read an LS-DYNA keyword deck into keyword blocks of cards (LS-DYNA Keyword User's Manual, "Introduction:
General card format"): ``$`` starts a comment line, ``*`` a keyword; a card is fixed-width (eight fields of 10
characters unless the keyword says otherwise) or free format (fields separated by commas); a blank field takes
its default. ``*INCLUDE`` (next card: the file name) is expanded in place; ``*PARAMETER`` values replace
``&name`` fields; nothing after ``*END`` is read.

A small reader of our own rather than ansys-dyna-core (pydyna): pydyna reads these cards correctly (checked on
*AIRBAG_WANG_NEFSKE) but its install pulls ansys-dpf-core, grpcio, docker and pandas (418 MB here) and its
import takes ~4 s, for the dozen keywords ventsim maps.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from cases.scene.errors import SceneError
from cases.decks.deck_io import deck_error, deck_lines, include_target

__all__ = ["DynaKeyword", "read_dyna", "fields", "refuse", "W10"]

#: eight fields of 10 characters, the default card
W10 = (10,) * 8


@dataclass
class DynaKeyword:
    """A keyword (upper case, e.g. ``AIRBAG_WANG_NEFSKE_ID``) and its cards: (file, line, raw text)."""

    name: str
    file: str
    line: int
    cards: list = field(default_factory=list)
    parameters: dict = field(default_factory=dict)  # *PARAMETER values, shared by the deck's keywords

    def error(self, message: str, line: int | None = None) -> SceneError:
        return deck_error(self.file, self.line if line is None else line, self.name, message)


def fields(kw: DynaKeyword, card, widths, kinds):
    """The values of one card: ``widths`` in characters, ``kinds`` 'i' (int), 'f' (float), 's' (text); blank
    fields are None. Free format (a comma in the card) splits at the commas instead."""
    _, line, text = card
    if "," in text:
        raw = [f.strip() for f in text.split(",")]
    else:
        raw, pos = [], 0
        for w in widths:
            raw.append(text[pos:pos + w].strip())
            pos += w
    raw = (raw + [""] * len(kinds))[:len(kinds)]
    out = []
    for i, (r, k) in enumerate(zip(raw, kinds)):
        if not r or k == "s":
            out.append(r or None)
            continue
        sign, ref = (-1.0, r[2:]) if r.startswith("-&") else (1.0, r[1:]) if r.startswith("&") else (1.0, None)
        if ref is not None:  # &name: a *PARAMETER value
            if ref.upper() not in kw.parameters:
                raise kw.error(f"field {i + 1}: {r!r} names no *PARAMETER defined before", line)
            r = repr(sign * kw.parameters[ref.upper()])
        try:
            v = float(r)
        except ValueError:
            raise kw.error(f"field {i + 1}: expected a number, got {r!r}", line) from None
        if k == "i":
            if v != int(v):
                raise kw.error(f"field {i + 1}: expected an integer, got {r!r}", line)
            v = int(v)
        out.append(v)
    return out


def _lines(path: Path, stack):
    raw = deck_lines(path)
    i = 0
    while i < len(raw):
        lineno, text = i + 1, raw[i].rstrip("\n")
        i += 1
        if text.upper().startswith("*INCLUDE"):
            while i < len(raw) and raw[i].startswith("$"):
                i += 1
            if i >= len(raw) or raw[i].startswith("*"):
                raise deck_error(path, lineno, "INCLUDE", "missing the card with the file name")
            name = raw[i].strip()
            i += 1
            target = include_target(path, lineno, name, stack)
            yield from _lines(target, stack + (target,))
            continue
        yield path, lineno, text


def read_dyna(path) -> list:
    """The keyword blocks of the LS-DYNA deck at ``path``, in order."""
    path = Path(path)
    blocks, current, parameters = [], None, {}
    for file, lineno, text in _lines(path, (path.resolve(),)):
        if not text.strip() or text.startswith("$"):
            continue
        if text.startswith("*"):
            name = text[1:].strip().upper()
            if name.split()[:1] == ["END"]:
                break  # LS-DYNA reads nothing after *END
            if name.endswith("+") or ("LONG=" in name.replace(" ", "") and name.startswith("KEYWORD")):
                raise deck_error(file, lineno, name, "long format (20-character fields) is not supported")
            current = DynaKeyword(name.split()[0] if name else name, str(file), lineno, parameters=parameters)
            blocks.append(current)
            continue
        if current is None:
            raise deck_error(file, lineno, "", f"card before any keyword: {text.strip()[:40]!r}")
        if current.name == "PARAMETER":
            _parameters(current, (str(file), lineno, text), parameters)
        current.cards.append((str(file), lineno, text))
    return blocks


def _parameters(kw, card, parameters):
    """*PARAMETER (LS-DYNA Keyword User's Manual): pairs of PRMR (type letter R or I and name, 10 characters)
    and VAL (10 characters), four pairs a card; later fields use them as &name."""
    _, line, text = card
    raw = [f.strip() for f in text.split(",")] if "," in text else [text[p:p + 10].strip() for p in range(0, 80, 10)]
    for prm, val in zip(raw[0::2], raw[1::2]):
        if not prm:
            continue
        kind, _, name = prm.partition(" ") if " " in prm else (prm[0], "", prm[1:])
        if kind.upper() not in ("R", "I") or not name.strip():
            raise kw.error(f"expected 'R name' or 'I name', got {prm!r} (character parameters are not supported)", line)
        try:
            parameters[name.strip().upper()] = float(val)
        except ValueError:
            raise kw.error(f"parameter {name.strip()}: expected a number, got {val!r}", line) from None


def refuse(kw, card, names, values):
    for n, v in zip(names, values):
        if v not in (None, 0, 0.0):
            raise kw.error(f"{n} = {v}: not supported (ventsim reads constant coefficients and areas)", card[1])
