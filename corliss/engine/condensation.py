"""Marks's law of initial condensation (Relative Proportions, Arts. 74-82): the period's
prediction of the steam that condenses on the walls at each stroke.

The loss is proportional to the temperature drop from cut-off to exhaust, to the
cast-iron surface exposed, and to the time it was exposed to the exhaust (Art. 75)::

    condensation per stroke = C (T_b - T_e) (pi d / 2N) (d + Y(e) s)          (eq. 221)
    Y(e) = 1 - [sqrt(1 - (2e - 1)^2) - (2e - 1) acos(2e - 1)] / pi           (curve of condensation)

with d the bore and s the stroke, N strokes per unit time, e the true cut-off (a
fraction of the volume with one clearance), T_b the steam temperature at cut-off and
T_e the exhaust temperature.  C = 0.02047 lb of steam per ft2, degF and minute, the
mean of his concordant experiments (Art. 82, L11126).
"""

from __future__ import annotations

import math

from corliss import units

#: Marks's mean constant of condensation, Art. 82, in kg / (m2 K s).
MARKS_C = 0.02047 * units.POUND_kg / (units.FOOT_m ** 2 * (5.0 / 9.0) * 60.0)


def curve_of_condensation(e: float) -> float:
    """Y(e) of Marks Art. 75 [-] for a true cut-off ``e`` in [0, 1]."""
    a = 2.0 * min(max(e, 0.0), 1.0) - 1.0
    return 1.0 - (math.sqrt(max(1.0 - a * a, 0.0)) - a * math.acos(a)) / math.pi


def marks_condensation_kg(bore_m: float, stroke_m: float, strokes_per_s: float, e: float,
                          t_cutoff_K: float, t_exhaust_K: float, C: float = MARKS_C) -> float:
    """Steam condensed per stroke [kg] by Marks's eq. 221 (SI throughout)."""
    return (C * max(t_cutoff_K - t_exhaust_K, 0.0) * math.pi * bore_m / (2.0 * strokes_per_s)
            * (bore_m + curve_of_condensation(e) * stroke_m))
