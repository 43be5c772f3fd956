"""Link motions: Stephenson (open and crossed rods), Gooch, Allen, in Zeuner's form or
solved exactly.

Two eccentrics of throw r and equal angular advance delta drive the ends of a link of
half-chord c through rods of length g; the valve takes its motion from the block at
distance u from the link's centre, the setting the reversing lever (or a governor)
moves, from u = c (full gear ahead) through 0 (mid gear) to -c (full gear astern).
With the rods' ends on straight lines through the shaft and the link's radius,
hanger arc and slip neglected (Spangler Art. 45), every one of these gears moves the
valve as a single "virtual" eccentric, x = C cos(theta) + S sin(theta)::

    Stephenson, open rods    C = r (sin d + (c^2 - u^2)/(c g) cos d)     S = (u r / c) cos d   (Art. 46)
    Stephenson, crossed rods C = r (sin d - (c^2 - u^2)/(c g) cos d)     S = -(u r / c) cos d  (Art. 55)
    Gooch                    C = r (sin d + (c / g) cos d)                S = (u r / c)(cos d - (c/g) sin d)  (Art. 65)
    Allen                    C = r (sin d + (c^2 - u u1)/(c g) cos d)     S = (u r / c)(cos d - c (u - u1)/(u g) sin d)  (Art. 73)

with C = lap + lead, the valve's displacement at the dead point.  For the Allen link
``u1`` is the link's own share of the block's offset, u1 = k u with k from the rocker
arms (k = 1 is Stephenson's open rods, k = 0 Gooch's fixed link); a scene that does
not give ``allen_ratio`` gets the ratio of Art. 73's rocker proportions
(:func:`allen_book_ratio`).

``motion = "exact"`` solves the linkage itself at every crank angle.  For Stephenson:
the eccentric centres on their circles, rods of length g pinned to the ends of a link
curved to radius rho (concave to the shaft, pins on the arc, Peabody's condition 1),
the link hung at its middle from a hanger of length h whose top the reversing lever
holds at height h - u, and the block riding on the link where it crosses the valve
spindle's line through the shaft (so the block slips).  The valve
is set for equal lead in full forward gear.  The solution is tabulated once at 1/2 deg
and read back through a periodic cubic spline.

For Gooch (Spangler Arts. 64-69, Fig. 45): the link, curved the other way (concave to
the valve) to a radius equal to the radius rod g1 (Art. 67, ``link_radius`` to change
it), hangs at its middle on the line of stroke (an infinitely long suspension rod,
Art. 68's rod swinging "equally above and below"); the rods' ends are pinned to its
ends; the block is held at the height -u (an infinitely long radius-rod hanger, the
block slipping in the link) and the radius rod g1 (``radius_rod``, by default the
eccentric rods' length) carries the motion to the valve stem on the line of stroke.
With the crank on a dead point the link is then an arc about the stem's end, so moving
the block moves the valve only through the finite rods' obliquity: the lead is
constant to that order (Art. 66).  For Allen (Arts. 72-73, Fig. 50): the same with a
straight link lifted u1 = k u while the radius rod's end drops u - u1 (the rocker mlk
with infinitely long hangers), so the block stands u from the link's centre.  Both
keep the valve set for equal lead in full forward gear and are tabulated like the
Stephenson.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Derived, Key, group
from corliss.keys.toml_table import Table
from corliss.valves.gear import GearType, register
from corliss.valves.newton import newton2
from corliss.valves.slide_valve import (ALLEN_KEYS, ANGULAR_ADVANCE, ECCENTRICITY, LAP_KEYS,
                                        PORT_KEYS, LappedValve, parse_allen_passage,
                                        parse_ports)

#: The link motions, by the ``link`` key's values.
KINDS = ("stephenson_open", "stephenson_crossed", "gooch", "allen")


@dataclass(frozen=True)
class LinkMotionSpec:
    """A link motion, in Zeuner's form or solved exactly (all SI).

    Parameters
    ----------
    kind : str
        One of :data:`~corliss.valves.link_motion.KINDS`: ``"stephenson_open"``,
        ``"stephenson_crossed"``, ``"gooch"`` or ``"allen"``.
    eccentricity_m : float
        Throw r of both eccentrics [m].
    angular_advance_rad : float
        Angular advance delta of both eccentrics [rad].
    eccentric_rod_m : float
        Eccentric rod length g [m].
    half_link_m : float
        Half the chord of the link, c [m].
    block_m : float
        Offset u of the block from the link's centre [m], the setting, in [-c, c]
        (c full gear ahead, 0 mid gear, -c full gear astern).
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
    allen_ratio : float, optional
        k = u1 / u, the link's own share of the block's offset, for the Allen link
        [-] (Spangler Art. 73; see :func:`allen_book_ratio`).
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (the linkage solved; see the module doc).
    link_radius_m : float or None, optional
        Radius of the link's arc [m]; None for the default: g for the Stephenson,
        g1 for the Gooch (the Allen link is straight).
    hanger_m : float or None, optional
        Length of the exact Stephenson link's hanger [m]; None for an infinitely
        long one.
    radius_rod_m : float or None, optional
        g1, the Gooch or Allen radius rod [m]; None for g.
    allen_passage_m : float or None, optional
        Width of the mouth of an Allen (trick) valve's passage [m] (Spangler
        Art. 27); None for a plain valve.
    """

    kind: str
    eccentricity_m: float
    angular_advance_rad: float
    eccentric_rod_m: float
    half_link_m: float
    block_m: float
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1
    allen_ratio: float = 0.5
    motion: str = "zeuner"
    link_radius_m: float | None = None
    hanger_m: float | None = None
    radius_rod_m: float | None = None
    allen_passage_m: float | None = None

    def coefficients(self, u: float | None = None) -> tuple[float, float]:
        """The virtual eccentric of Zeuner's form, ``x = C cos(theta) + S sin(theta)``
        (Spangler Arts. 46, 55, 65, 73; the formulas are in the module doc).

        Parameters
        ----------
        u : float or None, optional
            Block offset from the link's centre [m]; None for the spec's ``block_m``.

        Returns
        -------
        C, S : float
            Coefficients [m]: ``C`` is the valve's displacement at head-end dead
            centre (lap + lead), ``hypot(C, S)`` the virtual eccentric's throw.
        """
        r, d, g, c = (self.eccentricity_m, self.angular_advance_rad, self.eccentric_rod_m,
                      self.half_link_m)
        u = self.block_m if u is None else u
        sd, cd = math.sin(d), math.cos(d)
        if self.kind == "stephenson_open":
            return r * (sd + (c * c - u * u) / (c * g) * cd), u * r / c * cd
        if self.kind == "stephenson_crossed":
            return r * (sd - (c * c - u * u) / (c * g) * cd), -u * r / c * cd
        if self.kind == "gooch":
            return r * (sd + c / g * cd), u * r / c * (cd - c / g * sd)
        u1 = self.allen_ratio * u
        return (r * (sd + (c * c - u * u1) / (c * g) * cd),
                u * r / c * cd - r * (u - u1) / g * sd)

    @property
    def setting_range(self) -> tuple[float, float]:
        """Range of the setting (block offset u) [m]."""
        return (-self.half_link_m, self.half_link_m)


class LinkMotion(LappedValve):
    """A link motion (Zeuner's form or the exact linkage) driving a lapped slide valve.

    Its setting is the block offset as a fraction of the half link, ``u / c``.

    Parameters
    ----------
    spec : LinkMotionSpec
        The link, its eccentrics and rods, and the valve's laps and ports.
    """

    name = "link_motion"
    summary = ("link motions, Zeuner's form or exact: Stephenson open or crossed rods, Gooch, "
               "Allen "
               "(Spangler Chs. VII-XI); setting = block offset u / c")

    setting_name = "block offset u / c (1 full gear ahead, 0 mid gear, -1 full gear astern)"
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: LinkMotionSpec):
        self.spec = spec
        self._exact = None
        if spec.motion == "exact":
            self._exact = (_ExactStephenson(spec) if spec.kind.startswith("stephenson")
                           else _ExactGoochAllen(spec))

    def _at_setting(self, value: float) -> "LinkMotion":
        import dataclasses
        return LinkMotion(dataclasses.replace(self.spec, block_m=value * self.spec.half_link_m))

    def travel(self, theta):
        if self._exact is not None:
            return self._exact(theta)
        return self.zeuner_travel(theta)

    def joints(self, theta: float) -> "StephensonJoints | GoochAllenJoints":
        """The exact link's joints at crank angle ``theta``, from the solve that gives
        :meth:`travel` (for Stephenson's, its valve positions splined from 1/2 deg).

        Parameters
        ----------
        theta : float
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        StephensonJoints or GoochAllenJoints
            The joints [m] and the valve's displacement [m].

        Raises
        ------
        ValueError
            For a gear in Zeuner's form (not solved as a linkage).
        """
        if self._exact is None:
            raise ValueError(f"joints are solved for the exact links only (this is "
                             f"{self.spec.kind} in Zeuner's form)")
        return self._exact.joints(theta)

    def zeuner_travel(self, theta):
        """Valve displacement of Zeuner's form, ``C cos(theta) + S sin(theta)`` with
        ``(C, S)`` from :meth:`LinkMotionSpec.coefficients`.

        Parameters
        ----------
        theta : ndarray
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


class _ExactStephenson:
    """The Stephenson link solved as a linkage, tabulated and splined (see module doc)."""

    N = 720

    def __init__(self, spec: LinkMotionSpec):
        from scipy.interpolate import CubicSpline
        self.spec = spec
        th = np.linspace(0.0, 2 * math.pi, self.N + 1)
        ref = _block_x(spec, spec.half_link_m, np.array([0.0, math.pi]))
        self.x_ref = 0.5 * (ref[0] + ref[1])            # equal lead in full forward gear
        self.linkage = _StephensonLinkage(spec, spec.block_m)
        self.poses = self.linkage.poses(th)
        X = np.array([self.linkage.block(p)[0] for p in self.poses])
        x = -(X - self.x_ref)
        x[-1] = x[0]
        self._spline = CubicSpline(th, x, bc_type="periodic")

    def __call__(self, theta):
        return self._spline(np.asarray(theta, dtype=float) % (2 * math.pi))

    def joints(self, theta: float) -> "StephensonJoints":
        """The linkage at crank angle ``theta`` [rad]: the pose solved from the table's
        nearest pose, with the table's hanger (see :class:`StephensonJoints`)."""
        lk, spec = self.linkage, self.spec
        th = float(theta) % (2 * math.pi)
        k = int(round(th / (2 * math.pi) * self.N)) % self.N
        pose = lk.solve(self.poses[k].copy(), th)
        f, b = lk.eccentrics(th)
        top, bottom = lk.link_point(pose, lk.psi_c), lk.link_point(pose, -lk.psi_c)
        n = np.array([math.cos(pose[2]), math.sin(pose[2])])
        centre = pose[:2] - lk.rho * n
        block = lk.block(pose)

        def pt(v):
            return (float(v[0]), float(v[1]))

        return StephensonJoints(
            shaft=(0.0, 0.0), forward_eccentric=pt(f), backward_eccentric=pt(b),
            link_top=pt(top), link_bottom=pt(bottom), link_middle=pt(pose[:2]),
            link_centre=pt(centre), block=pt(block),
            hanger_top=None if lk.suspension is None else pt(lk.suspension),
            top_is_forward=lk.top_is_forward, eccentric_rod_m=spec.eccentric_rod_m,
            link_radius_m=lk.rho, hanger_m=lk.h, valve_m=float(-(block[0] - self.x_ref)),
            rods_m=_stephenson_rods(spec, lk))


def _stephenson_rods(spec: LinkMotionSpec, lk: _StephensonLinkage) -> dict:
    fwd, back = ("link_top", "link_bottom") if lk.top_is_forward else ("link_bottom", "link_top")
    rods = {"forward eccentric": (spec.eccentricity_m, "shaft", "forward_eccentric"),
            "backward eccentric": (spec.eccentricity_m, "shaft", "backward_eccentric"),
            "forward eccentric rod": (spec.eccentric_rod_m, "forward_eccentric", fwd),
            "backward eccentric rod": (spec.eccentric_rod_m, "backward_eccentric", back),
            "link top, radius": (lk.rho, "link_centre", "link_top"),
            "link bottom, radius": (lk.rho, "link_centre", "link_bottom"),
            "link middle, radius": (lk.rho, "link_centre", "link_middle"),
            "block, radius": (lk.rho, "link_centre", "block")}
    if lk.h is not None:
        rods["hanger"] = (lk.h, "hanger_top", "link_middle")
    return rods


@dataclass(frozen=True)
class StephensonJoints:
    """The joints of the exact Stephenson link at one crank angle (all SI; see the
    module doc): shaft at the origin, the valve spindle's line along X (y = 0), the link
    on the cylinder's side (X > 0).

    Parameters
    ----------
    shaft, forward_eccentric, backward_eccentric : tuple of float
        The shaft's centre and the two eccentrics' centres (x, y) [m].
    link_top, link_bottom : tuple of float
        The rods' pins at the link's ends (x, y) [m]; the forward rod drives the bottom
        one unless ``top_is_forward`` (crossed rods).
    link_middle, link_centre : tuple of float
        The link's middle (hung from the hanger) and the centre of its arc (x, y) [m].
    block : tuple of float
        The block, where the link's arc crosses the spindle's line (x, y) [m].
    hanger_top : tuple of float or None
        The hanger's top, held by the reversing lever (x, y) [m]; None for an
        infinitely long hanger (the link's middle held at height -u).
    top_is_forward : bool
        Whether the forward eccentric's rod drives the link's top.
    eccentric_rod_m, link_radius_m : float
        The rods' length and the link's radius [m].
    hanger_m : float or None
        The hanger's length [m].
    valve_m : float
        The valve's displacement in the sense that opens the head steam port [m]: the
        block's X, reversed through the rocker, from its mean in full forward gear.
    rods_m : dict
        Each rod, eccentric, hanger, and the link's radius to its pins, middle and block:
        ``{name: (length [m], joint, joint)}``.
    """

    shaft: tuple[float, float]
    forward_eccentric: tuple[float, float]
    backward_eccentric: tuple[float, float]
    link_top: tuple[float, float]
    link_bottom: tuple[float, float]
    link_middle: tuple[float, float]
    link_centre: tuple[float, float]
    block: tuple[float, float]
    hanger_top: tuple[float, float] | None
    top_is_forward: bool
    eccentric_rod_m: float
    link_radius_m: float
    hanger_m: float | None
    valve_m: float
    rods_m: dict


class _ExactGoochAllen:
    """The Gooch or Allen link solved as a linkage (see module doc): a vectorised Newton
    solve of the link's pose at the crank angles asked for, then the block and stem in
    closed form (cheap enough not to need a table)."""

    def __init__(self, spec: LinkMotionSpec):
        self.spec = spec
        ref = _stem_x(spec, spec.half_link_m, np.array([0.0, math.pi]))
        self._x_ref = 0.5 * (ref[0] + ref[1])           # equal lead in full forward gear

    def __call__(self, theta):
        t = np.asarray(theta, dtype=float)
        return -(_stem_x(self.spec, self.spec.block_m, t).reshape(np.shape(t)) - self._x_ref)

    def joints(self, theta: float) -> GoochAllenJoints:
        """The linkage at crank angle ``theta`` [rad] (see :class:`GoochAllenJoints`)."""
        spec = self.spec
        pts = _gooch_allen_points(spec, spec.block_m, np.array([float(theta)]))
        p = {name: (float(v[0, 0]), float(v[1, 0])) for name, v in pts.items()}
        g, r = spec.eccentric_rod_m, spec.eccentricity_m
        rods = {"forward eccentric": (r, "shaft", "forward_eccentric"),
                "backward eccentric": (r, "shaft", "backward_eccentric"),
                "forward eccentric rod": (g, "forward_eccentric", "link_bottom"),
                "backward eccentric rod": (g, "backward_eccentric", "link_top"),
                "radius rod": (spec.radius_rod_m or g, "block", "stem")}
        if "link_centre" in p:
            rho = spec.link_radius_m or spec.radius_rod_m or g
            for name in ("link_top", "link_bottom", "link_middle", "block"):
                rods[f"{name.replace('_', ' ')}, radius"] = (rho, "link_centre", name)
        else:
            rods["half link, top"] = (spec.half_link_m, "link_middle", "link_top")
            rods["half link, bottom"] = (spec.half_link_m, "link_middle", "link_bottom")
        return GoochAllenJoints(points=p, rods_m=rods, valve_m=-(p["stem"][0] - self._x_ref))


def _stem_x(spec: LinkMotionSpec, u: float, theta: np.ndarray) -> np.ndarray:
    """X of the valve stem's end of the radius rod (from the shaft, along the line of
    stroke) of the exact Gooch or Allen gear at crank angles ``theta``, block offset u."""
    return _gooch_allen_points(spec, u, theta)["stem"][0]


def _gooch_allen_points(spec: LinkMotionSpec, u: float, theta: np.ndarray) -> dict:
    """Every joint of the exact Gooch or Allen gear at crank angles ``theta``, block
    offset u (arrays of shape (2, n) [m]; ``link_centre`` only for Gooch's curved link)."""
    r, d, g, c = (spec.eccentricity_m, spec.angular_advance_rad, spec.eccentric_rod_m,
                  spec.half_link_m)
    g1 = spec.radius_rod_m or g
    gooch = spec.kind == "gooch"
    k = 0.0 if gooch else spec.allen_ratio
    ym = k * u                      # the link's middle, lifted u1 = k u
    yb = -(1.0 - k) * u             # the radius rod's end, dropped u - u1
    rho = (spec.link_radius_m or g1) if gooch else None
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    # forward eccentric on the lower end, as for the open-rod Stephenson above
    fx, fy = r * np.cos(th + math.pi / 2 + d), r * np.sin(th + math.pi / 2 + d)
    bx, by = r * np.cos(th - math.pi / 2 - d), r * np.sin(th - math.pi / 2 - d)

    def ends(xm, a):
        """(top, bottom) pin positions of the link with middle (xm, ym), normal angle a."""
        nx, ny, tx, ty = np.cos(a), np.sin(a), -np.sin(a), np.cos(a)
        if gooch:                   # arc concave to the valve, pins on the arc
            cpsi = math.sqrt(1.0 - (c / rho) ** 2)
            # point at arc angle psi: K - rho cos(psi) n + rho sin(psi) t, K = M + rho n
            ox, oy = xm + rho * (1.0 - cpsi) * nx, ym + rho * (1.0 - cpsi) * ny
        else:
            ox, oy = xm, ym
        return (ox + c * tx, oy + c * ty), (ox - c * tx, oy - c * ty)

    def residual(xm, a):
        (ux, uy), (lx, ly) = ends(xm, a)
        return (np.hypot(ux - bx, uy - by) - g, np.hypot(lx - fx, ly - fy) - g)

    xm = np.full(th.shape, math.sqrt(g * g - c * c))
    a = np.zeros(th.shape)
    xm, a = newton2(residual, xm, a, 1e-7 * g, 1e-7, 1e-14 * g, 1e-14)
    out = {}
    if gooch:                       # the block: where the arc (shaft side) meets y = yb
        assert rho is not None      # a Gooch link's radius, set above
        kx, ky = xm + rho * np.cos(a), ym + rho * np.sin(a)
        px = kx - np.sqrt(rho * rho - (yb - ky) ** 2)
        out["link_centre"] = np.array([kx, ky])
    else:                           # where the straight link meets y = yb
        px = xm - (yb - ym) / np.cos(a) * np.sin(a)
    top, bottom = ends(xm, a)
    n = th.size
    out.update({"shaft": np.zeros((2, n)), "forward_eccentric": np.array([fx, fy]),
                "backward_eccentric": np.array([bx, by]), "link_top": np.array(top),
                "link_bottom": np.array(bottom), "link_middle": np.array([xm, np.full(n, ym)]),
                "block": np.array([px, np.full(n, yb)]),
                "stem": np.array([px + math.sqrt(g1 * g1 - yb * yb), np.zeros(n)])})
    return out


@dataclass(frozen=True)
class GoochAllenJoints:
    """The joints of the exact Gooch or Allen link at one crank angle (all SI; see the
    module doc): shaft at the origin, the valve stem's line along X (y = 0), the link on
    the cylinder's side; each point an (x, y) pair [m].

    Parameters
    ----------
    points : dict
        Each joint by name: ``shaft``, ``forward_eccentric``, ``backward_eccentric``,
        ``link_top``, ``link_bottom`` (the rods' pins; the forward rod drives the
        bottom), ``link_middle``, ``block`` (where the radius rod takes hold), ``stem``
        (the radius rod's end on the stem's line) and, for Gooch's curved link,
        ``link_centre`` [m].
    rods_m : dict
        Each rod, eccentric and the link's radius to its pins and block: ``{name:
        (length [m], joint, joint)}``.
    valve_m : float
        The valve's displacement in the sense that opens the head steam port [m]: the
        stem's X, reversed, from its mean in full forward gear.
    """

    points: dict
    rods_m: dict
    valve_m: float


def _block_x(spec: LinkMotionSpec, u: float, theta: np.ndarray) -> np.ndarray:
    """X of the block (along the valve spindle's line, from the shaft) at crank angles
    ``theta`` with the reversing lever set for block offset ``u`` [m]."""
    linkage = _StephensonLinkage(spec, u)
    return np.array([linkage.block(p)[0] for p in linkage.poses(theta)])


class _StephensonLinkage:
    """The exact Stephenson link at one block offset u: the link's pose (xm, ym, a), its
    middle and the angle of its normal, solved by Newton's method per crank angle."""

    def __init__(self, spec: LinkMotionSpec, u: float):
        self.spec = spec
        r, d, g, c = (spec.eccentricity_m, spec.angular_advance_rad, spec.eccentric_rod_m,
                      spec.half_link_m)
        self.rho = spec.link_radius_m or g
        self.h = spec.hanger_m
        self.psi_c = math.asin(c / self.rho)
        # The books' open-rod formula (lead rising toward mid gear) holds when the rods are
        # uncrossed with the crank on the dead centre away from the link; here, with the
        # link on the cylinder's side of the shaft, the forward eccentric then drives the
        # lower end of the link (the upper, with crossed rods).  The figure is the mirror
        # of the books': a positive u (open rods, ahead) raises the link here.
        self.top_is_forward = spec.kind == "stephenson_crossed"
        self.lift = -u                          # the link's middle sits at y = -lift
        self.x0 = math.sqrt(g * g - c * c) + self.rho * (1 - math.cos(self.psi_c))
        # hanger top: over the link's mean position, at height h - u (infinite hanger: y = -u)
        self.suspension = None

    def eccentrics(self, th: float):
        """Centres of the (forward, backward) eccentrics at crank angle ``th``."""
        r, d = self.spec.eccentricity_m, self.spec.angular_advance_rad
        f = np.array([math.cos(th + math.pi / 2 + d), math.sin(th + math.pi / 2 + d)]) * r
        b = np.array([math.cos(th - math.pi / 2 - d), math.sin(th - math.pi / 2 - d)]) * r
        return f, b

    def link_point(self, pose, psi):
        """The point of the link's arc at arc angle ``psi`` from its middle."""
        xm, ym, a = pose
        n = np.array([math.cos(a), math.sin(a)])
        t = np.array([-math.sin(a), math.cos(a)])
        k = np.array([xm, ym]) - self.rho * n
        return k + self.rho * (math.cos(psi) * n + math.sin(psi) * t)

    def residual(self, pose, th):
        g = self.spec.eccentric_rod_m
        f, b = self.eccentrics(th)
        top, bottom = (f, b) if self.top_is_forward else (b, f)
        e1 = np.linalg.norm(self.link_point(pose, self.psi_c) - top) - g
        e2 = np.linalg.norm(self.link_point(pose, -self.psi_c) - bottom) - g
        if self.suspension is None:
            e3 = pose[1] + self.lift
        else:
            e3 = math.hypot(pose[0] - self.suspension[0], pose[1] - self.suspension[1]) - self.h
        return np.array([e1, e2, e3])

    def solve(self, pose, th):
        """The link's pose at crank angle ``th`` by Newton's method from ``pose``."""
        g = self.spec.eccentric_rod_m
        for _ in range(50):
            res = self.residual(pose, th)
            J = np.empty((3, 3))
            for j in range(3):
                dp = np.zeros(3)
                dp[j] = 1e-7 * (1.0 if j == 2 else max(g, 1.0))
                J[:, j] = (self.residual(pose + dp, th) - res) / dp[j]
            step = np.linalg.solve(J, -res)
            pose = pose + step
            if np.max(np.abs(step[:2])) < 1e-13 * g and abs(step[2]) < 1e-13:
                break
        return pose

    def block(self, pose):
        """The block: the point of the link's arc on the spindle's line y = 0."""
        lo, hi = -math.pi / 2, math.pi / 2
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if self.link_point(pose, mid)[1] < 0.0:
                lo = mid
            else:
                hi = mid
        return self.link_point(pose, 0.5 * (lo + hi))

    def poses(self, theta):
        """The link's pose at each crank angle of ``theta``, each solve started from the
        last; with a hanger, a second pass with the hanger hung over the link's mean
        position in the first."""
        self.suspension = None
        out = []
        pose = np.array([self.x0, -self.lift, 0.0])
        for th in theta:
            pose = self.solve(pose, th)
            out.append(pose)
        if self.h is not None:
            self.suspension = (float(np.mean([p[0] for p in out])), self.h - self.lift)
            out = []
            pose = np.array([self.x0, -self.lift, 0.0])
            for th in theta:
                pose = self.solve(pose, th)
                out.append(pose)
        return out


def allen_book_ratio(g: float, g1: float) -> float:
    """u1 / u of the Allen link from Spangler Art. 73's rocker proportions [-].

    The book gives u1 = u / (1 + (hj lk)/(ji lm)) and lk/lm = (ij/de)(1 + sqrt(1 +
    de/hj)), with de the eccentric rod g and hj the radius rod g1, so
    u1/u = 1 / (1 + (g1/g)(1 + sqrt(1 + g/g1))): 1/(2 + sqrt 2) = 0.293 for equal rods.
    That is exactly the ratio at which the valve's central position does not move with
    the setting: lifting a straight link u1 pulls the block towards the shaft by
    (u1^2 - 2 u u1)/(2 g) on average over a turn, dropping the radius rod's end u - u1
    pulls the stem by (u - u1)^2/(2 g1), and the two cancel when
    (1 - k)^2 g = k (2 - k) g1 (derived here; see tests/test_link_motion.py).

    Parameters
    ----------
    g : float
        Eccentric rod length de [m].
    g1 : float
        Radius rod length hj [m].

    Returns
    -------
    float
        k = u1 / u [-], from 0 (Gooch) to 1 (Stephenson's open rods).
    """
    q = g1 / g
    return 1.0 / (1.0 + q * (1.0 + math.sqrt(1.0 + 1.0 / q)))


LINK_MOTION_KEYS = group(
    "link_motion", "A reversing link motion (Stephenson's, Gooch's, Allen's) driving a "
    "lapped slide valve.",
    Key("link", "choice", "The kind of link.", choices=KINDS),
    ECCENTRICITY, ANGULAR_ADVANCE,
    Key("eccentric_rod", "length", "Each eccentric rod.", within=POSITIVE_LENGTH, unit="in"),
    Key("half_link", "length", "Half the link's chord c.", within=POSITIVE_LENGTH, unit="in"),
    Key("block", "length", "Offset u of the block from the link's middle, the notch: from "
        "half_link (full gear ahead) through 0 (mid gear) to -half_link (full gear astern); "
        "the cut-off follows from it (corliss design SCENE --cutoff F gives u / half_link).",
        unit="in"),
    Key("radius_rod", "length", "Radius rod, longer than the half link; absent: infinitely "
        "long.", default=None, within=POSITIVE_LENGTH, unit="in",
        when="with link = \"gooch\" or \"allen\""),
    Key("allen_ratio", "number", "Allen's ratio, 0 (Gooch) to 1 (Stephenson).",
        default=Derived("the book's ratio from the rods"), within=(0.0, 1.0),
        when="with link = \"allen\""),
    Key("motion", "choice", "Zeuner's motion (infinite rods) or the exact linkage.",
        default="zeuner", choices=("zeuner", "exact")),
    Key("link_radius", "length", "Radius of the link's arc, above the half link; absent: "
        "the book's (Stephenson: the eccentric rod).", default=None, within=POSITIVE_LENGTH,
        unit="in", when="except with link = \"allen\" (straight)"),
    Key("hanger", "length", "The link's hanger (Stephenson links only); absent: an "
        "infinitely long one.", default=None, within=POSITIVE_LENGTH, unit="in",
        when="with a Stephenson link"),
    LAP_KEYS, ALLEN_KEYS, PORT_KEYS,
)


def parse_link_motion(t: Table) -> LinkMotionSpec:
    """Read a ``[valve_gear] type = "link_motion"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`LINK_MOTION_KEYS`.

    Returns
    -------
    LinkMotionSpec
        The gear's spec.
    """
    t = t.bound(LINK_MOTION_KEYS)
    kind = t.get("link")
    r = t.get("eccentricity")
    delta = t.get("angular_advance")
    g = t.get("eccentric_rod")
    c = t.get("half_link")
    u = t.get("block")
    if abs(u) > c:
        raise InputError(t.key("block"), t.raw("block"),
                         f"a block offset within the link, -{c / 0.0254:.4g} in to "
                         f"{c / 0.0254:.4g} in (the half chord)")
    g1 = None
    if kind in ("gooch", "allen") and t.has("radius_rod"):
        g1 = t.get("radius_rod")
        if g1 <= c:
            raise InputError(t.key("radius_rod"), t.raw("radius_rod"),
                             "a radius rod longer than the half link")
    k = t.get("allen_ratio", allen_book_ratio(g, g1 or g)) if kind == "allen" else 0.5
    if not 0.0 <= k <= 1.0:
        raise InputError(t.key("allen_ratio"), k, "a ratio from 0 (Gooch) to 1 (Stephenson)")
    motion = t.get("motion")
    rho = t.get("link_radius")
    hanger = t.get("hanger")
    if rho is not None and rho <= c:
        raise InputError(t.key("link_radius"), t.raw("link_radius"), "a radius above the half link")
    if kind == "allen" and rho is not None:
        raise InputError(t.key("link_radius"), t.raw("link_radius"),
                         "no link_radius: the Allen link is straight (Spangler Art. 72)")
    if not kind.startswith("stephenson") and hanger is not None:
        raise InputError(t.key("hanger"), t.raw("hanger"), "no hanger: the exact Gooch and "
                         "Allen links are hung from infinitely long rods")
    spec = LinkMotionSpec(kind, r, delta, g, c, u, t.get("lap"), t.get("exhaust_lap"),
                          allen_ratio=k,
                          motion=motion, link_radius_m=rho, hanger_m=hanger, radius_rod_m=g1,
                          allen_passage_m=parse_allen_passage(t), **parse_ports(t))
    C, S = spec.coefficients()
    reach = math.hypot(C, S)
    for end, lap in zip(("head", "crank"), spec.lap_m):
        if lap >= reach:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap below the virtual eccentric's throw at this block "
                             f"({reach / 0.0254:.4g} in): the {end}-end port never opens")
    return spec


register(GearType("link_motion", LinkMotion.summary, parse_link_motion, LinkMotion,
                  LINK_MOTION_KEYS))
