"""Decks in: Abaqus/Explicit fluid-cavity decks (``.inp``) and LS-DYNA control-volume airbag decks (``.k``) read
into ventsim's scene format (the dict a TOML file gives), validated by the same loader, run like a TOML scene.

``import_deck(path, units)`` gives an :class:`Imported` (scene dict, the meshes and tables it names, the ignored
keywords); ``deck_scene(path, toml_path, units)`` writes those files beside ``toml_path`` and loads the scene
from them, so a deck and the TOML it was imported to give the same history. docs/decks.md has the mapping.
"""
from __future__ import annotations

from pathlib import Path

from cases.scene.errors import SceneError
from cases.decks.imported import Imported
from cases.decks.units import SYSTEMS

__all__ = ["import_deck", "deck_scene", "is_deck", "DECK_SUFFIXES", "Imported", "SYSTEMS"]

DECK_SUFFIXES = {".inp": "abaqus", ".k": "lsdyna", ".key": "lsdyna", ".dyn": "lsdyna"}


def is_deck(path) -> bool:
    """Whether ``path`` names a deck (by its suffix) rather than a TOML scene."""
    return Path(path).suffix.lower() in DECK_SUFFIXES


def import_deck(path, units: str = "SI") -> Imported:
    """Read the deck at ``path`` whose values are in ``units`` (SI, mm-t-s, mm-kg-ms)."""
    path = Path(path)
    if units not in SYSTEMS:
        raise SceneError(path, "", f"unknown --units {units!r}; known: {', '.join(SYSTEMS)}")
    if not path.is_file():
        raise SceneError(path, "", "deck file does not exist")
    kind = DECK_SUFFIXES.get(path.suffix.lower())
    if kind is None:
        raise SceneError(path, "", f"not a deck: expected one of {', '.join(DECK_SUFFIXES)}")
    if kind == "abaqus":
        from cases.decks.abaqus_model import read_abaqus as read
    else:
        from cases.decks.lsdyna import read_lsdyna as read
    try:
        return read(path, units)
    except SceneError:
        raise
    except Exception as exc:  # a reader bug must still reach the user as one line, not a traceback
        raise SceneError(path, "", f"ventsim could not read this deck ({type(exc).__name__}: {exc}); please report "
                                   "it with the deck") from None


def deck_scene(path, toml_path, units: str = "SI", *, imported: Imported | None = None):
    """Import the deck, write the scene TOML and its files at ``toml_path``, and load the scene from them."""
    from cases.scene.files import scene_from_dict
    from cases.decks.write_scene import write_imported

    imported = imported or import_deck(path, units)
    toml_path = write_imported(imported, toml_path)
    return scene_from_dict(imported.data, toml_path), imported
