"""The flywheel: the shaft's moment of inertia, given directly or by its rim.

Marks (Art. 61) sizes a flywheel by its rim alone, the arms and hub being "neglected
as of small moment": a rim of weight W at mean radius r stores 1/2 (W/g) r^2 omega^2,
so its moment of inertia is m r^2.  A scene gives either ``moment_of_inertia`` (of the
whole rotating train, flywheel, shaft and crank) or ``rim_weight`` and
``mean_radius``, optionally with ``other_inertia`` for the rest of the train.
"""

from __future__ import annotations

from dataclasses import dataclass

from corliss.errors import InputError
from corliss.tables import Table


@dataclass(frozen=True)
class FlywheelSpec:
    """The rotating train's inertia.

    Attributes
    ----------
    inertia_kg_m2 : float
        Moment of inertia about the shaft [kg m2].
    """

    inertia_kg_m2: float


def parse_flywheel(t: Table) -> FlywheelSpec:
    """Read a ``[flywheel]`` table."""
    direct = t.has("moment_of_inertia")
    rim = t.has("rim_weight") or t.has("mean_radius")
    if direct == rim:
        raise InputError(t.key("moment_of_inertia"), t.raw("moment_of_inertia", None),
                         "either moment_of_inertia, or rim_weight with mean_radius (not both)")
    if direct:
        inertia = t.quantity("moment_of_inertia", "inertia")
    else:
        m = t.quantity("rim_weight", "mass")
        r = t.length("mean_radius", positive=True)
        if not m > 0.0:
            raise InputError(t.key("rim_weight"), t.raw("rim_weight"), "a mass above zero")
        inertia = m * r * r
    inertia += t.quantity("other_inertia", "inertia", "0 kg m2")
    if not inertia > 0.0:
        raise InputError(t.key("moment_of_inertia"), t.raw("moment_of_inertia", None),
                         "a moment of inertia above zero")
    t.finish()
    return FlywheelSpec(inertia)
