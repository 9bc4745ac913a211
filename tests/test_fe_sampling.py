"""FE rules in time: flags sampled at t_k = k·Δt, used n cycles later, as the engine's step table of area."""
import numpy as np
import pytest
import trimesh

import blockage
from blockage.fe_rules import rule_blockage
from cases.model.build import build_model
from cases.run.area_integrals import area_distance
from cases.run.runner import run
from cases.scene.errors import SceneError
from cases.scene.files import scene_from_dict
from tests.scenes import tank
from tests.test_blockage_over_time import TOL, grid_vent, tilted_plate

END = 0.03


def plate_scene(tmp_path, fine=False, **blockage_keys):
    """The tilted plate comes down onto a 6 x 6 quad vent, rests and leaves (it covers the vent's x <= 6 mm
    columns); ``fine``: a plate of 0.5 mm triangles whose nodes land inside the vent's faces."""
    return scene_from_dict(plate_data(tmp_path, fine, **blockage_keys), tmp_path / "scene.toml")


def plate_data(tmp_path, fine=False, **blockage_keys) -> dict:
    """The TOML dict of :func:`plate_scene` (its mesh and table files written into ``tmp_path``)."""
    grid_vent(tmp_path / "vent.obj")
    plate = tilted_plate()
    if fine:
        plate = plate.subdivide_to_size(0.0045)
    plate.export(tmp_path / "plate.ply")
    (tmp_path / "motion.csv").write_text("t,s\n0,0\n0.01,1.2e-3\n0.02,1.2e-3\n0.03,0\n")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": END, "output_interval": 0.0005}
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [0, 0, -1], "displacement_table": "motion.csv"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    if blockage_keys:
        data["blockage"] = blockage_keys
    return data


def track_of(scene):
    return build_model(scene).network.areas[0].track


def area_time(track, t_end=END):
    edges = np.concatenate([[0.0], track.crossings, [t_end]])
    return float(np.sum(track.obstruction * np.diff(edges)))


def test_rule_exact_given_explicitly_is_bit_for_bit_the_default(tmp_path):
    a = run(build_model(plate_scene(tmp_path)))
    b = run(build_model(plate_scene(tmp_path, rule="exact")))
    assert np.array_equal(a.history, b.history) and a.columns == b.columns


@pytest.mark.parametrize("rule", ["abaqus", "radioss", "lsdyna_cpm", "lsdyna_cpg"])
def test_the_flags_used_with_a_lag_of_one_cycle_are_those_of_the_cycle_before(tmp_path, rule):
    step = 2.5e-4
    now = track_of(plate_scene(tmp_path, fine=True, rule=rule, step=step, lag_cycles=0))
    late = track_of(plate_scene(tmp_path, fine=True, rule=rule, step=step, lag_cycles=1))
    assert len(now.crossings) >= 4
    for k in range(1, int(END / step)):
        t = k * step
        np.testing.assert_array_equal(late.active_at(t), now.active_at(t - step))
        np.testing.assert_array_equal(late.source.face_fractions(t), now.source.face_fractions(t - step))
        assert late(t + 0.5 * step) == now(t - 0.5 * step)
    assert not late.active_at(0.0).any()  # cycle 0 has no flags of a cycle before it


@pytest.mark.parametrize("rule", ["abaqus", "radioss", "lsdyna_cpm", "lsdyna_cpg"])
def test_the_sampled_flags_are_the_rules_flags_at_each_step(tmp_path, rule):
    scene = plate_scene(tmp_path, fine=True, rule=rule, step=1e-3, lag_cycles=0, sdfblk=0.5)
    model = build_model(scene)
    track = model.network.areas[0].track
    surface = blockage.LeakageSurface.read(tmp_path / "vent.obj")
    body = model.geometry["bodies"]["plate"][0]
    touched_main = 0
    for k in range(31):
        t = k * 1e-3
        plate = trimesh.Trimesh(body.vertices_at(t), body.mesh.faces, process=False)
        want = rule_blockage(rule, surface, [plate], TOL, sdfblk=0.5)
        np.testing.assert_array_equal(track.active_at(t), want.flags)
        np.testing.assert_allclose(track.source.face_fractions(t), want.fractions, rtol=0, atol=1e-15)
        assert track(t) == pytest.approx(want.leak_area, rel=1e-12)
        touched_main += int(want.flags.sum() > rule_blockage("abaqus", surface, [plate], TOL).flags.sum())
    if rule in ("radioss", "lsdyna_cpg"):
        assert touched_main > 0  # the fine plate's nodes flag main segments beyond the nodes in contact


@pytest.mark.parametrize("rule", ["abaqus", "radioss", "lsdyna_cpm"])
def test_node_counting_rules_converge_to_exact_at_least_linearly_in_the_step(tmp_path, rule):
    exact = track_of(plate_scene(tmp_path))
    steps = [2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4]
    lag = 1 if rule == "radioss" else 0
    for s in steps:  # each switch is late by at most (lag + 1) steps, never early: ∫|ΔA| dt <= 2 A (lag + 1) Δt
        sampled = track_of(plate_scene(tmp_path, rule=rule, step=s))
        distance = area_distance(sampled, exact, 0.0, END)
        assert 0.0 < distance <= 2 * exact.total_area * (lag + 1) * s
        assert abs(area_time(sampled) - area_time(exact)) <= distance


def test_a_leak_fraction_and_sdfblk_scale_the_blocked_area(tmp_path):
    plain = track_of(plate_scene(tmp_path, rule="lsdyna_cpm", step=1e-3))
    scaled = track_of(plate_scene(tmp_path, rule="lsdyna_cpm", step=1e-3, sdfblk=0.5))
    t = 0.015
    assert plain.total_area - scaled(t) == pytest.approx(0.5 * (plain.total_area - plain(t)), rel=1e-12)
    assert plain(t) < plain.total_area


def test_lsdyna_block_exempts_vents_and_fe_rules_need_a_step(tmp_path):
    vent = track_of(plate_scene(tmp_path, rule="lsdyna_cpm", step=1e-3, block=4))  # an orifice: a vent
    assert vent(0.015) == vent.total_area
    with pytest.raises(SceneError, match=r"blockage\.step: rule 'radioss' samples"):
        plate_scene(tmp_path, rule="radioss")
    with pytest.raises(SceneError, match=r"blockage\.rule: expected one of"):
        plate_scene(tmp_path, rule="pamcrash", step=1e-6)
