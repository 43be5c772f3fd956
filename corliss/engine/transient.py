"""Transient runs: the engine, its flywheel, its load and its governor, turn by turn.

The scene's network (the same control volumes and effects as a steady run) is handed
to the compiled loop of :mod:`corliss.engine.kernels.loop` with speed, governor
coordinate and time as states.  Before t = 0 the engine runs ``warmup_cycles`` turns
at the scene's speed with the governor held at its equilibrium for that speed, so the
cylinders start from a periodic state; then the shaft is released.

What the governor moves is tabulated once: the throttle's effective area against its
opening, or the valve gear's port areas over a uniform grid of (setting, crank angle),
with the gear's events at the settings a turn visits for the per-cycle cut-off.
"""

from __future__ import annotations

import logging
import math
import time
import dataclasses
from dataclasses import dataclass
from typing import Callable

import numpy as np
import pandas as pd

from corliss.engine.kernels import dopri5, loop, rosenbrock
from corliss.engine.kernels.cache import announce_compile
from corliss.engine.kernels.data import (H_MODEL, TRIP_AREA, TRIP_CLOSING, TRIP_GRID,
                                         TRIP_RELEASE, TRIP_SCALARS, TS_CLOSE_ANGLE,
                                         TS_CLOSE_TIME, TS_N_CLOSING, TS_N_SETTINGS,
                                         TS_OPEN_ANGLE, WALL_NONE, LoopArrays, NetworkArrays,
                                         Physics, Tableau)
from corliss.engine.kernels.stepping import MAX_RHS_PER_CYCLE
from corliss.engine.kernels.tableaus import ROS_TABLEAUS
from corliss.engine.condensation import ScheduledWallHeat, wall_schedule
from corliss.engine.crank_resolved import budget_message
from corliss.engine.leak_paths import setting_leak_scales
from corliss.engine.setting_table import SettingTable
from corliss.engine.model import assemble, build_network
from corliss.engine.network import Network, throttle_area_m2
from corliss.governors.operating_point import (BALANCED, LOAD_TOO_HEAVY, SURPLUS_TOL,
                                           OperatingPoint, find_operating_point)
from corliss.engine.options import TRANSIENT_METHODS, record_of
from corliss.engine.result import TransientResult
from corliss.engine.reversal import backward_gear, reversible, run_reversal
from corliss.engine.speed_metrics import settled, step_time_of
from corliss.engine.start_from_rest import HANDOVER_FRACTION, start_from_rest
from corliss.errors import InputError, RunError
from corliss.governors import governor_type
from corliss.governors.mechanism import CREEP_PER_S, GovernorMechanism
from corliss.thermo.steam_table import TableArrays, load_table
from corliss.valves import events as gear_events
from corliss.valves.portmap import tabulate, tabulate_settings
from corliss.valves.gear import ValveGear
from corliss.valves.single_acting import single_acting

log = logging.getLogger(__name__)
TWO_PI = 2.0 * math.pi
#: Settings tabulated across a governed gear's actuator range (bilinear in between).
SETTING_POINTS = 21
#: The loop stops as stalled when the speed falls below this fraction of the start.
STALL_FRACTION = 0.05
#: Turns at most per evaluation of the surplus torque while the start is sought (each
#: starts from the cylinders' state at the last point, so two or three usually suffice).
EQUILIBRIUM_TURNS = 6
#: Trial turns that set the speed at dead centre for the start's turn-mean speed.
START_TRIALS = 3
#: A run ``until_settled`` looks whether it has settled every this many turns.
SETTLE_CHECK_TURNS = 10


@dataclass
class LoopTables:
    """Everything the compiled loop reads besides the network.

    Parameters
    ----------
    tr : LoopArrays
        The loop's tables (:class:`corliss.engine.kernels.data.LoopArrays`):
        ``(sc, lt, lf, sgrid, area_s, governed, gov, trip, thr)``: the scalars
        (indices ``S_*``: inertia [kg m2], reciprocating mass [kg], friction [N m],
        [N m s/rad], the governor's constants, the load's law, torque [N m] and
        reference speed [rad/s], ...), the load's times [s] and fractions [-], the
        setting grid [-], port areas over (cylinder, port, setting, crank angle) [m2],
        which cylinders the governor moves, the governor's M, M', G, R, J on a uniform z
        grid, the trip gear's tables, and the throttle's area over a uniform grid of
        opening [m2].
    governed_gear : ValveGear or None
        The valve gear the governor sets (None: it works the throttle, or there is no
        governor).
    setting_grid : ndarray or None
        The settings tabulated [-], with a governed gear.
    cutoff_table : SettingTable or None
        Head and crank cut-off over the settings, fractions of the stroke [-].
    z0 : float
        The governor's equilibrium coordinate at the run's speed [-] (0 without one).
    mechanism : GovernorMechanism or None
        The governor in its common form.
    """

    tr: LoopArrays
    governed_gear: ValveGear | None
    setting_grid: np.ndarray | None
    cutoff_table: SettingTable | None    # head and crank cut-off over the settings
    z0: float
    mechanism: GovernorMechanism | None


def _governor_arrays(mech):
    z = np.asarray(mech.z, dtype=float)
    if not (abs(z[0]) < 1e-12 and abs(z[-1] - 1.0) < 1e-12 and np.allclose(np.diff(z), z[1] - z[0])):
        raise ValueError("the governor's mechanism must be tabulated on a uniform grid of z "
                         "from 0 to 1")
    return np.vstack([mech.M, mech.dM_dz, mech.G, mech.R, mech.J]).astype(float)


def cutoff_table(gear, settings: np.ndarray, frac: Callable) -> SettingTable:
    """The cut-off of each end over the tabulated settings of a governed gear, each
    setting's found from the gear's events when a turn first needs it.

    The events of a setting cost a root search on the gear (about 4 ms of a Fink
    motion's); a load step visits a few of the settings, so finding all of them up
    front was a tenth of a 60-second run's time.

    Parameters
    ----------
    gear : object
        The governed valve gear.
    settings : ndarray
        The settings tabulated [-], increasing.
    frac : callable
        Crank angle [rad] -> piston position as a fraction of the stroke [-].

    Returns
    -------
    SettingTable
        Head and crank cut-off, fractions of the stroke [-] (NaN where an end has
        none), at a setting.
    """
    def find(setting: float) -> list:
        ev = gear_events(gear.with_setting(setting), frac)
        return [np.nan if ev[end]["cutoff_frac"] is None else ev[end]["cutoff_frac"]
                for end in ("head", "crank")]
    return SettingTable(settings, find)


def _gear_tables(gear, lo: float, hi: float, ncyl: int, governed: np.ndarray, nth: int,
                 frac: Callable):
    """Port areas over (setting, crank angle) for the governed cylinders, and the cut-off
    of each end over the settings."""
    spm = tabulate_settings(gear, lo, hi, SETTING_POINTS, nth)
    area = np.zeros((ncyl, 4, spm.settings.size, nth + 1))
    for c in range(ncyl):
        if governed[c]:
            area[c] = np.transpose(spm.area_m2, (1, 0, 2))
    return spm.settings, area, cutoff_table(gear, spm.settings, frac)


def _trip_tables(gear, grid: np.ndarray, nth: int):
    """The trip arrays of a gear that releases its steam valves (see trip_areas)."""
    theta = np.linspace(0.0, TWO_PI, nth + 1)
    latched = gear.latched_signed_openings(theta)
    widths = gear.port_widths()
    lengths = gear.port_lengths()
    t_close = float(gear.closing_time_s)
    nf = 101
    rows = np.full((TRIP_SCALARS + 1, max(grid.size, nf)), np.nan)
    rows[TRIP_GRID, :grid.size] = grid
    rows[TRIP_CLOSING, :nf] = gear.closing_fraction(np.linspace(0.0, t_close, nf))
    rows[TRIP_SCALARS, :] = 0.0
    rows[TRIP_SCALARS, TS_CLOSE_TIME] = t_close
    rows[TRIP_SCALARS, TS_N_SETTINGS] = grid.size
    rows[TRIP_SCALARS, TS_N_CLOSING] = nf
    for e, port in enumerate((0, 2)):
        op = latched[port]
        opened = op > 0.0
        # the latched window: from where the opening rises through zero to where it falls
        rise = np.nonzero(~opened[:-1] & opened[1:])[0]
        fall = np.nonzero(opened[:-1] & ~opened[1:])[0]
        if rise.size == 0 or fall.size == 0:
            raise ValueError("a trip gear's latched steam valve must open and close once a turn")
        rows[TRIP_SCALARS, TS_OPEN_ANGLE + e] = theta[rise[0]]
        rows[TRIP_SCALARS, TS_CLOSE_ANGLE + e] = theta[fall[0] + 1]
        for j, s in enumerate(grid):
            rel = gear.release_angle_rad(float(s))[e]
            rows[TRIP_RELEASE + e, j] = np.nan if rel is None else rel
            if rel is not None:
                x = float(np.interp(rel % TWO_PI, theta, op))
                rows[TRIP_AREA + e, j] = min(max(x, 0.0), widths[port]) * lengths[port]
    return rows, latched


def build_tables(scene, net, gear, geo) -> LoopTables:
    """The loop's tables from the scene.

    Parameters
    ----------
    scene : Scene
        The transient scene (flywheel, load, governor, effects, fidelity).
    net : Network
        Its network (the throttle's edge is ``steam_pipe``).
    gear : object
        Its valve gear, built once by the caller.
    geo : CylinderGeometry
        The (first or high-pressure) cylinder, for the cut-off at each setting.

    Returns
    -------
    LoopTables
        The tables; a gear governor's port areas over :data:`SETTING_POINTS` settings
        of its actuator range (a compound's LP gear is not governed).

    Raises
    ------
    ValueError
        A governor not tabulated on a uniform grid of z from 0 to 1, or a trip gear
        whose latched steam valve does not open and close once a turn.
    """
    fid = scene.run.fidelity
    omega0 = scene.run.speed_rad_s
    ncyl = len(net.geometries)
    sc = np.zeros(loop.N_SCALARS)
    sc[loop.S_INERTIA] = scene.flywheel.inertia_kg_m2
    if scene.run.has("inertia") and scene.engine.reciprocating_mass_kg:
        sc[loop.S_MREC] = scene.engine.reciprocating_mass_kg
    sc[loop.S_FRICTION_ON] = 1.0 if scene.run.has("friction") else 0.0
    sc[loop.S_TF0] = scene.engine.friction_torque_N_m
    sc[loop.S_TF1] = scene.engine.friction_N_m_s
    load = scene.load
    sc[loop.S_KLAW] = load.speed_exponent
    sc[loop.S_TREF] = load.torque_N_m
    sc[loop.S_WREF] = omega0
    sc[loop.S_WMIN] = STALL_FRACTION * omega0
    sc[loop.S_MAX_RHS] = MAX_RHS_PER_CYCLE
    lt = np.asarray(load.times_s, dtype=float)
    lf = np.asarray(load.fractions, dtype=float)
    gov = np.zeros((5, 2))
    gov[0, :] = 1.0
    sgrid = np.zeros(1)
    area_s = np.zeros((ncyl, 4, 1, 2))
    governed = np.zeros(ncyl, dtype=np.int64)
    thr = np.zeros(2)
    trip = np.zeros((7, 2))
    mech = None
    governed_gear = None
    cut = None
    z0 = 0.0
    if scene.governor is not None:
        g = governor_type(scene.governor_type).build(scene.governor)
        mech = g.mechanism(201)
        gov = _governor_arrays(mech)
        sc[loop.S_HAS_GOV] = 1.0
        sc[loop.S_RATIO] = mech.ratio
        sc[loop.S_DAMP] = mech.c
        sc[loop.S_FRIC] = mech.F_f
        sc[loop.S_VEPS] = CREEP_PER_S
        sc[loop.S_A0] = mech.actuator_at_rest
        sc[loop.S_A1] = mech.actuator_at_top
        if mech.safety_z > 0.0 and np.isfinite(mech.actuator_safety):
            sc[loop.S_SAFE_Z] = mech.safety_z
            sc[loop.S_SAFE_A] = mech.actuator_safety
        z0 = mech.equilibrium_z(omega0)
        if mech.acts_on == "throttle":
            sc[loop.S_ACT_GEAR] = 0.0
            sc[loop.S_THR_EDGE] = net.edge("steam_pipe")
            openings = np.linspace(0.0, 1.0, 201)
            thr = np.array([0.0] + [throttle_area_m2(dataclasses.replace(scene.supply, throttle=x))
                                    for x in openings[1:]])
        else:
            sc[loop.S_ACT_GEAR] = 1.0
            governed_gear = gear
            lo, hi = mech.actuator_range()
            governed[:] = 1
            if scene.compound is not None:
                governed[1:] = 0     # the governor moves the HP gear; the LP's is fixed
            sgrid, area_s, cut = _gear_tables(gear, lo, hi, ncyl, governed, fid.portmap_points,
                                              lambda t: float(geo.fraction(t)))
            if hasattr(gear, "release_angle_rad"):
                # the table holds the latched steam valves; the loop trips them itself,
                # at its own speed
                trip, latched = _trip_tables(gear, sgrid, fid.portmap_points)
                sc[loop.S_TRIP] = 1.0
                w, ln = gear.port_widths(), gear.port_lengths()
                for c in range(ncyl):
                    if governed[c]:
                        for port in (0, 2):
                            area_s[c, port, :, :] = (np.clip(latched[port], 0.0, w[port])
                                                     * ln[port])[None, :]
    tr = LoopArrays(sc, lt, lf, sgrid, area_s, governed, gov, trip, thr)
    return LoopTables(tr, governed_gear, sgrid if governed_gear is not None else None, cut,
                      z0, mech)


def setting_at(sc: np.ndarray, z: float) -> float:
    """The governor's actuator value at ``z``, as the loop finds it
    (:func:`corliss.engine.kernels.loop.actuator`, which the compiled turn calls): a
    gear's setting.

    Parameters
    ----------
    sc : numpy.ndarray
        The loop's scalars (the actuator's range and safety cams, ``S_*``).
    z : float
        The governor's coordinate [-].

    Returns
    -------
    float
        The actuator's value [-].
    """
    return float(loop.actuator(float(z), sc))


@dataclass
class GovernedSchedule:
    """A period law's schedule (:class:`~corliss.engine.condensation.ScheduledWallHeat`)
    whose windows follow a governed gear's setting turn by turn.

    Each turn takes the events of the gear at the setting the governor stands at when
    it starts (:func:`corliss.valves.events` of the gear at that setting, as the turn's
    row reports its cut-off), its rows and the turn's stops from them; within the turn
    they stay.  A compound's LP gear is not governed: its ends keep their events.

    Parameters
    ----------
    schedule : ScheduledWallHeat
        The run's schedule.
    gear : ValveGear
        The governed gear.
    frac : callable
        Crank angle [rad] -> piston position as a fraction of the stroke [-].
    sc : numpy.ndarray
        The loop's scalars (:func:`setting_at`).
    """

    schedule: ScheduledWallHeat
    gear: ValveGear
    frac: Callable
    sc: np.ndarray

    def apply(self, z: float, heat: np.ndarray) -> np.ndarray:
        """Set the schedule's events and rows for the setting at ``z``.

        Parameters
        ----------
        z : float
            The governor's coordinate [-].
        heat : numpy.ndarray
            The compiled network's wall-heat rows, written in place.

        Returns
        -------
        numpy.ndarray
            The turn's stops, the schedule's switches as shaft angles [rad].
        """
        self.schedule.set_events(gear_events(self.gear.with_setting(setting_at(self.sc, z)),
                                             self.frac))
        self.schedule.apply(heat)
        return np.array(self.schedule.stops_rad(), dtype=float)


@dataclass
class GovernedEdgeLeaks:
    """The period law's valve-edge leaks of the cylinders a governor sets, their scales
    following the setting turn by turn.

    An edge leaks the reference valve's rate times its scale, the port's length over
    the reference's and the reference's face width over the edge's mean overlap while
    closed (:mod:`corliss.engine.leak_paths`), both of which the setting moves.  Each
    turn takes the scales at the setting the governor stands at when it starts, read
    between the loop's tabulated settings as its port areas are; within the turn they
    stay (the leak is a small flow, the setting's change in a turn small).

    Parameters
    ----------
    scales : SettingTable
        The governed gear's scales over the loop's setting grid.
    edges : list of tuple
        ``(edge, port, rate)`` of each governed edge's leak: its index, its port and
        the reference rate [kg/(s Pa)] (:attr:`corliss.engine.network.Network.edge_leaks`).
    sc : numpy.ndarray
        The loop's scalars (the actuator's range and safety cams, ``S_*``).
    """

    scales: SettingTable
    edges: list
    sc: np.ndarray

    def apply(self, z: float, edge_area: np.ndarray) -> None:
        """Set each governed edge's rate for the setting at ``z``.

        Parameters
        ----------
        z : float
            The governor's coordinate [-].
        edge_area : numpy.ndarray
            The compiled network's edge areas (a linear edge's is its rate of leak
            [kg/(s Pa)]), written in place.
        """
        scale = self.scales.at(setting_at(self.sc, z))
        for e, port, rate in self.edges:
            edge_area[e] = rate * scale[port]


def governed_edge_leaks(network: Network, tables: LoopTables) -> GovernedEdgeLeaks | None:
    """The edge leaks a governed gear's setting moves, or None.

    Parameters
    ----------
    network : Network
        The run's network (its :attr:`~corliss.engine.network.Network.edge_leaks`).
    tables : LoopTables
        The loop's tables: the governed gear, the setting grid and the governed
        cylinders.

    Returns
    -------
    GovernedEdgeLeaks or None
        None without a governed gear or without edge leaks on a governed cylinder.
    """
    if tables.governed_gear is None or tables.setting_grid is None:
        return None
    edges = [(e, port, rate) for e, c, port, rate in network.edge_leaks
             if tables.tr.governed[c]]
    if not edges:
        return None
    return GovernedEdgeLeaks(setting_leak_scales(tables.governed_gear, tables.setting_grid),
                             edges, tables.tr.sc)


@dataclass
class TurnRunner:
    """The compiled turn of one transient run, with everything it reads: the network's,
    the steam table's and the loop's arrays, the tolerances, and the evaluations counted.

    Parameters
    ----------
    integrate : callable
        The turn's integrator (:func:`_turn_integrator`), with the arguments of
        :func:`corliss.engine.kernels.dopri5.integrate_turn`.
    network : Network
        The run's network (for its messages and its walls).
    net : NetworkArrays
        Its compiled arrays (replaced when a slip eccentric reverses the gear).
    tier : int
        The steam properties' compiled tier.
    tab : TableArrays
        The steam table's arrays.
    perf : numpy.ndarray
        The perfect-gas parameters of the ``perfect`` tier (zeros otherwise).
    tr : LoopArrays
        The loop's tables and scalars (``tr.sc``).
    rtol : float
        Relative tolerance [-].
    atol : numpy.ndarray
        Absolute tolerance of each state [its unit].
    nfev : int
        Right-hand-side evaluations so far.
    stops_rad : numpy.ndarray or None
        Shaft angles [rad] where each turn restarts its step: a wall-heat schedule's
        switches (:attr:`corliss.engine.network.Network.schedule_stops`); None for
        none (:func:`corliss.engine.kernels.loop.turn_stops`).
    edge_leaks : GovernedEdgeLeaks or None
        The valve-edge leaks whose scales follow the governed gear's setting, set
        at each turn's start (None: the scene's setting's, as built).
    schedule : GovernedSchedule or None
        A period law's schedule whose windows follow the governed gear's setting, its
        rows and :attr:`stops_rad` set at each turn's start (None: they stay).
    """

    integrate: Callable
    network: Network
    net: NetworkArrays
    tier: int
    tab: TableArrays
    perf: np.ndarray
    tr: LoopArrays
    rtol: float
    atol: np.ndarray
    nfev: int = 0
    stops_rad: np.ndarray | None = None
    edge_leaks: GovernedEdgeLeaks | None = None
    schedule: GovernedSchedule | None = None

    def turn(self, y: np.ndarray, th0: float, out_theta: np.ndarray, steps: bool,
             t_end: float) -> tuple:
        """One turn of the crank from ``th0`` (or less: a stall, ``t_end``).

        Parameters
        ----------
        y : numpy.ndarray
            The state at ``th0``: the network's and the loop's (:mod:`~corliss.engine.kernels.loop`).
        th0 : float
            Crank angle at the start [rad].
        out_theta : numpy.ndarray
            Crank angles to sample the state at [rad].
        steps : bool
            Record every accepted step as well.
        t_end : float
            Time at which to stop [s].

        Returns
        -------
        tuple
            ``(y, samples, recorded, n_recorded, status)``: the state at the turn's end,
            the samples at ``out_theta``, the steps recorded and their count, and the
            status (0 a whole turn, 2 stalled or ``t_end``, 1 failed, 4 over budget).
        """
        z = float(y[self.network.n_state + loop.X_Z])
        if self.edge_leaks is not None:
            self.edge_leaks.apply(z, self.net.edge_area)
        if self.schedule is not None:
            self.stops_rad = self.schedule.apply(z, self.net.heat)
        y, samples, rec, n_rec, nf, status = self.integrate(
            y, th0, out_theta, self.rtol, self.atol, self.net, self.tier, self.tab, self.perf,
            self.tr, steps, t_end, self.stops_rad)
        self.nfev += nf
        return y, samples, rec, n_rec, status

    def stop_on_failure(self, status: int, where: str, failed: str) -> None:
        """Raise when a turn went over the evaluation budget or its step size collapsed.

        Parameters
        ----------
        status : int
            The turn's status (:meth:`turn`).
        where : str
            Appended to the budget's message, e.g. ``" (in turn 3, at 0.412 s)"``.
        failed : str
            The message when the step size collapsed.

        Raises
        ------
        RunError
            Over the budget (:func:`~corliss.engine.crank_resolved.budget_message`).
        RuntimeError
            The step size collapsed.
        """
        if status == 4:
            raise RunError(budget_message(self.network, self.tr.sc[loop.S_MAX_RHS]) + where)
        if status == 1:
            raise RuntimeError(failed)


def _frozen_turns(turns: TurnRunner, y: np.ndarray, omega: float, z: float, count: int,
                  marks, steam, tol: float | None = None) -> tuple[np.ndarray, float]:
    """Turns at speed ``omega`` with the governor held at ``z``: ``count`` of them, or with
    ``tol`` [N m] until the turn's mean surplus torque changes by less (at most
    ``count``).  With Marks's law (``marks``) each turn is sampled every degree and its
    steam temperatures at cut-off (``steam``'s) set the next turn's rows, as a steady
    run's cycles do.  Returns the state and the last turn's surplus [N m]."""
    network = turns.network
    out_theta = _out_angles("degree", 0.0, 360) if marks is not None else np.zeros(0)
    nn = network.n_state
    y[nn + loop.X_OMEGA] = omega
    y[nn + loop.X_Z] = z
    y[nn + loop.X_ZDOT] = 0.0
    last = math.inf
    surplus = 0.0
    for turn in range(count):
        y[network.n_dyn:nn] = 0.0
        for q in (loop.X_TIME, loop.X_WLOAD, loop.X_WFRIC, loop.X_WGAS):
            y[nn + q] = 0.0
        if marks is not None:
            marks.strokes_per_s = omega / math.pi
            marks.apply(turns.net.heat)
        y, samples, _, _, status = turns.turn(y, 0.0, out_theta, False, math.inf)
        turns.stop_on_failure(status, " (in the warm-up turns before t = 0)",
                              "the integrator failed in the warm-up turns before t = 0")
        if marks is None:
            _update_wall(network, y)
        else:
            marks.update(steam, samples, out_theta)
            marks.apply(turns.net.heat)
        surplus = (y[nn + loop.X_WGAS] - y[nn + loop.X_WFRIC] - y[nn + loop.X_WLOAD]) / TWO_PI
        if tol is not None and turn >= 1 and abs(surplus - last) <= tol:
            break
        last = surplus
    return y, surplus


def _start_at_speed(turns: TurnRunner, y: np.ndarray, scene, tables: LoopTables, marks,
                    steam) -> tuple[np.ndarray, OperatingPoint]:
    """Warm-up turns at the scene's speed, then (``start = "equilibrium"``) the governor's
    operating point for the load, and the speed at dead centre that gives it as the
    turn's mean.  Returns the state released at t = 0 and the start."""
    run = scene.run
    nn = turns.network.n_state
    sc = tables.tr.sc
    omega0 = run.speed_rad_s
    y, _ = _frozen_turns(turns, y, omega0, tables.z0, run.warmup_cycles, marks, steam)
    start = OperatingPoint(omega0, tables.z0, math.nan, "run_speed", 0)
    if tables.mechanism is not None and run.start == "equilibrium":
        t_load = abs(sc[loop.S_TREF] * loop.load_factor(0.0, tables.tr.load_t, tables.tr.load_f))
        tol = 0.25 * SURPLUS_TOL * max(t_load, 1e-9)

        def surplus(omega, z):
            nonlocal y
            y, s = _frozen_turns(turns, y, omega, z, EQUILIBRIUM_TURNS, marks, steam, tol)
            return s

        start = find_operating_point(surplus, tables.mechanism, t_load)
        y, _ = _frozen_turns(turns, y, start.speed_rad_s, start.governor_z, 2, marks, steam)
        _report_start(start)
    # The flywheel lets the speed swing within a turn (Marks Art. 62), and the governor
    # balances on the turn's mean speed; released at dead centre at the mean speed, the
    # engine would gain or lose the swing's offset and the governor follow it.  So the
    # speed at dead centre is set, by trial turns with the governor held and the speed
    # free, to give the turn-mean speed of the start.
    sc[loop.S_FREEZE] = 2.0
    omega_dc = start.speed_rad_s
    for _ in range(START_TRIALS):
        trial = y.copy()
        trial[nn + loop.X_OMEGA] = omega_dc
        trial[nn + loop.X_TIME] = 0.0
        trial, _, _, _, status = turns.turn(trial, 0.0, np.zeros(0), False, math.inf)
        if status != 0:
            break
        omega_dc *= start.speed_rad_s / (TWO_PI / trial[nn + loop.X_TIME])
    sc[loop.S_FREEZE] = 0.0
    y[nn + loop.X_TIME] = 0.0
    y[nn + loop.X_OMEGA] = omega_dc
    y[nn + loop.X_Z] = start.governor_z
    y[nn + loop.X_ZDOT] = 0.0
    return y, start


def _start_at_rest(turns: TurnRunner, y: np.ndarray, scene, steam, tables: LoopTables
                   ) -> tuple[dict, OperatingPoint, dict, dict]:
    """From rest at ``run.start_angle`` to the dead centre where the crank-angle loop
    takes over (:func:`~corliss.engine.start_from_rest.start_from_rest`).  Returns what
    it gives, the start, and its per-turn row and time-series columns."""
    run = scene.run
    network = turns.network
    nn = network.n_state
    start = OperatingPoint(0.0, 0.0, math.nan, "rest", 0)
    turns.tr.sc[loop.S_FREEZE] = 0.0
    for q in (loop.X_OMEGA, loop.X_Z, loop.X_ZDOT, loop.X_TIME):
        y[nn + q] = 0.0
    begun = start_from_rest(y, run.start_angle_rad, run.speed_rad_s, turns.net, turns.tier,
                            turns.tab, turns.perf, turns.tr, turns.rtol, turns.atol,
                            run.max_duration_s or run.duration_s)
    turns.nfev += begun["nfev"]
    row, frame = _start_record(begun, y, network, steam, tables, nn)
    if begun["stalled"]:
        log.warning("the engine did not start: from rest at %.1f deg of crank it had not "
                    "reached %.0f %% of run.speed by %.3g s", math.degrees(run.start_angle_rad),
                    100 * HANDOVER_FRACTION, begun["y"][nn + loop.X_TIME])
    return begun, start, row, {c: frame[c].to_numpy() for c in frame.columns}


def _out_angles(record: str, th0: float, n_out: int) -> np.ndarray:
    """The crank angles a turn from ``th0`` is sampled at [rad]: ``n_out`` a turn with
    ``record = "degree"``, the turn's start with ``"cycle"``, none with ``"step"``."""
    if record == "degree":
        return th0 + np.arange(n_out) * (TWO_PI / n_out)
    if record == "cycle":
        return np.array([th0])
    return np.zeros(0)


def run_transient(scene, *, progress: Callable[[float, float], None] | None = None
                  ) -> TransientResult:
    """Run a transient scene.

    Parameters
    ----------
    scene : Scene
        ``run.mode = "transient"`` with [flywheel], [load] and optionally [governor].
    progress : callable, optional
        Called after each turn with (simulated time [s], duration [s]).

    Returns
    -------
    TransientResult
        The speed and governor histories, the per-turn table, the cards before the
        step and at the end, and the load-step metrics.
    """
    t_wall = time.perf_counter()
    run = scene.run
    fid = run.fidelity
    model = assemble(scene)
    steam = model.steam
    if steam.kernel_tier is None:
        raise InputError("run.fidelity", fid.name, "a fidelity on a compiled property tier "
                         "(\"standard\" or \"fast\", or properties = \"table\"): the transient "
                         "loop is compiled")
    method = loop_method(fid)
    chest, exhaust = model.chest, model.exhaust
    geo, gear, pm = model.geometry, model.gear, model.portmap
    network = build_network(scene, geo, pm, steam, chest, exhaust)
    tables = build_tables(scene, network, gear, geo)
    net = network.arrays()
    # Marks's or English's law from the gears' events at the start (each end's row from
    # its own cylinder's geometry, events and phase, a compound's LP ends from the LP
    # gear's, as on a steady run), with the supply's saturation temperature as the first
    # cut-off temperature, then each end's steam at its cut-off in the warm-up turns (and
    # in the turns sampled every degree); the heat follows the speed turn by turn, and a
    # governed gear's windows its setting at each turn's start (GovernedSchedule)
    marks = wall_schedule(scene, network, geo, model.events, run.speed_rad_s, chest.T, exhaust.T,
                          lp_events=model.lp_events)
    if marks is not None:
        marks.apply(net.heat)
    tab = steam.table.arrays() if hasattr(steam, "table") else _any_table()
    perf = (np.array(steam.perfect_params()) if hasattr(steam, "perfect_params") else np.zeros(3))
    nn = network.n_state
    omega0 = run.speed_rad_s
    y = np.concatenate([network.initial_state(), np.zeros(loop.N_EXTRA)])
    y[nn + loop.X_OMEGA] = omega0
    y[nn + loop.X_Z] = tables.z0
    atol = np.concatenate([fid.rtol * network.scales(),
                           fid.rtol * np.array([omega0, 1.0, 1.0, 1.0, 1e3, 1e3, 1e3, 1.0, 1.0])])
    sc = tables.tr.sc
    turns = TurnRunner(_turn_integrator(method, network), network, net, steam.kernel_tier, tab,
                       perf, tables.tr, fid.rtol, atol,
                       stops_rad=(np.array(network.schedule_stops, dtype=float)
                                  if marks is not None else None),
                       edge_leaks=governed_edge_leaks(network, tables),
                       schedule=(GovernedSchedule(marks, tables.governed_gear,
                                                  lambda t: float(geo.fraction(t)), tables.tr.sc)
                                 if marks is not None and tables.governed_gear is not None
                                 else None))
    # warm-up: speed and governor held, time held at zero
    announce_compile(turn=method)
    sc[loop.S_FREEZE] = 1.0

    rows, frames = [], []
    k = 0
    stalled_at_rest = False
    if run.start == "rest":
        begun, start, row, frame = _start_at_rest(turns, y, scene, steam, tables)
        rows.append(row)
        frames.append(frame)
        y = begun["y"]
        k = int(round(begun["theta_rad"] / TWO_PI))
        stalled_at_rest = begun["stalled"]
    else:
        y, start = _start_at_speed(turns, y, scene, tables, marks, steam)
    duration = run.duration_s
    record = record_of(run)
    n_out = max(1, int(round(TWO_PI / math.radians(fid.output_step_deg))))
    status = 2 if stalled_at_rest else 0
    since = step_time_of(scene.load) or 0.0
    longest = run.max_duration_s if run.until_settled else duration

    def go_on(t: float) -> bool:
        if t < duration:
            return True
        if t >= longest or len(rows) < SETTLE_CHECK_TURNS:
            return False
        if len(rows) % SETTLE_CHECK_TURNS:
            return True
        mid = np.array([0.5 * (r["t_start_s"] + r["t_end_s"]) for r in rows])
        return not settled(mid, np.array([r["mean_speed_rpm"] for r in rows]), since)[0]

    # a slip eccentric stalled by its load is carried through the change of direction
    # (corliss.engine.reversal); afterwards the loop runs in the backward frame, its
    # angles and speeds reported in the fixed frame (``sense`` -1)
    can_reverse = reversible(scene, gear)
    sense = 1.0
    th_offset = 0.0
    slip_deg = math.degrees(gear.spec.slip_rad) if can_reverse else 0.0
    while status != 2 and go_on(y[nn + loop.X_TIME]):
        th0 = TWO_PI * k + th_offset
        y[network.n_dyn:nn] = 0.0
        for q in (loop.X_WLOAD, loop.X_WFRIC, loop.X_WGAS, loop.X_ZDT, loop.X_ADT):
            y[nn + q] = 0.0
        y_start = y.copy()
        out_theta = _out_angles(record, th0, n_out)
        y, samples, rec, n_rec, status = turns.turn(y, th0, out_theta, record == "step", longest)
        turns.stop_on_failure(status, f" (in turn {k + 1}, at {y[nn + loop.X_TIME]:.3f} s)",
                              f"the integrator failed in turn {k + 1} (step size collapsed)")
        if status == 2 and can_reverse and sense > 0.0:
            rev = run_reversal(y_start, th0, omega0, turns.net, gear, steam.kernel_tier, tab,
                               perf, tables.tr, fid.rtol, atol, longest)
            turns.nfev += rev["nfev"]
            row, frame = _reversal_record(rev, k, y_start, network, steam, tables, nn, slip_deg,
                                          record == "degree")
            rows.append(row)
            frames.append(frame)
            y = rev["y"]
            k += 1
            if not rev["handed_over"]:
                break
            log.info("the load turned the engine backward: the eccentric slipped %.1f deg to "
                     "its backward stop at %.3f s", slip_deg, float(rev["samples"]["t"][-1]))
            sense, status = -1.0, 0
            th_offset = rev["phi_rad"] - TWO_PI * k
            # the backward stop's gear (a single-acting cylinder's kept single-acting)
            pm_back = tabulate(single_acting(backward_gear(gear), scene.engine.steam_ends),
                               fid.portmap_points)
            back = build_network(scene, geo, pm_back, steam, chest, exhaust).arrays()
            turns.net = turns.net._replace(port_grid=back.port_grid, port_npts=back.port_npts,
                                           port_area=back.port_area)
            sc[loop.S_TREF] = -sc[loop.S_TREF]    # the load keeps its direction
            continue
        appended = status != 2 or not rows
        if appended:
            # a turn the stall cut short is no turn: its row would be a wrong mean
            rows.append(_cycle_row(k, y_start, y, network, tables, nn))
        if marks is not None:
            if record == "degree" and status == 0:
                marks.update(steam, samples, out_theta)
            marks.strokes_per_s = 2.0 / (rows[-1]["t_end_s"] - rows[-1]["t_start_s"])
            marks.apply(turns.net.heat)
        else:
            _update_wall(network, y)
        frame = _frame(network, steam, tables, out_theta, samples, rec, n_rec, record, nn)
        if can_reverse:
            frame["eccentric_slip_deg"] = np.full(len(frame["time_s"]), 0.0 if sense > 0 else slip_deg)
        if sense < 0.0:
            _to_fixed_frame(rows[-1] if appended else {}, frame)
        frames.append({"cycle": np.full(len(frame["time_s"]), k + 1), **frame})
        k += 1
        if progress:
            progress(float(y[nn + loop.X_TIME]), max(duration, float(y[nn + loop.X_TIME])))
        if status == 2:
            log.warning("the engine stalled at t = %.3f s", y[nn + loop.X_TIME])
            break
    timeseries = _concat_columns(frames)
    return TransientResult(scene=scene, property_tier=steam.name, timeseries=timeseries,
                           cycles=pd.DataFrame(rows), rhs_evaluations=turns.nfev,
                           wall_time_s=time.perf_counter() - t_wall, geometry=geo,
                           stalled=status == 2, mechanism=tables.mechanism,
                           z_start=start.governor_z, chest=chest, exhaust=exhaust,
                           start=start, clamped_trials=int(sc[loop.S_CLAMPED_TRIALS]),
                           clamped_hot=int(sc[loop.S_CLAMPED_HOT]))


def loop_method(fidelity) -> str:
    """The integrator of the transient loop at a fidelity.

    The fidelity's ``transient_method``, or where unset its ``method``; a method the
    loop does not have (the steady cycle's ``rk4``, ``rosenbrock`` or a scipy one)
    becomes ``dopri5``.  Either integrates at the fidelity's ``rtol``.

    Parameters
    ----------
    fidelity : Fidelity
        The run's accuracy knobs.

    Returns
    -------
    str
        One of :data:`corliss.engine.options.TRANSIENT_METHODS`.
    """
    method = fidelity.transient_method or fidelity.method
    if method not in TRANSIENT_METHODS:
        log.info("the transient loop integrates with dopri5 at rtol %g (%s is for steady "
                 "cycles)", fidelity.rtol, method)
        method = "dopri5"
    return method


def _turn_integrator(method: str, network) -> Callable:
    """The compiled turn of the loop with a method, as a function of the arguments of
    :func:`corliss.engine.kernels.dopri5.integrate_turn`."""
    if method == "dopri5":
        return dopri5.integrate_turn
    color, owner = network.column_colors()
    tableau = ROS_TABLEAUS[method]

    def turn(y0, th0, out_theta, rtol, atol, net, tier, tab, perf, tr, record, t_end,
             inner=None):
        return rosenbrock.integrate_turn_ros(y0, th0, out_theta, rtol, atol,
                                             Physics(net, tier, tab, perf), tr, record, t_end,
                                             color, owner, Tableau(*tableau), inner)
    return turn


def _report_start(start: OperatingPoint) -> None:
    """Log where a governed run starts, and warn when no operating point exists."""
    rpm = start.speed_rad_s * 60.0 / TWO_PI
    if start.status == BALANCED:
        log.info("start: the governor balances the load at %.2f rpm, z = %.3f (%d surplus "
                 "evaluations)", rpm, start.governor_z, start.evaluations)
    elif start.status == LOAD_TOO_HEAVY:
        log.warning("the load is more than the engine carries with the governor down (at "
                    "%.1f rpm the surplus torque is %.4g N m): the engine will slow below the "
                    "governor's range; the run starts there", rpm, start.surplus_N_m)
    else:
        log.warning("with the governor at its top stop (%.1f rpm) the engine still has a "
                    "surplus torque of %.4g N m: it will run above the governor's range; the "
                    "run starts there", rpm, start.surplus_N_m)


def _start_record(begun: dict, y0: np.ndarray, network, steam, tables: LoopTables, nn: int):
    """The per-turn row and the time-series rows of a start from rest (``cycle`` 0):
    from rest to the dead centre where the crank-angle loop takes over."""
    t, theta, ys = begun["samples"]
    y = begun["y"]
    row = _cycle_row(-1, y0, y, network, tables, nn)
    dt = max(float(t[-1]), 1e-12)
    row["mean_speed_rpm"] = (theta[-1] - theta[0]) / dt * 60.0 / TWO_PI
    sc = tables.tr.sc
    z = np.clip(ys[nn + loop.X_Z], 0.0, 1.0)
    cols = {"cycle": 0, "time_s": t, "crank_angle_deg": np.degrees(theta),
            "speed_rpm": ys[nn + loop.X_OMEGA] * 60.0 / TWO_PI,
            "governor_z_frac": z, "actuator_frac": sc[loop.S_A0] + (sc[loop.S_A1] - sc[loop.S_A0]) * z}
    for end in ("head", "crank"):
        i = network.node(end)
        V = network.volume(i, theta)
        cols[f"p_{end}_Pa"] = steam.states(ys[2 * i] / V, ys[2 * i + 1] / ys[2 * i])[0]
    return row, pd.DataFrame(cols)


def _reversal_record(rev: dict, k: int, y0: np.ndarray, network, steam, tables: LoopTables,
                     nn: int, slip_deg: float, pressures: bool):
    """The per-turn row and the time-series columns of a change of direction
    (:func:`corliss.engine.reversal.run_reversal`), in the fixed frame: from the start of
    the turn that stalled to the dead centre where the loop runs on backward."""
    s = rev["samples"]
    t, theta, ys = s["t"], s["theta"], s["y"]
    row = _cycle_row(k, y0, rev["y"], network, tables, nn)
    dt = max(float(t[-1] - t[0]), 1e-12)
    rpm = 60.0 / TWO_PI
    row["mean_speed_rpm"] = (theta[-1] - theta[0]) / dt * rpm
    row["speed_end_rpm"] = float(ys[nn + loop.X_OMEGA, -1]) * rpm
    cols = {"cycle": np.full(t.size, k + 1), "time_s": t, "crank_angle_deg": np.degrees(theta),
            "speed_rpm": ys[nn + loop.X_OMEGA] * rpm, "governor_z_frac": np.zeros(t.size),
            "actuator_frac": np.zeros(t.size)}
    for end in ("head", "crank") if pressures else ():
        i = network.node(end)
        V = network.volume(i, theta)
        cols[f"p_{end}_Pa"] = steam.states(ys[2 * i] / V, ys[2 * i + 1] / ys[2 * i])[0]
    cols["valve_m"] = s["valve_m"]
    cols["eccentric_slip_deg"] = np.degrees(s["slip_rad"])
    return row, cols


def _to_fixed_frame(row: dict, frame: dict) -> None:
    """A turn run backward (the loop's angle, speed and torques in the direction of
    rotation) reported in the fixed frame: crank angle, speeds and torques negated."""
    for key in ("mean_speed_rpm", "speed_start_rpm", "speed_end_rpm"):
        if key in row:
            row[key] = -row[key]
    for key in ("crank_angle_deg", "speed_rpm", "indicated_torque_N_m", "load_torque_N_m"):
        if key in frame:
            frame[key] = -np.asarray(frame[key])


def _update_wall(network, y: np.ndarray) -> None:
    """With ``wall_heat``, each wall to the h A-weighted mean steam temperature of the
    turn just run (as the steady model does, see CrankResolved.update_wall); the array
    is the one the compiled loop reads."""
    if not any(row[0] > 0.0 for row in network.node_heat):
        return
    for i in range(network.n_nodes):
        ha = y[network.i_node_quad(i, "hA")]
        if ha > 0.0:
            network.wall_T[i] = y[network.i_node_quad(i, "hAT")] / ha


def _any_table():
    return load_table().arrays()


def _cycle_row(k: int, y0: np.ndarray, y: np.ndarray, network, tables: LoopTables, nn: int):
    """One turn's totals: speed, powers, steam, governor and what it set."""
    t0, t1 = y0[nn + loop.X_TIME], y[nn + loop.X_TIME]
    dt = t1 - t0
    w_gas = y[nn + loop.X_WGAS]
    row = {"cycle": k + 1, "t_start_s": t0, "t_end_s": t1,
           "mean_speed_rpm": TWO_PI / dt * 60.0 / TWO_PI,
           "speed_start_rpm": y0[nn + loop.X_OMEGA] * 60.0 / TWO_PI,
           "speed_end_rpm": y[nn + loop.X_OMEGA] * 60.0 / TWO_PI,
           "work_J": w_gas, "indicated_power_W": w_gas / dt,
           "load_work_J": y[nn + loop.X_WLOAD], "load_power_W": y[nn + loop.X_WLOAD] / dt,
           "friction_work_J": y[nn + loop.X_WFRIC],
           "governor_z_frac": y[nn + loop.X_ZDT] / dt, "governor_z_end_frac": y[nn + loop.X_Z]}
    totals = network.boundary_totals(y)
    row["m_supply_kg"] = totals["m_supply_kg"]
    for name, e in network.leak_edges():
        # each leakage path's mass over the turn, from its side a to its side b
        row[f"m_{name}_kg"] = y[network.i_edge_mass(e)]
    row["steam_rate_kg_per_h"] = totals["m_supply_kg"] / dt * 3600.0
    for i in (i for i, h in enumerate(network.node_heat) if h[H_MODEL] != WALL_NONE):
        # each end's heat over the turn: into the steam, and taken by the wall
        end = network.node_names[i]
        row[f"Q_{end}_J"] = y[network.i_node_quad(i, "heat")]
        row[f"Q_to_wall_{end}_J"] = y[network.i_node_quad(i, "heat_to_wall")]
    act = y[nn + loop.X_ADT] / dt
    mech = tables.mechanism
    if mech is not None:
        if mech.acts_on == "throttle":
            row["throttle_opening_frac"] = act
        else:
            row["gear_setting_frac"] = act
            assert tables.cutoff_table is not None      # tabulated for a governed gear
            head, crank = tables.cutoff_table.at(act)
            row["cutoff_head_frac"], row["cutoff_crank_frac"] = float(head), float(crank)
    return row


def _concat_columns(frames: list) -> pd.DataFrame:
    """One frame of the turns' columns (dicts of arrays), in order of first appearance; a
    column a turn lacks is NaN there (as ``pd.concat`` would): one frame built at the
    end, not one a turn (about a sixth of a 200-turn run's time went to those)."""
    names = list(dict.fromkeys(c for f in frames for c in f))
    cols = {}
    for c in names:
        cols[c] = np.concatenate([f[c] if c in f else np.full(len(f["cycle"]), np.nan)
                                  for f in frames])
    return pd.DataFrame(cols)


def _frame(network, steam, tables, out_theta, samples, rec, n_rec, record, nn):
    """The time-series columns of one turn, as arrays by name."""
    if record == "step":
        r = rec[:, :n_rec]
        return {"time_s": r[4], "crank_angle_deg": np.degrees(r[0]),
                "speed_rpm": r[1] * 60.0 / TWO_PI, "governor_z_frac": r[2],
                "actuator_frac": r[3], "indicated_torque_N_m": r[5],
                "load_torque_N_m": r[6]}
    s = samples
    omega = s[nn + loop.X_OMEGA]
    z = np.clip(s[nn + loop.X_Z], 0.0, 1.0)
    sc = tables.tr.sc
    cols = {"time_s": s[nn + loop.X_TIME], "crank_angle_deg": np.degrees(out_theta),
            "speed_rpm": omega * 60.0 / TWO_PI, "governor_z_frac": z,
            "actuator_frac": sc[loop.S_A0] + (sc[loop.S_A1] - sc[loop.S_A0]) * z}
    for end in ("head", "crank"):
        i = network.node(end)
        V = network.volume(i, out_theta)
        cols[f"p_{end}_Pa"] = steam.states(s[2 * i] / V, s[2 * i + 1] / s[2 * i])[0]
    return cols
