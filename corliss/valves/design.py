"""Valve design: from the events wanted to the valve, or to the gear's setting.

The forward problem (:mod:`corliss.valves.events`) takes a valve and finds its events;
this module runs it backwards.

**Plain slide valve.**  With infinite rods the Zeuner relations give the valve in
closed form (Spangler, *Valve-Gears*, Arts. 19-22, pp. 20-25).  With the crank at
``w`` from the dead point of the end considered, the valve's displacement is
``x = r sin(w + delta)`` (Art. 13, eq. 4) and that end's steam port is open past the
lap ``l`` while ``x > l``, so

* cut-off at ``w_c``:   ``l = r sin(w_c + delta)``, with ``w_c + delta`` in (90, 180) deg
  (the valve moving back, Art. 19, Problem 1);
* lead:                 ``i = r sin(delta) - l`` (Art. 14);
* greatest opening:     ``p = r - l`` (Art. 19; no overtravel counted).

Any two of lead, greatest opening, eccentricity, lap and angular advance with the
cut-off fix the valve (Problem 1, Art. 19: r and delta; Problem 2, Art. 20: lap and
lead; Problem 4, Art. 22: lead and opening).  With ``r = 1`` every length is a
function of ``delta`` alone, so two lengths fix ``delta`` by their ratio (a root in
one variable) and then ``r``: :func:`zeuner_valve`.

With a finite connecting rod the crank angles of equal piston positions on the two
strokes are not 180 deg apart, and with a finite eccentric rod the valve's motion is
not harmonic (Spangler Arts. 31, 34; Marks Art. 96).  The valve is then solved on the
exact forward model, the :class:`~corliss.valves.slide_valve.SlideValve` whose travel
``corliss events`` reads, per end: each event's crank angle is found from the piston
fraction asked by inverting the caller's ``piston_fraction`` (the crank train is not
this layer's), each lap is the valve's displacement at its own end's cut-off (so the
port closes there exactly), each exhaust lap the displacement at its release or
compression, and the two unknowns left, ``r`` and ``delta``, are found by a Newton
(Powell hybrid) solve of the two remaining conditions from the Zeuner answer.  Equal
cut-offs need unequal laps, which make the leads unequal (Art. 31); equal laps give
equal leads and unequal cut-offs (Art. 32), the cut-off asked then held at the
reference end.

The greatest displacement with a finite eccentric rod ``g``: the valve is
``x = r sin(phi) + sigma (K - sqrt(g^2 - r^2 cos^2 phi))`` (``phi = theta + delta``,
``K`` a constant), so ``dx/dphi = r cos(phi) (1 - sigma r sin(phi) / sqrt(g^2 -
r^2 cos^2 phi))``; the bracket vanishes only if ``r = g``, so the extremes stay at
``phi`` = 90 and 270 deg, where the harmonic ones are (derived here).

**Gears with a setting** (link and radial gears, shaft governors, the Corliss cam):
:func:`design_setting` finds the setting that gives the cut-off asked by a root solve
on the forward events over the gear's range.

Every design that cannot exist is an :class:`~corliss.errors.InputError` naming the
event asked, its value, and what range would be valid.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from corliss.errors import InputError
from corliss.keys import units
from corliss.valves.events import events as valve_events
from corliss.valves.gear import ValveGear
from corliss.valves.slide_valve import SlideValve, SlideValveSpec

TWO_PI = 2.0 * math.pi
#: The design is checked on the forward events to this [deg] (the asked tolerance is
#: 0.05 deg; the solve reaches 1e-9 deg, the events' bisection 1e-13 rad).
CHECK_DEG = 1e-6
KNOWN = ("lead", "max_opening", "eccentricity", "lap", "angular_advance", "lead_angle")
ANGLES = ("angular_advance", "lead_angle")
ENDS = ("head", "crank")


def _len(v: float, unit: str) -> str:
    """A length [m] for a message, in ``unit`` (the scene's: "in" or "mm")."""
    return f"{units.to_unit(v, unit):.4g} {unit}"


def _len_text(key: str, v: float, unit: str) -> str:
    return f"{math.degrees(v):.4g} deg" if key in ANGLES else _len(v, unit)


# ---------------------------------------------------------------- piston <-> crank
def crank_angle(piston_fraction: Callable[[float], float], frac: float, end: str,
                stroke: str) -> float:
    """The crank angle [rad] at which the piston is ``frac`` of the stroke from ``end``'s
    dead centre.

    Parameters
    ----------
    piston_fraction : callable
        Crank angle [rad] -> piston position from head-end dead centre, fraction of the
        stroke [-] (rising on 0..pi, falling on pi..2 pi).
    frac : float
        In [0, 1], of that end's stroke from its own dead centre, as
        :func:`corliss.valves.events.end_events` reports fractions [-].
    end : str
        ``"head"`` or ``"crank"``.
    stroke : str
        ``"out"``: the stroke away from that end (cut-off, release); ``"return"``: the
        stroke back towards it (compression).

    Returns
    -------
    float
        Crank angle [rad] from head-end dead centre, in [0, pi] on the head end's out
        stroke and [pi, 2 pi] on the other; found by Brent's method to 1e-15 rad.
    """
    from scipy.optimize import brentq

    head_out = (end == "head") == (stroke == "out")
    lo, hi = (0.0, math.pi) if head_out else (math.pi, TWO_PI)
    f = frac if end == "head" else 1.0 - frac
    if f <= 0.0:
        return lo if (end == "head") == (stroke == "out") else hi
    if f >= 1.0:
        return hi if head_out else lo
    return float(brentq(lambda t: piston_fraction(t) - f, lo, hi, xtol=1e-15, rtol=1e-15))


# ---------------------------------------------------------------- Zeuner, closed form
def _unit_quantities(delta: np.ndarray, w_c: float) -> dict:
    """Lengths of a valve of unit throw and the angle, as functions of delta, with the
    cut-off at ``w_c`` from the dead point (Arts. 14, 19): ``s = l / r``."""
    s = np.sin(w_c + delta)
    return {"lead": np.sin(delta) - s, "max_opening": 1.0 - s, "eccentricity": np.ones_like(s),
            "lap": s}


def zeuner_valve(cutoff_rad: float, **known: float) -> tuple[float, float, float] | None:
    """The plain valve of the Zeuner diagram (infinite rods) that cuts off where asked,
    given two more of its quantities.

    Spangler Arts. 19-22: ``l = r sin(w_c + delta)``, ``i = r sin(delta) - l``,
    ``p = r - l``.  Only valves with ``w_c + delta`` in (90, 180) deg (the port
    closes as the valve moves back, with a lap >= 0) and ``delta`` in (-90, 90) deg
    count.

    Parameters
    ----------
    cutoff_rad : float
        Crank angle of cut-off w_c from the end's own dead point [rad].
    **known : float
        Exactly two of ``lead``, ``max_opening``, ``eccentricity``, ``lap`` [m],
        ``angular_advance`` and ``lead_angle`` (the crank before the dead point at
        admission, Art. 21) [rad]; not both angles.

    Returns
    -------
    tuple of float or None
        ``(r, delta, lap)``: throw [m], angular advance [rad] and lap [m]; None when
        no such valve exists; of several, the one of least throw.

    Raises
    ------
    ValueError
        If ``known`` is not two of the names above.
    """
    names = sorted(known)
    if len(names) != 2 or not set(names) <= set(KNOWN):
        raise ValueError(f"two of {KNOWN}, not {names}")
    lo = max(0.5 * math.pi - cutoff_rad, -0.5 * math.pi) + 1e-12
    hi = min(math.pi - cutoff_rad, 0.5 * math.pi) - 1e-12
    if not lo < hi:
        return None
    if "lead_angle" in names:
        # Art. 21 (Problem 3): admission at asin(l/r) - delta, the angle of lead before
        # the dead point lam = delta - asin(l/r); with asin(l/r) = 180 deg - w_c - delta
        # the valve circle's diameter bisects the admission and cut-off lines:
        d = 0.5 * (math.pi - cutoff_rad + known["lead_angle"])
        if "angular_advance" in names:
            return None
        known = {"angular_advance": d, **{k: v for k, v in known.items() if k != "lead_angle"}}
        names = sorted(known)
    if "angular_advance" in names:
        d = known["angular_advance"]
        other = names[0] if names[1] == "angular_advance" else names[1]
        if not lo - 1e-12 <= d <= hi + 1e-12:
            return None
        q = float(_unit_quantities(np.array(d), cutoff_rad)[other])
        if q == 0.0:
            return None
        r = known[other] / q
        if not (r > 0.0 and math.isfinite(r)):
            return None
        return r, d, r * math.sin(cutoff_rad + d)
    from scipy.optimize import brentq
    a, b = names
    va, vb = known[a], known[b]

    def g(d):
        q = _unit_quantities(np.asarray(d), cutoff_rad)
        return q[a] * vb - q[b] * va

    grid = np.linspace(lo, hi, 4001)
    gv = g(grid)
    found = []
    for k in np.nonzero(np.sign(gv[:-1]) * np.sign(gv[1:]) <= 0.0)[0]:
        if gv[k] == 0.0 and k > 0 and gv[k - 1] == 0.0:
            continue
        d = grid[k] if gv[k] == 0.0 else float(brentq(g, grid[k], grid[k + 1], xtol=1e-15))
        qd = _unit_quantities(np.array(d), cutoff_rad)
        qa = float(qd[a])
        r = va / qa if abs(qa) > 1e-12 else vb / float(qd[b])
        if r > 0.0 and math.isfinite(r):
            found.append((r, float(d), r * math.sin(cutoff_rad + d)))
    return min(found) if found else None


# ---------------------------------------------------------------- slide valve
@dataclass(frozen=True)
class SlideValveDesign:
    """A plain slide valve designed for the events asked (all SI), as
    :func:`design_slide_valve` returns it.

    Parameters
    ----------
    spec : SlideValveSpec
        The valve, ready to build (:class:`~corliss.valves.slide_valve.SlideValve`).
    eccentricity_m, angular_advance_rad : float
        Throw [m] and angular advance [rad].
    lap_m, exhaust_lap_m : (float, float)
        Steam and exhaust laps of the (head, crank) end [m].
    lead_m, max_opening_m : (float, float)
        Lead and greatest signed port opening, r - l with a finite eccentric rod's
        correction (overtravel included), of each end [m].
    zeuner : dict
        The infinite-rod design the solve started from: ``eccentricity_m``,
        ``angular_advance_rad``, ``lap_m`` (of the reference end).
    asked_deg : dict
        ``{end: {"cutoff_deg": ..., "release_deg": ...}}``: the crank angles [deg] of
        the events that were asked, each end.
    asked : dict
        The design's inputs as given (SI; fractions of the stroke).
    events : dict
        The designed valve's events by :func:`corliss.valves.events.events`, each end.
    equalise : str
        ``"cutoff"`` (laps per end) or ``"laps"`` (equal laps).
    reference_end : str
        The end at which the lead and opening (or throw, lap, advance) asked hold.
    """

    spec: SlideValveSpec
    eccentricity_m: float
    angular_advance_rad: float
    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    lead_m: tuple[float, float]
    max_opening_m: tuple[float, float]
    zeuner: dict
    asked_deg: dict
    asked: dict
    events: dict
    equalise: str
    reference_end: str


def _pair(key: str, value) -> tuple:
    if value is None:
        return (None, None)
    if isinstance(value, (tuple, list)):
        if len(value) != 2:
            raise InputError(key, value, "one value, or a pair (head, crank)")
        return tuple(value)
    return (value, value)


def _fraction(key: str, v) -> float:
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise InputError(key, v, "a fraction of the stroke between 0 and 1") from None
    if not 0.0 < f < 1.0:
        raise InputError(key, v, "a fraction of the stroke between 0 and 1 (exclusive)")
    return f


def _check_inputs(base: SlideValveSpec, cutoff, cutoff_crank, known: dict, release,
                  compression, exhaust_lap, equalise, reference_end, overtravel_m=None,
                  unit: str = "in"):
    if equalise not in ("cutoff", "laps"):
        raise InputError("equalise", equalise, "\"cutoff\" (laps per end, Spangler Art. 31) "
                         "or \"laps\" (equal laps, unequal cut-offs, Art. 32)")
    if reference_end not in ENDS:
        raise InputError("reference_end", reference_end, "\"head\" or \"crank\"")
    ch = _fraction("cutoff", cutoff)
    cc = ch if cutoff_crank is None else _fraction("cutoff_crank", cutoff_crank)
    if cutoff_crank is not None and equalise == "laps":
        raise InputError("cutoff_crank", cutoff_crank, "no crank-end cut-off with equal laps "
                         "(equalise = \"laps\"): the crank end's cut-off then follows from the "
                         "valve (Spangler Art. 32); ask equalise = \"cutoff\" for laps per end")
    given = {k: v for k, v in known.items() if v is not None}
    if len(given) != 2:
        what = ("exactly two of lead, max_opening (or overtravel), eccentricity, lap, "
                "angular_advance and lead_angle with the cut-off (Spangler Arts. 19-22: e.g. "
                "lead and max_opening, Art. 22)")
        if not given:
            raise InputError("lead", "none given", what)
        raise InputError(", ".join(given),
                         ", ".join(_len_text(k, v, unit) for k, v in given.items()), what)
    for k, v in given.items():
        if not math.isfinite(v):
            raise InputError(k, v, "a finite number")
    if "max_opening" in given:
        p = given["max_opening"]
        if not p > 0.0:
            raise InputError("max_opening", _len(p, unit), "a port opening above zero")
        if p > base.port_width_m * (1 + 1e-12) and overtravel_m is None:
            raise InputError("max_opening", _len(p, unit), f"an opening no wider than the "
                             f"port ({_len(base.port_width_m, unit)}): the valve cannot open "
                             "the port further than its width (travel beyond it is "
                             "overtravel: give the overtravel instead, or a wider port)")
        if "lead" in given and given["lead"] >= p:
            raise InputError("lead", _len(given["lead"], unit), f"a lead less than the "
                             f"greatest opening ({_len(p, unit)}): the port opens further after "
                             "the dead point")
    if "eccentricity" in given and not given["eccentricity"] > 0.0:
        raise InputError("eccentricity", _len(given["eccentricity"], unit), "a throw above zero")
    if "lap" in given and given["lap"] < 0.0:
        raise InputError("lap", _len(given["lap"], unit), "a steam lap of zero or more")
    if "lead_angle" in given and "angular_advance" in given:
        raise InputError("lead_angle", _len_text("lead_angle", given["lead_angle"], unit),
                         "no angle of lead with the angular advance: with the cut-off either "
                         "fixes the other (Spangler Art. 21); give a length instead")
    if "lead_angle" in given and not abs(given["lead_angle"]) < 0.5 * math.pi:
        raise InputError("lead_angle", _len_text("lead_angle", given["lead_angle"], unit),
                         "an angle between -90 and 90 deg")
    if "angular_advance" in given and not abs(given["angular_advance"]) < 0.5 * math.pi:
        raise InputError("angular_advance", f"{math.degrees(given['angular_advance']):.4g} deg",
                         "an angle between -90 and 90 deg")
    rel, comp, el = _pair("release", release), _pair("compression", compression), \
        _pair("exhaust_lap", exhaust_lap)
    exhaust = []
    for k, end in enumerate(ENDS):
        kinds = [(n, v) for n, v in (("release", rel[k]), ("compression", comp[k]),
                                     ("exhaust_lap", el[k])) if v is not None]
        if len(kinds) > 1:
            raise InputError(kinds[1][0], kinds[1][1], f"one exhaust condition for the {end} "
                             f"end: {kinds[0][0]} is already given (one exhaust lap per end "
                             "sets one exhaust event, Spangler Art. 31)")
        if kinds and kinds[0][0] != "exhaust_lap":
            kinds = [(kinds[0][0], _fraction(kinds[0][0], kinds[0][1]))]
        exhaust.append(kinds[0] if kinds else ("exhaust_lap", 0.0))
    if equalise == "laps" and exhaust[0] != exhaust[1]:
        raise InputError("exhaust", exhaust, "the same exhaust condition for both ends with "
                         "equal laps (equalise = \"laps\")")
    return ch, cc, given, exhaust


class _NoValve(Exception):
    """No plain valve meets the conditions at the reference end (why, in words)."""


def _travel(base: SlideValveSpec, r: float, d: float, theta) -> np.ndarray:
    """Displacement [m] of the valve ``base`` with throw ``r`` and advance ``d``."""
    spec = dataclasses.replace(base, eccentricity_m=r, angular_advance_rad=d,
                               lap_m=(0.0, 0.0), exhaust_lap_m=(0.0, 0.0))
    return SlideValve(spec).travel(np.asarray(theta, dtype=float))


def _rate(base, r, d, end: int, theta: float) -> float:
    """Rate of an end's own displacement (positive opens its steam port) [m/rad]."""
    h = 1e-6
    x = _travel(base, r, d, np.array([theta - h, theta + h]))
    return (1.0 if end == 0 else -1.0) * float(x[1] - x[0]) / (2 * h)


def _solve_valve(base, piston_fraction, given: dict, th_cut, ref: int, equalise: str,
                 both: bool = False, unit: str = "in"):
    """Throw, advance and laps meeting the cut-offs at ``th_cut`` [rad] and the two
    quantities ``given`` at the reference end on the exact valve: the Zeuner valve
    (Arts. 19-22) as the start, then Powell's hybrid Newton method on (r, delta).

    With ``both`` (one cut-off asked of both ends, laps per end) the other end's lap
    must be one too.  ``unit`` ("in" or "mm") is the messages' length unit.

    Returns (r, delta, lap_head, lap_crank, zeuner (r, delta, lap)); raises _NoValve."""
    from scipy.optimize import root

    dead = (0.0, math.pi)
    z = zeuner_valve(th_cut[ref] - dead[ref], **given)
    if z is None:
        raise _NoValve("not even with infinite rods")
    r0, d0, _ = z
    sign = (1.0, -1.0)
    names = list(given)
    scale = [r0 if n not in ("angular_advance", "lead_angle") else 1.0 for n in names]
    g = base.eccentric_rod_m

    def laps(b, r, d):
        x = _travel(b, r, d, np.array(th_cut))
        lh, lc = float(x[0]), float(-x[1])
        if equalise == "laps":
            lh = lc = (lh, lc)[ref]
        return lh, lc

    def residual(v, b):
        r, d = r0 * v[0], v[1]
        if not (r > 0.0 and (b.eccentric_rod_m is None or r < b.eccentric_rod_m)):
            return [1e3, 1e3]
        lap = laps(b, r, d)[ref]
        lam = given.get("lead_angle", 0.0)
        x = sign[ref] * _travel(b, r, d, np.array([dead[ref], 0.5 * math.pi - d + dead[ref],
                                                   dead[ref] - lam]))
        q = {"lead": float(x[0]) - lap, "max_opening": float(x[1]) - lap,
             "eccentricity": r, "lap": lap, "angular_advance": d,
             # the port opens at the angle of lead before the dead point (Art. 21)
             "lead_angle": lam + (float(x[2]) - lap) / r0}
        return [(q[n] - given[n]) / s for n, s in zip(names, scale)]

    def attempt(b, start):
        sol = root(residual, start, args=(b,), method="hybr", options={"xtol": 1e-14})
        return sol.x, max(abs(v) for v in residual(sol.x, b)) <= 1e-10

    # (a continuation in 1/g from the Zeuner valve was tried on 1728 designs across rods,
    # connections and events: it rescued none that this start refuses; where it fails, no
    # valve with the asked lead reaches the asked opening on so short a rod)

    v, ok = attempt(base, [1.0, d0])
    r, d = r0 * float(v[0]), float(v[1])
    if not ok:
        rod = "infinite eccentric rods" if g is None else f"an eccentric rod of {_len(g, unit)}"
        raise _NoValve(f"the infinite-rod valve (throw {_len(r0, unit)}, advance "
                       f"{math.degrees(d0):.3f} deg) has no counterpart with {rod}")
    lh, lc = laps(base, r, d)
    if not abs(d) < 0.5 * math.pi:
        raise _NoValve(f"the advance would be {math.degrees(d):.1f} deg")
    lap = (lh, lc)[ref]
    if lap < 0.0:
        raise _NoValve(f"a negative steam lap ({_len(lap, unit)}) would be needed")
    if _rate(base, r, d, ref, th_cut[ref]) >= 0.0:
        raise _NoValve("the port would close while the valve still moves out")
    if both and equalise == "cutoff":
        k = 1 - ref
        if (lh, lc)[k] < 0.0:
            raise _NoValve(f"the {ENDS[k]} end would need a negative steam lap "
                           f"({_len((lh, lc)[k], unit)})")
        if _rate(base, r, d, k, th_cut[k]) >= 0.0:
            raise _NoValve(f"the {ENDS[k]} end's port would close while the valve still "
                           "moves out")
    return r, d, lh, lc, z


def _cutoff_range(base, piston_fraction, given, th_cut, ref, equalise, both):
    """The cut-off fractions [-] of the reference end (of both ends, with ``both``)
    from which to which a plain valve exists with the two quantities asked and the
    rods (scanned every 0.005 of the stroke); None if at none."""
    ok = []
    for f in np.arange(0.005, 0.9999, 0.005):
        th = list(th_cut)
        for k in ((0, 1) if both else (ref,)):
            th[k] = crank_angle(piston_fraction, float(f), ENDS[k], "out")
        try:
            _solve_valve(base, piston_fraction, given, th, ref, equalise, both)
        except _NoValve:
            continue
        ok.append(float(f))
    return (min(ok), max(ok)) if ok else None



def design_slide_valve(base: SlideValveSpec, piston_fraction: Callable[[float], float], *,
                       cutoff: float, cutoff_crank: float | None = None,
                       lead_m: float | None = None, max_opening_m: float | None = None,
                       eccentricity_m: float | None = None, lap_m: float | None = None,
                       angular_advance_rad: float | None = None,
                       lead_angle_rad: float | None = None, overtravel_m: float | None = None,
                       release=None, compression=None, exhaust_lap_m=None,
                       equalise: str = "cutoff", reference_end: str = "head",
                       length_unit: str = "in") -> SlideValveDesign:
    """Design a plain slide valve for the events asked.

    Parameters
    ----------
    base : SlideValveSpec
        Supplies what is not designed: port width and length, eccentric rod (None:
        infinite), connection, steam side, setting, discharge coefficient.
    piston_fraction : callable
        Crank angle [rad] -> piston position from head-end dead centre [-] (the
        engine's slide crank, or ``(1 - cos) / 2`` for an infinite rod).
    cutoff : float
        Cut-off, fraction of the stroke [-] (of both ends with ``equalise="cutoff"``
        unless ``cutoff_crank`` is given; of the reference end with ``"laps"``).
    cutoff_crank : float, optional
        Crank-end cut-off [-] when it differs from the head end's.
    lead_m, max_opening_m, eccentricity_m, lap_m : float, optional
        Lead, greatest port opening (no more than the port width), eccentric throw,
        steam lap of the reference end [m].
    angular_advance_rad, lead_angle_rad : float, optional
        Angular advance, and the angle of lead (the crank before the dead point when
        the port opens, Art. 21) [rad].  Exactly two of these six are given (Spangler
        Arts. 19-22), not both angles.
    overtravel_m : float, optional
        Instead of ``max_opening_m``: how far the valve travels past the far edge of
        the port, so that the greatest signed opening is the port width plus this
        (Art. 18; Art. 21 gives "width of port, and the overtravel") [m].
    release, compression : float or (float, float), optional
        Piston position at release, or at compression, as fraction of the end's stroke
        from its own dead centre as ``corliss events`` reports it (a compression of 0.1
        closes the exhaust at 0.9 of the return stroke) [-]; a pair for (head, crank).
    exhaust_lap_m : float or (float, float), optional
        Exhaust lap instead [m]; with none of the three, zero exhaust lap.
    equalise : str
        ``"cutoff"``: laps per end, so each end cuts off where asked (Art. 31);
        ``"laps"``: equal laps (and leads), the cut-off asked at ``reference_end``,
        the other end's following (Art. 32).
    reference_end : str
        ``"head"`` or ``"crank"``: where the lead and opening (or throw, lap) asked hold.
    length_unit : str
        The unit the messages quote lengths in: ``"in"`` or ``"mm"`` (the scene's
        unit system's).

    Returns
    -------
    SlideValveDesign
        The valve, checked on the forward events to :data:`CHECK_DEG`, with what was
        asked and its events.

    Raises
    ------
    InputError
        Naming the event asked that no plain valve can give, and the valid range.
    """
    unit = length_unit
    if unit not in ("in", "mm"):
        raise InputError("length_unit", unit, "\"in\" or \"mm\"")
    known = {"lead": lead_m, "max_opening": max_opening_m, "eccentricity": eccentricity_m,
             "lap": lap_m, "angular_advance": angular_advance_rad,
             "lead_angle": lead_angle_rad}
    if overtravel_m is not None:
        if max_opening_m is not None:
            raise InputError("overtravel", _len(overtravel_m, unit), "either the greatest "
                             "opening or the overtravel, not both (the opening is the port "
                             "width plus the overtravel, Spangler Art. 18)")
        if not overtravel_m >= 0.0:
            raise InputError("overtravel", _len(overtravel_m, unit),
                             "an overtravel of zero or more")
        known["max_opening"] = base.port_width_m + overtravel_m
    ch, cc, given, exhaust = _check_inputs(base, cutoff, cutoff_crank, known, release,
                                           compression, exhaust_lap_m, equalise, reference_end,
                                           overtravel_m, unit)
    ref = 0 if reference_end == "head" else 1
    cut = (ch, cc)
    th_cut = tuple(crank_angle(piston_fraction, cut[k], ENDS[k], "out") for k in (0, 1))
    dead = (0.0, math.pi)
    ref_key = "cutoff" if ref == 0 or cutoff_crank is None else "cutoff_crank"
    try:
        r, d, lh, lc, z = _solve_valve(base, piston_fraction, given, th_cut, ref, equalise,
                                       both=cutoff_crank is None, unit=unit)
    except _NoValve as exc:
        asked = ", ".join(f"{k} {_len_text(k, v, unit)}" for k, v in given.items())
        span = _cutoff_range(base, piston_fraction, given, th_cut, ref, equalise,
                             cutoff_crank is None)
        raise InputError(ref_key, cut[ref], (
            f"a cut-off from {span[0]:.3f} to {span[1]:.3f} of the stroke, the range over "
            f"which a plain slide valve exists with {asked} and these rods (Spangler "
            f"Arts. 19-22, 31; earlier needs a lap beyond any eccentric, later a negative "
            f"lap): {exc}") if span else
            f"other data: no plain slide valve cuts off anywhere with {asked} ({exc})") from None
    r0, d0, l0 = z
    sign = (1.0, -1.0)

    def travel(r, d, theta):
        return _travel(base, r, d, theta)

    def dx(end, theta):
        return _rate(base, r, d, end, theta)

    # the other end's lap, with laps per end: a lap, closing as the valve moves back
    if equalise == "cutoff":
        k = 1 - ref
        key = "cutoff" if k == 0 or cutoff_crank is None else "cutoff_crank"
        lap = (lh, lc)[k]
        if lap < 0.0 or dx(k, th_cut[k]) >= 0.0:
            raise InputError(key, cut[k], f"an earlier cut-off at the {ENDS[k]} end: with "
                             f"throw {_len(r, unit)} and advance {math.degrees(d):.3f} deg "
                             f"(set by the {ENDS[ref]} end) it would need a negative steam lap "
                             f"({_len(lap, unit)})" if lap < 0.0 else
                             f"a cut-off at the {ENDS[k]} end before the valve's extreme travel "
                             "is passed: the port closes only as the valve moves back")

    # exhaust laps: each the displacement at its event
    elaps = []
    asked_deg = {"head": {"cutoff_deg": math.degrees(th_cut[0])},
                 "crank": {"cutoff_deg": math.degrees(th_cut[1])}}
    if equalise == "laps":
        asked_deg[ENDS[1 - ref]].pop("cutoff_deg")
    if "lead_angle" in given:
        asked_deg[ENDS[ref]]["admission_deg"] = math.degrees(dead[ref] - given["lead_angle"]) % 360.0
    for k, end in enumerate(ENDS):
        kind, v = exhaust[k]
        if kind == "exhaust_lap":
            elaps.append(float(v))
            continue
        if equalise == "laps" and k != ref:
            elaps.append(math.nan)      # the reference end's, below
            continue
        th = crank_angle(piston_fraction, v, end, "out" if kind == "release" else "return")
        x = sign[k] * float(travel(r, d, np.array([th]))[0])
        rate = dx(k, th)
        if kind == "release" and not (rate < 0.0 and th > th_cut[k]):
            raise InputError("release", v, f"a release at the {end} end later in the stroke "
                             f"than its cut-off ({cut[k]:.4g})")
        if kind == "compression" and not rate > 0.0:
            raise InputError("compression", v, f"a compression at the {end} end after the "
                             "valve has turned back towards steam (at crank "
                             f"{math.degrees(1.5 * math.pi - d + dead[k]) % 360:.1f} deg from "
                             "head-end dead centre): a smaller fraction, later in the return "
                             "stroke")
        elaps.append(-x)
        asked_deg[end][f"{kind}_deg"] = math.degrees(th) % 360.0
    if equalise == "laps":
        elaps = [elaps[ref], elaps[ref]]
        asked_deg[ENDS[1 - ref]] = {}
    for k, end in enumerate(ENDS):
        if elaps[k] + (lh, lc)[k] < 0.0:
            kind = exhaust[k][0]
            raise InputError(kind, exhaust[k][1], f"an exhaust event at the {end} end that "
                             "leaves the port closed to exhaust while it takes steam: lap + "
                             f"exhaust lap = {_len(elaps[k] + (lh, lc)[k], unit)} < 0 would blow "
                             "steam through (release after the cut-off, compression before "
                             "admission)")
        if elaps[k] >= r:
            raise InputError(exhaust[k][0], exhaust[k][1], f"an exhaust lap below the throw "
                             f"{_len(r, unit)}: the {end}-end exhaust would never open")

    spec = dataclasses.replace(base, eccentricity_m=r, angular_advance_rad=d, lap_m=(lh, lc),
                               exhaust_lap_m=(elaps[0], elaps[1]))
    gear = SlideValve(spec)
    ev = valve_events(gear, piston_fraction)
    for end, want in asked_deg.items():
        for key, deg in want.items():
            got = ev[end][key]
            if got is None or abs((got - deg + 180.0) % 360.0 - 180.0) > CHECK_DEG:
                raise RuntimeError(f"design check failed: {end} {key} asked {deg:.6f} deg, "
                                   f"the valve gives {got}")
    xt = gear.travel(np.array([0.5 * math.pi - d, 1.5 * math.pi - d]))
    return SlideValveDesign(
        spec=spec, eccentricity_m=r, angular_advance_rad=d, lap_m=(lh, lc),
        exhaust_lap_m=(elaps[0], elaps[1]),
        lead_m=(ev["head"]["lead_m"], ev["crank"]["lead_m"]),
        max_opening_m=(float(xt[0]) - lh, float(-xt[1]) - lc),
        zeuner={"eccentricity_m": r0, "angular_advance_rad": d0, "lap_m": l0},
        asked_deg=asked_deg,
        asked={"cutoff": cut, "equalise": equalise, "reference_end": reference_end,
               **{k: given[k] for k in given},
               "exhaust": {ENDS[k]: exhaust[k] for k in (0, 1)}},
        events=ev, equalise=equalise, reference_end=reference_end)


# ---------------------------------------------------------------- gears with a setting
@dataclass(frozen=True)
class SettingDesign:
    """The setting of a gear that gives the cut-off asked, as :func:`design_setting`
    returns it.

    Parameters
    ----------
    gear_name : str
        The gear's registry name.
    setting : float
        In the gear's own normalised form (see ``setting_name``) [-].
    setting_name : str
        What the setting moves, and its scale (the gear's ``setting_name``).
    end : str
        ``"head"``, ``"crank"`` or ``"mean"``: whose cut-off was asked.
    cutoff_frac : float
        The cut-off asked [-].
    asked_deg : dict
        ``{end: {"cutoff_deg": ...}}`` for the end(s) asked [deg] (the mean: none).
    events : dict
        The gear's events at the setting, each end, by
        :func:`corliss.valves.events.events`.
    gear : ValveGear
        The gear at the setting (not compared, not shown in the repr).
    """

    gear_name: str
    setting: float
    setting_name: str
    end: str
    cutoff_frac: float
    asked_deg: dict
    events: dict
    gear: ValveGear = dataclasses.field(compare=False, repr=False)


def _cutoff_of(gear, piston_fraction, end) -> float | None:
    ev = valve_events(gear, piston_fraction)
    if end == "mean":
        a, b = ev["head"]["cutoff_frac"], ev["crank"]["cutoff_frac"]
        return None if a is None or b is None else 0.5 * (a + b)
    return ev[end]["cutoff_frac"]


def design_setting(gear: ValveGear, piston_fraction: Callable[[float], float], cutoff: float,
                   end: str = "head", bounds: tuple[float, float] | None = None,
                   samples: int = 41) -> SettingDesign:
    """The setting (notch, block, governor or cam position) of ``gear`` that cuts off
    at ``cutoff`` of the stroke.

    The cut-off is found at ``samples`` settings across ``bounds`` (by default the
    gear's range, only its forward half for a reversing gear), bracketed where it
    passes the value asked, and the bracket closed by Brent's method on the forward
    events (:func:`corliss.valves.events.events`) to 1e-10 of the setting.

    Parameters
    ----------
    gear : ValveGear
        A gear with a ``setting_range``.
    piston_fraction : callable
        Crank angle [rad] -> piston fraction from head-end dead centre [-].
    cutoff : float
        Cut-off asked, fraction of the stroke [-].
    end : str
        ``"head"``, ``"crank"`` or ``"mean"`` (of the two ends' fractions).
    bounds : (float, float), optional
        Settings to search between, within the gear's ``setting_range``.
    samples : int, optional
        Number of settings at which the cut-off is first found, evenly spaced over
        ``bounds``; the first bracket of the value asked, from ``bounds[0]``, is
        closed.

    Returns
    -------
    SettingDesign
        The setting, the gear at it and its events.

    Raises
    ------
    InputError
        ``cutoff`` outside what the gear gives over its settings, with that range; a
        gear without a setting; ``end`` or ``bounds`` not valid.
    """
    from scipy.optimize import brentq

    if gear.setting_range is None or gear.setting_name is None:
        raise InputError("cutoff", cutoff, f"a gear with a setting: the {gear.name} gear has "
                         "none (a plain slide valve is designed by its laps and eccentric)")
    if end not in ("head", "crank", "mean"):
        raise InputError("end", end, "\"head\", \"crank\" or \"mean\"")
    f = _fraction("cutoff", cutoff)
    lo, hi = gear.setting_range
    if bounds is None:
        bounds = (0.0, hi) if lo < 0.0 < hi else (lo, hi)
    a, b = bounds
    if not lo <= a < b <= hi:
        raise InputError("bounds", bounds, f"settings within the gear's range [{lo}, {hi}]")
    grid = np.linspace(a, b, samples)
    cut = [_cutoff_of(gear.with_setting(float(s)), piston_fraction, end) for s in grid]
    def missed(v: float) -> float:
        c = _cutoff_of(gear.with_setting(v), piston_fraction, end)
        if c is None:
            raise RuntimeError(f"the {gear.name} gear admits no steam at setting {v:g}, "
                               "inside a bracket of the cut-off asked")
        return c - f

    best = None
    for k in range(samples - 1):
        c0, c1 = cut[k], cut[k + 1]
        if c0 is None or c1 is None:
            continue
        if (c0 - f) * (c1 - f) <= 0.0:
            s = float(brentq(missed, grid[k], grid[k + 1], xtol=1e-10))
            best = s
            break
    if best is None:
        have = [c for c in cut if c is not None]
        span = (f"a cut-off from {min(have):.3f} to {max(have):.3f} of the stroke, the range "
                f"the {gear.name} gear gives over its settings {a:g} to {b:g} "
                f"({gear.setting_name})") if have else \
            f"a gear that admits steam: the {gear.name} gear never does over {a:g} to {b:g}"
        raise InputError("cutoff", cutoff, span)
    at = gear.with_setting(best)
    ev = valve_events(at, piston_fraction)
    asked_deg = {}
    if end != "mean":
        th = crank_angle(piston_fraction, f, end, "out")
        asked_deg = {end: {"cutoff_deg": math.degrees(th)}}
    return SettingDesign(gear_name=gear.name, setting=best, setting_name=gear.setting_name,
                         end=end, cutoff_frac=f, asked_deg=asked_deg, events=ev, gear=at)
