"""Declared scene keys: what each key of a section, gear, governor or effect is.

A :class:`Key` states a key's name, the kind of value it takes (a kind of quantity of
:mod:`corliss.keys.units`, or a plain number, whole number, choice, ...), its default, its
valid range or choices, and one line saying what it is.  A :class:`KeyGroup` holds the
keys of one scene table (a section, or one gear's or governor's ``[valve_gear]`` /
``[governor]`` keys); gears and governors carry theirs on their registry entry.

The loader reads a table through its group (:class:`corliss.keys.toml_table.Table` bound to
it), so the kind, unit, default and range written here are the ones validated, and the
scene reference (``docs/scene-reference.md``, ``corliss explain``) is printed from the
same declarations.  Reading a key that the group does not declare is a programming
error (:class:`UndeclaredKeyError`), not a user's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

from corliss.keys import units

#: The least length of a part that exists [m].
MICRON_m = 1e-6
#: The range of a length that must exist (a part's size, a rod, a throw) [m].
POSITIVE_LENGTH = (MICRON_m, math.inf)
#: The range of a quantity that is zero or more (a friction, a preload, an offset) [SI].
ZERO_OR_MORE = (0.0, math.inf)

#: Kinds of value that are not quantities with units.
PLAIN_KINDS = {
    "number": "a plain number",
    "integer": "a whole number",
    "choice": "one of the words listed",
    "string": "a string",
    "flag": "true or false",
    "list": "a list of the words listed",
    "table": "a table",
    "fraction": "a fraction of the swept volume",
    "number_pair": "a list [least, greatest] of two plain numbers",
    "angle_list": "a list of angles with their unit, one per cylinder",
    "arc": "a length on the valve face or a spindle angle",
}
#: Every kind a key may take.
KINDS = tuple(units.KINDS) + tuple(PLAIN_KINDS)


class _Marker:
    """A named sentinel."""

    def __init__(self, name: str):
        self.name = name

    def __repr__(self) -> str:
        return self.name


#: The default of a key the scene must give.
REQUIRED = _Marker("REQUIRED")


@dataclass(frozen=True)
class Derived:
    """A default computed from other keys or the scene, in words.

    Parameters
    ----------
    text : str
        What the default is, e.g. ``"the HP cylinder's stroke"``.
    """

    text: str


class UndeclaredKeyError(LookupError):
    """A parser read a key its table's :class:`KeyGroup` does not declare (a
    programming error: declare the key with its doc line)."""


@dataclass(frozen=True)
class Key:
    """One scene key.

    Parameters
    ----------
    name : str
        The key as the scene writes it (``"lap"``).
    kind : str
        One of :data:`KINDS`: a kind of quantity (read with its unit), or a plain kind.
    doc : str
        One line: what the key is.
    default : object
        :data:`REQUIRED`; None (optional: absent, the feature is off or the value is
        found otherwise, see ``doc``); a :class:`Derived`; or the value as a scene
        writes it (``"0 in"``, ``0.7``, ``"direct"``).
    within : (float, float) or None
        The valid range [SI for a quantity], narrowing the kind's physical range
        (:data:`corliss.keys.units.RANGES`); None: the kind's range.
    choices : tuple of str
        The words a ``choice`` or ``list`` key takes, or words a quantity key takes
        beside a quantity (``"saturated"``).
    unit : str or None
        The unit the reference shows the range in; None: the kind's
        (:data:`corliss.keys.units.RANGES`).
    ends : bool
        True for a value given once for both cylinder ends or as ``[head, crank]``.
    effect : str
        The effect (``run.effects``) the key serves, if any.
    when : str
        When the key is read, if not always (``"motion = \\"exact\\""``).
    """

    name: str
    kind: str
    doc: str
    default: object = REQUIRED
    within: tuple | None = None
    choices: tuple = ()
    unit: str | None = None
    ends: bool = False
    effect: str = ""
    when: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"key {self.name}: unknown kind {self.kind!r}")
        if self.kind in ("choice", "list") and not self.choices:
            raise ValueError(f"key {self.name}: a {self.kind} needs its choices")
        if not self.doc:
            raise ValueError(f"key {self.name}: a doc line is required")

    @property
    def required(self) -> bool:
        """True when a scene must give the key (wherever it is read).

        Returns
        -------
        bool
            Whether the default is :data:`REQUIRED`.
        """
        return self.default is REQUIRED

    @property
    def is_quantity(self) -> bool:
        """True for a quantity read with its unit.

        Returns
        -------
        bool
            Whether ``kind`` is a kind of :mod:`corliss.keys.units`.
        """
        return self.kind in units.KINDS

    def kind_text(self) -> str:
        """The kind in words, with its accepted units for a quantity.

        Returns
        -------
        str
            E.g. ``"length (m, mm, cm, in, ...)"`` or ``"a plain number"``.
        """
        if self.is_quantity:
            text = f"{self.kind.replace('_', ' ')} ({', '.join(_unit_list(self.kind))})"
        else:
            text = PLAIN_KINDS[self.kind]
        if self.ends:
            text += ", once or [head, crank]"
        return text

    def default_text(self) -> str:
        """The default in words.

        Returns
        -------
        str
            ``"required"``, ``"none"`` (optional), the derived default's words, or the
            value as a scene writes it.
        """
        d = self.default
        if d is REQUIRED:
            return "required"
        if d is None:
            return "none (optional)"
        if isinstance(d, Derived):
            return d.text
        if isinstance(d, bool):
            return "true" if d else "false"
        if isinstance(d, str):
            return f'"{d}"'
        if isinstance(d, list):
            return "[" + ", ".join(f'"{v}"' if isinstance(v, str) else f"{v:g}" for v in d) + "]"
        return f"{d:g}"

    def range_text(self) -> str:
        """The valid range or the choices in words.

        Returns
        -------
        str
            E.g. ``"1 um to 50 m"``, ``"0.1 to 1"``, ``"direct, reverse_lever"``; empty
            when the key has no range of its own beyond its kind.
        """
        words = ", ".join(f'"{c}"' for c in self.choices)
        if self.kind in ("choice", "list"):
            return words
        extra = f"; or {words}" if self.choices else ""
        if self.is_quantity:
            lo, hi, unit = units.RANGES[self.kind]
            if self.within is not None:
                lo, hi = max(lo, self.within[0]), min(hi, self.within[1])
            unit = self.unit or unit
            return f"{_show(lo, unit, self.kind)} to {_show(hi, unit, self.kind)}{extra}"
        if self.within is not None:
            return f"{_num(self.within[0])} to {_num(self.within[1])}{extra}"
        return words


def _num(x: float) -> str:
    if math.isinf(x):
        return "no limit" if x > 0 else "-no limit"
    return f"{x:g}"


def _show(x_si: float, unit: str, kind: str) -> str:
    if math.isinf(x_si):
        return "no limit" if x_si > 0 else "-no limit"
    if kind == "length" and x_si == MICRON_m:
        return "1 micron"
    v = x_si if unit == "K" else units.to_unit(x_si, unit)
    return f"{v:.4g} {unit}"



def _unit_list(kind: str) -> list[str]:
    names = list(units.units_of(kind))
    if kind == "pressure":      # the spellings' families, not every variant
        return ["psia", "psig", "bara", "barg", "kPa(a)", "kPa(g)", "MPa(a)", "MPa(g)", "Pa",
                "atm", "inHg", "mmHg", "inHg vacuum"]
    return names


@dataclass(frozen=True)
class KeyGroup:
    """The declared keys of one scene table (a section, a gear or a governor).

    Parameters
    ----------
    name : str
        What the keys belong to (``"engine"``, ``"slide_valve"``).
    keys : tuple of Key
        The keys, in the order the reference lists them.
    doc : str
        One line about the table.
    """

    name: str
    keys: tuple
    doc: str = ""
    def __post_init__(self):
        seen: dict[str, Key] = {}
        for k in self.keys:
            if k.name in seen and seen[k.name] != k:
                raise ValueError(f"{self.name}: key {k.name} declared twice, differently")
            seen[k.name] = k
        object.__setattr__(self, "keys", tuple(seen.values()))

    @cached_property
    def _by_name(self) -> dict[str, Key]:
        # read by name for every key of every scene a study loads: a dict, not a scan
        return {k.name: k for k in self.keys}

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and name in self._by_name

    def __getitem__(self, name: str) -> Key:
        k = self._by_name.get(name)
        if k is not None:
            return k
        raise UndeclaredKeyError(f"{self.name} declares no key {name!r}: declare it (with its "
                                 "doc line) in the key group its parser reads")

    @property
    def names(self) -> tuple:
        """The keys' names.

        Returns
        -------
        tuple of str
            In declaration order.
        """
        return tuple(k.name for k in self.keys)


def group(name: str, doc: str, *parts) -> KeyGroup:
    """A key group made of keys and other groups (shared keys declared once).

    Parameters
    ----------
    name : str
        The group's name.
    doc : str
        One line about the table.
    *parts : Key or KeyGroup
        Keys, and groups whose keys are taken in order; a key declared twice must be
        declared the same both times.

    Returns
    -------
    KeyGroup
        The group.
    """
    keys: list[Key] = []
    for p in parts:
        keys.extend(p.keys if isinstance(p, KeyGroup) else [p])
    return KeyGroup(name, tuple(keys), doc)
