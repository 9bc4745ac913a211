"""A seal exchange from its scene values: the gap law and viscosity it names (:func:`seal_setup`), then, once the
seal surface and the flange's contact are known, its conductance curve over the flange's displacement
(:func:`seal_law`, built once at load).

The load coordinate is the dynamic body's displacement s [m] (:class:`~exchange.seal.load_paths.DisplacementPath`
on the seat's node table and contact law): the contact must be penalty (linear) or softened (exponential), whose
contact pressure is a function of s. The curve is built piece by piece between the displacements where the seat's
force kinks (first touch of each distinct clearance), so the kink of the channel there is a knot of the curve.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from exchange.seal.conductance import conductance_curve, ConductanceCurve
from exchange.seal.film import seal_film
from exchange.seal.gap_laws import ExponentialGap, NoGap, PerssonGap, TableGap
from exchange.seal.hysteresis import PVRCGap
from exchange.seal.load_paths import DisplacementPath
from exchange.seal.reynolds import film_conductance
from exchange.seal.spec import SealSetup
from exchange.seal.viscosity import SUTHERLAND, coolprop_viscosity, sutherland_viscosity

__all__ = ["seal_setup", "gap_law_of", "viscosity_table", "seal_law", "piecewise_curve", "TEMPERATURES"]

#: Temperatures of the viscosity table [K]: 2 K apart (linear interpolation error < 1e-5 relative).
TEMPERATURES = np.arange(100.0, 1500.0 + 1.0, 2.0)


def gap_law_of(name, v, read_table):
    """The gap law object named ``name`` with the scene values ``v`` (a dict of the seal keys)."""
    cap = v["gap_max"] or math.inf
    if name == "exponential":
        return ExponentialGap(v["gap_h0"], v["gap_p0"], v["gap_percolation"])
    if name == "persson":
        return PerssonGap(v["gap_u0"], v["gap_p_star"], v["gap_percolation"], cap)
    if name == "table":
        if not v["gap_table"]:
            raise ValueError("gap_law = 'table' needs gap_table (CSV: contact pressure [Pa], channel height [m])")
        table = read_table("gap_table", "channel height [m]")
        return TableGap(tuple(table.x), tuple(table.y))
    if name == "pvrc":
        return PVRCGap(v["pvrc_gb"], v["pvrc_a"], v["pvrc_gs"], v["pvrc_h1"], cap)
    return NoGap()


def seal_setup(v, read_table):
    """The :class:`exchange.laws.seal.SealSetup` of a seal exchange's values ``v`` (its law keys)."""
    if not v["seal_displacement_max"] > v["seal_displacement_min"]:
        raise ValueError(f"seal_displacement_max ({v['seal_displacement_max']!r} m) must exceed "
                         f"seal_displacement_min ({v['seal_displacement_min']!r} m)")
    model = v["seal_viscosity_model"]
    if not v["seal_viscosity"] and model == "sutherland" and v["seal_gas"] not in SUTHERLAND:
        raise ValueError(f"Sutherland constants are known for {sorted(SUTHERLAND)}, not {v['seal_gas']!r}: give "
                         "seal_viscosity_model = 'coolprop' or seal_viscosity [Pa s]")
    try:
        gap = gap_law_of(v["gap_law"], v, read_table)
    except ValueError as exc:
        keys = {"exponential": "gap_h0, gap_p0, gap_percolation", "persson": "gap_u0, gap_p_star, gap_percolation, "
                "gap_max", "table": "gap_table", "pvrc": "pvrc_gb, pvrc_a, pvrc_gs, pvrc_h1, gap_max"}
        raise ValueError(f"gap_law = {v['gap_law']!r}: {exc} (its keys: {keys.get(v['gap_law'], '-')})") from None
    return SealSetup(gap, v["gap_law"], v["seal_pressurised_edge"],
                     v["seal_outer_edge"], v["seal_viscosity"], model, v["seal_gas"], bool(v["seal_slip"]),
                     v["seal_displacement_min"], v["seal_displacement_max"], v["seal_loaded_to"], v["seal_rtol"])


def viscosity_table(setup):
    """(T [K], μ [Pa s]) of a seal's gas: constant, Sutherland's law or CoolProp's."""
    if setup.viscosity:
        return (float(TEMPERATURES[0]), float(TEMPERATURES[-1])), (setup.viscosity, setup.viscosity)
    if setup.viscosity_model == "sutherland":
        mu = [sutherland_viscosity(T, *SUTHERLAND[setup.gas]) for T in TEMPERATURES]
    else:
        mu = [coolprop_viscosity(T, setup.gas) for T in TEMPERATURES]
    return tuple(TEMPERATURES.tolist()), tuple(float(m) for m in mu)


def piecewise_curve(film, path, breaks, lower, upper, rtol):
    """The :class:`ConductanceCurve` over [lower, upper] built between the displacements ``breaks`` (where the
    channel kinks): a knot at each break, the pieces joined (a break appears twice, with the slope of each side)."""
    cuts = [lower] + sorted(b for b in set(breaks) if lower < b < upper) + [upper]
    parts = [conductance_curve(film, path, a, b, rtol=rtol) for a, b in zip(cuts[:-1], cuts[1:])]
    return ConductanceCurve(np.concatenate([p.knots for p in parts]), np.concatenate([p.values for p in parts]),
                            np.concatenate([p.slopes for p in parts]), parts[0].closure, parts[0].direction,
                            sum(p.solves for p in parts), max(p.error_estimate for p in parts))


def seal_law(law, vertices, faces, high, low, seat_table, contact_law, breaks=()):
    """``law`` (a :class:`exchange.laws.seal.SealLaw` of its setup) with its film, path and conductance curve.

    ``vertices`` (n, 3), ``faces`` of the seal surface; ``high``, ``low`` its edges ("inner", "outer" or node
    indices); ``seat_table`` (n, 4) and ``contact_law`` the seat arrays of :mod:`exchange.contact.laws` for the same
    nodes; ``breaks`` the displacements where the seat's force kinks [m]. Returns (law, film, path).
    """
    setup = law.setup
    film = seal_film(vertices, faces, high, low)
    loaded = None if math.isnan(setup.loaded_to) else setup.loaded_to
    path = DisplacementPath(seat_table, contact_law, setup.gap, loaded_to=loaded)
    curve = piecewise_curve(film, path, breaks, setup.s_min, setup.s_max, setup.rtol)
    slip = None
    if setup.slip:
        slip = np.array([film_conductance(film, path.heights(q), power=2)[0] if v > 0.0 else 0.0
                         for q, v in zip(curve.knots, curve.values)])
    temperatures, viscosities = viscosity_table(setup)
    return replace(law, curve=curve, slip_values=slip, temperatures=temperatures, viscosities=viscosities,
                   load=float(np.clip(0.0, setup.s_min, setup.s_max))), film, path
