"""Switches where a tabulated law kinks in the state: rows of a discharge-coefficient table of pressure, rows of a
leakage table of |Δp|.

A kink the integrator does not stop at is straddled by a step whose error estimate may miss it (the estimate
assumes a smooth right-hand side); a switch there ends the step at the kink, as the orifice join does
(:meth:`exchange.network.Network.events`). The compiled path watches the same switches (kinds 11 and 12 of
:func:`exchange.compiled_rhs.switch_value`).
"""
from __future__ import annotations

__all__ = ["pressure_kinks", "dp_kinks", "kink_switches"]


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


def _labelled(func, label):
    func.label = label
    return func


def kink_switches(net, j: int) -> list:
    """Switch functions of exchange j's kinks, labelled ``name:kink<row>`` (each label names one switch: the
    integrator tells them apart by it): (max(p_a, p_b) − x)/x at each Cd row x, (|p_a − p_b| − d)/d at each
    leakage row d."""
    ex, out = net.exchanges[j], []

    def upstream(t, y):
        return max(net._pressures(t, y, j)[1:])

    def difference(t, y):
        _, pa, pb = net._pressures(t, y, j)
        return abs(pa - pb)

    for r, x in enumerate(pressure_kinks(ex.law)):
        out.append(_labelled(lambda t, y, x=x: (upstream(t, y) - x) / x, f"{ex.name}:kink{r}"))
    for r, d in enumerate(dp_kinks(ex.law), start=1):
        out.append(_labelled(lambda t, y, d=d: (difference(t, y) - d) / d, f"{ex.name}:kink{r}"))
    return out
