"""Bodies of a scene: a mesh, and a motion (prescribed rigid, prescribed vertex trajectory, or dynamic).

A rigid body's position is a displacement s [m] along its unit ``axis`` from where its mesh is given, optionally
combined with a rotation by an angle table about an axis through a centre. Prescribed bodies have s(t) (constant
velocity or a table); a deforming body follows vertex positions read from a file (e.g. a finite-element run),
linearly interpolated in time; a dynamic body has s and ds/dt as ODE unknowns and is pushed by the gauge pressure
of the cavity it intrudes into (force (p − p_amb)·dV/ds along the axis, which is the pressure acting on its
contact patch projected on the axis) and by gravity along the axis.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Body", "PrescribedMotion", "DynamicMotion", "VertexTrajectory", "translation", "rotation"]


def translation(axis, s: float) -> np.ndarray:
    """4x4 rigid transform translating by s [m] along the unit vector ``axis``."""
    m = np.eye(4)
    m[:3, 3] = np.asarray(axis, dtype=float) * s
    return m


def rotation(axis, centre, degrees: float) -> np.ndarray:
    """4x4 rigid rotation by ``degrees`` about the unit vector ``axis`` through the point ``centre`` [m]."""
    import trimesh

    return trimesh.transformations.rotation_matrix(math.radians(degrees), axis, centre)


@dataclass(frozen=True)
class PrescribedMotion:
    """s(t) = velocity·t, or a piecewise-linear displacement table s(t) [m]; optionally a rotation table
    angle(t) [deg] about ``rotation_axis`` through ``rotation_centre``, applied before the translation."""

    velocity: float = 0.0
    table: object = None  # cavity.tables.Table or None
    rotation_table: object = None
    rotation_axis: tuple = (0.0, 0.0, 1.0)
    rotation_centre: tuple = (0.0, 0.0, 0.0)

    def displacement(self, t: float) -> float:
        return self.table(t) if self.table is not None else self.velocity * t

    def speed(self, t: float) -> float:
        return self.table.slope(t) if self.table is not None else self.velocity

    @property
    def breakpoints(self) -> tuple:
        pts = self.table.breakpoints if self.table is not None else ()
        return pts + (self.rotation_table.breakpoints if self.rotation_table is not None else ())


@dataclass(frozen=True)
class VertexTrajectory:
    """Vertex positions over time: ``times`` (k,) [s] increasing, ``vertices`` (k, n, 3) [m], linear in between
    and held beyond the ends."""

    times: np.ndarray
    vertices: np.ndarray

    def at(self, t: float) -> np.ndarray:
        ts = self.times
        if t <= ts[0]:
            return self.vertices[0]
        if t >= ts[-1]:
            return self.vertices[-1]
        i = int(np.searchsorted(ts, t, side="right")) - 1
        w = (t - ts[i]) / (ts[i + 1] - ts[i])
        return (1.0 - w) * self.vertices[i] + w * self.vertices[i + 1]

    @property
    def breakpoints(self) -> tuple:
        return tuple(float(t) for t in self.times)


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

    @property
    def deforming(self) -> bool:
        return isinstance(self.motion, VertexTrajectory)

    def transform(self, theta: float) -> np.ndarray:
        """Rigid placement at θ (time for prescribed motion, displacement for a dynamic body)."""
        m = self.motion
        if self.dynamic:
            return translation(self.axis, theta)
        T = translation(self.axis, m.displacement(theta))
        if m.rotation_table is not None:
            T = T @ rotation(m.rotation_axis, m.rotation_centre, m.rotation_table(theta))
        return T

    def vertices_at(self, theta: float) -> np.ndarray:
        """World coordinates of the body's vertices at θ [m]."""
        if self.deforming:
            return self.motion.at(theta)
        T = self.transform(theta)
        return self.mesh.vertices @ T[:3, :3].T + T[:3, 3]

    def describe(self) -> str:
        m = self.motion
        if self.deforming:
            return f"prescribed vertex trajectory, {len(m.times)} frames"
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
