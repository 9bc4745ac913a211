"""Penetration counts as contact: nodes inside a closed blocker are active at any depth (blockage.sides)."""

import numpy as np
import trimesh

from blockage import LeakageSurface, evaluate, evaluate_nodes
from blockage.reference import evaluate_nodes_reference, evaluate_reference, winding_numbers

from blockage_scenes import grid_surface


def test_box_half_through_a_vent_blocks_the_nodes_inside_it():
    vertices, faces = grid_surface(10, 10, size=(0.02, 0.02), quads=True)  # 20 mm vent, 2 mm spacing, z = 0
    vent = LeakageSurface(vertices - [0.01, 0.01, 0.0], faces)
    box = trimesh.creation.box(extents=(0.0101, 0.03, 0.01))  # x in [-5.05, 5.05] mm, through the vent plane
    result = evaluate(vent, [box], 1e-4)
    inside = np.abs(vent.vertices[:, 0]) < 0.00505
    assert inside.sum() == 5 * 11  # the columns x = -4, -2, 0, 2, 4 mm: 5 mm deep inside the box
    np.testing.assert_array_equal(result.active_nodes, inside)
    assert not evaluate(vent, [box], 1e-4, penetration=False).active_nodes.any()  # 5 mm from any face
    slow = evaluate_reference(vent, [box], 1e-4)
    np.testing.assert_array_equal(slow.active_nodes, inside)
    assert result.obstruction_area == slow.obstruction_area


def test_inside_test_equals_the_winding_number_for_rotated_closed_bodies():
    rng = np.random.default_rng(3)
    for mesh in (trimesh.creation.icosphere(subdivisions=2, radius=0.05), trimesh.creation.box(extents=(0.1, 0.04, 0.06)),
                 trimesh.creation.capsule(height=0.05, radius=0.02)):
        T = trimesh.transformations.random_rotation_matrix(rng.random(3))
        T[:3, 3] = rng.normal(0.0, 0.01, 3)
        points = rng.uniform(-0.08, 0.08, (400, 3))
        fast = evaluate_nodes(points, [(mesh, T)], 1e-6)
        world = trimesh.transform_points(mesh.vertices, T)
        truth = winding_numbers(points, world, mesh.faces) > 0.5
        np.testing.assert_array_equal(fast.active_nodes, truth | (fast.distances <= 1e-6))
        np.testing.assert_array_equal(evaluate_nodes_reference(points, [(mesh, T)], 1e-6)[0], fast.active_nodes)


def test_an_open_sheet_blocks_behind_it_only_up_to_the_given_depth():
    vent = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    sheet = trimesh.Trimesh([[-1.0, -1, 0.01], [0.5, -1, 0.01], [0.5, 2, 0.01], [-1, 2, 0.01]], [[0, 1, 2], [0, 2, 3]])
    assert not evaluate(vent, [sheet], 1e-3).active_nodes.any()  # distance 10 mm: not in contact
    behind = evaluate(vent, [sheet], 1e-3, penetration=0.02).active_nodes  # normal +z: the vent is behind it
    assert behind.tolist() == [True, False, False, True]  # x = 1 lies beside the sheet's edge, not behind it
    assert evaluate_reference(vent, [sheet], 1e-3, penetration=0.02).active_nodes.tolist() == behind.tolist()
    assert not evaluate(vent, [sheet], 1e-3, penetration=0.005).active_nodes.any()
    flipped = trimesh.Trimesh(sheet.vertices, sheet.faces[:, ::-1])
    assert not evaluate(vent, [flipped], 1e-3, penetration=0.02).active_nodes.any()  # in front of it
