"""A wall of several materials (cavity/wall_materials.py): a composite slab's steady state exactly, its transient
converging at second order to the series solution, one material the same as the one-material wall, and the
scene keys' one-line errors."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cavity.wall import Wall
from cavity.wall_materials import WallMaterial, series_resistance
from tests.closed_forms import two_layer_slab_mean
from tests.realgas.test_realgas_scenes import SCENE

ALUMINIUM = dict(conductivity=237.0, density=2700.0, heat_capacity=900.0)
CFRP = dict(conductivity=0.5, density=1360.0, heat_capacity=1020.0)


def _wall(materials, inner_h, outer_h, area=1.0, outer_area=None, T0=300.0, T_amb=290.0):
    return Wall(0.0, 0.0, area, outer_area or area, inner_h, outer_h, 1.0, T0, T_amb, materials=materials)


def _rates(wall, T_gas):
    def rates(t, T):
        q_in, q_out = wall.heat_flows(None, 0.0, T_gas, T[0], 0.0, T[-1])
        return wall.layer_rates(T, q_in, q_out)
    return rates


@pytest.mark.parametrize("n_liner, n_shell", [(1, 1), (2, 3), (7, 5), (16, 40)])
def test_steady_state_of_a_composite_slab_is_exact(n_liner, n_shell):
    """5 mm aluminium in n_liner cells, 20 mm composite in n_shell, between gas at 350 K (h 100 W/(m² K)) and an
    ambient at 290 K (8 W/(m² K)): at steady state the flux through every face is ΔT/(1/h_i + Σ t/k + 1/h_o)
    for any number of cells (the finite-volume scheme is exact for a slab). Bound: the solve's forward error is at
    most about cond(G)·ε relative to the temperatures (Higham, Accuracy and Stability of Numerical Algorithms,
    §7.1), and the film's 3.4 K is 1e-2 of them, so the flux's is cond(G)·ε·T_gas/ΔT_film, times 10 for the
    backward error of LU: 1e-13 for one cell each, 6e-7 for 16 + 40 (cond 2.5e6), which measured 1e-12 to 2.4e-10
    with different numpy/LAPACK builds. A wrong cell conductance is off by 1e-3 or more."""
    materials = (WallMaterial(0.005, **ALUMINIUM, layers=n_liner), WallMaterial(0.020, **CFRP, layers=n_shell))
    wall = _wall(materials, 100.0, 8.0)
    rates = _rates(wall, 350.0)
    n = wall.layers
    C = np.asarray(wall.capacities)  # C·rates are heat flows, affine in T: solve G T + b = 0 (G symmetric)
    base = C * rates(0.0, np.zeros(n))
    G = np.column_stack([C * rates(0.0, np.eye(n)[j]) - base for j in range(n)])
    T = np.linalg.solve(G, -base)
    T -= np.linalg.solve(G, G @ T + base)  # one step of iterative refinement
    q_in, q_out = wall.heat_flows(None, 0.0, 350.0, T[0], 0.0, T[-1])
    exact = 60.0 / series_resistance(100.0, 8.0, (0.005, 0.020), (237.0, 0.5))
    bound = 10.0 * np.linalg.cond(G) * np.finfo(float).eps * 350.0 / (350.0 - T[0])
    assert q_in == pytest.approx(exact, rel=bound) and q_out == pytest.approx(exact, rel=bound)
    assert n == n_liner + n_shell


def test_transient_converges_to_the_series_solution():
    """A 5 mm steel liner (k 45 W/(m K), ρc 3.9e6 J/(m³ K)) under 10 mm of composite (0.5, 1.39e6), 300 K, its
    liner's face to gas at 200 K through h = 500 W/(m² K), the outside adiabatic, for 200 s (heat reaches the
    composite's far half): the mean temperature of N = 2 … 32 cells per material approaches the two-layer series
    solution monotonically at second order (error ratio 4.06, 4.01, 4.00, 4.00 a halving; 1.1e-2 at N = 2 →
    4.4e-5 at 32)."""
    steel, shell = (0.005, 45.0, 3.9e6), (0.010, 0.5, 1360.0 * 1020.0)
    T0, Tf, t_end, h = 300.0, 200.0, 200.0, 500.0
    exact = two_layer_slab_mean(t_end, h, steel, shell)
    errors = []
    for n in (2, 4, 8, 16, 32):
        materials = (WallMaterial(steel[0], steel[1], 7800.0, 500.0, n),
                     WallMaterial(shell[0], shell[1], 1360.0, 1020.0, n))
        wall = _wall(materials, h, 0.0, T0=T0)
        T = solve_ivp(_rates(wall, Tf), (0.0, t_end), [T0] * wall.layers, method="Radau", rtol=1e-12,
                      atol=1e-10).y[:, -1]
        mean = sum(C * (Tj - Tf) for C, Tj in zip(wall.capacities, T)) / (sum(wall.capacities) * (T0 - Tf))
        errors.append(abs(mean - exact))
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert all(3.5 < a / b < 4.5 for a, b in zip(errors, errors[1:])), errors
    assert errors[-1] < 6e-5, errors


def test_one_material_is_the_one_material_wall():
    """One material in N cells is the wall of wall_mass, wall_conductivity, wall_thickness and wall_layers with
    the same mass: same capacities, conductances and rates to 1e-14 (a cylinder's areas, A_o > A_i)."""
    steel = WallMaterial(0.025, 45.0, 7800.0, 500.0, 8)
    layered = _wall((steel,), 40.0, 5.0, 1.42, 1.76)
    mass = 7800.0 * 0.025 * 0.5 * (1.42 + 1.76)
    assert layered.mass == pytest.approx(mass, rel=1e-14) and layered.heat_capacity == pytest.approx(500.0, rel=1e-14)
    one = Wall(mass, 500.0, 1.42, 1.76, 40.0, 5.0, 1.0, 300.0, 290.0, layers=8, conductivity=45.0, thickness=0.025)
    assert np.allclose(layered.capacities, one.capacities, rtol=1e-14, atol=0)
    T = np.linspace(250.0, 290.0, 8)
    q1, q2 = layered.heat_flows(None, 0.0, 240.0, T[0], 0.0, T[-1]), one.heat_flows(None, 0.0, 240.0, T[0], 0.0, T[-1])
    assert np.allclose(q1, q2, rtol=1e-14, atol=0)
    assert np.allclose(layered.layer_rates(T, *q1), one.layer_rates(T, *q2), rtol=1e-12, atol=0)


def test_a_bad_material_is_refused():
    with pytest.raises(ValueError, match="'liner'.*must be > 0"):
        WallMaterial(0.005, 0.0, 2700.0, 900.0, 2, "liner")


WALL = SCENE + """energy = "wall"
wall_inner_area = 0.3
wall_outer_area = 0.4
wall_outer_h = 5.0
wall_length = 0.5
[[cavity.wall_materials]]
name = "liner"
thickness = 0.005
conductivity = 237.0
density = 2700.0
heat_capacity = 900.0
layers = 2
[[cavity.wall_materials]]
name = "shell"
thickness = 0.02
conductivity = 0.5
density = 1360.0
heat_capacity = 1020.0
"""


@pytest.mark.parametrize("old,new,where,what", [
    ("wall_length = 0.5", "wall_length = 0.5\nwall_mass = 3.0", "cavity[0].wall_mass", "not both"),
    ("wall_length = 0.5", "wall_length = 0.5\nwall_layers = 4", "cavity[0].wall_layers", "not both"),
    ("thickness = 0.005\n", "", "cavity[0].wall_materials[0].thickness", "missing required key"),
    ("conductivity = 0.5", "conductivity = -0.5", "cavity[0].wall_materials[1].conductivity", "> 0"),
    ("layers = 2", "layers = 0", "cavity[0].wall_materials[0].layers", "from 1 to 200"),
    ("density = 1360.0", "densty = 1360.0", "cavity[0].wall_materials[1].densty", "did you mean 'density'"),
    ('name = "shell"', 'name = "liner"', "cavity[0].wall_materials", "used twice"),
    ("wall_inner_area = 0.3\n", "", "cavity[0].wall_inner_area", "required"),
])
def test_bad_wall_materials_name_the_key(tmp_path, old, new, where, what):
    """Each bad wall_materials key stops the load with one line naming it."""
    from cases.scene.errors import SceneError
    from cases.scene.files import load_scene

    assert old in WALL
    (tmp_path / "s.toml").write_text(WALL.replace(old, new, 1))
    with pytest.raises(SceneError) as exc:
        load_scene(tmp_path / "s.toml")
    assert where in str(exc.value) and what in str(exc.value) and "\n" not in str(exc.value), str(exc.value)


def test_a_scene_wall_of_materials_is_built_from_them(tmp_path):
    """The scene's two materials become the cavity's wall: 2 + 4 (the default) cells, its mass the materials'
    ρ·t·(mean area) summed, the insulated outside (wall_outer_h = 0) allowed."""
    from cases.model.build import build_model
    from cases.scene.files import load_scene

    (tmp_path / "s.toml").write_text(WALL.replace("wall_outer_h = 5.0", "wall_outer_h = 0.0"))
    wall = build_model(load_scene(tmp_path / "s.toml")).network.cavities[0].wall
    assert wall.layers == 6 and [m.name for m in wall.materials] == ["liner", "shell"]
    A = lambda x: 0.3 + 0.1 * x / 0.025  # noqa: E731  the area through the wall
    mass = 2700.0 * 0.005 * 0.5 * (A(0) + A(0.005)) + 1360.0 * 0.02 * 0.5 * (A(0.005) + A(0.025))
    assert wall.mass == pytest.approx(mass, rel=1e-14)
    assert wall.heat_flows(None, 0.0, 300.0, 300.0, 0.0, 350.0)[1] == 0.0
