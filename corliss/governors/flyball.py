"""Fly-ball governors on a vertical spindle: Watt's conical pendulum, Porter's loaded
governor, and the spring-loaded governors (Hartnell, Pickering, Waters).

Watt and Porter (Marks Ch. XVIII Art. 97, Figs. 58-59)
------------------------------------------------------
N balls of mass m on arms of length l hung at a distance e from the spindle's axis
(e = 0: hung on the axis); links as long as the arms join each ball to a sleeve on the
spindle, which carries a central load of mass W (Porter's "pear-shaped load"; zero for
Watt's governor, whose sleeve only carries the rods).  With theta the arm's angle from
the spindle, the ball is at radius r = e + l sin(theta) and at h = l cos(theta) below
the point of suspension; the sleeve at 2 h below it.  The coordinate z is the sleeve's
lift over its travel, so cos(theta) is linear in z.

Equilibrium (Lagrange, or moments about the suspension)::

    omega_g^2 = g (N m + 2 W) tan(theta) / (N m r)

which for e = 0 and N = 2 is Porter's h = (g/omega_g^2)(m + W)/m, and for W = 0 is
Watt's h = g/omega_g^2, Marks eq. (254): h = 2936.3/N^2 ft with N the governor's rev/min
and g = 32.2 ft/s2.  (Marks writes Porter's as h = (2936.3/N^2)(W + W1)/W1 as far as the
print can be read, with W1 "the two balls and that part of the connecting links acting
with them"; the force balance agrees with that form when W1 is the weight of one ball,
or with (2W + W1)/W1 when W1 is both balls.)

Spring-loaded (Marks Art. 97: Pickering, Waters; the Hartnell form)
-------------------------------------------------------------------
Each ball is on the vertical arm (length b) of a bell-crank pivoted on the spindle's
frame at radius a; the bell-crank's other arm (length s, horizontal when the ball arm is
vertical) lifts the sleeve against a spring of stiffness k and preload P (the spring's
force when the governor is at rest).  With phi the bell-crank's turn outward from the
position where the ball arm is parallel to the spindle, the ball is at r = a + b sin(phi),
b cos(phi) below the pivot, and the sleeve lifts by x = s (sin(phi) - sin(phi0)), linear
in z.  Moments about the pivot for one bell-crank::

    m omega_g^2 r b cos(phi) = (P + k x + m_s g)/N s cos(phi) + m g b sin(phi)

Friction and dash-pot are given as they act on the sleeve: a force F and a damping
coefficient c_s along the sleeve; generalised, F_f = F dx/dz and c = c_s (dx/dz)^2, exact
because the sleeve's lift is linear in z.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.governors.mechanism import (GEAR_SETTING_KEYS, GRAVITY_M_S2, RATIO_KEY,
                                         THROTTLE_KEYS, Actuator, Governor, GovernorType,
                                         PointMass, WEIGHT_MASS_KG, parse_actuator,
                                         parse_ratio, register)
from corliss.keys.declared import POSITIVE_LENGTH, REQUIRED, ZERO_OR_MORE, Key, KeyGroup, group
from corliss.keys.toml_table import Table


class SleeveLosses:
    """Friction and dash-pot given as they act on the sleeve, generalised to z.

    A mixin of the fly-ball specs, which carry ``sleeve_friction_N``,
    ``sleeve_damping_N_s_m`` and ``sleeve_travel_m``: the sleeve's lift is linear in z,
    so ``F_f = F x_travel`` and ``c = c_s x_travel^2`` exactly.  It takes no
    constructor parameters of its own.
    """

    if TYPE_CHECKING:
        # what the mixing dataclasses define (as fields or properties), for the type
        # checker only: at run time a property here would become their fields' default
        @property
        def sleeve_friction_N(self) -> float: ...

        @property
        def sleeve_damping_N_s_m(self) -> float: ...

        @property
        def sleeve_travel_m(self) -> float: ...

    @property
    def friction(self) -> float:
        """Generalised Coulomb friction F_f, the sleeve's times its travel [J per unit z]."""
        return self.sleeve_friction_N * self.sleeve_travel_m

    @property
    def damping(self) -> float:
        """Generalised dash-pot damping c, the sleeve's times its travel squared.

        In [J s per unit z squared].
        """
        return self.sleeve_damping_N_s_m * self.sleeve_travel_m ** 2


@dataclass(frozen=True)
class FlyBallSpec(SleeveLosses):
    """Watt or Porter governor (all SI), as read from a ``[governor]`` table.

    Parameters
    ----------
    arm_length_m : float
        Arm length l, suspension pin to ball centre; the links are as long [m].
    ball_mass_kg : float
        Mass of one ball (with the part of its arm and link that moves with it) [kg].
    balls : int
        Number of balls N (2 or more).
    load_mass_kg : float
        Central load W with the sleeve and what moves with it [kg] (0 for a bare Watt).
    arm_angle_at_rest_rad, arm_angle_at_top_rad : float
        Arm angle from the spindle at the two stops [rad].
    suspension_offset_m : float, optional
        Distance e of the arms' pins from the spindle axis [m].
    ratio : float, optional
        Spindle speed over engine speed [-].
    sleeve_friction_N : float, optional
        Coulomb friction force along the sleeve [N].
    sleeve_damping_N_s_m : float, optional
        Dash-pot coefficient along the sleeve [N s/m].
    actuator : Actuator, optional
        What the sleeve moves (default: a throttle wide open at rest, shut at the top).
    """

    arm_length_m: float
    ball_mass_kg: float
    balls: int
    load_mass_kg: float
    arm_angle_at_rest_rad: float
    arm_angle_at_top_rad: float
    suspension_offset_m: float = 0.0
    ratio: float = 1.0
    sleeve_friction_N: float = 0.0
    sleeve_damping_N_s_m: float = 0.0
    actuator: Actuator = Actuator("throttle", 1.0, 0.0)

    @property
    def sleeve_travel_m(self) -> float:
        """Sleeve lift between the stops, ``2 l (cos theta0 - cos theta1)`` [m]."""
        return 2.0 * self.arm_length_m * (math.cos(self.arm_angle_at_rest_rad)
                                          - math.cos(self.arm_angle_at_top_rad))


class FlyBallGovernor(Governor):
    """Watt's conical pendulum or Porter's loaded governor (Marks Ch. XVIII Art. 97).

    Parameters
    ----------
    spec : FlyBallSpec
        Its geometry, masses, losses and actuator.
    """

    name = "flyball"
    spec: FlyBallSpec

    def __init__(self, spec: FlyBallSpec):
        self.spec = spec

    def _cos(self, z):
        c0 = math.cos(self.spec.arm_angle_at_rest_rad)
        dc = math.cos(self.spec.arm_angle_at_top_rad) - c0
        c = c0 + dc * np.asarray(z, dtype=float)
        return c, dc, np.sqrt(1.0 - c * c)

    def height_m(self, z) -> np.ndarray:
        """The suspension point's height above the balls' plane, ``h = l cos(theta)``.

        Watt's "height" of the conical pendulum (Marks Ch. XVIII Art. 97, eq. 254).

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        ndarray
            h [m], shaped as ``z``.
        """
        return self.spec.arm_length_m * self._cos(z)[0]

    def bodies(self, z):
        sp = self.spec
        l, e = sp.arm_length_m, sp.suspension_offset_m
        c, dc, s = self._cos(z)
        zero = np.zeros_like(c)
        ball = PointMass(sp.ball_mass_kg, x=e + l * s, y=zero, h=-l * c,
                         x_z=-l * c * dc / s, y_z=zero, h_z=-l * dc + zero,
                         x_zz=-l * dc * dc / s ** 3, y_zz=zero, h_zz=zero, count=sp.balls)
        load = PointMass(sp.load_mass_kg, x=zero, y=zero, h=-2.0 * l * c, x_z=zero, y_z=zero,
                         h_z=-2.0 * l * dc + zero, x_zz=zero, y_zz=zero, h_zz=zero)
        return [ball, load]

    def _weight(self) -> float:
        sp = self.spec
        return GRAVITY_M_S2 * sp.arm_length_m * (sp.balls * sp.ball_mass_kg
                                                 + 2.0 * sp.load_mass_kg)

    def potential(self, z):
        c, dc, _ = self._cos(z)
        return -self._weight() * (c - math.cos(self.spec.arm_angle_at_rest_rad))

    def restoring(self, z):
        c, dc, _ = self._cos(z)
        return -self._weight() * dc + np.zeros_like(c)


#: The angle of a fly-ball governor's arms from its spindle [rad]: out from the spindle
#: (at under a degree the arms stand all but upright, the balls have no radius to fly
#: out from and the geometry divides by it) and short of the horizontal.
ARM_ANGLE_RAD = (math.radians(1.0), math.radians(89.0))


#: Keys every fly-ball governor shares: its balls, arms, stops and losses.
_BALLS = group(
    "balls", "The balls and their arms.",
    Key("ball_mass", "mass", "Mass of each ball.", within=WEIGHT_MASS_KG, unit="lb"),
    Key("balls", "integer", "Number of balls, 2 or more.", default=2),
)
_TOP_STOP = group(
    "top_stop", "The top stop: an arm angle or a sleeve lift (one of them).",
    Key("arm_angle_at_top", "angle", "Arm angle at the top stop, above the rest angle and "
        "below 90 deg; or give sleeve_lift.", default=None,
        within=(-0.5 * math.pi, 0.5 * math.pi), unit="deg"),
    Key("sleeve_lift", "length", "The sleeve's lift from rest to the top stop; or give "
        "arm_angle_at_top.", default=None, within=POSITIVE_LENGTH, unit="in"),
)
_LOSSES = group(
    "losses", "Friction and dashpot at the sleeve.",
    Key("friction", "force", "Coulomb friction at the sleeve (zero or more).", default="0 N",
        unit="lbf", within=ZERO_OR_MORE),
    Key("dashpot", "damping", "Dashpot at the sleeve (zero or more).", default="0 N s/m",
        within=ZERO_OR_MORE),
)


def _flyball_keys(name: str, loaded: str, acts_on: str, corliss: bool = False) -> KeyGroup:
    """The keys of a fly-ball governor read by ``_flyball_parse(loaded, acts_on, corliss)``."""
    if loaded == "none":
        load = Key("sleeve_mass", "mass", "Mass of the sleeve (zero or more).", default="0 kg",
                   unit="lb", within=ZERO_OR_MORE)
    else:
        req = loaded == "required"
        load = Key("load_mass", "mass", "The central load on the sleeve (Porter's), "
                   + ("above zero." if req else "zero or more (none: Watt's)."),
                   default=REQUIRED if req else "0 kg", unit="lb", within=ZERO_OR_MORE)
    safety = () if not corliss else (
        Key("safety_lift", "length", "How far above rest the sleeve must be before the trip "
            "cams work; below it the safety cam holds the hooks off (Spangler Art. 155). Zero: "
            "no safety range.", within=ZERO_OR_MORE, unit="in"),
        Key("safety_setting", "number", "The gear's setting of no admission, held in the "
            "safety range.", when="with safety_lift above zero (required there)"))
    return group(
        name, "A fly-ball governor.",
        Key("arm_length", "length", "Length of each arm, suspension to ball centre.",
            within=POSITIVE_LENGTH, unit="in"),
        _BALLS, load,
        Key("arm_angle_at_rest", "angle", "Arm angle from the spindle at rest, between 0 and "
            "90 deg.", within=ARM_ANGLE_RAD, unit="deg"),
        _TOP_STOP,
        Key("suspension_offset", "length", "Offset of the arms' suspension from the spindle "
            "(zero or more).", default="0 in", unit="in", within=ZERO_OR_MORE),
        _LOSSES, THROTTLE_KEYS if acts_on == "throttle" else GEAR_SETTING_KEYS, *safety,
        RATIO_KEY)


def _flyball_parse(loaded: str, acts_on: str, corliss: bool = False):
    """A parser for a fly-ball governor table.

    loaded : "none" (Watt, optional sleeve mass), "required" (Porter), "optional".
    """
    keys = _flyball_keys("flyball", loaded, acts_on, corliss)

    def parse(t: Table):
        t = t.bound(keys)
        l = t.get("arm_length")
        m = t.get("ball_mass")
        if not m > 0.0:
            raise InputError(t.key("ball_mass"), t.raw("ball_mass"), "a mass above zero")
        balls = t.get("balls")
        if balls < 2:
            raise InputError(t.key("balls"), balls, "2 or more balls")
        key = "sleeve_mass" if loaded == "none" else "load_mass"
        W = t.get(key)
        if W < 0.0 or (loaded == "required" and not W > 0.0):
            raise InputError(t.key(key), t.raw(key), "a mass above zero" if loaded == "required"
                             else "a mass of zero or more")
        th0 = t.get("arm_angle_at_rest")
        if not 0.0 < th0 < 0.5 * math.pi:
            raise InputError(t.key("arm_angle_at_rest"), t.raw("arm_angle_at_rest"),
                             "an arm angle from the spindle between 0 and 90 deg (the balls "
                             "must hang out from the spindle at rest)")
        if t.has("arm_angle_at_top") == t.has("sleeve_lift"):
            raise InputError(t.key("arm_angle_at_top"), t.raw("arm_angle_at_top", None),
                             "either arm_angle_at_top or sleeve_lift (one of them) for the top "
                             "stop")
        if t.has("arm_angle_at_top"):
            th1 = t.get("arm_angle_at_top", within=ARM_ANGLE_RAD)
            if not th0 < th1 < 0.5 * math.pi:
                raise InputError(t.key("arm_angle_at_top"), t.raw("arm_angle_at_top"),
                                 f"an arm angle above the rest angle "
                                 f"({math.degrees(th0):.4g} deg) and below 90 deg")
        else:
            lift = t.get("sleeve_lift")
            c1 = math.cos(th0) - lift / (2.0 * l)
            if not c1 > 0.0:
                raise InputError(t.key("sleeve_lift"), t.raw("sleeve_lift"),
                                 f"a sleeve lift below 2 l cos(theta0) = "
                                 f"{2 * l * math.cos(th0) / units.INCH_m:.4g} in (beyond it the "
                                 "arms would pass the horizontal)")
            th1 = math.acos(c1)
        e = t.get("suspension_offset")
        if e < 0.0:
            raise InputError(t.key("suspension_offset"), t.raw("suspension_offset"),
                             "an offset of zero or more")
        friction = t.get("friction")
        damping = t.get("dashpot")
        if friction < 0.0 or damping < 0.0:
            raise InputError(t.key("friction" if friction < 0 else "dashpot"),
                             t.raw("friction" if friction < 0 else "dashpot"), "zero or more")
        actuator = _corliss_actuator(t) if corliss else parse_actuator(t, acts_on)
        spec = FlyBallSpec(l, m, balls, W, th0, th1, e, parse_ratio(t), friction, damping,
                           actuator)
        if corliss and actuator.safety_z > 0.0:
            # the safety range was given as a sleeve distance: turn it into z
            frac = actuator.safety_z / spec.sleeve_travel_m
            if not frac < 1.0:
                raise InputError(t.key("safety_lift"), t.raw("safety_lift"),
                                 f"a lift below the sleeve's travel "
                                 f"({spec.sleeve_travel_m / units.INCH_m:.4g} in)")
            spec = _with_safety(spec, frac, t)
        top = "arm_angle_at_top" if t.has("arm_angle_at_top") else "sleeve_lift"
        FlyBallGovernor(spec).check(t.key(top), t.raw(top))
        return spec

    return parse


def _corliss_actuator(t: Table) -> Actuator:
    """The Corliss governor's cam setting, with the safety range at the bottom.

    ``setting_at_rest`` and ``setting_at_top``: the trip cams' setting, linear in z,
    at z = 0 and z = 1.  ``safety_lift`` [length]: how far above its rest the sleeve
    must be before the trip cams work; below it the safety cam holds the hooks off
    (Spangler Art. 155, cam G, disengagement "if the arm v travels too far downwards"),
    so the steam valves are not opened and the gear sits at ``safety_setting`` (the
    gear's setting of no admission).  Returned with ``safety_z`` still as a lift [m].
    """
    a = parse_actuator(t, "gear")
    lift = t.get("safety_lift")
    if lift < 0.0:
        raise InputError(t.key("safety_lift"), t.raw("safety_lift"), "a lift of zero or more")
    safety = t.get("safety_setting") if lift > 0.0 else float("nan")
    return Actuator("gear", a.at_rest, a.at_top, lift, safety)


def _with_safety(spec: FlyBallSpec, frac: float, t: Table) -> FlyBallSpec:
    """The safety range as a fraction of the travel in z."""
    a = spec.actuator
    return dataclasses.replace(spec, actuator=Actuator("gear", a.at_rest, a.at_top, frac,
                                                       a.safety_value))


# --- spring-loaded ----------------------------------------------------------------------
@dataclass(frozen=True)
class SpringSpec(SleeveLosses):
    """Spring-loaded fly-ball governor of the Hartnell form (all SI).

    Parameters
    ----------
    ball_mass_kg : float
        Mass of one ball [kg].
    balls : int
        Number of balls (2 or more).
    pivot_radius_m : float
        Radius a of the bell-cranks' pivots from the spindle axis [m].
    ball_arm_m, sleeve_arm_m : float
        Bell-crank arms: pivot to ball centre b, pivot to sleeve pin s [m].
    arm_angle_at_rest_rad, arm_angle_at_top_rad : float
        Bell-crank turn phi from the position with the ball arm parallel to the spindle,
        outward positive, at the stops [rad].
    spring_stiffness_N_m : float
        Stiffness of the spring on the sleeve [N/m].
    spring_preload_N : float
        The spring's force on the sleeve at rest [N].
    sleeve_mass_kg : float, optional
        The sleeve and what it carries [kg].
    ratio : float, optional
        Spindle speed over engine speed [-].
    sleeve_friction_N : float, optional
        Coulomb friction force along the sleeve [N].
    sleeve_damping_N_s_m : float, optional
        Dash-pot coefficient along the sleeve [N s/m].
    actuator : Actuator, optional
        What the sleeve moves (default: a throttle wide open at rest, shut at the top).
    """

    ball_mass_kg: float
    balls: int
    pivot_radius_m: float
    ball_arm_m: float
    sleeve_arm_m: float
    arm_angle_at_rest_rad: float
    arm_angle_at_top_rad: float
    spring_stiffness_N_m: float
    spring_preload_N: float
    sleeve_mass_kg: float = 0.0
    ratio: float = 1.0
    sleeve_friction_N: float = 0.0
    sleeve_damping_N_s_m: float = 0.0
    actuator: Actuator = Actuator("throttle", 1.0, 0.0)

    @property
    def sleeve_travel_m(self) -> float:
        """Sleeve lift between the stops, ``s (sin phi1 - sin phi0)`` [m]."""
        return self.sleeve_arm_m * (math.sin(self.arm_angle_at_top_rad)
                                    - math.sin(self.arm_angle_at_rest_rad))


class SpringGovernor(Governor):
    """Balls on bell-cranks against a spring on the sleeve (Hartnell form, Marks Art. 97).

    Parameters
    ----------
    spec : SpringSpec
        Its geometry, spring, masses, losses and actuator.
    """

    name = "spring"
    summary = ("spring-loaded fly-balls on bell-cranks (Hartnell, Pickering, Waters; Marks "
               "Art. 97) moving the throttle")

    spec: SpringSpec

    def __init__(self, spec: SpringSpec):
        self.spec = spec

    def _sin(self, z):
        s0 = math.sin(self.spec.arm_angle_at_rest_rad)
        ds = math.sin(self.spec.arm_angle_at_top_rad) - s0
        s = s0 + ds * np.asarray(z, dtype=float)
        return s, ds, np.sqrt(1.0 - s * s)

    def sleeve_lift_m(self, z) -> np.ndarray:
        """Sleeve lift above its rest, linear in z.

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        ndarray
            The lift [m], shaped as ``z``.
        """
        return self.spec.sleeve_travel_m * np.asarray(z, dtype=float)

    def bodies(self, z):
        sp = self.spec
        a, b, arm = sp.pivot_radius_m, sp.ball_arm_m, sp.sleeve_arm_m
        s, ds, c = self._sin(z)
        zero = np.zeros_like(s)
        ball = PointMass(sp.ball_mass_kg, x=a + b * s, y=zero, h=-b * c, x_z=b * ds + zero,
                         y_z=zero, h_z=b * s * ds / c, x_zz=zero, y_zz=zero,
                         h_zz=b * ds * ds / c ** 3, count=sp.balls)
        lift = arm * (s - math.sin(sp.arm_angle_at_rest_rad))
        sleeve = PointMass(sp.sleeve_mass_kg, x=zero, y=zero, h=lift,
                           x_z=zero, y_z=zero, h_z=arm * ds + zero, x_zz=zero, y_zz=zero,
                           h_zz=zero)
        return [ball, sleeve]

    def potential(self, z):
        sp = self.spec
        s, ds, c = self._sin(z)
        c0 = math.cos(sp.arm_angle_at_rest_rad)
        x = self.sleeve_lift_m(z)
        gravity = GRAVITY_M_S2 * (sp.balls * sp.ball_mass_kg * (-sp.ball_arm_m) * (c - c0)
                                  + sp.sleeve_mass_kg * x)
        return gravity + sp.spring_preload_N * x + 0.5 * sp.spring_stiffness_N_m * x * x

    def restoring(self, z):
        sp = self.spec
        s, ds, c = self._sin(z)
        x = self.sleeve_lift_m(z)
        spring = (sp.spring_preload_N + sp.spring_stiffness_N_m * x
                  + sp.sleeve_mass_kg * GRAVITY_M_S2) * sp.sleeve_arm_m * ds
        return GRAVITY_M_S2 * sp.balls * sp.ball_mass_kg * sp.ball_arm_m * s * ds / c + spring


SPRING_KEYS = group(
    "spring", "A spring-loaded fly-ball governor of the Hartnell form.",
    _BALLS,
    Key("pivot_radius", "length", "Radius of the bell-crank pivots from the spindle.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("ball_arm", "length", "The bell-crank's ball arm.", within=POSITIVE_LENGTH, unit="in"),
    Key("sleeve_arm", "length", "The bell-crank's sleeve arm.", within=POSITIVE_LENGTH,
        unit="in"),
    Key("arm_angle_at_rest", "angle", "Bell-crank angle at rest, between -90 and 90 deg, the "
        "ball outside the spindle axis.", within=(-0.5 * math.pi, 0.5 * math.pi), unit="deg"),
    _TOP_STOP,
    Key("spring_stiffness", "stiffness", "Stiffness of the spring on the sleeve (zero or "
        "more).", unit="lbf/in", within=ZERO_OR_MORE),
    Key("spring_preload", "force", "The spring's load on the sleeve at rest (zero or more).",
        unit="lbf", within=ZERO_OR_MORE),
    Key("sleeve_mass", "mass", "Mass of the sleeve (zero or more).", default="0 kg", unit="lb",
        within=ZERO_OR_MORE),
    _LOSSES, THROTTLE_KEYS, RATIO_KEY,
)


def parse_spring(t: Table) -> SpringSpec:
    """Read a ``[governor] type = "spring"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`SPRING_KEYS`.

    Returns
    -------
    SpringSpec
        The governor's spec.
    """
    t = t.bound(SPRING_KEYS)
    m = t.get("ball_mass")
    if not m > 0.0:
        raise InputError(t.key("ball_mass"), t.raw("ball_mass"), "a mass above zero")
    balls = t.get("balls")
    if balls < 2:
        raise InputError(t.key("balls"), balls, "2 or more balls")
    a = t.get("pivot_radius")
    b = t.get("ball_arm")
    arm = t.get("sleeve_arm")
    ph0 = t.get("arm_angle_at_rest")
    if not -0.5 * math.pi < ph0 < 0.5 * math.pi or a + b * math.sin(ph0) <= 0.0:
        raise InputError(t.key("arm_angle_at_rest"), t.raw("arm_angle_at_rest"),
                         "a bell-crank angle between -90 and 90 deg that keeps the ball "
                         "outside the spindle axis")
    if t.has("arm_angle_at_top") == t.has("sleeve_lift"):
        raise InputError(t.key("arm_angle_at_top"), t.raw("arm_angle_at_top", None),
                         "either arm_angle_at_top or sleeve_lift (one of them) for the top stop")
    if t.has("arm_angle_at_top"):
        ph1 = t.get("arm_angle_at_top")
        if not ph0 < ph1 < 0.5 * math.pi:
            raise InputError(t.key("arm_angle_at_top"), t.raw("arm_angle_at_top"),
                             f"a bell-crank angle above the rest angle "
                             f"({math.degrees(ph0):.4g} deg) and below 90 deg")
    else:
        lift = t.get("sleeve_lift")
        s1 = math.sin(ph0) + lift / arm
        if not s1 < 1.0:
            raise InputError(t.key("sleeve_lift"), t.raw("sleeve_lift"),
                             f"a lift below s (1 - sin(phi0)) = "
                             f"{arm * (1 - math.sin(ph0)) / units.INCH_m:.4g} in, what the "
                             "bell-crank can give")
        ph1 = math.asin(s1)
    k = t.get("spring_stiffness")
    p = t.get("spring_preload")
    if k < 0.0:
        raise InputError(t.key("spring_stiffness"), t.raw("spring_stiffness"),
                         "a stiffness of zero or more")
    if p < 0.0:
        raise InputError(t.key("spring_preload"), t.raw("spring_preload"),
                         "a preload of zero or more (the spring pushes the sleeve down)")
    ms = t.get("sleeve_mass")
    if ms < 0.0:
        raise InputError(t.key("sleeve_mass"), t.raw("sleeve_mass"), "a mass of zero or more")
    friction = t.get("friction")
    damping = t.get("dashpot")
    if friction < 0.0 or damping < 0.0:
        raise InputError(t.key("friction" if friction < 0 else "dashpot"),
                         t.raw("friction" if friction < 0 else "dashpot"), "zero or more")
    spec = SpringSpec(m, balls, a, b, arm, ph0, ph1, k, p, ms, parse_ratio(t), friction,
                      damping, parse_actuator(t, "throttle"))
    SpringGovernor(spec).check(t.key("spring_preload"), t.raw("spring_preload"))
    return spec


# --- registry ---------------------------------------------------------------------------
def _flyball_type(name: str, summary: str, *how) -> GovernorType:
    cls = type(f"{name.title().replace('_', '')}Governor", (FlyBallGovernor,),
               {"name": name, "summary": summary})
    return register(GovernorType(name, summary, _flyball_parse(*how), cls,
                                 _flyball_keys(name, *how)))


WATT = _flyball_type("watt", "Watt's conical pendulum: h = g/omega^2, Marks eq. (254); moves "
                     "the throttle", "none", "throttle")
PORTER = _flyball_type("porter", "Porter's loaded governor: small fast balls under a heavy "
                       "central load (Marks Art. 97); moves the throttle",
                       "required", "throttle")
PORTER_ALLEN = _flyball_type("porter_allen", "Porter governor moving the radius rod in the "
                             "Fink link of the Porter-Allen gear (Spangler Art. 83)",
                             "required", "gear")
CORLISS = _flyball_type("corliss", "fly-ball (Porter, or Watt with no load) placing the "
                        "Corliss trip cams, safety cams at its lowest (Spangler Art. 155)",
                        "optional", "gear", True)
SPRING = register(GovernorType("spring", SpringGovernor.summary, parse_spring, SpringGovernor,
                               SPRING_KEYS))
