"""The exception types a user sees: a mistake in the input, and a run that cannot go on."""

from __future__ import annotations


class InputError(ValueError):
    """Bad input: names the offending key and value and says what would be valid.

    The CLI turns this into a one-paragraph message and exit code 2.

    Parameters
    ----------
    key : str
        Dotted scene key, e.g. ``"valve_gear.lap"``.
    value : object
        The value as given; None for a key or section the scene lacks (the message then
        says it is missing).
    expected : str
        What would be valid, in words.
    """

    def __init__(self, key: str, value: object, expected: str):
        self.key = key
        self.value = value
        self.expected = expected
        if value is None:       # a key or section the scene lacks
            super().__init__(f"{key} is missing: expected {expected}.")
        else:
            super().__init__(f"{key} = {value!r} is not valid: expected {expected}.")

    def with_prefix(self, prefix: str) -> "InputError":
        """The same error with its key placed under a table's name.

        Parameters
        ----------
        prefix : str
            The dotted name of the table the key belongs to (``"valve_gear"``).

        Returns
        -------
        InputError
            A new error whose key is ``prefix.key`` (unchanged if it already starts
            with ``prefix.``), with the same value and expectation.
        """
        key = self.key if self.key.startswith(prefix + ".") else f"{prefix}.{self.key}"
        return InputError(key, self.value, self.expected)


class InputErrors(InputError):
    """Several mistakes of one scene, reported together.

    Its ``key``, ``value`` and ``expected`` are the first mistake's, and its message
    starts with it; ``errors`` holds every one, and the message lists the others, one a
    line.

    Parameters
    ----------
    errors : list of InputError
        The mistakes, two or more, in the scene's order.
    """

    def __init__(self, errors: list[InputError]):
        first = errors[0]
        self.key = first.key
        self.value = first.value
        self.expected = first.expected
        self.errors = list(errors)
        ValueError.__init__(self, f"{first}\nThe scene has {len(errors) - 1} more "
                            f"mistake{'s' if len(errors) > 2 else ''}:\n"
                            + "\n".join(f"  - {e}" for e in errors[1:]) + "\n")

    def with_prefix(self, prefix: str) -> "InputErrors":
        """The same errors with their keys under a table's name.

        Parameters
        ----------
        prefix : str
            The dotted name of the table the keys belong to.

        Returns
        -------
        InputErrors
            Each error as :meth:`InputError.with_prefix` gives it.
        """
        return InputErrors([e.with_prefix(prefix) for e in self.errors])


class RunError(RuntimeError):
    """A run that cannot go on, for a reason in the scene rather than in the code.

    The run-time budget exhausted, a state outside the steam properties.  The CLI
    turns it into a one-paragraph message and exit code 5, with no files written.
    Raised as ``RunError(message)``, the message saying what happened, with the scene
    quantities that likely caused it (the constructor is :class:`RuntimeError`'s).
    """


#: Exit status of a run that ran but whose result is not one: its mass or energy balance
#: does not close within tolerance (:mod:`corliss.engine.balance`).  Its files are
#: written, for a look, and the message says why the run failed.  (2 is a user's
#: mistake, 4 a run that failed physically, 5 a run that stopped; 130 and 143 an
#: interrupt and a termination: docs/exit-codes.md.)
EXIT_BALANCE_FAILED = 3
#: Exit status after Ctrl-C (SIGINT), the shell's 128 + 2.
EXIT_INTERRUPTED = 130
#: Exit status after SIGTERM, the shell's 128 + 15.
EXIT_TERMINATED = 143


class Terminated(BaseException):
    """SIGTERM received: raised in the main thread so that a run unwinds (its staged
    files removed, the output folder as it was) and exits with :data:`EXIT_TERMINATED`.
    """


class StudyStopped(RunError):
    """A study stopped before its last run (Ctrl-C, SIGTERM): its workers ended, the rows
    done kept in its journal when it has one.

    The CLI turns it into a one-paragraph message naming the rows kept and how to
    resume, and the exit status of the signal (130 for Ctrl-C, 143 for SIGTERM).

    Parameters
    ----------
    message : str
        What stopped and what was kept.
    done, runs : int
        Rows finished, and runs in the study [-].
    journal : Path or None
        The journal holding the finished rows (None: they were not kept).
    signal_name : str
        ``"Ctrl-C"`` or ``"SIGTERM"``.
    """

    def __init__(self, message: str, done: int = 0, runs: int = 0, journal=None,
                 signal_name: str = "Ctrl-C"):
        super().__init__(message)
        self.done, self.runs, self.journal, self.signal_name = done, runs, journal, signal_name
