"""What a deck becomes: the scene dict (what a TOML file gives), the files it names, what was left out."""
from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Imported"]


@dataclass
class Imported:
    """A deck read into ventsim's scene format.

    ``data`` is the scene as ``tomllib`` would give it (file names relative to the scene file); ``files`` maps
    those names to their text (OBJ meshes, CSV tables); ``ignored`` lists each keyword ventsim left out once
    (``"ignored: *MATERIAL (line 40)"``); ``notes`` says where ventsim's reading differs from the solver's.
    """

    source: str
    data: dict
    files: dict = field(default_factory=dict)
    ignored: list = field(default_factory=list)
    notes: list = field(default_factory=list)

    def comment(self) -> str:
        lines = [f"Scene imported from {self.source} by ventsim (cases/decks); edit and rerun with ventsim run."]
        lines += self.ignored + [f"note: {n}" for n in self.notes]
        return "\n".join(lines)

    def modelled(self) -> dict:
        """The deck's entry for summary.json's 'modelled' section."""
        return {"source": self.source, "ignored": list(self.ignored), "notes": list(self.notes)}
