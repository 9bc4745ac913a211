"""Helpers for the blockage tests: small meshes and random-scene strategies (imported by name)."""

import numpy as np
import trimesh
from hypothesis import strategies as st


def grid_surface(nx, ny, size=(1.0, 1.0), z=0.0, quads=False):
    """A flat grid in the plane z = const: vertices and triangles or quads."""
    x = np.linspace(0.0, size[0], nx + 1)
    y = np.linspace(0.0, size[1], ny + 1)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    vertices = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, z)])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    a = (i * (ny + 1) + j).ravel()
    b, c, d = a + ny + 1, a + ny + 2, a + 1
    if quads:
        return vertices, np.column_stack([a, b, c, d])
    return vertices, np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def random_rigid(rng, translation=1.0):
    """A random rotation and translation as a 4x4 matrix."""
    matrix = trimesh.transformations.random_rotation_matrix(rng.random(3))
    matrix[:3, 3] = rng.uniform(-translation, translation, 3)
    return matrix


@st.composite
def random_meshes(draw, max_vertices=12, max_faces=16, scale=1.0):
    """Random triangle soups, including repeated and collinear vertices (degenerate faces)."""
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    n_vertices = draw(st.integers(3, max_vertices))
    vertices = rng.normal(size=(n_vertices, 3)) * scale
    if draw(st.booleans()):  # snap to a coarse lattice: exact coincidences and collinear triples
        vertices = np.round(vertices * 2.0) / 2.0
    faces = rng.integers(0, n_vertices, size=(draw(st.integers(1, max_faces)), 3))
    return trimesh.Trimesh(vertices, faces, process=False)
