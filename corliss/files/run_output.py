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

import dataclasses
import datetime as _dt
import hashlib
import json
import math
import os
import platform
import shutil
import tempfile
from importlib.metadata import PackageNotFoundError
from pathlib import Path

import numpy as np

from corliss import plot
from corliss.frames import columns
from corliss.engine import result as engine_result
from corliss.engine.options import Fidelity
from corliss.errors import InputError
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
        import corliss
        return corliss.__version__


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

def meta(result, column_units: dict | None = None, file: str | None = None,
         units_system: str | None = None) -> dict:
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
        "scene_file": scene.source,
        "scene_sha256": hashlib.sha256(text.encode("utf-8")).hexdigest() if text else None,
        "scene_toml": text,
        "scene_data": jsonable(scene.data),
        "run": jsonable(scene.run),
        "scene": jsonable(scene.resolved()),
        "summary": jsonable(result.summary),
    }


def scene_from_meta(path: str | Path):
    """The scene a meta file records, with the run's knobs as they were.

    Fidelity, cycles, duration and the rest: running the scene reproduces the result
    (``corliss run --from-meta``).

    Parameters
    ----------
    path : str or Path
        A ``.meta.json`` file written beside a result's table.

    Returns
    -------
    Scene
        The scene, loaded and checked from its recorded tables, with the recorded
        run knobs and scene text.

    Raises
    ------
    InputError
        If the file is not a corliss meta file.
    """
    p = Path(path)
    try:
        m = json.loads(p.read_text(encoding="utf-8"))
        data, run = m["scene_data"], dict(m["run"])
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
        raise InputError("--from-meta", str(path), f"a .meta.json file written by corliss "
                         f"({type(exc).__name__}: {exc})") from None
    if not isinstance(data, dict):
        raise InputError("--from-meta", str(path), "a meta file that holds its scene's tables")
    scene = scene_from_dict(data, name=m.get("scene_name") or p.stem.split(".")[0],
                            source=m.get("scene_file"))
    run["fidelity"] = Fidelity(**run["fidelity"])
    run["effects"] = tuple(run["effects"])
    scene = dataclasses.replace(scene, run=dataclasses.replace(scene.run, **run),
                                text=m.get("scene_toml"))
    return scene


# --- the transaction -------------------------------------------------------------------

class OutputFiles:
    """Files of one run, staged and then moved into ``out_dir`` together.

    Use as a context manager: ``stage(name)`` gives the path to write a file to;
    leaving the block without an exception moves every staged file into place (an
    earlier file of the same name is replaced only then); an exception leaves
    ``out_dir`` as it was, the folder itself removed if the run created it.

    Parameters
    ----------
    out_dir : str or Path
        The output folder (made, with any missing parents, on entering the block).
    """

    def __init__(self, out_dir: str | Path):
        self.out_dir = Path(out_dir)
        self.files: dict[str, Path] = {}
        self._created: list[Path] = []
        self._tmp: Path | None = None

    def __enter__(self) -> "OutputFiles":
        missing = []
        d = self.out_dir.absolute()
        while not d.exists():
            missing.append(d)
            d = d.parent
        self.out_dir.mkdir(parents=True, exist_ok=True)
        self._created = missing        # deepest first: removed in this order on failure
        self._tmp = Path(tempfile.mkdtemp(dir=self.out_dir, prefix=".corliss-"))
        return self

    def stage(self, name: str) -> Path:
        """Where to write a file of the run, staged until the block ends.

        Parameters
        ----------
        name : str
            A bare file name; the file ends up as ``out_dir / name`` (recorded in
            ``files``).

        Returns
        -------
        Path
            The staging path to write it to now.
        """
        self.files[name] = self.out_dir / name
        return self._tmp / name

    def __exit__(self, exc_type, exc, tb) -> None:
        try:
            if exc_type is None:
                self._commit()
        finally:
            shutil.rmtree(self._tmp, ignore_errors=True)
            if exc_type is not None:
                self._remove_created()

    def _commit(self) -> None:
        for target in self.files.values():
            if target.is_dir():
                raise IsADirectoryError(f"{target} is a folder: a file of this run goes there")
        backups, moved = [], []
        try:
            for name, target in self.files.items():
                if target.exists():
                    backup = self._tmp / f".{name}.before"
                    os.replace(target, backup)
                    backups.append((backup, target))
                os.replace(self._tmp / name, target)
                moved.append(target)
        except BaseException:
            for target in moved:
                target.unlink(missing_ok=True)
            for backup, target in backups:
                os.replace(backup, target)
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


def _write_table(result, table: str, path: Path, name: str, units_system: str | None) -> None:
    """Write one table as CSV and its meta file beside it (``path`` is the staged CSV)."""
    system = units_system or result.scene.output.units
    frame, col_units = columns.convert_columns(result.frame(table), system,
                                               result.scene.supply.barometer_Pa)
    write_csv(frame, path)
    m = meta(result, col_units, name, system)
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
        _write_table(result, table, staged, path.name, units_system)
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
        What the plotting function of :mod:`corliss.plot` returned (``ax`` or
        ``figure``, and the lines).

    Raises
    ------
    ValueError
        If ``kind`` is not a figure of this result.
    """
    if kind not in result.FIGURES or (kind == "lp_card" and result.scene.compound is None):
        raise ValueError(f"figure {kind!r}: one of {', '.join(result.FIGURES)} (lp_card for "
                         "a compound)")
    if kind == "card":
        return plot.plot_card(result, ax=ax, units_system=units_system)
    if kind == "lp_card":
        return plot.plot_card(result, ax=ax, units_system=units_system, prefix="lp_")
    if kind == "effort":
        return plot.plot_crank_effort(result, ax=ax, units_system=units_system)
    if kind == "loadstep":
        return plot.plot_load_step(result, units_system=units_system)
    if kind == "compare":
        return plot.plot_compare(result, units_system or result.scene.output.units)
    pts = result.points
    sweeps = ({f"{result.scene.title} ({k})": g for k, g in pts.groupby("knob", sort=False)}
              if "knob" in pts else {f"{result.scene.title} ({result.knob})": pts})
    return plot.plot_willans(sweeps, ax,
                             units_system or result.scene.output.units)


def _figures(result) -> list[tuple[str, tuple[float, float]]]:
    if result.kind == "steady":
        figs = [("card", (9, 5.5)), ("effort", (9, 4.5))]
        if result.scene.compound is not None:
            figs.append(("lp_card", (9, 5.5)))
        return figs
    if result.kind == "transient":
        return [("loadstep", (0, 0))]
    if result.kind == "compare":
        return [("compare", (0, 0))]
    return [("willans", (8, 5.5))]


def write(result, out_dir, plots: bool = True) -> dict[str, Path]:
    """Write every file of ``result`` into ``out_dir`` as one transaction.

    Each table of :data:`TABLE_FILES` as CSV with its meta file, in the scene's units;
    the figures as PNG; the summary as JSON.

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
    stem = result.scene.name
    files: dict[str, Path] = {}
    with OutputFiles(out_dir) as out:
        for table, suffix in TABLE_FILES[result.kind].items():
            name = f"{stem}.{suffix}.csv"
            staged = out.stage(name)
            out.stage(Path(name).with_suffix(".meta.json").name)
            _write_table(result, table, staged, name, None)
            files[table] = out.files[name]
        if plots:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            for kind, size in _figures(result):
                fig, ax = (plt.subplots(figsize=size) if size[0] else (None, None))
                try:
                    drawn = plot_result(result, kind, ax)
                    fig = drawn.get("figure", fig)
                    name = f"{stem}.{kind}.png"
                    fig.savefig(out.stage(name), dpi=DPI, bbox_inches="tight", format="png",
                                pil_kwargs=PNG_OPTIONS)
                    files[kind] = out.files[name]
                finally:
                    plt.close(fig)
        name = (f"{stem}.{result.kind}.summary.json" if result.kind in ("sweep", "compare")
                else f"{stem}.summary.json")
        out.stage(name).write_text(summary_json(result.summary))
        files["summary"] = out.files[name]
    return files


class _Exporter:
    """What the engine's results call for their export methods."""

    to_csv = staticmethod(to_csv)
    plot = staticmethod(plot_result)
    write = staticmethod(write)


engine_result.register_exporter(_Exporter())
