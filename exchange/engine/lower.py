"""Lowering a network (:class:`exchange.network.network.Network`, or a scene network with its geometry) onto the engine: its
model (:mod:`exchange.engine.layout`), its switch table and the Python objects it keeps (:class:`exchange.engine.
engine.Engine`), or why it cannot run there (:func:`unsupported_reason`).

Supported: ideal-gas mixtures with piecewise cp polynomials (adiabatic, isothermal or heat loss), real-gas cavities
(adiabatic, heat loss or a wall; hosted) and hydraulic cavities without inflators, with fixed, table, scaled-mesh or
wrapped volumes; every inflator kind; exchanges to ambient (one- or two-way) or between cavities with any law of
the registry or any object with ``mass_flow(up, p_down, area, t)`` (hosted), with activation (window, amplitude, pop
with hold, DELTA LEAKAGE AREA, close pressure) and blocked or moving leakage areas; one dynamic body, seated or not.
"""
from __future__ import annotations

import importlib.util
import math

import numpy as np

from cavity.volume import FixedVolume, ScaledMeshVolume, TableVolume
from exchange.laws import registry

from .geometry import Geometry
from .host import register
from .inflators import INFLATOR_KINDS, lower_inflators
from .layout import (LAW_SLOTS, UNLOCKED, AreaKind, BodyColumn, CavityFloat, CavityInt, Energy, ExchangeFloat,
                     ExchangeInt, Fluid, ModelArrays, SeatLaw, SeatNode,
                     SeatState, StateColumn, VolumeKind, new_model)
from .sampled import sampling_rows
from .switch_table import switch_table
from .tables import Tables

__all__ = ["lower", "unsupported_reason", "has_hosted_parts", "geometry_of"]

GAS_ENERGY = {"adiabatic": Energy.ADIABATIC, "isothermal": Energy.ISOTHERMAL, "heat_loss": Energy.HEAT_LOSS}
REAL_GAS_ENERGY = {"adiabatic": Energy.ADIABATIC, "heat_loss": Energy.HEAT_LOSS, "wall": Energy.WALL}


def geometry_of(net) -> Geometry:
    """The network's geometry for the engine (its ``lowered_geometry()``: :class:`exchange.engine.geometry.
    Geometry`), or none."""
    lowered = getattr(net, "lowered_geometry", None)
    return lowered() if lowered is not None else Geometry()


def unsupported_reason(net) -> str | None:
    """Why ``net`` cannot run on the engine (None: it can)."""
    if importlib.util.find_spec("numba") is None:
        return "numba is not installed"
    lowered = getattr(net, "lowered_geometry", None)
    if not net.is_plain() and lowered is None:
        return f"{type(net).__name__} is not a plain Network"
    if lowered is not None and isinstance(lowered(), str):
        return lowered()
    volumes = geometry_of(net).volumes
    for cav in net.cavities:
        kind = getattr(cav, "kind", "gas")
        if kind == "hydraulic" and cav.inflators:
            return f"cavity {cav.name}: a hydraulic cavity with inflators"
        if kind not in ("gas", "hydraulic", "realgas") or (kind == "gas" and cav.energy not in GAS_ENERGY) \
                or (kind == "realgas" and cav.energy not in REAL_GAS_ENERGY):
            return f"cavity {cav.name}: kind or energy model"
        if not isinstance(cav.volume, (FixedVolume, TableVolume, ScaledMeshVolume)) and cav.name not in volumes:
            return f"cavity {cav.name}: volume model {type(cav.volume).__name__}"
        for inf in cav.inflators:
            if type(inf) not in INFLATOR_KINDS or tuple(inf.gas.breaks) != tuple(net.gas.breaks):
                return f"inflator {inf.name}: {type(inf).__name__}"
    for ex in net.exchanges:
        if registry.spec_of(ex.law) is None and not callable(getattr(ex.law, "mass_flow", None)):
            return f"exchange {ex.name}: law {type(ex.law).__name__} has no mass_flow(up, p_down, area, t)"
    return None


def has_hosted_parts(net) -> bool:
    """A real-gas cavity or a law the engine calls in Python (:mod:`exchange.engine.hosted`)."""
    return any(getattr(c, "kind", "gas") == "realgas" for c in net.cavities) \
        or any(registry.spec_of(ex.law) is None for ex in net.exchanges)


def _cavities(net, tables, host, geometry) -> tuple:
    """(cavity_int, cavity_float) of the network's cavities."""
    ints, floats = [], []
    splines = geometry.volumes
    for cav, k, c in zip(net.cavities, net.offsets, net.ledger_offsets):
        vol, kind_name = cav.volume, getattr(cav, "kind", "gas")
        fluid = {"hydraulic": Fluid.HYDRAULIC, "realgas": Fluid.REAL_GAS}.get(kind_name, Fluid.GAS)
        if cav.name in splines:
            spline = splines[cav.name]
            kind = VolumeKind.SPLINE_OF_BODY if spline.by_body else VolumeKind.SPLINE_OF_TIME
            table = tables.add_spline(spline.knots, spline.coefficients)
        elif isinstance(vol, FixedVolume):
            kind, table = VolumeKind.FIXED, -1
        elif isinstance(vol, TableVolume):
            kind, table = VolumeKind.TABLE, tables.add(vol.table)
        else:
            kind, table = VolumeKind.SCALED_MESH, tables.add(vol.scale)
        size = vol.volume if kind == VolumeKind.FIXED else vol.mesh_volume if kind == VolumeKind.SCALED_MESH else 0.0
        liquid = fluid == Fluid.HYDRAULIC
        energy = Energy.ISOTHERMAL if liquid else (REAL_GAS_ENERGY if fluid == Fluid.REAL_GAS else GAS_ENERGY)[
            cav.energy]
        row = [0] * len(CavityInt)
        row[CavityInt.OFFSET], row[CavityInt.ENERGY], row[CavityInt.VOLUME] = k, energy, kind
        row[CavityInt.VOLUME_TABLE], row[CavityInt.LEDGER], row[CavityInt.SPECIES] = table, c, len(cav.initial_masses)
        row[CavityInt.BODY_OFFSET] = geometry.body.offset if kind == VolumeKind.SPLINE_OF_BODY else -1
        row[CavityInt.FLUID] = fluid
        row[CavityInt.TEMPERATURE_TABLE] = tables.add(cav.temperature) if liquid else -1
        row[CavityInt.HOST] = host if fluid == Fluid.REAL_GAS else -1
        row[CavityInt.PIECE] = UNLOCKED
        ints.append(row)
        hA = 0.0 if liquid else cav.heat_transfer_coefficient * cav.heat_transfer_area
        floats.append((cav.initial_temperature, cav.added_volume, cav.minimum_volume, hA,
                       0.0 if liquid else cav.ambient_temperature, size) + _liquid(cav))
    return (np.array(ints, dtype=np.int64).reshape(-1, len(CavityInt)),
            np.array(floats, dtype=float).reshape(-1, len(CavityFloat)))


def _liquid(cav) -> tuple:
    """A hydraulic cavity's reference density [kg/m^3], bulk modulus [Pa], reference pressure [Pa], reference
    temperature [K] and thermal expansion [1/K] (zeros for a gas)."""
    if getattr(cav, "kind", "gas") != "hydraulic":
        return (0.0,) * 5
    return (cav.reference_density, cav.bulk_modulus, cav.reference_pressure, cav.reference_temperature,
            cav.thermal_expansion)


def _area(tables, area) -> tuple:
    """(area table, scale table, AreaKind, switch scale) of an exchange's blocked area (AreaSteps), or of none."""
    if area is None:
        return -1, -1, AreaKind.CONSTANT, 1.0
    x, moving = area.crossings, area.moving
    steps = tables.add_arrays(np.concatenate([[-np.inf], x]), area.areas if moving is None else
                              np.arange(len(x) + 1.0))
    if moving is not None:  # a surface on a vertex trajectory: the steps give the interval, then its pack
        tables.add_arrays(np.zeros(len(moving)), moving)
    scale = tables.add(area.scale) if area.scale is not None else -1
    kind = AreaKind.MOVING_SURFACE if moving is not None else AreaKind.SAMPLED_OF_BODY if area.sampling is not None \
        else AreaKind.STEPS_OF_BODY if area.by_body else AreaKind.STEPS_OF_TIME
    return steps, scale, kind, area.switch_scale


def _exchanges(net, tables, host, geometry) -> tuple:
    """(exchange_int, exchange_float, law_int, law_float) of the network's exchanges."""
    ints, floats, law_ints, law_floats = [], [], [], []
    geometric = geometry.areas
    for j, ex in enumerate(net.exchanges):
        act = ex.activation
        window = act is not None
        pop = window and act.pop_pressure is not None
        slot, lf, li = registry.lowered(ex.law, tables, host, j)
        steps, scale, kind, switch_scale = _area(tables, geometric.get(j))
        amplitude = tables.add(act.amplitude) if window and act.amplitude is not None else -1
        ints.append((ex.upstream, -1 if ex.downstream is None else ex.downstream, int(bool(ex.two_way)), amplitude,
                     int(window), int(net.can_equalise(j)), int(pop), slot, steps, scale, kind,
                     int(window and act.delta_area), int(bool(ex.law.prescribed)),
                     int(bool(getattr(ex.law, "body_load", False)))))
        floats.append((ex.area, act.open_time if window else 0.0, act.close_time if window else math.inf,
                       act.pop_pressure if pop else 0.0, act.hold_time if pop else 0.0, switch_scale,
                       _area_at_activation(net, j), (act.close_pressure or 0.0) if window else 0.0,
                       float(getattr(ex.law, "join_below", 0.0))))
        law_ints.append(li)
        law_floats.append(lf)
    ne = len(net.exchanges)
    return (np.array(ints, dtype=np.int64).reshape(ne, len(ExchangeInt)),
            np.array(floats, dtype=float).reshape(ne, len(ExchangeFloat)),
            np.array(law_ints, dtype=np.int64).reshape(ne, registry.LAW_INTS),
            np.array(law_floats, dtype=float).reshape(ne, registry.LAW_FLOATS))


def _area_at_activation(net, j) -> float:
    """The base area [m^2] a DELTA LEAKAGE AREA subtracts, known in advance for an exchange opened by time (its
    area at its open time); a pop vent's is set when it pops."""
    act = net.exchanges[j].activation
    if act is None or not act.delta_area or act.pop_pressure is not None:
        return 0.0
    return float(net.base_area(j, act.open_time))


def _body(geometry) -> np.ndarray:
    """The dynamic body (BodyColumn; offset −1: none)."""
    if geometry.body is None:
        none = np.zeros(len(BodyColumn))
        none[BodyColumn.OFFSET] = -1.0
        return none
    return geometry.body.array()


def _seat(geometry) -> tuple:
    """(seat_state, seat_law, seat_nodes, seat_kinks) of the network's seat contact (zeros: none)."""
    seat = geometry.seat
    if seat is None:
        return np.zeros(len(SeatState)), np.zeros(len(SeatLaw)), np.zeros((0, len(SeatNode))), np.zeros(0)
    return (seat.state(), np.ascontiguousarray(seat.law, dtype=float), np.ascontiguousarray(seat.nodes, dtype=float),
            np.ascontiguousarray(seat.kinks, dtype=float))


def lower(net):
    """The network on the engine (:class:`exchange.engine.engine.Engine`), or None if a part is not supported."""
    from .engine import Engine

    if unsupported_reason(net) is not None:
        return None
    geometry = geometry_of(net)
    gas = net.gas
    _, rows, linear, breaks = gas._per_range  # rows (ns, nr, 7) per mole, constant-cp flags and breaks
    ns, nr = rows.shape[0], rows.shape[1]
    tables = Tables()
    host = register(net) if has_hosted_parts(net) else -1
    cavity_int, cavity_float = _cavities(net, tables, host, geometry)
    inflator_int, inflator_float, inflator_rows = lower_inflators(net, tables, ns, nr)
    exchange_int, exchange_float, law_int, law_float = _exchanges(net, tables, host, geometry)
    kinds, targets, labels, kink_int, kink_x = switch_table(net, geometry)
    table_x, table_y, table_index = tables.arrays()
    a = net.ambient.point()
    ambient = np.array([a.p, a.T, a.rho, a.R, a.gamma, a.h] + list(np.asarray(a.mass_fractions, dtype=float)))
    nc, ne = len(net.cavities), len(net.exchanges)
    T0 = np.array([c.initial_temperature for c in net.cavities], dtype=float)
    kernels = registry.kernels()
    assert len(kernels) == LAW_SLOTS
    arrays = ModelArrays(
        np.ascontiguousarray(rows, dtype=float), np.ascontiguousarray(breaks, dtype=float),
        np.ascontiguousarray(linear, dtype=np.int64), np.asarray(gas.molar_masses, dtype=float),
        table_x, table_y, table_index, cavity_int, cavity_float, inflator_int, inflator_float, inflator_rows,
        exchange_int, exchange_float, law_int, law_float, kernels, kink_int, kink_x, ambient,
        int(net.ledger_offset), T0.copy(), np.zeros((nc, StateColumn.FRACTIONS + ns)), np.zeros(ns), np.zeros(7),
        np.zeros(ne, dtype=np.int64), np.ones(ne, dtype=np.int64), np.full(ne, np.nan), np.zeros(ne, dtype=np.int64),
        sampling_rows(geometry, ne), _body(geometry), *_seat(geometry), kinds, targets)
    return Engine(new_model(arrays), arrays, labels, T0, net, host)
