"""The columns of history.csv an engineer expects beyond the state: gauge pressure and the blocked fraction of every
exchange, each placed beside the column it explains, and each inflator's mass flow and temperature (read back by the
engine) moved beside its cavity's volume."""
from __future__ import annotations

import numpy as np

from cases.results.leak_state import leak_area_at, open_area_at, thetas_at

__all__ = ["engineering_columns"]


def _blocked_fraction(model, trajectory, j: int, times) -> np.ndarray:
    """``1 − A_leak(t) / A_open`` [-] of exchange j at ``times`` (:mod:`cases.results.leak_state`), 0 without geometry."""
    geo = model.geometry
    if geo is None or j >= len(geo["areas"]) or geo["areas"][j] is None:
        return np.zeros(len(times))
    track, out = geo["areas"][j].track, np.zeros(len(times))
    for k, th in enumerate(thetas_at(model, trajectory, times)):
        th = float(th)
        a_open = open_area_at(track, th)
        out[k] = 1.0 - leak_area_at(track, th) / a_open if a_open > 0.0 else 0.0
    return out


def _inflator_columns(cav) -> list:
    return [f"{cav.name}.{inf.name}.{q}" for inf in getattr(cav, "inflators", ())
            for q in ("mass_flow [kg/s]", "temperature [K]")]


def _extra(model, trajectory, name: str, times, history, index) -> list:
    """[(column, values)] to place right after column ``name`` (full name with unit)."""
    net = model.network
    cavities = {f"{c.name}.pressure [Pa]": c for c in net.cavities}
    volumes = {f"{c.name}.volume [m^3]": c for c in net.cavities}
    areas = {f"{e.name}.area [m^2]": j for j, e in enumerate(net.exchanges)}
    if name in cavities:
        return [(f"{cavities[name].name}.gauge_pressure [Pa]", history[:, index[name]] - net.ambient.pressure)]
    if name in volumes:
        return [(col, history[:, index[col]]) for col in _inflator_columns(volumes[name])]
    if name in areas:
        j = areas[name]
        return [(f"{net.exchanges[j].name}.blocked_fraction [-]", _blocked_fraction(model, trajectory, j, times))]
    return []


def engineering_columns(model, trajectory, columns: list, history: np.ndarray) -> tuple[list, np.ndarray]:
    """``columns`` and ``history`` with, per cavity, ``<cavity>.gauge_pressure [Pa]`` (p − p_ambient) after its
    pressure and its inflators' ``<cavity>.<inflator>.mass_flow [kg/s]`` and ``.temperature [K]`` moved after its
    volume; per exchange ``<exchange>.blocked_fraction [-]`` after its area."""
    times = history[:, 0]
    index = {name: i for i, name in enumerate(columns)}
    moved = {col for c in model.network.cavities for col in _inflator_columns(c)}
    names, values = [], []
    for i, name in enumerate(columns):
        if name in moved:
            continue
        names.append(name)
        values.append(history[:, i])
        for extra, v in _extra(model, trajectory, name, times, history, index):
            names.append(extra)
            values.append(v)
    return names, np.column_stack(values) if values else history
