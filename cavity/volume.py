"""Cavity volume: a rigid tank, a tabulated history V(t), or a closed triangle mesh (divergence theorem).

Every volume model answers ``volume(t)`` [m^3], ``volume_rate(t)`` [m^3/s] and ``breakpoints`` (times where the
rate jumps), plus an added volume; the minimum volume replaces V in the equation of state when V falls below it
(Abaqus *FLUID CAVITY, MINIMUM VOLUME).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .tables import Table

__all__ = ["mesh_volume", "mesh_volumes", "closed_mesh_volume", "MeshError", "FixedVolume", "TableVolume", "ScaledMeshVolume",
           "effective_volume", "SeriesVolume", "series_volume_coefficients", "volume_cubic"]


class MeshError(ValueError):
    """A cavity mesh that does not bound a volume (open, inconsistently oriented, or inside out)."""


def mesh_volume(vertices, faces) -> float:
    r"""Volume enclosed by a closed, outward-oriented triangle surface [m^3] (divergence theorem).

    .. math:: V = \frac{1}{3}\sum_f \bar{\mathbf x}_f\cdot\mathbf n_f A_f
                = \frac{1}{6}\sum_f \mathbf x_0\cdot(\mathbf x_1\times\mathbf x_2)

    Parameters
    ----------
    vertices : (n, 3) float
        Node coordinates [m].
    faces : (m, 3) int
        Triangles, counter-clockwise seen from outside.

    Returns
    -------
    float
        Signed volume: negative when the normals point inwards.

    Examples
    --------
    The unit tetrahedron:

    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> round(mesh_volume(v, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]), 15)
    0.166666666666667
    """
    return float(mesh_volumes(vertices, faces))


def mesh_volumes(vertices, faces) -> np.ndarray:
    """:func:`mesh_volume` of many placements of one mesh at once: ``vertices`` (..., n, 3) [m] → (...) [m^3].

    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> mesh_volumes(np.stack([v, 2 * v]), [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]).round(12).tolist()
    [0.166666666667, 1.333333333333]
    """
    x = np.asarray(vertices, dtype=float)
    f = np.asarray(faces)
    x0, x1, x2 = x[..., f[:, 0], :], x[..., f[:, 1], :], x[..., f[:, 2], :]
    return np.einsum("...i,...i->...", x0, np.cross(x1, x2)).sum(axis=-1) / 6.0


def closed_mesh_volume(mesh, name: str = "mesh") -> float:
    """Volume of a trimesh surface after checking it bounds one consistently, outward-oriented region [m^3].

    Raises
    ------
    MeshError
        If the surface is open (not watertight), its faces are inconsistently wound, or the volume is
        negative (normals point inwards: flip the faces, e.g. ``mesh.invert()``).
    """
    if len(mesh.faces) == 0:
        raise MeshError(f"{name}: the mesh has no faces")
    if not mesh.is_watertight:
        raise MeshError(f"{name}: the surface is not closed (some edges do not have exactly two faces); "
                        "a cavity needs a closed surface")
    if not mesh.is_winding_consistent:
        raise MeshError(f"{name}: faces are not consistently oriented (neighbouring faces disagree on their normal)")
    v = mesh_volume(mesh.vertices, mesh.faces)
    if v <= 0.0:
        raise MeshError(f"{name}: the enclosed volume is {v:.6g} m^3 <= 0: the normals point inwards "
                        "(inside-out mesh); flip the face orientation")
    return v


def effective_volume(volume: float, minimum: float) -> float:
    """Volume used in the equation of state: max(V, V_min) [m^3] (Abaqus MINIMUM VOLUME)."""
    return volume if volume > minimum else minimum


@dataclass(frozen=True)
class FixedVolume:
    """A rigid tank of volume ``volume`` [m^3]."""

    volume: float

    def __call__(self, t: float) -> float:
        return self.volume

    def rate(self, t: float) -> float:
        return 0.0

    breakpoints: tuple = ()


@dataclass(frozen=True)
class TableVolume:
    """A volume history V(t) [m^3] from a piecewise-linear table; its rate is piecewise constant."""

    table: Table

    def __call__(self, t: float) -> float:
        return self.table(t)

    def rate(self, t: float) -> float:
        return self.table.slope(t)

    @property
    def breakpoints(self) -> tuple:
        return self.table.breakpoints


@dataclass(frozen=True)
class ScaledMeshVolume:
    """A closed mesh of volume ``mesh_volume`` scaled uniformly about a point by s(t): V = s³·V_mesh [m^3].

    The scale table is piecewise linear, so V is a cubic in t on each piece and dV/dt = 3 s² ṡ V_mesh exactly.
    """

    mesh_volume: float
    scale: Table

    def __call__(self, t: float) -> float:
        return self.scale(t) ** 3 * self.mesh_volume

    def rate(self, t: float) -> float:
        s = self.scale(t)
        return 3.0 * s * s * self.scale.slope(t) * self.mesh_volume

    @property
    def breakpoints(self) -> tuple:
        return self.scale.breakpoints


def volume_cubic(start, end, triangles) -> np.ndarray:
    r"""Coefficients (c0, c1, c2, c3) [m^3] of the volume enclosed by a triangle surface whose nodes move
    linearly from ``start`` to ``end``: V(w) = c0 + c1 w + c2 w^2 + c3 w^3 for x = start + w (end - start).

    .. math:: V(w) = \frac{1}{6}\sum_f \det[\mathbf x_a, \mathbf x_b, \mathbf x_c],\quad
              \mathbf x = \mathbf p + w\,\mathbf q

    and the determinant is trilinear, so c0 = Σ det[p_a, p_b, p_c]/6, c1 = Σ (det[q_a, p_b, p_c] +
    det[p_a, q_b, p_c] + det[p_a, p_b, q_c])/6, c2 likewise with two q's, c3 = Σ det[q_a, q_b, q_c]/6 (the
    divergence theorem, as :func:`mesh_volume`). Exact, not sampled.

    Parameters
    ----------
    start, end : (n, 3) float
        Node positions [m] at w = 0 and w = 1.
    triangles : (m, 3) int
        Closed surface, counter-clockwise seen from outside.

    >>> import trimesh
    >>> cube = trimesh.creation.box()  # 1 m^3; scaled by (1 + w): V = (1 + w)^3
    >>> volume_cubic(cube.vertices, 2.0 * cube.vertices, cube.faces).round(12).tolist()
    [1.0, 3.0, 3.0, 1.0]
    """
    p, q = np.asarray(start, dtype=float), np.asarray(end, dtype=float) - np.asarray(start, dtype=float)
    tri = np.asarray(triangles, dtype=np.int64)

    def det(a, b, c):
        return float(np.einsum("ij,ij->", a[tri[:, 0]], np.cross(b[tri[:, 1]], c[tri[:, 2]])))

    return np.array([det(p, p, p), det(q, p, p) + det(p, q, p) + det(p, p, q),
                     det(p, q, q) + det(q, p, q) + det(q, q, p), det(q, q, q)]) / 6.0


def series_volume_coefficients(times, vertices, faces) -> np.ndarray:
    """(4, k − 1) coefficients of (t − t_i)³, ², ¹, ⁰ of the volume of a closed mesh series on each frame interval
    (:func:`volume_cubic` rescaled to time), as :class:`scipy.interpolate.PPoly` takes them.

    >>> import trimesh
    >>> box = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    >>> c = series_volume_coefficients([0.0, 2.0], np.array([box.vertices, 2 * box.vertices]), box.faces)
    >>> [round(float(x), 12) for x in c[:, 0]]  # V = (1 + t/2)^3 = 1 + 1.5 t + 0.75 t^2 + 0.125 t^3
    [0.125, 0.75, 1.5, 1.0]
    """
    times, vertices = np.asarray(times, dtype=float), np.asarray(vertices, dtype=float)
    out = np.empty((4, len(times) - 1))
    for i in range(len(times) - 1):
        c = volume_cubic(vertices[i], vertices[i + 1], faces)
        out[:, i] = c[::-1] / (times[i + 1] - times[i]) ** np.array([3.0, 2.0, 1.0, 0.0])
    return out


@dataclass(frozen=True)
class SeriesVolume:
    """Volume of a closed mesh given as a series of frames, linear in time between them, held beyond the ends
    [m^3]: a piecewise cubic (:func:`series_volume_coefficients`), so V and dV/dt are exact."""

    spline: object  # scipy.interpolate.PPoly

    @classmethod
    def of(cls, times, vertices, faces) -> "SeriesVolume":
        from scipy.interpolate import PPoly

        return cls(PPoly(series_volume_coefficients(times, vertices, faces), np.asarray(times, dtype=float)))

    def __call__(self, t: float) -> float:
        x = self.spline.x
        return float(self.spline(min(max(t, x[0]), x[-1])))

    def rate(self, t: float) -> float:
        """dV/dt [m^3/s], from the right at a frame time, 0 beyond the ends."""
        x = self.spline.x
        return float(self.spline(t, 1)) if x[0] <= t < x[-1] else 0.0

    @property
    def breakpoints(self) -> tuple:
        return tuple(float(t) for t in self.spline.x)
