"""Valve gears drawn: valve travel, the Zeuner diagram and the Bilgram diagram
(Spangler Arts. 149-150), and :func:`plot_gear`, the full set of panels of any gear
(a gear whose motion is not one lapped valve has its own, in
:mod:`corliss.plot.gear_panels`)."""

from __future__ import annotations

import numpy as np

from corliss.keys import units
from corliss.plot.gear_panels import (find_by_class, plot_corliss_gear, plot_double_valve,
                                      plot_oscillating, plot_porter_allen)
from corliss.valves.corliss_gear import CorlissGear
from corliss.valves.double_valve import DoubleValve
from corliss.valves.fink_motion import PorterAllenGear
from corliss.valves.oscillating import OscillatingCylinder
from corliss.valves.slide_valve import LappedValve


def plot_valve_travel(gear, ax=None, units_system: str = "US") -> dict:
    """Valve travel against crank angle, with the laps of each end as horizontal lines.

    The exact motion, and Zeuner's (infinite eccentric rod) dashed over it where the
    gear has both; displacement positive where it opens the head-end steam port.

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``),
        as :func:`corliss.engine.simulate.build_gear` builds it.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 9 x 4 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {"travel": Line2D}}``, with ``"zeuner"`` when drawn.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(9, 4))
    u = "in" if units_system == "US" else "mm"
    th = np.linspace(0.0, 2 * np.pi, 721)
    deg = np.degrees(th)
    lines = {"travel": ax.plot(deg, units.to_unit(gear.travel(th), u), color="k", lw=1.4,
                               label="valve travel")[0]}
    if hasattr(gear, "zeuner_travel") and getattr(gear.spec, "eccentric_rod_m", None):
        lines["zeuner"] = ax.plot(deg, units.to_unit(gear.zeuner_travel(th), u), color="0.5",
                                  lw=1.0, ls="--", label="Zeuner (infinite rod)")[0]
    lh, lc = gear.spec.lap_m
    eh, ec = gear.spec.exhaust_lap_m
    for y, label, ls in ((lh, "head steam lap", "-"), (-lc, "crank steam lap", "-"),
                         (-eh, "head exhaust lap", ":"), (ec, "crank exhaust lap", ":")):
        if y == 0.0:
            continue
        ax.axhline(units.to_unit(y, u), color="0.6", lw=0.7, ls=ls)
        ax.text(362, units.to_unit(y, u), label, fontsize=7, va="center", color="0.4")
    ax.axhline(0, color="0.8", lw=0.5)
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.set_xlabel("crank angle from head-end dead centre [deg]")
    ax.set_ylabel(f"valve displacement, + opens head steam [{u}]")
    ax.legend(fontsize=8, frameon=False, loc="lower left")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines}


def plot_zeuner_diagram(gear, ax=None, units_system: str = "US") -> dict:
    """Zeuner's valve diagram (Spangler Arts. 10-18).

    The valve's displacement laid off along each crank position traces the valve
    circles, one for each end; the lap circles cut them at admission and cut-off, the
    exhaust-lap circles at release and compression.  Drawn with the crank rotating
    counter-clockwise from head-end dead centre on the right.

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``),
        as :func:`corliss.engine.simulate.build_gear` builds it.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 6 x 6 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {"head": Line2D, "crank": Line2D}}``, the two valve
        circles.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 6))
    u = "in" if units_system == "US" else "mm"
    th = np.linspace(0.0, 2 * np.pi, 1441)
    x = units.to_unit(gear.travel(th), u)
    pos = x > 0
    lines = {}
    for end, mask, rad, ls in (("head", pos, x, "-"), ("crank", ~pos, -x, "--")):
        xs = np.where(mask, rad * np.cos(th), np.nan)
        ys = np.where(mask, rad * np.sin(th), np.nan)
        lines[end] = ax.plot(xs, ys, color="k", lw=1.3, ls=ls, label=f"{end}-end valve circle")[0]
    lh, lc = (units.to_unit(v, u) for v in gear.spec.lap_m)
    eh, ec = (units.to_unit(v, u) for v in gear.spec.exhaust_lap_m)
    t = np.linspace(0, 2 * np.pi, 361)
    circles = [(lh, "-", "lap circle" if lh == lc else "head lap circle")]
    if lc != lh:                      # unequal laps (Spangler Art. 31): one circle each
        circles.append((lc, "--", "crank lap circle"))
    circles.append((abs(eh), ":", "exhaust lap circle" if eh == ec else "head exhaust lap circle"))
    if ec != eh:
        circles.append((abs(ec), "-.", "crank exhaust lap circle"))
    for r_, ls, label in circles:
        if r_ > 0:
            ax.plot(r_ * np.cos(t), r_ * np.sin(t), color="0.55", lw=0.8, ls=ls, label=label)
    rmax = float(np.nanmax(np.abs(x)))
    ax.axhline(0, color="0.8", lw=0.6)
    ax.axvline(0, color="0.8", lw=0.6)
    ax.set_aspect("equal")
    ax.set_xlim(-1.1 * rmax, 1.1 * rmax)
    ax.set_ylim(-1.1 * rmax, 1.1 * rmax)
    ax.set_title("Zeuner diagram", fontsize=10)
    ax.set_xlabel(f"[{u}]")
    ax.legend(fontsize=7, frameon=False, loc="lower right")
    return {"ax": ax, "lines": lines}


def _bilgram_point(gear) -> tuple[float, float]:
    """Zeuner's (C, S) of a lapped valve [m]: C = x(0), S = x(pi/2) of its Zeuner form
    (``zeuner_travel`` where the gear has one, else ``travel``)."""
    zt = getattr(gear, "zeuner_travel", None) or gear.travel
    C, S = (float(v) for v in np.asarray(zt(np.array([0.0, 0.5 * np.pi])), dtype=float))
    return C, S


# (end, event, signed level x = L of the valve's displacement as a function of the laps,
#  whether x rises through it there): the opening of each port is zero where x = L.
_BILGRAM_EVENTS = (
    ("head", "admission", lambda l, e: l[0], True),
    ("head", "cutoff", lambda l, e: l[0], False),
    ("head", "release", lambda l, e: -e[0], False),
    ("head", "compression", lambda l, e: -e[0], True),
    ("crank", "admission", lambda l, e: -l[1], False),
    ("crank", "cutoff", lambda l, e: -l[1], True),
    ("crank", "release", lambda l, e: e[1], True),
    ("crank", "compression", lambda l, e: e[1], False),
)


def bilgram_events(gear) -> dict:
    """Crank angles of the events read off the Bilgram diagram (Spangler Art. 149).

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear; its Zeuner form (``zeuner_travel`` where it has one,
        else ``travel``) places the Bilgram point.

    Returns
    -------
    dict
        ``{"head": {...}, "crank": {...}}``, each with ``admission_deg``,
        ``cutoff_deg``, ``release_deg`` and ``compression_deg``, crank angles [deg] in
        [0, 360) (None where the circle encloses o: the port never closes or never
        opens), and ``lead_m``, ``dk - lap`` [m], dk being the distance of d from oa
        (lap + lead, Art. 149).

    Notes
    -----
    The Bilgram point d lies at the throw r from o, at the angular advance from the
    dead-centre line oa, on the side that makes the perpendicular from d on the crank
    line the valve's displacement: with the crank at theta (counter-clockwise from
    head-end dead centre) ``d = (S, -C)``, and that perpendicular is
    ``d . (sin theta, -cos theta) = C cos theta + S sin theta = r sin(theta + delta)``.
    A port opens or closes where the crank line is tangent to the circle about d of
    radius the lap (steam) or exhaust lap: the two tangents from o make the angles
    ``+-asin(lap / od)`` with od.  Of each tangent line, the crank is on the ray on
    whose side d lies as the event needs (``x = +lap`` for the head end, ``-lap`` for
    the crank end), and the tangent point (the foot of the perpendicular from d) lies on
    the crank's ray where the displacement is growing (its rate is
    ``d . (cos theta, sin theta)``), behind o where it is falling: so the two tangents
    tell opening from closing.
    """
    C, S = _bilgram_point(gear)
    dx, dy = S, -C
    rho, alpha = float(np.hypot(dx, dy)), float(np.arctan2(dy, dx))
    laps, elaps = gear.spec.lap_m, gear.spec.exhaust_lap_m
    out: dict[str, dict] = {"head": {}, "crank": {}}
    for end, name, level, rising in _BILGRAM_EVENTS:
        L = level(laps, elaps)
        angle = None
        if abs(L) < rho:
            beta = float(np.arcsin(abs(L) / rho))
            for psi in (alpha + beta, alpha - beta):          # the two tangent lines
                for phi in (psi, psi + np.pi):                # the two rays of each
                    x = dx * np.sin(phi) - dy * np.cos(phi)   # perpendicular from d
                    foot = dx * np.cos(phi) + dy * np.sin(phi)
                    if (L == 0.0 or x * L > 0.0) and (foot > 0.0) == rising:
                        angle = float(np.degrees(phi) % 360.0)
        out[end][f"{name}_deg"] = angle
    out["head"]["lead_m"] = C - laps[0]
    out["crank"]["lead_m"] = C - laps[1]
    return out


def plot_bilgram_diagram(gear, ax=None, units_system: str = "US") -> dict:
    """Bilgram's valve diagram (Spangler Arts. 149-150).

    The circle of the eccentric's throw r about o, the Bilgram point d on it at the
    angular advance from the dead-centre line, and the lap and exhaust-lap circles
    about d; the valve's displacement at any crank position is the perpendicular from d
    on the crank line, and the crank lines tangent to the lap circles are the events
    (see :func:`bilgram_events`).  dk, from d square to the dead-centre line, is the lap
    plus the lead.  Drawn from the gear's Zeuner form, with the crank turning
    counter-clockwise from head-end dead centre on the right, as the Zeuner diagram.

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``),
        as :func:`corliss.engine.simulate.build_gear` builds it.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 6 x 6 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {...}, "events": {...}}``: the valve circle, the point
        d and the lap circles by label, and :func:`bilgram_events` of the gear.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 6))
    u = "in" if units_system == "US" else "mm"
    C, S = _bilgram_point(gear)
    dx, dy = units.to_unit(S, u), units.to_unit(-C, u)
    r = float(np.hypot(dx, dy))
    t = np.linspace(0.0, 2 * np.pi, 361)
    lines = {"valve_circle": ax.plot(r * np.cos(t), r * np.sin(t), color="k", lw=1.3,
                                     label="valve circle (radius r)")[0]}
    ax.plot([0, dx], [0, dy], color="k", lw=0.8)
    ax.plot([dx, dx], [0, dy], color="0.3", lw=0.8)
    lines["d"] = ax.plot([dx], [dy], "o", color="k", ms=4)[0]
    ax.annotate("d", (dx, dy), textcoords="offset points", xytext=(5, -9), fontsize=8)
    ax.annotate("k", (dx, 0), textcoords="offset points", xytext=(4, 3), fontsize=8)
    ax.annotate("o", (0, 0), textcoords="offset points", xytext=(-9, 3), fontsize=8)
    ax.text(dx, 0.5 * dy, "  dk = lap + lead", fontsize=7, color="0.3", va="center")
    lh, lc = (units.to_unit(v, u) for v in gear.spec.lap_m)
    eh, ec = (units.to_unit(v, u) for v in gear.spec.exhaust_lap_m)
    circles = [(lh, "-", "lap circle" if lh == lc else "head lap circle")]
    if lc != lh:
        circles.append((lc, "--", "crank lap circle"))
    circles.append((abs(eh), ":", "exhaust-lap circle" if eh == ec else "head exhaust-lap circle"))
    if ec != eh:
        circles.append((abs(ec), "-.", "crank exhaust-lap circle"))
    for rad, ls, label in circles:
        if rad > 0:
            lines[label] = ax.plot(dx + rad * np.cos(t), dy + rad * np.sin(t), color="0.45",
                                   lw=0.9, ls=ls, label=label)[0]
    ev = bilgram_events(gear)
    short = {"admission": "adm", "cutoff": "c/o", "release": "rel", "compression": "comp"}
    reach = 1.25 * r
    rays: dict[float, list[str]] = {}
    for end, ls in (("head", "-"), ("crank", "--")):
        for name, tag in short.items():
            a = ev[end][f"{name}_deg"]
            if a is None:
                continue
            p = np.radians(a)
            c, s = np.cos(p), np.sin(p)
            ax.plot([-reach * c, reach * c], [-reach * s, reach * s], color="0.75", lw=0.5,
                    ls=":")
            ax.plot([0, reach * c], [0, reach * s], color="0.35", lw=0.9, ls=ls)
            key = next((k for k in rays if abs((k - a + 180.0) % 360.0 - 180.0) < 2.0), a)
            rays.setdefault(key, []).append(f"{tag} {end[0].upper()}")
    for a, tags in rays.items():
        p = np.radians(a)
        ax.text(1.32 * r * np.cos(p), 1.32 * r * np.sin(p), ", ".join(tags), fontsize=6.5,
                ha="center", va="center", color="0.25")
    ax.axhline(0, color="0.8", lw=0.6)
    ax.axvline(0, color="0.8", lw=0.6)
    ax.set_aspect("equal")
    lim = 1.45 * r
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_title("Bilgram diagram (Art. 149)", fontsize=10)
    ax.set_xlabel(f"[{u}]  crank lines: head end solid, crank end dashed")
    ax.legend(fontsize=7, frameon=False, loc="lower left")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines, "events": ev}


def plot_lapped_valve(gear, fig=None, units_system: str = "US") -> dict:
    """The three standard panels of a lapped valve, side by side.

    Valve travel (:func:`plot_valve_travel`), the Zeuner diagram
    (:func:`plot_zeuner_diagram`) and the Bilgram diagram (:func:`plot_bilgram_diagram`).

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``),
        as :func:`corliss.engine.simulate.build_gear` builds it.
    fig : matplotlib.figure.Figure, optional
        Figure to draw on (three subplots are added); a new 19 x 5.5 in figure when
        None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"figure": fig, "axes": [travel, zeuner, bilgram], "travel": {...},
        "zeuner": {...}, "bilgram": {...}}``, the last three what each panel returned.
    """
    if fig is None:
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=(19, 5.5))
    travel = plot_valve_travel(gear, fig.add_subplot(1, 3, 1), units_system)
    zeuner = plot_zeuner_diagram(gear, fig.add_subplot(1, 3, 2), units_system)
    bilgram = plot_bilgram_diagram(gear, fig.add_subplot(1, 3, 3), units_system)
    return {"figure": fig, "axes": [travel["ax"], zeuner["ax"], bilgram["ax"]],
            "travel": travel, "zeuner": zeuner, "bilgram": bilgram}


#: The panels of each kind of gear: gear class -> drawing ``f(gear, fig, units_system)
#: -> dict``.  A gear takes the entry of its nearest class along its method resolution
#: order (a subclass its parent's); a gear of no class here, the standard panels of
#: :func:`plot_lapped_valve`.
GEAR_PANELS = {
    LappedValve: plot_lapped_valve,
    DoubleValve: plot_double_valve,
    CorlissGear: plot_corliss_gear,
    PorterAllenGear: plot_porter_allen,
    OscillatingCylinder: plot_oscillating,
}


def plot_gear(gear, fig=None, units_system: str = "US") -> dict:
    """All the panels of a valve gear, as ``corliss gear`` draws them.

    A lapped valve (slide valve, link motions, radial gears, shaft governor, Fink
    motion) gets valve travel, the Zeuner diagram and the Bilgram diagram; a double
    valve its travels, openings and the book's diagram of its kind; the Corliss gear
    its wrist plate, spindles and port openings with the trip; the Porter-Allen gear
    its stems, openings and the Zeuner diagram at the radius rod; the oscillating
    cylinder its swing, openings and port face.  The drawing is
    chosen from :data:`GEAR_PANELS` by the gear's class.

    Parameters
    ----------
    gear : ValveGear
        As :func:`corliss.engine.simulate.build_gear` builds it (the Corliss gear with
        its speed, for the trip).
    fig : matplotlib.figure.Figure, optional
        Drawn on; when None, a new figure sized for the panels (the caller closes it).
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        At least ``{"figure": fig, "axes": [...]}``, one axes per panel, and what the
        gear's drawing returns besides (e.g. ``"lines"``).
    """
    draw = find_by_class(GEAR_PANELS, gear) or plot_lapped_valve
    return draw(gear, fig, units_system)
