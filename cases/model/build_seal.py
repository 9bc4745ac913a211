"""The seal exchanges of a scene, finished once the network knows its flange: each ``law = "seal"`` exchange's
leakage surface is the seal surface, the [[contact]] whose seat it is gives the flange (the dynamic body) and the
contact law, and :func:`exchange.seal.setup.seal_law` builds its conductance curve over the flange's displacement.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from cases.scene.errors import SceneError
from exchange.contact.laws import HARD, SeatLaw

__all__ = ["SealModel", "finish_seals", "seal_models"]


@dataclass(frozen=True, eq=False)
class SealModel:
    """What the outputs of a seal need: its exchange index and name, film, load path, law and contact name."""

    exchange: int
    name: str
    film: object
    path: object
    law: object


def _edge(scene, where, key, value):
    """'inner', 'outer' or the node indices of a CSV file next to the scene."""
    if value in ("inner", "outer"):
        return value
    file = scene.base / value
    try:
        return np.loadtxt(file, delimiter=",", ndmin=1, comments="#").astype(np.int64).ravel()
    except (OSError, ValueError) as exc:
        raise SceneError(scene.path, f"{where}.{key}", f"expected 'inner', 'outer' or a CSV file of node indices; "
                                                       f"cannot read {value!r}: {exc}") from None


def finish_seals(scene, network, geo) -> None:
    """Replace each seal exchange's law by the law with its conductance curve; keeps the seals' :class:`SealModel`
    in ``geo["seals"]``. Raises SceneError naming the exchange when the seal has no flange or cannot be built."""
    from exchange.seal.setup import seal_law  # here: its film solver imports scipy.optimize and scipy.sparse

    seals = []
    contact = getattr(network, "contact", None)
    if geo is None:
        j = next(j for j, e in enumerate(scene.exchange) if e.law == "seal")
        raise SceneError(scene.path, f"exchange[{j}].leakage_surface", "a seal needs its seal surface: give "
                                                                       "leakage_surface (a mesh of the seal face)")
    exchanges = list(network.exchanges)
    for j, e in enumerate(scene.exchange):
        if e.law != "seal":
            continue
        where = f"exchange[{j}]"
        if contact is None or contact.exchange != j:
            raise SceneError(scene.path, where, f"seal {e.name!r} needs its flange: a [[contact]] with seat = "
                                                f"{e.name!r} (the dynamic body pressed on the seal surface)")
        if int(contact.law_vector[SeatLaw.KIND]) == HARD:
            raise SceneError(scene.path, f"contact.pressure_overclosure", f"seal {e.name!r}: the contact pressure "
                             "must follow the flange's displacement: give 'linear' (the gasket's stiffness [Pa/m]) "
                             "or 'exponential', not 'hard'")
        if not e.leakage_surface:
            raise SceneError(scene.path, f"{where}.leakage_surface", f"seal {e.name!r} needs its seal surface: "
                                                                     "a mesh of the seal face")
        if e.blocked_by or e.effective_area is not None:
            raise SceneError(scene.path, f"{where}.{'blocked_by' if e.blocked_by else 'effective_area'}",
                             f"seal {e.name!r} leaks through its film, not an area: remove the key (the flange's "
                             "contact with the seal face closes it)")
        surface = geo["surfaces"][j][0]
        high = _edge(scene, where, "seal_pressurised_edge", e.seal_pressurised_edge)
        low = _edge(scene, where, "seal_outer_edge", e.seal_outer_edge)
        try:
            law, film, path = seal_law(exchanges[j].law, np.asarray(surface.vertices, float),
                                       np.asarray(surface.faces), high, low, contact.table, contact.law_vector,
                                       contact.thresholds())
        except (ValueError, RuntimeError) as exc:
            raise SceneError(scene.path, where, f"seal {e.name!r}: {exc}") from None
        exchanges[j] = replace(exchanges[j], law=law)
        seals.append(SealModel(j, e.name, film, path, law))
    network.exchanges = tuple(exchanges)
    geo["seals"] = seals


def seal_models(model) -> list:
    """The :class:`SealModel` of every seal of a built model (none without geometry)."""
    return [] if model.geometry is None else model.geometry.get("seals", [])
