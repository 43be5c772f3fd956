"""What a run hands back: one result type for every kind of run, computed by the engine.

:class:`Result` is the base: the scene, the run's tables (SI, the unit in every column
name, see :mod:`corliss.frames.columns`), its summary, and the export methods every kind
shares (``to_pandas``, ``to_csv``, ``plot``, ``write``).  Its kinds:

- :class:`SteadyResult`: a steady run (crank-resolved or ideal card): the time series of
  every cycle, the per-cycle balances, the cards, the crank effort, the valve events;
- :class:`TransientResult`: a governed (or free) run through a change of load, crank-
  resolved or on the mean-value maps: speed and governor histories, the per-turn table,
  the load-step metrics, the cards before the step and at the end;
- :class:`SweepResult`: steady runs across the load range (the Willans line).

The physics of a result (cards, crank effort, balances, condensation, metrics) is
computed here.  Writing files and drawing figures is the files layer's job
(:mod:`corliss.files.run_output`, which draws with :mod:`corliss.plot`): the export
methods hand the result to it, loaded by name on first use (:data:`WRITER`).
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Generic, TypeVar, cast

import numpy as np

from corliss.frames import columns
from corliss.keys import units
from corliss.engine import crank_effort as ce
from corliss.engine.condensation import marks_condensation_kg
from corliss.engine.geometry import CylinderGeometry
from corliss.engine.options import record_of
from corliss.engine.scene_specs import SceneSpec
from corliss.engine.speed_metrics import final_turns, load_step_metrics, step_time_of
from corliss.engine.summary_keys import SteadySummary, TransientSummary
from corliss.engine.wall import NO_PERIODIC_STATE_JUMP, jacket_pressures_Pa
from corliss.engine.verdict import steady_failures, transient_failures
from corliss.frames.frame import Frame
from corliss.thermo.steam import HEOSSteam, State, TableSteam
from corliss.valves.portmap import PortMap

if TYPE_CHECKING:
    # the tables are handed out as DataFrames (pandas is imported then); a transient
    # result's governor types, which a steady run does not load
    import pandas as pd

    from corliss.governors.mechanism import GovernorMechanism
    from corliss.governors.operating_point import OperatingPoint

TWO_PI = 2.0 * math.pi
#: Why a card's fluctuation coefficient is undefined (the summary's value is null).
NO_WORK_REASON = ("undefined: the card does no net work, so there is no stroke's work to "
                  "refer the fluctuation to (Marks Art. 57)")

#: The module that writes a result's files and draws its figures (the files layer, above
#: this one): loaded by name the first time an export method is called, as
#: python-control's ``TimeResponseData`` hands its plots to a module of their own, so
#: that the engine imports no file writer and ``import corliss`` loads none.
WRITER = "corliss.files.run_output"


def _writer():
    """The module :data:`WRITER`, imported on first use."""
    return importlib.import_module(WRITER)


class Deferred:
    """A table a run builds only when it is first read: a study's run that records
    numbers of its summary never builds the time series of its cycles.

    Parameters
    ----------
    make : callable
        Called once, with no arguments, to build the table (a Frame or a DataFrame);
        what it reads must not change after the run (a run's own arrays).
    """

    def __init__(self, make):
        self.make = make


def _held(obj, name: str):
    """The table ``name`` of a result as held, built now if it was deferred."""
    held = obj.__dict__["_held"]
    value = held[name]
    if isinstance(value, Deferred):
        value = held[name] = value.make()
    return value


class _Table:
    """A table field of a result (``timeseries``, ``cycles``): held as the run built it,
    a :class:`~corliss.frames.frame.Frame` (a steady run: no pandas needed to compute the
    summary and write the CSVs) or a DataFrame, or :class:`Deferred` until first read,
    and given out as a DataFrame, converted once, on first access.
    :meth:`Result.frame` reads it as held."""

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, obj, objtype=None):
        if obj is None:     # no value on the class: the dataclass field has no default
            raise AttributeError(self.name)
        cache = obj.__dict__.setdefault("_pandas", {})
        if self.name not in cache:
            held = _held(obj, self.name)
            cache[self.name] = held.to_pandas() if isinstance(held, Frame) else held
        return cache[self.name]

    def __set__(self, obj, value):
        obj.__dict__.setdefault("_held", {})[self.name] = value
        obj.__dict__.setdefault("_pandas", {}).pop(self.name, None)


# a kind's summary: a typed mapping (:mod:`corliss.engine.summary_keys`) or a plain dict.
_SummaryT = TypeVar("_SummaryT", bound=Mapping[str, Any])


@dataclass(kw_only=True)
class Result(Generic[_SummaryT]):
    """A run's outcome (base of every kind).

    Parameters
    ----------
    scene : Scene
        The scene that was run (resolved, SI).
    property_tier : str
        The steam-property tier used (``heos``, ``table``, ``perfect``).
    timeseries : DataFrame
        The run's time series, SI (see the kind for its columns).
    cycles : DataFrame
        One row per cycle or turn, SI.
    rhs_evaluations : int
        Evaluations of the model's right-hand side over the run [-].
    wall_time_s : float
        Wall time of the run [s], set-up included.
    """

    kind: ClassVar[str] = "result"
    #: Tables ``to_pandas`` and ``to_csv`` know, besides ``timeseries`` and ``cycles``.
    TABLES: ClassVar[tuple[str, ...]] = ("timeseries", "cycles")
    #: Figures ``plot`` draws; the first is the default.
    FIGURES: ClassVar[tuple[str, ...]] = ()

    scene: SceneSpec
    property_tier: str
    timeseries: pd.DataFrame = _Table()
    cycles: pd.DataFrame = _Table()
    rhs_evaluations: int
    wall_time_s: float
    _summary: _SummaryT | None = field(default=None, init=False, repr=False)

    def __getstate__(self):
        # a pickled result holds its tables built (a deferred one is a closure)
        for name in list(self.__dict__.get("_held", {})):
            _held(self, name)
        return self.__dict__

    @property
    def summary(self) -> _SummaryT:
        """The run's summary (SI unless a key names its unit); computed once."""
        if self._summary is None:
            summary = self._make_summary()
            failures = self._failures(summary)
            if failures is not None:
                # every kind that reports failures declares the key
                cast("dict[str, object]", summary)["failures"] = failures
            self._summary = summary
        return self._summary

    def _failures(self, summary: _SummaryT) -> list[dict] | None:
        """The ways a completed run failed physically (see :mod:`corliss.engine.verdict`);
        None for a kind that reports none."""
        return None

    def _make_summary(self) -> _SummaryT:  # pragma: no cover - interface
        raise NotImplementedError

    def table(self, name: str | None = None) -> pd.DataFrame:
        """One of the result's tables, SI.

        Parameters
        ----------
        name : str, optional
            One of :attr:`TABLES` (the first by default).

        Returns
        -------
        DataFrame
            The table as computed, SI, the unit in every column name (not a copy: see
            :meth:`to_pandas`).

        Raises
        ------
        ValueError
            A name not in :attr:`TABLES`.
        """
        name = name or self.TABLES[0]
        if name not in self.TABLES:
            raise ValueError(f"table {name!r}: one of {', '.join(self.TABLES)}")
        return getattr(self, f"_table_{name}")() if hasattr(self, f"_table_{name}") \
            else getattr(self, name)

    def frame(self, name: str | None = None):
        """One of the result's tables as the run holds it, SI: a
        :class:`~corliss.frames.frame.Frame` where the run built one (a steady run's tables:
        read without importing pandas), else the DataFrame of :meth:`table`.

        Parameters
        ----------
        name : str, optional
            One of :attr:`TABLES` (the first by default).

        Returns
        -------
        Frame or DataFrame
            The table; both answer ``frame[column].to_numpy()`` and ``frame.columns``.
        """
        name = name or self.TABLES[0]
        if name not in self.TABLES:
            raise ValueError(f"table {name!r}: one of {', '.join(self.TABLES)}")
        if hasattr(self, f"_frame_{name}"):
            return getattr(self, f"_frame_{name}")()
        held = self.__dict__.get("_held", {})
        return _held(self, name) if name in held else self.table(name)

    def to_pandas(self, table: str | None = None, units_system: str | None = None
                  ) -> pd.DataFrame:
        """A table as a DataFrame, SI or converted.

        Parameters
        ----------
        table : str, optional
            One of :attr:`TABLES` (the first by default).
        units_system : str, optional
            None for SI as computed (``p_head_Pa``); ``"US"`` or ``"SI"`` for the output
            units of that system, named by them (``p_head_psia``, ``p_head_kPa_abs``).

        Returns
        -------
        DataFrame
            A copy of the table, its columns renamed to their units when converted.
        """
        df = self.table(table)
        if units_system is None:
            return df.copy()
        return columns.convert_frame(df, units_system, self.scene.supply.barometer_Pa)[0]

    def to_csv(self, path: str | Path, table: str | None = None,
               units_system: str | None = None) -> Path:
        """Write a table as CSV in the output units with its ``.meta.json`` beside it.

        Both files are written whole or not at all (by :data:`WRITER`).

        Parameters
        ----------
        path : str or Path
            The CSV file to write.
        table : str, optional
            One of :attr:`TABLES` (the first by default).
        units_system : str, optional
            ``"US"`` or ``"SI"`` (default: the scene's output units).

        Returns
        -------
        Path
            The CSV file written.
        """
        return _writer().to_csv(self, path, table or self.TABLES[0], units_system)

    def plot(self, kind: str | None = None, ax=None, units_system: str | None = None) -> dict:
        """Draw one of :attr:`FIGURES` in period style.

        Parameters
        ----------
        kind : str, optional
            One of :attr:`FIGURES` (the first by default).
        ax : matplotlib Axes, optional
            The axes to draw a one-axes figure on (``card``, ``effort``, ``lp_card``,
            ``willans``; default: a new figure).
        units_system : str, optional
            ``"US"`` or ``"SI"`` for the axes' units (default: the scene's).

        Returns
        -------
        dict
            The matplotlib objects drawn, one shape for every kind
            (:func:`corliss.plot.shape.one_shape`): ``figure``, ``axes`` (a list, the
            main first), ``ax`` (the main axes), ``lines`` (``{name: Line2D}``), and
            the plotting function's own entries beside them.
        """
        return _writer().plot_result(self, kind or self.FIGURES[0], ax, units_system)

    def write(self, out_dir: str | Path, *, plots: bool = True) -> dict[str, Path]:
        """Write every file of the run into a directory.

        The tables as CSV with their meta files, the summary as JSON and the figures as
        PNG.  All files appear together or none does; an earlier run's files are never
        damaged.

        Parameters
        ----------
        out_dir : str or Path
            The directory (made if missing).
        plots : bool
            Whether to draw the figures too.

        Returns
        -------
        dict of str to Path
            Each file written, keyed by the table, figure or summary it holds (the meta
            files beside the tables).
        """
        return _writer().write(self, out_dir, plots)


def _last(ts):
    """The rows of the last cycle of a time series (a Frame or a DataFrame)."""
    return ts[ts["cycle"] == ts["cycle"].max()]


@dataclass(kw_only=True)
class SteadyResult(Result[SteadySummary]):
    """A steady run: the speed held, cycles until periodic.

    Parameters
    ----------
    scene, property_tier, timeseries, cycles, rhs_evaluations, wall_time_s
        As for :class:`Result` (``wall_time_s`` [s]); the tables are described below.
    events : dict
        Valve events of each end (the JSON contract of ``corliss events``).
    geometry : CylinderGeometry
        The (first or high-pressure) cylinder.
    chest, exhaust : State
        Supply steam at the chest and dry saturated steam at back pressure.
    cycles_to_converge : int or None
        Cycles until the run was periodic (None if ``cycles`` fixed the count).
    portmap : PortMap or None
        Port areas against crank angle (None for the ideal card).
    ideal_cards : dict or None
        The algebraic cards of the hyperbolic ideal model.
    cylinders : list
        ``(column prefix, geometry, crank lead [rad])`` of every cylinder; ``""`` first.
    lp_events : dict or None
        A compound's low-pressure valve events.
    periodicity : dict
        The last cycle's distance from periodic, per state (see
        ``corliss.engine.steady``): work, mass, energy, mass balance, wall temperature
        [-], each against its own scale; a run has converged when all are below the
        fidelity's convergence tolerance.
    clamped_trials : int or None
        Evaluations at trial states (stages inside a step, rejected steps) that were
        clamped to the range of the steam properties (crank-resolved port flow; None
        otherwise); a state the run visits is never clamped (the run stops), but for
        ``clamped_hot``.
    clamped_hot : int or None
        Evaluations at visited states heated beyond the properties' greatest energy and
        evaluated at it (with a warning; see ``corliss.engine.crank_resolved``).
    final_state : SteadyStart or None
        Where a crank-resolved run ended: the ``start`` of a neighbouring run
        (``corliss.engine.steady.run_steady``); None for the other models.
    wall_jumps : dict
        End name to its :class:`~corliss.engine.wall.WallJump` where a skin wall's
        deep wall has no periodic state (its balance over a cycle jumps across its
        bracket); empty otherwise.

    Notes
    -----
    Tables: ``timeseries`` (``cycle``, ``crank_angle_deg``, ``time_s``, and per end
    ``p_*_Pa``, ``T_*_K``, ``x_*_frac`` (dryness), ``V_*_m3``, ``m_*_kg``), ``cycles``
    (per cycle: work, mass and enthalpy from the chest and to the exhaust, heat), ``cards``
    (the last cycle's card of each end: ``end``, ``crank_angle_deg``, ``piston_frac``,
    ``V_m3``, ``p_Pa``) and ``crank_effort`` (torque against crank angle).
    """

    kind: ClassVar[str] = "steady"
    TABLES: ClassVar[tuple[str, ...]] = ("timeseries", "cycles", "cards", "crank_effort")
    FIGURES: ClassVar[tuple[str, ...]] = ("card", "effort", "lp_card")

    events: dict = field(default_factory=dict)
    geometry: CylinderGeometry
    chest: State
    exhaust: State
    cycles_to_converge: int | None = None
    portmap: PortMap | None = None
    ideal_cards: dict | None = None
    cylinders: list | None = None
    lp_events: dict | None = None
    periodicity: dict = field(default_factory=dict)
    clamped_trials: int | None = None
    clamped_hot: int | None = None
    final_state: object = None
    wall_jumps: dict = field(default_factory=dict)

    def _wall_jump_keys(self) -> dict:
        """``wall_periodic_state`` and ``wall_balance_jumps`` where a deep wall's
        balance jumps (:attr:`wall_jumps`), else nothing."""
        if not self.wall_jumps:
            return {}
        return {"wall_periodic_state": NO_PERIODIC_STATE_JUMP,
                "wall_balance_jumps": [
                    {"end": end, "T_low_K": j.T_low_K, "T_high_K": j.T_high_K,
                     "balance_low_J": j.balance_low_J, "balance_high_J": j.balance_high_J}
                    for end, j in self.wall_jumps.items()]}

    def _end_condensation(self, end, ev, geo, e_idx, shift_deg, row, ts, at, sat) -> dict:
        """The condensation summary of one end (``end`` with its cylinder's prefix; its
        events ``ev`` in its own crank angle, ``shift_deg`` its lead on the shaft)."""
        out = {f"heat_to_walls_{end}_J_per_cycle": float(row[f"Q_to_wall_{end}_J"]),
               f"wall_temperature_{end}_K": (float(row[f"T_wall_{end}_K"])
                                             if f"T_wall_{end}_K" in row else None)}

        def angle(key):
            return None if ev.get(key) is None else (ev[key] - shift_deg) % 360.0

        if f"T_wall_{end}_K" in ts:
            tw = ts[f"T_wall_{end}_K"].to_numpy()
            out[f"wall_surface_swing_{end}_K"] = float(np.max(tw) - np.min(tw))
            out[f"wall_surface_mean_{end}_K"] = float(np.mean(tw))
            q_total = float(row[f"Q_{end}_J"])
            marks = [angle(k) for k in ("admission_deg", "cutoff_deg", "release_deg",
                                        "compression_deg")]
            if all(m is not None for m in marks):
                qs = [at(f"Q_{end}_J", m) for m in marks]
                for n, name in enumerate(("admission", "expansion", "exhaust", "compression")):
                    dq = qs[(n + 1) % 4] - qs[n]
                    if marks[(n + 1) % 4] < marks[n]:   # the phase wraps past 0
                        dq += q_total
                    out[f"heat_into_steam_{name}_{end}_J"] = dq
        if ev["cutoff_deg"] is None or ev["compression_deg"] is None:
            return out
        c, k = angle("cutoff_deg"), angle("compression_deg")
        out[f"wet_fraction_at_cutoff_{end}"] = 1.0 - at(f"x_{end}_frac", c)
        if f"m_film_{end}_kg" in ts:
            # the period's "wetness at cut-off" counts all the water present, the wall's
            # film with the mixture's (English, in DPJ 267, 1888, p. 302: what counts is
            # the water present at the end of admission, wherever it condensed)
            m, film = at(f"m_{end}_kg", c), at(f"m_film_{end}_kg", c)
            out[f"wet_fraction_at_cutoff_with_film_{end}"] = (
                (m * (1.0 - at(f"x_{end}_frac", c)) + film) / (m + film))
        supplied = float(row[f"m_chest_{end}_kg"])
        shown = (at(f"V_{end}_m3", c) * sat.px(at(f"p_{end}_Pa", c), 1.0).rho
                 - at(f"V_{end}_m3", k) * sat.px(at(f"p_{end}_Pa", k), 1.0).rho)
        out[f"card_missing_water_fraction_{end}"] = (supplied - shown) / supplied
        if f"m_{end}_kg" in ts:
            steam = (at(f"m_{end}_kg", c) * at(f"x_{end}_frac", c)
                     - at(f"m_{end}_kg", k) * at(f"x_{end}_frac", k))
            out[f"missing_water_fraction_{end}"] = (supplied - steam) / supplied
            # the mass Marks's eq. 221 predicts: condensation per stroke
            out[f"missing_water_per_stroke_{end}_kg"] = supplied - steam
        else:
            out[f"missing_water_fraction_{end}"] = out[f"card_missing_water_fraction_{end}"]
        # the period's prediction beside the model's (Marks eq. 221)
        vc, vs = geo.clearance_m3[e_idx], geo.swept_m3[e_idx]
        e_true = (vc + vs * ev["cutoff_frac"]) / (vc + vs)
        cond = marks_condensation_kg(
            geo.spec.bore_m, geo.spec.stroke_m, 2.0 * self.scene.run.speed_rad_s / TWO_PI,
            e_true, sat.t_sat(at(f"p_{end}_Pa", c)), self.exhaust.T)
        out[f"marks_missing_water_fraction_{end}"] = cond / (cond + shown)
        return out

    @property
    def cylinder_list(self) -> list:
        """(prefix, geometry, crank lead [rad]) of every cylinder; "" is the (HP) first."""
        return self.cylinders or [("", self.geometry, 0.0)]

    @property
    def last_cycle(self) -> pd.Series:
        """The per-cycle row of the last cycle."""
        return self.cycles.iloc[-1]

    def _last_row(self):
        """The last cycle's row as held (a Frame's row, or a Series)."""
        return self.frame("cycles").iloc[-1]

    @property
    def cards(self) -> dict[str, pd.DataFrame]:
        """Card of each end over the last cycle, keyed by end.

        Keys ``head``, ``crank``, ``lp_head``, ...; each frame has ``piston_frac`` (the
        piston's position as a fraction of the stroke from head-end dead centre, the
        card's abscissa), ``V_m3``, ``p_Pa``, and the cylinder's own
        ``crank_angle_deg`` (not for the hyperbolic ideal card).
        """
        return {end: f.to_pandas() for end, f in self.card_frames().items()}

    def card_frames(self) -> dict[str, Frame]:
        """The cards of :attr:`cards` as :class:`~corliss.frames.frame.Frame` (no pandas).

        Returns
        -------
        dict
            End to its card.
        """
        if self.ideal_cards is not None:
            out = {}
            for end, df in self.ideal_cards.items():
                frac = df["frac"] if end == "head" else 1.0 - df["frac"]
                out[end] = Frame({"piston_frac": frac.to_numpy(),
                                  "V_m3": df["V_m3"].to_numpy(),
                                  "p_Pa": df["p_Pa"].to_numpy()})
            return out
        ts = _last(self.frame("timeseries"))
        th = np.radians(ts["crank_angle_deg"].to_numpy()) % TWO_PI
        out = {}
        for prefix, geo, phase in self.cylinder_list:
            frac = geo.fraction(th + phase)
            for end in ("head", "crank"):
                out[prefix + end] = Frame({
                    # the cylinder's own crank angle, in which its events are given
                    "crank_angle_deg": ts["crank_angle_deg"].to_numpy() + math.degrees(phase),
                    "piston_frac": frac,
                    "V_m3": ts[f"V_{prefix}{end}_m3"].to_numpy(),
                    "p_Pa": ts[f"p_{prefix}{end}_Pa"].to_numpy()})
        return out

    def _frame_cards(self) -> Frame:
        return Frame.concat([f.assign(end=end)[["end", *f.columns]]
                             for end, f in self.card_frames().items()])

    def _table_cards(self) -> pd.DataFrame:
        return self._frame_cards().to_pandas()

    @property
    def crank_effort(self) -> pd.DataFrame:
        """Torque on the shaft over the last cycle (SI).

        Columns: ``crank_angle_deg``, the steam force on each cylinder's piston
        (``steam_force_N``, prefixed per cylinder), the inertia force of the
        reciprocating masses (``inertia_force_N``, ``inertia`` effect), the indicated
        torque they make (``torque_N_m``), the friction torque
        (``friction_torque_N_m``, ``friction`` effect) and the net torque left for the
        load (``net_torque_N_m``).
        """
        return self._frame_crank_effort().to_pandas()

    def _frame_crank_effort(self) -> Frame:
        ts = _last(self.frame("timeseries"))
        th = np.radians(ts["crank_angle_deg"].to_numpy())
        run, spec = self.scene.run, self.geometry.spec
        cols = {"crank_angle_deg": ts["crank_angle_deg"].to_numpy()}
        total = np.zeros(th.size)
        for prefix, g, phase in self.cylinder_list:
            force = ce.piston_force_N(g, ts[f"p_{prefix}head_Pa"].to_numpy(),
                                      ts[f"p_{prefix}crank_Pa"].to_numpy(),
                                      self.scene.supply.barometer_Pa)
            cols[f"{prefix}steam_force_N"] = force
            if run.has("inertia"):
                # the loader requires the mass with the inertia effect
                assert spec.reciprocating_mass_kg is not None
                f_in = ce.inertia_force_N(g, th + phase, run.speed_rad_s,
                                          spec.reciprocating_mass_kg)
                cols[f"{prefix}inertia_force_N"] = f_in
                force = force + f_in
            total = total + ce.torque_N_m(g, th + phase, force)
        cols["torque_N_m"] = total
        net = total
        if run.has("friction"):
            tf = spec.friction_torque_N_m + spec.friction_N_m_s * run.speed_rad_s
            cols["friction_torque_N_m"] = np.full(th.size, tf)
            net = net - tf
        cols["net_torque_N_m"] = net
        return Frame(cols)

    def _effort_summary(self, work_J: float) -> dict:
        eff = self._frame_crank_effort()
        th = np.radians(eff["crank_angle_deg"].to_numpy())
        dE = ce.energy_fluctuation_J(th, eff["torque_N_m"].to_numpy())
        out: dict[str, object]      # a number or a note, by the card's work
        out = {"max_torque_N_m": float(eff["torque_N_m"].max()),
               "min_torque_N_m": float(eff["torque_N_m"].min()),
               "mean_torque_N_m": work_J / TWO_PI,
               "energy_fluctuation_J": dE,
               # Marks Art. 57, Table IV: spread over the work of one stroke of one
               # cylinder; undefined when the card does no net work
               "fluctuation_coefficient_c": (dE / (0.5 * work_J / len(self.cylinder_list))
                                             if work_J > 0 else None)}
        if work_J <= 0:
            out["fluctuation_coefficient_note"] = NO_WORK_REASON
        run = self.scene.run
        row = self._last_row()
        rev_per_h = run.speed_rad_s / TWO_PI * 3600.0
        valve_leaks = [k for k in row.index if k.startswith("m_valve_leak_")]
        if valve_leaks:
            out["valve_leakage_kg_per_h"] = float(sum(row[k] for k in valve_leaks)) * rev_per_h
            for k in valve_leaks:       # each path's: the period's law has its own names
                out[f"{k[2:-3]}_kg_per_h"] = float(row[k]) * rev_per_h
            # the leak that leaves the steam side, as a fraction of the steam supplied:
            # straight to the exhaust (a compound's HP valve into the receiver, the LP's
            # from there) and into each end past its steam edge (the HP's; an LP end's
            # comes from the receiver); not an end's past its exhaust edge, steam the
            # end had already taken
            fed = [k for k in valve_leaks
                   if not (k.endswith("_exhaust_kg") and k != "m_valve_leak_exhaust_kg")
                   and not k.startswith("m_valve_leak_lp_")
                   and not (k == "m_valve_leak_exhaust_kg"
                            and "m_valve_leak_receiver_kg" in row)]
            supplied = float(row["m_supply_kg"])
            if supplied > 0.0 and fed:
                out["valve_leakage_fraction_of_steam"] = float(sum(row[k] for k in fed)) / supplied
        if "m_piston_leak_kg" in row:
            out["piston_leakage_net_kg_per_cycle"] = float(row["m_piston_leak_kg"])
        paths = [k for k in row.index if k.startswith("m_") and k.endswith("_kg")
                 and ("valve_leak" in k or "piston_leak" in k)]
        if paths:
            supplied = float(row["m_supply_kg"])
            out["leak_paths"] = {
                k[2:-3]: {"kg_per_cycle": float(row[k]), "kg_per_h": float(row[k]) * rev_per_h}
                | ({"fraction_of_steam": float(row[k]) / supplied} if supplied > 0.0 else {})
                for k in paths}
        if "Q_head_J" in row:
            out.update(self._condensation_summary(work_J))
        if "p_chest_Pa" in self.frame("timeseries"):
            last = _last(self.frame("timeseries"))
            out["chest_pressure_mean_Pa"] = float(last["p_chest_Pa"].mean())
            out["chest_pressure_min_Pa"] = float(last["p_chest_Pa"].min())
        if run.has("friction"):
            spec = self.geometry.spec
            tf = spec.friction_torque_N_m + spec.friction_N_m_s * run.speed_rad_s
            indicated = work_J * run.speed_rad_s / TWO_PI
            brake = indicated - tf * run.speed_rad_s
            out.update({"friction_torque_N_m": tf, "friction_power_W": tf * run.speed_rad_s,
                        "friction_work_J_per_cycle": tf * TWO_PI,
                        "brake_power_W": brake, "brake_power_hp": brake / units.HP_W,
                        "mechanical_efficiency": brake / indicated if indicated > 0 else None})
        return out

    def _compound_summary(self) -> dict:
        """Power of each cylinder; for a compound, LP mean pressures and the receiver's."""
        if len(self.cylinder_list) < 2:
            return {}
        row = self._last_row()
        rev_per_s = self.scene.run.speed_rad_s / TWO_PI
        if self.scene.compound is None:
            return {"cylinder_powers_W": [float(row[f"work_{p}head_J"] + row[f"work_{p}crank_J"])
                                          * rev_per_s for p, _, _ in self.cylinder_list]}
        _, lp, _ = self.cylinder_list[1]
        w_lp = float(row["work_lp_head_J"] + row["work_lp_crank_J"])
        w_hp = float(row["work_head_J"] + row["work_crank_J"])
        last = _last(self.frame("timeseries"))
        return {"hp_power_W": w_hp * rev_per_s, "lp_power_W": w_lp * rev_per_s,
                "lp_mep_head_Pa": float(row["work_lp_head_J"]) / lp.swept_m3[0],
                "lp_mep_crank_Pa": float(row["work_lp_crank_J"]) / lp.swept_m3[1],
                "receiver_pressure_mean_Pa": float(last["p_receiver_Pa"].mean()),
                "receiver_pressure_min_Pa": float(last["p_receiver_Pa"].min()),
                "receiver_pressure_max_Pa": float(last["p_receiver_Pa"].max())}

    def _condensation_summary(self, work_J: float) -> dict:
        """Initial condensation per end (Marks Art. 74).

        ``missing_water_fraction``: the steam supplied less the steam in the cylinder
        at cut-off, as a fraction of the steam supplied; the steam at cut-off is read
        from its state (mass times dryness, all of it when superheated) less the
        cushion's shut in at compression (Marks eq. 219a), so water on the wall or in
        the mixture is missing and superheat is not.  ``card_missing_water_fraction``:
        the same with the steam the card shows (volume times the density of dry
        saturated steam at the card's pressure), as the engineers of the time
        measured it, and beside it the fraction Marks's law predicts for that card
        (eq. 221).  Also the heat the steam gave the walls over the cycle, the wet
        fraction of the contents at cut-off, and with the skin model the swing of the
        wall's surface temperature and the heat into the steam in each phase
        (admission to cut-off, cut-off to release, release to compression,
        compression to admission).  Every end of every cylinder whose walls exchange
        heat, each with its own geometry and events (``lp_`` ends with the
        low-pressure cylinder's, the angles moved by the cylinder's crank lead).
        """
        # saturation read on the run's own table (no CoolProp import) or else on HEOS
        sat = TableSteam() if self.property_tier == "table" else HEOSSteam()
        row = self._last_row()
        ts = _last(self.frame("timeseries"))
        ang = np.mod(ts["crank_angle_deg"].to_numpy(), 360.0)
        ang, idx = np.unique(ang, return_index=True)
        out = {}

        def at(col, deg):
            return float(np.interp(deg, ang, ts[col].to_numpy()[idx], period=360.0))

        for prefix, geo, phase in self.cylinder_list:
            evs = self.lp_events if prefix == "lp_" and self.lp_events else self.events
            for e_idx, end0 in enumerate(("head", "crank")):
                end = prefix + end0
                if f"Q_to_wall_{end}_J" in row:
                    out.update(self._end_condensation(
                        end, evs[end0], geo, e_idx, math.degrees(phase), row, ts, at, sat))
        # the period's "missing quantity of feed water at cut-off" (Willans 1888): the
        # steam supplied less what the (high-pressure) cylinders hold as steam at
        # cut-off, of the steam supplied: condensation and leakage together
        per = [k for k in out if k.startswith("missing_water_per_stroke_")
               and not k.startswith("missing_water_per_stroke_lp_")]
        supplied = float(row["m_supply_kg"])
        if per and supplied > 0.0:
            steam = sum(float(row[f"m_chest_{k[len('missing_water_per_stroke_'):-3]}_kg"])
                        - out[k] for k in per)
            out["missing_water_fraction_of_feed"] = (supplied - steam) / supplied
        if self.scene.engine.jacket != "none":
            out.update(self._jacket_summary(row, sat, work_J))
        return out

    def _jacket_summary(self, row, sat, work_J: float) -> dict:
        """The jacket's steam (Marks Art. 79: the jacket's heat is paid for in steam).

        Over a periodic cycle the walls neither gain nor lose heat, so what the steam in
        the cylinders took from them net, the sum of ``Q_<end>_J``, is what the jacket
        gave through the iron.  The jacket condenses its steam (the scene's
        ``jacket_pressure``, or the supply's; a compound's LP jacket its receiver's) and drains it as saturated water at that
        pressure, so each kilogram gives the latent heat there; the period's trials counted that water with the feed (Marks Art.
        79, p. 204), and ``water_rate_with_jacket`` does too.
        """
        rev_per_s = self.scene.run.speed_rad_s / TWO_PI
        # each cylinder's jacket at its own pressure (a compound's LP at its
        # receiver's, wall.jacket_pressures_Pa): its heat over the latent heat there
        eng = self.scene.engine
        pj = jacket_pressures_Pa(self.scene.supply.pressure_Pa,
                                 self.scene.exhaust.pressure_Pa, self.scene.compound is not None,
                                 eng.jacket_pressure_Pa, eng.lp_jacket_pressure_Pa)
        q = jacket_kg = 0.0
        for c in row.index:
            if c.startswith("Q_") and "to_wall" not in c and c.endswith("_J"):
                p = pj[-1] if c.startswith("Q_lp_") else pj[0]
                qc = float(row[c])
                q += qc
                jacket_kg += qc / (sat.px(p, 1.0).h - sat.px(p, 0.0).h)
        jacket_kg_h = max(jacket_kg, 0.0) * rev_per_s * 3600.0
        steam_kg_h = float(row["m_supply_kg"]) * rev_per_s * 3600.0
        power_kW = work_J * rev_per_s / 1e3
        total = steam_kg_h + jacket_kg_h
        return {"jacket_heat_W": q * rev_per_s, "jacket_steam_kg_per_h": jacket_kg_h,
                "water_rate_with_jacket_kg_per_kWh": total / power_kW if power_kW > 0 else None}

    def _failures(self, summary: SteadySummary) -> list[dict]:
        return steady_failures(summary, fixed_cycles=self.scene.run.cycles is not None)

    def summary_with(self, keys: Iterable[str]) -> SteadySummary:
        """The summary's part that holds ``keys``: the whole :attr:`summary` when it is
        computed or a key needs it, else only the numbers read from the last cycle's
        row and the run's own figures, with the same values (no time series, cards or
        crank effort built: a study's run that records rates and balances).

        Parameters
        ----------
        keys : iterable of str
            Dotted keys of the summary (``events.head.cutoff_frac``).

        Returns
        -------
        SteadySummary
            The summary, or a part of it holding every key of ``keys`` that the whole
            summary holds (nested, as :attr:`summary`; no ``failures``).
        """
        if self._summary is not None:
            return self._summary
        part = self.__dict__.get("_light")
        if part is None:
            part = self.__dict__["_light"] = self._make_summary(light=True)
        for key in keys:
            node: object = part
            for name in key.split("."):
                if not isinstance(node, dict) or name not in node:
                    return self.summary
                node = node[name]
        return part

    def _make_summary(self, light: bool = False) -> SteadySummary:
        """The summary; ``light``: without the keys that need the time series (the
        peak pressure, the crank effort and what is read with it, a compound's
        cylinders)."""
        run = self.scene.run
        row = self._last_row()
        w_h, w_c = float(row["work_head_J"]), float(row["work_crank_J"])
        w = float(row["work_J"]) if "work_J" in row else w_h + w_c
        rev_per_s = run.speed_rad_s / TWO_PI
        power = w * rev_per_s
        sw_h, sw_c = self.geometry.swept_m3
        # what crossed the engine's boundary: from the supply, from (minus: to) the exhaust
        steam_cycle = float(row["m_supply_kg"])
        steam_rate = steam_cycle * rev_per_s * 3600.0
        m_exh = float(row["m_exhaust_kg"])
        H_in = float(row["H_supply_J"])
        H_ex = float(row["H_exhaust_J"]) if "H_exhaust_J" in row else math.nan
        p_peak = None if light else float(np.nanmax(np.concatenate(
            [c["p_Pa"].to_numpy() for c in self.card_frames().values()])))
        mass_err = abs(steam_cycle + m_exh) / abs(steam_cycle) if steam_cycle else None
        Q = sum(float(row[c]) for c in row.index if c.startswith("Q_") and "to_wall" not in c)
        energy_err = (abs(H_in + H_ex + Q - w) / abs(H_in) if math.isfinite(H_ex) and H_in
                      else None)
        power_kW = power / 1000.0
        ihp = power / units.HP_W

        def ratio(a, b):
            return a / b if b > 0 else None

        out: dict[str, Any] = {
            "title": self.scene.title,
            "kind": self.kind,
            "model": run.model,
            "effects": list(run.effects),
            "fidelity": run.fidelity.name,
            "property_tier": self.property_tier,
            "speed_rpm": run.speed_rpm,
            "indicated_power_W": power,
            "indicated_power_hp": ihp,
            "indicated_work_J_per_cycle": w,
            "mep_head_Pa": w_h / sw_h,
            "mep_crank_Pa": w_c / sw_c,
            # over all cylinders; a compound's is referred to its LP cylinder (Marks Art. 90)
            "mep_mean_Pa": w / (sum(self.cylinder_list[-1][1].swept_m3)
                                if self.scene.compound is not None else
                                sum(sum(g.swept_m3) for _, g, _ in self.cylinder_list)),
            "steam_per_cycle_kg": steam_cycle,
            "steam_rate_kg_per_h": steam_rate,
            "water_rate_kg_per_kWh": ratio(steam_rate, power_kW),
            "water_rate_lb_per_ihp_h": ratio(steam_rate / units.POUND_kg, ihp),
            "peak_pressure_Pa": p_peak,
            "supply_pressure_Pa": self.chest.p,
            "exhaust_pressure_Pa": self.exhaust.p,
            "cycles_simulated": int(len(self.frame("cycles"))),
            "cycles_to_converge": self.cycles_to_converge,
            "convergence_tolerance": run.fidelity.convergence_tolerance,
            "periodicity_residuals": dict(self.periodicity),
            **self._wall_jump_keys(),
            "mass_balance_error": mass_err,
            "energy_balance_error": energy_err,
            "rhs_evaluations": self.rhs_evaluations,
            # trial states clamped to the steam properties' range (a visited state that
            # needs it stops the run)
            "clamped_trial_evaluations_count": self.clamped_trials,
            "clamped_hot_state_evaluations_count": self.clamped_hot,
            "wall_time_s": self.wall_time_s,
            **({} if light else self._effort_summary(w)),
            **({} if light else self._compound_summary()),
            "events": self.events,
            **({"lp_events": self.lp_events} if self.lp_events is not None else {}),
        }
        if light:
            del out["peak_pressure_Pa"]
        # the keys and their types are declared in SteadySummary
        # (tests/test_summary_keys.py checks every bundled scene's against it)
        return cast(SteadySummary, out)


@dataclass(kw_only=True)
class TransientResult(Result[TransientSummary]):
    """A transient run: the speed a state, the load changing, the governor acting.

    Parameters
    ----------
    scene, property_tier, timeseries, cycles, rhs_evaluations, wall_time_s
        As for :class:`Result` (``wall_time_s`` [s]); the tables are described below.
    geometry : CylinderGeometry
        The cylinder.
    stalled : bool
        True when the load stopped the engine before the run's end.
    mechanism : GovernorMechanism or None
        The governor in its common form (None for a free engine).
    z_start : float
        The governor's coordinate at t = 0 [-].
    chest, exhaust : State or None
        Reservoir states (None on the mean-value maps).
    engine_map : EngineMap or None
        The mean-value model's maps of torque and steam (None crank-resolved).
    start : OperatingPoint or None
        Where the run started: the governed operating point at the initial load
        (``status`` "balanced", or why there is none), the run speed, or rest.
    clamped_trials, clamped_hot : int or None
        As for a steady run: evaluations at trial states clamped to the range of the
        steam properties, and visited states heated beyond their greatest energy.

    Notes
    -----
    Tables: ``timeseries`` (``cycle``, ``time_s``, ``crank_angle_deg``, ``speed_rpm``,
    ``governor_z_frac``, ``actuator_frac`` (the throttle's opening or the gear's
    setting), and with ``record`` = step or degree the cylinder pressures ``p_head_Pa``,
    ``p_crank_Pa`` or the torques), ``cycles`` (per turn: ``t_start_s``, ``t_end_s``,
    ``mean_speed_rpm``, ``work_J``, ``indicated_power_W``, ``load_work_J``,
    ``load_power_W``, ``friction_work_J``, ``m_supply_kg``, ``steam_rate_kg_per_h``,
    ``governor_z_frac``, the throttle opening or gear setting and its cut-off, and with
    wall heat each end's ``Q_<end>_J`` into the steam and ``Q_to_wall_<end>_J`` taken by
    the wall over the turn) and
    ``cards`` (the turn before the step and the last: ``phase``, ``end``, ``V_m3``,
    ``p_Pa``).
    """

    kind: ClassVar[str] = "transient"
    TABLES: ClassVar[tuple[str, ...]] = ("timeseries", "cycles", "cards")
    FIGURES: ClassVar[tuple[str, ...]] = ("loadstep",)

    geometry: CylinderGeometry
    stalled: bool = False
    mechanism: GovernorMechanism | None = None
    z_start: float = 0.0
    chest: State | None = None
    exhaust: State | None = None
    engine_map: object = None
    start: OperatingPoint | None = None
    clamped_trials: int | None = None
    clamped_hot: int | None = None

    @property
    def step_time_s(self) -> float | None:
        """The time of the load's step [s] (None for a load without one)."""
        return step_time_of(self.scene.load)

    def _failures(self, summary: TransientSummary) -> list[dict]:
        z_end = (float(self.cycles["governor_z_frac"].iloc[-1])
                 if "governor_z_frac" in self.cycles else None)
        return transient_failures(summary, self.mechanism, z_end,
                                  until_settled=self.scene.run.until_settled)

    @property
    def metrics(self) -> dict:
        """Regulation, largest deviation, settling and hunting (see speed_metrics)."""
        return load_step_metrics(self.cycles, self.step_time_s, self.scene.run.settling_band,
                                 self.timeseries)

    def _make_summary(self) -> TransientSummary:
        s = self.scene
        c = self.cycles
        # a transient run has both (the loader requires them in that mode)
        assert s.flywheel is not None and s.load is not None
        gov = None
        if s.governor is not None:
            assert self.mechanism is not None      # built from the governor
            gov = {"type": s.governor_type, "acts_on": self.mechanism.acts_on,
                   "z_at_start": self.z_start}
        start = None
        if self.start is not None:
            p = self.start
            start = {"status": p.status, "speed_rpm": p.speed_rad_s * 60.0 / (2.0 * np.pi),
                     "governor_z_frac": p.governor_z,
                     "surplus_torque_N_m": None if np.isnan(p.surplus_N_m) else p.surplus_N_m,
                     "evaluations_count": p.evaluations}
        out: dict[str, Any] = {
            "title": s.title, "kind": self.kind, "mode": "transient", "model": s.run.model,
            "effects": list(s.run.effects), "fidelity": s.run.fidelity.name,
            "property_tier": self.property_tier,
            "initial_speed_rpm": s.run.speed_rpm, "duration_s": s.run.duration_s,
            "simulated_s": float(c["t_end_s"].iloc[-1]), "turns": int(len(c)),
            "flywheel_inertia_kg_m2": s.flywheel.inertia_kg_m2,
            "load_torque_N_m": s.load.torque_N_m, "load_kind": s.load.kind,
            "load_speed_law": s.load.speed_law, "step_time_s": self.step_time_s,
            "governor": gov, "start": start, "until_settled": s.run.until_settled,
            "record": record_of(s.run) if s.run.model != "mean_value" else None,
            "stalled": self.stalled,
            **self.metrics,
            "final_indicated_power_W": float(final_turns(c)["indicated_power_W"].mean()),
            "final_steam_rate_kg_per_h": float(final_turns(c)["steam_rate_kg_per_h"].mean()),
            **self._final_state(),
            "clamped_trial_evaluations_count": self.clamped_trials,
            "clamped_hot_state_evaluations_count": self.clamped_hot,
            "rhs_evaluations": self.rhs_evaluations, "wall_time_s": self.wall_time_s,
        }
        # the keys and their types are declared in TransientSummary
        # (tests/test_summary_keys.py checks every bundled scene's against it)
        return cast(TransientSummary, out)

    def _final_state(self) -> dict:
        """The steady contract's keys (:class:`SteadyResult`'s summary) for the run's
        final state: power, steam and water rates over the final turns
        (:func:`~corliss.engine.speed_metrics.final_turns`, as
        ``final_indicated_power_W``), the mean effective pressure over both ends from
        their work, and each end's from the area of its card in the last turn
        (None without pressures: a ``"cycle"`` record, the mean-value model)."""
        c = final_turns(self.cycles)
        power = float(c["indicated_power_W"].mean())
        steam = float(c["steam_rate_kg_per_h"].mean())
        ihp = power / units.HP_W
        sw_h, sw_c = self.geometry.swept_m3
        mep = {"mep_head_Pa": None, "mep_crank_Pa": None,
               "mep_mean_Pa": float(c["work_J"].mean()) / (sw_h + sw_c)}
        cards = self.cards()
        if cards:
            for end, swept in (("head", sw_h), ("crank", sw_c)):
                mep[f"mep_{end}_Pa"] = _loop_work(cards["after"][end]) / swept
        return {"indicated_power_W": power, "indicated_power_hp": ihp,
                "steam_rate_kg_per_h": steam,
                "water_rate_kg_per_kWh": steam / (power / 1000.0) if power > 0 else None,
                "water_rate_lb_per_ihp_h": steam / units.POUND_kg / ihp if ihp > 0 else None,
                **mep}

    def cards(self) -> dict:
        """Head and crank cards of the turn before the step and of the last turn.

        Without a step in the run, "before" is the first turn.

        Returns
        -------
        dict
            ``{"before": {"head": frame, "crank": frame, "cycle": k}, "after": ...}``,
            each frame with ``piston_frac`` (the piston's position as a fraction of the
            stroke from head-end dead centre, the cards' abscissa) [-], ``V_m3`` [m3]
            and ``p_Pa`` [Pa] over the turn ``k``; empty
            when the time series has no pressures (``record`` = cycle, or the
            mean-value model).
        """
        ts = self.timeseries
        if "p_head_Pa" not in ts:
            return {}
        c = self.cycles
        t_step = self.step_time_s
        k_last = int(c["cycle"].iloc[-1])
        if t_step is not None and (c["t_end_s"] <= t_step).any():
            k_before = int(c.loc[c["t_end_s"] <= t_step, "cycle"].iloc[-1])
        else:
            k_before = int(c["cycle"].iloc[0])
        import pandas as pd      # a transient's tables are DataFrames (imported on use)
        out = {}
        for label, k in (("before", k_before), ("after", k_last)):
            rows = ts[ts["cycle"] == k]
            th = np.radians(rows["crank_angle_deg"].to_numpy())
            vh, vc = self.geometry.volumes_m3(th)
            frac = self.geometry.fraction(th % TWO_PI)
            out[label] = {"head": pd.DataFrame({"piston_frac": frac, "V_m3": vh,
                                                "p_Pa": rows["p_head_Pa"].to_numpy()}),
                          "crank": pd.DataFrame({"piston_frac": frac, "V_m3": vc,
                                                 "p_Pa": rows["p_crank_Pa"].to_numpy()}),
                          "cycle": k}
        return out

    def _table_cards(self) -> pd.DataFrame:
        import pandas as pd
        frames = [df.assign(phase=phase, end=end)[["phase", "end", "V_m3", "p_Pa"]]
                  for phase, d in self.cards().items()
                  for end, df in d.items() if end != "cycle"]
        return (pd.concat(frames, ignore_index=True) if frames else
                pd.DataFrame({"phase": [], "end": [], "V_m3": [], "p_Pa": []}))


def _loop_work(card) -> float:
    """The work of one end over a turn, the area of its card [J]: the closed loop's
    integral of p dV by the trapezoidal rule, the last sample joined to the first."""
    v = card["V_m3"].to_numpy()
    p = card["p_Pa"].to_numpy()
    return float(np.sum(0.5 * (p + np.roll(p, -1)) * (np.roll(v, -1) - v)))


@dataclass(kw_only=True)
class SweepResult(Result[dict[str, Any]]):
    """Steady runs across the load range at a series of gear settings or throttle openings.

    Parameters
    ----------
    scene, property_tier, timeseries, cycles, rhs_evaluations, wall_time_s
        As for :class:`Result` (``wall_time_s`` [s]); the tables are described below.
    knob : str
        ``"setting"`` or ``"throttle"``.
    values : list of float
        The settings [-] or openings [-] run.

    Notes
    -----
    Tables: ``points`` (one row per value: ``knob_frac`` (the setting or opening),
    ``indicated_power_W``, ``steam_rate_kg_per_h``, ``water_rate_kg_per_kWh``,
    ``cutoff_head_frac``, and ``brake_power_W`` with ``friction``), also as
    ``timeseries``/``cycles`` (the same one row per run).
    """

    kind: ClassVar[str] = "sweep"
    TABLES: ClassVar[tuple[str, ...]] = ("points",)
    FIGURES: ClassVar[tuple[str, ...]] = ("willans",)

    knob: str = "setting"
    values: list = field(default_factory=list)

    @property
    def points(self) -> pd.DataFrame:
        """One row per steady run (see the class's tables)."""
        return self.cycles

    def willans(self) -> tuple[float, float, float]:
        """The least-squares Willans line ``steam = a + b * power`` through the points.

        Returns
        -------
        a : float
            Intercept: the steam rate at no power [kg/h].
        b : float
            Slope: the steam of each further watt [kg/h per W].
        r2 : float
            Coefficient of determination [-].
        """
        return willans_fit(self.points)

    def _make_summary(self) -> dict:
        s = self.scene
        out: dict[str, object]      # numbers, names, lists
        out = {"title": s.title, "kind": self.kind, "knob": self.knob,
               "values": list(self.values), "fidelity": s.run.fidelity.name,
               "property_tier": self.property_tier}
        groups = (self.points.groupby("knob", sort=False) if "knob" in self.points
                  else [(self.knob, self.points)])
        for knob, pts in groups:
            a, b, r2 = willans_fit(pts) if len(pts) >= 2 else (None, None, None)
            pre = "" if self.knob != "both" else f"{knob}_"
            # compare's names for the same line: the slope as kg/kWh (b [kg/h per W]
            # x 1000 W/kW), the fit's R2 as a fraction
            out.update({f"{pre}willans_intercept_kg_per_h": a,
                        f"{pre}willans_slope_kg_per_kWh": None if b is None else 1e3 * b,
                        f"{pre}willans_r2_frac": r2})
        out.update({"rhs_evaluations": self.rhs_evaluations, "wall_time_s": self.wall_time_s})
        return out


def willans_fit(frame) -> tuple[float, float, float]:
    """Least-squares Willans line ``steam = a + b * power`` through a sweep.

    Parameters
    ----------
    frame : pandas.DataFrame or corliss.frames.frame.Frame
        At least two rows with ``indicated_power_W`` [W] and ``steam_rate_kg_per_h``
        [kg/h].

    Returns
    -------
    a : float
        Intercept: the steam rate at no power [kg/h].
    b : float
        Slope: the steam of each further watt [kg/h per W].
    r2 : float
        Coefficient of determination [-] (1 when every steam rate is the same).
    """
    x = frame["indicated_power_W"].to_numpy()
    y = frame["steam_rate_kg_per_h"].to_numpy()
    b, a = np.polyfit(x, y, 1)
    resid = y - (a + b * x)
    ss = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - float(np.sum(resid ** 2)) / ss if ss > 0 else 1.0
    return float(a), float(b), r2
