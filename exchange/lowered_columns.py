"""The law-, activation- and liquid-specific columns of the arrays :func:`exchange.compiled.lower` builds (layout:
:mod:`exchange.compiled_rhs`): each law's parameters and tables, a DELTA LEAKAGE AREA's base area, a hydraulic
cavity's liquid data, and the concatenated tables they index.
"""
from __future__ import annotations

import numpy as np

from .discharge import PRESSURE, DischargeTable

__all__ = ["Tables", "spline_entry", "law_parameters", "law_tables", "area_at_activation", "liquid", "UNLOCKED",
           "KNOT_SLACK"]

#: ``ci[i, 9]`` of a cavity whose volume spline is evaluated on the piece holding x (no piece held:
#: :func:`exchange.compiled_tables.spline_piece_value`).
UNLOCKED = -2
#: At a segment start the piece of a volume spline of the dynamic body's displacement is the one holding s nudged
#: by this fraction of the spline's span along the body's motion (after a knot switch s lies on the knot, to
#: round-off; :func:`exchange.compiled_modes.lock_pieces`).
KNOT_SLACK = 1e-9


def law_parameters(law) -> tuple:
    """(Cd, parameter 1, parameter 2) of a law for ``ef[:, (1, 6, 7)]`` (a Cd table: Cd 0, see
    :func:`law_tables`)."""
    name = type(law).__name__
    if name == "GraefeLaw":
        return 1.0, law.flc, law.fac
    if name == "LinearResistanceLaw":
        return 1.0, law.conductance, 0.0
    if name == "LeakageTableLaw":
        return 1.0, float(law.table.kind == "volume"), float(law.table.extrapolation == "constant")
    if name == "FluxLaw":
        return 1.0, law.flux, float(law.kind == "volume")
    if name == "BulkViscosityLaw":
        return 1.0, law.viscous, law.hydrodynamic
    cd = law.discharge_coefficient
    return (0.0 if isinstance(cd, DischargeTable) else float(cd)), getattr(law, "open_fraction", 1.0), 0.0


def law_tables(law, tables) -> tuple:
    """(law table, Cd table, Cd variable) of a law for ``ei[:, 11:14]``: the leakage table's rows or the flux
    amplitude (−1: none), the discharge-coefficient table (−1: a constant) and its abscissa (0 the upstream
    pressure, 1 time)."""
    name, law_table, cd_table, variable = type(law).__name__, -1, -1, 0
    if name == "LeakageTableLaw":
        law_table = tables.add_arrays(*law.table.rows)
    elif name == "FluxLaw" and law.amplitude is not None:
        law_table = tables.add(law.amplitude)
    cd = getattr(law, "discharge_coefficient", None)
    if isinstance(cd, DischargeTable):
        cd_table, variable = tables.add(cd.table), int(cd.variable != PRESSURE)
    return law_table, cd_table, variable


def area_at_activation(net, j) -> float:
    """``ef[j, 9]``: the base area [m^2] a DELTA LEAKAGE AREA subtracts, known in advance for an exchange opened by
    time (the area at its open time); a pop vent's is set when it pops
    (:func:`exchange.compiled_modes.on_event`)."""
    act = net.exchanges[j].activation
    if act is None or not act.delta_area or act.pop_pressure is not None:
        return 0.0
    return float(net.base_area(j, act.open_time))


def liquid(cav) -> tuple:
    """``cf[i, 6:11]`` of a hydraulic cavity (zeros for a gas): reference density [kg/m^3], bulk modulus [Pa],
    reference pressure [Pa], reference temperature [K], thermal expansion [1/K]."""
    if getattr(cav, "kind", "gas") != "hydraulic":
        return (0.0,) * 5
    return (cav.reference_density, cav.bulk_modulus, cav.reference_pressure, cav.reference_temperature,
            cav.thermal_expansion)


class Tables:
    """The tables of a lowered network, concatenated: ``tx``, ``ty`` and ``ti`` (:mod:`exchange.compiled_rhs`)."""

    def __init__(self):
        self.x, self.y, self.index, self.size = [], [], [], 0

    def add(self, table) -> int:
        x, y = np.asarray(table.x, dtype=float).ravel(), np.asarray(table.y, dtype=float).ravel()
        self.index.append((self.size, len(x), 1 if table.extrapolation == "linear" else 0))
        self.x.append(x)
        self.y.append(y)
        self.size += len(x)
        return len(self.index) - 1

    def add_arrays(self, x, y) -> int:
        """A raw entry (x and y of equal length), e.g. the steps of an area or the knots of a spline."""
        return self.add(type("T", (), {"x": x, "y": y, "extrapolation": "constant"})())

    def arrays(self):
        if not self.index:
            self.add(type("T", (), {"x": (0.0,), "y": (0.0,), "extrapolation": "constant"})())
        return (np.concatenate(self.x), np.concatenate(self.y), np.array(self.index, dtype=np.int64).reshape(-1, 3))


def spline_entry(tables, knots, coefficients) -> int:
    """Knots (table k, their values unused) and coefficients (table k + 1, 4 per piece) of a cubic spline."""
    knots = np.asarray(knots, dtype=float)
    k = tables.add_arrays(knots, np.zeros(len(knots)))
    flat = np.asarray(coefficients, dtype=float).T.ravel()
    tables.add_arrays(np.zeros(len(flat)), flat)
    return k
