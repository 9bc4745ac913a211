"""Contact intervals in closed form: a blade sliding over a vent with its gap inside the tolerance, brief contacts
at any gap, the segment-against-triangle intervals against brute force, and contact at gap 0."""
import math

import numpy as np
import pytest

from cases.model.build import build_model
from cases.model.segment_contact import triangle_intervals
from cases.scene.files import scene_from_dict
from tests.scenes import tank
from tests.test_blockage_over_time import _node_weights, grid_vent, track_blocked_area_time

TOL = 30e-6  # contact tolerance [m]


def blade_scene(folder, gap, length, speed=1.0, vent="vent.obj", rows=20001, nodes=None):
    """A box ``length`` [m] long in x, 40 mm wide, its underside ``gap`` [m] above the 20 mm vent in z = 0,
    sliding along +x at ``speed`` [m/s] so that its centre passes x = 0.01 m at t = 0.5 s (run 1 s)."""
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 1.0, "output_interval": 1.0 / (rows - 1)}
    start = 0.01 - 0.5 * speed
    data["body"] = [{"name": "blade", "box": [start, 0.01, gap + 0.001, length, 0.04, 0.002], "axis": [1, 0, 0],
                     "velocity": speed}]
    where = {"leakage_nodes": nodes} if nodes else {"leakage_surface": vent}
    data["exchange"] = [{"name": "vent", "from": "tank", **where, "blocked_by": ["blade"],
                         "contact_tolerance": TOL, "effective_area": 1e-4}]
    return scene_from_dict(data, folder / "scene.toml")


def blade_reference(x, box_lo, box_hi, gap, speed):
    """Exact contact interval [t_in, t_out] [s] of a node at x under the sliding box (its x range at t = 0 is
    [box_lo, box_hi], moved by speed·t): |x − box| ≤ √(tol² − gap²) in x, as the underside is flat."""
    reach = math.sqrt(TOL ** 2 - gap ** 2)
    return (x - box_hi - reach) / speed, (x - box_lo + reach) / speed


def test_a_blade_sliding_within_the_tolerance_blocks_what_brute_force_does(tmp_path):
    grid_vent(tmp_path / "vent.obj", n=10)
    gap, length = 18e-6, 1e-4
    model = build_model(blade_scene(tmp_path, gap, length))
    assert not any("not certified" in str(w) or "hover" in str(w) for w in model.warnings)
    track = model.network.areas[0].track
    surface, _ = model.geometry["surfaces"][0]
    vertices = model.geometry["bodies"]["blade"][1].vertices
    box, gap = vertices[:, 0], float(vertices[:, 2].min())  # the gap the float vertices give
    t_in, t_out = blade_reference(surface.vertices[:, 0], box.min(), box.max(), gap, 1.0)
    reference = float(np.sum(_node_weights(surface) * (t_out - t_in)))  # every node in contact once
    assert track.source.unresolved == 0
    assert track_blocked_area_time(track, 1.0) == pytest.approx(reference, rel=1e-6)
    assert 1e-4 < (t_out - t_in).min() < 2e-4  # each node in contact for about 1e-4 of the run


@pytest.mark.parametrize("gap", [0.0, 18e-6, TOL * (1 - 1e-6), TOL * (1 - 1e-12)])
def test_a_brief_contact_while_sliding_parallel_is_found_and_timed(tmp_path, gap):
    """One node; the blade's contact with it lasts 1e-6 of the 1 s run whatever its gap below the tolerance."""
    (tmp_path / "node.csv").write_text("x,y,z\n0.01,0.01,0.0\n")
    length = 2e-6
    speed = (length + 2 * math.sqrt(TOL ** 2 - gap ** 2)) / 1e-6
    model = build_model(blade_scene(tmp_path, gap, length, speed, nodes="node.csv"))
    found = model.network.areas[0].track.source
    vertices = model.geometry["bodies"]["blade"][1].vertices
    box, actual = vertices[:, 0], float(vertices[:, 2].min())  # the gap the float vertices give
    t_in, t_out = blade_reference(0.01, box.min(), box.max(), actual, speed)
    assert t_out - t_in == pytest.approx(1e-6, rel=1e-6)
    assert found.state.tolist() == [True, False] and found.unresolved == 0
    np.testing.assert_allclose(found.theta, [t_in, t_out], rtol=0, atol=1e-12)


def _distances(p, tri):
    """(k,) distances of points p (k, 3) to a triangle by brute force: the plane where the projection is inside,
    else the nearest of the three edges."""
    a, b, c = tri
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n)
    h = (p - a) @ n
    q = p - h[:, None] * n
    inside = np.all([np.cross(v1 - v0, q - v0) @ n >= 0 for v0, v1 in ((a, b), (b, c), (c, a))], axis=0)
    edge = np.min([np.linalg.norm(p - v0 - np.clip((p - v0) @ (v1 - v0) / ((v1 - v0) @ (v1 - v0)), 0, 1)[:, None]
                                  * (v1 - v0), axis=1) for v0, v1 in ((a, b), (b, c), (c, a))], axis=0)
    return np.where(inside, np.abs(h), edge)


def test_segment_intervals_match_dense_sampling_and_end_at_the_radius():
    rng = np.random.default_rng(7)
    ts = np.linspace(0.0, 1.0, 10001)
    for _ in range(200):
        tri = rng.normal(size=(1, 3, 3))
        P, D, r = rng.normal(size=(1, 3)) * 1.5, rng.normal(size=(1, 3)) * 3, abs(rng.normal()) * 0.7
        lo, hi = triangle_intervals(P, D, tri, r)
        inside = _distances(P[0] + ts[:, None] * D[0], tri[0]) <= r
        predicted = (ts >= lo[0]) & (ts <= hi[0])
        assert np.count_nonzero(inside != predicted) <= 2  # sampling can only disagree next to an end
        ends = np.array([t for t in (lo[0], hi[0]) if 0.0 < t < 1.0])
        if ends.size:
            np.testing.assert_allclose(_distances(P[0] + ends[:, None] * D[0], tri[0]), r, rtol=1e-9)


def test_touching_at_gap_zero_is_contact():
    tri = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    at_rest = triangle_intervals(np.array([[0.2, 0.2, 0.0]]), np.zeros((1, 3)), tri, 0.0)
    assert (at_rest[0][0], at_rest[1][0]) == (0.0, 1.0)
    sliding = triangle_intervals(np.array([[-1.0, 0.2, 0.0]]), np.array([[2.0, 0.0, 0.0]]), tri, 0.0)
    assert (sliding[0][0], sliding[1][0]) == pytest.approx((0.5, 0.9), abs=1e-15)  # x in [0, 0.8]
    crossing = triangle_intervals(np.array([[0.2, 0.2, -1.0]]), np.array([[0.0, 0.0, 2.0]]), tri, 0.0)
    assert crossing[0][0] == crossing[1][0] == 0.5  # an instant
    above = triangle_intervals(np.array([[0.2, 0.2, 1e-300]]), np.zeros((1, 3)), tri, 0.0)
    assert above[0][0] > above[1][0]


def test_a_node_slipping_behind_an_open_strip_around_its_edge_is_found(tmp_path):
    """An open strip x in [0, 0.01] (normal +z) slides along −x over a node 0.25 m below it: the node is behind
    the strip (within the 0.3 m penetration depth) while under it, 0.25 m from the surface, far outside the 1 mm
    tolerance; the gap jumps sign at the strip's edges, so only the edges' instants decide the contact."""
    strip = "v 0 -1 0\nv 0.01 -1 0\nv 0.01 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"
    (tmp_path / "strip.obj").write_text(strip)
    (tmp_path / "node.csv").write_text("x,y,z\n0.3,0.0,-0.25\n")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 1.0, "output_interval": 0.01}
    data["body"] = [{"name": "strip", "mesh": "strip.obj", "axis": [1, 0, 0], "velocity": 0.8}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_nodes": "node.csv", "blocked_by": ["strip"],
                         "contact_tolerance": 1e-3, "penetration_depth": 0.3, "effective_area": 1e-4}]
    found = build_model(scene_from_dict(data, tmp_path / "scene.toml")).network.areas[0].track.source
    assert found.state.tolist() == [True, False]
    np.testing.assert_allclose(found.theta, [0.29 / 0.8, 0.3 / 0.8], rtol=1e-14)


def rotating_blade(folder):
    """A 60 mm wide blade, underside 18 µm above z = 0, turning 90° about z in 1 s over one node at 45°: the gap
    stays inside the tolerance while it passes (0.56 s), which the speed bound cannot settle."""
    (folder / "turn.csv").write_text("t,deg\n0,0\n1,90\n")
    (folder / "node.csv").write_text("x,y,z,area\n0.05,0.05,0.0,1e-6\n")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 1.0, "output_interval": 0.01}
    data["body"] = [{"name": "blade", "box": [0.1, 0.0, 18e-6 + 0.001, 0.2, 0.06, 0.002], "axis": [1, 0, 0],
                     "rotation_table": "turn.csv"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_nodes": "node.csv", "blocked_by": ["blade"],
                         "contact_tolerance": TOL}]
    return scene_from_dict(data, folder / "scene.toml")


def test_a_rotating_blade_is_timed_by_chords_of_certified_deviation(tmp_path):
    model = build_model(rotating_blade(tmp_path))
    found = model.network.areas[0].track.source
    assert not any("certified" in str(w) for w in model.warnings) and found.unresolved == 0
    gap = float(model.geometry["bodies"]["blade"][1].vertices[:, 2].min())
    half = math.asin((0.03 + math.sqrt(TOL ** 2 - gap ** 2)) / math.hypot(0.05, 0.05)) / math.radians(90.0)
    assert found.state.tolist() == [True, False]
    np.testing.assert_allclose(found.theta, [0.5 - half, 0.5 + half], rtol=0, atol=1e-12)


def deforming_blade(folder, strict=False, data_only=False):
    """A 0.5 m long blade given as a vertex trajectory (a deforming body, bisected only) sliding at 1 m/s with its
    underside 18 µm over one node: in contact for about 0.5 s with the gap inside the tolerance."""
    import trimesh

    box = trimesh.creation.box(extents=(0.5, 0.04, 0.002))
    box.apply_translation((-0.5, 0.01, 18e-6 + 0.001))
    box.export(folder / "blade.ply")
    v = np.asarray(box.vertices)
    np.savez(folder / "blade.npz", times=np.array([0.0, 1.0]), vertices=np.stack([v, v + [1.0, 0.0, 0.0]]))
    (folder / "node.csv").write_text("x,y,z,area\n0.01,0.01,0.0,1e-6\n")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 1.0, "output_interval": 0.01}
    data["blockage"] = {"strict": strict}
    data["body"] = [{"name": "blade", "mesh": "blade.ply", "vertex_trajectory": "blade.npz"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_nodes": "node.csv", "blocked_by": ["blade"],
                         "contact_tolerance": TOL}]
    return data if data_only else scene_from_dict(data, folder / "scene.toml")


def test_an_uncertified_contact_names_its_node_and_bounds_what_is_at_stake(tmp_path):
    model = build_model(deforming_blade(tmp_path))
    found = model.network.areas[0].track.source
    message = " ".join(str(w) for w in model.warnings)
    assert "not certified" in message and "(0)" in message
    reach = math.sqrt(TOL ** 2 - 18e-6 ** 2)
    duration = 0.5 + 2 * reach  # exact contact time [s] at 1 m/s
    edges = np.concatenate([[0.0], found.theta, [1.0]])
    states = np.concatenate([found.initial[:1], found.state])
    blocked = float(np.sum(np.diff(edges)[states])) * 1e-6
    stake = float(found.uncertain[0]) * 1e-6  # node area 1e-6 m^2
    assert 0.0 < stake and abs(blocked - duration * 1e-6) <= stake  # the bound holds what was missed
    assert f"{stake:.3g} m^2*s" in message


def test_strict_turns_an_uncertified_contact_into_an_error(tmp_path):
    from cases.scene.errors import SceneError

    with pytest.raises(SceneError, match="strict"):
        build_model(deforming_blade(tmp_path, strict=True))


def test_run_strict_on_the_command_line_and_in_python(tmp_path, capsys):
    import ventsim
    from cases.cli import main
    from cases.scene.errors import SceneError
    from tests.toml_write import dumps

    (tmp_path / "scene.toml").write_text(dumps(deforming_blade(tmp_path, data_only=True)))
    assert main(["run", str(tmp_path / "scene.toml"), "--strict", "--quiet", "--out", str(tmp_path / "out")]) == 2
    assert "not certified" in capsys.readouterr().err
    with pytest.raises(SceneError, match="strict"):
        ventsim.run(tmp_path / "scene.toml", strict=True)


def test_closed_form_and_bisection_agree_where_the_bound_settles():
    """A box moving down and across a vent (every crossing transversal, which the bisection times to machine
    precision): solving every (node, interval) pair in closed form gives the same crossings."""
    import trimesh

    import blockage
    from cavity.tables import Table
    from cases.model.crossings import certified_crossings
    from cases.model.exact_crossings import exact_solver
    from cases.model.gaps import GapField, NodePath, RigidPlacement

    box = trimesh.creation.box(extents=(0.01, 0.012, 0.004))
    box.apply_transform(trimesh.transformations.rotation_matrix(0.3, (0.2, 1.0, 0.1)))
    box.apply_translation((-0.01, 0.01, 0.004))
    xs = np.linspace(0.0, 0.02, 9)
    nodes = np.array([[x, y, 0.0] for y in xs for x in xs])
    axis = np.array([0.8, 0.0, -0.6])
    there_and_back = Table((0.0, 0.45, 1.0), (0.0, 0.012, 0.002))  # down through the vent plane and back up
    placement = RigidPlacement(blockage.Blocker(box), tuple(axis), displacement=there_and_back)
    field = GapField(NodePath(nodes), [placement], 1e-4, 1e-3)
    knots = np.array([0.0, 0.3, 0.45, 1.0])
    by_bound = certified_crossings(field.excess, len(nodes), knots, field.speed(knots))
    closed = certified_crossings(field.excess, len(nodes), knots, field.speed(knots),
                                 exact=exact_solver(field, knots), exact_first=True)
    assert by_bound.state.sum() >= 10 and (~by_bound.state).sum() >= 10 and by_bound.unresolved == 0
    np.testing.assert_array_equal(closed.node, by_bound.node)
    np.testing.assert_array_equal(closed.state, by_bound.state)
    np.testing.assert_allclose(closed.theta, by_bound.theta, rtol=0, atol=1e-12)


def test_chords_and_bisection_agree_on_a_turning_box_where_the_bound_settles():
    """A box turning and moving down across a vent (transversal crossings, which the bisection times to machine
    precision): the chord solver on every pair gives the same crossings, and certifies them all."""
    import trimesh

    import blockage
    from cavity.tables import Table
    from cases.model.chord_crossings import chord_solver
    from cases.model.crossings import certified_crossings
    from cases.model.gaps import GapField, NodePath, RigidPlacement

    box = trimesh.creation.box(extents=(0.01, 0.012, 0.004))
    box.apply_translation((0.0, 0.01, 0.004))
    xs = np.linspace(0.0, 0.02, 9)
    nodes = np.array([[x, y, 0.0] for y in xs for x in xs])
    down_and_up = Table((0.0, 0.45, 1.0), (0.0, 0.005, 0.001))
    turn = Table((0.0, 1.0), (0.0, 60.0))
    placement = RigidPlacement(blockage.Blocker(box), (0.0, 0.0, -1.0), displacement=down_and_up, angle=turn,
                               rotation_axis=(0.0, 0.0, 1.0), centre=(0.0, 0.01, 0.0))
    field = GapField(NodePath(nodes), [placement], 1e-4, 1e-3)
    knots = np.array([0.0, 0.45, 1.0])
    by_bound = certified_crossings(field.excess, len(nodes), knots, field.speed(knots))
    chords = certified_crossings(field.excess, len(nodes), knots, field.speed(knots),
                                 exact=chord_solver(field, knots), exact_first=True)
    assert by_bound.state.sum() >= 5 and (~by_bound.state).sum() >= 5 and by_bound.unresolved == 0
    mine, ref = np.lexsort((chords.theta, chords.node)), np.lexsort((by_bound.theta, by_bound.node))
    np.testing.assert_array_equal(chords.node[mine], by_bound.node[ref])  # nodes of a row cross together
    np.testing.assert_array_equal(chords.state[mine], by_bound.state[ref])
    np.testing.assert_allclose(chords.theta[mine], by_bound.theta[ref], rtol=0, atol=1e-12)
    assert chords.unresolved == 0 and not chords.uncertain.any()
