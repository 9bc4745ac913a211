"""The state of a blocked leakage surface at a time t: one definition shared by history.csv's blocked fraction,
the pictures and the VTK series.

The leakage surface is placed where the geometry puts it at t (its nodes moved with the bodies they wrap) and the
blocking bodies at their pose at t (prescribed motion, or the dynamic body at the displacement the solver found);
then :func:`blockage.evaluate` gives the active nodes, the blocked area per face and the leakage area

    A_leak = A_total − (1 − permeability)·A_blocked      (or effective_area·(1 − A_blocked/A_total)).

The blocked fraction of the exchange is ``1 − A_leak / A_open`` with ``A_open`` the leakage area with no body
(the total area, or the effective area).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import blockage

__all__ = ["LeakState", "theta_at", "leak_state", "open_area"]


@dataclass(frozen=True)
class LeakState:
    """Exchange ``j``'s leakage surface at time ``t`` [s]: ``surface`` (placed), ``result``
    (:class:`blockage.BlockageResult`), ``open_area`` [m^2] and the blocked fraction [-]."""

    t: float
    surface: object
    result: object
    open_area: float

    @property
    def leak_area(self) -> float:
        """Leakage area [m^2] at t."""
        return float(self.result.leak_area)

    @property
    def blocked_fraction(self) -> float:
        """``1 − A_leak / A_open`` [-] (0 with no open area)."""
        return 1.0 - self.leak_area / self.open_area if self.open_area > 0.0 else 0.0

    @property
    def face_fraction(self) -> np.ndarray:
        """(m,) blocked area / face area per face, in [0, 1]."""
        areas = np.asarray(self.surface.face_areas)
        fraction = np.divide(self.result.face_blocked_area, areas, out=np.zeros_like(areas), where=areas > 0)
        return np.clip(fraction, 0.0, 1.0)


def theta_at(model, trajectory, t: float) -> float:
    """The geometry parameter at time t: t itself, or the dynamic body's displacement [m]."""
    driver = model.geometry["driver"]
    return t if driver.dynamic is None else float(trajectory(t)[model.network.body_offset])


def open_area(model, j: int) -> float:
    """Leakage area of exchange ``j`` with no blocking body [m^2] (total area, or the effective area)."""
    spec = model.scene.exchange[j]
    surface, _ = model.geometry["surfaces"][j]
    tol = spec.contact_tolerance
    return float(blockage.evaluate(surface, [], tol, effective_area=spec.effective_area or None,
                                   permeability=spec.permeability).leak_area)


def leak_state(model, trajectory, j: int, t: float, open_area_value: float | None = None) -> LeakState:
    """Exchange ``j``'s leakage surface and its blockage at time ``t`` [s] (see the module docstring)."""
    geo, spec = model.geometry, model.scene.exchange[j]
    surface, positions = geo["surfaces"][j]
    th = theta_at(model, trajectory, t)
    leak = surface.with_vertices(positions(th, None))
    placed = geo["driver"].placed(spec.blocked_by)(th)
    tol = spec.contact_tolerance
    res = blockage.evaluate(leak, placed, tol, cutoff=4 * tol, effective_area=spec.effective_area or None,
                            permeability=spec.permeability)
    return LeakState(t, leak, res, open_area(model, j) if open_area_value is None else open_area_value)
