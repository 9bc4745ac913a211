"""Read an Abaqus input file into keyword blocks: keyword, parameters, data lines, file and line number.

The syntax is the one of the Abaqus Analysis User's Guide, "Input syntax rules" (section 1.2.1 in the 6.x
manuals; "Abaqus Keywords Reference Guide: Introduction" in 2017+): a line starting with ``**`` is a comment; a
line starting with ``*`` is a keyword line ``*NAME, PARAM=VALUE, FLAG``, continued on the next line when it ends
with a comma; every other line is a data line of comma-separated fields. Keywords, parameters and labels are not
case sensitive (labels are folded to upper case, as Abaqus does for unquoted labels).

``*INCLUDE, INPUT=file`` is expanded in place (relative to the including file). ``*PARAMETER`` data lines
``name = expression`` define parameters that ``<name>`` substitutes in later keyword and data lines (Keywords
Reference, *PARAMETER); expressions use numbers, + - * / **, parentheses, pi, math functions (sqrt, exp, sin, ...)
and the parameters defined before.
"""
from __future__ import annotations

import ast
import math
import operator
import re
from dataclasses import dataclass, field
from pathlib import Path

from cases.scene.errors import SceneError
from cases.decks.deck_io import deck_error, deck_lines, include_target

__all__ = ["Keyword", "DataLine", "read_keywords", "deck_error", "keyword_name", "KEYWORDS"]

#: keywords ventsim reads or refuses by name; "blanks on a keyword line are ignored" and keywords "need not be
#: spelled out completely" (Analysis User's Guide, "Input syntax rules"): a line's keyword is matched without
#: blanks, exactly or as the unique abbreviation of one of these
KEYWORDS = ("HEADING", "PARAMETER", "INCLUDE", "NODE", "ELEMENT", "NSET", "ELSET", "SURFACE", "SYSTEM", "PART",
            "END PART", "ASSEMBLY", "END ASSEMBLY", "INSTANCE", "END INSTANCE", "PHYSICAL CONSTANTS",
            "FLUID BEHAVIOR", "MOLECULAR WEIGHT", "CAPACITY", "FLUID DENSITY", "FLUID BULK MODULUS",
            "FLUID EXPANSION", "FLUID CAVITY", "INITIAL CONDITIONS", "FLUID EXCHANGE", "FLUID EXCHANGE PROPERTY",
            "FLUID EXCHANGE ACTIVATION", "FLUID INFLATOR", "FLUID INFLATOR PROPERTY", "FLUID INFLATOR MIXTURE",
            "FLUID INFLATOR ACTIVATION", "AMPLITUDE", "CONTACT PROPERTY ASSIGNMENT", "SURFACE INTERACTION",
            "BLOCKAGE", "SURFACE BEHAVIOR", "CONTACT DAMPING", "FRICTION", "RIGID BODY", "BOUNDARY", "TRANSFORM",
            "STEP", "DYNAMIC", "END STEP", "OUTPUT", "NGEN", "NFILL", "NCOPY", "ELGEN", "FLUID LINK", "STATIC",
            "FLUID FLUX", "CONTACT", "CONTACT FORMULATION", "MATERIAL")
_KEYWORDS = {k.replace(" ", ""): k for k in KEYWORDS}
#: parameter values of more than one word, matched without blanks
VALUES = ("FLUID PRESSURE", "TEMPERATURE AND MASS", "TANK TEST", "PRESSURE AND MASS", "DUAL PRESSURE",
          "MASS FRACTION", "MOLAR FRACTION", "FABRIC LEAKAGE", "MASS RATE LEAKAGE", "VOLUME RATE LEAKAGE",
          "MASS FLUX", "VOLUME FLUX", "BULK VISCOSITY", "ENERGY FLUX", "ENERGY RATE LEAKAGE", "SMOOTH STEP",
          "EQUALLY SPACED", "STEP TIME", "TOTAL TIME", "EDGE TO EDGE", "FIXED INTERVAL")
_VALUES = {v.replace(" ", ""): v for v in VALUES}
_SUBST = re.compile(r"<\s*([A-Za-z_][A-Za-z0-9_]*)\s*>")
#: functions a *PARAMETER expression may call (Abaqus evaluates them as Python)
_FUNCTIONS = {name: getattr(math, name) for name in ("sqrt", "exp", "log", "log10", "sin", "cos", "tan", "asin",
                                                     "acos", "atan", "atan2", "radians", "degrees", "hypot")}
_FUNCTIONS.update(abs=abs, min=min, max=max, pi=math.pi)
_OPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
        ast.Pow: operator.pow, ast.USub: operator.neg, ast.UAdd: operator.pos}


@dataclass(frozen=True)
class DataLine:
    """One data line: its stripped fields (strings), file and line number."""

    fields: tuple
    file: str
    line: int


@dataclass
class Keyword:
    """A keyword block: ``name`` upper case with single spaces (``"FLUID CAVITY"``), ``params`` (upper-case
    names; a flag without ``=`` has the value ``True``), the data lines that follow it, where it starts."""

    name: str
    params: dict
    file: str
    line: int
    data: list = field(default_factory=list)

    def error(self, message: str, line: int | None = None) -> SceneError:
        return deck_error(self.file, self.line if line is None else line, self.name, message)

    def param(self, name: str, default=None):
        return self.params.get(name.replace(" ", ""), default)

    def label(self, name: str, required: bool = False) -> str | None:
        """A parameter whose value is a label or a choice (upper case, blanks removed; a known value of several
        words with its blanks, e.g. ``FLUID PRESSURE``); ``required`` raises when it is missing."""
        value = self.param(name)
        if value is None or value is True:
            if required:
                raise self.error(f"missing required parameter {name}=")
            return None
        value = value.upper().replace(" ", "")
        return _VALUES.get(value, value)

    def number(self, name: str, default=None) -> float | None:
        value = self.param(name)
        if value is None:
            return default
        try:
            return float(value)
        except (TypeError, ValueError):
            raise self.error(f"parameter {name}: expected a number, got {value!r}") from None


def _evaluate(expr: str, params: dict, file, line):
    """The value of a *PARAMETER expression (numbers, parameters, + - * / **)."""

    def ev(node):
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return node.value
        if isinstance(node, ast.Name) and node.id in params:
            return params[node.id]
        if isinstance(node, ast.Name) and node.id == "pi":
            return math.pi
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and callable(_FUNCTIONS.get(node.func.id))
                and not node.keywords):
            return _FUNCTIONS[node.func.id](*(ev(a) for a in node.args))
        if isinstance(node, ast.BinOp) and type(node.op) in _OPS:
            return _OPS[type(node.op)](ev(node.left), ev(node.right))
        if isinstance(node, ast.UnaryOp) and type(node.op) in _OPS:
            return _OPS[type(node.op)](ev(node.operand))
        if isinstance(node, ast.Name):
            raise deck_error(file, line, "PARAMETER", f"unknown parameter {node.id!r}")
        raise deck_error(file, line, "PARAMETER", f"unsupported expression {expr!r} (numbers, parameters, "
                                                  "+ - * / **, pi and math functions such as sqrt only)")

    try:
        return ev(ast.parse(expr.strip(), mode="eval"))
    except SceneError:
        raise
    except SyntaxError:
        raise deck_error(file, line, "PARAMETER", f"cannot read the expression {expr!r}") from None
    except (ZeroDivisionError, OverflowError, ValueError, TypeError) as exc:
        raise deck_error(file, line, "PARAMETER", f"{expr!r}: {exc}") from None


def _substitute(text: str, params: dict, file, line, keyword: str) -> str:
    def repl(m):
        name = m.group(1)
        if name not in params:
            raise deck_error(file, line, keyword, f"<{name}> names no *PARAMETER defined before this line")
        return repr(params[name]) if isinstance(params[name], float) else str(params[name])
    return _SUBST.sub(repl, text) if "<" in text else text


def keyword_name(text: str) -> str:
    """The canonical name of a keyword as written (blanks ignored, a unique abbreviation expanded).

    >>> keyword_name("fluidcavity"), keyword_name("Fluid Exchange Activ"), keyword_name("MEMBRANE  SECTION")
    ('FLUID CAVITY', 'FLUID EXCHANGE ACTIVATION', 'MEMBRANE SECTION')
    """
    compact = text.upper().replace(" ", "").replace("\t", "")
    if compact in _KEYWORDS:
        return _KEYWORDS[compact]
    matches = [v for k, v in _KEYWORDS.items() if k.startswith(compact)]
    return matches[0] if len(matches) == 1 and len(compact) >= 4 else " ".join(text.upper().split())


def _parse_keyword_line(text: str, file, line) -> tuple[str, dict]:
    parts = [p.strip() for p in text[1:].split(",")]
    name = keyword_name(parts[0])
    if not name:
        raise deck_error(file, line, "", "a '*' with no keyword name")
    params = {}
    for p in parts[1:]:
        if not p:
            continue
        k, eq, v = p.partition("=")
        k = k.upper().replace(" ", "")
        v = v.strip()
        params[k] = (v.strip('"') if v.startswith('"') or k == "INPUT" else v.replace(" ", "")) if eq else True
    return name, params


def _lines(path: Path, stack: tuple):
    """(file, line number, text) of ``path`` with *INCLUDE expanded."""
    raw = deck_lines(path)
    i = 0
    while i < len(raw):
        lineno, t = i + 1, raw[i].rstrip()
        i += 1
        if t.lstrip().startswith("*") and not t.lstrip().startswith("**"):
            while t.endswith(",") and i < len(raw) and not raw[i].lstrip().startswith("*"):
                t += raw[i].strip()
                i += 1
            if keyword_name(t.lstrip()[1:].split(",")[0]) == "INCLUDE":
                _, params = _parse_keyword_line(t.lstrip(), path, lineno)
                name = params.get("INPUT")
                if not isinstance(name, str) or not name:
                    raise deck_error(path, lineno, "INCLUDE", "missing INPUT=file")
                target = include_target(path, lineno, name, stack)
                yield from _lines(target, stack + (target,))
                continue
        yield path, lineno, t


def read_keywords(path) -> list:
    """The keyword blocks of the deck at ``path`` in order (data before the first keyword is an error)."""
    path = Path(path)
    blocks, params, current = [], {}, None
    for file, lineno, text in _lines(path, (path.resolve(),)):
        stripped = text.strip()
        if not stripped or stripped.startswith("**"):
            continue
        where = current.name if current is not None else ""
        if stripped.startswith("*"):
            name, kparams = _parse_keyword_line(_substitute(stripped, params, file, lineno, where), file, lineno)
            current = Keyword(name, kparams, str(file), lineno)
            blocks.append(current)
            continue
        if current is None:
            raise deck_error(file, lineno, "", f"data line before any keyword: {stripped[:40]!r}")
        if current.name == "PARAMETER":
            key, eq, expr = stripped.partition("=")
            if not eq or not key.strip().isidentifier():
                raise deck_error(file, lineno, "PARAMETER", f"expected 'name = expression', got {stripped!r}")
            params[key.strip()] = _evaluate(_substitute(expr, params, file, lineno, "PARAMETER"), params, file,
                                            lineno)
            continue
        if current.name == "HEADING":
            current.data.append(DataLine((stripped,), str(file), lineno))
            continue
        fields = tuple(f.strip() for f in _substitute(stripped, params, file, lineno, where).split(","))
        current.data.append(DataLine(fields, str(file), lineno))
    return blocks
