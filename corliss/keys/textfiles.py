"""Reading the text files a user gives (scenes, load schedules): any bytes in, the
text out or an InputError naming the file, the line and what is wrong."""

from __future__ import annotations

from pathlib import Path

from corliss.errors import InputError

#: The largest text file read [bytes]: a scene or a schedule is a few kilobytes; a
#: file a thousand times larger is not one.
MAX_BYTES = 20_000_000


def read_text(path: str | Path, key: str, what: str, max_bytes: int = MAX_BYTES) -> str:
    """The UTF-8 text of ``path``.

    Parameters
    ----------
    path : str or Path
        The file.
    key : str
        The scene key or option that named it, for the error.
    what : str
        What the file should be, e.g. ``"a scene file (.toml)"``.
    max_bytes : int, optional
        The largest file read [bytes] (default :data:`MAX_BYTES`).

    Returns
    -------
    str
        The file's text, a leading byte-order mark removed.

    Raises
    ------
    InputError
        If the file is missing, unreadable, too large, not UTF-8 (naming the line and
        column of the first bad byte) or holds a NUL byte (a binary file).
    """
    p = Path(path)
    try:
        if not p.is_file():
            raise InputError(key, str(path), f"the path of an existing file: {what}")
        size = p.stat().st_size
        if size > max_bytes:
            raise InputError(key, str(path), f"{what} of at most {max_bytes / 1e6:g} MB (it "
                             f"has {size / 1e6:.3g} MB)")
        data = p.read_bytes()
    except OSError as exc:
        raise InputError(key, str(path), f"a file that can be read: {what} "
                         f"({exc.strerror or exc})") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise InputError(key, str(path), f"{what} in UTF-8 text; line {line}, column {col} "
                         f"holds the byte 0x{data[exc.start]:02x}, which UTF-8 does not "
                         "allow (save the file as UTF-8)") from None
    if "\x00" in text:
        line = text.count("\n", 0, text.index("\x00")) + 1
        raise InputError(key, str(path), f"{what} in plain text; line {line} holds a NUL "
                         "byte (a binary file?)")
    return text.removeprefix("\ufeff")
