"""A measured card over the card fitted to it, in period style: gauge pressure with the
atmospheric line, the measured points as the indicator's dots, the fitted card drawn
through them."""

from __future__ import annotations

import numpy as np

from corliss.keys import units
from corliss.plot.cards import card_abscissa


def _position_m(geometry, end: str, abscissa: str, x):
    """A measured card's abscissa as piston position from head-end dead centre [m]:
    a fraction of the stroke, a position, or the end's volume (the head end's grows
    from its clearance as the piston leaves head-end dead centre, the crank end's from
    its clearance as it leaves crank-end dead centre)."""
    x = np.asarray(x, dtype=float)
    stroke = geometry.spec.stroke_m
    if abscissa == "piston_frac":
        return x * stroke
    if abscissa != "V_m3":
        return x
    side = end.removeprefix("lp_")
    k = 0 if side == "head" else 1
    area = geometry.area_head_m2 if side == "head" else geometry.area_crank_m2
    s = (x - geometry.clearance_m3[k]) / area
    return s if side == "head" else stroke - s


def plot_fit_card(fit, ax=None, units_system: str | None = None) -> dict:
    """The measured card (points) over the fitted card (lines), every end the card holds.

    Parameters
    ----------
    fit : FitResult
        From :func:`corliss.fit`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new 9 x 5.5 in figure when None.
    units_system : str, optional
        ``"US"`` (psig, inches) or ``"SI"`` (bar gauge, mm); default the scene's.

    Returns
    -------
    dict
        ``{"ax": ax, "measured": {end: line}, "fitted": {end: line}}``.
    """
    import matplotlib.pyplot as plt

    system = units_system or fit.scene.output.units
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5.5))
    res = fit.result
    baro = fit.scene.supply.barometer_Pa
    p_unit = "psig" if system == "US" else "barg"
    geos = {prefix: g for prefix, g, _ in res.cylinder_list}
    styles = {"head": dict(color="k", ls="-", marker="o"),
              "crank": dict(color="0.35", ls="--", marker="s")}
    measured, fitted = {}, {}
    unit_x = "in" if system == "US" else "mm"
    stroke = res.geometry.spec.stroke_m
    for end, e in fit.card.ends.items():
        g = geos.get("lp_" if end.startswith("lp_") else "", res.geometry)
        stroke = g.spec.stroke_m
        st = styles.get(end.removeprefix("lp_"), styles["head"])
        c = res.cards[end]
        # every card on one abscissa: a card measured on volume is laid on position
        xs = c["piston_frac"].to_numpy() * stroke
        xm = _position_m(g, end, e.abscissa, e.x)
        xs, xm = units.to_unit(xs, unit_x), units.to_unit(xm, unit_x)
        ys = units.to_unit(c["p_Pa"].to_numpy(), p_unit, barometer_Pa=baro)
        ym = units.to_unit(e.p_Pa, p_unit, barometer_Pa=baro)
        (fitted[end],) = ax.plot(xs, ys, color=st["color"], ls=st["ls"], lw=1.3,
                                 label=f"{end} end, fitted")
        (measured[end],) = ax.plot(xm, ym, ls="none", marker=st["marker"], ms=2.5,
                                   mfc="white", mec=st["color"], mew=0.7,
                                   label=f"{end} end, measured")
    ax.axhline(0.0, color="0.35", lw=0.8)
    # named beyond the card's right edge, where no curve runs
    ax.annotate("atmosphere", (1.0, 0.0), xycoords=ax.get_yaxis_transform(), xytext=(3, 0),
                textcoords="offset points", ha="left", va="center", fontsize=8,
                color="0.35", annotation_clip=False)
    card_abscissa(ax, stroke, system)
    ax.set_ylabel(f"pressure [{p_unit}]")
    parts = []
    for r in fit.ranges:
        v = fit.values[r.key]
        se = fit.standard_errors[r.key]
        unit = f" {r.unit}" if r.unit else ""
        parts.append(f"{r.key} = {v:.4g}" + (f" ± {se:.2g}{unit}" if se is not None
                                              else f"{unit} (not determined by the card)"))
    rms = fit.residual_rms_Pa / (units.PSI_Pa if system == "US" else 1e5)
    ax.set_title(f"{fit.scene.title}: measured card over the fitted one\n"
                 + "; ".join(parts) + f"\nresidual r.m.s. {rms:.3g} "
                 + ("psi" if system == "US" else "bar"), fontsize=9)
    ax.grid(True, color="0.9", lw=0.5)
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return {"ax": ax, "measured": measured, "fitted": fitted}
