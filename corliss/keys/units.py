"""Quantity strings to SI and back.

Scenes give every dimensional value as a string with its unit (``"14.5 in"``,
``"100 psig"``, ``"26 inHg vacuum"``, ``"2 3/4 in"``).  Inside corliss everything is
SI with absolute pressure; this module is the only place units are converted.

Gauge pressure is never implicit: ``psig``, ``barg``, ``kPa(g)`` and ``inHg vacuum``
are read against a barometer, which the scene states (default 14.696 psia).  A bare
``psi``, ``bar``, ``kPa`` or ``MPa`` is refused because it does not say which; each
takes ``a``, ``(a)``, ``abs`` or ``absolute`` after it for absolute, ``g``, ``(g)``,
``gauge`` or ``gage`` for gauge.  ``Pa``, ``atm``, ``inHg`` and ``mmHg`` are absolute
as written.  Lengths also in ``thou`` (a thousandth of an inch, ``"15 thou"``).
Speeds in ``rpm``, ``RPM``, ``rev/min``, ``r/min``, ``rev/s`` or ``rad/s``.
"""

from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from corliss.errors import InputError

if TYPE_CHECKING:  # for annotations only: this module never needs numpy at run time
    import numpy as np

#: Standard atmosphere [Pa], the default barometer.
STANDARD_ATMOSPHERE_Pa = 101_325.0

INCH_m = 0.0254
#: The thou, a thousandth of an inch [m]: the machinist's unit, in which live-steam
#: builders give laps, leads and clearances ("15 thou" is 0.015 in).
THOU_m = INCH_m / 1000.0
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
               "inches": INCH_m, "thou": THOU_m, "ft": FOOT_m, "feet": FOOT_m,
               "foot": FOOT_m},
    "area": {"m2": 1.0, "mm2": 1e-6, "cm2": 1e-4, "in2": INCH_m**2, "ft2": FOOT_m**2},
    "volume": {"m3": 1.0, "L": 1e-3, "l": 1e-3, "cm3": 1e-6, "in3": INCH_m**3,
               "ft3": FOOT_m**3},
    "speed": {"rpm": RPM_RAD_S, "RPM": RPM_RAD_S, "rev/min": RPM_RAD_S,
              "r/min": RPM_RAD_S, "rad/s": 1.0, "rev/s": 2.0 * math.pi},
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
    # a rate of leak: mass flow per unit of pressure difference (Callendar and
    # Nicolson's 3 lb/h per lbf/in2 of their flat valve)
    "leak_rate": {"kg/s Pa": 1.0, "kg/h bar": 1.0 / 3600.0 / 1e5,
                  "kg/h psi": 1.0 / 3600.0 / PSI_Pa, "lb/h psi": POUND_kg / 3600.0 / PSI_Pa},
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
#: Pressure units a scene must qualify as absolute or gauge: gauges of the period and of
#: today read in them as often as tables do.  ``Pa``, ``atm``, ``inHg`` and ``mmHg``
#: are absolute as written (a barometer reads inHg absolute; "inHg vacuum" is gauge).
_QUALIFIED = {"psi": PSI_Pa, "bar": 1e5, "kPa": 1e3, "MPa": 1e6}
#: The spellings of "absolute" and "gauge" after one of :data:`_QUALIFIED`:
#: ``psia``, ``psi(a)``, ``psi abs``, ``psi absolute``; ``psig``, ``psi(g)``, ...
_ABS_MARKS = ("a", "(a)", " a", " abs", " absolute")
_GAUGE_MARKS = ("g", "(g)", " g", " gauge", " gage")
_ABS_INPUT = {u + m: f for u, f in _QUALIFIED.items() for m in _ABS_MARKS}
_ABS_INPUT.update({u: _ABS_PRESSURE[u] for u in ("Pa", "atm", "inHg", "mmHg")})
_GAUGE_INPUT = {u + m: f for u, f in _QUALIFIED.items() for m in _GAUGE_MARKS}
_VACUUM = {"inHg vacuum": INHG_Pa, "inHg vac": INHG_Pa, "mmHg vacuum": MMHG_Pa,
           "mmHg vac": MMHG_Pa}
_TEMPERATURE = ("K", "degC", "degF", "degR")

KINDS = tuple(sorted(list(_LINEAR) + ["pressure", "temperature"]))

#: Triple point of water (IAPWS-95): the least pressure [Pa] and temperature [K] at
#: which steam exists beside liquid water; the critical pressure [Pa].
TRIPLE_POINT_Pa = 611.657
TRIPLE_POINT_K = 273.16
CRITICAL_PRESSURE_Pa = 22.064e6

#: The physical range of each kind of quantity, SI, and the unit it is shown in:
#: magnitudes a steam engine, its valve gear, its governor or its steam can have.
#: A value outside is refused whatever the key; a key may narrow its own range
#: (``within=`` of the scene's getters).  Pressures and temperatures span the steam
#: properties (IAPWS-95 from the triple point to 1273 K and 100 MPa); signed kinds
#: (laps, leads, angles, torques) are bounded in magnitude.
RANGES: dict[str, tuple[float, float, str]] = {
    "length": (-50.0, 50.0, "m"),
    "area": (0.0, 10.0, "m2"),
    "volume": (0.0, 100.0, "m3"),
    "speed": (0.0, 5000.0 * RPM_RAD_S, "rpm"),
    "time": (0.0, 36000.0, "s"),
    "torque": (-1e7, 1e7, "N m"),
    "torque_per_speed": (0.0, 1e7, "N m s"),
    "heat_transfer": (0.0, 1e6, "W/m2 K"),
    "power": (0.0, 1e8, "W"),
    "mass": (0.0, 1e5, "kg"),
    "inertia": (0.0, 1e8, "kg m2"),
    "angle": (-4.0 * math.pi, 4.0 * math.pi, "deg"),
    "mass_flow": (0.0, 1e3, "kg/s"),
    "leak_rate": (0.0, 1e-4, "lb/h psi"),
    "force": (-1e6, 1e6, "N"),
    "stiffness": (0.0, 1e9, "N/m"),
    "damping": (0.0, 1e8, "N s/m"),
    "specific_energy": (0.0, 1e7, "J/kg"),
    "energy": (0.0, 1e10, "J"),
    "specific_steam_consumption": (0.0, 1.0, "kg/kWh"),
    "pressure": (TRIPLE_POINT_Pa, 100e6, "kPa"),
    "temperature": (TRIPLE_POINT_K, 1273.15, "K"),
}


def _show(value_si: float, unit: str) -> str:
    v = to_unit(value_si, unit) if unit not in ("K",) else value_si
    return f"{v:.6g} {unit}"


def check_range(value_si: float, kind: str, key: str, text: object,
                within: tuple[float, float] | None = None) -> float:
    """``value_si`` if it lies in the physical range of ``kind`` (narrowed to ``within``,
    SI, when given), else an InputError naming the key, the value and the range.

    Parameters
    ----------
    value_si : float
        The value [SI].
    kind : str
        One of :data:`KINDS`.
    key : str
        The scene key, for the message.
    text : object
        The value as written, for the message.
    within : (float, float), optional
        The key's own range [SI].

    Returns
    -------
    float
        ``value_si``.
    """
    lo, hi, unit = RANGES[kind]
    if within is not None:
        lo, hi = max(lo, within[0]), min(hi, within[1])
    if not (lo <= value_si <= hi):
        extra = " absolute" if kind == "pressure" else ""
        name = kind.replace('_', ' ')
        article = "an" if name[0] in "aeiou" else "a"
        raise InputError(key, text, f"{article} {name} from {_show(lo, unit)} to "
                         f"{_show(hi, unit)}{extra}")
    return value_si

#: The grammar of a quantity: a signed decimal (up to 20 digits before and after the
#: point, an exponent of up to 3 digits), a fraction of whole numbers or a whole number
#: and a fraction (up to 9 digits each), then the unit.  Longer numbers are no
#: measurement; the bound keeps every conversion exact and finite.
_NUMBER = re.compile(
    r"^\s*(?P<sign>[-+])?\s*(?:(?P<whole>\d{1,9})\s+(?P<fn>\d{1,9})/(?P<fd>\d{1,9})"
    r"|(?P<num>\d{1,9})/(?P<den>\d{1,9})"
    r"|(?P<dec>(?:\d{1,20}(?:\.\d{0,20})?|\.\d{1,20})(?:[eE][-+]?\d{1,3})?))"
    r"\s*(?P<unit>.*?)\s*$"
)
#: The longest quantity string read [characters].
MAX_TEXT = 80


@dataclass(frozen=True)
class Quantity:
    """A parsed quantity string: the number as written and its unit text.

    Parameters
    ----------
    value : float
        The number.
    unit : str
        The unit's text.
    """

    value: float
    unit: str


#: The SI unit of each kind, in the spelling of unit libraries such as pint, for a
#: quantity object passed through the Python API (:func:`parse`).
SI_UNIT_TEXT = {
    "length": "m", "area": "m**2", "volume": "m**3", "speed": "rad/s", "time": "s",
    "torque": "N*m", "torque_per_speed": "N*m*s", "heat_transfer": "W/(m**2*K)",
    "power": "W", "mass": "kg", "inertia": "kg*m**2", "angle": "rad", "mass_flow": "kg/s",
    "leak_rate": "kg/(s*Pa)", "force": "N", "stiffness": "N/m", "damping": "N*s/m", "specific_energy": "J/kg",
    "energy": "J", "specific_steam_consumption": "kg/J", "temperature": "K",
}


def is_quantity_object(value: object) -> bool:
    """Whether ``value`` is a quantity object of a unit library (pint's ``Quantity``, or
    anything with ``.to(unit)`` and ``.magnitude``), not a scene's string.

    Parameters
    ----------
    value : object
        A value from a scene's tables.

    Returns
    -------
    bool
        True for a quantity object.
    """
    return (not isinstance(value, (str, int, float, bool)) and hasattr(value, "to")
            and hasattr(value, "magnitude"))


def _from_object(q: Any, kind: str, key: str, within) -> float:
    """A quantity object in SI, converted by ``kind``; the library is never imported
    here: the object converts itself."""
    if kind == "pressure":
        raise InputError(key, q, "a pressure as a string that says absolute or gauge "
                         "(\"100 psia\", \"85 psig\"): a quantity object does not say which")
    try:
        v = float(q.to(SI_UNIT_TEXT[kind]).magnitude)
    except (TypeError, ValueError, AttributeError) as exc:
        raise InputError(key, q, f"a {kind.replace('_', ' ')} ({exc})") from None
    if not math.isfinite(v):
        raise InputError(key, q, "a finite quantity")
    return check_range(v, kind, key, q, within)


def _parse_text(text: object, key: str) -> Quantity:
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise InputError(key, text, "a quantity string with a unit, such as \"12 in\"")
    if isinstance(text, (int, float)):
        raise InputError(key, text, "a quantity with its unit as a string, e.g. "
                         f"\"{text} in\"; a bare number is ambiguous")
    if len(text) > MAX_TEXT:
        raise InputError(key, text[:40] + "...", f"a quantity of at most {MAX_TEXT} characters, "
                         "e.g. \"2 3/4 in\"")
    m = _NUMBER.match(text)
    if not m:
        raise InputError(key, text, "a number (at most 20 digits, or a fraction of whole "
                         "numbers of at most 9) followed by a unit, e.g. \"2 3/4 in\"")
    den = m.group("fd") or m.group("den")
    if den is not None and int(den) == 0:
        raise InputError(key, text, "a fraction whose denominator is not zero")
    if m.group("whole") is not None:
        v = int(m.group("whole")) + int(m.group("fn")) / int(m.group("fd"))
    elif m.group("num") is not None:
        v = int(m.group("num")) / int(m.group("den"))
    else:
        v = float(m.group("dec"))
    if not math.isfinite(v):
        raise InputError(key, text, "a finite number with its unit")
    if m.group("sign") == "-":
        v = -v
    unit = re.sub(r"\s+", " ", m.group("unit").replace("°F", "degF").replace("°C", "degC"))
    unit = unit.replace("·", " ").replace("*", " ").replace("^2", "2").replace("²", "2")
    return Quantity(v, unit)


def units_of(kind: str) -> tuple[str, ...]:
    """Unit names accepted for a kind of quantity.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.

    Returns
    -------
    tuple of str
        The spellings accepted.
    """
    if kind == "pressure":
        return tuple(_ABS_INPUT) + tuple(_GAUGE_INPUT) + tuple(_VACUUM)
    if kind == "temperature":
        return _TEMPERATURE
    return tuple(_LINEAR[kind])


def parse(text: object, kind: str, key: str = "value", *,
          barometer_Pa: float = STANDARD_ATMOSPHERE_Pa,
          within: tuple[float, float] | None = None) -> float:
    """Read a quantity string as an SI float.

    Parameters
    ----------
    text : str or quantity object
        The quantity, e.g. ``"100 psig"``; or, through the Python API, a quantity of a
        unit library (a pint ``Quantity``: anything with ``.to`` and ``.magnitude``),
        converted to the kind's SI unit (:data:`SI_UNIT_TEXT`).  A pressure must be a
        string, which says absolute or gauge.
    kind : str
        One of :data:`KINDS`.
    key : str
        Scene key the value came from, for the error message.
    barometer_Pa : float
        Atmospheric pressure [Pa] for gauge and vacuum readings.
    within : (float, float), optional
        The key's own range [SI], inside the kind's physical range :data:`RANGES`.

    Returns
    -------
    float
        The value in SI (m, Pa absolute, K, rad/s, s, N m, W, kg, kg m2, m3, rad).

    Raises
    ------
    InputError
        If the text has no unit, an unknown unit, or a unit of another kind, or the value
        lies outside the physical range of its kind (or ``within``).
    """
    if is_quantity_object(text):
        return _from_object(text, kind, key, within)
    if isinstance(text, str) and (within is None or isinstance(within, tuple)):
        # a study reads the same texts run after run: a text read once is not read again
        return _parse_str(text, kind, key, barometer_Pa, within)
    return _parse(text, kind, key, barometer_Pa, within)


@functools.lru_cache(maxsize=4096)
def _parse_str(text: str, kind: str, key: str, barometer_Pa: float,
               within: tuple[float, float] | None) -> float:
    """:func:`parse` of a text, remembered (a refused text raises each time: an
    exception is not remembered)."""
    return _parse(text, kind, key, barometer_Pa, within)


def _parse(text, kind: str, key: str, barometer_Pa: float,
           within: tuple[float, float] | None) -> float:
    q = _parse_text(text, key)
    if q.unit == "":
        raise InputError(key, text, f"a {kind} with its unit; one of "
                         + ", ".join(units_of(kind)))
    if kind == "pressure":
        if q.unit in _ABS_INPUT:
            return check_range(q.value * _ABS_INPUT[q.unit], kind, key, text, within)
        if q.unit in _GAUGE_INPUT:
            return check_range(barometer_Pa + q.value * _GAUGE_INPUT[q.unit], kind, key,
                               text, within)
        if q.unit in _VACUUM:
            return check_range(barometer_Pa - q.value * _VACUUM[q.unit], kind, key, text,
                               within)
        if q.unit in _QUALIFIED:
            u, v = q.unit, f"{q.value:g}"
            a, g = ("a", "g") if u in ("psi", "bar") else ("(a)", "(g)")
            raise InputError(key, text, f"\"{v} {u}{a}\" (absolute) or \"{v} {u}{g}\" (gauge, "
                             f"against the barometer); a bare {u} does not say which")
    elif kind == "temperature":
        kelvin = {"K": q.value, "degC": q.value + 273.15,
                  "degF": (q.value - 32.0) * 5.0 / 9.0 + 273.15, "degR": q.value * 5.0 / 9.0}
        if q.unit in kelvin:
            return check_range(kelvin[q.unit], kind, key, text, within)
    elif kind in _LINEAR:
        table = _LINEAR[kind]
        if q.unit in table:
            return check_range(q.value * table[q.unit], kind, key, text, within)
    else:
        raise ValueError(f"unknown kind of quantity {kind!r}")
    if kind == "pressure":
        raise InputError(key, text, f"a pressure in {PRESSURE_UNITS_TEXT}")
    raise InputError(key, text, f"a {kind} in one of: " + ", ".join(units_of(kind)))


#: What a pressure's unit must be, in words (for the messages that refuse one).
PRESSURE_UNITS_TEXT = ("psia, psig, bara, barg, kPa(a), kPa(g), MPa(a), MPa(g), Pa, atm, inHg, "
                       "mmHg or inHg vacuum (absolute or gauge also as psi(a), bar abs, kPa "
                       "gauge, ...)")


def pressure_to_si(values, unit: str, *, barometer_Pa: float = STANDARD_ATMOSPHERE_Pa):
    """Absolute pressures [Pa] of ``values`` (a number or an array) read in ``unit``, a
    spelling a scene may use (:func:`units_of` ``("pressure")``; gauge and vacuum
    against ``barometer_Pa`` [Pa]).

    Parameters
    ----------
    values : float or numpy.ndarray
        Readings in ``unit``.
    unit : str
        A pressure unit a scene may use.
    barometer_Pa : float
        Atmospheric pressure [Pa] for gauge readings.

    Returns
    -------
    float or numpy.ndarray
        Absolute pressures [Pa].

    Raises
    ------
    ValueError
        For a unit that is not a pressure or does not say absolute or gauge.
    """
    if unit in _ABS_INPUT:
        return values * _ABS_INPUT[unit]
    if unit in _GAUGE_INPUT:
        return barometer_Pa + values * _GAUGE_INPUT[unit]
    if unit in _VACUUM:
        return barometer_Pa - values * _VACUUM[unit]
    raise ValueError(f"unknown pressure unit {unit!r}")


def to_unit(value_si: float | np.ndarray, unit: str, *, barometer_Pa: float = STANDARD_ATMOSPHERE_Pa):
    """Convert an SI value (array or float) to ``unit``.

    Pressure units with a gauge sense subtract the barometer; ``degF`` and
    ``degC`` apply their offsets.

    Parameters
    ----------
    value_si : float or numpy.ndarray
        The value [SI].
    unit : str
        The unit wanted.
    barometer_Pa : float
        Atmospheric pressure [Pa] for gauge readings.

    Returns
    -------
    float or numpy.ndarray
        The value in ``unit``.
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


def from_unit(value: float | np.ndarray, unit: str, *, barometer_Pa: float = STANDARD_ATMOSPHERE_Pa):
    """Convert ``value`` in ``unit`` to SI (the inverse of :func:`to_unit`).

    Parameters
    ----------
    value : float or numpy.ndarray
        The value in ``unit``.
    unit : str
        Its unit.
    barometer_Pa : float
        Atmospheric pressure [Pa] for gauge readings.

    Returns
    -------
    float or numpy.ndarray
        The value [SI].
    """
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
