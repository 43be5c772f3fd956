"""Export of a study (:class:`corliss.StudyResult`): the tidy table as CSV with
its meta file and as Parquet, the base scene, the summary and the figure, all written
together or none (:class:`corliss.files.run_output.OutputFiles`).

The table is written as the study made it: the varied keys in the units the user
wrote them in (the unit in the column's name, ``valve_gear.lap_in``), the responses
in SI as the summary names them (``indicated_power_W``; ask for
``indicated_power_hp`` to have horse-power).  A row's scene is the base scene with the
row's keys set; the meta file (``scene_data``, ``varied``) and the Parquet file's
schema metadata (``corliss``) both hold what :func:`corliss.studies.scene_data_of`
needs, and :func:`study_scene` rebuilds it from either file.

Parquet needs pyarrow (``pip install 'corliss[parquet]'``); without it the CSV is
written alone and a notice says how to have the Parquet file too.
"""

from __future__ import annotations

import json
import logging
import tomllib
from pathlib import Path

from corliss.errors import InputError
from corliss.logs import NOTICE
from corliss.plot import plot_study
from corliss.plot.shape import one_shape
from corliss.files.run_output import DPI, PNG_OPTIONS, OutputFiles, jsonable, meta, summary_json, write_csv
from corliss.scene.loader import scene_from_dict
from corliss.studies.study_result import column_unit, converted, scene_data_of
from corliss.keys.toml_text import dumps

log = logging.getLogger(__name__)

#: Key of the Parquet schema's metadata that holds the study's meta (JSON).
PARQUET_META_KEY = b"corliss"
#: How a row's scene is rebuilt, as the meta file says it.
REBUILD = ("the scene of a row is the base scene (scene_data, or the .base.toml file) with "
           "each varied key set to the row's value in its unit: "
           "with_keys(scene_data, {key: f'{row[column]:.12g} {unit}'}) (a bare number for "
           "a key without a unit); corliss.files.study_output.study_scene(file, run_id) does it")


def have_parquet() -> bool:
    """Whether pyarrow is installed (the Parquet file needs it).

    Returns
    -------
    bool
        True when ``pyarrow`` imports.
    """
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return False
    return True


def study_meta(result, name: str, frame=None, converted_units: dict | None = None,
               units_system: str | None = None, folder=None) -> dict:
    """The meta file of a study's table: what rebuilds each row's scene, and the units.

    Parameters
    ----------
    result : StudyResult
        The study.
    name : str
        The table file's name, recorded as ``file``.
    frame : pandas.DataFrame, optional
        The table as written; default the study's ``points`` as made.
    converted_units : dict of str to str, optional
        ``{column: unit}`` of the responses converted into ``units_system`` (from
        :func:`corliss.studies.study_result.converted`).
    units_system : str, optional
        ``"US"`` or ``"SI"`` when the responses were converted; None when the table
        is as made.

    folder : str or Path, optional
        The folder the meta file is written in (the scene's file is recorded relative
        to it).

    Returns
    -------
    dict
        :func:`corliss.files.run_output.meta` of the study (scene, versions, ``columns`` with
        every column's unit), with ``design``, ``seed``, ``varied``, ``responses``,
        ``fidelity`` and ``rebuild_scene`` (:data:`REBUILD`).
    """
    frame = result.points if frame is None else frame
    conv = converted_units or {}
    col_units = {c: conv[c] if c in conv else column_unit(c, result.varied)
                 for c in frame.columns}
    m = meta(result, col_units, name,
             f"varied keys in their own units, responses in {units_system}"
             if units_system else "varied keys in their own units, responses as the "
             "summary names them (SI unless the name says otherwise)", folder)
    m.update({"design": result.design, "seed": result.seed, "varied": result.varied,
              "responses": list(result.responses), "fidelity": result.fidelity,
              "rebuild_scene": REBUILD})
    return m


def _write_parquet(frame, path: Path, m: dict) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq
    table = pa.Table.from_pandas(frame, preserve_index=False)
    md = dict(table.schema.metadata or {})
    md[PARQUET_META_KEY] = json.dumps(jsonable(m)).encode("utf-8")
    pq.write_table(table.replace_schema_metadata(md), path)


def write(result, out_dir, plots: bool = True, parquet: bool | None = None) -> dict[str, Path]:
    """Write every file of a study into ``out_dir`` as one transaction.

    Parameters
    ----------
    result : StudyResult
        The study.
    out_dir : str or Path
        The directory (made if missing).
    plots : bool, optional
        Whether to draw the figure.
    parquet : bool or None, optional
        Whether to write the Parquet file: None writes it when pyarrow is installed
        (with a notice when it is not), True insists.

    Returns
    -------
    dict
        ``{kind: path}``: ``points`` (CSV, its meta beside it), ``parquet``, ``base``
        (the base scene's TOML: its file's text, or the tables written out),
        ``study`` (figure), ``summary``; ``parquet`` and ``study`` only when written.

    Raises
    ------
    InputError
        If ``parquet`` is True and pyarrow is not installed (before anything is
        written).
    """
    if parquet and not have_parquet():
        raise InputError("parquet", True, "pyarrow installed to write Parquet: pip install "
                         "'corliss[parquet]' (the CSV needs nothing more)")
    if parquet is None:
        parquet = have_parquet()
        if not parquet:
            log.log(NOTICE, "pyarrow is not installed: writing the study's CSV without its "
                    "Parquet copy (pip install 'corliss[parquet]' to have both)")
    stem = f"{result.scene.name}.study"
    files: dict[str, Path] = {}
    pts = result.points
    with OutputFiles(out_dir) as out:
        name = f"{stem}.csv"
        m = study_meta(result, name, folder=out_dir)
        write_csv(pts, out.stage(name))
        files["points"] = out.files[name]
        out.stage(f"{stem}.meta.json").write_text(json.dumps(m, indent=2))
        if parquet:
            pname = f"{stem}.parquet"
            _write_parquet(pts, out.stage(pname), m | {"file": pname})
            files["parquet"] = out.files[pname]
        bname = f"{stem}.base.toml"
        text = (result.scene.text if result.scene.text and
                tomllib.loads(result.scene.text) == result.base_data
                else dumps(result.base_data))
        out.stage(bname).write_text(text, encoding="utf-8")
        files["base"] = out.files[bname]
        if plots:
            import matplotlib.pyplot as plt       # only when drawing
            with plt.ioff():
                drawn = plot(result, None, None)
            try:
                fname = f"{stem}.png"
                drawn["figure"].savefig(out.stage(fname), dpi=DPI, bbox_inches="tight",
                                        format="png", pil_kwargs=PNG_OPTIONS)
                files["study"] = out.files[fname]
            finally:
                plt.close(drawn["figure"])
        sname = f"{stem}.summary.json"
        out.stage(sname).write_text(summary_json(result.summary))
        files["summary"] = out.files[sname]
    journal = getattr(result, "journal", None)
    if journal and Path(journal).resolve().parent == Path(out_dir).resolve():
        Path(journal).unlink(missing_ok=True)      # the study's files hold its rows now
    return files


def to_csv(result, path, units_system: str | None = None) -> Path:
    """Write a study's table as CSV with its ``.meta.json``, both or neither.

    Parameters
    ----------
    result : StudyResult
        The study.
    path : str or Path
        The CSV file; ``NAME.meta.json`` is written beside ``NAME.csv``.
    units_system : str, optional
        ``"US"`` or ``"SI"`` to convert the responses (the varied keys stay in their
        own units); None writes the table as made.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    frame, renamed = converted(result.points, result.responses, units_system,
                               result.scene.supply.barometer_Pa)
    with OutputFiles(path.parent) as out:
        staged = out.stage(path.name)
        meta_name = path.name[:-len(".csv")] if path.name.endswith(".csv") else path.name
        m = study_meta(result, path.name, frame, renamed, units_system, path.parent)
        write_csv(frame, staged)
        out.stage(f"{meta_name}.meta.json").write_text(json.dumps(m, indent=2))
    return path


def plot(result, ax=None, units_system: str | None = None) -> dict:
    """The study's figure: each response against each varied key.

    Parameters
    ----------
    result : StudyResult
        The study.
    ax : matplotlib.axes.Axes, optional
        Ignored: the figure is a grid of axes of its own.
    units_system : str, optional
        ``"US"`` or ``"SI"`` for the responses' axes; default the scene's.

    Returns
    -------
    dict
        :func:`corliss.plot.plot_study`'s figure and axes in the one shape of every
        ``plot()`` (:func:`corliss.plot.shape.one_shape`: ``figure``, ``axes``,
        ``ax``, ``lines``).
    """
    return one_shape(plot_study(result.points, result.varied, list(result.responses),
                                units_system=units_system or result.scene.output.units))


def read_study(path) -> tuple:
    """A study's table and meta from its CSV (the meta file beside it) or Parquet file.

    Parameters
    ----------
    path : str or Path
        A study's ``.csv`` (its ``.meta.json`` beside it) or ``.parquet`` file.

    Returns
    -------
    frame : pandas.DataFrame
        The table as written.
    meta : dict
        Its meta (:func:`study_meta`): from the meta file, or from the Parquet
        schema's metadata.

    Raises
    ------
    InputError
        If the file, or its meta, cannot be read as a study's.
    """
    import pandas as pd
    p = Path(path)
    try:
        if p.suffix == ".parquet":
            import pyarrow.parquet as pq
            table = pq.read_table(p)
            m = json.loads(table.schema.metadata[PARQUET_META_KEY])
            return table.to_pandas(), m
        frame = pd.read_csv(p, keep_default_na=False, na_values=[""])
        m = json.loads(p.with_name(p.name[:-len(".csv")] + ".meta.json").read_text())
        return frame, m
    except (OSError, KeyError, ValueError, TypeError) as exc:
        raise InputError("study file", str(path), "a study's .csv (with its .meta.json "
                         f"beside it) or .parquet written by corliss ({type(exc).__name__}: "
                         f"{exc})") from None


def study_scene(path, run_id: int):
    """The scene of one run of a written study, loaded and checked: the scene that was run.

    Parameters
    ----------
    path : str or Path
        The study's ``.csv`` or ``.parquet`` file.
    run_id : int
        The run's number in the design (its ``run_id``).

    Returns
    -------
    Scene
        The base scene with the row's keys set, at the study's fidelity.

    Raises
    ------
    InputError
        If the file cannot be read as a study's, or it has no such run.
    """
    frame, m = read_study(path)
    rows = frame[frame["run_id"] == int(run_id)]
    if rows.empty:
        raise InputError("run_id", run_id, f"a run of the study: 0 to {len(frame) - 1}")
    data = scene_data_of(m["scene_data"], m["varied"], rows.iloc[0].to_dict())
    sc = scene_from_dict(data, name=m.get("scene_name") or "scene")
    return sc.with_fidelity(m["fidelity"]) if m.get("fidelity") else sc

