"""Willans lines: steam per hour against indicated power across the load range."""

from __future__ import annotations

import numpy as np

from corliss import units


def plot_willans(sweeps: dict, ax=None, units_system: str = "US") -> dict:
    """Willans lines: steam per hour against indicated power, one line per sweep of the
    load range (``{label: frame}`` from :func:`corliss.engine.load_range.load_range`),
    with the least-squares straight line of each drawn thin."""
    import matplotlib.pyplot as plt

    from corliss.engine.result import willans_fit

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
