"""One progress bar for ventsim's long loops (an integration, a sweep): tqdm on stderr, shown only when stderr is a
terminal (a log file gets nothing), after a short delay, and ending at 100 % when the work is complete."""
from __future__ import annotations

import sys

__all__ = ["ProgressBar", "DELAY"]

DELAY = 1.0
"""Seconds before a bar appears by default (a short run shows nothing)."""


class ProgressBar:
    """A tqdm bar over ``total`` units, or nothing.

    Parameters
    ----------
    total : float
        What complete means (e.g. the end time [s] minus the start time, or the number of variants).
    desc : str
        Label in front of the bar.
    unit : str
        Unit of ``total`` shown by tqdm.
    enabled : bool
        False: never shown.
    delay : float, optional
        Seconds before the bar appears (default :data:`DELAY`).
    stream : file, optional
        Default ``sys.stderr``; the bar is shown only if ``stream.isatty()``.
    initial : float
        Units already done (a resumed sweep).

    Examples
    --------
    >>> import io
    >>> class Terminal(io.StringIO):
    ...     def isatty(self):
    ...         return True
    >>> out = Terminal()
    >>> bar = ProgressBar(2.0, desc="run", unit="s", delay=0.0, stream=out)
    >>> bar.update_to(1.5)
    >>> bar.close(complete=True)
    >>> out.getvalue().splitlines()[-1].split("|")[0]
    'run: 100.0%'

    >>> ProgressBar(2.0, stream=io.StringIO()).shown  # not a terminal: quiet
    False
    """

    def __init__(self, total: float, *, desc: str = "", unit: str = "it", enabled: bool = True, delay: float | None = None,
                 stream=None, initial: float = 0.0, integer: bool = False):
        stream = stream if stream is not None else sys.stderr
        self.total, self._bar = total, None
        if enabled and getattr(stream, "isatty", lambda: False)():
            from tqdm import tqdm

            fmt = None if integer else "{desc}: {percentage:5.1f}%|{bar}| {n:.4g}/{total:.4g} {unit} [{elapsed}<{remaining}]"
            self._bar = tqdm(total=total, desc=desc, unit=unit, delay=DELAY if delay is None else delay, file=stream, initial=initial,
                             leave=True, dynamic_ncols=True, bar_format=fmt, mininterval=0.2)

    @property
    def shown(self) -> bool:
        return self._bar is not None

    def update_to(self, done: float) -> None:
        """Set the units done so far."""
        if self._bar is not None:
            self._bar.update(min(done, self.total) - self._bar.n)

    def advance(self, units: float = 1.0, postfix: str | None = None) -> None:
        if self._bar is not None:
            if postfix is not None:
                self._bar.set_postfix_str(postfix, refresh=False)
            self._bar.update(units)

    def close(self, complete: bool = False) -> None:
        """Close the bar; ``complete``: the work is done, so the bar shows 100 %."""
        if self._bar is not None:
            if complete:
                self.update_to(self.total)
            self._bar.close()
            self._bar = None
