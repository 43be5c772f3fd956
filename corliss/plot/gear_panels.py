"""The panels of gears whose motion is not one lapped valve: the double valves
(Spangler Chs. XV-XVIII), the Corliss gear (Ch. XX), the Porter-Allen gear (Arts.
30, 83) and the oscillating cylinder's port face.  Each function draws on a figure (a new one when ``fig`` is None), returns
what it drew and never calls ``show()``; the numbers come from the gears' public
methods.  :func:`corliss.plot.plot_gear` chooses among them by the gear's class.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.keys import units
from corliss.plot.crank_lines import crank_lines, dead_centre_lines, period_frame, polar_events
from corliss.plot.labels import fit_inside
from corliss.valves.buckeye import BuckeyeGear
from corliss.valves.single_acting import working_gear
from corliss.valves.double_valve import DoubleValve
from corliss.valves.gridiron import GridironValve
from corliss.valves.meyer import MeyerValve
from corliss.valves.oscillating import swing_angle

TWO_PI = 2.0 * math.pi
#: Size of a new figure of a gear's own panels [in].
FIGSIZE = (13, 5.5)


def _figure(fig, size=FIGSIZE):
    """``fig``, or a new figure of ``size`` [in] when it is None."""
    if fig is None:
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=size)
    return fig


def _unit(units_system: str) -> str:
    return "in" if units_system == "US" else "mm"


def find_by_class(registry: dict, gear):
    """The entry of a registry keyed on gear classes for the nearest class of a gear.

    Classes are tried along the gear's method resolution order, so a subclass finds
    its parent's entry.

    Parameters
    ----------
    registry : dict
        ``{gear class: entry}``, as :data:`DOUBLE_VALVE_DIAGRAMS` or
        :data:`corliss.plot.gears.GEAR_PANELS`.
    gear : object
        The gear (any object; its type's MRO is searched).

    Returns
    -------
    object or None
        The entry of the nearest class; None if no class of ``gear`` has one.
    """
    for cls in type(working_gear(gear)).__mro__:
        if cls in registry:
            return registry[cls]
    return None


# -- double valves ------------------------------------------------------------------

def plot_double_valve(gear, fig=None, units_system: str = "US") -> dict:
    """Valve travels, steam-port openings and the book's diagram of a double valve.

    Left above: main, cut-off and relative valve travel against crank angle, with the
    laps; left below: the head-end steam opening of each valve and the combined one
    (the crank end's combined dashed), any double admission shaded; right: the valve
    diagram of :func:`plot_double_valve_diagram`.

    Parameters
    ----------
    gear : DoubleValve
        A double valve (riding cut-off, gridiron, Meyer or Buckeye).
    fig : matplotlib.figure.Figure, optional
        Drawn on; a new one of :data:`FIGSIZE` when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"figure": fig, "axes": [travel, openings, diagram], "lines": {...}}``.
    """
    fig = _figure(fig)
    u = _unit(units_system)
    gs = fig.add_gridspec(2, 2, width_ratios=(1.7, 1.0), hspace=0.35, wspace=0.25)
    ax_t, ax_o, ax_d = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[1, 0]), \
        fig.add_subplot(gs[:, 1])
    th = np.linspace(0.0, TWO_PI, 1441)
    deg = np.degrees(th)
    U = lambda v: units.to_unit(np.asarray(v), u)  # noqa: E731
    lines = {"main": ax_t.plot(deg, U(gear.main_travel(th)), color="k", lw=1.4,
                               label="main valve")[0]}
    lines["cutoff"] = ax_t.plot(deg, U(gear.cutoff_travel(th)), color="0.35", lw=1.1,
                                ls="--", label="cut-off valve")[0]
    sh, sc = gear.spec.cutoff.lap_m
    lh, lc = gear.spec.main.lap_m
    if gear.spec.cutoff.kind == "seat":
        marks = [(sh, "cut-off valve closes, +s", ":"), (-sc, "cut-off valve closes, -s", ":")]
    else:
        lines["relative"] = ax_t.plot(deg, U(gear.closing_travel(th)), color="0.45", lw=1.0,
                                      ls=":", label=gear.relative_label)[0]
        marks = [(sh, "head block lap s", ":"), (-sc, "crank block lap s", ":")]
    marks += [(lh, "head steam lap", "-"), (-lc, "crank steam lap", "-")]
    span = float(np.ptp(U(gear.cutoff_travel(th)))) or 1.0
    placed: list[float] = []
    for y, lab, ls in sorted(marks, key=lambda m: -abs(m[0])):
        ax_t.axhline(U(y), color="0.6", lw=0.7, ls=ls)
        yt = float(U(y))
        for other in placed:           # keep the labels of near laps apart
            if abs(yt - other) < 0.07 * span:
                yt = other + math.copysign(0.07 * span, yt - other if yt != other else -yt)
        placed.append(yt)
        ax_t.text(362, yt, lab, fontsize=7, va="center", color="0.4")
    ax_t.axhline(0, color="0.8", lw=0.5)
    ax_t.set_ylabel(f"displacement [{u}]")
    ax_t.legend(fontsize=7, frameon=False, loc="lower left", ncol=3)

    w = gear.port_widths()
    main = np.clip(gear.main_signed(th)[0], 0.0, gear.spec.main.port_width_m)
    cut = np.clip(gear.cutoff_signed(th)[0], 0.0, gear.spec.cutoff.passage_width_m)
    comb = np.clip(gear.signed_openings(th), 0.0, w[:, None])
    ax_o.plot(deg, U(main), color="0.55", lw=1.0, label="main valve, head port")
    ax_o.plot(deg, U(cut), color="0.55", lw=1.0, ls="--", label="cut-off valve, head passage")
    lines["combined"] = ax_o.plot(deg, U(comb[0]), color="k", lw=1.5,
                                  label="both together, head")[0]
    ax_o.plot(deg, U(comb[2]), color="k", lw=1.0, ls="--", label="both together, crank")
    for end, spans in gear.double_admissions().items():
        for a, b in spans:
            ax_o.axvspan(a, b if b > a else b + 360.0, color="0.85", lw=0)
            ax_o.text(a, U(w[0]) * 1.02, f"2nd admission ({end})", fontsize=7, color="0.3")
    ax_o.set_ylabel(f"steam opening [{u}]")
    ax_o.legend(fontsize=7, frameon=False, loc="upper right", ncol=2)
    for ax in (ax_t, ax_o):
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 45))
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
    ax_o.set_xlabel("crank angle from head-end dead centre [deg]")
    plot_double_valve_diagram(gear, ax_d, units_system)
    return {"figure": fig, "axes": [ax_t, ax_o, ax_d], "lines": lines}


def plot_double_valve_diagram(gear, ax=None, units_system: str = "US") -> dict:
    """The book's valve diagram of a double valve, chosen by its class.

    From :data:`DOUBLE_VALVE_DIAGRAMS`: the relative valve circle (Spangler Art. 128)
    for a riding cut-off valve, the combined diagram (Arts. 118-119) for the gridiron,
    the Meyer diagram (Art. 142), the Buckeye's cut-off valve circle on the main valve
    (Arts. 137-139).  Drawn with the crank turning counter-clockwise from head-end dead
    centre on the right.

    Parameters
    ----------
    gear : DoubleValve
        A double valve (riding cut-off, gridiron, Meyer or Buckeye).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 6 x 6 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {label: Line2D}}``.
    """
    if ax is None:
        import matplotlib.pyplot as plt
        _, ax = plt.subplots(figsize=(6, 6))
    u = _unit(units_system)
    body, title = find_by_class(DOUBLE_VALVE_DIAGRAMS, gear)
    lines = body(gear, ax, u)
    _finish_diagram(ax, u, title)
    return {"ax": ax, "lines": lines}


def _relative_circle(gear, ax, u) -> dict:
    """The relative valve circle (Art. 128) of the Zeuner motion, with the block lap
    circle of radius ``s`` (Art. 130: cut-off and re-opening where it cuts the relative
    circle) and the main valve's circle and lap circle in grey."""
    th = np.linspace(0.0, TWO_PI, 1441)
    C, S = gear.zeuner_closing_coefficients()
    xr = units.to_unit(C * np.cos(th) + S * np.sin(th), u)
    lines: dict = {}
    _polar(ax, th, xr, "k", "relative valve circle", lines)
    _polar(ax, th, units.to_unit(gear.main_travel(th), u), "0.6", "main valve circle", lines,
           lw=0.9)
    sh = units.to_unit(gear.spec.cutoff.lap_m[0], u)
    _circle(ax, abs(sh), "0.3", ":" if sh >= 0 else "-.", "block lap s", lines)
    _circle(ax, units.to_unit(gear.spec.main.lap_m[0], u), "0.6", "-", "main lap", lines)
    return lines


def _combined_diagram(gear, ax, u) -> dict:
    """The gridiron's combined diagram (Art. 119, Fig. 80): the main valve circle and lap
    circle, the cut-off valve's circle and the circle of radius s, which cuts it where
    the cut-off valve closes (E) and opens again (F)."""
    th = np.linspace(0.0, TWO_PI, 1441)
    lines: dict = {}
    _polar(ax, th, units.to_unit(gear.main_travel(th), u), "k", "main valve circle", lines)
    _polar(ax, th, units.to_unit(gear.cutoff_travel(th), u), "0.4", "cut-off valve circle",
           lines, lw=1.0)
    _circle(ax, units.to_unit(gear.spec.main.lap_m[0], u), "0.6", "-", "main lap", lines)
    _circle(ax, units.to_unit(gear.spec.cutoff.lap_m[0], u), "0.3", ":", "s = (e + f)/2",
            lines)
    return lines


def _meyer_diagram(gear, ax, u) -> dict:
    """The Meyer diagram (Art. 142, Fig. 92): the relative valve circle, the circle of
    radius L/2 - d about the origin, on which any cut-off line cuts off ``be = L/2 - d =
    y + s``, and the block lap circle s of this setting."""
    lines = _relative_circle(gear, ax, u)
    _circle(ax, units.to_unit(gear.spec.blocks_together_lap_m, u), "0.45", "--",
            "L/2 - d (Art. 142)", lines)
    return lines


def _polar(ax, th, x, color, label, lines, lw=1.3):
    """The Zeuner polar of a displacement: x laid off along each crank line, the
    positive loop (head end) solid and the negative one (crank end) dashed."""
    pos = x > 0
    for mask, rad, ls, lab in ((pos, x, "-", label), (~pos, -x, "--", None)):
        line = ax.plot(np.where(mask, rad * np.cos(th), np.nan),
                       np.where(mask, rad * np.sin(th), np.nan),
                       color=color, lw=lw, ls=ls, label=lab)[0]
        lines.setdefault(label if lab else label + " (crank end)", line)


def _circle(ax, radius, color, ls, label, lines):
    t = np.linspace(0.0, TWO_PI, 361)
    if radius > 0:
        lines[label] = ax.plot(radius * np.cos(t), radius * np.sin(t), color=color, lw=0.8,
                               ls=ls, label=label)[0]


def _finish_diagram(ax, u, title):
    ax.axhline(0, color="0.8", lw=0.6)
    ax.axvline(0, color="0.8", lw=0.6)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(f"[{u}]  (crank turning counter-clockwise from head dead centre, right)")
    ax.xaxis.label.set_fontsize(7)
    ax.legend(fontsize=7, frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)


#: The diagram of each kind of double valve: gear class -> (drawing, title).  A gear
#: takes the entry of its nearest class (see :func:`find_by_class`).
DOUBLE_VALVE_DIAGRAMS = {
    DoubleValve: (_relative_circle, "Relative valve circle (Art. 128)"),
    GridironValve: (_combined_diagram, "Combined diagram (Arts. 118-119)"),
    MeyerValve: (_meyer_diagram, "Meyer diagram (Arts. 128, 142)"),
    BuckeyeGear: (_relative_circle, "Cut-off valve circle on the main valve (Arts. 137-139)"),
}


# -- Corliss gear -------------------------------------------------------------------

def plot_corliss_gear(gear, fig=None, units_system: str = "US") -> dict:
    """Wrist plate and spindle angles, and the four port openings, against crank angle.

    The wrist plate and spindles as in Spangler Art. 156; the steam ports' openings
    latched (dotted) and tripped (solid), Art. 155.  The tripped openings need the
    gear's speed (:meth:`corliss.valves.corliss_gear.CorlissGear.with_speed`); without
    it the latched ones are drawn as the actual ones.

    Parameters
    ----------
    gear : CorlissGear
        The Corliss gear, with its speed for the trip.
    fig : matplotlib.figure.Figure, optional
        Drawn on; a new one of :data:`FIGSIZE` when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"figure": fig, "axes": [angles, openings], "lines": {...}}``.
    """
    fig = _figure(fig)
    u = _unit(units_system)
    ax_a, ax_o = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    th = np.linspace(0.0, TWO_PI, 1441)
    deg = np.degrees(th)
    lines = {"plate": ax_a.plot(deg, np.degrees(gear.plate_angle(th)), color="k", lw=1.6,
                                label="wrist plate")[0]}
    ang = np.degrees(gear.spindle_angles(th))
    styles = [("head steam", "0.2", "-"), ("head exhaust", "0.45", "-"),
              ("crank steam", "0.2", "--"), ("crank exhaust", "0.45", "--")]
    for p, (lab, c, ls) in enumerate(styles):
        lines[lab + " spindle"] = ax_a.plot(deg, ang[p], color=c, lw=1.0, ls=ls,
                                            label=f"{lab} spindle (latched)")[0]
    ax_a.set_ylabel("angle from mid position [deg]")
    ax_a.set_title("Wrist plate and valve spindles (Art. 156)", fontsize=10)
    U = lambda v: units.to_unit(np.asarray(v), u)  # noqa: E731
    w = gear.port_widths()[:, None]
    lat = np.clip(gear.latched_signed_openings(th), 0.0, w)
    act = np.clip(gear.signed_openings(th), 0.0, w) if gear.spec.speed_rad_s else lat
    for p, (lab, c, ls) in enumerate(styles):
        if p in (0, 2):
            lines[lab + " latched"] = ax_o.plot(deg, U(lat[p]), color=c, lw=0.9, ls=":",
                                                label=f"{lab}, latched")[0]
        lines[lab] = ax_o.plot(deg, U(act[p]), color=c, lw=1.4, ls=ls,
                               label=lab + (", tripped" if p in (0, 2) else ""))[0]
    ax_o.set_ylabel(f"port opening [{u}]")
    spd = (f", {gear.spec.speed_rad_s / units.RPM_RAD_S:.0f} rpm"
           if gear.spec.speed_rad_s else "")
    ax_o.set_title(f"Port openings, cam s = {gear.spec.setting:g}{spd} (Art. 155)",
                   fontsize=10)
    for ax in (ax_a, ax_o):
        ax.set_xlabel("crank angle from head-end dead centre [deg]")
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 60))
        ax.axhline(0, color="0.8", lw=0.5)
        ax.grid(True, color="0.9", lw=0.5)
        ax.legend(fontsize=7, frameon=False)
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
    return {"figure": fig, "axes": [ax_a, ax_o], "lines": lines}


# -- Porter-Allen gear --------------------------------------------------------------

def plot_porter_allen(gear, fig=None, units_system: str = "US") -> dict:
    """The Porter-Allen gear in three panels.

    The stems' travels and the four port openings against crank angle, and the Zeuner
    diagram of the steam motion at the radius rod with the laps referred to it
    (Spangler Arts. 30, 83), the crank line of each steam event (admission and cut-off
    of each end) through its circles' meeting.

    Parameters
    ----------
    gear : PorterAllenGear
        The Porter-Allen gear at its setting.
    fig : matplotlib.figure.Figure, optional
        Drawn on; a new one of :data:`FIGSIZE` when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"figure": fig, "axes": [travels, openings, zeuner], "lines": {...},
        "labels": [Text, ...], "events": {...}}``: the steam events' crank lines are
        ``lines["crank_lines"][end][event]``, their angles [deg] ``events``.
    """
    fig = _figure(fig)
    u = _unit(units_system)
    th = np.linspace(0.0, 2 * math.pi, 721)
    deg = np.degrees(th)
    ax1, ax2, ax3 = (fig.add_subplot(1, 3, k) for k in (1, 2, 3))
    lines = {}
    v = units.to_unit(gear.valve_travels(th), u)
    for row, label, style in ((0, "head steam valve", dict(color="k", lw=1.3)),
                              (1, "crank steam valve", dict(color="0.35", lw=1.3, ls="--")),
                              (2, "exhaust valves' stem", dict(color="0.55", lw=1.0, ls=":"))):
        lines[label] = ax1.plot(deg, v[row], label=label, **style)[0]
    lh, lc = gear.spec.steam_lap_m
    laps = ([(lh, "steam laps", "-")] if lh == lc else
            [(lh, "head steam lap", "-"), (lc, "crank steam lap", "--")])
    for lam, label, ls in laps + [(gear.spec.exhaust_lap_m[0], "head exhaust lap", ":")]:
        if lam != 0.0:
            ax1.axhline(units.to_unit(lam, u), color="0.6", lw=0.7, ls=ls)
            ax1.text(362, units.to_unit(lam, u), label, fontsize=7, va="center", color="0.4")
    ax1.set_ylabel(f"stem displacement, + opens its port [{u}]")
    ax1.set_title("Valve travels", fontsize=10)
    op = units.to_unit(gear.openings(th), u)
    n = gear.openings_per_edge()
    for port, label, style in ((0, "head steam", dict(color="k", lw=1.3)),
                               (2, "crank steam", dict(color="0.35", lw=1.3, ls="--")),
                               (1, "head exhaust", dict(color="0.55", lw=1.0)),
                               (3, "crank exhaust", dict(color="0.55", lw=1.0, ls="--"))):
        lines[label] = ax2.plot(deg, op[port], label=label, **style)[0]
        if n[port] > 1:
            # the steam plate's openings together: the area over one opening's length
            together = f"{label}, its {n[port]:g} openings together"
            lines[together] = ax2.plot(deg, n[port] * op[port], label=together,
                                       **{**style, "lw": 0.8, "color": "#b03a2e"})[0]
    ax2.set_ylabel(f"port opening [{u}]")
    ax2.set_title("Port openings" + (f"\n(each edge's; {gear.spec.steam_openings} openings "
                                     "a steam valve)" if n[0] > 1 else ""), fontsize=10)
    for ax in (ax1, ax2):
        ax.axhline(0, color="0.8", lw=0.5)
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 90))
        ax.set_xlabel("crank angle from head-end dead centre [deg]")
        ax.legend(fontsize=7, frameon=False, loc="upper center")
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
    t = np.linspace(0, 2 * math.pi, 1441)
    x = units.to_unit(gear.steam_drive(t), u)
    pos = x > 0
    for end, mask, rad, ls in (("head", pos, x, "-"), ("crank", ~pos, -x, "--")):
        lines[f"{end}-end valve circle"] = ax3.plot(
            np.where(mask, rad * np.cos(t), np.nan), np.where(mask, rad * np.sin(t), np.nan),
            color="k", lw=1.3, ls=ls, label=f"{end}-end valve circle")[0]
    c = np.linspace(0, 2 * math.pi, 361)
    for lam, ls, label in zip(units.to_unit(np.array(gear.spec.equivalent_lap_m), u),
                              ("-", "--"), ("head lap at the rod", "crank lap at the rod")):
        lines[label] = ax3.plot(lam * np.cos(c), lam * np.sin(c), color="0.45", lw=0.8, ls=ls,
                                label=label)[0]
    # the steam events where the valve circles meet the laps at the rod (the exhaust
    # valves have their own motion, not drawn here)
    radius = 1.08 * float(np.nanmax(np.abs(x)))
    dead_centre_lines(ax3, radius)
    ev = polar_events(gear.steam_drive, gear.spec.equivalent_lap_m)
    labels = crank_lines(ax3, ev, radius, lines)
    ax3.set_xlim(-1.1 * radius, 1.1 * radius)
    ax3.set_ylim(-1.1 * radius, 1.1 * radius)
    period_frame(ax3, u, f"Zeuner diagram of the steam motion (s = {gear.spec.setting:g}),\n"
                 "steam events")
    fit_inside(ax3, labels)
    return {"figure": fig, "axes": [ax1, ax2, ax3], "lines": lines, "labels": labels,
            "events": ev}


# -- oscillating cylinder ---------------------------------------------------------------

def plot_oscillating(gear, fig=None, units_system: str = "US") -> dict:
    """An oscillating cylinder in three panels.

    The cylinder's swing against crank angle with the angles at which its port meets
    the standard's (the laps over the port radius), the four port openings, and the port
    face seen from the trunnion's end: the standard's steam and exhaust ports on their
    circle, the cylinder's ports at mid swing and at the swing's extremes, asin(R/D)
    either way (module doc of :mod:`corliss.valves.oscillating`).

    Parameters
    ----------
    gear : OscillatingCylinder or SingleActing
        The gear (single-acting: wrapped by ``[engine] steam_ends``, its head end's
        ports drawn alone).
    fig : matplotlib.figure.Figure, optional
        Drawn on; a new one of :data:`FIGSIZE` when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"figure": fig, "axes": [swing, openings, port face], "lines": {...}}``.
    """
    fig = _figure(fig)
    u = _unit(units_system)
    s = gear.spec
    th = np.linspace(0.0, 2 * math.pi, 721)
    deg = np.degrees(th)
    ax1, ax2, ax3 = (fig.add_subplot(1, 3, k) for k in (1, 2, 3))
    lines = {"swing": ax1.plot(deg, np.degrees(swing_angle(s, th)), color="k", lw=1.4,
                               label="swing psi")[0]}
    rho = s.port_radius_m
    for lam, label, ls in ((s.lap_m[0] / rho, "steam port met", "-"),
                           (-s.exhaust_lap_m[0] / rho, "exhaust port met", ":")):
        ax1.axhline(math.degrees(lam), color="0.6", lw=0.7, ls=ls)
        ax1.text(358, math.degrees(lam), label, fontsize=7, ha="right",
                 va="bottom" if ls == "-" else "top", color="0.4")
    ax1.set_ylabel("cylinder's swing from the line of centres [deg]")
    ax1.set_title(f"Swing, at most asin(R/D) = {math.degrees(s.max_swing_rad):.2f} deg",
                  fontsize=10)
    op = units.to_unit(gear.openings(th), u)
    for port, label, style in ((0, "head steam", dict(color="k", lw=1.3)),
                               (2, "crank steam", dict(color="0.35", lw=1.3, ls="--")),
                               (1, "head exhaust", dict(color="0.55", lw=1.0)),
                               (3, "crank exhaust", dict(color="0.55", lw=1.0, ls="--"))):
        lines[label] = ax2.plot(deg, op[port], label=label, **style)[0]
    ax2.set_ylabel(f"port opening [{u}]")
    # a single-acting oscillator ([engine] steam_ends) works its head end only
    crank_too = getattr(gear, "steam_end", "both") != "head"
    ax2.set_title(f"Port openings ({'double' if crank_too else 'single'}-acting)", fontsize=10)
    for ax in (ax1, ax2):
        ax.axhline(0, color="0.8", lw=0.5)
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 90))
        ax.set_xlabel("crank angle from head-end dead centre [deg]")
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
    ax2.legend(fontsize=7, frameon=False, loc="upper center")
    # the port face: angles from the line of centres, the head end's ports up the page
    r = units.to_unit(rho, u)
    circ = np.linspace(0, 2 * math.pi, 181)
    lines["port circle"] = ax3.plot(r * np.cos(circ), r * np.sin(circ), color="0.8", lw=0.6)[0]

    def slot(centre_rad, width_m, up, **style):
        half = 0.5 * width_m / rho
        a = np.linspace(centre_rad - half, centre_rad + half, 16) + (0.5 * math.pi if up
                                                                      else -0.5 * math.pi)
        return ax3.plot(r * np.cos(a), r * np.sin(a), solid_capstyle="butt", **style)[0]

    for up in (True, False) if crank_too else (True,):
        sign = 1.0 if up else -1.0
        # psi turns the head end's port towards +beta_s; the face is seen with +psi
        # counter-clockwise, so the crank end's steam port is at -beta_s below
        lines["steam ports" if up else "crank steam port"] = slot(
            sign * s.steam_port_angle_rad, s.standard_port_m, up, color="#b03a2e", lw=7,
            alpha=0.6)
        lines["exhaust ports" if up else "crank exhaust port"] = slot(
            -sign * s.exhaust_port_angle_rad, s.standard_port_m, up, color="#2e5fb0", lw=7,
            alpha=0.6)
        for psi, ls in ((0.0, "-"), (s.max_swing_rad, ":"), (-s.max_swing_rad, ":")):
            slot(psi, s.cylinder_port_m, up, color="k", lw=2.5 if psi == 0.0 else 1.5,
                 ls=ls)
    ax3.plot([0], [0], "o", color="0.4", ms=5)
    ax3.set_aspect("equal")
    ax3.set_xlim(-1.5 * r, 1.5 * r)
    ax3.set_ylim(-1.5 * r, 1.5 * r)
    ax3.set_title("Port face: standard's steam (red) and exhaust (blue) ports,\n"
                  "cylinder's port at mid swing and either extreme", fontsize=9)
    ax3.set_xlabel(f"[{u}], the trunnion at the centre, the head end up")
    return {"figure": fig, "axes": [ax1, ax2, ax3], "lines": lines}
