"""The mean-value model for long transients: the speed loop on maps of the engine.

The crank-resolved engine is run steady on a grid of (governor actuator value, speed)
once: at each point the mean indicated torque over a turn and the steam per turn.  The
transient then steps in time with the shaft and the governor only::

    I domega/dt = T_map(a(z), omega) - T_friction(omega) - T_load(t, omega)
    M z'' + 1/2 M' z'^2 = G (ratio omega)^2 - R - c z' - F_f sat(z'/v_e) - J ratio domega/dt

(the governor's common form, as in :mod:`corliss.engine.kernels.loop`, one equation of
motion for both: :func:`corliss.engine.kernels.governor.governor_motion`; stops at 0
and 1 are held by clipping).  The maps are read bilinearly in the actuator and in
speed, the engine's torque being smooth in both away from the trip's limit.  What the
mean-value model leaves out is everything inside a turn: the torque's fluctuation (and
with it the flywheel's coefficient of steadiness), the chest's filling lag behind a
throttle, and the wait until the next cut-off for a new setting to act.  It is the
period's own picture of governing (Marks Arts. 62, 97), at a small fraction of the
cost for runs of many minutes.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time

import numpy as np
import pandas as pd

from corliss.engine.ivp_events import terminal_event
from corliss.engine.kernels.governor import governor_motion
from corliss.engine.model import at_knob, geometry_of, steady_scene
from corliss.governors.operating_point import OperatingPoint, find_operating_point
from corliss.engine.result import TransientResult
from corliss.engine.steady import run_steady
from corliss.governors import governor_type
from corliss.governors.mechanism import CREEP_PER_S

log = logging.getLogger(__name__)
TWO_PI = 2.0 * math.pi
#: Grid of the maps: actuator values across the governor's range, and speeds as
#: fractions of the run's speed.
ACTUATOR_POINTS = 9
SPEED_FRACTIONS = (0.8, 0.9, 1.0, 1.1, 1.2)


@dataclasses.dataclass
class EngineMap:
    """Mean indicated torque and steam per turn on (actuator, speed) grids.

    Parameters
    ----------
    actuator : ndarray
        The actuator's values [-] (throttle opening or gear setting), increasing;
        shape (na,).
    speed_rad_s : ndarray
        The speeds [rad/s], increasing; shape (nw,).
    torque_N_m : ndarray
        Mean indicated torque over a turn [N m]; shape (na, nw).
    steam_kg : ndarray
        Steam from the supply per turn [kg]; shape (na, nw).
    cutoff_head_frac : ndarray
        The head end's cut-off at the middle speed [-], as a fraction of the stroke;
        shape (na,), NaN for a throttle (or no governor).
    build_s : float
        Wall time spent building the maps [s].
    """

    actuator: np.ndarray
    speed_rad_s: np.ndarray
    torque_N_m: np.ndarray      # (actuator, speed)
    steam_kg: np.ndarray        # (actuator, speed)
    cutoff_head_frac: np.ndarray  # (actuator,), nan for a throttle
    build_s: float

    def at(self, a: float, w: float) -> tuple[float, float]:
        """Torque and steam per turn by bilinear interpolation, held at the grid's edges.

        Parameters
        ----------
        a : float
            Actuator value [-].
        w : float
            Shaft speed [rad/s].

        Returns
        -------
        torque : float
            Mean indicated torque [N m].
        steam : float
            Steam per turn [kg].
        """
        i, fa = _cell(self.actuator, a)
        j, fw = _cell(self.speed_rad_s, w)
        def bil(tab):
            return ((1 - fa) * ((1 - fw) * tab[i, j] + fw * tab[i, j + 1])
                    + fa * ((1 - fw) * tab[i + 1, j] + fw * tab[i + 1, j + 1]))
        return bil(self.torque_N_m), bil(self.steam_kg)


def _cell(grid: np.ndarray, x: float):
    n = grid.size
    k = int(np.clip(np.searchsorted(grid, x) - 1, 0, n - 2))
    f = (x - grid[k]) / (grid[k + 1] - grid[k])
    return k, min(max(f, 0.0), 1.0)


def build_map(scene, mech) -> EngineMap:
    """Build the maps from steady crank-resolved runs on the grid.

    :data:`ACTUATOR_POINTS` actuator values across the governor's range (without a
    governor, two points at the scene's own gear and throttle) by
    :data:`SPEED_FRACTIONS` of the run's speed, each run steady with the scene's effects
    and fidelity.

    Parameters
    ----------
    scene : Scene
        The transient scene.
    mech : GovernorMechanism or None
        The governor in its common form: what it acts on (``throttle`` or the gear's
        ``setting``) and its actuator's range; None for a free engine.

    Returns
    -------
    EngineMap
        The maps.
    """
    t0 = time.perf_counter()
    knob = "throttle" if mech is not None and mech.acts_on == "throttle" else "setting"
    if mech is None:
        acts = np.array([0.0, 1.0])
    else:
        lo, hi = mech.actuator_range()
        acts = np.linspace(lo, hi, ACTUATOR_POINTS)
    speeds = np.array(SPEED_FRACTIONS) * scene.run.speed_rad_s
    torque = np.empty((acts.size, speeds.size))
    steam = np.empty_like(torque)
    cut = np.full(acts.size, np.nan)
    steady = dataclasses.replace(scene, run=dataclasses.replace(scene.run, model="crank_resolved"))
    for i, a in enumerate(acts):
        if mech is None:        # no governor: the scene's own gear and throttle
            base = steady_scene(steady)
        else:
            base = at_knob(steady, knob, float(max(a, 1e-3) if knob == "throttle" else a))
        for j, w in enumerate(speeds):
            sc = dataclasses.replace(base, run=dataclasses.replace(base.run, speed_rad_s=float(w)))
            s = run_steady(sc).summary
            torque[i, j] = s["indicated_power_W"] / w
            steam[i, j] = s["steam_rate_kg_per_h"] / 3600.0 * TWO_PI / w
            if knob == "setting" and mech is not None and j == speeds.size // 2:
                c = s["events"]["head"]["cutoff_frac"]
                cut[i] = np.nan if c is None else c
    return EngineMap(acts, speeds, torque, steam, cut, time.perf_counter() - t0)


def run_mean_value(scene, *, progress=None) -> TransientResult:
    """Run a transient scene on the mean-value model.

    Parameters
    ----------
    scene : Scene
        ``run.mode = "transient"``, ``run.model = "mean_value"``.
    progress : callable, optional
        Called with (simulated time [s], duration [s]).

    Returns
    -------
    TransientResult
        The same tables as the crank-resolved loop (per-turn table, time series of speed
        and governor), without cylinder pressures.
    """
    t_wall = time.perf_counter()
    gov = None
    mech = None
    if scene.governor is not None:
        gov = governor_type(scene.governor_type).build(scene.governor)
        mech = gov.mechanism(201)
    emap = build_map(scene, mech)
    eng, load, run = scene.engine, scene.load, scene.run
    I = scene.flywheel.inertia_kg_m2
    fric = run.has("friction")
    w_ref = run.speed_rad_s
    k_law = load.speed_exponent
    lt, lf = np.asarray(load.times_s), np.asarray(load.fractions)
    if mech is not None:
        zg = np.asarray(mech.z)
        tabs = [np.asarray(v) for v in (mech.M, mech.dM_dz, mech.G, mech.R, mech.J)]

    def actuator(z):
        return 0.0 if mech is None else float(mech.actuator(min(max(z, 0.0), 1.0)))

    def torques(t, w, z):
        tg, _ = emap.at(actuator(z), w)
        tl = load.torque_N_m * float(np.interp(t, lt, lf)) * (w / w_ref) ** k_law
        tf = (eng.friction_torque_N_m + eng.friction_N_m_s * w) if fric else 0.0
        return tg, tl, tf

    def rhs(t, y):
        th, w, z, zd, wg_, wl_, wf_ = y
        tg, tl, tf = torques(t, w, z)
        wdot = (tg - tl - tf) / I
        out = [w, wdot, 0.0, 0.0, tg * w, tl * w, tf * w]
        if mech is not None:
            zc = min(max(z, 0.0), 1.0)
            M, dM, G, R, J = (float(np.interp(zc, zg, tab)) for tab in tabs)
            out[2], out[3] = governor_motion.py_func(z, zd, M, dM, G, R, J, mech.ratio, mech.c,
                                                     mech.F_f, CREEP_PER_S, w, wdot)
        return out

    start = OperatingPoint(w_ref, mech.equilibrium_z(w_ref) if mech is not None else 0.0,
                           math.nan, "run_speed", 0)
    if mech is not None and run.start == "equilibrium":
        def surplus(w, z):
            tg, tl, tf = torques(0.0, w, z)
            return tg - tl - tf

        start = find_operating_point(surplus, mech, load.torque_N_m * float(lf[0]))
    z0 = start.governor_z
    y0 = np.array([0.0, start.speed_rad_s, z0, 0.0, 0.0, 0.0, 0.0])
    t_int = time.perf_counter()

    def stalled(t, y):
        return y[1] - 0.05 * w_ref
    terminal_event(stalled, -1)
    # scipy at its one point of use: every run imports this module through
    # corliss.engine.simulate, and only the mean-value model integrates with scipy
    from scipy.integrate import solve_ivp
    sol = solve_ivp(rhs, (0.0, run.duration_s), y0, method="LSODA", rtol=min(run.fidelity.rtol, 1e-6),
                    atol=np.array([1e-6, 1e-6 * w_ref, 1e-7, 1e-6, 1e-3, 1e-3, 1e-3]),
                    events=stalled, dense_output=True)
    t_end = float(sol.t[-1])
    # turns: where the crank angle passes each multiple of 2 pi (theta rises with t)
    tg = np.linspace(0.0, t_end, max(2000, int(50 * t_end * w_ref / TWO_PI)))
    yg = sol.sol(tg)
    n_turns = int(yg[0, -1] // TWO_PI)
    edges = np.interp(TWO_PI * np.arange(n_turns + 1), yg[0], tg)
    ye = sol.sol(edges)
    rows = []
    for k in range(n_turns):
        t0, t1 = edges[k], edges[k + 1]
        dt = t1 - t0
        z_a, z_b = np.clip(ye[2, k], 0, 1), np.clip(ye[2, k + 1], 0, 1)
        w_mean = TWO_PI / dt
        a_mean = actuator(0.5 * (z_a + z_b))
        _, steam = emap.at(a_mean, w_mean)
        work = ye[4:7, k + 1] - ye[4:7, k]
        row = {"cycle": k + 1, "t_start_s": t0, "t_end_s": t1,
               "mean_speed_rpm": w_mean * 30 / math.pi,
               "speed_start_rpm": ye[1, k] * 30 / math.pi, "speed_end_rpm": ye[1, k + 1] * 30 / math.pi,
               "work_J": work[0], "indicated_power_W": work[0] / dt,
               "load_work_J": work[1], "load_power_W": work[1] / dt, "friction_work_J": work[2],
               "governor_z_frac": 0.5 * (z_a + z_b), "governor_z_end_frac": z_b,
               "m_supply_kg": steam, "steam_rate_kg_per_h": steam / dt * 3600.0}
        if mech is not None:
            if mech.acts_on == "throttle":
                row["throttle_opening_frac"] = a_mean
            else:
                row["gear_setting_frac"] = a_mean
                row["cutoff_head_frac"] = float(np.interp(a_mean, emap.actuator,
                                                          emap.cutoff_head_frac))
        rows.append(row)
    cycle = np.clip(np.searchsorted(edges, tg, side="right"), 1, max(n_turns, 1))
    z = np.clip(yg[2], 0.0, 1.0)
    series = pd.DataFrame({"cycle": cycle, "time_s": tg, "crank_angle_deg": np.degrees(yg[0]),
                           "speed_rpm": yg[1] * 30 / math.pi, "governor_z_frac": z,
                           "actuator_frac": mech.actuator(z) if mech is not None else 0.0 * z})
    log.info("mean-value model: maps %.2f s, integration %.2f s (%d evaluations)",
             emap.build_s, time.perf_counter() - t_int, sol.nfev)
    if progress:
        progress(t_end, run.duration_s)
    result = TransientResult(scene=scene, property_tier=scene.run.fidelity.properties,
                             timeseries=series, cycles=pd.DataFrame(rows),
                             rhs_evaluations=int(sol.nfev),
                             wall_time_s=time.perf_counter() - t_wall,
                             geometry=geometry_of(scene), stalled=sol.status == 1,
                             mechanism=mech, z_start=z0, engine_map=emap, start=start)
    return result
