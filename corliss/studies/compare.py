"""Throttling against cut-off governing: one engine governed both ways across its load.

A governor meets a lighter load either by closing a throttle in the steam pipe, the
cut-off fixed, or by shortening the cut-off, the throttle wide open.  On the card the
second wins: the steam is expanded further instead of being wire-drawn (Marks,
*Relative Proportions of the Steam-Engine*, Art. 2).  But the shorter the cut-off the
larger the initial condensation (Marks Arts. 74-75), which eats into that advantage,
and for a small engine may reverse it.  This study runs both: from one scene's
engine, a throttled variant at a fixed gear setting and a cut-off variant at full
throttle, each at a series of loads, with and without the wall-heat effect.

At each load the operating point is the throttle opening or gear setting that gives
the engine that power at the scene's speed: a root of power against the knob,
bracketed on a grid of the knob, solved on the ``fast`` tier and refined on the
scene's.  The runs go to the process's kept pool of workers
(:mod:`corliss.studies.pool`, as a study's do), one on every core unless told.

Both variants keep the same steam chest and pipe: the scene's, or when the scene has
none, a chest of :data:`DEFAULT_CHEST_OF_SWEPT` of the swept volume and a pipe sized
for :data:`PIPE_STEAM_SPEED_M_S` at the mean piston speed.  A chest charges between
admissions and then expands into the cylinder like an early cut-off; that is real, and
the table shows it (``chest_pressure_admission_Pa``).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import os
import time
from typing import Any

import numpy as np
import pandas as pd

from corliss.engine.model import at_knob, build_gear, geometry_of, steady_scene
from corliss.engine.result import willans_fit
from corliss.engine.steady import run_steady
from corliss.engine.summary_keys import end_value
from corliss.errors import InputError, RunError
from corliss.governors import GOVERNORS
from corliss.governors.operating_point import characteristic_speed, working_travel
from corliss.logs import at_point
from corliss.progress import progress_for
from corliss.studies.compare_result import CompareResult
from corliss.studies.pool import prestart, run_tasks

log = logging.getLogger(__name__)
TWO_PI = 2.0 * math.pi

__all__ = ["VARIANTS", "compare", "variants", "DEFAULT_LOADS"]

#: The two governings, in the order of the tables.
VARIANTS = ("throttling", "cutoff")
#: Loads of the study, as fractions of the rated power [-].
DEFAULT_LOADS = tuple(round(0.1 * i, 10) for i in range(1, 12))
#: A chest added when the scene has none, as a fraction of the head end's swept volume
#: (a slide-valve chest of the period held some tenth of the cylinder; the Watt scene's
#: 0.2 ft3 is 13 %).
DEFAULT_CHEST_OF_SWEPT = 0.10
#: Steam speed in the supply pipe at the mean piston speed when the scene gives no pipe
#: [m/s]: the rule of the time, 6000 ft/min (Kent, *Mechanical Engineers' Pocket-Book*,
#: "Steam pipes"), the pipe's area = piston area x piston speed / 6000 ft/min.
PIPE_STEAM_SPEED_M_S = 6000.0 * 0.3048 / 60.0
#: Knob values of the grid that brackets each operating point [-].
GRID_POINTS = 9
#: The grid of each variant is run as this many chains of neighbouring knobs (a chain
#: is one task; its runs start each where the last ended).
GRID_CHAINS = 2
#: Least throttle opening the study tries [-] (a shut throttle runs no engine); the
#: grid of openings is geometric, the power changing most at small openings.
LEAST_OPENING = 0.005
#: The refined operating point's power is within this fraction of the asked power [-].
POWER_TOL = 0.003
#: The fast tier's root is within this fraction of the asked power [-].
FAST_TOL = 0.002
#: Most refinement steps on the scene's tier.
MAX_REFINE = 5


@dataclasses.dataclass(frozen=True)
class Variant:
    """One governing of the engine.

    Parameters
    ----------
    name : str
        ``"throttling"`` or ``"cutoff"``.
    knob : str
        The knob the governor works: ``"throttle"`` or ``"setting"``.
    knob_range : (float, float)
        Its range [-].
    scene : Scene
        The steady scene with the other knob fixed (throttle wide open, or the gear at
        the throttled variant's setting).
    fixed : float
        The other knob's value [-].
    """

    name: str
    knob: str
    knob_range: tuple[float, float]
    scene: object
    fixed: float


def _with_chest(scene, chest_volume_m3: float | None, pipe_diameter_m: float | None):
    """The scene with a steam chest and pipe (its own, or the defaults)."""
    sup = scene.supply
    geo = geometry_of(scene)
    vol = chest_volume_m3 or sup.chest_volume_m3 or DEFAULT_CHEST_OF_SWEPT * float(geo.swept_m3[0])
    if pipe_diameter_m is None and sup.pipe_diameter_m is None:
        piston_speed = 2.0 * scene.engine.stroke_m * scene.run.speed_rad_s / (2.0 * math.pi)
        area = math.pi / 4.0 * scene.engine.bore_m ** 2 * piston_speed / PIPE_STEAM_SPEED_M_S
        pipe_diameter_m = math.sqrt(4.0 * area / math.pi)
    pipe = pipe_diameter_m or sup.pipe_diameter_m
    effects = tuple(dict.fromkeys(scene.run.effects + ("steam_chest",)))
    sc = scene.replace_run(effects=effects)
    return dataclasses.replace(sc, supply=dataclasses.replace(
        sup, chest_volume_m3=vol, pipe_diameter_m=pipe, throttle=1.0))


def _with_wall_heat(scene, on: bool):
    eff = tuple(e for e in scene.run.effects if e != "wall_heat")
    return scene.replace_run(effects=eff + (("wall_heat",) if on else ()))


def variants(scene, *, throttled_setting: float | None = None,
             setting_range: tuple[float, float] | None = None,
             chest_volume_m3: float | None = None,
             pipe_diameter_m: float | None = None) -> dict[str, Variant]:
    """The throttled and the cut-off-governed variants of ``scene``'s engine.

    Parameters
    ----------
    scene : Scene
        Any scene whose gear has a setting (the cut-off variant works it).
    throttled_setting : float, optional
        The gear setting the throttled variant keeps [-] (default: the scene's).
    setting_range : (float, float), optional
        The settings the cut-off governor may use [-] (default: the gear's range).
    chest_volume_m3, pipe_diameter_m : float, optional
        Steam chest [m3] and pipe [m] of both variants (default: the scene's, else
        :data:`DEFAULT_CHEST_OF_SWEPT` of the swept volume and a pipe for
        :data:`PIPE_STEAM_SPEED_M_S`).

    Returns
    -------
    dict of str to Variant
        ``"throttling"``: the throttle as knob over [:data:`LEAST_OPENING`, 1], the gear
        at ``throttled_setting``; ``"cutoff"``: the gear setting as knob over
        ``setting_range``, the throttle wide open.  Both with the steam chest and pipe.

    Raises
    ------
    InputError
        A gear without a setting, or a setting out of the gear's range.
    """
    base = steady_scene(scene)
    gear = build_gear(base)
    if gear.setting_range is None:
        raise InputError("valve_gear.type", scene.gear_type, "a gear with a setting (cut-off "
                         "governing works it); the throttled engine alone is `corliss sweep "
                         "--throttle`")
    lo, hi = gear.setting_range
    rng = tuple(float(v) for v in (setting_range or (lo, hi)))
    if not (lo <= min(rng) < max(rng) <= hi):
        raise InputError("--setting-range", rng, f"two settings from {lo} to {hi}")
    fixed = float(gear.spec.setting if throttled_setting is None else throttled_setting)
    if not lo <= fixed <= hi:
        raise InputError("--throttled-setting", fixed, f"a setting from {lo} to {hi}")
    for v, key in ((chest_volume_m3, "chest_volume_m3"), (pipe_diameter_m, "pipe_diameter_m")):
        if v is not None and not v > 0:
            raise InputError(key, v, "a positive size")
    base = _with_chest(base, chest_volume_m3, pipe_diameter_m)
    thr = at_knob(base, "setting", fixed)
    return {"throttling": Variant("throttling", "throttle", (LEAST_OPENING, 1.0), thr, fixed),
            "cutoff": Variant("cutoff", "setting", (min(rng), max(rng)), base, 1.0)}


# --- one steady run, and the rows made of it ---------------------------------------------

def _run(scene, knob: str, value: float, tier: str | None, start=None) -> dict | None:
    """One steady run's figures (None if the run stopped), started from ``start`` (a
    :class:`~corliss.engine.steady.SteadyStart`) when given; ``final_state`` in the row
    is where it ended, the start of the next run nearby."""
    sc = at_knob(scene, knob, value)
    if tier is not None:
        sc = sc.with_fidelity(tier)
    try:
        r = run_steady(sc, start=start)
    except RunError as exc:
        log.debug("%s at %s: %s", knob, value, exc)
        return None
    s = r.summary
    ts = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    adm = s["events"]["head"].get("admission_deg")
    p_adm = float("nan")
    if adm is not None and "p_chest_Pa" in ts:
        ang = np.mod(ts["crank_angle_deg"].to_numpy(), 360.0)
        ang, idx = np.unique(ang, return_index=True)
        p_adm = float(np.interp(adm, ang, ts["p_chest_Pa"].to_numpy()[idx], period=360.0))
    miss = [m for end in ("head", "crank")
            if (m := end_value(s, "missing_water_fraction", end)) is not None]
    # a jacket is paid for in steam (Marks Art. 79): the study counts it with the feed
    steam = s["steam_rate_kg_per_h"] + s.get("jacket_steam_kg_per_h", 0.0)
    power_kW = s["indicated_power_W"] / 1e3
    return {"indicated_power_W": s["indicated_power_W"],
            "brake_power_W": s.get("brake_power_W", s["indicated_power_W"]),
            "steam_rate_kg_per_h": steam,
            "water_rate_kg_per_kWh": steam / power_kW if power_kW > 0 else float("nan"),
            "cutoff_head_frac": s["events"]["head"]["cutoff_frac"],
            "chest_pressure_admission_Pa": p_adm,
            "missing_water_frac": float(np.mean(miss)) if miss else float("nan"),
            "rhs_evaluations": r.rhs_evaluations, "final_state": r.final_state}


def _power(row: dict | None, brake: bool) -> float:
    if row is None:
        return float("nan")
    return row["brake_power_W" if brake else "indicated_power_W"]


def _grid_task(scene, knob, values):
    """Steady runs at a run of neighbouring knob ``values`` on the fast tier, each
    started where the one before ended: [(value, row)]."""
    out, last = [], None
    for value in values:
        row = _run(scene, knob, value, "fast", last)
        if row is not None:
            last = row["final_state"]
        out.append((value, row))
    return out


def _point_task(scene, knob, bracket, target_W, brake, tier, guess=None, exact=True,
                wider=None, start=None):
    """The operating point at ``target_W``: a bracketed root on the fast tier (the first
    trial at ``guess``, the root of the grid's interpolant), refined by secant steps on
    the scene's tier (``tier`` None: the fast root is final).  ``exact`` False: the
    bracket's powers are estimates (the grid ran at another speed); they are run at this
    scene's speed if the root is not found inside them, and ``wider`` (the neighbouring
    grid knobs) if it is not between them either.  Each run starts where the one before
    it ended (the first, from ``start``: the grid's run nearest the guess), so the walls
    settle once, not at every trial."""
    (a, pa), (b, pb) = bracket
    lo_k, hi_k = min(a, b), max(a, b)
    slope = (pb - pa) / (b - a)
    runs = 0
    cache = {}
    tol = FAST_TOL * abs(target_W)
    last = start

    def f(k):
        nonlocal runs, last
        runs += 1
        row = _run(scene, knob, k, "fast", last)
        cache[k] = row
        if row is not None:
            last = row["final_state"]
        p = _power(row, brake)
        if not math.isfinite(p):
            raise RunError(f"{knob} {k}: the run stopped")
        return p - target_W

    def illinois(a, fa, b, fb, guess):
        """Regula falsi, Illinois-modified: a bracketing root to FAST_TOL of the power."""
        k, fk = (a, fa) if abs(fa) < abs(fb) else (b, fb)
        if guess is not None and lo_k < guess < hi_k and abs(fk) > tol:
            k, fk = guess, f(guess)
            if fk * fa > 0:
                a, fa, b, fb = b, fb, k, fk      # the newest point is b, as below
            else:
                b, fb = k, fk
        for _ in range(40):
            if abs(fk) <= tol or fa == fb:
                break
            k = b - fb * (b - a) / (fb - fa)
            fk = f(k)
            if fk * fb < 0:
                a, fa = b, fb
            else:
                fa = fa / 2.0
            b, fb = k, fk
        return k, fk

    k, fk = illinois(a, pa - target_W, b, pb - target_W, guess)
    if abs(fk) > tol and not exact:
        fa, fb = f(a), f(b)
        if fa * fb > 0 and wider is not None:
            # the root moved past an end with the speed: beyond the end nearer the
            # power asked, out to the neighbouring grid knob on that side
            near, f_near = (a, fa) if abs(fa) < abs(fb) else (b, fb)
            far = max(wider) if near == max(a, b) else min(wider)
            a, fa, b = near, f_near, far
            lo_k, hi_k = min(lo_k, *wider), max(hi_k, *wider)
            fb = f(b) if b != a else fa
        if fa * fb > 0:
            raise RunError(f"no {knob} gives {target_W:.6g} W at this speed")
        k, fk = illinois(a, fa, b, fb, k)
    row = cache.get(k) or _run(scene, knob, k, "fast", last)
    if row is not None:
        last = row["final_state"]
    if tier is not None and tier != "fast":
        pts = []
        for _ in range(MAX_REFINE):
            row = _run(scene, knob, k, tier, last)
            runs += 1
            if row is not None:
                last = row["final_state"]
            err = _power(row, brake) - target_W
            if not math.isfinite(err):
                raise RunError(f"{knob} {k}: the run stopped on the {tier} tier")
            pts.append((k, err))
            if abs(err) <= POWER_TOL * abs(target_W):
                break
            if len(pts) >= 2 and pts[-1][1] != pts[-2][1]:
                slope = (pts[-1][1] - pts[-2][1]) / (pts[-1][0] - pts[-2][0])
            k = float(np.clip(k - err / slope, lo_k, hi_k))
    return k, row, runs


def _map(tasks, workers: int, progress, done0: int, total: int, warm=None):
    """Run ``tasks`` [(fn, args, label)] on ``workers`` processes of the kept pool
    (here, serially, when 1); results in order, an exception in place of a task's
    result when it failed.  The messages of each task name its point, ``label``."""
    out = [None] * len(tasks)
    done = done0

    def collect(i, result):
        nonlocal done
        out[i] = result
        done += 1
        if progress:
            progress(done, total)

    if workers <= 1 or len(tasks) <= 1:
        for i, (fn, args, label) in enumerate(tasks):
            collect(i, _safe(label, fn, *args))
    else:
        run_tasks([(_safe, (label, fn, *args)) for fn, args, label in tasks], workers,
                  collect, warm=warm)
    return out, done


def _guess(curve, bracket, target_W):
    """The knob where the monotone cubic through the grid's powers gives ``target_W``
    (None if it cannot be had): the operating point's first trial."""
    from scipy.interpolate import PchipInterpolator
    from scipy.optimize import brentq

    k = np.array([c[0] for c in curve])
    p = np.array([c[1] for c in curve])
    ok = np.isfinite(p)
    k, p = k[ok], p[ok]
    order = np.argsort(k)
    k, p = k[order], p[order]
    if len(k) < 3 or np.any(np.diff(k) <= 0):
        return None
    try:
        f = PchipInterpolator(k, p - target_W)
        (a, _), (b, _) = bracket
        return float(brentq(f, min(a, b), max(a, b), xtol=1e-9))
    except ValueError:
        return None


def _group_label(key) -> str:
    """A group's name for a message: its variant, and whether its walls take heat."""
    name, walled = key
    return f"{name}, {'with' if walled else 'without'} condensation"


def _safe(label, fn, *args):
    try:
        with at_point(label):
            return fn(*args)
    except (RunError, ValueError) as exc:
        return exc


def droop_speeds(scene, loads) -> dict[float, float] | None:
    """The shaft speed the scene's governor holds at each load.

    The governor balances along its static characteristic (Marks Art. 70), at the
    bottom of its working travel under full load and at the top with none, so the speed
    falls linearly with the load across the governor's range (its droop), full load at
    the slowest.  Loads beyond 1 extrapolate the line.

    Parameters
    ----------
    scene : Scene
        The scene; its governor (if any) gives the characteristic.
    loads : iterable of float
        Loads as fractions of the rated power [-].

    Returns
    -------
    dict or None
        The speed at each load [rad/s], keyed by the load (float to float); None when
        the scene has no governor.
    """
    if scene.governor is None or scene.governor_type is None:
        return None
    mech = GOVERNORS[scene.governor_type].build(scene.governor).mechanism(201)
    z_lo, z_hi = working_travel(mech)
    w_lo, w_hi = sorted(characteristic_speed(mech, z) for z in (z_lo, z_hi))
    return {load: w_hi - (w_hi - w_lo) * load for load in loads}


def rated_power_W(scene, brake: bool) -> float | None:
    """The scene's rated power: its reference load, at full load (load fraction 1).

    The ``[load]`` section's torque or power is the reference load; its schedule's
    fractions are of it (a step from 50 % to 80 % starts at fraction 0.5), so full
    load is fraction 1 whatever the schedule's first fraction.

    Parameters
    ----------
    scene : Scene
        The scene; its load's reference torque and the run's speed are read.
    brake : bool
        Whether the study compares brake power (the ``friction`` effect named); the
        load's torque x speed is the power either way, so it does not change the value.

    Returns
    -------
    float or None
        ``reference torque x speed`` [W] (the ``power`` given, when the load was
        given as one), or None when the scene has no load.
    """
    if scene.load is None:
        return None
    return scene.load.torque_N_m * scene.run.speed_rad_s


def compare(scene, loads=DEFAULT_LOADS, *, condensation: str = "both",
            fidelity: str | None = None, workers: int | None = None, droop: bool = False,
            progress: Any = None, **variant_options):
    """Run the throttling-versus-cut-off study of ``scene``'s engine.

    Parameters
    ----------
    scene : Scene
        A scene whose gear has a setting; a transient one is run steady at its speed.
    loads : sequence of float
        Loads as fractions of the rated power [-]: the scene's reference load at
        fraction 1 (:func:`rated_power_W`; brake power when ``friction`` is named, else
        indicated), or without a load, the throttled variant's power wide open.
    condensation : str
        ``"both"``, ``"on"`` or ``"off"``: with the ``wall_heat`` effect, without, or
        both.
    fidelity : str, optional
        The tier the operating points are refined on (default: the scene's).
    workers : int, optional
        Processes (default: every core; 1 runs here, in this process).  The runs go
        to the process's kept pool (:mod:`corliss.studies.pool`), as a study's do:
        Ctrl-C ends its workers at once.
    droop : bool
        False (default): every load at the scene's speed, so the two governings are
        compared at one speed and differ only in how they meet the load (the summary's
        ``speed_basis`` is ``"constant"``).  True, with a governor in the scene: each
        load at a speed on the governor's static characteristic, full load at the
        bottom of its working travel (:func:`droop_speeds`; ``"governor_droop"``), an
        assumption about where the governor sits that a transient run of the scene
        need not share.
    progress : None, True, ProgressBar or callable, optional
        True draws a bar (:mod:`corliss.progress`); a callable is called with (runs
        done, runs in all).  Each run's messages name its variant and load.
    **variant_options
        ``throttled_setting``, ``setting_range``, ``chest_volume_m3``,
        ``pipe_diameter_m`` (see :func:`variants`); by default the scene's ``[compare]``
        section's.

    Returns
    -------
    CompareResult
        One row per variant, condensation and load: the knob at the operating point
        (``knob_frac``), power, steam and water rates, cut-off, chest pressure at
        admission, missing water, or ``status = "unreached"``.

    Raises
    ------
    InputError
        Loads outside (0, 2], an unknown ``condensation``, or what :func:`variants`
        refuses.
    """
    t0 = time.perf_counter()
    loads = [float(v) for v in loads]
    if not loads or any(not (0.0 < v <= 2.0) for v in loads):
        raise InputError("--loads", loads, "fractions of the rated power above 0, up to 2")
    if condensation not in ("both", "on", "off"):
        raise InputError("--with-condensation", condensation, "both, on or off")
    if fidelity is not None:
        scene = scene.with_fidelity(fidelity)
    tier = scene.run.fidelity.name
    if scene.compare is not None:       # the scene's [compare] section, unless overridden
        for k, v in dataclasses.asdict(scene.compare).items():
            if v is not None:
                variant_options.setdefault(k, v)
    chest_source = ("compare" if variant_options.get("chest_volume_m3") is not None else
                    "scene" if scene.supply.chest_volume_m3 is not None else "default")
    var = variants(scene, **variant_options)
    conds = {"both": (False, True), "on": (True,), "off": (False,)}[condensation]
    brake = scene.run.has("friction")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise InputError("--jobs", workers, "a whole number of processes, 1 or more")
    workers = workers or os.cpu_count() or 1
    speeds = droop_speeds(scene, loads) if droop else None

    groups = {}
    for v in var.values():
        for c in conds:
            groups[(v.name, c)] = dataclasses.replace(v, scene=_with_wall_heat(v.scene, c))
    prestart(workers, lambda: _warm_scenes(groups), (__name__,))
    # the full-power run of each group sets the rated power when the scene has no load
    rated = rated_power_W(scene, brake)
    grid_tasks, grid_keys = [], []
    # each group's grid in GRID_CHAINS runs of neighbouring knobs, the walled groups
    # (whose walls settle slowly, and settle once a chain) first
    for key, v in sorted(groups.items(), key=lambda kv: not kv[0][1]):
        grid = (np.geomspace if v.knob == "throttle" else np.linspace)(*v.knob_range,
                                                                       GRID_POINTS)
        for chain in np.array_split(grid, GRID_CHAINS):
            grid_tasks.append((_grid_task, (v.scene, v.knob, [float(k) for k in chain]),
                               f"{_group_label(key)}, {v.knob} {chain[0]:g} to {chain[-1]:g}"))
            grid_keys.append(key)
    total = len(grid_tasks) + len(groups) * len(loads)
    # the kept pool for both rounds: a worker pays its imports and steam table once
    with progress_for(progress, "runs") as bar:
        result = _solve(scene, loads, var, groups, grid_tasks, grid_keys, rated, brake,
                        tier, workers, bar, total, t0, speeds)
    result.chest_source = chest_source
    return result


def _warm_scenes(groups):
    """One scene of each kernel version the grids run first (the ``fast`` tier, walls
    that take heat and walls that do not), a cycle each: for the pool's forkserver to
    load before its first fork."""
    seen, out = set(), []
    for (_, walled), v in groups.items():
        if walled not in seen:
            seen.add(walled)
            out.append(v.scene.with_fidelity("fast").replace_run(cycles=1))
    return out


def _solve(scene, loads, var, groups, grid_tasks, grid_keys, rated, brake, tier, workers,
           progress, total, t0, speeds):
    """The two rounds of :func:`compare`: the knob grids, then the operating points."""
    conds = sorted({c for _, c in groups})
    grid, done = _map(grid_tasks, workers, progress, 0, total)
    curves = {key: [] for key in groups}
    states = {key: {} for key in groups}
    runs = GRID_POINTS * len(groups)
    for key, chain in zip(grid_keys, grid):
        if isinstance(chain, Exception):
            continue
        for k, row in chain:
            if row is not None:
                curves[key].append((k, _power(row, brake)))
                states[key][k] = row["final_state"]
    for key in curves:
        curves[key].sort()
    if rated is None:
        p = [pw for k, pw in curves[("throttling", False if False in conds else True)]]
        rated = max(p) if p else float("nan")

    point_tasks, point_keys = [], []
    for key, v in groups.items():
        curve = curves[key]
        for load in loads:
            target = load * rated
            sc, crv = v.scene, curve
            if speeds is not None:
                # at the governor's speed for this load; the grid's powers scaled to it
                # (the work of a turn changes little with a few per cent of speed)
                w = speeds[load]
                sc = v.scene.replace_run(speed_rad_s=w)
                crv = [(k, p * w / scene.run.speed_rad_s) for k, p in curve]
            bracket = wider = None
            for i, ((k0, p0), (k1, p1)) in enumerate(zip(crv, crv[1:])):
                if (p0 - target) * (p1 - target) <= 0 and p0 != p1:
                    bracket = ((k0, p0), (k1, p1))
                    wider = (crv[max(i - 1, 0)][0], crv[min(i + 2, len(crv) - 1)][0])
                    break
            point_keys.append((key, load, target, bracket))
            if bracket is not None:
                guess = _guess(crv, bracket, target)
                near = min(states[key], key=lambda kk: abs(kk - (
                    guess if guess is not None else bracket[0][0])))
                point_tasks.append((_point_task, (sc, v.knob, bracket, target, brake,
                                                  None if tier == "fast" else tier,
                                                  guess, speeds is None, wider,
                                                  states[key][near]),
                                    f"{_group_label(key)} at {100 * load:g} % load"))
    found, _ = _map(point_tasks, workers, progress, done, total)
    found = iter(found)
    rows = []
    for (name, cond), load, target, bracket in point_keys:
        v = groups[(name, cond)]
        base = {"load_frac": load, "variant": name, "condensation": "on" if cond else "off",
                "knob": v.knob,
                "speed_rpm": (speeds[load] if speeds else scene.run.speed_rad_s) * 60 / TWO_PI,
                "target_power_W": target}
        res = next(found) if bracket is not None else None
        if bracket is None or isinstance(res, Exception) or res[1] is None:
            why = ("beyond the engine's reach" if bracket is None else f"no steady run: {res}")
            log.info("%s, condensation %s, load %.2f: %s", name, base["condensation"], load, why)
            rows.append({**base, "status": "unreached", "knob_frac": float("nan")})
            continue
        k, row, n = res
        runs += n
        row = dict(row)
        row.pop("rhs_evaluations", None)
        row.pop("final_state", None)
        if not brake:
            row.pop("brake_power_W", None)
        got = row["brake_power_W" if brake else "indicated_power_W"]
        rows.append({**base, "status": "found", "knob_frac": k, **row,
                     "power_error_frac": (got - target) / target})
    points = pd.DataFrame(rows)
    return CompareResult(scene=scene, property_tier=scene.run.fidelity.properties,
                         timeseries=points, cycles=points, rhs_evaluations=0,
                         wall_time_s=time.perf_counter() - t0, loads=loads,
                         variants={n: {"knob": v.knob, "knob_range": list(v.knob_range),
                                       "fixed": v.fixed} for n, v in var.items()},
                         rated_power_W=rated, brake=brake, runs=runs,
                         chest_volume_m3=var["cutoff"].scene.supply.chest_volume_m3,
                         pipe_diameter_m=var["cutoff"].scene.supply.pipe_diameter_m,
                         workers=workers, droop=speeds is not None)


__all__ += ["Variant", "rated_power_W", "willans_fit"]
