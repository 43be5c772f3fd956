"""Link motions in Zeuner's form: Stephenson (open and crossed rods), Gooch, Allen.

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
arms (k = 1 is Stephenson's open rods, k = 0 Gooch's fixed link).

``motion = "exact"`` (Stephenson only, for now) solves the linkage itself at every
crank angle: the eccentric centres on their circles, rods of length g pinned to the
ends of a link curved to radius rho (concave to the shaft, pins on the arc, Peabody's
condition 1), the link hung at its middle from a hanger of length h whose top the
reversing lever holds at height h - u, and the block riding on the link where it
crosses the valve spindle's line through the shaft (so the block slips).  The valve
is set for equal lead in full forward gear.  The solution is tabulated once at 1/2 deg
and read back through a periodic cubic spline.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.tables import Table
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import LappedValve, pair, parse_ports

KINDS = ("stephenson_open", "stephenson_crossed", "gooch", "allen")


@dataclass(frozen=True)
class LinkMotionSpec:
    """A link motion in Zeuner's form (all SI).

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    eccentricity_m, angular_advance_rad : float
        Throw r [m] and angular advance delta [rad] of both eccentrics.
    eccentric_rod_m : float
        Eccentric rod length g [m].
    half_link_m : float
        Half the chord of the link, c [m].
    block_m : float
        Offset u of the block from the link's centre [m], the setting, in [-c, c].
    allen_ratio : float
        u1 / u for the Allen link [-].
    lap_m, exhaust_lap_m, port_width_m, port_length_m, discharge_coefficient,
    ports_per_end : as for the slide valve.
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

    def coefficients(self, u: float | None = None) -> tuple[float, float]:
        """(C, S) of x = C cos(theta) + S sin(theta) [m] at block offset ``u`` [m]."""
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
    """A link motion (Zeuner form) driving a lapped slide valve."""

    name = "link_motion"
    summary = ("link motions in Zeuner's form: Stephenson open or crossed rods, Gooch, Allen "
               "(Spangler Chs. VII-XI); setting = block offset")

    setting_name = "block offset u / c (1 full gear ahead, 0 mid gear, -1 full gear astern)"
    setting_range = (-1.0, 1.0)

    def __init__(self, spec: LinkMotionSpec):
        self.spec = spec
        self._exact = None
        if spec.motion == "exact":
            self._exact = _ExactStephenson(spec)

    def with_setting(self, value: float) -> "LinkMotion":
        import dataclasses
        lo, hi = self.setting_range
        if not lo <= value <= hi:
            raise ValueError(f"setting {value} outside {self.setting_range}")
        return LinkMotion(dataclasses.replace(self.spec, block_m=value * self.spec.half_link_m))

    def travel(self, theta):
        if self._exact is not None:
            return self._exact(theta)
        return self.zeuner_travel(theta)

    def zeuner_travel(self, theta):
        """Valve displacement of Zeuner's form [m]."""
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
        x_ref = 0.5 * (ref[0] + ref[1])                 # equal lead in full forward gear
        X = _block_x(spec, spec.block_m, th)
        x = -(X - x_ref)
        x[-1] = x[0]
        self._spline = CubicSpline(th, x, bc_type="periodic")

    def __call__(self, theta):
        return self._spline(np.asarray(theta, dtype=float) % (2 * math.pi))


def _block_x(spec: LinkMotionSpec, u: float, theta: np.ndarray) -> np.ndarray:
    """X of the block (along the valve spindle's line, from the shaft) at crank angles
    ``theta`` with the reversing lever set for block offset ``u`` [m]."""
    r, d, g, c = spec.eccentricity_m, spec.angular_advance_rad, spec.eccentric_rod_m, spec.half_link_m
    rho = spec.link_radius_m or g
    h = spec.hanger_m
    psi_c = math.asin(c / rho)
    # Open rods are uncrossed with the crank on the dead centre away from the link (the
    # books' formula, with the lead rising toward mid gear, holds for that arrangement):
    # here, with the link on the cylinder's side of the shaft, the forward eccentric
    # then drives the lower end of the link.
    # The books' open-rod formula (lead rising toward mid gear) holds when the rods are
    # uncrossed with the crank on the dead centre away from the link; here, with the
    # link on the cylinder's side of the shaft, the forward eccentric then drives the
    # lower end of the link (the upper, with crossed rods).  The figure is the mirror
    # of the books': a positive u (open rods, ahead) raises the link here.
    top_is_forward = spec.kind == "stephenson_crossed"
    lift = -u                               # the link's middle sits at y = -lift

    def link_point(pose, psi):
        xm, ym, a = pose
        n = np.array([math.cos(a), math.sin(a)])
        t = np.array([-math.sin(a), math.cos(a)])
        k = np.array([xm, ym]) - rho * n
        return k + rho * (math.cos(psi) * n + math.sin(psi) * t)

    x0 = math.sqrt(g * g - c * c) + rho * (1 - math.cos(psi_c))
    # hanger top: over the link's mean position, at height h - u (infinite hanger: y = -u)
    suspension = None

    def residual(pose, th):
        f = np.array([math.cos(th + math.pi / 2 + d), math.sin(th + math.pi / 2 + d)]) * r
        b = np.array([math.cos(th - math.pi / 2 - d), math.sin(th - math.pi / 2 - d)]) * r
        top, bottom = (f, b) if top_is_forward else (b, f)
        e1 = np.linalg.norm(link_point(pose, psi_c) - top) - g
        e2 = np.linalg.norm(link_point(pose, -psi_c) - bottom) - g
        if suspension is None:
            e3 = pose[1] + lift
        else:
            e3 = math.hypot(pose[0] - suspension[0], pose[1] - suspension[1]) - h
        return np.array([e1, e2, e3])

    def solve(pose, th):
        for _ in range(50):
            res = residual(pose, th)
            J = np.empty((3, 3))
            for j in range(3):
                dp = np.zeros(3)
                dp[j] = 1e-7 * (1.0 if j == 2 else max(g, 1.0))
                J[:, j] = (residual(pose + dp, th) - res) / dp[j]
            step = np.linalg.solve(J, -res)
            pose = pose + step
            if np.max(np.abs(step[:2])) < 1e-13 * g and abs(step[2]) < 1e-13:
                break
        return pose

    def block(pose):
        lo, hi = -math.pi / 2, math.pi / 2      # the point of the arc on y = 0
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if link_point(pose, mid)[1] < 0.0:
                lo = mid
            else:
                hi = mid
        return link_point(pose, 0.5 * (lo + hi))[0]

    poses = []
    pose = np.array([x0, -lift, 0.0])
    for th in theta:
        pose = solve(pose, th)
        poses.append(pose)
    if h is not None:   # second pass with the hanger hung over the link's mean position
        suspension = (float(np.mean([p[0] for p in poses])), h - lift)
        poses = []
        pose = np.array([x0, -lift, 0.0])
        for th in theta:
            pose = solve(pose, th)
            poses.append(pose)
    return np.array([block(p) for p in poses])


def parse_link_motion(t: Table) -> LinkMotionSpec:
    """Read a ``[valve_gear] type = "link_motion"`` table."""
    kind = t.choice("link", KINDS)
    r = t.length("eccentricity", positive=True)
    delta = t.angle("angular_advance")
    g = t.length("eccentric_rod", positive=True)
    c = t.length("half_link", positive=True)
    u = t.length("block")
    if abs(u) > c:
        raise InputError(t.key("block"), t.raw("block"),
                         f"a block offset within the link, -{c / 0.0254:.4g} in to "
                         f"{c / 0.0254:.4g} in (the half chord)")
    k = t.number("allen_ratio", 0.5) if kind == "allen" else 0.5
    if not 0.0 <= k <= 1.0:
        raise InputError(t.key("allen_ratio"), k, "a ratio from 0 (Gooch) to 1 (Stephenson)")
    motion = t.choice("motion", ("zeuner", "exact"), "zeuner")
    if motion == "exact" and not kind.startswith("stephenson"):
        raise InputError(t.key("motion"), motion, "\"zeuner\": the exact linkage is built for "
                         "the Stephenson link only, so far")
    rho = t.length("link_radius", positive=True) if t.has("link_radius") else None
    hanger = t.length("hanger", positive=True) if t.has("hanger") else None
    if rho is not None and rho <= c:
        raise InputError(t.key("link_radius"), t.raw("link_radius"), "a radius above the half link")
    spec = LinkMotionSpec(kind, r, delta, g, c, u, pair(t, "lap", "length"),
                          pair(t, "exhaust_lap", "length", "0 in"), allen_ratio=k,
                          motion=motion, link_radius_m=rho, hanger_m=hanger, **parse_ports(t))
    C, S = spec.coefficients()
    reach = math.hypot(C, S)
    for end, lap in zip(("head", "crank"), spec.lap_m):
        if lap >= reach:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap below the virtual eccentric's throw at this block "
                             f"({reach / 0.0254:.4g} in): the {end}-end port never opens")
    return spec


register(GearType("link_motion", LinkMotion.summary, parse_link_motion, LinkMotion))
