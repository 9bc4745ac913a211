"""The exact kernels: Ericson point-triangle and segment-segment, numpy vs compiled, vs oracles."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from blockage.segment_distance import closest_points_between_segments, closest_points_of_segments
from blockage.triangle_distance import (closest_point_on_triangle, closest_points_on_segments,
                                        closest_points_on_triangles, degenerate_triangles, is_degenerate,
                                        squared_distances)
from blockage.tolerance import TOL


def oracle_triangle_distance(p, tri):
    """Independent formula: plane projection if inside (barycentric solve), else the nearest edge."""
    a, b, c = tri
    normal = np.cross(b - a, c - a)
    best = min(np.linalg.norm(p - q) for q in closest_points_on_segments(
        np.repeat(p[None], 3, 0), np.array([a, b, c]), np.array([b, c, a])))
    nn = normal @ normal
    if nn > 1e-20 * ((b - a) @ (b - a)) * ((c - a) @ (c - a)):
        foot = p - normal * ((p - a) @ normal) / nn
        matrix = np.column_stack([b - a, c - a])
        v, w = np.linalg.lstsq(matrix, foot - a, rcond=None)[0]
        if v >= 0 and w >= 0 and v + w <= 1:
            best = min(best, abs((p - a) @ normal) / np.sqrt(nn))
    return best


def compiled(points, triangles, degenerate):
    return np.array([closest_point_on_triangle(*p, *t.ravel(), d) for p, t, d in zip(points, triangles, degenerate)])


def test_regions_of_the_unit_triangle():
    tri = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    cases = {  # point -> closest point: the 7 Voronoi regions
        (0.25, 0.25, 3.0): (0.25, 0.25, 0.0), (-1.0, -1.0, 0.0): (0.0, 0.0, 0.0), (2.0, -0.5, 1.0): (1.0, 0.0, 0.0),
        (-0.5, 2.0, 0.0): (0.0, 1.0, 0.0), (0.5, -1.0, 0.0): (0.5, 0.0, 0.0), (-1.0, 0.5, 0.0): (0.0, 0.5, 0.0),
        (1.0, 1.0, 0.0): (0.5, 0.5, 0.0)}
    points = np.array(list(cases))
    expected = np.array(list(cases.values()))
    triangles = np.repeat(tri[None], len(points), 0)
    flags = np.zeros(len(points), bool)
    np.testing.assert_array_equal(closest_points_on_triangles(points, triangles, flags), expected)
    np.testing.assert_array_equal(compiled(points, triangles, flags), expected)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([1e-6, 1.0, 1e4]))
def test_numpy_and_compiled_kernels_are_bit_identical_and_match_an_oracle(seed, scale):
    rng = np.random.default_rng(seed)
    n = 200
    triangles = rng.normal(size=(n, 3, 3)) * scale
    triangles[:20, 2] = triangles[:20, 0]  # repeated vertex
    triangles[20:40, 2] = 2 * triangles[20:40, 1] - triangles[20:40, 0]  # collinear
    triangles[40:60] = triangles[40:60, :1]  # a point
    points = rng.normal(size=(n, 3)) * scale * rng.choice([0.1, 1.0, 10.0], size=(n, 1))
    flags = degenerate_triangles(triangles)
    assert flags[:60].all()
    fast = compiled(points, triangles, flags)
    vector = closest_points_on_triangles(points, triangles, flags)
    assert np.array_equal(fast, vector)
    distances = np.sqrt(squared_distances(points, vector))
    oracle = np.array([oracle_triangle_distance(p, t) for p, t in zip(points, triangles)])
    np.testing.assert_allclose(distances, oracle, rtol=1e-9, atol=1e-12 * scale)


def test_degenerate_flags_are_bit_identical_between_forms():
    rng = np.random.default_rng(3)
    triangles = rng.normal(size=(2000, 3, 3))
    triangles[:, 2] = triangles[:, 0] + (triangles[:, 1] - triangles[:, 0]) * 0.3 + rng.normal(
        size=(2000, 3)) * np.logspace(-12, 0, 2000)[:, None]
    vector = degenerate_triangles(triangles)
    scalar = np.array([is_degenerate(*t.ravel(), TOL.degenerate_sin2) for t in triangles])
    assert np.array_equal(vector, scalar)
    assert vector.any() and not vector.all()


def test_sliver_distance_is_accurate():
    # a needle 1e-7 wide: treated as edges or as a triangle, the distance stays exact to ~1e-12
    tri = np.array([[[0.0, 0, 0], [1, 0, 0], [0.5, 1e-7, 0]]])
    p = np.array([[0.5, 5e-8, 0.25]])
    d = np.sqrt(squared_distances(p, closest_points_on_triangles(p, tri)))
    assert abs(d[0] - 0.25) < 1e-12


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_segment_kernels_bit_identical_and_no_worse_than_sampling(seed):
    rng = np.random.default_rng(seed)
    n = 80
    p1, q1, p2, q2 = (rng.normal(size=(n, 3)) for _ in range(4))
    q1[:10] = p1[:10]  # zero-length first segment
    q2[10:20] = p2[10:20]
    q2[20:30] = p2[20:30] + (q1[20:30] - p1[20:30]) * 1.5  # parallel
    vector = closest_points_between_segments(p1, q1, p2, q2)
    scalar = np.array([closest_points_of_segments(*a, *b, *c, *d) for a, b, c, d in zip(p1, q1, p2, q2)])
    assert np.array_equal(vector, scalar)
    distance = np.linalg.norm(vector[:, :3] - vector[:, 3:], axis=1)
    s = np.linspace(0, 1, 101)
    for k in range(n):
        first = p1[k] + np.outer(s, q1[k] - p1[k])
        second = p2[k] + np.outer(s, q2[k] - p2[k])
        sampled = np.min(np.linalg.norm(first[:, None] - second[None], axis=2))
        assert distance[k] <= sampled + 1e-12


@pytest.mark.parametrize("point, expected", [((0.5, 0.5, 0.0), 0.5), ((-1.0, 0.0, 0.0), 1.0),
                                             ((4.0, 0.0, 4.0), 5.0)])
def test_point_segment_analytic(point, expected):
    q = closest_points_on_segments(np.array([point]), np.zeros((1, 3)), np.array([[1.0, 0.0, 0.0]]))
    assert np.linalg.norm(np.array(point) - q[0]) == pytest.approx(expected, rel=1e-15)
    zero_length = closest_points_on_segments(np.array([point]), np.ones((1, 3)), np.ones((1, 3)))
    assert zero_length.tolist() == [[1.0, 1.0, 1.0]]
