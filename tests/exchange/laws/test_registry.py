"""The law registry: every law's engine kernel against its own Python object, and a law added from outside the
package running on the engine without recompiling it."""
from __future__ import annotations

import copy
import math
from dataclasses import replace

import numba
import numpy as np
import pytest

from cases.model.build import build_model
from cases.scene.files import scene_from_dict
from cavity.integration import integrate
from cavity.tolerances import R_UNIVERSAL
from exchange.engine.layout import LAW_SIGNATURE, ExchangeInt, StateColumn
from exchange.laws import registry
from exchange.laws.discharge import DischargeTable
from exchange.laws.leakage_table import LeakageTable
from exchange.network.vent import GasPoint
from tests.exchange.laws import toy_law
from tests.scenes import tank

#: one object of each registered law, the tables they read included
OBJECTS = {
    "orifice": lambda m: m.OrificeLaw(DischargeTable((1e5, 3e5), (0.6, 0.8))),
    "fabric_leakage": lambda m: m.FabricLeakageLaw(0.7, 0.4),
    "graefe": lambda m: m.GraefeLaw(0.5, 0.3),
    "mass_rate_leakage": lambda m: m.LeakageTableLaw(LeakageTable((0.0, 1e4, 5e4), (0.0, 0.2, 0.5), "mass")),
    "mass_flux": lambda m: m.FluxLaw("mass", 0.3),
    "bulk_viscosity": lambda m: m.BulkViscosityLaw(2e3, 0.5),
    "linear_resistance": lambda m: m.LinearResistanceLaw(1e-6),
    "seal": lambda m: _seal_law(m),
}


def _seal_law(m):
    """A seal on a small ring under a flat flange 1 um away (penalty contact), with slip, evaluated half-way to
    touch."""
    from exchange.seal.film import seal_film
    from exchange.seal.gap_laws import ExponentialGap
    from exchange.seal.meshes import annulus_mesh, flat_flange_seat
    from exchange.seal.setup import seal_law

    v, f = annulus_mesh(0.01, 0.02, 2, 16)
    seat = flat_flange_seat(v, seal_film(v, f).areas, 1e-6)
    contact = np.array([1.0, 1e12, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.02])
    setup = m.seal.SealSetup(ExponentialGap(5e-6, 1e6, 1e-7), "exponential", "inner", "outer", 0.0, "sutherland",
                             "Nitrogen", True, -2e-6, 1e-6, math.nan, 1e-4)
    law = seal_law(m.seal.SealLaw(setup), v, f, "inner", "outer", seat, contact, (1e-6,))[0]
    return replace(law, load=0.5e-6)


def kernel_flow(law, up: GasPoint, p_down, area, t):
    """The law's flow through its registered kernel, on a one-cavity state scratch holding ``up``."""
    from exchange.engine.tables import Tables

    tables = Tables()
    slot, lf, li = registry.lowered(law, tables, -1, 0)
    tx, ty, ti = tables.arrays()
    st = np.zeros((1, StateColumn.FRACTIONS + 1))
    st[0, :6] = up.p, up.T, up.rho, up.R, up.gamma, up.h
    return registry.LAWS[slot].kernel(lf, li, tx, ty, ti, st, np.zeros(7), 0, p_down, area, t)


@pytest.mark.parametrize("name", list(OBJECTS))
def test_each_kernel_gives_its_law_objects_flow(name):
    """Naive against fast: the Python object's mass_flow (the pure law on a GasPoint) and the engine's kernel (the
    lowered parameters and tables) agree to round-off over pressures, temperatures and times."""
    import exchange.laws as laws

    law = OBJECTS[name](laws)
    assert registry.spec_of(law) is not None
    rng = np.random.default_rng(7)
    for _ in range(200):
        p_up, T = rng.uniform(0.5e5, 6e5), rng.uniform(250.0, 900.0)
        up = GasPoint(p_up, T, p_up / (296.8 * T), 296.8, 1.4, 1.04e3 * T, np.ones(1))
        p_down, area, t = p_up * rng.uniform(0.1, 1.2), rng.uniform(1e-5, 1e-2), rng.uniform(0.0, 0.1)
        expected = law.mass_flow(up, p_down, area, t)
        got = kernel_flow(law, up, p_down, area, t)
        assert got == pytest.approx(expected, rel=1e-13, abs=1e-300), (name, p_up, p_down)


def test_every_kernel_has_the_law_signature():
    for spec in registry.LAWS:
        assert tuple(spec.kernel.signatures) == (LAW_SIGNATURE.args,), spec.names


@pytest.fixture
def power_law():
    slot = registry.register(toy_law.LAW)
    try:
        yield slot
    finally:
        if toy_law.LAW in registry.LAWS:
            registry.LAWS.remove(toy_law.LAW)


def _tank_network(tmp_path):
    data = tank(pressure=3e5, energy="isothermal")
    data["time"]["end"] = 0.05
    data["exchange"] = [{"name": "vent", "from": "tank", "law": "linear_resistance", "conductance": 1e-6,
                         "area": 2e-4}]
    model = build_model(scene_from_dict(copy.deepcopy(data), tmp_path / "scene.toml"))
    return model, model.network


def test_a_law_added_outside_the_package_runs_on_the_engine(tmp_path, power_law):
    """The toy law (tests/exchange/laws/toy_law.py) registered from outside: its exchange lowers to its own slot
    (not the hosted Python call), the model's numba type is the one every scene has (so the engine is not compiled
    again), and the isothermal blowdown through ṁ = C·A·Δp equals its closed form
    p − p_a = (p0 − p_a)·exp(−C·A·R·T·t/V) to 1e-9."""
    model, net = _tank_network(tmp_path)
    plain_type = numba.typeof(net.engine().model)
    C, area = 3e-7, 2e-4
    net.exchanges = (replace(net.exchanges[0], law=toy_law.PowerLawLeak(C, 1.0), area=area),)
    traj = integrate(net, net.initial_state(), 0.0, 0.05, model.options)
    engine = net.compiled_solver()
    assert traj.path == "compiled" and engine.host == -1
    assert engine.arrays.exchange_int[0, ExchangeInt.LAW] == power_law
    assert numba.typeof(engine.model) == plain_type
    cav = net.cavities[0]
    R = R_UNIVERSAL / 0.0280134
    times = np.linspace(0.0, 0.05, 11)
    p = np.array([s[0].pressure for s in (net.states(t, traj(t)) for t in times)])
    expected = 1e5 + 2e5 * np.exp(-C * area * R * cav.initial_temperature * times / cav.volume.volume)
    np.testing.assert_allclose(p, expected, rtol=1e-9)


def test_a_law_added_outside_equals_its_hosted_python_run(tmp_path, power_law):
    """The same object registered (its kernel) and not (hosted: its Python mass_flow in numba's object mode): one
    history to 1e-12, for a non-linear exponent."""
    model, net = _tank_network(tmp_path)
    law = toy_law.PowerLawLeak(2e-6, 0.5)
    net.exchanges = (replace(net.exchanges[0], law=law),)
    times = np.linspace(0.0, 0.05, 21)
    runs = []
    for registered in (True, False):
        if not registered:
            registry.LAWS.remove(toy_law.LAW)
        net.exchanges = (replace(net.exchanges[0]),)  # a new network: lowered again, with the registry as it is
        traj = integrate(net, net.initial_state(), 0.0, 0.05, model.options)
        assert (net.compiled_solver().host >= 0) == (not registered)
        runs.append([s[0].pressure for s in (net.states(t, traj(t)) for t in times)])
    registry.register(toy_law.LAW)  # the fixture removes it
    np.testing.assert_allclose(runs[0], runs[1], rtol=1e-12)
    assert not math.isclose(runs[0][-1], runs[0][0])
