"""The seal film's geometry, built once: chart, element stiffness, edges, nodal areas.

:func:`seal_film` turns a seal-surface mesh into a :class:`SealFilm`, everything the Reynolds solve
(:mod:`exchange.seal.reynolds`) needs that does not depend on the gap: which nodes are on the pressurised and the
outer edge, the chart the film equation is discretised in (:mod:`exchange.seal.chart`), the unit-coefficient
stiffness of every element and the tributary area of every node.

Elements whose nodes all lie on one edge carry no flow (their nodes share one fixed pressure) and are dropped;
that also drops the elements that are flat in the polar chart (three nodes on one circle).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exchange.seal import chart as charts
from exchange.seal.surface import edge_nodes, nodal_areas, split_faces

__all__ = ["SealFilm", "seal_film"]


@dataclass(frozen=True, eq=False)
class SealFilm:
    """Geometry of a seal film (arrays are not to be modified).

    Attributes
    ----------
    vertices : (n, 3) float
        Node positions [m].
    triangles, quads : (mt, 3), (mq, 4) int
        The elements that can carry flow.
    high, low : (n,) bool
        Nodes of the pressurised edge (pressure p1) and of the outer edge (p2).
    chart : str
        "polar" or "local" (:mod:`exchange.seal.chart`).
    centre, axis : (3,) float
        Centre and axis of the polar chart (the best-fit plane's normal and centroid for "local").
    stiffness_tri, stiffness_quad : (mt, 3, 3), (mq, 4, 4) float
        Unit-coefficient element stiffness in the chart [-].
    areas : (n,) float
        Tributary area of every node [m²] (every element of the surface, dropped or not).
    pattern : (indptr, indices)
        Sparsity pattern (CSR) of the assembled film operator, computed once.
    slots_tri, slots_quad : (mt, 9), (mq, 16) int
        Position in the CSR data of every entry of every element matrix: assembling is one bincount.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    quads: np.ndarray
    high: np.ndarray
    low: np.ndarray
    chart: str
    centre: np.ndarray
    axis: np.ndarray
    stiffness_tri: np.ndarray
    stiffness_quad: np.ndarray
    areas: np.ndarray
    pattern: tuple
    slots_tri: np.ndarray
    slots_quad: np.ndarray

    @property
    def n_nodes(self):
        return len(self.vertices)


def _pattern(n, triangles, quads):
    """CSR pattern of the operator and each element entry's slot in its data array."""
    rows = np.concatenate([np.repeat(triangles, 3, axis=1).ravel(), np.repeat(quads, 4, axis=1).ravel()])
    cols = np.concatenate([np.tile(triangles, (1, 3)).ravel(), np.tile(quads, (1, 4)).ravel()])
    key = rows * n + cols
    unique, slots = np.unique(key, return_inverse=True)
    indptr = np.searchsorted(unique // n, np.arange(n + 1)).astype(np.int64)
    split = 9 * len(triangles)
    return (indptr, (unique % n).astype(np.int64)), slots[:split].reshape(-1, 9), slots[split:].reshape(-1, 16)


def _keep(elements, high, low):
    return ~(high[elements].all(axis=1) | low[elements].all(axis=1))


def _polar(vertices, triangles, quads, high, low, axis, centre):
    """(chart coordinates per element type, centre, axis) or None where the polar chart does not fit."""
    origin, a, e1, e2, flatness = charts.plane_frame(vertices, axis)
    if flatness > charts.PLANE_TOL:
        return None
    if centre is None:
        hole = high if np.ptp(vertices[high], axis=0).sum() <= np.ptp(vertices[low], axis=0).sum() else low
        d = vertices[hole] - origin
        c2 = charts.circle_centre(np.c_[d @ e1, d @ e2])
        centre = origin + c2[0] * e1 + c2[1] * e2
    centre = np.asarray(centre, float)
    plane = np.c_[(vertices - centre) @ e1, (vertices - centre) @ e2]
    polar = charts.polar_coordinates(vertices, centre, e1, e2)
    coords = []
    for elements in (triangles, quads):
        if len(elements) == 0:
            coords.append(np.zeros((0, elements.shape[1], 2)))
            continue
        physical = plane[elements]
        if charts.contains_point(physical, np.zeros(2)).any():
            return None
        chart = charts.element_polar(polar, elements)
        sign_physical = np.sign(charts.signed_areas(physical)).reshape(len(elements), -1)
        sign_chart = np.sign(charts.signed_areas(chart)).reshape(len(elements), -1)
        if np.any(sign_chart == 0) or np.any(sign_chart != sign_physical[:, :1]):
            return None
        coords.append(chart)
    return coords, centre, a


def _local(vertices, triangles, quads, axis):
    """(chart coordinates per element type, centroid, axis) of the local chart; an error on a degenerate element."""
    with np.errstate(divide="ignore", invalid="ignore"):
        tri_coords, quad_coords = charts.element_local(vertices, triangles), charts.element_local(vertices, quads)
    areas = np.abs(charts.signed_areas(tri_coords))
    flat = ~(areas > 1e-14 * np.nanmax(areas, initial=0.0))
    if len(areas) and flat.any():
        raise ValueError(f"triangle {int(np.argmax(flat))} of the seal surface has no area")
    if len(quads):
        jacobians = charts.signed_areas(quad_coords)
        bad = ~np.all(jacobians * np.sign(jacobians[:, :1]) > 0.0, axis=1)
        if bad.any():
            raise ValueError(f"quad {int(np.argmax(bad))} of the seal surface is twisted or degenerate "
                             "(its Jacobian changes sign or vanishes)")
    origin, a, _, _, _ = charts.plane_frame(vertices, axis)
    return (tri_coords, quad_coords), origin, a


def seal_film(vertices, faces, high="inner", low="outer", chart="auto", axis=None, centre=None):
    """Build the :class:`SealFilm` of a seal surface.

    Parameters
    ----------
    vertices : (n, 3) float
        Node positions [m].
    faces : (m, 3) or (m, 4) int
        Triangles and quads (triangles padded with −1 in a 4-column array).
    high, low : str or (k,) int
        The pressurised edge and the outer edge: "inner" or "outer" (boundary loops of a ring) or node indices.
    chart : str
        "auto" (polar when the face is plane and the polar chart maps every element one to one, else local),
        "polar" (an error if it does not fit) or "local".
    axis : (3,) float, optional
        Axis of the polar chart (default: the best-fit plane's normal).
    centre : (3,) float, optional
        Centre of the polar chart (default: the centre of the circle fitted to the smaller edge).

    Examples
    --------
    >>> from exchange.seal.meshes import annulus_mesh
    >>> v, f = annulus_mesh(0.01, 0.02, 4, 32)
    >>> film = seal_film(v, f)
    >>> film.chart, int(film.high.sum()), int(film.low.sum())
    ('polar', 32, 32)
    """
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 3 or not np.isfinite(v).all():
        raise ValueError(f"vertices must be a finite (n, 3) array, got shape {v.shape}")
    triangles, quads = split_faces(faces)
    if len(triangles) + len(quads) == 0 or max(triangles.max(initial=-1), quads.max(initial=-1)) >= len(v):
        raise ValueError("faces must be a non-empty set of elements whose indices are vertices")
    areas = nodal_areas(v, triangles, quads)
    hi = edge_nodes(v, triangles, quads, high)
    lo = edge_nodes(v, triangles, quads, low, other=hi)
    if not lo.any():
        raise ValueError("the outer edge has no node that is not on the pressurised edge")
    triangles, quads = triangles[_keep(triangles, hi, lo)], quads[_keep(quads, hi, lo)]
    if chart not in ("auto", "polar", "local"):
        raise ValueError(f"chart must be 'auto', 'polar' or 'local', got {chart!r}")
    polar = None if chart == "local" else _polar(v, triangles, quads, hi, lo, axis, centre)
    if polar is None and chart == "polar":
        raise ValueError("the polar chart does not fit this surface: it is not plane, or the centre lies on it, "
                         "or an element folds over in (ln r, theta); use chart='local'")
    if polar is not None:
        (tri_coords, quad_coords), c, a = polar
        name = "polar"
    else:
        (tri_coords, quad_coords), c, a = _local(v, triangles, quads, axis)
        name = "local"
    k_tri, k_quad = charts.triangle_stiffness(tri_coords), charts.quad_stiffness(quad_coords)
    pattern, slots_tri, slots_quad = _pattern(len(v), triangles, quads)
    return SealFilm(v, triangles, quads, hi, lo, name, np.asarray(c, float), np.asarray(a, float),
                    k_tri, k_quad, areas, pattern, slots_tri, slots_quad)
