"""The flow laws ventsim knows, in one list: each law's scene names and keys, its Python class, its numba kernel and
how it lowers onto the engine.

A law is one module of :mod:`exchange.laws` that ends with a :class:`LawSpec` named ``LAW``; the list
:data:`LAWS` below names it once. Everything else reads this list: the scene's ``law`` choices and keys
(:mod:`cases.scene.files`), how a scene's values build the law object (:mod:`cases.model.build`), which laws are for
gases only (their class's ``pneumatic``), the engine's law slots (:func:`kernels`) and each exchange's slot and
parameters (:func:`lowered`). A law outside the package joins with :func:`register`
(``docs/architecture.md`` has a worked example).

The engine calls a law's kernel through ``M.laws[slot]`` with :data:`exchange.engine.layout.LAW_SIGNATURE`:
``(law floats, law ints, table_x, table_y, table_index, state, ambient, u, p_down, area, t) -> ṁ [kg/s]``, the flow
from side u (a cavity, −1 ambient) into p_down [Pa], >= 0 and 0 when p_down >= p_u; a prescribed law (its class's
``prescribed``) returns a signed flow from the exchange's first cavity instead. A law object the registry does not
lower (a subclass, a law of one's own with only ``mass_flow(up, p_down, area, t)``, the real-gas nozzle) runs
through the hosted kernel (:mod:`exchange.laws.hosted`), which calls its Python method in numba's object mode.
"""
from __future__ import annotations

import math
import numpy as np

from exchange.engine.layout import LAW_SLOTS

from . import bulk_viscosity, fabric, flux, graefe, leakage_table, linear_resistance, orifice, seal
from .spec import LAW_FLOATS, LAW_INTS, LawKey, LawSpec

__all__ = ["LawKey", "LawSpec", "LAWS", "LAW_FLOATS", "LAW_INTS", "register", "spec_of_name", "spec_of", "names",
           "law_keys", "kernels", "lowered", "law_kinks"]

#: The laws, in slot order (:func:`kernels`): one line per law module.
LAWS = [
    orifice.LAW,
    fabric.LAW,
    graefe.LAW,
    leakage_table.LAW,
    flux.LAW,
    bulk_viscosity.LAW,
    linear_resistance.LAW,
    seal.LAW,
]


def _laws() -> list:
    return LAWS


def register(spec: LawSpec) -> int:
    """Add a law (a :class:`LawSpec`, e.g. of a module outside the package); returns its slot. Its names must be new.
    """
    laws = _laws()
    taken = {n for s in laws for n in s.names}
    if taken & set(spec.names):
        raise ValueError(f"law names already registered: {sorted(taken & set(spec.names))}")
    if len(laws) + 2 > LAW_SLOTS:  # a slot for the hosted kernel, and the no-flow filler
        raise ValueError(f"no free law slot: the engine has {LAW_SLOTS}")
    laws.append(spec)
    return len(laws) - 1


def names() -> tuple:
    """Every law name a scene may give, in registry order."""
    return tuple(n for s in _laws() for n in s.names)


def spec_of_name(name: str) -> LawSpec:
    for s in _laws():
        if name in s.names:
            return s
    raise KeyError(name)


def law_keys() -> tuple:
    """Every law key (LawKey), each once, in registry order."""
    seen, out = set(), []
    for s in _laws():
        for k in s.keys:
            if k.name not in seen:
                seen.add(k.name)
                out.append(k)
    return tuple(out)


def spec_of(law) -> LawSpec | None:
    """The spec that lowers this law object (exactly its class, and the spec accepts it), None: hosted."""
    for s in _laws():
        if type(law) is s.law and s.lowers(law):
            return s
    return None


def kernels() -> tuple:
    """The engine's ``laws`` (:data:`LAW_SLOTS` kernels): the registry's, then the hosted kernel, then the no-flow
    kernel in the free slots."""
    from .hosted import hosted_kernel, no_flow

    laws = [s.kernel for s in _laws()] + [hosted_kernel]
    return tuple(laws + [no_flow] * (LAW_SLOTS - len(laws)))


def lowered(law, tables, host: int, j: int) -> tuple:
    """(slot, law floats (LAW_FLOATS,), law ints (LAW_INTS,)) of exchange j's law; a hosted law's ints are its host
    id and j."""
    spec = spec_of(law)
    if spec is None:
        floats, ints, slot = (), (host, j), len(_laws())
    else:
        floats, ints = spec.lower(law, tables)
        slot = _laws().index(spec)
    return slot, _row(floats, LAW_FLOATS, float), _row(ints, LAW_INTS, np.int64)


def law_kinks(law) -> tuple:
    """((KinkVariable, x, row), ...) of a law object (none when hosted)."""
    spec = spec_of(law)
    return tuple(spec.kinks(law)) if spec is not None else ()


def _row(values, width: int, dtype) -> np.ndarray:
    if len(values) > width:
        raise ValueError(f"a law lowers to at most {width} entries, got {len(values)}")
    out = np.full(width, -1 if dtype is np.int64 else math.nan, dtype=dtype)
    out[:len(values)] = values
    return out
