"""Indicator cards and crank-effort diagrams in period style.

The indicator card is drawn as the indicator drew it: pressure against piston
position (the drum turned with the crosshead), both ends on one card, gauge pressure
(psig, or bar gauge in SI) with the atmospheric line, and the events marked.
"""

from __future__ import annotations

import numpy as np

from corliss.keys import units
from corliss.plot.labels import place_clear

_EVENT_MARK = {"cutoff": ("c/o", "v"), "release": ("rel", "s"), "compression": ("comp", "^"),
               "admission": ("adm", "o")}


#: The label of every card's abscissa (the indicator drum turned with the crosshead).
POSITION_LABEL = "piston position from head-end dead centre"


def card_abscissa(ax, stroke_m: float, units_system: str, volume=None) -> str:
    """Set a card's abscissa: piston position in the scene's units, with the fraction
    of the stroke on the axis above (and an end's volume, where given, below it).

    Every card corliss draws (a steady run's, a load step's, a fitted one) is drawn on
    this one abscissa, so cards compare by eye.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The card's axes, its x data in ``in`` (US) or ``mm`` (SI) from head-end dead
        centre.
    stroke_m : float
        The stroke [m].
    units_system : str
        ``"US"`` (inches) or ``"SI"`` (mm).
    volume : (str, float, float, str) or None, optional
        ``(end, clearance [m3], area [m2], unit)``: an end's volume as a secondary axis
        under the plot (``unit`` ``"ft3"`` or ``"L"``; for the crank end the volume
        grows towards head-end dead centre); None for none.

    Returns
    -------
    str
        The unit of the abscissa, ``"in"`` or ``"mm"``.
    """
    x_unit = "in" if units_system == "US" else "mm"
    xs = float(units.to_unit(stroke_m, x_unit))
    ax.set_xlabel(f"{POSITION_LABEL} [{x_unit}]")
    top = ax.secondary_xaxis("top", functions=(lambda x: x / xs, lambda f: f * xs))
    top.set_xlabel("fraction of the stroke", fontsize=8, color="0.35")
    top.tick_params(labelsize=7, colors="0.35")
    if volume is not None:
        end, clearance, area, v_unit = volume
        m = float(units.to_unit(stroke_m, x_unit)) / stroke_m       # axis units per metre

        def to_v(x, sign=1.0 if end == "head" else -1.0):
            s = np.asarray(x, dtype=float) / m
            return units.to_unit(clearance + area * (s if sign > 0 else stroke_m - s), v_unit)

        def to_x(v):
            s = (units.from_unit(np.asarray(v, dtype=float), v_unit) - clearance) / area
            return (s if end == "head" else stroke_m - s) * m

        low = ax.secondary_xaxis(-0.2, functions=(to_v, to_x))
        low.set_xlabel(f"{end}-end volume [{v_unit}]", fontsize=8, color="0.35")
        low.tick_params(labelsize=7, colors="0.35")
    return x_unit


def plot_card(result, ax=None, units_system: str | None = None, prefix: str = "") -> dict:
    """Indicator card of both ends of the last cycle.

    Pressure (gauge, above the scene's barometer) against piston position from
    head-end dead centre, the atmospheric and zero-pressure lines, and the events
    (cut-off, release, compression, admission) marked on each end's card; the title
    gives speed, indicated power and mean effective pressure.

    Parameters
    ----------
    result : SteadyResult
        A steady run (or any result with ``cards``, ``events`` and ``summary``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 9 x 5.5 in figure when None.
    units_system : str, optional
        ``"US"`` (psig, inches of stroke) or ``"SI"`` (bar gauge, mm); default from
        the scene's ``output.units``.
    prefix : str, optional
        ``""`` for the (first or high-pressure) cylinder, ``"lp_"`` for the
        low-pressure cylinder of a compound.

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {"head": Line2D, "crank": Line2D}, "markers": [Line2D,
        ...], "labels": [Annotation, ...]}``, the event markers and their labels in the
        order drawn (each label placed where neither card line runs,
        :func:`corliss.plot.labels.place_clear`).
    """
    import matplotlib.pyplot as plt

    system = units_system or result.scene.output.units
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5.5))
    baro = result.scene.supply.barometer_Pa
    p_unit, x_unit = ("psig", "in") if system == "US" else ("barg", "mm")
    geo = {p: g for p, g, _ in result.cylinder_list}[prefix]
    stroke = geo.spec.stroke_m
    held = result.card_frames()            # the cards without pandas
    cards = {end: held[prefix + end] for end in ("head", "crank")}
    lines = {}
    style = {"head": dict(color="k", lw=1.4, ls="-"), "crank": dict(color="0.25", lw=1.4, ls="--")}
    for end, card in cards.items():
        x = units.to_unit(card["piston_frac"].to_numpy() * stroke, x_unit)
        y = units.to_unit(card["p_Pa"].to_numpy(), p_unit, barometer_Pa=baro)
        (lines[end],) = ax.plot(x, y, label=f"{end} end", **style[end])
    xs = units.to_unit(stroke, x_unit)
    ax.axhline(0.0, color="0.35", lw=0.8)
    # the two lines named beyond the card's right edge, where no curve runs
    beside = ax.get_yaxis_transform()       # x in the axes' fraction, y in data
    ax.annotate("atmosphere", (1.0, 0.0), xycoords=beside, xytext=(3, 0),
                textcoords="offset points", ha="left", va="center", fontsize=8,
                color="0.35", annotation_clip=False)
    vac = units.to_unit(0.0, p_unit, barometer_Pa=baro)
    ax.axhline(vac, color="0.6", lw=0.6, ls=":")
    ax.annotate("zero pressure", (1.0, vac), xycoords=beside, xytext=(3, 0),
                textcoords="offset points", ha="left", va="center", fontsize=7, color="0.5",
                annotation_clip=False)
    markers = []
    labels = []
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
            labels.append(ax.annotate(label, (xm, ym), textcoords="offset points",
                                      xytext=(3, 4), fontsize=7, color=style[end]["color"]))
    s = result.summary
    ax.set_xlim(-0.02 * xs, 1.02 * xs)
    # a single-acting cylinder's card is its working end's: its volume read below
    working = getattr(result.scene.engine, "steam_ends", "both")
    volume = None
    if working in ("head", "crank") and prefix == "":
        k = 0 if working == "head" else 1
        area = geo.area_head_m2 if working == "head" else geo.area_crank_m2
        volume = (working, geo.clearance_m3[k], area, "ft3" if system == "US" else "L")
    card_abscissa(ax, stroke, system, volume)
    ax.set_ylabel(f"pressure [{p_unit}]")
    if prefix == "":
        which, power, mep = "", s["indicated_power_W"], s["mep_mean_Pa"]
        if "hp_power_W" in s:
            which, power = "high-pressure cylinder, ", s["hp_power_W"]
    else:
        which, power = "low-pressure cylinder, ", s["lp_power_W"]
        mep = power * 2 * np.pi / result.scene.run.speed_rad_s / sum(geo.swept_m3)
    ax.set_title(f"{result.scene.title}\n{which}{s['speed_rpm']:.0f} rpm, "
                 + (f"{units.to_unit(power, 'hp'):.1f} ihp" if system == "US"
                    else f"{power / 1e3:.2f} kW indicated")
                 + ", m.e.p. "
                 f"{units.to_unit(mep, 'psia' if system == 'US' else 'bar'):.{1 if system == 'US' else 2}f} "
                 f"{'psi' if system == 'US' else 'bar'}", fontsize=10)
    ax.grid(True, color="0.9", lw=0.5)
    # the legend outside the diagram, where it crosses no curve
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    # the event labels near their points, where no curve runs (the limits fixed first:
    # they set where a text lands)
    ax.set_ylim(*ax.get_ylim())
    place_clear(labels, list(lines.values()))
    return {"ax": ax, "lines": lines, "markers": markers, "labels": labels}


def plot_crank_effort(result, ax=None, units_system: str | None = None) -> dict:
    """Crank-effort diagram: shaft torque against crank angle over the last cycle.

    With the mean torque (the uniform resistance of Marks Arts. 56-59) and the excess
    and deficit shaded; the net torque less friction where the scene names
    ``friction``.  The title gives the coefficient of fluctuation of Marks Art. 57.

    Parameters
    ----------
    result : SteadyResult
        A steady run (its ``crank_effort`` table and ``summary``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 9 x 4.5 in figure when None.
    units_system : str, optional
        ``"US"`` (torque in lbf ft) or ``"SI"`` (N m); default from the scene's
        ``output.units``.

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {"torque": Line2D, "mean": Line2D}}``, with ``"net"``
        when friction is named.
    """
    import matplotlib.pyplot as plt

    system = units_system or result.scene.output.units
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 4.5))
    t_unit = "lbf ft" if system == "US" else "N m"
    ce = result.frame("crank_effort")
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
    c = s["fluctuation_coefficient_c"]
    ax.set_title("Crank effort: " + (f"fluctuation c = {c:.3f} of one stroke's work" if c is not None
                                     else "fluctuation c " + s["fluctuation_coefficient_note"]
                                     .replace(", so", ",\n so")), fontsize=10)
    ax.grid(True, color="0.9", lw=0.5)
    ax.legend(fontsize=8, frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              ncol=5)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "lines": lines}
