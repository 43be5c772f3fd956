"""Valve events of each cylinder end, found from the gear's port openings.

An event is a crank angle where a port edge is crossed: admission and cut-off where
the end's steam port opens and closes, release and compression where its exhaust
port opens and closes (Spangler Art. 17: admission, cut-off, release, compression).
Each is found by bisection on the gear's own signed opening to 1e-13 rad, so it holds
for any gear, any lap (negative included) and any rod length; an event that never
happens is ``None``.

Angles are crank angles from head-end dead centre in the direction of rotation, in
[0, 360) degrees.  Fractions are of that end's own stroke, from its own dead centre,
through a ``piston_fraction`` function the caller supplies (the valves layer does not
know the crank train).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from corliss.valves.gear import ValveGear

TWO_PI = 2.0 * math.pi
_SAMPLES = 7200


def crossing_table(gear: ValveGear, levels: np.ndarray) -> list[list[list[tuple[float, bool]]]]:
    """Where each port's signed opening crosses each of its levels, all found at once.

    Parameters
    ----------
    gear : ValveGear
    levels : ndarray, shape (4, L)
        Levels [m] to cross for each port.

    Returns
    -------
    list
        ``out[port][level]`` = sorted list of ``(angle [rad] in [0, 2 pi), rising)``;
        ``rising`` is True where the opening passes the level upwards.  Brackets come
        from 7200 samples a turn; all of them are bisected together to 1e-13 rad.
    """
    levels = np.atleast_2d(np.asarray(levels, dtype=float))
    th = np.linspace(0.0, TWO_PI, _SAMPLES + 1)
    s = gear.signed_openings(th)
    ports, levs, idx, rising = [], [], [], []
    for port in range(4):
        for li, level in enumerate(levels[port]):
            above = s[port] - level > 0.0
            i = np.nonzero(above[1:] != above[:-1])[0]
            ports += [port] * i.size
            levs += [li] * i.size
            idx.append(i)
            rising.append(above[i + 1])
    out = [[[] for _ in range(levels.shape[1])] for _ in range(4)]
    if not ports:
        return out
    ports = np.array(ports)
    idx = np.concatenate(idx)
    rising = np.concatenate(rising)
    lev = levels[ports, np.array(levs)]
    a, b = th[idx].copy(), th[idx + 1].copy()
    cols = np.arange(idx.size)
    for _ in range(42):
        m = 0.5 * (a + b)
        above_m = gear.signed_openings(m)[ports, cols] - lev > 0.0
        # the left end is below when the crossing rises: move it while m is still below
        move_a = above_m != rising
        a = np.where(move_a, m, a)
        b = np.where(move_a, b, m)
    t = (0.5 * (a + b)) % TWO_PI
    for k in range(idx.size):
        out[ports[k]][levs[k]].append((float(t[k]), bool(rising[k])))
    for row in out:
        for lst in row:
            lst.sort()
    return out


def crossings(gear: ValveGear, port: int, level: float = 0.0) -> list[tuple[float, bool]]:
    """Crank angles [rad] in [0, 2 pi) where one port's signed opening crosses ``level``."""
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
               table: list | None = None) -> dict:
    """Events of one end (``"head"`` or ``"crank"``) as the JSON contract names them.

    Parameters
    ----------
    gear : ValveGear
    end : str
        ``"head"`` or ``"crank"``.
    piston_fraction : callable
        Crank angle [rad] -> piston position as a fraction of the stroke from the
        head-end dead centre [-].
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
    th = np.linspace(0.0, TWO_PI, _SAMPLES, endpoint=False)
    opening = gear.openings(th)[steam]
    width = gear.port_widths()[steam]
    signed_max = float(gear.signed_openings(th)[steam].max())

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
        "lead_m": float(gear.signed_openings(np.array([dead]))[steam, 0]),
        "max_port_opening_m": float(opening.max()),
        "overtravel_m": float(max(signed_max - width, 0.0)),
    }


def events(gear: ValveGear, piston_fraction: Callable[[float], float],
           table: list | None = None) -> dict:
    """Events of both ends: ``{"head": {...}, "crank": {...}}``.

    ``table`` may be a crossing table already found (a PortMap's ``crossings``),
    whose first level is zero.
    """
    if table is None:
        table = crossing_table(gear, np.zeros((4, 1)))
    return {end: end_events(gear, end, piston_fraction, table) for end in ("head", "crank")}
