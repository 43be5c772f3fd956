"""Measured indicator cards read from CSV, every column's quantity and unit named in
its header.

A card is a closed loop of points per cylinder end: the piston's position (or the
cylinder's volume) against the pressure, in the order the indicator's pencil (or the
digitiser) went round it.  Two layouts are read:

- long, one row per point with an ``end`` column (``head``, ``crank``, or ``lp_head``,
  ``lp_crank`` for a compound's low-pressure cylinder)::

      end,piston_position [in],pressure [psig]
      head,0.0,98.1
      ...

  This is also the layout of the card CSV ``corliss run`` writes
  (``end,crank_angle_deg,piston_frac,V_ft3,p_psia`` in US units,
  ``...,V_m3,p_kPa_abs`` in SI), which is read as it stands;

- wide, the end in each column's name (``head pressure [psig]``, ``p_crank [bara]``,
  ``piston_position_head [in]``), a column pair per end; an end's rows may stop early
  (empty fields).

A header names a column's unit in brackets (``pressure [psig]``, ``(psig)`` also) or,
as corliss writes, as the last part of the name (``p_psia``, ``p_kPa_abs``, ``V_ft3``,
``piston_frac``).  Quantities: pressure (``p``, ``pressure``: any pressure unit of
:mod:`corliss.keys.units`, gauge ones read against the scene's barometer), the piston's
position from head-end dead centre (``piston_position``, ``position``, ``x``: a length,
or ``piston_frac`` as a fraction of the stroke), volume (``V``, ``volume``: a volume
unit, the end's whole volume with its clearance), and optionally ``crank_angle``
(``deg``), which is kept but not needed.  When a file gives both position and volume,
the position is used: it is what an indicator draws.
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass, field

import numpy as np

from corliss.keys import limits, units
from corliss.errors import InputError
from corliss.keys.textfiles import read_text

#: Ends a card may hold.
ENDS = ("head", "crank", "lp_head", "lp_crank")
#: The fewest points of one end's loop that a fit reads [-].
MIN_POINTS = 12

_PRESSURE_NAMES = ("p", "pressure")
_POSITION_NAMES = ("piston_position", "position", "x", "piston", "piston_frac",
                   "piston_fraction", "stroke_fraction")
_VOLUME_NAMES = ("v", "volume")
_ANGLE_NAMES = ("crank_angle", "angle", "crank_angle_deg")
#: Units corliss writes as the end of a column's name, and what they are.
_SUFFIX_UNITS = {"psia": "psia", "psig": "psig", "kpa_abs": "kPa(a)", "kpa": "kPa", "pa": "Pa",
                 "bar": "bar", "bara": "bara", "barg": "barg", "ft3": "ft3", "m3": "m3", "in3": "in3",
                 "in": "in", "mm": "mm", "m": "m", "frac": "frac", "deg": "deg"}
_BRACKET = re.compile(r"^(?P<name>.*?)\s*[\[(](?P<unit>[^\])]*)[\])]\s*$")


@dataclass(frozen=True)
class EndCard:
    """One end's measured loop, SI.

    Parameters
    ----------
    abscissa : str
        What ``x`` is: ``"piston_frac"`` (fraction of the stroke from head-end dead
        centre [-]), ``"piston_m"`` (the piston's distance from head-end dead centre
        [m]) or ``"V_m3"`` (the end's volume [m3]).
    x : ndarray, shape (n,)
        The abscissa of each point, in the unit ``abscissa`` names, in loop order.
    p_Pa : ndarray, shape (n,)
        Absolute pressure of each point [Pa].
    crank_angle_deg : ndarray, shape (n,), optional
        Crank angle of each point [deg], when the file gives it (None otherwise).
    """

    abscissa: str
    x: np.ndarray
    p_Pa: np.ndarray
    crank_angle_deg: np.ndarray | None = None

    @property
    def n(self) -> int:
        """Number of points [-]."""
        return int(self.x.size)


@dataclass(frozen=True)
class MeasuredCard:
    """A card read from a file: the loop of each end it holds.

    Parameters
    ----------
    ends : dict of str to EndCard
        ``{end: EndCard}``, in the order of :data:`ENDS`.
    source : str, optional
        The file read (or ``"<data>"``).
    columns : dict of str to str, optional
        ``{column as written: "quantity [unit]"}``, how each column was read.
    barometer_Pa : float, optional
        The barometer gauge pressures were read against [Pa].
    """

    ends: dict
    source: str = "<data>"
    columns: dict = field(default_factory=dict)
    barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa

    @property
    def n_points(self) -> int:
        """Points over every end [-]."""
        return sum(e.n for e in self.ends.values())


def _split_header(col: str, where: str) -> tuple[str, str, str | None]:
    """(quantity name, unit, end or None) of one header field."""
    text = col.strip()
    m = _BRACKET.match(text)
    if m:
        name, unit = m.group("name").strip(), m.group("unit").strip()
        if not unit:
            raise InputError(where, col, "a column name with its unit, e.g. "
                             "\"pressure [psig]\" or \"piston_position [in]\"")
    else:
        name, unit = text, None
    low = re.sub(r"[\s\-]+", "_", name.lower())
    if low == "end":
        return "end", "", None
    if unit is None:
        for sfx in sorted(_SUFFIX_UNITS, key=len, reverse=True):
            if low.endswith("_" + sfx) and len(low) > len(sfx) + 1:
                low, unit = low[: -len(sfx) - 1], _SUFFIX_UNITS[sfx]
                break
        else:
            raise InputError(where, col, "a column whose header names its unit, e.g. "
                             "\"pressure [psig]\", \"piston_position [in]\", \"volume [ft3]\""
                             " or as corliss writes them, p_psia, piston_frac, V_ft3")
    end = None
    for e in sorted(ENDS, key=len, reverse=True):
        for pat in (rf"^{e}_(.+)$", rf"^(.+)_{e}$"):
            mm = re.match(pat, low)
            if mm and mm.group(1) != "lp" and not mm.group(1).startswith("angle"):
                low, end = mm.group(1), e
                break
        if end is not None:
            break
    return low, unit, end


def _kind(name: str, unit: str, where: str, col: str) -> str:
    """``"p"``, ``"piston_frac"``, ``"piston_m"``, ``"V"``, ``"angle"`` or ``"end"``."""
    if name == "end":
        return "end"
    if name in _PRESSURE_NAMES:
        if unit not in units.units_of("pressure") or "vac" in unit:
            raise InputError(where, col, f"a pressure in {units.PRESSURE_UNITS_TEXT}; gauge "
                             "read against the scene's barometer")
        return "p"
    if name in _POSITION_NAMES:
        if unit in ("frac", "-", ""):
            return "piston_frac"
        if unit not in units.units_of("length"):
            raise InputError(where, col, "the piston's position in a length unit ("
                             + ", ".join(units.units_of("length"))
                             + ") or as a fraction of the stroke [frac]")
        return "piston_m"
    if name in _VOLUME_NAMES:
        if unit not in units.units_of("volume"):
            raise InputError(where, col, "a volume in one of: "
                             + ", ".join(units.units_of("volume")))
        return "V"
    if name in _ANGLE_NAMES:
        if unit not in ("deg", "rad"):
            raise InputError(where, col, "a crank angle in deg or rad")
        return "angle"
    raise InputError(where, col, "a column of pressure (p, pressure), piston position "
                     "(piston_position, x, piston_frac), volume (V, volume), crank_angle or end")


def _to_si(values: np.ndarray, kind: str, unit: str, barometer_Pa: float) -> np.ndarray:
    if kind == "piston_frac":
        return values
    if kind == "angle":
        return values if unit == "deg" else np.degrees(values)
    if kind == "p":
        return np.asarray(units.pressure_to_si(values, unit, barometer_Pa=barometer_Pa),
                          dtype=float)
    return np.asarray(units.from_unit(values, unit, barometer_Pa=barometer_Pa), dtype=float)


def count_loops(x: np.ndarray) -> int:
    """How many times a card's points go round its loop.

    A loop goes along the stroke and back once.  The points' position is followed
    with hysteresis: a traverse counts when the points pass from the lowest third of
    their range to the highest (or back), so a digitiser's jitter near one place
    counts nothing.  A loop started anywhere is one traverse each way; ``n`` loops
    are ``n`` (a start mid-stroke may add a part traverse, which never reaches both
    thirds).

    Parameters
    ----------
    x : ndarray
        The abscissa of each point, in loop order (position or volume).

    Returns
    -------
    int
        The larger of the traverses out and back [-] (1 for one loop).
    """
    lo, hi = float(np.min(x)), float(np.max(x))
    a, b = lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0
    state, ups, downs = None, 0, 0
    for v in x.tolist():
        if v <= a:
            if state == "high":
                downs += 1
            state = "low"
        elif v >= b:
            if state == "low":
                ups += 1
            state = "high"
    return max(ups, downs, 1)


def parse_card(text: str, *, barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa,
               source: str = "<data>") -> MeasuredCard:
    """A :class:`MeasuredCard` from the text of a card CSV (see the module's layouts).

    Parameters
    ----------
    text : str
        The CSV text, a header line first.
    barometer_Pa : float, optional
        Atmospheric pressure [Pa] that gauge pressures are read against (the scene's).
    source : str, optional
        The file's name, for messages.

    Returns
    -------
    MeasuredCard
        Each end's loop in SI (absolute pressure [Pa]; position [m] or fraction of
        the stroke [-], or volume [m3]), the points with an empty field dropped.

    Raises
    ------
    InputError
        A header without units, an unknown quantity or unit, a field that is not a
        number, no end, an end of fewer than :data:`MIN_POINTS` points, a pressure at or
        below zero absolute.
    """
    where = f"card {source}"
    try:
        rows = [r for r in csv.reader(io.StringIO(text)) if any(f.strip() for f in r)
                and not r[0].lstrip().startswith("#")]
    except csv.Error as exc:
        raise InputError(where, source, f"a CSV file with a header line and a row per point "
                         f"({exc})") from None
    if len(rows) > limits.MAX_CARD_POINTS + 1:
        raise InputError(where, source, f"a card of at most {limits.MAX_CARD_POINTS} points "
                         f"(it has {len(rows) - 1} lines)")
    if not rows:
        raise InputError(where, source, "a CSV file with a header line and a row per point")
    header = rows[0]
    parsed = [_split_header(c, where) for c in header]
    kinds = [_kind(n, u, where, c) for (n, u, _), c in zip(parsed, header)]
    if len(rows) < 2:
        raise InputError(where, source, "a CSV file with a header line and a row per point")
    described = {c: (f"{k} [{u}]" if k != "end" else "end") for c, k, (_, u, _)
                 in zip(header, kinds, parsed)}
    body = rows[1:]

    def number(r, i, line):
        field_ = r[i].strip() if i < len(r) else ""
        if field_ == "":
            return math.nan
        try:
            v = float(field_)
        except ValueError:
            raise InputError(where, field_, f"a number in column {header[i]!r} on line "
                             f"{line}") from None
        if not math.isfinite(v):
            raise InputError(where, field_, f"a finite number in column {header[i]!r} on "
                             f"line {line}")
        return v

    columns: dict[str, dict[str, tuple[int, str, str]]] = {}
    long = "end" in kinds
    for i, ((_, unit, end), kind) in enumerate(zip(parsed, kinds)):
        if kind == "end":
            continue
        if long and end is not None:
            raise InputError(where, header[i], "one layout: an end column, or the end in "
                             "each column's name, not both")
        key = end if not long else "*"
        if key is None:
            raise InputError(where, header[i], "the end in the column's name (e.g. "
                             "\"head pressure [psig]\"), or an end column")
        slot = columns.setdefault(key, {})
        group = {"piston_frac": "x_pos", "piston_m": "x_pos"}.get(kind, kind)
        if group in slot:
            raise InputError(where, header[i], f"one {kind} column per end")
        slot[group] = (i, unit, kind)

    ends: dict[str, dict[str, list]] = {}
    if long:
        i_end = kinds.index("end")
        for n, r in enumerate(body, start=2):
            label = r[i_end].strip() if i_end < len(r) else ""
            if label not in ENDS:
                raise InputError(where, label, f"an end of {', '.join(ENDS)} on line {n}")
            d = ends.setdefault(label, {})
            for group, (i, _, _) in columns["*"].items():
                d.setdefault(group, []).append(number(r, i, n))
        spec = {e: columns["*"] for e in ends}
    else:
        spec = columns
        for e, slot in columns.items():
            d = ends.setdefault(e, {})
            for group, (i, _, _) in slot.items():
                d[group] = [number(r, i, n) for n, r in enumerate(body, start=2)]
    if not ends:
        raise InputError(where, source, "points of at least one end (head or crank)")

    out = {}
    for e in ENDS:
        if e not in ends:
            continue
        slot, d = spec[e], ends[e]
        if "p" not in slot:
            raise InputError(where, e, "a pressure column for every end")
        if "x_pos" in slot:
            xi = "x_pos"
        elif "V" in slot:
            xi = "V"
        else:
            raise InputError(where, e, "a piston position or volume column for every end")
        p = np.asarray(d["p"], dtype=float)
        x = np.asarray(d[xi], dtype=float)
        ang = np.asarray(d["angle"], dtype=float) if "angle" in d else None
        keep = np.isfinite(p) & np.isfinite(x)
        if (np.isfinite(p) != np.isfinite(x)).any():
            raise InputError(where, e, "a position (or volume) and a pressure on every line "
                             "of an end's points")
        p, x = p[keep], x[keep]
        ang = None if ang is None else ang[keep]
        if p.size < MIN_POINTS:
            raise InputError(where, e, f"at least {MIN_POINTS} points round the {e} end's "
                             f"loop (it has {p.size})")
        _, unit, kind = slot[xi]
        _, punit, _ = slot["p"]
        p_si = _to_si(p, "p", punit, barometer_Pa)
        if (p_si <= 0.0).any():
            raise InputError(where, e, "pressures above zero absolute (a gauge reading "
                             "below minus one barometer?)")
        if (p_si >= units.CRITICAL_PRESSURE_Pa).any():
            raise InputError(where, e, "pressures below the critical pressure of water, "
                             f"22.064 MPa, the steam tables' range (the highest is "
                             f"{p_si.max():.4g} Pa: a unit mistaken?)")
        abscissa = {"piston_frac": "piston_frac", "piston_m": "piston_m", "V": "V_m3"}[kind]
        x_si = _to_si(x, kind, unit, barometer_Pa)
        if not np.isfinite(x_si).all() or np.ptp(x_si) <= 0.0:
            raise InputError(where, e, "points spread along the stroke")
        slack = limits.CARD_FRACTION_SLACK
        if abscissa == "piston_frac" and not (-slack <= x_si.min() and x_si.max() <= 1 + slack):
            raise InputError(where, e, f"piston fractions of the stroke from 0 to 1 (within "
                             f"{slack:g}; they run from {x_si.min():.4g} to {x_si.max():.4g})")
        loops = count_loops(x_si)
        if loops > 1:
            raise InputError(where, e, f"one loop round the {e} end's card: its points go "
                             f"round {loops} times (several cycles digitised?); give one "
                             "cycle per end")
        if ang is not None:
            _, aunit, _ = slot["angle"]
            ang = _to_si(ang, "angle", aunit, barometer_Pa)
        out[e] = EndCard(abscissa, x_si, p_si, ang)
    return MeasuredCard(out, source, described, barometer_Pa)


def read_card(path, *, barometer_Pa: float = units.STANDARD_ATMOSPHERE_Pa) -> MeasuredCard:
    """Read a card CSV (its layouts in the module docstring).

    Parameters
    ----------
    path : str or Path
        The card file.
    barometer_Pa : float, optional
        Atmospheric pressure [Pa] that gauge pressures are read against (the scene's).

    Returns
    -------
    MeasuredCard
        The card, as :func:`parse_card` reads the file's text.

    Raises
    ------
    InputError
        If the file cannot be read or is not a card (naming the column or line).
    """
    text = read_text(path, "card", "a card CSV file", max_bytes=limits.MAX_CARD_BYTES)
    return parse_card(text, barometer_Pa=barometer_Pa, source=str(path))
