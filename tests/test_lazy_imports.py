"""What a process loads: ``import ventsim`` nothing heavy, a compiled run no scipy.integrate, no plotting or
distributed package, until a picture, a plot or a sweep asks for it (and a scene without seal or mesh no
scipy.optimize, scipy.sparse or trimesh); the DOP853 tableau read without
scipy.integrate is scipy's."""
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def loaded(code: str, names) -> dict:
    """{name: whether the module is in sys.modules} after running ``code`` in a fresh interpreter."""
    probe = f"{code}\nimport sys\nprint(' '.join(str(int(n in sys.modules)) for n in {list(names)!r}))"
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, check=True)
    return dict(zip(names, (s == "1" for s in out.stdout.split()[-len(names):])))


def test_import_ventsim_loads_nothing_heavy():
    heavy = ["numba", "scipy", "numpy", "trimesh", "matplotlib", "pyvista", "pandas", "dask", "CoolProp"]
    found = loaded("import ventsim", heavy)
    assert not any(found.values()), found
    # the public names still arrive on first use
    names = loaded("import ventsim\nventsim.load, ventsim.run, ventsim.Scene, ventsim.Results", ["numba"])
    assert names["numba"]


def test_a_compiled_run_loads_no_integrator_plotting_or_cluster_package():
    code = ("from cases.run.runner import run_scene\n"
            "r = run_scene('cases/verification/blowdown_choked.toml')\n"
            "assert r.summary['solver']['path'] == 'compiled'")
    found = loaded(code, ["scipy.integrate", "matplotlib", "pyvista", "dask", "distributed", "pandas",
                          "scipy.optimize", "scipy.sparse", "trimesh", "networkx"])  # no seal, no mesh
    assert not any(found.values()), found


def test_the_main_job_up_to_its_history_and_summary_draws_nothing(tmp_path):
    """The README's main job built, solved and written (history.csv, summary.json) without the plot or pictures."""
    code = ("from cases.run.runner import run_scene\n"
            "from cases.results.output import write_history, write_summary\n"
            "r = run_scene('cases/airbag_impactor_dynamic.toml')\n"
            f"write_history({str(tmp_path / 'history.csv')!r}, r.columns, r.history)\n"
            f"write_summary({str(tmp_path / 'summary.json')!r}, r.summary)")
    found = loaded(code, ["matplotlib", "pyvista", "vtk", "scipy.integrate", "pandas", "dask"])
    assert not any(found.values()), found
    assert (tmp_path / "history.csv").is_file() and (tmp_path / "summary.json").is_file()


def test_the_tableau_is_scipys():
    from scipy.integrate._ivp import dop853_coefficients as scipy_tableau

    from cavity.dop853_tableau import tableau

    ours = tableau()
    assert ours.N_STAGES == scipy_tableau.N_STAGES == 12
    for name in ("A", "B", "C", "E3", "E5", "D"):
        assert np.array_equal(getattr(ours, name), getattr(scipy_tableau, name)), name
