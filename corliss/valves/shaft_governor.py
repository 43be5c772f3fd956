"""Shaft-governor eccentrics: the governor moves the eccentric's centre, changing throw
and advance together (Spangler Ch. XII, Arts. 84-91).

In Zeuner's form the valve moves as x = C cos(theta) + S sin(theta), where (C, S) is
the eccentric centre's position in the plane of the valve diagram: C = r sin(delta)
(lap + lead) and S = r cos(delta).  The governor's setting s runs from 0 (at rest,
greatest throw, latest cut-off) to 1 (full speed, least throw, earliest cut-off):

* ``path = "straight"``: the centre moves in a straight slot at right angles to the
  crank, as in the Erie governor (Art. 88) and the Armington & Sims double eccentric
  set for constant lead (Art. 89): C = lap + lead stays fixed and
  S(s) = r0 cos(delta0) - s d, with d the centre's travel across the shaft.
  The lead is the same at every load.
* ``path = "arc"``: the eccentric's pin swings on an arc about a point fixed to the
  flywheel, as in the Ball governor (Arts. 90-91): with the arc's centre at (C_v, S_v)
  and radius a, the pin is at (C_v + a cos(phi), S_v + a sin(phi)), phi running from
  phi0 at rest through a swing of dphi.  Its distribution is "practically the same as in
  a Stephenson's link with open rods": placed as the book places it, the lead grows as
  the cut-off shortens.

Piston valves taking steam inside (Armington & Sims, Ball) move the same x in the
sense that opens the head steam port, with the eccentric set accordingly (Art. 29).

**Finite eccentric rod** (optional ``eccentric_rod`` = g).  At each governor position the
eccentric is one of throw r = hypot(C, S) and advance delta = atan2(C, S), so the rod's
end falls short of its harmonic position by Zeuner's "missing quantity" g - sqrt(g^2 -
r^2 cos^2(theta + delta)) exactly as for the plain slide valve (Marks Art. 96, eqs.
229-232), where r cos(theta + delta) = S cos(theta) - C sin(theta) is the centre's
offset across the line of stroke.  The valve stem is set once, for equal lead with the
governor at rest (s = 0: the valve is set with the engine standing, the weights held in
by the springs), and the governor then moves the eccentric under that fixed setting::

    x = C cos(theta) + S sin(theta)
        + sigma [ sqrt(g^2 - S0^2) - sqrt(g^2 - (S cos(theta) - C sin(theta))^2) ]

with S0 the centre's S at rest and sigma the sign of the slide valve (+1 directly
connected taking steam outside, -1 taking steam inside or through a reverse lever;
Spangler Arts. 24, 29).  At a dead centre the correction is sigma [sqrt(g^2 - S0^2) -
sqrt(g^2 - S^2)], the same at both: it shifts the valve bodily, so once the governor
has moved (S != S0) one end gains the lead the other loses, by about (S0^2 - S^2)/(2g)
each: the straight path's constant lead (Art. 87) holds in Zeuner's form only.  Over
the revolution the correction is of order r^2/(2 g) and makes the crank positions at
cut-off no longer 180 deg apart (Spangler Art. 63).  ``zeuner_travel`` gives Zeuner's
form of the same setting, which ``travel`` is without a rod.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import Table
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import (ANGULAR_ADVANCE, ECCENTRICITY, LAP_KEYS, PORT_KEYS,
                                        LappedValve, parse_ports)


@dataclass(frozen=True)
class ShaftGovernorSpec:
    """A governor-moved eccentric and its valve (all SI; Spangler Ch. XII).

    Parameters
    ----------
    path : str
        ``"straight"`` (Erie, Armington & Sims) or ``"arc"`` (Ball).
    eccentricity_m : float
        Throw at rest (s = 0) [m]; for the arc it fixes, with the advance, the pin's
        position at rest.
    angular_advance_rad : float
        Advance at rest (s = 0) [rad].
    lap_m : tuple of float
        Steam lap of the (head, crank) end [m].
    exhaust_lap_m : tuple of float
        Exhaust lap of the (head, crank) end [m]; negative = exhaust clearance.
    port_width_m : float
        Width of each steam port in the direction of valve travel [m].
    port_length_m : float
        Length of each port across the valve face [m].
    discharge_coefficient : float, optional
        Of the port openings [-].
    ports_per_end : int, optional
        Number of openings each edge uncovers.
    centre_travel_m : float, optional
        Straight path: how far the centre moves across the shaft at s = 1 [m].
    arc_radius_m : float, optional
        Arc path: radius a of the pin's arc [m].
    arc_swing_rad : float, optional
        Arc path: the pin's swing dphi from rest to full speed [rad].
    arc_start_rad : float, optional
        Arc path: direction phi0 of the pin from the arc's centre at rest, in the
        valve-diagram plane [rad].
    setting : float, optional
        The governor's position s in [0, 1] [-].
    eccentric_rod_m : float or None, optional
        Eccentric rod plus valve stem g [m]; None for Zeuner's form.  The valve is set
        for equal lead at s = 0.
    connection : str, optional
        ``"direct"`` or ``"reverse_lever"``: with ``steam``, the sign of the rod's
        correction, as for the slide valve.
    steam : str, optional
        ``"outside"`` or ``"inside"``.
    """

    path: str
    eccentricity_m: float
    angular_advance_rad: float
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1
    centre_travel_m: float = 0.0
    arc_radius_m: float = 0.0
    arc_swing_rad: float = 0.0
    arc_start_rad: float = 0.0
    setting: float = 0.0
    eccentric_rod_m: float | None = None
    connection: str = "direct"
    steam: str = "outside"

    @property
    def sigma(self) -> int:
        """Sign with which the rod end's shortfall moves the valve (as the slide
        valve's).

        Returns
        -------
        int
            +1 direct with steam outside, -1 for one reversal, +1 for two [-].
        """
        return (1 if self.steam == "outside" else -1) * (1 if self.connection == "direct" else -1)

    def coefficients(self, s: float | None = None) -> tuple[float, float]:
        """The eccentric centre's position in the valve-diagram plane, at a governor
        setting: ``C = r sin(delta)`` (lap + lead), ``S = r cos(delta)`` (module doc).

        Parameters
        ----------
        s : float or None, optional
            Governor position in [0, 1] [-]; None for the spec's ``setting``.

        Returns
        -------
        C, S : float
            Coefficients [m] of the valve's Zeuner motion
            ``C cos(theta) + S sin(theta)``.
        """
        s = self.setting if s is None else s
        c0 = self.eccentricity_m * math.sin(self.angular_advance_rad)
        s0 = self.eccentricity_m * math.cos(self.angular_advance_rad)
        if self.path == "straight":
            return c0, s0 - s * self.centre_travel_m
        a, p0 = self.arc_radius_m, self.arc_start_rad
        cv, sv = c0 - a * math.cos(p0), s0 - a * math.sin(p0)
        p = p0 + s * self.arc_swing_rad
        return cv + a * math.cos(p), sv + a * math.sin(p)


class ShaftGovernorGear(LappedValve):
    """A slide or piston valve on a governor-moved eccentric.

    Its setting is the governor's position s, 0 at rest (full throw) to 1 at full
    speed.

    Parameters
    ----------
    spec : ShaftGovernorSpec
        The eccentric's path, the valve and its ports.
    """

    name = "shaft_governor"
    summary = ("shaft-governor eccentric: Erie and Armington & Sims (straight path, constant "
               "lead), Ball (arc) (Spangler Ch. XII); setting = governor position 0..1")
    setting_name = "governor position s (0 at rest, full throw; 1 at full speed)"
    setting_range = (0.0, 1.0)

    def __init__(self, spec: ShaftGovernorSpec):
        self.spec = spec

    def zeuner_travel(self, theta):
        """Zeuner's form ``x = C cos(theta) + S sin(theta)`` at this setting.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m], of the shape of ``theta``.
        """
        C, S = self.spec.coefficients()
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)

    def travel(self, theta):
        """Valve displacement: Zeuner's form, plus with a finite eccentric rod the
        rod end's shortfall measured from the valve's setting at rest (module doc).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m] in the sense that opens the head steam port, of the
            shape of ``theta``.
        """
        sp = self.spec
        x = self.zeuner_travel(theta)
        g = sp.eccentric_rod_m
        if g is None:
            return x
        C, S = sp.coefficients()
        S0 = sp.coefficients(0.0)[1]
        th = np.asarray(theta, dtype=float)
        across = S * np.cos(th) - C * np.sin(th)
        return x + sp.sigma * (math.sqrt(g * g - S0 * S0) - np.sqrt(g * g - across * across))


SHAFT_GOVERNOR_GEAR_KEYS = group(
    "shaft_governor", "A slide valve on an eccentric that a shaft governor moves across the "
    "shaft or swings on an arc.",
    Key("path", "choice", "The eccentric's centre moves straight across the shaft (Erie, "
        "Armington & Sims) or on an arc (Ball).", choices=("straight", "arc")),
    ECCENTRICITY, ANGULAR_ADVANCE,
    Key("centre_travel", "length", "How far the centre moves across the shaft at setting 1.",
        within=POSITIVE_LENGTH, unit="in", when="with path = \"straight\" (required there)"),
    Key("arc_radius", "length", "Radius of the pin's arc.", within=POSITIVE_LENGTH, unit="in",
        when="with path = \"arc\" (required there)"),
    Key("arc_swing", "angle", "The pin's swing from rest to full speed.", unit="deg",
        when="with path = \"arc\" (required there)"),
    Key("arc_start", "angle", "Direction of the pin from the arc's centre at rest.",
        unit="deg", when="with path = \"arc\" (required there)"),
    Key("setting", "number", "Governor position s, 0 (at rest) to 1.", default=0.0,
        within=(0.0, 1.0)),
    LAP_KEYS,
    Key("connection", "choice", "The valve driven directly or through a reversing rocker.",
        default="direct", choices=("direct", "reverse_lever")),
    Key("steam", "choice", "Steam outside (D valve) or inside (piston valve) the valve.",
        default="outside", choices=("outside", "inside")),
    Key("eccentric_rod", "length", "Eccentric rod plus valve stem, longer than the greatest "
        "throw; absent: Zeuner's form.", default=None, within=POSITIVE_LENGTH, unit="in"),
    PORT_KEYS,
)


def parse_shaft_governor(t: Table) -> ShaftGovernorSpec:
    """Read a ``[valve_gear] type = "shaft_governor"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`SHAFT_GOVERNOR_GEAR_KEYS`.

    Returns
    -------
    ShaftGovernorSpec
        The gear's spec.
    """
    t = t.bound(SHAFT_GOVERNOR_GEAR_KEYS)
    path = t.get("path")
    kw = {}
    if path == "straight":
        kw["centre_travel_m"] = t.get("centre_travel")
    else:
        kw["arc_radius_m"] = t.get("arc_radius")
        kw["arc_swing_rad"] = t.get("arc_swing")
        kw["arc_start_rad"] = t.get("arc_start")
    setting = t.get("setting")
    spec = ShaftGovernorSpec(path, t.get("eccentricity"), t.get("angular_advance"),
                             t.get("lap"), t.get("exhaust_lap"), setting=setting,
                             connection=t.get("connection"), steam=t.get("steam"),
                             **parse_ports(t), **kw)
    if t.has("eccentric_rod"):
        g = t.get("eccentric_rod")
        reach = max(math.hypot(*spec.coefficients(v)) for v in np.linspace(0.0, 1.0, 101))
        if g <= reach:
            raise InputError(t.key("eccentric_rod"), t.raw("eccentric_rod"),
                             f"an eccentric rod longer than the greatest throw over the "
                             f"governor's range ({reach / units.INCH_m:.4g} in)")
        spec = dataclasses.replace(spec, eccentric_rod_m=g)
    C, S = spec.coefficients()
    if max(spec.lap_m) >= math.hypot(C, S):
        raise InputError(t.key("setting"), setting, "a setting at which the eccentric's throw "
                         "exceeds the lap (otherwise the port never opens)")
    return spec


register(GearType("shaft_governor", ShaftGovernorGear.summary, parse_shaft_governor,
                  ShaftGovernorGear, SHAFT_GOVERNOR_GEAR_KEYS))
