"""The oscillating cylinder: the valve is the cylinder's own port face.

The cylinder swings on trunnions; its piston rod goes straight to the crank pin, so the
cylinder's axis always passes through the trunnion and the crank pin.  With the
trunnion a distance D from the shaft and a crank of radius R at crank angle theta from
head-end dead centre (the crank pin then pointing at the trunnion, the piston nearest
the head, the end beyond the trunnion), the cylinder's swing from the line of centres
is (*derived here*, the triangle shaft-trunnion-crank pin)::

    psi(theta) = atan2(R sin(theta), D - R cos(theta))       |psi| <= asin(R / D)

positive while the head end takes steam (0 < theta < 180 deg).  The largest swing,
asin(R/D), comes where cos(theta) = R/D.

The port face is flat, square to the trunnion, and swings against the face of the
standard.  The cylinder's port (one for each end of a double-acting cylinder: the head
end's at radius rho from the trunnion's centre towards the head, the crank end's
opposite it) is a slot of width ``w_c`` along its arc; the standard has a steam port
and an exhaust port of width ``w_s`` on the same circle, their centres ``beta_s`` and
``beta_e`` either side of the line of centres (the head end's steam port on the side the
cylinder's head-end port swings to while the head end takes steam; the crank end's
steam port on the same side of the line of centres, across the trunnion, where the
crank end's port, diametrically opposite the head end's, comes as the cylinder swings
back).  Two slots on one
circle overlap by ``(w_c + w_s)/2 - rho |psi - beta|`` (clipped to [0, min(w_c, w_s)]):
arc lengths on a circle add as on a straight face.  The port face is therefore a lapped
valve (:class:`~corliss.valves.slide_valve.LappedValve`) whose travel is the arc the
port swings through and whose laps are the arcs still to go at mid swing::

    x = rho psi
    steam lap   l = rho beta_s - (w_c + w_s)/2
    exhaust lap e = rho beta_e - (w_c + w_s)/2
    port width  min(w_c, w_s)

exactly, as long as the swing never carries the cylinder's port past full register
with the standard's port (the parser checks it: beyond, the opening would fall again
as the port runs off the far edge).  A zero lap admits at the dead centre and cuts off
at the other: the full-stroke admission of most toy and model oscillators.  The head
end's admission and cut-off fall where psi = l / rho on the way out and back, at
``R sin(theta + lambda) = D sin(lambda)`` with lambda = l / rho (the swing's equation
rearranged), the closed form tests/test_live_steam_gears.py checks the events against.

A single-acting oscillator is said as every single-acting cylinder is, with
``[engine] steam_ends = "head"`` (:mod:`corliss.valves.single_acting`): the crank end's
steam port never opens and its exhaust port stands open, so that side of the piston
breathes the exhaust, as the open-ended cylinder of a single-acting toy or model
oscillator breathes the air.  The gear's own ``acting`` key of earlier versions (which
closed the crank end instead, a space whose steam sprang back with the piston) is
refused, naming ``steam_ends``.

The piston moves ``sqrt(D^2 + R^2 - 2 D R cos(theta)) - (D - R)`` from head-end dead
centre: that of a slider crank whose connecting rod is D, to second order in R/D
(expand both: ``R (1 - cos) + R^2 sin^2 / (2 D)``), so the scene's engine takes
``connecting_rod`` = the trunnion's distance (at D = 4 R the two differ by at most
0.2 % of the stroke).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import DISCHARGE_COEFFICIENT, Table
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import LappedValve

@dataclass(frozen=True)
class OscillatingSpec:
    """An oscillating cylinder's port face (all SI).

    Parameters
    ----------
    crank_m : float
        Crank radius R, half the stroke [m].
    trunnion_distance_m : float
        D, from the shaft's centre to the trunnion's [m].
    port_radius_m : float
        rho, from the trunnion's centre to the ports' centres on the face [m].
    cylinder_port_m : float
        w_c, width of the cylinder's port along its arc [m].
    standard_port_m : float
        w_s, width of each of the standard's ports along the arc [m].
    steam_port_angle_rad : float
        beta_s, the standard's steam port's centre from the line of centres [rad].
    exhaust_port_angle_rad : float
        beta_e, the exhaust port's centre from the line of centres, the other side [rad].
    port_length_m : float
        The ports' extent across the arc (radially) [m].
    discharge_coefficient : float, optional
        Of the port opening [-].
    """

    crank_m: float
    trunnion_distance_m: float
    port_radius_m: float
    cylinder_port_m: float
    standard_port_m: float
    steam_port_angle_rad: float
    exhaust_port_angle_rad: float
    port_length_m: float
    discharge_coefficient: float = 0.7

    # what a lapped valve's spec carries (module doc)
    @property
    def lap_m(self) -> tuple[float, float]:
        """Steam lap of each end, ``rho beta_s - (w_c + w_s)/2`` [m]."""
        l = self.port_radius_m * self.steam_port_angle_rad - self._half
        return (l, l)

    @property
    def exhaust_lap_m(self) -> tuple[float, float]:
        """Exhaust lap of each end, ``rho beta_e - (w_c + w_s)/2`` [m]."""
        e = self.port_radius_m * self.exhaust_port_angle_rad - self._half
        return (e, e)

    @property
    def port_width_m(self) -> float:
        """The most two slots overlap, ``min(w_c, w_s)`` [m]."""
        return min(self.cylinder_port_m, self.standard_port_m)

    @property
    def ports_per_end(self) -> int:
        """One port each end [-]."""
        return 1

    @property
    def allen_passage_m(self) -> None:
        """No Allen passage."""
        return None

    @property
    def _half(self) -> float:
        return 0.5 * (self.cylinder_port_m + self.standard_port_m)

    @property
    def max_swing_rad(self) -> float:
        """The largest swing, ``asin(R / D)`` [rad]."""
        return math.asin(self.crank_m / self.trunnion_distance_m)


def swing_angle(spec: OscillatingSpec, theta) -> np.ndarray:
    """The cylinder's swing from the line of centres (module doc).

    Parameters
    ----------
    spec : OscillatingSpec
        The engine's crank and trunnion.
    theta : float or ndarray
        Crank angles [rad] from head-end dead centre.

    Returns
    -------
    ndarray
        psi [rad], positive while the head end takes steam, of the shape of ``theta``.
    """
    th = np.asarray(theta, dtype=float)
    R, D = spec.crank_m, spec.trunnion_distance_m
    return np.arctan2(R * np.sin(th), D - R * np.cos(th))


class OscillatingCylinder(LappedValve):
    """An oscillating cylinder's port face over the standard's ports (module doc).

    Parameters
    ----------
    spec : OscillatingSpec
        The crank, trunnion and ports.
    """

    name = "oscillating"
    summary = ("oscillating cylinder: the port face swings over the standard's ports as "
               "the crank turns")

    def __init__(self, spec: OscillatingSpec):
        self.spec = spec

    def travel(self, theta):
        """The arc the cylinder's port has swung through, ``rho psi(theta)``.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre.

        Returns
        -------
        ndarray
            x [m], in the sense that opens the head steam port.
        """
        return self.spec.port_radius_m * swing_angle(self.spec, theta)

    def joints(self, theta: float) -> "OscillatingJoints":
        """The shaft, crank pin, trunnion and piston at crank angle ``theta``.

        Parameters
        ----------
        theta : float
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        OscillatingJoints
            The joints [m], the swing [rad] and the port's travel [m].
        """
        return oscillating_joints(self.spec, float(theta))


@dataclass(frozen=True)
class OscillatingJoints:
    """An oscillating engine at one crank angle (all SI): the shaft at the origin, the
    trunnion on +Y at D, the crank turning clockwise seen from the port face's side.

    The piston rod is drawn D long, so that the piston is at the trunnion at mid swing
    of the rod (a schematic length: the port events do not depend on it).

    Parameters
    ----------
    shaft, crank_pin, trunnion, piston : tuple of float
        (x, y) [m].
    swing_rad : float
        psi [rad].
    valve_m : float
        The port's travel rho psi [m].
    rods_m : dict
        ``{name: (length [m], joint, joint)}``: the crank and the piston rod.
    """

    shaft: tuple[float, float]
    crank_pin: tuple[float, float]
    trunnion: tuple[float, float]
    piston: tuple[float, float]
    swing_rad: float
    valve_m: float
    rods_m: dict


def oscillating_joints(spec: OscillatingSpec, theta: float) -> OscillatingJoints:
    """The joints of :class:`OscillatingJoints` at crank angle ``theta``.

    Parameters
    ----------
    spec : OscillatingSpec
        The engine.
    theta : float
        Crank angle from head-end dead centre [rad].

    Returns
    -------
    OscillatingJoints
        The joints [m].
    """
    R, D = spec.crank_m, spec.trunnion_distance_m
    pin = (R * math.sin(theta), R * math.cos(theta))
    trunnion = (0.0, D)
    dx, dy = trunnion[0] - pin[0], trunnion[1] - pin[1]
    d = math.hypot(dx, dy)
    piston = (pin[0] + D * dx / d, pin[1] + D * dy / d)
    psi = float(swing_angle(spec, theta))
    return OscillatingJoints((0.0, 0.0), pin, trunnion, piston, psi,
                             spec.port_radius_m * psi,
                             {"crank": (R, "shaft", "crank_pin"),
                              "piston rod": (D, "crank_pin", "piston")})


_LEN: dict[str, Any] = dict(within=POSITIVE_LENGTH, unit="in")
OSCILLATING_KEYS = group(
    "oscillating", "An oscillating cylinder: its port face over the standard's ports, in "
    "the trunnion's terms.",
    Key("stroke", "length", "The engine's stroke (twice the crank): the gear's own copy of "
        "[engine].", **_LEN),
    Key("trunnion_distance", "length", "From the shaft's centre to the trunnion's, longer "
        "than the crank (the scene's engine takes it as its connecting rod).", **_LEN),
    Key("port_radius", "length", "From the trunnion's centre to the ports' centres on the "
        "port face.", **_LEN),
    Key("cylinder_port", "length", "Width of the cylinder's port along its arc.", **_LEN),
    Key("standard_port", "length", "Width of each of the standard's ports along the arc; "
        "absent: the cylinder port's.", default=None, **_LEN),
    Key("steam_port_angle", "angle", "The standard's steam port's centre from the line of "
        "centres (shaft to trunnion), seen from the trunnion.", within=(0.0, math.pi / 2),
        unit="deg"),
    Key("exhaust_port_angle", "angle", "The exhaust port's centre from the line of centres, "
        "on the other side; absent: the steam port's angle.", default=None,
        within=(0.0, math.pi / 2), unit="deg"),
    Key("port_length", "length", "The ports' extent across the arc (radially).", **_LEN),
    Key("discharge_coefficient", "number", "Discharge coefficient of a port opening.",
        default=0.7, within=DISCHARGE_COEFFICIENT),
)


def _deg(a: float) -> str:
    return f"{math.degrees(a):.4g} deg"


def parse_oscillating(t: Table) -> OscillatingSpec:
    """Read a ``[valve_gear] type = "oscillating"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`OSCILLATING_KEYS`.

    Returns
    -------
    OscillatingSpec
        The port face's spec.
    """
    if "acting" in t.data:
        # one way to say single-acting, for every gear: the engine's steam_ends
        raise InputError(t.key("acting"), t.data["acting"],
                         "no acting key: a single-acting oscillator is said as [engine] "
                         "steam_ends = \"head\" (the crank end's steam port shut, its "
                         "exhaust port open, as an open-ended cylinder's), and a "
                         "double-acting one by leaving steam_ends at its default, \"both\"")
    t = t.bound(OSCILLATING_KEYS)
    R = t.get("stroke") / 2
    D = t.get("trunnion_distance")
    if not D > R:
        raise InputError(t.key("trunnion_distance"), t.raw("trunnion_distance"),
                         f"a distance above the crank's radius ({R / units.INCH_m:.4g} in)")
    rho = t.get("port_radius")
    wc = t.get("cylinder_port")
    ws = t.get("standard_port") if t.has("standard_port") else wc
    bs = t.get("steam_port_angle")
    be = t.get("exhaust_port_angle") if t.has("exhaust_port_angle") else bs
    spec = OscillatingSpec(crank_m=R, trunnion_distance_m=D, port_radius_m=rho,
                           cylinder_port_m=wc, standard_port_m=ws, steam_port_angle_rad=bs,
                           exhaust_port_angle_rad=be, port_length_m=t.get("port_length"),
                           discharge_coefficient=t.get("discharge_coefficient"))
    psi = spec.max_swing_rad
    half = 0.5 * (wc + ws)
    for key, beta in (("steam_port_angle", bs), ("exhaust_port_angle", be)):
        opens = (beta * rho - half) / rho
        if not opens < psi:
            raise InputError(t.key(key), t.raw(key, None),
                             f"an angle below {_deg(psi + half / rho)}: the cylinder swings "
                             f"{_deg(psi)} either way (asin(R/D)), so its port never reaches "
                             "this one")
        register_end = beta + 0.5 * abs(wc - ws) / rho
        if psi > register_end:
            raise InputError(t.key(key), t.raw(key, None),
                             f"an angle of at least {_deg(psi - 0.5 * abs(wc - ws) / rho)}: "
                             f"the cylinder swings {_deg(psi)} either way and would carry its "
                             "port past full register with this one")
    if spec.lap_m[0] + spec.exhaust_lap_m[0] < 0.0:
        raise InputError(t.key("steam_port_angle"), t.raw("steam_port_angle"),
                         "ports spaced so that the cylinder's port never bridges the steam "
                         f"and exhaust ports: their centres at least {_deg(2 * half / rho)} "
                         "apart (steam plus exhaust angle), or steam blows through")
    return spec


register(GearType("oscillating", OscillatingCylinder.summary, parse_oscillating,
                  OscillatingCylinder, OSCILLATING_KEYS))
