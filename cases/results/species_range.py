"""Warnings for a run that used a species outside the temperatures its data hold (cp held constant there)."""
from __future__ import annotations

import numpy as np

__all__ = ["species_range_warnings"]


def _outside(species, names, what, t_min, t_max) -> list:
    out = []
    for s in species:
        lo, hi = s.valid_range
        if s.name in names and (t_min < lo or t_max > hi):
            out.append(f"{what} reached {t_min:.6g} to {t_max:.6g} K, outside the data range of species "
                       f"{s.name!r} ({lo:g} to {hi:g} K): its cp is held at the end value there; for data over that range "
                       "give [[species]] with coolprop = '<fluid>' (or cp coefficients valid there)")
    return out


def species_range_warnings(model, history: np.ndarray, columns: list) -> list:
    """Messages for every species whose ``valid_range`` the run left: a cavity temperature in ``history`` (named
    by ``columns``, those of ``cases.run.runner.history_columns``) with that species in the cavity or its inflators, or an
    inflator's gas temperature table."""
    species = model.network.gas.species
    if history.size == 0 or all(s.valid_range == (0.0, np.inf) for s in species):
        return []
    out = []
    for i, cav in enumerate(model.network.cavities):
        if getattr(cav, "kind", "gas") != "gas":
            continue
        present = {s.name for k, s in enumerate(species) if cav.initial_masses[k] > 0
                   or any(inf.mass_fractions[k] > 0 for inf in cav.inflators)}
        k = columns.index(f"{cav.name}.temperature [K]") if f"{cav.name}.temperature [K]" in columns else None
        if k is None:
            continue
        T = history[:, k]
        out += _outside(species, present, f"cavity {cav.name!r}", float(np.min(T)), float(np.max(T)))
        for inf in cav.inflators:
            table = getattr(inf, "temperature_table", None)
            if table is not None:
                names = {s.name for k, s in enumerate(species) if inf.mass_fractions[k] > 0}
                out += _outside(species, names, f"inflator {inf.name!r}", min(table.y), max(table.y))
    return out
