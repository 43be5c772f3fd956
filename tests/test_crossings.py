"""Port-edge crossings read off a turn's samples and proved on the gear
(corliss.valves.events.crossing_table), against the Zeuner closed form and, for
every bundled gear, against the gear's own opening either side of each crossing."""

import importlib
import math

import numpy as np
import pytest

from corliss.engine.model import build_gear
from corliss.scene.loader import bundled_scenes, load_scene

from conftest import make_scene

events = importlib.import_module("corliss.valves.events")

IN = 0.0254
R, LH, LC, EH, EC, DELTA_DEG, W = 3.0, 1.0, 0.875, 0.125, -0.0625, 30.0, 1.25


def test_crossings_equal_the_zeuner_closed_form():
    """Spangler, *Valve-Gears*, Art. 13, eq. 4: an eccentric on an infinite rod moves
    the valve x = r sin(theta + delta), so the head steam port's signed opening
    x - l crosses a level v at theta = asin((l + v) / r) - delta (rising) and
    pi - asin((l + v) / r) - delta (falling); the head exhaust's -x - e at
    pi + asin((e + v) / r) - delta (rising) and 2 pi - asin((e + v) / r) - delta;
    the crank end's ports the same on -x and x.  Levels 0 (the port's opening and
    closing) and the port width (full opening).

    Tolerance 2e-13 rad: each crossing is the middle of a bracket no wider than
    CROSSING_TOL_RAD = 1e-13 rad holding the crossing, so it is within 0.5e-13 of
    it; asin and the sums here add a few 1e-16."""
    gear = build_gear(make_scene(valve_gear={
        "eccentricity": f"{R} in", "lap": [f"{LH} in", f"{LC} in"],
        "exhaust_lap": [f"{EH} in", f"{EC} in"], "lead": None,
        "angular_advance": f"{DELTA_DEG} deg", "port_width": f"{W} in",
        "eccentric_rod": None}))
    levels = np.array([[0.0, W * IN]] * 4)
    table = events.crossing_table(gear, levels)
    d = math.radians(DELTA_DEG)
    # (port, lap, the angle's offset: the port opens on +x at asin - delta, on -x at
    # pi + asin - delta)
    ports = [(0, LH, 0.0), (1, EH, math.pi), (2, LC, math.pi), (3, EC, 0.0)]
    found = 0
    for port, lap, shift in ports:
        for li, level in enumerate((0.0, W)):
            v = (lap + level) / R
            if abs(v) >= 1.0:
                assert table[port][li] == [], (port, level)
                continue
            a = math.asin(v)
            want = sorted([((shift + a - d) % (2 * math.pi), True),
                           ((shift + math.pi - a - d) % (2 * math.pi), False)])
            got = table[port][li]
            assert [r for _, r in got] == [r for _, r in want], (port, level)
            for (t, _), (t0, _) in zip(got, want):
                assert t == pytest.approx(t0, abs=2e-13), (port, level)
                found += 1
    assert found == 16     # every lap plus the width is inside the throw: 2 each


@pytest.mark.parametrize("name", sorted(bundled_scenes()))
def test_every_bundled_gears_crossings_change_side(name):
    """Every crossing of every bundled scene's gear (its kink levels, as the port map
    finds them), whether read off the samples or solved by regula falsi where they do
    not give it: the gear's signed opening is on one side of the level 0.5e-13 rad
    before the crossing and on the other 0.5e-13 rad after, the side the crossing's
    ``rising`` says (a point is above the level when its difference is positive).

    The width 1e-13 rad is CROSSING_TOL_RAD: the crossing is the middle of a bracket
    that wide, so both ends of that bracket lie within 0.5e-13 of it; the points
    checked are those ends' farthest positions."""
    gear = build_gear(load_scene(bundled_scenes()[name]))
    levels = np.atleast_2d(gear.kink_levels())
    table = events.crossing_table(gear, levels)
    half = 0.5 * events.CROSSING_TOL_RAD
    n = 0
    for port in range(4):
        for li in range(levels.shape[1]):
            for t, rising in table[port][li]:
                s = gear.signed_openings(np.array([t - half, t + half]))[port] - levels[port, li]
                assert (s[0] > 0.0, s[1] > 0.0) == (not rising, rising), (port, li, t)
                n += 1
    assert n >= 4           # every gear opens and closes its steam ports
