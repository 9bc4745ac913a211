"""Mesh series: exact round trips through .pvd (.vtp, .vtu), XDMF and .npz; linear interpolation in time against
closed forms; and one clear error, naming the frame, for every way a series can be wrong."""
import re

import numpy as np
import pytest

from cases.scene.errors import SceneError
from cases.model.mesh_series import MeshSeries, read_mesh_series, write_npz, write_pvd, write_xdmf

KEY = "body[0].mesh_series"
T = np.array([0.0, 1e-3, 2.5e-3, 4e-3, 7e-3])  # [s], uneven on purpose


def sphere():
    import trimesh

    m = trimesh.creation.icosphere(subdivisions=2, radius=0.1)
    return np.array(m.vertices), np.array(m.faces)


def plate():
    """A 4 x 3 plate of quads whose last row is split into triangles: mixed faces, padded with -1."""
    x, y = np.meshgrid(np.linspace(0.0, 0.3, 5), np.linspace(0.0, 0.2, 4))
    pts = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    quads = [[r * 5 + c, r * 5 + c + 1, (r + 1) * 5 + c + 1, (r + 1) * 5 + c] for r in range(3) for c in range(4)]
    faces = [q for q in quads[:8]] + [t for q in quads[8:] for t in ([q[0], q[1], q[2], -1], [q[0], q[2], q[3], -1])]
    return pts, np.array(faces)


def frames(x0, times=T):
    """x(t) = X (1 + 40 t + 1e4 t^2) + (0, 0, 3 t): stretching and moving, nonlinear in t."""
    return np.stack([x0 * (1.0 + 40.0 * t + 1e4 * t * t) + [0.0, 0.0, 3.0 * t] for t in times])


def message(excinfo):
    return str(excinfo.value)


@pytest.mark.parametrize("mesh", [sphere, plate])
@pytest.mark.parametrize("fmt", ["vtp", "vtu", "xdmf", "npz"])
def test_round_trip_is_exact(tmp_path, fmt, mesh):
    x0, faces = mesh()
    verts = frames(x0)
    if fmt in ("vtp", "vtu"):
        path = tmp_path / "s.pvd"
        write_pvd(path, T, verts, faces, frame_format=fmt)
    elif fmt == "xdmf":
        path = write_xdmf(tmp_path / "s.xdmf", T, verts, faces)
    else:
        path = write_npz(tmp_path / "s.npz", T, verts, faces)
    s = read_mesh_series(path, where=KEY)
    assert np.array_equal(s.times, T) and np.array_equal(s.vertices, verts) and np.array_equal(s.faces, faces)
    assert s.vertices.dtype == np.float64 and s.source == str(path)
    assert s.face_sizes.tolist() == (faces >= 0).sum(axis=1).tolist()


def write_with_pyvista(folder, times, verts, faces, ids=None, name="s"):
    """A ParaView series written by hand: pyvista.PolyData frames and the .pvd XML."""
    import pyvista

    flat = np.column_stack([np.full(len(faces), faces.shape[1]), faces]).ravel()
    lines = []
    for i, t in enumerate(times):
        mesh = pyvista.PolyData(verts[i], faces=flat)
        if ids is not None:
            mesh.point_data["vtkOriginalPointIds"] = ids[i]
        mesh.save(folder / f"{name}{i}.vtp")
        lines.append(f'    <DataSet timestep="{float(t)!r}" part="0" file="{name}{i}.vtp"/>')
    path = folder / f"{name}.pvd"
    path.write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
                    + "\n".join(lines) + "\n  </Collection>\n</VTKFile>\n")
    return path


def test_series_written_with_pyvista_reads_back_exactly(tmp_path):
    x0, faces = sphere()
    verts = frames(x0)
    ids = np.tile(np.arange(len(x0)), (len(T), 1))
    s = read_mesh_series(write_with_pyvista(tmp_path, T, verts, faces, ids), where=KEY)
    assert np.array_equal(s.vertices, verts) and np.array_equal(s.faces, faces) and np.array_equal(s.times, T)


def test_xdmf_as_meshio_writes_it_mesh_plus_displacement(tmp_path):
    """meshio's TimeSeriesWriter (and FEniCS) write the mesh once and a displacement field a step."""
    import meshio

    x0, faces = sphere()
    verts = frames(x0)
    path = tmp_path / "u.xdmf"
    with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:
        w.write_points_cells(x0, [("triangle", faces)])
        for t, x in zip(T, verts):
            w.write_data(t, point_data={"displacement": x - x0})
    s = read_mesh_series(path, where=KEY)
    assert np.array_equal(s.vertices, x0 + (verts - x0)) and np.array_equal(s.times, T)
    assert np.abs(s.vertices - verts).max() < 1e-15


def test_interpolation_is_linear_between_frames_and_held_beyond():
    """The chord of x(t) = X (1 + t^2) between frames: X (1 + t_i^2 + (t - t_i)(t_i + t_{i+1}))."""
    x0, faces = sphere()
    ts = np.array([0.0, 0.5, 1.25, 2.0])
    s = MeshSeries(ts, np.stack([x0 * (1.0 + t * t) for t in ts]), faces)
    for t in np.linspace(-1.0, 3.0, 41):
        i = min(max(int(np.searchsorted(ts, t, side="right")) - 1, 0), 2)
        tc = min(max(t, ts[0]), ts[-1])
        exact = x0 * (1.0 + ts[i] ** 2 + (tc - ts[i]) * (ts[i] + ts[i + 1]))
        assert np.allclose(s.at(t), exact, rtol=1e-14, atol=1e-16), t
        assert s.interval(t) == i
    assert s.breakpoints == (0.0, 0.5, 1.25, 2.0)
    r = np.linalg.norm(x0, axis=1)
    for i in range(3):
        assert np.allclose(s.node_speeds(i), r * (ts[i] + ts[i + 1]), rtol=1e-13)
        assert s.velocity_bound(i) == pytest.approx(r.max() * (ts[i] + ts[i + 1]), rel=1e-13)
    assert np.allclose(s.speed_bounds(), [s.velocity_bound(i) for i in range(3)], rtol=1e-15)
    with pytest.raises(IndexError):
        s.node_speeds(3)


def test_velocity_bound_bounds_every_point_of_every_face():
    """A point at fixed barycentric coordinates of a face never moves faster than the largest node speed."""
    x0, faces = sphere()
    s = MeshSeries(T, frames(x0), faces)
    rng = np.random.default_rng(1)
    w = rng.dirichlet(np.ones(3), size=len(faces))
    for i in range(len(T) - 1):
        ta, tb = T[i] + 0.3 * (T[i + 1] - T[i]), T[i] + 0.7 * (T[i + 1] - T[i])
        pa, pb = (np.einsum("fk,fkd->fd", w, s.at(t)[faces]) for t in (ta, tb))
        speed = np.linalg.norm(pb - pa, axis=1) / (tb - ta)
        assert speed.max() <= s.velocity_bound(i) * (1 + 1e-12)
        assert speed.max() >= 0.9 * s.velocity_bound(i)  # the bound is tight on this mesh


def test_large_legitimate_motion_is_not_taken_for_a_permutation(tmp_path):
    """A quarter turn plus a 3x uniform stretch between two frames keeps every edge ratio at 3: accepted."""
    x0, faces = sphere()
    turn = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    verts = np.stack([x0, 3.0 * x0 @ turn.T, 3.3 * x0 @ turn.T])
    s = read_mesh_series(write_npz(tmp_path / "s.npz", T[:3], verts, faces), where=KEY)
    assert s.n_frames == 3 and s.n_nodes == len(x0)


def permuted(verts, frame, seed=0):
    out = verts.copy()
    out[frame] = out[frame][np.random.default_rng(seed).permutation(verts.shape[1])]
    return out


@pytest.mark.parametrize("fmt", ["vtp", "xdmf", "npz"])
def test_permuted_frame_is_an_error_naming_it(tmp_path, fmt):
    x0, faces = sphere()
    verts = permuted(frames(x0), 3)
    if fmt == "vtp":
        path = tmp_path / "s.pvd"
        write_pvd(path, T, verts, faces)
    elif fmt == "xdmf":
        path = write_xdmf(tmp_path / "s.xdmf", T, verts, faces)
    else:
        path = write_npz(tmp_path / "s.npz", T, verts, faces)
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY)
    text = message(e)
    where = "frame 3 (t = 0.004 s, s/s_0003.vtp)" if fmt == "vtp" else "frame 3 (t = 0.004 s)"
    assert text.startswith(f"{path}: {KEY}: {where}: nodes permuted relative to frame 2? edge ")
    assert "every frame must list the nodes in the order of frame 0 (rule: each edge within 1/4 to 4 times" in text
    assert "\n" not in text


def test_permuted_point_ids_are_an_error_naming_the_array(tmp_path):
    x0, faces = sphere()
    order = np.random.default_rng(2).permutation(len(x0))
    verts, ids = frames(x0), np.tile(np.arange(len(x0)), (len(T), 1))
    verts[3], ids[3] = verts[3][order], ids[3][order]
    j = int(np.flatnonzero(order != np.arange(len(x0)))[0])
    with pytest.raises(SceneError) as e:
        read_mesh_series(write_with_pyvista(tmp_path, T, verts, faces, ids), where=KEY)
    assert (f"{KEY}: frame 3 (t = 0.004 s, s3.vtp): nodes permuted relative to frame 2: point id "
            f"'vtkOriginalPointIds' is {order[j]} at node {j}, {j} in frame 2 (") in message(e)


def test_ids_vouch_for_the_order_where_edges_alone_would_refuse(tmp_path):
    """With identical point ids the edge test is not applied: an 8x stretch in one frame interval is accepted."""
    x0, faces = sphere()
    verts = np.stack([x0 * (1.0 + 7.0 * (i == 4)) for i in range(len(T))])
    ids = np.tile(np.arange(len(x0)), (len(T), 1))
    assert read_mesh_series(write_with_pyvista(tmp_path, T, verts, faces, ids)).n_frames == 5
    with pytest.raises(SceneError, match=r"frame 4 \(t = 0.007 s, t4.vtp\): nodes permuted relative to frame 3\? "
                                         r"edge \d+-\d+ changes length 8x"):
        read_mesh_series(write_with_pyvista(tmp_path, T, verts, faces, name="t"))


def test_changed_connectivity_is_an_error_naming_the_frame(tmp_path):
    x0, faces = sphere()
    verts = frames(x0)
    flipped = faces.copy()
    flipped[7] = flipped[7][[1, 0, 2]]
    path = tmp_path / "s.pvd"
    write_pvd(path, T, verts, faces)
    write_pvd(tmp_path / "x.pvd", T, verts, flipped)
    (tmp_path / "x" / "x_0002.vtp").replace(tmp_path / "s" / "s_0002.vtp")
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY)
    f = faces[7].tolist()
    assert message(e) == (f"{path}: {KEY}: frame 2 (t = 0.0025 s, s/s_0002.vtp): face 7 is {[f[1], f[0], f[2]]}, "
                          f"in frame 0 {f} (1 faces differ): every frame must have the nodes and connectivity of "
                          f"frame 0")


@pytest.mark.parametrize("what,expected", [
    ("nodes", "frame 2 (t = 0.0025 s, s/s_0002.vtp): 161 nodes, frame 0 has 162: every frame must have the nodes"),
    ("faces", "frame 2 (t = 0.0025 s, s/s_0002.vtp): 319 faces, frame 0 has 320: every frame must have the nodes"),
])
def test_changed_node_or_face_count_is_an_error_naming_the_frame(tmp_path, what, expected):
    x0, faces = sphere()
    verts = frames(x0)
    path = tmp_path / "s.pvd"
    write_pvd(path, T, verts, faces)
    if what == "nodes":
        keep = faces[(faces != len(x0) - 1).all(axis=1)]
        write_pvd(tmp_path / "x.pvd", T, verts[:, :-1], keep[:len(faces) - 1] if len(keep) >= 320 else keep)
    else:
        write_pvd(tmp_path / "x.pvd", T, verts, faces[:-1])
    (tmp_path / "x" / "x_0002.vtp").replace(tmp_path / "s" / "s_0002.vtp")
    with pytest.raises(SceneError, match="^" + re.escape(f"{path}: {KEY}: {expected}")):
        read_mesh_series(path, where=KEY)


def test_changed_xdmf_topology_is_an_error_naming_the_frame(tmp_path):
    x0, faces = sphere()
    path = write_xdmf(tmp_path / "s.xdmf", T, frames(x0), faces)
    other = faces.copy()
    other[[0, 1]] = other[[1, 0]]
    text = path.read_text()
    own = write_xdmf(tmp_path / "o.xdmf", T, frames(x0), other).read_text()
    topology = own[own.index("<Topology"):own.index("</Topology>") + len("</Topology>")]
    parts = text.split("<xi:include")
    parts[3] = parts[3][parts[3].index("/>") + 2:]
    path.write_text("<xi:include".join(parts[:3]) + topology + parts[3] + "<xi:include" + "<xi:include".join(parts[4:]))
    with pytest.raises(SceneError, match=r"s.xdmf: frame 3 \(t = 0.004 s\): face 0 is .*, in frame 0 .* \(2 faces "
                                         r"differ\): every frame must have the nodes and connectivity"):
        read_mesh_series(path)


def test_wrong_vertex_order_against_the_reference_mesh_is_an_error(tmp_path):
    x0, faces = sphere()
    order = np.random.default_rng(3).permutation(len(x0))
    path = write_npz(tmp_path / "s.npz", T, frames(x0)[:, order], faces)
    j = int(np.flatnonzero(order != np.arange(len(x0)))[0])
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY, scene_path="bag.toml", reference_vertices=x0)
    text = message(e)
    assert text.startswith(f"bag.toml: {KEY}: {path}: frame 0 (t = 0 s) does not match the reference mesh: vertex {j}"
                           f" is ")
    tol = 1e-5 * np.linalg.norm(np.ptp(x0, axis=0))
    assert (f"off by more than {tol:.3g} m = 1e-05 x the mesh size); it is the reference mesh with its vertices in "
            f"another order (its vertex {j} is reference vertex {order[j]}): write the series in the mesh's vertex "
            f"order") in text
    assert read_mesh_series(write_npz(tmp_path / "ok.npz", T, frames(x0), faces), reference_vertices=x0 + 1e-7)


def test_npz_faces_may_come_from_the_reference_mesh(tmp_path):
    x0, faces = sphere()
    path = tmp_path / "v.npz"
    np.savez(path, times=T, vertices=frames(x0))
    assert np.array_equal(read_mesh_series(path, reference_faces=faces).faces, faces)
    with pytest.raises(SceneError, match=r"v.npz: body\[0\].mesh_series: no array 'faces' \(it has: times, vertices\)"):
        read_mesh_series(path, where=KEY)


@pytest.mark.parametrize("times,expected", [
    ([0.0, 1e-3, 1e-3, 4e-3, 7e-3], "frame 2 (t = 0.001 s): not after frame 1 (t = 0.001 s): frame times must "
                                    "increase strictly"),
    ([0.0, 1e-3, 2.5e-3, np.nan, 7e-3], "frame 3 (t = nan s): the time is not finite"),
])
def test_times_must_increase_strictly(tmp_path, times, expected):
    x0, faces = sphere()
    path = tmp_path / "s.npz"
    np.savez(path, times=np.array(times), vertices=frames(x0), faces=faces)
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY)
    assert message(e) == f"{path}: {KEY}: {expected}"


def test_pvd_times_must_increase_strictly(tmp_path):
    x0, faces = sphere()
    path = tmp_path / "s.pvd"
    write_pvd(path, T, frames(x0), faces)
    path.write_text(path.read_text().replace('timestep="0.004"', 'timestep="0.002"'))
    with pytest.raises(SceneError, match=r"frame 3 \(t = 0.002 s, s/s_0003.vtp\): not after frame 2 \(t = 0.0025 s\)"):
        read_mesh_series(path, where=KEY)


def test_missing_frame_file_is_an_error_naming_it(tmp_path):
    x0, faces = sphere()
    path = tmp_path / "s.pvd"
    files = write_pvd(path, T, frames(x0), faces)
    files[2].unlink()
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY)
    assert message(e) == (f"{path}: {KEY}: frame 2 (t = 0.0025 s, s/s_0002.vtp): frame file s/s_0002.vtp not found "
                          f"(in {tmp_path})")


def test_volume_cells_only_are_an_error(tmp_path):
    import meshio

    pts = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    meshio.write_points_cells(tmp_path / "tet.vtu", pts, [("tetra", np.array([[0, 1, 2, 3]]))])
    path = tmp_path / "s.pvd"
    path.write_text('<VTKFile type="Collection"><Collection><DataSet timestep="0" file="tet.vtu"/></Collection>'
                    '</VTKFile>')
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY)
    assert message(e) == (f"{path}: {KEY}: frame 0 (t = 0 s, tet.vtu): no surface cells (triangle, quad, or polygon "
                          f"of 3 or 4 nodes); found 1 tetra")


@pytest.mark.parametrize("cells,expected", [
    ([("triangle6", [[0, 1, 2, 3, 4, 5]])], "1 triangle6 cells: only linear triangles and quads (3 or 4 nodes)"),
    ([("polygon", [[0, 1, 2, 3, 4]])], "1 polygon cells of 5 nodes: only linear triangles and quads (3 or 4 nodes)"),
])
def test_unsupported_surface_cells_are_an_error(tmp_path, cells, expected):
    import meshio

    pts = np.random.default_rng(0).random((6, 3))
    meshio.write_points_cells(tmp_path / "f.vtu", pts, [(k, np.array(c)) for k, c in cells])
    path = tmp_path / "s.pvd"
    path.write_text('<VTKFile type="Collection"><Collection><DataSet timestep="0" file="f.vtu"/></Collection>'
                    '</VTKFile>')
    with pytest.raises(SceneError) as e:
        read_mesh_series(path, where=KEY)
    assert message(e) == f"{path}: {KEY}: frame 0 (t = 0 s, f.vtu): {expected} are taken"


def test_bad_files_are_one_line_errors(tmp_path):
    x0, faces = sphere()
    verts = frames(x0)
    verts[1, 5, 2] = np.inf
    with pytest.raises(SceneError, match=r"frame 1 \(t = 0.001 s\): node 5 has a non-finite coordinate"):
        read_mesh_series(write_npz(tmp_path / "s.npz", T, verts, faces), where=KEY)
    with pytest.raises(SceneError, match=r"s.obj: body\[0\].mesh_series: unknown mesh-series format '.obj': expected "
                                         r"one of .pvd \(ParaView series\), .xdmf"):
        read_mesh_series(tmp_path / "s.obj", where=KEY)
    with pytest.raises(SceneError, match=r"one.npz: 1 frame: a mesh series needs at least 2 \(for a fixed surface"):
        read_mesh_series(write_npz(tmp_path / "one.npz", T[:1], frames(x0)[:1], faces))
    with pytest.raises(SceneError, match=r"none.pvd: body\[0\].mesh_series: file not found$"):
        read_mesh_series(tmp_path / "none.pvd", where=KEY)
    (tmp_path / "bad.pvd").write_text("<VTKFile type='PolyData'/>")
    with pytest.raises(SceneError, match=r"bad.pvd: not a ParaView series: expected <VTKFile type=\"Collection\">"):
        read_mesh_series(tmp_path / "bad.pvd")
    bad = faces.copy()
    bad[4, 1] = len(x0)
    with pytest.raises(SceneError, match=r"frame 0 \(t = 0 s\): face 4 .* names a node outside 0..161 \(162 nodes\)"):
        read_mesh_series(write_npz(tmp_path / "f.npz", T, frames(x0), bad))


def test_xdmf_step_without_positions_is_an_error(tmp_path):
    import meshio

    x0, faces = sphere()
    path = tmp_path / "p.xdmf"
    with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:
        w.write_points_cells(x0, [("triangle", faces)])
        w.write_data(0.0, point_data={"pressure": np.zeros(len(x0))})
    with pytest.raises(SceneError, match=r"p.xdmf: frame 0 \(t = 0 s\): no <Geometry> of its own and no displacement "
                                         r"point data \(one of displacement, "):
        read_mesh_series(path)


def test_mesh_series_is_a_vertex_trajectory_with_read_only_arrays():
    from cases.model.bodies import VertexTrajectory

    x0, faces = sphere()
    s = MeshSeries(T, frames(x0), faces)
    assert isinstance(s, VertexTrajectory) and s.n_frames == 5 and s.n_nodes == 162
    with pytest.raises(ValueError):
        s.vertices[0, 0, 0] = 1.0
    with pytest.raises(ValueError, match="times must increase strictly"):
        MeshSeries(T[::-1], frames(x0), faces)


def test_small_meshes_permuted_or_mirrored_are_errors_and_affine_motion_is_not(tmp_path):
    """Where edges alone see nothing (42-node icosphere, 8-node box): the one-ring affine fit and its sign."""
    import trimesh

    ico, box = trimesh.creation.icosphere(subdivisions=1, radius=0.1), trimesh.creation.box(extents=(0.2, 0.1, 0.3))
    turn = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    for mesh in (ico, box):  # a quarter turn, then a 3x / 0.4x anisotropic stretch and a shift: accepted
        x0, faces = np.array(mesh.vertices), np.array(mesh.faces)
        verts = np.stack([x0, x0 @ turn.T, x0 @ turn.T * [3.0, 1.0, 0.4] + 0.05])
        assert read_mesh_series(write_npz(tmp_path / "ok.npz", T[:3], verts, faces)).n_frames == 3
    x0, faces = np.array(ico.vertices), np.array(ico.faces)
    with pytest.raises(SceneError, match=r"frame 3 \(t = 0.004 s\): nodes permuted relative to frame 2\? the nodes' "
                                         r"neighbourhoods do not follow any smooth motion \(median affine misfit of "
                                         r"the one-rings 0\.\d+, more than 0.25, over 42 nodes\)"):
        moving = np.stack([x0 + [0.0, 0.0, 3.0 * t] for t in T])
        read_mesh_series(write_npz(tmp_path / "ico.npz", T, permuted(moving, 3), faces))
    x0, faces = np.array(box.vertices), np.array(box.faces)
    verts = frames(x0)
    verts[3] = verts[3][::-1]  # trimesh's box: the reversed order is the point reflection through the centre
    with pytest.raises(SceneError, match=r"frame 3 \(t = 0.004 s\): nodes permuted relative to frame 2\? it is the "
                                         r"mirror image of frame 2 \(8 of 8 3-D neighbourhoods reflected"):
        read_mesh_series(write_npz(tmp_path / "box.npz", T, verts, faces))


def test_vtu_frames_meshio_cannot_read_are_read_with_vtk(tmp_path):
    """meshio 5.3 fails on LZ4-compressed VTU; the reader falls back to pyvista/VTK and gets the same arrays."""
    import pyvista
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

    x0, faces = sphere()
    verts = frames(x0)
    path = tmp_path / "s.pvd"
    files = write_pvd(path, T, verts, faces, frame_format="vtu")
    for i, file in enumerate(files):
        grid = pyvista.PolyData(verts[i], faces=np.column_stack([np.full(len(faces), 3), faces]).ravel())
        writer = vtkXMLUnstructuredGridWriter()
        writer.SetFileName(str(file))
        writer.SetInputData(grid.cast_to_unstructured_grid())
        writer.SetCompressorTypeToLZ4()
        writer.Write()
    s = read_mesh_series(path, where=KEY)
    assert np.array_equal(s.vertices, verts) and np.array_equal(s.faces, faces)


@pytest.mark.parametrize("data_format", ["HDF", "Binary"])
def test_xdmf_with_hdf5_or_raw_binary_data(tmp_path, monkeypatch, data_format):
    """HDF5 (the `hdf5` extra: h5py) as FEniCS and ParaView write it; raw binary files read from another folder."""
    import meshio

    if data_format == "HDF":
        pytest.importorskip("h5py")
    x0, faces = sphere()
    verts = frames(x0)
    monkeypatch.chdir(tmp_path)  # meshio writes raw binary files into the working folder
    with meshio.xdmf.TimeSeriesWriter(tmp_path / "u.xdmf", data_format=data_format) as w:
        w.write_points_cells(x0, [("triangle", faces)])
        for t, x in zip(T, verts):
            w.write_data(t, point_data={"u": x - x0})
    monkeypatch.chdir(tmp_path.parent)
    s = read_mesh_series(tmp_path / "u.xdmf", where=KEY)
    assert np.array_equal(s.vertices, x0 + (verts - x0)) and np.array_equal(s.faces, faces)


def test_series_volume_is_exact_between_frames():
    """The cubic per interval equals the divergence-theorem volume of the interpolated mesh at any t, and its rate
    the derivative; for a cube scaled by s(t) linear between frames, V = s^3 (closed form)."""
    import trimesh

    from cavity.volume import SeriesVolume, mesh_volume

    x0, faces = sphere()
    s = MeshSeries(T, frames(x0), faces)
    vol = SeriesVolume.of(s.times, s.vertices, s.triangles())
    for t in np.linspace(-1e-3, 8e-3, 37):
        # two sums of the same face terms in different orders: n·ε of the volume at most (terms of one sign)
        assert vol(t) == pytest.approx(mesh_volume(s.at(t), faces), rel=len(faces) * np.finfo(float).eps)
        h = 1e-7
        if T[0] < t - h and t + h < T[-1] and not np.any(np.abs(T - t) < 2 * h):
            assert vol.rate(t) == pytest.approx((vol(t + h) - vol(t - h)) / (2 * h), rel=1e-6)
    assert vol.rate(-1e-3) == 0.0 and vol.rate(T[-1]) == 0.0 and vol.breakpoints == tuple(T)
    cube = trimesh.creation.box()
    scale = np.array([1.0, 1.5, 1.2])
    c = MeshSeries([0.0, 1.0, 3.0], cube.vertices[None] * scale[:, None, None], cube.faces)
    v = SeriesVolume.of(c.times, c.vertices, c.triangles())
    for t, sc, ds in ((0.5, 1.25, 0.5), (2.0, 1.35, -0.15)):
        assert v(t) == pytest.approx(sc ** 3, rel=1e-14) and v.rate(t) == pytest.approx(3 * sc * sc * ds, rel=1e-13)


def test_quads_split_into_triangles_for_the_volume():
    x0, faces = plate()
    s = MeshSeries(T, frames(x0), faces)
    tri = s.triangles()
    assert tri.shape == (8 * 2 + 8, 3) and (tri >= 0).all()
    assert np.isclose(sum(np.linalg.norm(np.cross(x0[b] - x0[a], x0[c] - x0[a]), axis=0) / 2 for a, b, c in tri), 0.06)
