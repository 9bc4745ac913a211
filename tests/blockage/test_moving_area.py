"""The area of a surface moving between frames (blockage.moving_area) against face areas of the interpolated nodes."""
import numpy as np
import pytest

from blockage.areas import active_counts, face_areas, leak_area
from blockage.moving_area import area_coefficients, moving_areas, moving_leak_area, pack


def mixed_surface(rng, n_side=4):
    """A warped grid of quads, every other one split into two triangles: (vertices (n, 3), faces (m, 4), sizes)."""
    xs = np.linspace(0.0, 1.0, n_side + 1)
    x, y = np.meshgrid(xs, xs)
    vertices = np.column_stack([x.ravel(), y.ravel(), 0.1 * rng.standard_normal(x.size)])
    faces, sizes = [], []
    for j in range(n_side):
        for i in range(n_side):
            a, b, c, d = j * (n_side + 1) + i, j * (n_side + 1) + i + 1, (j + 1) * (n_side + 1) + i + 1, \
                (j + 1) * (n_side + 1) + i
            if (i + j) % 2:
                faces += [[a, b, c, d]]
                sizes += [4]
            else:
                faces += [[a, b, c, -1], [a, c, d, -1]]
                sizes += [3, 3]
    return vertices, np.array(faces), np.array(sizes)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_moving_areas_equal_face_areas_of_the_interpolated_nodes_for_every_active_set(seed):
    """Naive (nodes interpolated, blockage.areas on them) against the pack, at random times inside and beyond the
    frames, with the cursor sent back and forth over random crossings."""
    rng = np.random.default_rng(seed)
    x0, faces, sizes = mixed_surface(rng)
    n = len(x0)
    times = np.array([0.0, 0.3, 0.5, 1.0])
    frames = np.stack([x0] + [x0 * rng.uniform(0.5, 1.5, 3) + 0.2 * rng.standard_normal(x0.shape)
                              for _ in times[1:]])
    initial = rng.random(n) < 0.3
    node = rng.integers(0, n, 40)
    active, states, prev = initial.copy(), [], []
    for k in node:  # each crossing flips its node
        prev.append(active[k])
        active[k] = not active[k]
        states.append(active[k])
    delta = np.array(states, dtype=int) - np.array(prev, dtype=int)
    applied = np.concatenate([[0], np.sort(rng.choice(np.arange(1, 41), 9, replace=False))])
    p = pack(times, area_coefficients(times, frames, faces, sizes), faces, sizes, initial, applied, node, delta,
             None, 0.25)
    for i, t in zip(rng.integers(-1, len(applied), 60), rng.uniform(-0.2, 1.2, 60)):
        k = min(max(np.searchsorted(times, t, side="right") - 1, 0), len(times) - 2)
        w = min(max((t - times[k]) / (times[k + 1] - times[k]), 0.0), 1.0)
        moved = (1 - w) * frames[k] + w * frames[k + 1]
        area = face_areas(moved, faces, sizes)
        on = initial.copy()
        if i >= 0:
            on[node[:applied[i]]] = np.array(states, dtype=bool)[:applied[i]]
        else:
            on[:] = False
        blocked = float(np.sum(area * active_counts(on, faces, sizes) / sizes))
        total, obstruction = moving_areas(p, int(i), float(t))
        assert total == pytest.approx(area.sum(), rel=1e-13)
        assert obstruction == pytest.approx(blocked, rel=1e-13, abs=1e-15)
        assert moving_leak_area(p, int(i), float(t)) == pytest.approx(leak_area(area.sum(), blocked,
                                                                                permeability=0.25), rel=1e-12)


def test_a_fully_blocked_surface_leaks_nothing_and_an_effective_area_keeps_only_the_fraction():
    """All nodes active: exactly zero (the ratio N_c/N_e is 1); with an effective area the area is A_eff·(1 − f)
    whatever the stretch, here a uniform one (f stays 1/3)."""
    v0 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    faces, sizes = np.array([[0, 1, 2, -1]]), np.array([3])
    coef = area_coefficients([0.0, 1.0], np.stack([v0, 3 * v0]), faces, sizes)
    full = pack([0.0, 1.0], coef, faces, sizes, np.ones(3, bool), np.array([0]), np.zeros(0), np.zeros(0))
    assert moving_leak_area(full, 0, 0.37) == 0.0
    third = pack([0.0, 1.0], coef, faces, sizes, np.array([1, 0, 0], bool), np.array([0]), np.zeros(0),
                 np.zeros(0), 2e-4)
    assert [moving_leak_area(third, 0, t) for t in (0.0, 0.5, 2.0)] == pytest.approx([2e-4 * 2 / 3] * 3, rel=1e-15)
    assert moving_leak_area(third, -1, 0.5) == 2e-4
