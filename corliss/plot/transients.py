"""Load steps: speed, governor and cut-off against time, with the cards before the
step and at the end; a governor's static characteristic."""

from __future__ import annotations

import numpy as np

from corliss.keys import units
from corliss.plot.cards import card_abscissa


def plot_load_step(result, units_system: str | None = None) -> dict:
    """A load step on one sheet.

    Left, against time: speed (turn by turn and within the turn) with the settling
    band, the governor's position and what it sets (cut-off or throttle opening), and
    the indicated and load power.  Right: the head-end and crank-end cards of the turn
    before the step and of the last turn (against piston position, as every card:
    :func:`corliss.plot.cards.card_abscissa`), and the governor's static characteristic
    with its mean position before the step and at the end.

    Parameters
    ----------
    result : TransientResult
        A transient run (its ``timeseries``, ``cycles``, ``metrics`` and cards).
    units_system : str, optional
        ``"US"`` (hp, psig, inches) or ``"SI"`` (kW, bar gauge, mm); default from the
        scene's ``output.units``.

    Returns
    -------
    dict
        ``{"figure": fig, "axes": {...}}``, the axes keyed ``"speed"``, ``"governor"``,
        ``"power"``, and ``"card_before"``, ``"card_after"`` and ``"static"`` when drawn.
    """
    import matplotlib.pyplot as plt

    system = units_system or result.scene.output.units
    ts, cyc = result.timeseries, result.cycles
    fig = plt.figure(figsize=(13, 9.5))
    gs = fig.add_gridspec(3, 2, width_ratios=(1.8, 1.0), hspace=0.7, wspace=0.3)
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
    if t_step is not None and m.get("regulation_frac") is not None:
        st = m["settling_time_s"]
        title += (f"\nregulation {100 * m['regulation_frac']:+.2f} %, largest change "
                  f"{100 * m['max_deviation_frac']:+.2f} %, settling "
                  + ("beyond the run" if st is None else f"{st:.2f} s"))
    elif not m["settled"]:
        title += "\nnot settled by the end of the run: no steady-state speeds"
    if m["hunting"]:
        title += f"; HUNTING, period {m['hunting_period_s']:.2f} s"
    ax_n.set_title(title, fontsize=10)
    ax_n.legend(fontsize=7, frameon=False, loc="best")
    ax_g.plot(tmid, cyc["governor_z_end_frac"] if "governor_z_end_frac" in cyc else tmid * 0, color="k",
              lw=1.2, label="governor position z (0 at rest, 1 at top stop)")
    if "cutoff_head_frac" in cyc:
        ax_g.plot(tmid, cyc["cutoff_head_frac"], color="0.35", lw=1.2, ls="--",
                  label="cut-off, head end (fraction of stroke)")
    if "throttle_opening_frac" in cyc:
        ax_g.plot(tmid, cyc["throttle_opening_frac"], color="0.35", lw=1.2, ls="--",
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
        pu = "psig" if system == "US" else "barg"
        stroke = result.scene.engine.stroke_m
        xu = "in" if system == "US" else "mm"
        for r, label in enumerate(("before", "after")):
            ax = fig.add_subplot(gs[r, 1])
            for end, style in (("head", "-"), ("crank", "--")):
                card = cards[label][end]
                ax.plot(units.to_unit(card["piston_frac"].to_numpy() * stroke, xu),
                        units.to_unit(card["p_Pa"].to_numpy(), pu, barometer_Pa=baro),
                        color="k", lw=1.1, ls=style, label=f"{end} end")
            ax.axhline(0.0, color="0.35", lw=0.8)
            ax.set_title(f"cards, turn {cards[label]['cycle']} "
                         f"({'before the step' if label == 'before' else 'at the end'})",
                         fontsize=9)
            card_abscissa(ax, stroke, system)
            ax.xaxis.label.set_fontsize(8)
            ax.set_ylabel(f"pressure [{pu}]")
            ax.legend(fontsize=7, frameon=False, loc="upper left", bbox_to_anchor=(1.0, 1.0))
            for side in ("top", "right"):
                ax.spines[side].set_visible(False)
            axes[f"card_{label}"] = ax
    mech = result.mechanism
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
                ax.plot([last["mean_speed_rpm"].mean()], [last["governor_z_frac"].mean()], mark,
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
    """A governor's static characteristic: its position against its balancing speed.

    The speed at which the governor balances without friction
    (:meth:`corliss.governors.mechanism.Governor.static_characteristic`), in rev/min.

    Parameters
    ----------
    governor : Governor
        The governor (any registered type, built from its spec).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 6 x 4.5 in figure when None.
    n : int, optional
        Number of evenly spaced positions z from 0 to 1.

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {"static": Line2D}}``.
    """
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
