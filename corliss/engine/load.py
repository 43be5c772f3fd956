"""The load on the shaft: a torque that follows a schedule in time and may vary with speed.

    T_load(t, omega) = T_ref f(t) (omega / omega_ref)^k

``T_ref`` is the reference torque (given as a torque, or as a power at the run's
speed, T = P / omega_ref); ``f(t)`` a schedule of load fractions, piecewise linear in
time; ``k`` = 0 (constant torque: a hoist, a mill shafting at fixed resistance),
1 (torque proportional to speed: a generator on a fixed resistance at constant field,
viscous drag) or 2 (torque as the square of speed: a fan or centrifugal pump).

The schedule (``kind``):

* ``"constant"``: f = 1;
* ``"step"``: f = ``initial_fraction`` (default 1) until ``step_time``, then
  ``step_fraction``: "from 50 % to 80 %" is ``initial_fraction = 0.5``,
  ``step_fraction = 0.8``;
* ``"ramp"``: f = ``initial_fraction`` (default 1) until ``ramp_start``, linear to
  ``ramp_fraction`` at ``ramp_end``;
* ``"schedule"``: a CSV file (``schedule``, relative to the scene) with columns
  ``time_s`` and ``load_fraction``, read piecewise linearly and held beyond its ends.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.toml_table import Table
from corliss.keys.textfiles import read_text

SPEED_LAWS = {"constant": 0, "proportional": 1, "square": 2}


@dataclass(frozen=True)
class LoadSpec:
    """The shaft load (all SI): ``T_load(t, omega) = T_ref f(t) (omega / omega_ref)^k``.

    Parameters
    ----------
    torque_N_m : float
        Reference torque T_ref [N m].
    speed_law : str
        ``"constant"``, ``"proportional"`` or ``"square"`` (k = 0, 1, 2).
    times_s : tuple of float
        Schedule times [s], non-decreasing (a repeated time is a step).
    fractions : tuple of float
        Load fractions f at those times [-].
    kind : str
        How the schedule was given.
    """

    torque_N_m: float
    speed_law: str
    times_s: tuple[float, ...]
    fractions: tuple[float, ...]
    kind: str

    @property
    def speed_exponent(self) -> int:
        """The exponent ``k`` of the speed law [-]: 0, 1 or 2."""
        return SPEED_LAWS[self.speed_law]

    def fraction(self, t_s):
        """The schedule's load fraction ``f(t)``, piecewise linear, held beyond its ends.

        Parameters
        ----------
        t_s : float or array_like
            Time from the start of the run [s].

        Returns
        -------
        float or ndarray
            ``f`` [-], of ``t_s``'s shape.
        """
        t = np.asarray(t_s, dtype=float)
        return np.interp(t, self.times_s, self.fractions)

    def change_times_s(self) -> list[float]:
        """Times where the schedule changes slope or steps.

        Returns
        -------
        list of float
            The schedule's inner times, sorted, without repeats [s] (empty for a
            constant load).
        """
        return sorted(set(self.times_s[1:-1])) if len(self.times_s) > 2 else []


def _fraction(t: Table, key: str, default=None) -> float:
    v = t.number(key) if default is None else t.number(key, default)
    if not 0.0 <= v <= 5.0:
        raise InputError(t.key(key), v, "a load fraction from 0 to 5 (of the reference load)")
    return v


def parse_load(t: Table, speed_rad_s: float, scene_dir: Path | None) -> LoadSpec:
    """Read a ``[load]`` table.

    Parameters
    ----------
    t : Table
        The scene's ``[load]`` table.
    speed_rad_s : float
        The run's speed [rad/s], which turns a ``power`` into the reference torque
        (``T_ref = P / omega_ref``).
    scene_dir : Path or None
        The scene's directory, against which a relative ``schedule`` path is read.

    Returns
    -------
    LoadSpec
        The load; a step or ramp as a schedule of four points, the last one second
        after the change.

    Raises
    ------
    InputError
        Both or neither of ``torque`` and ``power``, a negative load, a fraction outside
        0 to 5, a bad step or ramp time, a bad schedule file, or an unknown key.
    """
    if t.has("torque") and t.has("power"):
        raise InputError(t.key("torque"), t.raw("torque", None),
                         "either torque or power (at the run's speed), not both")
    if not (t.has("torque") or t.has("power")):
        raise InputError(t.key("power"), None, "a load: power (at the run's speed) or "
                         "torque; one of them is required")
    if t.has("torque"):
        torque = t.quantity("torque", "torque")
    else:
        torque = t.quantity("power", "power") / speed_rad_s
    if torque < 0.0:
        raise InputError(t.key("torque" if t.has("torque") else "power"),
                         t.raw("torque", t.raw("power", None)), "a load of zero or more")
    law = t.choice("speed_law", tuple(SPEED_LAWS), "constant")
    kind = t.choice("kind", ("constant", "step", "ramp", "schedule"), "constant")
    times: tuple[float, ...]
    fracs: tuple[float, ...]
    if kind == "constant":
        times, fracs = (0.0, 1.0), (1.0, 1.0)
    elif kind == "step":
        ts = t.quantity("step_time", "time")
        if ts < 0.0:
            raise InputError(t.key("step_time"), t.raw("step_time"), "a time of zero or more")
        f0 = _fraction(t, "initial_fraction", 1.0)
        f = _fraction(t, "step_fraction")
        times, fracs = (0.0, ts, ts, ts + 1.0), (f0, f0, f, f)
    elif kind == "ramp":
        a = t.quantity("ramp_start", "time")
        b = t.quantity("ramp_end", "time")
        if not 0.0 <= a < b:
            raise InputError(t.key("ramp_end"), t.raw("ramp_end"),
                             "a ramp end after its start (both zero or more)")
        f0 = _fraction(t, "initial_fraction", 1.0)
        f = _fraction(t, "ramp_fraction")
        times, fracs = (0.0, a, b, b + 1.0), (f0, f0, f, f)
    else:
        times, fracs = _read_schedule(t, scene_dir)
    t.finish()
    return LoadSpec(torque, law, tuple(times), tuple(fracs), kind)


def _read_schedule(t: Table, scene_dir: Path | None):
    """The schedule CSV: a header naming ``time_s`` and ``load_fraction``, then one row
    per point, times from zero up and never decreasing (equal times make a step)."""
    name = t.string("schedule")
    path = Path(name)
    if not path.is_absolute() and scene_dir is not None:
        path = scene_dir / path
    key = t.key("schedule")
    what = "a CSV file (relative to the scene) with columns time_s and load_fraction"
    text = read_text(path, key, what)
    try:
        reader = csv.DictReader(io.StringIO(text, newline=""))
        header = reader.fieldnames or []
        rows = []
        for row in reader:
            rows.append((reader.line_num, row))
    except csv.Error as exc:
        raise InputError(key, name, f"{what}; it is not CSV ({exc})") from None
    if not rows or not {"time_s", "load_fraction"} <= {h.strip() for h in header}:
        raise InputError(key, name, "a CSV with a header row naming the columns time_s and "
                         "load_fraction, and at least one row below it")
    times: list[float] = []
    fracs: list[float] = []
    for line, row in rows:
        row = {(k or "").strip(): v for k, v in row.items()}
        t_cell, f_cell = row.get("time_s"), row.get("load_fraction")
        if t_cell is None or f_cell is None or not t_cell.strip() or not f_cell.strip():
            raise InputError(key, name, f"a time and a load fraction on every row; line "
                             f"{line} has too few cells")
        try:
            tv, fv = float(t_cell), float(f_cell)
        except ValueError:
            raise InputError(key, name, f"numbers on every row; line {line} has "
                             f"{t_cell!r}, {f_cell!r}") from None
        if not (math.isfinite(tv) and math.isfinite(fv)):
            raise InputError(key, name, f"finite numbers; line {line} has {tv}, {fv}")
        if not 0.0 <= tv <= units.RANGES["time"][1]:
            raise InputError(key, name, f"times from 0 to {units.RANGES['time'][1]:g} s; line "
                             f"{line} has {tv:g} s")
        if times and tv < times[-1]:
            raise InputError(key, name, f"times never decreasing; line {line} goes back from "
                             f"{times[-1]:g} s to {tv:g} s")
        if not 0.0 <= fv <= 5.0:
            raise InputError(key, name, f"load fractions from 0 to 5; line {line} has {fv:g}")
        times.append(tv)
        fracs.append(fv)
    if len(times) == 1:
        times, fracs = times * 2, fracs * 2
        times[1] += 1.0
    return times, fracs
