"""Quantity strings to SI and back.

Scenes give every dimensional value as a string with its unit (``"14.5 in"``,
``"100 psig"``, ``"26 inHg vacuum"``, ``"2 3/4 in"``).  Inside corliss everything is
SI with absolute pressure; this module is the only place units are converted.

Gauge pressure is never implicit: ``psig``, ``barg`` and ``inHg vacuum`` are read
against a barometer, which the scene states (default 14.696 psia).  A bare ``psi``
is refused because it does not say which.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from corliss.errors import InputError

#: Standard atmosphere [Pa], the default barometer.
STANDARD_ATMOSPHERE_Pa = 101_325.0

INCH_m = 0.0254
FOOT_m = 0.3048
POUND_kg = 0.45359237
LBF_N = 4.4482216152605
PSI_Pa = LBF_N / INCH_m**2
INHG_Pa = 3386.389  # conventional inch of mercury at 0 degC
MMHG_Pa = 133.322387415
HP_W = 745.69987158227  # mechanical horse-power, 550 ft lbf/s
RPM_RAD_S = 2.0 * math.pi / 60.0

#: Kinds of quantity and their units: name -> (factor to SI, offset to SI).
#: Pressure units with a gauge or vacuum sense are handled separately.
_LINEAR: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": INCH_m, "inch": INCH_m,
               "inches": INCH_m, "ft": FOOT_m, "feet": FOOT_m, "foot": FOOT_m},
    "area": {"m2": 1.0, "mm2": 1e-6, "cm2": 1e-4, "in2": INCH_m**2, "ft2": FOOT_m**2},
    "volume": {"m3": 1.0, "L": 1e-3, "l": 1e-3, "cm3": 1e-6, "in3": INCH_m**3,
               "ft3": FOOT_m**3},
    "speed": {"rpm": RPM_RAD_S, "rad/s": 1.0, "rev/s": 2.0 * math.pi},
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0},
    "torque": {"N m": 1.0, "kN m": 1e3, "lbf ft": LBF_N * FOOT_m,
               "ft lbf": LBF_N * FOOT_m, "lbf in": LBF_N * INCH_m},
    "torque_per_speed": {"N m s": 1.0, "N m/rpm": 1.0 / RPM_RAD_S,
                         "lbf ft/rpm": LBF_N * FOOT_m / RPM_RAD_S},
    "heat_transfer": {"W/m2 K": 1.0, "kW/m2 K": 1e3,
                      "Btu/ft2 degF min": 1055.05585 / (FOOT_m ** 2 * 5.0 / 9.0 * 60.0),
                      "Btu/ft2 degF h": 1055.05585 / (FOOT_m ** 2 * 5.0 / 9.0 * 3600.0)},
    "power": {"W": 1.0, "kW": 1e3, "MW": 1e6, "hp": HP_W, "ihp": HP_W},
    "mass": {"kg": 1.0, "g": 1e-3, "t": 1e3, "lb": POUND_kg, "lbm": POUND_kg},
    "inertia": {"kg m2": 1.0, "lb ft2": POUND_kg * FOOT_m**2,
                "lbm ft2": POUND_kg * FOOT_m**2, "slug ft2": 14.5939029 * FOOT_m**2},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0},
    "mass_flow": {"kg/s": 1.0, "kg/h": 1.0 / 3600.0, "lb/h": POUND_kg / 3600.0},
    "force": {"N": 1.0, "kN": 1e3, "lbf": LBF_N},
    "stiffness": {"N/m": 1.0, "N/mm": 1e3, "kN/m": 1e3, "lbf/in": LBF_N / INCH_m,
                  "lbf/ft": LBF_N / FOOT_m},
    "damping": {"N s/m": 1.0, "kN s/m": 1e3, "lbf s/in": LBF_N / INCH_m,
                "lbf s/ft": LBF_N / FOOT_m},
    "specific_energy": {"J/kg": 1.0, "kJ/kg": 1e3, "Btu/lb": 2326.0},
    "energy": {"J": 1.0, "kJ": 1e3, "MJ": 1e6, "Btu": 1055.05585},
    "specific_steam_consumption": {"kg/J": 1.0, "kg/kWh": 1.0 / 3.6e6,
                                   "lb/hp h": POUND_kg / (HP_W * 3600.0)},
}

_ABS_PRESSURE = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "bar": 1e5, "bara": 1e5,
                 "psia": PSI_Pa, "atm": STANDARD_ATMOSPHERE_Pa, "inHg": INHG_Pa,
                 "mmHg": MMHG_Pa}
_GAUGE_PRESSURE = {"psig": PSI_Pa, "barg": 1e5, "kPag": 1e3}
_VACUUM = {"inHg vacuum": INHG_Pa, "inHg vac": INHG_Pa, "mmHg vacuum": MMHG_Pa,
           "mmHg vac": MMHG_Pa}
_TEMPERATURE = ("K", "degC", "degF", "degR")

KINDS = tuple(sorted(list(_LINEAR) + ["pressure", "temperature"]))

_NUMBER = re.compile(
    r"^\s*(?P<sign>[-+])?\s*(?:(?P<whole>\d+)\s+(?P<fn>\d+)/(?P<fd>\d+)|(?P<num>\d+)/(?P<den>\d+)"
    r"|(?P<dec>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))\s*(?P<unit>.*?)\s*$"
)


@dataclass(frozen=True)
class Quantity:
    """A parsed quantity string: the number as written and its unit text."""

    value: float
    unit: str


def _parse_text(text: object, key: str) -> Quantity:
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise InputError(key, text, "a quantity string with a unit, such as \"12 in\"")
    if isinstance(text, (int, float)):
        raise InputError(key, text, "a quantity with its unit as a string, e.g. "
                         f"\"{text} in\"; a bare number is ambiguous")
    m = _NUMBER.match(text)
    if not m:
        raise InputError(key, text, "a number followed by a unit, e.g. \"2 3/4 in\"")
    if m.group("whole") is not None:
        v = int(m.group("whole")) + int(m.group("fn")) / int(m.group("fd"))
    elif m.group("num") is not None:
        v = int(m.group("num")) / int(m.group("den"))
    else:
        v = float(m.group("dec"))
    if m.group("sign") == "-":
        v = -v
    unit = re.sub(r"\s+", " ", m.group("unit").replace("°F", "degF").replace("°C", "degC"))
    unit = unit.replace("·", " ").replace("*", " ").replace("^2", "2").replace("²", "2")
    return Quantity(v, unit)


def units_of(kind: str) -> tuple[str, ...]:
    """Unit names accepted for a kind of quantity."""
    if kind == "pressure":
        return tuple(_ABS_PRESSURE) + tuple(_GAUGE_PRESSURE) + tuple(_VACUUM)
    if kind == "temperature":
        return _TEMPERATURE
    return tuple(_LINEAR[kind])


def parse(text: object, kind: str, key: str = "value", *,
          barometer_Pa: float = STANDARD_ATMOSPHERE_Pa) -> float:
    """Read a quantity string as an SI float.

    Parameters
    ----------
    text : str
        The quantity, e.g. ``"100 psig"``.
    kind : str
        One of :data:`KINDS`.
    key : str
        Scene key the value came from, for the error message.
    barometer_Pa : float
        Atmospheric pressure [Pa] for gauge and vacuum readings.

    Returns
    -------
    float
        The value in SI (m, Pa absolute, K, rad/s, s, N m, W, kg, kg m2, m3, rad).

    Raises
    ------
    InputError
        If the text has no unit, an unknown unit, or a unit of another kind.
    """
    q = _parse_text(text, key)
    if q.unit == "":
        raise InputError(key, text, f"a {kind} with its unit; one of "
                         + ", ".join(units_of(kind)))
    if kind == "pressure":
        if q.unit in _ABS_PRESSURE:
            return q.value * _ABS_PRESSURE[q.unit]
        if q.unit in _GAUGE_PRESSURE:
            return barometer_Pa + q.value * _GAUGE_PRESSURE[q.unit]
        if q.unit in _VACUUM:
            return barometer_Pa - q.value * _VACUUM[q.unit]
        if q.unit == "psi":
            raise InputError(key, text, "\"psia\" (absolute) or \"psig\" (gauge); a "
                             "bare psi does not say which")
    elif kind == "temperature":
        if q.unit == "K":
            return q.value
        if q.unit == "degC":
            return q.value + 273.15
        if q.unit == "degF":
            return (q.value - 32.0) * 5.0 / 9.0 + 273.15
        if q.unit == "degR":
            return q.value * 5.0 / 9.0
    elif kind in _LINEAR:
        table = _LINEAR[kind]
        if q.unit in table:
            return q.value * table[q.unit]
    else:
        raise ValueError(f"unknown kind of quantity {kind!r}")
    raise InputError(key, text, f"a {kind} in one of: " + ", ".join(units_of(kind)))


def to_unit(value_si: float, unit: str, *, barometer_Pa: float = STANDARD_ATMOSPHERE_Pa):
    """Convert an SI value (array or float) to ``unit``.

    Pressure units with a gauge sense subtract the barometer; ``degF`` and
    ``degC`` apply their offsets.
    """
    if unit in _ABS_PRESSURE:
        return value_si / _ABS_PRESSURE[unit]
    if unit in _GAUGE_PRESSURE:
        return (value_si - barometer_Pa) / _GAUGE_PRESSURE[unit]
    if unit == "K":
        return value_si
    if unit == "degC":
        return value_si - 273.15
    if unit == "degF":
        return (value_si - 273.15) * 9.0 / 5.0 + 32.0
    for table in _LINEAR.values():
        if unit in table:
            return value_si / table[unit]
    raise ValueError(f"unknown unit {unit!r}")


def from_unit(value: float, unit: str, *, barometer_Pa: float = STANDARD_ATMOSPHERE_Pa):
    """Convert ``value`` in ``unit`` to SI (the inverse of :func:`to_unit`)."""
    if unit in _ABS_PRESSURE:
        return value * _ABS_PRESSURE[unit]
    if unit in _GAUGE_PRESSURE:
        return barometer_Pa + value * _GAUGE_PRESSURE[unit]
    if unit == "K":
        return value
    if unit == "degC":
        return value + 273.15
    if unit == "degF":
        return (value - 32.0) * 5.0 / 9.0 + 273.15
    for table in _LINEAR.values():
        if unit in table:
            return value * table[unit]
    raise ValueError(f"unknown unit {unit!r}")
