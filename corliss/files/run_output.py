"""Export of results: tables in US or SI as CSV with a meta file, the summary as JSON,
the figures as PNG; every file of a run written whole or not at all.

The engine's results (:mod:`corliss.engine.result`) are SI, the unit in each column's
name.  On output the scene's ``[output] units`` (or the caller) chooses US (psia,
ft3, degF, lb, ft lbf, hp) or SI (kPa absolute, m3, degC, kg, J, kW); names carry the
unit either way (:mod:`corliss.frames.columns`).  A ``.meta.json`` beside each CSV holds what
reruns the result exactly: the scene (its file's text and SHA-256, the tables as read,
the resolved values), the run's knobs, the package and dependency versions, the
property tier, the wall time and the unit of every column; ``corliss run --from-meta``
reads it back (:func:`scene_from_meta`).

Writing is a transaction (:class:`OutputFiles`): files are staged in a private
directory inside the output folder, created with the ordinary permissions (the umask
applies), and moved into place only when every file of the run has been written; a
failure anywhere leaves the folder as it was.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime as _dt
import errno
import hashlib
import json
import logging
import math
import os
import platform
import shutil
import signal
import tempfile
import threading
import time
import tomllib
from importlib.metadata import PackageNotFoundError
from pathlib import Path
from typing import Any

import numpy as np

try:
    import fcntl
except ImportError:  # pragma: no cover - not a POSIX system
    fcntl = None  # type: ignore[assignment]  # no POSIX locks here: the lock is skipped

from corliss import __version__, plot
from corliss.plot.shape import one_shape
from corliss.frames import columns
from corliss.engine.options import PRESETS, Fidelity
from corliss.errors import InputError, RunError
from corliss.keys import limits
from corliss.keys.textfiles import read_text
from corliss.logs import NOTICE
from corliss.scene.loader import scene_from_dict
from corliss.versions import installed_version

#: Distributions whose versions a meta file records.
DEPENDENCIES = ("numpy", "scipy", "pandas", "matplotlib", "numba", "CoolProp")
#: Resolution of the PNG figures [dots per inch].
DPI = 120
#: PNG compression: zlib's fastest level.  Measured on the default scene's two figures,
#: it saves about 12 ms of the 190 ms they take to draw and save, for files 7 % larger
#: (126 kB, not 118 kB): the drawing, not the compression, is the cost.
PNG_OPTIONS = {"compress_level": 1}

log = logging.getLogger(__name__)


def package_version() -> str:
    """The installed corliss version.

    Returns
    -------
    str
        The distribution's version from its metadata; ``corliss.__version__`` when
        running from a source tree that is not installed.
    """
    try:
        return installed_version("corliss")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        return __version__


def dependency_versions() -> dict[str, str | None]:
    """Versions of Python and the dependencies, from their metadata (nothing imported).

    Returns
    -------
    dict of str to (str or None)
        ``{"python": ..., name: version}`` for each of :data:`DEPENDENCIES`; None for
        one not installed.
    """
    out: dict[str, str | None] = {"python": platform.python_version()}
    for name in DEPENDENCIES:
        try:
            out[name] = installed_version(name)
        except PackageNotFoundError:  # pragma: no cover
            out[name] = None
    return out


def jsonable(obj):
    """Turn numpy scalars and arrays, tuples, dataclasses and NaN into plain JSON values.

    Parameters
    ----------
    obj : object
        Any value; containers are converted recursively.

    Returns
    -------
    object
        Dicts (keys as strings), lists, floats (NaN and infinities as None), ints,
        bools and whatever else ``obj`` held, unchanged.
    """
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return jsonable(dataclasses.asdict(obj))
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        f = float(obj)
        return f if math.isfinite(f) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def summary_json(summary: dict) -> str:
    """The summary as the JSON text of ``corliss run --json``.

    Parameters
    ----------
    summary : dict
        A result's summary.

    Returns
    -------
    str
        Indented JSON, NaN written as null.
    """
    return json.dumps(jsonable(summary), indent=2)


# --- meta files and reruns ------------------------------------------------------------

def relative_source(source: str | None, folder) -> str | None:
    """A scene file's path as a meta file in ``folder`` records it: relative to that
    folder (``/``-separated), so that the folder and the scene moved together still
    find each other and no absolute path of the machine is written; as it is where no
    relative path exists (another drive) or without a folder or a file.

    Parameters
    ----------
    source : str or None
        The scene's file.
    folder : str or Path or None
        The folder the meta file is written in.

    Returns
    -------
    str or None
    """
    if not source or folder is None:
        return source
    try:
        return Path(os.path.relpath(Path(source).absolute(), Path(folder).absolute())).as_posix()
    except ValueError:          # on another drive
        return source


def meta(result, column_units: dict | None = None, file: str | None = None,
         units_system: str | None = None, folder=None) -> dict:
    """The meta file of a table of a result: what reruns it and what its columns are.

    Parameters
    ----------
    result : Result
        The run.
    column_units : dict of str to str, optional
        ``{column: unit}`` of the table as written.
    file : str, optional
        The table file's name.
    units_system : str, optional
        The table's units, recorded as ``units_system``; default the scene's.

    folder : str or Path, optional
        The folder the meta file is written in: the scene's file is recorded relative
        to it (:func:`relative_source`).

    Returns
    -------
    dict
        The file, kind, versions (corliss, CoolProp and the dependencies), property
        backend, creation time (UTC), wall time [s], units, ``columns``, the scene
        (name, file, SHA-256 and text, tables as read, resolved values), the run's
        knobs and the summary, all JSON values.
    """
    scene = result.scene
    text = scene.text
    versions = dependency_versions()
    return {
        "file": file,
        "kind": result.kind,
        "corliss_version": package_version(),
        "coolprop_version": versions["CoolProp"],
        "versions": versions,
        "property_backend": result.property_tier,
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "wall_time_s": result.wall_time_s,
        "units_system": units_system or scene.output.units,
        "pressure": "absolute",
        "columns": column_units,
        "scene_name": scene.name,
        "scene_file": relative_source(scene.source, folder),
        "scene_sha256": hashlib.sha256(text.encode("utf-8")).hexdigest() if text else None,
        "scene_toml": text,
        "scene_data": jsonable(scene.data),
        "run": jsonable(scene.run),
        "scene": _with_source(jsonable(scene.resolved()), relative_source(scene.source, folder)),
        "summary": jsonable(result.summary),
    }


def _with_source(resolved, source):
    """The resolved scene with its file recorded as the meta file records it."""
    if isinstance(resolved, dict) and "source" in resolved:
        return {**resolved, "source": source}
    return resolved


def _first_difference(a, b, key: str = "") -> tuple[str, object, object] | None:
    """The first dotted key where two JSON values differ, with both values."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b), key=str):
            sub = f"{key}.{k}" if key else str(k)
            if k not in a or k not in b:
                return sub, a.get(k), b.get(k)
            d = _first_difference(a[k], b[k], sub)
            if d is not None:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            d = _first_difference(x, y, f"{key}[{i}]")
            if d is not None:
                return d
        return None
    return None if (a == b and type(a) is type(b)) else (key, a, b)


#: The run's knobs a command line changes (``--fidelity``, ``--cycles``,
#: ``--duration``, ``--until-settled``), which a meta file records as run; every other
#: field of its ``run`` is the scene's own and must agree with its scene.
RUN_KNOBS = ("fidelity", "cycles", "duration_s", "until_settled", "max_duration_s")


def _meta_run(run: object, base, key: str, edited: bool):
    """The scene's run with the meta file's knobs, each checked; ``base`` the scene's."""
    names = [f.name for f in dataclasses.fields(base)]
    if not isinstance(run, dict):
        raise InputError(key, _short(run), "a table of the run's knobs")
    unknown = sorted(set(run) - set(names), key=str)
    if unknown:
        raise InputError(f"{key}.{unknown[0]}", _short(run[unknown[0]]),
                         "a field of a run: " + ", ".join(names))
    missing = [n for n in names if n not in run]
    if missing:
        raise InputError(f"{key}.{missing[0]}", None, "every field of the run a meta file "
                         "records")
    if run["mode"] == "steady" and base.mode == "transient":
        base = dataclasses.replace(base, mode="steady", duration_s=None)   # a study's
    if not edited:
        for n in names:
            if n in RUN_KNOBS:
                continue
            d = _first_difference(jsonable(run[n]), jsonable(getattr(base, n)))
            if d is not None:
                raise InputError(f"{key}.{n}", _short(run[n]), f"the scene's own "
                                 f"{_short(jsonable(getattr(base, n)))!r}: the meta file's run "
                                 "disagrees with its scene (edited by hand?)")
    fid = run["fidelity"]
    known = [jsonable(base.fidelity)] + [jsonable(f) for f in PRESETS.values()]
    if fid not in known:
        raise InputError(f"{key}.fidelity", _short(fid), "the scene's fidelity or one of the "
                         "presets " + ", ".join(PRESETS) + " (what a run records)")
    fidelity = base.fidelity if fid == known[0] else Fidelity(**fid)
    cycles = run["cycles"]
    if cycles is not None and not (type(cycles) is int and 1 <= cycles <= limits.MAX_CYCLES
                                   and base.mode == "steady"):
        raise InputError(f"{key}.cycles", _short(cycles), "null, or in a steady run a whole "
                         f"number of cycles from 1 to {limits.MAX_CYCLES}")
    times: dict[str, float | None] = {}
    for n in ("duration_s", "max_duration_s"):
        v = run[n]
        ok = (v is None and (base.mode != "transient" or n != "duration_s")) or (
            type(v) in (int, float) and 0.0 < v <= limits.MAX_DURATION_S
            and base.mode == "transient")
        if not ok:
            raise InputError(f"{key}.{n}", _short(v), "in a transient run a time above 0 "
                             f"up to {limits.MAX_DURATION_S:g} s [s]; null in a steady one")
        times[n] = None if v is None else float(v)
    if type(run["until_settled"]) is not bool:
        raise InputError(f"{key}.until_settled", _short(run["until_settled"]), "true or false")
    duration_s, max_duration_s = times["duration_s"], times["max_duration_s"]
    # a transient run (the only kind with a max_duration_s) always has its duration_s
    if run["until_settled"] and (max_duration_s is None or (
            duration_s is not None and max_duration_s < duration_s)):
        raise InputError(f"{key}.max_duration_s", times["max_duration_s"], "a time at least "
                         "the duration in a run until settled")
    return dataclasses.replace(base, fidelity=fidelity, cycles=cycles,
                               until_settled=run["until_settled"], **times)


def _short(value: object, chars: int = 80) -> object:
    """A value for an error message: long text or tables shortened."""
    text = repr(value)
    return value if len(text) <= chars else text[:chars] + "..."


def scene_from_meta(path: str | Path, edited: bool = False):
    """The scene a meta file records, with the run's knobs as they were.

    Fidelity, cycles, duration and the rest: running the scene reproduces the result
    (``corliss run --from-meta``).  A meta file is a thing people send each other,
    so it is read as untrusted input: its scene's text must have the SHA-256 it
    records and give the tables it records, its run may differ from its scene's only
    in the knobs a command line sets (:data:`RUN_KNOBS`, each checked), its scene's
    name must be a plain file name (the output files' stem), and every other field is
    checked as a scene's.

    Parameters
    ----------
    path : str or Path
        A ``.meta.json`` file written beside a result's table.
    edited : bool, optional
        Run the meta file's scene text as it is now (edited since the run): its hash
        and recorded tables are not checked, the text's tables are used.

    Returns
    -------
    Scene
        The scene, loaded and checked from its recorded tables, with the recorded
        run knobs and scene text.

    Raises
    ------
    InputError
        If the file is not a corliss meta file, disagrees with itself, or any field is
        not valid.
    """
    p = Path(path)
    raw = read_text(p, "--from-meta", "a .meta.json file written by corliss")
    try:
        m = json.loads(raw)
    except (ValueError, RecursionError) as exc:
        raise InputError("--from-meta", str(path), "a .meta.json file written by corliss "
                         f"(not JSON: {str(exc)[:120]})") from None
    if not isinstance(m, dict):
        raise InputError("--from-meta", str(path), "a .meta.json file written by corliss (a "
                         "JSON object)")
    text, sha = m.get("scene_toml"), m.get("scene_sha256")
    if text is not None and type(text) is not str:
        raise InputError("scene_toml", _short(text), "the scene file's text, or null")
    if sha is not None and not (type(sha) is str and len(sha) == 64
                                and all(c in "0123456789abcdef" for c in sha)):
        raise InputError("scene_sha256", _short(sha), "64 lower-case hexadecimal digits, or "
                         "null")
    data = m.get("scene_data")
    if text is not None:
        actual = hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()
        if not edited and sha != actual:
            raise InputError("scene_sha256", sha, f"the SHA-256 of the meta file's scene "
                             f"text, {actual}: the text was changed after the run (run "
                             "it as edited with --as-edited)")
        try:
            parsed = tomllib.loads(text)
        except (tomllib.TOMLDecodeError, RecursionError) as exc:
            raise InputError("scene_toml", _short(text, 40), f"a scene's TOML text "
                             f"({str(exc)[:120]})") from None
        if edited:
            data = parsed
        else:
            d = _first_difference(jsonable(parsed), data)
            if d is not None:
                raise InputError(f"scene_data.{d[0]}" if d[0] else "scene_data",
                                 _short(d[2]), f"{_short(d[1])!r}, as the meta file's scene "
                                 "text has it: its tables were changed after the run "
                                 "(run the text as edited with --as-edited)")
    elif sha is not None:
        raise InputError("scene_toml", None, "the scene text whose SHA-256 the meta file "
                         "records")
    if not isinstance(data, dict):
        raise InputError("scene_data", _short(data), "the scene's tables (a JSON object)")
    name = m.get("scene_name")
    if name is None:
        name = p.name.split(".")[0]
    plain_name(name, "scene_name")
    source = m.get("scene_file")
    if source is not None and not (type(source) is str and len(source) <= 4096):
        raise InputError("scene_file", _short(source), "the scene file's path, or null")
    if source is not None and not Path(source).is_absolute():
        source = str(p.absolute().parent / source)    # recorded relative to the meta file
    try:
        scene = scene_from_dict(data, name=name, source=source)
    except RecursionError:
        raise InputError("scene_data", "(nested too deeply)", "the scene's tables") from None
    if "run" not in m:
        raise InputError("run", None, "the run's knobs, as a meta file records them")
    run = _meta_run(m["run"], scene.run, "run", edited)
    return dataclasses.replace(scene, run=run, text=text)


# --- the transaction -------------------------------------------------------------------

#: Prefix of a run's private staging folder inside the output folder.
STAGING_PREFIX = ".corliss-"
#: The staging folder's journal: written (atomically) before the first file is moved
#: into place, it lists the run's files; a staging folder that holds it belongs to a
#: run that had decided to commit, and the next run into the folder finishes the moves.
JOURNAL = ".commit.json"
#: How long a run waits for another corliss run to finish writing into the same
#: output folder before it gives up [s].  A run's files take well under a second to
#: write; a large study's Parquet and figures a few seconds.
LOCK_WAIT_S = 120.0
#: A scene's units when its tables name none (``[output] units``' declared default).
OWN_UNITS_DEFAULT = "US"
#: The longest output file stem (a scene's name) [characters].
MAX_STEM_CHARS = 120


def plain_name(name: str, key: str = "scene name") -> str:
    """``name`` if it is a plain file name that stays inside its folder.

    No path separator, no ``..``, not absolute, not hidden (a leading dot: corliss's
    own staging folders start so), no control character, at most
    :data:`MAX_STEM_CHARS` characters plus a suffix.

    Parameters
    ----------
    name : str
        A file name or a stem.
    key : str, optional
        What named it, for the error.

    Returns
    -------
    str
        ``name``.

    Raises
    ------
    InputError
        If it is not such a name.
    """
    ok = (type(name) is str and 0 < len(name) <= MAX_STEM_CHARS + 40
          and name not in (".", "..") and not name.startswith(".")
          and not any(c in name for c in "/\\")
          and name.isprintable() and name == name.strip()
          and not (len(name) > 1 and name[1] == ":"))       # no Windows drive
    if not ok:
        raise InputError(key, name, "a plain file name: no folder separators or '..', not "
                         "absolute or hidden, printable, at most "
                         f"{MAX_STEM_CHARS} characters")
    return name


def output_stem(scene, units_system: str | None = None) -> str:
    """The stem of the files a command writes for ``scene``: its name, and the unit
    system when the files are not in the scene's own.

    A scene's files in its own units keep the plain stem (``default.summary.json``);
    ``--units SI`` on an inch scene writes ``default.SI.summary.json`` beside them,
    so a US and an SI run of one scene into one folder never overwrite each other.
    Each command adds its name after the stem (``default.sweep.csv``,
    ``default.design.toml``, ``default.fit.json``); ``run``'s tables are named for
    themselves (``default.cycles.csv``).

    Parameters
    ----------
    scene : Scene
        The scene (its name, its tables' ``[output] units`` and the units asked,
        ``scene.output.units``).
    units_system : str, optional
        The files' units, when not ``scene.output.units``.

    Returns
    -------
    str
        The stem.
    """
    system = units_system or scene.output.units
    own = ((scene.data or {}).get("output") or {}).get("units", OWN_UNITS_DEFAULT) \
        if scene.data is not None else scene.output.units
    return scene.name if system == own else f"{scene.name}.{system}"


@contextlib.contextmanager
def _signals_held():
    """SIGINT and SIGTERM held while the block runs, then delivered.

    The moves of a commit take milliseconds; a Ctrl-C among them is acted on once every
    file is in place, so the folder holds the new run's whole set.  Only the main
    thread can set handlers; elsewhere the commit's own roll-back covers an exception.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []

    def hold(signum, frame):
        caught.append(signum)
    old = {}
    try:
        for s in (signal.SIGINT, signal.SIGTERM):
            old[s] = signal.signal(s, hold)
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)
        if caught:
            signal.raise_signal(caught[0])


class _FolderLock:
    """One writer per output folder: an exclusive ``flock`` on the folder itself.

    Released by the system when the process ends, however it ends (a killed run holds
    nothing).  A second run waits up to :data:`LOCK_WAIT_S`, then stops with a
    :class:`~corliss.errors.RunError`.  Where ``fcntl`` is missing (Windows) there is
    no lock.
    """

    def __init__(self, folder: Path, wait_s: float):
        self.folder = folder
        self.wait_s = wait_s
        self.fd: int | None = None

    def acquire(self) -> None:
        if fcntl is None:      # pragma: no cover - not a POSIX system
            return
        self.fd = os.open(self.folder, os.O_RDONLY)
        t0 = time.monotonic()
        told = False
        while True:
            try:
                fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                return
            except BlockingIOError:
                pass
            if not told:
                log.log(NOTICE, "waiting for another corliss run writing into %s",
                        self.folder)
                told = True
            if time.monotonic() - t0 > self.wait_s:
                self.release()
                raise RunError(f"another corliss run has been writing into {self.folder} "
                               f"for over {self.wait_s:.0f} s; give --out another folder, or "
                               "wait for that run to finish")
            time.sleep(0.05)

    def release(self) -> None:
        if self.fd is not None:
            os.close(self.fd)           # closing drops the flock
            self.fd = None


def recover_staging(out_dir: Path) -> list[str]:
    """Finish or remove what killed runs left in ``out_dir``: their staging folders.

    A staging folder with a journal belongs to a run that was moving its files into
    place when it was killed: its remaining files are moved in and the earlier run's
    files it was retiring removed, so the folder holds that run's whole set.  One without a journal never began to move anything: it is
    removed, the folder's files untouched.  Call it holding the folder's lock.

    Parameters
    ----------
    out_dir : Path
        The output folder.

    Returns
    -------
    list of str
        What was done, a line per staging folder (also logged).
    """
    done = []
    for d in sorted(out_dir.glob(STAGING_PREFIX + "*")):
        if d.is_symlink() or not d.is_dir():
            continue
        journal = d / JOURNAL
        moved = 0
        if journal.is_file():
            try:
                entry = json.loads(journal.read_text(encoding="utf-8"))
                names = [plain_name(n, "journal") for n in entry["files"]]
                stale = [plain_name(n, "journal") for n in entry.get("retire", [])]
            except (OSError, ValueError, KeyError, TypeError, AttributeError):
                names, stale = [], []
            for name in names:
                src = d / name
                if src.is_file() and not src.is_symlink():
                    os.replace(src, out_dir / name)
                    moved += 1
            for name in stale:
                target = out_dir / name
                if os.path.lexists(target) and not (target.is_dir() and not target.is_symlink()):
                    target.unlink()
            line = (f"finished moving the files of a run killed while writing into "
                    f"{out_dir} ({moved} moved)")
        else:
            line = f"removed the staging folder {d.name} of a run killed before writing"
        shutil.rmtree(d, ignore_errors=True)
        log.warning(line)
        done.append(line)
    return done


#: Errors of the folder or the disk, not of the code: a full disk, a quota, a folder
#: that cannot be written; a run meeting one stops with a message, not a traceback.
_FOLDER_ERRNOS = {errno.ENOSPC, errno.EDQUOT, errno.EACCES, errno.EROFS, errno.EPERM}


class OutputFiles:
    """Files of one run, staged and then moved into ``out_dir`` together.

    Use as a context manager: ``stage(name)`` gives the path to write a file to;
    leaving the block without an exception moves every staged file into place;
    an exception leaves ``out_dir`` as it was, the folder itself removed if the run
    created it.

    The folder has one writer at a time (a lock on it, held from entering the block to
    leaving it); entering finishes or removes what a killed run left
    (:func:`recover_staging`).  Files of an earlier run this one does not replace
    (:meth:`retire`: a plotted run's figures under a run without them) are removed in
    the same commit.  The commit never removes an earlier file: each new file
    is renamed over its old one (an atomic replace), the earlier files hard-linked
    beside the staged ones first, so a failure part-way puts every earlier file back;
    a journal written before the first move lets the next run finish the moves of a
    run killed among them; SIGINT and SIGTERM are held during the moves.

    Parameters
    ----------
    out_dir : str or Path
        The output folder (made, with any missing parents, on entering the block).
    lock_wait_s : float, optional
        How long to wait for another run writing into the folder [s].
    """

    def __init__(self, out_dir: str | Path, lock_wait_s: float = LOCK_WAIT_S):
        self.out_dir = Path(out_dir)
        self.files: dict[str, Path] = {}
        self.retired: list[str] = []
        self._created: list[Path] = []
        self._tmp: Path | None = None
        self._lock = _FolderLock(self.out_dir, lock_wait_s)

    def __enter__(self) -> "OutputFiles":
        missing = []
        d = self.out_dir.absolute()
        while not d.exists():
            missing.append(d)
            d = d.parent
        try:
            self.out_dir.mkdir(parents=True, exist_ok=True)
            if not self.out_dir.is_dir():
                raise NotADirectoryError(f"{self.out_dir} is not a folder")
        except OSError as exc:
            raise RunError(f"could not make the output folder {self.out_dir} "
                           f"({exc.strerror or exc}); give --out a folder that can be "
                           "written to") from None
        self._created = missing        # deepest first: removed in this order on failure
        try:
            self._lock.acquire()
            recover_staging(self.out_dir)
            self._tmp = Path(tempfile.mkdtemp(dir=self.out_dir, prefix=STAGING_PREFIX))
        except BaseException as exc:
            self._lock.release()
            self._remove_created()
            if isinstance(exc, OSError):
                raise RunError(f"could not write into the output folder {self.out_dir} "
                               f"({exc.strerror or exc}); give --out a folder that can be "
                               "written to") from None
            raise
        return self

    @property
    def _staging(self) -> Path:
        """The staging folder, made on entering the ``with`` block."""
        if self._tmp is None:
            raise RuntimeError("OutputFiles staged a file outside its with block")
        return self._tmp

    def stage(self, name: str) -> Path:
        """Where to write a file of the run, staged until the block ends.

        Parameters
        ----------
        name : str
            A bare file name (:func:`plain_name`); the file ends up as
            ``out_dir / name`` (recorded in ``files``).

        Returns
        -------
        Path
            The staging path to write it to now.
        """
        plain_name(name, "output file")
        self.files[name] = self.out_dir / name
        return self._staging / name

    def retire(self, names) -> None:
        """Files of an earlier run that this run's set does not replace, to be removed
        in its commit: moved into the staging folder with the other moves (and put
        back if the commit fails), so the folder describes one run.

        Parameters
        ----------
        names : iterable of str
            Bare file names in the output folder (:func:`plain_name`); those this run
            stages, and those not there or that are folders, are left alone.
        """
        for name in names:
            plain_name(name, "output file")
            if name not in self.files and name not in self.retired:
                self.retired.append(name)

    def __exit__(self, exc_type, exc, tb) -> None:
        try:
            if exc_type is None:
                self._commit()
        except OSError as failed:
            exc_type, exc = type(failed), failed
            raise
        finally:
            try:
                shutil.rmtree(self._staging, ignore_errors=True)
                if exc_type is not None:
                    self._remove_created()
            finally:
                self._lock.release()
            if isinstance(exc, OSError) and exc.errno in _FOLDER_ERRNOS:
                raise RunError(f"could not write the run's files into {self.out_dir} "
                               f"({exc.strerror or exc}); the folder is as it was") from None

    def _commit(self) -> None:
        for target in self.files.values():
            if target.is_dir() and not target.is_symlink():
                raise IsADirectoryError(f"{target} is a folder: a file of this run goes there")
        backups: dict[str, Path] = {}
        for name, target in self.files.items():
            if os.path.lexists(target):
                backup = self._staging / f".{name}.before"
                try:
                    os.link(target, backup, follow_symlinks=False)
                except OSError:       # a file system without hard links
                    shutil.copy2(target, backup, follow_symlinks=False)
                backups[name] = backup
        stale = [n for n in self.retired if n not in self.files
                 and os.path.lexists(self.out_dir / n)
                 and not ((self.out_dir / n).is_dir() and not (self.out_dir / n).is_symlink())]
        part = self._staging / (JOURNAL + ".part")
        part.write_text(json.dumps({"files": list(self.files), "retire": stale}),
                        encoding="utf-8")
        os.replace(part, self._staging / JOURNAL)
        moved, aside = [], []
        with _signals_held():
            try:
                for name, target in self.files.items():
                    os.replace(self._staging / name, target)
                    moved.append(name)
                for name in stale:
                    # moved aside into the staging folder, removed with it
                    os.replace(self.out_dir / name, self._staging / f".{name}.retired")
                    aside.append(name)
            except BaseException:
                for name in aside:
                    os.replace(self._staging / f".{name}.retired", self.out_dir / name)
                for name in moved:
                    if name in backups:
                        os.replace(backups[name], self.files[name])
                    else:
                        self.files[name].unlink(missing_ok=True)
                (self._staging / JOURNAL).unlink(missing_ok=True)
                self._remove_created()
                raise

    def _remove_created(self) -> None:
        for d in self._created:
            try:
                d.rmdir()
            except OSError:
                break


# --- the export layer's operations -----------------------------------------------------

#: Output files of each kind of result: table name -> file suffix.
TABLE_FILES = {"steady": {"timeseries": "timeseries", "cycles": "cycles", "cards": "cards"},
               "transient": {"timeseries": "timeseries", "cycles": "cycles"},
               "sweep": {"points": "sweep"},
               "compare": {"points": "compare", "willans": "compare.willans",
                           "verdict": "compare.verdict"}}


#: Format of the CSVs' floats: nine significant digits (a re-read reproduces every
#: figure to 5e-9 relative, below the 1e-6 the summary is compared to).
FLOAT_FORMAT = "%.9g"


def write_csv(frame, path: Path) -> None:
    """``frame`` (a DataFrame or a :class:`~corliss.frames.frame.Frame`) as CSV at ``path``: no
    index, floats as :data:`FLOAT_FORMAT`, NaN as an empty field, lines ended by
    ``\\n``: the text of pandas' ``to_csv(index=False, float_format=FLOAT_FORMAT)``.

    A table of numbers, and of text that needs no quoting (a card's ``end``), is
    formatted row by row with one %-format string, four times as fast as pandas' writer
    on a long transient and with no pandas imported; any other table goes through
    pandas (its quoting).

    Parameters
    ----------
    frame : DataFrame or Frame
        The table, its columns named with their units.
    path : Path
        The file to write.
    """
    names = [str(c) for c in frame.columns]
    kinds = [frame[c].dtype.kind for c in frame.columns]
    plain = len(set(names)) == len(names) and not any(
        any(ch in n for ch in ',"\n\r') for n in names)
    cols, fmts = [], []
    for c, k in zip(frame.columns, kinds):
        if not plain:
            break
        v = frame[c].to_numpy()
        if k == "f" and np.isnan(v).any():       # NaN as an empty field, as pandas
            cols.append(["" if x != x else FLOAT_FORMAT % x for x in v.tolist()])
            fmts.append("%s")
        elif k in "fiu":
            cols.append(v.tolist())
            fmts.append(FLOAT_FORMAT if k == "f" else "%d")
        elif k == "O" and all(type(x) is str and x and not any(ch in x for ch in ',"\n\r')
                              and x == x.strip() for x in v.tolist()):
            cols.append(v.tolist())               # words pandas writes as they are
            fmts.append("%s")
        else:
            plain = False
    if not plain:
        (frame if hasattr(frame, "to_csv") else frame.to_pandas()).to_csv(
            path, index=False, float_format=FLOAT_FORMAT)
        return
    fmt = ",".join(fmts) + "\n"
    with open(path, "w", encoding="utf-8", newline="") as f:
        f.write(",".join(names) + "\n")
        f.write("".join([fmt % row for row in zip(*cols)]))


def _write_table(result, table: str, path: Path, name: str, units_system: str | None,
                 folder) -> None:
    """Write one table as CSV and its meta file beside it (``path`` is the staged CSV,
    ``folder`` the one it is moved into)."""
    system = units_system or result.scene.output.units
    frame, col_units = columns.convert_columns(result.frame(table), system,
                                               result.scene.supply.barometer_Pa)
    write_csv(frame, path)
    m = meta(result, col_units, name, system, folder)
    path.with_suffix(".meta.json").write_text(json.dumps(m, indent=2))


def to_csv(result, path, table: str, units_system: str | None = None) -> Path:
    """Write a result's table as CSV with its ``.meta.json``, both or neither.

    Parameters
    ----------
    result : Result
        The run.
    path : str or Path
        The CSV file; the meta file is written beside it, ``.csv`` replaced by
        ``.meta.json``.
    table : str
        One of the result's ``TABLES``.
    units_system : str, optional
        ``"US"`` or ``"SI"``; default the scene's ``output.units``.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    with OutputFiles(path.parent) as out:
        staged = out.stage(path.name)
        out.stage(path.with_suffix(".meta.json").name)
        _write_table(result, table, staged, path.name, units_system, path.parent)
    return path


def plot_result(result, kind: str, ax=None, units_system: str | None = None) -> dict:
    """Draw one of a result's figures.

    Parameters
    ----------
    result : Result
        The run.
    kind : str
        One of its ``FIGURES``: ``"card"``, ``"effort"``, ``"lp_card"`` (a compound),
        ``"loadstep"``, ``"compare"`` or ``"willans"``.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (ignored by the figures of several panels, ``loadstep`` and
        ``compare``).
    units_system : str, optional
        ``"US"`` or ``"SI"``; default the scene's ``output.units``.

    Returns
    -------
    dict
        One shape for every kind (:func:`corliss.plot.shape.one_shape`): ``figure``,
        ``axes`` (a list, the main first), ``ax`` (the main axes) and ``lines``
        (``{name: Line2D}``), beside what the plotting function of
        :mod:`corliss.plot` returned.

    Raises
    ------
    ValueError
        If ``kind`` is not a figure of this result.
    """
    if kind not in result.FIGURES or (kind == "lp_card" and result.scene.compound is None):
        raise ValueError(f"figure {kind!r}: one of {', '.join(result.FIGURES)} (lp_card for "
                         "a compound)")
    if kind == "card":
        return one_shape(plot.plot_card(result, ax=ax, units_system=units_system))
    if kind == "lp_card":
        return one_shape(plot.plot_card(result, ax=ax, units_system=units_system,
                                        prefix="lp_"))
    if kind == "effort":
        return one_shape(plot.plot_crank_effort(result, ax=ax, units_system=units_system))
    if kind == "loadstep":
        return one_shape(plot.plot_load_step(result, units_system=units_system))
    if kind == "compare":
        return one_shape(plot.plot_compare(result, units_system or result.scene.output.units))
    pts = result.points
    sweeps = ({f"{result.scene.title} ({k})": g for k, g in pts.groupby("knob", sort=False)}
              if "knob" in pts else {f"{result.scene.title} ({result.knob})": pts})
    return one_shape(plot.plot_willans(sweeps, ax, units_system or result.scene.output.units))


def _figures(result) -> list[tuple[str, tuple[float, float]]]:
    if result.kind == "steady":
        figs: list[tuple[str, tuple[float, float]]] = [("card", (9, 5.5)),
                                                       ("effort", (9, 4.5))]
        if result.scene.compound is not None:
            figs.append(("lp_card", (9, 5.5)))
        return figs
    if result.kind == "transient":
        return [("loadstep", (0, 0))]
    if result.kind == "compare":
        return [("compare", (0, 0))]
    return [("willans", (8, 5.5))]


def plain_text(plots: bool = True):
    """A block whose figures show text as it is: a ``$`` in a scene's title is a
    dollar, not the start of mathtext (``$\\frac{a}{$`` stopped a run's plot); none
    of corliss's own labels uses mathtext.

    Parameters
    ----------
    plots : bool, optional
        Whether the block draws; without figures it imports no matplotlib.

    Returns
    -------
    contextlib.AbstractContextManager
        matplotlib's ``rc_context`` with ``text.parse_math`` off, or a block that
        does nothing when ``plots`` is false.
    """
    if not plots:
        return contextlib.nullcontext()
    import matplotlib
    return matplotlib.rc_context({"text.parse_math": False})


def write(result, out_dir, plots: bool = True) -> dict[str, Path]:
    """Write every file of ``result`` into ``out_dir`` as one transaction.

    Each table of :data:`TABLE_FILES` as CSV with its meta file, in the scene's units;
    the figures as PNG; the summary as JSON.  Files of the same stem an earlier run
    wrote and this one does not (:func:`family_names`: figures under ``plots=False``,
    a steady run's cards under a transient run) are removed in the same commit.

    Parameters
    ----------
    result : Result
        The run.
    out_dir : str or Path
        The output folder (made if missing).
    plots : bool, optional
        Whether to draw the figures.

    Returns
    -------
    dict
        ``{kind: path}`` of the tables, figures and summary written (meta files beside
        the tables).
    """
    stem = output_stem(result.scene)
    files: dict[str, Path] = {}
    with OutputFiles(out_dir) as out, plain_text(plots):
        for table, suffix in TABLE_FILES[result.kind].items():
            name = f"{stem}.{suffix}.csv"
            staged = out.stage(name)
            out.stage(Path(name).with_suffix(".meta.json").name)
            _write_table(result, table, staged, name, None, out_dir)
            files[table] = out.files[name]
        if plots:
            import matplotlib.pyplot as plt     # only when drawing: a run without
            from matplotlib.figure import Figure  # figures imports no matplotlib
            for kind, size in _figures(result):
                # a one-axes figure is drawn on a Figure of its own (no pyplot, no
                # backend); a figure of several axes is made by its plot function
                fig: Any = Figure(figsize=size) if size[0] else None
                ax = fig.add_subplot() if fig is not None else None
                try:
                    with plt.ioff():
                        drawn = plot_result(result, kind, ax)
                    fig = drawn.get("figure", fig)
                    name = f"{stem}.{kind}.png"
                    fig.savefig(out.stage(name), dpi=DPI, bbox_inches="tight", format="png",
                                pil_kwargs=PNG_OPTIONS)
                    files[kind] = out.files[name]
                finally:
                    plt.close(fig)
        name = _summary_name(stem, result.kind)
        out.stage(name).write_text(summary_json(result.summary))
        files["summary"] = out.files[name]
        out.retire(sorted(family_names(stem, result.kind)))
    return files


#: The figures each kind of result may draw (:func:`_figures`: ``lp_card`` for a
#: compound only).
FIGURE_NAMES = {"steady": ("card", "effort", "lp_card"), "transient": ("loadstep",),
                "sweep": ("willans",), "compare": ("compare",)}


def _summary_name(stem: str, kind: str) -> str:
    return f"{stem}.{kind}.summary.json" if kind in ("sweep", "compare") else f"{stem}.summary.json"


def family_names(stem: str, kind: str) -> set[str]:
    """Every file :func:`write` may write for a stem and a kind of result.

    A steady and a transient run share their tables' and summary's names, so their
    files are one family: a run of either replaces the whole family, and what it does
    not write (figures under ``--no-plots``, a steady run's cards under a transient
    run) goes, so the folder describes one run.  A sweep's and a comparison's names
    are their own.

    Parameters
    ----------
    stem : str
        The files' stem (the scene's name).
    kind : str
        ``"steady"``, ``"transient"``, ``"sweep"`` or ``"compare"``.

    Returns
    -------
    set of str
        The tables with their meta files, the figures and the summary.
    """
    kinds = ("steady", "transient") if kind in ("steady", "transient") else (kind,)
    names = set()
    for k in kinds:
        for suffix in TABLE_FILES[k].values():
            names |= {f"{stem}.{suffix}.csv", f"{stem}.{suffix}.meta.json"}
        names |= {f"{stem}.{fig}.png" for fig in FIGURE_NAMES[k]}
        names.add(_summary_name(stem, k))
    return names

