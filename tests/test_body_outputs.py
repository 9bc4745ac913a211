"""The headform drop's history: displacement, velocity and acceleration obey the equations of motion."""
import numpy as np
import pytest
from scipy.integrate import cumulative_simpson

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import load_scene
from exchange.readback.values import body_values, load_mode
from tests.conftest import ROOT


@pytest.fixture(scope="module")
def drop():
    model = build_model(load_scene(ROOT / "cases" / "airbag_impactor_dynamic.toml"))
    return run(model)


def test_acceleration_is_gravity_plus_the_gas_force_over_the_mass(drop):
    a, f = drop.column("headform.acceleration"), drop.column("headform.gas_force")
    motion = drop.model.network.body.motion
    np.testing.assert_allclose(a, motion.gravity + f / motion.mass, rtol=1e-12, atol=1e-12 * np.abs(a).max())
    # the cushion pushes back (against the axis) while it is covered; the C² spline of the wrapped volume rings
    # a little near the first contact (a 0.1 % bump of the wrong sign)
    assert f.min() < -1000.0 and f.max() <= 2e-3 * -f.min()


def test_velocity_and_displacement_integrate_the_acceleration(drop):
    """Over 50 µs windows on the dense output (Simpson on 201 points): v = v0 + ∫a dt, s = s0 + ∫v dt to 1e-8."""
    net, traj = drop.model.network, drop.trajectory
    k = net.body_offset
    for t0 in (0.0031, 0.0152, 0.0298, 0.0451):
        ts = np.linspace(t0, t0 + 5e-5, 201)
        ys = traj.sample(ts)
        acc = []
        for t, y in zip(ts, ys):
            load_mode(net.engine(), traj.mode_at(t))
            acc.append(body_values(net.engine(), t, y)[1])
        v = ys[0, k + 1] + cumulative_simpson(np.array(acc), x=ts, initial=0.0)
        s = ys[0, k] + cumulative_simpson(ys[:, k + 1], x=ts, initial=0.0)
        scale_v, scale_s = np.abs(ys[:, k + 1]).max(), np.abs(ys[:, k]).max() + 1e-3
        assert np.max(np.abs(v - ys[:, k + 1])) <= 1e-8 * scale_v
        assert np.max(np.abs(s - ys[:, k])) <= 1e-8 * scale_s


def test_history_columns_match_the_trajectory(drop):
    net, traj = drop.model.network, drop.trajectory
    t = drop.column("time")
    ys = traj.sample(t)
    np.testing.assert_array_equal(drop.column("headform.displacement"), ys[:, net.body_offset])
    np.testing.assert_array_equal(drop.column("headform.velocity"), ys[:, net.body_offset + 1])
    assert drop.summary["impactor"]["deepest displacement [m]"] >= drop.column("headform.displacement").max()
