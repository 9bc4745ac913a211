"""Feature edges of blockers and edge-to-edge distances."""

import numpy as np
import trimesh

from blockage import Blocker, reference
from blockage.edges import feature_edges, surface_edges

from blockage_scenes import grid_surface


def test_feature_edges_of_closed_smooth_open_and_sharp_meshes():
    assert len(feature_edges(*_arrays(trimesh.creation.box()))) == 12  # the 12 sharp edges, no diagonals
    assert len(feature_edges(*_arrays(trimesh.creation.icosphere(3)))) == 0
    vertices, faces = grid_surface(3, 3)
    assert len(feature_edges(vertices, faces)) == 12  # the boundary of a flat 3 x 3 grid
    creased = vertices.copy()
    creased[:, 2] = np.where(creased[:, 0] > 0.5, (creased[:, 0] - 0.5) * 2, 0.0)  # fold ~63 deg at x = 2/3
    assert len(feature_edges(creased, faces)) > 12
    assert len(feature_edges(creased, faces, angle_deg=80.0)) == 12


def test_surface_edges_of_quads_skip_diagonals():
    vertices, faces = grid_surface(2, 1, quads=True)
    assert len(surface_edges(faces, np.full(len(faces), 4))) == 7


def test_edge_distances_match_brute_force(rng):
    mesh = trimesh.creation.box(extents=(1.0, 2.0, 0.5))
    mesh.apply_transform(trimesh.transformations.random_rotation_matrix(rng.random(3)))
    blocker = Blocker(mesh)
    starts, ends = rng.normal(size=(300, 3)), rng.normal(size=(300, 3))
    feature = blocker.feature_edges
    truth = reference.nearest_segments(starts, ends, mesh.vertices[feature[:, 0]], mesh.vertices[feature[:, 1]])
    for cutoff in (0.05, 0.3, np.inf):
        fast = blocker.edge_distances(starts, ends, cutoff)
        inside = truth <= cutoff
        assert np.array_equal(fast <= cutoff, inside)
        assert np.array_equal(fast[inside], truth[inside])
        assert np.isinf(fast[~inside]).all()


def _arrays(mesh):
    return np.asarray(mesh.vertices), np.asarray(mesh.faces)
