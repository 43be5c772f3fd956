"""Radial valve gears: Hackworth, Marshall, Angstrom, Joy (Spangler Chs. XIII-XIV) and
Walschaerts, in Zeuner's form or solved exactly.

A radial gear takes the valve's motion from a point of a vibrating link one point of
which moves on a closed curve while another moves on a straight line or open curve
(Spangler Art. 92).  Every one of them moves the valve, to first order, as a single
virtual eccentric, x = C cos(theta) + S sin(theta), with C = lap + lead the valve's
displacement at the dead centre, the same at both ends and at every setting: the
constant lead of radial gears (Arts. 94, 111, 114).

Hackworth (Arts. 93-97), Marshall (105-108), Angstrom (109-110)
    An eccentric of throw r set opposite the crank (Art. 93) drives one end of the
    vibrating link (length l1, the book's "eccentric-rod" ch, Art. 107); its other end
    h slides along a guide through the point i it occupies at both dead centres; the
    valve rod is pinned at distance l2 from h (Art. 95)::

        C = (|l2| / l1) r          S = r ((l1 - l2) / l1) tan(alpha)        (Art. 95)

    with alpha the guide's inclination to the line of centres, the setting the reverse
    lever moves (alpha > 0 ahead, 0 mid gear, < 0 astern).  l2 is signed: positive
    between h and the eccentric (Fig. 62), negative beyond h ("attached outside",
    Art. 102: Problems 50-52 give l2 = -16 5/8 and -21 in; Bremme's lead arm
    hd = -4.5 ac, Art. 107).  An outside attachment sends the valve the other way at the
    dead centre, so the valve is connected (steam inside, or through a rocker, Art.
    101) to put the lead on the right port; x is reckoned that way, and alpha is then
    taken on the side that runs the engine ahead.  That is why C carries ``|l2|``: with l2
    the outside distance written positive, the result is the book's Art. 102 formula
    x = (l2/l1) r cos + r ((l1 + l2)/l1) tan(alpha) sin, which is right for the
    reversed connection (the book's text, "l2 changes sign", would give -(l2/l1) r cos
    with a direct one).  Hackworth's guide is straight; Marshall's h swings on a link
    gh = gi about the end g of the reversing arm, so it runs on a circular arc of radius
    ``guide_radius`` tangent at i to Hackworth's guide (Art. 105); Angstrom's h is the
    middle of the rod kl of a parallel motion (Watt's: two equal radius links of
    length ``parallel_link`` on opposite sides, pivoted so that at i they stand square
    to kl, of length ``parallel_rod``, which lies along the guide; Art. 109, Figs.
    71-72 are not in the text we have).

Joy (Arts. 112-114)
    No eccentric: a point d of the connecting rod (length b), at distance c from the
    crosshead, drives the jack link de (length l3), whose end e swings on the anchor
    link ef about the fixed point f; the vibrating lever ig is pinned to de at g
    (dg = l4); its point h (hg = l1) slides on the curved guide through k, which the
    reverse lever inclines by alpha; its end i, l2 beyond h, drives the valve rod.
    d moves across the line of stroke (c/b) R sin(theta), and g along it
    ((l3 - l4)/l3) R cos(theta) (Art. 113), so::

        C = ((l3 - l4)/l3) R (l2 / l1)       S = R ((l1 + l2)/l1) tan(alpha) (c/b)   (Art. 113)

    The exact linkage here places e at the same point at both dead centres
    (l3 sin(theta_d) = R, Art. 113's "d should travel symmetrically under k"), and k at
    distance l1 from both dead-centre positions of g (l4 sin(theta_d) + l1 sin(phi) = R):
    then h stands at k at both dead centres whatever alpha, and the lead is constant
    and equal at both ends exactly, as Art. 114 says of the actual gear.  The book's
    third condition, l4 vers(theta_d) = l1 vers(phi), only centres g's oval under k; a
    gear that misses it (Problem 57 does) still assembles.

Walschaerts (not in Spangler)
    A return crank of throw e about 90 deg from the main crank swings the expansion link
    about its trunnion through the eccentric rod pinned to the link's foot, a distance
    k below the trunnion; the radius rod runs from the die (offset u along the link
    from the trunnion: the setting) to the top of the combination lever, whose lower
    end the union link ties to the crosshead and from which the valve stem is driven,
    a from the radius rod's pin, the union link's pin being at l from it.

    *Derived here* (not from a book): with infinitely long rods the crosshead moves
    R cos(theta) and turns the lever about the radius-rod pin, moving the valve
    (a/l) R cos(theta): a component in phase with the piston, independent of the die;
    at the dead centres the link is square to the radius rod, so the die's position
    does not move the valve and that component alone is lap + lead.  The link turns
    (e/k) sin(theta) about its trunnion, so the die moves (u/k) e sin(theta); the lever,
    now turning about its union-link pin, multiplies that by (l + a)/l for a valve
    taking steam outside (valve pin beyond the radius-rod pin) or (l - a)/l for one
    taking steam inside (valve pin between the two)::

        C = (a/l) R                         S = (1 +- a/l)(u/k) e

    The lead is therefore the same at every cut-off and in both gears, as Marks,
    *Relative Proportions of the Steam-Engine*, Art. 72, says of Heusinger von
    Waldegg's (Walschaerts's) gear ("has a constant lead"), and as the American
    Locomotive Company's erecting rules quoted by L. V. Ludy, *Locomotive Boilers and
    Engines* (1920), p. 88, put it: the difference between the valve's positions on
    the two dead centres "is the lead and lap doubled and it cannot be changed except
    by changing the leverage relations of the combination lever".

``motion = "exact"`` solves each linkage with finite rods and links at every crank
angle (closed-form circle intersections where there are, a vectorised Newton solve
for the Angstrom parallel motion and the Walschaerts combination lever), tabulates it
at 1/2 deg and reads it back through a periodic cubic spline.  The valve's zero is set
for equal lead (the mean of its two dead-centre positions), and its travel is
reckoned in the sense that opens the head steam port, as everywhere.  Conventions of
the exact linkages (the book's figures are missing, so the unseen details are chosen
and said):

* Hackworth, Marshall, Angstrom: a vertical engine, cylinder above the shaft (head end
  up), the link running across the line of stroke from the eccentric to the guide, the
  valve above the link on a valve rod (``valve_rod``, default infinitely long) running
  parallel to the stroke.  ``hand = "right"`` is clockwise seen with the eccentric end
  on the left, the guide on the right and the valve above (Art. 98).  The Marshall
  arc's centre g is on the valve's side of the guide for a positive ``guide_radius``
  (that side gives Art. 106's statements on the two rotations; the other side
  reverses every one of them, see tests/test_radial_gears.py).
* Joy: a horizontal engine, cylinder on the right, the jack link hanging from d to e
  below the line of stroke and the lever rising from g past it to h and i (so that the
  vers terms of Art. 113 work against each other, and the valve stem stands about
  l2 + l1 - l4 above the cylinder's axis, as the book says), anchor pivot f on the
  shaft's side of e, valve rod (``valve_rod``) running from i towards
  the cylinder.  ``hand = "right"`` by Art. 98's definition is then counter-clockwise
  seen with the cylinder on the right (Fig. 73's arrow is the other way, left-hand).
  ``guide_radius`` is the radius of the curved guide (Problem 57: the reversing arm
  and radius rod, 12 in), its centre on the cylinder's side for a positive value;
  none for a straight guide.
* Walschaerts: a locomotive running ahead, seen from the side with the cylinder on the
  right (so the wheels turn clockwise); the crosshead on the line of stroke, the
  valve stem ``valve_height`` above it; the lever hanging from the valve stem, the
  union link horizontal at the dead centres; the radius rod horizontal at the dead
  centres, the link curved to the radius rod's length about the radius rod's pin there
  (so the lead stays exactly constant); the return crank set square to the line from
  the axle to the link's foot on the dead centres (the erecting rule: the link's foot
  takes the same place on both dead centres), which fixes how far ahead of the axle
  the link stands for the given eccentric rod; the die held at its place in the link
  (its slip neglected).  Two first-order effects of the finite rods vanish only as the
  rods grow: the die at arc length u along a link curved to the radius rod rho acts
  as if at rho tan(u/rho), and an eccentric rod inclined by phi at the dead centres
  swings the link 1/cos(phi) times more than the return crank's throw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import Table
from corliss.valves.gear import GearType, register
from corliss.valves.newton import newton2
from corliss.valves.slide_valve import (ALLEN_KEYS, LAP_KEYS, PORT_KEYS, LappedValve,
                                        parse_allen_passage, parse_ports)

#: The radial gears, by the ``kind`` key's values.
KINDS = ("hackworth", "marshall", "angstrom", "joy", "walschaerts")
SIMPLE = ("hackworth", "marshall", "angstrom")


@dataclass(frozen=True, kw_only=True)
class _RadialBase:
    """What every radial gear's spec carries (all SI).

    Attributes
    ----------
    kind : str
        One of :data:`~corliss.valves.radial_gear.KINDS`.
    setting : float
        The reverse lever's position, -1 (full gear astern) .. 0 (mid gear) .. 1 (full
        gear ahead): the guide's inclination alpha / alpha_max, or the Walschaerts die's
        offset u / u_max.
    motion : str
        ``"zeuner"`` or ``"exact"`` (see the module doc).
    valve_rod_m : float or None
        Length of the valve rod (the book's "valve connecting-rod") [m]; None for an
        infinitely long one.  Not used by the Walschaerts gear (the valve stem is
        guided straight).
    lap_m, exhaust_lap_m, port_width_m, port_length_m, discharge_coefficient,
    ports_per_end, allen_passage_m : as for the slide valve.
    """

    kind: str
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1
    allen_passage_m: float | None = None
    setting: float = 1.0
    motion: str = "zeuner"
    valve_rod_m: float | None = None


@dataclass(frozen=True, kw_only=True)
class SimpleRadialSpec(_RadialBase):
    """Hackworth, Marshall or Angstrom gear (Spangler Arts. 93-110; all SI).

    All fields are keyword-only.

    Parameters
    ----------
    kind : str
        One of :data:`~corliss.valves.radial_gear.KINDS`.
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
        Number of openings each edge uncovers (2 for a double-ported valve).
    allen_passage_m : float or None, optional
        Width of the mouth of an Allen (trick) valve's passage [m] (Spangler
        Art. 27); None for a plain valve.
    setting : float, optional
        The reverse lever's position, -1 (full gear astern) .. 0 (mid gear) .. 1 (full
        gear ahead) [-]: the guide's inclination alpha / alpha_max.
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (see the module doc).
    valve_rod_m : float or None, optional
        Length of the valve rod (the book's "valve connecting-rod") [m]; None for an
        infinitely long one.
    eccentricity_m : float
        r, throw of the eccentric set opposite the crank [m].
    link_m : float
        l1, the vibrating link ch from the eccentric's centre to the guided end h [m].
    valve_arm_m : float
        l2, the valve rod's pin from h along the link [m]: positive towards the
        eccentric, negative beyond h (attached outside).
    max_inclination_rad : float
        The guide's inclination alpha at full gear [rad] (Bremme: never above 25 deg,
        Art. 107).
    hand : str, optional
        ``"right"`` or ``"left"`` rotation (Art. 98).
    guide_radius_m : float or None, optional
        Marshall: radius gh = gi of h's arc [m], signed (positive: centre on the valve's
        side).  None for Hackworth's straight guide.
    parallel_link_m, parallel_rod_m : float or None, optional
        Angstrom: the parallel motion's radius links and the rod kl carrying h [m].
    """

    eccentricity_m: float
    link_m: float
    valve_arm_m: float
    max_inclination_rad: float
    hand: str = "right"
    guide_radius_m: float | None = None
    parallel_link_m: float | None = None
    parallel_rod_m: float | None = None

    @property
    def inclination_rad(self) -> float:
        """The guide's inclination alpha at this setting [rad]."""
        return self.setting * self.max_inclination_rad

    def coefficients(self, setting: float | None = None) -> tuple[float, float]:
        """Zeuner's form ``x = C cos(theta) + S sin(theta)`` (Spangler Art. 95).

        Parameters
        ----------
        setting : float or None, optional
            Reverse lever position alpha / alpha_max [-]; None for the spec's.

        Returns
        -------
        C, S : float
            Coefficients [m]: ``C = (|l2| / l1) r``, lap + lead, the same at every
            setting; ``S = r ((l1 - l2) / l1) tan(alpha)``.
        """
        s = self.setting if setting is None else setting
        r, l1, l2 = self.eccentricity_m, self.link_m, self.valve_arm_m
        return (abs(l2) / l1 * r,
                r * (l1 - l2) / l1 * math.tan(s * self.max_inclination_rad))

    @property
    def eccentric_rod_m(self) -> float | None:
        """The rod whose finite length the exact motion takes in (the book's eccentric
        rod ch, Art. 107) [m]; None in Zeuner's form."""
        return self.link_m if self.motion == "exact" else None


@dataclass(frozen=True, kw_only=True)
class JoySpec(_RadialBase):
    """Joy gear (Spangler Arts. 112-114; the book's letters; all SI).

    All fields are keyword-only.

    Parameters
    ----------
    kind : str
        One of :data:`~corliss.valves.radial_gear.KINDS`.
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
        Number of openings each edge uncovers (2 for a double-ported valve).
    allen_passage_m : float or None, optional
        Width of the mouth of an Allen (trick) valve's passage [m] (Spangler
        Art. 27); None for a plain valve.
    setting : float, optional
        The reverse lever's position, -1 (full gear astern) .. 0 (mid gear) .. 1 (full
        gear ahead) [-]: the curved guide's inclination alpha / alpha_max.
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (see the module doc).
    valve_rod_m : float or None, optional
        Length of the valve rod (the book's "valve connecting-rod") [m]; None for an
        infinitely long one.
    crank_m, connecting_rod_m : float
        R and b = cb [m].
    rod_point_m : float
        c, from the crosshead to the point d of the connecting rod [m].
    jack_link_m, jack_point_m : float
        l3 = de and l4 = dg [m].
    lever_m, valve_arm_m : float
        l1 = hg and l2 = hi [m] (i beyond h).
    anchor_link_m : float
        ef [m].
    max_inclination_rad : float
        alpha at full gear [rad].
    hand : str, optional
        ``"right"`` or ``"left"`` rotation (Art. 98).
    guide_radius_m : float or None, optional
        Radius of the curved guide lkm [m], signed (positive: centre on the
        cylinder's side); None for a straight guide.
    """

    crank_m: float
    connecting_rod_m: float
    rod_point_m: float
    jack_link_m: float
    jack_point_m: float
    lever_m: float
    valve_arm_m: float
    anchor_link_m: float
    max_inclination_rad: float
    hand: str = "right"
    guide_radius_m: float | None = None

    @property
    def inclination_rad(self) -> float:
        """The guide's inclination alpha at this setting [rad]."""
        return self.setting * self.max_inclination_rad

    def coefficients(self, setting: float | None = None) -> tuple[float, float]:
        """Zeuner's form ``x = C cos(theta) + S sin(theta)`` (Spangler Art. 113).

        Parameters
        ----------
        setting : float or None, optional
            Reverse lever position alpha / alpha_max [-]; None for the spec's.

        Returns
        -------
        C, S : float
            Coefficients [m]: ``C = ((l3 - l4)/l3) R (l2 / l1)``, lap + lead, the
            same at every setting; ``S = R ((l1 + l2)/l1) tan(alpha) (c/b)``.
        """
        s = self.setting if setting is None else setting
        R, b, c = self.crank_m, self.connecting_rod_m, self.rod_point_m
        l1, l2, l3, l4 = self.lever_m, self.valve_arm_m, self.jack_link_m, self.jack_point_m
        return ((l3 - l4) / l3 * R * l2 / l1,
                R * (l1 + l2) / l1 * math.tan(s * self.max_inclination_rad) * c / b)

    @property
    def eccentric_rod_m(self) -> float | None:
        """The connecting rod, whose finite length the exact motion takes in [m]; None
        in Zeuner's form."""
        return self.connecting_rod_m if self.motion == "exact" else None


@dataclass(frozen=True, kw_only=True)
class WalschaertsSpec(_RadialBase):
    """Walschaerts gear (see the module doc for the arrangement; all SI).

    All fields are keyword-only.

    Parameters
    ----------
    kind : str
        One of :data:`~corliss.valves.radial_gear.KINDS`.
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
        Number of openings each edge uncovers (2 for a double-ported valve).
    allen_passage_m : float or None, optional
        Width of the mouth of an Allen (trick) valve's passage [m] (Spangler
        Art. 27); None for a plain valve.
    setting : float, optional
        The reverse lever's position, -1 (full gear astern) .. 0 (mid gear) .. 1 (full
        gear ahead) [-]: the die's offset u / u_max.
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (see the module doc).
    valve_rod_m : float or None, optional
        Length of a valve rod [m]: not used, the Walschaerts valve stem being
        guided straight.
    crank_m, connecting_rod_m : float
        Main crank R and connecting rod [m].
    return_crank_m : float
        e, throw of the return crank (or eccentric) [m].
    eccentric_rod_m : float
        From the return crank's pin to the link's foot [m].
    link_foot_m : float
        k, from the link's trunnion to the eccentric rod's pin [m].
    max_die_m : float
        The die's greatest offset from the trunnion, full gear [m].
    radius_rod_m : float
        From the die to the combination lever; also the link's radius [m].
    lever_valve_m : float
        a, along the combination lever from the radius rod's pin to the valve stem's [m].
    lever_crosshead_m : float
        l, along the lever from the radius rod's pin to the union link's [m].
    union_link_m : float
        The union link, from the crosshead arm to the combination lever's lower pin
        [m].
    valve_height_m : float
        The valve stem's line above the line of stroke [m].
    admission : str, optional
        ``"outside"`` (D valve; valve pin above the radius rod's) or ``"inside"``
        (piston valve; valve pin between the radius rod's and the union link's).
    """

    crank_m: float
    connecting_rod_m: float
    return_crank_m: float
    eccentric_rod_m: float
    link_foot_m: float
    max_die_m: float
    radius_rod_m: float
    lever_valve_m: float
    lever_crosshead_m: float
    union_link_m: float
    valve_height_m: float
    admission: str = "outside"

    @property
    def die_m(self) -> float:
        """The die's offset u at this setting [m]."""
        return self.setting * self.max_die_m

    def coefficients(self, setting: float | None = None) -> tuple[float, float]:
        """Zeuner's form ``x = C cos(theta) + S sin(theta)`` (derived in the module
        doc).

        Parameters
        ----------
        setting : float or None, optional
            Die offset u / u_max [-]; None for the spec's.

        Returns
        -------
        C, S : float
            Coefficients [m]: ``C = (a/l) R``, lap + lead, the same at every
            setting; ``S = (1 +- a/l)(u/k) e`` (+ for outside admission).
        """
        s = self.setting if setting is None else setting
        q = self.lever_valve_m / self.lever_crosshead_m
        gain = 1.0 + q if self.admission == "outside" else 1.0 - q
        return (q * self.crank_m,
                gain * s * self.max_die_m / self.link_foot_m * self.return_crank_m)


SETTING_NAMES = {
    "hackworth": "guide inclination alpha / alpha_max (1 full gear ahead, 0 mid gear, -1 astern)",
    "marshall": "reversing arm's inclination alpha / alpha_max (1 ahead, 0 mid gear, -1 astern)",
    "angstrom": "parallel motion's inclination alpha / alpha_max (1 ahead, 0 mid gear, -1 astern)",
    "joy": "curved guide's inclination alpha / alpha_max (1 full gear ahead, 0 mid gear, -1 astern)",
    "walschaerts": "die offset u / u_max (1 full gear ahead, 0 mid gear, -1 full gear astern)",
}


class RadialGear(LappedValve):
    """A radial valve gear (Zeuner's form or exact) driving a lapped slide valve.

    Its setting is the reverse lever's, -1 (full gear astern) to 1 (full gear ahead);
    ``setting_name`` says what it moves for the spec's kind.  The exact motion is
    tabulated at 1/2 deg when the gear is built.

    Parameters
    ----------
    spec : SimpleRadialSpec or JoySpec or WalschaertsSpec
        The gear's linkage and its valve.

    Raises
    ------
    InputError
        With ``motion = "exact"``, if the linkage cannot be assembled at some crank
        angle.
    """

    name = "radial_gear"
    summary = ("radial gears, Zeuner's form or exact: Hackworth, Marshall, Angstrom, Joy "
               "(Spangler Chs. XIII-XIV) and Walschaerts; setting = reverse lever")
    setting_range = (-1.0, 1.0)

    def __init__(self, spec):
        self.spec = spec
        self.setting_name = SETTING_NAMES[spec.kind]
        self._spline = None
        self._zero = None
        if spec.motion == "exact":
            self._spline, self._zero = _tabulate(spec)

    def travel(self, theta):
        if self._spline is not None:
            return self._spline(np.asarray(theta, dtype=float) % (2 * math.pi))
        return self.zeuner_travel(theta)

    def zeuner_travel(self, theta):
        """Valve displacement of Zeuner's form, ``C cos(theta) + S sin(theta)``.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m] in the sense that opens the head steam port, of the
            shape of ``theta``.
        """
        C, S = self.spec.coefficients()
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)

    def joints(self, theta: float) -> "WalschaertsJoints | RadialJoints":
        """The exact gear's joints at crank angle ``theta``, from the solve whose valve
        positions, tabulated at 1/2 deg and splined, are :meth:`travel`.

        Parameters
        ----------
        theta : float
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        WalschaertsJoints or RadialJoints
            The joints [m] and the valve's displacement [m].

        Raises
        ------
        ValueError
            For a gear in Zeuner's form (not solved as a linkage).
        """
        if self._spline is None:
            raise ValueError("joints are solved for the exact radial gears only "
                             f"(this is {self.spec.kind} in Zeuner's form)")
        if self.spec.kind == "walschaerts":
            return walschaerts_joints(self.spec, theta, self._zero)
        return radial_joints(self.spec, theta, self._zero)


# --------------------------------------------------------------------------- exact linkages

N_TABLE = 720


def _tabulate(spec):
    """Valve travel of the exact linkage at 1/2 deg, zeroed for equal lead, as a
    periodic cubic spline."""
    from scipy.interpolate import CubicSpline

    th = np.linspace(0.0, 2 * math.pi, N_TABLE + 1)
    raw = exact_valve_position(spec, th)
    if not np.all(np.isfinite(raw)):
        raise InputError("valve_gear.motion", "exact",
                         "a gear whose linkage can be assembled at every crank angle: with "
                         "these dimensions a rod or link is too short to reach")
    zero = 0.5 * (raw[0] + raw[N_TABLE // 2])
    x = raw - zero
    x[-1] = x[0]
    return CubicSpline(th, x, bc_type="periodic"), float(zero)


def exact_valve_position(spec, theta: np.ndarray) -> np.ndarray:
    """The valve's position in the exact linkage, solved at each crank angle (see the
    module doc for each gear's arrangement).

    Parameters
    ----------
    spec : SimpleRadialSpec or JoySpec or WalschaertsSpec
        The gear.
    theta : float or ndarray
        Crank angles [rad] from head-end dead centre, shape ``(n,)``.

    Returns
    -------
    ndarray
        Valve position [m] in the sense that opens the head steam port, from an
        arbitrary origin (:class:`RadialGear` zeroes it for equal lead), shape
        ``(n,)``; NaN where the linkage cannot be assembled.
    """
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    if spec.kind in SIMPLE:
        return _simple(spec, th)
    if spec.kind == "joy":
        return _joy(spec, th)
    return _walschaerts(spec, th)


def circle_intersection(c1, r1, c2, r2, near):
    """The intersection of two circles nearer a given point, at every crank angle.

    Parameters
    ----------
    c1, c2 : ndarray
        The circles' centres, shape (2, n) [m].
    r1, r2 : float or ndarray
        Their radii [m].
    near : ndarray
        The point, shape (2, n) or (2,) [m], whose nearer intersection is taken.

    Returns
    -------
    ndarray
        The intersection, shape (2, n) [m]; NaN where the circles do not meet.
    """
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d = np.hypot(dx, dy)
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    with np.errstate(invalid="ignore"):
        h = np.sqrt(r1 * r1 - a * a)
    px, py = c1[0] + a * dx / d, c1[1] + a * dy / d
    ox, oy = -dy / d * h, dx / d * h
    p1 = np.array([px + ox, py + oy])
    p2 = np.array([px - ox, py - oy])
    n = np.asarray(near, dtype=float).reshape(2, -1)
    first = np.hypot(p1[0] - n[0], p1[1] - n[1]) <= np.hypot(p2[0] - n[0], p2[1] - n[1])
    return np.where(first, p1, p2)


def _on_guide(origin, t, nrm, radius, centre_of, reach, near):
    """Point of a guide through ``origin`` (tangent t, normal nrm) at distance ``reach``
    from ``centre_of`` (points, shape (2, n)): a straight guide for radius None, else an
    arc of |radius| with its centre on the side sign(radius) of nrm."""
    if radius is None:
        wx, wy = origin[0] - centre_of[0], origin[1] - centre_of[1]
        tw = t[0] * wx + t[1] * wy
        with np.errstate(invalid="ignore"):
            s = -tw + np.sqrt(tw * tw - (wx * wx + wy * wy) + reach * reach)
        return np.array([origin[0] + s * t[0], origin[1] + s * t[1]])
    rho = abs(radius)
    k = math.copysign(1.0, radius)
    cc = np.array([origin[0] + k * rho * nrm[0], origin[1] + k * rho * nrm[1]])
    cc = np.repeat(cc[:, None], centre_of.shape[1], axis=1)
    return circle_intersection(cc, rho, centre_of, reach, near)


def _simple(spec: SimpleRadialSpec, th):
    return _simple_points(spec, th)["x_raw"]


def _guide_points(origin, t, nrm, radius, span):
    """Points along a guide through ``origin`` (tangent t, normal nrm), straight for
    radius None, else an arc of |radius| centred on the side sign(radius) of nrm;
    ``span`` either way of ``origin``, shape (2, 21)."""
    s = np.linspace(-span, span, 21)
    if radius is None:
        return np.array([origin[0] + s * t[0], origin[1] + s * t[1]])
    rho = abs(radius)
    k = math.copysign(1.0, radius)
    cx, cy = origin[0] + k * rho * nrm[0], origin[1] + k * rho * nrm[1]
    a0 = math.atan2(origin[1] - cy, origin[0] - cx)
    # the arc's direction at origin is +t for one sense of the angle
    sense = 1.0 if (-math.sin(a0) * t[0] + math.cos(a0) * t[1]) > 0 else -1.0
    a = a0 + sense * s / rho
    return np.array([cx + rho * np.cos(a), cy + rho * np.sin(a)])


def _simple_points(spec: SimpleRadialSpec, th) -> dict:
    """The joints of the exact Hackworth, Marshall or Angstrom gear at crank angles
    ``th`` (arrays of shape (2, n) [m], X along the stroke towards the valve, Y across
    it), the guide, and ``x_raw``, the valve's position from an arbitrary origin."""
    r, l1, l2 = spec.eccentricity_m, spec.link_m, spec.valve_arm_m
    eps = 1.0 if spec.hand == "right" else -1.0
    sgn = 1.0 if l2 > 0 else -1.0
    tau = -sgn                                        # the valve's head-opening sense
    ap = sgn * eps * spec.inclination_rad             # the guide's physical inclination
    # X along the stroke (up, towards the valve); Y across it, from the shaft to the guide
    t = (math.sin(ap), math.cos(ap))
    nrm = (math.cos(ap), -math.sin(ap))
    D = math.sqrt(l1 * l1 - r * r)
    E = np.array([-r * np.cos(th), -eps * r * np.sin(th)])     # eccentric opposite the crank
    n = th.size
    G = np.array([[0.0], [D]])
    near = np.repeat(G, n, axis=1)
    if spec.kind == "angstrom":
        H = _watt(spec, G[:, 0], t, nrm, E, l1)
    else:
        H = _on_guide(G[:, 0], t, nrm, spec.guide_radius_m, E, l1, near)
    K = H + (l2 / l1) * (E - H)
    X = K[0]
    out = {"shaft": np.zeros((2, n)), "eccentric": E, "guided_end": H, "valve_pin": K}
    yf = D * (1.0 - l2 / l1)                          # the valve rod's line
    if spec.valve_rod_m is not None:
        g2 = spec.valve_rod_m
        with np.errstate(invalid="ignore"):
            X = X + np.sqrt(g2 * g2 - (K[1] - yf) ** 2)
        out["valve_rod_end"] = np.array([X, np.full(n, yf)])
    out["x_raw"] = tau * X
    out["guide"] = _guide_points(G[:, 0], t, nrm, spec.guide_radius_m, 1.2 * r)
    if spec.guide_radius_m is not None:             # Marshall: h swings on gh about g
        k = math.copysign(1.0, spec.guide_radius_m)
        rho = abs(spec.guide_radius_m)
        out["guide_centre"] = np.repeat(np.array([[G[0, 0] + k * rho * nrm[0]],
                                                  [G[1, 0] + k * rho * nrm[1]]]), n, axis=1)
    return out


def _watt(spec: SimpleRadialSpec, G, t, nrm, E, l1):
    """h on the Angstrom gear's parallel motion (Watt's, rod along the guide at i):
    a scalar Newton solve per crank angle for the first radius link's swing."""
    a, b = spec.parallel_link_m, spec.parallel_rod_m
    assert a is not None and b is not None   # an Angstrom gear's, read with its kind
    t, nrm = np.asarray(t), np.asarray(nrm)
    p1 = G - 0.5 * b * t + a * nrm
    p2 = G + 0.5 * b * t - a * nrm
    far = (G + 0.5 * b * t)[:, None]

    def h_of(beta):
        e1 = p1[:, None] - a * (np.outer(nrm, np.cos(beta)) - np.outer(t, np.sin(beta)))
        e2 = circle_intersection(np.repeat(p2[:, None], beta.size, axis=1), a, e1, b,
                      np.repeat(far, beta.size, axis=1))
        return 0.5 * (e1 + e2)

    def f(beta):
        h = h_of(beta)
        return np.hypot(h[0] - E[0], h[1] - E[1]) - l1

    straight = _on_guide(G, tuple(t), tuple(nrm), None, E, l1, None)
    s0 = (straight[0] - G[0]) * t[0] + (straight[1] - G[1]) * t[1]
    beta = np.arcsin(np.clip(s0 / a, -0.99, 0.99))
    for _ in range(40):
        f0 = f(beta)
        step = -f0 / ((f(beta + 1e-7) - f0) / 1e-7)
        beta = beta + step
        if np.max(np.abs(step)) < 1e-13:
            break
    return h_of(beta)


def _joy(spec: JoySpec, th):
    return _joy_points(spec, th)["x_raw"]


def _joy_points(spec: JoySpec, th) -> dict:
    """The joints of the exact Joy gear at crank angles ``th`` (arrays of shape (2, n)
    [m], X along the line of stroke towards the cylinder, Y up), the guide, and
    ``x_raw``, the valve's position from an arbitrary origin."""
    R, b, c = spec.crank_m, spec.connecting_rod_m, spec.rod_point_m
    l1, l2, l3, l4 = spec.lever_m, spec.valve_arm_m, spec.jack_link_m, spec.jack_point_m
    eps = 1.0 if spec.hand == "right" else -1.0
    ap = math.atan(-eps * math.tan(spec.inclination_rad))
    n = th.size
    # X along the line of stroke towards the cylinder, Y up; shaft at the origin
    B = np.array([R * np.cos(th), eps * R * np.sin(th)])
    Cx = B[0] + np.sqrt(b * b - B[1] ** 2)
    Dp = np.array([Cx + c / b * (B[0] - Cx), c / b * B[1]])
    dmid = b - c
    e0 = np.array([dmid, -math.sqrt(l3 * l3 - R * R)])     # e below the line of stroke
    f = e0 - np.array([spec.anchor_link_m, 0.0])
    E = circle_intersection(np.repeat(f[:, None], n, axis=1), spec.anchor_link_m, Dp, l3,
                 np.repeat(e0[:, None], n, axis=1))
    Gp = Dp + (l4 / l3) * (E - Dp)
    g0y = l4 / l3 * e0[1]
    half = R * (1.0 - l4 / l3)
    k = np.array([dmid, g0y + math.sqrt(l1 * l1 - half * half)])
    t = (math.sin(ap), math.cos(ap))
    nrm = (math.cos(ap), -math.sin(ap))
    H = _on_guide(k, t, nrm, spec.guide_radius_m, Gp, l1, np.repeat(k[:, None], n, axis=1))
    I = H + (l2 / l1) * (H - Gp)
    X = I[0]
    out = {"shaft": np.zeros((2, n)), "crank_pin": B, "crosshead": np.array([Cx, np.zeros(n)]),
           "rod_point": Dp, "anchor": np.repeat(f[:, None], n, axis=1), "jack_end": E,
           "jack_point": Gp, "guided_point": H, "valve_pin": I}
    if spec.valve_rod_m is not None:
        g2 = spec.valve_rod_m
        iy0 = k[1] + l2 / l1 * (k[1] - g0y)
        with np.errstate(invalid="ignore"):
            X = X + np.sqrt(g2 * g2 - (I[1] - iy0) ** 2)
        out["valve_rod_end"] = np.array([X, np.full(n, iy0)])
    out["x_raw"] = -X                           # head steam opens as the valve moves back
    out["guide"] = _guide_points(k, t, nrm, spec.guide_radius_m, 1.2 * half + 0.2 * l1)
    return out


@dataclass(frozen=True)
class RadialJoints:
    """The joints of an exact Hackworth, Marshall, Angstrom or Joy gear at one crank
    angle (all SI; see the module doc), each an (x, y) pair [m] in the figure's frame:
    for Hackworth, Marshall and Angstrom (a vertical engine) x across the stroke and y
    along it, up towards the valve; for Joy x along the line of stroke towards the
    cylinder and y up.  The shaft is at the origin.

    Parameters
    ----------
    points : dict
        Each joint by name (``shaft``, ``eccentric``, ``guided_end``, ``valve_pin``,
        ``valve_rod_end``, Marshall's ``guide_centre``; Joy's ``crank_pin``, ``crosshead``, ``rod_point``, ``anchor``,
        ``jack_end``, ``jack_point``, ``guided_point``) [m].
    guide : tuple of tuple of float
        Points along the guide the guided joint runs on, at this setting [m] (the
        Angstrom gear's parallel motion, which stands in for it, is not given).
    rods_m : dict
        Each rod or link: ``{name: (length [m], joint, joint)}``, a joint named as in
        ``points``.
    valve_m : float
        The valve's displacement in the sense that opens the head steam port [m], from
        its equal-lead zero.
    """

    points: dict
    guide: tuple
    rods_m: dict
    valve_m: float


def radial_joints(spec, theta: float, zero_m: float) -> RadialJoints:
    """The exact Hackworth, Marshall, Angstrom or Joy gear's joints at crank angle
    ``theta``, from the solve that gives its valve travel.

    Parameters
    ----------
    spec : SimpleRadialSpec or JoySpec
        The gear.
    theta : float
        Crank angle from head-end dead centre [rad].
    zero_m : float
        The valve's zero, the mean of :func:`exact_valve_position` at the two dead
        centres [m].

    Returns
    -------
    RadialJoints
        The joints [m] and the valve's displacement [m].
    """
    th = np.array([float(theta)])
    if spec.kind == "joy":
        pts = _joy_points(spec, th)
        swap = False
        rods = {"crank": (spec.crank_m, "shaft", "crank_pin"),
                "connecting rod": (spec.connecting_rod_m, "crank_pin", "crosshead"),
                "rod point": (spec.rod_point_m, "crosshead", "rod_point"),
                "jack link": (spec.jack_link_m, "rod_point", "jack_end"),
                "anchor link": (spec.anchor_link_m, "anchor", "jack_end"),
                "jack point": (spec.jack_point_m, "rod_point", "jack_point"),
                "lever": (spec.lever_m, "jack_point", "guided_point"),
                "valve arm": (spec.valve_arm_m, "guided_point", "valve_pin")}
    else:
        pts = _simple_points(spec, th)
        swap = True
        rods = {"eccentric": (spec.eccentricity_m, "shaft", "eccentric"),
                "link": (spec.link_m, "eccentric", "guided_end"),
                "valve arm": (abs(spec.valve_arm_m), "guided_end", "valve_pin")}
        if spec.guide_radius_m is not None:
            rods["reversing link"] = (abs(spec.guide_radius_m), "guide_centre", "guided_end")
    if spec.valve_rod_m is not None:
        rods["valve rod"] = (spec.valve_rod_m, "valve_pin", "valve_rod_end")
    x = float(pts.pop("x_raw")[0]) - zero_m
    guide = pts.pop("guide")

    def pt(v, i=0):
        return (float(v[1, i]), float(v[0, i])) if swap else (float(v[0, i]), float(v[1, i]))

    return RadialJoints(points={name: pt(v) for name, v in pts.items()},
                        guide=tuple(pt(guide, i) for i in range(guide.shape[1])),
                        rods_m=rods, valve_m=x)


def walschaerts_layout(spec: WalschaertsSpec) -> dict:
    """The fixed points of the exact Walschaerts gear (see the module doc).

    Coordinates: the axle at the origin, x towards the cylinder along the line of
    stroke, y up.

    Parameters
    ----------
    spec : WalschaertsSpec
        The gear.

    Returns
    -------
    dict
        ``A0``: the radius rod's pin at the dead centres; ``T``: the link's trunnion;
        ``F0``: the link's foot at the dead centres; ``Q0``: the return crank's pin at
        head dead centre (each an ndarray ``(x, y)`` [m]); ``gamma0``: the lever's
        swing at the dead centres [rad]; ``yL``: the union link's height [m];
        ``arm``: the crosshead arm's offset from the crosshead [m].  The trunnion's x
        is NaN when the eccentric rod cannot reach.
    """
    R, b, e, er = spec.crank_m, spec.connecting_rod_m, spec.return_crank_m, spec.eccentric_rod_m
    k, rho, a, ell, ul = (spec.link_foot_m, spec.radius_rod_m, spec.lever_valve_m,
                          spec.lever_crosshead_m, spec.union_link_m)
    g0 = math.asin(R / ell)
    ay = spec.valve_height_m + (-a if spec.admission == "outside" else a) * math.cos(g0)
    fy = ay - k
    reach2 = er * er - e * e - fy * fy
    tx = math.sqrt(reach2) if reach2 > 0 else float("nan")
    T = np.array([tx, ay])
    A0 = T + np.array([rho, 0.0])
    F0 = T + np.array([0.0, -k])
    Q0 = e * np.array([-F0[1], F0[0]]) / math.hypot(*F0)
    yL = ay - ell * math.cos(g0)
    return {"A0": A0, "T": T, "F0": F0, "Q0": Q0, "gamma0": g0, "yL": yL,
            "arm": A0[0] - ul - b}


def _walschaerts(spec: WalschaertsSpec, th):
    pts = _walschaerts_points(spec, th)
    return -pts["valve_pin"][0] if spec.admission == "outside" else pts["valve_pin"][0]


def combination_lever(Dd, XH, rho, a, ell, ul, yv, outside):
    """The combination lever of a Walschaerts or Baker gear solved at every crank angle:
    its radius rod (length ``rho``) pinned at ``Dd``, its union link (length ``ul``)
    at the crosshead arm ``XH`` (points, shape (2, n) [m]), its valve pin on the line
    ``y = yv``; ``a`` and ``ell`` from the radius rod's pin to the valve pin's and the
    union link's, the valve pin above the radius rod's (``outside``) or between the two.

    Parameters
    ----------
    Dd : ndarray
        The radius rod's (Baker: valve rod's) far end at each crank angle, shape (2, n) [m].
    XH : ndarray
        The union link's pin on the crosshead arm, shape (2, n) [m].
    rho : float
        The radius rod's length [m].
    a, ell : float
        Along the lever from the radius rod's pin to the valve pin and to the union
        link's pin [m].
    ul : float
        The union link's length [m].
    yv : float
        The valve stem's height [m].
    outside : bool
        Outside admission (the valve pin above the radius rod's pin).

    Returns
    -------
    V : ndarray
        The valve pin, shape (2, n) [m].
    w : ndarray
        The lever's unit vector, valve pin towards the radius rod's pin for outside
        admission (shape (2, n)).
    da, dl : float
        The radius rod's pin at ``V + da w`` and the union link's at ``V + dl w`` [m].
    """
    n = Dd.shape[1]
    # the lever: unknowns the valve pin's x and the lever's angle gamma from the vertical
    if outside:
        da, dl = -a, -(a + ell)            # A = V + da w, L = V + dl w
    else:
        da, dl = a, -(ell - a)

    def residual(vx, g):
        wx, wy = np.sin(g), np.cos(g)
        ax_, ay_ = vx + da * wx, yv + da * wy
        lx, ly = vx + dl * wx, yv + dl * wy
        return (np.hypot(ax_ - Dd[0], ay_ - Dd[1]) - rho,
                np.hypot(lx - XH[0], ly - XH[1]) - ul)

    ax0 = Dd[0] + rho
    lx0 = XH[0] + ul
    g = np.arcsin(np.clip((ax0 - lx0) / ell, -0.99, 0.99))
    vx = ax0 - da * np.sin(g)
    vx, g = newton2(residual, vx, g, 1e-7 * rho, 1e-8, 1e-13 * rho, 1e-13)
    w = np.array([np.sin(g), np.cos(g)])
    return np.array([vx, np.full(n, yv)]), w, da, dl


def _walschaerts_points(spec: WalschaertsSpec, th) -> dict:
    """Every joint of the exact Walschaerts gear at crank angles ``th`` (arrays of shape
    (2, n) [m]; see the module doc)."""
    R, b, e, er = spec.crank_m, spec.connecting_rod_m, spec.return_crank_m, spec.eccentric_rod_m
    k, rho, a, ell, ul = (spec.link_foot_m, spec.radius_rod_m, spec.lever_valve_m,
                          spec.lever_crosshead_m, spec.union_link_m)
    outside = spec.admission == "outside"
    lay = walschaerts_layout(spec)
    T, F0 = lay["T"], lay["F0"]
    n = th.size
    lam = math.atan2(lay["Q0"][1], lay["Q0"][0])
    # running ahead, clockwise seen with the cylinder on the right
    Q = np.array([e * np.cos(lam - th), e * np.sin(lam - th)])
    Bx, By = R * np.cos(th), -R * np.sin(th)
    Cx = Bx + np.sqrt(b * b - By * By)
    XH = np.array([Cx + lay["arm"], np.full(n, lay["yL"])])
    F = circle_intersection(np.repeat(T[:, None], n, axis=1), k, Q, er, np.repeat(F0[:, None], n, axis=1))
    beta = np.arctan2(F[0] - T[0], -(F[1] - T[1]))

    def on_link(s):
        px, py = rho * (1.0 - math.cos(s / rho)), rho * math.sin(s / rho)
        return np.array([T[0] + np.cos(beta) * px - np.sin(beta) * py,
                         T[1] + np.sin(beta) * px + np.cos(beta) * py])

    s = (1.0 if outside else -1.0) * spec.die_m
    Dd = on_link(s)
    V, w, da, dl = combination_lever(Dd, XH, rho, a, ell, ul, spec.valve_height_m, outside)
    umax = spec.max_die_m
    return {"axle": np.zeros((2, n)), "crank_pin": np.array([Bx, By]),
            "crosshead": np.array([Cx, np.zeros(n)]), "crosshead_arm": XH,
            "return_crank_pin": Q, "link_foot": F, "trunnion": np.repeat(T[:, None], n, axis=1),
            "link_top": on_link(umax), "link_bottom": on_link(-umax),
            "link_centre": on_link(0.0) + rho * np.array([np.cos(beta), np.sin(beta)]),
            "die": Dd, "radius_rod_pin": V + da * w, "valve_pin": V, "union_pin": V + dl * w}


@dataclass(frozen=True)
class WalschaertsJoints:
    """The joints of the exact Walschaerts gear at one crank angle (all SI; see the
    module doc): the axle at the origin, X along the line of stroke towards the
    cylinder, Y up; each point an (x, y) pair [m].

    Parameters
    ----------
    axle, crank_pin, crosshead : tuple of float
        The driving axle, the main crank's pin and the crosshead [m].
    crosshead_arm : tuple of float
        The union link's pin on the crosshead's arm [m].
    return_crank_pin, link_foot, trunnion : tuple of float
        The return crank's pin, the eccentric rod's pin at the link's foot and the
        link's fixed trunnion [m].
    link_top, link_bottom, link_centre : tuple of float
        The link's ends (the die's travel at full gear either way) and the centre of its
        arc [m].
    die : tuple of float
        The die in the link, where the radius rod takes its motion [m].
    radius_rod_pin, valve_pin, union_pin : tuple of float
        The combination lever's pins: the radius rod's, the valve stem's and the union
        link's [m].
    rods_m : dict
        Each rod's or arm's name and its length from the spec [m], with the pair of
        joints it joins: ``{name: (length, joint, joint)}``.
    valve_m : float
        The valve's displacement in the sense that opens the head steam port [m] (the
        valve pin's X, signed by admission, from its mean at the dead centres).
    """

    axle: tuple[float, float]
    crank_pin: tuple[float, float]
    crosshead: tuple[float, float]
    crosshead_arm: tuple[float, float]
    return_crank_pin: tuple[float, float]
    link_foot: tuple[float, float]
    trunnion: tuple[float, float]
    link_top: tuple[float, float]
    link_bottom: tuple[float, float]
    link_centre: tuple[float, float]
    die: tuple[float, float]
    radius_rod_pin: tuple[float, float]
    valve_pin: tuple[float, float]
    union_pin: tuple[float, float]
    rods_m: dict
    valve_m: float


def walschaerts_joints(spec: WalschaertsSpec, theta: float, zero_m: float) -> WalschaertsJoints:
    """The exact Walschaerts gear's joints at crank angle ``theta``, from the solve that
    gives its valve travel.

    Parameters
    ----------
    spec : WalschaertsSpec
        The gear.
    theta : float
        Crank angle from head-end dead centre [rad].
    zero_m : float
        The valve's zero, the mean of :func:`exact_valve_position` at the two dead
        centres [m].

    Returns
    -------
    WalschaertsJoints
        The joints [m] and the valve's displacement [m].
    """
    pts = _walschaerts_points(spec, np.array([float(theta)]))
    p = {name: (float(v[0, 0]), float(v[1, 0])) for name, v in pts.items()}
    vx = p["valve_pin"][0]
    x = (-vx if spec.admission == "outside" else vx) - zero_m
    rods = {"main crank": (spec.crank_m, "axle", "crank_pin"),
            "connecting rod": (spec.connecting_rod_m, "crank_pin", "crosshead"),
            "return crank": (spec.return_crank_m, "axle", "return_crank_pin"),
            "eccentric rod": (spec.eccentric_rod_m, "return_crank_pin", "link_foot"),
            "link foot": (spec.link_foot_m, "trunnion", "link_foot"),
            "radius rod": (spec.radius_rod_m, "die", "radius_rod_pin"),
            "lever, valve": (spec.lever_valve_m, "radius_rod_pin", "valve_pin"),
            "lever, crosshead": (spec.lever_crosshead_m, "radius_rod_pin", "union_pin"),
            "union link": (spec.union_link_m, "union_pin", "crosshead_arm")}
    return WalschaertsJoints(**p, rods_m=rods, valve_m=x)


# --------------------------------------------------------------------------- scene table

_SIMPLE = "with kind = \"hackworth\", \"marshall\" or \"angstrom\""
_GUIDED = "with kind = \"hackworth\", \"marshall\", \"angstrom\" or \"joy\""
_JOY_WALS = "with kind = \"joy\" or \"walschaerts\""
_WALS = "with kind = \"walschaerts\""


def _len(name: str, doc: str, when: str, positive: bool = True, **kw) -> Key:
    """A length key of some kinds of radial gear."""
    return Key(name, "length", doc, within=POSITIVE_LENGTH if positive else None, unit="in",
               when=when, **kw)


RADIAL_GEAR_KEYS = group(
    "radial_gear", "Radial valve gears (Spangler Arts. 98-110): Hackworth, Marshall, "
    "Angstrom, Joy and Walschaerts; the keys read depend on kind.",
    Key("kind", "choice", "Which radial gear.", choices=KINDS),
    LAP_KEYS,
    Key("setting", "number", "The reverse lever: -1 (full gear astern) through 0 (mid gear) "
        "to 1 (full gear ahead).", default=1.0, within=(-1.0, 1.0)),
    Key("motion", "choice", "Zeuner's motion or the exact linkage.", default="zeuner",
        choices=("zeuner", "exact")),
    ALLEN_KEYS, PORT_KEYS,
    Key("valve_rod", "length", "The valve rod (the book's valve connecting-rod); absent: "
        "infinitely long.", default=None, within=POSITIVE_LENGTH, unit="in",
        when="except with kind = \"walschaerts\""),
    _len("eccentricity", "r: throw of the eccentric set opposite the crank.", _SIMPLE),
    _len("link", "l1: the vibrating link from the eccentric's centre to the guided end, "
         "longer than the throw.", _SIMPLE),
    _len("valve_arm", "l2: the valve rod's pin from the guided end along the link (Joy: "
         "along the lever); below the link's length, negative beyond the guided end.",
         _GUIDED, positive=False),
    Key("max_inclination", "angle", "The guide's inclination at full gear, above 0 and below "
        "60 deg (Bremme: never above 25 deg, Art. 107).", within=(0.0, math.radians(60.0)),
        unit="deg", when=_GUIDED),
    Key("hand", "choice", "Right- or left-hand rotation (Art. 98).", default="right",
        choices=("right", "left"), when=_GUIDED),
    _len("guide_radius", "Radius of the guide's arc, signed (positive: centre on the valve's "
         "side; Joy: on the cylinder's); absent: a straight guide.",
         "with kind = \"marshall\" (required there) or \"joy\"", positive=False,
         default=None),
    _len("parallel_link", "Angstrom: the parallel motion's radius links.",
         "with kind = \"angstrom\" (required there)"),
    _len("parallel_rod", "Angstrom: the rod carrying the guided end.",
         "with kind = \"angstrom\" (required there)"),
    _len("stroke", "The engine's stroke (twice the main crank).", _JOY_WALS),
    _len("connecting_rod", "The engine's connecting rod.", _JOY_WALS),
    _len("rod_point", "c: from the crosshead to the point of the connecting rod the jack "
         "link hangs from.", "with kind = \"joy\""),
    _len("jack_link", "l3: the jack link, longer than the crank.", "with kind = \"joy\""),
    _len("jack_point", "l4: the lever's point on the jack link, below its length.",
         "with kind = \"joy\""),
    _len("lever", "l1: the lever to the guide.", "with kind = \"joy\""),
    _len("anchor_link", "The anchor link holding the jack link.", "with kind = \"joy\""),
    _len("lever_crosshead", "l: along the combination lever from the radius rod's pin to "
         "the union link's, longer than the crank.", _WALS),
    _len("lever_valve", "a: along the combination lever from the radius rod's pin to the "
         "valve stem's.", _WALS),
    Key("admission", "choice", "Outside admission (D valve) or inside (piston valve).",
        default="outside", choices=("outside", "inside"), when=_WALS),
    _len("link_foot", "k: from the link's trunnion to the eccentric rod's pin, longer than "
         "the return crank.", _WALS),
    _len("radius_rod", "From the die to the combination lever (also the link's radius), "
         "longer than max_die.", _WALS),
    _len("max_die", "The die's greatest offset from the trunnion, full gear.", _WALS),
    _len("return_crank", "e: throw of the return crank (or eccentric).", _WALS),
    _len("eccentric_rod", "From the return crank's pin to the link's foot.", _WALS),
    _len("union_link", "The union link from the crosshead to the combination lever.", _WALS),
    _len("valve_height", "The valve stem's line above the line of stroke.", _WALS,
         positive=False),
)


def _hand(t: Table) -> str:
    return t.get("hand")


def _inclination(t: Table) -> float:
    a = t.get("max_inclination")
    if not 0.0 < a < math.radians(60.0):
        raise InputError(t.key("max_inclination"), t.raw("max_inclination"),
                         "an angle above 0 and below 60 deg (Bremme: never above 25 deg, "
                         "Spangler Art. 107)")
    return a


def _setting(t: Table) -> float:
    return t.get("setting")


def _longer(t: Table, key: str, value: float, than: float, what: str) -> None:
    if not value > than:
        raise InputError(t.key(key), t.raw(key),
                         f"a length above {than / units.INCH_m:.4g} in ({what})")


def _signed_radius(t: Table) -> float | None:
    if not t.has("guide_radius"):
        return None
    v = t.get("guide_radius")
    if v == 0.0:
        raise InputError(t.key("guide_radius"), t.raw("guide_radius"),
                         "a nonzero radius (leave the key out for a straight guide)")
    return v


def parse_radial_gear(t: Table):
    """Read a ``[valve_gear] type = "radial_gear"`` table (keys per ``kind``).

    Parameters
    ----------
    t : Table
        The table, bound to :data:`RADIAL_GEAR_KEYS`.

    Returns
    -------
    SimpleRadialSpec or JoySpec or WalschaertsSpec
        The gear's spec, by ``kind``.
    """
    t = t.bound(RADIAL_GEAR_KEYS)
    kind = t.get("kind")
    common: dict[str, Any] = dict(
        kind=kind, lap_m=t.get("lap"), exhaust_lap_m=t.get("exhaust_lap"),
        setting=_setting(t), motion=t.get("motion"),
        allen_passage_m=parse_allen_passage(t), **parse_ports(t))
    if kind != "walschaerts" and t.has("valve_rod"):
        common["valve_rod_m"] = t.get("valve_rod")
    spec: SimpleRadialSpec | JoySpec | WalschaertsSpec
    if kind in SIMPLE:
        r = t.get("eccentricity")
        l1 = t.get("link")
        _longer(t, "link", l1, r, "the vibrating link must reach past the eccentric's throw")
        l2 = t.get("valve_arm")
        if l2 == 0.0 or l2 >= l1:
            raise InputError(t.key("valve_arm"), t.raw("valve_arm"),
                             "a nonzero distance from the guided end, below the link's length "
                             "(negative: attached outside, beyond the guided end)")
        extra: dict[str, Any] = {}
        if kind == "marshall":
            extra["guide_radius_m"] = _signed_radius(t)
            if extra["guide_radius_m"] is None:
                raise InputError(t.key("guide_radius"), None, "the radius gh = gi of the arc h "
                                 "swings on (Spangler Art. 105; Bremme: 6 times the eccentricity)")
        if kind == "angstrom":
            extra["parallel_link_m"] = t.get("parallel_link")
            extra["parallel_rod_m"] = t.get("parallel_rod")
        spec = SimpleRadialSpec(eccentricity_m=r, link_m=l1, valve_arm_m=l2,
                                max_inclination_rad=_inclination(t), hand=_hand(t),
                                **extra, **common)
    elif kind == "joy":
        R = t.get("stroke") / 2
        b = t.get("connecting_rod")
        c = t.get("rod_point")
        _longer(t, "connecting_rod", b, c, "the rod point lies on the connecting rod")
        l3 = t.get("jack_link")
        _longer(t, "jack_link", l3, R, "the jack link must reach past the crank radius")
        l4 = t.get("jack_point")
        if not l4 < l3:
            raise InputError(t.key("jack_point"), t.raw("jack_point"),
                             "a point on the jack link, below its length")
        l1 = t.get("lever")
        _longer(t, "lever", l1, R * (1 - l4 / l3), "the lever must reach the guide from g")
        spec = JoySpec(crank_m=R, connecting_rod_m=b, rod_point_m=c, jack_link_m=l3,
                       jack_point_m=l4, lever_m=l1,
                       valve_arm_m=t.get("valve_arm", within=POSITIVE_LENGTH),
                       anchor_link_m=t.get("anchor_link"),
                       max_inclination_rad=_inclination(t), hand=_hand(t),
                       guide_radius_m=_signed_radius(t), **common)
    else:
        R = t.get("stroke") / 2
        ell = t.get("lever_crosshead")
        _longer(t, "lever_crosshead", ell, R, "the lever must swing the crosshead's half stroke")
        a = t.get("lever_valve")
        admission = t.get("admission")
        if admission == "inside" and not a < ell:
            raise InputError(t.key("lever_valve"), t.raw("lever_valve"),
                             "with inside admission, a valve pin between the radius rod's and "
                             "the union link's (shorter than lever_crosshead)")
        k = t.get("link_foot")
        rho = t.get("radius_rod")
        umax = t.get("max_die")
        _longer(t, "radius_rod", rho, umax, "the link is curved to the radius rod")
        e = t.get("return_crank")
        _longer(t, "link_foot", k, e, "the link's foot must swing the return crank's throw")
        spec = WalschaertsSpec(crank_m=R, connecting_rod_m=t.get("connecting_rod"),
                               return_crank_m=e, eccentric_rod_m=t.get("eccentric_rod"),
                               link_foot_m=k, max_die_m=umax, radius_rod_m=rho, lever_valve_m=a,
                               lever_crosshead_m=ell, union_link_m=t.get("union_link"),
                               valve_height_m=t.get("valve_height"), admission=admission,
                               **common)
        if not math.isfinite(walschaerts_layout(spec)["T"][0]):
            raise InputError(t.key("eccentric_rod"), t.raw("eccentric_rod"),
                             "an eccentric rod long enough to reach the link's foot")
    C, S = spec.coefficients()
    reach = math.hypot(C, S)
    for end, lap in zip(("head", "crank"), spec.lap_m):
        if lap >= reach:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap below the virtual eccentric's throw at this setting "
                             f"({reach / units.INCH_m:.4g} in): the {end}-end port never opens")
    return spec


register(GearType("radial_gear", RadialGear.summary, parse_radial_gear, RadialGear,
                  RADIAL_GEAR_KEYS))
