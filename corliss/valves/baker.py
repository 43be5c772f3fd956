"""The Baker valve gear, solved exactly as a linkage.

A radial gear without a sliding link, on many North American locomotives from about
1910.  Its parts, as the makers and the enginemen's catechisms name them (The Pilliod
Company's booklet *The Baker Valve Gear*; the question-and-answer section on the Baker
gear of Project Gutenberg ebook no. 17783, Qs. 15-23; the Wikipedia article "Baker valve
gear", section Operation):

* the eccentric crank on the main crank pin, which "always follows the main pin"
  (Q. 17), and the eccentric rod to the lower end of the gear connecting rod;
* the gear connecting rod (the "main link"), hung at its middle pin from the radius
  bars (the "swing links"), which hang from a pin on the reverse yoke;
* the reverse yoke, pivoted on the gear frame and tilted by the reach rod: the setting;
* the bell crank, pivoted on the gear frame, its horizontal arm to the top of the gear
  connecting rod, its vertical arm to the valve rod (the radius rod), which drives the
  combination lever as in Walschaerts's gear (union link to the crosshead).

The radius bars and reverse yoke "take the place of the link" (Q. 16).  The crosshead
"moves the valve the amount of the lap and lead each way, and the eccentric crank gives
the remainder of the movement.  In the short cut-offs the actual effect of the eccentric
crank is reduced, while the crosshead movement is constant" (Pilliod): the lead is the
same at every cut-off.  With the bell crank blocked the valve has "lap and lead travel
and a port opening equal to the lead for all cut-offs" (Q. 18).  Wikipedia: with the
yoke centred, the top of the gear connecting rod is in line with the yoke's two pivots,
and the back-and-forth motion of the rod's lower end leaves its top nearly still.

Layout (*chosen here*, the drawings not being at hand; every choice said): the axle at
the origin, X along the line of stroke towards the cylinder, Y up, the engine running
ahead clockwise (as the Walschaerts gear of :mod:`corliss.valves.radial_gear`).  The
combination lever, union link and crosshead arm are laid out exactly as that gear's
(:func:`corliss.valves.radial_gear.combination_lever`).  At the dead centres the valve
rod is horizontal, the bell crank's arms horizontal and vertical, the gear connecting
rod vertical below the bell crank's horizontal arm (its top U, middle M and lower end P
on one vertical line), and the eccentric crank square to the line from the axle to P
(P then takes the same place on both dead centres, as the Walschaerts link's foot does).
The reverse yoke pivots about the point O where the middle pin stands at the dead
centres, and carries the radius bars' pin Y at the radius bars' length h from O: so Y
is on a circle of radius h about O, the middle pin M on a circle of radius h about Y,
and at the dead centres M = O whatever the yoke's angle.  Tilting the yoke then moves
nothing at the dead centres: the lead is exactly constant (Pilliod).  With the yoke
centred (Y straight above O) M runs on a circle whose tangent at O is horizontal, so
the gear connecting rod's top stays still to first order (Wikipedia) and the valve
has the combination lever's travel alone, 2 (lap + lead) (Q. 18).  Tilted by alpha,
M's arc is inclined by alpha at O, so the rod's horizontal swing raises and lowers its
top, which the bell crank turns into the valve rod's motion.

*Derived here*, with long rods (first order): the eccentric rod, inclined by phi at the
dead centres, moves P along the stroke (e / cos phi) sin(theta); the gear connecting
rod turns about its top, so M moves n / (n + m) of that (m, n the rod's lower and upper
parts), rising tan(alpha) times as much; the top rises as M does, the bell crank
turns that (k2 / k1) times into the valve rod's motion, and the lever multiplies that
by (1 +- a/l) as Walschaerts's does::

    C = (a/l) R        S = (1 +- a/l) (k2/k1) (n/(n+m)) tan(alpha) e / cos(phi)

*Derived here* too, to second order: the middle pin's arc about Y lifts it
Delta^2 / (2 h) as it swings Delta either way, while the gear connecting rod's tilt
drops its top n phi^2 / 2 below the middle pin's rise (phi = Delta / n): with the yoke
centred the top stays still to second order when the radius bars are as long as the
rod's upper part (h = n), the top then standing where the radius bars hang from, in
line with the yoke's pivots (Wikipedia's statement).  Otherwise the difference lifts
the top once each way of the swing, and the two ends' cut-offs part.

The exact linkage is solved at every crank angle: the eccentric crank's pin; then the
radius bars' angle by Newton's method (one unknown: the gear connecting rod's top
found from it where the rod meets the bell crank's arm, a circle intersection, and its
lower end on the line through the two, which the eccentric rod must reach); then the
combination lever as Walschaerts's; tabulated at 1/2 deg, splined, zeroed for
equal lead.  The yoke is tilted the way that runs the engine ahead for a positive
setting (that way found from the linkage itself when the gear is built).
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
from corliss.valves.radial_gear import RadialJoints, circle_intersection, combination_lever
from corliss.valves.slide_valve import (ALLEN_KEYS, LAP_KEYS, PORT_KEYS, LappedValve,
                                        parse_allen_passage, parse_ports)


@dataclass(frozen=True, kw_only=True)
class BakerSpec:
    """The Baker gear and its valve (all SI; see the module doc for the letters).

    All fields are keyword-only.

    Parameters
    ----------
    lap_m, exhaust_lap_m : tuple of float
        Steam and exhaust laps of the (head, crank) end [m].
    port_width_m, port_length_m : float
        Width of each steam port along the valve's travel, and its length [m].
    discharge_coefficient : float, optional
        Of the port openings [-].
    ports_per_end : int, optional
        Openings each edge uncovers.
    allen_passage_m : float or None, optional
        An Allen valve's passage [m]; None for a plain valve.
    setting : float, optional
        The reverse yoke's inclination over its full-gear inclination, -1 (full gear
        astern) .. 0 (mid gear) .. 1 (full gear ahead) [-].
    crank_m, connecting_rod_m : float
        Main crank R and connecting rod [m].
    eccentric_crank_m : float
        e, throw of the eccentric crank [m].
    eccentric_rod_m : float
        From the eccentric crank's pin to the gear connecting rod's lower end P [m].
    gear_rod_lower_m, gear_rod_upper_m : float
        m, from P to the middle pin M; n, from M to the top U [m].
    radius_bar_m : float
        h, the radius bars, from the yoke's pin Y to M (and the yoke's arm, O to Y) [m].
    bell_crank_horizontal_m, bell_crank_vertical_m : float
        k1, the bell crank's arm to U; k2, its arm to the valve rod [m].
    valve_rod_m : float
        From the bell crank's vertical arm to the combination lever [m].
    lever_valve_m, lever_crosshead_m, union_link_m, valve_height_m : float
        a, l, the union link and the valve stem's height, as Walschaerts's [m].
    max_yoke_rad : float
        The yoke's inclination at full gear [rad].
    admission : str, optional
        ``"outside"`` or ``"inside"``.
    """

    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1
    allen_passage_m: float | None = None
    setting: float = 1.0
    crank_m: float
    connecting_rod_m: float
    eccentric_crank_m: float
    eccentric_rod_m: float
    gear_rod_lower_m: float
    gear_rod_upper_m: float
    radius_bar_m: float
    bell_crank_horizontal_m: float
    bell_crank_vertical_m: float
    valve_rod_m: float
    lever_valve_m: float
    lever_crosshead_m: float
    union_link_m: float
    valve_height_m: float
    max_yoke_rad: float
    admission: str = "outside"

    def coefficients(self, setting: float | None = None) -> tuple[float, float]:
        """Zeuner's form ``x = C cos(theta) + S sin(theta)`` (module doc, first order).

        Parameters
        ----------
        setting : float or None, optional
            Yoke setting [-]; None for the spec's.

        Returns
        -------
        C, S : float
            Coefficients [m].
        """
        s = self.setting if setting is None else setting
        q = self.lever_valve_m / self.lever_crosshead_m
        gain = 1.0 + q if self.admission == "outside" else 1.0 - q
        lay = baker_layout(self)
        P0 = lay["P0"]
        cos_phi = math.sqrt(P0 @ P0) / self.eccentric_rod_m
        m, n = self.gear_rod_lower_m, self.gear_rod_upper_m
        S = (gain * self.bell_crank_vertical_m / self.bell_crank_horizontal_m * n / (n + m)
             * math.tan(s * self.max_yoke_rad) * self.eccentric_crank_m / cos_phi)
        return q * self.crank_m, S


def baker_layout(spec: BakerSpec) -> dict:
    """The fixed points of the Baker gear (module doc), the axle at the origin.

    Parameters
    ----------
    spec : BakerSpec
        The gear.

    Returns
    -------
    dict
        ``A0`` (the valve rod's pin on the lever at the dead centres), ``V0``, ``K``
        (the bell crank's pivot), ``U0``, ``O`` (the yoke's pivot, where M stands at
        the dead centres), ``P0``, ``Q0`` (the eccentric crank's pin at head dead
        centre), each an ndarray (x, y) [m]; ``yL`` the union link's height and ``arm``
        the crosshead arm's offset [m], as Walschaerts's.  ``P0``'s x is NaN when the
        eccentric rod cannot reach.
    """
    R, b, e, er = spec.crank_m, spec.connecting_rod_m, spec.eccentric_crank_m, spec.eccentric_rod_m
    a, ell = spec.lever_valve_m, spec.lever_crosshead_m
    g0 = math.asin(R / ell)
    ay = spec.valve_height_m + (-a if spec.admission == "outside" else a) * math.cos(g0)
    py = ay - spec.bell_crank_vertical_m - spec.gear_rod_upper_m - spec.gear_rod_lower_m
    reach2 = er * er - e * e - py * py
    px = math.sqrt(reach2) if reach2 > 0 else float("nan")
    P0 = np.array([px, py])
    O = P0 + np.array([0.0, spec.gear_rod_lower_m])
    U0 = O + np.array([0.0, spec.gear_rod_upper_m])
    K = U0 + np.array([spec.bell_crank_horizontal_m, 0.0])
    V0 = K + np.array([0.0, spec.bell_crank_vertical_m])
    A0 = V0 + np.array([spec.valve_rod_m, 0.0])
    # square to the axle-P line, following the main pin (clockwise running)
    Q0 = e * np.array([-P0[1], P0[0]]) / math.hypot(*P0)
    return {"A0": A0, "V0": V0, "K": K, "U0": U0, "O": O, "P0": P0, "Q0": Q0,
            "yL": ay - ell * math.cos(g0), "arm": A0[0] - spec.union_link_m - b}


def _points(spec: BakerSpec, th: np.ndarray, sense: float) -> dict:
    """Every joint at crank angles ``th`` (arrays (2, n) [m]) with the yoke tilted
    ``sense * setting * max_yoke``, and ``x_raw``, the valve's position from an
    arbitrary origin in the sense that opens the head steam port."""
    R, b, e, er = spec.crank_m, spec.connecting_rod_m, spec.eccentric_crank_m, spec.eccentric_rod_m
    m, n, h = spec.gear_rod_lower_m, spec.gear_rod_upper_m, spec.radius_bar_m
    k1, k2 = spec.bell_crank_horizontal_m, spec.bell_crank_vertical_m
    lay = baker_layout(spec)
    O, K = lay["O"], lay["K"]
    N = th.size
    lam = math.atan2(lay["Q0"][1], lay["Q0"][0])
    Q = np.array([e * np.cos(lam - th), e * np.sin(lam - th)])
    Bx, By = R * np.cos(th), -R * np.sin(th)
    Cx = Bx + np.sqrt(b * b - By * By)
    XH = np.array([Cx + lay["arm"], np.full(N, lay["yL"])])
    alpha = sense * spec.setting * spec.max_yoke_rad
    Y = O + h * np.array([math.sin(alpha), math.cos(alpha)])

    U0 = np.repeat(lay["U0"][:, None], N, axis=1)
    Kn = np.repeat(K[:, None], N, axis=1)

    def joints(mu):
        # M on its circle about Y; U where the rod's upper part meets the bell crank's
        # arm (the branch nearer U's place at the dead centres); P on the line M-U
        M = np.array([Y[0] - h * np.sin(mu), Y[1] - h * np.cos(mu)])
        U = circle_intersection(M, n, Kn, k1, U0)
        P = M + (m / n) * (M - U)
        return M, U, P

    def residual(mu):
        M, U, P = joints(mu)
        return np.hypot(P[0] - Q[0], P[1] - Q[1]) - er

    # one unknown, the radius bars' angle: Newton's method, the derivative by a
    # difference, each step held to 0.1 rad
    mu = np.full(N, alpha)
    for _ in range(60):
        f0 = residual(mu)
        d = (residual(mu + 1e-7) - f0) / 1e-7
        step = np.clip(-f0 / d, -0.1, 0.1)
        mu = mu + step
        if np.all(np.abs(step) < 1e-14):
            break
    M, U, P = joints(mu)
    bad = ~(np.abs(residual(mu)) < 1e-9 * er)
    nu = np.arctan2(K[1] - U[1], K[0] - U[0])
    V = np.array([K[0] - k2 * np.sin(nu), K[1] + k2 * np.cos(nu)])
    outside = spec.admission == "outside"
    W, w, da, dl = combination_lever(V, XH, spec.valve_rod_m, spec.lever_valve_m,
                                     spec.lever_crosshead_m, spec.union_link_m,
                                     spec.valve_height_m, outside)
    x_raw = -W[0] if outside else W[0]
    x_raw = np.where(bad, np.nan, x_raw)
    rep = lambda p: np.repeat(np.asarray(p, dtype=float)[:, None], N, axis=1)  # noqa: E731
    return {"axle": np.zeros((2, N)), "crank_pin": np.array([Bx, By]),
            "crosshead": np.array([Cx, np.zeros(N)]), "crosshead_arm": XH,
            "eccentric_crank_pin": Q, "gear_rod_lower": P, "gear_rod_middle": M,
            "gear_rod_top": U, "yoke_pivot": rep(O), "yoke_pin": rep(Y),
            "bell_crank_pivot": rep(K), "bell_crank_valve": V,
            "radius_rod_pin": W + da * w, "valve_pin": W, "union_pin": W + dl * w,
            "x_raw": x_raw}


def _sense(spec: BakerSpec) -> float:
    """+1 or -1: the yoke's tilt that runs the engine ahead at a positive setting (the
    valve then leads the crank: the first harmonic's sine part positive)."""
    th = np.array([0.5 * math.pi, 1.5 * math.pi])
    x = _points(dataclasses.replace(spec, setting=1.0), th, 1.0)["x_raw"]
    return 1.0 if x[0] - x[1] >= 0.0 else -1.0


N_TABLE = 720

SETTING_NAME = "reverse yoke's inclination / its full-gear inclination (1 full gear ahead, " \
               "0 mid gear, -1 full gear astern)"


class BakerGear(LappedValve):
    """The Baker gear driving a lapped valve, solved exactly (module doc).

    Parameters
    ----------
    spec : BakerSpec
        The gear and its valve.

    Raises
    ------
    InputError
        If the linkage cannot be assembled at some crank angle.
    """

    name = "baker"
    summary = ("Baker radial gear (reverse yoke, radius bars, gear connecting rod, bell "
               "crank), solved exactly; setting = reverse yoke")
    setting_name = SETTING_NAME
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: BakerSpec):
        self.spec = spec
        self.sense = _sense(spec)
        th = np.linspace(0.0, 2 * math.pi, N_TABLE + 1)
        raw = _points(spec, th, self.sense)["x_raw"]
        if not np.all(np.isfinite(raw)):
            raise InputError("valve_gear.eccentric_rod", f"{spec.eccentric_rod_m} m",
                             "a Baker linkage that can be assembled at every crank angle: with "
                             "these dimensions a rod or bar is too short to reach")
        self._zero = 0.5 * (raw[0] + raw[N_TABLE // 2])
        x = raw - self._zero
        x[-1] = x[0]
        from scipy.interpolate import CubicSpline   # a Baker gear only: a run of another
        self._spline = CubicSpline(th, x, bc_type="periodic")  # gear imports no scipy solver

    def travel(self, theta):
        return self._spline(np.asarray(theta, dtype=float) % (2 * math.pi))

    def zeuner_travel(self, theta):
        """Valve displacement of the first-order form ``C cos + S sin`` (module doc).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad].

        Returns
        -------
        ndarray
            x [m].
        """
        C, S = self.spec.coefficients()
        th = np.asarray(theta, dtype=float)
        return C * np.cos(th) + S * np.sin(th)

    def points(self, theta) -> dict:
        """Every joint at crank angles ``theta``, from the solve the travel comes from.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad], shape ``(n,)``.

        Returns
        -------
        dict
            ``{joint: ndarray (2, n)}`` [m], and ``x`` the valve's displacement [m].
        """
        p = _points(self.spec, np.atleast_1d(np.asarray(theta, dtype=float)), self.sense)
        p["x"] = p.pop("x_raw") - self._zero
        return p

    def joints(self, theta: float) -> RadialJoints:
        """The joints at crank angle ``theta``, drawn as the radial gears' are.

        Parameters
        ----------
        theta : float
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        RadialJoints
            The joints [m], the arc the middle pin swings on (``guide``), the rods and
            the valve's displacement [m].
        """
        p = self.points(np.array([float(theta)]))
        x = float(p.pop("x")[0])
        pts = {k: (float(v[0, 0]), float(v[1, 0])) for k, v in p.items()}
        s = self.spec
        Y, h = np.array(pts["yoke_pin"]), s.radius_bar_m
        a0 = math.atan2(pts["yoke_pivot"][1] - Y[1], pts["yoke_pivot"][0] - Y[0])
        arc = a0 + np.linspace(-0.35, 0.35, 21)
        guide = tuple((float(Y[0] + h * math.cos(a)), float(Y[1] + h * math.sin(a))) for a in arc)
        rods = {"main crank": (s.crank_m, "axle", "crank_pin"),
                "connecting rod": (s.connecting_rod_m, "crank_pin", "crosshead"),
                "eccentric crank": (s.eccentric_crank_m, "axle", "eccentric_crank_pin"),
                "eccentric rod": (s.eccentric_rod_m, "eccentric_crank_pin", "gear_rod_lower"),
                "gear rod, lower": (s.gear_rod_lower_m, "gear_rod_lower", "gear_rod_middle"),
                "gear rod, upper": (s.gear_rod_upper_m, "gear_rod_middle", "gear_rod_top"),
                "radius bar": (h, "yoke_pin", "gear_rod_middle"),
                "yoke": (h, "yoke_pivot", "yoke_pin"),
                "bell crank, horizontal": (s.bell_crank_horizontal_m, "bell_crank_pivot",
                                           "gear_rod_top"),
                "bell crank, vertical": (s.bell_crank_vertical_m, "bell_crank_pivot",
                                         "bell_crank_valve"),
                "valve rod": (s.valve_rod_m, "bell_crank_valve", "radius_rod_pin"),
                "lever, valve": (s.lever_valve_m, "radius_rod_pin", "valve_pin"),
                "lever, crosshead": (s.lever_crosshead_m, "radius_rod_pin", "union_pin"),
                "union link": (s.union_link_m, "union_pin", "crosshead_arm")}
        return RadialJoints(points=pts, guide=guide, rods_m=rods, valve_m=x)


def _len(name: str, doc: str, **kw) -> Key:
    return Key(name, "length", doc, within=POSITIVE_LENGTH, unit="in", **kw)


BAKER_KEYS = group(
    "baker", "The Baker valve gear (reverse yoke, radius bars, gear connecting rod, bell "
    "crank, combination lever), solved exactly.",
    LAP_KEYS,
    Key("setting", "number", "The reverse yoke: -1 (full gear astern) through 0 (mid gear) "
        "to 1 (full gear ahead).", default=1.0, within=(-1.0, 1.0)),
    ALLEN_KEYS, PORT_KEYS,
    _len("stroke", "The engine's stroke (twice the main crank): the gear's own copy."),
    _len("connecting_rod", "The engine's connecting rod: the gear's own copy."),
    _len("eccentric_crank", "e: throw of the eccentric crank."),
    _len("eccentric_rod", "From the eccentric crank's pin to the gear connecting rod's lower "
         "end."),
    _len("gear_rod_lower", "m: the gear connecting rod from its lower end to its middle pin."),
    _len("gear_rod_upper", "n: the gear connecting rod from its middle pin to its top."),
    _len("radius_bar", "h: the radius bars, from the yoke's pin to the middle pin (the yoke's "
         "arm from its pivot to that pin is the same)."),
    _len("bell_crank_horizontal", "k1: the bell crank's horizontal arm, to the gear "
         "connecting rod's top."),
    _len("bell_crank_vertical", "k2: the bell crank's vertical arm, to the valve rod."),
    _len("valve_rod", "From the bell crank to the combination lever."),
    _len("lever_crosshead", "l: along the combination lever from the valve rod's pin to the "
         "union link's, longer than the crank."),
    _len("lever_valve", "a: along the combination lever from the valve rod's pin to the "
         "valve stem's."),
    _len("union_link", "The union link from the crosshead to the combination lever."),
    Key("valve_height", "length", "The valve stem's line above the line of stroke.",
        unit="in"),
    Key("max_yoke", "angle", "The reverse yoke's inclination at full gear, above 0 and below "
        "45 deg.", within=(0.0, math.radians(45.0)), unit="deg"),
    Key("admission", "choice", "Outside admission (D valve) or inside (piston valve).",
        default="outside", choices=("outside", "inside")),
)


def parse_baker(t: Table) -> BakerSpec:
    """Read a ``[valve_gear] type = "baker"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`BAKER_KEYS`.

    Returns
    -------
    BakerSpec
        The gear's spec.
    """
    t = t.bound(BAKER_KEYS)
    R = t.get("stroke") / 2
    ell = t.get("lever_crosshead")
    if not ell > R:
        raise InputError(t.key("lever_crosshead"), t.raw("lever_crosshead"),
                         f"a length above {R / units.INCH_m:.4g} in (the lever must swing the "
                         "crosshead's half stroke)")
    a = t.get("lever_valve")
    admission = t.get("admission")
    if admission == "inside" and not a < ell:
        raise InputError(t.key("lever_valve"), t.raw("lever_valve"),
                         "with inside admission, a valve pin between the valve rod's and the "
                         "union link's (shorter than lever_crosshead)")
    ymax = t.get("max_yoke")
    if not 0.0 < ymax < math.radians(45.0):
        raise InputError(t.key("max_yoke"), t.raw("max_yoke"), "an angle above 0 and below 45 deg")
    spec = BakerSpec(
        lap_m=t.get("lap"), exhaust_lap_m=t.get("exhaust_lap"), setting=t.get("setting"),
        allen_passage_m=parse_allen_passage(t), **parse_ports(t),
        crank_m=R, connecting_rod_m=t.get("connecting_rod"),
        eccentric_crank_m=t.get("eccentric_crank"), eccentric_rod_m=t.get("eccentric_rod"),
        gear_rod_lower_m=t.get("gear_rod_lower"), gear_rod_upper_m=t.get("gear_rod_upper"),
        radius_bar_m=t.get("radius_bar"),
        bell_crank_horizontal_m=t.get("bell_crank_horizontal"),
        bell_crank_vertical_m=t.get("bell_crank_vertical"), valve_rod_m=t.get("valve_rod"),
        lever_valve_m=a, lever_crosshead_m=ell, union_link_m=t.get("union_link"),
        valve_height_m=t.get("valve_height"), max_yoke_rad=ymax, admission=admission)
    if not math.isfinite(baker_layout(spec)["P0"][0]):
        raise InputError(t.key("eccentric_rod"), t.raw("eccentric_rod"),
                         "an eccentric rod long enough to reach the gear connecting rod's "
                         "lower end")
    C, S = spec.coefficients()
    reach = math.hypot(C, S)
    for end, lap in zip(("head", "crank"), spec.lap_m):
        if lap >= reach:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap below the valve's half travel at this setting "
                             f"({reach / units.INCH_m:.4g} in): the {end}-end port never opens")
    return spec


register(GearType("baker", BakerGear.summary, parse_baker, BakerGear, BAKER_KEYS))
