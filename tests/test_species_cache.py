"""The CoolProp fit cache (cavity.species_fits): a cached fit equals a fresh fit bit for bit, the shipped table
covers every built-in species for the installed CoolProp, and a run that finds its fits never imports CoolProp."""
import json
import subprocess
import sys
from pathlib import Path

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
    assert species_from_coolprop(name) == fit_species_from_coolprop(name)


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
