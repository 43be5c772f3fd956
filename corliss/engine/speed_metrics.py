"""What engineers read off a load step: regulation, largest deviation, settling, hunting.

All from the per-turn table of a transient run (mean speed of each turn, the
governor's mean position), so the speed's fluctuation within a turn, which the
flywheel sets (Marks Art. 62, the coefficient of steadiness), is not mistaken for the
governor's doing.

* **Regulation (droop)**: the change of steady speed between the loads before and after
  the step, as a fraction of the speed before it; a centrifugal governor cannot avoid it
  (Marks Art. 70: "the engine must go fast in order to go slow").
* **Largest deviation**: the largest departure of the turn-mean speed from the speed
  before the step [rpm and fraction].
* **Settling time**: from the step to the last time the turn-mean speed was outside the
  band (a fraction of the final speed) about the final speed.
* **Hunting**: a sustained oscillation of the governor.  Over the last third of the
  run, the governor's turn-mean position less its mean must swing by more than 1 % of
  its travel, cross its mean at least four times, and the swing of the last half of
  that window must be at least 70 % of the first half's (not decaying).  The period is
  twice the mean spacing of the crossings.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: Turns averaged for a steady speed (before the step, and at the end).
STEADY_TURNS = 5
HUNT_SWING = 0.01      # of the governor's travel
HUNT_CROSSINGS = 4
HUNT_PERSISTENCE = 0.7


def _mid_times(cycles: pd.DataFrame) -> np.ndarray:
    return 0.5 * (cycles["t_start_s"].to_numpy() + cycles["t_end_s"].to_numpy())


def hunting(cycles: pd.DataFrame) -> dict:
    """Whether the governor hunts at the end of the run, its period and swing."""
    t = _mid_times(cycles)
    if "governor_z_frac" not in cycles or len(cycles) < 12:
        return {"hunting": False, "hunting_period_s": None, "governor_swing": 0.0}
    z = cycles["governor_z_frac"].to_numpy()
    window = t >= t[0] + (t[-1] - t[0]) * 2.0 / 3.0
    tw, zw = t[window], z[window]
    d = zw - zw.mean()
    swing = float(d.max() - d.min())
    sign = np.sign(d)
    sign[sign == 0] = 1
    cross = np.nonzero(sign[1:] != sign[:-1])[0]
    half = tw.size // 2
    first, last = d[:half], d[half:]
    persist = (np.ptp(last) / np.ptp(first)) if first.size and np.ptp(first) > 0 else 0.0
    hunt = bool(swing > HUNT_SWING and cross.size >= HUNT_CROSSINGS and persist >= HUNT_PERSISTENCE)
    period = None
    if cross.size >= 2:
        tc = tw[cross]
        period = float(2.0 * np.mean(np.diff(tc)))
    return {"hunting": hunt, "hunting_period_s": period if hunt else None,
            "governor_swing": swing}


def load_step_metrics(cycles: pd.DataFrame, step_time_s: float | None, band: float) -> dict:
    """Regulation, largest deviation and settling after a load change at ``step_time_s``.

    Parameters
    ----------
    cycles : DataFrame
        The per-turn table of a transient run.
    step_time_s : float or None
        When the load changed [s]; None for a run without a change (only hunting and the
        final speed are reported).
    band : float
        Settling band, a fraction of the final speed [-].
    """
    t = _mid_times(cycles)
    n = cycles["mean_speed_rpm"].to_numpy()
    out = {"final_speed_rpm": float(np.mean(n[-STEADY_TURNS:])), **hunting(cycles)}
    if step_time_s is None:
        return out
    before = cycles["t_end_s"].to_numpy() <= step_time_s
    after = t > step_time_s
    if before.sum() < 1 or after.sum() < 2:
        out.update(speed_before_rpm=None, regulation=None, max_deviation_rpm=None,
                   max_deviation_frac=None, settling_time_s=None)
        return out
    n0 = float(np.mean(n[before][-STEADY_TURNS:]))
    n1 = out["final_speed_rpm"]
    dev = n[after] - n0
    k = int(np.argmax(np.abs(dev)))
    outside = np.abs(n[after] - n1) > band * n1
    if not outside.any():
        settle = 0.0
    elif outside[-1]:
        settle = None          # not settled by the end of the run
    else:
        last = int(np.nonzero(outside)[0][-1])
        settle = float(cycles["t_end_s"].to_numpy()[after][last] - step_time_s)
    out.update(speed_before_rpm=n0, regulation=(n1 - n0) / n0,
               max_deviation_rpm=float(dev[k]), max_deviation_frac=float(dev[k] / n0),
               time_of_max_deviation_s=float(t[after][k] - step_time_s),
               settling_time_s=settle)
    return out


def step_time_of(load) -> float | None:
    """The first time the load schedule changes [s], or None for a constant load."""
    times = load.change_times_s()
    return times[0] if times else None
