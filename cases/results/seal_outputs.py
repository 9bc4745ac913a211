"""What a run reports of its seals: history columns of the channel, the summary's account of what was modelled, and
a picture of the gap field over the seal with its contact region.

Per seal exchange ``<seal>`` (its leak rate is the exchange's ``<seal>.mass_flow [kg/s]``):
``<seal>.min_gap [m]`` and ``<seal>.mean_gap [m]`` (area-weighted) of the channel height over the seal's nodes,
``<seal>.contact_fraction [-]`` the area of the nodes in contact over the seal's area, ``<seal>.conductance [m^3]``
the film conductance K(s) the engine used, all at the flange's displacement s of each row.
"""
from __future__ import annotations

import math

import numpy as np

from cases.model.build_seal import seal_models

__all__ = ["seal_columns", "seal_summary", "write_seal_pictures"]


def _displacements(model, columns, history):
    name = f"{model.network.body.name}.displacement [m]"
    return history[:, columns.index(name)]


def seal_columns(model, columns, history) -> list:
    """[(column, values)] of every seal at the rows of ``history`` (which holds the flange's displacement).

    The channel is evaluated once per distinct row of the seal's node table (a flat ring: one per radius) and the
    area sums are taken over those rows with their summed areas."""
    out = []
    for seal in seal_models(model):
        s = _displacements(model, columns, history)
        path, node_row = seal.path.distinct()
        areas = np.bincount(node_row, weights=seal.film.areas, minlength=len(path.nodes))
        total = float(np.sum(areas))  # the same sum as a fraction's numerator: all in contact gives 1 exactly
        h, touching = (np.array(v) for v in zip(*(path.state(q) for q in s))) if len(s) else (np.zeros((0, 1)),) * 2
        mins, means = h.min(axis=1, initial=np.inf), np.sum(h * areas, axis=1) / total
        fractions = np.sum(np.where(touching, areas, 0.0), axis=1) / total
        conductance = np.array([seal.law.conductance(q)[0] for q in s])
        out += [(f"{seal.name}.min_gap [m]", mins), (f"{seal.name}.mean_gap [m]", means),
                (f"{seal.name}.contact_fraction [-]", fractions), (f"{seal.name}.conductance [m^3]", conductance)]
    return out


def seal_summary(seals) -> dict:
    """What was modelled for each seal (summary.json, under "modelled")."""
    out = {}
    for seal in seals:
        law, c = seal.law, seal.law.curve
        setup = law.setup
        viscosity = f"{setup.viscosity} Pa s" if setup.viscosity else \
            f"{setup.viscosity_model} mu(T) of {setup.gas}"
        out[seal.name] = {
            "model": "compressible Reynolds film through the seal interface, laminar, isothermal at the upstream "
                     "temperature, no inertia; conductance K(s) of the flange displacement tabulated once",
            "gap law": f"{setup.gap_name}: {setup.gap!r}",
            "hysteresis": "loading curve" if math.isnan(setup.loaded_to) else
                          f"unloading from the contact pressure at s = {setup.loaded_to} m",
            "viscosity": viscosity, "slip": "first-order slip" if setup.slip else "none (no-slip)",
            "film nodes": int(seal.film.vertices.shape[0]), "chart": seal.film.chart,
            "tabulated displacement [m]": [setup.s_min, setup.s_max],
            "closure displacement [m]": float(c.closure) if math.isfinite(c.closure) else None,
            "knots": int(len(c.knots)), "Reynolds solves": int(c.solves)}
    return out


def write_seal_pictures(results, out) -> list:
    """``seal_<name>.png``: the gap field at the row of the largest leak rate (or the last row), for each seal."""
    from exchange.seal.outputs import gap_picture

    written = []
    model, columns, history = results.model, results.columns, results.history
    for seal in seal_models(model):
        flow = history[:, columns.index(f"{seal.name}.mass_flow [kg/s]")]
        r = int(np.argmax(flow)) if np.any(flow > 0.0) else len(flow) - 1
        q = _displacements(model, columns, history)[r]
        path = out / f"seal_{seal.name}.png"
        gap_picture(seal.film, seal.path.heights(q), seal.path.in_contact(q), path,
                    title=f"{seal.name} at t = {history[r, 0]:.6g} s: leak {flow[r]:.4g} kg/s, s = {q:.4g} m")
        written.append(path)
    return written
