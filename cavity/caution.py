"""Warnings a run gives instead of clamping a value silently: an inflator temperature held at a bound, a
species used outside its data range, a table extrapolated. They are ordinary Python warnings of category
:class:`VentsimWarning`; ``cases.run.runner`` records them in ``summary.json`` ("warnings") and the ``ventsim``
command prints them on stderr."""
from __future__ import annotations

import warnings

__all__ = ["VentsimWarning", "caution"]


class VentsimWarning(UserWarning):
    """A result that is computed but worth a look: the message names what was held, clamped or extrapolated."""


def caution(message: str) -> None:
    """Warn with ``message`` (keep it free of times and values that change per call: it is shown once)."""
    warnings.warn(message, VentsimWarning, stacklevel=3)
