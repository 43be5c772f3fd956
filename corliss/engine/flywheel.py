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
from corliss.keys.toml_table import Table


#: The flywheels engines have [SI]: a model engine's rim of a kilogram a few centimetres
#: out, to the largest mill engines' (rims of some 100 t, 15 m across; Marks Art. 61
#: sizes them).  Smaller or larger is no flywheel: a rim of a microgram would let the
#: speed swing without bound within a turn.
RIM_MASS_RANGE = (0.1, 1e5)             # [kg]
RIM_RADIUS_RANGE = (0.01, 10.0)         # [m]
INERTIA_RANGE = (1e-5, 2e7)             # [kg m2]


@dataclass(frozen=True)
class FlywheelSpec:
    """The rotating train's inertia.

    Parameters
    ----------
    inertia_kg_m2 : float
        Moment of inertia about the shaft [kg m2].
    """

    inertia_kg_m2: float


def parse_flywheel(t: Table) -> FlywheelSpec:
    """Read a ``[flywheel]`` table.

    Either ``moment_of_inertia``, or ``rim_weight`` with ``mean_radius`` (the rim's
    ``m r^2``, Marks Art. 61); ``other_inertia`` is added to either.

    Parameters
    ----------
    t : Table
        The scene's ``[flywheel]`` table.

    Returns
    -------
    FlywheelSpec
        The train's moment of inertia [kg m2].

    Raises
    ------
    InputError
        Both forms or neither, a value outside :data:`INERTIA_RANGE`,
        :data:`RIM_MASS_RANGE` or :data:`RIM_RADIUS_RANGE`, or an unknown key.
    """
    direct = t.has("moment_of_inertia")
    rim = t.has("rim_weight") or t.has("mean_radius")
    if direct == rim:
        raise InputError(t.key("moment_of_inertia"), t.raw("moment_of_inertia", None),
                         "either moment_of_inertia, or rim_weight with mean_radius (not both)")
    if direct:
        inertia = t.quantity("moment_of_inertia", "inertia", within=INERTIA_RANGE)
    else:
        m = t.quantity("rim_weight", "mass", within=RIM_MASS_RANGE)
        r = t.length("mean_radius", within=RIM_RADIUS_RANGE)
        inertia = m * r * r
    inertia += t.quantity("other_inertia", "inertia", "0 kg m2")
    if not inertia > 0.0:
        raise InputError(t.key("moment_of_inertia"), t.raw("moment_of_inertia", None),
                         "a moment of inertia above zero")
    t.finish()
    return FlywheelSpec(inertia)
