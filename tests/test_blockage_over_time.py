"""Blockage over time: rebounds, brief contacts, penetration and stretching vents, against brute force."""
import dataclasses
import math
import tomllib

import numpy as np
import pytest
import trimesh

import blockage
from blockage.reference import nearest_faces
from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import load_scene, scene_from_dict
from tests.conftest import ROOT, VERIFICATION
from tests.scenes import tank

TOL, SLOPE, Z0 = 1e-4, 0.02, 1e-3  # contact tolerance [m], plate tilt [-], plate height over x = 0 [m]


def grid_vent(path, n=6, size=0.02):
    """A flat vent of n x n quads in z = 0 (OBJ keeps quads)."""
    xs = np.linspace(0.0, size, n + 1)
    lines = [f"v {float(x)!r} {float(y)!r} 0.0" for y in xs for x in xs]
    lines += [f"f {j * (n + 1) + i + 1} {j * (n + 1) + i + 2} {(j + 1) * (n + 1) + i + 2} {(j + 1) * (n + 1) + i + 1}"
              for j in range(n) for i in range(n)]
    path.write_text("\n".join(lines) + "\n")


def tilted_plate():
    """A plate whose lower face is z = Z0 + SLOPE·x: node columns come within the tolerance one after another."""
    plate = trimesh.creation.box(extents=(0.2, 0.2, 0.004))
    plate.apply_transform(trimesh.transformations.rotation_matrix(-math.atan(SLOPE), (0, 1, 0)))
    plate.apply_translation((0.0, 0.0, Z0 + 0.002 * math.sqrt(1 + SLOPE ** 2)))
    return plate


def dip_scene(tmp_path, duration, t_end=1.0):
    """The plate dips once to the vent: the x = 0 column is in contact for ``duration`` [s]."""
    grid_vent(tmp_path / "vent.obj")
    tilted_plate().export(tmp_path / "plate.ply")
    threshold = Z0 - TOL * math.sqrt(1 + SLOPE ** 2)  # s at which the x = 0 column touches
    peak, tc = threshold + 0.3 * SLOPE * 0.02, 0.37 * t_end  # deep enough for the x <= 6 mm columns
    w = 0.5 * duration / (1.0 - threshold / peak)  # half-width of the triangular dip
    (tmp_path / "dip.csv").write_text(f"t,s\n0,0\n{tc - w!r},0\n{tc!r},{peak!r}\n{tc + w!r},0\n{t_end!r},0\n")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": t_end, "output_interval": t_end / 50}
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [0, 0, -1], "displacement_table": "dip.csv"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    return scene_from_dict(data, tmp_path / "scene.toml"), (tc - w, tc + w)


def brute_force_blocked_area_time(surface, body, window, samples=4001):
    """∫ obstruction dt by brute force: every node's gap to every plate face at ``samples`` times of the window,
    then each sign change bisected to machine precision with the same brute-force distance."""
    verts, faces = np.asarray(body.mesh.vertices), np.asarray(body.mesh.faces)

    def gaps(t, nodes):
        moved = verts + np.asarray(body.axis) * body.motion.displacement(t)
        return nearest_faces(surface.vertices[nodes], moved, faces).distances - TOL

    times = np.linspace(*window, samples)
    nodes = np.arange(len(surface.vertices))
    inside = np.array([gaps(t, nodes) <= 0 for t in times])
    weights = _node_weights(surface)
    total = 0.0
    for i, node in np.argwhere(inside[1:] != inside[:-1]):
        a, b = times[i], times[i + 1]
        entering = inside[i + 1, node]
        while b - a > 4 * np.finfo(float).eps * b:
            m = 0.5 * (a + b)
            if (gaps(m, [node])[0] <= 0) == entering:
                b = m
            else:
                a = m
        total += weights[node] * (-b if entering else b)
    return total


def _node_weights(surface):
    w = np.zeros(len(surface.vertices))
    for f, k, area in zip(surface.faces, surface.face_sizes, surface.face_areas):
        w[f[:k]] += area / k
    return w


def track_blocked_area_time(track, t_end):
    edges = np.concatenate([[0.0], track.crossings, [t_end]])
    return float(np.sum(track.obstruction * np.diff(edges)))


@pytest.mark.parametrize("fraction", [1e-4, 1e-6])
def test_brief_contacts_keep_their_blocked_area_time(tmp_path, fraction):
    scene, window = dip_scene(tmp_path, duration=fraction * 1.0)
    model = build_model(scene)
    track = model.network.areas[0].track
    surface, _ = model.geometry["surfaces"][0]
    body = model.geometry["bodies"]["plate"][0]
    reference = brute_force_blocked_area_time(surface, body, window)
    assert reference > 0.0 and len(track.crossings) >= 4
    assert abs(track_blocked_area_time(track, 1.0) - reference) <= 1e-6 * reference
    assert track(1.0) == pytest.approx(surface.total_area, rel=1e-15)  # released


def test_a_box_that_stops_half_through_a_vent_blocks_the_nodes_inside_it(tmp_path):
    grid_vent(tmp_path / "vent.obj", n=10)
    box = trimesh.creation.box(extents=(0.0101, 0.03, 0.02))
    box.apply_translation((0.01, 0.01, 0.0105))  # 0.5 mm above the vent, x in [4.95, 15.05] mm
    box.export(tmp_path / "box.ply")
    (tmp_path / "push.csv").write_text("t,s\n0,0\n0.01,0.0105\n1,0.0105\n")  # stops with its centre in z = 0
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 0.02, "output_interval": 0.001}
    data["body"] = [{"name": "box", "mesh": "box.ply", "axis": [0, 0, -1], "displacement_table": "push.csv"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["box"],
                         "contact_tolerance": 1e-5}]
    r = run(build_model(scene_from_dict(data, tmp_path / "scene.toml")))
    track = r.model.network.areas[0].track
    surface, _ = r.model.geometry["surfaces"][0]
    x = surface.vertices[:, 0]
    inside = (x > 0.00495) & (x < 0.01505)
    np.testing.assert_array_equal(track.source.active_at(0.02), inside)  # 10 mm deep inside the box: active
    body, blocker = r.model.geometry["bodies"]["box"]
    final = blockage.evaluate(surface, [(blocker, body.transform(0.02))], 1e-5)
    np.testing.assert_array_equal(final.active_nodes, inside)
    assert r.column("vent.area")[-1] == pytest.approx(final.leak_area, rel=1e-12)


def test_a_stretching_cavity_carries_its_vent_area(tmp_path):
    scene_dict = tomllib.loads((VERIFICATION / "compression_mesh.toml").read_text())
    scene_dict["exchange"] = [{"name": "vent", "from": "bag", "leakage_box": [-1, -1, 0.15, 1, 1, 1],
                               "discharge_coefficient": 0.6}]
    scene = scene_from_dict(scene_dict, VERIFICATION / "stretch.toml")
    r = run(build_model(scene))
    mesh = trimesh.load(VERIFICATION / "sphere_r200mm.ply", process=True)
    a0 = blockage.LeakageSurface.from_region(mesh, box=(np.array([-1, -1, 0.15]), np.ones(3))).total_area
    t = r.column("time")
    s = np.interp(t, [0.0, 0.01, 0.02, 0.03], [1.0, 0.9, 0.8, 0.85])
    np.testing.assert_allclose(r.column("vent.area"), s ** 2 * a0, rtol=1e-12)


def test_a_rebounding_headform_releases_the_vent_and_converges_monotonically():
    model = build_model(load_scene(ROOT / "cases" / "airbag_impactor_dynamic.toml"))
    finals = {}
    for rtol in (1e-6, 1e-8, 1e-10, 1e-12):
        ratio = rtol / model.options.rtol
        options = dataclasses.replace(model.options, rtol=rtol, atol=model.options.atol * ratio)
        r = run(dataclasses.replace(model, options=options))
        finals[rtol] = r.column("cushion.pressure")[-1]
        net = r.model.network
        s = r.trajectory(r.trajectory.t_final)[net.body_offset]
        surface, _ = r.model.geometry["surfaces"][0]
        body, blocker = r.model.geometry["bodies"]["headform"]
        assert s < 0.0  # rebounded above its start
        final = blockage.evaluate(surface, [(blocker, body.transform(s))], 0.002, effective_area=1.4e-3)
        assert r.column("vent.area")[-1] == final.leak_area
    errors = [abs(finals[k] - finals[1e-12]) for k in (1e-6, 1e-8, 1e-10)]
    floor = 1e-13 * finals[1e-12]  # round-off: with the exact wrapped volume rtol 1e-6 already lands here
    assert all(a > b or a <= floor for a, b in zip(errors, errors[1:])), errors
    assert errors[2] <= 1e-7 * finals[1e-12]


def write_pvd_with_pyvista(folder, stem, times, vertices, faces):
    """A ParaView series written as a user would: one .vtp per frame with pyvista, and the .pvd collection."""
    import pyvista as pv

    rows = []
    for k, (t, x) in enumerate(zip(times, vertices)):
        f = faces[k] if isinstance(faces, list) else faces  # per frame, or one for all
        name = f"{stem}_{k:03d}.vtp"
        pv.PolyData(np.asarray(x, dtype=float), np.hstack([np.full((len(f), 1), f.shape[1]), f]).ravel()).save(
            folder / name)
        rows.append(f'<DataSet timestep="{float(t)!r}" part="0" file="{name}"/>')
    (folder / f"{stem}.pvd").write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
                                        "<Collection>\n" + "\n".join(rows) + "\n</Collection>\n</VTKFile>\n")
    return f"{stem}.pvd"


def plate_frames(times):
    """The tilted plate's vertices following a down-and-up motion, frame by frame."""
    plate = tilted_plate()
    s = np.interp(times, [0.0, 0.01, 0.02, 0.03], [0.0, 1.2e-3, 1.2e-3, 0.0])
    return plate, plate.vertices[None] - s[:, None, None] * np.array([0.0, 0.0, 1.0])


def series_scenes(tmp_path):
    grid_vent(tmp_path / "vent.obj")
    times = np.linspace(0.0, 0.03, 7)
    plate, frames = plate_frames(times)
    plate.export(tmp_path / "plate.ply")
    np.savez(tmp_path / "plate.npz", times=times, vertices=frames)
    pvd = write_pvd_with_pyvista(tmp_path, "plate", times, frames, np.asarray(plate.faces))
    scenes = []
    for body in ({"mesh": "plate.ply", "vertex_trajectory": "plate.npz"}, {"mesh_series": pvd}):
        data = tank(pressure=2.0e5)
        data["time"] = {"end": 0.03, "output_interval": 0.0005}
        data["body"] = [{"name": "plate", **body}]
        data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                             "contact_tolerance": TOL}]
        scenes.append(scene_from_dict(data, tmp_path / "scene.toml"))
    return scenes, plate, frames, times


def test_a_mesh_series_gives_the_histories_of_the_equivalent_vertex_trajectory(tmp_path):
    (trajectory, series), *_ = series_scenes(tmp_path)
    a, b = run(build_model(trajectory)), run(build_model(series))
    assert len(a.model.network.areas[0].track.crossings) >= 6  # columns touch and release
    np.testing.assert_allclose(b.history, a.history, rtol=1e-12, atol=0.0)


def test_permuted_nodes_and_changed_connectivity_in_a_series_are_clear_errors(tmp_path):
    from cases.scene.errors import SceneError

    (_, series), plate, frames, times = series_scenes(tmp_path)
    faces = np.asarray(plate.faces)
    permuted = frames.copy()
    permuted[3] = permuted[3][np.random.default_rng(1).permutation(len(plate.vertices))]
    write_pvd_with_pyvista(tmp_path, "plate", times, permuted, faces)
    with pytest.raises(SceneError, match=r"body\[0\]\.mesh_series: .*plate\.pvd: frame 3 .*"):
        build_model(series)
    flipped = faces.copy()
    flipped[5] = flipped[5][::-1]  # one face turned over in frame 1
    write_pvd_with_pyvista(tmp_path, "plate", times[:2], frames[:2], [faces, flipped])
    with pytest.raises(SceneError, match=r"frame 1 .*(face|connectivity)"):
        build_model(series)
    np.savez(tmp_path / "plate.npz", times=times, vertices=frames[:, ::-1])  # trajectory in the wrong node order
    data = tank(pressure=2.0e5)
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "vertex_trajectory": "plate.npz"}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    with pytest.raises(SceneError, match=r"body\[0\]\.vertex_trajectory: .*plate\.npz: .*frame 0"):
        build_model(scene_from_dict(data, tmp_path / "scene.toml"))


def test_a_cavity_given_as_a_mesh_series_has_the_exact_volume_and_vent_area(tmp_path):
    sphere = trimesh.creation.icosphere(subdivisions=2, radius=0.1)
    times = np.array([0.0, 0.01, 0.02])
    scale = np.array([1.0, 1.3, 0.9])
    frames = sphere.vertices[None] * scale[:, None, None]
    np.savez(tmp_path / "bag.npz", times=times, vertices=frames, faces=sphere.faces)
    data = tank(pressure=1.5e5)
    data["cavity"][0].pop("volume")
    data["cavity"][0]["mesh_series"] = "bag.npz"
    data["time"] = {"end": 0.02, "output_interval": 0.0005}
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_box": [-1, -1, 0.07, 1, 1, 1]}]
    r = run(build_model(scene_from_dict(data, tmp_path / "scene.toml")))
    t = r.column("time")
    s = np.interp(t, times, scale)
    v0 = sphere.volume
    a0 = blockage.LeakageSurface.from_region(sphere, box=(np.array([-1, -1, 0.07]), np.ones(3))).total_area
    np.testing.assert_allclose(r.column("tank.volume"), s ** 3 * v0, rtol=1e-12)
    np.testing.assert_allclose(r.column("vent.area"), s ** 2 * a0, rtol=1e-12)


def test_a_leakage_surface_series_moving_on_its_own_meets_a_fixed_plate_as_a_moving_plate_meets_it(tmp_path):
    grid_vent(tmp_path / "vent.obj")
    tilted_plate().export(tmp_path / "plate.ply")
    vent = blockage.LeakageSurface.read(tmp_path / "vent.obj")
    times = np.array([0.0, 0.01, 0.02, 0.03])
    s = np.array([0.0, 1.2e-3, 1.2e-3, 0.0])
    frames = vent.vertices[None] + s[:, None, None] * np.array([0.0, 0.0, 1.0])
    quads = np.asarray(vent.faces)
    np.savez(tmp_path / "vent_up.npz", times=times, vertices=frames, faces=quads)
    (tmp_path / "down.csv").write_text("t,s\n" + "".join(f"{float(t)!r},{float(x)!r}\n" for t, x in zip(times, s)))
    tracks = []
    for body, leak in (({"displacement_table": "down.csv"}, "vent.obj"), ({}, "vent_up.npz")):
        data = tank(pressure=2.0e5)
        data["time"] = {"end": 0.03, "output_interval": 0.001}
        data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [0, 0, -1], **body}]
        data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": leak, "blocked_by": ["plate"],
                             "contact_tolerance": TOL}]
        tracks.append(build_model(scene_from_dict(data, tmp_path / "scene.toml")).network.areas[0].track)
    moving_plate, moving_vent = tracks
    assert len(moving_vent.crossings) == len(moving_plate.crossings) >= 6
    np.testing.assert_allclose(moving_vent.crossings, moving_plate.crossings, rtol=1e-9)
    np.testing.assert_allclose(moving_vent.areas, moving_plate.areas, rtol=1e-12)


def test_library_cases_of_node_based_edge_and_self_contact_blockage():
    models = {n: build_model(load_scene(ROOT / "cases" / f"{n}.toml"))
              for n in ("seal_vent", "seal_vent_nodes", "vent_bar_edge", "bag_unfold")}
    elements, nodes = (models[n].network.areas[0].track for n in ("seal_vent", "seal_vent_nodes"))
    np.testing.assert_allclose(nodes.crossings, elements.crossings, rtol=1e-12)  # node shares = element areas
    np.testing.assert_allclose(nodes.areas, elements.areas, rtol=1e-12)
    bar = models["vent_bar_edge"]
    surface, _ = bar.geometry["surfaces"][0]
    down = bar.network.areas[0].track.active_at(0.008)
    np.testing.assert_array_equal(down, np.isclose(surface.vertices[:, 0], 0.0) | np.isclose(surface.vertices[:, 0],
                                                                                               0.01))
    body, blocker = bar.geometry["bodies"]["bar"]
    assert not blockage.evaluate(surface, [(blocker, body.transform(0.008))], 1e-3).active_nodes.any()
    assert np.array_equal(blockage.evaluate(surface, [(blocker, body.transform(0.008))], 1e-3,
                                            edge_contact=True).active_nodes, down)
    bag = models["bag_unfold"].network.areas[0].track
    assert bag.actives[0] == len(bag.source.initial) and bag.areas[0] == 0.0  # the flat bag's top sheet covers it
    assert len(bag.crossings) == 1 and bag.crossings[0] == pytest.approx(0.005 + 0.0025 / 3.0, rel=1e-12)
    assert bag(0.01) == pytest.approx(2.0e-4, rel=1e-15)


def sampled_disagreements(model, times):
    """Instants among ``times`` where the track's active set differs from blockage.evaluate of the pose (each
    body placed at t), away from the crossings found (within one sample of them the state may have changed)."""
    geo = model.geometry
    track = model.network.areas[0].track
    surface, positions = geo["surfaces"][0]
    spec = model.scene.exchange[0]
    step = times[1] - times[0]
    bad = []
    for t in times:
        if track.crossings.size and np.min(np.abs(track.crossings - t)) < step:
            continue
        placed = geo["driver"].placed(spec.blocked_by)(t)
        truth = blockage.evaluate(surface.with_vertices(positions(t)), placed, spec.contact_tolerance).active_nodes
        if not np.array_equal(truth, track.active_at(t)):
            bad.append(t)
    return bad


def test_a_rotating_flap_and_a_deforming_blocker_agree_with_evaluate_at_every_sampled_instant(tmp_path):
    grid_vent(tmp_path / "vent.obj", n=8)
    flap = trimesh.creation.box(extents=(0.03, 0.03, 0.002))
    flap.apply_translation((0.015, 0.01, 0.0015))  # hinged near x = 0, 0.5 mm above the vent
    flap.export(tmp_path / "flap.ply")
    (tmp_path / "angle.csv").write_text("t,deg\n0,-30\n0.01,0.5\n0.011,0.5\n0.02,-30\n")  # closes, holds, opens
    sphere = trimesh.creation.icosphere(subdivisions=2, radius=0.006)
    times = np.linspace(0.0, 0.02, 6)
    path = np.array([[0.0, 0.01, 0.02], [0.01, 0.01, 0.006], [0.02, 0.01, 0.0055], [0.01, 0.01, 0.0048],
                     [0.005, 0.01, 0.0055], [0.0, 0.01, 0.02]])  # it rolls over the vent, pressing into it
    squash = np.array([1.0, 1.0, 0.9, 0.8, 0.9, 1.0])  # the ball flattens as it rolls over the vent
    frames = np.array([sphere.vertices * [1.0, 1.0, s] + c for s, c in zip(squash, path)])
    trimesh.Trimesh(frames[0], sphere.faces, process=False).export(tmp_path / "ball.ply")
    np.savez(tmp_path / "ball.npz", times=times, vertices=frames)
    bodies = ({"name": "flap", "mesh": "flap.ply", "rotation_table": "angle.csv", "rotation_axis": [0, 1, 0],
               "rotation_centre": [0.0, 0.01, 0.0015]},
              {"name": "ball", "mesh": "ball.ply", "vertex_trajectory": "ball.npz"})
    for body in bodies:
        data = tank(pressure=2.0e5)
        data["time"] = {"end": 0.02, "output_interval": 0.001}
        data["body"] = [body]
        data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj",
                             "blocked_by": [body["name"]], "contact_tolerance": 5e-4}]
        model = build_model(scene_from_dict(data, tmp_path / "scene.toml"))
        assert len(model.network.areas[0].track.crossings) >= 4, body["name"]
        assert sampled_disagreements(model, np.linspace(0.0, 0.02, 401)) == [], body["name"]


def test_a_plate_sliding_just_outside_the_tolerance_is_solved_exactly_without_a_warning(tmp_path):
    """The gap stays 1e-15 m above the tolerance while the plate slides along the vent: the speed bound cannot
    settle any interval, so the crowded pairs go to the closed form, which finds no contact and leaves nothing
    uncertified."""
    grid_vent(tmp_path / "vent.obj", n=2)
    plate = trimesh.creation.box(extents=(0.2, 0.2, 0.002))
    plate.apply_translation((0.0, 0.0, 1e-3 + 1e-15 + 0.001))  # lower face TOL·10 + 1e-15 above the vent
    plate.export(tmp_path / "plate.ply")
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 0.01, "output_interval": 0.001}
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [1, 0, 0], "velocity": 1.0}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.obj", "blocked_by": ["plate"],
                         "contact_tolerance": 1e-3}]
    model = build_model(scene_from_dict(data, tmp_path / "scene.toml"))
    assert not any("certified" in w for w in model.warnings)
    track = model.network.areas[0].track
    assert len(track.crossings) == 0 and track.source.unresolved == 0 and track(0.005) == track.total_area
    assert float(model.geometry["bodies"]["plate"][1].vertices[:, 2].min()) > 1e-3  # the gap in floats
