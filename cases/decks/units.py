"""Unit systems of a deck (``--units``): the scene's own (:mod:`cases.scene.unit_systems`), one code for both."""
from __future__ import annotations

from cases.scene.unit_systems import DIMENSIONS, SYSTEMS, UnitSystem, unit_system

__all__ = ["UnitSystem", "SYSTEMS", "unit_system", "DIMENSIONS"]
