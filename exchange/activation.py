"""When an exchange flows, and how much of its area: time window, pop pressure with hold time, amplitude.

Abaqus *FLUID EXCHANGE ACTIVATION (amplitude, DELTA LEAKAGE AREA), Radioss vents (open at Tstart or once
p > p_ext + ΔPdef has held for ΔtPdef; close at Tstop), LS-DYNA PPOP (opens at a gauge pressure, stays open).
The discrete part (armed → holding → open) lives in the network; this module holds the definition and the pure
area rule.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Activation", "activated_area", "arm_pop_vents"]


@dataclass(frozen=True)
class Activation:
    """Activation of one exchange.

    Attributes
    ----------
    open_time : float
        Time before which the exchange is closed [s].
    close_time : float
        Time from which it is closed again [s] (inf: never).
    pop_pressure : float or None
        Gauge pressure difference p_from − p_to [Pa] that opens it (None: no pop condition; it is open from
        ``open_time``). Once open it stays open.
    hold_time : float
        How long the pressure difference must stay above ``pop_pressure`` before it opens [s].
    amplitude : cavity.tables.Table or None
        Multiplier on the area against time [-].
    delta_area : bool
        Use the current leakage area minus the area at activation (Abaqus DELTA LEAKAGE AREA).
    """

    open_time: float = 0.0
    close_time: float = math.inf
    pop_pressure: float | None = None
    hold_time: float = 0.0
    amplitude: object = None
    delta_area: bool = False

    @property
    def breakpoints(self) -> tuple:
        pts = [self.open_time] + ([self.close_time] if math.isfinite(self.close_time) else [])
        if self.amplitude is not None:
            pts += list(self.amplitude.breakpoints)
        return tuple(pts)


def activated_area(area: float, t: float, activation: Activation | None, popped: bool,
                   area_at_activation: float = 0.0) -> float:
    r"""Flow area of an exchange after activation [m^2].

    .. math:: A_{flow} = a(t)\,\big(A - A_{act}\big) \text{ if open, else } 0

    with :math:`a(t)` the amplitude and :math:`A_{act}` the area at activation when DELTA LEAKAGE AREA is set
    (clipped at zero).

    Parameters
    ----------
    area : float
        Current (leakage) area [m^2].
    t : float
        Time [s].
    activation : Activation or None
        None: always open, full area.
    popped : bool
        Whether the pop condition has been met (ignored without a pop pressure).
    area_at_activation : float
        Area when the exchange opened [m^2] (used with ``delta_area``).

    Examples
    --------
    >>> activated_area(2.0, 0.5, Activation(open_time=1.0), popped=False)
    0.0
    >>> activated_area(2.0, 1.5, Activation(open_time=1.0, close_time=2.0), popped=False)
    2.0
    >>> activated_area(2.0, 0.1, Activation(pop_pressure=5e4), popped=True)
    2.0
    """
    if activation is None:
        return area
    if not (activation.open_time <= t < activation.close_time):
        return 0.0
    if activation.pop_pressure is not None and not popped:
        return 0.0
    a = activation.amplitude(t) if activation.amplitude is not None else 1.0
    if activation.delta_area:
        area = max(area - area_at_activation, 0.0)
    return a * area


def arm_pop_vents(net, t: float, y) -> list:
    """:meth:`Network.arm`: at the start of a run, every pop vent already above its pop pressure starts its hold (or opens) now,
    as if its pressure had just crossed it; returns the labels of these pops (for the event log)."""
    labels = []
    for j, ex in enumerate(net.exchanges):
        act = ex.activation
        if act is None or act.pop_pressure is None or net.popped[j] or net.holding_since[j] is not None:
            continue
        if net._pop_switch(t, y, j) > 0.0:
            net.on_event(t, y, f"{ex.name}:pop")
            labels.append(f"{ex.name}:pop")
    return labels
