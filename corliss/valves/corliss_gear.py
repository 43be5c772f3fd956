"""The Hamilton-Corliss valve gear: wrist plate, four rotary valves, trip and dash-pot
(Spangler, *Valve-Gears*, Ch. XX, Arts. 155-157).

The linkage (Art. 155, Fig. 107)
--------------------------------
One eccentric of throw r and angular advance delta drives, through the hook rod, a pin
f at radius ``wrist_plate_radius`` (of) on the wrist plate, a disc rocking about its
fixed centre o.  The book's eccentric rod, rocker de and hook rod are replaced by one
rod of length g from the eccentric to f: Art. 157 notes that "it would be possible to
design a gear in which the connection from b to f should be made by one rod only and
give exactly the same distribution of steam"; a rocker's ratio de/dc is taken into
``eccentricity``, which is the throw as felt at the hook.  The wrist plate carries
four studs; each drives a valve rod to an arm on the spindle of a rotary valve: two
steam valves on top, two exhaust valves below (Art. 155).  The steam and exhaust
chains of the crank end are the mirror images of the head end's, so one geometry per
kind of valve serves both ends.

Exact motion (``motion = "exact"``, the default).  Shaft at the origin, X along the
line of stroke, the eccentric centre at r (sin, cos)(theta + delta).  The hook pin is
at o + of (sin psi, -cos psi) with the plate's centre o at (X_o, of), so the rod is
along X with the plate at mid position (psi = 0).  The rod's length fixes psi per crank
angle in closed form: with ``d = o - E``,
``d_x sin psi - d_y cos psi = (g^2 - |d|^2 - of^2) / (2 of)``.  X_o is set so the
plate swings equally either side of its mid position
(Art. 157: "e swings equally above and below the line Oo").

Each valve chain is a four-bar linkage: frame o-q (o the plate's centre, q the valve
spindle at ``*_spindle_distance`` D), crank oj (the stud, radius rho, at angle alpha0
from oq at the plate's mid position), coupler jl (the valve rod, its length taken from
the mid position) and rocker ql (the spindle arm, length a, at angle gamma0 from qo at
mid position).  With the plate turned by u in the sense that opens that valve, the
stud is at rho (cos, sin)(alpha0 + u) and the arm's angle gamma follows in closed form
from the rod's length (same equation as above).  The valve face, of radius R_v, moves
the arc X = R_v (gamma - gamma0) (signed so that it opens the port as u grows).  The
head steam valve opens with u = psi, the crank steam valve with u = -psi, the head
exhaust with u = -psi and the crank exhaust with u = psi.

The toggle action (Art. 156): "the steam-valves should therefore open on that portion
of their motion where j is moving away from oq and ql is approaching it".  With the
stud near the line of the rod (near its own dead point) the rod, and so the valve,
hardly moves while the plate swings: the valve dwells while it is closed; as the stud
turns away from the rod's line and the arm turns towards it, the valve moves fast past
the port edge.  The exact solution shows this; Art. 156's linear formula cannot.

Zeuner form (``motion = "harmonic"``).  Art. 156 (de/dc = 1)::

    x = (rad. valve / ql) (oj / of) r sin(theta + delta)

which holds "as long as oj is to the left of the line og", i.e. away from the toggle
positions, and assumes the stud and the arm square to the rod.  This module's harmonic
motion is x = k r sin(theta + delta) with k = (1 / of) dX/du at mid position, the gear
ratio of the exact chain linearised there: Art. 156's k when the stud and the arm are
square to the rod, as the book assumes.  The book gives the actual motion only by
drawing (Fig. 109, "the marks show the actual movements ... for each 30 degrees"; the
figure is missing from the scan), so the exact chain is this module's own.

Port openings (Art. 156: "As in the case of a plain slide-valve, the steam-port opens
when the valve has moved from its central position a distance equal to the lap, and
... closes again at the same point").  The signed opening of a rotary valve is the arc
its edge has moved past the port's edge, X - lap; the lap and the port's width are arcs
on the valve face (a lap may be given as an angle of the spindle: arc = R_v x angle).
The exhaust valves are usually open at mid position (Art. 157: "the exhaust-port is
open from 1/16 to 1/8 inch"), a negative exhaust lap.

The trip (Art. 155, Fig. 108)
-----------------------------
The steam valve's arm is hooked to the rod's arm and follows the wrist plate until the
hook meets the knock-off cam, which the governor places; the valve is then "closed by
means of the rod H, the lower end of which is attached to a dash-pot".  Here:

* The SETTING s is the cam's position, normalised for each end on the latched valve's
  own swing: s = 0 at the arm's position where the port begins to open, s = 1 at the
  end of the arm's travel (the wrist plate's extreme).  The valve is released where its
  latched signed opening, rising, reaches s times its greatest latched signed opening.
* s > 1: the cam stands beyond the hook's reach, there is no release, and the valve
  closes with the wrist plate at its lap: the longest cut-off of the gear (about half
  stroke: with x = k r sin(theta + delta) it closes at theta = 180 deg - delta -
  asin(lap / k r)).  The cut-off jumps there from the longest trip cut-off (release at
  the plate's extreme plus the dash-pot's closing angle) to the latched one.
* s <= 0: the safety range (the governor fallen to its lowest position, belt broken:
  the safety cam holds the hook off).  The hook is released before the valve opens and
  no steam is admitted; ``release_angle_rad`` gives the latched opening angle, where the
  opening at release is zero.  A Corliss governor's ``safety_setting`` should be < 0.
* The dash-pot closes the valve in ``dashpot_closing_time`` T (from release to the port
  closed), whatever the speed: the crank turns omega T meanwhile, so cut-off comes later
  at higher speed for the same cam.  The closing law taken: the valve, let go, moves
  back like a weight falling from rest (the dash-pot's vacuum or weight pulling it),
  travel proportional to the square of the time, so the fraction still open is
  ``closing_fraction(t) = 1 - (t / T)^2`` for t < T, 0 from T on.
* While tripped, the port is open min(latched opening, opening at release x
  closing_fraction(time since release)), from the release until the latched valve
  would have closed anyway (where the hook catches again on the return).

Exhaust valves follow the wrist plate (no trip).
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import math
from dataclasses import dataclass

import numpy as np

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import DISCHARGE_COEFFICIENT, Table
from corliss.valves.gear import GearType, ValveGear, register

log = logging.getLogger(__name__)

# scipy.optimize (a third of a second to import) is imported in the three methods that
# solve for the trip gear's angles: every scene loads this module with the gear registry,
# and only a Corliss gear calls them.

TWO_PI = 2.0 * math.pi
#: Setting range: below 0 the safety cam (no admission), above 1 no release.
SETTING_RANGE = (-0.25, 1.25)


@dataclass(frozen=True)
class ValveChain:
    """One wrist-plate stud, valve rod and spindle arm (a four-bar chain), all SI.

    Parameters
    ----------
    stud_radius_m : float
        Radius of the stud on the wrist plate, oj or ok [m].
    stud_angle_rad : float
        Angle of the stud from the line of centres o -> q at the plate's mid position,
        positive in the sense the plate turns to open this valve [rad].
    arm_m : float
        Spindle arm, ql or pt [m].
    arm_angle_rad : float
        Angle of the arm from the line q -> o at mid position, positive on the same
        side as a positive stud angle [rad].
    spindle_distance_m : float
        Distance from the plate's centre to the valve spindle, oq [m].
    valve_radius_m : float
        Radius of the valve's face [m].
    """

    stud_radius_m: float
    stud_angle_rad: float
    arm_m: float
    arm_angle_rad: float
    spindle_distance_m: float
    valve_radius_m: float

    def _points(self, u, gamma):
        rho, a, D = self.stud_radius_m, self.arm_m, self.spindle_distance_m
        a0 = self.stud_angle_rad + u
        j = (rho * np.cos(a0), rho * np.sin(a0))
        l_ = (D - a * np.cos(gamma), a * np.sin(gamma))
        return j, l_

    @property
    def rod_m(self) -> float:
        """Valve rod length, jl, from the mid position [m]."""
        j, l_ = self._points(0.0, self.arm_angle_rad)
        return math.hypot(l_[0] - j[0], l_[1] - j[1])

    def _branch(self, u, sign):
        rho, a, D, L = self.stud_radius_m, self.arm_m, self.spindle_distance_m, self.rod_m
        a0 = self.stud_angle_rad + np.asarray(u, dtype=float)
        dx = D - rho * np.cos(a0)
        dy = -rho * np.sin(a0)
        # |d + a(-cos g, sin g)| = L  ->  dy sin g - dx cos g = K
        K = (L * L - dx * dx - dy * dy - a * a) / (2.0 * a)
        M = np.hypot(dx, dy)
        mu = np.arctan2(dx, dy)
        arg = K / M
        if np.any(np.abs(arg) > 1.0):
            raise ValueError("the valve rod cannot reach the spindle arm (the chain locks)")
        return mu + (np.arcsin(arg) if sign > 0 else math.pi - np.arcsin(arg))

    @functools.cached_property
    def _sign(self) -> int:
        """The branch of the chain's solution through the mid position."""
        g0 = self.arm_angle_rad
        for sign in (1, -1):
            g = float(self._branch(0.0, sign))
            if abs(math.remainder(g - g0, TWO_PI)) < 1e-9:
                return sign
        raise AssertionError("mid position not on either branch")  # pragma: no cover

    def arm_angle(self, u) -> np.ndarray:
        """Spindle arm angle gamma, on the branch of the chain through the mid position.

        Parameters
        ----------
        u : float or ndarray
            Angle the wrist plate has turned from its mid position [rad], in the sense
            that opens this valve.

        Returns
        -------
        ndarray
            gamma [rad], measured as ``arm_angle_rad``, of the shape of ``u``.

        Raises
        ------
        ValueError
            If the valve rod cannot reach the spindle arm (the chain locks).
        """
        g0 = self.arm_angle_rad
        return g0 + np.remainder(self._branch(u, self._sign) - g0 + math.pi, TWO_PI) - math.pi

    @functools.cached_property
    def opening_sense(self) -> float:
        """+1 or -1: the sign of d gamma / du at mid position."""
        h = 1e-6
        return 1.0 if float(self.arm_angle(h) - self.arm_angle(-h)) > 0.0 else -1.0

    def valve_arc(self, u) -> np.ndarray:
        """Arc the valve's face has moved from its mid position, ``R_v (gamma -
        gamma0)``, positive towards opening.

        Parameters
        ----------
        u : float or ndarray
            Angle the wrist plate has turned from its mid position [rad], in the sense
            that opens this valve.

        Returns
        -------
        ndarray
            Arc X [m] on the valve's face, of the shape of ``u``.
        """
        return self.opening_sense * self.valve_radius_m * (self.arm_angle(u) - self.arm_angle_rad)

    def spindle_angle(self, u) -> np.ndarray:
        """Spindle angle from its mid position, positive towards opening.

        Parameters
        ----------
        u : float or ndarray
            Angle the wrist plate has turned from its mid position [rad], in the sense
            that opens this valve.

        Returns
        -------
        ndarray
            Angle [rad], of the shape of ``u``.
        """
        return self.opening_sense * (self.arm_angle(u) - self.arm_angle_rad)

    def ratio_at_mid(self) -> float:
        """The chain's gear ratio at mid position, by central difference.

        Returns
        -------
        float
            dX/du [m/rad]: valve arc per radian of the plate.
        """
        h = 1e-5
        return float(self.valve_arc(h) - self.valve_arc(-h)) / (2.0 * h)


@dataclass(frozen=True)
class CorlissSpec:
    """A Corliss gear (all SI; Spangler Arts. 155-157).

    Parameters
    ----------
    eccentricity_m, angular_advance_rad : float
        Throw at the hook [m] and angular advance [rad].
    hook_rod_m : float
        Length of the rod from the eccentric to the wrist-plate pin [m].
    wrist_plate_radius_m : float
        Radius of the hook pin on the wrist plate, of [m].
    steam, exhaust : ValveChain
        The chains of the steam and exhaust valves (head end; the crank end mirrors).
    steam_lap_m, exhaust_lap_m : tuple of float
        Laps (head, crank) as arcs on the valve face at the plate's mid position [m];
        a negative exhaust lap is an exhaust open at mid position.
    steam_port_width_m, exhaust_port_width_m, port_length_m : float
        Port widths (arcs on the valve face) and the ports' length [m].
    dashpot_closing_time_s : float
        Time from release to the steam port closed [s].
    discharge_coefficient : float, optional
        Of every port opening [-].
    ports_per_end : int, optional
        Number of openings each valve uncovers.
    setting : float, optional
        Cam position s [-] in :data:`SETTING_RANGE` (see the module doc).
    motion : str, optional
        ``"exact"`` or ``"harmonic"``.
    speed_rad_s : float or None, optional
        Shaft speed [rad/s], set by :meth:`CorlissGear.with_speed`; the gear's
        openings need it once a steam valve trips.
    """

    eccentricity_m: float
    angular_advance_rad: float
    hook_rod_m: float
    wrist_plate_radius_m: float
    steam: ValveChain
    exhaust: ValveChain
    steam_lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    steam_port_width_m: float
    exhaust_port_width_m: float
    port_length_m: float
    dashpot_closing_time_s: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1
    setting: float = 0.5
    motion: str = "exact"
    speed_rad_s: float | None = None


class CorlissGear(ValveGear):
    """Corliss wrist plate, four rotary valves, trip and dash-pot (Spangler Ch. XX).

    Its setting is the knock-off cam's position s (see the module doc).  Building the
    gear finds, once, the plate's centre and each steam valve's latched opening and
    closing angles; the same gear at another setting or speed shares them.

    Parameters
    ----------
    spec : CorlissSpec
        The eccentric, wrist plate, valve chains, laps, ports and dash-pot.
    _geom : dict or None, optional
        Internal: the geometry of the same gear already found (passed by
        :meth:`~corliss.valves.gear.ValveGear.with_setting` and
        :meth:`with_speed`); None to find it.

    Raises
    ------
    ValueError
        If the hook rod or a valve rod cannot reach at some crank angle, or a steam
        valve does not open and close once a turn.
    """

    name = "corliss"
    summary = ("Corliss gear: wrist plate, four rotary valves, steam valves released by the "
               "governor's cams and closed by dash-pots (Spangler Arts. 155-157); setting = "
               "cam position (0 trips at admission, 1 at the end of the hook's travel, > 1 "
               "no trip, < 0 safety cam: no admission)")
    setting_name = ("cam position s (0: release at admission, 1: at the end of the hook's "
                    "travel; > 1 no release, < 0 safety cam)")
    setting_range = SETTING_RANGE

    def __init__(self, spec: CorlissSpec, _geom: dict | None = None):
        self.spec = spec
        # geometry-only quantities, shared by the same gear at other settings and speeds
        self._geom = _geom if _geom is not None else self._prepare()

    # ------------------------------------------------------------------ settings
    def _at_setting(self, value: float) -> "CorlissGear":
        return CorlissGear(dataclasses.replace(self.spec, setting=value), self._geom)

    def with_speed(self, speed_rad_s: float) -> "CorlissGear":
        """The same gear at another shaft speed (the dash-pot's closing angle is speed
        times closing time).

        Parameters
        ----------
        speed_rad_s : float
            Shaft speed [rad/s], positive.

        Returns
        -------
        CorlissGear
            The gear at that speed, its geometry shared.

        Raises
        ------
        ValueError
            If the speed is not positive.
        """
        if not speed_rad_s > 0.0:
            raise ValueError(f"speed {speed_rad_s} rad/s must be positive")
        return CorlissGear(dataclasses.replace(self.spec, speed_rad_s=float(speed_rad_s)),
                           self._geom)

    @property
    def closing_time_s(self) -> float:
        """Dash-pot closing time, release to port closed [s]."""
        return self.spec.dashpot_closing_time_s

    # ------------------------------------------------------------------ motion
    def _hook_setup(self) -> float:
        """X_o of the plate's centre that makes the plate swing equally both ways."""
        s = self.spec
        th = np.linspace(0.0, TWO_PI, 721)

        def asym(xo):
            p = self._psi_exact(th, xo)
            return float(p.max() + p.min())

        from scipy.optimize import brentq
        g, r = s.hook_rod_m, s.eccentricity_m
        return brentq(asym, g - 0.9 * r, g + 0.9 * r, xtol=1e-14)

    def _psi_exact(self, theta, xo):
        s = self.spec
        R, g, r = s.wrist_plate_radius_m, s.hook_rod_m, s.eccentricity_m
        ph = np.asarray(theta, dtype=float) + s.angular_advance_rad
        dx = xo - r * np.sin(ph)
        dy = R - r * np.cos(ph)
        K = (g * g - dx * dx - dy * dy - R * R) / (2.0 * R)
        M = np.hypot(dx, dy)
        mu = np.arctan2(dy, dx)
        arg = K / M
        if np.any(np.abs(arg) > 1.0):
            raise ValueError("the hook rod cannot reach the wrist-plate pin")
        return mu + np.arcsin(arg)

    def plate_angle(self, theta) -> np.ndarray:
        """Wrist plate angle psi from its mid position: the hook rod's closed form
        (module doc), or ``r sin(theta + delta) / of`` for the harmonic motion.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            psi [rad], positive in the sense that opens the head steam valve, of the
            shape of ``theta``.
        """
        s = self.spec
        th = np.asarray(theta, dtype=float)
        if s.motion == "harmonic":
            return s.eccentricity_m * np.sin(th + s.angular_advance_rad) / s.wrist_plate_radius_m
        return self._psi_exact(th, self._geom["xo"])

    def zeuner_travels(self, theta) -> np.ndarray:
        """Art. 156's valve motion ``x = k r sin(theta + delta)``, with
        ``k = (1 / of) dX/du`` at mid position (Art. 156's
        ``(rad. valve / ql)(oj / of)`` when the stud and the arm are square to the rod).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Arc x [m] of the (steam, exhaust) valve of the head end, shape ``(2, n)``.
        """
        s = self.spec
        base = s.eccentricity_m * np.sin(np.asarray(theta, dtype=float) + s.angular_advance_rad)
        base = base / s.wrist_plate_radius_m
        return np.vstack([self._geom["k_steam"] * base, self._geom["k_exhaust"] * base])

    def valve_arcs(self, theta) -> np.ndarray:
        """Arc each valve's face has moved from mid position towards opening, the steam
        valves latched (never tripped).

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Arcs [m], shape ``(4, n)``, in port order (head steam, head exhaust, crank
            steam, crank exhaust).
        """
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        s = self.spec
        if s.motion == "harmonic":
            zs, ze = self.zeuner_travels(th)
            return np.vstack([zs, -ze, -zs, ze])
        psi = self.plate_angle(th)
        return np.vstack([s.steam.valve_arc(psi), s.exhaust.valve_arc(-psi),
                          s.steam.valve_arc(-psi), s.exhaust.valve_arc(psi)])

    def spindle_angles(self, theta) -> np.ndarray:
        """Spindle angle of each valve from mid position towards opening, the steam
        valves latched.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Angles [rad], shape ``(4, n)``, in port order.
        """
        radii = np.array([self.spec.steam.valve_radius_m, self.spec.exhaust.valve_radius_m] * 2)
        return self.valve_arcs(theta) / radii[:, None]

    def latched_signed_openings(self, theta) -> np.ndarray:
        """Signed openings as if the steam valves never tripped: arc less lap.

        Parameters
        ----------
        theta : float or ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Signed openings [m], shape ``(4, n)``, in port order.
        """
        s = self.spec
        laps = np.array([s.steam_lap_m[0], s.exhaust_lap_m[0], s.steam_lap_m[1],
                         s.exhaust_lap_m[1]])
        return self.valve_arcs(theta) - laps[:, None]

    # ------------------------------------------------------------------ trip
    def _prepare(self) -> dict:
        from scipy.optimize import brentq, minimize_scalar
        s = self.spec
        sh = {"xo": None, "k_steam": s.steam.ratio_at_mid(), "k_exhaust": s.exhaust.ratio_at_mid()}
        self._geom = sh
        if s.motion == "exact":
            sh["xo"] = self._hook_setup()
        th = np.linspace(0.0, TWO_PI, 7201)
        op = self.latched_signed_openings(th)
        windows = []
        for e, port in enumerate((0, 2)):
            p = op[port]
            up = np.nonzero((p[:-1] <= 0.0) & (p[1:] > 0.0))[0]
            dn = np.nonzero((p[:-1] > 0.0) & (p[1:] <= 0.0))[0]
            if up.size != 1 or dn.size != 1:
                raise ValueError(f"the {('head', 'crank')[e]}-end steam valve must open and "
                                 "close once a turn with the wrist plate")
            def f(t, port=port):
                return float(self.latched_signed_openings(np.array([t]))[port, 0])
            t_open = brentq(f, th[up[0]], th[up[0] + 1], xtol=1e-14)
            t_close = brentq(f, th[dn[0]], th[dn[0] + 1], xtol=1e-14)
            span = (t_close - t_open) % TWO_PI
            u = (th - t_open) % TWO_PI
            inside = u < span
            k = int(np.argmax(np.where(inside, p, -np.inf)))
            res = minimize_scalar(lambda t: -f(t), bracket=None,
                                  bounds=(th[k] - 2 * TWO_PI / 7200, th[k] + 2 * TWO_PI / 7200),
                                  method="bounded", options={"xatol": 1e-12})
            t_peak = float(res.x) % TWO_PI
            # the rise from opening to the peak, sampled: it brackets each release
            # (kept only when it rises throughout, as a bracket by search needs)
            rise = np.nonzero(inside & (u <= (t_peak - t_open) % TWO_PI))[0]
            rise = rise[np.argsort(u[rise])]
            if not np.all(np.diff(p[rise]) > 0.0):
                rise = rise[:0]
            windows.append({"open": t_open % TWO_PI, "close": t_close % TWO_PI,
                            "peak": t_peak, "p_max": -float(res.fun), "f": f,
                            "rise_t": t_open + u[rise], "rise_p": p[rise]})
        sh["windows"] = windows
        return sh

    def release_angle_rad(self, setting: float | None = None):
        """Crank angles at which the steam valves are released.

        Parameters
        ----------
        setting : float or None, optional
            Cam position s [-]; None for the gear's own (then computed once and kept).

        Returns
        -------
        tuple of (float or None)
            Release angle of the (head, crank) valve [rad] in [0, 2 pi): where its
            latched signed opening, rising, reaches s times its greatest; None for an
            end whose cam cannot trip it (s > 1); the latched opening angle for
            s <= 0 (safety: released before the valve opens).
        """
        if setting is None:
            if not hasattr(self, "_release"):
                self._release = self._release_at(self.spec.setting)
            return self._release
        return self._release_at(float(setting))

    @functools.cached_property
    def _released_opening(self) -> tuple:
        """The steam valves' latched openings at release (head, crank) [m], at the
        gear's own setting (0 at the safety cam; None for an end not released)."""
        out: list[float | None] = []
        for w, rel in zip(self._geom["windows"], self.release_angle_rad()):
            if rel is None:
                out.append(None)
            else:
                out.append(0.0 if self.spec.setting <= 0.0 else max(w["f"](rel), 0.0))
        return tuple(out)

    def _release_at(self, s: float):
        from scipy.optimize import brentq
        out: list[float | None] = []
        for w in self._geom["windows"]:
            if s > 1.0:
                out.append(None)
            elif s <= 0.0:
                out.append(w["open"])
            elif s == 1.0:
                out.append(w["peak"])
            else:
                level = s * w["p_max"]
                a = w["open"]
                b = a + (w["peak"] - a) % TWO_PI
                # the samples' bracket of the level, else the whole rise
                k = int(np.searchsorted(w["rise_p"], level))
                if 0 < k < w["rise_p"].size:
                    a, b = w["rise_t"][k - 1], w["rise_t"][k]
                t = brentq(lambda t: w["f"](t) - level, a, b, xtol=1e-14)
                out.append(t % TWO_PI)
        return tuple(out)

    def closing_fraction(self, t_s) -> np.ndarray:
        """Fraction of the opening at release still open a time after release.

        ``1 - (t/T)^2``: a valve let go from rest moving back like a falling weight,
        closed at the dash-pot's closing time T.

        Parameters
        ----------
        t_s : float or ndarray
            Time since release [s].

        Returns
        -------
        ndarray
            Fraction [-] in [0, 1], of the shape of ``t_s``: 1 before release, 0 from
            T on.
        """
        T = self.spec.dashpot_closing_time_s
        x = np.clip(np.asarray(t_s, dtype=float) / T, 0.0, 1.0)
        return 1.0 - x * x

    def closing_angle_rad(self) -> float:
        """Crank angle swept while the dash-pot closes the valve, ``omega T``.

        Returns
        -------
        float
            Angle [rad].

        Raises
        ------
        ValueError
            If the gear has no speed (see :meth:`with_speed`).
        """
        return self._speed() * self.spec.dashpot_closing_time_s

    def _speed(self) -> float:
        if self.spec.speed_rad_s is None:
            raise ValueError("the Corliss gear needs the shaft speed for its dash-pots: "
                             "call with_speed(speed_rad_s) first")
        return self.spec.speed_rad_s

    def _trips(self, th):
        """For each steam port (0, 2): None if never released, else (mask of ``th``
        where the valve is released, the dash-pot's time since release there [s], the
        opening at release [m])."""
        rel = self.release_angle_rad()
        out = []
        for e in range(2):
            if rel[e] is None:
                out.append(None)
                continue
            w = self._geom["windows"][e]
            window = (w["close"] - w["open"]) % TWO_PI
            rel_from_open = (rel[e] - w["open"]) % TWO_PI
            if self.spec.setting <= 0.0:
                rel_from_open = 0.0
            since_open = (th - w["open"]) % TWO_PI
            m = (since_open >= rel_from_open) & (since_open <= window)
            tau = (since_open[m] - rel_from_open) / self._speed()
            out.append((m, tau, self._released_opening[e]))
        return out

    def signed_openings(self, theta):
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        out = self.latched_signed_openings(th)
        if all(r is None for r in self.release_angle_rad()):
            return out
        for port, trip in zip((0, 2), self._trips(th)):
            if trip is not None and np.any(trip[0]):
                m, tau, p_rel = trip
                out[port, m] = np.minimum(out[port, m], p_rel * self.closing_fraction(tau))
        return out

    def joints(self, theta: float) -> "CorlissJoints":
        """The wrist plate, its rods and the four valves at crank angle ``theta``, from
        the same solve as :meth:`plate_angle` and :meth:`signed_openings`.

        The spec fixes each valve chain's shape, not the direction from the plate's
        centre to its spindle, which does not change the motion; the picture puts the
        head-end valves on the left, the steam spindles at 120 deg and 60 deg from the
        line of stroke, the exhaust spindles at 240 deg and 300 deg (each chain of the
        crank end the mirror image of the head end's, as the module doc says).

        Parameters
        ----------
        theta : float
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        CorlissJoints
            The joints [m], the plate's and the valves' angles [rad] and the trip's state.

        Raises
        ------
        ValueError
            For the harmonic motion, which solves no linkage.
        """
        s = self.spec
        if s.motion != "exact":
            raise ValueError("joints are solved for the exact motion only (this gear's "
                             "motion is harmonic)")
        th = np.array([float(theta)])
        phase = float(th[0]) + s.angular_advance_rad
        R, r = s.wrist_plate_radius_m, s.eccentricity_m
        psi = float(self.plate_angle(th)[0])
        o = np.array([self._geom["xo"], R])
        ecc = (r * math.sin(phase), r * math.cos(phase))
        hook = o + R * np.array([math.sin(psi), -math.cos(psi)])
        frames = ((2 * math.pi / 3, 1.0, s.steam, psi), (-2 * math.pi / 3, -1.0, s.exhaust, -psi),
                  (math.pi / 3, -1.0, s.steam, -psi), (-math.pi / 3, 1.0, s.exhaust, psi))
        studs, arms, spindles, senses = [], [], [], []
        # each rod: (length, the joint at one end, the joint at the other), a joint named
        # or given as (its list, its index)
        rods: dict[str, tuple[float, str | tuple[str, int], str | tuple[str, int]]] = {
            "eccentric": (r, "shaft", "eccentric"),
            "hook rod": (s.hook_rod_m, "eccentric", "hook_pin"),
            "plate arm": (R, "plate_centre", "hook_pin")}
        for i, (phi, m, ch, u) in enumerate(frames):
            c, sn = math.cos(phi), math.sin(phi)

            def place(lx, ly, c=c, sn=sn, m=m):
                return (float(o[0] + c * lx - sn * m * ly), float(o[1] + sn * lx + c * m * ly))

            a0 = ch.stud_angle_rad + u
            gamma = float(ch.arm_angle(u))
            studs.append(place(ch.stud_radius_m * math.cos(a0), ch.stud_radius_m * math.sin(a0)))
            arms.append(place(ch.spindle_distance_m - ch.arm_m * math.cos(gamma),
                              ch.arm_m * math.sin(gamma)))
            spindles.append(place(ch.spindle_distance_m, 0.0))
            # the arm's direction in the chain's frame is pi - gamma; the figure turns it
            # m times that, so the valve turns -m x (its opening sense) as it opens
            senses.append(-m * ch.opening_sense)
            port = PORTS_OF_GEAR[i]
            rods[f"{port} stud"] = (ch.stud_radius_m, "plate_centre", ("studs", i))
            rods[f"{port} valve rod"] = (ch.rod_m, ("studs", i), ("arm_ends", i))
            rods[f"{port} arm"] = (ch.arm_m, ("spindles", i), ("arm_ends", i))
        laps = np.array([s.steam_lap_m[0], s.exhaust_lap_m[0], s.steam_lap_m[1],
                         s.exhaust_lap_m[1]])
        radii = np.array([s.steam.valve_radius_m, s.exhaust.valve_radius_m] * 2)
        latched = self.spindle_angles(th)[:, 0]
        actual = (self.signed_openings(th)[:, 0] + laps) / radii
        released, held = [False, False], [1.0, 1.0]
        if any(x is not None for x in self.release_angle_rad()):
            for e, trip in enumerate(self._trips(th)):
                if trip is not None and trip[0][0]:
                    released[e] = True
                    held[e] = float(self.closing_fraction(trip[1])[0])
        return CorlissJoints(shaft=(0.0, 0.0), eccentric=ecc,
                             hook_pin=(float(hook[0]), float(hook[1])),
                             plate_centre=(float(o[0]), float(o[1])), studs=tuple(studs),
                             arm_ends=tuple(arms), spindles=tuple(spindles),
                             plate_angle_rad=psi, latched_angles_rad=tuple(map(float, latched)),
                             valve_angles_rad=tuple(map(float, actual)),
                             released=tuple(released), dashpot_held_frac=tuple(held),
                             opening_sense=tuple(senses), rods_m=rods)

    # ------------------------------------------------------------------ ports
    def port_widths(self):
        s = self.spec
        return np.array([s.steam_port_width_m, s.exhaust_port_width_m] * 2)

    def port_lengths(self):
        return np.full(4, self.spec.port_length_m * self.spec.ports_per_end)

    def openings_per_edge(self):
        return np.full(4, float(self.spec.ports_per_end))

    def discharge_coefficients(self):
        return np.full(4, self.spec.discharge_coefficient)


#: The ports in the order of :data:`corliss.valves.gear.PORTS`, as the joints name them.
PORTS_OF_GEAR = ("head steam", "head exhaust", "crank steam", "crank exhaust")


@dataclass(frozen=True)
class CorlissJoints:
    """The Corliss gear at one crank angle (all SI): shaft at the origin, X along the
    hook rod, Y up; each point an (x, y) pair [m], each tuple of four in port order
    (head steam, head exhaust, crank steam, crank exhaust).

    Parameters
    ----------
    shaft, eccentric, hook_pin, plate_centre : tuple of float
        The shaft, the eccentric's centre, the hook rod's pin on the wrist plate and the
        plate's centre [m].
    studs, arm_ends, spindles : tuple of tuple of float
        Each valve's stud on the plate, its rod's pin on the spindle arm, and its
        spindle [m].
    plate_angle_rad : float
        The plate's turn from mid position, counter-clockwise [rad].
    latched_angles_rad : tuple of float
        Each spindle arm's angle from mid position towards opening, as the plate drives
        it [rad].
    valve_angles_rad : tuple of float
        Each valve's angle from mid position towards opening [rad]: the arm's while
        latched; a steam valve released by the trip closes on its dash-pot
        ((signed opening + lap) / valve radius, from :meth:`CorlissGear.signed_openings`).
    released : tuple of bool
        Whether the (head, crank) steam valve is released from its hook.
    dashpot_held_frac : tuple of float
        The fraction of the opening at release the dash-pot still holds, (head, crank),
        1 while latched [-].
    opening_sense : tuple of float
        +1 where a valve turns counter-clockwise in the figure as it opens, -1 where
        clockwise.
    rods_m : dict
        Each rod or arm: ``{name: (length [m], joint, joint)}``, a joint named by its
        field, or by ``(field, port index)`` in a tuple of four.
    """

    shaft: tuple[float, float]
    eccentric: tuple[float, float]
    hook_pin: tuple[float, float]
    plate_centre: tuple[float, float]
    studs: tuple
    arm_ends: tuple
    spindles: tuple
    plate_angle_rad: float
    latched_angles_rad: tuple
    valve_angles_rad: tuple
    released: tuple
    dashpot_held_frac: tuple
    opening_sense: tuple
    rods_m: dict


# ---------------------------------------------------------------------- parsing
def _arc(t: Table, key: str, radius: float) -> tuple[float, float]:
    """A lap given as an arc (length) or as a spindle angle, once or as [head, crank]
    (its default the declared one)."""
    raw = t.raw(key)
    vals = raw if isinstance(raw, list) else [raw, raw]
    if len(vals) != 2:
        raise InputError(t.key(key), raw, "one value, or a list [head, crank] of two")
    out = []
    for v in vals:
        try:
            out.append(units.parse(v, "length", t.key(key)))
        except InputError:
            try:
                out.append(radius * units.parse(v, "angle", t.key(key)))
            except InputError:
                raise InputError(t.key(key), raw, "an arc on the valve face (\"0.375 in\") or "
                                 "a spindle angle (\"8 deg\")") from None
    return out[0], out[1]


def _chain(t: Table, kind: str) -> ValveChain:
    ch = ValveChain(t.get(f"{kind}_stud_radius"), t.get(f"{kind}_stud_angle"),
                    t.get(f"{kind}_arm"), t.get(f"{kind}_arm_angle"),
                    t.get(f"{kind}_spindle_distance"), t.get(f"{kind}_valve_radius"))
    if ch.rod_m <= 0.0:
        raise InputError(t.key(f"{kind}_arm_angle"), t.raw(f"{kind}_arm_angle"),
                         "an arm placed apart from the stud")
    return ch


#: Typical values of each chain's keys: those of the bundled 20 x 42 engine
#: (``corliss-trip-gear``, proportioned after Spangler Art. 157), steam then exhaust.
_TYPICAL = {"stud_radius": ("6 in", "6 in"), "stud_angle": ("25 deg", "30 deg"),
            "arm": ("4 in", "4 in"), "arm_angle": ("-45 deg", "-45 deg"),
            "spindle_distance": ("30 in", "24 in"), "valve_radius": ("2.5 in", "3 in")}


def _chain_keys(kind: str) -> list:
    """The keys of the head-end ``kind`` (steam or exhaust) valve's chain."""
    col = 0 if kind == "steam" else 1
    return [Key(f"{kind}_{name}", k, f"{what} of the {kind} valve's chain (head end; the "
                f"crank end mirrors); typical {_TYPICAL[name][col]}.",
                within=POSITIVE_LENGTH if k == "length" else None,
                unit="in" if k == "length" else "deg")
            for name, k, what in (
                ("stud_radius", "length", "Radius oj of the wrist-plate stud"),
                ("stud_angle", "angle", "Angle of the stud oj from the line of centres "
                 "o->q (plate centre to spindle) at the plate's mid position, positive the "
                 "way the plate turns to open this valve"),
                ("arm", "length", "Spindle arm ql"),
                ("arm_angle", "angle", "Angle of the spindle arm ql from the line q->o at "
                 "mid position, positive on the side of a positive stud angle (negative: "
                 "the arm across the line from the stud, set for the toggle of Art. 156)"),
                ("spindle_distance", "length", "Distance oq from the plate's centre to the "
                 "spindle"),
                ("valve_radius", "length", "Radius of the valve's face"))]


CORLISS_KEYS = group(
    "corliss", "Corliss's trip gear: a wrist plate rocks four rotary valves; the steam "
    "valves are tripped by the cams and closed by dashpots.  The keys are sketched below "
    "from the bundled corliss-trip-gear scene (its values the typical ones given); the "
    "crank end's chains are the head end's mirror images.",
    *_chain_keys("steam"), *_chain_keys("exhaust"),
    Key("eccentricity", "length", "Throw of the eccentric at the hook, less than the "
        "wrist-plate radius; typical 3.5 in (Art. 157: 3 1/2 to 10 in).",
        within=POSITIVE_LENGTH, unit="in"),
    Key("angular_advance", "angle", "Angular advance of the eccentric: how far beyond "
        "90 deg it leads the crank, in the sense of rotation; typical 32 deg.", unit="deg"),
    Key("wrist_plate_radius", "length", "Radius of the hook pin f on the wrist plate (of, "
        "Fig. 107); typical 11 in (Art. 157: 10 to 12 in).", within=POSITIVE_LENGTH,
        unit="in"),
    Key("hook_rod", "length", "Rod from the eccentric to the wrist-plate pin, longer than "
        "twice the throw plus the plate's radius; typical 120 in.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("dashpot_closing_time", "time", "Time from release to the steam port closed "
        "(above zero); typical 0.04 s (19 deg of crank at 80 rev/min).", unit="s"),
    Key("setting", "number", "Cam position s: 0 trips the steam valve at admission, 1 at "
        "the end of the hook's travel; above 1 no trip, below 0 the safety cam admits no "
        "steam.", default=0.5, within=SETTING_RANGE),
    Key("discharge_coefficient", "number", "Discharge coefficient of a port opening.",
        default=0.7, within=DISCHARGE_COEFFICIENT),
    Key("ports_per_end", "integer", "Openings each valve uncovers.", default=1,
        within=(1, 8)),
    Key("steam_lap", "arc", "Steam valves' lap at the plate's mid position: an arc on the "
        "valve face or a spindle angle; typical 0.5 in (Art. 157: 7/16 to 1/2 in).",
        ends=True),
    Key("exhaust_lap", "arc", "Exhaust valves' lap at mid position (negative: open there); "
        "typical -0.1 in (Art. 157: open 1/16 to 1/8 in).", default="0 in", ends=True),
    Key("steam_port_width", "length", "Steam ports' width, an arc on the valve face; "
        "typical 1.25 in.", within=POSITIVE_LENGTH, unit="in"),
    Key("exhaust_port_width", "length", "Exhaust ports' width, an arc on the valve face; "
        "typical 1.5 to 2 times the steam port's (1.875 in).", within=POSITIVE_LENGTH,
        unit="in"),
    Key("port_length", "length", "The ports' length along the valve.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("motion", "choice", "The exact four-bar linkage, or harmonic motion.",
        default="exact", choices=("exact", "harmonic")),
)


def parse_corliss(t: Table) -> CorlissSpec:
    """Read a ``[valve_gear] type = "corliss"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`CORLISS_KEYS`.

    Returns
    -------
    CorlissSpec
        The gear's spec.
    """
    t = t.bound(CORLISS_KEYS)
    steam, exhaust = _chain(t, "steam"), _chain(t, "exhaust")
    r = t.get("eccentricity")
    R = t.get("wrist_plate_radius")
    if r >= R:
        raise InputError(t.key("eccentricity"), t.raw("eccentricity"),
                         f"a throw less than the wrist-plate radius ({R / units.INCH_m:.4g} in)")
    g = t.get("hook_rod")
    if g <= 2.0 * (r + R):
        raise InputError(t.key("hook_rod"), t.raw("hook_rod"),
                         "a hook rod longer than twice the throw plus the wrist-plate radius")
    closing = t.get("dashpot_closing_time")
    if not closing > 0.0:
        raise InputError(t.key("dashpot_closing_time"), t.raw("dashpot_closing_time"),
                         "a time greater than zero")
    setting = t.get("setting")
    cd = t.get("discharge_coefficient")
    ports = t.get("ports_per_end")   # double- and multi-ported valves
    spec = CorlissSpec(
        eccentricity_m=r, angular_advance_rad=t.get("angular_advance"), hook_rod_m=g,
        wrist_plate_radius_m=R, steam=steam, exhaust=exhaust,
        steam_lap_m=_arc(t, "steam_lap", steam.valve_radius_m),
        exhaust_lap_m=_arc(t, "exhaust_lap", exhaust.valve_radius_m),
        steam_port_width_m=t.get("steam_port_width"),
        exhaust_port_width_m=t.get("exhaust_port_width"), port_length_m=t.get("port_length"),
        dashpot_closing_time_s=closing, discharge_coefficient=cd, ports_per_end=ports,
        setting=setting, motion=t.get("motion"))
    try:
        CorlissGear(spec)
    except ValueError as exc:
        raise InputError(t.key("steam_lap"), t.raw("steam_lap"),
                         f"a gear whose linkage works and whose steam valves open and close "
                         f"once a turn ({exc})") from None
    return spec


register(GearType("corliss", CorlissGear.summary, parse_corliss, CorlissGear, CORLISS_KEYS))
