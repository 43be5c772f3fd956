"""A single-acting cylinder's gear: one end takes steam, the other stands open.

The engines the period measured condensation and leakage on were single-acting
(Callendar and Nicolson's 10.5 x 12 in engine at McGill, steam "only at the end away
from the crank", Min. Proc. ICE 131, 1897-98, in DPJ 312, 1899, p. 161; Willans's
central-valve engines; Donkin's single-acting runs).  The gear that serves the working
end is the scene's own; the idle end's steam port is never opened (its signed opening
held one port width under the lap) and its exhaust port stands wide open, so that
side of the piston breathes the exhaust (or the atmosphere the engine exhausts to) at
its pressure: its card is a line at back pressure, its work over a cycle the pumping
through a full port (a small loss), and it takes no steam from the chest.
"""

from __future__ import annotations

import numpy as np

from corliss.valves.gear import ValveGear

#: Which ends a cylinder may take steam at.
STEAM_ENDS = ("both", "head", "crank")


class SingleActing(ValveGear):
    """A gear whose one end takes no steam, its exhaust port held wide open.

    Parameters
    ----------
    gear : ValveGear
        The scene's gear, serving the working end.
    steam_end : str
        The end that takes steam: ``"head"`` (the end away from the shaft) or
        ``"crank"``.

    Raises
    ------
    ValueError
        For an end that is not ``"head"`` or ``"crank"``.
    """

    def __init__(self, gear: ValveGear, steam_end: str):
        if steam_end not in ("head", "crank"):
            raise ValueError(f"steam_end={steam_end!r}: \"head\" or \"crank\"")
        self.inner = gear
        self.steam_end = steam_end
        self.name = gear.name
        self.summary = gear.summary
        self.setting_name = gear.setting_name
        self.setting_range = gear.setting_range
        # ``spec`` and the rest of the inner gear's attributes come through __getattr__
        #: The idle end's ports in :data:`corliss.valves.gear.PORTS` order: steam, exhaust.
        self.idle_ports = (2, 3) if steam_end == "head" else (0, 1)

    def __getattr__(self, name):
        # what the wrapper does not define (a gear's own drawing data, ``with_speed``
        # and the like) is the inner gear's
        if name == "inner":
            raise AttributeError(name)
        return getattr(self.inner, name)

    def with_setting(self, value: float) -> "SingleActing":
        """The same single-acting gear with the inner gear at another setting.

        Parameters
        ----------
        value : float
            The new setting (the inner gear's units and range).

        Returns
        -------
        SingleActing
            A new wrapper round the inner gear at ``value``.
        """
        return SingleActing(self.inner.with_setting(value), self.steam_end)

    def with_speed(self, omega_rad_s: float) -> "SingleActing":
        """The same single-acting gear with the inner gear at the run's speed (for the
        gears whose motion depends on it; others are returned unchanged inside).

        Parameters
        ----------
        omega_rad_s : float
            Crank speed [rad/s].

        Returns
        -------
        SingleActing
            A new wrapper.
        """
        inner = (self.inner.with_speed(omega_rad_s) if hasattr(self.inner, "with_speed")
                 else self.inner)
        return SingleActing(inner, self.steam_end)

    def signed_openings(self, theta: np.ndarray) -> np.ndarray:
        """The inner gear's signed openings, the idle end's steam port held shut (one
        port width under its lowest kink level) and its exhaust port held full (one
        port width past its highest).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad], shape ``(n,)``.

        Returns
        -------
        ndarray
            Signed openings [m], shape ``(4, n)``.
        """
        s = np.array(self.inner.signed_openings(np.atleast_1d(theta)), dtype=float)
        w = self.inner.port_widths()
        lev = self.inner.kink_levels()
        st, ex = self.idle_ports
        # clear of every level the gear's areas kink at: no crossing, no event
        s[st] = lev[st].min() - w[st]
        s[ex] = lev[ex].max() + w[ex]
        return s

    def openings(self, theta: np.ndarray) -> np.ndarray:
        """Physical opening of each port: the inner gear's (its own area law kept), the
        idle end's steam port shut and its exhaust port full.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad], shape ``(n,)``.

        Returns
        -------
        ndarray
            Openings [m], shape ``(4, n)``.
        """
        o = np.array(self.inner.openings(np.atleast_1d(theta)), dtype=float)
        w = self.inner.port_widths()
        st, ex = self.idle_ports
        o[st] = 0.0
        o[ex] = w[ex]
        return o

    def areas(self, theta: np.ndarray) -> np.ndarray:
        """Open area of each port: the inner gear's, the idle end's steam port shut and
        its exhaust port at the most the inner gear ever opens it.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad], shape ``(n,)``.

        Returns
        -------
        ndarray
            Open areas [m2], shape ``(4, n)``.
        """
        a = np.array(self.inner.areas(np.atleast_1d(theta)), dtype=float)
        st, ex = self.idle_ports
        a[st] = 0.0
        a[ex] = self._full_exhaust_area()
        return a

    def _full_exhaust_area(self) -> float:
        """The most the inner gear opens the idle end's exhaust port over a turn [m2]."""
        th = np.linspace(0.0, 2.0 * np.pi, 721)
        return float(self.inner.areas(th)[self.idle_ports[1]].max())

    def port_widths(self) -> np.ndarray:
        """The inner gear's port widths [m], shape ``(4,)``.

        Returns
        -------
        ndarray
            Port widths [m].
        """
        return self.inner.port_widths()

    def port_lengths(self) -> np.ndarray:
        """The inner gear's effective port lengths [m], shape ``(4,)``.

        Returns
        -------
        ndarray
            Port lengths [m].
        """
        return self.inner.port_lengths()

    def openings_per_edge(self) -> np.ndarray:
        """The inner gear's openings at each edge [-], shape ``(4,)``.

        Returns
        -------
        ndarray
            Openings each port's edge uncovers [-].
        """
        return self.inner.openings_per_edge()

    def discharge_coefficients(self) -> np.ndarray:
        """The inner gear's discharge coefficients [-], shape ``(4,)``.

        Returns
        -------
        ndarray
            Discharge coefficients [-].
        """
        return self.inner.discharge_coefficients()

    def kink_levels(self) -> np.ndarray:
        """The inner gear's kink levels [m], shape ``(4, L)``.

        Returns
        -------
        ndarray
            Levels [m].
        """
        return self.inner.kink_levels()


def single_acting(gear: ValveGear, steam_ends: str) -> ValveGear:
    """The gear for a cylinder taking steam at ``steam_ends``: the gear itself for
    ``"both"``, else :class:`SingleActing` round it.

    Parameters
    ----------
    gear : ValveGear
        The scene's gear.
    steam_ends : str
        One of :data:`STEAM_ENDS`.

    Returns
    -------
    ValveGear
        The gear to tabulate.
    """
    return gear if steam_ends == "both" else SingleActing(gear, steam_ends)


def working_gear(gear):
    """The gear that moves the valve: the inner gear of a :class:`SingleActing`, any
    other gear itself (for the drawings, which show the valve and its linkage as
    built; the idle end's ports are the simulation's matter).

    Parameters
    ----------
    gear : ValveGear
        A gear.

    Returns
    -------
    ValveGear
        The gear whose linkage and valve are drawn.
    """
    return gear.inner if isinstance(gear, SingleActing) else gear
