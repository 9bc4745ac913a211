"""What a network with bodies hands the engine besides its gas: blocked leakage areas, wrapped volumes, the dynamic
body and its seat (a scene network's ``lowered_geometry()``, :mod:`cases.model.scene_lowering`)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .layout import BodyColumn, SeatState

__all__ = ["AreaSteps", "VolumeSpline", "BodyParameters", "Seat", "Geometry"]


@dataclass(frozen=True)
class AreaSteps:
    """A blocked leakage area, piecewise constant between its crossings: ``crossings`` (k,) [s, or m of the dynamic
    body's displacement when ``by_body``], ``areas`` (k + 1,) [m^2] before the first crossing, between and after;
    ``scale`` a mesh scale table of time (area × s², None); ``switch_scale`` [m] of its crossings' switches; ``moving``
    the pack of :func:`blockage.moving_area.moving_leak_area` of a surface on a vertex trajectory (None);
    ``sampling`` (step [s], lag [cycles]) of an FE rule's flags sampled from the dynamic body (None: exact; its last
    crossing is +inf, its area the flagless one: :mod:`exchange.engine.sampled`)."""

    crossings: np.ndarray
    areas: np.ndarray
    scale: object = None
    by_body: bool = False
    switch_scale: float = 1.0
    moving: np.ndarray | None = None
    sampling: tuple | None = None


@dataclass(frozen=True)
class VolumeSpline:
    """A volume wrapped around bodies: a cubic spline (knots (k,), coefficients (4, k − 1), highest power first) of
    time, or of the dynamic body's displacement when ``by_body``."""

    knots: np.ndarray
    coefficients: np.ndarray
    by_body: bool = False


@dataclass(frozen=True)
class BodyParameters:
    """The dynamic body: its first unknown, mass [kg], gravity along its axis [m/s^2], the cavity it intrudes into
    and the one whose gauge pressure pushes it on ``pressure_area`` [m^2] (−1: none), spring [N/m] and preload [N],
    the speed scale of its turning-point switch [m/s] and the slack of its area intervals' re-derivation [m]."""

    offset: int
    mass: float
    gravity: float
    pushed: int
    pressure_cavity: int
    pressure_area: float
    stiffness: float
    preload: float
    speed_scale: float
    slack: float

    def array(self) -> np.ndarray:
        """The model's ``body`` field (BodyColumn)."""
        out = np.empty(len(BodyColumn))
        for column in BodyColumn:
            out[column] = getattr(self, column.name.lower())
        return out


@dataclass(frozen=True)
class Seat:
    """The dynamic body's seat contact: its law vector (:class:`exchange.contact.laws.SeatLaw`), node table
    (:class:`exchange.contact.laws.SeatNode`), the displacements where its force kinks [m], whether hard contact holds
    the body at the start, the force scale of the lift-off switch [N], and whether the contact is hard."""

    law: np.ndarray
    nodes: np.ndarray
    kinks: np.ndarray
    held: bool
    force_scale: float
    hard: bool

    def state(self) -> np.ndarray:
        """The model's ``seat_state`` field (SeatState)."""
        out = np.zeros(len(SeatState))
        out[SeatState.HAS], out[SeatState.HELD], out[SeatState.FORCE_SCALE] = 1.0, float(self.held), self.force_scale
        return out


@dataclass(frozen=True)
class Geometry:
    """A network's geometry for the engine: blocked areas by exchange index, wrapped volumes by cavity name, the
    dynamic body and its seat (None: none)."""

    areas: dict = field(default_factory=dict)
    volumes: dict = field(default_factory=dict)
    body: BodyParameters | None = None
    seat: Seat | None = None
