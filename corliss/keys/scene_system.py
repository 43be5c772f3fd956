"""A scene's TOML text in one unit system, its comments, key order and layout kept.

``corliss design`` and ``corliss fit`` write a scene back: the source scene with some
keys set.  Written again from its tables it would lose the source's comments, which
cite where each dimension came from, and a design asked in SI of an inch scene would
mix millimetres and inches.  So the source text is edited in place through tomlkit (a
TOML library that reads and writes a document with its comments and layout) and every
quantity in it is written in one unit system: :func:`scene_text`.

The drawing office's rule, applied to every value this module writes (a value already
in the system is kept as its author wrote it, fractions of an inch included):

- a length to the nearest thousandth of an inch (0.001 in, a thou) or hundredth of a
  millimetre (0.01 mm): the finest a valve setter's or machinist's drawing gives;
- an angle to the nearest hundredth of a degree;
- every other quantity to four significant figures (a gauge, a balance or a spring
  scale reads no finer), an absolute pressure to five (a barometer reads to 0.01 inHg,
  and 14.696 psia is 101.33 kPa: four figures would move every gauge reading);
- a pressure stays gauge, absolute or vacuum as it was written: 100 psig becomes
  689.5 kPa(g), so the scene's barometer still reads it.

Units by system (:data:`TARGET`): US writes in, in2, ft3, psia/psig, inHg vacuum, degF,
lb, lbf, lbf/in, lbf s/in, lbf ft, lb ft2, hp, lb/h, Btu; SI writes mm, mm2, m3,
kPa(a)/kPa(g), mmHg vacuum, degC, kg, N, N/mm, N s/m, N m, kg m2, kW, kg/h, kJ.
Speeds, times and angles are the same in both and are kept.
"""

from __future__ import annotations

import math

import tomlkit
from tomlkit.items import Array, InlineTable, String, Table
from tomlkit.container import Container

from corliss.errors import InputError
from corliss.keys import units

#: The unit systems a scene is written in.
SYSTEMS = ("US", "SI")

#: Each kind's unit in each system: (the spelling written, the unit converted to, the
#: sense of a pressure).  A pressure's sense is kept: ``abs``, ``gauge`` or ``vacuum``.
TARGET: dict[str, dict[str, str]] = {
    "US": {"length": "in", "area": "in2", "volume": "ft3", "torque": "lbf ft",
           "torque_per_speed": "lbf ft/rpm", "heat_transfer": "Btu/ft2 degF h",
           "power": "hp", "mass": "lb", "inertia": "lb ft2", "mass_flow": "lb/h",
           "leak_rate": "lb/h psi", "force": "lbf", "stiffness": "lbf/in",
           "damping": "lbf s/in", "specific_energy": "Btu/lb", "energy": "Btu",
           "specific_steam_consumption": "lb/hp h", "temperature": "degF",
           "abs": "psia", "gauge": "psig", "vacuum": "inHg vacuum"},
    "SI": {"length": "mm", "area": "mm2", "volume": "m3", "torque": "N m",
           "torque_per_speed": "N m/rpm", "heat_transfer": "W/m2 K",
           "power": "kW", "mass": "kg", "inertia": "kg m2", "mass_flow": "kg/h",
           "leak_rate": "kg/h bar", "force": "N", "stiffness": "N/mm",
           "damping": "N s/m", "specific_energy": "kJ/kg", "energy": "kJ",
           "specific_steam_consumption": "kg/kWh", "temperature": "degC",
           "abs": "kPa(a)", "gauge": "kPa(g)", "vacuum": "mmHg vacuum"},
}
#: The size of one of each written pressure unit [Pa] (gauge and vacuum: of the
#: difference from the barometer).
_PRESSURE_SIZE = {"psia": units.PSI_Pa, "psig": units.PSI_Pa, "inHg vacuum": units.INHG_Pa,
                  "kPa(a)": 1e3, "kPa(g)": 1e3, "mmHg vacuum": units.MMHG_Pa}
#: Units of the US system as a scene may write them; the rest of a kind's units are
#: SI (or, as ``kg/h psi`` and ``atm``, of neither, and converted to either).
_US = {"in", "inch", "inches", "thou", "ft", "feet", "foot", "in2", "ft2", "in3", "ft3",
       "lbf ft", "ft lbf", "lbf in", "lbf ft/rpm", "Btu/ft2 degF min", "Btu/ft2 degF h",
       "hp", "ihp", "lb", "lbm", "lb ft2", "lbm ft2", "slug ft2", "lb/h", "lb/h psi", "lbf",
       "lbf/in", "lbf/ft", "lbf s/in", "lbf s/ft", "Btu/lb", "Btu", "lb/hp h", "degF",
       "degR", "inHg"}
#: Kinds written alike in both systems.
_NEUTRAL = {"speed", "time", "angle"}
#: Decimal places of a written length by unit, and of an angle in degrees.
LENGTH_DECIMALS = {"in": 3, "mm": 2}
ANGLE_DECIMALS = 2
#: Significant figures of every other quantity written; of an absolute pressure.
FIGURES = 4
FIGURES_ABSOLUTE = 5


def _kind_of(unit: str) -> tuple[str, str] | None:
    """(kind, pressure sense or the kind again) of a unit a scene may write; None for
    a text that is not a unit."""
    for kind, table in units._LINEAR.items():
        if unit in table:
            return kind, kind
    if unit in units._ABS_INPUT:
        return "pressure", "abs"
    if unit in units._GAUGE_INPUT:
        return "pressure", "gauge"
    if unit in units._VACUUM:
        return "pressure", "vacuum"
    if unit in units._TEMPERATURE:
        return "temperature", "temperature"
    return None


def system_of(unit: str) -> str | None:
    """The unit system a unit belongs to.

    Parameters
    ----------
    unit : str
        A unit as a scene writes it (``"in"``, ``"psig"``, ``"N m"``).

    Returns
    -------
    str or None
        ``"US"`` or ``"SI"``; None for a unit of both (speeds, times, angles) or of
        neither (``atm``, ``kg/h psi``), and for a text that is not a unit.
    """
    found = _kind_of(unit)
    if found is None or found[0] in _NEUTRAL or unit in ("atm", "kg/h psi"):
        return None
    if unit in _US or unit.startswith("psi") or unit.startswith("inHg"):
        return "US"
    return "SI"


def _number(x: float) -> str:
    """A number as a drawing writes it: positional, no trailing zeros, no ``-0``."""
    text = f"{x:.12f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def rounded(value: float, kind: str, unit: str) -> str:
    """A value in ``unit``, rounded by the drawing office's rule (module text).

    Parameters
    ----------
    value : float
        The value, in ``unit`` (not SI).
    kind : str
        Its kind (``"length"``, ``"angle"``, ``"pressure"``, ...).
    unit : str
        Its unit.

    Returns
    -------
    str
        ``"1.023 in"``, ``"689.5 kPa(g)"``.
    """
    if kind == "length" and unit in LENGTH_DECIMALS:
        v = round(value, LENGTH_DECIMALS[unit])
    elif kind == "angle":
        v = round(value, ANGLE_DECIMALS)
    elif value == 0.0 or not math.isfinite(value):
        v = value
    else:
        figures = FIGURES_ABSOLUTE if unit in ("psia", "kPa(a)") else FIGURES
        v = round(value, figures - 1 - math.floor(math.log10(abs(value))))
    return f"{_number(v)} {unit}"


def quantity(value_si: float, kind: str, system: str) -> str:
    """An SI value written in ``system``'s unit for its kind, rounded by the rule.

    Parameters
    ----------
    value_si : float
        The value [SI] (a pressure: not for this function, whose sense is not known).
    kind : str
        Its kind: a kind of :data:`TARGET` or a neutral one (angle: in degrees).
    system : str
        ``"US"`` or ``"SI"``.

    Returns
    -------
    str
        The quantity string (``"3.012 in"``, ``"76.5 mm"``, ``"30.25 deg"``).
    """
    if kind == "angle":
        return rounded(math.degrees(value_si), kind, "deg")
    unit = TARGET[system][kind]
    return rounded(units.to_unit(value_si, unit), kind, unit)


def converted(text: str, system: str, key: str = "value") -> str | None:
    """A scene's quantity string written in ``system``, or None to keep it as it is.

    Parameters
    ----------
    text : str
        A value from a scene (any string: one that is not a quantity is kept).
    system : str
        ``"US"`` or ``"SI"``.
    key : str, optional
        Its key, for an error.

    Returns
    -------
    str or None
        The converted string, rounded by the rule; None for a string that is not a
        quantity, is already in ``system``, or is of a kind both systems write alike.
    """
    try:
        q = units._parse_text(text, key)
    except InputError:
        return None
    found = _kind_of(q.unit)
    if found is None or system_of(q.unit) == system or found[0] in _NEUTRAL:
        return None
    kind, sense = found
    target = TARGET[system][sense]
    if kind == "pressure":
        source = {**units._ABS_INPUT, **units._GAUGE_INPUT, **units._VACUUM}[q.unit]
        return rounded(q.value * source / _PRESSURE_SIZE[target], kind, target)
    if kind == "temperature":
        return rounded(units.to_unit(units.parse(text, kind, key), target), kind, target)
    return rounded(q.value * units._LINEAR[kind][q.unit] / units._LINEAR[kind][target],
                   kind, target)


def _convert_all(node, system: str, path: str) -> None:
    """Every quantity string under ``node`` (a table, an inline table or an array)
    written in ``system``, in place; the title is a title."""
    if isinstance(node, (Container, Table, InlineTable)):
        for k in list(node.keys()):
            v = node[k]
            where = f"{path}.{k}" if path else k
            if where == "title":
                continue
            if isinstance(v, str):
                new = converted(str(v), system, where)
                if new is not None:
                    node[k] = new
            elif isinstance(v, (Table, InlineTable, Array, list)):
                _convert_all(v, system, where)
    elif isinstance(node, (Array, list)):
        for i, v in enumerate(list(node)):
            if isinstance(v, str):
                new = converted(str(v), system, path)
                if new is not None:
                    node[i] = new
            else:
                _convert_all(v, system, path)


def _set(doc, key: str, value) -> None:
    parts = key.split(".")
    node = doc
    for part in parts[:-1]:
        if part not in node:
            node[part] = tomlkit.table()
        node = node[part]
    if isinstance(value, (list, tuple)):
        arr = tomlkit.array()
        arr.extend(value)
        value = arr
    node[parts[-1]] = value


def _drop(doc, key: str) -> None:
    parts = key.split(".")
    node = doc
    for part in parts[:-1]:
        if part not in node:
            return
        node = node[part]
    if parts[-1] in node:
        del node[parts[-1]]


def _edited_doc(source: str, values: dict, drop=()):
    """The parsed source with ``values`` set and ``drop`` removed (comments kept)."""
    doc = tomlkit.parse(source)
    for key, value in values.items():
        _set(doc, key, value)
    for key in drop:
        _drop(doc, key)
    return doc


def edited(source: str, values: dict) -> str:
    """The source scene's text with keys set, its units, comments and layout kept.

    Parameters
    ----------
    source : str
        The source scene's TOML text.
    values : dict
        ``{dotted key: value}``, each as a scene writes it.  A key that is there
        keeps its place and its comment; one that is not is added at the end of its
        table.

    Returns
    -------
    str
        The TOML text.
    """
    return tomlkit.dumps(_edited_doc(source, values))


def scene_text(source: str, system: str, values: dict | None = None, drop=(),
               header: str = "") -> str:
    """The source scene's text with keys set, in one unit system, comments kept.

    Parameters
    ----------
    source : str
        The source scene's TOML text.
    system : str
        ``"US"`` or ``"SI"``: every quantity is written in it (the rule of the
        module's text) and ``[output] units`` says it.
    values : dict, optional
        ``{dotted key: value}`` set first, each as a scene writes it (a value in the
        other system is converted with the rest).  A key that is there keeps its
        place and its comment; one that is not is added at the end of its table.
    drop : iterable of str, optional
        Dotted keys removed.
    header : str, optional
        Comment lines written first, one ``#`` line per line of it, above the
        source's own.

    Returns
    -------
    str
        The TOML text.

    Raises
    ------
    InputError
        For a system that is not US or SI.
    """
    if system not in SYSTEMS:
        raise InputError("--units", system, "US or SI")
    doc = _edited_doc(source, values or {}, drop)
    _convert_all(doc, system, "")
    _set(doc, "output.units", system)
    text = tomlkit.dumps(doc)
    if header:
        lines = [("# " + line).rstrip() for line in header.splitlines()]
        text = "\n".join(lines) + "\n\n" + text
    return text


__all__ = ["ANGLE_DECIMALS", "FIGURES", "FIGURES_ABSOLUTE", "LENGTH_DECIMALS", "SYSTEMS", "TARGET", "converted", "edited",
           "quantity", "rounded", "scene_text", "system_of"]
