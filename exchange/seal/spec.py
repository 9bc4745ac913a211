"""What a scene says about a seal exchange, before its surface and flange are known (no heavy imports: the law
registry imports it at start-up)."""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["SealSetup"]


@dataclass(frozen=True)
class SealSetup:
    """What a scene says about a seal (its keys), before the seal surface and the flange are known."""

    gap: object  # a gap law of exchange.seal.gap_laws / hysteresis
    gap_name: str
    pressurised_edge: str
    outer_edge: str
    viscosity: float  # [Pa s], 0: from the model
    viscosity_model: str
    gas: str
    slip: bool
    s_min: float
    s_max: float
    loaded_to: float  # [m] nan: no earlier loading
    rtol: float
