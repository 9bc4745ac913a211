"""`ventsim run --render` on airbag_impactor: annotated PNGs (colour bar, title) and a GIF off screen, the blocked
colour absent before and present after; a whole-scene view; a VTK series of every surface that meshio and pyvista
read, whose vent area is the one definition of :mod:`cases.results.leak_state`."""
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest
from PIL import Image

from cases.results.leak_state import leak_state
from cases.results.pictures import default_times, write_pictures, write_vtk
from cases.results.render import BLOCKED_RGB, UNBLOCKED_RGB, blocked_colour_fraction, fraction_rgb
from cases.results.render_annotate import COLOUR_BAR_WIDTH, view_part
from cases.run.runner import run_scene

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def pictures(tmp_path_factory):
    results = run_scene(ROOT / "cases" / "airbag_impactor.toml")
    out = tmp_path_factory.mktemp("pictures")
    return results, write_pictures(results, out, animation_frames=6)


def rgb(path):
    with Image.open(path) as picture:
        return np.asarray(picture.convert("RGB"))


def colour_bar_column(image):
    """(x, top, bottom) of a vertical run in the colour-bar strip going from the blocked colour (top) through
    pale yellow to the unblocked colour (bottom), every pixel on the scale :func:`fraction_rgb`; or None."""
    height, width = image.shape[:2]
    scale = fraction_rgb(np.linspace(0.0, 1.0, 1001)).astype(float)
    for x in range(width - COLOUR_BAR_WIDTH, width):
        column = image[:, x].astype(float)
        if np.count_nonzero(np.abs(column - 255).sum(axis=1)) < height // 2:
            continue  # mostly white: no bar here
        off_scale = np.min(np.linalg.norm(column[:, None, :] - scale[None], axis=2), axis=1) > 3.0
        on = np.flatnonzero(~off_scale & (np.abs(column - 255).sum(axis=1) > 0))
        if len(on) < height // 2:
            continue
        top, bottom = on[0], on[-1]
        if (np.all(~off_scale[top:bottom + 1]) and np.linalg.norm(column[top] - BLOCKED_RGB) < 3
                and np.linalg.norm(column[bottom] - UNBLOCKED_RGB) < 3):
            return x, top, bottom
    return None


def test_png_blocked_colour_absent_before_and_present_once_covered(pictures):
    results, written = pictures
    before, covered = written["png"]
    t_first = results.summary["blockage"]["vent"]["first blockage time [s]"]
    assert default_times(results, 0)[0] == 0.0 < t_first
    assert blocked_colour_fraction(view_part(rgb(before))) == 0.0
    assert blocked_colour_fraction(view_part(rgb(covered))) > 0.01
    img = Image.open(covered).convert("RGB")
    assert len(img.getcolors(1 << 20)) > 10  # not blank


def test_a_rendered_png_has_its_colour_bar(pictures):
    _, written = pictures
    for path in written["png"] + written["scene"]:
        image = rgb(path)
        found = colour_bar_column(image)
        assert found is not None, path
        x, top, bottom = found
        assert bottom - top > 0.7 * image.shape[0] and x >= image.shape[1] - COLOUR_BAR_WIDTH
    assert colour_bar_column(np.full((600, 930, 3), 255, np.uint8)) is None  # the finder can fail


def test_whole_scene_view_shows_the_cavity_bodies_and_vent(pictures):
    _, written = pictures
    (scene,) = written["scene"]
    view = view_part(rgb(scene)).reshape(-1, 3).astype(int)
    grey = (np.abs(view - view[:, :1]).max(axis=1) <= 2) & (view[:, 0] > 150) & (view[:, 0] < 250)
    assert grey.mean() > 0.05  # the translucent cushion covers a good part of the view
    assert blocked_colour_fraction(view.reshape(1, -1, 3).astype(np.uint8)) > 0.002


def test_animation(pictures):
    _, written = pictures
    with Image.open(written["gif"][0]) as gif:
        assert gif.n_frames >= 2


def test_meshio_and_pyvista_read_every_frame_of_every_surface(pictures):
    import pyvista as pv

    results, written = pictures
    *per_surface, scene = written["pvd"]
    assert [p.stem for p in per_surface] == ["cavity_cushion", "leakage_vent", "body_headform"]
    files = [e.get("file") for e in ET.parse(scene).getroot().findall("./Collection/DataSet")]
    assert len(files) == 3 * 6
    for name in files:
        mesh = meshio.read(scene.parent / name)
        grid = pv.read(scene.parent / name)
        assert mesh.points.shape == (grid.n_points, 3) and sum(len(c.data) for c in mesh.cells) == grid.n_cells
        if name.startswith("leakage"):
            assert {"active", "gap"} <= set(mesh.point_data) and "blocked_fraction" in mesh.cell_data
            assert float(mesh.field_data["leak_area"].ravel()[0]) > 0.0
        if name.startswith("cavity"):
            assert {"pressure", "gauge_pressure", "temperature"} <= set(mesh.cell_data)
        assert "displacement" in mesh.point_data or name.startswith("leakage")


def vtk_areas(results, folder, times):
    pvd = next(p for p in write_vtk(results, folder, times) if p.stem == "leakage_vent")
    files = [e.get("file") for e in ET.parse(pvd).getroot().findall("./Collection/DataSet")]
    return np.array([float(meshio.read(pvd.parent / f).field_data["leak_area"].ravel()[0]) for f in files])


def test_vtk_vent_area_is_the_leak_state_area_and_the_history_blocked_fraction(pictures, tmp_path):
    results, _ = pictures
    times = results.history[::25, 0]
    areas = vtk_areas(results, tmp_path, times)
    state = [leak_state(results.model, results.trajectory, 0, t) for t in times]
    assert np.array_equal(areas, [s.leak_area for s in state])
    blocked = results.history[::25, results.columns.index("vent.blocked_fraction [-]")]
    np.testing.assert_allclose(1.0 - areas / state[0].open_area, blocked, rtol=0, atol=1e-12)


@pytest.fixture(scope="module")
def dynamic():
    return run_scene(ROOT / "cases" / "airbag_impactor_dynamic.toml")


@pytest.mark.parametrize("case", ["prescribed", "dynamic"])
def test_vtk_vent_area_equals_the_history_area(pictures, dynamic, tmp_path, case):
    results = pictures[0] if case == "prescribed" else dynamic
    rows = slice(None, None, 10)
    areas = vtk_areas(results, tmp_path, results.history[rows, 0])
    history = results.history[rows, results.columns.index("vent.area [m^2]")]
    assert areas.min() < 0.9 * areas.max()  # the vent is covered in between
    np.testing.assert_allclose(areas, history, rtol=1e-12, atol=0)
