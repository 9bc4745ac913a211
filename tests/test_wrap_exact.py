"""The exact wrapped volume of a translating convex body against the per-placement definition, and its fit."""
import numpy as np
import pytest
import trimesh

from cases.model.bodies import Body, DynamicMotion
from cases.model.wrap_exact import exact_wrap
from cases.model.wrap_fit import fit_wrap, overshoot
from cases.model.wrap_pieces import convex_planes
from cases.model.wrapped_volume import Wrapper
from cavity.volume import mesh_volume

AXIS = np.array([0.0, 0.0, -1.0])


@pytest.fixture(scope="module")
def scene():
    """A 40 mm icosphere (320 faces) 5 mm above a subdivided 0.2 m cube cavity, pushed down by s."""
    body = trimesh.creation.icosphere(subdivisions=2, radius=0.04)
    body.apply_transform(trimesh.transformations.random_rotation_matrix(np.random.default_rng(1).random(3)))
    body.apply_translation((0.003, -0.002, 0.145))  # no symmetry: no node is ever as near two planes for long
    cavity = trimesh.creation.box(extents=(0.2, 0.2, 0.2)).subdivide().subdivide().subdivide()
    planes = convex_planes(body.vertices, body.faces)
    exact = exact_wrap(planes, cavity.vertices, cavity.faces, cavity.vertex_faces, AXIS, 0.0, 0.06)
    return body, cavity, exact


def brute_force(body, cavity, s):
    """The per-placement definition: nodes the placed body would contain moved to their closest point on it
    (trimesh's closest point, exact enough at these sizes), then the divergence-theorem volume."""
    import blockage

    moving = Body("b", body, tuple(AXIS), DynamicMotion(1.0, 0.0, 0.0))
    wrapper = Wrapper([moving], lambda th: [(blockage.Blocker(body), moving.transform(th))])
    return mesh_volume(wrapper.place(np.asarray(cavity.vertices), s), cavity.faces)


def test_exact_volume_matches_the_per_placement_definition(scene):
    body, cavity, exact = scene
    v0 = mesh_volume(cavity.vertices, cavity.faces)
    s = np.linspace(0.0, 0.06, 25)[1:]
    want = np.array([brute_force(body, cavity, x) for x in s]) - v0
    # where a node is equally far from two body planes (here at s = 0.045) either closest point is the
    # definition's: the exact volume jumps there, and the brute force takes one of the two sides
    left, right = exact.value(s, side="left")[0], exact.value(s, side="right")[0]
    err = np.minimum(np.abs(left - want), np.abs(right - want))
    assert np.max(err) <= 1e-12 * v0, np.max(err)
    assert np.min(right) < -1e-5  # the body went in


def test_nothing_moves_before_first_contact(scene):
    _, _, exact = scene
    v, d = exact.value(np.linspace(0.0, 0.0049, 50))
    assert np.all(v == 0.0) and np.all(d == 0.0)


def test_fit_holds_its_bound_and_is_flat_before_contact(scene):
    _, cavity, exact = scene
    v0 = mesh_volume(cavity.vertices, cavity.faces)
    peak = float(np.max(np.abs(exact.value(exact.breaks)[1])))
    fit = fit_wrap(exact, 1e-9 * v0, 1e-6 * peak, 1e-3 * 0.06)
    p = fit.ppoly()
    s = np.linspace(0.0, 0.06, 60001)
    assert np.max(np.abs(p(s) - exact.value(s)[0])) <= fit.bound
    first = exact.breaks[np.argmax(np.any(exact.coef != 0.0, axis=1))]
    before = s[s <= first]
    assert np.all(p(before, 1) == 0.0)


def test_fit_against_the_per_placement_definition_within_its_bound(scene):
    """The fitted volume (what the run uses) against the old definition evaluated densely: within the bound."""
    body, cavity, exact = scene
    v0 = mesh_volume(cavity.vertices, cavity.faces)
    peak = float(np.max(np.abs(exact.value(exact.breaks)[1])))
    fit = fit_wrap(exact, 1e-9 * v0, 1e-6 * peak, 1e-3 * 0.06)
    s = np.linspace(0.0, 0.06, 241)
    want = np.array([brute_force(body, cavity, x) for x in s]) - v0
    assert np.max(np.abs(fit.ppoly()(s) - want)) <= fit.bound + 1e-12 * v0


def test_slope_does_not_ring_near_first_contact(scene):
    """Each piece's slope stays between its end slopes (to 1e-6 of the peak) where the geometry's is monotone."""
    _, cavity, exact = scene
    v0 = mesh_volume(cavity.vertices, cavity.faces)
    peak = float(np.max(np.abs(exact.value(exact.breaks)[1])))
    fit = fit_wrap(exact, 1e-9 * v0, 1e-6 * peak, 1e-3 * 0.06)
    k, y = fit.knots, fit.values
    near = (k[:-1] < 0.015)
    over = overshoot(k[:-1], k[1:], y[:-1], y[1:], fit.start, fit.end)[near]
    assert np.max(over) <= 1e-6 * peak, np.max(over) / peak


def test_a_concave_body_is_not_taken():
    mesh = trimesh.creation.annulus(r_min=0.02, r_max=0.04, height=0.01)
    assert convex_planes(mesh.vertices, mesh.faces) is None


@pytest.fixture(scope="module")
def impactor():
    """airbag_impactor's and airbag_impactor_dynamic's cushion volumes (headform in translation: the exact path)."""
    from cases.model.build import build_model
    from cases.run.library import CASES, HERE
    from cases.scene.files import load_scene

    return [build_model(load_scene(HERE / CASES[n])) for n in ("airbag_impactor", "airbag_impactor_dynamic")]


def test_library_volume_in_time_holds_its_bound(impactor):
    """Prescribed motion: V(t) within its bound of V0 + the exact ΔV(s(t)), s(t) the headform's table (in 13 ms
    to 65 mm, hold, out), whose breaks are among the knots."""
    from cases.run.library import HERE

    model, _ = impactor
    vt = model.network.cavities[0].volume
    body = model.geometry["bodies"]["headform"][0]
    cushion = trimesh.load(HERE / "meshes" / "cushion.ply")
    exact = exact_wrap(convex_planes(body.mesh.vertices, body.mesh.faces), cushion.vertices, cushion.faces,
                       cushion.vertex_faces, body.axis, 0.0, 0.065)
    t = np.linspace(0.0, 0.06, 20001)
    s = np.array([body.motion.displacement(x) for x in t])
    got = np.array([vt.at(x) for x in t])
    want = mesh_volume(cushion.vertices, cushion.faces) + exact.value(s)[0]
    assert np.max(np.abs(got - want)) <= vt.bound < 1e-4 * want.max()
    assert set(body.motion.breakpoints) <= set(vt.breakpoints)


def test_library_gas_force_is_flat_before_contact_and_does_not_ring(impactor):
    """dV/ds is exactly 0 until the headform (5 mm above the cushion) first touches it; then on every piece of the
    first 10 mm of contact the slope stays within its end slopes, or within what the geometry's own slope does
    inside the piece, to 1e-6 of the peak (the 401-sample spline rang there by 1e-3 of the peak)."""
    import cases.model.wrapped_volume as wv
    from cases.model.wrap_fit import excursion, smoothed_jumps
    from cases.run.library import HERE

    _, dynamic = impactor
    vol = dynamic.network.cavities[0].volume
    body = dynamic.geometry["bodies"]["headform"][0]
    cushion = trimesh.load(HERE / "meshes" / "cushion.ply")
    planes = convex_planes(body.mesh.vertices, body.mesh.faces)
    exact = exact_wrap(planes, cushion.vertices, cushion.faces, cushion.vertex_faces, body.axis, 0.0, 0.02)
    target, _ = smoothed_jumps(exact, wv.JUMP_WIDTH * float(body.mesh.edges_unique_length.mean()))
    first = exact.breaks[np.argmax(np.any(exact.coef != 0.0, axis=1))]
    assert 0.004 < first < 0.006
    pp = vol.spline
    assert np.all(pp(np.linspace(vol.lo, first, 1000)[:-1], 1) == 0.0)
    peak = float(np.max(np.abs(pp(np.linspace(0.0, 0.075, 20001), 1))))  # the headform stops at 73.5 mm
    slopes = np.c_[target.value(target.breaks, "left")[1], target.value(target.breaks, "right")[1]].ravel()
    k = pp.x[(pp.x >= first) & (pp.x <= first + 0.01)]
    for a, b in zip(k[:-1], k[1:]):
        d = pp(np.linspace(a, b, 401)[:-1], 1)
        c = pp.c[:, np.searchsorted(pp.x, a, side="right") - 1]
        d0, d1 = c[2], (3.0 * c[0] * (b - a) + 2.0 * c[1]) * (b - a) + c[2]  # the piece's own end slopes
        room = max(excursion(slopes, target.breaks, np.array([a]), np.array([b]), np.array([d0]),
                             np.array([d1]))[0], 0.0)
        beyond = max(np.max(d) - max(d0, d1), min(d0, d1) - np.min(d), 0.0)
        assert beyond <= room + 1e-6 * peak, (a, b, beyond / peak, room / peak)
    assert len(k) >= 5
