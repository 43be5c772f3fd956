"""The plain D slide valve driven by a single eccentric.

Valve displacement, positive in the sense that opens the head-end steam port
(Spangler, *Valve-Gears*, Art. 13, eq. 4)::

    x(theta) = r sin(theta + delta)                       Zeuner (infinite rod)

With an eccentric rod of finite length ``g`` the rod end falls short of its
harmonic position by ``g - sqrt(g^2 - r^2 cos^2(theta + delta))``, always towards the
shaft (Marks, *Relative Proportions*, Art. 96, eqs. 229-232: Zeuner's "missing
quantity").  The valve takes that shortfall with the sign ``sigma``: +1 for a
directly connected valve taking steam outside, -1 through a reverse lever or with
steam inside (Spangler Arts. 24, 29: either reversal puts the eccentric behind the
crank).  A valve set for equal lead (the usual practice; Marks Art. 96: "equalizing
the lead very nearly equalizes the cut-off") has its zero at the mean of its two
dead-point positions, so the correction vanishes at both dead centres::

    x(theta) = r sin(theta + delta)
               + sigma [ sqrt(g^2 - r^2 cos^2 delta) - sqrt(g^2 - r^2 cos^2(theta + delta)) ]

A valve set for equal extreme travels (``setting = "mid_travel"``) keeps the whole
correction instead.

Port openings (Spangler Arts. 15-17, pp. 13-14): head steam ``x - l_h``,
head exhaust ``-x - e_h``, crank steam ``-x - l_c``, crank exhaust ``x - e_c``, with
``l`` the steam lap and ``e`` the exhaust lap of each end (negative for clearance).

A double-ported valve (Spangler Art. 26) is ``ports_per_end = 2``: each edge uncovers
two openings into the same passage, "the problem is exactly the same as for a single
valve", only the area doubles.  The Allen or trick valve (Art. 27) carries a passage
``e`` cast through it: as the valve's end passes the edge of the port, the far end of
the passage passes the outer edge of the seat at the same moment, so steam enters the
port past the valve's edge *and* through the passage, "double the area for the same
movement".  The passage's own mouth, of width ``a`` (``allen_passage``), limits what it
adds, and both streams enter the cylinder through the same port face of width ``w``, so
with ``p = x - l`` the steam port's effective opening is::

    min(p + min(p, a), w)    for p >= 0 (0 while the port is covered)

twice the plain opening while ``p < a`` (and ``2 p < w``), the plain opening plus ``a``
beyond, until the port face is full.  The signed openings (and so every event, the
lead and the overtravel) stay the plain valve's: the passage opens and closes with the
valve's edge.  Exhaust is under the valve "as in the plain slide" and is unchanged.
The opening has kinks where ``p = a`` and where it reaches ``w``; a PortMap puts on its
grid only the angles where the *signed* opening crosses 0 and ``w``, so those two kinks
fall between grid points: linear interpolation across a kink errs by at most r h / 4
of opening (h the grid's step; 0.16 % of a locomotive port's full area on the default
1440-interval grid).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.valves.gear import OPENINGS_OF_SIGNED, GearType, ValveGear, register
from corliss.valves.travel_kernel import eccentric_signed, eccentric_travel
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import DISCHARGE_COEFFICIENT, Table


@dataclass(frozen=True)
class SlideValveSpec:
    """A plain slide valve and its eccentric (all SI).

    Parameters
    ----------
    eccentricity_m : float
        Eccentric throw r, half the valve travel [m].
    lap_m : tuple of float
        Steam lap of the (head, crank) end [m].
    exhaust_lap_m : tuple of float
        Exhaust lap of the (head, crank) end [m]; negative = exhaust clearance.
    angular_advance_rad : float
        Angular advance delta [rad].
    port_width_m, port_length_m : float
        Width of each steam port in the direction of valve travel, and its length
        across the valve face [m].
    discharge_coefficient : float, optional
        Of the port opening [-].
    eccentric_rod_m : float or None, optional
        Eccentric rod plus valve stem length g [m]; None for the Zeuner motion
        (an infinite rod).
    connection : str, optional
        ``"direct"`` or ``"reverse_lever"`` (which reverses the valve's motion:
        Spangler Art. 24).
    steam : str, optional
        ``"outside"`` (D valve) or ``"inside"`` (piston valve, Spangler Art. 29).
    setting : str, optional
        ``"equal_lead"`` (the valve's zero at the mean of its two dead-point
        positions) or ``"mid_travel"`` (equal extreme travels); matters only with a
        finite rod (see the module doc).
    ports_per_end : int, optional
        Number of openings each edge uncovers (2 for a double-ported valve,
        Spangler Art. 26).
    allen_passage_m : float or None, optional
        Width of the mouth of an Allen (trick) valve's supplementary passage [m]
        (Spangler Art. 27); None for a plain valve.
    """

    eccentricity_m: float
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    angular_advance_rad: float
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    eccentric_rod_m: float | None = None
    connection: str = "direct"
    steam: str = "outside"
    setting: str = "equal_lead"
    ports_per_end: int = 1
    allen_passage_m: float | None = None

    @property
    def sigma(self) -> int:
        """Sign with which the rod-end shortfall moves the valve.

        Returns
        -------
        int
            +1 for a directly connected valve taking steam outside, -1 through a
            reverse lever or with steam inside, +1 with both [-].
        """
        a = 1 if self.steam == "outside" else -1
        b = 1 if self.connection == "direct" else -1
        return a * b

    @property
    def lead_m(self) -> tuple[float, float]:
        """Zeuner lead of each end, ``r sin(delta) - lap`` (Spangler Art. 14).

        Returns
        -------
        tuple of float
            Lead of the (head, crank) end [m], the steam port's opening at the end's
            dead centre on an infinite rod.
        """
        rs = self.eccentricity_m * math.sin(self.angular_advance_rad)
        return (rs - self.lap_m[0], rs - self.lap_m[1])


class LappedValve(ValveGear):
    """A valve whose displacement ``x`` (in the sense that opens the head steam port)
    uncovers the ports past its laps: head steam ``x - l_h``, head exhaust ``-x - e_h``,
    crank steam ``-x - l_c``, crank exhaust ``x - e_c`` (Spangler Art. 15).  Subclasses
    give :meth:`travel`; the spec carries ``lap_m``, ``exhaust_lap_m``, ``port_width_m``,
    ``port_length_m``, ``ports_per_end`` and ``discharge_coefficient``, and may carry
    ``allen_passage_m`` (an Allen valve's passage, Spangler Art. 27: see the module doc)."""

    def travel(self, theta: np.ndarray) -> np.ndarray:  # pragma: no cover - interface
        """Valve displacement in the sense that opens the head steam port, from the
        valve's zero as its gear sets it (mid travel, or the mean of its dead-centre
        positions for a valve set for equal lead).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacement x [m], shape ``(n,)``.
        """
        raise NotImplementedError

    def signed_openings(self, theta):
        x = self.travel(theta)
        lh, lc = self.spec.lap_m
        eh, ec = self.spec.exhaust_lap_m
        if x.ndim != 1:
            return np.vstack([x - lh, -x - eh, -x - lc, x - ec])
        # the four rows written in place (the same operations: -x once, each row's
        # difference), not made apart and stacked: a turn's 7201 samples a run
        out = np.empty((4, x.size))
        np.negative(x, out=out[2])
        np.subtract(out[2], eh, out=out[1])
        np.subtract(out[2], lc, out=out[2])
        np.subtract(x, lh, out=out[0])
        np.subtract(x, ec, out=out[3])
        return out

    def openings(self, theta):
        """Physical opening of each port; an Allen valve's steam ports add the
        passage's opening ``min(p, a)`` to the plain one, up to the port's width
        (Spangler Art. 27).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad], shape ``(n,)`` (a scalar counts as ``n = 1``).

        Returns
        -------
        ndarray
            Openings [m], shape ``(4, n)``, each in [0, port width], in the order of
            :data:`corliss.valves.gear.PORTS`.
        """
        return self._openings_of(self.signed_openings(np.atleast_1d(theta)))

    def _openings_of(self, s):
        """:meth:`openings` from the signed openings ``s`` [m], shape ``(4, n)``."""
        w = self.spec.port_width_m
        out = np.clip(s, 0.0, w)
        a = getattr(self.spec, "allen_passage_m", None)
        if a:
            for port in (0, 2):
                out[port] = np.minimum(out[port] + np.clip(s[port], 0.0, a), w)
        return out

    def kink_levels(self):
        """Signed openings at which each port's open area has a kink.

        With an Allen passage of width ``a``, the steam ports' area also kinks where
        the passage is full (plain opening ``a``) and where the two together fill the
        port (``p + min(p, a) = w``).

        Returns
        -------
        ndarray
            Levels [m], shape ``(4, 2)`` for a plain valve, ``(4, 4)`` with an Allen
            passage (the exhaust ports' extra levels are 0, repeating their opening).
        """
        base = super().kink_levels()
        a = getattr(self.spec, "allen_passage_m", None)
        if not a:
            return base
        w = self.spec.port_width_m
        full = w - a if w >= 2.0 * a else 0.5 * w
        extra = np.array([[a, full], [0.0, 0.0], [a, full], [0.0, 0.0]])
        return np.hstack([base, extra])

    def port_widths(self):
        return np.full(4, self.spec.port_width_m)

    def port_lengths(self):
        return np.full(4, self.spec.port_length_m * self.spec.ports_per_end)

    def openings_per_edge(self):
        return np.full(4, float(self.spec.ports_per_end))

    def discharge_coefficients(self):
        return np.full(4, self.spec.discharge_coefficient)


OPENINGS_OF_SIGNED.add(LappedValve.openings)


class SlideValve(LappedValve):
    """Plain D slide valve or piston valve on a single eccentric.

    The travel is Zeuner's harmonic motion, corrected for a finite eccentric rod by
    the rod end's shortfall (Spangler Art. 13; Marks, *Relative Proportions*,
    Art. 96): see the module doc.

    Parameters
    ----------
    spec : SlideValveSpec
        The valve, its eccentric and its ports.
    """

    name = "slide_valve"
    summary = "plain D slide valve or piston valve on one eccentric (Spangler Ch. I-IV)"

    def __init__(self, spec: SlideValveSpec):
        self.spec = spec

    def travel(self, theta: np.ndarray) -> np.ndarray:
        """Valve displacement in the sense that opens the head steam port, with the
        finite rod's correction when the spec has a rod.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m] from the valve's zero (see ``setting``), of the shape
            of ``theta``.
        """
        s = self.spec
        theta = np.asarray(theta)
        if theta.ndim == 1 and theta.dtype == np.float64:
            # the same operations as on other arrays below, angle by angle, in one
            # compiled loop (a turn's 7201 samples a run)
            return eccentric_travel(np.ascontiguousarray(theta), *self._travel_args)
        phase = theta + s.angular_advance_rad
        if phase.ndim == 0:
            x = s.eccentricity_m * np.sin(phase)
            g = s.eccentric_rod_m
            if g is not None:
                r = s.eccentricity_m
                short = g - np.sqrt(g * g - (r * np.cos(phase)) ** 2)
                if s.setting == "equal_lead":
                    short = short - (g - math.sqrt(g * g - (r * math.cos(s.angular_advance_rad))
                                                   ** 2))
                x = x + s.sigma * short
            return x
        # the same operations on arrays, each into the array it reads
        x = np.sin(phase)
        x *= s.eccentricity_m
        g = s.eccentric_rod_m
        if g is not None:
            r = s.eccentricity_m
            short = np.cos(phase, out=phase)
            short *= r
            np.square(short, out=short)
            np.subtract(g * g, short, out=short)
            np.sqrt(short, out=short)
            np.subtract(g, short, out=short)
            if s.setting == "equal_lead":
                short -= g - math.sqrt(g * g - (r * math.cos(s.angular_advance_rad)) ** 2)
            if s.sigma != 1:
                short *= s.sigma
            x += short
        return x

    @functools.cached_property
    def _travel_args(self) -> tuple:
        """:func:`~corliss.valves.travel_kernel.eccentric_travel`'s arguments after the
        angles, from the spec (found once a gear: the spec is frozen)."""
        s = self.spec
        g = s.eccentric_rod_m
        r = s.eccentricity_m
        shift = 0.0
        if g is not None and s.setting == "equal_lead":
            shift = g - math.sqrt(g * g - (r * math.cos(s.angular_advance_rad)) ** 2)
        return (s.angular_advance_rad, r, 0.0 if g is None else g,
                0.0 if g is None else g * g, shift, float(s.sigma), g is not None)

    def signed_openings(self, theta):
        theta = np.asarray(theta)
        if (theta.ndim == 1 and theta.dtype == np.float64
                and type(self).travel is SlideValve.travel):
            # the travel and the four rows in one compiled loop, the same operations
            # (:meth:`LappedValve.signed_openings` of :meth:`travel`)
            (lh, lc), (eh, ec) = self.spec.lap_m, self.spec.exhaust_lap_m
            return eccentric_signed(np.ascontiguousarray(theta), *self._travel_args,
                                    np.array([lh, eh, lc, ec], dtype=np.float64))
        return super().signed_openings(theta)

    def zeuner_travel(self, theta: np.ndarray) -> np.ndarray:
        """Valve displacement of the Zeuner (infinite rod) motion,
        ``r sin(theta + delta)`` (Spangler Art. 13, eq. 4).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m], of the shape of ``theta``.
        """
        s = self.spec
        return s.eccentricity_m * np.sin(np.asarray(theta) + s.angular_advance_rad)

    def joints(self, theta: float) -> "EccentricJoints":
        """The eccentric's linkage at crank angle ``theta``, from the same closed form as
        :meth:`travel`.

        Parameters
        ----------
        theta : float
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        EccentricJoints
            The shaft, the eccentric's centre and the rod's end [m], and the valve's
            displacement [m].
        """
        return eccentric_joints(self.spec, float(theta))


@dataclass(frozen=True)
class EccentricJoints:
    """The joints of a single eccentric driving a valve at one crank angle (all SI).

    The shaft is at the origin, the line of stroke (and the valve spindle's line) along
    X; the eccentric's centre is at r (sin, cos)(theta + delta), so that its projection
    on X is Zeuner's r sin(theta + delta) (Spangler Art. 13).  With a finite rod the
    rod's end runs on the spindle's line: on the side X < 0 for ``sigma`` = +1 (it
    falls short towards the shaft as the valve moves towards +X) and X > 0 for
    ``sigma`` = -1.  With an infinitely long rod the valve is driven as by a slotted
    yoke: the rod's end is the eccentric's centre projected on the spindle's line,
    which moves the valve exactly harmonically.

    Parameters
    ----------
    shaft : tuple of float
        The shaft's centre (x, y) [m].
    eccentric : tuple of float
        The eccentric's centre (x, y) [m].
    rod_end : tuple of float
        The eccentric rod's end on the valve spindle's line (x, y) [m].
    rod_m : float or None
        The eccentric rod's length [m]; None for the slotted yoke.
    valve_m : float
        The valve's displacement in the sense that opens the head steam port [m]:
        the rod end's X less its X with the valve at its zero.
    rods_m : dict
        The eccentric's throw and the rod: ``{name: (length [m], joint, joint)}``.
    """

    shaft: tuple[float, float]
    eccentric: tuple[float, float]
    rod_end: tuple[float, float]
    rod_m: float | None
    valve_m: float
    rods_m: dict


def eccentric_joints(spec: SlideValveSpec, theta: float) -> EccentricJoints:
    """The eccentric, rod and valve of a slide valve's gear at crank angle ``theta``.

    The valve's displacement is the rod end's X from the rod end's X at the valve's
    zero (the rod on the side X < 0 for sigma = +1, X > 0 for -1): for equal lead (Marks, Art. 96)
    the zero is the mean of the two dead-point positions, sqrt(g^2 - r^2 cos^2 delta)
    from the eccentric's projection, for equal travels g; this is the module's formula
    for the valve's travel, term for term.

    Parameters
    ----------
    spec : SlideValveSpec
        The valve and its eccentric.
    theta : float
        Crank angle from head-end dead centre [rad].

    Returns
    -------
    EccentricJoints
        The joints [m] and the valve's displacement [m].
    """
    r, g = spec.eccentricity_m, spec.eccentric_rod_m
    phase = theta + spec.angular_advance_rad
    ex, ey = r * math.sin(phase), r * math.cos(phase)
    if g is None:
        return EccentricJoints((0.0, 0.0), (ex, ey), (ex, 0.0), None, ex,
                               {"eccentric": (r, "shaft", "eccentric")})
    sigma = spec.sigma
    end_x = ex - sigma * math.sqrt(g * g - ey * ey)
    if spec.setting == "equal_lead":
        zero = -sigma * math.sqrt(g * g - (r * math.cos(spec.angular_advance_rad)) ** 2)
    else:
        zero = -sigma * g
    return EccentricJoints((0.0, 0.0), (ex, ey), (end_x, 0.0), g, end_x - zero,
                           {"eccentric": (r, "shaft", "eccentric"),
                            "eccentric rod": (g, "eccentric", "rod_end")})


#: Keys every lapped valve shares: its ports.
PORT_KEYS = group(
    "ports", "The steam ports a lapped valve uncovers.",
    Key("port_width", "length", "Width of each steam port along the valve's travel.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("port_length", "length", "Length of each port across the valve face.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("discharge_coefficient", "number", "Discharge coefficient of a port opening.",
        default=0.7, within=DISCHARGE_COEFFICIENT),
    Key("ports_per_end", "integer", "Openings each edge uncovers (2 for a double-ported "
        "valve).", default=1, within=(1, 8)),
)
#: The laps of a lapped valve.
LAP_KEYS = group(
    "laps", "A lapped valve's laps.",
    Key("lap", "length", "Steam (outside) lap: the valve's overlap of the steam port's edge "
        "at mid travel, less than its half travel; negative: both ends take steam at mid "
        "travel.", ends=True, unit="in"),
    Key("exhaust_lap", "length", "Exhaust (inside) lap, less than the valve's half travel; "
        "negative: exhaust clearance.",
        default="0 in", ends=True, unit="in"),
)
#: An Allen (trick) valve's passage.
ALLEN_KEYS = group(
    "allen", "An Allen valve's supplementary passage.",
    Key("allen_passage", "length", "Width of the mouth of an Allen (trick) valve's "
        "passage, no wider than the port (Spangler Art. 27); absent: a plain valve.",
        default=None, within=POSITIVE_LENGTH, unit="in"),
)
#: The throw of a gear's (main) eccentric.
ECCENTRICITY = Key("eccentricity", "length", "Throw of the (main) eccentric, half its travel.",
                   within=POSITIVE_LENGTH, unit="in")
#: The range of an eccentric's angular advance [rad]: the valve stands lap + lead =
#: r sin(delta) from mid travel at the dead centre (Spangler, *Valve-Gears*, Art. 13), so
#: delta lies in [-90 deg, 90 deg].
ADVANCE_RANGE_rad = (-math.pi / 2, math.pi / 2)
#: The angular advance of a gear's (main) eccentric.
ANGULAR_ADVANCE = Key("angular_advance", "angle", "Angular advance of the (main) eccentric: how "
                      "far beyond 90 deg it leads the crank. The gear takes no lead key: "
                      "the lead follows from lap and advance (corliss events prints it).",
                      within=ADVANCE_RANGE_rad, unit="deg")
SLIDE_VALVE_KEYS = group(
    "slide_valve", "A plain slide valve (D or piston valve) on one eccentric.",
    ECCENTRICITY, LAP_KEYS,
    Key("angular_advance", "angle", "Angular advance, between -90 and 90 deg; or give lead "
        "(exactly one of the two).", default=None, within=ADVANCE_RANGE_rad, unit="deg"),
    Key("lead", "length", "Lead at the head end, lap + lead no more than the eccentricity; "
        "or give angular_advance (exactly one of the two).", default=None, unit="in"),
    Key("eccentric_rod", "length", "Eccentric rod plus valve stem, longer than the "
        "eccentricity; absent: the Zeuner (infinite rod) motion.", default=None,
        within=POSITIVE_LENGTH, unit="in"),
    Key("connection", "choice", "The valve driven directly or through a reversing rocker.",
        default="direct", choices=("direct", "reverse_lever")),
    Key("steam", "choice", "Steam outside (D valve) or inside (piston valve) the valve.",
        default="outside", choices=("outside", "inside")),
    Key("setting", "choice", "How the valve is set on its rod: equal leads or mid travel.",
        default="equal_lead", choices=("equal_lead", "mid_travel")),
    ALLEN_KEYS, PORT_KEYS,
)


def parse_slide_valve(t: Table) -> SlideValveSpec:
    """Read a ``[valve_gear] type = "slide_valve"`` table (see the scene example).

    Parameters
    ----------
    t : Table
        The table, bound to :data:`SLIDE_VALVE_KEYS`.

    Returns
    -------
    SlideValveSpec
        The valve's spec.
    """
    t = t.bound(SLIDE_VALVE_KEYS)
    r = t.get("eccentricity")
    lap = t.get("lap")
    exhaust_lap = t.get("exhaust_lap")
    for end, l in zip(("head", "crank"), lap):
        if l >= r:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap smaller than the eccentricity ({r / units.INCH_m:.4g} in): "
                             f"with lap >= eccentricity the {end}-end steam port never opens")
    for end, e in zip(("head", "crank"), exhaust_lap):
        if e >= r:
            raise InputError(t.key("exhaust_lap"), t.raw("exhaust_lap"),
                             "an exhaust lap smaller than the eccentricity: the "
                             f"{end}-end exhaust would never open")
    has_lead, has_adv = t.has("lead"), t.has("angular_advance")
    if has_lead == has_adv:
        raise InputError(t.key("lead"), t.raw("lead", None),
                         "exactly one of lead or angular_advance (not both, not neither)")
    if has_lead:
        lead = t.get("lead")
        arg = (lap[0] + lead) / r
        if not -1.0 <= arg <= 1.0:
            raise InputError(t.key("lead"), t.raw("lead"),
                             "a lead with lap + lead no larger than the eccentricity "
                             f"({r / units.INCH_m:.4g} in)")
        delta = math.asin(arg)
    else:
        delta = t.get("angular_advance")
        if not -math.pi / 2 < delta < math.pi / 2:
            raise InputError(t.key("angular_advance"), t.raw("angular_advance"),
                             "an angle between -90 deg and 90 deg")
    g = t.get("eccentric_rod")
    if g is not None and g <= r:
        raise InputError(t.key("eccentric_rod"), t.raw("eccentric_rod"),
                         "an eccentric rod longer than the eccentricity")
    return SlideValveSpec(
        eccentricity_m=r, lap_m=lap, exhaust_lap_m=exhaust_lap, angular_advance_rad=delta,
        eccentric_rod_m=g, connection=t.get("connection"), steam=t.get("steam"),
        setting=t.get("setting"), allen_passage_m=parse_allen_passage(t), **parse_ports(t),
    )


def parse_allen_passage(t: Table) -> float | None:
    """The ``allen_passage`` key: width of an Allen valve's passage mouth, no wider
    than the steam port it delivers into (Spangler Art. 27), or None.

    Parameters
    ----------
    t : Table
        The table, bound to a group with :data:`ALLEN_KEYS` and :data:`PORT_KEYS`.

    Returns
    -------
    float or None
        The passage's width [m], or None for a plain valve.
    """
    a = t.get("allen_passage")
    if a is None:
        return None
    w = t.get("port_width")
    if a > w:
        raise InputError(t.key("allen_passage"), t.raw("allen_passage"),
                         f"a passage no wider than the steam port ({w / units.INCH_m:.4g} in): "
                         "it delivers into that port")
    return a


def parse_ports(t: Table) -> dict:
    """The port keys every lapped valve shares (:data:`PORT_KEYS`): widths, lengths,
    openings, discharge.

    Parameters
    ----------
    t : Table
        The table, bound to a group with :data:`PORT_KEYS`.

    Returns
    -------
    dict
        ``port_width_m`` [m], ``port_length_m`` [m], ``discharge_coefficient`` [-] and
        ``ports_per_end``, as a lapped valve's spec takes them.
    """
    return {"port_width_m": t.get("port_width"), "port_length_m": t.get("port_length"),
            "discharge_coefficient": t.get("discharge_coefficient"),
            "ports_per_end": t.get("ports_per_end")}


register(GearType("slide_valve", SlideValve.summary, parse_slide_valve, SlideValve,
                  SLIDE_VALVE_KEYS))
