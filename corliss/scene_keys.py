"""Scene keys named on the command line: ``KEY=LOW:HIGH`` ranges and edited scenes.

Studies, fits and designs change a scene one key at a time.  A key is its dotted name
in the scene (``engine.clearance``, ``valve_gear.lap``, ``run.speed``); a value is
written as the scene writes it, a quantity string with its unit (``"0.9 in"``) or a
bare number for a dimensionless key (``0.08``).  A range ``LOW:HIGH`` is two values in
one unit: ``valve_gear.lap=0.8in:1.2in`` or ``valve_gear.lap=0.8:1.2in`` (the unit
written once, at the end, serves both) or ``engine.clearance=0.04:0.12``.

Nothing here knows what a key means: the edited scene is validated by the loader
(:func:`corliss.scene.scene_from_dict`), which names the key of any bad value.
"""

from __future__ import annotations

import copy
import math
import re
from dataclasses import dataclass

from corliss.errors import InputError

_KEY = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)+$")
_VALUE = re.compile(r"^\s*(?P<num>[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*"
                    r"(?P<unit>[^:]*?)\s*$")


@dataclass(frozen=True)
class KeyValue:
    """A number in a unit, as a scene writes it.

    Attributes
    ----------
    number : float
        The number as written, in ``unit``.
    unit : str
        The unit text (``"in"``, ``"psig"``), empty for a dimensionless key.
    """

    number: float
    unit: str

    def text(self, number: float | None = None):
        """The scene value for ``number`` (default: this one) in this unit: a quantity
        string, or a float for a dimensionless key."""
        x = self.number if number is None else float(number)
        return x if self.unit == "" else f"{x:.12g} {self.unit}"


@dataclass(frozen=True)
class KeyRange:
    """A scene key and the range it may take, both ends in one unit.

    Attributes
    ----------
    key : str
        Dotted scene key, e.g. ``"valve_gear.lap"``.
    low, high : float
        The ends of the range, in ``unit``; ``low < high``.
    unit : str
        The unit both ends are written in; empty for a dimensionless key.
    """

    key: str
    low: float
    high: float
    unit: str

    def text(self, number: float):
        """The scene value of ``number`` (in :attr:`unit`)."""
        return KeyValue(number, self.unit).text()

    @property
    def label(self) -> str:
        """``key [unit]`` for a table's column or an axis."""
        return f"{self.key} [{self.unit or '-'}]"


def check_key(key: str, where: str) -> str:
    """``key`` if it is a dotted scene key (``section.name``), else an InputError."""
    if not isinstance(key, str) or not _KEY.match(key):
        raise InputError(where, key, "a dotted scene key such as engine.clearance, "
                         "valve_gear.lap or run.speed")
    return key


def parse_value(text: str, where: str) -> KeyValue:
    """A number and its unit from ``"0.9 in"``, ``"0.9in"`` or ``"0.08"``."""
    m = _VALUE.match(str(text))
    if not m:
        raise InputError(where, text, "a number and its unit, e.g. 0.9in, 100psig or 0.08")
    x = float(m.group("num"))
    if not math.isfinite(x):
        raise InputError(where, text, "a finite number")
    return KeyValue(x, m.group("unit"))


def parse_range(spec: str, where: str = "--vary") -> KeyRange:
    """A ``KEY=LOW:HIGH`` option as a :class:`KeyRange`.

    Raises
    ------
    InputError
        If the option is not ``KEY=LOW:HIGH``, the ends are in different units, or
        ``LOW`` is not below ``HIGH``.
    """
    example = "KEY=LOW:HIGH, e.g. valve_gear.lap=0.8in:1.2in or engine.clearance=0.04:0.12"
    if not isinstance(spec, str) or spec.count("=") != 1:
        raise InputError(where, spec, example)
    key, rng = (s.strip() for s in spec.split("="))
    check_key(key, where)
    if rng.count(":") != 1:
        raise InputError(f"{where} {key}", rng, "LOW:HIGH, two values in one unit")
    lo, hi = (parse_value(s, f"{where} {key}") for s in rng.split(":"))
    unit = hi.unit if lo.unit == "" else lo.unit
    if lo.unit not in ("", unit) or hi.unit not in ("", unit):
        raise InputError(f"{where} {key}", rng, f"both ends in one unit, e.g. {lo.number:g}"
                         f"{hi.unit}:{hi.number:g}{hi.unit}")
    if not lo.number < hi.number:
        raise InputError(f"{where} {key}", rng, "LOW below HIGH")
    return KeyRange(key, lo.number, hi.number, unit)


def get_key(data: dict, key: str):
    """The value of dotted ``key`` in a scene's raw tables, or None if it is absent."""
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def with_keys(data: dict, values: dict) -> dict:
    """A copy of a scene's raw tables with dotted keys set.

    Parameters
    ----------
    data : dict
        The scene as read from its TOML file; not changed.
    values : dict
        ``{dotted key: value}``, each value as the scene writes it.

    Raises
    ------
    InputError
        If a key's section is not a table of the scene (``engine.bore`` needs an
        ``[engine]`` table; a section the scene lacks is created only when it is
        the key's last level above the name).
    """
    out = copy.deepcopy(data)
    for key, value in values.items():
        parts = key.split(".")
        node = out
        for depth, part in enumerate(parts[:-1]):
            if part not in node and depth == len(parts) - 2:
                node[part] = {}
            node = node.get(part)
            if not isinstance(node, dict):
                raise InputError(key, value, "a key of a table the scene has; "
                                 f"{'.'.join(parts[:depth + 1])} is not one")
        node[parts[-1]] = value
    return out
