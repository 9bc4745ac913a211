"""The switch table of a lowered network: every switch function the compiled engine may watch (kinds of
:mod:`exchange.compiled_modes`), the exchange, cavity or seat kink each one reads, and its label."""
from __future__ import annotations

import numpy as np

from .law_kinks import dp_kinks, pressure_kinks

__all__ = ["switch_table"]


def switch_table(net, geometry):
    """Switch kinds (0 choke, 7 orifice join, 1 one-way reversal, 2/3 equalise/release, 11/12 a law's kink,
    4 pop, 5 pop-drop, 6 pop-hold, 8/9 the dynamic body's displacement reaching the crossing above/below its area
    interval, 10 its turning point, 15/16 the knot above/below the piece of the volume spline it holds, 13 its seat,
    14 a kink of the seat's force, 17 the downstream cavity reaching the close pressure), their exchanges (a law's kink: j + ne·(row + 1); a knot: the pushed cavity;
    the seat's kink: its index) and labels (each watched only in its discrete state:
    :func:`exchange.compiled_modes.watched`)."""
    kinds, js, labels = [], [], []

    def add(kind, j, what):
        kinds.append(kind)
        js.append(j)
        labels.append(f"{net.exchanges[j].name}:{what}")

    for j, ex in enumerate(net.exchanges):
        driven = not ex.law.prescribed  # a prescribed flux has no pressure-driven switch
        if ex.law.pneumatic and driven:
            add(0, j, "choke")
        if getattr(ex.law, "orifice_join", False) and driven:
            add(7, j, "join")
        if driven and ex.downstream is None and not ex.two_way:
            add(1, j, "reversal")
        elif driven and net.can_equalise(j):
            add(2, j, "equalise")
            add(3, j, "release")
        if driven:  # a law's kinks: row k of its Cd table of pressure (11) or leakage table (12), j + ne·(k + 1)
            for kind, rows in ((11, pressure_kinks(ex.law)), (12, dp_kinks(ex.law))):
                for k in range(len(rows)):
                    r = k + (1 if kind == 12 else 0)  # the row of the table
                    add(kind, j, f"kink{r}")
                    js[-1] = j + len(net.exchanges) * (r + 1)
        if ex.activation is not None and ex.activation.pop_pressure is not None:
            add(4, j, "pop")
            add(5, j, "pop-drop")
            add(6, j, "pop-hold")
        if ex.activation is not None and ex.activation.close_pressure is not None:
            add(17, j, "close")
    if geometry.get("body") is not None:  # the dynamic body's turning point, and its area crossings
        kinds.append(10)
        js.append(0)
        labels.append(f"{net.body.name}:turn")
        for j, area in geometry["areas"].items():
            if area[3]:
                add(9, j, "contact-down")
                add(8, j, "contact-up")
        _knot_switches(net, geometry, kinds, js, labels)
    seat = geometry.get("contact")
    if seat is not None:  # the seat switch of hard contact, then the kinks of the seat's force
        name = net.contact.name
        hard = int(seat[0][3]) == 0
        extra = [(13, 0, f"{name}:seat")] if hard else []
        extra += [(14, i, f"{name}:kink-{i}") for i in range(len(seat[2]))]
        for kind, j, label in extra:
            kinds.append(kind)
            js.append(j)
            labels.append(label)
    return np.array(kinds, dtype=np.int64), np.array(js, dtype=np.int64), labels


def _knot_switches(net, geometry, kinds, js, labels) -> None:
    """The knots below/above (16/15) the held piece of the pushed cavity's volume spline of the body's displacement."""
    pushed = int(geometry["body"][3])
    if pushed >= 0 and net.cavities[pushed].name in geometry["volumes"]:
        for kind, what in ((16, "knot-down"), (15, "knot-up")):
            kinds.append(kind)
            js.append(pushed)
            labels.append(f"{net.cavities[pushed].name}:{what}")
