"""The discrete state of a network during one segment: what switches change and a trajectory keeps per segment."""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["DiscreteState"]


@dataclass(frozen=True)
class DiscreteState:
    """The discrete state of a network during one segment (what :meth:`Network.snapshot` returns and a trajectory
    keeps per segment). Per exchange: whether its pop condition has been met, when its hold started (None: not
    holding), its area when it opened (DELTA LEAKAGE AREA; None: not yet), whether it is held closed (equalised),
    whether it closed for good at its close pressure, and the dynamic body's area interval (None: its area does not
    follow the body); whether hard contact holds the dynamic body on its seat."""

    popped: tuple
    holding_since: tuple
    area_at_activation: tuple
    equalised: tuple
    closed: tuple
    intervals: tuple
    held: bool = False
