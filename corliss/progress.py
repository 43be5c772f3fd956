"""Progress bars for runs and studies, on a terminal or in a notebook, with the
messages of the runs printed above the bar.

Drawn by tqdm (``tqdm.auto``: a text bar on a terminal, a widget in a Jupyter
notebook), which also estimates the rate and the time to go, and whose
``tqdm.write`` prints a line above its bars and draws them again below it: a
warning from one point of a sweep never lands in the middle of the bar.

Every function that runs for a while takes ``progress=``: None (nothing), True (a
bar of its own), a :class:`ProgressBar` (a bar set up by the caller: its stream,
its delay) or any callable ``f(done, total)``.  What the two numbers are is the
kind of bar: ``"time"`` (seconds simulated and to simulate), ``"runs"`` (runs done
and in all) or ``"cycles"`` (a steady run's cycle number and the relative change of
its work over the last cycle: its total is unknown until the run is periodic).
"""

from __future__ import annotations

import logging
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from tqdm.auto import tqdm

from corliss.logs import PointFilter

log = logging.getLogger("corliss")

KINDS = ("time", "runs", "cycles")


class TqdmHandler(logging.Handler):
    """A logging handler that writes each record above any tqdm bar on its stream.

    Parameters
    ----------
    stream : file-like, optional
        Where to write; ``sys.stderr`` as it is at each record when None.
    level : int, optional
        The least level written (:mod:`logging`'s levels); all when ``NOTSET``.
    """

    def __init__(self, stream=None, level: int = logging.NOTSET):
        super().__init__(level)
        self.stream = stream
        self.addFilter(PointFilter())

    def emit(self, record: logging.LogRecord) -> None:
        try:
            tqdm.write(self.format(record), file=self.stream or sys.stderr)
        except Exception:           # logging's own convention: never raise from emit
            self.handleError(record)


class ProgressBar:
    """A tqdm bar called as ``bar(done, total)``: the ``progress`` of a run or study.

    While it is open, and where the ``corliss`` logger has no handler of its own (a
    script or a notebook that configured none), the logger's warnings are written
    above the bar (:class:`TqdmHandler`), each naming the point of a study it came
    from (:func:`corliss.logs.at_point`).

    Parameters
    ----------
    kind : str, optional
        ``"time"``, ``"runs"`` or ``"cycles"`` (see the module's docstring).
    delay_s : float, optional
        Nothing is drawn before the work has taken this long [s].
    file : file-like, optional
        Where to draw (default ``sys.stderr``).
    disable : bool or None, optional
        True: draw nothing; None: draw only on a terminal (the command line's choice,
        so a log gets no bar); False (default): draw.
    tolerance : float, optional
        The periodicity tolerance shown beside a ``"cycles"`` bar [-].
    """

    def __init__(self, kind: str = "runs", delay_s: float = 0.0, file=None,
                 disable: bool | None = False, tolerance: float | None = None):
        if kind not in KINDS:
            raise ValueError(f"kind {kind!r}: one of {', '.join(KINDS)}")
        self.kind = kind
        self.delay_s = delay_s
        self.file = file
        self.disable = disable
        self.tolerance = tolerance
        self._bar: Any = None
        self._handler: TqdmHandler | None = None

    def _open(self, total: float | None) -> None:
        unit = {"time": "s", "runs": "run", "cycles": "cycle"}[self.kind]
        fmt = ("{l_bar}{bar}| {n:.2f}/{total:g} s simulated [{elapsed}<{remaining}]"
               if self.kind == "time" else None)
        self._bar = tqdm(total=total, unit=unit, delay=self.delay_s, file=self.file,
                         disable=self.disable, leave=False, dynamic_ncols=True,
                         **({"bar_format": fmt} if fmt else {}))
        if not log.handlers and not getattr(self._bar, "disable", False):
            self._handler = TqdmHandler(self.file, logging.WARNING)
            self._handler.setFormatter(logging.Formatter("corliss: %(message)s"))
            log.addHandler(self._handler)

    def open(self) -> None:
        """Draw the bar (its total unknown until the first call) and start writing the
        logger's messages above it: before the work begins, so that the first run's
        messages go above it too."""
        if self._bar is None:
            self._open(None)

    def __call__(self, done: float, total: float) -> None:
        if self._bar is None:
            self._open(None if self.kind == "cycles" else total)
        bar = self._bar
        if self.kind == "cycles":
            bar.n = int(done)
            bar.set_postfix_str(f"work changed {total:.2e}"
                                + (f", periodic at {self.tolerance:.0e}" if self.tolerance
                                   else ""), refresh=False)
        else:
            if bar.total != total:
                bar.total = total
            bar.n = done if self.kind == "time" else int(done)
        bar.refresh()

    def close(self) -> None:
        """Take the bar away and stop writing the logger's messages above it."""
        if self._handler is not None:
            log.removeHandler(self._handler)
            self._handler = None
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self) -> "ProgressBar":
        self.open()
        return self

    def __exit__(self, *exc) -> None:
        self.close()


@contextmanager
def progress_for(progress, kind: str, **options) -> Iterator[Callable[[float, float], None] | None]:
    """The callback for a ``progress=`` argument, open for the block.

    Parameters
    ----------
    progress : None, bool, ProgressBar or callable
        What the caller asked for: None or False (no callback), True (a
        :class:`ProgressBar` of ``kind``, closed at the block's end), a
        :class:`ProgressBar` (closed at the block's end) or a callable (passed on).
    kind : str
        The bar's kind when ``progress`` is True.
    **options
        More arguments of a :class:`ProgressBar` made here.

    Yields
    ------
    callable or None
        ``f(done, total)``.
    """
    if progress is None or progress is False:
        yield None
        return
    if progress is True:
        progress = ProgressBar(kind, **options)
    if not callable(progress):
        raise TypeError(f"progress={progress!r}: None, True, a ProgressBar or a callable "
                        "f(done, total)")
    if isinstance(progress, ProgressBar):
        progress.open()
    try:
        yield progress
    finally:
        if isinstance(progress, ProgressBar):
            progress.close()
