"""The rigid-box deck the deck tests vary: its nodes, surface and N2 behaviour, and a writer for variants."""
from __future__ import annotations

from cases.run.library import HERE

BOX = (HERE / "decks" / "box_mesh.inp").read_text()
HEAD = """*HEADING
{title}
*PARAMETER
LX = 0.5
LY = 0.4
LZ = 0.3
*INCLUDE, INPUT=box_mesh.inp
*NODE, NSET=REF
 100, 0.25, 0.2, 0.15
*SURFACE, NAME=WALL
 BOX, SPOS
*PHYSICAL CONSTANTS, ABSOLUTE ZERO={zero}, UNIVERSAL GAS CONSTANT=8.314462618
*FLUID BEHAVIOR, NAME=N2
*MOLECULAR WEIGHT
 0.0280134
*CAPACITY, TYPE=POLYNOMIAL
 29.100619163
*FLUID CAVITY, NAME=TANK, BEHAVIOR=N2, REF NODE=REF, SURFACE=WALL, ADIABATIC, AMBIENT PRESSURE=1.0e5
"""


def head(title: str, zero: str = "0.") -> str:
    """The first 19 lines of a box deck: mesh by *INCLUDE, N2 with constant cp, the cavity TANK on node REF."""
    return HEAD.format(title=title, zero=zero)


def write(folder, text, mesh=BOX, name="deck.inp"):
    """Write ``text`` as ``folder/name`` beside the box mesh it includes."""
    (folder / "box_mesh.inp").write_text(mesh)
    (folder / name).write_text(text)
    return folder / name
