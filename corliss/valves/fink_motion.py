"""The Fink link motion and the Porter-Allen gear built on it (Spangler Arts. 74-83, 30).

Fink motion (Spangler Art. 74, Fig. 51).  One eccentric of throw r, set 90 deg from
the valve's middle position (Art. 81), drives a rod rigid with the link: a point p' of
the rod, a distance a from the eccentric's centre, is held on the line of stroke
(by a suspension rod, "or very nearly so"), and the link's middle j is a further b
along the rod; the link is an arc of radius rho, concave towards the valve, square to
the rod at j.  The radius rod (length g1) runs from the block, which a hanger holds at
the height u above the line of stroke, to the valve stem on that line.  The governor
or reversing lever sets u.  Spangler's equation (A) of Art. 77, the valve's
displacement from its central position, with omega the crank angle from the dead
point::

    x = r cos w + (u r / a)(1 + b/g1) sin w
        + (r^2 / 2a^2)(b + b^2/g1 + 3u^2/(2 g1) - a) sin^2 w             (A)

("The last term in this equation is generally small, and may be omitted"): Zeuner's
form is the first line, C = r, S = (u r / a)(1 + b/g1).  Since C = r for every u, "the
lap plus the lead equals the throw of the eccentric" (Art. 78): the lead is the same at
every setting when rho = g1 (Art. 75: with the crank on a dead point the link is an arc
about the valve-stem end, so moving the block does not move the valve).

``motion`` selects ``"zeuner"`` (the first line of (A)), ``"second_order"`` (all of
(A), the Art. 77 derivation to order r^2/a^2) or ``"exact"``: the linkage solved at
each crank angle in closed form (p' exactly on the line of stroke, the block exactly at
height u, the link a true arc of radius rho and the radius rod of length g1 reaching the
stem on the line of stroke), its zero the mean of the stem's two dead-point positions at
the end of the link (u = c), which is the book's a + b + g1 (+ g2) when rho = g1
(Art. 75).  The crank angle here is theta from head-end dead centre, x positive in the
sense that opens the head steam port.

A point fixed on the link at a distance y from the rod (Art. 79, the Porter-Allen
exhaust rod) moves in the same way with y for u, but without the factor (1 + b/g1),
which comes from the block sliding along the curved link at constant height: for the
fixed point the linkage gives x = r cos w + (y r / a) sin w (the book's statement is
exact for b = 0, "generally" its case, Art. 78).

Porter-Allen gear (Art. 83, Fig. 53; valves Art. 30, Fig. 22).  A Fink motion whose
radius rod, moved in the link by the governor, drives the rock shaft j; two arms on
that shaft drive the head and crank steam valves, each a flat plate with its own lap,
the arms set so that "each valve is moving its fastest when opening and closing its
port".  The exhaust rod hangs from one fixed point g' of the link and works the two
exhaust valves, on one stem, through a bell crank; so "the exhaust events do not change
with the cut-off".  Modelled: the radius rod's end i' swings the driving arm (length
R_d) through phi = asin(x_s / R_d); a valve arm of length R_v set at the angle beta
from square to its stem moves its valve R_v [sin(phi - beta) + sin beta] from mid
position, and with lap lambda the port opens by R_v sin(phi - beta) - (lambda - R_v sin
beta).  Setting beta = asin(lambda / R_v), the arm is square to the stem (the valve at
its fastest) just as the edge crosses the port: the signed opening is R_v sin(phi -
beta).  The crank-end valve is worked by its arm the other way (-phi).  Each steam valve
is a flat plate "having rectangular openings through them" (Art. 30, p. 31), so as it
moves it uncovers ``steam_openings`` edges at once, its own end and the near edge of each
opening through it, every edge moving with the plate: one signed opening s for all of
them (the events are the first edge's crossings, the same for every n), and the open
area n L clip(s, 0, w), w the width of each opening along the travel and L its length
across (the plate's bars wider than its travel, so no opening passes over the next
port's edge: the double-ported valve's condition, Art. 26).  The exhaust
stem moves k_e times the exhaust point's travel, reversed by the bell crank (the
exhaust valves are "indirectly connected", Art. 30): the head exhaust opens by
-k_e x_e - e_h, the crank exhaust by k_e x_e - e_c.  The governor's setting s runs from
0 at rest (block at ``block_at_rest``, longest cut-off) to 1 at the top of its lift
(block at ``block_at_top``, towards the link's centre: shortest cut-off).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, ZERO_OR_MORE, Derived, Key, group
from corliss.keys.toml_table import DISCHARGE_COEFFICIENT, Table
from corliss.valves.gear import GearType, ValveGear, register
from corliss.valves.slide_valve import ECCENTRICITY, LAP_KEYS, PORT_KEYS, LappedValve, parse_ports

#: The motions a Fink gear is computed by (see the module doc).
MOTIONS = ("zeuner", "second_order", "exact")


@dataclass(frozen=True)
class FinkLink:
    """Dimensions of a Fink link motion (Spangler Art. 74, Fig. 51), all SI.

    Parameters
    ----------
    eccentricity_m : float
        Throw r of the eccentric [m].
    rod_a_m : float
        a: eccentric centre to the point p' held on the line of stroke [m].
    rod_b_m : float
        b: from p' to the link's middle j [m] (often 0, Art. 78).
    radius_rod_m : float
        g1: radius rod, block to valve stem [m].
    half_link_m : float
        c: the most the block may stand off the line of stroke [m].
    link_radius_m : float
        rho: radius of the link's arc [m]; g1 for constant lead (Art. 75), "slightly
        more" in the Porter-Allen (Art. 83).
    motion : str, optional
        One of :data:`~corliss.valves.fink_motion.MOTIONS`: ``"zeuner"``,
        ``"second_order"`` (all of eq. (A), Art. 77) or ``"exact"`` (see the module
        doc).
    """

    eccentricity_m: float
    rod_a_m: float
    rod_b_m: float
    radius_rod_m: float
    half_link_m: float
    link_radius_m: float
    motion: str = "zeuner"

    def coefficients(self, u: float) -> tuple[float, float]:
        """Zeuner's form ``x = C cos(theta) + S sin(theta)``, the first line of eq. (A)
        (Spangler Arts. 77-78).

        Parameters
        ----------
        u : float
            Height of the block above the line of stroke [m].

        Returns
        -------
        C, S : float
            Coefficients [m]: ``C = r`` at every u (Art. 78), ``S = (u r / a)(1 +
            b / g1)``.
        """
        r, a, b, g1 = self.eccentricity_m, self.rod_a_m, self.rod_b_m, self.radius_rod_m
        return r, u * r / a * (1.0 + b / g1)

    def sin2_coefficient(self, u: float) -> float:
        """Coefficient of ``sin^2(theta)`` in Spangler's eq. (A), Art. 77.

        Parameters
        ----------
        u : float
            Height of the block above the line of stroke [m].

        Returns
        -------
        float
            ``(r^2 / 2a^2)(b + b^2/g1 + 3u^2/(2 g1) - a)`` [m].
        """
        r, a, b, g1 = self.eccentricity_m, self.rod_a_m, self.rod_b_m, self.radius_rod_m
        return r * r / (2 * a * a) * (b + b * b / g1 + 1.5 * u * u / g1 - a)

    def block_travel(self, u: float, theta) -> np.ndarray:
        """Displacement of the valve-stem end of the radius rod, by :attr:`motion`.

        Parameters
        ----------
        u : float
            Height of the block above the line of stroke [m].
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m] from the stem's central position (:meth:`stem_zero`
            for the exact motion), + toward opening the head steam port, of the shape
            of ``theta``.
        """
        th = np.asarray(theta, dtype=float)
        if self.motion == "exact":
            return _stem_x(self, u, th) - self.stem_zero()
        C, S = self.coefficients(u)
        x = C * np.cos(th) + S * np.sin(th)
        if self.motion == "second_order":
            x = x + self.sin2_coefficient(u) * np.sin(th) ** 2
        return x

    def stem_zero(self) -> float:
        """The valve stem's central position in the exact linkage: the mean of its two
        dead-point positions with the block at the end of the link (u = c).

        Returns
        -------
        float
            Distance of the stem's end from the shaft [m]; the book's
            ``a + b + g1`` when ``rho = g1`` (Art. 75).
        """
        dead = _stem_x(self, self.half_link_m, np.array([0.0, math.pi]))
        return float(0.5 * (dead[0] + dead[1]))

    def point_travel(self, y: float, theta) -> np.ndarray:
        """Displacement of the point fixed on the link a distance y from the rod
        (Art. 79), from the mean of its dead-point positions:
        ``r cos(theta) + (y r / a) sin(theta)`` unless the motion is exact.

        Parameters
        ----------
        y : float
            Distance of the point from the rod's line, along the link [m].
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement [m], of the shape of ``theta``.
        """
        th = np.asarray(theta, dtype=float)
        r, a = self.eccentricity_m, self.rod_a_m
        if self.motion != "exact":
            return r * np.cos(th) + y * r / a * np.sin(th)
        dead = _link_point_x(self, y, np.array([0.0, math.pi]))
        return _link_point_x(self, y, th) - 0.5 * (dead[0] + dead[1])


def _frame(link: FinkLink, theta: np.ndarray):
    """Unit vector t along the eccentric rod (towards the valve), its normal n, and the
    link's centre of curvature K, at crank angles theta (Fig. 51 laid out with the shaft
    at the origin and the line of stroke the x axis)."""
    r, a, b, rho = link.eccentricity_m, link.rod_a_m, link.rod_b_m, link.link_radius_m
    ex, ey = r * np.cos(theta), r * np.sin(theta)
    px = ex + np.sqrt(a * a - ey * ey)                  # p' on the line of stroke
    tx, ty = (px - ex) / a, -ey / a
    kx = ex + (a + b + rho) * tx                        # j = E + (a + b) t, K = j + rho t
    ky = ey + (a + b + rho) * ty
    return (tx, ty), (-ty, tx), (kx, ky)


def _stem_x(link: FinkLink, u: float, theta: np.ndarray) -> np.ndarray:
    """Distance from the shaft of the radius rod's stem end [m]: the block where the
    link's arc (the side towards the shaft) meets the height u, then the rod g1 down
    to the line of stroke."""
    _, _, (kx, ky) = _frame(link, theta)
    rho, g1 = link.link_radius_m, link.radius_rod_m
    bx = kx - np.sqrt(rho * rho - (u - ky) ** 2)
    return bx + math.sqrt(g1 * g1 - u * u)


def _link_point_x(link: FinkLink, y: float, theta: np.ndarray) -> np.ndarray:
    """Distance from the shaft [m] of the point of the link's arc a chord-distance y
    from the rod's line."""
    (tx, _), (nx, _), (kx, _) = _frame(link, theta)
    rho = link.link_radius_m
    return kx - math.sqrt(rho * rho - y * y) * tx + y * nx


# ---------------------------------------------------------------------------- Fink gear

@dataclass(frozen=True)
class FinkMotionSpec:
    """A Fink link motion driving a lapped slide valve (all SI).

    Parameters
    ----------
    link : FinkLink
        The linkage.
    block_m : float
        The block's height u above the line of stroke [m], the setting, within
        [-c, c].
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
    """

    link: FinkLink
    block_m: float
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1


class FinkMotion(LappedValve):
    """A slide valve on the Fink link motion (Spangler Arts. 74-82).

    Its setting is the block's height as a fraction of the half link, ``u / c``.

    Parameters
    ----------
    spec : FinkMotionSpec
        The linkage, the block's height and the valve.
    """

    name = "fink_motion"
    summary = ("Fink link motion: one eccentric, the link on its rod, the block's height the "
               "setting (Spangler Arts. 74-82); Zeuner's form, eq. (A) or the exact linkage")
    setting_name = "block height u / c (1 full gear ahead, 0 mid gear, -1 full gear astern)"
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: FinkMotionSpec):
        self.spec = spec

    def _at_setting(self, value: float) -> "FinkMotion":
        return FinkMotion(dataclasses.replace(self.spec,
                                              block_m=value * self.spec.link.half_link_m))

    def travel(self, theta):
        return self.spec.link.block_travel(self.spec.block_m, theta)

    def zeuner_travel(self, theta):
        """Zeuner's form of the same setting (Art. 77, eq. (A) less its last term).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, any shape.

        Returns
        -------
        ndarray
            Displacement x [m], of the shape of ``theta``.
        """
        C, S = self.spec.link.coefficients(self.spec.block_m)
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)


#: The linkage keys shared by the Fink and Porter-Allen gears.
FINK_LINK_KEYS = group(
    "fink_link", "Fink's link on the eccentric strap.",
    ECCENTRICITY,
    Key("rod_a", "length", "a: eccentric centre to the point held on the line of stroke, "
        "longer than the eccentricity.", within=POSITIVE_LENGTH, unit="in"),
    Key("rod_b", "length", "b: from that point to the link's middle (zero or more; often 0, "
        "Art. 78).", default="0 in", unit="in", within=ZERO_OR_MORE),
    Key("radius_rod", "length", "g1: radius rod, block to valve stem.", within=POSITIVE_LENGTH,
        unit="in"),
    Key("half_link", "length", "c: the most the block may stand off the line of stroke; "
        "shorter than the radius rod and the link's radius.", within=POSITIVE_LENGTH,
        unit="in"),
    Key("link_radius", "length", "Radius of the link's arc.", default=Derived("the radius rod"),
        within=POSITIVE_LENGTH, unit="in"),
    Key("motion", "choice", "Zeuner's motion, the second-order one, or the exact linkage.",
        default="zeuner", choices=MOTIONS),
)


def parse_fink_link(t: Table) -> FinkLink:
    """The linkage keys shared by the Fink and Porter-Allen gears (:data:`FINK_LINK_KEYS`).

    Parameters
    ----------
    t : Table
        The table, bound to :data:`FINK_LINK_KEYS`.

    Returns
    -------
    FinkLink
        The link.
    """
    r = t.get("eccentricity")
    a = t.get("rod_a")
    b = t.get("rod_b")
    if b < 0.0:
        raise InputError(t.key("rod_b"), t.raw("rod_b"), "a length of zero or more")
    g1 = t.get("radius_rod")
    c = t.get("half_link")
    rho = t.get("link_radius") if t.has("link_radius") else g1
    if a <= r:
        raise InputError(t.key("rod_a"), t.raw("rod_a"),
                         f"a rod longer than the eccentricity ({r / units.INCH_m:.4g} in)")
    if c >= min(g1, rho):
        raise InputError(t.key("half_link"), t.raw("half_link"),
                         "a half link shorter than the radius rod and the link's radius")
    motion = t.get("motion")
    return FinkLink(r, a, b, g1, c, rho, motion)


FINK_MOTION_KEYS = group(
    "fink_motion", "Fink's link motion driving a lapped slide valve.",
    FINK_LINK_KEYS,
    Key("block", "length", "Height u of the block in the link, within the half link "
        "(its sign reverses the engine).", unit="in"),
    LAP_KEYS, PORT_KEYS,
)


def parse_fink_motion(t: Table) -> FinkMotionSpec:
    """Read a ``[valve_gear] type = "fink_motion"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`FINK_MOTION_KEYS`.

    Returns
    -------
    FinkMotionSpec
        The gear's spec.
    """
    t = t.bound(FINK_MOTION_KEYS)
    link = parse_fink_link(t)
    u = t.get("block")
    c = link.half_link_m
    if abs(u) > c:
        raise InputError(t.key("block"), t.raw("block"),
                         f"a block height within the link, -{c / units.INCH_m:.4g} in to "
                         f"{c / units.INCH_m:.4g} in (the half link)")
    spec = FinkMotionSpec(link, u, t.get("lap"), t.get("exhaust_lap"), **parse_ports(t))
    reach = float(np.max(np.abs(link.block_travel(u, np.linspace(0, 2 * math.pi, 721)))))
    if max(spec.lap_m) >= reach:
        raise InputError(t.key("lap"), t.raw("lap"),
                         f"a lap below the valve's greatest travel at this block "
                         f"({reach / units.INCH_m:.4g} in): the port never opens")
    return spec


register(GearType("fink_motion", FinkMotion.summary, parse_fink_motion, FinkMotion,
                  FINK_MOTION_KEYS))


# ---------------------------------------------------------------------- Porter-Allen gear

@dataclass(frozen=True)
class PorterAllenSpec:
    """A Porter-Allen gear (Spangler Art. 83, Art. 30), all SI.

    Parameters
    ----------
    link : FinkLink
        The Fink linkage.
    block_at_rest_m, block_at_top_m : float
        Block height u with the governor at rest (s = 0) and at the top of its lift
        (s = 1) [m].
    drive_arm_m : float
        R_d, the rock-shaft arm ji' the radius rod works [m].
    valve_arm_m : float
        R_v, the arms jl', jk' to the steam-valve stems [m].
    steam_lap_m : tuple of float
        Lap of the (head, crank) steam valve [m].
    exhaust_point_m : float
        y of the link point g' carrying the exhaust rod [m].
    exhaust_ratio : float
        k_e, exhaust-stem travel over the point g''s travel (the bell crank q'rs') [-].
    exhaust_lap_m : tuple of float
        Lap of the (head, crank) exhaust valve [m]; negative = clearance.
    steam_port_width_m, steam_port_length_m : float
        Steam ports' width along the valve's travel and length across it [m].
    exhaust_port_width_m, exhaust_port_length_m : float
        Exhaust ports' width along the valve's travel and length across it [m].
    discharge_coefficient : float, optional
        Of every port opening [-].
    setting : float, optional
        Governor position s in [0, 1] [-].
    steam_openings : int, optional
        n, the openings each steam valve uncovers at once (its plate's end and the
        openings through it, Spangler Art. 30), each ``steam_port_width_m`` wide and
        ``steam_port_length_m`` long [-].
    """

    link: FinkLink
    block_at_rest_m: float
    block_at_top_m: float
    drive_arm_m: float
    valve_arm_m: float
    steam_lap_m: tuple[float, float]
    exhaust_point_m: float
    exhaust_ratio: float
    exhaust_lap_m: tuple[float, float]
    steam_port_width_m: float
    steam_port_length_m: float
    exhaust_port_width_m: float
    exhaust_port_length_m: float
    discharge_coefficient: float = 0.7
    setting: float = 0.0
    steam_openings: int = 1

    @property
    def block_m(self) -> float:
        """Block height u at the present governor position [m]."""
        s = self.setting
        return (1.0 - s) * self.block_at_rest_m + s * self.block_at_top_m

    @property
    def arm_angles_rad(self) -> tuple[float, float]:
        """beta of the (head, crank) valve arm: square to its stem as the edge crosses
        the port [rad]."""
        head, crank = (math.asin(lam / self.valve_arm_m) for lam in self.steam_lap_m)
        return head, crank

    @property
    def equivalent_lap_m(self) -> tuple[float, float]:
        """The laps as seen at the radius rod's end, R_d sin(beta) [m]: where the Zeuner
        diagram of the steam motion is cut."""
        head, crank = (self.drive_arm_m * math.sin(b) for b in self.arm_angles_rad)
        return head, crank


class PorterAllenGear(ValveGear):
    """Four valves on a Porter-Allen (Fink) gear with the governor moving the block.

    Its setting is the governor's position s, 0 at rest (longest cut-off) to 1 at the
    top of its lift.

    Parameters
    ----------
    spec : PorterAllenSpec
        The linkage, the arms, the four valves and their ports.
    """

    name = "porter_allen"
    summary = ("Porter-Allen: Fink link, governor moves the steam radius rod; rock shaft with "
               "two arms to separate steam valves, exhaust valves from a fixed point of the "
               "link (Spangler Arts. 30, 83); setting = governor position 0..1")
    setting_name = "governor position s (0 at rest, longest cut-off; 1 at the top of its lift)"
    setting_range = (0.0, 1.0)

    def __init__(self, spec: PorterAllenSpec):
        self.spec = spec

    # -- the motions
    def steam_drive(self, theta) -> np.ndarray:
        """x_s: travel of the steam radius rod's end i' (Fink motion at the block).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacement [m], shape ``(n,)``.
        """
        return self.spec.link.block_travel(self.spec.block_m, theta)

    def exhaust_drive(self, theta) -> np.ndarray:
        """x_e: travel of the link point g' carrying the exhaust rod (Art. 79).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacement [m], shape ``(n,)``.
        """
        return self.spec.link.point_travel(self.spec.exhaust_point_m, theta)

    def rock_angle(self, theta) -> np.ndarray:
        """phi of the rock shaft, ``asin(x_s / R_d)``, 0 with the radius rod at mid
        travel.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Angle phi [rad], shape ``(n,)``.
        """
        return np.arcsin(np.clip(self.steam_drive(theta) / self.spec.drive_arm_m, -1.0, 1.0))

    def valve_travels(self, theta) -> np.ndarray:
        """Displacement from mid position of the head steam, crank steam and exhaust
        stems (see the module doc).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacements [m], shape ``(3, n)``: head steam, crank steam, exhaust,
            each in the sense that opens its (head steam, crank steam, head exhaust)
            port.
        """
        s = self.spec
        phi = self.rock_angle(theta)
        bh, bc = s.arm_angles_rad
        rv = s.valve_arm_m
        return np.vstack([rv * (np.sin(phi - bh) + math.sin(bh)),
                          rv * (np.sin(-phi - bc) + math.sin(bc)),
                          -s.exhaust_ratio * self.exhaust_drive(theta)])

    # -- the ValveGear interface
    def signed_openings(self, theta):
        s = self.spec
        v = self.valve_travels(np.atleast_1d(theta))
        lh, lc = s.steam_lap_m
        eh, ec = s.exhaust_lap_m
        return np.vstack([v[0] - lh, v[2] - eh, v[1] - lc, -v[2] - ec])

    def port_widths(self):
        s = self.spec
        return np.array([s.steam_port_width_m, s.exhaust_port_width_m] * 2)

    def port_lengths(self):
        s = self.spec
        return np.array([s.steam_port_length_m * s.steam_openings,
                         s.exhaust_port_length_m] * 2)

    def openings_per_edge(self):
        n = float(self.spec.steam_openings)
        return np.array([n, 1.0, n, 1.0])

    def discharge_coefficients(self):
        return np.full(4, self.spec.discharge_coefficient)


PORTER_ALLEN_KEYS = group(
    "porter_allen", "The Porter-Allen gear: Fink's link works four valves through a rock "
    "shaft; the governor moves the block.",
    FINK_LINK_KEYS,
    Key("block_at_rest", "length", "Block height u with the governor at rest (setting 0), "
        "within the half link.", unit="in"),
    Key("block_at_top", "length", "Block height u with the governor at the top of its lift "
        "(setting 1), within the half link.", unit="in"),
    Key("exhaust_point", "length", "Height of the link point carrying the exhaust rod, "
        "within the half link.", unit="in"),
    Key("setting", "number", "Governor position, 0 (at rest) to 1 (top).", default=0.0,
        within=(0.0, 1.0)),
    Key("drive_arm", "length", "R_d: the rock-shaft arm the radius rod works.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("valve_arm", "length", "R_v: the arms to the steam-valve stems.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("steam_lap", "length", "Lap of the steam valves, zero or more and shorter than the "
        "valve arm.", ends=True, unit="in", within=ZERO_OR_MORE),
    Key("exhaust_ratio", "number", "k_e: the exhaust stem's travel over the exhaust point's "
        "(the bell crank).", default=1.0, within=(0.05, 20.0)),
    Key("exhaust_lap", "length", "Lap of the exhaust valves; negative: clearance.",
        default="0 in", ends=True, unit="in"),
    Key("steam_port_width", "length", "Width along the valve's travel of each opening a "
        "steam valve uncovers.", within=POSITIVE_LENGTH, unit="in"),
    Key("steam_port_length", "length", "Length across the valve of each opening a steam "
        "valve uncovers.", within=POSITIVE_LENGTH, unit="in"),
    Key("steam_openings", "integer", "Openings each steam valve uncovers at once, its "
        "plate's end and the openings through it (Spangler Art. 30, p. 31): the area that "
        "many times one opening's, the events the same, the largest opening reported the n "
        "openings' together (other gears: ports_per_end).",
        default=1, within=(1, 4)),
    Key("exhaust_port_width", "length", "Exhaust ports' width along the valve's travel.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("exhaust_port_length", "length", "Exhaust ports' length across the valve.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("discharge_coefficient", "number", "Discharge coefficient of a port opening.",
        default=0.7, within=DISCHARGE_COEFFICIENT),
)


def parse_porter_allen(t: Table) -> PorterAllenSpec:
    """Read a ``[valve_gear] type = "porter_allen"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`PORTER_ALLEN_KEYS`.

    Returns
    -------
    PorterAllenSpec
        The gear's spec.
    """
    t = t.bound(PORTER_ALLEN_KEYS)
    link = parse_fink_link(t)
    c = link.half_link_m
    blocks = []
    for key in ("block_at_rest", "block_at_top", "exhaust_point"):
        v = t.get(key)
        if abs(v) > c:
            raise InputError(t.key(key), t.raw(key), "a height within the link, "
                             f"-{c / units.INCH_m:.4g} in to {c / units.INCH_m:.4g} in "
                             "(the half link)")
        blocks.append(v)
    setting = t.get("setting")
    rd = t.get("drive_arm")
    rv = t.get("valve_arm")
    lap = t.get("steam_lap")
    if not all(0.0 <= lam < rv for lam in lap):
        raise InputError(t.key("steam_lap"), t.raw("steam_lap"),
                         "laps of zero or more, shorter than the valve arm")
    # k_e, a bell crank's proportion: a few times either way, never orders of magnitude
    ratio = t.get("exhaust_ratio")
    cd = t.get("discharge_coefficient")
    spec = PorterAllenSpec(
        link, blocks[0], blocks[1], rd, rv, lap, blocks[2], ratio, t.get("exhaust_lap"),
        t.get("steam_port_width"), t.get("steam_port_length"), t.get("exhaust_port_width"),
        t.get("exhaust_port_length"), cd, setting, t.get("steam_openings"))
    th = np.linspace(0, 2 * math.pi, 721)
    reach = max(float(np.max(np.abs(link.block_travel(u, th)))) for u in blocks[:2])
    beta = max(spec.arm_angles_rad)
    if reach >= rd or math.asin(reach / rd) + beta >= math.pi / 2:
        raise InputError(t.key("drive_arm"), t.raw("drive_arm"),
                         f"a driving arm long enough for the radius rod's travel "
                         f"(+-{reach / units.INCH_m:.4g} in) to swing the valve arms less "
                         "than square to their stems")
    if max(spec.equivalent_lap_m) >= float(np.max(np.abs(link.block_travel(blocks[0], th)))):
        raise InputError(t.key("steam_lap"), t.raw("steam_lap"),
                         "laps at which the steam valves open with the governor at rest")
    return spec


register(GearType("porter_allen", PorterAllenGear.summary, parse_porter_allen, PorterAllenGear,
                  PORTER_ALLEN_KEYS))
