"""Rigid bodies of a scene: a mesh, and a motion along a fixed axis (prescribed or dynamic).

A body's position is a displacement s [m] along its unit ``axis`` from where its mesh is given. Prescribed bodies
have s(t) (constant velocity or a table); a dynamic body has s and ds/dt as ODE unknowns and is pushed by the
gauge pressure of the cavity it intrudes into (force (p − p_amb)·dV/ds along the axis, which is the pressure
acting on its contact patch projected on the axis) and by gravity along the axis.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Body", "PrescribedMotion", "DynamicMotion", "translation"]


def translation(axis, s: float) -> np.ndarray:
    """4x4 rigid transform translating by s [m] along the unit vector ``axis``."""
    m = np.eye(4)
    m[:3, 3] = np.asarray(axis, dtype=float) * s
    return m


@dataclass(frozen=True)
class PrescribedMotion:
    """s(t) = velocity·t, or a piecewise-linear displacement table s(t) [m]."""

    velocity: float = 0.0
    table: object = None  # cavity.tables.Table or None

    def displacement(self, t: float) -> float:
        return self.table(t) if self.table is not None else self.velocity * t

    def speed(self, t: float) -> float:
        return self.table.slope(t) if self.table is not None else self.velocity

    @property
    def breakpoints(self) -> tuple:
        return self.table.breakpoints if self.table is not None else ()


@dataclass(frozen=True)
class DynamicMotion:
    """A rigid body of mass [kg] with an initial speed [m/s] along the axis and gravity [m/s^2] along it."""

    mass: float
    initial_velocity: float
    gravity: float = 0.0

    breakpoints = ()


@dataclass(frozen=True)
class Body:
    """A named rigid body: its mesh (trimesh.Trimesh, in its initial position), axis and motion."""

    name: str
    mesh: object
    axis: tuple
    motion: object

    @property
    def dynamic(self) -> bool:
        return isinstance(self.motion, DynamicMotion)

    def transform(self, s: float) -> np.ndarray:
        return translation(self.axis, s)

    def describe(self) -> str:
        m = self.motion
        if self.dynamic:
            return (f"dynamic rigid body, mass {m.mass} kg, initial speed {m.initial_velocity} m/s along "
                    f"{list(self.axis)}, gravity {m.gravity} m/s^2")
        if m.table is not None:
            return f"prescribed displacement table along {list(self.axis)}"
        return f"prescribed constant velocity {m.velocity} m/s along {list(self.axis)}"


def unit(axis, where: str = "axis") -> tuple:
    a = np.asarray(axis, dtype=float)
    n = float(np.linalg.norm(a))
    if a.shape != (3,) or not math.isfinite(n) or n == 0.0:
        raise ValueError(f"{where}: expected a non-zero 3-vector, got {axis!r}")
    return tuple(a / n)
