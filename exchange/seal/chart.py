r"""2-D charts of a seal surface and the element stiffness of the film operator ∇·(k ∇u) in them.

The film equation ∇·(k ∇u) = 0 (k = h³, u = p²) is conformally invariant in two dimensions: its Dirichlet
integral ∫ k |∇u|² dA and the flux across any curve are unchanged by a conformal map. Two charts are used:

* **polar** — for a plane seal face around an axis: (ξ, θ) = (ln r, θ) about a centre on the axis. It is
  conformal, so the film equation keeps its form, and radial flow u = a + b·ln r is *linear* in it: linear (P1)
  triangles and bilinear (Q1) quads reproduce it exactly, whatever the mesh, and a circle r = const is the
  straight line ξ = const. A uniform gap on an annulus therefore gives the closed-form flow to round-off.
* **local** — any surface: each element in an orthonormal frame of its own plane (isometric for triangles and
  plane quads). Second-order accurate in the element size, like any P1/Q1 discretisation.

Stiffness with unit coefficient: K_ij = ∫_e ∇φ_i·∇φ_j dA (triangles exactly; quads by 2×2 Gauss, which integrates
∫∇φ_i exactly, so linear fields pass the patch test).
"""
from __future__ import annotations

import numpy as np

__all__ = ["plane_frame", "circle_centre", "polar_coordinates", "element_polar", "element_local",
           "triangle_stiffness", "quad_stiffness", "signed_areas", "contains_point", "PLANE_TOL"]

#: Largest out-of-plane distance, relative to the surface size, for the polar chart [-].
PLANE_TOL = 1e-6
_G = 1.0 / np.sqrt(3.0)
_GAUSS = np.array([[-_G, -_G], [_G, -_G], [_G, _G], [-_G, _G]])


def plane_frame(vertices, axis=None):
    """(origin, axis, e1, e2, flatness): the best-fit plane of the vertices (or the plane normal to ``axis``)
    with an orthonormal frame; flatness is the largest distance to the plane over the surface size [-].

    >>> o, a, e1, e2, flat = plane_frame(np.array([[0.0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]))
    >>> abs(a).tolist(), flat
    ([0.0, 0.0, 1.0], 0.0)
    """
    x = np.asarray(vertices, float)
    origin = x.mean(axis=0)
    if axis is None:
        axis = np.linalg.svd(x - origin, full_matrices=False)[2][-1]
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    helper = np.eye(3)[int(np.argmin(np.abs(a)))]
    e1 = np.cross(a, helper)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    size = float(np.linalg.norm(x.max(axis=0) - x.min(axis=0))) or 1.0
    flatness = float(np.max(np.abs((x - origin) @ a))) / size
    return origin, a, e1, e2, flatness


def circle_centre(points):
    """Centre (2,) of the least-squares circle through 2-D points (Kasa's algebraic fit; exact for points on a
    circle).

    >>> t = np.array([0.1, 1.0, 2.5, 4.0])
    >>> np.round(circle_centre(np.c_[1 + 2 * np.cos(t), -3 + 2 * np.sin(t)]), 12).tolist()
    [1.0, -3.0]
    """
    p = np.asarray(points, float)
    shift = p.mean(axis=0)
    q = p - shift
    matrix = np.c_[2.0 * q, np.ones(len(q))]
    solution = np.linalg.lstsq(matrix, (q ** 2).sum(axis=1), rcond=None)[0]
    return solution[:2] + shift


def polar_coordinates(vertices, centre, e1, e2):
    """(n, 2) chart coordinates (ln r, θ) of 3-D points about ``centre`` (3,) in the plane spanned by e1, e2."""
    d = np.asarray(vertices, float) - centre
    x, y = d @ e1, d @ e2
    return np.c_[0.5 * np.log(x * x + y * y), np.arctan2(y, x)]


def element_polar(chart, elements):
    """(m, k, 2) polar-chart coordinates per element, θ unwrapped to within π of the element's first node."""
    c = chart[elements].copy()
    theta = c[..., 1]
    theta -= 2.0 * np.pi * np.round((theta - theta[:, :1]) / (2.0 * np.pi))
    return c


def element_local(vertices, elements):
    """(m, k, 2) coordinates of each element's nodes in an orthonormal frame of its own (mean) plane."""
    x = np.asarray(vertices, float)[elements]
    k = elements.shape[1]
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]) if k == 3 else \
        np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    e1 = x[:, 1] - x[:, 0]
    e1 -= (e1 * normal).sum(axis=1, keepdims=True) * normal
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(normal, e1)
    d = x - x[:, :1]
    return np.stack([np.einsum("mki,mi->mk", d, e1), np.einsum("mki,mi->mk", d, e2)], axis=-1)


def signed_areas(coords):
    """Signed area (m,) of triangles (m, 3, 2), or (m, 4) Jacobian determinants at the Gauss points of quads."""
    if coords.shape[1] == 3:
        d1, d2 = coords[:, 1] - coords[:, 0], coords[:, 2] - coords[:, 0]
        return 0.5 * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    return np.stack([np.linalg.det(_jacobian(coords, r, s)) for r, s in _GAUSS], axis=1)


def triangle_stiffness(coords):
    """(m, 3, 3) unit-coefficient stiffness of linear triangles with chart coordinates ``coords`` (m, 3, 2).

    >>> np.round(triangle_stiffness(np.array([[[0.0, 0], [1, 0], [0, 1]]]))[0], 12).tolist()
    [[1.0, -0.5, -0.5], [-0.5, 0.5, 0.0], [-0.5, 0.0, 0.5]]
    """
    x, y = coords[..., 0], coords[..., 1]
    b = np.stack([y[:, 1] - y[:, 2], y[:, 2] - y[:, 0], y[:, 0] - y[:, 1]], axis=1)
    c = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    area = np.abs(signed_areas(coords))
    return (b[:, :, None] * b[:, None, :] + c[:, :, None] * c[:, None, :]) / (4.0 * area)[:, None, None]


def _shape_derivatives(r, s):
    return 0.25 * np.array([[-(1 - s), 1 - s, 1 + s, -(1 + s)], [-(1 - r), -(1 + r), 1 + r, 1 - r]])


def _jacobian(coords, r, s):
    return np.einsum("ak,mkb->mab", _shape_derivatives(r, s), coords)


def quad_stiffness(coords):
    """(m, 4, 4) unit-coefficient stiffness of bilinear quads (nodes in order around the quad), 2×2 Gauss.

    >>> k = quad_stiffness(np.array([[[0.0, 0], [1, 0], [1, 1], [0, 1]]]))[0]
    >>> np.round(k * 6, 12).tolist()[0]
    [4.0, -1.0, -2.0, -1.0]
    """
    out = np.zeros((len(coords), 4, 4))
    for r, s in _GAUSS:
        dn = _shape_derivatives(r, s)
        jac = _jacobian(coords, r, s)
        grad = np.linalg.solve(jac, np.broadcast_to(dn, (len(coords), 2, 4)))
        out += np.einsum("mai,maj->mij", grad, grad) * np.abs(np.linalg.det(jac))[:, None, None]
    return out


def contains_point(coords, point):
    """(m,) True where the 2-D triangle or quad (split 0-1-2, 0-2-3) contains ``point`` (2,) (boundary included)."""
    def inside(a, b, c):
        d = [(q[:, 0] - point[0]) * (r[:, 1] - point[1]) - (q[:, 1] - point[1]) * (r[:, 0] - point[0])
             for q, r in ((a, b), (b, c), (c, a))]
        return ((d[0] >= 0) & (d[1] >= 0) & (d[2] >= 0)) | ((d[0] <= 0) & (d[1] <= 0) & (d[2] <= 0))
    hit = inside(coords[:, 0], coords[:, 1], coords[:, 2])
    if coords.shape[1] == 4:
        hit |= inside(coords[:, 0], coords[:, 2], coords[:, 3])
    return hit
