"""The switch table of a lowered network: every switch the engine may watch, what it reads, and its label in the
event log (``<exchange>:<label>``, :data:`~exchange.engine.layout.SWITCH_LABELS`). Each switch is watched only in
its discrete state (:func:`exchange.engine.modes.watched`)."""
from __future__ import annotations

import numpy as np

from exchange.laws.registry import law_kinks

from .layout import SWITCH_LABELS, SwitchKind

__all__ = ["switch_table"]

K = SwitchKind


def switch_table(net, geometry) -> tuple:
    """(kinds, targets, labels, kink_int, kink_x) of a network with its geometry (:class:`exchange.engine.geometry.
    Geometry`): per exchange its
    choke, join, one-way reversal or equalise/release, its law's kinks (the registry's), pop, pop-drop, pop-hold and
    close switches; the dynamic body's turning point, area crossings and spline knots; the seat's switch and the
    kinks of its force."""
    kinds, targets, labels, kinks = [], [], [], []

    def add(kind, target, owner, label=None):
        kinds.append(int(kind))
        targets.append(int(target))
        labels.append(f"{owner}:{SWITCH_LABELS[kind] if label is None else label}")

    for j, ex in enumerate(net.exchanges):
        law, name = ex.law, ex.name
        driven = not law.prescribed  # a prescribed flux has no pressure-driven switch
        if driven and law.pneumatic:
            add(K.CHOKE, j, name)
        if driven and getattr(law, "join_below", 0.0) > 0.0:
            add(K.JOIN, j, name)
        if driven and ex.downstream is None and not ex.two_way:
            add(K.REVERSAL, j, name)
        elif driven and net.can_equalise(j):
            add(K.EQUALISE, j, name)
            add(K.RELEASE, j, name)
        for variable, x, row in law_kinks(law) if driven else ():
            add(K.LAW_KINK, len(kinks), name, f"kink{row}")
            kinks.append((j, int(variable), float(x)))
        act = ex.activation
        if act is not None and act.pop_pressure is not None:
            for kind in (K.POP, K.POP_DROP, K.POP_HOLD):
                add(kind, j, name)
        if act is not None and act.close_pressure is not None:
            add(K.CLOSE, j, name)
    if geometry.body is not None:  # the dynamic body's turning point, area crossings and spline knots
        add(K.TURN, 0, net.body.name)
        for j, area in geometry.areas.items():
            if area.by_body:
                add(K.CROSSING_DOWN, j, net.exchanges[j].name)
                add(K.CROSSING_UP, j, net.exchanges[j].name)
            if area.sampling is not None:
                add(K.SAMPLE, j, net.exchanges[j].name)
        pushed = geometry.body.pushed
        if pushed >= 0 and net.cavities[pushed].name in geometry.volumes:
            for kind in (K.KNOT_DOWN, K.KNOT_UP):
                add(kind, pushed, net.cavities[pushed].name)
    seat = geometry.seat
    if seat is not None:  # the seat switch of hard contact, then the kinks of the seat's force
        name = net.contact.name
        if seat.hard:
            add(K.SEAT, 0, name)
        for i in range(len(seat.kinks)):
            add(K.SEAT_KINK, i, name, f"kink-{i}")
    kink_int = np.array([(j, v) for j, v, _ in kinks], dtype=np.int64).reshape(-1, 2)
    kink_x = np.array([x for _, _, x in kinks], dtype=float)
    return np.array(kinds, dtype=np.int64), np.array(targets, dtype=np.int64), labels, kink_int, kink_x
