"""The workbench's controls: what a person sets on a real engine, from the key
declarations, and how a control's value is written back into the scene.

Each control edits one scene key (one end of a key given per end).  Its kind, unit
and valid range come from the key's declaration (:mod:`corliss.keys.declared`): the gear's
own keys from its registry entry, and the engine's speed, supply pressure and
superheat, exhaust pressure, clearance, effects and fidelity from the sections'.  A
slider spans the declared range where it is finite, else the current value to either
side.  Nothing here knows the page: :mod:`corliss.workbench.app` draws the controls.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from CoolProp.CoolProp import PropsSI

from corliss.engine.options import EFFECTS, PRESETS
from corliss.keys import units
from corliss.keys.declared import REQUIRED, Derived, Key
from corliss.keys.edits import get_key
from corliss.scene.sections import ENGINE, EXHAUST, RUN, SUPPLY
from corliss.valves import GEARS

#: The unit a slider shows for each kind of quantity, by unit system.
DISPLAY_UNITS = {
    "US": {"length": "in", "angle": "deg", "pressure": "psig", "speed": "rpm",
           "temperature": "degF", "area": "in2", "volume": "in3", "mass": "lb", "time": "s",
           "force": "lbf", "torque": "lbf ft", "stiffness": "lbf/in", "damping": "lbf s/in"},
    "SI": {"length": "mm", "angle": "deg", "pressure": "barg", "speed": "rpm",
           "temperature": "degC", "area": "cm2", "volume": "L", "mass": "kg", "time": "s",
           "force": "N", "torque": "N m", "stiffness": "N/m", "damping": "N s/m"},
}
#: Superheat's unit and greatest value on the slider, by unit system: a temperature
#: difference (one degree Fahrenheit is 5/9 K).
SUPERHEAT = {"US": ("degF", 400.0, 5.0 / 9.0), "SI": ("K", 220.0, 1.0)}
#: Plain kinds a slider edits.
_NUMERIC_PLAIN = ("number", "fraction", "integer")
#: Points across a slider's span.
STEPS = 200


@dataclass(frozen=True)
class Control:
    """One control of the page.

    Parameters
    ----------
    key : str
        The dotted scene key it edits (``"valve_gear.lap"``), or ``"output.units"``.
    label : str
        What the page calls it.
    widget : str
        ``"slider"``, ``"choice"``, ``"effects"`` (a list of check boxes) or
        ``"superheat"`` (a slider of superheat, 0 for saturated steam).
    doc : str
        The key's one line.
    end : int or None
        0 (head) or 1 (crank) for one end of a key given per end, else None.
    kind : str
        The key's kind (:data:`corliss.keys.declared.KINDS`).
    unit : str
        The unit the slider shows (empty for a plain number).
    start, stop, step : float
        The slider's span and step, in ``unit``.
    value : object
        The value now: a number in ``unit``, a word, or a list of words.
    choices : tuple of str
        The words of a choice or effects control.
    """

    key: str
    label: str
    widget: str
    doc: str
    end: int | None = None
    kind: str = ""
    unit: str = ""
    start: float = 0.0
    stop: float = 1.0
    step: float = 0.01
    value: object = None
    choices: tuple = ()

    @property
    def name(self) -> str:
        """The control's name on the page: its key, and its end where it has one.

        Returns
        -------
        str
            E.g. ``"valve_gear.lap"`` or ``"valve_gear.lap[crank]"``.
        """
        return self.key if self.end is None else f"{self.key}[{('head', 'crank')[self.end]}]"


def _nice_step(raw: float) -> float:
    """The 1, 2, 5 times a power of ten at or below ``raw``."""
    if not raw > 0.0 or not math.isfinite(raw):
        return 1.0
    p = 10.0 ** math.floor(math.log10(raw))
    for m in (5.0, 2.0, 1.0):
        if m * p <= raw:
            return m * p
    return p


def _si(key: Key, value, barometer_Pa: float) -> float:
    if key.is_quantity:
        return float(units.parse(value, key.kind, key.name, barometer_Pa=barometer_Pa))
    return float(value)


def _shown(key: Key, x_si: float, unit: str, barometer_Pa: float) -> float:
    if not key.is_quantity:
        return x_si
    return float(units.to_unit(x_si, unit, barometer_Pa=barometer_Pa))


def _span(key: Key, now: float, scale: float, unit: str, barometer_Pa: float):
    """(start, stop, step) of a slider in ``unit`` around ``now`` [SI]."""
    if key.is_quantity:
        lo, hi, _ = units.RANGES[key.kind]
    else:
        lo, hi = (0.0, math.inf) if key.kind != "integer" else (0.0, 100.0)
    if key.within is not None:
        lo, hi = max(lo, key.within[0]), min(hi, key.within[1])
    if key.kind == "fraction" and key.within is None:
        lo, hi = max(lo, 0.0), min(hi, 0.5)
    if math.isfinite(lo) and math.isfinite(hi) and hi - lo <= 4.0 * max(abs(now), scale):
        a, b = lo, hi
    else:
        half = abs(now) if now != 0.0 else scale
        a, b = max(lo, now - half), min(hi, now + half)
        if key.kind == "speed" or (key.is_quantity and lo >= 0.0 and now > 0.0):
            a = max(a, 0.0)
    sa, sb = (_shown(key, v, unit, barometer_Pa) for v in (a, b))
    step = 1.0 if key.kind == "integer" else _nice_step((sb - sa) / STEPS)
    shown = _shown(key, now, unit, barometer_Pa)
    for _ in range(4):      # a finer step where the value now is off the grid
        if abs(shown / step - round(shown / step)) < 1e-6:
            break
        step /= 10.0
    start = math.ceil(sa / step - 1e-9) * step
    stop = math.floor(sb / step + 1e-9) * step
    return start, stop, step


def _value_of(key: Key, table: dict):
    """The value a scene gives a key, or its concrete default; None where it has
    neither (optional, derived or required and absent), or where the key is read only
    in some cases (its ``when``) and the scene does not give it."""
    if key.name in table:
        return table[key.name]
    d = key.default
    if d is REQUIRED or d is None or isinstance(d, Derived) or key.when:
        return None
    return d


def _sliders(section: str, key: Key, table: dict, system: str, barometer_Pa: float,
             scale: float, label: str | None = None) -> list[Control]:
    """The slider (or one per end) of a numeric key that has a value."""
    raw = _value_of(key, table)
    if raw is None:
        return []
    per_end = list(raw) if (key.ends and isinstance(raw, list)) else None
    if isinstance(raw, list) and per_end is None:
        return []
    unit = DISPLAY_UNITS[system].get(key.kind, units.units_of(key.kind)[0]) \
        if key.is_quantity else ""
    out = []
    for end in ((0, 1) if key.ends else (None,)):
        v = per_end[end] if per_end is not None and end is not None else raw
        now = _si(key, v, barometer_Pa)
        start, stop, step = _span(key, now, scale, unit, barometer_Pa)
        shown = float(f"{_shown(key, now, unit, barometer_Pa):.9g}")
        name = label or key.name.replace("_", " ")
        out.append(Control(f"{section}.{key.name}", name + ("" if end is None else
                           f", {('head', 'crank')[end]} end"), "slider", key.doc, end,
                           key.kind, unit, min(start, shown), max(stop, shown), step, shown))
    return out


def _choice(section: str, key: Key, table: dict, label: str | None = None) -> list[Control]:
    raw = _value_of(key, table)
    if not isinstance(raw, str):
        return []
    return [Control(f"{section}.{key.name}", label or key.name.replace("_", " "), "choice",
                    key.doc, kind=key.kind, value=raw, choices=tuple(key.choices))]


def _length_scale(group, table: dict) -> float:
    """Half the median of the lengths the gear's table gives [m]: the half-span of a
    slider whose value is zero (an exhaust lap of nothing)."""
    found = []
    for k in group.keys:
        if k.kind != "length" or k.name not in table:
            continue
        vals = table[k.name] if isinstance(table[k.name], list) else [table[k.name]]
        for v in vals:
            try:
                x = abs(float(units.parse(v, "length", k.name)))
                if x > 0.0:
                    found.append(x)
            except Exception:           # a value the loader will name; no scale from it
                continue
    return 0.5 * float(np.median(found)) if found else 0.0254


def superheat_K(data: dict) -> float:
    """The supply's superheat [K]: its temperature above saturation at its pressure,
    0 for saturated steam.

    Parameters
    ----------
    data : dict
        The scene's tables.

    Returns
    -------
    float
        Superheat [K].
    """
    sup = data.get("supply", {})
    t = sup.get("temperature", "saturated")
    if t == "saturated":
        return 0.0
    baro = units.parse(sup.get("barometer", "14.696 psia"), "pressure", "supply.barometer")
    p = units.parse(sup["pressure"], "pressure", "supply.pressure", barometer_Pa=baro)
    return max(float(units.parse(t, "temperature", "supply.temperature"))
               - PropsSI("T", "P", p, "Q", 0, "Water"), 0.0)


def barometer_of(data: dict) -> float:
    """The scene's barometer [Pa absolute] (``supply.barometer``, default standard).

    Parameters
    ----------
    data : dict
        The scene's tables.

    Returns
    -------
    float
        The barometer [Pa].
    """
    b = data.get("supply", {}).get("barometer")
    return units.STANDARD_ATMOSPHERE_Pa if b is None else \
        float(units.parse(b, "pressure", "supply.barometer"))


def controls_for(data: dict, system: str) -> list[Control]:
    """The controls of a scene, in the order the page shows them.

    The gear's own keys (those the scene gives, and those with a plain default),
    then speed, supply pressure and superheat, exhaust pressure, clearance, the
    effects and the fidelity.

    Parameters
    ----------
    data : dict
        The scene's tables (as TOML reads them).
    system : str
        ``"US"`` or ``"SI"``: the units the sliders show.

    Returns
    -------
    list of Control
        The controls.
    """
    baro = barometer_of(data)
    vg = data.get("valve_gear", {})
    entry = GEARS.get(vg.get("type"))
    out: list[Control] = []
    if entry is not None:
        scale = _length_scale(entry.keys, vg)
        for key in entry.keys.keys:
            if key.name == "type":
                continue
            if key.kind == "choice":
                out += _choice("valve_gear", key, vg)
            elif key.is_quantity or key.kind in _NUMERIC_PLAIN:
                out += _sliders("valve_gear", key, vg, system, baro, scale)
    run, sup, exh, eng = (data.get(s, {}) for s in ("run", "supply", "exhaust", "engine"))
    out += _sliders("run", RUN["speed"], run, system, baro, 0.0, "speed")
    out += _sliders("supply", SUPPLY["pressure"], sup, system, baro, 0.0, "supply pressure")
    unit, top, _ = SUPERHEAT[system]
    sh = superheat_K(data) / SUPERHEAT[system][2]
    out.append(Control("supply.temperature", "superheat (0: saturated)", "superheat",
                       SUPPLY["temperature"].doc, kind="temperature", unit=unit, start=0.0,
                       stop=max(top, sh), step=_nice_step(top / STEPS), value=sh))
    out += _sliders("exhaust", EXHAUST["pressure"], exh, system, baro,
                    units.STANDARD_ATMOSPHERE_Pa, "exhaust pressure")
    out += _sliders("engine", ENGINE["clearance"], eng, system, baro, 0.0, "clearance")
    out.append(Control("run.effects", "effects", "effects", RUN["effects"].doc,
                       value=list(run.get("effects", [])), choices=tuple(EFFECTS)))
    out.append(Control("run.fidelity", "fidelity", "choice", RUN["fidelity"].doc,
                       value=run.get("fidelity", "standard"), choices=tuple(PRESETS)))
    return out


def scene_value(control: Control, value, data: dict):
    """The scene value a control's setting writes to its key.

    Parameters
    ----------
    control : Control
        The control.
    value : object
        Its new value: a number in the control's unit, a word or a list of words.
    data : dict
        The scene's tables now (for the other end of a key given per end, and the
        supply pressure that superheat is counted from).

    Returns
    -------
    object
        The value as a scene writes it: a quantity string with its unit, a number,
        a word, a list.
    """
    if control.widget == "superheat":
        if float(value) <= 0.0:
            return "saturated"
        unit = "degF" if control.unit == "degF" else "degC"
        dt_K = float(value) * SUPERHEAT["US" if unit == "degF" else "SI"][2]
        sup = data.get("supply", {})
        p = units.parse(sup["pressure"], "pressure", "supply.pressure",
                        barometer_Pa=barometer_of(data))
        t = PropsSI("T", "P", p, "Q", 0, "Water") + dt_K
        return f"{units.to_unit(t, unit):.6g} {unit}"
    if control.widget != "slider":
        return list(value) if control.widget == "effects" else value
    one = slider_value(control, value)
    if control.end is None:
        return one
    now = get_key(data, control.key)
    pair = list(now) if isinstance(now, list) else [now, now]
    pair[control.end] = one
    return pair[0] if pair[0] == pair[1] else pair


def slider_value(control: Control, value):
    """The scene value of a slider's setting alone (one end of a key given per end):
    the setting on the slider's steps, with the slider's unit.

    Parameters
    ----------
    control : Control
        A slider.
    value : float
        Its setting, in the control's unit.

    Returns
    -------
    str or float or int
        ``"1.05 in"``, or a plain number for a key without a unit.
    """
    x = round(float(value) / control.step) * control.step
    x = int(round(x)) if control.kind == "integer" else float(f"{x:.10g}")
    return x if control.unit == "" else f"{x:.10g} {control.unit}"
