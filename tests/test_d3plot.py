"""LS-DYNA d3plot results in: parts of a d3plot written by lasso-python become mesh series that run exactly as the
equivalent .npz series; wrong parts and node orders are one-line errors naming the file and the part."""
import numpy as np
import pytest

import blockage
from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.errors import SceneError
from cases.scene.files import scene_from_dict
from tests.scenes import tank
from tests.test_blockage_over_time import TOL, grid_vent, plate_frames

lasso = pytest.importorskip("lasso.dyna", reason="the d3plot reader needs lasso-python (ventsim[lsdyna])")

TIMES = np.linspace(0.0, 0.03, 7)


def write_d3plot(folder, plate, plate_frames_, vent, units=1.0, time_unit=1.0):
    """A double-precision d3plot of three shell parts: 3 the plate (triangles), 5 the vent (quads, fixed), 7 a
    stray quad; node ids and element ids as a model would number them; coordinates divided by ``units``."""
    from lasso.dyna import ArrayType as A, D3plot

    n_p, n_v = len(plate.vertices), len(vent.vertices)
    stray = np.array([[1.0, 1.0, 1.0], [1.1, 1.0, 1.0], [1.1, 1.1, 1.0], [1.0, 1.1, 1.0]])
    x0 = np.concatenate([plate.vertices, vent.vertices, stray])
    tri = np.asarray(plate.faces)
    shells = np.concatenate([np.column_stack([tri, tri[:, 2]]), np.asarray(vent.faces) + n_p,
                             np.array([[0, 1, 2, 3]]) + n_p + n_v])
    parts = np.concatenate([np.zeros(len(tri)), np.ones(len(vent.faces)), [2]]).astype(int)
    coords = np.stack([np.concatenate([f, vent.vertices, stray]) for f in plate_frames_])
    d3 = D3plot()
    d3.header.ftype, d3.header.itype, d3.header.wordsize = np.float64, np.int64, 8  # double precision
    d3.arrays[A.node_coordinates] = x0 / units
    d3.arrays[A.node_ids] = 1000 + 3 * np.arange(len(x0))
    d3.arrays[A.element_shell_node_indexes] = shells
    d3.arrays[A.element_shell_part_indexes] = parts
    d3.arrays[A.element_shell_ids] = np.arange(1, len(shells) + 1)
    d3.arrays[A.part_ids] = np.array([3, 5, 7])
    d3.arrays[A.node_displacement] = coords / units
    d3.arrays[A.global_timesteps] = TIMES / time_unit
    (folder / "run").mkdir(exist_ok=True)
    d3.write_d3plot(str(folder / "run" / "d3plot"))


def scenes(tmp_path, body_parts=(3,), vent_parts=(5,), **fe_run):
    grid_vent(tmp_path / "vent.obj")
    vent = blockage.LeakageSurface.read(tmp_path / "vent.obj")
    plate, frames = plate_frames(TIMES)
    np.savez(tmp_path / "plate.npz", times=TIMES, vertices=frames, faces=np.asarray(plate.faces))
    np.savez(tmp_path / "vent.npz", times=TIMES, vertices=np.repeat(vent.vertices[None], len(TIMES), axis=0),
             faces=vent.faces)
    units = {"SI": (1.0, 1.0), "mm-kg-ms": (1e-3, 1e-3)}[fe_run.get("units", "SI")]
    write_d3plot(tmp_path, plate, frames, vent, *units)
    out = []
    for body, leak in (({"mesh_series": "plate.npz"}, {"leakage_surface": "vent.npz"}),
                       ({"mesh_series": "run/d3plot", "parts": list(body_parts)},
                        {"leakage_surface": "run/d3plot", "parts": list(vent_parts)})):
        data = tank(pressure=2.0e5)
        data["time"] = {"end": 0.03, "output_interval": 0.0005}
        data["body"] = [{"name": "plate", **body}]
        data["exchange"] = [{"name": "vent", "from": "tank", "blocked_by": ["plate"], "contact_tolerance": TOL,
                             **leak}]
        if fe_run:
            data["fe_run"] = fe_run
        out.append(data)
    return out


@pytest.mark.parametrize("units", ["SI", "mm-kg-ms"])
def test_a_d3plot_gives_the_history_of_the_equivalent_npz_series(tmp_path, units):
    npz, d3 = (scene_from_dict(d, tmp_path / "scene.toml") for d in scenes(tmp_path, units=units))
    a, b = run(build_model(npz)), run(build_model(d3))
    assert len(a.model.network.areas[0].track.crossings) >= 6  # columns touch and release
    np.testing.assert_allclose(b.history, a.history, rtol=1e-12, atol=1e-300)
    for rule in ("radioss", "lsdyna_cpg"):  # and under an FE rule too
        x, y = (scene_from_dict({**d, "blockage": {"rule": rule, "step": 1e-3}}, tmp_path / "scene.toml")
                for d in scenes(tmp_path, units=units))
        np.testing.assert_allclose(run(build_model(y)).history, run(build_model(x)).history, rtol=1e-12)


def test_a_wrong_part_is_a_one_line_error_naming_the_file_and_the_part(tmp_path):
    _, d3 = scenes(tmp_path, body_parts=(4,))
    with pytest.raises(SceneError, match=r"body\[0\]\.mesh_series: .*run/d3plot: part 4 is not in this d3plot; "
                                         r"its parts are \[3, 5, 7\]") as err:
        build_model(scene_from_dict(d3, tmp_path / "scene.toml"))
    assert "\n" not in str(err.value)
    _, d3 = scenes(tmp_path)
    d3["exchange"][0].pop("parts")
    with pytest.raises(SceneError, match=r"exchange\[0\]\.leakage_surface: .*name the parts"):
        build_model(scene_from_dict(d3, tmp_path / "scene.toml"))
    npz, _ = scenes(tmp_path)
    npz["body"][0]["parts"] = [3]
    with pytest.raises(SceneError, match=r"body\[0\]\.parts: parts apply to an LS-DYNA d3plot"):
        scene_from_dict(npz, tmp_path / "scene.toml")


def test_a_node_order_that_is_not_the_meshs_is_a_one_line_error_naming_the_part(tmp_path):
    import trimesh

    _, d3 = scenes(tmp_path)
    plate, _ = plate_frames(TIMES)
    order = np.random.default_rng(3).permutation(len(plate.vertices))
    shuffled = trimesh.Trimesh(plate.vertices[order], np.argsort(order)[plate.faces], process=False)
    shuffled.export(tmp_path / "plate.ply")
    d3["body"][0] = {"name": "plate", "mesh": "plate.ply", "vertex_trajectory": "run/d3plot", "parts": [3]}
    with pytest.raises(SceneError, match=r"body\[0\]\.vertex_trajectory: .*d3plot parts \[3\]") as err:
        build_model(scene_from_dict(d3, tmp_path / "scene.toml"))
    assert "\n" not in str(err.value)
