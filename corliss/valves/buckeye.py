"""The Buckeye gear: cut-off blocks riding inside a main valve that takes steam inside,
driven through a floating lever so that their motion on the main valve is the cut-off
eccentric's alone; a shaft governor turns the loose cut-off eccentric (Spangler Arts.
135-140).

Linkage (Art. 136, Fig. 87): the main eccentric (r, delta) drives the valve stem at d
through its rod; d is also on a lever df pivoted to the frame at f; the middle i of df
carries the centre of the floating lever hj, whose end h the cut-off eccentric (r1)
drives and whose end j drives the cut-off valve stem.  Since i is the middle of both df
and hj, j = d + f - h: the cut-off valve's displacement relative to the main valve is
that of h reversed, "independent of the main eccentric" (Art. 137)::

    x_r = r sin(w + d) + r1 sin(w - d1) - r sin(w + d) = r1 sin(w - d1)

"the cut-off valve moves on the main valve in the same way as though the main valve did
not move at all, and the cut-off eccentric was connected through an ordinary reverse
lever".  The block closes its passage when x_r reaches s (Art. 138: closed from "oc"
until "oe", where the circle of radius s cuts the cut-off valve circle).

Sign of delta1.  Art. 137 measures the cut-off eccentric's angle from its mid position
against the rotation (g'ag = delta1 - w).  The valve circle of Arts. 138-139 is drawn as
any valve circle is, its advance measured with the rotation, and in that sense Art.
139's statements hold: "If the angle of advance delta1 is zero, the cut-off takes place
at on, and the port is again open to steam at oj after the main valve has cut off" and
"As delta1 increases negatively the point of cut-off is later and later".  This module
uses that sense throughout: x_r = r1 sin(w + delta1), + closing the head passage (the
same motion as Art. 137's with the sign of its delta1 reversed).  The governor's
setting runs from 0 (at rest: delta1 at its most negative, latest cut-off) to 1 (full
speed: delta1 turned forward by the governor's swing, earliest cut-off); the main
eccentric is keyed (Art. 140).

``motion = "exact"``: the linkage itself per crank angle (closed-form circle
intersections): both rods of finite length, d on its arc about f, h on its arc about i;
the stems taking the motion of d and j along the line of the valves; each valve set for
equal lead.  The identity j - d = f - h is then still exact as vectors, but h depends a
little on i, so the relative motion depends on the main eccentric to second order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import Table
from corliss.valves import double_valve as dv
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import ANGULAR_ADVANCE, ECCENTRICITY


@dataclass(frozen=True)
class BuckeyeSpec:
    """A Buckeye gear (all SI; Spangler Arts. 135-140).

    Parameters
    ----------
    main : MainValveSpec
        The main valve's laps and ports (it takes steam inside).
    cutoff : CutoffSpec
        The blocks' passages (``kind = "riding"``).
    eccentricity_m : float
        Main eccentric's throw r [m].
    angular_advance_rad : float
        Main eccentric's angular advance delta [rad] (keyed, Art. 140).
    cutoff_eccentricity_m : float
        Cut-off eccentric's throw r1 [m] ("in the Buckeye engine these are equal",
        Art. 136).
    cutoff_angular_advance_rad : float
        delta1 at rest (setting 0), in the sense of Arts. 138-139 (see the module
        doc) [rad].
    governor_swing_rad : float
        How far the governor turns the cut-off eccentric forward from rest to full
        speed [rad].
    setting : float, optional
        Governor position in [0, 1] [-]: 0 at rest (latest cut-off), 1 at full speed.
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (the linkage solved; see the module doc).
    eccentric_rod_m, cutoff_eccentric_rod_m : float or None, optional
        The exact linkage's eccentric rods cd and gh [m]; None for Zeuner's motion.
    rock_lever_m : float or None, optional
        The exact linkage's lever df, d to f [m].
    floating_lever_m : float or None, optional
        The exact linkage's floating lever hj [m]; None for the rock lever's length.
    """

    main: dv.MainValveSpec
    cutoff: dv.CutoffSpec
    eccentricity_m: float
    angular_advance_rad: float
    cutoff_eccentricity_m: float
    cutoff_angular_advance_rad: float
    governor_swing_rad: float
    setting: float = 0.0
    motion: str = "zeuner"
    eccentric_rod_m: float | None = None
    cutoff_eccentric_rod_m: float | None = None
    rock_lever_m: float | None = None
    floating_lever_m: float | None = None

    @property
    def delta1(self) -> float:
        """delta1 at the current setting: the rest value turned forward by the
        setting's share of the governor's swing.

        Returns
        -------
        float
            The cut-off eccentric's advance [rad], in the sense of Arts. 138-139.
        """
        return self.cutoff_angular_advance_rad + self.setting * self.governor_swing_rad


class BuckeyeGear(dv.DoubleValve):
    """Buckeye gear: floating lever, cut-off blocks inside the main valve, shaft governor.

    Its setting is the governor's position, 0 (at rest) to 1 (full speed).

    Parameters
    ----------
    spec : BuckeyeSpec
        The valves, eccentrics, governor swing and (for the exact motion) levers.
    """

    name = "buckeye"
    summary = ("Buckeye gear: cut-off blocks inside a main valve taking steam inside, floating "
               "lever, governor-turned cut-off eccentric (Spangler Arts. 135-140); setting = "
               "governor position 0..1")
    setting_name = "governor position (0 at rest, latest cut-off; 1 full speed, cut-off eccentric turned forward)"
    setting_range = (0.0, 1.0)
    relative_label = "relative (cut-off - main)"

    def __init__(self, spec: BuckeyeSpec):
        self.spec = spec
        self._exact = _Linkage(spec) if spec.motion == "exact" else None

    def main_travel(self, theta):
        if self._exact is not None:
            return self._exact(theta)[0]
        s = self.spec
        return dv.eccentric_travel(theta, s.eccentricity_m, s.angular_advance_rad)

    def closing_travel(self, theta):
        """Relative displacement of the blocks on the main valve, + closing the head
        passage: ``r1 sin(theta + delta1)`` in Zeuner's form (Art. 137), or the
        solved linkage's with ``motion = "exact"``.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Relative displacement x_r [m], shape ``(n,)``.
        """
        if self._exact is not None:
            return self._exact(theta)[1]
        s = self.spec
        return dv.eccentric_travel(theta, s.cutoff_eccentricity_m, s.delta1)

    def cutoff_travel(self, theta):
        """The blocks' own displacement: the main valve's plus the relative one.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacement [m], shape ``(n,)``, in the sense that opens the head
            steam port.
        """
        return self.main_travel(theta) + self.closing_travel(theta)

    def zeuner_closing_coefficients(self):
        s = self.spec
        return (s.cutoff_eccentricity_m * math.sin(s.delta1),
                s.cutoff_eccentricity_m * math.cos(s.delta1))


class _Linkage:
    """The Buckeye linkage solved per crank angle (see the module doc).

    Plane coordinates: X along the valves' line in the sense that opens the head steam
    port, the shaft at the origin, the rods running from the shaft towards +X.  The
    main eccentric's centre is at r (sin, cos)(theta + delta), so its rod end moves
    r sin(theta + delta) to first order; the cut-off eccentric's at -r1 (sin, cos)(theta
    + delta1), so that h moves back as the blocks move forward (j = d + f - h).  d sits
    on the valves' line (y = 0) at mid travel with f straight below it at -rock; i is
    the middle of df; the floating lever's half length equals half the rock lever's
    unless given, which puts h on the valves' line at mid travel.
    """

    def __init__(self, spec: BuckeyeSpec):
        self.s = spec

    def __call__(self, theta):
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        main, rel = self._raw(np.concatenate([th, [0.0, math.pi]]))
        main = main[:-2] - 0.5 * (main[-2] + main[-1])   # equal lead
        rel = rel[:-2] - 0.5 * (rel[-2] + rel[-1])
        return main.reshape(np.shape(theta)), rel.reshape(np.shape(theta))

    def _raw(self, th):
        s = self.s
        r, g, a2 = s.eccentricity_m, s.eccentric_rod_m, s.rock_lever_m
        r1, g1 = s.cutoff_eccentricity_m, s.cutoff_eccentric_rod_m
        b = 0.5 * (s.floating_lever_m if s.floating_lever_m is not None else a2)
        ph = th + s.angular_advance_rad
        pc = np.vstack([r * np.sin(ph), r * np.cos(ph)])
        f = np.array([[math.sqrt(g * g - r * r)], [-a2]])
        d = _intersect(pc, g, f, a2, upper=True)
        i = 0.5 * (d + f)
        p1 = th + s.delta1
        gc = -np.vstack([r1 * np.sin(p1), r1 * np.cos(p1)])
        h = _intersect(gc, g1, i, b, upper=True)
        j = 2.0 * i - h
        return d[0], j[0] - d[0]


def _intersect(p, rp, q, rq, upper: bool):
    """The intersection of circles (p, rp) and (q, rq) [centres as arrays (2, n) or
    (2, 1)]: the branch of greater y when ``upper``, else of smaller y."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    dist = np.hypot(dx, dy)
    if np.any(dist > rp + rq) or np.any(dist < abs(rp - rq)):
        raise ValueError("the Buckeye linkage cannot be assembled at some crank angle: "
                         "lengthen the rods or levers")
    a = (rp * rp - rq * rq + dist * dist) / (2 * dist)
    hgt = np.sqrt(np.maximum(rp * rp - a * a, 0.0))
    mx, my = p[0] + a * dx / dist, p[1] + a * dy / dist
    x1, y1 = mx + hgt * dy / dist, my - hgt * dx / dist
    x2, y2 = mx - hgt * dy / dist, my + hgt * dx / dist
    pick1 = (y1 > y2) if upper else (y1 < y2)
    return np.vstack([np.where(pick1, x1, x2), np.where(pick1, y1, y2)])


BUCKEYE_KEYS = group(
    "buckeye", "The Buckeye gear: main valve on a rocker, riding cut-off valve on a "
    "governed eccentric.",
    ECCENTRICITY, ANGULAR_ADVANCE, dv.CUTOFF_ECCENTRIC_KEYS, dv.MAIN_KEYS, dv.RIDING_KEYS,
    Key("governor_swing", "angle", "How far the governor turns the cut-off eccentric "
        "between settings 0 and 1.", default="0 deg", unit="deg"),
    dv.setting_key(0.0, 1.0, "governor position"), dv.MOTION_KEYS,
    Key("rock_lever", "length", "Rocker arm, more than four times the eccentric's throw.",
        within=POSITIVE_LENGTH, unit="in", when="with motion = \"exact\" (required there)"),
    Key("floating_lever", "length", "Floating lever of the cut-off, more than four times the "
        "throw; absent: none.", default=None, within=POSITIVE_LENGTH, unit="in",
        when="with motion = \"exact\""),
)


def parse_buckeye(t: Table) -> BuckeyeSpec:
    """Read a ``[valve_gear] type = "buckeye"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`BUCKEYE_KEYS`.

    Returns
    -------
    BuckeyeSpec
        The gear's spec.
    """
    t = t.bound(BUCKEYE_KEYS)
    main = dv.parse_main(t)
    cut = dv.parse_riding(t, main)
    r = t.get("eccentricity")
    r1 = t.get("cutoff_eccentricity")
    motion = t.get("motion")
    kw = {}
    if motion == "exact":
        kw = {"eccentric_rod_m": dv.rod(t, "eccentric_rod", r, motion),
              "cutoff_eccentric_rod_m": dv.rod(t, "cutoff_eccentric_rod", r1, motion),
              "rock_lever_m": t.get("rock_lever"),
              "floating_lever_m": t.get("floating_lever")}
        for key, v in (("rock_lever", kw["rock_lever_m"]),
                       ("floating_lever", kw["floating_lever_m"])):
            if v is not None and v <= 4 * max(r, r1):
                raise InputError(t.key(key), t.raw(key), "a lever more than four times the "
                                 "eccentric's throw (its arc must stay near its line)")
    spec = BuckeyeSpec(main, cut, r, t.get("angular_advance"), r1,
                       t.get("cutoff_angular_advance"), t.get("governor_swing"),
                       dv.check_setting(t, "setting", 0.0, 1.0, "governor position"),
                       motion, **kw)
    if motion == "exact":
        try:
            BuckeyeGear(spec).main_travel(np.linspace(0, 2 * math.pi, 73))
        except ValueError as exc:
            raise InputError(t.key("rock_lever"), t.raw("rock_lever"), str(exc)) from None
    return spec


register(GearType("buckeye", BuckeyeGear.summary, parse_buckeye,
                  lambda spec: dv.built(BuckeyeGear(spec)), BUCKEYE_KEYS))
