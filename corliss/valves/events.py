"""Valve events of each cylinder end, found from the gear's port openings.

An event is a crank angle where a port edge is crossed: admission and cut-off where
the end's steam port opens and closes, release and compression where its exhaust
port opens and closes (Spangler Art. 17: admission, cut-off, release, compression).
Each is bracketed by a turn's samples of the gear's own signed opening, read off them
by interpolation and proved on the gear to 1e-13 rad (or solved there by regula falsi
where the samples do not give it), so it holds for any gear, any lap (negative
included) and any rod length; an event that never happens is ``None``.

Angles are crank angles from head-end dead centre in the direction of rotation, in
[0, 360) degrees.  Fractions are of that end's own stroke, from its own dead centre,
through a ``piston_fraction`` function the caller supplies (the valves layer does not
know the crank train).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from corliss.valves.crossing_kernels import inverse_quintic, sign_changes
from corliss.valves.gear import OPENINGS_OF_SIGNED, ValveGear

TWO_PI = 2.0 * math.pi
_SAMPLES = 7200


def _fixed(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


#: The samples' angles [rad], a turn and its end (the crossings' brackets), and a turn
#: without its end (the events' largest openings): made once, read by every gear.
_TURN_CLOSED = _fixed(np.linspace(0.0, TWO_PI, _SAMPLES + 1))
_TURN_OPEN = _fixed(np.linspace(0.0, TWO_PI, _SAMPLES, endpoint=False))
#: The head and crank ends' dead centres [rad], where the leads are read.
_DEAD_CENTRES = _fixed(np.array([0.0, math.pi]))


def crossing_table(gear: ValveGear, levels: np.ndarray) -> list[list[list[tuple[float, bool]]]]:
    """Where each port's signed opening crosses each of its levels, all found at once.

    Parameters
    ----------
    gear : ValveGear
        The gear, at its present setting.
    levels : ndarray, shape (4, L)
        Levels [m] to cross for each port.

    Returns
    -------
    list
        ``out[port][level]`` = sorted list of ``(angle [rad] in [0, 2 pi), rising)``;
        ``rising`` is True where the opening passes the level upwards.  Brackets come
        from 7200 samples a turn; each is read off the six samples around it and
        proved on the gear to 1e-13 rad, all at once in one evaluation of the gear
        (:func:`_crossings_of_samples`), those it does not prove solved by regula
        falsi, Illinois-modified (:func:`_solve_crossings`).
    """
    return sampled_crossings(gear, levels)[0]


def sampled_crossings(gear: ValveGear, levels: np.ndarray) -> tuple[list, np.ndarray]:
    """:func:`crossing_table`, and the signed openings over the turn's samples it was
    found from.

    Parameters
    ----------
    gear : ValveGear
        The gear, at its present setting.
    levels : ndarray, shape (4, L)
        Levels [m] to cross for each port.

    Returns
    -------
    table : list
        As :func:`crossing_table`.
    signed : ndarray
        ``gear.signed_openings`` [m] at the :data:`_SAMPLES` angles ``2 pi k /
        _SAMPLES`` a turn, shape ``(4, _SAMPLES)`` (the angles :func:`events` reads
        the largest openings at: :func:`events` takes them instead of finding them
        again).
    """
    levels = np.atleast_2d(np.asarray(levels, dtype=float))
    th = _TURN_CLOSED
    s = gear.signed_openings(th)
    # every port's samples against every one of its levels, in one compiled pass (above
    # the level: the difference's sign, found without the differences: ``a - b > 0`` is
    # ``a > b`` for every pair of floats, the difference of two unequal finite floats
    # never rounding to zero)
    # (float64 C arrays whatever the gear gives: one compiled version for every gear)
    s = np.ascontiguousarray(s, dtype=np.float64)
    ports, levs, idx, rising = sign_changes(s, np.ascontiguousarray(levels))
    out: list[list[list[tuple[float, bool]]]] = [[[] for _ in range(levels.shape[1])]
                                                 for _ in range(4)]
    if not ports.size:
        return out, s[:, :_SAMPLES]
    lev = levels[ports, levs]
    t = _crossings_of_samples(gear, s, ports, lev, idx, th) % TWO_PI
    for k, (port, li) in enumerate(zip(ports.tolist(), levs.tolist())):
        out[port][li].append((float(t[k]), bool(rising[k])))
    for row in out:
        for lst in row:
            lst.sort()
    return out, s[:, :_SAMPLES]


#: The crossings' bracket is closed to this width [rad].
CROSSING_TOL_RAD = 1e-13
#: The samples the crossing of a bracket ``[idx, idx + 1]`` is read from, in steps from
#: ``idx`` (:func:`_crossings_of_samples`).
CROSSING_NODES = (-2, -1, 0, 1, 2, 3)
_STEPS = np.array(CROSSING_NODES, dtype=np.int64)
#: Half the width of the bracket that proves a crossing found from the samples
#: (:func:`_crossings_of_samples`), as a fraction of :data:`CROSSING_TOL_RAD` [-].
CROSSING_PROOF_HALF = 0.4


def _crossings_of_samples(gear: ValveGear, s: np.ndarray, ports: np.ndarray,
                          lev: np.ndarray, idx: np.ndarray, th: np.ndarray) -> np.ndarray:
    """Each crossing read off the samples around its bracket and proved on the gear;
    :func:`_solve_crossings` for those it does not prove [rad].

    The crossing between the samples ``idx`` and ``idx + 1`` is read off the quintic
    through the six samples ``idx - 2 .. idx + 3`` (:data:`CROSSING_NODES`; a turn's
    samples wrap round), taken as the angle against the opening: inverse Lagrange
    interpolation, the angle where that polynomial puts the level, in closed form.  On
    a smooth opening its error is of the order of the sample step to the sixth power
    (far below the tolerance at 7200 samples a turn, where a cubic's, of the fourth
    power, missed it for half the bundled scenes' crossings), so one
    evaluation of the gear at ``c -+ d`` (``d`` = :data:`CROSSING_PROOF_HALF` x
    :data:`CROSSING_TOL_RAD`, each clipped to the bracket) proves it: the opening is
    on the bracket's left side of the level at ``c - d`` and on its right side at
    ``c + d``, a bracket narrower than the tolerance, as the regula falsi of
    :func:`_solve_crossings` would close it, and the crossing is its middle.  Where
    that fails (an opening resting at the level or turning among the six samples, a
    kink in them: the bundled scenes' Corliss trip gears and a few others, 1 % of
    their crossings) the crossing is solved by :func:`_solve_crossings` from its
    sample bracket, as before (each crossing's solution does not depend on the
    others solved beside it).  Every crossing found either way lies within
    :data:`CROSSING_TOL_RAD` of a change of side of the level.

    Parameters
    ----------
    gear : ValveGear
        The gear.
    s : ndarray
        Its signed openings [m] at ``th``, shape ``(4, N + 1)``, the last sample a
        turn after the first.
    ports, lev, idx : ndarray
        Each crossing's port, level [m] and sample bracket ``[th[idx], th[idx + 1]]``.
    th : ndarray
        The samples' angles [rad], uniform, shape ``(N + 1,)``.

    Returns
    -------
    ndarray
        The crossings [rad], each in its bracket.
    """
    n = th.size - 1
    h = th[1] - th[0]
    a, b = th[idx], th[idx + 1]
    # the bracket's two samples less the level
    f0 = s[ports, idx] - lev
    f1 = s[ports, (idx + 1) % n] - lev
    left_above = f0 > 0.0
    half = CROSSING_PROOF_HALF * CROSSING_TOL_RAD
    # Lagrange in the opening: u(0) = sum_i u_i prod_{j != i} (0 - f_j) / (f_i - f_j),
    # compiled (:func:`~corliss.valves.crossing_kernels.inverse_quintic`)
    c = inverse_quintic(s, ports, lev, idx, _STEPS, a, h)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        proved, c = _prove(gear, ports, lev, c, a, b, left_above, half)
    if not proved.all():
        rest = np.flatnonzero(~proved)
        c[rest] = _solve_crossings(gear, ports[rest], lev[rest], a[rest], b[rest],
                                   f0[rest], f1[rest])
    return c


def _prove(gear, ports, lev, c, a, b, left_above, half):
    """Whether the opening crosses its level within ``half`` of each ``c``: on the
    bracket's left side of it at ``max(c - half, a)``, on its right side at
    ``min(c + half, b)``; and the middle of those two points (of ``[a, b]`` where
    ``c`` is not a number or outside the bracket)."""
    fine = np.isfinite(c) & (c >= a) & (c <= b)
    c = np.where(fine, c, 0.5 * (a + b))
    lo, hi = np.maximum(c - half, a), np.minimum(c + half, b)
    k = c.size
    f = gear.signed_openings(np.concatenate([lo, hi]))
    cols = np.arange(k)
    f_lo, f_hi = f[ports, cols] - lev, f[ports, cols + k] - lev
    proved = fine & ((f_lo > 0.0) == left_above) & ((f_hi > 0.0) != left_above)
    return proved, np.where(proved, 0.5 * (lo + hi), c)


#: The step off an end the secant falls on, as a fraction of the tolerance [-].
CROSSING_NUDGE = 0.4
#: Most evaluations of the gear in the solve (bisection alone needs 43 from a sample's
#: bracket to 1e-13 rad).
CROSSING_MAX_ROUNDS = 60


def _solve_crossings(gear: ValveGear, ports: np.ndarray, lev: np.ndarray, a: np.ndarray,
                     b: np.ndarray, fa: np.ndarray, fb: np.ndarray) -> np.ndarray:
    """Where ``signed_openings(t)[ports] - lev`` passes from above zero to not above (or
    back) in each bracket [a, b], whose ends' differences ``fa`` and ``fb`` lie on the
    two sides, all brackets together [rad].

    Illinois steps; a bisection instead where the secant's point falls outside its
    bracket (as it does where an opening rests at the level, a valve seated after its
    dash-pot closed it: the crossing is then the edge of that rest) or where the
    bracket did not shrink to a quarter in three steps.  A point is above when its
    difference is positive, as the samples' brackets were found."""
    a, b, fa, fb = (np.array(v, dtype=float) for v in (a, b, fa, fb))
    cols = np.arange(a.size)
    w = b - a
    aw = np.abs(w)
    width0 = aw
    nudge_ok = np.ones(a.size, dtype=bool)
    nudged = np.zeros(a.size, dtype=bool)
    # (each bracket's width is found once a round and read where the steps read it)
    with np.errstate(divide="ignore", invalid="ignore"):
        for rnd in range(CROSSING_MAX_ROUNDS):
            # a bracket closed stays as it is, whatever the others still need, so that
            # each crossing is the same however many it is solved beside
            active = aw > CROSSING_TOL_RAD
            if not active.any():
                break
            nudge_ok &= ~(nudged & active)      # a step off an end that did not close it
            c = b - fb * w / (fb - fa)
            outside = ~((c > np.minimum(a, b)) & (c < np.maximum(a, b)))
            check = rnd % 3 == 2
            bisect = (outside | (aw > 0.25 * width0)) if check else outside
            c = np.where(bisect, 0.5 * (a + b), c)
            # a secant that falls on an end (that end is on the crossing to the last
            # bits, and the other far off; or its difference is zero) would leave
            # bisection alone to close the bracket, some 30 rounds: a step of a
            # fraction of the tolerance off that end, towards the other, closes it in
            # one where the crossing is there; where it is not (an opening resting at
            # the level), bisection goes on
            nudged = outside & nudge_ok & active
            if nudged.any():
                near_b = (np.abs(fb) <= np.abs(fa))
                end, other = np.where(near_b, b, a), np.where(near_b, a, b)
                step = np.minimum(CROSSING_NUDGE * CROSSING_TOL_RAD, 0.5 * np.abs(other - end))
                c = np.where(nudged, end + np.copysign(step, other - end), c)
            fc = gear.signed_openings(c)[ports, cols] - lev
            # the new point replaces the end on its side; the kept end's value is
            # halved when it was kept on a secant step (Illinois), so that both ends move
            same_b = (fc > 0.0) == (fb > 0.0)
            fa = np.where(active, np.where(same_b, np.where(bisect, fa, 0.5 * fa), fb), fa)
            a = np.where(active, np.where(same_b, a, b), a)
            b, fb = np.where(active, c, b), np.where(active, fc, fb)
            w = b - a
            aw = np.abs(w)
            if check:
                width0 = aw
    return 0.5 * (a + b)


def crossings(gear: ValveGear, port: int, level: float = 0.0) -> list[tuple[float, bool]]:
    """Crank angles where one port's signed opening crosses ``level``.

    Parameters
    ----------
    gear : ValveGear
        The gear, at its present setting.
    port : int
        Index of the port in :data:`corliss.valves.gear.PORTS` (0 head steam,
        1 head exhaust, 2 crank steam, 3 crank exhaust).
    level : float, optional
        Signed opening [m] to cross: 0 for the port's opening and closing, the port
        width for its full opening.

    Returns
    -------
    list of (float, bool)
        Sorted ``(angle [rad] in [0, 2 pi), rising)`` pairs, as
        :func:`crossing_table` gives them; empty when the opening never reaches the
        level.
    """
    levels = np.zeros((4, 1))
    levels[port, 0] = level
    return crossing_table(gear, levels)[port][0]


def _circ_dist(a: float, b: float) -> float:
    d = (a - b) % TWO_PI
    return min(d, TWO_PI - d)


def _interval_near(cross: list[tuple[float, bool]], anchor: float):
    """The (open, close) angles of the opening interval whose start is nearest ``anchor``."""
    opens = [t for t, rising in cross if rising]
    closes = [t for t, rising in cross if not rising]
    if not opens or not closes:
        return None, None
    start = min(opens, key=lambda t: _circ_dist(t, anchor))
    end = min(closes, key=lambda t: (t - start) % TWO_PI)
    return start, end


def end_events(gear: ValveGear, end: str, piston_fraction: Callable[[float], float],
               table: list | None = None, sampled: tuple | None = None,
               lead: float | None = None) -> dict:
    """Events of one end (``"head"`` or ``"crank"``) as the JSON contract names them.

    Admission and cut-off are the opening and closing of the steam port nearest the
    end's dead centre; release and compression those of the exhaust port nearest the
    opposite dead centre (Spangler, *Valve-Gears*, Art. 17).

    Parameters
    ----------
    gear : ValveGear
        The gear, at its present setting.
    end : str
        ``"head"`` or ``"crank"``.
    piston_fraction : callable
        Crank angle [rad] -> piston position as a fraction of the stroke from the
        head-end dead centre [-].
    table : list or None, optional
        A crossing table already found, whose first level is zero (a PortMap's
        ``crossings``); found here when None.
    sampled : tuple of ndarray, optional
        ``(gear.openings(th), gear.signed_openings(th))`` over a turn's samples
        (both ends read the same samples: :func:`events` finds them once); found
        here when None.
    lead : float, optional
        The steam port's signed opening at the end's dead centre [m] (:func:`events`
        finds both ends' in one evaluation of the gear); found here when None.

    Returns
    -------
    dict
        ``admission_deg``, ``cutoff_deg``, ``release_deg``, ``compression_deg``:
        crank angles [deg] in [0, 360) from head-end dead centre; ``cutoff_frac``,
        ``release_frac``, ``compression_frac``: piston travel from this end's own dead
        centre as a fraction of the stroke [-] (each None for an event that never
        happens); ``lead_m``: signed opening of the steam port at the end's dead
        centre [m]; ``max_port_opening_m``: largest physical opening of the steam port,
        the openings its edge uncovers at once taken together
        (:meth:`~corliss.valves.gear.ValveGear.openings_per_edge` times one edge's
        largest opening: a Porter-Allen plate's ``steam_openings``, a double-ported
        valve's ``ports_per_end``), so that times one opening's length is the port's
        largest area [m]; ``overtravel_m``: how far the valve edge travels past full
        opening [m] (0 when it never does; one edge's).
    """
    steam, exhaust = (0, 1) if end == "head" else (2, 3)
    dead = 0.0 if end == "head" else math.pi

    def frac(t):
        if t is None:
            return None
        f = piston_fraction(t)
        return float(f if end == "head" else 1.0 - f)

    if table is None:
        table = crossing_table(gear, np.zeros((4, 1)))
    adm, cut = _interval_near(table[steam][0], dead)
    rel, comp = _interval_near(table[exhaust][0], dead + math.pi)
    if sampled is None:
        sampled = _sampled(gear)
    opening = sampled[0][steam]
    width = gear.port_widths()[steam]
    signed_max = float(sampled[1][steam].max())

    def deg(t):
        return None if t is None else float(math.degrees(t) % 360.0)

    return {
        "admission_deg": deg(adm),
        "cutoff_deg": deg(cut),
        "cutoff_frac": frac(cut),
        "release_deg": deg(rel),
        "release_frac": frac(rel),
        "compression_deg": deg(comp),
        "compression_frac": frac(comp),
        "lead_m": (float(gear.signed_openings(np.array([dead]))[steam, 0]) if lead is None
                   else float(lead)),
        # the port's whole opening: every edge the valve uncovers at once opens alike
        "max_port_opening_m": float(gear.openings_per_edge()[steam]) * float(opening.max()),
        "overtravel_m": float(max(signed_max - width, 0.0)),
    }


def events(gear: ValveGear, piston_fraction: Callable[[float], float],
           table: list | None = None, signed: np.ndarray | None = None,
           fractions_of: Callable[[np.ndarray], np.ndarray] | None = None) -> dict:
    """Events of both ends: ``{"head": {...}, "crank": {...}}``.

    Parameters
    ----------
    gear : ValveGear
        The gear, at its present setting.
    piston_fraction : callable
        Crank angle [rad] -> piston position as a fraction of the stroke from the
        head-end dead centre [-].
    table : list or None, optional
        A crossing table already found, whose first level is zero (a PortMap's
        ``crossings``); found here when None.
    signed : ndarray or None, optional
        The gear's signed openings [m] at the :data:`_SAMPLES` angles a turn, as
        :func:`sampled_crossings` gives them (a PortMap's ``signed_samples``); found
        here when None.
    fractions_of : callable, optional
        ``piston_fraction`` over an array of crank angles at once [rad] -> [-], each
        angle's fraction the number ``piston_fraction`` gives for it alone (an
        element-wise function: :meth:`corliss.engine.geometry.CylinderGeometry.fraction`):
        the events' fractions are then found in one call, not one call each.

    Returns
    -------
    dict
        ``{"head": ..., "crank": ...}``, each the dict
        :func:`~corliss.valves.events.end_events` returns.
    """
    if table is None:
        table = crossing_table(gear, np.zeros((4, 1)))
    sampled = _largest(gear, signed)
    if fractions_of is not None:
        # the angles end_events reads the fractions at (cut-off, release, compression
        # of each end), found at once
        at = [t for steam, exhaust, dead in ((0, 1, 0.0), (2, 3, math.pi))
              for t in (_interval_near(table[steam][0], dead)[1],
                        *_interval_near(table[exhaust][0], dead + math.pi))
              if t is not None]
        known = dict(zip(at, np.asarray(fractions_of(np.array(at, dtype=float))).tolist()))
        piston_fraction = _known_first(known, piston_fraction)
    # both ends' leads in one evaluation of the gear (each angle's openings are its
    # own, evaluated beside others or alone)
    dead = gear.signed_openings(_DEAD_CENTRES)
    return {end: end_events(gear, end, piston_fraction, table, sampled,
                            dead[0, 0] if end == "head" else dead[2, 1])
            for end in ("head", "crank")}


def _known_first(known: dict, piston_fraction: Callable[[float], float]):
    """``piston_fraction`` answered from ``known`` (angle [rad] -> fraction [-]) where it
    holds the angle."""
    def frac(t):
        f = known.get(t)
        return piston_fraction(t) if f is None else f
    return frac


def _sampled(gear: ValveGear, signed: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The gear's openings and signed openings over :data:`_SAMPLES` angles a turn
    (the signed ones given when ``signed`` is not None)."""
    return gear.sampled(_TURN_OPEN, signed)


def _largest(gear: ValveGear, signed: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """What :func:`end_events` reads of :func:`_sampled`: each port's largest opening
    and largest signed opening over the samples, shape ``(4, 1)`` each.

    Where the gear's openings are its signed ones through ``_openings_of``
    (:data:`~corliss.valves.gear.OPENINGS_OF_SIGNED`, nondecreasing in each signed
    opening), the largest opening is ``_openings_of`` of the largest signed one, the
    same number as the largest of the openings, found on four values instead of the
    turn's samples; otherwise the openings over the samples."""
    if type(gear).openings not in OPENINGS_OF_SIGNED:
        return _sampled(gear, signed)
    s = gear.signed_openings(_TURN_OPEN) if signed is None else signed
    top = s.max(axis=1)[:, None]
    return gear._openings_of(top.copy()), top
