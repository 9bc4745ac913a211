"""The one error type a user sees for a bad scene: one line naming the file, the key and what was expected."""
from __future__ import annotations

__all__ = ["SceneError", "SweepError"]


class SceneError(ValueError):
    """A scene file (or a file it names) that cannot be run; ``str()`` is a one-line message."""

    def __init__(self, file, where: str, message: str):
        self.file, self.where = str(file), where
        super().__init__(f"{self.file}: {where}: {message}" if where else f"{self.file}: {message}")


class SweepError(SceneError):
    """A sweep that cannot start (bad ``--vary``, design or variants file, a folder in use); ``str()`` is one
    line."""

    def __init__(self, message: str):
        ValueError.__init__(self, message)
        self.file, self.where = "", ""
