"""Willans lines: steam per hour against indicated power across the load range."""

from __future__ import annotations

import numpy as np

from corliss.engine.result import willans_fit
from corliss.keys import units


def plot_willans(sweeps: dict, ax=None, units_system: str = "US") -> dict:
    """Willans lines: steam per hour against indicated power, one line per sweep.

    Each sweep of the load range is drawn with markers, and the least-squares straight
    line through it (:func:`corliss.engine.result.willans_fit`) drawn thin.

    Parameters
    ----------
    sweeps : dict of str to pandas.DataFrame
        ``{label: points}``, each the ``points`` table of a
        :func:`corliss.studies.load_range.load_range` sweep (columns
        ``indicated_power_W`` and ``steam_rate_kg_per_h``).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 8 x 5.5 in figure when None.
    units_system : str, optional
        ``"US"`` (hp, lb/h) or ``"SI"`` (kW, kg/h).

    Returns
    -------
    dict
        ``{"ax": ax, "lines": {label: Line2D}}``.
    """
    import matplotlib.pyplot as plt

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


def plot_compare(result, units_system: str = "US") -> dict:
    """The throttling-versus-cut-off study on one figure, period style.

    Left, the Willans line of each governing with and without condensation, the fitted
    intercept and slope in its label; right, the steam per indicated horse-power-hour
    (or kWh) against the load.  Only the points whose run found its load are drawn.

    Parameters
    ----------
    result : CompareResult
        The study (:func:`corliss.studies.compare.compare`): its ``points`` and
        ``willans`` tables.
    units_system : str, optional
        ``"US"`` (hp, lb/h, lb per ihp-h) or ``"SI"`` (kW, kg/h, kg/kWh).

    Returns
    -------
    dict
        ``{"figure": Figure, "axes": (ax, ax2), "lines": {(variant, condensation):
        Line2D}}``, the lines those of the Willans panel.
    """
    import matplotlib.pyplot as plt

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 5.5))
    us = units_system == "US"
    p_unit, m_unit = ("hp", "lb/h") if us else ("kW", "kg/h")
    m_scale = 1.0 / units.POUND_kg if us else 1.0
    rate_unit = "lb per ihp-h" if us else "kg/kWh"
    rate_scale = units.HP_W / 1000.0 / units.POUND_kg if us else 1.0
    styles = {("throttling", "off"): dict(color="k", marker="o", ls="-"),
              ("throttling", "on"): dict(color="k", marker="o", ls="--"),
              ("cutoff", "off"): dict(color="0.5", marker="s", ls="-"),
              ("cutoff", "on"): dict(color="0.5", marker="s", ls="--")}
    pts = result.points
    pts = pts[pts["status"] == "found"]
    fits = result.willans.set_index(["variant", "condensation"])
    lines = {}
    for (var, cond), g in pts.groupby(["variant", "condensation"], sort=False):
        g = g.sort_values("indicated_power_W")
        style = styles.get((var, cond), dict(color="0.3", marker="^", ls=":"))
        name = f"{'throttled' if var == 'throttling' else 'cut-off governed'}, " \
               f"{'with' if cond == 'on' else 'without'} condensation"
        x = units.to_unit(g["indicated_power_W"].to_numpy(), p_unit)
        label = name
        if (var, cond) in fits.index:
            a = fits.loc[(var, cond), "willans_intercept_kg_per_h"]
            b = fits.loc[(var, cond), "willans_slope_kg_per_kWh"]
            label += (f": {a * m_scale:.0f} {m_unit} + {b * rate_scale:.2f} x {p_unit}"
                      if us else f": {a:.0f} kg/h + {b:.2f} x kW")
            xs = np.linspace(0.0, float(g["indicated_power_W"].max()), 50)
            ax.plot(units.to_unit(xs, p_unit), (a + b * xs / 1000.0) * m_scale,
                    color=style["color"], lw=0.6, alpha=0.7, ls=style["ls"])
        lines[(var, cond)] = ax.plot(x, g["steam_rate_kg_per_h"].to_numpy() * m_scale,
                                     lw=0, ms=5, mfc="white", label=label,
                                     marker=style["marker"], color=style["color"])[0]
        ax2.plot(g["load_frac"].to_numpy() * 100.0,
                 g["water_rate_kg_per_kWh"].to_numpy() * rate_scale, lw=1.2, ms=4,
                 mfc="white", label=name, **style)
    for a_ in (ax, ax2):
        a_.set_xlim(left=0.0)
        a_.set_ylim(bottom=0.0)
        a_.grid(True, color="0.9", lw=0.5)
        a_.legend(fontsize=7.5, frameon=False)
        for side in ("top", "right"):
            a_.spines[side].set_visible(False)
    ax.set_xlabel(f"indicated power [{p_unit}]")
    ax.set_ylabel(f"steam [{m_unit}]")
    ax.set_title("Willans lines: steam = intercept + slope x power", fontsize=10)
    ax2.set_xlabel(f"load [% of {'brake' if result.brake else 'indicated'} rating]")
    ax2.set_ylabel(f"steam [{rate_unit}]")
    ax2.set_title("Steam rate against load", fontsize=10)
    fig.suptitle(f"{result.scene.title}: throttling or cut-off?", fontsize=11)
    return {"figure": fig, "axes": (ax, ax2), "lines": lines}
