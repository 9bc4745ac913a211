"""The FE codes' blockage rules at a fixed pose against an implementation written here from their descriptions.

The pose is analytic: a flat vent of quads and triangles in z = 0, and boxes whose lower faces hover within the
tolerance over part of it. A vent node is in contact when it lies under a box's lower face; a box node touches the
vent face whose interior holds its (x, y) when it is within the tolerance above z = 0. Areas by the shoelace
formula, fractions by counting nodes as each code's manual or source says.
"""
import numpy as np
import pytest
import trimesh

import blockage
from blockage.fe_rules import RULES, blocks_exchange, rule_blockage

TOL = 1e-3


def vent():
    """A 4 x 3 grid of unit-size 0.01 m cells in z = 0; cells (1, 1) and (2, 0) are cut into two triangles."""
    h, nx, ny = 0.01, 4, 3
    v = np.array([[i * h, j * h, 0.0] for j in range(ny + 1) for i in range(nx + 1)])
    faces = []
    for j in range(ny):
        for i in range(nx):
            a, b = j * (nx + 1) + i, j * (nx + 1) + i + 1
            c, d = b + nx + 1, a + nx + 1
            faces += [[a, b, c], [a, c, d]] if (i, j) in ((1, 1), (2, 0)) else [[a, b, c, d]]
    return blockage.LeakageSurface(v, faces)


def box(lo, hi, gap):
    """A box over [lo, hi] in x and y whose lower face is ``gap`` above z = 0."""
    b = trimesh.creation.box(bounds=[[lo[0], lo[1], gap], [hi[0], hi[1], gap + 0.004]])
    return b


def polygon_area(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def inside_polygon(q, p):
    """q strictly inside the convex counter-clockwise polygon p (2-D)."""
    edges = np.roll(p, -1, axis=0) - p
    rel = q[None, :] - p
    return bool(np.all(edges[:, 0] * rel[:, 1] - edges[:, 1] * rel[:, 0] > 0))


def reference(rule, surface, boxes, side, sdfblk=1.0, leak_fraction=0.0):
    """(flags, fractions, obstruction, leak area) from the rules' descriptions on the analytic pose."""
    faces = [f[f >= 0] for f in surface.faces]
    xy = surface.vertices[:, :2]
    secondary = np.zeros(len(xy), bool)
    touched = np.zeros(len(faces), bool)
    for b, (lo, hi, gap) in boxes:
        if gap <= TOL:
            secondary |= np.all((xy >= np.array(lo) - 1e-12) & (xy <= np.array(hi) + 1e-12), axis=1)
            for q in np.asarray(b.vertices):
                if q[2] <= TOL:
                    hits = [k for k, f in enumerate(faces) if inside_polygon(q[:2], xy[f])]
                    touched[hits] = True
    main = np.zeros(len(xy), bool)
    for k in np.flatnonzero(touched):
        main[faces[k]] = True
    flags = {"secondary": secondary, "main": main, "both": secondary | main}[side]
    fractions = []
    for f in faces:
        n_c = int(flags[f].sum())
        if rule == "lsdyna_cpg":  # whole element when it receives contact force
            fractions.append(1.0 if n_c else 0.0)
        else:  # 1/4 per flagged node of a quad, 1/3 of a triangle
            fractions.append(n_c * (0.25 if len(f) == 4 else 1.0 / 3.0) * (sdfblk if rule == "lsdyna_cpm" else 1.0))
    areas = np.array([polygon_area(xy[f]) for f in faces])
    obstruction = float(np.sum(areas * np.array(fractions)))
    return flags, np.array(fractions), obstruction, areas.sum() - (1 - leak_fraction) * obstruction


POSES = {
    # a box over the left half, its lower face within the tolerance; its corners lie inside vent faces
    "half": [((0.0049, -0.0051), (0.0251, 0.0152), 0.5 * TOL)],
    # a small box resting inside one triangle cell's area: no vent node under it, only its corners touch faces
    "small": [((0.0112, 0.0113), (0.0118, 0.0131), 0.2 * TOL), ((0.031, 0.021), (0.038, 0.028), 0.9 * TOL)],
    # a box out of reach
    "far": [((0.0, 0.0), (0.04, 0.03), 3 * TOL)],
}


@pytest.mark.parametrize("pose", sorted(POSES))
@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("side", ["secondary", "main", "both"])
def test_each_rule_blocks_what_its_description_says_on_a_fixed_pose(rule, side, pose):
    surface = vent()
    boxes = [(box(lo, hi, gap), (lo, hi, gap)) for lo, hi, gap in POSES[pose]]
    sdf = 0.6 if rule == "lsdyna_cpm" else 1.0
    got = rule_blockage(rule, surface, [b for b, _ in boxes], TOL, side=side, sdfblk=sdf, leak_fraction=0.1)
    flags, fractions, obstruction, leak = reference(rule, surface, boxes, side, sdf, 0.1)
    np.testing.assert_array_equal(got.flags, flags)
    np.testing.assert_allclose(got.fractions, fractions, rtol=0, atol=1e-12)
    assert got.obstruction_area == pytest.approx(obstruction, rel=1e-12, abs=1e-18)
    assert got.leak_area == pytest.approx(leak, rel=1e-12)
    if pose == "small" and side == "secondary":
        assert not flags.any()  # the small box touches faces between nodes: only the main side sees it
    if pose == "small" and side != "secondary":
        assert flags.any()


def test_the_rules_differ_where_their_descriptions_differ():
    surface = vent()
    blockers = [box(lo, hi, gap) for lo, hi, gap in POSES["half"]]
    got = {r: rule_blockage(r, surface, blockers, TOL).obstruction_area for r in RULES}
    assert got["exact"] == got["abaqus"] == got["lsdyna_cpm"]  # the leakage nodes in contact, 1/N_e each
    assert got["radioss"] > got["abaqus"]  # also the nodes of the faces the box's corners touch
    assert got["lsdyna_cpg"] > got["radioss"]  # whole elements


def test_which_exchanges_the_lsdyna_block_digit_exempts():
    table = {0: (False, False, False), 1: (True, True, True), 2: (False, True, True), 3: (True, False, True),
             4: (False, False, True)}
    for n, expected in table.items():
        for m in (0, 1):  # the tens digit (escaping particles) does not matter
            got = (blocks_exchange("lsdyna_cpm", 10 * m + n, True, True),
                   blocks_exchange("lsdyna_cpm", 10 * m + n, True, False),
                   blocks_exchange("lsdyna_cpm", 10 * m + n, False, True))
            assert got == expected
    assert blocks_exchange("lsdyna_cpg", 4, True, True) is False and blocks_exchange("lsdyna_cpg", 4, False, True)
    assert blocks_exchange("radioss", 0, True, True)
