"""Shaft governors: weights on arms pivoted on the flywheel, against springs, moving the
eccentric (Spangler Ch. XII Arts. 84-91: Erie, Armington & Sims, Ball; Ch. XVII Art. 140:
Buckeye; Marks Art. 97: Thompson's shaft governor, the inertia governors).

Geometry (in the plane of the wheel, turning with it)
-----------------------------------------------------
Each of N weights (the book's a, a of the Erie, j, j of the Ball, d, d of the Buckeye)
is on an arm pivoted at radius a from the shaft's centre; its centre of mass is at
distance b from the pivot.  With beta the angle at the pivot between the arm and the
line from the pivot outward along the radius, the weight's centre is at::

    x = a + b cos(beta),   y = +-b sin(beta)        r^2 = a^2 + b^2 + 2 a b cos(beta)

with y > 0 when the weight leads its pivot in the direction of rotation
(``weight_position = "leading"``) and y < 0 when it trails.  The scene gives the
weight's radius at the two stops; beta is linear in z between them (beta falls as the
weight flies out).  Gravity turns with the wheel and averages out over a revolution;
it is left out.

The spring acts on each arm at lever d about the pivot, along the arc the arm's spring
point describes (as through a chain on a quadrant, or a spring whose line of action
stays square to the arm); its deflection is d (beta0 - beta) and its force
P + k d (beta0 - beta), P the preload at rest.  Moments about the pivot::

    m omega^2 a b sin(beta) = d (P + k d (beta0 - beta))

the centrifugal force m omega^2 r acting along the radius, whose moment arm about the
pivot is a b sin(beta)/r.

Inertia action
--------------
When the wheel speeds up, the weight and any heavy bar keep their absolute motion for a
moment and so turn relative to the wheel: the term -J d(omega)/dt with
J = m (x y' - y x') + I psi', psi the arm's angle, I the moment of inertia of the weight
and arm about their own centre of mass (``weight_inertia``).  A leading weight is thrown
outward (toward early cut-off) as the wheel accelerates: the inertia action anticipates
the speed change.  An inertia governor (Rites's heavy bar, used on high-speed engines
such as the Armington & Sims) makes I large for that purpose; a plain centrifugal
design has a small I.  Neither Spangler (Art. 89 describes the Armington & Sims weights
only as centrifugal) nor Marks gives an inertia bar's dimensions: the scene supplies them.

Friction and dash-pot are given as a torque about each arm's pivot and a damping torque
per unit angular speed of the arm (the Ball governor's dash-pot, Art. 90);
generalised, ``F_f = N T_f |dbeta/dz|`` and ``c = N c_t (dbeta/dz)^2``, exact because
beta is linear in z.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.governors.mechanism import (GEAR_SETTING_KEYS, Actuator, Governor, GovernorType,
                                         PointMass, WEIGHT_MASS_KG, parse_actuator, register)
from corliss.keys.declared import POSITIVE_LENGTH, ZERO_OR_MORE, Key, group
from corliss.keys.toml_table import Table


@dataclass(frozen=True)
class ShaftSpec:
    """A shaft governor (all SI), as read from a ``[governor]`` table.

    Parameters
    ----------
    weight_mass_kg : float
        Mass of one weight with its arm [kg].
    weights : int
        Number of weights N.
    pivot_radius_m : float
        Radius a of the arm's pivot from the shaft's centre [m].
    arm_length_m : float
        Distance b from the pivot to the weight's centre of mass [m].
    weight_radius_at_rest_m, weight_radius_at_top_m : float
        Radius of the weight's centre of mass at the two stops [m], strictly between
        ``|a - b|`` and ``a + b``.
    spring_arm_m : float
        Lever d of each arm's spring about the pivot [m].
    spring_stiffness_N_m : float
        Stiffness of each arm's spring [N/m].
    spring_preload_N : float
        Each spring's force at rest [N].
    weight_inertia_kg_m2 : float, optional
        Moment of inertia of weight and arm about their own centre of mass [kg m2]
        (the inertia bar; 0 for a plain centrifugal governor).
    leading : bool, optional
        True when the weight leads its pivot in the direction of rotation.
    friction_torque_N_m : float, optional
        Coulomb friction torque per arm about its pivot [N m].
    dashpot_N_m_s : float, optional
        Dash-pot torque per arm per unit angular speed of the arm [N m s].
    actuator : Actuator, optional
        The valve gear's setting at the two stops (default 0 at rest, 1 at the top).
    ratio : float, optional
        Governor speed over shaft speed [-] (1: the governor turns with the wheel).
    """

    weight_mass_kg: float
    weights: int
    pivot_radius_m: float
    arm_length_m: float
    weight_radius_at_rest_m: float
    weight_radius_at_top_m: float
    spring_arm_m: float
    spring_stiffness_N_m: float
    spring_preload_N: float
    weight_inertia_kg_m2: float = 0.0
    leading: bool = True
    friction_torque_N_m: float = 0.0
    dashpot_N_m_s: float = 0.0
    actuator: Actuator = Actuator("gear", 0.0, 1.0)
    ratio: float = 1.0

    def beta(self, r: float) -> float:
        """Arm angle at which the weight's centre is at a given radius.

        From ``r^2 = a^2 + b^2 + 2 a b cos(beta)`` (the module docstring).

        Parameters
        ----------
        r : float
            Radius of the weight's centre of mass from the shaft's centre [m].

        Returns
        -------
        float
            beta [rad], from 0 (arm along the radius, outward) to pi.
        """
        a, b = self.pivot_radius_m, self.arm_length_m
        return math.acos((r * r - a * a - b * b) / (2.0 * a * b))

    @property
    def beta_rest(self) -> float:
        """Arm angle beta0 at the rest stop [rad]."""
        return self.beta(self.weight_radius_at_rest_m)

    @property
    def beta_swing(self) -> float:
        """The arm's turn from rest to the top stop, ``beta0 - beta1 > 0`` [rad]."""
        return self.beta_rest - self.beta(self.weight_radius_at_top_m)

    @property
    def friction(self) -> float:
        """Generalised Coulomb friction F_f, ``N T_f (beta0 - beta1)`` [J per unit z]."""
        return self.weights * self.friction_torque_N_m * self.beta_swing

    @property
    def damping(self) -> float:
        """Generalised dash-pot damping c, ``N c_t (beta0 - beta1)^2``.

        In [J s per unit z squared].
        """
        return self.weights * self.dashpot_N_m_s * self.beta_swing ** 2


class ShaftGovernor(Governor):
    """Weights on pivoted arms in the flywheel against springs (Spangler Ch. XII).

    Parameters
    ----------
    spec : ShaftSpec
        Its geometry, springs, losses and actuator.
    """

    name = "shaft"
    vertical_spindle = False
    spec: ShaftSpec

    def __init__(self, spec: ShaftSpec):
        self.spec = spec

    def beta(self, z) -> np.ndarray:
        """The arm angle, linear in z from beta0 at rest to beta1 at the top stop.

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        ndarray
            beta [rad], shaped as ``z``.
        """
        return self.spec.beta_rest - self.spec.beta_swing * np.asarray(z, dtype=float)

    def bodies(self, z):
        sp = self.spec
        a, b = sp.pivot_radius_m, sp.arm_length_m
        beta = self.beta(z)
        db = -sp.beta_swing
        sg = 1.0 if sp.leading else -1.0
        zero = np.zeros_like(beta)
        cb, sb = np.cos(beta), np.sin(beta)
        w = PointMass(sp.weight_mass_kg, x=a + b * cb, y=sg * b * sb, h=zero,
                      x_z=-b * sb * db, y_z=sg * b * cb * db, h_z=zero,
                      x_zz=-b * cb * db * db, y_zz=-sg * b * sb * db * db, h_zz=zero,
                      inertia_kg_m2=sp.weight_inertia_kg_m2, psi_z=sg * db + zero,
                      psi_zz=zero, count=sp.weights)
        return [w]

    def spring_deflection_m(self, z) -> np.ndarray:
        """Deflection of each arm's spring from its rest, ``d (beta0 - beta)``.

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        ndarray
            The deflection [m], shaped as ``z``.
        """
        return self.spec.spring_arm_m * self.spec.beta_swing * np.asarray(z, dtype=float)

    def potential(self, z):
        sp = self.spec
        x = self.spring_deflection_m(z)
        return sp.weights * (sp.spring_preload_N * x + 0.5 * sp.spring_stiffness_N_m * x * x)

    def restoring(self, z):
        sp = self.spec
        x = self.spring_deflection_m(z)
        return sp.weights * (sp.spring_preload_N + sp.spring_stiffness_N_m * x) \
            * sp.spring_arm_m * sp.beta_swing


SHAFT_KEYS = group(
    "shaft", "A shaft governor: weights on arms in the flywheel or a disc, held in by "
    "springs, set the gear.",
    Key("weight_mass", "mass", "Mass of each weight.", within=WEIGHT_MASS_KG, unit="lb"),
    Key("weights", "integer", "Number of weights, 1 or more.", default=2),
    Key("pivot_radius", "length", "a: radius of the arms' pivots from the shaft.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("arm_length", "length", "b: from the pivot to the weight's centre.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("weight_radius_at_rest", "length", "The weight's radius from the shaft at rest, "
        "between |a - b| and a + b.", within=POSITIVE_LENGTH, unit="in"),
    Key("weight_radius_at_top", "length", "The weight's radius at the top stop, above the "
        "radius at rest and below a + b.", within=POSITIVE_LENGTH, unit="in"),
    Key("weight_inertia", "inertia", "Each weight's moment of inertia about its pivot (inertia "
        "action; zero or more).", default="0 kg m2", within=ZERO_OR_MORE),
    Key("weight_position", "choice", "The weights lead or trail their pivots in the sense of "
        "rotation.", default="leading", choices=("leading", "trailing")),
    Key("spring_arm", "length", "The spring's arm about the pivot.", within=POSITIVE_LENGTH,
        unit="in"),
    Key("spring_stiffness", "stiffness", "Stiffness of each spring (zero or more).",
        unit="lbf/in", within=ZERO_OR_MORE),
    Key("spring_preload", "force", "Each spring's load with the weights at rest (zero or "
        "more).", unit="lbf", within=ZERO_OR_MORE),
    Key("friction_torque", "torque", "Coulomb friction torque at the pivots (zero or more).",
        default="0 N m", within=ZERO_OR_MORE),
    Key("dashpot", "torque_per_speed", "Dashpot torque per speed of swing (zero or more).",
        default="0 N m s", within=ZERO_OR_MORE),
    GEAR_SETTING_KEYS,
)


def parse_shaft(t: Table) -> ShaftSpec:
    """Read a ``[governor]`` table of a shaft governor (erie, armington_sims, ball,
    buckeye, thompson).

    Parameters
    ----------
    t : Table
        The table, bound to :data:`SHAFT_KEYS`.

    Returns
    -------
    ShaftSpec
        The governor's spec.
    """
    t = t.bound(SHAFT_KEYS)
    m = t.get("weight_mass")
    if not m > 0.0:
        raise InputError(t.key("weight_mass"), t.raw("weight_mass"), "a mass above zero")
    n = t.get("weights")
    if n < 1:
        raise InputError(t.key("weights"), n, "1 or more weights")
    a = t.get("pivot_radius")
    b = t.get("arm_length")
    lo, hi = abs(a - b), a + b
    r0 = t.get("weight_radius_at_rest")
    r1 = t.get("weight_radius_at_top")
    for key, r in (("weight_radius_at_rest", r0), ("weight_radius_at_top", r1)):
        if not lo < r < hi:
            raise InputError(t.key(key), t.raw(key),
                             f"a radius strictly between |a - b| = {lo / units.INCH_m:.4g} in "
                             f"and a + b = {hi / units.INCH_m:.4g} in, what the arm can reach "
                             "(at either end the arm is in line with the radius and the "
                             "weights have no purchase)")
    if not r1 > r0:
        raise InputError(t.key("weight_radius_at_top"), t.raw("weight_radius_at_top"),
                         f"a radius above the radius at rest ({r0 / units.INCH_m:.4g} in): the "
                         "weights fly outward as the speed rises")
    inertia = t.get("weight_inertia")
    if inertia < 0.0:
        raise InputError(t.key("weight_inertia"), t.raw("weight_inertia"),
                         "a moment of inertia of zero or more")
    leading = t.get("weight_position") == "leading"
    d = t.get("spring_arm")
    k = t.get("spring_stiffness")
    p = t.get("spring_preload")
    if k < 0.0:
        raise InputError(t.key("spring_stiffness"), t.raw("spring_stiffness"),
                         "a stiffness of zero or more")
    if p < 0.0:
        raise InputError(t.key("spring_preload"), t.raw("spring_preload"),
                         "a preload of zero or more (the spring holds the weights in)")
    tf = t.get("friction_torque")
    ct = t.get("dashpot")
    if tf < 0.0 or ct < 0.0:
        raise InputError(t.key("friction_torque" if tf < 0 else "dashpot"),
                         t.raw("friction_torque" if tf < 0 else "dashpot"), "zero or more")
    spec = ShaftSpec(m, n, a, b, r0, r1, d, k, p, inertia, leading, tf, ct,
                     parse_actuator(t, "gear"))
    ShaftGovernor(spec).check(t.key("spring_preload"), t.raw("spring_preload"))
    return spec


def _shaft_type(name: str, summary: str) -> GovernorType:
    cls = type(f"{name.title().replace('_', '')}Governor", (ShaftGovernor,),
               {"name": name, "summary": summary})
    return register(GovernorType(name, summary, parse_shaft, cls, SHAFT_KEYS))


ERIE = _shaft_type("erie", "Erie shaft governor: weights on bell-cranks slide the eccentric "
                   "across the shaft (Spangler Art. 88); sets the gear")
ARMINGTON_SIMS = _shaft_type("armington_sims", "Armington & Sims shaft governor turning the "
                             "double eccentric (Spangler Art. 89), with inertia action when "
                             "weight_inertia is given; sets the gear")
BALL = _shaft_type("ball", "Ball shaft governor: weights swing the eccentric pin on an arc, "
                   "with dash-pot (Spangler Arts. 90-91); sets the gear")
BUCKEYE = _shaft_type("buckeye", "Buckeye shaft governor turning the loose cut-off eccentric "
                      "(Spangler Art. 140); sets the gear")
THOMPSON = _shaft_type("thompson", "Thompson's shaft governor changing the eccentric's "
                       "advance (Marks Art. 97); sets the gear")
