"""Scene keys named on the command line: ``KEY=LOW:HIGH`` ranges and edited scenes.

Studies, fits and designs change a scene one key at a time.  A key is its dotted name
in the scene (``engine.clearance``, ``valve_gear.lap``, ``run.speed``); a value is
written as the scene writes it, a quantity string with its unit (``"0.9 in"``) or a
bare number for a dimensionless key (``0.08``).  A range ``LOW:HIGH`` is two values in
one unit: ``valve_gear.lap=0.8in:1.2in`` or ``valve_gear.lap=0.8:1.2in`` (the unit
written once, at the end, serves both) or ``engine.clearance=0.04:0.12``.

Nothing here knows what a key means: the edited scene is validated by the loader
(:func:`corliss.scene.loader.scene_from_dict`), which names the key of any bad value.
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

    Parameters
    ----------
    number : float
        The number as written, in ``unit``.
    unit : str
        The unit text (``"in"``, ``"psig"``), empty for a dimensionless key.
    """

    number: float
    unit: str

    def text(self, number: float | None = None):
        """The scene value for ``number`` (default: this one) in this unit.

        Parameters
        ----------
        number : float, optional
            A number in :attr:`unit`; default this value's.

        Returns
        -------
        str or float
            A quantity string, or a float for a dimensionless key.
        """
        x = self.number if number is None else float(number)
        return x if self.unit == "" else f"{x:.12g} {self.unit}"


class _KeyInUnit:
    """What a key with values in one unit writes: ``key`` and ``unit`` attributes."""

    key: str
    unit: str

    def text(self, number: float):
        """The scene value of ``number`` (in :attr:`unit`)."""
        return KeyValue(number, self.unit).text()

    @property
    def label(self) -> str:
        """``key [unit]`` for a table's column or an axis."""
        return f"{self.key} [{self.unit or '-'}]"


@dataclass(frozen=True)
class KeyRange(_KeyInUnit):
    """A scene key and the range it may take, both ends in one unit.

    Parameters
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


def check_key(key: str, where: str) -> str:
    """``key`` if it is a dotted scene key (``section.name``), else an InputError.

    Parameters
    ----------
    key : str
        The key.
    where : str
        What the option is, for the message (``"--vary"``).

    Returns
    -------
    str
        ``key``.
    """
    if not isinstance(key, str) or not _KEY.match(key):
        raise InputError(where, key, "a dotted scene key such as engine.clearance, "
                         "valve_gear.lap or run.speed")
    return key


def parse_value(text: str, where: str) -> KeyValue:
    """A number and its unit from ``"0.9 in"``, ``"0.9in"`` or ``"0.08"``.

    Parameters
    ----------
    text : str
        The value as written.
    where : str
        What the option is, for the message (``"--vary"``).

    Returns
    -------
    KeyValue
        Its number and unit.
    """
    m = _VALUE.match(str(text))
    if not m:
        raise InputError(where, text, "a number and its unit, e.g. 0.9in, 100psig or 0.08")
    x = float(m.group("num"))
    if not math.isfinite(x):
        raise InputError(where, text, "a finite number")
    return KeyValue(x, m.group("unit"))


def parse_range(spec: str, where: str = "--vary") -> KeyRange:
    """A ``KEY=LOW:HIGH`` option as a :class:`KeyRange`.

    Parameters
    ----------
    spec : str
        The option's text.
    where : str
        What the option is, for the message (``"--vary"``).

    Returns
    -------
    KeyRange
        The key and its range.

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
    """The value of dotted ``key`` in a scene's raw tables, or None if it is absent.

    Parameters
    ----------
    data : dict
        The scene's tables.
    key : str
        A dotted key.

    Returns
    -------
    object
        The value as written, or None.
    """
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

    Returns
    -------
    dict
        The edited copy.

    Raises
    ------
    InputError
        If a key's section is not a table of the scene (``engine.bore`` needs an
        ``[engine]`` table; a section the scene lacks is created only when it is
        the key's last level above the name).
    """
    # the path-copying edit of a whole copy: nothing shared with ``data``
    return edited(copy.deepcopy(data), values)


def edited(data: dict, values: dict) -> dict:
    """A scene's raw tables with dotted keys set, as :func:`with_keys` sets them, that
    shares every table it does not edit with ``data`` (a study's runs: the base
    scene's tables copied on each run's path to its keys only, not whole).

    Parameters
    ----------
    data : dict
        The scene as read from its TOML file; not changed, and not to be changed
        while the copy is in use (the two share their unedited tables).
    values : dict
        ``{dotted key: value}``, each value as the scene writes it.

    Returns
    -------
    dict
        The edited tables; read them, do not change them.

    Raises
    ------
    InputError
        As :func:`with_keys`.
    """
    out = dict(data)
    copied = {id(out)}
    for key, value in values.items():
        parts = key.split(".")
        node = out
        for depth, part in enumerate(parts[:-1]):
            if part not in node and depth == len(parts) - 2:
                node[part] = {}
                copied.add(id(node[part]))
            child = node.get(part)
            if not isinstance(child, dict):
                raise InputError(key, value, "a key of a table the scene has; "
                                 f"{'.'.join(parts[:depth + 1])} is not one")
            if id(child) not in copied:
                child = node[part] = dict(child)
                copied.add(id(child))
            node = child
        node[parts[-1]] = value
    return out


# --- grids and distributions (the study's --vary) ------------------------------------------

_CALL = re.compile(r"^\s*(?P<kind>[A-Za-z_]+)\s*\((?P<args>[^()]*)\)\s*(?P<unit>[^()]*?)\s*$")
#: Distributions a Monte Carlo or Latin-hypercube key may take, with their parameters.
DISTRIBUTIONS = {"uniform": ("low", "high"), "normal": ("mean", "sd"),
                 "triangular": ("low", "mode", "high")}


@dataclass(frozen=True)
class KeyValues(_KeyInUnit):
    """A scene key and an explicit list of its values, all in one unit (a grid's
    levels: ``KEY=a,b,c`` with the unit once at the end or on every value).

    Parameters
    ----------
    key : str
        Dotted scene key.
    values : tuple of float
        The values in ``unit``, in the order given, no repeats.
    unit : str
        Their unit; empty for a dimensionless key.
    """

    key: str
    values: tuple
    unit: str


@dataclass(frozen=True)
class KeyDistribution(_KeyInUnit):
    """A scene key and the distribution it is drawn from, its parameters in one unit.

    Parameters
    ----------
    key : str
        Dotted scene key.
    kind : str
        ``"uniform"`` (low, high), ``"normal"`` (mean, sd) or ``"triangular"``
        (low, mode, high): :data:`DISTRIBUTIONS`.
    params : tuple of float
        The parameters in ``unit``, in the order of :data:`DISTRIBUTIONS`.
    unit : str
        Their unit; empty for a dimensionless key.
    """

    key: str
    kind: str
    params: tuple
    unit: str


    def ppf(self, u):
        """The values at the cumulative probabilities ``u``: the inverse of the
        distribution function, so uniform samples of ``u`` (random or stratified) become
        samples of the distribution.

        Parameters
        ----------
        u : array_like
            Cumulative probabilities in (0, 1) [-].

        Returns
        -------
        numpy.ndarray
            The values [unit].
        """
        import numpy as np
        u = np.asarray(u, dtype=float)
        if self.kind == "uniform":
            lo, hi = self.params
            return lo + (hi - lo) * u
        if self.kind == "normal":
            from scipy.special import ndtri
            mean, sd = self.params
            return mean + sd * ndtri(u)
        a, c, b = self.params          # triangular: closed-form inverse on either side
        f = (c - a) / (b - a)
        return np.where(u < f, a + np.sqrt(u * (b - a) * (c - a)),
                        b - np.sqrt((1.0 - u) * (b - a) * (b - c)))


def _one_unit(values: list, where: str, text: str) -> tuple[list[float], str]:
    """Numbers of several :class:`KeyValue` and their one unit (a unit written on the
    last value only serves them all)."""
    units = {v.unit for v in values if v.unit != ""}
    if len(units) > 1:
        raise InputError(where, text, "every value in one unit, e.g. 0.8,1.0,1.2in")
    return [v.number for v in values], (units.pop() if units else "")


def parse_values(spec: str, where: str = "--vary") -> KeyValues:
    """A ``KEY=a,b,c`` option (a grid's explicit levels) as a :class:`KeyValues`.

    Parameters
    ----------
    spec : str
        The option's text.
    where : str
        What the option is, for the message (``"--vary"``).

    Returns
    -------
    KeyValues
        The key and its levels.

    Raises
    ------
    InputError
        If the option is not ``KEY=a,b,...`` with two or more distinct values in one
        unit.
    """
    if not isinstance(spec, str) or spec.count("=") != 1:
        raise InputError(where, spec, "KEY=a,b,c, e.g. valve_gear.lap=0.8,1.0,1.2in")
    key, rest = (s.strip() for s in spec.split("="))
    check_key(key, where)
    here = f"{where} {key}"
    parts = [s for s in rest.split(",")]
    if len(parts) < 2 or any(not s.strip() for s in parts):
        raise InputError(here, rest, "two values or more separated by commas, e.g. 0.8,1.0,1.2in")
    numbers, unit = _one_unit([parse_value(s, here) for s in parts], here, rest)
    if len(set(numbers)) != len(numbers):
        raise InputError(here, rest, "values that differ (a level given twice runs twice)")
    return KeyValues(key, tuple(numbers), unit)


def parse_distribution(spec: str, where: str = "--vary") -> KeyDistribution:
    """A ``KEY=LOW:HIGH`` (uniform), ``KEY=uniform(LOW,HIGH)UNIT``,
    ``KEY=normal(MEAN,SD)UNIT`` or ``KEY=triangular(LOW,MODE,HIGH)UNIT`` option as a
    :class:`KeyDistribution` (the unit at the end, or on every parameter).

    Parameters
    ----------
    spec : str
        The option's text.
    where : str
        What the option is, for the message (``"--vary"``).

    Returns
    -------
    KeyDistribution
        The key and its distribution.

    Raises
    ------
    InputError
        Naming the option, for an unknown distribution, a wrong count of parameters,
        parameters in two units, ``sd <= 0``, or ends out of order.
    """
    if isinstance(spec, str) and spec.count("=") == 1 and "(" not in spec:
        r = parse_range(spec, where)
        return KeyDistribution(r.key, "uniform", (r.low, r.high), r.unit)
    example = ("KEY=LOW:HIGH, KEY=normal(MEAN,SD)UNIT or KEY=triangular(LOW,MODE,HIGH)UNIT, "
               "e.g. run.speed=normal(120,5)rpm")
    if not isinstance(spec, str) or spec.count("=") != 1:
        raise InputError(where, spec, example)
    key, rest = (s.strip() for s in spec.split("="))
    check_key(key, where)
    here = f"{where} {key}"
    m = _CALL.match(rest)
    if not m or m.group("kind") not in DISTRIBUTIONS:
        raise InputError(here, rest, "a distribution: " + ", ".join(
            f"{k}({','.join(p)})UNIT" for k, p in DISTRIBUTIONS.items()) + ", or LOW:HIGH")
    kind, names = m.group("kind"), DISTRIBUTIONS[m.group("kind")]
    args = [parse_value(s, here) for s in m.group("args").split(",")]
    if len(args) != len(names):
        raise InputError(here, rest, f"{kind} takes {len(names)} parameters: "
                         f"{kind}({','.join(names)})")
    tail = m.group("unit")
    numbers, unit = _one_unit(args + ([KeyValue(0.0, tail)] if tail else []), here, rest)
    numbers = numbers[:len(names)]
    if kind == "normal" and not numbers[1] > 0:
        raise InputError(here, rest, "a standard deviation above 0")
    if kind == "uniform" and not numbers[0] < numbers[1]:
        raise InputError(here, rest, "low below high")
    if kind == "triangular" and not (numbers[0] <= numbers[1] <= numbers[2]
                                     and numbers[0] < numbers[2]):
        raise InputError(here, rest, "low <= mode <= high, low below high")
    return KeyDistribution(key, kind, tuple(numbers), unit)
