"""The software renderer of the pictures (cases.results.raster): its id buffer covers what the faces project onto,
a pixel's depth is the depth of the face's plane along its ray, the nearer face wins, and a body's silhouette lies
on its rim as seen from the camera."""
import numpy as np
import pytest

from cases.results.raster import Camera, face_ids, face_normals, plane_depth, silhouette_edges, triangles_of
from cases.results.render_style import VIEW_ANGLE

SIZE = (200, 150)
CAMERA = [(0.0, 0.0, 1.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)]  # 1 m above the origin, looking down -z


def square(half, z):
    return np.array([[-half, -half, z], [half, -half, z], [half, half, z], [-half, half, z]]), np.array([[0, 1, 2, 3]])


def draw(cam, vertices, faces, order=None):
    f, valid = triangles_of(faces)
    corners = cam.project(vertices)[np.where(valid, f, f[:, :1]), :2]
    return face_ids((cam.height, cam.width), corners, valid, np.arange(len(f)) if order is None else order)


def test_a_square_covers_its_projected_area():
    cam = Camera(CAMERA, VIEW_ANGLE, SIZE)
    vertices, faces = square(0.1, 0.0)
    ids = draw(cam, vertices, faces)
    side = 0.2 / (2.0 * np.tan(np.radians(VIEW_ANGLE) / 2.0)) * SIZE[1]  # [px] at 1 m
    assert abs(np.count_nonzero(ids == 1) - side ** 2) <= 4 * side + 4  # within the boundary pixels
    assert set(np.unique(ids)) == {0, 1}


def test_pixel_depth_is_the_planes_depth_along_each_ray():
    cam = Camera(CAMERA, VIEW_ANGLE, SIZE)
    vertices = np.array([[-0.2, -0.2, 0.0], [0.2, -0.2, 0.1], [0.2, 0.2, 0.1], [-0.2, 0.2, 0.0]])  # tilted in x
    faces = np.array([[0, 1, 2, 3]])
    ids = draw(cam, vertices, faces)
    normals = face_normals(vertices, faces)
    depth = plane_depth(ids, cam.rays(), cam.eye, vertices[[0]], normals, np.array([1.0]))
    ys, xs = np.nonzero(ids)
    # brute force: the plane z = 0.25 (x + 0.2) seen through the pixel centre
    ndc_x = ((xs + 0.5) / SIZE[0] * 2 - 1) * cam.half * SIZE[0] / SIZE[1]
    expected = (1.0 - 0.05) / (1.0 + 0.25 * ndc_x)  # depth d: z = 1 - d, x = d ndc_x
    np.testing.assert_allclose(depth[ys, xs], expected, rtol=1e-12)
    assert np.isinf(depth[ids == 0]).all()


@pytest.mark.parametrize("order", [[0, 1], [1, 0]])
def test_faces_drawn_later_cover_earlier_ones(order):
    cam = Camera(CAMERA, VIEW_ANGLE, SIZE)
    far, faces = square(0.1, 0.0)
    near, _ = square(0.05, 0.2)
    ids = draw(cam, np.concatenate([far, near]), np.concatenate([faces, faces + 4]), np.array(order))
    centre = ids[SIZE[1] // 2, SIZE[0] // 2]
    assert centre == order[-1] + 1


def test_the_silhouette_of_a_sphere_is_its_rim():
    trimesh = pytest.importorskip("trimesh")
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=0.05)
    eye = np.array([0.0, 0.0, 10.0])  # far: the rim is the equator z = 0
    centroids = sphere.vertices[sphere.faces].mean(axis=1)
    front = np.einsum("ij,ij->i", face_normals(sphere.vertices, sphere.faces), eye - centroids) > 0
    edges = silhouette_edges(sphere.faces, front)
    assert len(edges) >= 40  # a closed loop round the sphere
    z = sphere.vertices[edges.ravel(), 2]
    assert np.all(np.abs(z) < 0.2 * 0.05)
    assert not len(silhouette_edges(sphere.faces, np.ones(len(sphere.faces), bool)))  # all front: no rim
