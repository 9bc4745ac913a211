"""The one tolerances object of the gas core: every numerical threshold used by `cavity` has a name here."""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Tolerances", "TOL", "R_UNIVERSAL"]

#: Universal gas constant [J/(mol K)] (CODATA 2018, exact).
R_UNIVERSAL = 8.314462618


@dataclass(frozen=True)
class Tolerances:
    """Numerical thresholds of the gas core.

    Attributes
    ----------
    newton_rtol : float
        Relative Newton step below which the solve of T from internal energy stops [-]; convergence is
        quadratic, so the returned T (one step further) is exact to round-off.
    newton_max_iterations : int
        Newton iterations before the temperature solve is declared failed [-].
    temperature_floor : float
        Lowest temperature the Newton iteration may step to [K] (keeps e/T^2 terms finite).
    table_time_eps : float
        Relative gap below which two breakpoints are merged [-].
    """

    newton_rtol: float = 1e-10
    newton_max_iterations: int = 60
    temperature_floor: float = 1.0
    table_time_eps: float = 1e-14


TOL = Tolerances()
