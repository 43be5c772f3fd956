"""A study's rows kept on disk as they finish: a stopped study keeps them, and
``corliss study --resume`` finishes it without repeating them.

The journal is ``<scene>.study.partial.jsonl`` in the study's output directory: a
first line (JSON) that says the file is partial and which study it is (a fingerprint
of the base scene, the design's values, the seed, the responses and the fidelity),
then one line a finished run, ``[run_id, status, error, *responses]``.  Each row is
written whole by one ``write`` call as its chunk comes back, so a process killed
outright leaves every row written before it whole (a line cut short by the kill is
not read back).  Floats go through JSON as Python's shortest round-trip repr, so a
row read back is the row written, bit for bit.  The study's own files replace the
journal when it completes.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import tempfile
from pathlib import Path

import numpy as np

from corliss.errors import InputError

log = logging.getLogger(__name__)

__all__ = ["Journal", "check_writable", "fingerprint", "journal_path", "read_rows"]

#: What the journal's first line says of the file.
PARTIAL_NOTE = ("partial: the rows of a study that has not finished, appended as its runs "
                "finished ([run_id, status, error, *responses]); the same command with "
                "--resume finishes it without repeating them")


def journal_path(out_dir, name: str) -> Path:
    """The journal of scene ``name``'s study in ``out_dir``.

    Parameters
    ----------
    out_dir : str or Path
        The study's output directory.
    name : str
        The base scene's name.

    Returns
    -------
    Path
        ``out_dir / f"{name}.study.partial.jsonl"``.
    """
    return Path(out_dir) / f"{name}.study.partial.jsonl"


def check_writable(out_dir, flag: str = "--out") -> Path:
    """Make ``out_dir`` if missing and prove a file can be written in it.

    Called before the first run, so a directory that cannot take the output is found
    before any work rather than after it.

    Parameters
    ----------
    out_dir : str or Path
        The output directory.
    flag : str, optional
        The option that named it, for the error.

    Returns
    -------
    Path
        The directory.

    Raises
    ------
    InputError
        If the directory cannot be made or written (read-only, a file in its place,
        no permission), naming it and the reason.
    """
    path = Path(out_dir)
    try:
        path.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".corliss-probe-", dir=path)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise InputError(flag, str(out_dir), "a directory this user can write the output "
                         f"into ({type(exc).__name__}: {exc.strerror or exc})") from None
    return path


def fingerprint(base: dict, name: str, fidelity, responses, design) -> str:
    """What identifies a study's runs: a hash of everything a row depends on.

    Parameters
    ----------
    base : dict
        The base scene's tables.
    name : str
        The scene's name.
    fidelity : str or None
        The fidelity preset.
    responses : sequence of str
        The responses recorded.
    design : Design
        The design (its kind, keys, seed and values).

    Returns
    -------
    str
        A SHA-256 hex digest.
    """
    h = hashlib.sha256()
    h.update(json.dumps({"base": base, "name": name, "fidelity": fidelity,
                         "responses": list(responses), "design": design.kind,
                         "varied": design.describe(), "seed": design.seed},
                        sort_keys=True, default=str).encode("utf-8"))
    h.update(np.ascontiguousarray(design.values, dtype=float).tobytes())
    return h.hexdigest()


def read_rows(path: Path, finger: str, n_fields: int) -> dict[int, tuple]:
    """The rows a journal holds, by run number.

    Parameters
    ----------
    path : Path
        The journal.
    finger : str
        The study's :func:`fingerprint`: the journal must be of this study.
    n_fields : int
        Fields a row has (3 and the responses); a line cut short is skipped.

    Returns
    -------
    dict of int to tuple
        ``{run_id: (run_id, status, error, *responses)}``.

    Raises
    ------
    InputError
        If the file is not a study's journal, or is another study's.
    """
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    try:
        head = json.loads(lines[0])
    except (json.JSONDecodeError, IndexError):
        head = {}
    if not isinstance(head, dict) or head.get("fingerprint") != finger:
        raise InputError("--resume", str(path), "the partial file of this same study (the "
                         "same scene, keys, design, seed, responses and fidelity); it is of "
                         "another study: run without --resume to start afresh")
    rows = {}
    for line in lines[1:]:
        try:
            r = json.loads(line)
        except json.JSONDecodeError:
            continue                    # a line cut short by a kill, or the empty last one
        if isinstance(r, list) and len(r) == n_fields:
            rows[int(r[0])] = (int(r[0]), r[1], r[2], *(float(v) for v in r[3:]))
    return rows


class Journal:
    """The journal of one study, open for appending.

    Parameters
    ----------
    path : Path
        The file.
    head : dict
        What its first line records (``fingerprint`` and the design), written when
        the file is started.
    keep : bool
        True to append to the journal there (a resumed study), False to start it
        afresh.
    """

    def __init__(self, path: Path, head: dict, keep: bool):
        self.path = Path(path)
        #: The open file's descriptor; None once closed.
        self._fd: int | None
        if keep and self.path.exists():
            self._fd = os.open(self.path, os.O_WRONLY | os.O_APPEND)
            with open(self.path, "rb") as f:
                f.seek(0, os.SEEK_END)
                if f.tell():
                    f.seek(-1, os.SEEK_END)
                    if f.read(1) != b"\n":    # a line cut short by a kill: end it
                        os.write(self._fd, b"\n")
        else:
            self._fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
            line = json.dumps({"corliss_study": PARTIAL_NOTE, **head}, default=str)
            os.write(self._fd, (line + "\n").encode("utf-8"))

    def append(self, rows) -> None:
        """Write finished rows, each a line, in one call.

        Parameters
        ----------
        rows : iterable of tuple
            ``(run_id, status, error, *responses)``.
        """
        if self._fd is None:
            raise ValueError(f"journal {self.path} is closed: no rows can be appended")
        text = "".join(json.dumps(list(r)) + "\n" for r in rows)
        if text:
            os.write(self._fd, text.encode("utf-8"))

    def close(self) -> None:
        """Close the file (kept on disk)."""
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def remove(self) -> None:
        """Close and delete the file (the study's own files hold its rows now)."""
        self.close()
        try:
            self.path.unlink()
        except FileNotFoundError:
            pass
