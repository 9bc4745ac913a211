"""The deck side of the ``ventsim`` command: ``ventsim run deck.inp|deck.k [--units U]`` and ``ventsim import``."""
from __future__ import annotations

import sys
from pathlib import Path

from cases.decks import SYSTEMS, deck_scene, import_deck, is_deck

__all__ = ["scene_for_run", "add_import_parser"]


def _report(imported, quiet: bool) -> None:
    if not quiet:
        for line in imported.ignored + [f"note: {n}" for n in imported.notes]:
            print(f"ventsim: {imported.source}: {line}", file=sys.stderr)


def scene_for_run(path, out, units: str = "SI", quiet: bool = False):
    """(scene or path, Imported or None): a deck is imported to ``out/scene/<stem>.toml`` (its meshes and tables
    beside it) and loaded from there; a TOML scene is passed through."""
    if not is_deck(path):
        return path, None
    imported = import_deck(path, units)
    _report(imported, quiet)
    scene, imported = deck_scene(path, Path(out) / "scene" / f"{Path(path).stem}.toml", units, imported=imported)
    return scene, imported


def _import(args) -> int:
    imported = import_deck(args.deck, args.units)
    _report(imported, args.quiet)
    scene, _ = deck_scene(args.deck, args.out, args.units, imported=imported)
    if not args.quiet:
        print(f"wrote {args.out} and {len(imported.files)} file(s) beside it: {', '.join(imported.files)}")
    return 0


def add_import_parser(sub) -> None:
    """The ``ventsim import`` subcommand."""
    p = sub.add_parser("import", help="read an Abaqus .inp or LS-DYNA .k deck and write the scene TOML with its "
                                      "meshes and tables")
    p.add_argument("deck", type=Path, help="deck file (.inp Abaqus, .k LS-DYNA)")
    p.add_argument("--out", type=Path, required=True, help="scene TOML to write (files go beside it)")
    add_units_argument(p)
    p.add_argument("--quiet", action="store_true", help="print nothing but errors")
    p.set_defaults(func=_import)


def add_units_argument(p) -> None:
    p.add_argument("--units", default="SI", choices=list(SYSTEMS),
                   help="unit system of a deck's numbers (default SI; mm-t-s: mm, t, s, MPa; mm-kg-ms: mm, kg, "
                        "ms, GPa)")
