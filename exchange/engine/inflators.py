"""Inflators on the engine: each inflator's mass flow, gas temperature and enthalpy flow at t (the laws of
:mod:`cavity.inflator` and :mod:`cavity.inflator_orifice`, numba kernels Python calls too), and how a network's
inflators lower onto the model (``inflator_int``, ``inflator_float``, ``inflator_rows``)."""
from __future__ import annotations

import numpy as np
from numba import njit

from cavity.caution import caution
from cavity.gas_rows import range_of, row_enthalpy, rows_gamma
from cavity.inflator import MassTemperatureInflator, TankTestInflator, tank_test_mass_flow
from cavity.inflator_orifice import (DualPressureInflator, PressureMassInflator, clamped_message,
                                     dual_pressure_state, pressure_mass_state)
from cavity.inflator_realgas import RealGasTankTestInflator
from cavity.tolerances import R_UNIVERSAL as R_U

from .layout import InflatorFloat, InflatorInt, InflatorKind
from .tables import table_slope, table_value

__all__ = ["INFLATOR_KINDS", "inflator_flow", "inflator_enthalpy_flow", "lower_inflators", "warn_clamped"]

IF, II = InflatorFloat, InflatorInt

#: Inflator class -> its kind on the engine.
INFLATOR_KINDS = {MassTemperatureInflator: InflatorKind.MASS_TEMPERATURE, TankTestInflator: InflatorKind.TANK_TEST,
                  PressureMassInflator: InflatorKind.PRESSURE_MASS, DualPressureInflator: InflatorKind.DUAL_PRESSURE,
                  RealGasTankTestInflator: InflatorKind.REAL_GAS_TANK_TEST}


@njit(cache=True)
def inflator_flow(M, q, t):
    """(ṁ [kg/s], T_i [K]) of inflator q at t >= its start (``mass_flow`` and ``temperature`` of its class), by kind:
    the scaled mass-flow table and the temperature table; a tank test's :func:`cavity.inflator.tank_test_mass_flow`
    on the slope of the tank-pressure table (none while it falls); the mass-flow table and T_i of
    :func:`cavity.inflator_orifice.pressure_mass_state`; both from :func:`cavity.inflator_orifice.dual_pressure_state`;
    a real-gas tank's delivered-mass slope and the temperature table. A temperature held at a bound raises the
    inflator's CLAMPED flag (warned after the run, :func:`warn_clamped`)."""
    ii, fl, tx, ty, ti = M.inflator_int, M.inflator_float, M.table_x, M.table_y, M.table_index
    x, scale, kind = t - fl[q, IF.START], fl[q, IF.SCALE], ii[q, II.KIND]
    first, second = ii[q, II.FIRST_TABLE], ii[q, II.SECOND_TABLE]
    mass, moles = fl[q, IF.GAS_MASS], fl[q, IF.MOLES]
    if kind == InflatorKind.MASS_TEMPERATURE:
        return scale * table_value(tx, ty, ti, first, x), table_value(tx, ty, ti, second, x)
    if kind == InflatorKind.REAL_GAS_TANK_TEST:
        return scale * table_slope(tx, ty, ti, first, x), table_value(tx, ty, ti, second, x)
    if kind == InflatorKind.TANK_TEST:
        T = table_value(tx, ty, ti, second, x)
        rate = table_slope(tx, ty, ti, first, x)
        if rate <= 0.0:
            return 0.0, T
        g = rows_gamma(M.inflator_rows[q], M.gas_breaks, moles, T)
        return scale * tank_test_mass_flow(fl[q, IF.TANK_VOLUME], rate, g, moles * R_U / mass, T), T
    p = table_value(tx, ty, ti, second, x)
    if kind == InflatorKind.PRESSURE_MASS:
        mdot = table_value(tx, ty, ti, first, x)
        T, clamped = pressure_mass_state(mdot, p, fl[q, IF.ORIFICE_AREA], fl[q, IF.CD], M.inflator_rows[q],
                                         M.gas_breaks, moles, mass)
    else:
        mdot, T, clamped = dual_pressure_state(p, table_slope(tx, ty, ti, first, x), fl[q, IF.TANK_VOLUME],
                                               fl[q, IF.ORIFICE_AREA], fl[q, IF.CD], M.inflator_rows[q],
                                               M.gas_breaks, moles, mass)
    if clamped:
        ii[q, II.CLAMPED] = 1
    return scale * mdot, T


@njit(cache=True)
def inflator_enthalpy_flow(M, q, mdot, T_in):
    """Enthalpy flow [W] of ``mdot`` [kg/s] of inflator q's gas at T_in [K]: ṁ·H(T_in)/m of its gas's rows."""
    r = M.inflator_rows[q, range_of(M.gas_breaks, T_in)]
    return mdot * row_enthalpy(r, T_in) / M.inflator_float[q, IF.GAS_MASS]


def _tables(inf, kind: int) -> tuple:
    """The inflator's two tables (FIRST_TABLE, SECOND_TABLE)."""
    if kind == InflatorKind.REAL_GAS_TANK_TEST:  # the delivered mass its states give at load, and the temperature
        return inf.delivered, inf.temperature_table
    first = inf.tank_pressure_table if kind in (InflatorKind.TANK_TEST, InflatorKind.DUAL_PRESSURE) \
        else inf.mass_flow_table
    second = inf.pressure_table if kind in (InflatorKind.PRESSURE_MASS, InflatorKind.DUAL_PRESSURE) \
        else inf.temperature_table
    return first, second


def lower_inflators(net, tables, ns: int, nr: int) -> tuple:
    """(inflator_int, inflator_float, inflator_rows) of a network's inflators, in the order of its cavities and their
    inflators (``tables`` the :class:`exchange.engine.tables.Tables` being filled)."""
    ints, floats, rows = [], [], []
    for i, cav in enumerate(net.cavities):
        for inf in cav.inflators:
            kind = INFLATOR_KINDS[type(inf)]
            first, second = _tables(inf, kind)
            ints.append((i, tables.add(first), tables.add(second), int(kind), 0))
            floats.append([inf.start, inf.scale, inf.gas.mass, getattr(inf, "tank_volume", 0.0), inf.gas.moles,
                           getattr(inf, "area", 0.0), getattr(inf, "discharge_coefficient", 0.0)]
                          + list(np.asarray(inf.mass_fractions, dtype=float)))
            rows.append(np.array(inf.gas.rows, dtype=float))
    return (np.array(ints, dtype=np.int64).reshape(-1, len(II)),
            np.array(floats, dtype=float).reshape(-1, IF.FRACTIONS + ns),
            np.array(rows, dtype=float).reshape(-1, nr, 7))


def warn_clamped(net, inflator_int) -> None:
    """Warn (:func:`cavity.caution.caution`, the inflator's own message) for each inflator whose CLAMPED flag a run
    raised, and lower the flags."""
    flagged = np.flatnonzero(inflator_int[:, II.CLAMPED])
    if flagged.size:
        inflators = [inf for cav in net.cavities for inf in cav.inflators]
        for q in flagged:
            caution(clamped_message(inflators[q].name))
        inflator_int[:, II.CLAMPED] = 0
