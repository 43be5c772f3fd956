"""Logging conventions: every module logs to a child of the ``corliss`` logger, and
never prints.

:data:`NOTICE` sits between INFO and WARNING: a one-line account of work that takes
seconds and happens once on a machine (compiling the kernels, building the steam
table), which the command line shows by default and ``-q`` would hide.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

#: Level of the once-per-machine notices.
NOTICE = 25
logging.addLevelName(NOTICE, "NOTICE")


# --- the point a message concerns --------------------------------------------------------
#: The point of a study (a load, a variant, a setting) now being run, for the messages
#: of its run: set with :func:`at_point`, read by :class:`PointFilter`.
_POINT: ContextVar[str | None] = ContextVar("corliss_point", default=None)


@contextmanager
def at_point(label: str) -> Iterator[None]:
    """Name the point of a study that the runs inside the block belong to.

    Every record logged meanwhile carries it as ``record.point`` (see
    :class:`PointFilter`), so a warning from one run of a sweep says which.

    Parameters
    ----------
    label : str
        The point, as a reader knows it: ``"setting 0.4"``, ``"throttled at 60 % load"``.

    Yields
    ------
    None
        The block runs with the point named; the name before it is restored after.
    """
    token = _POINT.set(label)
    try:
        yield
    finally:
        _POINT.reset(token)


def current_point() -> str | None:
    """The label of the point now being run (see :func:`at_point`).

    Returns
    -------
    str or None
        The label, or None outside every point.
    """
    return _POINT.get()


class PointFilter(logging.Filter):
    """Puts the point now being run (:func:`at_point`) before a warning's message.

    Only warnings and errors are marked: a notice (a compile, the steam table built)
    is about the machine, not the point that happened to set it off.

    For a handler: ``handler.addFilter(PointFilter())``.  A record logged outside any
    point passes unchanged; one already marked is not marked twice.

    Parameters
    ----------
    name : str, optional
        :class:`logging.Filter`'s: only records of this logger and its children pass
        (all when empty).
    """

    def filter(self, record: logging.LogRecord) -> bool:
        point = _POINT.get()
        if (point is not None and record.levelno >= logging.WARNING
                and not getattr(record, "point", None)):
            record.point = point
            record.msg = f"[{point}] {record.getMessage()}"
            record.args = None
        return True
