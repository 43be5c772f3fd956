"""The result of a study (:func:`corliss.study`): one tidy table, a row a run.

Kept apart from :mod:`corliss.engine.result` (whose base class it extends): a study
is made of scenes (the scene layer), not of one engine's model.
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from corliss.frames import columns
from corliss.engine.result import Result
from corliss.keys.edits import KeyValue, with_keys
from corliss.scene.loader import scene_from_dict

if TYPE_CHECKING:      # annotations only: pandas is not imported by a run
    import pandas as pd

#: Columns every study table has besides the varied keys and the responses.
RUN_ID = "run_id"
STATUS = "status"
ERROR = "error"

#: The module that writes a study's files and draws its figure (the files layer, above
#: this one): loaded by name the first time an export method is called, as
#: python-control's ``TimeResponseData`` hands its plots to a module of their own, so
#: that the studies package imports no file writer and ``import corliss`` loads none.
WRITER = "corliss.files.study_output"


def _writer():
    """The module :data:`WRITER`, imported on first use."""
    return importlib.import_module(WRITER)


def column_unit(column: str, varied: list[dict]) -> str:
    """The unit of a study table's column (for its meta file and axes).

    Parameters
    ----------
    column : str
        The column's name.
    varied : list of dict
        The study's varied keys (``column`` and ``unit`` of each).

    Returns
    -------
    str
        A varied key's unit as given (``"-"`` for a dimensionless one); for
        ``run_id``, ``status`` and ``error`` a description; for a response the unit
        its name ends in (:func:`corliss.frames.columns.unit_of`), else ``"-"``.
    """
    for v in varied:
        if v["column"] == column:
            return v["unit"] or "-"
    if column in (RUN_ID, STATUS, ERROR):
        return {RUN_ID: "count (the run's number in the design, from 0)",
                STATUS: "label (ok, or failed: the run stopped or did not converge, see "
                        "error)",
                ERROR: "label (why the run stopped; empty when it did not)"}[column]
    try:
        return columns.unit_of(column.rsplit(".", 1)[-1])
    except KeyError:
        return "-"


@dataclass
class StudyResult(Result[dict[str, Any]]):
    """Steady runs of one base scene with some of its keys changed, a row a run.

    Made by :func:`corliss.studies.runner.study`.  Its one table, ``points`` (also
    held as ``timeseries`` and ``cycles``), has ``run_id``, one column per varied key
    in its unit (``valve_gear.lap_in``), one per response in SI as the summary names
    it (``indicated_power_W``, ``events.head.cutoff_frac``), ``status`` (``ok`` or
    ``failed``) and ``error`` (why a run stopped, its responses NaN; or ``not
    converged: ...`` when it ran but is not periodic or its balances do not close, its
    responses kept for a look).

    Parameters
    ----------
    scene : Scene
        The base scene.
    property_tier : str
        The steam-property tier of the runs (``heos``, ``table``, ``perfect``).
    timeseries, cycles : pandas.DataFrame
        The study's table, both (a study has no time series of its own).
    rhs_evaluations : int
        Evaluations of the model's right-hand side over every run [-].
    wall_time_s : float
        Wall time of the study [s], checks and set-up included.
    design : str
        ``"grid"``, ``"lhs"`` or ``"monte_carlo"``.
    varied : list of dict
        Each varied key: ``key``, ``unit``, ``column`` (its column in the table),
        and its range, levels or distribution.
    responses : list of str
        The summary keys recorded (the table's columns after the varied keys).
    seed : int or None
        The random designs' seed.
    base_data : dict
        The base scene's tables as read: a row's scene is :meth:`scene_data` of it.
    fidelity : str
        The fidelity preset the runs were made at.
    runs, failed : int
        Runs made, and of them the ones that stopped [-].
    workers : int
        Processes (local) or Dask workers' threads that ran them [-].
    scheduler : str or None
        The Dask scheduler's address, or None for local processes.
    journal : str or None
        The journal its rows were appended to as they finished
        (:mod:`corliss.studies.journal`); writing the study into its directory
        removes it.  None when the study had no output directory.
    """

    kind: ClassVar[str] = "study"
    TABLES: ClassVar[tuple[str, ...]] = ("points",)
    FIGURES: ClassVar[tuple[str, ...]] = ("study",)

    design: str = "grid"
    varied: list = field(default_factory=list)
    responses: list = field(default_factory=list)
    seed: int | None = None
    base_data: dict = field(default_factory=dict)
    fidelity: str = ""
    runs: int = 0
    failed: int = 0
    workers: int = 1
    scheduler: str | None = None
    journal: str | None = None

    @property
    def points(self) -> pd.DataFrame:
        """The study's table, a row a run (its columns in the class docstring)."""
        return self.cycles.reset_index(drop=True)

    def scene_data(self, row) -> dict:
        """The scene of one run as tables (what :func:`corliss.scene_from_dict` loads).

        Parameters
        ----------
        row : int or Series or dict
            A ``run_id``, or a row of the table (from the result, or read back from
            its CSV or Parquet file).

        Returns
        -------
        dict
            The base scene's tables with the row's varied keys set.
        """
        return scene_data_of(self.base_data, self.varied, self._row(row))

    def scene_of(self, row):
        """The scene of one run, loaded and checked: the scene that was run.

        Parameters
        ----------
        row : int or pandas.Series or dict
            A ``run_id``, or a row of the table (as for :meth:`scene_data`).

        Returns
        -------
        Scene
            The run's scene, at the study's fidelity.
        """
        sc = scene_from_dict(self.scene_data(row), name=self.scene.name)
        return sc.with_fidelity(self.fidelity) if self.fidelity else sc

    def _row(self, row):
        if isinstance(row, (int, np.integer)):
            return self.points.set_index(RUN_ID).loc[int(row)].to_dict() | {RUN_ID: int(row)}
        return dict(row)

    def _make_summary(self) -> dict:
        pts = self.points
        ok = pts[pts[STATUS] == "ok"]
        ranges = {}
        for r in self.responses:
            v = ok[r].to_numpy(dtype=float)
            v = v[np.isfinite(v)]
            ranges[r] = ({"min": float(v.min()), "median": float(np.median(v)),
                          "max": float(v.max())} if v.size else None)
        return {"title": self.scene.title, "kind": self.kind, "design": self.design,
                "runs": self.runs, "failed": self.failed, "seed": self.seed,
                "varied": self.varied, "responses": list(self.responses),
                "response_ranges": ranges, "fidelity": self.fidelity,
                "property_tier": self.property_tier, "workers": self.workers,
                "scheduler": self.scheduler, "rhs_evaluations": self.rhs_evaluations,
                "wall_time_s": self.wall_time_s,
                "runs_per_s": self.runs / self.wall_time_s if self.wall_time_s > 0
                else math.nan}

    def to_pandas(self, table: str | None = None, units_system: str | None = None
                  ) -> pd.DataFrame:
        """The table as a DataFrame, as the study made it or converted.

        With ``units_system`` the responses whose names end in a unit are converted
        and renamed (``indicated_power_W`` to ``indicated_power_hp``); the varied keys
        stay in the units they were given (a row's scene is rebuilt from them), and a
        response without a unit in its name (``fluctuation_coefficient_c``) as it is.

        Parameters
        ----------
        table : str, optional
            ``"points"``, the study's one table (the default).
        units_system : str, optional
            ``"US"`` or ``"SI"``; None keeps the table as made.

        Returns
        -------
        pandas.DataFrame
            A copy of the table.
        """
        return converted(self.table(table), self.responses, units_system,
                         self.scene.supply.barometer_Pa)[0]

    def to_csv(self, path: str | Path, table: str | None = None,
               units_system: str | None = None) -> Path:
        """Write the table as CSV with its ``.meta.json`` (both or neither).

        Parameters
        ----------
        path : str or Path
            The CSV file; the meta file is written beside it (``NAME.meta.json`` for
            ``NAME.csv``).
        table : str, optional
            Ignored: a study has one table, ``points``.
        units_system : str, optional
            ``"US"`` or ``"SI"`` to convert the responses as :meth:`to_pandas` does;
            None writes the table as made.

        Returns
        -------
        Path
            ``path``.
        """
        return _writer().to_csv(self, path, units_system)

    def write(self, out_dir: str | Path, *, plots: bool = True,
              parquet: bool | None = None) -> dict[str, Path]:
        """Write the study's files into a directory, all together or none.

        ``<scene>.study.csv`` with its meta file, ``<scene>.study.parquet``, the base
        scene (``<scene>.study.base.toml``), the summary as JSON and the figure.

        Parameters
        ----------
        out_dir : str or Path
            The directory (made if missing).
        plots : bool, optional
            Whether to draw the figure (``<scene>.study.png``).
        parquet : bool or None, optional
            Whether to write the Parquet file: None writes it when pyarrow is
            installed, True insists (an InputError without pyarrow).

        Returns
        -------
        dict of str to Path
            ``{kind: path}`` (see :func:`corliss.files.study_output.write`).
        """
        return _writer().write(self, out_dir, plots, parquet)

    def plot(self, kind: str | None = None, ax=None, units_system: str | None = None) -> dict:
        """Each response against each varied key, as scatter plots.

        Parameters
        ----------
        kind : str, optional
            Ignored: a study has one figure, ``"study"``.
        ax : matplotlib.axes.Axes, optional
            Ignored: the figure is a grid of axes of its own.
        units_system : str, optional
            ``"US"`` or ``"SI"`` for the responses' axes; default the scene's.

        Returns
        -------
        dict
            ``figure``, ``axes``, ``ax`` and ``lines``, the one shape of every
            ``plot()`` (:func:`corliss.plot.shape.one_shape`).
        """
        return _writer().plot(self, ax, units_system)


def converted(frame: pd.DataFrame, responses, units_system: str | None,
              barometer_Pa: float) -> tuple[pd.DataFrame, dict]:
    """A study's table with its responses in a system of units.

    Parameters
    ----------
    frame : pandas.DataFrame
        The study's table.
    responses : sequence of str
        Its response columns (only these are converted).
    units_system : str or None
        ``"US"`` or ``"SI"``; None returns the table as made.
    barometer_Pa : float
        Barometric pressure [Pa], for gauge pressures.

    Returns
    -------
    frame : pandas.DataFrame
        A copy, each response whose name ends in a unit converted and renamed.
    changed : dict of str to str
        ``{new column name: its unit}`` of the columns converted.
    """
    out = frame.copy()
    if units_system is None:
        return out, {}
    renamed = {}
    for col in responses:
        try:
            conv, col_units = columns.convert_frame(frame[[col]], units_system, barometer_Pa)
        except KeyError:              # no unit in the name: a pure number
            continue
        new = conv.columns[0]
        out[col] = conv[new].to_numpy()
        renamed[col] = (new, col_units[new])
    return out.rename(columns={k: v[0] for k, v in renamed.items()}), dict(renamed.values())


def scene_data_of(base_data: dict, varied: list[dict], row: dict) -> dict:
    """A study row's scene as tables: the base scene with the row's varied keys set.

    That is ``with_keys(base, {key: value in its unit})``
    (:func:`corliss.keys.edits.with_keys`).

    Parameters
    ----------
    base_data : dict
        The base scene's tables (the study's meta file holds them as
        ``scene_data``, and its ``.base.toml`` as text).
    varied : list of dict
        The meta file's ``varied``: ``key``, ``unit`` and ``column`` of each key.
    row : dict
        A row of the study's table, by column.

    Returns
    -------
    dict
        The base scene's tables with the row's keys set (a new dict; what
        :func:`corliss.scene_from_dict` loads).
    """
    changes = {v["key"]: KeyValue(float(row[v["column"]]), v["unit"]).text()
               for v in varied}
    return with_keys(base_data, changes)
