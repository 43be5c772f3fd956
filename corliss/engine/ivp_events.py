"""Terminal events for scipy's ``solve_ivp``, typed.

``solve_ivp`` reads an event function's ``terminal`` and ``direction`` attributes; a
Python function takes them at run time, but a type checker does not know a function
has them.  :func:`terminal_event` sets them in one place and returns the function
typed as what ``solve_ivp`` reads.
"""

from __future__ import annotations

from typing import Callable, Protocol, cast


class TerminalEvent(Protocol):
    """An event function of ``solve_ivp`` that ends the integration.

    Called as ``event(t, y)`` (time [s], state), it returns a float, zero at the event.
    A protocol: never made, its arguments are those of the class machinery.

    Parameters
    ----------
    *args, **kwargs
        Not taken: a protocol is not instantiated.
    """

    terminal: bool
    direction: int

    def __call__(self, t, y) -> float: ...


def terminal_event(fn: Callable, direction: int) -> TerminalEvent:
    """Make ``fn`` a terminal event of ``solve_ivp`` crossing zero in ``direction``.

    Parameters
    ----------
    fn : callable
        ``fn(t, y)``, zero at the event.
    direction : int
        1: the event counts only rising through zero; -1: only falling; 0: either.

    Returns
    -------
    TerminalEvent
        ``fn`` itself, its ``terminal`` set to True and its ``direction`` set.
    """
    setattr(fn, "terminal", True)
    setattr(fn, "direction", direction)
    return cast(TerminalEvent, fn)     # the two attributes it lacked are set above
