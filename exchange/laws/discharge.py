"""Discharge coefficient: a constant, or a validated table against pressure [Pa] or time [s].

Abaqus tabulates the discharge coefficient of TYPE=ORIFICE and TYPE=FABRIC LEAKAGE "as a function of pressure,
temperature, and other predefined field variables" (Abaqus Keywords Reference, *FLUID EXCHANGE PROPERTY); LS-DYNA
gives the vent and leakage orifice coefficients against time (*AIRBAG_WANG_NEFSKE LCC23, LCCP23). Temperature and
field-variable dependence is not supported here.

Beyond the ends of a table the coefficient is held at the end value (clamped). This is the Abaqus convention for
tabulated data ("constant outside the range of the independent variables", Abaqus "Material data definition");
that it applies to this table too is our assumption.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import IntEnum

import numpy as np
from numba import njit

from cavity.tables import Table
from exchange.engine.layout import StateColumn, side
from exchange.engine.tables import table_value

from .spec import LawKey

__all__ = ["PRESSURE", "TIME", "DischargeTable", "discharge_coefficient", "DischargeFloat", "DischargeInt",
           "lowered_cd", "cd_value", "cd_breakpoints", "cd_of_values", "pressure_kinks", "CD_KEYS", "lowers_cd"]

PRESSURE = "pressure"
"""Table abscissa: absolute pressure [Pa] (the upstream cavity pressure, by our convention)."""
TIME = "time"
"""Table abscissa: time [s]."""

_VARIABLES = (PRESSURE, TIME)
_UNITS = {PRESSURE: "Pa", TIME: "s"}


@dataclass(frozen=True)
class DischargeTable:
    """Validated discharge-coefficient table, linear between rows and clamped beyond the ends.

    Parameters
    ----------
    x : sequence of float, (n,)
        Abscissa, strictly increasing and finite: absolute pressure [Pa] or time [s], per ``variable``.
    cd : sequence of float, (n,)
        Discharge coefficient at each abscissa [-], finite and >= 0. Values above 1 are accepted: for fabric a
        "discharge coefficient" often lumps an open-area fraction too.
    variable : {"pressure", "time"}
        What ``x`` is.

    Raises
    ------
    ValueError
        Naming the row (numbered from 1) and what was expected.

    Examples
    --------
    >>> t = DischargeTable(x=(1.0e5, 2.0e5), cd=(0.6, 0.8))
    >>> t(1.5e5), t(0.5e5), t(3.0e5)
    (0.7, 0.6, 0.8)
    >>> DischargeTable(x=(0.0, 1.0), cd=(0.6, -0.1), variable="time")
    Traceback (most recent call last):
    ...
    ValueError: discharge table row 2: Cd must be >= 0, got -0.1
    """

    x: tuple[float, ...]
    cd: tuple[float, ...]
    variable: str = PRESSURE
    table: Table = field(init=False, repr=False, compare=False)  # the interpolation (the compiled path lowers it)

    def __post_init__(self) -> None:
        x = tuple(float(v) for v in self.x)
        cd = tuple(float(v) for v in self.cd)
        _check_table(x, cd, self.variable)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "cd", cd)
        object.__setattr__(self, "table", Table(x, cd, f"discharge coefficient against {self.variable}"))

    def __call__(self, value):
        """Cd at ``value`` (pressure [Pa] or time [s]); float or numpy array."""
        if isinstance(value, np.ndarray):
            return np.interp(value, self.x, self.cd)
        return self.table(value)


def discharge_coefficient(cd, pressure=None, time=None):
    """Evaluate a discharge coefficient given as a constant or a :class:`DischargeTable` [-].

    Parameters
    ----------
    cd : float or DischargeTable
        Constant coefficient, or a table against pressure or time.
    pressure : float, optional
        Absolute pressure [Pa]; required by a pressure table.
    time : float, optional
        Time [s]; required by a time table.

    Examples
    --------
    >>> discharge_coefficient(0.62)
    0.62
    >>> round(discharge_coefficient(DischargeTable((0.0, 0.01), (0.0, 0.7), "time"), time=0.005), 12)
    0.35
    """
    if not isinstance(cd, DischargeTable):
        return cd
    value = pressure if cd.variable == PRESSURE else time
    if value is None:
        raise ValueError(f"this discharge table is a function of {cd.variable}: pass {cd.variable}=...")
    return cd(value)


def _check_table(x: tuple[float, ...], cd: tuple[float, ...], variable: str) -> None:
    if variable not in _VARIABLES:
        raise ValueError(f"discharge table variable must be one of {_VARIABLES}, got {variable!r}")
    if len(x) != len(cd):
        raise ValueError(f"discharge table: {len(x)} {variable} values but {len(cd)} Cd values")
    if not x:
        raise ValueError("discharge table needs at least one row")
    unit = _UNITS[variable]
    for n, (a, b) in enumerate(zip(x, cd), start=1):
        if not (math.isfinite(a) and math.isfinite(b)):
            raise ValueError(f"discharge table row {n}: values must be finite, got ({a}, {b})")
        if b < 0.0:
            raise ValueError(f"discharge table row {n}: Cd must be >= 0, got {b}")
        if n > 1 and not a > x[n - 2]:
            raise ValueError(f"discharge table row {n}: {variable} must be strictly greater than row {n - 1}'s "
                             f"{x[n - 2]} {unit}, got {a} {unit}")


class DischargeFloat(IntEnum):
    """``law_float`` entries of a law with a discharge coefficient (its own follow)."""
    CD = 0  # a constant Cd [-] (0 with a table)


class DischargeInt(IntEnum):
    """``law_int`` entries of a law with a discharge coefficient."""
    TABLE = 0  # its table, −1: the constant
    OF_TIME = 1  # 1: the table's abscissa is time, 0: the upstream pressure


#: The scene keys of a discharge coefficient (orifice, fabric leakage).
CD_KEYS = (LawKey("discharge_coefficient", "orifice, fabric_leakage: Cd, a number or a CSV table of "
                  "`discharge_coefficient_of`", default=1.0, kind="cd"),
           LawKey("discharge_coefficient_of", "abscissa of a Cd table: upstream pressure [Pa] or time [s]",
                  default="pressure", choices=("pressure", "time")))


def cd_of_values(values: dict):
    """The discharge coefficient of a scene's exchange: its number, or its CSV table as a DischargeTable."""
    cd = values["discharge_coefficient"]
    return cd if isinstance(cd, float) else DischargeTable(cd.x, cd.y, values["discharge_coefficient_of"])


def cd_breakpoints(cd) -> tuple:
    """Times where a Cd table of time kinks [s] (the integrator stops there); none otherwise."""
    return tuple(cd.x) if isinstance(cd, DischargeTable) and cd.variable != PRESSURE else ()


def lowers_cd(cd) -> bool:
    """A Cd the engine evaluates (a number or a DischargeTable); anything else makes its law hosted."""
    return isinstance(cd, (int, float, DischargeTable))


def lowered_cd(cd, tables) -> tuple:
    """((Cd,), (table, of time)) of a constant or a :class:`DischargeTable` (its rows added to ``tables``)."""
    if isinstance(cd, DischargeTable):
        return (0.0,), (tables.add(cd.table), int(cd.variable != PRESSURE))
    return (float(cd),), (-1, 0)


@njit(cache=True)
def cd_value(lf, li, tx, ty, ti, st, amb, u, t):
    """Discharge coefficient [-] of a lowered law with side u upstream: the constant, or its table at the upstream
    pressure or at t (:func:`discharge_coefficient`)."""
    k = li[DischargeInt.TABLE]
    if k < 0:
        return lf[DischargeFloat.CD]
    return table_value(tx, ty, ti, k, t if li[DischargeInt.OF_TIME] == 1 else side(st, amb, u, StateColumn.P))


def pressure_kinks(cd) -> tuple:
    """Rows of a Cd table of pressure, where the law kinks in the state: ((UPSTREAM_PRESSURE, x, row), ...)
    (none for a constant, a table of time or a single row)."""
    from exchange.engine.layout import KinkVariable

    if not isinstance(cd, DischargeTable) or cd.variable != PRESSURE or len(cd.x) < 2:
        return ()
    return tuple((KinkVariable.UPSTREAM_PRESSURE, x, r) for r, x in enumerate(cd.x))
