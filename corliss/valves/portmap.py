"""A gear tabulated once: the open area of every port over crank angle.

The hot loop reads areas from this table by linear interpolation, never calling the
gear.  The grid is uniform plus every angle where a port opens, closes or reaches
full opening, so the piecewise-linear table is exact at the kinks, and the
integrator can stop there (``breakpoints``).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from corliss.valves.crossing_kernels import merged_grid
from corliss.valves.events import sampled_crossings
from corliss.valves.gear import PORTS, ValveGear

TWO_PI = 2.0 * math.pi


@functools.lru_cache(maxsize=8)
def _uniform(n: int) -> np.ndarray:
    """``n`` uniform intervals of a turn, its ends included [rad] (read-only: shared
    by every map on ``n`` intervals)."""
    grid = np.linspace(0.0, TWO_PI, n + 1)
    grid.setflags(write=False)
    return grid


def _rounded_unique(angles: list[float]) -> list[float]:
    """``np.unique(np.round(np.asarray(angles) % TWO_PI, 12))`` as a list, on Python
    floats (a tabulation's dozen crossings: no array calls) [rad].

    The same numbers: Python's ``%`` on floats is numpy's (``fmod``, then the divisor
    added to a remainder of the other sign); ``np.round(x, 12)`` is ``rint(x * 1e12) /
    1e12``, and Python's ``round`` of a float rounds half to even as ``rint`` does, to
    an integer that is exactly a float here (below 2**53); equal numbers are kept once,
    in increasing order."""
    return sorted({float(round((t % TWO_PI) * 1e12)) / 1e12 for t in angles})


@dataclass(frozen=True)
class PortMap:
    """Open area of the four ports against crank angle.

    Built by :func:`tabulate`; read by linear interpolation in angle.

    Parameters
    ----------
    theta_rad : ndarray
        Crank angles [rad], increasing, from 0 to 2 pi inclusive, shape ``(n,)``.
    area_m2 : ndarray
        Open area [m2], shape ``(4, len(theta_rad))``, in the order of
        :data:`corliss.valves.gear.PORTS`.
    cd : ndarray
        Discharge coefficient of each port [-], shape ``(4,)``.
    breakpoints_rad : ndarray
        Angles in [0, 2 pi) where any port opens, closes or reaches full opening.
    crossings : list or None, optional
        ``crossings[port][0]`` where the port opens or closes, ``[port][1]`` where it
        reaches full opening, as :func:`corliss.valves.events.crossing_table` gives
        them (the events are read from the first); None when not kept.
    signed_samples : ndarray or None, optional
        The gear's signed openings [m] over the turn's samples the crossings were
        found from (:func:`corliss.valves.events.sampled_crossings`), shape
        ``(4, n)``: the events read the largest openings from them; None when not
        kept.
    """

    theta_rad: np.ndarray
    area_m2: np.ndarray
    cd: np.ndarray
    breakpoints_rad: np.ndarray
    crossings: list | None = None
    signed_samples: np.ndarray | None = None

    def areas(self, theta: float) -> np.ndarray:
        """Open areas of the four ports at one crank angle, interpolated linearly.

        Parameters
        ----------
        theta : float
            Crank angle [rad] from head-end dead centre; any turn (taken modulo
            2 pi).

        Returns
        -------
        ndarray
            Open areas [m2], shape ``(4,)``, in the order of :attr:`ports`.
        """
        t = theta % TWO_PI
        return np.array([np.interp(t, self.theta_rad, a) for a in self.area_m2])

    def open_mask(self, theta: np.ndarray) -> np.ndarray:
        """Which ports are open at each crank angle.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad], shape ``(n,)``; any turn (taken modulo 2 pi).

        Returns
        -------
        ndarray of bool
            Shape ``(4, n)``: True where the interpolated area of the port is above
            zero.
        """
        t = np.asarray(theta) % TWO_PI
        return np.vstack([np.interp(t, self.theta_rad, a) > 0.0 for a in self.area_m2])

    def scaled(self, factor: float) -> "PortMap":
        """The same map with every area multiplied by ``factor`` (a study device).

        Parameters
        ----------
        factor : float
            Multiplier of every open area [-].

        Returns
        -------
        PortMap
            A new map; angles, discharge coefficients, breakpoints and crossings
            unchanged.
        """
        return PortMap(self.theta_rad, self.area_m2 * factor, self.cd, self.breakpoints_rad,
                       self.crossings, self.signed_samples)

    @property
    def ports(self) -> tuple[str, ...]:
        """Names of the four ports in the order of the area rows.

        Returns
        -------
        tuple of str
            :data:`corliss.valves.gear.PORTS`: head steam, head exhaust, crank steam,
            crank exhaust.
        """
        return PORTS


def tabulate(gear: ValveGear, n: int = 1440) -> PortMap:
    """Tabulate a gear to a :class:`PortMap` on ``n`` uniform intervals plus its kinks.

    The kinks are every angle where a port's signed opening crosses one of the gear's
    :meth:`~corliss.valves.gear.ValveGear.kink_levels`; a uniform point within
    1e-9 rad of a kink is dropped in favour of the kink.

    Parameters
    ----------
    gear : ValveGear
        The gear at the setting to tabulate.
    n : int, optional
        Number of uniform intervals over one turn (1440: a quarter degree).

    Returns
    -------
    PortMap
        Areas on the merged grid, with the gear's discharge coefficients, the kinks
        as breakpoints and the crossing table (from which the events are read).
    """
    table, signed = sampled_crossings(gear, gear.kink_levels())
    kinks = np.array(_rounded_unique([t for row in table for lst in row for t, _ in lst]),
                     dtype=float)
    # the uniform grid and the kinks merged (np.union1d's array), and whether no point
    # but the kink itself lies within 2e-9 rad of any kink, in one compiled pass
    grid, alone = merged_grid(_uniform(n), kinks, 2e-9)
    # drop uniform points closer than 1e-9 rad to a kink (keep the kink itself: the
    # point nearest it), every kink at once; where no point but the kink itself lies
    # within twice that of any kink (the usual grid: its step is 9e-3 rad at the fast
    # preset's 720 intervals), none is dropped, and the distances need not be found
    if not alone:
        dist = np.abs(grid[None, :] - kinks[:, None])
        near = dist < 1e-9
        near[np.arange(kinks.size), np.argmin(dist, axis=1)] = False
        grid = grid[~near.any(axis=0)]
    return PortMap(theta_rad=grid, area_m2=gear.areas(grid), cd=gear.discharge_coefficients(),
                   breakpoints_rad=kinks, crossings=table, signed_samples=signed)


@dataclass(frozen=True)
class SettingPortMap:
    """Open area of the four ports over (gear setting, crank angle), for a gear that a
    governor or reverse lever resets while the engine runs.

    Both grids are uniform, so the hot loop finds its cell without a search and reads
    the area bilinearly; the port kinks, which move with the setting, fall between grid
    points (at the default 1440 intervals a kink is smoothed over 1/4 deg).

    Parameters
    ----------
    settings : ndarray
        Gear settings, uniform, increasing (the gear's own normalised setting units,
        see :attr:`~corliss.valves.gear.ValveGear.setting_name`), shape ``(m,)``.
    theta_rad : ndarray
        Crank angles [rad], uniform from 0 to 2 pi inclusive, shape ``(n,)``.
    area_m2 : ndarray
        Open area [m2], shape ``(m, 4, n)``.
    cd : ndarray
        Discharge coefficient of each port [-], shape ``(4,)``.
    """

    settings: np.ndarray
    theta_rad: np.ndarray
    area_m2: np.ndarray
    cd: np.ndarray

    def areas(self, setting: float, theta: float) -> np.ndarray:
        """Open areas of the four ports, bilinear in (setting, angle).

        Parameters
        ----------
        setting : float
            Gear setting (the gear's own units); clipped to the tabulated range.
        theta : float
            Crank angle [rad]; any turn (taken modulo 2 pi).

        Returns
        -------
        ndarray
            Open areas [m2], shape ``(4,)``, in the order of
            :data:`corliss.valves.gear.PORTS`.
        """
        s = np.clip(setting, self.settings[0], self.settings[-1])
        t = theta % TWO_PI
        per_setting = np.array([[np.interp(t, self.theta_rad, a) for a in row]
                                for row in self.area_m2])
        return np.array([np.interp(s, self.settings, per_setting[:, p]) for p in range(4)])


def tabulate_settings(gear: ValveGear, lo: float, hi: float, n_settings: int = 21,
                      n: int = 1440) -> SettingPortMap:
    """Tabulate a gear over ``n_settings`` settings from ``lo`` to ``hi`` and ``n`` uniform
    crank-angle intervals.

    Parameters
    ----------
    gear : ValveGear
        A gear with a setting (``setting_range`` not None).
    lo, hi : float
        Lowest and highest setting to tabulate (the gear's own units), within its
        ``setting_range``; one setting only when ``hi <= lo``.
    n_settings : int, optional
        Number of settings, evenly spaced from ``lo`` to ``hi``.
    n : int, optional
        Number of uniform crank-angle intervals over one turn (1440: a quarter
        degree).

    Returns
    -------
    SettingPortMap
        Areas of the gear rebuilt at each setting, on the uniform grids.
    """
    settings = np.linspace(lo, hi, n_settings) if hi > lo else np.array([lo])
    theta = np.linspace(0.0, TWO_PI, n + 1)
    area = np.stack([gear.with_setting(float(s)).areas(theta) for s in settings])
    return SettingPortMap(settings, theta, area, gear.discharge_coefficients())
