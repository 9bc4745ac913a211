"""Parts, assembly and instances (the layout Abaqus/CAE writes) read like the flat deck they stand for."""
from __future__ import annotations

import numpy as np
import pytest

from cases.decks import deck_scene, import_deck
from cases.decks.abaqus_lexer import read_keywords
from cases.decks.abaqus_parts import flatten_parts
from cases.scene.errors import SceneError
from cases.run.library import HERE, column_errors
from cases.run.runner import run_scene

FLAT = (HERE / "decks" / "vented_box_blockage.inp").read_text()
MESH = (HERE / "decks" / "vented_box_mesh.inp").read_text()

PARTS = """*HEADING
Rigid 8 L box of air venting through a 1 dm^2 top vent that a sliding rigid plate covers (units: SI)
*PART, NAME=BOX
*INCLUDE, INPUT=vented_box_mesh.inp
*END PART
*PART, NAME=PLATE
*NODE
 1, 0.0, 0.0, 0.0
 2, 0.06, 0.0, 0.0
 3, 0.12, 0.0, 0.0
 4, 0.0, 0.06, 0.0
 5, 0.06, 0.06, 0.0
 6, 0.12, 0.06, 0.0
 7, 0.0, 0.12, 0.0
 8, 0.06, 0.12, 0.0
 9, 0.12, 0.12, 0.0
*ELEMENT, TYPE=R3D4, ELSET=PLATE
 1, 1, 2, 5, 4
 2, 2, 3, 6, 5
 3, 4, 5, 8, 7
 4, 5, 6, 9, 8
*END PART
*ASSEMBLY, NAME=ASSEMBLY
*INSTANCE, NAME=BOX-1, PART=BOX
*END INSTANCE
*INSTANCE, NAME=PLATE-1, PART=PLATE
 -0.15, 0.04, 0.2005
*END INSTANCE
*NODE
 1000, 0.1, 0.1, 0.1
 2100, -0.09, 0.10, 0.2005
*NSET, NSET=BOX_REF
 1000
*NSET, NSET=PLATE_REF
 2100
*RIGID BODY, REF NODE=PLATE_REF, ELSET=PLATE-1.PLATE
*SURFACE, NAME=BOX_WALL
 BOX-1.BOX, SPOS
*SURFACE, NAME=VENT_SURF
 BOX-1.VENT_ELS, SPOS
*SURFACE, NAME=PLATE_SURF
 PLATE-1.PLATE, SPOS
*END ASSEMBLY
"""


def test_instance_deck_gives_the_flat_deck_history(tmp_path):
    body = FLAT[FLAT.index("*MATERIAL"):].replace(" BOX_NODES, ENCASTRE", " BOX-1.BOX_NODES, ENCASTRE")
    (tmp_path / "vented_box_mesh.inp").write_text(MESH)
    (tmp_path / "vented_box_blockage.inp").write_text(PARTS + body)
    parts = deck_scene(tmp_path / "vented_box_blockage.inp", tmp_path / "p" / "s.toml")[0]
    flat = deck_scene(HERE / "decks" / "vented_box_blockage.inp", tmp_path / "f" / "s.toml")[0]
    a, b = run_scene(parts), run_scene(flat)
    assert a.columns == b.columns
    assert max(column_errors(a.columns, a.history, b.columns, b.history).values()) <= 1e-12
    assert b.column("vent.area")[-1] == 0.0 and a.column("vent.area")[-1] == 0.0


def test_instance_rotation_and_node_labels(tmp_path):
    (tmp_path / "d.inp").write_text("""*PART, NAME=P
*NODE, NSET=ALL
 1, 1.0, 0.0, 0.0
 2, 0.0, 2.0, 0.0
*END PART
*ASSEMBLY, NAME=A
*INSTANCE, NAME=I, PART=P
 1.0, 0.0, 0.0
 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 90.0
*END INSTANCE
*NSET, NSET=ONE, INSTANCE=I
 1
*END ASSEMBLY
*BOUNDARY
 I.2, 1, 3
""")
    blocks = flatten_parts(read_keywords(tmp_path / "d.inp"))
    node = next(kw for kw in blocks if kw.name == "NODE")
    xyz = [[float(x) for x in d.fields[1:]] for d in node.data]
    np.testing.assert_allclose(xyz, [[0.0, 2.0, 0.0], [-2.0, 1.0, 0.0]], atol=1e-15)  # shift, then 90° about z
    assert node.params["NSET"] == "I.ALL"
    one = next(kw for kw in blocks if kw.name == "NSET")
    assert one.data[0].fields == ("1000000001",) and "INSTANCE" not in one.params
    bc = next(kw for kw in blocks if kw.name == "BOUNDARY")
    assert bc.data[0].fields[0] == "1000000002"


def test_an_unknown_part_is_an_error(tmp_path):
    (tmp_path / "d.inp").write_text("*ASSEMBLY, NAME=A\n*INSTANCE, NAME=I, PART=Q\n*END INSTANCE\n*END ASSEMBLY\n")
    with pytest.raises(SceneError) as info:
        import_deck(tmp_path / "d.inp")
    assert str(info.value) == f"{tmp_path / 'd.inp'}: line 2: *INSTANCE: PART=Q: no *PART of that name"
