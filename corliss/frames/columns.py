"""The vocabulary of column names and summary keys: every name ends in its unit.

Inside corliss a table's columns are SI, the unit the last part of the name
(``p_head_Pa``, ``steam_rate_kg_per_h``, ``governor_z_frac``).  This module knows
every such suffix, its SI unit, and what it becomes in either output system, so a
frame converts to US or SI by its names alone; :func:`unit_of` answers for any
column, and a column whose suffix is not here is an error, not a silent pass.

Sign convention of flows, in every table: mass and enthalpy are counted positive
*into* the engine's steam (``m_supply_kg`` > 0 from the chest; ``m_exhaust_kg`` < 0
for steam leaving to the exhaust; a leak's mass positive into the end it names);
heat ``Q_*_J`` is positive into the steam, ``Q_to_wall_*_J`` positive into the wall;
work ``work_*_J`` is positive done by the steam on the piston.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from corliss.keys import units
from corliss.frames.frame import Frame

if TYPE_CHECKING:      # convert_frame's DataFrame: pandas is imported when it is called
    import pandas as pd

#: Columns that name a row rather than measure something, with their meaning.
INDEX_COLUMNS = {"cycle": "count (turn or cycle number, from 1)",
                 "end": "label (head or crank, with a cylinder prefix)",
                 "phase": "label (before or after the load step)",
                 "knob": "label (setting or throttle)",
                 "variant": "label (throttling or cutoff: how the engine is governed)",
                 "condensation": "label (on or off: the wall-heat effect)",
                 "status": "label (found, or unreached: no operating point at that load)",
                 "winner": "label (the governing that uses less steam at that load)"}

#: Suffix -> (SI unit, US suffix, US unit, SI output suffix, SI output unit).  The
#: units are names :mod:`corliss.keys.units` converts; suffixes of two parts come first.
SUFFIXES: dict[str, tuple[str, str, str, str, str]] = {
    "kg_per_kWh": ("kg/kWh", "lb_per_hp_h", "lb/hp h", "kg_per_kWh", "kg/kWh"),
    "kg_per_h": ("kg/h", "lb_per_h", "lb/h", "kg_per_h", "kg/h"),
    "N_m": ("N m", "lbf_ft", "lbf ft", "N_m", "N m"),
    "kg_m2": ("kg m2", "lb_ft2", "lb ft2", "kg_m2", "kg m2"),
    "Pa": ("Pa", "psia", "psia", "kPa_abs", "kPa"),
    "m3": ("m3", "ft3", "ft3", "m3", "m3"),
    "m": ("m", "in", "in", "mm", "mm"),
    "K": ("K", "degF", "degF", "degC", "degC"),
    "kg": ("kg", "lb", "lb", "kg", "kg"),
    "J": ("J", "ft_lbf", "ft lbf", "J", "J"),
    "N": ("N", "lbf", "lbf", "N", "N"),
    "W": ("W", "hp", "hp", "kW", "kW"),
    "s": ("s", "s", "s", "s", "s"),
    "deg": ("deg", "deg", "deg", "deg", "deg"),
    "rpm": ("rpm", "rpm", "rpm", "rpm", "rpm"),
    "frac": ("-", "frac", "-", "frac", "-"),
}
#: Units a column may carry once converted (for the meta file's ``columns``).
DIMENSIONLESS = "-"


def split(column: str) -> tuple[str, str | None]:
    """A column name split into its base and its unit suffix.

    Parameters
    ----------
    column : str
        A column name or summary key (``p_head_Pa``, ``steam_rate_kg_per_h``).

    Returns
    -------
    base : str
        The name without its suffix (``p_head``); the whole name for an index column.
    suffix : str or None
        A key of :data:`SUFFIXES` (``"Pa"``, ``"kg_per_h"``); None for an index column
        (:data:`INDEX_COLUMNS`).

    Raises
    ------
    KeyError
        If the name ends in no known unit.
    """
    if column in INDEX_COLUMNS:
        return column, None
    for sfx in SUFFIXES:
        if column.endswith("_" + sfx) and len(column) > len(sfx) + 1:
            return column[: -len(sfx) - 1], sfx
    raise KeyError(f"column {column!r} ends in no known unit: "
                   + ", ".join(sorted(SUFFIXES)))


def unit_of(column: str) -> str:
    """The SI unit of an internal column.

    Parameters
    ----------
    column : str
        A column name or summary key ending in a known unit suffix.

    Returns
    -------
    str
        The SI unit (``"Pa"``, ``"kg/h"``); ``"-"`` for fractions and index columns.

    Raises
    ------
    KeyError
        If the name ends in no known unit.
    """
    _, sfx = split(column)
    return DIMENSIONLESS if sfx is None else SUFFIXES[sfx][0]


def convert_frame(df: pd.DataFrame, system: str,
                  barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa
                  ) -> tuple[pd.DataFrame, dict[str, str]]:
    """A copy of an SI frame in ``system`` and the unit of each of its columns.

    :func:`convert_columns` does the work and hands back a
    :class:`~corliss.frames.frame.Frame`; this is the same as a DataFrame.

    Parameters
    ----------
    df : pandas.DataFrame
        Columns named by the vocabulary above, SI.
    system : str
        ``"US"`` (psia, ft3, degF, lb, ft lbf, hp) or ``"SI"`` (kPa absolute, m3, degC,
        kg, J, kW).
    barometer_Pa : float, optional
        Atmospheric pressure [Pa] (only gauge units read it; outputs are absolute).

    Returns
    -------
    frame : pandas.DataFrame
        The converted frame, each name carrying its output unit (``p_head_psia``).
    units : dict of str to str
        ``{column: unit}``, pressures marked absolute, index columns described.

    Raises
    ------
    KeyError
        If a column's name ends in no known unit.
    ValueError
        If ``system`` is neither ``"US"`` nor ``"SI"``.
    """
    frame, col_units = convert_columns(df, system, barometer_Pa)
    return frame.to_pandas(), col_units


def convert_columns(df, system: str, barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa
                    ) -> tuple[Frame, dict[str, str]]:
    """An SI table in ``system`` as a :class:`~corliss.frames.frame.Frame` (no pandas), and the
    unit of each of its columns.

    Parameters
    ----------
    df : Frame or DataFrame
        Columns named by the vocabulary above, SI.
    system : str
        ``"US"`` or ``"SI"`` (see :func:`convert_frame`).
    barometer_Pa : float
        Atmospheric pressure [Pa] (only gauge units read it; outputs are absolute).

    Returns
    -------
    (Frame, dict)
        The converted table (names carry the output unit) and ``{column: unit}``.
    """
    if system not in ("US", "SI"):
        raise ValueError(f"units system {system!r}: 'US' or 'SI'")
    out, col_units = {}, {}
    for col in df.columns:
        base, sfx = split(col)
        if sfx is None:
            out[col] = df[col].to_numpy()
            col_units[col] = INDEX_COLUMNS[col]
            continue
        si_unit, us_sfx, us_unit, si_sfx, si_out = SUFFIXES[sfx]
        out_sfx, unit = (us_sfx, us_unit) if system == "US" else (si_sfx, si_out)
        name = f"{base}_{out_sfx}"
        values = df[col].to_numpy(dtype=float)
        if unit != si_unit and unit != DIMENSIONLESS:
            values = units.to_unit(units.from_unit(values, si_unit), unit,
                                   barometer_Pa=barometer_Pa)
        out[name] = values
        col_units[name] = unit + (" absolute" if sfx == "Pa" else "")
    return Frame(out), col_units


def convert_record(record: dict, system: str,
                   barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa) -> dict:
    """A mapping of named quantities (a row, an end's valve events) in a unit system.

    Each key ending in a known unit (:data:`SUFFIXES`) is renamed to the system's unit
    and its value converted, as :func:`convert_frame` does a table's columns; None
    stays None, and other keys pass unchanged.  A mean effective pressure, a
    difference of pressures, is named ``_psi`` or ``_kPa`` (not absolute).

    Parameters
    ----------
    record : dict
        ``{name: value}``, SI as the package names it (``lead_m``).
    system : str
        ``"US"`` or ``"SI"``.
    barometer_Pa : float, optional
        For gauge pressures [Pa].

    Returns
    -------
    dict
        The converted mapping (``lead_in``, or ``lead_mm``), in the same order.
    """
    if system not in ("US", "SI"):
        raise ValueError(f"units system {system!r}: 'US' or 'SI'")
    out = {}
    for key, value in record.items():
        try:
            base, sfx = split(key)
        except KeyError:            # not a quantity (a label, a count)
            out[key] = value
            continue
        if sfx is None:
            out[key] = value
            continue
        si_unit, us_sfx, us_unit, si_sfx, si_out = SUFFIXES[sfx]
        out_sfx, unit = (us_sfx, us_unit) if system == "US" else (si_sfx, si_out)
        if value is not None and unit != si_unit and unit != DIMENSIONLESS:
            value = float(units.to_unit(units.from_unit(float(value), si_unit), unit,
                                        barometer_Pa=barometer_Pa))
        if sfx == "Pa" and base.startswith("mep"):
            out_sfx = "psi" if system == "US" else "kPa"    # a difference: not absolute
        out[f"{base}_{out_sfx}"] = value
    return out
