"""A lowered network's values at one instant, for results and the Python API: the cavity states as records, each
exchange's flow and area, the dynamic body's forces, in a discrete state loaded from a trajectory's mode.

Every value comes from the compiled kernels of :mod:`exchange.compiled_point` (the ones the right-hand side runs);
this module only loads the discrete state, calls them and wraps what they return.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .compiled_point import point_body, point_exchanges, point_states
from .compiled_tables import DV, FR, GAM, H, MASS, P, RG, RHO, TT, V

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


def _check(fast, ok: bool, t: float) -> None:
    if not ok:
        raise ArithmeticError(f"at t = {t:.9g} s: {fast.failure()}")


def load_mode(fast, mode) -> None:
    """Load a trajectory's mode (the network's ``snapshot()`` of a segment) into the network and its arrays."""
    fast.network.restore(mode)
    fast.load_discrete_state()


def cavity_states(fast, t: float, y) -> list:
    """The :class:`GasState` of every cavity at (t, y) (the equation of state does not depend on the discrete
    state)."""
    y = np.ascontiguousarray(y, dtype=float)
    _check(fast, point_states(fast.model, float(t), y), t)
    st, net, out = fast.model[17], fast.network, []
    for i, (cav, k) in enumerate(zip(net.cavities, net.offsets)):
        row, ns = st[i], len(cav.initial_masses)
        walls = ()
        wall = getattr(cav, "wall", None)
        if wall is not None:
            walls = (float(y[k + ns + 1]), float(y[k + ns + wall.layers]))
        out.append(GasState(float(row[P]), float(row[TT]), float(row[MASS]), float(row[V]), float(row[DV]),
                            float(row[RHO]), float(row[RG]), float(row[GAM]),
                            float(row[H]), row[FR:FR + ns].copy(), *walls))
    return out


def exchange_values(fast, t: float, y) -> tuple[np.ndarray, np.ndarray]:
    """(mass flow [kg/s] up → down, flow area [m^2]) of every exchange at (t, y) in the loaded discrete state."""
    ne = len(fast.network.exchanges)
    flows, areas = np.empty(ne), np.empty(ne)
    _check(fast, point_exchanges(fast.model, float(t), np.ascontiguousarray(y, dtype=float), flows, areas), t)
    return flows, areas


def body_values(fast, t: float, y) -> tuple[float, float, float, float]:
    """(gas force [N], acceleration [m/s^2], reaction of a hard seat holding it at rest [N], gas and spring force
    [N]) of the dynamic body at (t, y) in the loaded discrete state (:func:`exchange.compiled_point.point_body`)."""
    out = np.empty(4)
    _check(fast, point_body(fast.model, float(t), np.ascontiguousarray(y, dtype=float), out), t)
    return float(out[0]), float(out[1]), float(out[2]), float(out[3])
