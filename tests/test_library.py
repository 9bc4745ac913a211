"""Regression: every case of the library reproduces its reference history (tolerance: cases.run.library.RTOL)."""
import numpy as np
import pytest

from cases.run.library import CASES, RTOL, check_case, column_errors, read_reference, reference_path


@pytest.mark.parametrize("name", list(CASES))
def test_case_matches_reference(name):
    result = check_case(name)
    assert result.passed, f"{name}: {result.worst_column} differs by {result.error:.3e} > {RTOL} {result.message}"
    assert result.path == "compiled", (name, result.path)  # every library case runs on the one engine


def test_check_detects_a_changed_history():
    cols, ref = read_reference(reference_path("blowdown_choked"))
    changed = ref.copy()
    changed[-1, 1] *= 1 + 10 * RTOL
    errors = column_errors(cols, changed, cols, ref)
    assert errors["tank.pressure [Pa]"] > RTOL and errors["time [s]"] == 0.0
    assert column_errors(cols[:-1], ref[:, :-1], cols, ref) == {"(shape or columns)": np.inf}


def test_cli_check_prints_table(capsys):
    from cases.cli import main

    assert main(["check", "fill_constant", "blowdown_choked"]) == 0
    out = capsys.readouterr().out
    assert "fill_constant" in out and "PASS" in out and "2 passed, 0 failed" in out
    assert main(["check", "fill_constnt"]) == 2
    assert "did you mean 'fill_constant'" in capsys.readouterr().err


@pytest.mark.parametrize("name", list(CASES))
def test_peak_pressure_independent_of_output_interval(name):
    """Ten times finer output: peak pressures agree to 1e-8 (they are located on the dense output)."""
    from dataclasses import replace

    from cases.model.build import build_model
    from cases.run.library import HERE
    from cases.run.runner import run
    from cases.scene.files import load_scene

    scene = load_scene(HERE / CASES[name])
    fine = replace(scene, time=replace(scene.time, output_interval=(scene.time.output_interval
                                                                    or scene.time.end / 500) / 10))
    a, b = (run(build_model(s)).summary["cavities"] for s in (scene, fine))
    for cav in a:
        pa, pb = a[cav]["peak pressure [Pa]"], b[cav]["peak pressure [Pa]"]
        assert abs(pa / pb - 1.0) <= 1e-8, (cav, pa, pb)


def test_wrapped_volume_run_converges_in_rtol():
    """airbag_impactor (a prescribed body wrapped by the cushion): the wrapped volume's spline knots are stops, so
    the peak pressure and the pressure history converge monotonically down the rtol ladder to round-off; with the
    knots straddled the error stalled near 3e-8 of the pressure whatever the rtol."""
    from dataclasses import replace

    from cases.model.build import build_model
    from cases.run.library import HERE
    from cases.run.runner import run
    from cases.scene.files import load_scene

    model = build_model(load_scene(HERE / CASES["airbag_impactor"]))
    runs = [run(replace(model, options=replace(model.options, rtol=r))) for r in (1e-4, 1e-6, 1e-8, 1e-12)]
    c = runs[0].columns.index("cushion.pressure [Pa]")
    ref = runs[-1].history[:, c]
    errors = [float(np.max(np.abs(r.history[:, c] - ref)) / ref.max()) for r in runs[:-1]]
    assert all(b <= a for a, b in zip(errors, errors[1:])) and errors[-1] <= 1e-12, errors
    volume = model.network.cavities[0].volume
    assert set(volume.spline.x[1:-1]) <= set(volume.breakpoints) and len(volume.spline.x) > 100


@pytest.mark.parametrize("integrator", ["compiled", "scipy"])
def test_volume_of_a_dynamic_body_converges_in_rtol(integrator):
    """airbag_impactor_dynamic (the cushion's volume a spline of the headform's displacement, a state): the
    knots bounding the spline piece a segment holds are switches, so no step straddles a knot's jump in the third
    derivative and the pressure history converges down the ladder (measured 1.6e-5, 1.6e-5, 3.6e-7, 8.0e-12 of
    the peak at rtol 1e-4, 1e-6, 1e-8, 1e-10 against 1e-12; with the knots straddled 3.5e-3, 7.1e-5, 1.8e-6,
    8.2e-7), on both integrators."""
    from dataclasses import replace

    from cases.model.build import build_model
    from cases.run.library import HERE
    from cases.run.runner import run
    from cases.scene.files import load_scene

    model = build_model(load_scene(HERE / CASES["airbag_impactor_dynamic"]))
    ladder = (1e-6, 1e-8, 1e-10, 1e-12) if integrator == "compiled" else (1e-8, 1e-10, 1e-12)
    runs = [run(replace(model, options=replace(model.options, rtol=r, integrator=integrator))) for r in ladder]
    assert {r.summary["solver"]["path"] for r in runs} == {"compiled" if integrator == "compiled"
                                                          else "compiled, solve_ivp"}
    c = runs[0].columns.index("cushion.pressure [Pa]")
    ref = runs[-1].history[:, c]
    errors = [float(np.max(np.abs(r.history[:, c] - ref)) / ref.max()) for r in runs[:-1]]
    assert all(b <= a for a, b in zip(errors, errors[1:])) and errors[-1] <= 1e-10, errors
    assert runs[-1].summary["solver"]["events"] > 50  # the knots the headform passes, each a switch


def test_a_dynamic_body_on_a_leakage_surface_that_moves_in_time_is_refused(tmp_path):
    """airbag_impactor_dynamic with the cushion's mesh scaled by a table of time: the headform's blockage track is
    one of its displacement, the surface's motion one of time, so the scene is refused on the blocking key with
    what to do instead (it used to run, reading the time table at the displacement)."""
    from cases.model.build import build_model
    from cases.run.library import HERE
    from cases.scene.errors import SceneError
    from cases.scene.files import load_scene

    (tmp_path / "scale.csv").write_text("time,scale\n0,1\n0.06,1.05\n")
    text = (HERE / CASES["airbag_impactor_dynamic"]).read_text()
    for folder in ("meshes", "data"):
        text = text.replace(f'"{folder}/', f'"{(HERE / folder).as_posix()}/')
    assert 'wrapped_by = ["headform"]' in text
    path = tmp_path / "scaled.toml"
    scaled = 'wrapped_by = ["headform"]\nmesh_scale_table = "scale.csv"'
    path.write_text(text.replace('wrapped_by = ["headform"]', scaled, 1))
    with pytest.raises(SceneError, match=r"exchange\[0\]\.blocked_by: the leakage surface scales .* prescribed motion"):
        build_model(load_scene(path))
