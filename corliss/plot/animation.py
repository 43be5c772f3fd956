"""Moving pictures of a valve gear: the linkage turning with the crank, the valve over
its ports, the port openings against crank angle and the indicator card traced as the
crank turns.

Every position drawn comes from the gear's own solve: a gear that solves its linkage
exactly gives its joints at a crank angle (``gear.joints(theta)``: the plain slide
valve's eccentric and rod, the exact Stephenson, Gooch and Allen links, the exact radial
gears
(Walschaerts, Joy, Hackworth, Marshall, Angstrom) and the Baker gear, the oscillating
cylinder swinging on its trunnion (its port face drawn developed flat, the cylinder's
ports over the standard's), the Corliss wrist plate with its four
valves and trip), the same solve its valve travel and
port openings come from; any other gear with one lapped valve is drawn from its travel
alone (the crank, its virtual eccentric and the valve over its ports, the linkage not
drawn).  The Porter-Allen gear is drawn from its own rock shaft and valve travels: the
crank, the rock shaft's arms at the gear's angle, and its four flat valves over their
ports, each steam plate uncovering its ``steam_openings`` ports at once
(:mod:`corliss.plot.plate_valves`); its Fink link is not drawn.  A gear of a main and a
cut-off valve (the double valves) is not drawn.  The valve
section is schematic in its proportions (bridges and exhaust port) but exact in its
edges: the laps, the port widths and the valve's displacement are the gear's.

:func:`animate_gear` returns the figure, the ``FuncAnimation`` and the function that
draws frame ``i``; :func:`write_animation` writes it as GIF (Pillow) or HTML
(``to_jshtml``).  matplotlib is imported when a figure is first drawn.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from corliss.keys import units
from corliss.valves.baker import BakerGear
from corliss.plot.plate_valves import PlateValvesPanel
from corliss.valves.corliss_gear import CorlissGear, CorlissSpec
from corliss.valves.fink_motion import PorterAllenGear
from corliss.valves.gear import openings_note
from corliss.valves.link_motion import LinkMotion, LinkMotionSpec
from corliss.valves.oscillating import OscillatingCylinder
from corliss.valves.radial_gear import JoySpec, RadialGear, SimpleRadialSpec, WalschaertsSpec
from corliss.valves.single_acting import working_gear
from corliss.valves.slide_valve import LappedValve, SlideValve

#: Colours: the moving parts black, fixed parts grey, the steam edges and ports marked.
_FIXED, _ROD, _STEAM, _EXHAUST, _TRIP = "0.55", "k", "#b03a2e", "#2e5fb0", "#c77c0e"
_PORT_STYLE = (("head steam", _STEAM, "-"), ("head exhaust", _EXHAUST, "-"),
               ("crank steam", _STEAM, "--"), ("crank exhaust", _EXHAUST, "--"))


def linkage_kind(gear) -> str:
    """Which picture :func:`animate_gear` draws of ``gear``.

    Parameters
    ----------
    gear : ValveGear
        The gear.

    Returns
    -------
    str
        ``"eccentric"`` (a plain slide valve), ``"stephenson"`` (the exact Stephenson
        link), ``"gooch_allen"`` (the exact Gooch or Allen link), ``"walschaerts"`` (the
        exact Walschaerts gear), ``"radial"`` (the exact Hackworth, Marshall, Angstrom or
        Joy gear), ``"corliss"``, ``"porter_allen"`` (the rock shaft and the four flat
        valves, the Fink link not drawn), or ``"travel"`` (a lapped valve drawn from its
        travel, the linkage not drawn).

    Raises
    ------
    ValueError
        For a gear with neither joints nor one valve's travel (the double valves, the
        Corliss gear's harmonic motion: see :func:`exact_linkage_spec`).
    """
    gear = working_gear(gear)
    if isinstance(gear, CorlissGear) and gear.spec.motion == "exact":
        return "corliss"
    if isinstance(gear, SlideValve):
        return "eccentric"
    if isinstance(gear, LinkMotion) and gear.spec.motion == "exact":
        return "stephenson" if gear.spec.kind.startswith("stephenson") else "gooch_allen"
    if isinstance(gear, RadialGear) and gear.spec.motion == "exact":
        return "walschaerts" if gear.spec.kind == "walschaerts" else "radial"
    if isinstance(gear, BakerGear):
        return "radial"
    if isinstance(gear, OscillatingCylinder):
        return "oscillating"
    if isinstance(gear, PorterAllenGear):
        return "porter_allen"
    if isinstance(gear, LappedValve):
        return "travel"
    raise ValueError(f"the {gear.name} gear has no single valve to animate")


def exact_linkage_spec(spec):
    """The spec of the gear solved as its linkage, so that it can be drawn: Zeuner's form
    of a link motion or a radial gear, or the harmonic Corliss gear, becomes
    ``motion = "exact"``; any other spec is returned as it is.

    Parameters
    ----------
    spec : object
        A gear's spec (a scene's ``gear``).

    Returns
    -------
    tuple
        (the spec, True if its motion was changed to the exact linkage).
    """
    if isinstance(spec, LinkMotionSpec) and spec.motion != "exact":
        return dataclasses.replace(spec, motion="exact"), True
    if isinstance(spec, (WalschaertsSpec, SimpleRadialSpec, JoySpec)) and spec.motion != "exact":
        return dataclasses.replace(spec, motion="exact"), True
    if isinstance(spec, CorlissSpec) and spec.motion != "exact":
        return dataclasses.replace(spec, motion="exact"), True
    return spec, False


def _unit(units_system: str) -> str:
    return "in" if units_system == "US" else "mm"


def _xy(p, scale):
    return (p[0] * scale, p[1] * scale)


def _resolve(j, ref):
    """A joint of ``j`` by field name or (field, index)."""
    if isinstance(ref, tuple):
        return getattr(j, ref[0])[ref[1]]
    points = getattr(j, "points", None)
    return points[ref] if points is not None else getattr(j, ref)


def rod_lengths(joints) -> dict:
    """Each drawn rod's length between its joints, against the spec's.

    Parameters
    ----------
    joints : EccentricJoints, StephensonJoints, WalschaertsJoints, RadialJoints or CorlissJoints
        A gear's joints at one crank angle (each has ``rods_m``).

    Returns
    -------
    dict
        ``{name: (length between the joints [m], the spec's length [m])}``.
    """
    out = {}
    for name, (length, a, b) in joints.rods_m.items():
        pa, pb = _resolve(joints, a), _resolve(joints, b)
        out[name] = (math.hypot(pa[0] - pb[0], pa[1] - pb[1]), length)
    return out


# ------------------------------------------------------------------ valve in section

def _valve_layout(gear) -> dict:
    """The seat's edges [m] of a lapped valve drawn in section: head steam port on the
    left, the exhaust port in the middle, crank steam port on the right, +x to the right.
    The bridges (3/4 of the port's width) and the exhaust port (wide enough that the
    valve's cavity never covers it) are drawn to the usual proportions; the steam edges
    and laps are the gear's."""
    s = gear.spec
    w = s.port_width_m
    bridge = 0.75 * w
    th = np.linspace(0.0, 2 * math.pi, 361)
    reach = float(np.max(np.abs(gear.travel(th))))
    exhaust = max(1.5 * w, reach + w - bridge + 0.25 * w)
    inner = 0.5 * exhaust + bridge
    inside = getattr(s, "steam", None) == "inside" or getattr(s, "admission", None) == "inside"
    return {"w": w, "inner": inner, "outer": inner + w, "exhaust": exhaust, "inside": inside,
            "sense": -1.0 if inside else 1.0, "reach": reach}


def valve_outline(gear, x_m: float, layout: dict | None = None) -> np.ndarray:
    """The outline of a lapped valve in section with its displacement ``x_m``.

    An outside-admission (D) valve moves +x with ``x_m``: its outer edges stand the
    steam laps outside the steam ports' outer edges and its cavity's edges the exhaust
    laps inside their inner edges, so the head steam port is open x - lap (Spangler
    Art. 15).  A piston valve taking steam inside moves -x: the laps change places (the
    steam laps on the cavity, which holds the steam).

    Parameters
    ----------
    gear : LappedValve
        The gear (its spec's laps and port width).
    x_m : float
        The valve's displacement in the sense that opens the head steam port [m].
    layout : dict, optional
        The seat's layout (computed from the gear if not given).

    Returns
    -------
    ndarray
        The outline's vertices, shape (8, 2) [m].
    """
    lay = layout or _valve_layout(gear)
    lh, lc = gear.spec.lap_m
    eh, ec = gear.spec.exhaust_lap_m
    if lay["inside"]:
        (oh, oc), (ch, cc) = (eh, ec), (lh, lc)
    else:
        (oh, oc), (ch, cc) = (lh, lc), (eh, ec)
    xp = lay["sense"] * x_m
    o_l, o_r = -lay["outer"] - oh + xp, lay["outer"] + oc + xp
    c_l, c_r = -lay["inner"] + ch + xp, lay["inner"] - cc + xp
    h = lay["w"]
    return np.array([(o_l, 0.0), (c_l, 0.0), (c_l, 0.6 * h), (c_r, 0.6 * h), (c_r, 0.0),
                     (o_r, 0.0), (o_r, h), (o_l, h)])


def _draw_seat(ax, lay, scale):
    from matplotlib.patches import Rectangle
    w, inner, outer = lay["w"] * scale, lay["inner"] * scale, lay["outer"] * scale
    depth = 1.2 * w
    far = outer + 1.2 * w + lay["reach"] * scale
    for x0, x1 in ((-far, -outer), (-inner, -0.5 * lay["exhaust"] * scale),
                   (0.5 * lay["exhaust"] * scale, inner), (outer, far)):
        ax.add_patch(Rectangle((x0, -depth), x1 - x0, depth, facecolor="0.82",
                               edgecolor=_FIXED, hatch="///", lw=0.6))
    exh_c = _STEAM if lay["inside"] else _EXHAUST
    for x0, lab in ((-outer, "head\nport"), (inner, "crank\nport")):
        ax.text(x0 + 0.5 * w, -depth * 1.08, lab, ha="center", va="top", fontsize=7)
    ax.text(0.0, -depth * 1.08, "steam" if lay["inside"] else "exhaust", ha="center",
            va="top", fontsize=7, color=exh_c)
    outside_lab = "exhaust" if lay["inside"] else "steam chest"
    ax.text(-far * 0.95, 1.25 * w, outside_lab, fontsize=7,
            color=_EXHAUST if lay["inside"] else _STEAM)
    ax.set_xlim(-far, far)
    ax.set_ylim(-depth * 1.9, 3.2 * w)
    ax.set_aspect("equal")
    ax.axis("off")


def _draw_port_face(ax, gear, scale) -> list:
    """An oscillating cylinder's port face developed flat along its arc (arc length
    rho psi to the right): the standard's steam and exhaust ports fixed, one row for
    each end (the crank end's below, its steam port on the other side of the line of
    centres, as the swing meets it), and the cylinder's port of each end drawn over them
    where its travel puts it.  Returns the cylinder's ports (patches to move)."""
    from matplotlib.patches import Rectangle
    s = gear.spec
    rho, h = s.port_radius_m, s.port_length_m
    rows = [(0.0, s.steam_port_angle_rad, -s.exhaust_port_angle_rad, "head end")]
    if getattr(gear, "steam_end", "both") != "head":    # single-acting: the head end's only
        rows.append((-2.2 * h, -s.steam_port_angle_rad, s.exhaust_port_angle_rad, "crank end"))
    ports = []
    reach = rho * (s.max_swing_rad + max(s.steam_port_angle_rad, s.exhaust_port_angle_rad)) \
        + s.standard_port_m
    for y0, steam, exhaust, label in rows:
        ax.add_patch(Rectangle((-reach * scale, (y0 - 0.1 * h) * scale), 2 * reach * scale,
                               1.2 * h * scale, facecolor="0.9", edgecolor=_FIXED, lw=0.6))
        for beta, colour in ((steam, _STEAM), (exhaust, _EXHAUST)):
            ax.add_patch(Rectangle(((rho * beta - 0.5 * s.standard_port_m) * scale, y0 * scale),
                                   s.standard_port_m * scale, h * scale, facecolor=colour,
                                   alpha=0.45, edgecolor=colour))
        ax.text(-reach * scale, (y0 + 1.2 * h) * scale, label, fontsize=7, va="bottom")
        ports.append(ax.add_patch(Rectangle((-0.5 * s.cylinder_port_m * scale, y0 * scale),
                                            s.cylinder_port_m * scale, h * scale,
                                            facecolor="none", edgecolor="k", lw=1.6)))
    ax.set_xlim(-1.1 * reach * scale, 1.1 * reach * scale)
    ax.set_ylim((rows[-1][0] - 0.6 * h) * scale, 2.4 * h * scale)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title("port face: the cylinder's port (black) over\nthe steam (red) and "
                 "exhaust (blue) ports", fontsize=8)
    return ports


# ------------------------------------------------------------------ linkages

def _line(ax, color=_ROD, lw=1.6, moving=None, **kw):
    line = ax.plot([], [], color=color, lw=lw, solid_capstyle="round", **kw)[0]
    if moving is not None:
        moving.append(line)
    return line


def _set(line, *points):
    line.set_data([p[0] for p in points], [p[1] for p in points])


def _arc(centre, p, q, n=24):
    """Points of the arc about ``centre`` from ``p`` to ``q`` (the shorter way)."""
    a0 = math.atan2(p[1] - centre[1], p[0] - centre[0])
    a1 = math.atan2(q[1] - centre[1], q[0] - centre[0])
    d = math.remainder(a1 - a0, 2 * math.pi)
    r = math.hypot(p[0] - centre[0], p[1] - centre[1])
    a = a0 + np.linspace(0.0, d, n)
    return centre[0] + r * np.cos(a), centre[1] + r * np.sin(a)


class _Linkage:
    """Draws one kind of linkage in an Axes; ``update(theta)`` moves it."""

    def __init__(self, ax, gear, scale, stroke_m):
        self.ax, self.gear, self.scale, self.stroke_m = ax, gear, scale, stroke_m
        self.rods = {}
        self.moving = []

    def _mv(self, artist):
        self.moving.append(artist)
        return artist

    def _crank(self, polar):
        if self.stroke_m is None:
            return None
        r = 0.5 * self.stroke_m * self.scale
        return (r * math.cos(polar), r * math.sin(polar))

    def _circle(self, centre, radius_m, **kw):
        t = np.linspace(0, 2 * math.pi, 73)
        r = radius_m * self.scale
        return self.ax.plot(centre[0] + r * np.cos(t), centre[1] + r * np.sin(t), **kw)[0]


class _Eccentric(_Linkage):
    """A slide valve's eccentric, rod (or slotted yoke) and the crank."""

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        self.sigma = s.sigma
        r = s.eccentricity_m * scale
        g = (s.eccentric_rod_m or 4.0 * s.eccentricity_m) * scale
        self._circle((0, 0), s.eccentricity_m, color=_FIXED, lw=0.6, ls=":")
        side = -self.sigma
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        ax.axhline(0.0, color="0.85", lw=0.6, zorder=0)
        self.crank = _line(ax, lw=3.0, moving=self.moving)
        self.ecc = _line(ax, color=_FIXED, lw=2.0, moving=self.moving)
        self.rod = _line(ax, moving=self.moving)
        self.stem = _line(ax, lw=2.4, moving=self.moving)
        self.pin = self._mv(ax.plot([], [], "o", color=_ROD, ms=3)[0])
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        lo = min(side * (g + 2.5 * r), -max(r, crank_r) * 1.2)
        hi = max(side * (g + 2.5 * r), max(r, crank_r) * 1.2)
        ax.set_xlim(lo, hi)
        ax.set_ylim(-1.3 * max(r, crank_r), 1.3 * max(r, crank_r))
        self.side, self.g = side, g
        ax.text(0.99 if side > 0 else 0.01, 0.03, "to the valve", transform=ax.transAxes,
                ha="right" if side > 0 else "left", fontsize=7, color="0.4")

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        e, end = _xy(j.eccentric, sc), _xy(j.rod_end, sc)
        # the crank at head dead centre points towards the cylinder (the valve's side)
        polar = (math.pi if self.sigma > 0 else 0.0) - theta
        c = self._crank(polar)
        if c is not None:
            _set(self.crank, (0, 0), c)
        _set(self.ecc, (0, 0), e)
        if j.rod_m is None:                   # slotted yoke
            _set(self.rod, (end[0], e[1]), (end[0], -e[1]))
        else:
            _set(self.rod, e, end)
        _set(self.stem, end, (end[0] + self.side * 0.25 * self.g, 0.0))
        self.pin.set_data([e[0], end[0]], [e[1], end[1]])
        self.rods = {"eccentric rod": (self.rod, j.rod_m)} if j.rod_m is not None else {}
        return j


class _Stephenson(_Linkage):
    """The exact Stephenson link: eccentrics, rods, the curved link, hanger, block."""

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        self._circle((0, 0), s.eccentricity_m, color=_FIXED, lw=0.6, ls=":")
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        ax.axhline(0.0, color="0.85", lw=0.6, zorder=0)
        self.crank = _line(ax, lw=3.0, moving=self.moving)
        mv = self.moving
        self.fwd_ecc = _line(ax, color=_FIXED, lw=2, moving=mv)
        self.back_ecc = _line(ax, color=_FIXED, lw=2, moving=mv)
        self.fwd_rod, self.back_rod = _line(ax, moving=mv), _line(ax, color="0.3", moving=mv)
        self.link = _line(ax, lw=4.0, color="0.25", moving=self.moving)
        self.hanger = _line(ax, lw=1.2, color="0.4", moving=self.moving)
        self.block = self._mv(ax.plot([], [], "s", color=_STEAM, ms=6)[0])
        self.stem = _line(ax, lw=2.4, moving=self.moving)
        g, c, r = s.eccentric_rod_m * scale, s.half_link_m * scale, s.eccentricity_m * scale
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        ax.set_xlim(-1.2 * max(r, crank_r), g + 3 * c)
        ax.set_ylim(-1.6 * max(c, crank_r), 1.6 * max(c, crank_r))
        self.g, self.c = g, c
        ax.text(0.99, 0.03, "the valve moves opposite the block (through a rocker)",
                transform=ax.transAxes, ha="right", fontsize=7, color="0.4")

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        P = {k: _xy(getattr(j, k), sc) for k in ("forward_eccentric", "backward_eccentric",
                                                  "link_top", "link_bottom", "link_middle",
                                                  "link_centre", "block")}
        c = self._crank(theta)             # counter-clockwise, towards the link at 0
        if c is not None:
            _set(self.crank, (0, 0), c)
        _set(self.fwd_ecc, (0, 0), P["forward_eccentric"])
        _set(self.back_ecc, (0, 0), P["backward_eccentric"])
        top_f = j.top_is_forward
        _set(self.fwd_rod, P["forward_eccentric"], P["link_top"] if top_f else P["link_bottom"])
        _set(self.back_rod, P["backward_eccentric"], P["link_bottom"] if top_f else P["link_top"])
        self.link.set_data(*_arc(P["link_centre"], P["link_top"], P["link_bottom"]))
        if j.hanger_top is not None:
            _set(self.hanger, _xy(j.hanger_top, sc), P["link_middle"])
        else:
            _set(self.hanger, (P["link_middle"][0], P["link_middle"][1] + 1.2 * self.c),
                 P["link_middle"])
        b = P["block"]
        self.block.set_data([b[0]], [b[1]])
        _set(self.stem, b, (b[0] + 1.5 * self.c, 0.0))
        self.rods = {"forward eccentric rod": (self.fwd_rod, j.eccentric_rod_m),
                     "backward eccentric rod": (self.back_rod, j.eccentric_rod_m)}
        return j


class _GoochAllen(_Linkage):
    """The exact Gooch or Allen link: eccentrics, rods, the link (curved or straight),
    the block and the radius rod to the valve stem."""

    DRAWN = ("forward eccentric", "backward eccentric", "forward eccentric rod",
             "backward eccentric rod", "radius rod")

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        self._circle((0, 0), s.eccentricity_m, color=_FIXED, lw=0.6, ls=":")
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        ax.axhline(0.0, color="0.85", lw=0.6, zorder=0)
        mv = self.moving
        self.crank = _line(ax, lw=3.0, moving=mv)
        self.lines = {n: _line(ax, lw=2.0 if n.endswith("eccentric") else 1.6,
                               color=_FIXED if n.endswith("eccentric") else _ROD, moving=mv)
                      for n in self.DRAWN}
        self.link = _line(ax, lw=4.0, color="0.25", moving=mv)
        self.block = self._mv(ax.plot([], [], "s", color=_STEAM, ms=6)[0])
        self.stem = _line(ax, lw=2.4, moving=mv)
        j0 = gear.joints(0.0)
        c = s.half_link_m * scale
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        r = s.eccentricity_m * scale
        ax.set_xlim(-1.2 * max(r, crank_r), j0.points["stem"][0] * scale + 2.5 * c)
        ax.set_ylim(-1.6 * max(c, crank_r), 1.6 * max(c, crank_r))
        self.c = c
        ax.text(0.99, 0.03, "the valve moves opposite the stem's end (through a rocker)",
                transform=ax.transAxes, ha="right", fontsize=7, color="0.4")

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        P = {k: _xy(v, sc) for k, v in j.points.items()}
        c = self._crank(theta)             # counter-clockwise, towards the link at 0
        if c is not None:
            _set(self.crank, (0, 0), c)
        for n in self.DRAWN:
            _, a, b = j.rods_m[n]
            _set(self.lines[n], P[a], P[b])
        if "link_centre" in P:
            self.link.set_data(*_arc(P["link_centre"], P["link_top"], P["link_bottom"]))
        else:
            _set(self.link, P["link_top"], P["link_bottom"])
        self.block.set_data([P["block"][0]], [P["block"][1]])
        _set(self.stem, P["stem"], (P["stem"][0] + 1.5 * self.c, 0.0))
        self.rods = {n: (self.lines[n], j.rods_m[n][0]) for n in self.DRAWN}
        return j


class _Walschaerts(_Linkage):
    """The exact Walschaerts gear: crank, return crank, eccentric rod, link, radius rod,
    combination lever, union link, crosshead."""

    NAMES = ("main crank", "connecting rod", "return crank", "eccentric rod", "link foot",
             "radius rod", "lever, valve", "lever, crosshead", "union link")

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        ax.axhline(0.0, color="0.85", lw=0.6, zorder=0)
        ax.axhline(s.valve_height_m * scale, color="0.85", lw=0.6, zorder=0)
        self._circle((0, 0), s.crank_m, color=_FIXED, lw=0.6, ls=":")
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        widths = {"main crank": 3.0, "connecting rod": 2.4, "return crank": 2.0,
                  "link foot": 1.0}
        self.lines = {n: _line(ax, lw=widths.get(n, 1.4), moving=self.moving,
                               color=_FIXED if n == "link foot" else _ROD) for n in self.NAMES}
        self.link = _line(ax, lw=4.0, color="0.25", moving=self.moving)
        self.arm = _line(ax, lw=1.4, color="0.3", moving=self.moving)
        self.stem = _line(ax, lw=2.4, moving=self.moving)
        self.die = self._mv(ax.plot([], [], "s", color=_STEAM, ms=6)[0])
        self.trunnion = self._mv(ax.plot([], [], "o", color=_FIXED, ms=5)[0])
        j0 = gear.joints(0.0)
        R = s.crank_m * scale
        xs = [p[0] * scale for p in (j0.crosshead, j0.valve_pin, j0.union_pin)]
        ax.set_xlim(-1.3 * R, max(xs) + 0.6 * R)
        ax.set_ylim(-1.3 * R, max(s.valve_height_m * scale + 0.6 * R,
                                  j0.link_top[1] * scale + 0.3 * R))

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        for n in self.NAMES:
            _, a, b = j.rods_m[n]
            _set(self.lines[n], _xy(_resolve(j, a), sc), _xy(_resolve(j, b), sc))
        self.link.set_data(*_arc(_xy(j.link_centre, sc), _xy(j.link_top, sc),
                                 _xy(j.link_bottom, sc)))
        _set(self.arm, _xy(j.crosshead, sc), _xy(j.crosshead_arm, sc))
        v = _xy(j.valve_pin, sc)
        _set(self.stem, v, (v[0] + 0.3 * self.gear.spec.crank_m * sc, v[1]))
        d = _xy(j.die, sc)
        self.die.set_data([d[0]], [d[1]])
        t = _xy(j.trunnion, sc)
        self.trunnion.set_data([t[0]], [t[1]])
        self.rods = {n: (self.lines[n], j.rods_m[n][0]) for n in self.NAMES}
        return j


class _Radial(_Linkage):
    """The exact Hackworth, Marshall, Angstrom (a vertical engine), Joy or Baker gear: its
    rods and links as the joints give them, the guide at its setting (the Baker gear's:
    the arc its gear connecting rod's middle pin swings on), and the crank."""

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        # the Joy and Baker gears draw their main crank among their rods
        self.joy = getattr(gear.spec, "kind", "baker") in ("joy", "baker")
        j0 = gear.joints(0.0)
        gx, gy = zip(*(_xy(p, scale) for p in j0.guide))
        ax.plot(gx, gy, color=_FIXED, lw=5.0, alpha=0.5, solid_capstyle="butt")
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        mv = self.moving
        self.crank = None if self.joy else _line(ax, lw=3.0, moving=mv)
        widths = {"crank": 3.0, "main crank": 3.0, "eccentric": 2.0, "connecting rod": 2.4}
        self.lines = {n: _line(ax, lw=widths.get(n, 1.5), moving=mv,
                               color=_FIXED if n in ("eccentric", "anchor link", "yoke")
                               else _ROD)
                      for n in j0.rods_m}
        self.pins = self._mv(ax.plot([], [], "o", color=_ROD, ms=3)[0])
        self.valve = self._mv(ax.plot([], [], "s", color=_STEAM, ms=6)[0])
        pts = []
        for th in np.linspace(0.0, 2 * math.pi, 13):
            pts += list(gear.joints(th).points.values())
        pts = np.array(pts) * scale
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        lo = np.minimum(pts.min(axis=0), [-crank_r, -crank_r])
        hi = np.maximum(pts.max(axis=0), [crank_r, crank_r])
        pad = 0.08 * float(np.max(hi - lo))
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        if not self.joy:
            ax.text(0.01, 0.97, "a vertical engine: the stroke runs up the page",
                    transform=ax.transAxes, va="top", fontsize=7, color="0.4")

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        for n, (_, a, b) in j.rods_m.items():
            _set(self.lines[n], _xy(j.points[a], sc), _xy(j.points[b], sc))
        if self.crank is not None and self.stroke_m is not None:
            # the eccentric is set opposite the crank (Spangler Art. 93)
            e = j.points["eccentric"]
            r = math.hypot(*e)
            _set(self.crank, (0, 0), (-e[0] / r * 0.5 * self.stroke_m * sc,
                                      -e[1] / r * 0.5 * self.stroke_m * sc))
        xs, ys = zip(*(_xy(p, sc) for p in j.points.values()))
        self.pins.set_data(xs, ys)
        v = _xy(j.points.get("valve_rod_end", j.points["valve_pin"]), sc)
        self.valve.set_data([v[0]], [v[1]])
        self.rods = {n: (self.lines[n], j.rods_m[n][0]) for n in j.rods_m}
        return j


class _Oscillating(_Linkage):
    """An oscillating engine: the crank, the piston rod and the cylinder swinging on its
    trunnion (the cylinder's body drawn schematically, a stroke and a bit long about the
    trunnion); the valve panel beside it is the port face developed flat."""

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        R, D = s.crank_m * scale, s.trunnion_distance_m * scale
        self._circle((0, 0), s.crank_m, color=_FIXED, lw=0.6, ls=":")
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        ax.plot([0], [D], "o", color=_FIXED, ms=6)
        mv = self.moving
        self.crank = _line(ax, lw=3.0, moving=mv)
        self.prod = _line(ax, lw=2.0, moving=mv)
        self.body = _line(ax, lw=1.4, moving=mv)
        self.piston = _line(ax, lw=3.0, color=_STEAM, moving=mv)
        self.half = 1.3 * R
        self.radius = 0.5 * R
        ax.set_xlim(-2.2 * R, 2.2 * R)
        ax.set_ylim(-1.3 * R, D + 1.6 * R)
        ax.text(0.01, 0.03, "oscillating cylinder: the port face swings with it",
                transform=ax.transAxes, va="bottom", fontsize=7, color="0.4")

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        pin, tr, pi_ = _xy(j.crank_pin, sc), _xy(j.trunnion, sc), _xy(j.piston, sc)
        _set(self.crank, (0, 0), pin)
        _set(self.prod, pin, pi_)
        ux, uy = tr[0] - pin[0], tr[1] - pin[1]
        d = math.hypot(ux, uy)
        ux, uy = ux / d, uy / d
        nx, ny = -uy * self.radius, ux * self.radius
        a = (tr[0] - ux * self.half, tr[1] - uy * self.half)
        b = (tr[0] + ux * self.half, tr[1] + uy * self.half)
        _set(self.body, (a[0] + nx, a[1] + ny), (b[0] + nx, b[1] + ny), (b[0] - nx, b[1] - ny),
             (a[0] - nx, a[1] - ny), (a[0] + nx, a[1] + ny))
        _set(self.piston, (pi_[0] + nx, pi_[1] + ny), (pi_[0] - nx, pi_[1] - ny))
        self.rods = {"crank": (self.crank, self.gear.spec.crank_m)}
        return j


class _Travel(_Linkage):
    """A gear drawn from its travel alone: the crank, the virtual eccentric (the travel's
    first harmonic, A sin(theta + phi), drawn as the slide valve's eccentric is) and a
    slotted yoke on the valve's spindle standing at the travel itself."""

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        th = np.linspace(0.0, 2 * math.pi, 720, endpoint=False)
        x = gear.travel(th)
        a1, b1 = 2 * np.mean(x * np.cos(th)), 2 * np.mean(x * np.sin(th))
        self.amp, self.phi = math.hypot(a1, b1), math.atan2(a1, b1)
        r = self.amp * scale
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        big = max(r, crank_r)
        self._circle((0, 0), self.amp, color=_FIXED, lw=0.6, ls=":")
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        ax.axhline(0.0, color="0.85", lw=0.6, zorder=0)
        mv = self.moving
        self.crank = _line(ax, lw=3.0, moving=mv)
        self.ecc = _line(ax, color=_FIXED, lw=2.0, moving=mv)
        self.yoke = _line(ax, lw=2.0, moving=mv)
        self.stem = _line(ax, lw=2.4, moving=mv)
        ax.set_xlim(-1.3 * big, 1.3 * big + 4 * r)
        ax.set_ylim(-1.3 * big, 1.3 * big)
        what = ", ".join(str(v) for v in (getattr(gear.spec, "kind", None),
                                          getattr(gear.spec, "motion", None)) if v)
        ax.text(0.5, 0.97, f"{gear.name}{f' ({what})' if what else ''}: its linkage not drawn; "
                "the virtual eccentric, and the valve at the gear's travel", transform=ax.transAxes,
                ha="center", va="top", fontsize=7, color="0.4")

    def update(self, theta):
        sc = self.scale
        c = self._crank(math.pi - theta)
        if c is not None:
            _set(self.crank, (0, 0), c)
        ph = theta + self.phi
        e = (self.amp * math.sin(ph) * sc, self.amp * math.cos(ph) * sc)
        _set(self.ecc, (0, 0), e)
        x = float(self.gear.travel(np.array([theta]))[0]) * sc
        r = self.amp * sc
        _set(self.yoke, (x, -1.1 * r), (x, 1.1 * r))
        _set(self.stem, (x, 0.0), (x + 4 * r, 0.0))
        return None


class _RockShaft(_Linkage):
    """The Porter-Allen's crank and rock shaft: the driving arm the radius rod works at
    the gear's own angle phi (:meth:`~corliss.valves.fink_motion.PorterAllenGear.rock_angle`),
    the two valve arms set beta from square to their stems, and the stems (the head's
    above, the crank's below, worked the other way).  The Fink link and its eccentric
    are not drawn: the travels come from the gear's solve of them."""

    def __init__(self, ax, gear, scale, stroke_m):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        self.rd, self.rv = s.drive_arm_m * scale, s.valve_arm_m * scale
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        self.shaft = (1.6 * crank_r + 2.0 * self.rd, 0.0)
        ax.plot([0], [0], "o", color=_FIXED, ms=5)
        ax.plot([self.shaft[0]], [0], "o", color=_FIXED, ms=7)
        if crank_r:
            self._circle((0, 0), 0.5 * stroke_m, color=_FIXED, lw=0.6, ls=":")
        mv = self.moving
        self.crank = _line(ax, lw=3.0, moving=mv)
        self.drive = _line(ax, lw=2.6, moving=mv)
        self.arms = [_line(ax, color=_STEAM, lw=2.2, moving=mv) for _ in range(2)]
        self.stems = [_line(ax, color=_STEAM, lw=1.4, moving=mv) for _ in range(2)]
        big = max(crank_r, self.rd, self.rv)
        ax.set_xlim(-1.3 * big, self.shaft[0] + 3.5 * big)
        ax.set_ylim(-1.6 * big, 1.6 * big)
        ax.text(0.5, 0.97, "the crank and the rock shaft at the gear's angle:\n"
                "driving arm black, steam-valve arms red\n(the Fink link not drawn)",
                transform=ax.transAxes, ha="center", va="top", fontsize=7, color="0.4")

    def update(self, theta):
        c = self._crank(math.pi - theta)
        if c is not None:
            _set(self.crank, (0, 0), c)
        phi = float(self.gear.rock_angle(np.array([theta]))[0])
        bh, bc = self.gear.spec.arm_angles_rad
        o = self.shaft
        # the driving arm hangs down, swung phi by the radius rod's travel
        _set(self.drive, o, (o[0] + self.rd * math.sin(phi), o[1] - self.rd * math.cos(phi)))
        for k, (ang, up) in enumerate(((phi - bh, 1.0), (-phi - bc, -1.0))):
            tip = (o[0] + self.rv * math.sin(ang) * up, o[1] + up * self.rv * math.cos(ang))
            _set(self.arms[k], o, tip)
            _set(self.stems[k], tip, (tip[0] + 2.5 * self.rv, tip[1]))
        return None


class _Corliss(_Linkage):
    """The wrist plate, its studs and rods, the four rotary valves over their ports, the
    trip and the dash-pots; the eccentric and hook rod drawn in ``ax_shaft``."""

    def __init__(self, ax, gear, scale, stroke_m, ax_shaft, ax_valves):
        super().__init__(ax, gear, scale, stroke_m)
        s = gear.spec
        self.ax_shaft = ax_shaft
        j0 = gear.joints(0.0)
        o = _xy(j0.plate_centre, scale)
        R = s.wrist_plate_radius_m * scale
        self._circle(o, s.wrist_plate_radius_m * 1.15, color="0.3", lw=1.5)
        self.plate_line = _line(ax, lw=1.0, color="0.3", moving=self.moving)
        self.hook = _line(ax, lw=1.6, moving=self.moving)
        self.hook_shaft = _line(ax_shaft, lw=1.6, moving=self.moving)
        self.ecc = _line(ax_shaft, color=_FIXED, lw=2.0, moving=self.moving)
        self.crank = _line(ax_shaft, lw=3.0, moving=self.moving)
        ax_shaft.plot([0], [0], "o", color=_FIXED, ms=5)
        t = np.linspace(0, 2 * math.pi, 73)
        er = s.eccentricity_m * scale
        ax_shaft.plot(er * np.cos(t), er * np.sin(t), color=_FIXED, lw=0.6, ls=":")
        crank_r = 0.5 * (stroke_m or 0.0) * scale
        lim = 1.25 * max(er, crank_r)
        ax_shaft.set_xlim(-lim, lim)
        ax_shaft.set_ylim(-lim, lim)
        ax_shaft.set_aspect("equal")
        ax_shaft.set_title("crank, and the eccentric as felt at the hook", fontsize=8)
        self.studs = [_line(ax, lw=1.0, color="0.3", moving=self.moving) for _ in range(4)]
        self.vrods = [_line(ax, lw=1.4, moving=self.moving) for _ in range(4)]
        self.arms = [_line(ax, lw=2.0, moving=self.moving) for _ in range(4)]
        self.edges, self.text = [], []
        self.radii = (s.steam.valve_radius_m, s.exhaust.valve_radius_m) * 2
        laps = (s.steam_lap_m[0], s.exhaust_lap_m[0], s.steam_lap_m[1], s.exhaust_lap_m[1])
        widths = (s.steam_port_width_m, s.exhaust_port_width_m) * 2
        # each valve's zero direction: towards the cylinder (steam valves above it, down;
        # exhaust valves below it, up); a valve turns towards opening in the figure's
        # sense j.opening_sense
        self.base = (-math.pi / 2, math.pi / 2, -math.pi / 2, math.pi / 2)
        self.sense = j0.opening_sense
        for p in range(4):
            q = _xy(j0.spindles[p], scale)
            rv = self.radii[p] * scale
            col = _STEAM if p in (0, 2) else _EXHAUST
            self._circle(q, self.radii[p] * 1.12, color=_FIXED, lw=0.8)
            # the port: its edge where the valve's edge stands at the lap, then its width
            a0 = self.base[p] + self.sense[p] * laps[p] / self.radii[p]
            a1 = a0 + self.sense[p] * widths[p] / self.radii[p]
            a = np.linspace(a0, a1, 12)
            ax.plot(q[0] + 1.12 * rv * np.cos(a), q[1] + 1.12 * rv * np.sin(a), color=col,
                    lw=4.0, solid_capstyle="butt")
            ax.plot([q[0] + 0.9 * rv * math.cos(a0), q[0] + 1.3 * rv * math.cos(a0)],
                    [q[1] + 0.9 * rv * math.sin(a0), q[1] + 1.3 * rv * math.sin(a0)],
                    color=col, lw=0.8)
            self.edges.append(_line(ax, lw=2.2, color=col, moving=self.moving))
            self.text.append(self._mv(ax.text(q[0], q[1] + (2.1 if p in (0, 2) else -2.4) * rv,
                                              "", ha="center", fontsize=7, color=_TRIP)))
            ax.text(q[0], q[1] + (1.45 if p in (0, 2) else -1.75) * rv,
                    ("head steam", "head exhaust", "crank steam", "crank exhaust")[p],
                    ha="center", fontsize=6, color="0.35")
        # dash-pots under the steam valves: the plunger's height is the fraction of the
        # opening at release the dash-pot still holds
        self.pots = []
        from matplotlib.patches import Rectangle
        for p in (0, 2):
            q = _xy(j0.spindles[p], scale)
            rv = self.radii[p] * scale
            x0 = q[0] + (-2.6 if p == 0 else 2.0) * rv
            ax.add_patch(Rectangle((x0, q[1] - 1.5 * rv), 0.6 * rv, 2.0 * rv, fill=False,
                                   edgecolor=_FIXED, lw=0.8))
            self.pots.append((_line(ax, lw=3.0, color=_TRIP, moving=self.moving), x0 + 0.3 * rv,
                              q[1] - 1.5 * rv, 2.0 * rv))
        xs = [_xy(p, scale)[0] for p in j0.spindles]
        ys = [_xy(p, scale)[1] for p in j0.spindles]
        span = max(self.radii) * scale * 3.0
        ax.set_xlim(min(xs + [o[0] - R]) - span, max(xs + [o[0] + R]) + span)
        ax.set_ylim(min(ys) - span, max(ys) + span)
        ax.text(0.01, 0.01, "hook rod from the eccentric", transform=ax.transAxes, fontsize=7,
                color="0.4")
        self._valves_panel(ax_valves, laps, widths)

    #: Where each valve stands in the panel of valves, in its largest radius.
    PLACES = ((-1.6, 1.25), (-1.6, -1.25), (1.6, 1.25), (1.6, -1.25))

    def _valves_panel(self, ax, laps, widths):
        """The four valves enlarged, each in its chamber over its port: the valve's body
        runs from its working edge forward in the sense that opens it, the port begins
        the lap ahead of the edge's mid position (so it opens by arc - lap, Spangler
        Art. 156); the drive arm the plate moves and, on a steam valve, the valve's own
        arm, which the trip lets go."""
        from matplotlib.patches import Polygon
        big = max(self.radii) * self.scale
        self.v_centres, self.v_bodies, self.v_edges, self.v_arms, self.v_hooks = [], [], [], [], []
        for p in range(4):
            cx, cy = self.PLACES[p]
            c = (cx * 1.45 * big, cy * 1.5 * big)
            rv = self.radii[p] * self.scale
            col = _STEAM if p in (0, 2) else _EXHAUST
            t = np.linspace(0, 2 * math.pi, 73)
            ax.plot(c[0] + 1.08 * rv * np.cos(t), c[1] + 1.08 * rv * np.sin(t), color=_FIXED,
                    lw=1.0)
            a0 = self.base[p] + self.sense[p] * laps[p] / self.radii[p]
            a1 = a0 + self.sense[p] * widths[p] / self.radii[p]
            a = np.linspace(a0, a1, 16)
            ax.fill(np.r_[c[0] + 1.08 * rv * np.cos(a), c[0] + 1.45 * rv * np.cos(a[::-1])],
                    np.r_[c[1] + 1.08 * rv * np.sin(a), c[1] + 1.45 * rv * np.sin(a[::-1])],
                    color=col, alpha=0.35, lw=0)
            ax.plot([c[0] + 1.0 * rv * math.cos(a0), c[0] + 1.55 * rv * math.cos(a0)],
                    [c[1] + 1.0 * rv * math.sin(a0), c[1] + 1.55 * rv * math.sin(a0)],
                    color=col, lw=1.0)
            ax.text(c[0], c[1] + (1.75 if cy > 0 else -1.95) * rv,
                    ("head steam", "head exhaust", "crank steam", "crank exhaust")[p],
                    ha="center", fontsize=7, color="0.3")
            self.v_centres.append(c)
            self.v_bodies.append(self._mv(ax.add_patch(Polygon(np.zeros((3, 2)), closed=True,
                                                               facecolor="0.7", edgecolor="k",
                                                               lw=0.8))))
            self.v_edges.append(_line(ax, lw=2.0, color=col, moving=self.moving))
            self.v_arms.append(_line(ax, lw=2.6, color="0.2", moving=self.moving))
            self.v_hooks.append(_line(ax, lw=1.4, color=_TRIP, moving=self.moving)
                                if p in (0, 2) else None)
        ax.set_xlim(-4.1 * big, 4.1 * big)
        ax.set_ylim(-4.1 * big, 4.1 * big)
        ax.set_aspect("equal")
        ax.axis("off")
        ax.set_title("the valves, their ports and the trip", fontsize=8)

    def _move_valves(self, j):
        for p in range(4):
            c, rv = self.v_centres[p], self.radii[p] * self.scale
            e = self.base[p] + self.sense[p] * j.valve_angles_rad[p]
            a = e + self.sense[p] * np.linspace(0.0, math.radians(160.0), 24)
            body = np.column_stack([np.r_[c[0], c[0] + rv * np.cos(a)],
                                    np.r_[c[1], c[1] + rv * np.sin(a)]])
            self.v_bodies[p].set_xy(body)
            _set(self.v_edges[p], c, (c[0] + 1.02 * rv * math.cos(e),
                                      c[1] + 1.02 * rv * math.sin(e)))
            # the drive arm, opposite the valve's middle, as the plate sets it
            d = self.base[p] + self.sense[p] * (j.latched_angles_rad[p] + math.radians(80.0)) \
                + math.pi
            _set(self.v_arms[p], c, (c[0] + 1.6 * rv * math.cos(d), c[1] + 1.6 * rv * math.sin(d)))
            if self.v_hooks[p] is not None:
                h = e + self.sense[p] * math.radians(80.0) + math.pi
                _set(self.v_hooks[p], c, (c[0] + 1.35 * rv * math.cos(h),
                                          c[1] + 1.35 * rv * math.sin(h)))

    def update(self, theta):
        j = self.gear.joints(theta)
        sc = self.scale
        o, hook, e = _xy(j.plate_centre, sc), _xy(j.hook_pin, sc), _xy(j.eccentric, sc)
        _set(self.plate_line, o, hook)
        _set(self.hook, e, hook)
        _set(self.hook_shaft, e, hook)
        _set(self.ecc, (0, 0), e)
        c = self._crank(math.pi - theta)
        if c is not None:
            _set(self.crank, (0, 0), c)
        for p in range(4):
            stud, arm, q = _xy(j.studs[p], sc), _xy(j.arm_ends[p], sc), _xy(j.spindles[p], sc)
            _set(self.studs[p], o, stud)
            _set(self.vrods[p], stud, arm)
            _set(self.arms[p], q, arm)
            a = self.base[p] + self.sense[p] * j.valve_angles_rad[p]
            rv = self.radii[p] * sc
            _set(self.edges[p], q, (q[0] + 1.1 * rv * math.cos(a), q[1] + 1.1 * rv * math.sin(a)))
        for e_, p in enumerate((0, 2)):
            tripped = j.released[e_]
            self.edges[p].set_color(_TRIP if tripped else _STEAM)
            self.text[p].set_text("tripped: dash-pot closing" if tripped and
                                  j.dashpot_held_frac[e_] > 0 else
                                  ("tripped: closed" if tripped else ""))
            line, x, y0, h = self.pots[e_]
            frac = j.dashpot_held_frac[e_]
            _set(line, (x, y0 + h * (0.15 + 0.7 * frac)), (x, y0 + h * 1.3))
        self._move_valves(j)
        s = self.gear.spec
        self.rods = {"hook rod": (self.hook, s.hook_rod_m)}
        for p, ch in enumerate((s.steam, s.exhaust, s.steam, s.exhaust)):
            name = ("head steam", "head exhaust", "crank steam", "crank exhaust")[p]
            self.rods[f"{name} valve rod"] = (self.vrods[p], ch.rod_m)
            self.rods[f"{name} arm"] = (self.arms[p], ch.arm_m)
            self.rods[f"{name} stud"] = (self.studs[p], ch.stud_radius_m)
        return j


# ------------------------------------------------------------------ the figure

def _openings_panel(ax, gear, u: str, moving: list):
    """The four port openings against crank angle, with a dot on each and a cursor at
    the crank's angle (appended to ``moving``).  Returns the dots and the cursor."""
    th = np.linspace(0.0, 2 * math.pi, 721)
    op = units.to_unit(gear.openings(th), u)
    deg = np.degrees(th)
    dots = []
    for p, (lab, col, ls) in enumerate(_PORT_STYLE):
        ax.plot(deg, op[p], color=col, ls=ls, lw=1.1, label=lab)
        dots.append(ax.plot([], [], "o", color=col, ms=4)[0])
        moving.append(dots[-1])
    cursor = ax.axvline(0.0, color="0.3", lw=0.8)
    moving.append(cursor)
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 90))
    ax.set_xlabel("crank angle [deg]", fontsize=8)
    ax.set_ylabel(f"port opening [{u}]", fontsize=8)
    note = openings_note(gear)
    if note:                          # the edges that uncover more than one opening
        ax.set_title(note, fontsize=7)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6, frameon=False, loc="upper right")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return dots, cursor


def _card_panel(ax, result, units_system: str, u: str, moving: list) -> dict:
    """The steady run's card of both ends in grey, with a trace and a dot per end that
    follow the crank (appended to ``moving``).  Returns ``{end: (crank angles [deg],
    x, y, trace, dot)}``."""
    card_lines = {}
    baro = result.scene.supply.barometer_Pa
    p_unit = "psig" if units_system == "US" else "barg"
    stroke = result.scene.engine.stroke_m
    for end, ls in (("head", "-"), ("crank", "--")):
        card = result.cards[end]
        x = units.to_unit(card["piston_frac"].to_numpy() * stroke, u)
        y = units.to_unit(card["p_Pa"].to_numpy(), p_unit, barometer_Pa=baro)
        a = card["crank_angle_deg"].to_numpy()
        ax.plot(x, y, color="0.8", lw=0.8, ls=ls)
        trace = ax.plot([], [], color="k", lw=1.3, ls=ls, label=f"{end} end")[0]
        head = ax.plot([], [], "o", color=_STEAM, ms=4)[0]
        card_lines[end] = (a, x, y, trace, head)
        moving += [trace, head]
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel(f"piston position [{u}]", fontsize=8)
    ax.set_ylabel(f"pressure [{p_unit}]", fontsize=8)
    ax.set_title("indicator card", fontsize=9)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6, frameon=False, loc="upper right")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return card_lines


def animate_gear(gear, result=None, *, frames: int = 72, stroke_m: float | None = None,
                 units_system: str = "US", title: str | None = None,
                 interval_ms: float = 80.0, dpi: float = 72.0) -> dict:
    """An animation of ``gear`` over one turn of the crank.

    Panels: the linkage (from ``gear.joints`` where the gear solves one, see
    :func:`linkage_kind`), the valve in section over its ports (a lapped valve; the
    Corliss valves are drawn on their spindles, the Porter-Allen's four flat valves over
    their ports), the four port openings against crank
    angle with a marker at the crank's angle, and, with a steady ``result``, the
    indicator card of both ends traced as the crank turns.  What does not move is drawn
    once, into an image behind the moving parts, at the figure's ``dpi``: frames saved at
    that dpi are exact (at another, the image is resized), and ``bbox_inches="tight"``
    would misplace it.

    Parameters
    ----------
    gear : ValveGear
        The gear (a Corliss gear at its speed, :meth:`CorlissGear.with_speed`).
    result : SteadyResult, optional
        A steady run of the scene, whose last cycle's cards are traced; None for none.
    frames : int
        Frames in one turn, at crank angles 2 pi i / frames [-].
    stroke_m : float, optional
        The engine's stroke, to draw the crank [m]; by default the result's, or none.
    units_system : str
        ``"US"`` (inches, psig) or ``"SI"`` (mm, bar gauge).
    title : str, optional
        The figure's title.
    interval_ms : float
        Time between frames when played [ms].
    dpi : float
        The figure's resolution [dots per inch].

    Returns
    -------
    dict
        ``figure``, ``animation`` (a ``FuncAnimation``), ``update`` (draws frame ``i``
        and returns the gear's joints there, or None), ``angles_rad`` (each frame's crank
        angle [rad]), ``kind`` (:func:`linkage_kind`), ``axes`` and ``artists`` (a lapped
        valve's outline ``valve``, with ``valve_rest`` its vertices at zero displacement
        and ``valve_sense`` the sign of its motion, drawn in ``length_unit``, ``scale`` of
        them to the metre; the Corliss valves' ``valve_edges``, each (Line2D from the
        spindle to the working edge, spindle, the edge's angle at mid position [rad],
        +1 or -1 the sense it turns to open); the Porter-Allen's ``plates``, a
        :class:`~corliss.plot.plate_valves.PlateValvesPanel`), and ``rods``, which
        gives the rods drawn in the frame last drawn, ``{name: (Line2D, the spec's length [m])}``; a lapped
        valve's ``seat_m``, the edges of its steam ports (``head``, ``crank``: (from, to)
        [m]) and whether it takes steam ``inside``.
    """
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation
    from matplotlib.patches import Polygon

    if frames < 2:
        raise ValueError(f"frames {frames}: at least 2")
    kind = linkage_kind(gear)
    u = _unit(units_system)
    scale = units.to_unit(1.0, u)
    if stroke_m is None and result is not None:
        stroke_m = result.scene.engine.stroke_m
    angles = 2 * math.pi * np.arange(frames) / frames
    has_card = result is not None and hasattr(result, "cards") and "head" in result.cards
    fig = plt.figure(figsize=(10.0, 6.2), dpi=dpi)
    gs = fig.add_gridspec(2, 3, height_ratios=(1.1, 1.0), hspace=0.3, wspace=0.28,
                          left=0.06, right=0.98, bottom=0.08, top=0.92)
    if kind == "corliss":
        ax_shaft = fig.add_subplot(gs[0, 0])
        ax_link = fig.add_subplot(gs[0, 1])
        ax_valves = fig.add_subplot(gs[0, 2])
        ax_valve = None
    elif kind == "porter_allen":      # the four valves take the wider panel
        ax_link = fig.add_subplot(gs[0, 0])
        ax_valves = fig.add_subplot(gs[0, 1:3])
        ax_valve = None
    else:
        ax_link = fig.add_subplot(gs[0, 0:2])
        ax_valve = fig.add_subplot(gs[0, 2])
    ax_open = fig.add_subplot(gs[1, 0:2] if has_card else gs[1, :])
    ax_card = fig.add_subplot(gs[1, 2]) if has_card else None
    ax_link.set_aspect("equal")
    ax_link.axis("off")
    artists: dict = {}
    linkage = {"eccentric": _Eccentric, "stephenson": _Stephenson, "walschaerts": _Walschaerts,
               "gooch_allen": _GoochAllen, "radial": _Radial, "travel": _Travel,
               "oscillating": _Oscillating, "porter_allen": _RockShaft}
    drawer: _Linkage
    if kind == "corliss":
        cd = _Corliss(ax_link, gear, scale, stroke_m, ax_shaft, ax_valves)
        artists["valve_edges"] = [(line, c, b, sn) for line, c, b, sn in
                                  zip(cd.v_edges, cd.v_centres, cd.base, cd.sense)]
        ax_shaft.axis("off")
        drawer = cd
    else:
        drawer = linkage[kind](ax_link, gear, scale, stroke_m)
    moving = list(drawer.moving)
    plates = None
    if kind == "porter_allen":
        plates = PlateValvesPanel(ax_valves, gear, scale, u, moving)
        artists["plates"] = plates
    valve_rest, valve_sense, lay = None, None, None
    if ax_valve is not None and kind == "oscillating":
        artists["cylinder_ports"] = _draw_port_face(ax_valve, gear, scale)
        moving += artists["cylinder_ports"]
        artists["valve_x"] = ax_valve.text(0.0, 1.6 * gear.spec.port_length_m * scale, "",
                                           ha="center", va="bottom", fontsize=7)
        moving.append(artists["valve_x"])
    elif ax_valve is not None:
        lay = _valve_layout(gear)
        _draw_seat(ax_valve, lay, scale)
        valve_rest = valve_outline(gear, 0.0, lay) * scale
        valve_sense = lay["sense"]
        artists["valve"] = ax_valve.add_patch(Polygon(valve_rest.copy(), closed=True,
                                                      facecolor="0.65", edgecolor="k", lw=1.0))
        ax_valve.set_title("valve over its ports", fontsize=9)
        moving.append(artists["valve"])
        artists["valve_x"] = ax_valve.text(0.0, 2.6 * lay["w"] * scale, "", ha="center",
                                           va="bottom", fontsize=7)
        moving.append(artists["valve_x"])
    dots, artists["cursor"] = _openings_panel(ax_open, gear, u, moving)
    card_lines = {} if ax_card is None else _card_panel(ax_card, result, units_system, u, moving)
    if title:
        fig.suptitle(title, fontsize=10)
    label = fig.text(0.01, 0.985, "", fontsize=8, va="top")
    moving.append(label)
    openings_at = units.to_unit(gear.openings(angles), u)

    def update(i):
        theta = float(angles[i % frames])
        joints = drawer.update(theta)
        if plates is not None:
            plates.update(theta)
        label.set_text(f"crank {math.degrees(theta):5.1f} deg")
        if ax_valve is not None:
            x_m = joints.valve_m if joints is not None else float(gear.travel(np.array([theta]))[0])
            if kind == "oscillating":
                for patch in artists["cylinder_ports"]:
                    patch.set_x((x_m - 0.5 * gear.spec.cylinder_port_m) * scale)
            else:
                artists["valve"].set_xy(valve_outline(gear, x_m, lay) * scale)
            artists["valve_x"].set_text(f"x = {x_m * scale:+.3f} {u} (+ opens head steam)")
        d = math.degrees(theta)
        artists["cursor"].set_xdata([d, d])
        for p in range(4):
            dots[p].set_data([d], [openings_at[p, i % frames]])
        for end, (a, x, y, trace, head) in card_lines.items():
            # the card from its start at the crank's angle of the run's cycle
            since = a - a[0]
            m = since <= np.mod(d - a[0], 360.0)
            trace.set_data(x[m], y[m])
            k = int(np.argmin(np.abs(np.mod(a - d + 180.0, 360.0) - 180.0)))
            head.set_data([x[k]], [y[k]])
        return joints

    _flatten(fig, moving)
    update(0)
    anim = FuncAnimation(fig, update, frames=frames, interval=interval_ms, blit=False)
    return {"figure": fig, "animation": anim, "update": update, "angles_rad": angles,
            "kind": kind, "axes": {"linkage": ax_link, "valve": ax_valve, "openings": ax_open,
                                   "card": ax_card},
            "artists": artists, "valve_rest": valve_rest, "valve_sense": valve_sense,
            "length_unit": u, "scale": scale, "rods": lambda: dict(drawer.rods),
            "seat_m": None if lay is None else {
                "head": (-lay["outer"], -lay["inner"]), "crank": (lay["inner"], lay["outer"]),
                "inside": lay["inside"]}}


def _flatten(fig, moving) -> None:
    """Draw everything that does not move once, into one image behind the moving
    artists, and hide it: each frame then draws the image and the moving parts only
    (a tenth of the time of drawing every axis, label and legend again).  The image is
    the figure's pixels at its own dpi, so the figure must be saved at that dpi."""
    keep = set(map(id, moving))
    for a in moving:
        a.set_visible(False)
    fig.canvas.draw()
    background = np.asarray(fig.canvas.buffer_rgba()).copy()
    for a in moving:
        a.set_visible(True)
    ancestors = set()
    for a in moving:
        ax = a.axes
        if ax is not None:
            ancestors.add(id(ax))
    for obj in fig.findobj():
        if obj is fig or id(obj) in keep or id(obj) in ancestors:
            continue
        if hasattr(obj, "get_children") and obj in fig.axes:
            continue
        obj.set_visible(False)
    for ax in fig.axes:
        ax.set_visible(True)
        ax.patch.set_visible(False)
    fig.patch.set_visible(False)
    fig.add_artist(_background_artist(background))


def _background_artist(rgba):
    """An artist that puts the figure's pixels ``rgba`` back as they were, unresampled
    when the figure is drawn at the dpi it was captured at (resized, if a caller saves
    it at another)."""
    from matplotlib.artist import Artist

    class _Background(Artist):
        zorder = -10

        def draw(self, renderer):
            img = rgba
            w, h = int(renderer.width), int(renderer.height)
            if (h, w) != img.shape[:2]:
                from PIL import Image
                img = np.asarray(Image.fromarray(rgba).resize((w, h)))
            gc = renderer.new_gc()
            renderer.draw_image(gc, 0, 0, img[::-1])
            gc.restore()

    return _Background()


def render_frames(drawn: dict) -> list:
    """Every frame of an animation from :func:`animate_gear`, as RGB images.

    Parameters
    ----------
    drawn : dict
        What :func:`animate_gear` returned.

    Returns
    -------
    list of PIL.Image.Image
        One image per frame, at the figure's size and dpi.
    """
    from PIL import Image

    fig = drawn["figure"]
    out = []
    for i in range(len(drawn["angles_rad"])):
        drawn["update"](i)
        fig.canvas.draw()
        out.append(Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()))
    return out


#: The player's button icons as characters, in place of the icon font matplotlib's
#: player loads from a content-delivery network (a page that is blank offline).
_PLAYER_ICONS = {"fa fa-play fa-flip-horizontal": "&#9664;", "fa fa-fast-backward": "&#9198;",
                 "fa fa-fast-forward": "&#9197;", "fa fa-step-backward": "&#9204;&#8203;|",
                 "fa fa-step-forward": "|&#9205;", "fa fa-minus": "&minus;",
                 "fa fa-plus": "+", "fa fa-pause": "&#10073;&#10073;", "fa fa-play": "&#9654;"}


def self_contained_html(html: str) -> str:
    """matplotlib's ``to_jshtml`` page with nothing fetched from elsewhere.

    The player's stylesheet link (an icon font on a content-delivery network) is
    removed and each icon written as a character, so the page works offline and makes
    no request; the frames are already inline (``data:`` URIs).

    Parameters
    ----------
    html : str
        What ``Animation.to_jshtml`` returned.

    Returns
    -------
    str
        The same player, self-contained.
    """
    import re
    html = re.sub(r"<link[^>]*?href=\"https?://[^\"]*\"[^>]*>", "", html, flags=re.S)
    for cls, char in _PLAYER_ICONS.items():     # longest class first: the flipped play
        html = html.replace(f'<i class="{cls}"></i>', f"<span>{char}</span>")
    return html


def write_animation(drawn: dict, path, fmt: str = "gif", fps: float = 12.0) -> None:
    """Write an animation from :func:`animate_gear` to ``path``.

    A GIF is written through Pillow with one palette of 96 colours for every frame,
    taken from four frames a quarter of a turn apart (matplotlib's ``PillowWriter``
    takes a palette per frame: three times the file and the time, measured on the
    default scene's 72 frames, 667 kB against 201 kB).  HTML is matplotlib's
    ``to_jshtml``: the frames and a player in one page.

    Parameters
    ----------
    drawn : dict
        What :func:`animate_gear` returned.
    path : str, Path or file object
        The file to write (a binary file object for a GIF: the workbench sends the
        bytes to its page).
    fmt : str
        ``"gif"`` (through Pillow) or ``"html"`` (a page with the frames and a player).
    fps : float
        Frames per second [1/s].
    """
    from PIL import Image

    if fmt == "gif":
        frames = render_frames(drawn)
        n = len(frames)
        picks = [frames[(k * n) // 4] for k in range(4)]
        w, h = picks[0].size
        sheet = Image.new("RGB", (w, h * len(picks)))
        for k, im in enumerate(picks):
            sheet.paste(im, (0, k * h))
        palette = sheet.quantize(colors=96, method=Image.Quantize.MEDIANCUT)
        q = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in frames]
        q[0].save(path if hasattr(path, "write") else str(path), format="GIF",
                  save_all=True, append_images=q[1:], duration=int(round(1000.0 / fps)),
                  loop=0)
    elif fmt == "html":
        html = self_contained_html(drawn["animation"].to_jshtml(fps=fps, default_mode="loop"))
        with open(path, "w", encoding="utf-8") as f:
            f.write("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"></head><body>\n")
            f.write(html)
            f.write("\n</body></html>\n")
    else:
        raise ValueError(f"format {fmt!r}: gif or html")
