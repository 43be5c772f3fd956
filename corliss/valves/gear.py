"""What every valve gear provides, and the registry of gears by name.

A gear is built from its frozen spec and answers one question: for crank angles
``theta`` [rad], how far is each of the four ports of a double-acting cylinder open?
It answers with *signed openings* [m]: the distance the controlling valve edge has
travelled past the port edge, positive when open, negative when the port is covered
(its magnitude then being the lap still to travel).  The physical opening is the
signed opening clipped to [0, port width]; the open area is that times the port
length times the number of openings.

Port order everywhere: head steam, head exhaust, crank steam, crank exhaust.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Callable, cast

import numpy as np

from corliss.keys.registry import Registry, RegistryEntry

#: Names of the four ports of a double-acting cylinder, in the order of every array of
#: openings, widths, lengths and areas.
PORTS = ("head_steam", "head_exhaust", "crank_steam", "crank_exhaust")


class ValveGear:
    """Base class of a valve gear.

    Subclasses set ``name`` and ``spec`` and implement :meth:`signed_openings`,
    :meth:`port_widths` and :meth:`port_lengths`.
    """

    # Each gear class sets these four; an instance may hold its own (a gear whose
    # setting's meaning depends on its spec's kind, a wrapper round another gear), so
    # they are instance attributes with class defaults, not class variables.
    name: str = "abstract"
    summary: str = ""
    #: What a reverse lever or governor moves, in its natural normalised form, or None.
    setting_name: str | None = None
    setting_range: tuple[float, float] | None = None
    #: The gear's frozen spec dataclass; each subclass sets (and may narrow) it.
    spec: Any

    def with_setting(self, value: float) -> "ValveGear":
        """The same gear at another setting of its reverse lever or governor.

        Parameters
        ----------
        value : float
            The new setting, in the gear's own normalised units (see
            ``setting_name``); must lie in ``setting_range``.

        Returns
        -------
        ValveGear
            A new gear of the same type, its spec changed only where the setting
            moves it.

        Raises
        ------
        ValueError
            If the gear has no setting, or ``value`` lies outside ``setting_range``.
        """
        if self.setting_range is None:
            raise ValueError(f"the {self.name} gear has no setting")
        lo, hi = self.setting_range
        if not lo <= value <= hi:
            raise ValueError(f"setting {value} outside [{lo}, {hi}]")
        return self._at_setting(float(value))

    def _at_setting(self, value: float) -> "ValveGear":
        """The gear rebuilt at a setting already checked: by default its spec's
        ``setting`` field replaced; a gear whose setting moves other fields overrides."""
        # every gear's constructor takes its spec, which the base class cannot declare
        rebuild = cast(Callable[[Any], ValveGear], type(self))
        return rebuild(dataclasses.replace(self.spec, setting=value))

    def signed_openings(self, theta: np.ndarray) -> np.ndarray:  # pragma: no cover
        """Signed opening of each port: how far the controlling edge has passed the
        port edge, positive open, negative covered (the lap still to travel).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre in the direction of
            rotation, shape ``(n,)``; any turn.

        Returns
        -------
        ndarray
            Signed openings [m], shape ``(4, n)``,
            in the order of :data:`~corliss.valves.gear.PORTS`.
        """
        raise NotImplementedError

    def port_widths(self) -> np.ndarray:  # pragma: no cover
        """Width of each port in the direction of valve travel.

        Returns
        -------
        ndarray
            The most the valve can open each port [m], shape ``(4,)``, in the order
            of :data:`~corliss.valves.gear.PORTS`.
        """
        raise NotImplementedError

    def port_lengths(self) -> np.ndarray:  # pragma: no cover
        """Length of each port across the valve face, times its number of openings.

        Returns
        -------
        ndarray
            Effective port length [m], shape ``(4,)``: open area [m2] per metre of
            opening,
            in the order of :data:`~corliss.valves.gear.PORTS`.
        """
        raise NotImplementedError

    def openings_per_edge(self) -> np.ndarray:
        """How many openings each port's controlling edge uncovers at once, all moving
        with the valve (a double-ported valve's two, Spangler Art. 26; a Porter-Allen
        steam plate's end and the openings through it, Art. 30): :meth:`port_lengths`
        is one opening's length times this.

        Returns
        -------
        ndarray
            Openings [-], shape ``(4,)``, in the order of
            :data:`~corliss.valves.gear.PORTS`; one each unless a gear says otherwise.
        """
        return np.ones(4)

    def discharge_coefficients(self) -> np.ndarray:  # pragma: no cover
        """Discharge coefficient of each port opening.

        Returns
        -------
        ndarray
            Discharge coefficient [-], shape ``(4,)``,
            in the order of :data:`~corliss.valves.gear.PORTS`.
        """
        raise NotImplementedError

    def kink_levels(self) -> np.ndarray:
        """Signed openings at which each port's open area has a kink.

        The tabulated :class:`~corliss.valves.portmap.PortMap` puts a grid point at
        every crossing of every level, so its linear interpolation is exact there.

        Returns
        -------
        ndarray
            Levels [m], shape ``(4, L)``: column 0 where the port opens (0), column 1
            where it is full (the port width), and any further columns a gear's own
            area law adds.
        """
        return np.column_stack([np.zeros(4), self.port_widths()])

    def openings(self, theta: np.ndarray) -> np.ndarray:
        """Physical opening of each port: the signed opening clipped to [0, port width].

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad], shape ``(n,)`` (a scalar counts as ``n = 1``).

        Returns
        -------
        ndarray
            Openings [m], shape ``(4, n)``,
            in the order of :data:`~corliss.valves.gear.PORTS`.
        """
        s = self.signed_openings(np.atleast_1d(theta))
        return np.clip(s, 0.0, self.port_widths()[:, None])

    def _openings_of(self, s: np.ndarray) -> np.ndarray:
        """:meth:`openings` from the signed openings ``s`` [m], shape ``(4, n)``."""
        return np.clip(s, 0.0, self.port_widths()[:, None])

    def sampled(self, theta: np.ndarray,
                signed: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`openings` and :meth:`signed_openings` at the same angles, the gear's
        motion found once where its openings are its signed ones clipped (a gear whose
        class has its own :meth:`openings` has both found as each finds them).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad], shape ``(n,)``.
        signed : ndarray, optional
            ``signed_openings(theta)`` when the caller has them [m], shape ``(4, n)``.

        Returns
        -------
        openings : ndarray
            Openings [m], shape ``(4, n)``, as :meth:`openings` gives them.
        signed : ndarray
            Signed openings [m], shape ``(4, n)``, as :meth:`signed_openings` gives them.
        """
        if type(self).openings in OPENINGS_OF_SIGNED:
            s = self.signed_openings(np.atleast_1d(theta)) if signed is None else signed
            return self._openings_of(s), s
        return self.openings(theta), (self.signed_openings(theta) if signed is None
                                      else signed)

    def areas(self, theta: np.ndarray) -> np.ndarray:
        """Open area of each port: the opening times the effective port length.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad], shape ``(n,)`` (a scalar counts as ``n = 1``).

        Returns
        -------
        ndarray
            Open areas [m2], shape ``(4, n)``,
            in the order of :data:`~corliss.valves.gear.PORTS`.
        """
        return self.openings(theta) * self.port_lengths()[:, None]


def openings_note(gear: ValveGear) -> str:
    """What a drawing of one edge's openings says of the ports whose edges uncover more
    than one opening (:meth:`ValveGear.openings_per_edge`): their areas are that many
    times the opening drawn.

    Parameters
    ----------
    gear : ValveGear
        The gear drawn.

    Returns
    -------
    str
        E.g. ``"steam ports: 2 openings an edge, the area 2 x the opening drawn"``;
        empty when every edge uncovers one opening.
    """
    n = np.asarray(gear.openings_per_edge(), dtype=float)
    if np.all(n == 1.0):
        return ""
    groups = {"steam": n[[0, 2]], "exhaust": n[[1, 3]]}
    parts = []
    for kind, counts in groups.items():
        if np.all(counts == counts[0]):
            if counts[0] != 1.0:
                parts.append(f"{kind} ports: {counts[0]:g} openings an edge")
        else:
            parts.append(f"{kind} ports: {counts[0]:g} (head), {counts[1]:g} (crank) "
                         "openings an edge")
    return "; ".join(parts) + ", the area that many times the opening drawn"


#: The :meth:`ValveGear.openings` methods that are ``_openings_of(signed_openings(theta))``
#: (:meth:`ValveGear.sampled` finds the motion once for those), with an ``_openings_of``
#: nondecreasing in each signed opening (the events take the largest opening as
#: ``_openings_of`` of the largest signed one: :func:`corliss.valves.events.events`).
OPENINGS_OF_SIGNED: set = {ValveGear.openings}

#: A registry entry: how to read a gear's scene table and build the gear.
GearType = RegistryEntry
GEARS = Registry("valve_gear.type", "gear")
register = GEARS.register
gear_type = GEARS.lookup
