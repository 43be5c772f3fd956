"""Force, stiffness and damping quantities for governor keys (read through
:mod:`corliss.units`, which holds their unit tables; ``lb`` is a mass there, so a
force is given in ``lbf``).  Everything returned is SI.
"""

from __future__ import annotations

from corliss import units
from corliss.tables import Table

KINDS = ("force", "stiffness", "damping")


def parse(text: object, kind: str, key: str) -> float:
    """Read a force, stiffness or damping quantity string as SI [N, N/m, N s/m]."""
    return units.parse(text, kind, key)


def quantity(t: Table, key: str, kind: str, default=None) -> float:
    """Read ``key`` of ``t`` as a force, stiffness or damping (``default`` if absent)."""
    if default is not None and not t.has(key):
        return t.quantity(key, kind, default)
    return t.quantity(key, kind)
