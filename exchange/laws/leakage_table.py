"""Tabulated leakage (Abaqus *FLUID EXCHANGE PROPERTY, TYPE=MASS RATE LEAKAGE / VOLUME RATE LEAKAGE).

A table gives the flow per unit area, mass [kg/(s m^2)] or volume [m^3/(s m^2)], against the absolute pressure
difference |Δp| [Pa]. It is validated once, when built, and then evaluated cheaply inside the cavity ODE.

Abaqus data lines list the flow first and |Δp| second, and "the first tabular value entered must always be zero"
for both (Abaqus Scripting Reference, FluidExchangeProperty, MASS_RATE_LEAK / VOL_RATE_LEAK). Use
:meth:`LeakageTable.from_abaqus_rows` for rows in that order.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import IntEnum

import numpy as np
from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, KinkVariable, StateColumn, TableColumn, side

from .spec import LawKey, LawSpec

__all__ = ["CONSTANT", "LINEAR", "MASS", "VOLUME", "LeakageTable", "leakage_table_mass_flow", "leakage_flow_per_area",
           "tabulated_leakage_mass_flow", "LeakageTableLaw", "leakage_table_kernel", "LAW"]

MASS = "mass"
"""Table kind: mass flow per unit area [kg/(s m^2)]."""
VOLUME = "volume"
"""Table kind: volume flow per unit area [m^3/(s m^2)], converted to mass with the upstream density."""
LINEAR = "linear"
"""Beyond the last row: continue the last segment's straight line (clamped at zero flow)."""
CONSTANT = "constant"
"""Beyond the last row: hold the last flow value."""

_KINDS = (MASS, VOLUME)
_EXTRAPOLATIONS = (LINEAR, CONSTANT)
_MIN_ROWS = 2


@dataclass(frozen=True)
class LeakageTable:
    """Validated flow-per-unit-area table against |Δp|; build once, evaluate many times.

    Parameters
    ----------
    dp : sequence of float, (n,)
        Absolute pressure differences |Δp| [Pa]: first 0, strictly increasing, finite.
    flow : sequence of float, (n,)
        Flow per unit area at each |Δp|: first 0, every value finite and >= 0;
        [kg/(s m^2)] for ``kind="mass"``, [m^3/(s m^2)] for ``kind="volume"``.
    kind : {"mass", "volume"}
        Abaqus MASS RATE LEAKAGE or VOLUME RATE LEAKAGE.
    extrapolation : {"linear", "constant"}
        Rule beyond the last row. Abaqus's rule for this table could not be confirmed, so the default is linear
        extrapolation of the last segment, clamped at zero flow (a falling last segment never yields a negative
        flow). "constant" holds the last value (the Abaqus convention for material property tables).

    Raises
    ------
    ValueError
        Naming the row (numbered from 1) and what was expected, for a first row other than (0, 0), a |Δp| not
        strictly increasing, a negative or non-finite entry, mismatched lengths, fewer than 2 rows, or an
        unknown ``kind`` / ``extrapolation``.

    Examples
    --------
    >>> t = LeakageTable(dp=(0.0, 1000.0, 3000.0), flow=(0.0, 2.0, 3.0))
    >>> t.flow_per_area(500.0), t.flow_per_area(2000.0), t.flow_per_area(5000.0)
    (1.0, 2.5, 4.0)
    >>> LeakageTable(dp=(0.0, 1000.0, 1000.0), flow=(0.0, 2.0, 3.0))
    Traceback (most recent call last):
    ...
    ValueError: leakage table row 3: |dp| must be strictly greater than row 2's 1000.0 Pa, got 1000.0 Pa
    """

    dp: tuple[float, ...]
    flow: tuple[float, ...]
    kind: str = MASS
    extrapolation: str = LINEAR
    rows: tuple = field(init=False, repr=False, compare=False)  # (dp (n,), flow (n,)) arrays for the kernels

    def __post_init__(self) -> None:
        dp = tuple(float(x) for x in self.dp)
        flow = tuple(float(x) for x in self.flow)
        _check_options(self.kind, self.extrapolation)
        _check_rows(dp, flow)
        object.__setattr__(self, "dp", dp)
        object.__setattr__(self, "flow", flow)
        object.__setattr__(self, "rows", (np.array(dp), np.array(flow)))

    @classmethod
    def from_rows(cls, rows, kind: str = MASS, extrapolation: str = LINEAR) -> LeakageTable:
        """Build from ``(|Δp| [Pa], flow per area)`` pairs.

        >>> LeakageTable.from_rows([(0, 0), (100, 1e-3)]).flow_per_area(50.0)
        0.0005
        """
        rows = [tuple(r) for r in rows]
        _check_pairs(rows)
        return cls(tuple(r[0] for r in rows), tuple(r[1] for r in rows), kind, extrapolation)

    @classmethod
    def from_abaqus_rows(cls, rows, kind: str = MASS, extrapolation: str = LINEAR) -> LeakageTable:
        """Build from Abaqus data-line order ``(flow per area, |Δp| [Pa])``.

        >>> LeakageTable.from_abaqus_rows([(0, 0), (1e-3, 100)]).dp
        (0.0, 100.0)
        """
        rows = [tuple(r) for r in rows]
        _check_pairs(rows)
        return cls(tuple(r[1] for r in rows), tuple(r[0] for r in rows), kind, extrapolation)

    def flow_per_area(self, dp):
        r"""Flow per unit area at pressure difference ``dp`` [kg/(s m^2)] or [m^3/(s m^2)]:
        :func:`leakage_flow_per_area` on this table's rows (a float, or a numpy array element by element)."""
        hold = self.extrapolation == CONSTANT
        if isinstance(dp, np.ndarray):
            return _flow_per_area_each(np.ascontiguousarray(dp, dtype=float).ravel(), *self.rows, hold) \
                .reshape(dp.shape)
        return leakage_flow_per_area(float(dp), *self.rows, hold)


@njit(cache=True)
def leakage_flow_per_area(dp, dps, flows, hold_last):
    r"""Flow per unit area of a leakage table at pressure difference ``dp`` [kg/(s m^2)] or [m^3/(s m^2)].

    .. math::

        f(\Delta p) = \max\Big(f_i + \frac{f_{i+1} - f_i}{\Delta p_{i+1} - \Delta p_i}(\Delta p - \Delta p_i),\;
        0\Big), \qquad \Delta p_i \le \Delta p < \Delta p_{i+1}

    Linear interpolation between rows; beyond the last row the last segment continued (clamped at zero flow), or
    the last value held when ``hold_last``. One-directional: ``dp <= 0`` (and NaN) gives 0 (the caller swaps
    upstream and downstream for reverse flow). Continuous at dp = 0 because the first row is (0, 0).

    Parameters
    ----------
    dp : float
        p_up − p_down [Pa].
    dps, flows : (n,) float
        The rows of a validated :class:`LeakageTable` (``table.rows``): |Δp| [Pa], first 0 and strictly
        increasing, and the flow per area at each, first 0 and >= 0.
    hold_last : bool
        Extrapolation "constant" (True) or "linear" (False).

    References
    ----------
    Abaqus Keywords Reference, *FLUID EXCHANGE PROPERTY, TYPE=MASS RATE LEAKAGE / VOLUME RATE LEAKAGE.

    Examples
    --------
    >>> import numpy as np
    >>> dps, flows = np.array([0.0, 1000.0, 3000.0]), np.array([0.0, 2.0, 3.0])
    >>> leakage_flow_per_area(2000.0, dps, flows, False), leakage_flow_per_area(5000.0, dps, flows, False)
    (2.5, 4.0)
    >>> leakage_flow_per_area(5000.0, dps, flows, True), leakage_flow_per_area(-1.0, dps, flows, True)
    (3.0, 0.0)
    """
    if not dp > 0.0:  # also maps NaN to 0 instead of propagating it silently into an ODE
        return 0.0
    last = dps.size - 1
    i = np.searchsorted(dps, dp, side="right") - 1
    if i >= last:
        if hold_last:
            return flows[last]
        i = last - 1
    slope = (flows[i + 1] - flows[i]) / (dps[i + 1] - dps[i])
    return max(flows[i] + slope * (dp - dps[i]), 0.0)


@njit(cache=True)
def _flow_per_area_each(dp, dps, flows, hold_last):
    out = np.empty(dp.size)
    for k in range(dp.size):
        out[k] = leakage_flow_per_area(dp[k], dps, flows, hold_last)
    return out


@njit(cache=True)
def tabulated_leakage_mass_flow(dp, area, rho_up, dps, flows, hold_last, volume):
    r"""Mass flow through a tabulated leakage surface [kg/s].

    .. math::

        \dot m = A\, f(\Delta p) \quad \text{(MASS RATE LEAKAGE)}, \qquad
        \dot m = \rho_e\, A\, f(\Delta p) \quad \text{(VOLUME RATE LEAKAGE)}

    with f of :func:`leakage_flow_per_area`.

    Parameters
    ----------
    dp : float
        p_up − p_down [Pa]; ``dp <= 0`` gives 0.
    area : float
        Leakage area A [m^2], >= 0.
    rho_up : float
        Upstream gas density ρ_e [kg/m^3] (used by a volume table only).
    dps, flows, hold_last
        The table, as :func:`leakage_flow_per_area`.
    volume : bool
        The flows are volume flows per area [m^3/(s m^2)] (VOLUME RATE LEAKAGE), else mass flows [kg/(s m^2)].

    Notes
    -----
    Abaqus states that the flow is driven by the absolute value of the pressure difference. Which density converts
    Abaqus's volume rate to mass rate is not stated in what we could read; the upstream density (the gas that
    actually leaves) is our choice.

    Examples
    --------
    >>> import numpy as np
    >>> dps, flows = np.array([0.0, 1.0e4]), np.array([0.0, 0.5])
    >>> round(tabulated_leakage_mass_flow(5.0e3, 0.02, 1.2, dps, flows, False, True), 12)
    0.006
    """
    q = leakage_flow_per_area(dp, dps, flows, hold_last)
    if volume:
        return rho_up * area * q
    return area * q


def leakage_table_mass_flow(table: LeakageTable, dp: float, area: float, rho_up=None) -> float:
    r"""Mass flow through a tabulated leakage surface [kg/s]: :func:`tabulated_leakage_mass_flow` on a
    :class:`LeakageTable`.

    Parameters
    ----------
    table : LeakageTable
        Validated flow-per-area table.
    dp : float
        p_up − p_down [Pa]; ``dp <= 0`` gives 0 (one-directional: the caller swaps the cavities for reverse flow).
    area : float
        Leakage area A [m^2], >= 0.
    rho_up : float, optional
        Upstream gas density ρ_e [kg/m^3]; required for a volume table.

    Examples
    --------
    >>> t = LeakageTable.from_rows([(0.0, 0.0), (1.0e4, 0.5)], kind="volume")
    >>> round(leakage_table_mass_flow(t, 5.0e3, 0.02, rho_up=1.2), 12)
    0.006
    """
    volume = table.kind == VOLUME
    if volume and rho_up is None:
        raise ValueError("a VOLUME RATE LEAKAGE table needs the upstream density rho_up [kg/m^3]")
    return tabulated_leakage_mass_flow(float(dp), float(area), float(rho_up) if volume else 0.0, *table.rows,
                                       table.extrapolation == CONSTANT, volume)


def _check_options(kind: str, extrapolation: str) -> None:
    if kind not in _KINDS:
        raise ValueError(f"leakage table kind must be one of {_KINDS}, got {kind!r}")
    if extrapolation not in _EXTRAPOLATIONS:
        raise ValueError(f"leakage table extrapolation must be one of {_EXTRAPOLATIONS}, got {extrapolation!r}")


def _check_pairs(rows) -> None:
    for n, r in enumerate(rows, start=1):
        if len(r) != 2:
            raise ValueError(f"leakage table row {n}: expected 2 values, got {len(r)}: {r!r}")


def _check_rows(dp: tuple[float, ...], flow: tuple[float, ...]) -> None:
    if len(dp) != len(flow):
        raise ValueError(f"leakage table: {len(dp)} |dp| values but {len(flow)} flow values")
    if len(dp) < _MIN_ROWS:
        raise ValueError(f"leakage table needs at least {_MIN_ROWS} rows (the first is (0, 0)), got {len(dp)}")
    for n, (x, y) in enumerate(zip(dp, flow), start=1):
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(f"leakage table row {n}: values must be finite, got ({x}, {y})")
    if dp[0] != 0.0 or flow[0] != 0.0:
        raise ValueError(f"leakage table row 1 must be (0, 0) (zero flow at zero |dp|), got ({dp[0]}, {flow[0]})")
    for n in range(1, len(dp)):
        if not dp[n] > dp[n - 1]:
            raise ValueError(f"leakage table row {n + 1}: |dp| must be strictly greater than row {n}'s "
                             f"{dp[n - 1]} Pa, got {dp[n]} Pa")
        if flow[n] < 0.0:
            raise ValueError(f"leakage table row {n + 1}: flow per area must be >= 0, got {flow[n]}")


@dataclass(frozen=True)
class LeakageTableLaw:
    """Abaqus MASS RATE LEAKAGE / VOLUME RATE LEAKAGE: :func:`leakage_table_mass_flow`."""

    table: LeakageTable
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        return leakage_table_mass_flow(self.table, up.p - p_down, area, up.rho)


class LeakageFloat(IntEnum):
    VOLUME = 0  # 1: a volume rate (times the upstream density)
    HOLD_LAST = 1  # 1: the last row held beyond the table


class LeakageInt(IntEnum):
    ROWS = 0  # the table's rows (|Δp|, flow per area)


@njit(LAW_SIGNATURE, cache=True)
def leakage_table_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's tabulated leakage from side u [kg/s]: :func:`tabulated_leakage_mass_flow` on the lowered rows."""
    k = li[LeakageInt.ROWS]
    s, n = ti[k, TableColumn.START], ti[k, TableColumn.ROWS]
    return tabulated_leakage_mass_flow(side(st, amb, u, StateColumn.P) - p_down, area,
                                       side(st, amb, u, StateColumn.RHO), tx[s:s + n], ty[s:s + n],
                                       lf[LeakageFloat.HOLD_LAST] == 1.0, lf[LeakageFloat.VOLUME] == 1.0)


def _build(name, values, read_table) -> LeakageTableLaw:
    t = read_table("leakage_table", "leakage")
    kind = MASS if name == "mass_rate_leakage" else VOLUME
    return LeakageTableLaw(LeakageTable(t.x, t.y, kind, values["leakage_table_extrapolation"]))


def _lower(law, tables) -> tuple:
    table = law.table
    return ((float(table.kind == VOLUME), float(table.extrapolation == CONSTANT)),
            (tables.add_arrays(*table.rows),))


def _kinks(law) -> tuple:
    """Rows of the table after the first (|Δp| = 0, where the one-way switch or the flow's sign change already
    stops)."""
    return tuple((KinkVariable.PRESSURE_DIFFERENCE, dp, r) for r, dp in enumerate(law.table.dp[1:], start=1))


LAW = LawSpec(names=("mass_rate_leakage", "volume_rate_leakage"), law=LeakageTableLaw, kernel=leakage_table_kernel,
              keys=(LawKey("leakage_table", "mass_rate_leakage / volume_rate_leakage: CSV (|Δp| [Pa], flow per area "
                           "[kg/(s m^2)] or [m^3/(s m^2)]); first row 0, 0", default="", kind="file"),
                    LawKey("leakage_table_extrapolation", "beyond the last row", default="linear",
                           choices=("linear", "constant"))),
              required={"mass_rate_leakage": ("leakage_table",), "volume_rate_leakage": ("leakage_table",)},
              build=_build, lower=_lower, kinks=_kinks)
