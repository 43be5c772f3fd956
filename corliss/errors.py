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
        """The same error with its key placed under ``prefix`` (a table name)."""
        key = self.key if self.key.startswith(prefix + ".") else f"{prefix}.{self.key}"
        return InputError(key, self.value, self.expected)


class RunError(RuntimeError):
    """A run that cannot go on, for a reason in the scene rather than in the code: the
    run-time budget exhausted, a state outside the steam properties.  The CLI turns it
    into a one-paragraph message and exit code 2, with no files written.

    Parameters
    ----------
    message : str
        What happened, with the scene quantities that likely caused it.
    """
