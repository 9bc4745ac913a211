"""A lowered network's values at one instant, for results and the Python API: the cavity states as records, each
exchange's flow and area, the dynamic body's forces, in a discrete state loaded from a trajectory's mode.

Every value comes from the engine's kernels (:func:`exchange.engine.gas.states`, :mod:`exchange.readback.points`:
the ones the right-hand side runs); this module only loads the discrete state, calls them and wraps what they
return.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from exchange.engine.gas import states
from exchange.engine.layout import StateColumn

from .points import point_body, point_exchanges

__all__ = ["GasState", "cavity_states", "exchange_values", "body_values", "load_mode"]


@dataclass(frozen=True, slots=True)
class GasState:
    """The state of one cavity at one instant.

    pressure [Pa], temperature [K], mass [kg], volume [m^3], volume_rate [m^3/s], density [kg/m^3],
    gas_constant [J/(kg K)] (NaN for a liquid), gamma [-], specific_enthalpy [J/kg], mass_fractions (ns,) [-];
    a real-gas cavity with a wall: wall_temperature and outer_wall_temperature [K] of its inner and outer layers
    (the same when lumped; NaN without a wall)."""

    pressure: float
    temperature: float
    mass: float
    volume: float
    volume_rate: float
    density: float
    gas_constant: float
    gamma: float
    specific_enthalpy: float
    mass_fractions: np.ndarray
    wall_temperature: float = math.nan
    outer_wall_temperature: float = math.nan


def _check(engine, ok: bool, t: float) -> None:
    if not ok:
        raise ArithmeticError(f"at t = {t:.9g} s: {engine.failure()}")


def load_mode(engine, mode) -> None:
    """Load a trajectory's discrete state of a segment into the network and its engine's model."""
    engine.network.restore(mode)
    engine.load_discrete_state()


def cavity_states(engine, t: float, y) -> list:
    """The :class:`GasState` of every cavity at (t, y) (the equation of state does not depend on the discrete
    state)."""
    y = np.ascontiguousarray(y, dtype=float)
    _check(engine, states(engine.model, float(t), y), t)
    st, net, out, c = engine.arrays.state, engine.network, [], StateColumn
    for i, (cav, k) in enumerate(zip(net.cavities, net.offsets)):
        row, ns = st[i], len(cav.initial_masses)
        walls = ()
        wall = getattr(cav, "wall", None)
        if wall is not None:
            walls = (float(y[k + ns + 1]), float(y[k + ns + wall.layers]))
        out.append(GasState(float(row[c.P]), float(row[c.T]), float(row[c.MASS]), float(row[c.V]), float(row[c.DV]),
                            float(row[c.RHO]), float(row[c.R]), float(row[c.GAMMA]), float(row[c.H]),
                            row[c.FRACTIONS:c.FRACTIONS + ns].copy(), *walls))
    return out


def exchange_values(engine, t: float, y) -> tuple[np.ndarray, np.ndarray]:
    """(mass flow [kg/s] first side → second, flow area [m^2]) of every exchange at (t, y) in the loaded discrete
    state."""
    ne = len(engine.network.exchanges)
    flows, areas = np.empty(ne), np.empty(ne)
    _check(engine, point_exchanges(engine.model, float(t), np.ascontiguousarray(y, dtype=float), flows, areas), t)
    return flows, areas


def body_values(engine, t: float, y) -> tuple[float, float, float, float]:
    """(gas force [N], acceleration [m/s^2], reaction of a hard seat holding it at rest [N], gas and spring force
    [N]) of the dynamic body at (t, y) in the loaded discrete state (:func:`exchange.readback.points.point_body`)."""
    out = np.empty(4)
    _check(engine, point_body(engine.model, float(t), np.ascontiguousarray(y, dtype=float), out), t)
    return float(out[0]), float(out[1]), float(out[2]), float(out[3])
