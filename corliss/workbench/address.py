"""The workbench page's settings in its address, so that a setting can be sent to someone.

The query holds the scene's name, the unit system and every control's value, each
under the control's name and written as a scene writes it (the slider's unit after
the number)::

    ?scene=default&output.units=US&valve_gear.lap[head]=1.05+in&valve_gear.lap[crank]=1+in
    &...&run.effects=wall_heat,leakage&run.fidelity=fast

:func:`address_query` writes it from the page's controls; :func:`read_address` reads
one back into the scene's settings.  A value is handed to the scene loader as
written (a bare number on a slider with a unit takes the slider's unit), so a bad
value in an address gets the loader's own message, shown beside its control, and the
page draws the engine with the rest of the address; a name that is no control of the
page, or an address made for another scene, is said in words and set nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from urllib.parse import quote, quote_plus

from corliss.errors import InputError
from corliss.keys.edits import get_key, with_keys
from corliss.scene.loader import scene_from_dict
from corliss.workbench.controls import Control, controls_for, scene_value, slider_value

#: The query's name of the scene the address was made for.
SCENE = "scene"
#: The query's name of the unit system.
UNITS = "output.units"


def control_text(control: Control, value, data: dict) -> str:
    """A control's value as its address writes it.

    Parameters
    ----------
    control : Control
        The control.
    value : object
        Its setting: a number in the control's unit, a word, or a list of words.
    data : dict
        The scene's tables now (superheat is written as the supply's temperature,
        counted from its pressure).

    Returns
    -------
    str
        ``"1.05 in"``, ``"0.07"``, ``"saturated"``, ``"400 degF"``, ``"fast"`` or
        ``"wall_heat,leakage"``.
    """
    if control.widget == "slider":
        return str(slider_value(control, value))
    if control.widget == "effects":
        return ",".join(value)
    return str(scene_value(control, value, data))


def address_query(scene: str, system: str, values: list[tuple[Control, object]],
                  data: dict) -> str:
    """The page's address query of its settings.

    Parameters
    ----------
    scene : str
        The scene's name.
    system : str
        ``"US"`` or ``"SI"``.
    values : list of (Control, object)
        Each control and its setting.
    data : dict
        The scene's tables now.

    Returns
    -------
    str
        ``"?scene=...&output.units=...&<control>=<value>..."``.
    """
    pairs = [(SCENE, scene), (UNITS, system)]
    pairs += [(c.name, control_text(c, v, data)) for c, v in values]
    return "?" + "&".join(f"{quote(k, safe='[].')}={quote_plus(v, safe=',')}"
                          for k, v in pairs)


@dataclass
class Address:
    """What an address sets.

    Parameters
    ----------
    edits : dict
        ``{dotted key: value}``: the settings the scene loads with.
    errors : dict
        ``{control name: the loader's message}`` for each value refused.
    notes : list of str
        What was said of the address itself (a name that is no control, another
        scene's address, a unit system refused).
    """

    edits: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)


def _scene_value(control: Control, text: str):
    """The scene value of one control's text in an address."""
    text = text.strip()
    if control.widget == "effects":
        return [w.strip() for w in text.split(",") if w.strip()]
    if control.widget != "slider":
        return text
    try:
        x = float(text)
    except ValueError:
        return text                 # "1.05 in", or a mistake the loader names
    if control.unit:
        return f"{text} {control.unit}"
    return int(x) if control.kind == "integer" and x == int(x) else x


def _load_error(base: dict, edits: dict) -> InputError | None:
    try:
        scene_from_dict(with_keys(base, edits))
    except InputError as exc:
        return exc
    return None


def read_address(args: dict, base: dict, edits: dict, scene: str) -> Address:
    """The settings an address asks for, each checked by the scene loader.

    Parameters
    ----------
    args : dict
        ``{name: text}``: the address's query.
    base : dict
        The source scene's tables.
    edits : dict
        The settings the page starts with (its fidelity).
    scene : str
        The name of the scene the page serves.

    Returns
    -------
    Address
        The settings that load, with the page's own; the loader's message for each
        value refused; notes on the rest.
    """
    out = Address(edits=dict(edits))
    args = {k: v for k, v in args.items()}
    asked = args.pop(SCENE, None)
    if asked is not None and asked != scene:
        out.notes.append(str(InputError(
            "the address's scene", asked, f"{scene}, the scene this page serves: the "
            "address was made for another scene, and none of its settings is set")))
        return out
    if UNITS in args:
        out.edits[UNITS] = args.pop(UNITS).strip()
        if (err := _load_error(base, out.edits)) is not None:
            out.notes.append(str(err))
            del out.edits[UNITS]
    data = with_keys(base, out.edits)
    controls = {c.name: c for c in controls_for(data, data.get("output", {}).get("units",
                                                                                  "US"))}
    asked_keys: dict[str, list[str]] = {}       # key -> the control names that set it
    values: dict[str, object] = {}
    for name, text in args.items():
        c = controls.get(name)
        if c is None:
            out.notes.append(str(InputError(
                "the address", name, "a control of this page, written as the page writes "
                "it in its address (such as valve_gear.lap[head] or run.speed)")))
            continue
        if text.strip() == control_text(c, c.value, data):
            continue                    # as the scene has it: the scene keeps its own text
        v = _scene_value(c, text)
        if c.end is not None:
            now = values.get(c.key, get_key(data, c.key))
            if now is None:             # a key the scene leaves at its default
                now = [_scene_value(e, control_text(e, e.value, data)) for e in
                       (controls[c.key + "[head]"], controls[c.key + "[crank]"])]
            pair = list(now) if isinstance(now, list) else [now, now]
            pair[c.end] = v
            v = pair[0] if pair[0] == pair[1] else pair
        values[c.key] = v
        asked_keys.setdefault(c.key, []).append(name)
    # the loader checks each value with those kept before it, in the address's order
    # (a second pass takes a value that a later one made good); a value it refuses is
    # dropped, its message kept for its controls
    kept: dict = {}
    refused: dict = {}
    for _ in range(2):
        for k, v in values.items():
            if k in kept:
                continue
            exc = _load_error(base, {**out.edits, **kept, k: v})
            if exc is None:
                kept[k] = v
                refused.pop(k, None)
            else:
                refused[k] = str(exc)
        if not refused:
            break
    for k, msg in refused.items():
        for name in asked_keys[k]:
            out.errors[name] = msg
    values = kept
    out.edits.update(values)
    return out
