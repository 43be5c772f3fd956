"""The common form every governor is reduced to, and the registry of governors by name.

A governor is a mechanism of one degree of freedom, its coordinate z running from 0
(at rest, on the lowest-speed stop) to 1 (the highest-speed stop).  Its parts turn with
the spindle at omega_g = ratio x omega_shaft; in the frame turning with the spindle they
move with z only.  Writing the kinetic energy of the parts in that frame::

    T = 1/2 M(z) z'^2 + J(z) omega_g z' + 1/2 I_axis(z) omega_g^2,

with the potential V(z) of gravity and springs, Lagrange's equation for z is::

    M(z) z'' + 1/2 M'(z) z'^2 = G(z) omega_g^2 - R(z) - c z' - F_f sign(z') - J(z) d(omega_g)/dt

where G = 1/2 dI_axis/dz (the generalised centrifugal coefficient) and R = dV/dz (the
generalised restoring force).  For point masses m_i at (x_i, y_i, h_i) in the turning
frame (x, y across the spin axis, h along it, upward for a vertical spindle)::

    M = sum m_i |dp_i/dz|^2 + sum I_i (dpsi_i/dz)^2
    G = sum m_i (x_i x_i' + y_i y_i')
    J = sum m_i (x_i y_i' - y_i x_i') + sum I_i dpsi_i/dz

the last terms for a body of moment of inertia I_i about its own centre of mass turning
by psi_i(z) about an axis parallel to the spin axis (the inertia bar of a shaft
governor).  J is the inertia action (the Coriolis term of the moving weights): it is
zero for fly-balls, whose parts move in a plane through the spindle.

In equilibrium without friction omega_g^2 = R/G (Marks Ch. XVIII Art. 97 for the
conical pendulum, eq. 251); with Coulomb friction F_f the governor stays put for
omega_g^2 in [(R - F_f)/G, (R + F_f)/G].

Each governor here describes its geometry (:meth:`Governor.bodies`, analytic first and
second derivatives in z) and its potential (:meth:`Governor.potential` and its analytic
derivative :meth:`Governor.restoring`); the base class assembles the common form.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import ClassVar, Protocol

import numpy as np

from corliss.errors import InputError
from corliss.keys.declared import Key, group
from corliss.keys.registry import Registry, RegistryEntry

log = logging.getLogger(__name__)

#: standard gravity [m/s2]
GRAVITY_M_S2 = 9.80665

ACTS_ON = ("throttle", "gear")


#: Creep speed of the regularised governor friction, as a fraction of full travel per
#: second: a governor held by friction creeps by less than 0.2 % of its travel a second.
CREEP_PER_S = 2e-3

@dataclass(frozen=True)
class PointMass:
    """A part of the governor as a point mass, positions as functions of z.

    The arrays are all shaped as the grid of z the governor's
    :meth:`Governor.bodies` was called with (or are scalars where constant).

    Parameters
    ----------
    mass_kg : float
        Its mass [kg] (times the number of identical parts it stands for, ``count``).
    x, y, h : ndarray
        Position in the frame turning with the spindle [m]: x and y across the spin
        axis, h along it (upward when the spindle is vertical).
    x_z, y_z, h_z, x_zz, y_zz, h_zz : ndarray
        First and second derivatives of the position with respect to z [m].
    inertia_kg_m2 : float
        Moment of inertia of the part about its own centre of mass, about an axis
        parallel to the spin axis [kg m2] (0 for a ball).
    psi_z, psi_zz : ndarray or float
        Rate of turn of the part about that axis per unit z [rad], and its derivative
        in z [rad] (0 for a part that does not turn).
    count : int
        Number of identical parts, placed symmetrically about the spin axis.
    """

    mass_kg: float
    x: np.ndarray
    y: np.ndarray
    h: np.ndarray
    x_z: np.ndarray
    y_z: np.ndarray
    h_z: np.ndarray
    x_zz: np.ndarray
    y_zz: np.ndarray
    h_zz: np.ndarray
    inertia_kg_m2: float = 0.0
    psi_z: np.ndarray | float = 0.0
    psi_zz: np.ndarray | float = 0.0
    count: int = 1


@dataclass(frozen=True)
class GovernorMechanism:
    """A governor in the common form, tabulated on a uniform grid of z.

    Built by :meth:`Governor.mechanism`; the speed loop integrates Lagrange's equation
    of the module docstring with these tables.

    Parameters
    ----------
    z : ndarray, shape (n,)
        The grid, uniform from 0 to 1 [-]; every array below is shaped as it.
    M : ndarray
        Generalised mass [kg m2 per unit z squared].
    dM_dz : ndarray
        Its derivative in z [kg m2 per unit z cubed].
    G : ndarray
        Generalised centrifugal coefficient [kg m2 per unit z]; ``G omega_g^2`` is the
        generalised centrifugal force [J per unit z].
    R : ndarray
        Generalised restoring force (gravity and springs) [J per unit z].
    J : ndarray
        Inertia-action coefficient [kg m2 per unit z] (zero for fly-balls).
    I_axis : ndarray
        Moment of inertia of the governor's moving parts about the spin axis [kg m2]
        (``G = 1/2 dI_axis/dz``); what the governor adds to the spindle's inertia.
    c : float
        Dash-pot damping, generalised [J s per unit z squared].
    F_f : float
        Coulomb friction, generalised [J per unit z].
    ratio : float
        Spindle speed over shaft speed [-].
    acts_on : str
        ``"throttle"`` (opening of the throttle in the steam pipe, 0..1) or ``"gear"``
        (the valve gear's setting).
    actuator_at_rest, actuator_at_top : float
        The actuator's value at z = 0 and z = 1 [-] (throttle opening or gear
        setting); it is linear in z between them.
    safety_z : float, optional
        Below this z [-] the actuator is held at ``actuator_safety`` instead (the Corliss
        governor's safety cams, Spangler Art. 155); 0 when the governor has none.
    actuator_safety : float, optional
        The actuator's value in the safety range [-] (NaN when there is none).
    name : str, optional
        The governor type (its registry name).
    """

    z: np.ndarray
    M: np.ndarray
    dM_dz: np.ndarray
    G: np.ndarray
    R: np.ndarray
    J: np.ndarray
    I_axis: np.ndarray
    c: float
    F_f: float
    ratio: float
    acts_on: str
    actuator_at_rest: float
    actuator_at_top: float
    safety_z: float = 0.0
    actuator_safety: float = float("nan")
    name: str = ""

    def actuator(self, z):
        """The actuator's value at ``z``, linear between the stops.

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-], 0 at rest to 1 at the top stop.

        Returns
        -------
        ndarray
            Throttle opening or gear setting [-], shaped as ``z``; ``actuator_safety``
            where ``z`` is below ``safety_z``.
        """
        z = np.asarray(z, dtype=float)
        a = self.actuator_at_rest + (self.actuator_at_top - self.actuator_at_rest) * z
        if self.safety_z > 0.0:
            a = np.where(z < self.safety_z, self.actuator_safety, a)
        return a

    def actuator_range(self) -> tuple[float, float]:
        """The least and greatest actuator values the governor can set.

        Returns
        -------
        tuple of float
            ``(least, greatest)`` throttle opening or gear setting [-], the safety
            setting included when the governor has one.
        """
        vals = [self.actuator_at_rest, self.actuator_at_top]
        if self.safety_z > 0.0 and np.isfinite(self.actuator_safety):
            vals.append(self.actuator_safety)
        return min(vals), max(vals)

    def equilibrium_z(self, omega_shaft: float) -> float:
        """The coordinate at which the governor balances at a shaft speed, without friction.

        Solves ``G(z) (ratio omega)^2 = R(z)`` (Marks Ch. XVIII Art. 97, eq. 251, in the
        common form) by linear interpolation on the tabulated grid.

        Parameters
        ----------
        omega_shaft : float
            Shaft speed [rad/s].

        Returns
        -------
        float
            The balancing coordinate z [-]; 0 when the governor is held on its rest
            stop at this speed, 1 when it is driven to its top stop.
        """
        wg2 = (self.ratio * omega_shaft) ** 2
        f = self.G * wg2 - self.R
        if f[0] <= 0.0:
            return 0.0
        if f[-1] >= 0.0:
            return 1.0
        k = int(np.nonzero(f < 0.0)[0][0])
        z0, z1 = self.z[k - 1], self.z[k]
        return float(z0 + (z1 - z0) * f[k - 1] / (f[k - 1] - f[k]))


@dataclass(frozen=True)
class Actuator:
    """What a governor moves, linear in z (see :class:`GovernorMechanism`).

    Parameters
    ----------
    acts_on : str
        ``"throttle"`` or ``"gear"`` (one of :data:`ACTS_ON`).
    at_rest, at_top : float
        The throttle opening (0 shut to 1 open) or gear setting [-] at z = 0 and z = 1.
    safety_z : float, optional
        Below this z [-] the actuator is held at ``safety_value`` (0: no safety range).
    safety_value : float, optional
        The actuator's value in the safety range [-] (NaN when there is none).
    """

    acts_on: str
    at_rest: float
    at_top: float
    safety_z: float = 0.0
    safety_value: float = float("nan")


class _GovernorSpec(Protocol):
    """What :class:`Governor` reads from every spec (read-only; see its docstring)."""

    @property
    def ratio(self) -> float: ...

    @property
    def damping(self) -> float: ...

    @property
    def friction(self) -> float: ...

    @property
    def actuator(self) -> Actuator: ...


class Governor:
    """Base class of a governor: geometry and potential in, common form out.

    Subclasses set ``name``, ``summary`` and ``spec`` and implement :meth:`bodies`,
    :meth:`potential` and :meth:`restoring`; ``spec`` must carry ``ratio`` [-],
    ``damping`` (generalised c [J s per unit z squared]), ``friction`` (generalised
    F_f [J per unit z]) and ``actuator`` (an :class:`Actuator`).  The base class takes
    no constructor parameters; each subclass documents its own.
    """

    name: ClassVar[str] = "abstract"
    summary: ClassVar[str] = ""
    #: True when the spin axis is vertical and gravity acts along h.
    vertical_spindle: ClassVar[bool] = True

    spec: _GovernorSpec

    # --- what a governor describes --------------------------------------------------
    def bodies(self, z: np.ndarray) -> list[PointMass]:  # pragma: no cover
        """The moving parts at ``z``, with analytic derivatives.

        Parameters
        ----------
        z : ndarray, shape (n,)
            The governor's coordinate [-], 0 at rest to 1 at the top stop.

        Returns
        -------
        list of PointMass
            One entry per kind of part (balls, arms, links, sleeve load, weights),
            positions and derivatives shaped as ``z``.
        """
        raise NotImplementedError

    def potential(self, z: np.ndarray) -> np.ndarray:  # pragma: no cover
        """Potential energy of gravity and springs, zero at z = 0.

        Parameters
        ----------
        z : ndarray, shape (n,)
            The governor's coordinate [-].

        Returns
        -------
        ndarray, shape (n,)
            V(z) [J].
        """
        raise NotImplementedError

    def restoring(self, z: np.ndarray) -> np.ndarray:  # pragma: no cover
        """The generalised restoring force ``R = dV/dz``, analytic.

        Parameters
        ----------
        z : ndarray, shape (n,)
            The governor's coordinate [-].

        Returns
        -------
        ndarray, shape (n,)
            R(z) [J per unit z].
        """
        raise NotImplementedError

    # --- scalars ----------------------------------------------------------------------
    @property
    def ratio(self) -> float:
        """Spindle speed over shaft speed [-]."""
        return self.spec.ratio

    @property
    def damping(self) -> float:
        """Generalised dash-pot damping c [J s per unit z squared]."""
        return self.spec.damping

    @property
    def friction(self) -> float:
        """Generalised Coulomb friction F_f [J per unit z]."""
        return self.spec.friction

    @property
    def actuator(self) -> Actuator:
        """What the governor moves, and its values at the stops."""
        return self.spec.actuator

    # --- the common form --------------------------------------------------------------
    def centrifugal_energy_coefficient(self, z) -> np.ndarray:
        """Half the moment of inertia of the moving parts about the spin axis.

        ``1/2 sum m r^2``, the centrifugal potential per ``omega_g^2``, computed from the
        positions alone; its derivative in z is G (the tests check :meth:`terms` by it).

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        ndarray, shape (n,)
            The coefficient [kg m2] at each z (``z`` taken as at least 1-d).
        """
        z = np.atleast_1d(np.asarray(z, dtype=float))
        return sum(0.5 * b.count * b.mass_kg * (b.x ** 2 + b.y ** 2) for b in self.bodies(z))

    def terms(self, z) -> dict[str, np.ndarray]:
        """The common form's coefficients at ``z`` (see the module docstring).

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        dict of str to ndarray
            ``"M"`` [kg m2 per unit z squared], ``"dM_dz"``, ``"G"`` [kg m2 per unit z],
            ``"R"`` [J per unit z], ``"J"`` [kg m2 per unit z] and ``"I_axis"`` [kg m2],
            each shaped as ``z`` taken as at least 1-d.
        """
        z = np.atleast_1d(np.asarray(z, dtype=float))
        zero = np.zeros_like(z)
        M, dM, G, J, I = zero.copy(), zero.copy(), zero.copy(), zero.copy(), zero.copy()
        for b in self.bodies(z):
            m = b.count * b.mass_kg
            inertia = b.count * b.inertia_kg_m2
            M = M + m * (b.x_z ** 2 + b.y_z ** 2 + b.h_z ** 2) + inertia * np.square(b.psi_z)
            dM = dM + 2.0 * m * (b.x_z * b.x_zz + b.y_z * b.y_zz + b.h_z * b.h_zz) \
                + 2.0 * inertia * np.multiply(b.psi_z, b.psi_zz)
            G = G + m * (b.x * b.x_z + b.y * b.y_z)
            J = J + m * (b.x * b.y_z - b.y * b.x_z) + inertia * np.asarray(b.psi_z)
            I = I + m * (b.x ** 2 + b.y ** 2)
        return {"M": M, "dM_dz": dM, "G": G, "R": self.restoring(z) + zero, "J": J + zero,
                "I_axis": I}

    def mechanism(self, n: int = 201) -> GovernorMechanism:
        """The common form tabulated for the speed loop.

        Parameters
        ----------
        n : int, optional
            Number of points of the uniform grid from z = 0 to 1 (at least 2).

        Returns
        -------
        GovernorMechanism
            The coefficients on the grid, with the spec's ratio, damping, friction and
            actuator.

        Raises
        ------
        ValueError
            If ``n`` is less than 2.
        """
        if n < 2:
            raise ValueError("a governor's mechanism needs at least 2 grid points")
        z = np.linspace(0.0, 1.0, n)
        t = self.terms(z)
        a = self.actuator
        return GovernorMechanism(z=z, c=float(self.damping), F_f=float(self.friction),
                                 ratio=float(self.ratio), acts_on=a.acts_on,
                                 actuator_at_rest=float(a.at_rest),
                                 actuator_at_top=float(a.at_top), safety_z=float(a.safety_z),
                                 actuator_safety=float(a.safety_value), name=self.name, **t)

    def equilibrium_speed_rad_s(self, z) -> np.ndarray:
        """Shaft speed at which the governor balances at ``z``, without friction.

        ``omega_g^2 = R/G`` (Marks Ch. XVIII Art. 97, eq. 251, for the conical
        pendulum), divided by the ratio.

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        ndarray
            Shaft speed [rad/s], shaped as ``z``.
        """
        t = self.terms(z)
        return (np.sqrt(t["R"] / t["G"]) / self.ratio).reshape(np.shape(z))

    def friction_band(self, z) -> tuple[np.ndarray, np.ndarray]:
        """Lowest and highest shaft speeds at which friction holds the governor still.

        ``omega_g^2`` in ``[(R - F_f)/G, (R + F_f)/G]``, divided by the ratio.

        Parameters
        ----------
        z : float or array_like
            The governor's coordinate [-].

        Returns
        -------
        lo, hi : ndarray
            Shaft speeds [rad/s], shaped as ``z``; ``lo`` is 0 where friction alone
            holds the governor up.
        """
        t = self.terms(z)
        lo = np.sqrt(np.maximum(t["R"] - self.friction, 0.0) / t["G"]) / self.ratio
        hi = np.sqrt((t["R"] + self.friction) / t["G"]) / self.ratio
        return lo.reshape(np.shape(z)), hi.reshape(np.shape(z))

    def static_characteristic(self, n: int = 101) -> tuple[np.ndarray, np.ndarray]:
        """The balancing speed along the governor's travel, without friction.

        Parameters
        ----------
        n : int, optional
            Number of evenly spaced points from z = 0 to 1.

        Returns
        -------
        z : ndarray, shape (n,)
            The coordinate [-].
        omega : ndarray, shape (n,)
            Shaft speed at which the governor balances there [rad/s].
        """
        z = np.linspace(0.0, 1.0, n)
        return z, self.equilibrium_speed_rad_s(z)

    def droop(self) -> float:
        """Fractional speed change between the stops.

        Returns
        -------
        float
            ``(w1 - w0) / ((w1 + w0) / 2)`` [-], w0 and w1 the balancing shaft speeds at
            z = 0 and z = 1 (without friction).
        """
        w0, w1 = self.equilibrium_speed_rad_s(np.array([0.0, 1.0]))
        return float((w1 - w0) / (0.5 * (w1 + w0)))

    def check(self, key: str, value: object, n: int = 201) -> None:
        """Refuse a governor that cannot balance, and warn when it is unstable.

        Parameters
        ----------
        key : str
            Scene key named in the error (the governor's table or the key that set
            the offending geometry).
        value : object
            The value named in the error.
        n : int, optional
            Number of evenly spaced points from z = 0 to 1 at which to check.

        Raises
        ------
        InputError
            If G or R is not positive somewhere between the stops.

        Notes
        -----
        A falling static characteristic (speed decreasing as z rises) is logged as a
        warning: the governor hunts there.
        """
        z = np.linspace(0.0, 1.0, n)
        t = self.terms(z)
        if not np.all(t["G"] > 0.0):
            raise InputError(key, value, "stops between which the weights move outward as the "
                             "governor rises (the centrifugal coefficient vanishes or changes "
                             "sign inside this range)")
        if not np.all(t["R"] > 0.0):
            k = int(np.argmax(t["R"] <= 0.0))
            raise InputError(key, value, "springs and weights that hold the governor down at "
                             f"every position (at z = {z[k]:.3g} nothing resists the weights: "
                             "the governor would fly to its top stop at any speed)")
        w = np.sqrt(t["R"] / t["G"])
        if np.any(np.diff(w) <= 0.0):
            log.warning("governor %s: its static characteristic falls somewhere between the "
                        "stops; it is unstable there (it hunts)", self.name)


#: A registry entry: how to read a ``[governor]`` table and build the governor.
GovernorType = RegistryEntry
GOVERNORS = Registry("governor.type", "governor")
register = GOVERNORS.register
governor_type = GOVERNORS.lookup


# --- scene keys every governor shares ---------------------------------------------------
#: Governor spindle speed over shaft speed: a belt or gearing steps the speed up or
#: down a few times (the bundled governors run at 0.5 to 3.75), never by orders of
#: magnitude.
RATIO_RANGE = (0.05, 20.0)


#: The mass of a governor's ball or weight [kg]: from a model's 10 g to a tonne.  A
#: lighter one is no governor: the dashpot and friction of any real one dwarf its
#: inertia, and a ball of 1e-11 lb made a run need two million evaluations a cycle.
WEIGHT_MASS_KG = (0.01, 1000.0)


#: The drive ratio every governor takes.
RATIO_KEY = Key("ratio", "number", "Governor spindle speed over shaft speed (belt or "
                "gearing).", default=1.0, within=RATIO_RANGE)
#: What a throttling governor moves: the throttle's opening, linear in z.
THROTTLE_KEYS = group(
    "throttle_actuator", "The throttle the governor moves.",
    Key("opening_at_rest", "number", "Throttle opening with the governor at rest, 0 (shut) "
        "to 1 (open).", default=1.0, within=(0.0, 1.0)),
    Key("opening_at_top", "number", "Throttle opening at the governor's top stop, 0 (shut) "
        "to 1 (open).", default=0.0, within=(0.0, 1.0)),
)
#: What a gear-setting governor moves: the gear's setting, linear in z.
GEAR_SETTING_KEYS = group(
    "gear_actuator", "The gear setting the governor moves.",
    Key("setting_at_rest", "number", "The gear's setting with the governor at rest, within "
        "the gear's setting range.", default=0.0),
    Key("setting_at_top", "number", "The gear's setting at the governor's top stop, within "
        "the gear's setting range.", default=1.0),
)


def parse_ratio(t) -> float:
    """``ratio`` (:data:`RATIO_KEY`): governor spindle speed over shaft speed (belt or
    gearing), default 1, within :data:`RATIO_RANGE`.

    Parameters
    ----------
    t : corliss.keys.toml_table.Table
        The governor's table.

    Returns
    -------
    float
        The ratio [-].
    """
    return t.get("ratio")


def parse_actuator(t, acts_on: str) -> Actuator:
    """What the governor moves, linear in z.

    Throttle: ``opening_at_rest`` (default 1, wide open) and ``opening_at_top``
    (default 0, shut), each from 0 to 1.  Gear: ``setting_at_rest`` (default 0) and
    ``setting_at_top`` (default 1), plain numbers in the gear's own setting (the
    shaft-governor gear's runs from 0 at rest to 1 at full speed).

    Parameters
    ----------
    t : corliss.keys.toml_table.Table
        The governor's table, with :data:`THROTTLE_KEYS` or :data:`GEAR_SETTING_KEYS`.
    acts_on : str
        ``"throttle"`` or ``"gear"``.

    Returns
    -------
    Actuator
        What the governor moves, at rest and at the top stop.
    """
    if acts_on == "throttle":
        a0 = t.get("opening_at_rest")
        a1 = t.get("opening_at_top")
        return Actuator("throttle", a0, a1)
    return Actuator("gear", t.get("setting_at_rest"), t.get("setting_at_top"))
