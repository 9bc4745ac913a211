"""Switches where a tabulated law kinks in the state: rows of a discharge-coefficient table of pressure, rows of a
leakage table of |Δp|.

A kink the integrator does not stop at is straddled by a step whose error estimate may miss it (the estimate
assumes a smooth right-hand side); a switch there ends the step at the kink, as the orifice join does. The
compiled engine watches them (kinds 11 and 12, :func:`exchange.compiled_sources.kink_value`).
"""
from __future__ import annotations

__all__ = ["pressure_kinks", "dp_kinks"]


def pressure_kinks(law) -> tuple:
    """Upstream pressures [Pa] where a law's discharge-coefficient table of pressure kinks (its rows; none for a
    constant Cd, a table of time or a single row)."""
    cd = getattr(law, "discharge_coefficient", None)
    x = getattr(cd, "x", ())
    return tuple(x) if getattr(cd, "variable", None) == "pressure" and len(x) > 1 else ()


def dp_kinks(law) -> tuple:
    """Pressure differences |Δp| [Pa] where a leakage table's law kinks: its rows after the first (Δp = 0, where
    the one-way switch or the flow's sign change already stops)."""
    table = getattr(law, "table", None)
    return tuple(table.dp[1:]) if table is not None and hasattr(table, "dp") else ()

