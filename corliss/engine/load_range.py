"""An engine across its load range: steady cards at a series of governor positions.

A governor meets a lighter load by shortening the cut-off (through the gear's setting)
or by closing the throttle; at each position the engine settles to a steady card.  A
sweep of either knob gives the steam the engine costs across its load range, which the
engineers of the time drew as the Willans line (steam per hour against indicated power:
straight for a throttled engine, P. W. Willans, Min. Proc. Inst. C.E. 1888; curved for
one governed by cut-off, whose steam per horse-power is least at its economical
cut-off, Marks Art. 2).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from corliss.errors import InputError

KNOBS = ("setting", "throttle")


def steady_scene(scene):
    """The scene as a steady run: no flywheel, load or governor, speed held."""
    run = dataclasses.replace(scene.run, mode="steady", duration_s=None)
    return dataclasses.replace(scene, run=run, governor=None, governor_type=None, flywheel=None,
                               load=None)


def at_knob(scene, knob: str, value: float):
    """The steady scene with the gear's setting, or the throttle's opening, at ``value``."""
    from corliss.engine.simulate import build_gear
    sc = steady_scene(scene)
    if knob == "setting":
        gear = build_gear(sc)
        if gear.setting_range is None:
            raise InputError("--settings", value, f"a gear with a setting; the "
                             f"{scene.gear_type} gear has none (sweep --throttle instead)")
        lo, hi = gear.setting_range
        if not lo <= value <= hi:
            raise InputError("--settings", value, f"settings from {lo} to {hi} "
                             f"({gear.setting_name})")
        return dataclasses.replace(sc, gear=gear.with_setting(value).spec)
    if knob == "throttle":
        if not sc.run.has("steam_chest") or sc.supply.pipe_diameter_m is None:
            raise InputError("--throttle", value, "a scene with the \"steam_chest\" effect and "
                             "supply.pipe_diameter: the throttle is in the steam pipe")
        if not 0.0 < value <= 1.0:
            raise InputError("--throttle", value, "openings above 0, up to 1 (wide open)")
        return dataclasses.replace(sc, supply=dataclasses.replace(sc.supply, throttle=value))
    raise ValueError(f"knob {knob!r}: one of {KNOBS}")


def load_range(scene, knob: str, values) -> pd.DataFrame:
    """Steady runs at each value of ``knob``, one row each.

    Parameters
    ----------
    scene : Scene
        Any scene (a transient one is run steady at its initial speed).
    knob : str
        ``"setting"`` (the gear's setting, as its governor or reverse lever sets it) or
        ``"throttle"`` (opening of the throttle, 0..1).
    values : sequence of float

    Returns
    -------
    DataFrame
        ``value``, ``indicated_power_W``, ``steam_rate_kg_per_h``,
        ``water_rate_kg_per_kWh``, ``cutoff_head_frac``, and
        ``brake_power_W`` when ``friction`` is named.
    """
    from corliss.engine.simulate import simulate
    scenes = [at_knob(scene, knob, float(v)) for v in values]     # check all before work
    rows = []
    for v, sc in zip(values, scenes):
        s = simulate(sc).summary
        rows.append({"value": float(v), "indicated_power_W": s["indicated_power_W"],
                     "steam_rate_kg_per_h": s["steam_rate_kg_per_h"],
                     "water_rate_kg_per_kWh": s["water_rate_kg_per_kWh"],
                     "cutoff_head_frac": s["events"]["head"]["cutoff_frac"],
                     **({"brake_power_W": s["brake_power_W"]} if "brake_power_W" in s else {})})
    return pd.DataFrame(rows)


def willans_fit(frame: pd.DataFrame) -> tuple[float, float, float]:
    """Least-squares line steam = a + b power through a sweep: (a [kg/h], b [kg/h per W],
    R^2)."""
    x = frame["indicated_power_W"].to_numpy()
    y = frame["steam_rate_kg_per_h"].to_numpy()
    b, a = np.polyfit(x, y, 1)
    resid = y - (a + b * x)
    r2 = 1.0 - float(np.sum(resid ** 2)) / float(np.sum((y - y.mean()) ** 2))
    return float(a), float(b), r2
