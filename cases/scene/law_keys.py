"""The flow laws' scene keys, as the law registry declares them (:mod:`exchange.laws.registry`): the fields they add
to ``[[exchange]]``, how their values are read (a number or a CSV table, a file name) and checked, which are
required by which law, and which laws are for gases only. Nothing here names a law: a law registered in the
registry brings its keys with it."""
from __future__ import annotations

from dataclasses import make_dataclass

from exchange.laws import registry

from cases.scene.schema import key

__all__ = ["LawKeys", "names", "required", "gas_only", "of_kind", "label", "key_type"]


def key_type(k) -> str:
    """The annotation a law key's field gets (the scene parser checks by it)."""
    if k.kind in ("cd", "table"):
        return "object"
    if k.kind == "file" or isinstance(k.default, str):
        return "str"
    return "bool" if isinstance(k.default, bool) else "float"


#: The laws' keys as a spec class the exchange spec inherits (one field per key, each once).
LawKeys = make_dataclass("LawKeys", [(k.name, key_type(k), key(k.doc, k.unit, default=k.default, check=k.check,
                                                                 choices=k.choices))
                                     for k in registry.law_keys()], frozen=True, kw_only=True)


def names() -> tuple:
    """Every law name a scene may give."""
    return registry.names()


def required(law: str) -> tuple:
    """The keys a scene must give with ``law``."""
    return tuple(registry.spec_of_name(law).required.get(law, ()))


def gas_only(law: str) -> bool:
    """The law is pneumatic (for gases only: not between hydraulic cavities)."""
    return bool(registry.spec_of_name(law).law.pneumatic)


def of_kind(kind: str) -> tuple:
    """The law keys (LawKey) of a kind: "cd" (a discharge coefficient, a number > 0 or a CSV table), "table" (a
    number or a CSV table of time), "file" (a CSV file the scene names)."""
    return tuple(k for k in registry.law_keys() if k.kind == kind)


def label(k) -> str:
    """A law key's quantity with its unit, for messages about its table: ``discharge coefficient [-]``."""
    return f"{k.name.replace('_', ' ')} [{k.unit}]"
