"""Quantity strings the governors need that :mod:`corliss.units` has no kind for yet:
force (spring preload, friction), spring stiffness and linear damping (dash-pots).

They are read with the same number grammar as every other scene quantity; only the
unit tables are local.  Everything returned is SI.
"""

from __future__ import annotations

from corliss import units
from corliss.errors import InputError
from corliss.tables import Table

_LBF = units.LBF_N
_IN = units.INCH_m
_FT = units.FOOT_m

#: unit tables: kind -> unit -> factor to SI
KINDS: dict[str, dict[str, float]] = {
    "force": {"N": 1.0, "kN": 1e3, "lbf": _LBF, "lb": _LBF},
    "stiffness": {"N/m": 1.0, "N/mm": 1e3, "kN/m": 1e3, "lbf/in": _LBF / _IN,
                  "lbf/ft": _LBF / _FT},
    "damping": {"N s/m": 1.0, "kN s/m": 1e3, "lbf s/in": _LBF / _IN, "lbf s/ft": _LBF / _FT},
}


def parse(text: object, kind: str, key: str) -> float:
    """Read a force, stiffness or damping quantity string as SI [N, N/m, N s/m]."""
    q = units._parse_text(text, key)
    table = KINDS[kind]
    if q.unit not in table:
        raise InputError(key, text, f"a {kind} in one of: " + ", ".join(table))
    return q.value * table[q.unit]


def quantity(t: Table, key: str, kind: str, default=None) -> float:
    """Read ``key`` of ``t`` as a force, stiffness or damping (``default`` if absent)."""
    if default is not None and not t.has(key):
        t.raw(key, default)
        return parse(default, kind, t.key(key))
    return parse(t.raw(key), kind, t.key(key))
