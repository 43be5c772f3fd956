"""Riding cut-off valves driven through links: the Polonceau gear (Spangler Arts. 117,
127-134) and the Guinotte gear (Arts. 146-148).

A cut-off block rides on the back of the main valve over the passages through it, and
cuts off when the distance between the valves' centres reaches its lap ``s`` (Art.
130).  With both valves moving harmonically, x = C cos + S sin, the distance between
them, + closing the head passage, is the relative valve circle (Art. 128)::

    x_r = x_main - x_cutoff = (C - C1) cos(theta) + (S - S1) sin(theta)

**Polonceau gear** (Arts. 131-133): a Gooch link with two radius rods, the main valve's
at u and the cut-off valve's at u1, so each valve moves as Gooch's (Art. 65)::

    C = r (sin d + (c/g) cos d),     S = (u r / c)(cos d - (c/g) sin d)

C is the same for both: the relative circle's centre lies on the line at right angles
to the dead points, x_r = ((u - u1) r / c)(cos d - (c/g) sin d) sin(theta), and the
cut-off and re-opening fall symmetrically about mid stroke (in crank angle).  "If the
radius-rods are at the same point on the link, the valves move together and the
cut-off is that due to the main valve" (Art. 131); lowering the cut-off rod cuts off
earlier, the earliest at u1 = -c; the latest is where "the distance from the point of
cut-off to mid-stroke is the same as the distance from mid-stroke to the point of
cut-off by the main valve" (Art. 133).  The setting is u1 / c.

**Guinotte gear** (Arts. 146-148): the main valve on its own eccentric (r, delta); the
cut-off valve on a Gooch link with unequal eccentrics (r1, d1 to the upper end, r2, d2
to the lower), rods g1, g2 and link parts c1, c2 above and below the suspension::

    C1 = (c2 + u)/(c1 + c2) r1 (sin d1 + (c1/g1) cos d1) + (c1 - u)/(c1 + c2) r2 (sin d2 + (c2/g2) cos d2)
    S1 = (c2 + u)/(c1 + c2) r1 (cos d1 - (c1/g1) sin d1) - (c1 - u)/(c1 + c2) r2 (cos d2 - (c2/g2) sin d2)

(Art. 147, the book's A and B), both linear in u, "therefore the centre of the
valve-circles moves in a straight line inclined to os": a wider range of cut-off than
the Gooch link's.  The setting runs from -1 (u = -c2) through 0 to 1 (u = c1).

``motion = "exact"`` (Polonceau): the Gooch link solved as a linkage (the link motion
module's exact Gooch: finite eccentric rods, link curved to the radius rod, block held
at its height, radius rod g1 to the stem), once for each radius rod, both valves set for
equal lead in full forward gear as one link sets them.  The Guinotte gear, whose link
has unequal halves, is given in Zeuner's form only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Derived, Key, group
from corliss.keys.toml_table import Table
from corliss.valves import double_valve as dv
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import ANGULAR_ADVANCE, ECCENTRICITY


def gooch(r: float, delta: float, g: float, c: float, u: float) -> tuple[float, float]:
    """Zeuner's form of a Gooch link's valve, ``x = C cos(theta) + S sin(theta)``
    (Spangler Art. 65).

    Parameters
    ----------
    r : float
        Eccentrics' throw [m].
    delta : float
        Eccentrics' angular advance [rad].
    g : float
        Eccentric rod length [m].
    c : float
        Half the link's chord [m].
    u : float
        Block (radius rod) offset from the link's centre [m], in [-c, c].

    Returns
    -------
    C, S : float
        Coefficients [m].
    """
    sd, cd = math.sin(delta), math.cos(delta)
    return r * (sd + c / g * cd), u * r / c * (cd - c / g * sd)


def guinotte(r1, d1, g1, c1, r2, d2, g2, c2, u) -> tuple[float, float]:
    """Zeuner's form of the Guinotte cut-off valve, ``x = C cos(theta) + S sin(theta)``
    (Spangler Art. 147: C is the book's A, the coefficient of cos, S its B).

    Parameters
    ----------
    r1, r2 : float
        Throw of the eccentric to the link's upper and lower end [m].
    d1, d2 : float
        Their angular advances [rad].
    g1, g2 : float
        Their rods' lengths [m].
    c1, c2 : float
        The link's parts above and below the suspension [m].
    u : float
        Block offset from the suspension [m], from ``-c2`` to ``c1``.

    Returns
    -------
    C, S : float
        Coefficients [m], both linear in ``u``.
    """
    k1, k2 = (c2 + u) / (c1 + c2), (c1 - u) / (c1 + c2)
    A = (k1 * r1 * (math.sin(d1) + c1 / g1 * math.cos(d1))
         + k2 * r2 * (math.sin(d2) + c2 / g2 * math.cos(d2)))
    B = (k1 * r1 * (math.cos(d1) - c1 / g1 * math.sin(d1))
         - k2 * r2 * (math.cos(d2) - c2 / g2 * math.sin(d2)))
    return A, B


class _HarmonicRiding(dv.DoubleValve):
    """A riding cut-off valve where both valves move harmonically (Zeuner's form)."""

    def main_coefficients(self) -> tuple[float, float]:  # pragma: no cover - interface
        raise NotImplementedError

    def cutoff_coefficients(self) -> tuple[float, float]:  # pragma: no cover - interface
        raise NotImplementedError

    def main_travel(self, theta):
        C, S = self.main_coefficients()
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)

    def cutoff_travel(self, theta):
        C, S = self.cutoff_coefficients()
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)

    def zeuner_closing_coefficients(self):
        (C, S), (C1, S1) = self.main_coefficients(), self.cutoff_coefficients()
        return C - C1, S - S1


@dataclass(frozen=True)
class PolonceauSpec:
    """A Polonceau gear (all SI; Spangler Arts. 127-134).

    Parameters
    ----------
    main : MainValveSpec
        The main valve's laps and ports.
    cutoff : CutoffSpec
        The cut-off block's passages (``kind = "riding"``).
    eccentricity_m : float
        The Gooch link's eccentrics' throw r [m].
    angular_advance_rad : float
        Their angular advance delta [rad].
    eccentric_rod_m : float
        Eccentric rod length g [m].
    half_link_m : float
        Half the link's chord c [m].
    main_block_m : float
        Offset u of the main valve's radius rod from the link's centre [m].
    setting : float, optional
        Offset of the cut-off valve's radius rod, u1 / c [-], in [-1, 1].
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (the Gooch link solved; see the module doc).
    radius_rod_m : float or None, optional
        Radius rod g1 of the exact motion [m]; None for the eccentric rods' length.
    """

    main: dv.MainValveSpec
    cutoff: dv.CutoffSpec
    eccentricity_m: float
    angular_advance_rad: float
    eccentric_rod_m: float
    half_link_m: float
    main_block_m: float
    setting: float = 1.0
    motion: str = "zeuner"
    radius_rod_m: float | None = None


class PolonceauGear(_HarmonicRiding):
    """Polonceau valve on a Gooch link with two radius rods.

    Its setting is the cut-off valve's radius rod on the link, ``u1 / c``.

    Parameters
    ----------
    spec : PolonceauSpec
        The link, both radius rods and the valves.
    """

    name = "polonceau"
    summary = ("Polonceau valve: cut-off block on the main valve's back, both valves on one "
               "Gooch link by two radius rods (Spangler Arts. 127-134); setting = u1/c")
    setting_name = "cut-off valve's radius rod on the link, u1 / c (1 top, -1 bottom)"
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: PolonceauSpec):
        self.spec = spec
        self._exact = None
        if spec.motion == "exact":
            self._exact = (self._link(spec.main_block_m),
                           self._link(spec.setting * spec.half_link_m))

    def _link(self, u: float):
        from corliss.valves.link_motion import LinkMotion, LinkMotionSpec
        s, m = self.spec, self.spec.main
        return LinkMotion(LinkMotionSpec(
            kind="gooch", eccentricity_m=s.eccentricity_m, angular_advance_rad=s.angular_advance_rad,
            eccentric_rod_m=s.eccentric_rod_m, half_link_m=s.half_link_m, block_m=u,
            lap_m=m.lap_m, exhaust_lap_m=m.exhaust_lap_m, port_width_m=m.port_width_m,
            port_length_m=m.port_length_m, motion="exact", radius_rod_m=s.radius_rod_m))

    def main_travel(self, theta):
        if self._exact is not None:
            return self._exact[0].travel(theta)
        return super().main_travel(theta)

    def cutoff_travel(self, theta):
        if self._exact is not None:
            return self._exact[1].travel(theta)
        return super().cutoff_travel(theta)

    def _gooch(self, u):
        s = self.spec
        return gooch(s.eccentricity_m, s.angular_advance_rad, s.eccentric_rod_m, s.half_link_m, u)

    def main_coefficients(self):
        """The main valve's motion in Zeuner's form, a Gooch valve at ``u``.

        Returns
        -------
        C, S : float
            Coefficients [m] of ``C cos(theta) + S sin(theta)`` (Art. 65).
        """
        return self._gooch(self.spec.main_block_m)

    def cutoff_coefficients(self):
        """The cut-off valve's motion in Zeuner's form, a Gooch valve at ``u1``.

        Returns
        -------
        C, S : float
            Coefficients [m] of ``C cos(theta) + S sin(theta)`` (Art. 65).
        """
        return self._gooch(self.spec.setting * self.spec.half_link_m)


@dataclass(frozen=True)
class GuinotteSpec:
    """A Guinotte gear (all SI; Spangler Arts. 146-148).

    Parameters
    ----------
    main : MainValveSpec
        The main valve's laps and ports.
    cutoff : CutoffSpec
        The cut-off valve's passages (``kind = "riding"``).
    eccentricity_m : float
        Main eccentric's throw r [m].
    angular_advance_rad : float
        Main eccentric's angular advance delta [rad].
    upper : tuple of float
        ``(r1 [m], d1 [rad], g1 [m], c1 [m])``: the eccentric, its advance and rod
        to the link's upper end, and the link's part above the suspension.
    lower : tuple of float
        ``(r2 [m], d2 [rad], g2 [m], c2 [m])``: the same for the lower end.
    setting : float, optional
        Block position in [-1, 1] [-]: u = setting c1 above the centre, setting c2
        below.
    """

    main: dv.MainValveSpec
    cutoff: dv.CutoffSpec
    eccentricity_m: float
    angular_advance_rad: float
    upper: tuple[float, float, float, float]
    lower: tuple[float, float, float, float]
    setting: float = 1.0

    @property
    def block_m(self) -> float:
        """Block offset u from the link's suspension at this setting.

        Returns
        -------
        float
            u [m]: ``setting * c1`` for a setting >= 0, ``setting * c2`` below.
        """
        return self.setting * (self.upper[3] if self.setting >= 0 else self.lower[3])


class GuinotteGear(_HarmonicRiding):
    """Guinotte gear: main eccentric, cut-off valve on a Gooch link with unequal eccentrics.

    Its setting is the block's position on the link, ``u / c1`` above the centre and
    ``u / c2`` below.

    Parameters
    ----------
    spec : GuinotteSpec
        The main eccentric, the link's two eccentrics and rods, and the valves.
    """

    name = "guinotte"
    summary = ("Guinotte gear: Polonceau-type valve, cut-off valve on a Gooch link with unequal "
               "eccentrics, rods and link parts (Spangler Arts. 146-148); setting = u/c1 or u/c2")
    setting_name = "cut-off radius rod on the link (1: u = c1, 0: centre, -1: u = -c2)"
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: GuinotteSpec):
        self.spec = spec

    def main_coefficients(self):
        """The main valve's motion in Zeuner's form: its own eccentric,
        ``r sin(theta + delta)``.

        Returns
        -------
        C, S : float
            Coefficients [m] of ``C cos(theta) + S sin(theta)``: ``r sin(delta)``,
            ``r cos(delta)``.
        """
        s = self.spec
        return (s.eccentricity_m * math.sin(s.angular_advance_rad),
                s.eccentricity_m * math.cos(s.angular_advance_rad))

    def cutoff_coefficients(self, u: float | None = None):
        """The cut-off valve's motion in Zeuner's form (Art. 147; see :func:`guinotte`).

        Parameters
        ----------
        u : float or None, optional
            Block offset from the suspension [m]; None for the spec's
            :attr:`GuinotteSpec.block_m`.

        Returns
        -------
        C, S : float
            Coefficients [m] of ``C cos(theta) + S sin(theta)``.
        """
        s = self.spec
        r1, d1, g1, c1 = s.upper
        r2, d2, g2, c2 = s.lower
        return guinotte(r1, d1, g1, c1, r2, d2, g2, c2, s.block_m if u is None else u)


POLONCEAU_KEYS = group(
    "polonceau", "Polonceau's gear: a riding cut-off valve driven from a Gooch link.",
    ECCENTRICITY, ANGULAR_ADVANCE, dv.MAIN_KEYS, dv.RIDING_KEYS,
    Key("eccentric_rod", "length", "The link's eccentric rod.", within=POSITIVE_LENGTH,
        unit="in"),
    Key("half_link", "length", "Half the link's length c.", within=POSITIVE_LENGTH, unit="in"),
    Key("main_block", "length", "Offset of the main valve's block in the link, within the "
        "half link.", default=Derived("the half link"), unit="in"),
    dv.setting_key(-1.0, 1.0, "u1 / c"),
    Key("motion", "choice", "Zeuner's motion (infinite rods) or the exact linkage.",
        default="zeuner", choices=("zeuner", "exact")),
    Key("radius_rod", "length", "Radius rod of the link; absent: infinitely long.",
        default=None, within=POSITIVE_LENGTH, unit="in", when="with motion = \"exact\""),
)
GUINOTTE_KEYS = group(
    "guinotte", "Guinotte's gear: the cut-off valve from a link between two eccentrics.",
    ECCENTRICITY, ANGULAR_ADVANCE, dv.MAIN_KEYS, dv.RIDING_KEYS,
    *[Key(f"{name}_{k}", kind, f"{what} of the link's eccentric {k}.",
          within=POSITIVE_LENGTH if kind == "length" else None,
          unit="in" if kind == "length" else "deg")
      for k in ("1", "2")
      for name, kind, what in (("cutoff_eccentricity", "length", "Throw"),
                               ("cutoff_angular_advance", "angle", "Angular advance"),
                               ("cutoff_eccentric_rod", "length", "Rod"),
                               ("link_part", "length", "The link's part toward the end"))],
    dv.setting_key(-1.0, 1.0, "u / c1 or u / c2"),
)


def parse_polonceau(t: Table) -> PolonceauSpec:
    """Read a ``[valve_gear] type = "polonceau"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`POLONCEAU_KEYS`.

    Returns
    -------
    PolonceauSpec
        The gear's spec.
    """
    t = t.bound(POLONCEAU_KEYS)
    main = dv.parse_main(t)
    c = t.get("half_link")
    u = t.get("main_block", t.raw("half_link"))
    if abs(u) > c:
        raise InputError(t.key("main_block"), t.raw("main_block"), "an offset within the half link")
    r = t.get("eccentricity")
    motion = t.get("motion")
    g1 = t.get("radius_rod") if motion == "exact" else None
    return PolonceauSpec(main, dv.parse_riding(t, main), r, t.get("angular_advance"),
                         t.get("eccentric_rod"), c, u,
                         dv.check_setting(t, "setting", -1.0, 1.0, "u1 / c"), motion, g1)


def parse_guinotte(t: Table) -> GuinotteSpec:
    """Read a ``[valve_gear] type = "guinotte"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`GUINOTTE_KEYS`.

    Returns
    -------
    GuinotteSpec
        The gear's spec.
    """
    t = t.bound(GUINOTTE_KEYS)
    main = dv.parse_main(t)
    ends = []
    for k in ("1", "2"):
        ends.append((t.get(f"cutoff_eccentricity_{k}"), t.get(f"cutoff_angular_advance_{k}"),
                     t.get(f"cutoff_eccentric_rod_{k}"), t.get(f"link_part_{k}")))
    return GuinotteSpec(main, dv.parse_riding(t, main), t.get("eccentricity"),
                        t.get("angular_advance"), ends[0], ends[1],
                        dv.check_setting(t, "setting", -1.0, 1.0, "u / c1 or u / c2"))


register(GearType("polonceau", PolonceauGear.summary, parse_polonceau,
                  lambda spec: dv.built(PolonceauGear(spec)), POLONCEAU_KEYS))
register(GearType("guinotte", GuinotteGear.summary, parse_guinotte,
                  lambda spec: dv.built(GuinotteGear(spec)), GUINOTTE_KEYS))
