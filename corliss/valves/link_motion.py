"""Link motions in Zeuner's form: Stephenson (open and crossed rods), Gooch, Allen.

Two eccentrics of throw r and equal angular advance delta drive the ends of a link of
half-chord c through rods of length g; the valve takes its motion from the block at
distance u from the link's centre, the setting the reversing lever (or a governor)
moves, from u = c (full gear ahead) through 0 (mid gear) to -c (full gear astern).
With the rods' ends on straight lines through the shaft and the link's radius,
hanger arc and slip neglected (Spangler Art. 45), every one of these gears moves the
valve as a single "virtual" eccentric, x = C cos(theta) + S sin(theta)::

    Stephenson, open rods    C = r (sin d + (c^2 - u^2)/(c g) cos d)     S = (u r / c) cos d   (Art. 46)
    Stephenson, crossed rods C = r (sin d - (c^2 - u^2)/(c g) cos d)     S = -(u r / c) cos d  (Art. 55)
    Gooch                    C = r (sin d + (c / g) cos d)                S = (u r / c)(cos d - (c/g) sin d)  (Art. 65)
    Allen                    C = r (sin d + (c^2 - u u1)/(c g) cos d)     S = (u r / c)(cos d - c (u - u1)/(u g) sin d)  (Art. 73)

with C = lap + lead, the valve's displacement at the dead point.  For the Allen link
``u1`` is the link's own share of the block's offset, u1 = k u with k from the rocker
arms (k = 1 is Stephenson's open rods, k = 0 Gooch's fixed link).  The exact linkage
motion (finite rods, link radius, hanger, slip) is not in this module yet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.tables import Table
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import LappedValve, pair, parse_ports

KINDS = ("stephenson_open", "stephenson_crossed", "gooch", "allen")


@dataclass(frozen=True)
class LinkMotionSpec:
    """A link motion in Zeuner's form (all SI).

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    eccentricity_m, angular_advance_rad : float
        Throw r [m] and angular advance delta [rad] of both eccentrics.
    eccentric_rod_m : float
        Eccentric rod length g [m].
    half_link_m : float
        Half the chord of the link, c [m].
    block_m : float
        Offset u of the block from the link's centre [m], the setting, in [-c, c].
    allen_ratio : float
        u1 / u for the Allen link [-].
    lap_m, exhaust_lap_m, port_width_m, port_length_m, discharge_coefficient,
    ports_per_end : as for the slide valve.
    """

    kind: str
    eccentricity_m: float
    angular_advance_rad: float
    eccentric_rod_m: float
    half_link_m: float
    block_m: float
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1
    allen_ratio: float = 0.5

    def coefficients(self, u: float | None = None) -> tuple[float, float]:
        """(C, S) of x = C cos(theta) + S sin(theta) [m] at block offset ``u`` [m]."""
        r, d, g, c = (self.eccentricity_m, self.angular_advance_rad, self.eccentric_rod_m,
                      self.half_link_m)
        u = self.block_m if u is None else u
        sd, cd = math.sin(d), math.cos(d)
        if self.kind == "stephenson_open":
            return r * (sd + (c * c - u * u) / (c * g) * cd), u * r / c * cd
        if self.kind == "stephenson_crossed":
            return r * (sd - (c * c - u * u) / (c * g) * cd), -u * r / c * cd
        if self.kind == "gooch":
            return r * (sd + c / g * cd), u * r / c * (cd - c / g * sd)
        u1 = self.allen_ratio * u
        return (r * (sd + (c * c - u * u1) / (c * g) * cd),
                u * r / c * cd - r * (u - u1) / g * sd)

    @property
    def setting_range(self) -> tuple[float, float]:
        """Range of the setting (block offset u) [m]."""
        return (-self.half_link_m, self.half_link_m)


class LinkMotion(LappedValve):
    """A link motion (Zeuner form) driving a lapped slide valve."""

    name = "link_motion"
    summary = ("link motions in Zeuner's form: Stephenson open or crossed rods, Gooch, Allen "
               "(Spangler Chs. VII-XI); setting = block offset")

    setting_name = "block offset u / c (1 full gear ahead, 0 mid gear, -1 full gear astern)"
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: LinkMotionSpec):
        self.spec = spec

    def with_setting(self, value: float) -> "LinkMotion":
        import dataclasses
        lo, hi = self.setting_range
        if not lo <= value <= hi:
            raise ValueError(f"setting {value} outside {self.setting_range}")
        return LinkMotion(dataclasses.replace(self.spec, block_m=value * self.spec.half_link_m))

    def travel(self, theta):
        C, S = self.spec.coefficients()
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)


def parse_link_motion(t: Table) -> LinkMotionSpec:
    """Read a ``[valve_gear] type = "link_motion"`` table."""
    kind = t.choice("link", KINDS)
    r = t.length("eccentricity", positive=True)
    delta = t.angle("angular_advance")
    g = t.length("eccentric_rod", positive=True)
    c = t.length("half_link", positive=True)
    u = t.length("block")
    if abs(u) > c:
        raise InputError(t.key("block"), t.raw("block"),
                         f"a block offset within the link, -{c / 0.0254:.4g} in to "
                         f"{c / 0.0254:.4g} in (the half chord)")
    k = t.number("allen_ratio", 0.5) if kind == "allen" else 0.5
    if not 0.0 <= k <= 1.0:
        raise InputError(t.key("allen_ratio"), k, "a ratio from 0 (Gooch) to 1 (Stephenson)")
    spec = LinkMotionSpec(kind, r, delta, g, c, u, pair(t, "lap", "length"),
                          pair(t, "exhaust_lap", "length", "0 in"), allen_ratio=k,
                          **parse_ports(t))
    C, S = spec.coefficients()
    reach = math.hypot(C, S)
    for end, lap in zip(("head", "crank"), spec.lap_m):
        if lap >= reach:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap below the virtual eccentric's throw at this block "
                             f"({reach / 0.0254:.4g} in): the {end}-end port never opens")
    return spec


register(GearType("link_motion", LinkMotion.summary, parse_link_motion, LinkMotion))
