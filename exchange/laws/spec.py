"""What a flow law declares to the registry (:mod:`exchange.laws.registry`): its scene keys and its spec."""
from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["LawKey", "LawSpec", "LAW_FLOATS", "LAW_INTS"]

#: Width of the model's ``law_float`` and ``law_int`` rows: the most parameters a law lowers to.
LAW_FLOATS, LAW_INTS = 4, 4


@dataclass(frozen=True)
class LawKey:
    """A scene key of a law (a field of ``[[exchange]]``): name, documentation, unit, default and check, as
    :func:`cases.scene.schema.key` takes them."""

    name: str
    doc: str
    unit: str = "-"
    default: object = None
    check: str | None = None
    choices: tuple | None = None
    kind: str = "value"  # "value"; "table": a number or a CSV table (of time); "cd": Cd or its CSV table; "file"


@dataclass(frozen=True)
class LawSpec:
    """One flow law as the registry knows it.

    Attributes
    ----------
    names : tuple of str
        Its names in a scene's ``law`` key.
    law : type
        Its Python class (``mass_flow(up, p_down, area, t)``; class attributes ``pneumatic``, ``prescribed``,
        ``join_below``: the |Δp|/p where it changes form, a switch there).
    kernel : numba dispatcher
        Its engine kernel, :data:`exchange.engine.layout.LAW_SIGNATURE`.
    keys : tuple of LawKey
        The scene keys it reads beyond the exchange's own.
    required : dict
        Per name, the keys a scene must give.
    build : callable
        ``build(name, values, read_table) -> law``: the law of a scene's exchange; ``values`` maps each of its keys to
        the scene's value, ``read_table(key, what)`` reads a CSV table the scene names.
    lower : callable
        ``lower(law, tables) -> (floats, ints)``: its ``law_float`` and ``law_int`` entries (``tables`` an
        :class:`exchange.engine.tables.Tables` to add its tables to).
    kinks : callable
        ``kinks(law) -> ((KinkVariable, x, row), ...)``: where its flow kinks in the state (a row of a table), which
        the engine stops at.
    lowers : callable
        ``lowers(law) -> bool``: this object can run on the kernel (else it is hosted).
    """

    names: tuple
    law: type
    kernel: object
    build: object
    lower: object
    keys: tuple = ()
    required: dict = field(default_factory=dict)
    kinks: object = lambda law: ()
    lowers: object = lambda law: True
