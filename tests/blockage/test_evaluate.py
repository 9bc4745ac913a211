"""evaluate / evaluate_nodes: active sets and areas against the brute-force reference and closed forms."""

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

import blockage
from blockage import LeakageSurface, evaluate, evaluate_nodes
from blockage.reference import evaluate_nodes_reference, evaluate_reference

from blockage_scenes import grid_surface, random_meshes, random_rigid


def assert_same_result(fast, slow, exact=True):
    """Same active set and areas; distances bit-identical (or to 1e-12 when a transform moved the points)."""
    assert np.array_equal(fast.active_nodes, slow.active_nodes)
    assert np.array_equal(fast.face_active_count, slow.face_active_count)
    assert np.array_equal(fast.face_blocked_area, slow.face_blocked_area)
    assert (fast.total_area, fast.obstruction_area, fast.leak_area) == (slow.total_area, slow.obstruction_area,
                                                                      slow.leak_area)
    found = np.isfinite(fast.distances)
    assert np.array_equal(found, slow.distances <= fast.tolerance)
    if exact:
        assert np.array_equal(fast.distances[found], slow.distances[found])
    else:
        np.testing.assert_allclose(fast.distances[found], slow.distances[found], atol=1e-12)


@settings(max_examples=25, deadline=None)
@given(random_meshes(max_vertices=20, max_faces=30), random_meshes(), st.floats(0.0, 1.0), st.booleans(),
       st.booleans())
def test_evaluate_equals_reference_on_random_scenes(leak, other, tolerance, quads, edge_contact):
    vertices, faces = grid_surface(3, 2, size=(2.0, 2.0), quads=quads)
    vent = LeakageSurface(vertices - [1.0, 1.0, 0.0], faces)
    for surface in (leak, vent):
        # random meshes self-intersect: inside/outside is meaningless there (tests/blockage/test_penetration.py)
        fast = evaluate(surface, [other], tolerance, edge_contact=edge_contact, penetration=False)
        slow = evaluate_reference(surface, [other], tolerance, edge_contact=edge_contact, penetration=False)
        assert_same_result(fast, slow)


def test_plate_over_half_a_quad_vent_blocks_its_two_nodes():
    vent = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    plate = trimesh.Trimesh([[-1.0, -1, 1e-3], [0.5, -1, 1e-3], [0.5, 2, 1e-3], [-1, 2, 1e-3]], [[0, 1, 2], [0, 2, 3]])
    result = evaluate(vent, [plate], 1e-3)  # nodes exactly at the tolerance are active (inclusive)
    assert result.active_nodes.tolist() == [True, False, False, True]
    assert result.face_blocked_area.tolist() == [0.5]  # A_e * N_c / N_e = 1 * 2 / 4
    assert (result.obstruction_area, result.leak_area, result.blocked_fraction) == (0.5, 0.5, 0.5)
    assert evaluate(vent, [plate], np.nextafter(1e-3, 0)).active_nodes.sum() == 0
    np.testing.assert_array_equal(result.gaps[[0, 3]], [0.0, 0.0])


def test_effective_area_and_permeability_scale_the_leak_area():
    vertices, faces = grid_surface(4, 4, quads=True)
    vent = LeakageSurface(vertices, faces)
    wall = trimesh.creation.box(extents=(1.0, 3.0, 1.0))
    wall.apply_translation([0.0, 0.5, 0.5005])  # covers x <= 0.5, 0.5 mm above the vent
    full = evaluate(vent, [wall], 1e-3)
    fraction = full.obstruction_area / full.total_area
    assert 0 < fraction < 1
    assert evaluate(vent, [wall], 1e-3, effective_area=2e-4).leak_area == pytest.approx(2e-4 * (1 - fraction))
    leaky = evaluate(vent, [wall], 1e-3, permeability=0.25)
    assert leaky.leak_area == pytest.approx(full.total_area - 0.75 * full.obstruction_area)
    assert leaky.obstruction_area == full.obstruction_area


def test_quads_read_from_a_file_with_a_named_group(tmp_path):
    meshio = pytest.importorskip("meshio")
    vertices, faces = grid_surface(2, 1, size=(2.0, 1.0), quads=True)
    path = tmp_path / "vent.inp"
    meshio.write(path, meshio.Mesh(vertices, [("quad", faces)], cell_sets={"VENT": [np.array([1])]}))
    whole = LeakageSurface.read(path)
    vent = LeakageSurface.read(path, group="VENT")
    assert whole.face_sizes.tolist() == [4, 4] and vent.face_sizes.tolist() == [4]
    assert vent.total_area == pytest.approx(1.0)
    block = trimesh.creation.box(extents=(0.2, 0.2, 0.2))
    block.apply_translation([1.0, 0.0, 0.1])  # touches the node (1, 0, 0) only
    result = evaluate(vent, [block], 1e-9)
    assert result.active_nodes.sum() == 1
    assert result.obstruction_area == pytest.approx(0.25)  # 1 m^2 * 1 / 4
    assert_same_result(result, evaluate_reference(vent, [block], 1e-9))


def test_pyvista_quads_and_mixed_faces():
    pyvista = pytest.importorskip("pyvista")
    plane = pyvista.Plane(i_size=1.0, j_size=1.0, i_resolution=4, j_resolution=4)
    surface = LeakageSurface.from_pyvista(plane)
    assert (surface.face_sizes == 4).all() and surface.total_area == pytest.approx(1.0)
    mixed = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]], [[0, 1, 2, 3], [1, 4, 2]])
    ball = trimesh.creation.icosphere(2, radius=0.3)
    ball.apply_translation([1.0, 0.0, 0.3])  # touches node 1 (shared by both faces)
    result = evaluate(mixed, [ball], 1e-3)
    assert result.active_nodes.tolist() == [False, True, False, False, False]
    assert result.face_blocked_area.tolist() == [0.25, 0.5 / 3]


def test_degenerate_faces_in_leak_and_blocker():
    leak = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], [[0, 1, 2], [0, 1, 3], [1, 1, 1]])
    assert leak.face_areas.tolist() == [0.0, 0.5, 0.0]
    needle = trimesh.Trimesh([[0.0, 0, 0.01], [1, 0, 0.01], [2, 0, 0.01], [5, 5, 5]], [[0, 1, 2], [3, 3, 3]],
                             process=False)
    result = evaluate(leak, [needle], 0.01)
    assert result.active_nodes.tolist() == [True, True, True, False]
    assert_same_result(result, evaluate_reference(leak, [needle], 0.01))


def test_empty_blocker_list_and_faceless_blocker():
    vertices, faces = grid_surface(2, 2)
    vent = LeakageSurface(vertices, faces)
    for blockers in ([], [trimesh.Trimesh(np.zeros((0, 3)), np.zeros((0, 3), int))]):
        result = evaluate(vent, blockers, 1.0)
        assert not result.active_nodes.any()
        assert result.leak_area == result.total_area == pytest.approx(1.0)


def test_self_contact_excludes_faces_sharing_the_node():
    cavity = trimesh.creation.icosphere(3)
    vent = LeakageSurface.from_region(cavity, sphere=([0.0, 0.0, 1.0], 0.3))
    # alone, the cavity does not block its own vent: every node touches only its own faces
    assert not evaluate(vent, [cavity], 1e-3).active_nodes.any()
    # folded: a flat pouch whose top vent lies 1 mm above its own bottom sheet
    pouch = trimesh.creation.box(extents=(1.0, 1.0, 1e-3))
    pouch = pouch.subdivide().subdivide()
    top = LeakageSurface.from_region(pouch, box=([-0.3, -0.3, 0.0], [0.3, 0.3, 1.0]))
    result = evaluate(top, [pouch], 1.5e-3)
    assert result.active_nodes.all()
    assert_same_result(result, evaluate_reference(top, [pouch], 1.5e-3))
    assert not evaluate(top, [pouch], 0.5e-3).active_nodes.any()


def test_thin_bar_across_a_vent_between_nodes_needs_edge_contact():
    """A bar 0.1 wide lies across the first of two 1 m quads, 1/2 tolerance above, away from all nodes."""
    tolerance = 2e-3
    vertices, faces = grid_surface(2, 1, size=(2.0, 1.0), quads=True)
    vent = LeakageSurface(vertices, faces)
    bar = trimesh.creation.box(extents=(0.1, 2.0, 0.05))
    bar.apply_translation([0.5, 0.5, 0.025 + tolerance / 2])
    node_only = evaluate(vent, [bar], tolerance)
    assert not node_only.active_nodes.any()
    with_edges = evaluate(vent, [bar], tolerance, edge_contact=True)
    # the bar's bottom edges cross the vent edges y = 0 and y = 1 between x = 0 and x = 1
    active = {tuple(v[:2]) for v in vent.vertices[with_edges.active_nodes]}
    assert active == {(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)}
    assert with_edges.face_blocked_area.tolist() == [1.0, 0.5]
    assert_same_result(with_edges, evaluate_reference(vent, [bar], tolerance, edge_contact=True))


def test_node_based_surface_ratio():
    wall = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    tolerance = 2.0**-10  # exactly representable: the node at 0.5 + tolerance is exactly at the tolerance
    points = np.array([[0.0, 0, 0.5], [0, 0, 0.5 + tolerance], [0, 0, 0.6], [2, 2, 2], [0.5, 0.5, 0.5]])
    result = evaluate_nodes(points, [wall], tolerance)
    assert result.active_nodes.tolist() == [True, True, False, False, True]
    assert result.blocked_fraction == pytest.approx(3 / 5)
    active, _ = evaluate_nodes_reference(points, [wall], tolerance)
    assert np.array_equal(active, result.active_nodes)


def test_several_blockers_and_the_accepted_forms():
    vertices, faces = grid_surface(4, 4)
    vent = LeakageSurface(vertices, faces)
    left, right = trimesh.creation.box(extents=(0.3, 1.2, 0.1)), trimesh.creation.box(extents=(0.3, 1.2, 0.1))
    left.apply_translation([0.0, 0.5, 0.05])
    shift = np.eye(4)
    shift[:3, 3] = [1.0, 0.5, 0.05]
    both = evaluate(vent, [left, (right, shift)], 1e-6)
    assert both.active_nodes.sum() == 10  # the columns x = 0 and x = 1 lie on the boxes' bottoms
    by_blocker = evaluate(vent, [blockage.Blocker(left), (blockage.Blocker(right), shift)], 1e-6)
    assert np.array_equal(both.active_nodes, by_blocker.active_nodes)
    assert evaluate(vent, left, 1e-6).active_nodes.sum() == 5  # a single mesh is accepted
    trimesh_leak = trimesh.Trimesh(vertices, faces, process=False)
    assert np.array_equal(evaluate(trimesh_leak, [left, (right, shift)], 1e-6).active_nodes, both.active_nodes)
    assert_same_result(both, evaluate_reference(vent, [left, (right, shift)], 1e-6), exact=False)


def test_moving_a_blocker_in_place_refits_the_cached_tree(rng):
    vertices, faces = grid_surface(10, 10)
    vent = LeakageSurface(vertices, faces)
    ball = trimesh.creation.icosphere(3, radius=0.2)
    cached = blockage.api.placed_blockers([ball])[0][0]
    for _ in range(5):
        ball.apply_transform(random_rigid(rng, translation=0.1))
        ball.apply_translation([0.5, 0.5, 0.2] - ball.centroid + rng.uniform(-0.01, 0.01, 3))
        fast = evaluate(vent, [ball], 0.02)
        assert_same_result(fast, evaluate_reference(vent, [ball], 0.02))
        assert blockage.api.placed_blockers([ball])[0][0] is cached  # refitted, not rebuilt
    ball.vertices += [0.0, 0.0, -0.01]  # an in-place change of the vertices is noticed too
    assert_same_result(evaluate(vent, [ball], 0.02), evaluate_reference(vent, [ball], 0.02))
    ball.faces = ball.faces[:-10]
    assert blockage.api.placed_blockers([ball])[0][0] is not cached  # new topology: rebuilt


def test_rigid_motion_of_the_whole_scene_keeps_the_active_set(rng):
    vertices, faces = grid_surface(12, 12, quads=True)
    vent = LeakageSurface(vertices, faces)
    ball = trimesh.creation.icosphere(3, radius=0.3)
    ball.apply_translation([0.5, 0.5, 0.3 + 1e-3])
    before = evaluate(vent, [ball], 0.05)
    matrix = random_rigid(rng, translation=100.0)
    moved_ball = ball.copy()
    moved_ball.apply_transform(matrix)
    after = evaluate(vent.transformed(matrix), [moved_ball], 0.05)
    assert np.array_equal(before.active_nodes, after.active_nodes)
    assert after.obstruction_area == pytest.approx(before.obstruction_area, rel=1e-12)
    scaled = evaluate(LeakageSurface(vertices * 1000, faces),
                      [trimesh.Trimesh(ball.vertices * 1000, ball.faces, process=False)], 50.0)
    assert np.array_equal(before.active_nodes, scaled.active_nodes)
    assert scaled.obstruction_area == pytest.approx(before.obstruction_area * 1e6, rel=1e-12)


@pytest.mark.parametrize("call, message", [
    (lambda v, b: evaluate(v, b, -1.0), "tolerance"),
    (lambda v, b: evaluate(v, b, float("nan")), "tolerance"),
    (lambda v, b: evaluate(v, b, 1.0, effective_area=-2.0), "effective_area"),
    (lambda v, b: evaluate(v, b, 1.0, permeability=1.5), "permeability"),
    (lambda v, b: evaluate(v, ["box"], 1.0), "blockers must be"),
    (lambda v, b: evaluate(v, None, 1.0), "blockers must be"),
    (lambda v, b: evaluate(v, [(b[0], np.eye(4) * 2)], 1.0), "rigid"),
    (lambda v, b: evaluate("vent", b, 1.0), "leak must be"),
    (lambda v, b: evaluate_nodes(np.zeros((2, 4)), b, 1.0), r"shape \(n, 3\)"),
    (lambda v, b: evaluate_nodes([[np.nan, 0, 0]], b, 1.0), "finite"),
])
def test_bad_input_raises_a_clear_value_error(call, message):
    vertices, faces = grid_surface(1, 1)
    with pytest.raises(ValueError, match=message):
        call(LeakageSurface(vertices, faces), [trimesh.creation.box()])
