"""Area laws: A_eb = A_e N_c / N_e, obstruction, leak area, effective area, node fraction."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from blockage import areas


@settings(max_examples=50, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 1.0), st.none() | st.floats(1e-6, 10.0))
def test_area_bounds_and_the_closed_forms(seed, permeability, effective):
    rng = np.random.default_rng(seed)
    n_faces = int(rng.integers(1, 30))
    sizes = rng.choice([3, 4], n_faces)
    faces = np.where(np.arange(4)[None] < sizes[:, None], rng.integers(0, 20, (n_faces, 4)), -1)
    active = rng.random(20) < 0.4
    face_area = rng.random(n_faces)
    counts = areas.active_counts(active, faces, sizes)
    expected = [sum(active[v] for v in row[:k]) for row, k in zip(faces, sizes)]
    assert counts.tolist() == expected
    blocked = areas.blocked_face_areas(face_area, counts, sizes)
    assert np.all((blocked >= 0) & (blocked <= face_area))
    total = float(face_area.sum())
    obstruction = areas.obstruction_area(blocked)
    left = areas.leak_area(total, obstruction, effective, permeability)
    if effective is None:
        assert left == pytest.approx(total - (1 - permeability) * obstruction, rel=1e-12, abs=1e-15)
        assert -1e-12 <= left <= total + 1e-12
    else:
        assert left == pytest.approx(effective * (1 - (1 - permeability) * obstruction / total), rel=1e-12)


def test_fully_blocked_and_unblocked_surfaces():
    faces, sizes = np.array([[0, 1, 2, 3], [1, 4, 2, -1]]), np.array([4, 3])
    face_area = np.array([1.0, 0.5])
    for active, blocked in ((np.ones(5, bool), 1.5), (np.zeros(5, bool), 0.0)):
        counts = areas.active_counts(active, faces, sizes)
        assert areas.obstruction_area(areas.blocked_face_areas(face_area, counts, sizes)) == blocked
    assert areas.leak_area(1.5, 1.5) == 0.0 and areas.leak_area(1.5, 1.5, effective_area=3.0) == 0.0
    assert areas.leak_area(0.0, 0.0, effective_area=3.0) == 3.0  # empty surface: nothing to block


def test_node_based_fraction():
    assert areas.blocked_fraction(np.array([True, True, False, False, False])) == 0.4
