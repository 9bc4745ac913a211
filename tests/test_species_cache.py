"""The CoolProp fit cache (cavity.species_fits): a cached fit equals a fresh fit (to round-off in cp), the shipped table
covers every built-in species for the installed CoolProp, and a run that finds its fits never imports CoolProp."""
import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cavity import species_fits
from cavity.species import BUILTIN_COOLPROP_NAMES, coolprop_fit_key, fit_species_from_coolprop, species_from_coolprop

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = json.loads(species_fits.SHIPPED.read_text())


def test_the_shipped_fits_are_for_the_installed_coolprop_and_every_builtin():
    assert SHIPPED["coolprop"] == species_fits.coolprop_version()
    assert set(SHIPPED["fits"]) == {coolprop_fit_key(f, None, 100.0) for f in BUILTIN_COOLPROP_NAMES.values()}


@pytest.mark.parametrize("name", sorted(BUILTIN_COOLPROP_NAMES))
def test_a_cached_fit_equals_a_fresh_fit(name):
    """The shipped fit is the fit this machine makes: the same breaks, molar mass, range and source, and cp(T)
    equal to 1e-14 on a dense grid over the range and 50 K past each end. Not bit for bit: the shipped fits were
    made on another machine, whose LAPACK solved the least squares in another order; on this one the cubic
    coefficients differ by up to 1.3e-10 of their size (cancelling), cp by at most 8.9e-16 (measured). A fit cached
    on the machine that reads it is equal bit for bit (next test)."""
    cached, fresh = species_from_coolprop(name), fit_species_from_coolprop(name)
    assert dataclasses.replace(cached, pieces=fresh.pieces) == fresh
    T = np.linspace(cached.breaks[0] - 50.0, cached.breaks[-1] + 50.0, 4001)
    assert max(abs(cached.molar_cp(t) / fresh.molar_cp(t) - 1.0) for t in T) <= 1e-14


def test_a_fresh_fit_fills_the_user_cache_and_is_read_back(tmp_path, monkeypatch):
    monkeypatch.setenv("VENTSIM_CACHE_DIR", str(tmp_path))
    fresh = species_from_coolprop("N2", t_range=(250.0, 650.0), width=50.0)  # not shipped
    (cache,) = tmp_path.iterdir()
    assert cache.name == f"coolprop_fits-{species_fits.coolprop_version()}.json"
    assert species_fits.lookup(coolprop_fit_key("Nitrogen", (250.0, 650.0), 50.0)) is not None
    assert species_from_coolprop("N2", t_range=(250.0, 650.0), width=50.0) == fresh
    monkeypatch.setenv("VENTSIM_CACHE_DIR", "")
    assert species_fits.user_cache_file() is None


def test_a_run_with_builtin_species_does_not_import_coolprop():
    code = ("import sys; from cases.scene.files import load_scene; from cases.model.build import build_model; "
            "build_model(load_scene('cases/airbag_vented.toml')); print('CoolProp' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
