"""The wrapped-volume fits kept on disk: a fit read back is the fresh one bit for bit, a damaged file is computed
again, an empty VENTSIM_CACHE_DIR keeps nothing."""
import os
from pathlib import Path

import numpy as np
import pytest

from cases.model import fit_cache
from cases.model import wrapped_volume as wv
from cases.model.build import build_model
from cases.scene.files import load_scene

SCENE = Path(__file__).resolve().parents[1] / "cases" / "airbag_impactor.toml"


def _volume(scene):
    """The cushion's wrapped volume built afresh in this process (the in-process fits emptied first)."""
    wv._FITS.clear()
    return build_model(scene).network.cavities[0].volume


def fresh_knots(volume):
    """The fit's knots in s of a volume built in time (its own, not the spline's knots in t)."""
    return next(iter(wv._FITS.values()))[0].knots


def _same(a, b) -> bool:
    return (np.array_equal(a.spline.x, b.spline.x) and np.array_equal(a.spline.c, b.spline.c)
            and a.bound == b.bound and type(a.bound) is type(b.bound) and a.breakpoints == b.breakpoints)


@pytest.fixture
def scene():
    return load_scene(SCENE)


def test_a_stored_fit_is_read_back_bit_for_bit(scene, tmp_path, monkeypatch):
    monkeypatch.setenv("VENTSIM_CACHE_DIR", str(tmp_path))
    fresh = _volume(scene)
    files = list((tmp_path / "wrap_fits").glob("*.npz"))
    assert len(files) == 1
    computed = []
    monkeypatch.setattr("cases.model.wrap_pieces.convex_planes", lambda *a: computed.append(1))
    read = _volume(scene)
    assert not computed  # read back, not computed
    assert _same(fresh, read)


def test_a_damaged_file_is_computed_again(scene, tmp_path, monkeypatch):
    monkeypatch.setenv("VENTSIM_CACHE_DIR", str(tmp_path))
    fresh = _volume(scene)
    (path,) = (tmp_path / "wrap_fits").glob("*.npz")
    path.write_bytes(b"not a zip file")
    assert _same(fresh, _volume(scene))
    with np.load(path) as stored:  # stored again, readable
        assert np.array_equal(stored["knots"], fresh_knots(fresh))


def test_an_empty_cache_dir_keeps_nothing(scene, tmp_path, monkeypatch):
    monkeypatch.setenv("VENTSIM_CACHE_DIR", "")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setenv("HOME", str(tmp_path))
    _volume(scene)
    assert fit_cache.fit_file("any") is None
    assert not list(tmp_path.rglob("*.npz"))


def test_only_the_newest_files_are_kept(tmp_path, monkeypatch):
    monkeypatch.setenv("VENTSIM_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(fit_cache, "MAX_FILES", 3)
    from cases.model.wrap_fit import HermiteFit

    fit = HermiteFit(np.array([0.0, 1.0]), np.array([0.0, 2.0]), np.array([1.0]), np.array([3.0]), np.float64(0.5))
    for k in range(5):
        fit_cache.store_fit(f"key{k}", fit, 1.0)
        os.utime(fit_cache.fit_file(f"key{k}"), (1000 + k, 1000 + k))  # distinct ages, oldest first
    kept = sorted(p.name for p in (tmp_path / "wrap_fits").glob("*.npz"))
    assert kept == sorted(fit_cache.fit_file(f"key{k}").name for k in (2, 3, 4))
    read, v0 = fit_cache.load_fit("key4")
    assert v0 == 1.0 and read.bound == 0.5 and np.array_equal(read.end, fit.end)
