"""Plots in period style.  Every function takes ``ax=None``, returns what it drew and
never calls ``show()``.

The indicator card is drawn as the indicator drew it: pressure against piston
position (the drum turned with the crosshead), both ends on one card, gauge pressure
(psig, or bar gauge in SI) with the atmospheric line, and the events marked.
"""

from __future__ import annotations

import numpy as np

from corliss import units

_EVENT_MARK = {"cutoff": ("c/o", "v"), "release": ("rel", "s"), "compression": ("comp", "^"),
               "admission": ("adm", "o")}


def plot_card(result, ax=None, units_system: str | None = None, prefix: str = "") -> dict:
    """Indicator card of both ends of the last cycle.

    Parameters
    ----------
    result : Result
    ax : matplotlib Axes, optional
    units_system : str, optional
        ``"US"`` (psig, inches of stroke) or ``"SI"`` (bar gauge, mm); default from
        the scene.
    prefix : str
        ``""`` for the (first or high-pressure) cylinder, ``"lp_"`` for the
        low-pressure cylinder of a compound.

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {...}, "markers": [...]}``.
    """
    import matplotlib.pyplot as plt

    system = units_system or result.scene.output.units
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5.5))
    baro = result.scene.supply.barometer_Pa
    p_unit, x_unit = ("psig", "in") if system == "US" else ("barg", "mm")
    geo = {p: g for p, g, _ in result.cylinder_list}[prefix]
    stroke = geo.spec.stroke_m
    cards = {end: result.cards[prefix + end] for end in ("head", "crank")}
    lines = {}
    style = {"head": dict(color="k", lw=1.4, ls="-"), "crank": dict(color="0.25", lw=1.4, ls="--")}
    for end, card in cards.items():
        x = units.to_unit(card["piston_frac"].to_numpy() * stroke, x_unit)
        y = units.to_unit(card["p_Pa"].to_numpy(), p_unit, barometer_Pa=baro)
        (lines[end],) = ax.plot(x, y, label=f"{end} end", **style[end])
    xs = units.to_unit(stroke, x_unit)
    ax.axhline(0.0, color="0.35", lw=0.8)
    ax.text(xs * 0.5, 0.0, "atmosphere", ha="center", va="bottom", fontsize=8, color="0.35")
    vac = units.to_unit(0.0, p_unit, barometer_Pa=baro)
    ax.axhline(vac, color="0.6", lw=0.6, ls=":")
    ax.text(xs * 0.995, vac, "zero pressure", ha="right", va="bottom", fontsize=7, color="0.5")
    markers = []
    events = result.events if prefix == "" else (getattr(result, "lp_events", None) or {})
    for end, ev in events.items():
        card = cards[end]
        for name, (label, m) in _EVENT_MARK.items():
            deg = ev.get(f"{name}_deg")
            if deg is None:
                continue
            th = np.radians(deg)
            frac = float(geo.fraction(th))
            if "crank_angle_deg" in card:
                ang = np.mod(card["crank_angle_deg"].to_numpy(), 360.0)
                i = int(np.argmin(np.abs(((ang - deg) + 180.0) % 360.0 - 180.0)))
                p = card["p_Pa"].iloc[i]
            else:
                i = int(np.argmin(np.abs(card["piston_frac"].to_numpy() - frac)))
                p = card["p_Pa"].iloc[i]
            xm = units.to_unit(frac * stroke, x_unit)
            ym = units.to_unit(p, p_unit, barometer_Pa=baro)
            markers.append(ax.plot([xm], [ym], m, ms=4, color=style[end]["color"])[0])
            ax.annotate(label, (xm, ym), textcoords="offset points", xytext=(3, 4), fontsize=7,
                        color=style[end]["color"])
    s = result.summary
    ax.set_xlim(-0.02 * xs, 1.02 * xs)
    ax.set_xlabel(f"piston position from head-end dead centre [{x_unit}]")
    ax.set_ylabel(f"pressure [{p_unit}]")
    if prefix == "":
        which, power, mep = "", s["indicated_power_W"], s["mep_mean_Pa"]
        if "hp_power_W" in s:
            which, power = "high-pressure cylinder, ", s["hp_power_W"]
    else:
        which, power = "low-pressure cylinder, ", s["lp_power_W"]
        mep = power * 2 * np.pi / result.scene.run.speed_rad_s / sum(geo.swept_m3)
    ax.set_title(f"{result.scene.title}\n{which}{s['speed_rpm']:.0f} rpm, "
                 f"{units.to_unit(power, 'hp'):.1f} ihp, m.e.p. "
                 f"{units.to_unit(mep, 'psia' if system == 'US' else 'bar'):.1f} "
                 f"{'psi' if system == 'US' else 'bar'}", fontsize=10)
    ax.grid(True, color="0.9", lw=0.5)
    ax.legend(loc="center", fontsize=8, frameon=False)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines, "markers": markers}


def plot_crank_effort(result, ax=None, units_system: str | None = None) -> dict:
    """Crank-effort diagram: shaft torque against crank angle over the last cycle, with
    the mean torque (the uniform resistance of Marks Arts. 56-59) and the excess and
    deficit shaded; the friction torque and net torque where ``friction`` is named.

    Returns ``{"ax": ax, "lines": {...}}``.
    """
    import matplotlib.pyplot as plt

    system = units_system or result.scene.output.units
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 4.5))
    t_unit = "lbf ft" if system == "US" else "N m"
    ce = result.crank_effort
    ang = ce["crank_angle_deg"].to_numpy()
    ang = ang - 360.0 * np.floor(ang[0] / 360.0)
    tq = units.to_unit(ce["torque_N_m"].to_numpy(), t_unit)
    mean = units.to_unit(result.summary["mean_torque_N_m"], t_unit)
    lines = {"torque": ax.plot(ang, tq, color="k", lw=1.3, label="crank effort")[0],
             "mean": ax.axhline(mean, color="0.4", lw=0.9, ls="--", label="mean (uniform load)")}
    ax.fill_between(ang, tq, mean, where=tq >= mean, color="0.8", lw=0, label="excess")
    ax.fill_between(ang, tq, mean, where=tq < mean, color="0.93", hatch="///", lw=0,
                    edgecolor="0.6", label="deficit")
    if "friction_torque_N_m" in ce:
        lines["net"] = ax.plot(ang, units.to_unit(ce["net_torque_N_m"].to_numpy(), t_unit),
                               color="0.3", lw=0.9, ls=":", label="less friction")[0]
    s = result.summary
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.set_xlabel("crank angle from head-end dead centre [deg]")
    ax.set_ylabel(f"torque [{t_unit}]")
    ax.set_title(f"Crank effort: fluctuation c = {s['fluctuation_coefficient_c']:.3f} of one "
                 "stroke's work", fontsize=10)
    ax.grid(True, color="0.9", lw=0.5)
    ax.legend(fontsize=8, frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              ncol=5)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines}


def plot_valve_travel(gear, ax=None, units_system: str = "US") -> dict:
    """Valve travel against crank angle, the exact motion over Zeuner's where the gear
    has both, with the steam and exhaust laps of each end as horizontal lines."""
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
    """Zeuner's valve diagram (Spangler Arts. 10-18): the valve's displacement laid off
    along each crank position traces the valve circles, one for each end; the lap
    circles cut them at admission and cut-off, the exhaust-lap circles at release and
    compression.  Drawn with the crank rotating counter-clockwise from head-end dead
    centre on the right."""
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
    for r_, label in ((lh, "lap"), (abs(eh), "exhaust lap")):
        if r_ > 0:
            ax.plot(r_ * np.cos(t), r_ * np.sin(t), color="0.55", lw=0.8,
                    ls="-" if label == "lap" else ":", label=f"{label} circle")
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


def plot_load_step(result, units_system: str | None = None) -> dict:
    """A load step on one sheet: speed (turn by turn and within the turn), the governor's
    position and what it sets (cut-off or throttle opening) against time, the load, and
    the head-end and crank-end cards of the turn before the step and of the last turn.

    Returns ``{"figure": fig, "axes": {...}}``.
    """
    import matplotlib.pyplot as plt

    system = units_system or result.scene.output.units
    ts, cyc = result.timeseries, result.cycles
    fig = plt.figure(figsize=(13, 8.5))
    gs = fig.add_gridspec(3, 2, width_ratios=(1.8, 1.0), hspace=0.45, wspace=0.25)
    ax_n = fig.add_subplot(gs[0, 0])
    ax_g = fig.add_subplot(gs[1, 0], sharex=ax_n)
    ax_l = fig.add_subplot(gs[2, 0], sharex=ax_n)
    tmid = 0.5 * (cyc["t_start_s"] + cyc["t_end_s"])
    ax_n.plot(ts["time_s"], ts["speed_rpm"], color="0.7", lw=0.6, label="speed within the turn")
    ax_n.plot(tmid, cyc["mean_speed_rpm"], color="k", lw=1.4, label="mean speed of each turn")
    t_step = result.step_time_s
    m = result.metrics
    band = result.scene.run.settling_band
    n1 = m["final_speed_rpm"]
    ax_n.axhspan(n1 * (1 - band), n1 * (1 + band), color="0.92", lw=0,
                 label=f"settling band ({100 * band:g} %)")
    ax_n.set_ylabel("speed [rev/min]")
    title = result.scene.title
    if t_step is not None and m.get("regulation") is not None:
        st = m["settling_time_s"]
        title += (f"\nregulation {100 * m['regulation']:+.2f} %, largest change "
                  f"{100 * m['max_deviation_frac']:+.2f} %, settling "
                  + ("beyond the run" if st is None else f"{st:.2f} s"))
    if m["hunting"]:
        title += f"; HUNTING, period {m['hunting_period_s']:.2f} s"
    ax_n.set_title(title, fontsize=10)
    ax_n.legend(fontsize=7, frameon=False, loc="best")
    ax_g.plot(tmid, cyc["governor_z_end"] if "governor_z_end" in cyc else tmid * 0, color="k",
              lw=1.2, label="governor position z (0 at rest, 1 at top stop)")
    if "cutoff_head_frac" in cyc:
        ax_g.plot(tmid, cyc["cutoff_head_frac"], color="0.35", lw=1.2, ls="--",
                  label="cut-off, head end (fraction of stroke)")
    if "throttle_opening" in cyc:
        ax_g.plot(tmid, cyc["throttle_opening"], color="0.35", lw=1.2, ls="--",
                  label="throttle opening")
    ax_g.set_ylim(-0.05, 1.05)
    ax_g.set_ylabel("[-]")
    ax_g.legend(fontsize=7, frameon=False, loc="best")
    p_unit = "hp" if system == "US" else "kW"
    ax_l.plot(tmid, units.to_unit(cyc["indicated_power_W"].to_numpy(), p_unit), color="k",
              lw=1.2, label="indicated power")
    ax_l.plot(tmid, units.to_unit(cyc["load_power_W"].to_numpy(), p_unit), color="0.45", lw=1.2,
              ls="--", label="load power")
    ax_l.set_ylabel(f"power [{p_unit}]")
    ax_l.set_xlabel("time [s]")
    ax_l.legend(fontsize=7, frameon=False, loc="best")
    for ax in (ax_n, ax_g, ax_l):
        if t_step is not None:
            ax.axvline(t_step, color="0.5", lw=0.7, ls=":")
        ax.grid(True, color="0.9", lw=0.5)
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
    axes = {"speed": ax_n, "governor": ax_g, "power": ax_l}
    cards = result.cards()
    if cards:
        baro = result.scene.supply.barometer_Pa
        pu, vu = ("psig", "ft3") if system == "US" else ("barg", "L")
        for r, label in enumerate(("before", "after")):
            ax = fig.add_subplot(gs[r, 1])
            for end, style in (("head", "-"), ("crank", "--")):
                card = cards[label][end]
                ax.plot(units.to_unit(card["V_m3"].to_numpy(), vu),
                        units.to_unit(card["p_Pa"].to_numpy(), pu, barometer_Pa=baro),
                        color="k", lw=1.1, ls=style, label=f"{end} end")
            ax.axhline(0.0, color="0.35", lw=0.8)
            ax.set_title(f"cards, turn {cards[label]['cycle']} "
                         f"({'before the step' if label == 'before' else 'at the end'})",
                         fontsize=9)
            ax.set_xlabel(f"volume [{vu}]")
            ax.set_ylabel(f"pressure [{pu}]")
            ax.legend(fontsize=7, frameon=False)
            for side in ("top", "right"):
                ax.spines[side].set_visible(False)
            axes[f"card_{label}"] = ax
    mech = getattr(result.tables, "mechanism", None) if result.tables is not None else None
    if mech is not None:
        ax = fig.add_subplot(gs[2, 1])
        z = np.asarray(mech.z)
        with np.errstate(invalid="ignore", divide="ignore"):
            w = np.sqrt(np.asarray(mech.R) / np.asarray(mech.G)) / mech.ratio
        ax.plot(w * 60.0 / (2 * np.pi), z, color="k", lw=1.3, label="static characteristic")
        c = cyc
        before = c[c["t_end_s"] <= t_step] if t_step is not None else c.iloc[:0]
        for rows, mark, label in ((before, "o", "before the step"), (c, "s", "at the end")):
            if len(rows):
                last = rows.iloc[-5:]
                ax.plot([last["mean_speed_rpm"].mean()], [last["governor_z"].mean()], mark,
                        color="0.3", ms=6, mfc="white", label=label)
        ax.set_xlabel("shaft speed [rev/min]")
        ax.set_ylabel("governor position z [-]")
        ax.set_ylim(-0.05, 1.05)
        ax.set_title(f"governor: {result.scene.governor_type}", fontsize=9)
        ax.legend(fontsize=7, frameon=False)
        ax.grid(True, color="0.9", lw=0.5)
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
        axes["static"] = ax
    return {"figure": fig, "axes": axes}


def plot_static_characteristic(governor, ax=None, n: int = 101) -> dict:
    """A governor's static characteristic: its position against the shaft speed at
    which it balances, with the friction band where the mechanism has friction."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.5))
    z, w = governor.static_characteristic(n)
    rpm = np.asarray(w) * 60.0 / (2.0 * np.pi)
    lines = {"static": ax.plot(rpm, z, color="k", lw=1.4, label="equilibrium")[0]}
    ax.set_xlabel("shaft speed [rev/min]")
    ax.set_ylabel("governor position z [-]")
    ax.set_ylim(-0.05, 1.05)
    ax.grid(True, color="0.9", lw=0.5)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
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

    The Bilgram point d lies at the throw r from o, at the angular advance from the
    dead-centre line oa, on the side that makes the perpendicular from d on the crank
    line the valve's displacement: with the crank at theta (counter-clockwise from
    head-end dead centre) d = (S, -C), and that perpendicular is d . (sin theta, -cos
    theta) = C cos theta + S sin theta = r sin(theta + delta).  A port opens or closes
    where the crank line is tangent to the circle about d of radius the lap (steam) or
    exhaust lap: the two tangents from o make the angles +-asin(lap / od) with od.  Of
    each tangent line, the crank is on the ray on whose side d lies as the event needs
    (x = +lap for the head end, -lap for the crank end), and the tangent point (the foot
    of the perpendicular from d) lies on the crank's ray where the displacement is
    growing (its rate is d . (cos theta, sin theta)), behind o where it is falling: so
    the two tangents tell opening from closing.

    Returns ``{"head": {...}, "crank": {...}}`` with ``admission_deg``, ``cutoff_deg``,
    ``release_deg``, ``compression_deg`` in [0, 360) (None where the circle encloses o:
    the port never closes or never opens), and ``lead_m`` = dk - lap, dk being the
    distance of d from oa (lap + lead, Art. 149).
    """
    C, S = _bilgram_point(gear)
    dx, dy = S, -C
    rho, alpha = float(np.hypot(dx, dy)), float(np.arctan2(dy, dx))
    laps, elaps = gear.spec.lap_m, gear.spec.exhaust_lap_m
    out = {"head": {}, "crank": {}}
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
    """Bilgram's valve diagram (Spangler Arts. 149-150): the circle of the eccentric's
    throw r about o, the Bilgram point d on it at the angular advance from the
    dead-centre line, and the lap and exhaust-lap circles about d; the valve's
    displacement at any crank position is the perpendicular from d on the crank line,
    and the crank lines tangent to the lap circles are the events (see
    :func:`bilgram_events`).  dk, from d square to the dead-centre line, is the lap
    plus the lead.  Drawn from the gear's Zeuner form, with the crank turning
    counter-clockwise from head-end dead centre on the right, as the Zeuner diagram."""
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


def plot_willans(sweeps: dict, ax=None, units_system: str = "US") -> dict:
    """Willans lines: steam per hour against indicated power, one line per sweep of the
    load range (``{label: frame}`` from :func:`corliss.engine.load_range.load_range`),
    with the least-squares straight line of each drawn thin."""
    import matplotlib.pyplot as plt

    from corliss.engine.load_range import willans_fit

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 5.5))
    p_unit, m_unit = ("hp", "lb/h") if units_system == "US" else ("kW", "kg/h")
    m_scale = 1.0 / units.POUND_kg if units_system == "US" else 1.0
    styles = [dict(color="k", marker="o"), dict(color="0.45", marker="s", ls="--"),
              dict(color="0.25", marker="^", ls=":")]
    lines = {}
    for (label, frame), style in zip(sweeps.items(), styles * 3):
        frame = frame.sort_values("indicated_power_W")
        x = units.to_unit(frame["indicated_power_W"].to_numpy(), p_unit)
        y = frame["steam_rate_kg_per_h"].to_numpy() * m_scale
        lines[label] = ax.plot(x, y, lw=1.3, ms=4, mfc="white", label=label, **style)[0]
        a, b, r2 = willans_fit(frame)
        xs = np.linspace(0.0, float(frame["indicated_power_W"].max()), 50)
        ax.plot(units.to_unit(xs, p_unit), (a + b * xs) * m_scale, color=style["color"], lw=0.6,
                ls="-", alpha=0.6)
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel(f"indicated power [{p_unit}]")
    ax.set_ylabel(f"steam [{m_unit}]")
    ax.set_title("Willans lines: steam against power across the load range", fontsize=10)
    ax.grid(True, color="0.9", lw=0.5)
    ax.legend(fontsize=8, frameon=False)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines}
