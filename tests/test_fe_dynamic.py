"""FE rules with a dynamic body: the rule's area along the body's displacement s, sampled by the engine at the
explicit code's cycles t_k = k·Δt from s(t_k) and used n cycles later."""
import numpy as np
import pytest
import trimesh

import blockage
from blockage.fe_rules import rule_blockage
from cases.model.build import build_model
from cases.run.compare import time_tracks
from cases.run.area_integrals import area_distance, blocked_area_time
from cases.run.runner import run
from cases.scene.files import scene_from_dict
from tests.scenes import tank
from tests.test_blockage_over_time import TOL, grid_vent, tilted_plate

END = 0.03
#: The plate is thrown at the vent at V0 and decelerated by A0 [m/s^2] (gravity along its axis, against it): it
#: comes V0²/(2·A0) = 1.2 mm down, past the tolerance of every column of nodes at x <= 6 mm, and back up.
V0, A0 = 0.2, -0.2 ** 2 / (2 * 1.2e-3)


def dynamic_data(tmp_path, fine=False, **blockage_keys) -> dict:
    """The tilted plate of tests/test_blockage_over_time.py as a 50 g dynamic body thrown at the 6 x 6 quad vent
    of a 2 bar tank, whose gauge pressure pushes it on 0.1 mm^2; ``fine``: 0.5 mm triangles (main segments)."""
    grid_vent(tmp_path / "vent.obj")
    plate = tilted_plate()
    if fine:
        plate = plate.subdivide_to_size(0.0045)
    plate.export(tmp_path / "plate.ply")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": END, "output_interval": 0.0005}
    data["solver"] = {"rtol": 1e-9, "max_step": 1e-4}  # a turn inside a step would hide its crossings
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [0, 0, -1], "mass": 0.05,
                     "initial_velocity": V0, "gravity": A0, "pressure_cavity": "tank", "pressure_area": 1e-7}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    if blockage_keys:
        data["blockage"] = blockage_keys
    return data


def dynamic_run(tmp_path, fine=False, **keys):
    return run(build_model(scene_from_dict(dynamic_data(tmp_path, fine, **keys), tmp_path / "scene.toml")))


def vent_track(results):
    return time_tracks(results)["vent"]


def test_the_plate_approaches_the_vent_and_leaves_it(tmp_path):
    res = dynamic_run(tmp_path)
    s = res.column("plate.displacement")
    assert 1.0e-3 < s.max() < 1.4e-3 and s[-1] < 1e-4
    area = res.column("vent.area")
    assert area.min() < 0.9 * area[0] and area[-1] == area[0]


def test_rule_exact_given_explicitly_is_bit_for_bit_the_default(tmp_path):
    a, b = dynamic_run(tmp_path), dynamic_run(tmp_path, rule="exact")
    assert np.array_equal(a.history, b.history) and a.columns == b.columns
    assert b.model.network.areas[0].track.__class__.__name__ == "AreaTrack"


def used_interval(results, t):
    """The area interval exchange 0 uses at time t of a run (the discrete state of t's segment)."""
    return results.trajectory.mode_at(t).intervals[0]


@pytest.mark.parametrize("rule,lag", [("abaqus", 0), ("abaqus", 1), ("radioss", 1), ("lsdyna_cpg", 2)])
def test_the_area_used_over_each_cycle_is_the_rules_at_the_displacement_n_cycles_before(tmp_path, rule, lag):
    step = 2.5e-4
    res = dynamic_run(tmp_path, fine=True, rule=rule, step=step, lag_cycles=lag)
    track = res.model.network.areas[0].track
    flagless = len(track.crossings)
    k = np.arange(int(round(END / step)))
    s = res.trajectory.sample(k * step)[:, res.model.network.body_offset]
    finite = track.crossings[:-1]
    near = np.min(np.abs(s[:, None] - finite[None, :]), axis=1) < 1e-9  # s(t_k) on a crossing, to the solver's error
    assert near.sum() <= 1
    changes = 0
    for i in k:
        want = flagless if i < lag else track.interval(s[i - lag])
        if near[i - lag] if i >= lag else False:
            continue
        got = used_interval(res, (i + 0.5) * step)
        assert got == want, (i, got, want)
        changes += int(i > 0 and got != used_interval(res, (i - 0.5) * step))
    assert changes >= 4 + (lag > 0)


def test_lag_one_uses_exactly_the_flags_of_the_cycle_before(tmp_path):
    step = 2.5e-4
    now = dynamic_run(tmp_path, rule="abaqus", step=step, lag_cycles=0)
    late = dynamic_run(tmp_path, rule="abaqus", step=step, lag_cycles=1)
    a, b = vent_track(now), vent_track(late)
    for i in range(1, int(round(END / step))):  # the body's motion barely feels the vent: the same flags, a cycle on
        assert b((i + 0.5) * step) == a((i - 0.5) * step)
    assert b(0.5 * step) == b.open_area(0.0) and len(a.crossings) >= 8


@pytest.mark.parametrize("rule", ["exact", "abaqus", "radioss", "lsdyna_cpm", "lsdyna_cpg"])
def test_the_rules_area_at_each_pose_is_the_rule_evaluated_there(tmp_path, rule):
    """The track along s against :func:`blockage.fe_rules.rule_blockage` (the rule's description, evaluated with
    the plate placed at s) on poses through the approach, with the fine plate whose nodes touch main segments."""
    keys = {} if rule == "exact" else {"rule": rule, "step": 1e-4, "sdfblk": 0.5}
    model = build_model(scene_from_dict(dynamic_data(tmp_path, True, **keys), tmp_path / "scene.toml"))
    track = model.network.areas[0].track
    surface = blockage.LeakageSurface.read(tmp_path / "vent.obj")
    body = model.geometry["bodies"]["plate"][0]
    more = 0
    for s in np.linspace(0.0, 1.3e-3, 27):
        plate = trimesh.Trimesh(body.vertices_at(s), body.mesh.faces, process=False)
        want = rule_blockage("abaqus" if rule == "exact" else rule, surface, [plate], TOL,
                             sdfblk=0.5 if rule == "lsdyna_cpm" else 1.0)
        assert track(s) == pytest.approx(want.leak_area, rel=1e-12, abs=1e-18)
        if rule != "exact":
            np.testing.assert_allclose(track.source.face_fractions(s), want.fractions, rtol=0, atol=1e-15)
        if rule in ("radioss", "lsdyna_cpg"):
            more += int(want.flags.sum() > rule_blockage("abaqus", surface, [plate], TOL).flags.sum())
    if rule in ("radioss", "lsdyna_cpg"):
        assert more > 0  # the fine plate's nodes flag main segments beyond the nodes in contact


@pytest.mark.parametrize("rule", ["abaqus", "lsdyna_cpm"])
def test_node_counting_rules_converge_to_exact_at_least_linearly_in_the_step(tmp_path, rule):
    """Each switch of the rule comes at most one cycle late (lag 0), never early, so ∫|A − A_exact| dt <=
    A·Δt per switch; the body's motion barely feels the vent (the runs share s(t) to far below the step's effect),
    and halving the step at least halves the distance, up to a quarter of it (a switch lands where it lands in its
    cycle)."""
    exact = vent_track(dynamic_run(tmp_path))
    distances = []
    for step in (1e-3, 5e-4, 2.5e-4):
        sampled = vent_track(dynamic_run(tmp_path, rule=rule, step=step))
        distances.append(area_distance(sampled, exact, 0.0, END))
        assert 0.0 < distances[-1] <= exact.open_area(0.0) * step * len(exact.crossings)
        assert abs(blocked_area_time(sampled, 0.0, END) - blocked_area_time(exact, 0.0, END)) <= distances[-1]
    assert all(b <= 0.75 * a for a, b in zip(distances, distances[1:]))


def test_the_main_segments_along_s_replay_the_segments_of_each_pose(tmp_path):
    """:func:`main_segments_along` (a grid, then bisection) against the naive query of every node at 400 random
    poses, the fine plate's nodes over the vent (they enter, change face and leave)."""
    from blockage.fe_rules import LeakTree
    from cases.model.fe_dynamic import main_segments_along

    grid_vent(tmp_path / "vent.obj")
    vent = blockage.LeakageSurface.read(tmp_path / "vent.obj")
    x = tilted_plate().subdivide_to_size(0.0045).vertices
    axis = np.array([0.0, 0.0, -1.0])
    tree = LeakTree(vent.vertices, vent.faces, vent.face_sizes)
    lo, hi = -1e-4, 6e-3
    initial, s, node, seg = main_segments_along(tree, x, axis, lo, hi, TOL)
    assert len(s) > 20 and np.all(np.diff(s) >= 0)
    for pose in np.random.default_rng(1).uniform(lo, hi, 400):
        now = initial.copy()
        k = np.searchsorted(s, pose, side="right")
        now[node[:k]] = seg[:k]
        np.testing.assert_array_equal(now, tree.segments(x + pose * axis, TOL))


def test_scipys_integrator_samples_the_same_cycles(tmp_path):
    """solve_ivp stepping the same kernels (a second implementation of the segment loop) uses the same samples."""
    tracks = []
    for integrator in ("compiled", "scipy"):
        data = dynamic_data(tmp_path, rule="abaqus", step=5e-4, lag_cycles=1)
        data["solver"]["integrator"] = integrator
        tracks.append(vent_track(run(build_model(scene_from_dict(data, tmp_path / "scene.toml")))))
    np.testing.assert_array_equal(tracks[0].crossings, tracks[1].crossings)
    np.testing.assert_array_equal(tracks[0].areas, tracks[1].areas)
    assert len(tracks[0].crossings) >= 8
