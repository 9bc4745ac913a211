"""Lowering a network's inflators to the arrays of the compiled path (``ii``, ``if_``, ``irows``; layout in
:mod:`exchange.compiled_rhs`), and the warning of an orifice inflator whose temperature the compiled run held at
a bound (the flag ``ii[:, 4]`` that :func:`exchange.compiled_sources.inflator_flow` raises)."""
from __future__ import annotations

import numpy as np

from cavity.caution import caution
from cavity.inflator import MassTemperatureInflator, TankTestInflator
from cavity.inflator_orifice import DualPressureInflator, PressureMassInflator, clamped_message
from cavity.inflator_realgas import RealGasTankTestInflator

__all__ = ["INFLATOR_KINDS", "lower_inflators", "warn_clamped"]

#: inflator class -> kind code in ``ii[:, 3]`` (:func:`exchange.compiled_sources.inflator_flow`)
INFLATOR_KINDS = {MassTemperatureInflator: 0, TankTestInflator: 1, PressureMassInflator: 2, DualPressureInflator: 3,
                  RealGasTankTestInflator: 4}


def _tables(inf, kind: int) -> tuple:
    """The inflator's two tables as ``ii[:, 1]`` and ``ii[:, 2]`` hold them: (mass flow or tank pressure,
    temperature or inflator pressure)."""
    if kind == 4:  # a real-gas tank: the delivered mass its states give at load, and the temperature table
        return inf.delivered, inf.temperature_table
    first = inf.tank_pressure_table if kind in (1, 3) else inf.mass_flow_table
    second = inf.pressure_table if kind >= 2 else inf.temperature_table
    return first, second


def lower_inflators(net, tables, ns: int, nr: int) -> tuple:
    """``ii`` (cavity, first table, second table, kind, clamped flag), ``if_`` (start, scale, gas mass, mass
    fractions, tank volume, gas moles, orifice area, Cd) and ``irows`` of the inflators (:mod:`exchange.compiled_rhs`),
    in the order of the cavities and their inflators; ``tables`` is the :class:`exchange.lowered_columns.Tables` being
    filled."""
    ii, ifl, irows = [], [], []
    for i, cav in enumerate(net.cavities):
        for inf in cav.inflators:
            kind = INFLATOR_KINDS[type(inf)]
            first, second = _tables(inf, kind)
            ii.append((i, tables.add(first), tables.add(second), kind, 0))
            ifl.append([inf.start, inf.scale, inf.gas.mass] + list(np.asarray(inf.mass_fractions, dtype=float))
                       + [getattr(inf, "tank_volume", 0.0), inf.gas.moles, getattr(inf, "area", 0.0),
                          getattr(inf, "discharge_coefficient", 0.0)])
            irows.append(np.array(inf.gas.rows, dtype=float))
    return (np.array(ii, dtype=np.int64).reshape(-1, 5), np.array(ifl, dtype=float).reshape(-1, 7 + ns),
            np.array(irows, dtype=float).reshape(-1, nr, 7))


def warn_clamped(net, ii: np.ndarray) -> None:
    """Warn (:func:`cavity.caution.caution`, the inflator's own message) for each inflator whose flag ``ii[q, 4]``
    a compiled run raised, and lower the flags."""
    flagged = np.flatnonzero(ii[:, 4])
    if flagged.size:
        inflators = [inf for cav in net.cavities for inf in cav.inflators]
        for q in flagged:
            caution(clamped_message(inflators[q].name))
        ii[:, 4] = 0
