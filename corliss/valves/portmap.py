"""A gear tabulated once: the open area of every port over crank angle.

The hot loop reads areas from this table by linear interpolation, never calling the
gear.  The grid is uniform plus every angle where a port opens, closes or reaches
full opening, so the piecewise-linear table is exact at the kinks, and the
integrator can stop there (``breakpoints``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.valves.events import crossing_table
from corliss.valves.gear import PORTS, ValveGear

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class PortMap:
    """Open area of the four ports against crank angle.

    Attributes
    ----------
    theta_rad : ndarray
        Crank angles [rad], increasing, from 0 to 2 pi inclusive.
    area_m2 : ndarray
        Open area [m2], shape ``(4, len(theta_rad))``, in the order of
        :data:`corliss.valves.gear.PORTS`.
    cd : ndarray
        Discharge coefficient of each port [-], shape ``(4,)``.
    breakpoints_rad : ndarray
        Angles in [0, 2 pi) where any port opens, closes or reaches full opening.
    crossings : list
        ``crossings[port][0]`` where the port opens or closes, ``[port][1]`` where it
        reaches full opening, as :func:`corliss.valves.events.crossing_table` gives
        them (the events are read from the first).
    """

    theta_rad: np.ndarray
    area_m2: np.ndarray
    cd: np.ndarray
    breakpoints_rad: np.ndarray
    crossings: list | None = None

    def areas(self, theta: float) -> np.ndarray:
        """Open areas [m2] of the four ports at crank angle ``theta`` [rad] (any turn)."""
        t = theta % TWO_PI
        return np.array([np.interp(t, self.theta_rad, a) for a in self.area_m2])

    def open_mask(self, theta: np.ndarray) -> np.ndarray:
        """Boolean ``(4, n)``: which ports are open at each angle [rad]."""
        t = np.asarray(theta) % TWO_PI
        return np.vstack([np.interp(t, self.theta_rad, a) > 0.0 for a in self.area_m2])

    def scaled(self, factor: float) -> "PortMap":
        """The same map with every area multiplied by ``factor`` (a study device)."""
        return PortMap(self.theta_rad, self.area_m2 * factor, self.cd, self.breakpoints_rad,
                       self.crossings)

    @property
    def ports(self) -> tuple[str, ...]:
        return PORTS


def tabulate(gear: ValveGear, n: int = 1440) -> PortMap:
    """Tabulate a gear to a :class:`PortMap` on ``n`` uniform intervals plus its kinks."""
    table = crossing_table(gear, gear.kink_levels())
    kinks = [t for row in table for lst in row for t, _ in lst]
    kinks = np.unique(np.round(np.asarray(kinks, dtype=float) % TWO_PI, 12))
    grid = np.union1d(np.linspace(0.0, TWO_PI, n + 1), kinks)
    # drop uniform points closer than 1e-9 rad to a kink (keep the kink itself)
    keep = np.ones(grid.size, dtype=bool)
    for k in kinks:
        near = np.abs(grid - k) < 1e-9
        near[np.argmin(np.abs(grid - k))] = False
        keep &= ~near
    grid = grid[keep]
    return PortMap(theta_rad=grid, area_m2=gear.areas(grid), cd=gear.discharge_coefficients(),
                   breakpoints_rad=kinks, crossings=table)


@dataclass(frozen=True)
class SettingPortMap:
    """Open area of the four ports over (gear setting, crank angle), for a gear that a
    governor or reverse lever resets while the engine runs.

    Both grids are uniform, so the hot loop finds its cell without a search and reads
    the area bilinearly; the port kinks, which move with the setting, fall between grid
    points (at the default 1440 intervals a kink is smoothed over 1/4 deg).

    Attributes
    ----------
    settings : ndarray
        Gear settings, uniform, increasing (the gear's own setting units).
    theta_rad : ndarray
        Crank angles [rad], uniform from 0 to 2 pi inclusive.
    area_m2 : ndarray
        Open area [m2], shape ``(len(settings), 4, len(theta_rad))``.
    cd : ndarray
        Discharge coefficient of each port [-].
    """

    settings: np.ndarray
    theta_rad: np.ndarray
    area_m2: np.ndarray
    cd: np.ndarray

    def areas(self, setting: float, theta: float) -> np.ndarray:
        """Open areas [m2] of the four ports, bilinear in (setting, angle)."""
        s = np.clip(setting, self.settings[0], self.settings[-1])
        t = theta % TWO_PI
        per_setting = np.array([[np.interp(t, self.theta_rad, a) for a in row]
                                for row in self.area_m2])
        return np.array([np.interp(s, self.settings, per_setting[:, p]) for p in range(4)])


def tabulate_settings(gear: ValveGear, lo: float, hi: float, n_settings: int = 21,
                      n: int = 1440) -> SettingPortMap:
    """Tabulate a gear over ``n_settings`` settings from ``lo`` to ``hi`` and ``n`` uniform
    crank-angle intervals."""
    settings = np.linspace(lo, hi, n_settings) if hi > lo else np.array([lo])
    theta = np.linspace(0.0, TWO_PI, n + 1)
    area = np.stack([gear.with_setting(float(s)).areas(theta) for s in settings])
    return SettingPortMap(settings, theta, area, gear.discharge_coefficients())
