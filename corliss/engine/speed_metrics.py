"""What engineers read off a load step: regulation, largest deviation, settling, hunting.

All from the per-turn table of a transient run (mean speed of each turn, the
governor's mean position), so the speed's fluctuation within a turn, which the
flywheel sets (Marks Art. 62, the coefficient of steadiness), is not mistaken for the
governor's doing.

* **Settled**: a speed is a steady speed only once the engine has settled: over the
  last third of the time after the step (at least ``SETTLE_MIN_TURNS`` turns), the
  turn-mean speed swings by no more than ``SETTLED_SWING`` of itself.  A slow swing
  of the governor that has not died away (a Porter-Allen engine's period can be half a
  minute) fails this however quiet its last few turns look.
* **Regulation (droop)**: the change of steady speed between the loads before and after
  the step, as a fraction of the speed before it; a centrifugal governor cannot avoid it
  (Marks Art. 70: "the engine must go fast in order to go slow").  Reported only when
  the speed before the step and at the end have both settled (None otherwise, with
  ``settled`` False: run longer, or ``until_settled``).
* **Largest deviation**: the largest departure of the turn-mean speed from the speed
  before the step [rpm and fraction].
* **Settling time**: from the step to the last entry of the turn-mean speed into the
  band (a fraction of the final speed) about the final speed; None when not settled.
* **Hunting**: a sustained oscillation of the governor.  Over the last half of the time
  after the step (of the run, without a step), the governor's position less its mean
  must swing by more than 1 % of its travel, cross its mean at least four times, and
  the swing of the last half of that window must be at least 70 % of the first half's
  (not decaying).  The period is twice the mean spacing of the crossings.

  The position is read from the crank-resolved time series where the run recorded one
  (``record = "degree"`` or ``"step"``): a turn-mean position samples the motion once a
  turn, so a hunt shorter than two turns aliases into a slower, smaller one (Shannon's
  sampling theorem; a slow Corliss engine's hunt is about one and a half turns).  The
  governor also follows the speed's fluctuation within each turn (the flywheel's
  coefficient of steadiness, Marks Art. 62), a ripple periodic in the crank angle; it
  is removed by a least-squares fit of the turn's first :data:`RIPPLE_HARMONICS`
  harmonics in the crank angle (a motion at a period that is not a whole number of
  turns averages out of that fit over the window's many turns), and the crossings are
  counted with a hysteresis of :data:`HUNT_HYSTERESIS` of the half-swing, so what is
  left of the ripple cannot count as a crossing.  Without a crank-resolved series (a
  ``"cycle"`` record, the mean-value model), the turn means serve, and a period under
  two turns cannot be told there.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:      # annotations only: pandas is not imported by a run
    import pandas as pd

#: Turns averaged for a steady speed (before the step, and at the end).
STEADY_TURNS = 5
#: Settled: the turn-mean speed's swing over the settling window, as a fraction of the
#: speed.  0.02 % bounds what more running can change the final speed by, if the
#: motion decays, to about that: an order below the 0.05 % to which regulation is
#: reported meaningful, and well below any period governor's droop (1 to 5 %).
SETTLED_SWING = 2e-4
#: The settling window: the last third of the time after the step, at least this many
#: turns.
SETTLE_FRACTION = 1.0 / 3.0
SETTLE_MIN_TURNS = 12
HUNT_SWING = 0.01      # of the governor's travel
HUNT_CROSSINGS = 4
HUNT_PERSISTENCE = 0.7
#: Harmonics of the turn fitted to the crank-resolved position and taken off it (the
#: torque of a double-acting engine pulses twice a turn, and its harmonics follow).
RIPPLE_HARMONICS = 4
#: Crossings of the mean counted only after the position has gone this fraction of its
#: half-swing beyond it on the other side (a Schmitt trigger).
HUNT_HYSTERESIS = 0.25
#: Samples a turn below which a time series is not crank-resolved.
MIN_SAMPLES_PER_TURN = 8


def _mid_times(cycles: pd.DataFrame) -> np.ndarray:
    return 0.5 * (cycles["t_start_s"].to_numpy() + cycles["t_end_s"].to_numpy())


def _window(t: np.ndarray, since: float, fraction: float, min_turns: int) -> np.ndarray:
    """Mask of the turns in the last ``fraction`` of the time after ``since``, and at
    least the last ``min_turns`` turns."""
    mask = t >= since + (t[-1] - since) * (1.0 - fraction)
    if mask.sum() < min_turns:
        mask = np.zeros(t.size, dtype=bool)
        mask[-min_turns:] = True
    return mask


def settled(t_mid_s: np.ndarray, speed_rpm: np.ndarray, since_s: float) -> tuple[bool, float]:
    """Whether the turn-mean speed has settled after a change of load, and its swing.

    Settled: over the last third of the time after ``since_s`` (at least
    :data:`SETTLE_MIN_TURNS` turns), the speed swings by no more than
    :data:`SETTLED_SWING` of its mean.

    Parameters
    ----------
    t_mid_s : ndarray
        Mid-times of the turns [s].
    speed_rpm : ndarray
        Turn-mean speeds [rpm].
    since_s : float
        The last change of load [s] (0 without one).

    Returns
    -------
    settled : bool
        Whether the swing is at most :data:`SETTLED_SWING` (False with fewer than
        :data:`SETTLE_MIN_TURNS` turns after ``since_s``).
    swing : float
        The swing of the turn-mean speed over the settling window, a fraction of its
        mean [-] (NaN with too few turns).
    """
    after = t_mid_s > since_s
    if after.sum() < SETTLE_MIN_TURNS:
        return False, math.nan
    t, n = t_mid_s[after], speed_rpm[after]
    w = _window(t, since_s, SETTLE_FRACTION, SETTLE_MIN_TURNS)
    swing = float(np.ptp(n[w]) / np.mean(n[w]))
    return bool(swing <= SETTLED_SWING), swing


def _crossings(t: np.ndarray, d: np.ndarray, hysteresis: float) -> np.ndarray:
    """Times [s] at which ``d`` crosses zero, counted only where it goes beyond
    ``+hysteresis`` and ``-hysteresis`` in turn (each interpolated linearly at the
    last change of sign between the two)."""
    beyond = np.nonzero(np.abs(d) > hysteresis)[0]
    if beyond.size < 2:
        return np.zeros(0)
    side = np.sign(d[beyond])
    turn = np.nonzero(side[1:] != side[:-1])[0]
    times = []
    for j in turn:
        i0, i1 = beyond[j], beyond[j + 1]
        seg = np.sign(d[i0:i1 + 1])
        seg[seg == 0] = side[j]
        k = i0 + int(np.nonzero(seg[1:] != seg[:-1])[0][-1])
        times.append(t[k] - d[k] * (t[k + 1] - t[k]) / (d[k + 1] - d[k]))
    return np.asarray(times)


def _without_ripple(theta_rad: np.ndarray, z: np.ndarray, t_s: np.ndarray | None = None,
                    period_s: float | None = None) -> np.ndarray:
    """``z`` less its mean and less its part periodic in the crank angle.

    The least-squares fit of a constant and the first :data:`RIPPLE_HARMONICS`
    harmonics of the turn, taken off.  Given the hunt's period (from a first pass),
    the hunt's own first :data:`RIPPLE_HARMONICS` harmonics in time are fitted beside
    them and kept: over a window of a few beats between the two, a hunt near a whole
    number of turns would otherwise leak into the turn's harmonics (by a few per cent
    of its swing over twenty turns)."""
    cols = [np.ones_like(theta_rad)]
    for h in range(1, RIPPLE_HARMONICS + 1):
        cols += [np.cos(h * theta_rad), np.sin(h * theta_rad)]
    n_ripple = len(cols)
    if period_s is not None and t_s is not None:
        w = 2.0 * math.pi / period_s
        for h in range(1, RIPPLE_HARMONICS + 1):
            cols += [np.cos(h * w * t_s), np.sin(h * w * t_s)]
    a = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(a, z, rcond=None)
    return z - a[:, :n_ripple] @ coef[:n_ripple]


def _resolved(timeseries, t0: float, turns: int):
    """The crank-resolved governor position from ``t0`` on: (time [s], crank angle
    [rad], position [-]), or None where the series is not crank-resolved."""
    if timeseries is None or "governor_z_frac" not in timeseries or len(timeseries) == 0:
        return None
    t = timeseries["time_s"].to_numpy()
    keep = t >= t0
    if keep.sum() < MIN_SAMPLES_PER_TURN * turns:
        return None
    return (t[keep], np.radians(timeseries["crank_angle_deg"].to_numpy()[keep]),
            timeseries["governor_z_frac"].to_numpy()[keep])


def hunting(cycles: pd.DataFrame, since_s: float = 0.0, timeseries=None) -> dict:
    """Whether the governor hunts at the end of the run, its period and swing.

    Over the last half of the time after ``since_s`` (at least 12 turns), by the test
    of the module's docstring, on the crank-resolved position where ``timeseries``
    holds one, else on the turn means.

    Parameters
    ----------
    cycles : DataFrame
        The per-turn table of a transient run (``t_start_s``, ``t_end_s``,
        ``governor_z_frac``).
    since_s : float
        The last change of load [s] (0 without one; the whole run when fewer than 12
        turns follow it).
    timeseries : DataFrame, optional
        The run's time series (``time_s``, ``crank_angle_deg``, ``governor_z_frac``);
        used where it has at least :data:`MIN_SAMPLES_PER_TURN` samples a turn.

    Returns
    -------
    dict
        ``hunting`` (bool), ``hunting_period_s`` (twice the mean spacing of the
        crossings of the mean [s], None unless hunting), ``governor_swing_frac`` (the
        swing of the governor's position, peak to peak, a fraction of its travel [-])
        and ``hunting_read_from`` (``"crank_angle"`` or ``"turn_means"``); no hunting
        without a governor or with fewer than 12 turns.
    """
    t = _mid_times(cycles)
    if "governor_z_frac" not in cycles or len(cycles) < 12:
        return {"hunting": False, "hunting_period_s": None, "governor_swing_frac": 0.0,
                "hunting_read_from": None}
    since = since_s if (t > since_s).sum() >= 12 else t[0]
    window = _window(t, since, 0.5, 12)
    start = float(cycles["t_start_s"].to_numpy()[window][0])
    resolved = _resolved(timeseries, start, int(window.sum()))
    if resolved is not None:
        tw, theta, z = resolved
        d = _without_ripple(theta, z)
        swing = float(d.max() - d.min())
        cross = _crossings(tw, d, HUNT_HYSTERESIS * 0.5 * swing)
        if cross.size >= 2:      # second pass: the hunt fitted beside the ripple
            d = _without_ripple(theta, z, tw, float(2.0 * np.mean(np.diff(cross))))
        read_from = "crank_angle"
    else:
        tw, z = t[window], cycles["governor_z_frac"].to_numpy()[window]
        d = z - z.mean()
        read_from = "turn_means"
    swing = float(d.max() - d.min())
    cross = _crossings(tw, d, HUNT_HYSTERESIS * 0.5 * swing)
    mid = 0.5 * (tw[0] + tw[-1])
    first, last = d[tw < mid], d[tw >= mid]
    persist = (np.ptp(last) / np.ptp(first)) if first.size and np.ptp(first) > 0 else 0.0
    hunt = bool(swing > HUNT_SWING and cross.size >= HUNT_CROSSINGS and persist >= HUNT_PERSISTENCE)
    period = float(2.0 * np.mean(np.diff(cross))) if hunt else None
    return {"hunting": hunt, "hunting_period_s": period, "governor_swing_frac": swing,
            "hunting_read_from": read_from}


def final_turns(cycles: "pd.DataFrame") -> "pd.DataFrame":
    """The turns a transient run's final state is read from: the last
    :data:`STEADY_TURNS`, none of them before the last change of direction.

    A turn through a change of direction (a reversing slip eccentric,
    :mod:`corliss.engine.reversal`) starts at one sign of speed and ends at the other;
    its mean speed is its net angle over its time, neither direction's speed, so it and
    the turns before it are not the final state.

    Parameters
    ----------
    cycles : DataFrame
        The per-turn table of a transient run (``speed_start_rpm`` and
        ``speed_end_rpm`` where recorded).

    Returns
    -------
    DataFrame
        Its last rows: at most :data:`STEADY_TURNS`, all after the last turn whose
        speed changed sign (all the last :data:`STEADY_TURNS` when none did).
    """
    tail = cycles.iloc[-STEADY_TURNS:]
    if not {"speed_start_rpm", "speed_end_rpm"} <= set(cycles.columns):
        return tail
    turned = np.flatnonzero(np.sign(cycles["speed_start_rpm"].to_numpy())
                            * np.sign(cycles["speed_end_rpm"].to_numpy()) < 0.0)
    if turned.size == 0 or turned[-1] == len(cycles) - 1:
        return tail
    return cycles.iloc[max(int(turned[-1]) + 1, len(cycles) - STEADY_TURNS):]


def load_step_metrics(cycles: pd.DataFrame, step_time_s: float | None, band: float,
                      timeseries=None) -> dict:
    """Regulation, largest deviation and settling after a load change at ``step_time_s``.

    Parameters
    ----------
    cycles : DataFrame
        The per-turn table of a transient run.
    step_time_s : float or None
        When the load changed [s]; None for a run without a change (only hunting,
        whether it settled and the final speed are reported).
    band : float
        Settling band, a fraction of the final speed [-].
    timeseries : DataFrame, optional
        The run's time series, for the hunting test (see :func:`hunting`).

    Returns
    -------
    dict
        ``final_speed_rpm``, ``settled``, ``settled_swing_frac``, the hunting keys, and
        with a step ``speed_before_rpm``, ``settled_before``, ``regulation_frac``,
        ``max_deviation_rpm``, ``max_deviation_frac``, ``time_of_max_deviation_s``,
        ``settling_time_s`` (None where they cannot be measured).
    """
    t = _mid_times(cycles)
    n = cycles["mean_speed_rpm"].to_numpy()
    since = step_time_s if step_time_s is not None else float(cycles["t_start_s"].iloc[0])
    ok, swing = settled(t, n, since)
    out = {"final_speed_rpm": float(final_turns(cycles)["mean_speed_rpm"].mean()),
           "settled": ok,
           "settled_swing_frac": None if math.isnan(swing) else swing,
           **hunting(cycles, since, timeseries)}
    if step_time_s is None:
        return out
    before = cycles["t_end_s"].to_numpy() <= step_time_s
    after = t > step_time_s
    out.update(speed_before_rpm=None, settled_before=False, regulation_frac=None,
               max_deviation_rpm=None, max_deviation_frac=None, time_of_max_deviation_s=None,
               settling_time_s=None)
    if before.sum() < 1 or after.sum() < 2:
        return out
    n0 = float(np.mean(n[before][-STEADY_TURNS:]))
    nb = n[before][-STEADY_TURNS:]
    out["settled_before"] = bool(np.ptp(nb) / n0 <= SETTLED_SWING)
    n1 = out["final_speed_rpm"]
    dev = n[after] - n0
    k = int(np.argmax(np.abs(dev)))
    out.update(speed_before_rpm=n0, max_deviation_rpm=float(dev[k]),
               max_deviation_frac=float(dev[k] / n0),
               time_of_max_deviation_s=float(t[after][k] - step_time_s))
    if not (ok and out["settled_before"]):
        return out
    outside = np.abs(n[after] - n1) > band * n1
    if not outside.any():
        settle = 0.0
    else:
        last = int(np.nonzero(outside)[0][-1])
        settle = float(cycles["t_end_s"].to_numpy()[after][last] - step_time_s)
    out.update(regulation_frac=(n1 - n0) / n0, settling_time_s=settle)
    return out


def step_time_of(load) -> float | None:
    """The first time the load schedule changes.

    Parameters
    ----------
    load : LoadSpec
        The scene's load.

    Returns
    -------
    float or None
        The time [s], or None for a constant load.
    """
    times = load.change_times_s()
    return times[0] if times else None
