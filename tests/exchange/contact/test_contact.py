"""Contact mechanics of issue 7: analytic oracles for pressure-overclosure, damping and CPRESS."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from exchange.contact import (
    ContactDamping, Hard, LinearPenalty, Softened, contact_stiffness, cpress, critical_damping_coefficient,
    damping_coefficient, damping_pressure, default_critical_fraction, hard_contact_pressure, overclosure_pressure,
    suggest_mu0, suggest_mu0_euler_column,
)

MASS, AREA, K_PEN, V_IN = 2.0, 1e-4, 1e10, 1.5  # kg, m², Pa/m, m/s -> k_c = 1e6 N/m


def _drop(zeta, t_end_periods=1.0):
    """Rigid mass entering a damped linear-penalty contact at V_IN, gravity off; returns the solve_ivp result."""
    law = LinearPenalty(K_PEN)
    k_c = AREA * contact_stiffness(1e-9, law)
    c = critical_damping_coefficient(zeta, MASS, k_c)
    rule = ContactDamping(mu0=c / AREA, style="explicit")

    def rhs(t, y):
        p, _ = cpress(y[0], y[1], law, rule)  # trial stages may peek past h = 0: open, p = 0
        return [y[1], -AREA * p / MASS]

    def leave(t, y):
        return y[0]
    leave.terminal, leave.direction = True, -1
    period = 2.0 * math.pi * math.sqrt(MASS / k_c)
    return solve_ivp(rhs, (0.0, t_end_periods * period), [0.0, V_IN], method="DOP853", rtol=1e-13, atol=1e-18,
                     events=leave)


@pytest.mark.parametrize("zeta", [0.0, 0.03, 0.2, 0.5])
def test_drop_restitution_matches_damped_oscillator(zeta):
    sol = _drop(zeta)
    assert sol.status == 1 and len(sol.t_events[0]) == 1
    exit_speed = -sol.y_events[0][0][1]
    assert exit_speed / V_IN == pytest.approx(math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta ** 2)), abs=1e-6)


def test_drop_critically_damped_never_leaves():
    sol = _drop(1.0, t_end_periods=3.0)  # omega*t ~ 19: h ~ 1e-11 m, still > 0
    assert sol.status == 0 and len(sol.t_events[0]) == 0
    assert np.all(sol.y[0][1:] > 0.0)
    omega = math.sqrt(AREA * K_PEN / MASS)  # critically damped: h = v0·t·exp(-omega·t) > 0 for all t > 0
    assert np.allclose(sol.y[0], V_IN * sol.t * np.exp(-omega * sol.t), rtol=1e-8, atol=1e-16)
    assert abs(sol.y[1][-1]) < 1e-6 * V_IN


def test_critical_damping_unavailable_for_hard_contact():
    with pytest.raises(ValueError, match="hard"):
        default_critical_fraction(Hard())
    with pytest.raises(ValueError, match="hard"):
        critical_damping_coefficient(0.03, 1.0, math.inf)
    with pytest.raises(TypeError):
        overclosure_pressure(1e-6, Hard())
    assert default_critical_fraction(LinearPenalty(1.0)) == default_critical_fraction(Softened(1e-3, 1.0)) == 0.03


@pytest.mark.parametrize("eta", [0.0, 0.25, 0.9])
def test_bilinear_clearance_rule_corners(eta):
    mu0, c0 = 7.0, 2e-3
    assert damping_coefficient(-1e-4, mu0, c0, eta) == mu0
    assert damping_coefficient(0.0, mu0, c0, eta) == mu0
    assert damping_coefficient(eta * c0, mu0, c0, eta) == mu0
    assert damping_coefficient(c0, mu0, c0, eta) == 0.0
    assert damping_coefficient(3 * c0, mu0, c0, eta) == 0.0
    for s in (0.1, 0.5, 0.8):  # linear between eta*c0 and c0
        c = eta * c0 + s * (1.0 - eta) * c0
        assert damping_coefficient(c, mu0, c0, eta) == pytest.approx(mu0 * (1.0 - s), rel=1e-12)


def test_explicit_style_is_constant_while_closed():
    rule = ContactDamping(mu0=3.0, c0=1e-3, eta=0.5, style="explicit")
    assert damping_pressure(2.0, 0.0, rule) == damping_pressure(2.0, -1e-4, rule) == 6.0
    assert damping_pressure(2.0, 1e-6, rule) == 0.0
    assert rule.tangent == 1.0 and ContactDamping(3.0).tangent == 0.0


def test_softened_law_endpoints_and_continuity():
    law = Softened(c0=1e-3, p0=2e5)
    assert overclosure_pressure(0.0, law) == pytest.approx(2e5, rel=1e-15)
    assert overclosure_pressure(-1e-3, law) == 0.0 and overclosure_pressure(-2e-3, law) == 0.0
    assert overclosure_pressure(-1e-3 + 1e-12, law) < 1e-2  # C¹ start: p ~ slope0 * dh² -> tiny
    h = np.linspace(-0.99e-3, 1e-3, 41)
    fd = [(overclosure_pressure(x + 1e-10, law) - overclosure_pressure(x - 1e-10, law)) / 2e-10 for x in h]
    assert np.allclose(fd, [contact_stiffness(x, law) for x in h], rtol=1e-5)


def test_cpress_statuses():
    law, rule = Softened(c0=1e-3, p0=1e5), ContactDamping(mu0=1e3, c0=3e-3, eta=0.0)
    assert cpress(-5e-4, 0.0, law, rule)[1] == "closed"  # softened: closed inside c0
    p, status = cpress(-2e-3, 1.0, law, rule)
    assert status == "VD" and p == pytest.approx(1e3 * (1.0 / 3.0), rel=1e-12)
    assert cpress(-4e-3, 1.0, law, rule) == (0.0, "open")
    assert cpress(-4e-3, 1.0, law) == (0.0, "open") and cpress(1e-5, 1.0, LinearPenalty(1e9))[1] == "closed"


def _annular_seat(r_in, r_out, n_r, n_theta):
    """Nodal tributary areas of a structured annular quad mesh (each quad splits its area equally to 4 nodes)."""
    r = np.linspace(r_in, r_out, n_r)
    dtheta = 2.0 * math.pi / n_theta
    areas = np.zeros((n_r, n_theta))
    for i in range(n_r - 1):
        quad = 0.5 * (r[i + 1] ** 2 - r[i] ** 2) * dtheta
        for j in range(n_theta):
            for a, b in ((i, j), (i + 1, j), (i, (j + 1) % n_theta), (i + 1, (j + 1) % n_theta)):
                areas[a, b] += quad / 4.0
    return areas.ravel()


def test_static_poppet_cpress_equals_force_over_area():
    force, r_in, r_out = 250.0, 4e-3, 5e-3
    areas = _annular_seat(r_in, r_out, 4, 48)
    total = areas.sum()
    assert total == pytest.approx(math.pi * (r_out ** 2 - r_in ** 2), rel=1e-12)
    # hard contact: rigid flat poppet on a rigid flat seat, equilibrium fixes the multiplier at every node
    p_hard = hard_contact_pressure(force, total)
    nodal = [cpress(0.0, 0.0, Hard(), multiplier=p_hard) for _ in areas]
    pressures = np.array([p for p, _ in nodal])
    assert {s for _, s in nodal} == {"closed"}
    assert np.all(np.abs(pressures - force / total) <= 1e-9 * force / total)
    assert float(pressures @ areas) == pytest.approx(force, rel=1e-9)
    # a stiff penalty seat solved for the common penetration gives the same CPRESS (hard-contact limit)
    law = LinearPenalty(1e14)
    delta = force / (law.stiffness * total)
    penalty = np.array([cpress(delta, 0.0, law)[0] for _ in areas])
    assert np.allclose(penalty, force / total, rtol=1e-9, atol=0.0)


def test_suggest_mu0_helpers():
    mu0 = suggest_mu0(1e6, -2.0, fraction=0.02)
    assert mu0 == pytest.approx(1e4) and damping_pressure(2.0, 0.0, ContactDamping(mu0)) == pytest.approx(0.02 * 1e6)
    assert suggest_mu0_euler_column(1e-3, 2.0, 900.0, 1000.0) == pytest.approx(1e-3 * math.pi ** 2 / 4.0 * 100.0)
    with pytest.raises(ValueError):
        suggest_mu0(0.0, 1.0)
