"""Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9).

As in :mod:`blockage.triangle_distance`, the law is written as a compiled scalar
function (:func:`closest_points_of_segments`, used by the tree query) and as a numpy
function over pairs (:func:`closest_points_between_segments`, used by the
brute-force reference), with the same operations in the same order, so both return
bit-identical points. Zero-length segments are points; parallel segments (zero
denominator) take ``s = 0`` on the first and the matching point on the second.

>>> import numpy as np
>>> c = closest_points_between_segments(np.array([[0.0, 0, 0]]), np.array([[2.0, 0, 0]]),
...                                     np.array([[1.0, -1, 1]]), np.array([[1.0, 1, 1]]))
>>> c.tolist()
[[1.0, 0.0, 0.0, 1.0, 0.0, 1.0]]
>>> closest_points_of_segments(0.0, 0, 0, 2, 0, 0, 1, -1, 1, 1, 1, 1)
(1.0, 0.0, 0.0, 1.0, 0.0, 1.0)
"""

import numpy as np

from blockage._jit import njit

__all__ = ["closest_points_between_segments", "closest_points_of_segments"]


@njit
def _clamp01(x):
    return min(max(x, 0.0), 1.0)


@njit
def closest_points_of_segments(p1x, p1y, p1z, q1x, q1y, q1z, p2x, p2y, p2z, q2x, q2y, q2z):
    """Closest points ``c1`` on ``p1 q1`` and ``c2`` on ``p2 q2`` (scalar form).

    Returns ``(c1x, c1y, c1z, c2x, c2y, c2z)`` [m].
    """
    d1x, d1y, d1z = q1x - p1x, q1y - p1y, q1z - p1z
    d2x, d2y, d2z = q2x - p2x, q2y - p2y, q2z - p2z
    rx, ry, rz = p1x - p2x, p1y - p2y, p1z - p2z
    a = d1x * d1x + d1y * d1y + d1z * d1z
    e = d2x * d2x + d2y * d2y + d2z * d2z
    f = d2x * rx + d2y * ry + d2z * rz
    c = d1x * rx + d1y * ry + d1z * rz
    b = d1x * d2x + d1y * d2y + d1z * d2z
    s = 0.0
    t = 0.0
    if a <= 0.0 and e <= 0.0:
        pass
    elif a <= 0.0:
        t = _clamp01(f / e)
    elif e <= 0.0:
        s = _clamp01(-c / a)
    else:
        denom = a * e - b * b
        if denom != 0.0:
            s = _clamp01((b * f - c * e) / denom)
        t = (b * s + f) / e
        if t < 0.0:
            t = 0.0
            s = _clamp01(-c / a)
        elif t > 1.0:
            t = 1.0
            s = _clamp01((b - c) / a)
    return p1x + d1x * s, p1y + d1y * s, p1z + d1z * s, p2x + d2x * t, p2y + d2y * t, p2z + d2z * t


def _dot(u, v):
    return u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1] + u[:, 2] * v[:, 2]


def _parameters(a, b, c, e, f):
    """Vector form of the branch logic of :func:`closest_points_of_segments`."""
    clamp = lambda x: np.minimum(np.maximum(x, 0.0), 1.0)  # noqa: E731
    with np.errstate(all="ignore"):
        denom = a * e - b * b
        s_gen = np.where(denom != 0.0, clamp((b * f - c * e) / denom), 0.0)
        t_gen = (b * s_gen + f) / e
        s_gen = np.where(t_gen < 0.0, clamp(-c / a), np.where(t_gen > 1.0, clamp((b - c) / a), s_gen))
        t_gen = np.where(t_gen < 0.0, 0.0, np.where(t_gen > 1.0, 1.0, t_gen))
        a_zero, e_zero = a <= 0.0, e <= 0.0
        s = np.where(a_zero, 0.0, np.where(e_zero, clamp(-c / a), s_gen))
        t = np.where(a_zero, np.where(e_zero, 0.0, clamp(f / e)), np.where(e_zero, 0.0, t_gen))
    return s, t


def closest_points_between_segments(p1, q1, p2, q2):
    """Closest points of segment pairs ``p1 q1`` and ``p2 q2`` (numpy form).

    Parameters
    ----------
    p1, q1, p2, q2 : (n, 3) float
        End points of the first and second segment of each pair [m].

    Returns
    -------
    closest : (n, 6) float
        ``c1`` on the first and ``c2`` on the second segment [m], bit-identical to
        :func:`closest_points_of_segments`.
    """
    p1, q1, p2, q2 = (np.asarray(x, dtype=np.float64) for x in (p1, q1, p2, q2))
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    s, t = _parameters(_dot(d1, d1), _dot(d1, d2), _dot(d1, r), _dot(d2, d2), _dot(d2, r))
    return np.concatenate([p1 + d1 * s[:, None], p2 + d2 * t[:, None]], axis=1)
