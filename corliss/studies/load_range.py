"""An engine across its load range: steady cards at a series of governor positions.

A governor meets a lighter load by shortening the cut-off (through the gear's setting)
or by closing the throttle; at each position the engine settles to a steady card.  A
sweep of either knob gives the steam the engine costs across its load range, which the
engineers of the time drew as the Willans line (steam per hour against indicated power:
straight for a throttled engine, P. W. Willans, Min. Proc. Inst. C.E. 1888; curved for
one governed by cut-off, whose steam per horse-power is least at its economical
cut-off, Marks Art. 2).
"""

from __future__ import annotations

import time
from typing import Any

import pandas as pd

from corliss.engine.model import KNOBS, at_knob
from corliss.engine.result import SweepResult, willans_fit
from corliss.engine.steady import run_steady
from corliss.engine.summary_keys import SteadySummary
from corliss.logs import at_point
from corliss.progress import progress_for

__all__ = ["KNOBS", "load_range", "load_ranges", "willans_fit"]


def load_range(scene, knob: str, values, *,
               progress: Any = None) -> SweepResult:
    """Steady runs at each value of ``knob``, one row each.

    Parameters
    ----------
    scene : Scene
        Any scene (a transient one is run steady at its initial speed).
    knob : str
        ``"setting"`` (the gear's setting, as its governor or reverse lever sets it) or
        ``"throttle"`` (opening of the throttle, 0..1).
    values : sequence of float
        The settings [-] or openings [-]; every one is checked before any run.
    progress : None, True, ProgressBar or callable, optional
        True draws a bar (:mod:`corliss.progress`); a callable is called after each
        run with (runs done, runs in all).  Each run's messages name its point
        (``setting 0.4``).

    Returns
    -------
    SweepResult
        Its ``points`` table: ``knob_frac``, ``indicated_power_W``,
        ``steam_rate_kg_per_h``, ``water_rate_kg_per_kWh``, ``cutoff_head_frac``, and
        ``brake_power_W`` when ``friction`` is named.

    Raises
    ------
    InputError
        A value :func:`corliss.engine.model.at_knob` refuses, before any run.
    """
    t0 = time.perf_counter()
    values = [float(v) for v in values]
    scenes = [at_knob(scene, knob, v) for v in values]     # check all before work
    rows = []
    nfev = 0
    tier = scene.run.fidelity.properties
    with progress_for(progress, "runs") as bar:
        for n, (v, sc) in enumerate(zip(values, scenes), start=1):
            with at_point(f"{knob} {v:g}"):
                r = run_steady(sc)
                s = r.summary
            nfev += r.rhs_evaluations
            tier = r.property_tier
            rows.append(_row(v, s))
            if bar:
                bar(n, len(values))
    points = pd.DataFrame(rows)

    return SweepResult(scene=scene, property_tier=tier, timeseries=points, cycles=points,
                       rhs_evaluations=nfev, wall_time_s=time.perf_counter() - t0, knob=knob,
                       values=values)


def _row(v: float, s: SteadySummary) -> dict:
    return {"knob_frac": v, "indicated_power_W": s["indicated_power_W"],
            "steam_rate_kg_per_h": s["steam_rate_kg_per_h"],
            "water_rate_kg_per_kWh": s["water_rate_kg_per_kWh"],
            "cutoff_head_frac": s["events"]["head"]["cutoff_frac"],
            **({"brake_power_W": s["brake_power_W"]} if "brake_power_W" in s else {})}


def load_ranges(scene, values_by_knob: dict, *, progress: Any = None) -> SweepResult:
    """Steady runs at each value of several knobs, in one table with a ``knob`` column.

    Parameters
    ----------
    scene : Scene
        Any scene (a transient one is run steady at its initial speed).
    values_by_knob : dict
        ``{"setting": [...], "throttle": [...]}`` (either or both); every value is
        checked before any run.
    progress : None, True, ProgressBar or callable, optional
        As :func:`load_range`'s, over all the runs.

    Returns
    -------
    SweepResult
        ``knob`` is ``"both"`` when both knobs ran; its ``points`` carry the ``knob``
        of each row.

    Raises
    ------
    InputError
        A value :func:`corliss.engine.model.at_knob` refuses, before any run.
    """
    for knob, values in values_by_knob.items():
        for v in values:
            at_knob(scene, knob, float(v))
    if len(values_by_knob) == 1:
        (knob, values), = values_by_knob.items()
        return load_range(scene, knob, values, progress=progress)
    t0 = time.perf_counter()
    total = sum(len(v) for v in values_by_knob.values())
    parts, nfev, done, tier = [], 0, 0, scene.run.fidelity.properties
    with progress_for(progress, "runs") as bar:
        for knob, values in values_by_knob.items():
            def step(n, _total, base=done):
                if bar:
                    bar(base + n, total)
            r = load_range(scene, knob, values, progress=step)
            done += len(values)
            nfev += r.rhs_evaluations
            tier = r.property_tier
            parts.append(r.points.assign(knob=knob))
    points = pd.concat(parts, ignore_index=True)
    points = points[["knob"] + [c for c in points.columns if c != "knob"]]
    return SweepResult(scene=scene, property_tier=tier, timeseries=points, cycles=points,
                       rhs_evaluations=nfev, wall_time_s=time.perf_counter() - t0, knob="both",
                       values=[float(v) for vs in values_by_knob.values() for v in vs])
