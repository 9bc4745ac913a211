"""`ventsim run --render` on airbag_impactor: PNGs and a GIF off screen, blocked colour absent before, present after."""
from pathlib import Path

import pytest
from PIL import Image

from cases.pictures import default_times, write_pictures
from cases.render import blocked_colour_fraction
from cases.runner import run_scene

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def pictures(tmp_path_factory):
    results = run_scene(ROOT / "cases" / "airbag_impactor.toml")
    out = tmp_path_factory.mktemp("pictures")
    return results, write_pictures(results, out, animation_frames=6)


def test_png_blocked_colour_absent_before_and_present_once_covered(pictures):
    results, written = pictures
    before, covered = written["png"]
    t_first = results.summary["blockage"]["vent"]["first blockage time [s]"]
    assert default_times(results, 0)[0] == 0.0 < t_first
    assert blocked_colour_fraction(before) == 0.0
    assert blocked_colour_fraction(covered) > 0.01
    img = Image.open(covered).convert("RGB")
    assert len(img.getcolors(1 << 20)) > 10  # not blank


def test_animation_and_vtk_series(pictures):
    _, written = pictures
    gif = Image.open(written["gif"][0])
    assert gif.n_frames >= 2
    pvd = written["pvd"][0].read_text()
    assert pvd.count("<DataSet") == 6 and (written["pvd"][0].parent / "vent_0005.vtp").is_file()
