"""When an exchange flows, and how much of its area: time window, pop pressure with hold time, amplitude.

Abaqus *FLUID EXCHANGE ACTIVATION (amplitude, DELTA LEAKAGE AREA), Radioss vents (open at Tstart or once
p > p_ext + ΔPdef has held for ΔtPdef; close at Tstop), LS-DYNA PPOP (opens at a gauge pressure, stays open).
The discrete part (armed → holding → open) is the engine's (:mod:`exchange.engine.modes`); this module
holds the definition and the area rule, which the engine calls.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

__all__ = ["Activation", "activated_area"]


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
    close_pressure : float or None
        Absolute pressure of the downstream cavity [Pa] at which the exchange closes for good (a filling stopped at
        its target pressure; None: never).
    """

    open_time: float = 0.0
    close_time: float = math.inf
    pop_pressure: float | None = None
    hold_time: float = 0.0
    amplitude: object = None
    delta_area: bool = False
    close_pressure: float | None = None

    @property
    def breakpoints(self) -> tuple:
        pts = [self.open_time] + ([self.close_time] if math.isfinite(self.close_time) else [])
        if self.amplitude is not None:
            pts += list(self.amplitude.breakpoints)
        return tuple(pts)


@njit(cache=True, inline="always")
def activated_area(area, t, open_time, close_time, shut, amplitude, area_at_activation):
    r"""Flow area of an exchange after activation [m^2].

    .. math:: A_{flow} = a(t)\,\max\big(A - A_{act},\, 0\big) \quad \text{if } t_{open} \le t < t_{close}
              \text{ and not shut, else } 0

    with :math:`a(t)` the amplitude and :math:`A_{act}` the area when the exchange opened (Abaqus DELTA LEAKAGE
    AREA; 0 without it, when the clip changes nothing). A pop vent is shut until its pop condition has been met
    (Radioss ΔPdef held for ΔtPdef, LS-DYNA PPOP); it then stays open; an exchange with a close pressure is shut
    for good once its downstream cavity has reached it.

    Parameters
    ----------
    area : float
        Current (leakage) area [m^2].
    t : float
        Time [s].
    open_time, close_time : float
        The window [s] (−inf, inf: none).
    shut : bool
        A pop vent whose pop condition has not been met, or an exchange closed at its close pressure.
    amplitude : float
        a(t) [-] (1 without an amplitude table).
    area_at_activation : float
        A_act [m^2].

    Examples
    --------
    >>> activated_area(2.0, 0.5, 1.0, math.inf, False, 1.0, 0.0)
    0.0
    >>> activated_area(2.0, 1.5, 1.0, 2.0, False, 1.0, 0.0)
    2.0
    >>> activated_area(2.0, 0.1, -math.inf, math.inf, True, 1.0, 0.0)
    0.0
    >>> activated_area(2.0, 0.1, -math.inf, math.inf, False, 0.5, 0.5)
    0.75
    """
    if shut or not (open_time <= t < close_time):
        return 0.0
    return amplitude * max(area - area_at_activation, 0.0)
