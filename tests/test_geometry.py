"""Mesh volume by the divergence theorem: exact for polyhedra, second-order convergence on spheres."""
import math

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings, strategies as st

from cavity.volume import MeshError, closed_mesh_volume, mesh_volume


def test_box_volume_exact():
    box = trimesh.creation.box(extents=(0.3, 0.2, 0.1))
    assert mesh_volume(box.vertices, box.faces) == pytest.approx(0.006, rel=1e-14)


def test_sphere_volume_converges_at_second_order():
    r, exact = 0.25, 4.0 / 3.0 * math.pi * 0.25**3
    h, err = [], []
    for n in range(2, 7):
        m = trimesh.creation.icosphere(subdivisions=n, radius=r)
        err.append(abs(mesh_volume(m.vertices, m.faces) - exact) / exact)
        h.append(m.edges_unique_length.mean())
    rates = np.diff(np.log(err)) / np.diff(np.log(h))
    assert np.all(np.abs(rates[-3:] - 2.0) < 0.05), rates


@settings(max_examples=30, deadline=None)
@given(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5), st.floats(0.1, 3.0), st.floats(0, 2 * math.pi))
def test_volume_invariant_under_rigid_motion_and_scales_cubically(dx, dy, dz, s, angle):
    m = trimesh.creation.icosphere(subdivisions=2, radius=0.1)
    v0 = mesh_volume(m.vertices, m.faces)
    rot = trimesh.transformations.rotation_matrix(angle, [1, 2, 3])
    x = (m.vertices @ rot[:3, :3].T) * s + [dx, dy, dz]
    assert mesh_volume(x, m.faces) == pytest.approx(v0 * s**3, rel=1e-11)


def test_inside_out_and_open_meshes_are_errors():
    m = trimesh.creation.icosphere(subdivisions=1)
    m.invert()
    with pytest.raises(MeshError, match="inwards"):
        closed_mesh_volume(m)
    m = trimesh.creation.icosphere(subdivisions=1)
    m.update_faces(np.arange(len(m.faces)) > 0)
    with pytest.raises(MeshError, match="not closed"):
        closed_mesh_volume(m)
