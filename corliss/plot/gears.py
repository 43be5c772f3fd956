"""Valve gears drawn: valve travel, the Zeuner diagram and the Bilgram diagram
(Spangler Arts. 149-150), and :func:`plot_gear`, the full set of panels of any gear
(a gear whose motion is not one lapped valve has its own, in
:mod:`corliss.plot.gear_panels`)."""

from __future__ import annotations

import numpy as np

from corliss.keys import units
from corliss.plot.crank_lines import (EVENT_WORDS, POLAR_EVENTS, crank_lines,  # noqa: F401
                                      dead_centre_lines, period_frame, polar_events)
from corliss.plot.labels import fit_inside, place_clear
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
    names, places = [], []
    for y, label, ls in ((lh, "head steam lap", "-"), (-lc, "crank steam lap", "-"),
                         (-eh, "head exhaust lap", ":"), (ec, "crank exhaust lap", ":")):
        if y == 0.0:
            continue
        yu = float(units.to_unit(y, u))
        ax.axhline(yu, color="0.6", lw=0.7, ls=ls)
        # named inside the panel, just above or below its line, where no curve runs
        va = "bottom" if y > 0 else "top"
        names.append(ax.text(357, yu, label, fontsize=7, ha="right", va=va, color="0.4"))
        places.append([(x_, yu) for x_ in (357, 300, 240, 180, 120, 60)])
    ax.axhline(0, color="0.8", lw=0.5)
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.set_xlabel("crank angle from head-end dead centre [deg]")
    ax.set_ylabel(f"valve displacement, + opens head steam [{u}]")
    ax.legend(fontsize=8, frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.16),
              ncol=2)
    ax.set_ylim(*ax.get_ylim())
    place_clear(names, list(lines.values()), positions=places)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines}


def _idle_end(gear) -> str | None:
    """The end of a single-acting cylinder that takes no steam (it has no events)."""
    ports = getattr(gear, "idle_ports", None)
    return None if ports is None else ("head" if ports[0] == 0 else "crank")


def zeuner_events(gear) -> dict:
    """Crank angles of the events read off the Zeuner diagram (Spangler Arts. 12-17).

    Where the valve circle of an end (the polar of the valve's displacement x against
    crank angle) meets that end's lap circle the steam port opens or closes, where it
    meets the exhaust-lap circle the exhaust opens or closes: the crank lines through
    those points are the events (Art. 16: "when the crank reaches ok the steam-port on
    the right closes and cut-off takes place").  Read from the gear's own displacement
    (``travel``, the exact motion where the gear has one), each meeting solved to
    1e-12 rad.

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``).

    Returns
    -------
    dict
        ``{"head": {...}, "crank": {...}}``, each with ``admission_deg``,
        ``cutoff_deg``, ``release_deg`` and ``compression_deg``, crank angles [deg] in
        [0, 360) from head-end dead centre (None where the circles do not meet, and for
        the idle end of a single-acting cylinder).

    Notes
    -----
    An end's steam port is open while ``x`` is past its lap (head: ``x > l_h``, crank:
    ``-x > l_c``), its exhaust while ``x`` is past the exhaust lap the other way (head:
    ``-x > e_h``, crank: ``x > e_c``; Art. 15).  Where a circle is met more than once a
    turn, the opening taken is the one nearest the end's dead centre (steam) or the
    opposite one (exhaust), and the closing the first after it, as the events table
    takes them (:func:`corliss.valves.events.end_events`).
    """
    return polar_events(gear.travel, gear.spec.lap_m, gear.spec.exhaust_lap_m,
                        _idle_end(gear))


def plot_zeuner_diagram(gear, ax=None, units_system: str = "US") -> dict:
    """Zeuner's valve diagram (Spangler Arts. 10-18), with every event's crank line.

    The valve's displacement laid off along each crank position traces the valve
    circles, one for each end (Art. 11); the lap circles cut them at admission and
    cut-off, the exhaust-lap circles at release and compression (Arts. 12, 15-16).  The
    crank line through each of those meetings is drawn and lettered with its event
    and angle, the head end's solid and the crank end's dashed; the steam port's
    opening, the valve circle beyond the lap circle, is hatched (Art. 12: "the portion
    remaining is the opening of the port").  The crank turns counter-clockwise from
    head-end dead centre on the right.

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``),
        as :func:`corliss.engine.simulate.build_gear` builds it.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 6.5 x 7 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {"head": Line2D, "crank": Line2D, "crank_lines":
        {end: {event: Line2D}}, ...}, "labels": [Text, ...], "events": {...},
        "crank_radius": float}``: the two valve circles, the crank line of each event
        (:func:`zeuner_events`, from o to ``crank_radius`` [in or mm]) and their labels.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 7))
    u = "in" if units_system == "US" else "mm"
    th = np.linspace(0.0, 2 * np.pi, 1441)
    x = units.to_unit(gear.travel(th), u)
    pos = x > 0
    lines: dict = {}
    for end, mask, rad, ls in (("head", pos, x, "-"), ("crank", ~pos, -x, "--")):
        xs = np.where(mask, rad * np.cos(th), np.nan)
        ys = np.where(mask, rad * np.sin(th), np.nan)
        lines[end] = ax.plot(xs, ys, color="k", lw=1.3, ls=ls, label=f"{end}-end valve circle")[0]
    lh, lc = (units.to_unit(v, u) for v in gear.spec.lap_m)
    eh, ec = (units.to_unit(v, u) for v in gear.spec.exhaust_lap_m)
    # the steam ports' openings: the valve circle beyond the lap circle (hatched)
    for rad, lap, hatch in ((x, lh, "///"), (-x, lc, "\\\\\\")):
        open_ = rad > lap
        if lap >= 0 and open_.any():
            r_in = np.where(open_, rad, lap)
            ax.fill(np.concatenate([r_in * np.cos(th), lap * np.cos(th[::-1])]),
                    np.concatenate([r_in * np.sin(th), lap * np.sin(th[::-1])]),
                    facecolor="none", edgecolor="0.78", hatch=hatch, lw=0.0)
    t = np.linspace(0, 2 * np.pi, 361)
    circles = [(lh, "-", "lap circle" if lh == lc else "head lap circle")]
    if lc != lh:                      # unequal laps (Spangler Art. 31): one circle each
        circles.append((lc, "--", "crank lap circle"))
    circles.append((abs(eh), ":", "exhaust lap circle" if eh == ec else "head exhaust lap circle"))
    if ec != eh:
        circles.append((abs(ec), "-.", "crank exhaust lap circle"))
    for r_, ls, label in circles:
        if r_ > 0:
            lines[label] = ax.plot(r_ * np.cos(t), r_ * np.sin(t), color="0.45", lw=0.8,
                                   ls=ls, label=label)[0]
    rmax = float(np.nanmax(np.abs(x)))
    radius = 1.08 * rmax
    dead_centre_lines(ax, radius)
    ev = zeuner_events(gear)
    labels = crank_lines(ax, ev, radius, lines)
    ax.set_xlim(-1.1 * radius, 1.1 * radius)
    ax.set_ylim(-1.1 * radius, 1.1 * radius)
    period_frame(ax, u, "Zeuner diagram (Arts. 11-17)")
    fit_inside(ax, labels)
    return {"ax": ax, "lines": lines, "labels": labels, "events": ev, "crank_radius": radius}


def _bilgram_point(gear) -> tuple[float, float]:
    """Zeuner's (C, S) of a lapped valve [m]: C = x(0), S = x(pi/2) of its Zeuner form
    (``zeuner_travel`` where the gear has one, else ``travel``)."""
    zt = getattr(gear, "zeuner_travel", None) or gear.travel
    C, S = (float(v) for v in np.asarray(zt(np.array([0.0, 0.5 * np.pi])), dtype=float))
    return C, S


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
    for end, name, level, rising in POLAR_EVENTS:
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
    """Bilgram's valve diagram (Spangler Arts. 149-150), the whole construction inside
    the axes.

    The circle of the eccentric's throw r about o, the Bilgram point d on it at the
    angular advance from the dead-centre line, and the lap and exhaust-lap circles
    about d; the valve's displacement at any crank position is the perpendicular from d
    on the crank line, and the crank lines tangent to the lap circles are the events
    (see :func:`bilgram_events`), each drawn from o and lettered with its event and
    angle.  dk, from d square to the dead-centre line, is the lap plus the lead.  Drawn
    from the gear's Zeuner form, with the crank turning counter-clockwise from head-end
    dead centre on the right, as the Zeuner diagram.  The limits are widened until
    every circle, line and label lies inside (:func:`corliss.plot.labels.fit_inside`).

    Parameters
    ----------
    gear : ValveGear
        A lapped valve gear (its ``travel``, ``spec.lap_m`` and ``spec.exhaust_lap_m``),
        as :func:`corliss.engine.simulate.build_gear` builds it.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 6.5 x 7 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {...}, "labels": [Text, ...], "events": {...},
        "crank_radius": float}``: the valve circle, the point d, the lap circles by
        label and the crank lines (``lines["crank_lines"][end][event]``), the texts,
        :func:`bilgram_events` of the gear and the crank lines' length [in or mm].
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 7))
    u = "in" if units_system == "US" else "mm"
    C, S = _bilgram_point(gear)
    dx, dy = units.to_unit(S, u), units.to_unit(-C, u)
    r = float(np.hypot(dx, dy))
    t = np.linspace(0.0, 2 * np.pi, 361)
    lines: dict = {"valve_circle": ax.plot(r * np.cos(t), r * np.sin(t), color="k", lw=1.3,
                                           label="valve circle (radius r)")[0]}
    lines["od"] = ax.plot([0, dx], [0, dy], color="k", lw=0.8)[0]
    lines["dk"] = ax.plot([dx, dx], [0, dy], color="0.3", lw=0.8,
                          label="dk = lap + lead (k on the dead-centre line)")[0]
    lines["d"] = ax.plot([dx], [dy], "o", color="k", ms=4)[0]
    lh, lc = (units.to_unit(v, u) for v in gear.spec.lap_m)
    eh, ec = (units.to_unit(v, u) for v in gear.spec.exhaust_lap_m)
    circles = [(lh, "-", "lap circle" if lh == lc else "head lap circle")]
    if lc != lh:
        circles.append((lc, "--", "crank lap circle"))
    circles.append((abs(eh), ":", "exhaust-lap circle" if eh == ec else "head exhaust-lap circle"))
    if ec != eh:
        circles.append((abs(ec), "-.", "crank exhaust-lap circle"))
    biggest = 0.0
    for rad, ls, label in circles:
        if rad > 0:
            biggest = max(biggest, rad)
            lines[label] = ax.plot(dx + rad * np.cos(t), dy + rad * np.sin(t), color="0.45",
                                   lw=0.9, ls=ls, label=label)[0]
    ev = bilgram_events(gear)
    idle = _idle_end(gear)
    if idle is not None:
        ev = {**ev, idle: {k: (None if k.endswith("_deg") else v) for k, v in ev[idle].items()}}
    # the crank lines reach past every circle, so their labels lie clear of all
    radius = max(1.1 * r, r + biggest + 0.06 * r)
    dead_centre_lines(ax, radius)
    labels = crank_lines(ax, ev, radius, lines)
    letters = [ax.annotate(name, xy, textcoords="offset points", xytext=(4, 3), fontsize=8)
               for name, xy in (("d", (dx, dy)), ("k", (dx, 0.0)), ("o", (0.0, 0.0)))]
    ax.set_xlim(-1.1 * radius, 1.1 * radius)
    ax.set_ylim(-1.1 * radius, 1.1 * radius)
    period_frame(ax, u, "Bilgram diagram (Art. 149)")
    fit_inside(ax, labels)
    # the letters where no line runs (the limits now fixed)
    place_clear(letters, [ln for ln in ax.lines if ln is not lines["d"]])
    fit_inside(ax, labels + letters)
    return {"ax": ax, "lines": lines, "labels": labels + letters, "events": ev,
            "crank_radius": radius}


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
