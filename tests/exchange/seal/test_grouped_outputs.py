"""The per-node outputs of a large seat and seal evaluated once per distinct (clearance, side, reach) row: the same
values as node by node."""
import numpy as np
import pytest

from cases.model.seat_contact import MERGE_ABOVE, SeatContact
from exchange.contact import ContactDamping, Hard, LinearPenalty, Softened
from exchange.contact.laws import seat_nodal
from exchange.seal.channel import contact_fraction
from exchange.seal.gap_laws import ExponentialGap
from exchange.seal.hysteresis import PVRCGap
from exchange.seal.load_paths import DisplacementPath
from exchange.seal.meshes import flat_flange_seat


def _seat(n, rng):
    """n nodes on 7 clearances, areas all different (as a mesh's tributary areas are)."""
    g0 = rng.choice(np.linspace(-2e-6, 4e-6, 7), n)
    return g0, rng.uniform(0.5e-6, 2e-6, n)


@pytest.mark.parametrize("law, damping, fraction", [
    (LinearPenalty(5e10), "critical", 0.5), (Softened(c0=2e-6, p0=1e6), ContactDamping(1e4, c0=3e-6, eta=0.3), None),
    (Hard(), ContactDamping(2e3, style="explicit"), None)])
def test_nodal_by_rows_matches_every_node(law, damping, fraction):
    """CPRESS and status of a seat above MERGE_ABOVE nodes: status exactly, CPRESS to round-off (the critical
    damping coefficient per unit area is the same for every area)."""
    rng = np.random.default_rng(3)
    n = MERGE_ABOVE + 500
    g0, areas = _seat(n, rng)
    c = SeatContact("c", "b", law, None if damping == "critical" else damping, fraction, g0, -np.ones(n), areas,
                    2.0, np.zeros((n, 3)), np.zeros((0, 3), int))
    rows, node_row = c.nodal_rows()
    assert (node_row is None) == isinstance(law, Hard)
    assert node_row is None or len(rows) == 7
    for s, v in ((-1e-6, 0.0), (0.5e-6, -0.3), (3e-6, 0.8)):
        p, status = c.nodal(s, v, reaction=1.0)
        ref_p, ref_status = seat_nodal(s, v, 1.0, c.table, c.law_vector)
        assert np.array_equal(status, ref_status)
        np.testing.assert_allclose(p, ref_p, rtol=1e-14, atol=0.0)


def test_distinct_path_gives_every_node_bit_for_bit():
    """Heights, contact and closing of a seal's path from its distinct rows equal the node-by-node values exactly,
    with hysteresis (the pressure at bolt-up per node) too."""
    rng = np.random.default_rng(4)
    n = 3000
    g0, areas = _seat(n, rng)
    table = flat_flange_seat(np.zeros((n, 3)), areas, 0.0)
    table[:, 0] = g0
    law = np.array([1.0, 5e10, 0, 0, 0, 0, 0, 0, 1.0, 1.0, 0.01])
    for gap, loaded in ((ExponentialGap(10e-6, 1e6, 0.5e-6), None),
                        (PVRCGap(Gb=2e6, a=0.3, Gs=2e4, h1=8e-6, h_max=30e-6), 3e-6)):
        path = DisplacementPath(table, law, gap, loaded_to=loaded)
        rows, node_row = path.distinct()
        assert len(rows.nodes) == 7
        assert np.array_equal(rows.closing()[node_row], path.closing())
        for s in np.linspace(-4e-6, 8e-6, 25):
            h, touching = path.state(s)
            h_rows, touching_rows = rows.state(s)
            assert np.array_equal(h_rows[node_row], h) and np.array_equal(touching_rows[node_row], touching)
            summed = np.bincount(node_row, weights=areas)
            assert np.sum(np.where(touching_rows, summed, 0.0)) / summed.sum() == \
                pytest.approx(contact_fraction(touching, areas), rel=1e-14)
