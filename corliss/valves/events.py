"""Valve events of each cylinder end, found from the gear's port openings.

An event is a crank angle where a port edge is crossed: admission and cut-off where
the end's steam port opens and closes, release and compression where its exhaust
port opens and closes (Spangler Art. 17: admission, cut-off, release, compression).
Each is found by bisection on the gear's own signed opening to 1e-9 rad, so it holds
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


def _refine(f: Callable[[float], float], a: float, b: float) -> float:
    """Bisect for the sign change of ``f`` between ``a`` and ``b``."""
    fa = f(a) > 0.0
    for _ in range(60):
        m = 0.5 * (a + b)
        if (f(m) > 0.0) == fa:
            a = m
        else:
            b = m
        if b - a < 1e-10:
            break
    return 0.5 * (a + b)


def crossings(gear: ValveGear, port: int, level: float = 0.0) -> list[tuple[float, bool]]:
    """Crank angles [rad] in [0, 2 pi) where a port's signed opening crosses ``level``.

    Returns a list of ``(angle, rising)`` sorted by angle; ``rising`` is True where
    the opening passes ``level`` upwards (the port opens).
    """
    th = np.linspace(0.0, TWO_PI, _SAMPLES + 1)
    s = gear.signed_openings(th)[port] - level
    above = s > 0.0
    out = []

    def f(t):
        return float(gear.signed_openings(np.array([t]))[port, 0] - level)

    for i in np.nonzero(above[1:] != above[:-1])[0]:
        t = _refine(f, th[i], th[i + 1]) % TWO_PI
        out.append((t, bool(above[i + 1])))
    return sorted(out)


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


def end_events(gear: ValveGear, end: str, piston_fraction: Callable[[float], float]) -> dict:
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

    adm, cut = _interval_near(crossings(gear, steam), dead)
    rel, comp = _interval_near(crossings(gear, exhaust), dead + math.pi)
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


def events(gear: ValveGear, piston_fraction: Callable[[float], float]) -> dict:
    """Events of both ends: ``{"head": {...}, "crank": {...}}``."""
    return {end: end_events(gear, end, piston_fraction) for end in ("head", "crank")}
