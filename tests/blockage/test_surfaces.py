"""Leakage surfaces: construction from meshes, selections, files; moving; validation."""

import numpy as np
import pytest
import trimesh

from blockage import LeakageSurface

from blockage_scenes import grid_surface


def test_from_trimesh_keeps_every_vertex_and_the_source():
    mesh = trimesh.creation.icosphere(1)
    surface = LeakageSurface.from_trimesh(mesh)
    assert surface.source is mesh
    assert np.array_equal(surface.source_vertices, np.arange(len(mesh.vertices)))
    assert surface.total_area == pytest.approx(mesh.area, rel=1e-12)
    assert (surface.face_sizes == 3).all() and surface.faces.shape == (len(mesh.faces), 3)


def test_selection_by_faces_compacts_the_vertices():
    mesh = trimesh.creation.icosphere(2)
    surface = LeakageSurface.from_faces(mesh, [3, 7, 8])
    assert len(surface.faces) == 3
    np.testing.assert_array_equal(surface.vertices, mesh.vertices[surface.source_vertices])
    np.testing.assert_array_equal(surface.source_vertices[surface.faces], mesh.faces[[3, 7, 8]])
    assert surface.total_area == pytest.approx(mesh.area_faces[[3, 7, 8]].sum(), rel=1e-12)


def test_selection_by_box_and_sphere_regions():
    mesh = trimesh.creation.icosphere(3)
    centroids = mesh.triangles_center
    cap = LeakageSurface.from_region(mesh, sphere=([0.0, 0.0, 1.0], 0.4))
    expected = np.linalg.norm(centroids - [0, 0, 1], axis=1) <= 0.4
    assert len(cap.faces) == expected.sum()
    band = LeakageSurface.from_region(mesh, box=([-2, -2, -0.1], [2, 2, 0.1]))
    assert len(band.faces) == (np.abs(centroids[:, 2]) <= 0.1).sum()
    with pytest.raises(ValueError, match="exactly one"):
        LeakageSurface.from_region(mesh)
    with pytest.raises(ValueError, match="no face"):
        LeakageSurface.from_region(mesh, sphere=([5.0, 5.0, 5.0], 0.1))


def test_padded_and_listed_quads_and_triangles():
    vertices = [[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]]
    listed = LeakageSurface(vertices, [[0, 1, 2, 3], [1, 4, 2]])
    padded = LeakageSurface(vertices, np.array([[0, 1, 2, 3], [1, 4, 2, -1]]))
    assert np.array_equal(listed.faces, padded.faces)
    assert listed.face_sizes.tolist() == [4, 3]
    assert listed.edges.tolist() == [[0, 1], [0, 3], [1, 2], [1, 4], [2, 3], [2, 4]]


def test_quad_area_is_exact_for_planar_and_vector_area_for_warped():
    vertices, faces = grid_surface(3, 2, size=(3.0, 2.0), quads=True)
    assert LeakageSurface(vertices, faces).face_areas.tolist() == [1.0] * 6
    warped = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0.5], [0, 1, 0]], [[0, 1, 2, 3]])
    assert warped.face_areas[0] == pytest.approx(0.5 * np.linalg.norm(np.cross([1, 1, 0.5], [-1, 1, 0])))


def test_meshio_higher_order_cells_use_corner_nodes():
    meshio = pytest.importorskip("meshio")
    points = np.array([[0.0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]])  # 2-D points are padded with z = 0
    surface = LeakageSurface.from_meshio(meshio.Mesh(points, [("triangle6", np.array([[0, 1, 2, 3, 4, 5]]))]))
    assert surface.total_area == pytest.approx(2.0) and len(surface.vertices) == 3
    with pytest.raises(ValueError, match="no triangle or quad"):
        LeakageSurface.from_meshio(meshio.Mesh(points, [("line", np.array([[0, 1]]))]))


def test_with_vertices_and_transformed_share_topology():
    vertices, faces = grid_surface(2, 2)
    surface = LeakageSurface(vertices, faces)
    stretched = surface.with_vertices(vertices * [2.0, 1.0, 1.0])
    assert stretched.total_area == pytest.approx(2.0) and stretched.faces is surface.faces
    turn = trimesh.transformations.rotation_matrix(0.3, [1, 1, 0], point=[5, 0, 0])
    assert surface.transformed(turn).total_area == pytest.approx(surface.total_area, rel=1e-14)
    with pytest.raises(ValueError, match="with_vertices"):
        surface.with_vertices(vertices[:3])


@pytest.mark.parametrize("faces, message", [
    ([[0, 1, 9]], r"in \[0, 3\)"), ([[0, 1]], "shape"), (np.array([[0, 1, 2.5]]), "integers"),
    ([[0, 1, 2], [0, 1, 2, 0, 1]], "3 or 4"), ([[-1, 0, 1]], r"in \[0, 3\)")])
def test_bad_faces_raise(faces, message):
    with pytest.raises(ValueError, match=message):
        LeakageSurface(np.eye(3), faces)


def test_bad_selection_raises():
    mesh = trimesh.creation.box()
    with pytest.raises(ValueError, match=r"face indices must lie in \[0, 12\)"):
        LeakageSurface.from_faces(mesh, [0, 12])
    with pytest.raises(ValueError, match="vertices"):
        LeakageSurface(np.zeros((3, 2)), [[0, 1, 2]])
