"""One redraw of the workbench: a scene's tables in, everything the page shows out.

:func:`compute_view` loads the edited scene, runs its steady card and gathers what the
page draws (the card of each end with its events, the events table, the Zeuner
diagram, the port openings against crank angle and the summary), in the units the
page shows, as arrays (sent to the browser as binary buffers), numbers and text: it runs in a worker process, off the page
server's event loop, and its answer crosses back by pickling.  A scene the loader
refuses comes back as its message and the key it names.
"""

from __future__ import annotations

import math
import time

import numpy as np

from corliss.engine.model import build_gear, steady_scene
from corliss.engine.result import SteadyResult
from corliss.engine.simulate import simulate
from corliss.engine.summary_keys import SteadySummary, end_value
from corliss.errors import InputError, RunError
from corliss.keys import units
from corliss.scene.loader import scene_from_dict
from corliss.valves.gear import PORTS, openings_note

#: The events marked on the card, with their labels (as :func:`corliss.plot.cards.plot_card`).
EVENT_LABELS = {"admission": "adm", "cutoff": "c/o", "release": "rel", "compression": "comp"}
#: Crank angles the port openings and the Zeuner diagram are drawn at.
ANGLES = 721


def _fmt(x, digits: int = 4) -> str:
    return "never" if x is None else f"{x:.{digits}g}"


def card_view(result, system: str) -> dict:
    """The card of each end and its event marks, in the page's units.

    Parameters
    ----------
    result : SteadyResult
        The run.
    system : str
        ``"US"`` (psig against inches of stroke) or ``"SI"`` (bar gauge against mm).

    Returns
    -------
    dict
        ``{"head": {"x", "y"}, "crank": {...}, "marks": {"x", "y", "label", "end"},
        "x_unit", "p_unit", "stroke", "vacuum"}``: piston position from head-end dead
        centre and gauge pressure, the events where the card passes them.
    """
    baro = result.scene.supply.barometer_Pa
    p_unit, x_unit = ("psig", "in") if system == "US" else ("barg", "mm")
    geo = {p: g for p, g, _ in result.cylinder_list}[""]
    stroke = geo.spec.stroke_m
    held = result.card_frames()
    out = {"x_unit": x_unit, "p_unit": p_unit,
           "stroke": float(units.to_unit(stroke, x_unit)),
           "vacuum": float(units.to_unit(0.0, p_unit, barometer_Pa=baro))}
    marks: dict[str, list] = {"x": [], "y": [], "label": [], "end": []}
    for end in ("head", "crank"):
        card = held[end]
        frac = np.asarray(card["piston_frac"], dtype=float)
        p = np.asarray(card["p_Pa"], dtype=float)
        out[end] = {"x": np.asarray(units.to_unit(frac * stroke, x_unit), dtype=float),
                    "y": np.asarray(units.to_unit(p, p_unit, barometer_Pa=baro), dtype=float)}
        ev = result.events.get(end, {})
        ang = np.mod(np.asarray(card["crank_angle_deg"], dtype=float), 360.0) \
            if "crank_angle_deg" in card else None
        for name, label in EVENT_LABELS.items():
            deg = ev.get(f"{name}_deg")
            if deg is None:
                continue
            f = float(geo.fraction(math.radians(deg)))
            i = int(np.argmin(np.abs(((ang - deg) + 180.0) % 360.0 - 180.0))) \
                if ang is not None else int(np.argmin(np.abs(frac - f)))
            marks["x"].append(float(units.to_unit(f * stroke, x_unit)))
            marks["y"].append(float(units.to_unit(p[i], p_unit, barometer_Pa=baro)))
            marks["label"].append(label)
            marks["end"].append(end)
    out["marks"] = marks
    return out


def events_rows(events: dict, system: str) -> dict:
    """The events table: a row per event, a column per end, as the page shows them.

    Parameters
    ----------
    events : dict
        ``{"head": {...}, "crank": {...}}`` as :func:`corliss.valves.events.events`.
    system : str
        ``"US"`` (inches) or ``"SI"`` (mm) for the lead and the opening.

    Returns
    -------
    dict
        Columns ``"event"``, ``"head"``, ``"crank"`` of text.
    """
    u = "in" if system == "US" else "mm"
    rows = [("admission, crank angle [deg]", "admission_deg", 1.0, 5),
            ("cut-off, fraction of stroke", "cutoff_frac", 1.0, 3),
            ("release, fraction of stroke", "release_frac", 1.0, 3),
            ("compression, fraction of stroke", "compression_frac", 1.0, 3),
            (f"lead [{u}]", "lead_m", None, 3),
            (f"greatest opening, all its edges [{u}]", "max_port_opening_m", None, 3)]
    out: dict[str, list] = {"event": [], "head": [], "crank": []}
    for label, key, _, digits in rows:
        out["event"].append(label)
        for end in ("head", "crank"):
            v = events.get(end, {}).get(key)
            if v is not None and key.endswith("_m"):
                v = float(units.to_unit(v, u))
            out[end].append(_fmt(v, digits))
    return out


def ports_view(gear, system: str) -> dict:
    """Each port's opening against crank angle, in inches or mm.

    Parameters
    ----------
    gear : ValveGear
        The built gear.
    system : str
        ``"US"`` or ``"SI"``.

    Returns
    -------
    dict
        ``{"deg": [...], "head_steam": [...], ...}`` (the ports of
        :data:`corliss.valves.gear.PORTS`).
    """
    th = np.linspace(0.0, 2.0 * np.pi, ANGLES)
    op = units.to_unit(np.asarray(gear.openings(th), dtype=float), "in" if system == "US"
                       else "mm")
    out = {"deg": np.degrees(th)}
    for i, port in enumerate(PORTS):
        out[port] = op[i]
    return out


def zeuner_view(gear, system: str) -> dict | None:
    """Zeuner's valve circles and the lap circles (as
    :func:`corliss.plot.gears.plot_zeuner_diagram`), or None for a gear whose motion
    is not one lapped valve (no ``travel`` and laps).

    Parameters
    ----------
    gear : ValveGear
        The built gear.
    system : str
        ``"US"`` or ``"SI"``.

    Returns
    -------
    dict or None
        ``{"head": {"x", "y"}, "crank": {...}, "circles": {"x": [[...]], "y":
        [[...]]}, "r": greatest radius}``; NaN where a circle has a gap.
    """
    spec = getattr(gear, "spec", None)
    if not hasattr(gear, "travel") or not hasattr(spec, "lap_m") \
            or not hasattr(spec, "exhaust_lap_m"):
        return None
    u = "in" if system == "US" else "mm"
    th = np.linspace(0.0, 2.0 * np.pi, ANGLES)
    x = units.to_unit(np.asarray(gear.travel(th), dtype=float), u)
    out: dict[str, object] = {}
    for end, mask, rad in (("head", x > 0, x), ("crank", x <= 0, -x)):
        out[end] = {"x": np.where(mask, rad * np.cos(th), np.nan),
                    "y": np.where(mask, rad * np.sin(th), np.nan)}
    t = np.linspace(0.0, 2.0 * np.pi, 181)
    laps = (*getattr(spec, "lap_m"), *getattr(spec, "exhaust_lap_m"))   # checked above
    radii = sorted({abs(float(units.to_unit(v, u))) for v in laps} - {0.0})
    out["circles"] = {"x": [r * np.cos(t) for r in radii],
                      "y": [r * np.sin(t) for r in radii]}
    out["r"] = float(np.nanmax(np.abs(x))) if x.size else 1.0
    return out


def summary_view(summary: SteadySummary, system: str) -> dict:
    """The summary's numbers as the page shows them, each as text.

    Parameters
    ----------
    summary : SteadySummary
        A steady run's summary (:attr:`SteadyResult.summary`).
    system : str
        ``"US"`` (ihp, psi, lb/h, lb per ihp-hour) or ``"SI"`` (kW, bar, kg/h, kg/kWh).

    Returns
    -------
    dict
        ``{label: text}``: power, m.e.p., steam, steam per power-hour, and the missing
        water of each end where the walls exchange heat.
    """
    s = summary
    if system == "US":
        out = {"indicated power": f"{s['indicated_power_hp']:.2f} ihp",
               "m.e.p.": f"{units.to_unit(s['mep_mean_Pa'], 'psia'):.2f} psi",
               "steam": f"{s['steam_rate_kg_per_h'] / units.POUND_kg:.1f} lb/h",
               "steam per ihp-hour": ("never" if s["water_rate_lb_per_ihp_h"] is None else
                                      f"{s['water_rate_lb_per_ihp_h']:.2f} lb")}
    else:
        out = {"indicated power": f"{s['indicated_power_W'] / 1e3:.2f} kW",
               "m.e.p.": f"{s['mep_mean_Pa'] / 1e5:.3f} bar",
               "steam": f"{s['steam_rate_kg_per_h']:.1f} kg/h",
               "steam per kWh": ("never" if s["water_rate_kg_per_kWh"] is None else
                                 f"{s['water_rate_kg_per_kWh']:.2f} kg")}
    for end in ("head", "crank"):
        m = end_value(s, "missing_water_fraction", end)
        if m is not None:
            out[f"missing water, {end} end"] = f"{m:.3f} of the steam at cut-off"
    return out


def compute_view(data: dict, name: str = "scene", source: str | None = None) -> dict:
    """Load the edited scene, run its card, and gather what the page draws.

    A transient scene runs steady at its speed (its governor and load aside); the
    view says so.

    Parameters
    ----------
    data : dict
        The scene's tables, as TOML reads them, with the page's settings.
    name : str, optional
        The scene's name.
    source : str, optional
        The file it came from.

    Returns
    -------
    dict
        ``{"ok": True, "card", "events", "zeuner", "ports", "ports_title" (saying
        which ports' edges uncover more than one opening), "summary", "title", "note",
        "compute_s"}``, or ``{"ok": False, "message", "key"}`` when the loader
        refuses the scene (the key it names) or the run cannot go on (key None).
    """
    t0 = time.perf_counter()
    try:
        scene = scene_from_dict(data, name=name, source=source)
        note = ""
        if scene.run.mode != "steady":
            scene = steady_scene(scene)
            note = "a transient scene, shown as a steady card at its speed"
        result = simulate(scene)
        assert isinstance(result, SteadyResult)     # a steady scene: a steady result
        gear = build_gear(scene)
    except InputError as exc:
        return {"ok": False, "message": str(exc), "key": exc.key}
    except RunError as exc:
        return {"ok": False, "message": f"the run stopped: {exc}", "key": None}
    system = scene.output.units
    return {"ok": True, "title": scene.title, "note": note,
            "card": card_view(result, system),
            "events": events_rows(result.events, system),
            "zeuner": zeuner_view(gear, system),
            "ports": ports_view(gear, system),
            "ports_title": "port openings" + (f" ({n})" if (n := openings_note(gear)) else ""),
            "summary": summary_view(result.summary, system),
            "speed_rpm": result.summary["speed_rpm"],
            "compute_s": time.perf_counter() - t0}
