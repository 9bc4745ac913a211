"""Blocker (tree + exact kernel) against the brute-force reference."""

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from blockage import Blocker, reference, traversal
from blockage.parallel import MIN_ROWS

from blockage_scenes import random_meshes, random_rigid


def assert_same_within(fast, truth, cutoff):
    """Identical active sets, bit-identical distances within the cutoff, inf beyond."""
    inside = truth.distances <= cutoff
    assert np.array_equal(fast.distances <= cutoff, inside)
    assert np.array_equal(fast.distances[inside], truth.distances[inside])
    assert np.isinf(fast.distances[~inside]).all()
    assert (fast.faces[inside] >= 0).all() and (fast.faces[~inside] == -1).all()
    assert np.isnan(fast.closest_points[~inside]).all()


@settings(max_examples=40, deadline=None)
@given(random_meshes(), st.integers(0, 2**32 - 1), st.floats(0.0, 2.0), st.integers(1, 9))
def test_fast_equals_brute_force_on_random_meshes(mesh, seed, tolerance, leaf_size):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(150, 3)) * 1.5
    blocker = Blocker(mesh, leaf_size=leaf_size)
    truth = reference.nearest_faces(points, mesh.vertices, mesh.faces)
    assert_same_within(blocker.distances(points, tolerance), truth, tolerance)
    everywhere = blocker.distances(points, np.inf)
    assert np.array_equal(everywhere.distances, truth.distances)
    # the reported closest point is at the reported distance from the query
    np.testing.assert_allclose(np.linalg.norm(everywhere.closest_points - points, axis=1), everywhere.distances,
                               rtol=1e-12, atol=1e-15)


@settings(max_examples=25, deadline=None)
@given(random_meshes(max_vertices=30, max_faces=40), st.integers(0, 2**32 - 1))
def test_nodes_at_the_tolerance_classify_identically(mesh, seed):
    """Tolerance set to a node's exact distance: inclusive; one ulp below: exclusive; 1 +- 1e-12."""
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(60, 3))
    truth = reference.nearest_faces(points, mesh.vertices, mesh.faces).distances
    blocker = Blocker(mesh)
    for d in truth[:10]:
        for tolerance in (d, np.nextafter(d, 0.0), d * (1 - 1e-12), d * (1 + 1e-12)):
            fast = blocker.distances(points, tolerance).distances <= tolerance
            assert np.array_equal(fast, truth <= tolerance)
        assert (blocker.distances(points, d).distances[truth == d] == d).all()


def test_nodes_placed_at_tolerance_one_plus_minus_1e12(rng):
    """Nodes offset from face interiors by tol*(1 -+ 1e-12) are active / inactive, fast and reference."""
    mesh = trimesh.creation.icosphere(3, radius=0.05)  # a 5 cm ball, SI units
    tolerance = 1e-3
    faces = rng.integers(0, len(mesh.faces), 400)
    weights = rng.dirichlet([4.0, 4.0, 4.0], 400)
    base = np.einsum("ij,ijk->ik", weights, mesh.triangles[faces])
    sign = np.where(np.arange(400) % 2 == 0, 1.0 - 1e-12, 1.0 + 1e-12)
    points = base + mesh.face_normals[faces] * (tolerance * sign)[:, None]  # outward: the own face is nearest
    expected = sign < 1
    fast = Blocker(mesh).distances(points, tolerance).distances <= tolerance
    truth = reference.nearest_faces(points, mesh.vertices, mesh.faces).distances <= tolerance
    assert np.array_equal(fast, truth)
    assert np.array_equal(truth, expected)


@settings(max_examples=15, deadline=None)
@given(random_meshes(), st.integers(0, 2**32 - 1))
def test_rigid_motion_transform_refit_and_reference_agree(mesh, seed):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(100, 3)) * 1.5
    matrix = random_rigid(rng)
    moved = mesh.copy()
    moved.apply_transform(matrix)
    tolerance = 0.7
    truth = reference.nearest_faces(points, moved.vertices, moved.faces)
    by_transform = Blocker(mesh).distances(points, tolerance, transform=matrix)
    by_refit = Blocker(mesh).refit(moved.vertices).distances(points, tolerance)
    assert_same_within(by_refit, truth, tolerance)  # refit is exact: same arithmetic as the reference
    near = np.abs(truth.distances - tolerance) > 1e-9  # transforming the points rounds at 1e-16
    assert np.array_equal((by_transform.distances <= tolerance)[near], (truth.distances <= tolerance)[near])
    inside = truth.distances <= tolerance - 1e-9
    np.testing.assert_allclose(by_transform.distances[inside], truth.distances[inside], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(by_transform.closest_points[inside], truth.closest_points[inside], atol=1e-9)


def test_change_of_units_keeps_the_active_set(rng):
    mesh = trimesh.creation.icosphere(2, radius=0.1)
    points = rng.normal(size=(500, 3)) * 0.1
    tolerance = 0.02
    metres = Blocker(mesh).distances(points, tolerance)
    millimetres = Blocker(trimesh.Trimesh(mesh.vertices * 1000, mesh.faces, process=False)).distances(
        points * 1000, tolerance * 1000)
    assert np.array_equal(metres.distances <= tolerance, millimetres.distances <= tolerance * 1000)
    inside = np.isfinite(metres.distances)
    # round-off is relative to the coordinates (0.1 m), not to the (possibly tiny) distance
    np.testing.assert_allclose(millimetres.distances[inside], metres.distances[inside] * 1000, rtol=1e-12,
                               atol=1e-12 * 100.0)


def test_large_queries_are_sorted_and_threaded_with_identical_results(rng):
    mesh = trimesh.creation.icosphere(2)
    points = rng.normal(size=(MIN_ROWS * 2 + 17, 3))
    fast = Blocker(mesh).distances(points, 0.3)
    truth = reference.nearest_faces(points, mesh.vertices, mesh.faces)
    assert_same_within(fast, truth, 0.3)


def test_blocker_keeps_its_own_copy_of_the_vertices():
    mesh = trimesh.creation.box()
    blocker = Blocker(mesh)
    before = blocker.distances([[0.0, 0.0, 2.0]], 5.0).distances
    mesh.vertices += [0.0, 0.0, 1.0]  # the caller moves its mesh in place: the blocker is unchanged
    assert blocker.distances([[0.0, 0.0, 2.0]], 5.0).distances.tolist() == before.tolist() == [1.5]
    assert blocker.refit(mesh.vertices).distances([[0.0, 0.0, 2.0]], 5.0).distances.tolist() == [0.5]


def test_empty_blocker_and_empty_query():
    empty = Blocker(np.zeros((0, 3)), np.zeros((0, 3), int))
    found = empty.distances(np.zeros((4, 3)), 1.0)
    assert np.isinf(found.distances).all() and (found.faces == -1).all()
    assert Blocker(trimesh.creation.box()).distances(np.zeros((0, 3)), 1.0).distances.shape == (0,)


def test_self_contact_exclusion_ignores_incident_faces():
    mesh = trimesh.creation.icosphere(2)
    points = np.asarray(mesh.vertices)
    blocker = Blocker(mesh)
    assert (blocker.distances(points, 0.01).distances == 0).all()
    excluded = blocker.distances(points, 0.01, exclude_vertices=np.arange(len(points)))
    assert np.isinf(excluded.distances).all()
    truth = reference.nearest_faces(points, mesh.vertices, mesh.faces, np.arange(len(points)))
    assert_same_within(blocker.distances(points, 0.5, exclude_vertices=np.arange(len(points))), truth, 0.5)


def test_analytic_oracle_ball_of_radius_one():
    """Points at radius 2 around a unit ball are at distance 1 (up to the faceting)."""
    mesh = trimesh.creation.icosphere(4)
    directions = trimesh.unitize(np.random.default_rng(1).normal(size=(300, 3)))
    d = Blocker(mesh).distances(directions * 2.0, 1.1).distances
    assert np.all((d >= 1.0 - 1e-12) & (d <= 1.0 + 2e-3))


def test_the_python_fallback_runs_the_same_code():
    mesh = trimesh.creation.icosphere(1)
    blocker = Blocker(mesh)
    points = np.random.default_rng(5).normal(size=(20, 3))
    tree = blocker._tree
    args = (points, np.full(20, -1), 0.25, tree.boxes, tree.slots, tree.leaf_size, blocker._sorted_tri,
            blocker._sorted_degenerate, blocker._sorted_bounds, blocker._sorted_faces, blocker.margin)
    compiled = traversal.nearest_triangles(*args)
    python = getattr(traversal.nearest_triangles, "py_func", traversal.nearest_triangles)(*args)
    assert np.array_equal(compiled, python, equal_nan=True)


@pytest.mark.parametrize("points, message", [
    (np.zeros((3, 2)), "shape"), ([[0.0, np.nan, 0.0]], "finite"), ("abc", "points")])
def test_bad_points_raise(points, message):
    with pytest.raises(ValueError, match=message):
        Blocker(trimesh.creation.box()).distances(points, 1.0)


def test_bad_blocker_inputs_raise():
    with pytest.raises(ValueError, match="blocker faces"):
        Blocker(np.zeros((3, 3)), np.array([[0, 1, 5]]))
    with pytest.raises(ValueError, match="Trimesh"):
        Blocker("mesh")
    box = Blocker(trimesh.creation.box())
    with pytest.raises(ValueError, match="cutoff"):
        box.distances(np.zeros((1, 3)), -1.0)
    with pytest.raises(ValueError, match="rigid"):
        box.distances(np.zeros((1, 3)), 1.0, transform=np.diag([2.0, 1, 1, 1]))
    with pytest.raises(ValueError, match="4x4"):
        box.distances(np.zeros((1, 3)), 1.0, transform=np.eye(3))
    with pytest.raises(ValueError, match="exclude_vertices"):
        box.distances(np.zeros((2, 3)), 1.0, exclude_vertices=[1])
    with pytest.raises(ValueError, match="refit"):
        box.refit(np.zeros((3, 3)))
