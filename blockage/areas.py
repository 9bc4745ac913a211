"""Area laws of contact blockage (Abaqus *FLUID EXCHANGE, BLOCKAGE; Radioss Bvent).

A leakage-surface element ``e`` with ``N_e`` nodes (3 or 4), ``N_c`` of which are
active blockage nodes, is blocked over

.. math::  A_{eb} = A_e \\, N_c / N_e

The obstruction area is :math:`\\sum_e A_{eb}`; the leakage area is the total minus
the obstruction, or, when an effective area is given, the effective area reduced
in proportion: :math:`A_{eff} (1 - A_{obstr} / A_{total})`. A node-based surface is
blocked in the fraction of its nodes that are active. Radioss lets a blocked area
still leak in proportion ``Bvent`` (here ``permeability``, default 0: fully
blocked).

References: Abaqus Analysis User's Guide, "Fluid exchange" (contact blockage);
OpenRadioss ``engine/source/airbag`` (Bvent); ``shared/PHYSICS.md``.
"""

import math

import numpy as np

from blockage._jit import njit

__all__ = [
    "active_counts",
    "blocked_face_areas",
    "blocked_fraction",
    "edge_vectors",
    "face_areas",
    "leak_area",
    "leak_area_of",
    "obstruction_area",
]


def face_areas(vertices, faces, face_sizes):
    """Area of each triangle or quad.

    A triangle's area is :math:`|ab \\times ac| / 2`; a quad's is half the norm of
    the cross product of its diagonals, :math:`|ac \\times bd| / 2`, exact for
    planar quads and the norm of the vector area for warped ones.

    Parameters
    ----------
    vertices : (n, 3) float
        Vertex positions [m].
    faces : (m, 4) int
        Vertex ids, triangles padded with -1 in the last column.
    face_sizes : (m,) int
        3 or 4.

    Returns
    -------
    areas : (m,) float
        [m^2]

    >>> v = np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]])
    >>> face_areas(v, np.array([[0, 1, 2, 3], [0, 1, 2, -1]]), np.array([4, 3])).tolist()
    [2.0, 1.0]
    """
    first, second = edge_vectors(vertices, faces, face_sizes)
    return 0.5 * np.linalg.norm(np.cross(first, second), axis=1)


def edge_vectors(vertices, faces, face_sizes):
    """The two vectors whose cross product is twice a face's vector area: a triangle's AB and AC, a quad's
    diagonals AC and BD; each (m, 3) [m] (:func:`face_areas`, :mod:`blockage.moving_area`).

    >>> v = np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]])
    >>> [x.tolist() for x in edge_vectors(v, np.array([[0, 1, 2, 3]]), np.array([4]))]
    [[[2.0, 1.0, 0.0]], [[-2.0, 1.0, 0.0]]]
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    quad = np.asarray(face_sizes) == 4
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    d = vertices[np.where(quad, faces[:, -1], faces[:, 0])]
    return np.where(quad[:, None], c - a, b - a), np.where(quad[:, None], d - b, c - a)


def active_counts(active_nodes, faces, face_sizes):
    """Number of active nodes ``N_c`` of each face.

    Parameters
    ----------
    active_nodes : (n,) bool
        Active blockage nodes.
    faces : (m, 4) int
        Vertex ids padded with -1.
    face_sizes : (m,) int
        3 or 4.

    Returns
    -------
    counts : (m,) int

    >>> active_counts(np.array([True, False, True, True]), np.array([[0, 1, 2, 3], [1, 2, 3, -1]]),
    ...               np.array([4, 3])).tolist()
    [3, 2]
    """
    faces = np.asarray(faces, dtype=np.int64)
    active = np.asarray(active_nodes, bool).view(np.uint8)
    counts = np.zeros(len(faces), dtype=np.int64)
    for corner in range(faces.shape[1]):
        ids = faces[:, corner]
        counts += np.where(ids >= 0, active[ids], 0) if corner == 3 else active[ids]
    return counts


def blocked_face_areas(areas, counts, face_sizes):
    """Blocked area of each face, :math:`A_{eb} = A_e N_c / N_e`.

    Parameters
    ----------
    areas : (m,) float
        Face areas ``A_e`` [m^2].
    counts : (m,) int
        Active nodes ``N_c`` of each face.
    face_sizes : (m,) int
        Nodes ``N_e`` of each face (3 or 4).

    Returns
    -------
    blocked : (m,) float
        [m^2]

    >>> blocked_face_areas(np.array([2.0, 1.0]), np.array([1, 3]), np.array([4, 3])).tolist()
    [0.5, 1.0]
    """
    # the ratio first: a fully blocked face gives exactly A_e, a partly blocked one never more
    return np.asarray(areas, dtype=np.float64) * (np.asarray(counts) / np.asarray(face_sizes))


def obstruction_area(blocked):
    """Obstruction area :math:`\\sum_e A_{eb}` [m^2].

    >>> obstruction_area(np.array([0.5, 1.0]))
    1.5
    """
    return float(np.sum(blocked))


def leak_area(total_area, obstruction, effective_area=None, permeability=0.0):
    """Leakage area left by an obstruction.

    .. math::

        A = A_{total} - (1 - \\beta) A_{obstr}
        \\quad\\text{or}\\quad
        A = A_{eff} \\left(1 - (1 - \\beta) \\frac{A_{obstr}}{A_{total}}\\right)

    Parameters
    ----------
    total_area : float
        Area of the leakage surface [m^2].
    obstruction : float
        Obstruction area [m^2], ``0 <= obstruction <= total_area``.
    effective_area : float, optional
        Effective leakage area [m^2] (Abaqus EFFECTIVE AREA): the surface is then
        used only for the blocked fraction.
    permeability : float
        Fraction ``beta`` of a blocked area that still leaks (Radioss Bvent),
        0 (fully blocked) to 1.

    Returns
    -------
    area : float
        [m^2]

    >>> leak_area(3.0, 1.5)
    1.5
    >>> leak_area(3.0, 1.5, effective_area=0.01)
    0.005
    >>> leak_area(3.0, 1.5, permeability=0.5)
    2.25
    """
    eff = math.nan if effective_area is None else float(effective_area)
    return float(leak_area_of(float(total_area), float(obstruction), eff, float(permeability)))


@njit(inline="always")
def leak_area_of(total_area, obstruction, effective_area, permeability):
    """:func:`leak_area` in numba's terms (the one implementation): ``effective_area`` NaN when none [m^2].

    >>> leak_area_of(3.0, 1.5, math.nan, 0.0), leak_area_of(3.0, 1.5, 0.01, 0.0)
    (1.5, 0.005)
    """
    if effective_area != effective_area:
        return total_area - (1.0 - permeability) * obstruction
    fraction = obstruction / total_area if total_area > 0.0 else 0.0
    return effective_area * (1.0 - (1.0 - permeability) * fraction)


def blocked_fraction(active_nodes):
    """Blocked fraction of a node-based surface: active nodes / all nodes.

    >>> blocked_fraction(np.array([True, False, False, True]))
    0.5
    >>> blocked_fraction(np.zeros(0, bool))
    0.0
    """
    active_nodes = np.asarray(active_nodes, bool)
    return float(active_nodes.mean()) if active_nodes.size else 0.0
